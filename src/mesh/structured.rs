//! Structured box meshes built in code, for tests and benchmarks: a box
//! `[0, Lx] × [0, Ly] × [0, Lz]` with `nx × ny × nz` cells, as Hex8, as
//! Tet4 (six Kuhn tetrahedra per cell, conforming across cells) or as
//! Wedge6 (two per cell, split along the cell's diagonal `0–2` in `xy`),
//! and their quadratic kinds with a node at the middle of each edge
//! ([`with_mid_side_nodes`]). The region
//! is `"body"`; the six sides are the surface sets `xmin`, `xmax`, `ymin`,
//! `ymax`, `zmin`, `zmax`, outward-oriented.

use super::{
    boundary::boundary_facets, topology, Element, ElementKind, FacetKind, Mesh, Region, SurfaceSet,
};
use std::collections::HashMap;

/// A structured box mesh. See the module documentation.
pub fn box_mesh(kind: ElementKind, cells: [usize; 3], lengths: [f64; 3]) -> Mesh {
    let linear = box_mesh_linear(topology::linear(kind), cells, lengths);
    if kind.is_quadratic() {
        with_mid_side_nodes(&linear, kind)
    } else {
        linear
    }
}

/// The mesh `linear` with every element whose corners make a `kind`
/// (its [`topology::linear`] kind) turned into a `kind`, a new node at the
/// middle of each of its edges (shared by the elements on the edge), and
/// the facets of the surface sets given their mid-side nodes: the
/// straight-sided quadratic mesh on the same corners.
pub fn with_mid_side_nodes(linear: &Mesh, kind: ElementKind) -> Mesh {
    let mut mesh = linear.clone();
    let mut mid: HashMap<[usize; 2], usize> = HashMap::new();
    let mut next_id = mesh.node_ids.iter().max().map_or(1, |m| m + 1);
    let mut node_on = |mesh: &mut Mesh, a: usize, b: usize| {
        *mid.entry(sorted_pair(a, b)).or_insert_with(|| {
            let (xa, xb) = (mesh.nodes[a], mesh.nodes[b]);
            mesh.nodes
                .push(std::array::from_fn(|d| 0.5 * (xa[d] + xb[d])));
            mesh.node_ids.push(next_id);
            next_id += 1;
            mesh.nodes.len() - 1
        })
    };
    for e in 0..mesh.elements.len() {
        if mesh.elements[e].kind != topology::linear(kind) {
            continue;
        }
        let corners = mesh.elements[e].nodes.clone();
        let mut nodes = corners.clone();
        for [a, b] in topology::edges(kind) {
            nodes.push(node_on(&mut mesh, corners[*a], corners[*b]));
        }
        mesh.elements[e] = Element {
            kind,
            nodes,
            id: mesh.elements[e].id,
        };
    }
    for s in 0..mesh.surfaces.len() {
        for f in 0..mesh.surfaces[s].facets.len() {
            let corners = mesh.surfaces[s].facets[f].nodes.clone();
            let c = corners.len();
            let Some(edges) = (0..c)
                .map(|k| {
                    mid.get(&sorted_pair(corners[k], corners[(k + 1) % c]))
                        .copied()
                })
                .collect::<Option<Vec<usize>>>()
            else {
                continue;
            };
            let facet = &mut mesh.surfaces[s].facets[f];
            facet.nodes.extend(edges);
            facet.kind = FacetKind::of_node_count(facet.nodes.len()).unwrap_or(facet.kind);
        }
    }
    mesh
}

fn sorted_pair(a: usize, b: usize) -> [usize; 2] {
    [a.min(b), a.max(b)]
}

