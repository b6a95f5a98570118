//! Frictionless dual mortar contact between two deformable bodies (issue
//! 28), a gap producer of the node driver beside
//! [`surface_contact`](super::surface_contact): the kernels of
//! [`mortar`](super::mortar) give `D`, `M` and the averaged nodal normals;
//! this file turns one secondary node's row of them into the
//! [`GapKinematics`] the driver's chain rule reads.
//!
//! ## The node's gap and lever (Popp, Gee & Wall 2009)
//! Secondary node `j` with dual multiplier `λ_j`, weighted gap
//! `g̃_j = n_jᵀ (Σ_l M_jl x_l − D_j x̃_j)` (`x̃_j = Σ_k R_jk x_k`, the
//! quadratic basis transformation; `R = I` on linear faces). The normal law
//! is evaluated per node on the area `A_j = D_j` and the normalised gap
//! `g_j = g̃_j / D_j`, so its automatic parameters `E/h` and the reported
//! `contact_pressure = λ_j` keep their node-to-surface meaning. The force
//! is Popp's `Σ_j λ_j D_j b_j`, acting through the lever
//! ```text
//! b_j = ∂g_j/∂q at fixed D, M, n:  −R_jk n_j on secondary node k,  (M_jl/D_j) n_j on primary node l,
//! ```
//! (the discrete mortar forces of [`MortarCoupling::contact_forces`]), and
//! the constraint row is the gap's linearisation
//! ```text
//! ∇g_j = b_j + (1/D_j) (∂n_j/∂q)ᵀ (Σ_l M_jl x_l − D_j x̃_j),
//! ∂b_j/∂q = (1/D_j) (−D_j R_jk ∂n_j/∂q on rows k,  M_jl ∂n_j/∂q on rows l).
//! ```
//!
//! ## What the linearisation holds today
//! Positions and the nodal normals' derivatives
//! ([`nodal_normal_derivatives`]) at FIXED `D`, `M` (a fixed segmentation).
//! The derivatives of `D_j`, `M_jl` and of the segmentation are not in yet:
//! [`node_row`](MortarGap::node_row) is the one place that gathers a node's
//! row, where they will drop in. Dropping `g_j ∂D_j` from
//! `∂g_j = (∂g̃_j − g_j ∂D_j)/D_j` costs nothing at a converged active
//! state (`g_j = 0` there); `∂M` does: Newton's rate is linear where the
//! primary side moves relative to the secondary one.
//!
//! ## Search
//! Candidate face pairs from a bounding-box search (an R*-tree, the `rstar`
//! crate): each primary face's box grown by `2 h_f + 2 d` (`h_f` its size,
//! `d` the largest motion over the last increment, as
//! [`primary`](super::primary)'s rule), paired with every secondary face
//! whose box it meets; refreshed at the start of each increment, so the
//! sparsity pattern holds through it.
//!
//! A secondary node with `D_j ≤ 0` (no segment yet: beyond the primary
//! surface, or only partly over it with a negative dual integral) is open
//! at the search margin.

use super::friction::{Coulomb, FrictionHistory, SlipKinematics, TangentialResponse};
use super::kinematics::{
    current_position, CoupledNodes, GapKinematics, GapProducer, PrimaryWeights, SecondaryNode,
    SlipFrame,
};
use super::laws::NodeContactState;
use super::mortar::{
    mortar_coupling, nodal_normal_derivatives, FaceShape, MortarCoupling, SurfaceFace,
};
use crate::mesh::{FacetKind, Mesh};
use nalgebra::{DMatrix, DVector, Dyn, Matrix3, OMatrix, Vector3, U3};
use rstar::primitives::{GeomWithData, Rectangle};
use rstar::{RTree, AABB};

/// The two surfaces of a mortar interface and their candidate face pairs.
#[derive(Clone, Debug)]
pub struct MortarSurfaces {
    /// The primary surface set's name.
    pub primary_surface: String,
    /// The secondary surface's faces (global node numbers).
    pub secondary_faces: Vec<SurfaceFace>,
    /// The primary surface's faces.
    pub primary_faces: Vec<SurfaceFace>,
    /// The primary surface's nodes (sorted).
    pub primary_nodes: Vec<usize>,
    /// Per secondary node (the interface's order), the secondary faces
    /// that hold it.
    pub node_faces: Vec<Vec<usize>>,
    /// Per secondary face, the candidate primary faces (refreshed by
    /// [`refresh`](Self::refresh)).
    pub candidates: Vec<Vec<usize>>,
    /// The primary surface's element size (square root of its mean face
    /// area in the reference configuration).
    pub element_size: f64,
    /// The search margin of the last refresh: the gap reported for a node
    /// without a segment.
    pub margin: f64,
}

