//! A triangulated surface as a rigid obstacle (or, later, as a primary
//! surface): closest-point search through an R*-tree and a
//! signed gap that does not jump at edges and vertices.
//!
//! ## Orientation
//! Each triangle `(x₁, x₂, x₃)` has the right-hand normal
//! `n = (a₁ × a₂)/|a₁ × a₂|`, `a₁ = x₂ − x₁`, `a₂ = x₃ − x₁` (paper eqs.
//! 27–28). It must point **out of the obstacle, toward the body**: for a
//! closed solid that is the outward normal, which is the STL convention
//! (vertices counter-clockwise seen from outside) and the orientation of a
//! Gmsh surface set after [`Mesh::orient_surfaces`]. Adjacent triangles must
//! agree (each shared edge traversed in opposite directions); the
//! constructor checks it.
//!
//! ## Signed gap and normal
//! With `x̄` the closest point and `d = |x − x̄|`:
//! - on a triangle's face, `n` is the face normal and `g = (x − x̄)·n`;
//! - on an edge or a vertex, the sign is that of `(x − x̄)·N`, with `N` the
//!   pseudo-normal of the feature (Bærentzen & Aanæs, 2005): for an edge the
//!   normalised sum of the normals of its (one or two) triangles, for a
//!   vertex the angle-weighted sum `Σ αₜ nₜ` of its triangles' normals. Then
//!   `n = sign · (x − x̄)/d` and `g = sign · d`, so the normal turns
//!   continuously around a convex edge instead of jumping from one face
//!   normal to the next. When `d ≤ 10⁻¹⁰ L` (`L` the diagonal of the
//!   surface's bounding box) the direction of `x − x̄` is round-off and `n`
//!   is the pseudo-normal itself.
//!
//! For a closed, consistently oriented surface this sign is exact (points
//! inside the solid get `g < 0`). For an open sheet, points beyond its
//! boundary are classified by the side of the boundary triangle's plane.
//!
//! ## Curvature
//! `∂²g/∂x²` of the piecewise gap function: `0` on a face,
//! `sign (I − e eᵀ − n nᵀ)/d` on an edge of unit direction `e`,
//! `sign (I − n nᵀ)/d` on a vertex (a sphere or cylinder of radius zero),
//! and `0` when `d ≤ 10⁻¹⁰ L`, where the gap is not differentiable.
//!
//! ## Search
//! The triangles are bulk-loaded once into an R*-tree (the `rstar` crate,
//! the georust spatial index); a query is its exact nearest-neighbour
//! search with the point-to-triangle distance (branch and bound on the
//! boxes' distances), so the result is the brute-force minimum over all
//! triangles. The triangles as near within the tie tolerance (a point over
//! an edge or a vertex) are then gathered from the tree and one is chosen
//! by the geometric rule of deformable primary surfaces
//! ([`best_triangle`](crate::contact::primary::best_triangle)), so the
//! projection is a function of the point alone: the same in Newton's
//! iterations and in the condensed path's rounds.
//!
//! ## Facet choice of a contact node
//! A contact node is projected as on a deformable primary surface
//! (`contact::primary`, "Facet choice": the triangle its
//! [`FacetWalk`](crate::contact::facet_walk::FacetWalk) keeps, the last
//! converged increment's until a flip back;
//! [`project_keeping`](TriangulatedSurface::project_keeping)): the face of
//! the kept triangle while the node is over it within the sticky band and
//! has not slid inside another face (by [`INSIDE`]), else the closest
//! point above. At the answer of an exact law a node lies on the
//! surface, and on an edge or a vertex the closest point's feature (face
//! normal or pseudo-normal) followed the side from which round-off left
//! the node: on an STL cap of a sphere Newton and the condensed rounds
//! differed by 1.9e-5 of the displacements and 2 % of the peak traction.
//! Kept on one face, both read the same normal.
//!
//! [`Mesh::orient_surfaces`]: crate::mesh::Mesh::orient_surfaces