/// [`box_mesh`] of a linear kind (Tet4, Hex8, Wedge6).
fn box_mesh_linear(kind: ElementKind, cells: [usize; 3], lengths: [f64; 3]) -> Mesh {
    let [nx, ny, nz] = cells;
    let node = |i: usize, j: usize, k: usize| i + (nx + 1) * (j + (ny + 1) * k);
    let mut nodes = Vec::with_capacity((nx + 1) * (ny + 1) * (nz + 1));
    for k in 0..=nz {
        for j in 0..=ny {
            for i in 0..=nx {
                nodes.push([
                    lengths[0] * i as f64 / nx as f64,
                    lengths[1] * j as f64 / ny as f64,
                    lengths[2] * k as f64 / nz as f64,
                ]);
            }
        }
    }
    let mut elements = Vec::new();
    for k in 0..nz {
        for j in 0..ny {
            for i in 0..nx {
                // corners in Gmsh Hex8 order
                let c = [
                    node(i, j, k),
                    node(i + 1, j, k),
                    node(i + 1, j + 1, k),
                    node(i, j + 1, k),
                    node(i, j, k + 1),
                    node(i + 1, j, k + 1),
                    node(i + 1, j + 1, k + 1),
                    node(i, j + 1, k + 1),
                ];
                match kind {
                    ElementKind::Tet4 => {
                        for tet in kuhn_tetrahedra(&c) {
                            elements.push(tet.to_vec());
                        }
                    }
                    ElementKind::Wedge6 => {
                        elements.push(vec![c[0], c[1], c[2], c[4], c[5], c[6]]);
                        elements.push(vec![c[0], c[2], c[3], c[4], c[6], c[7]]);
                    }
                    _ => elements.push(c.to_vec()),
                }
            }
        }
    }
    let elements: Vec<Element> = elements
        .into_iter()
        .enumerate()
        .map(|(e, nodes)| Element {
            kind,
            nodes,
            id: e as u64 + 1,
        })
        .collect();
    let node_ids = (1..=nodes.len() as u64).collect();
    let mut mesh = Mesh {
        nodes,
        node_ids,
        regions: vec![Region {
            name: "body".into(),
            elements: (0..elements.len()).collect(),
        }],
        elements,
        surfaces: Vec::new(),
        node_sets: Vec::new(),
    };
    let names = ["xmin", "xmax", "ymin", "ymax", "zmin", "zmax"];
    let mut sets: Vec<SurfaceSet> = names
        .iter()
        .map(|n| SurfaceSet {
            name: n.to_string(),
            facets: Vec::new(),
        })
        .collect();
    let tol = 1e-12;
    for (f, mut facet) in boundary_facets(&mesh).into_iter().enumerate() {
        facet.id = f as u64 + 1;
        for d in 0..3 {
            for (side, value) in [(0, 0.0), (1, lengths[d])] {
                if facet
                    .nodes
                    .iter()
                    .all(|&n| (mesh.nodes[n][d] - value).abs() < tol * lengths[d])
                {
                    sets[2 * d + side].facets.push(facet.clone());
                }
            }
        }
    }
    mesh.surfaces = sets;
    mesh
}

/// The six Kuhn tetrahedra of a hexahedral cell (corners in Gmsh order),
/// all sharing the diagonal 0–6, each positively oriented.
fn kuhn_tetrahedra(c: &[usize; 8]) -> [[usize; 4]; 6] {
    // paths from corner 0 to corner 6 through the cube's edges
    [
        [c[0], c[1], c[2], c[6]],
        [c[0], c[2], c[3], c[6]],
        [c[0], c[3], c[7], c[6]],
        [c[0], c[7], c[4], c[6]],
        [c[0], c[4], c[5], c[6]],
        [c[0], c[5], c[1], c[6]],
    ]
}

/// Move every node not on the box boundary by a pseudo-random amount of up
/// to `fraction` of the smallest cell size in each direction (a
/// deterministic generator, so tests are repeatable). Used to make the
/// irregular meshes of patch tests.
pub fn perturb_interior(
    mesh: &mut Mesh,
    cells: [usize; 3],
    lengths: [f64; 3],
    fraction: f64,
    seed: u64,
) {
    let mut state = seed
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    let mut next = move || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((state >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
    };
    let h = (0..3)
        .map(|d| lengths[d] / cells[d] as f64)
        .fold(f64::INFINITY, f64::min);
    for x in &mut mesh.nodes {
        let interior =
            (0..3).all(|d| x[d] > 1e-12 * lengths[d] && x[d] < lengths[d] * (1.0 - 1e-12));
        let shifts = [next(), next(), next()];
        if interior {
            for d in 0..3 {
                x[d] += fraction * h * shifts[d];
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn signed_volume(mesh: &Mesh, e: &Element) -> f64 {
        let p = |a: usize| nalgebra::Vector3::from(mesh.nodes[e.nodes[a]]);
        (p(1) - p(0)).cross(&(p(2) - p(0))).dot(&(p(3) - p(0))) / 6.0
    }

    #[test]
    fn tet_box_is_positive_and_fills_the_volume() {
        let mesh = box_mesh(ElementKind::Tet4, [3, 2, 2], [1.0, 2.0, 0.5]);
        assert_eq!(mesh.elements.len(), 6 * 12);
        let v: f64 = mesh
            .elements
            .iter()
            .map(|e| {
                let v = signed_volume(&mesh, e);
                assert!(v > 0.0);
                v
            })
            .sum();
        assert!((v - 1.0).abs() < 1e-12);
        // each side is split into two triangles per cell face
        assert_eq!(mesh.surface("xmin").unwrap().facets.len(), 2 * 2 * 2);
        assert_eq!(mesh.surface("zmax").unwrap().facets.len(), 2 * 3 * 2);
    }

    #[test]
    fn facets_point_outward() {
        for kind in [ElementKind::Tet4, ElementKind::Hex8] {
            let mesh = box_mesh(kind, [2, 2, 2], [1.0, 1.0, 1.0]);
            for (d, s) in [
                (0, "xmin"),
                (0, "xmax"),
                (1, "ymin"),
                (1, "ymax"),
                (2, "zmin"),
                (2, "zmax"),
            ] {
                let sign = if s.ends_with("max") { 1.0 } else { -1.0 };
                for f in &mesh.surface(s).unwrap().facets {
                    let p = |a: usize| nalgebra::Vector3::from(mesh.nodes[f.nodes[a]]);
                    let n = (p(1) - p(0)).cross(&(p(f.nodes.len() - 1) - p(0)));
                    assert!(n[d] * sign > 0.0, "{s} facet not outward");
                }
            }
        }
    }
}