/// The face shape of a mesh facet (same node order).
fn face_shape(kind: FacetKind) -> FaceShape {
    match kind {
        FacetKind::Tri3 => FaceShape::Tri3,
        FacetKind::Quad4 => FaceShape::Quad4,
        FacetKind::Tri6 => FaceShape::Tri6,
        FacetKind::Quad8 => FaceShape::Quad8,
    }
}

impl MortarSurfaces {
    /// Surface set `secondary` of `mesh` (its nodes `nodes`, sorted)
    /// against surface set `primary`, paired in the reference
    /// configuration; `None` if the mesh lacks either set.
    pub fn from_mesh(mesh: &Mesh, secondary: &str, primary: &str, nodes: &[usize]) -> Option<Self> {
        let faces = |name: &str| -> Option<Vec<SurfaceFace>> {
            let set = mesh.surface(name)?;
            Some(
                set.facets
                    .iter()
                    .map(|f| SurfaceFace {
                        shape: face_shape(f.kind),
                        nodes: f.nodes.clone(),
                    })
                    .collect(),
            )
        };
        let (secondary_faces, primary_faces) = (faces(secondary)?, faces(primary)?);
        let mut node_faces = vec![Vec::new(); nodes.len()];
        for (e, face) in secondary_faces.iter().enumerate() {
            for n in &face.nodes {
                if let Ok(i) = nodes.binary_search(n) {
                    node_faces[i].push(e);
                }
            }
        }
        let primary_nodes = mesh.surface_nodes(mesh.surface(primary)?);
        let reference = coordinates(&mesh.nodes, &vec![0.0; 3 * mesh.num_nodes()]);
        let area: f64 = primary_faces
            .iter()
            .map(|f| face_size(f, &reference).powi(2))
            .sum();
        let element_size = (area / primary_faces.len().max(1) as f64).sqrt();
        let mut out = Self {
            primary_surface: primary.to_string(),
            secondary_faces,
            primary_faces,
            primary_nodes,
            node_faces,
            candidates: Vec::new(),
            element_size,
            margin: 2.0 * element_size,
        };
        out.refresh(&mesh.nodes, &vec![0.0; 3 * mesh.num_nodes()], 0.0);
        Some(out)
    }

    /// Recompute the candidate face pairs at configuration `x`: each
    /// primary face's box grown by `2 h_f + 2 motion` against the
    /// secondary faces' boxes. Returns whether a pair changed.
    pub fn refresh(&mut self, reference: &[[f64; 3]], x: &[f64], motion: f64) -> bool {
        let xs = coordinates(reference, x);
        let mut smallest = f64::INFINITY;
        let tree = RTree::bulk_load(
            self.primary_faces
                .iter()
                .enumerate()
                .map(|(p, face)| {
                    let margin = 2.0 * face_size(face, &xs) + 2.0 * motion;
                    if margin > 0.0 {
                        smallest = smallest.min(margin);
                    }
                    let (lo, hi) = face_box(face, &xs, margin);
                    GeomWithData::new(Rectangle::from_corners(lo, hi), p)
                })
                .collect(),
        );
        let candidates: Vec<Vec<usize>> = self
            .secondary_faces
            .iter()
            .map(|face| {
                let (lo, hi) = face_box(face, &xs, 0.0);
                let mut found: Vec<usize> = tree
                    .locate_in_envelope_intersecting(AABB::from_corners(lo, hi))
                    .map(|p| p.data)
                    .collect();
                found.sort_unstable();
                found
            })
            .collect();
        let changed = candidates != self.candidates;
        self.candidates = candidates;
        if smallest.is_finite() {
            self.margin = smallest.max(1e-3 * self.element_size);
        }
        changed
    }

    /// The candidate (secondary face, primary face) pairs.
    pub fn pairs(&self) -> Vec<(usize, usize)> {
        self.candidates
            .iter()
            .enumerate()
            .flat_map(|(s, ps)| ps.iter().map(move |&p| (s, p)))
            .collect()
    }