use crate::contact::primary::{best_triangle, STICKY_BAND, TIE_TOLERANCE};
use crate::contact::projection::Projection;
use crate::contact::triangle::{closest_point_on_triangle, Feature, TriangleProjection};
use crate::contact::triangle_gap::{facet_triangles, triangle_gap};
use crate::error::{Error, Result};
use crate::mesh::Mesh;
use nalgebra::{Matrix3, Vector3};
use rstar::{PointDistance, RTree, RTreeObject, AABB};
use std::collections::HashMap;
use std::path::Path;

/// Distance below which `x − x̄` gives no reliable direction, relative to
/// the diagonal of the surface's bounding box.
const DIRECTION_TOLERANCE: f64 = 1e-10;

/// How far off a triangle (in barycentric coordinates) a contact node
/// still counts as over it, and how far inside another's face it must lie
/// to have slid there
/// ([`project_keeping`](TriangulatedSurface::project_keeping)): above the
/// differences of two converged answers (1e-10 relative) and round-off,
/// far below the distances nodes slide.
pub const INSIDE: f64 = 1e-6;

/// A triangulated surface with its search tree and pseudo-normals. See the
/// module documentation for the orientation convention.
#[derive(Clone, Debug)]
pub struct TriangulatedSurface {
    vertices: Vec<Vector3<f64>>,
    triangles: Vec<[usize; 3]>,
    /// Unit right-hand normal of each triangle.
    face_normals: Vec<Vector3<f64>>,
    /// Unit pseudo-normal of edge `i` (vertex `i` to `i + 1`) of each triangle.
    edge_normals: Vec<[Vector3<f64>; 3]>,
    /// Unit angle-weighted pseudo-normal of each vertex.
    vertex_normals: Vec<Vector3<f64>>,
    /// Search tree over the triangles.
    tree: RTree<SearchTriangle>,
    /// Below this distance `x − x̄` gives no direction.
    tiny: f64,
}

impl TriangulatedSurface {
    /// A surface from vertex positions and triangles (indices into
    /// `vertices`, right-hand normal toward the body). Errors on no
    /// triangles, an index out of range, a non-finite coordinate, a
    /// zero-area triangle or inconsistently oriented neighbours.
    pub fn new(vertices: Vec<Vector3<f64>>, triangles: Vec<[usize; 3]>) -> Result<Self> {
        Self::build(vertices, triangles, "triangulated surface")
    }