    /// The mesh nodes secondary node `i`'s weighted gap may couple in this
    /// increment: the nodes of its faces (the normal, the transformation)
    /// and of their candidate primary faces (`M`); the node itself first.
    pub fn coupled_nodes(&self, i: usize, node: usize) -> Vec<usize> {
        let mut nodes = vec![node];
        for &e in &self.node_faces[i] {
            nodes.extend(&self.secondary_faces[e].nodes);
            for &p in &self.candidates[e] {
                nodes.extend(&self.primary_faces[p].nodes);
            }
        }
        nodes[1..].sort_unstable();
        let mut seen = std::collections::HashSet::new();
        nodes.retain(|n| seen.insert(*n));
        nodes
    }

    /// `D_j` of every secondary node `nodes` in the reference configuration
    /// of `mesh` (`None` where the coupling fails to integrate; 0 at a node
    /// without segments): the nodes' areas `A_j`.
    pub fn reference_areas(&self, mesh: &Mesh, nodes: &[usize]) -> Option<Vec<f64>> {
        let xs = coordinates(&mesh.nodes, &vec![0.0; 3 * mesh.num_nodes()]);
        let coupling = mortar_coupling(
            &self.secondary_faces,
            &self.primary_faces,
            &self.pairs(),
            &xs,
        )
        .ok()?;
        Some(
            nodes
                .iter()
                .map(|n| coupling.d.get(n).copied().unwrap_or(0.0))
                .collect(),
        )
    }
}

/// Current positions `X + u` of every mesh node.
fn coordinates(reference: &[[f64; 3]], x: &[f64]) -> Vec<Vector3<f64>> {
    (0..reference.len())
        .map(|n| current_position(reference, x, n))
        .collect()
}

/// A face's size: the square root of its corners' polygon area (the
/// diagonals' cross product).
fn face_size(face: &SurfaceFace, xs: &[Vector3<f64>]) -> f64 {
    let c = |k: usize| xs[face.nodes[k]];
    let area = if face.shape.is_triangle() {
        0.5 * (c(1) - c(0)).cross(&(c(2) - c(0))).norm()
    } else {
        0.5 * (c(2) - c(0)).cross(&(c(3) - c(1))).norm()
    };
    area.sqrt()
}

/// A face's bounding box grown by `margin`.
fn face_box(face: &SurfaceFace, xs: &[Vector3<f64>], margin: f64) -> ([f64; 3], [f64; 3]) {
    let first = xs[face.nodes[0]];
    let (lo, hi) = face.nodes.iter().fold((first, first), |(lo, hi), &n| {
        (lo.inf(&xs[n]), hi.sup(&xs[n]))
    });
    let (lo, hi) = (lo.add_scalar(-margin), hi.add_scalar(margin));
    ([lo.x, lo.y, lo.z], [hi.x, hi.y, hi.z])
}

/// One secondary node's row of the mortar coupling: what its weighted gap
/// is made of, at fixed `D`, `M`.
#[derive(Clone, Debug)]
pub struct NodeRow {
    /// `D_j`.
    pub d: f64,
    /// `(l, M_jl)` over the primary nodes.
    pub m: Vec<(usize, f64)>,
    /// `(k, R_jk)`: `x̃_j = Σ_k R_jk x_k`.
    pub transformation: Vec<(usize, f64)>,
    /// `n_j`.
    pub normal: Vector3<f64>,
    /// `(k, ∂n_j/∂x_k)` over the nodes of the node's faces.
    pub normal_derivatives: Vec<(usize, Matrix3<f64>)>,
}

/// The mortar gap producer in one configuration: the coupling `D`, `M`,
/// `n` integrated there, and the nodes' current positions.
pub struct MortarGap<'a> {
    pub surfaces: &'a MortarSurfaces,
    pub coupling: MortarCoupling,
    pub coordinates: Vec<Vector3<f64>>,
}

impl<'a> MortarGap<'a> {
    /// The producer at unknowns `x`. A face the kernels cannot integrate
    /// (degenerate, or a projection that fails) leaves every node open in
    /// this evaluation; the element assembly reports such a face's
    /// element.
    pub fn at(surfaces: &'a MortarSurfaces, reference: &[[f64; 3]], x: &[f64]) -> Self {
        let coordinates = coordinates(reference, x);
        let coupling = mortar_coupling(
            &surfaces.secondary_faces,
            &surfaces.primary_faces,
            &surfaces.pairs(),
            &coordinates,
        )
        .unwrap_or_default();
        Self {
            surfaces,
            coupling,
            coordinates,
        }
    }