    /// `new`, with `what` naming the source in error messages.
    fn build(vertices: Vec<Vector3<f64>>, triangles: Vec<[usize; 3]>, what: &str) -> Result<Self> {
        if triangles.is_empty() {
            return Err(Error::contact_input(
                what,
                "the surface has no triangles".into(),
            ));
        }
        if let Some(v) = vertices
            .iter()
            .position(|v| !v.iter().all(|x| x.is_finite()))
        {
            return Err(Error::contact_input(
                what,
                format!("vertex {v} has a non-finite coordinate"),
            ));
        }
        for (t, tri) in triangles.iter().enumerate() {
            if let Some(&i) = tri.iter().find(|&&i| i >= vertices.len()) {
                return Err(Error::contact_input(
                    what,
                    format!(
                        "triangle {t} refers to vertex {i}, but there are {} vertices",
                        vertices.len()
                    ),
                ));
            }
        }

        // face normals; reject zero-area triangles
        let mut face_normals = Vec::with_capacity(triangles.len());
        for (t, tri) in triangles.iter().enumerate() {
            let [a, b, c] = tri.map(|i| vertices[i]);
            let cross = (b - a).cross(&(c - a));
            let scale = (b - a)
                .norm_squared()
                .max((c - a).norm_squared())
                .max((c - b).norm_squared());
            if !(cross.norm_squared() > 1e-24 * scale * scale) {
                return Err(Error::contact_input(
                    what,
                    format!(
                        "triangle {t} (vertices {}, {}, {}) has zero area",
                        tri[0], tri[1], tri[2]
                    ),
                ));
            }
            face_normals.push(cross.normalize());
        }

        // edge pseudo-normals and the orientation check: every directed
        // edge appears at most once
        let mut directed: HashMap<(usize, usize), usize> = HashMap::new();
        let mut edge_sum: HashMap<(usize, usize), Vector3<f64>> = HashMap::new();
        for (t, tri) in triangles.iter().enumerate() {
            for i in 0..3 {
                let (p, q) = (tri[i], tri[(i + 1) % 3]);
                if let Some(other) = directed.insert((p, q), t) {
                    return Err(Error::contact_input(
                        what,
                        format!(
                            "triangles {other} and {t} both run along edge {p}→{q}: \
                             neighbouring triangles are not consistently oriented"
                        ),
                    ));
                }
                *edge_sum
                    .entry((p.min(q), p.max(q)))
                    .or_insert_with(Vector3::zeros) += face_normals[t];
            }
        }
        let edge_normals = triangles
            .iter()
            .enumerate()
            .map(|(t, tri)| {
                std::array::from_fn(|i| {
                    let (p, q) = (tri[i], tri[(i + 1) % 3]);
                    edge_sum[&(p.min(q), p.max(q))]
                        .try_normalize(1e-12)
                        .unwrap_or(face_normals[t])
                })
            })
            .collect();

        // angle-weighted vertex pseudo-normals
        let mut vertex_sum = vec![Vector3::zeros(); vertices.len()];
        let mut some_face = vec![Vector3::zeros(); vertices.len()];
        for (t, tri) in triangles.iter().enumerate() {
            for i in 0..3 {
                let v = vertices[tri[i]];
                let u = vertices[tri[(i + 1) % 3]] - v;
                let w = vertices[tri[(i + 2) % 3]] - v;
                let angle = u.cross(&w).norm().atan2(u.dot(&w));
                vertex_sum[tri[i]] += face_normals[t] * angle;
                some_face[tri[i]] = face_normals[t];
            }
        }
        let vertex_normals = vertex_sum
            .iter()
            .zip(&some_face)
            .map(|(s, f)| s.try_normalize(1e-12).unwrap_or(*f))
            .collect();

        let tree = search_tree(&vertices, &triangles);
        let bounds = tree.root().envelope();
        let diagonal = (Vector3::from(bounds.upper()) - Vector3::from(bounds.lower())).norm();
        Ok(TriangulatedSurface {
            tiny: DIRECTION_TOLERANCE * diagonal,
            vertices,
            triangles,
            face_normals,
            edge_normals,
            vertex_normals,
            tree,
        })
    }

    /// Reads an STL file, ASCII or binary (via the `stl_io` crate). STL
    /// stores single-precision coordinates; bit-identical vertices are
    /// merged, so a closed STL solid gives a closed surface. The facet
    /// normals in the file are ignored: the vertex order (counter-clockwise
    /// seen from outside) defines the normal. Errors name the file.
    pub fn from_stl(path: &Path) -> Result<Self> {
        let what = format!("STL file '{}'", path.display());
        let mesh = crate::mesh::stl::read_stl(path)?;
        let vertices = mesh
            .vertices
            .iter()
            .map(|v| Vector3::new(v.0[0] as f64, v.0[1] as f64, v.0[2] as f64))
            .collect();
        let triangles = mesh.faces.iter().map(|f| f.vertices).collect();
        Self::build(vertices, triangles, &what)
    }

    /// The surface set `surface` of `mesh` (e.g. read by
    /// [`crate::mesh::gmsh::read_msh`]), in the reference configuration.
    /// Quadrangles `(0, 1, 2, 3)` are split along the diagonal 0–2 into
    /// `(0, 1, 2)` and `(0, 2, 3)`. The facets' orientation (outward from
    /// the mesh's body) is kept: the body being projected must lie on that
    /// side. Vertices are the surface's nodes, in increasing node index.
    pub fn from_surface_facets(mesh: &Mesh, surface: &str) -> Result<Self> {
        let set = mesh.surface(surface).ok_or_else(|| Error::UnknownGroup {
            key: "obstacle surface".into(),
            kind: "surface set",
            name: surface.to_string(),
            available: mesh.surface_names(),
        })?;
        let nodes = mesh.surface_nodes(set);
        let local: HashMap<usize, usize> = nodes.iter().enumerate().map(|(i, &n)| (n, i)).collect();
        let vertices = nodes
            .iter()
            .map(|&n| Vector3::from(mesh.nodes[n]))
            .collect();
        let triangles = facet_triangles(&set.facets, |n| local[&n]);
        Self::build(vertices, triangles, &format!("surface set '{surface}'"))
    }

    /// Vertex positions.
    pub fn vertices(&self) -> &[Vector3<f64>] {
        &self.vertices
    }

    /// Triangles as vertex indices.
    pub fn triangles(&self) -> &[[usize; 3]] {
        &self.triangles
    }

    /// Unit right-hand normal of triangle `t`.
    pub fn face_normal(&self, t: usize) -> Vector3<f64> {
        self.face_normals[t]
    }

    /// The surface moved rigidly by `d` (the search tree is built again).
    pub fn translated(&self, d: &Vector3<f64>) -> Self {
        let mut moved = self.clone();
        for v in &mut moved.vertices {
            *v += d;
        }
        moved.tree = search_tree(&moved.vertices, &moved.triangles);
        moved
    }

    /// The closest point on the surface to `x`: the triangle's index and the
    /// projection onto it. Where several triangles are as near (a point
    /// over an edge or a vertex), the one [`best_triangle`] chooses among
    /// them (the facet choice of deformable primary surfaces: a function of
    /// the geometry, not of the tree's order or of round-off). `None` only
    /// for a surface without triangles, which the constructors do not make.
    pub fn closest_point(&self, x: &Vector3<f64>) -> Option<(usize, TriangleProjection)> {
        let point = [x.x, x.y, x.z];
        let nearest = self.tree.nearest_neighbor(point)?;
        let size = (0..3)
            .map(|i| (nearest.corners[(i + 1) % 3] - nearest.corners[i]).norm())
            .fold(0.0, f64::max);
        let reach = nearest.distance_2(&point).sqrt() + 2.0 * TIE_TOLERANCE * size;
        let near: Vec<(usize, [Vector3<f64>; 3])> = (self.tree)
            .locate_within_distance(point, reach * reach)
            .map(|t| (t.index, t.corners))
            .collect();
        let choice = best_triangle(x, &near)?;
        Some((choice.triangle, choice.projection))
    }

    /// Projects the spatial point `x` onto the surface: closest point,
    /// normal, signed gap and curvature as in the module documentation.
    pub fn project(&self, x: &Vector3<f64>) -> Projection {
        self.project_keeping(x, None).1
    }

    /// The projection of a contact node at `x` by the facet choice of
    /// deformable primary surfaces (module docs, "Facet choice"), and the
    /// triangle it is on: while `x` lies over triangle `kept` within
    /// [`STICKY_BAND`] (its plane projection's barycentric coordinates all
    /// `≥ −STICKY_BAND`) and, where it is off `kept` by more than
    /// [`INSIDE`], not inside the face of its nearest triangle (the closest
    /// point's barycentric coordinates all `≥ INSIDE`: it slid there), the
    /// face of `kept`:
    /// `g = (x − x₁)·n_t`, `n = n_t`, curvature `0`; else
    /// [`project`](Self::project)'s closest point.
    pub fn project_keeping(&self, x: &Vector3<f64>, kept: Option<usize>) -> (usize, Projection) {
        #[allow(clippy::expect_used)]
        // `TriangulatedSurface::new` refuses a surface without triangles
        let (t, p) = self
            .closest_point(x)
            .expect("a TriangulatedSurface has at least one triangle");
        // kept while over it within the band, unless `x`, off it, lies
        // inside the face of its nearest triangle: it slid onto that one
        let slid = |k: usize| k != t && p.barycentric.iter().all(|&b| b >= INSIDE);
        match kept.and_then(|k| self.face_within_band(x, k)) {
            Some((k, face, shape)) if shape.iter().all(|&n| n >= -INSIDE) || !slid(k) => (k, face),
            _ => (t, self.closest_point_projection(x, t, &p)),
        }
    }