    /// Secondary node `i` (mesh node `j`)'s row at fixed `D`, `M`: the one
    /// place that gathers it (the derivatives of `D`, `M` and of the
    /// segmentation will join here); `None` where `D_j ≤ 0`.
    pub fn node_row(&self, i: usize, j: usize) -> Option<NodeRow> {
        let d = *self.coupling.d.get(&j)?;
        if !(d > 0.0) {
            return None;
        }
        let m = self
            .coupling
            .m
            .range((j, 0)..=(j, usize::MAX))
            .filter(|entry| *entry.1 != 0.0)
            .map(|(&(_, l), &m)| (l, m))
            .collect();
        Some(NodeRow {
            d,
            m,
            transformation: self.coupling.transformation.get(&j)?.clone(),
            normal: *self.coupling.normals.get(&j)?,
            normal_derivatives: self.normal_derivatives(i, j)?,
        })
    }

    /// `∂n_j/∂x_k` for every node `k` of node `i`'s faces, column `d` the
    /// directional derivative ([`nodal_normal_derivatives`]) along `x_k`'s
    /// axis `d`, on the node's faces alone (renumbered locally).
    fn normal_derivatives(&self, i: usize, j: usize) -> Option<Vec<(usize, Matrix3<f64>)>> {
        let faces = &self.surfaces.node_faces[i];
        let mut nodes: Vec<usize> = faces
            .iter()
            .flat_map(|&e| self.surfaces.secondary_faces[e].nodes.iter().copied())
            .collect();
        nodes.sort_unstable();
        nodes.dedup();
        let local = |n: &usize| nodes.binary_search(n).ok();
        let local_faces: Vec<SurfaceFace> = faces
            .iter()
            .map(|&e| {
                let face = &self.surfaces.secondary_faces[e];
                let nodes = face.nodes.iter().filter_map(local).collect();
                SurfaceFace {
                    shape: face.shape,
                    nodes,
                }
            })
            .collect();
        let xs: Vec<Vector3<f64>> = nodes.iter().map(|&n| self.coordinates[n]).collect();
        let me = local(&j)?;
        let mut out = Vec::with_capacity(nodes.len());
        for (a, &k) in nodes.iter().enumerate() {
            let mut block = Matrix3::zeros();
            for axis in 0..3 {
                let mut dx = vec![Vector3::zeros(); nodes.len()];
                dx[a][axis] = 1.0;
                let dn = nodal_normal_derivatives(&local_faces, &xs, &dx).ok()?;
                block.set_column(axis, dn.get(&me)?);
            }
            out.push((k, block));
        }
        Some(out)
    }

    /// The node's kinematics from its `row` (see the module docs): `q`
    /// over the node, its faces' nodes and its primary nodes.
    pub fn row_kinematics(&self, j: usize, row: &NodeRow) -> GapKinematics<Dyn> {
        let mut nodes: CoupledNodes = smallvec::smallvec![j];
        let all = row.transformation.iter().map(|(k, _)| *k);
        let all = all.chain(row.normal_derivatives.iter().map(|(k, _)| *k));
        for n in all.chain(row.m.iter().map(|(l, _)| *l)) {
            if !nodes.contains(&n) {
                nodes.push(n);
            }
        }
        let at = |n: usize| 3 * nodes.iter().position(|&m| m == n).unwrap_or(0);
        let q = Dyn(3 * nodes.len());
        let (n, d) = (row.normal, row.d);
        // v = Σ_l M_jl x_l − D_j x̃_j, g̃ = n·v
        let mut v: Vector3<f64> = row.m.iter().map(|(l, m)| self.coordinates[*l] * *m).sum();
        for (k, r) in &row.transformation {
            v -= self.coordinates[*k] * (d * r);
        }
        let mut lever = DVector::zeros(3 * nodes.len());
        for (k, r) in &row.transformation {
            lever.fixed_rows_mut::<3>(at(*k)).axpy(-d * r, &n, 1.0);
        }
        for (l, m) in &row.m {
            lever.fixed_rows_mut::<3>(at(*l)).axpy(*m, &n, 1.0);
        }
        let mut normal_gradient = OMatrix::<f64, U3, Dyn>::zeros_generic(U3, q);
        for (k, dn) in &row.normal_derivatives {
            normal_gradient.fixed_columns_mut::<3>(at(*k)).copy_from(dn);
        }
        let gradient = &lever + normal_gradient.transpose() * v;
        // ∂b̃/∂q: rows k get −D R_jk ∂n/∂q, rows l get M_jl ∂n/∂q
        let mut hessian = DMatrix::zeros(3 * nodes.len(), 3 * nodes.len());
        let weights = row.transformation.iter().map(|(k, r)| (*k, -d * r));
        for (node, w) in weights.chain(row.m.iter().copied()) {
            let mut rows = hessian.fixed_rows_mut::<3>(at(node));
            rows += w * &normal_gradient;
        }
        // the driver's normal points from the primary toward the secondary
        // body (`∂g/∂x_j = −R_jj n_j`): the force on the secondary node is
        // along `−n_j`
        GapKinematics {
            primary: row
                .m
                .iter()
                .map(|(l, m)| (*l, m / d))
                .collect::<PrimaryWeights>(),
            nodes,
            gap: n.dot(&v) / d,
            gradient: gradient / d,
            lever: Some(lever / d),
            hessian: hessian / d,
            area: Some(d),
            normal: -n,
            normal_gradient: -normal_gradient,
            facet: None,
            point: (),
        }
    }
}

impl GapProducer<Dyn> for MortarGap<'_> {
    type Point = ();

    /// The node's row at fixed `D`, `M`, carried to its unknowns; `None`
    /// without a segment (`D_j ≤ 0`).
    fn kinematics(
        &self,
        node: &SecondaryNode,
        _state: &NodeContactState,
    ) -> Option<GapKinematics<Dyn>> {
        let row = self.node_row(node.index, node.mesh_node)?;
        Some(self.row_kinematics(node.mesh_node, &row))
    }

    fn open_gap(&self) -> f64 {
        self.surfaces.margin
    }

    fn relative_position(&self, node: &SecondaryNode) -> Vector3<f64> {
        node.position()
    }

    /// Mortar is frictionless this session (the case file refuses
    /// `friction_coefficient` with `discretisation = "mortar"`): a frame
    /// with no lever, so no tangential force reaches the nodes.
    fn slip(
        &self,
        node: &SecondaryNode,
        kinematics: &mut GapKinematics<Dyn>,
        history: &FrictionHistory,
    ) -> SlipFrame<Dyn> {
        let q = Dyn(kinematics.gradient.len());
        let zero = OMatrix::<f64, U3, Dyn>::zeros_generic(U3, q);
        SlipFrame {
            kinematics: SlipKinematics {
                traction: Vector3::zeros(),
                traction_gradient: zero.clone(),
                offset: node.position() - history.anchor,
                offset_gradient: zero.clone(),
                normal: kinematics.normal,
                normal_gradient: kinematics.normal_gradient.clone(),
            },
            lever: zero,
        }
    }

    fn stick_stiffness(
        &self,
        kinematics: &GapKinematics<Dyn>,
        _: &SlipFrame<Dyn>,
        _: &TangentialResponse<Dyn>,
        _: &Coulomb,
        _: f64,
    ) -> DMatrix<f64> {
        let q = kinematics.gradient.len();
        DMatrix::zeros(q, q)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::laws::{NodeContactState, NormalLaw};
    use crate::mesh::structured::box_mesh;
    use crate::mesh::{ElementKind, Mesh, Region, SurfaceSet};

    /// A 2 × 2 Quad4 (or Quad8) secondary patch (an upper block's bottom)
    /// over a 3 × 3 primary one (a lower block's top), the upper block
    /// warped and pressed in by `depth`: the mesh and the two surfaces.
    fn pair(kind: ElementKind) -> (Mesh, MortarSurfaces, Vec<usize>) {
        let lower = box_mesh(kind, [3, 3, 1], [1.0, 1.0, 0.5]);
        let upper = box_mesh(kind, [2, 2, 1], [1.0, 1.0, 0.5]);
        let n = lower.nodes.len();
        let mut mesh = lower.clone();
        mesh.nodes
            .extend(upper.nodes.iter().map(|x| [x[0], x[1], x[2] + 0.5]));
        mesh.node_ids = (1..=mesh.nodes.len() as u64).collect();
        mesh.regions = vec![Region {
            name: "body".into(),
            elements: vec![],
        }];
        let shifted = |s: &SurfaceSet, name: &str, by: usize| {
            let mut s = s.clone();
            s.name = name.into();
            s.facets
                .iter_mut()
                .for_each(|f| f.nodes.iter_mut().for_each(|k| *k += by));
            s
        };
        mesh.elements.clear();
        mesh.surfaces = vec![
            shifted(lower.surface("zmax").unwrap(), "primary", 0),
            shifted(upper.surface("zmin").unwrap(), "secondary", n),
        ];
        let nodes = mesh.surface_nodes(mesh.surface("secondary").unwrap());
        let surfaces = MortarSurfaces::from_mesh(&mesh, "secondary", "primary", &nodes).unwrap();
        (mesh, surfaces, nodes)
    }

    /// A configuration that warps both surfaces and presses the secondary
    /// `nodes` in by 0.03.
    fn state(mesh: &Mesh, nodes: &[usize]) -> Vec<f64> {
        let mut x: Vec<f64> = (0..3 * mesh.nodes.len())
            .map(|i| 0.005 * ((i as f64) * 0.77).sin())
            .collect();
        nodes.iter().for_each(|&n| x[3 * n + 2] -= 0.03);
        x
    }

    /// The producer at `x` with the coupling's `D`, `M` frozen at `fixed`
    /// (its normals those of `x`): the fixed segmentation the driver's
    /// terms are differentiated at.
    fn frozen<'a>(
        s: &'a MortarSurfaces,
        mesh: &Mesh,
        fixed: &MortarCoupling,
        x: &[f64],
    ) -> MortarGap<'a> {
        let mut p = MortarGap::at(s, &mesh.nodes, x);
        p.coupling = MortarCoupling {
            normals: p.coupling.normals.clone(),
            ..fixed.clone()
        };
        p
    }

    /// The driver's terms of a mortar node at fixed `D`, `M` against
    /// central differences (step 1e-6): `∇g` of the normalised gap,
    /// `∂b/∂q` of the lever, `∂n/∂q`, and the normal law's `r_q = f b`
    /// with its `K_qq = (∂f/∂g) b ∇gᵀ + f ∂b/∂q`, to 1e-7 of their size;
    /// on linear and quadratic faces.
    #[test]
    fn driver_terms_match_finite_differences_at_fixed_segmentation() {
        for kind in [ElementKind::Hex8, ElementKind::Hex20] {
            let (mesh, surfaces, nodes) = pair(kind);
            let x = state(&mesh, &nodes);
            let fixed = MortarGap::at(&surfaces, &mesh.nodes, &x).coupling;
            let law = NormalLaw::Penalty { epsilon: 300.0 };
            let st = NodeContactState::initial(&law, -1.0);
            let mut checked = 0;
            for (i, &j) in nodes.iter().enumerate().take(nodes.len() / 2 + 3) {
                let p0 = frozen(&surfaces, &mesh, &fixed, &x);
                let Some(row) = p0.node_row(i, j) else {
                    continue;
                };
                let k0 = p0.row_kinematics(j, &row);
                let r0 = k0.normal_response(&law, k0.area.unwrap(), &st);
                assert!(r0.active, "{kind:?} node {j} closed");
                let lever = k0.lever.clone().unwrap();
                let h = 1e-6;
                for (a, &node) in k0.nodes.iter().enumerate() {
                    for d in 0..3 {
                        let at = |s: f64| {
                            let mut y = x.clone();
                            y[3 * node + d] += s * h;
                            let p = frozen(&surfaces, &mesh, &fixed, &y);
                            let k = p.row_kinematics(j, &p.node_row(i, j).unwrap());
                            assert_eq!(k.nodes, k0.nodes);
                            let r = k.normal_response(&law, k.area.unwrap(), &st);
                            (k, r)
                        };
                        let ((kp, rp), (km, rm)) = (at(1.0), at(-1.0));
                        let c = 3 * a + d;
                        let close = |fd: f64, exact: f64, scale: f64, what: &str| {
                            assert!(
                                (fd - exact).abs() <= 1e-7 * scale,
                                "{kind:?} node {j}, q{c} {what}: fd {fd:e} exact {exact:e}"
                            );
                        };
                        let scale = k0.gradient.amax().max(1.0);
                        close((kp.gap - km.gap) / (2.0 * h), k0.gradient[c], scale, "∇g");
                        for r in 0..k0.gradient.len() {
                            let fd = (kp.lever.as_ref().unwrap()[r]
                                - km.lever.as_ref().unwrap()[r])
                                / (2.0 * h);
                            close(fd, k0.hessian[(r, c)], lever.amax().max(1.0), "∂b/∂q");
                            let fd = (rp.residual[r] - rm.residual[r]) / (2.0 * h);
                            close(fd, r0.stiffness[(r, c)], r0.stiffness.amax(), "K_qq");
                        }
                        for r in 0..3 {
                            let fd = (kp.normal[r] - km.normal[r]) / (2.0 * h);
                            close(fd, k0.normal_gradient[(r, c)], 1.0, "∂n/∂q");
                        }
                    }
                }
                checked += 1;
            }
            assert!(checked >= 4, "{kind:?}: {checked} nodes checked");
        }
    }
}