    /// The face projection of `x` on triangle `t`, and the barycentric
    /// coordinates of `x`'s projection on its plane, where they are all
    /// `≥ −STICKY_BAND` (see [`project_keeping`](Self::project_keeping)).
    fn face_within_band(
        &self,
        x: &Vector3<f64>,
        t: usize,
    ) -> Option<(usize, Projection, [f64; 3])> {
        let corners = self.triangles.get(t)?.map(|i| self.vertices[i]);
        let face = triangle_gap(x, [&corners[0], &corners[1], &corners[2]])?;
        (face.shape.iter().all(|&n| n >= -STICKY_BAND)).then(|| {
            let normal = self.face_normals[t];
            let gap = (x - corners[0]).dot(&normal);
            let projection = Projection {
                point: x - normal * gap,
                normal,
                gap,
                curvature: Matrix3::zeros(),
            };
            (t, projection, face.shape)
        })
    }

    /// The projection of `x` from its closest point `p` on triangle `t`
    /// (module docs: the face normal on a face, the pseudo-normal's side
    /// on an edge or a vertex).
    fn closest_point_projection(
        &self,
        x: &Vector3<f64>,
        t: usize,
        p: &TriangleProjection,
    ) -> Projection {
        let diff = x - p.point;
        let tri = self.triangles[t];
        let pseudo = match p.feature {
            Feature::Face => {
                let n = self.face_normals[t];
                return Projection {
                    point: p.point,
                    normal: n,
                    gap: diff.dot(&n),
                    curvature: Matrix3::zeros(),
                };
            }
            Feature::Edge(i) => self.edge_normals[t][i],
            Feature::Vertex(i) => self.vertex_normals[tri[i]],
        };
        let d = diff.norm();
        if !(d > self.tiny) {
            return Projection {
                point: p.point,
                normal: pseudo,
                gap: diff.dot(&pseudo),
                curvature: Matrix3::zeros(),
            };
        }
        let sign = if diff.dot(&pseudo) >= 0.0 { 1.0 } else { -1.0 };
        let n = diff * (sign / d);
        let mut projector = Matrix3::identity() - n * n.transpose();
        if let Feature::Edge(i) = p.feature {
            let e = (self.vertices[tri[(i + 1) % 3]] - self.vertices[tri[i]]).normalize();
            projector -= e * e.transpose();
        }
        Projection {
            point: p.point,
            normal: n,
            gap: sign * d,
            curvature: projector * (sign / d),
        }
    }
}

/// A triangle in the search tree: its index and corners.
#[derive(Clone, Debug)]
struct SearchTriangle {
    index: usize,
    corners: [Vector3<f64>; 3],
}

impl SearchTriangle {
    fn project(&self, x: &Vector3<f64>) -> TriangleProjection {
        let [a, b, c] = &self.corners;
        closest_point_on_triangle(x, a, b, c)
    }
}

impl RTreeObject for SearchTriangle {
    type Envelope = AABB<[f64; 3]>;
    fn envelope(&self) -> Self::Envelope {
        let corners = self.corners.map(|c| [c.x, c.y, c.z]);
        AABB::from_points(corners.iter())
    }
}

impl PointDistance for SearchTriangle {
    /// Squared distance from `x` to the triangle (to its closest point).
    fn distance_2(&self, x: &[f64; 3]) -> f64 {
        let x = Vector3::from(*x);
        (x - self.project(&x).point).norm_squared()
    }
}

/// The R*-tree over the triangles of a surface at the given vertex positions.
fn search_tree(vertices: &[Vector3<f64>], triangles: &[[usize; 3]]) -> RTree<SearchTriangle> {
    RTree::bulk_load(
        triangles
            .iter()
            .enumerate()
            .map(|(index, t)| SearchTriangle {
                index,
                corners: t.map(|i| vertices[i]),
            })
            .collect(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Unit square in z = 0 as two triangles, normal +z.
    fn square() -> TriangulatedSurface {
        TriangulatedSurface::new(
            vec![
                Vector3::new(0.0, 0.0, 0.0),
                Vector3::new(1.0, 0.0, 0.0),
                Vector3::new(1.0, 1.0, 0.0),
                Vector3::new(0.0, 1.0, 0.0),
            ],
            vec![[0, 1, 2], [0, 2, 3]],
        )
        .unwrap()
    }

    #[test]
    fn square_gap_on_face_edge_and_vertex() {
        let s = square();
        let p = s.project(&Vector3::new(0.3, 0.6, 0.25));
        assert!((p.gap - 0.25).abs() < 1e-15 && p.normal == Vector3::z());
        // beyond the edge x = 1, above the plane: distance to the edge
        let p = s.project(&Vector3::new(1.3, 0.5, 0.4));
        assert!((p.gap - 0.5).abs() < 1e-15);
        assert!((p.normal - Vector3::new(0.6, 0.0, 0.8)).norm() < 1e-15);
        // below the plane, beyond the vertex (0, 0)
        let p = s.project(&Vector3::new(-1.0, -2.0, -2.0));
        assert!((p.gap + 3.0).abs() < 1e-15);
        // on the diagonal (shared edge): the pseudo-normal is +z
        let p = s.project(&Vector3::new(0.5, 0.5, 0.0));
        assert_eq!(p.normal, Vector3::z());
        assert_eq!(p.gap, 0.0);
    }

    /// The facet choice of a contact node: the kept triangle's face within
    /// the band (its plane gap beyond the surface's edge, where the closest
    /// point measures to the edge), on the shared edge whichever is kept,
    /// and the nearest once the node lies inside its face.
    #[test]
    fn a_contact_node_keeps_its_face_until_it_slides_inside_another() {
        let s = square();
        // beyond the edge x = 1 by 0.02 (within the band of triangle 0)
        let x = Vector3::new(1.02, 0.5, 0.1);
        let (t, p) = s.project_keeping(&x, Some(0));
        assert_eq!((t, p.gap, p.normal), (0, 0.1, Vector3::z()));
        assert!((s.project(&x).gap - (0.02f64.hypot(0.1))).abs() < 1e-15);
        // on the diagonal (the edge both share): the kept one
        let x = Vector3::new(0.5, 0.5, 0.1);
        assert_eq!(s.project_keeping(&x, Some(0)).0, 0);
        assert_eq!(s.project_keeping(&x, Some(1)).0, 1);
        // off triangle 0 by 1e-9 of it: still over it
        let x = Vector3::new(0.5, 0.5 + 1e-9, 0.1);
        assert_eq!(s.project_keeping(&x, Some(0)).0, 0);
        // inside triangle 1 by 1e-3, within 0's band: slid onto 1
        let x = Vector3::new(0.5, 0.501, 0.1);
        assert_eq!(s.project_keeping(&x, Some(0)).0, 1);
        // beyond the band: the nearest
        let x = Vector3::new(1.2, 0.5, 0.1);
        assert_eq!(s.project_keeping(&x, Some(1)).0, 0);
    }

    #[test]
    fn rejects_bad_surfaces() {
        let v = vec![
            Vector3::zeros(),
            Vector3::x(),
            Vector3::y(),
            Vector3::x() * 2.0,
        ];
        let e = TriangulatedSurface::new(v.clone(), vec![]).unwrap_err();
        assert!(e.to_string().contains("no triangles"), "{e}");
        let e = TriangulatedSurface::new(v.clone(), vec![[0, 1, 7]]).unwrap_err();
        assert!(e.to_string().contains("vertex 7"), "{e}");
        let e = TriangulatedSurface::new(v.clone(), vec![[0, 1, 3]]).unwrap_err();
        assert!(e.to_string().contains("zero area"), "{e}");
        let e = TriangulatedSurface::new(v, vec![[0, 1, 2], [1, 2, 0]]).unwrap_err();
        assert!(e.to_string().contains("consistently oriented"), "{e}");
    }
}
