//! Meshes and reference integrals shared by the mortar tests.
#![allow(dead_code)]

use std::collections::BTreeMap;

use nalgebra::Vector3;
use signorini::contact::mortar::{FaceShape, MortarFace, SurfaceFace};

/// A structured surface on the grid `xs × ys` at height `z`, split into
/// `shape` faces (two triangles per cell for Tri3/Tri6), with nodes
/// appended to `coords`. `facing_down` reverses the corner order so the
/// face normal is −z (a primary surface above a secondary one).
/// `perturb(x, y)` moves the interior corner nodes in the plane.
pub fn grid(
    xs: &[f64],
    ys: &[f64],
    z: f64,
    shape: FaceShape,
    facing_down: bool,
    perturb: &dyn Fn(f64, f64) -> [f64; 2],
    coords: &mut Vec<Vector3<f64>>,
) -> Vec<SurfaceFace> {
    let first = coords.len();
    let (nx, ny) = (xs.len(), ys.len());
    for (j, y) in ys.iter().enumerate() {
        for (i, x) in xs.iter().enumerate() {
            let interior = i > 0 && i + 1 < nx && j > 0 && j + 1 < ny;
            let d = if interior {
                perturb(*x, *y)
            } else {
                [0.0, 0.0]
            };
            coords.push(Vector3::new(x + d[0], y + d[1], z));
        }
    }
    let id = |i: usize, j: usize| first + j * nx + i;
    let mut corner_sets = Vec::new();
    for j in 0..ny - 1 {
        for i in 0..nx - 1 {
            let q = [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)];
            if shape.is_triangle() {
                corner_sets.push(vec![q[0], q[1], q[2]]);
                corner_sets.push(vec![q[0], q[2], q[3]]);
            } else {
                corner_sets.push(q.to_vec());
            }
        }
    }
    let mut mids: BTreeMap<(usize, usize), usize> = BTreeMap::new();
    corner_sets
        .into_iter()
        .map(|mut corners| {
            if facing_down {
                corners.reverse();
            }
            let mut nodes = corners.clone();
            if shape.is_quadratic() {
                for e in 0..corners.len() {
                    let (a, b) = (corners[e], corners[(e + 1) % corners.len()]);
                    let key = (a.min(b), a.max(b));
                    let m = *mids.entry(key).or_insert_with(|| {
                        coords.push((coords[a] + coords[b]) * 0.5);
                        coords.len() - 1
                    });
                    nodes.push(m);
                }
            }
            SurfaceFace { shape, nodes }
        })
        .collect()
}

/// Uniformly spaced points `a, …, b` (`n` intervals).
pub fn linspace(a: f64, b: f64, n: usize) -> Vec<f64> {
    (0..=n).map(|i| a + (b - a) * i as f64 / n as f64).collect()
}

/// The consistent nodal integrals `∫ N_k dA` of a surface (Lagrange
/// functions, face rule), per global node.
pub fn consistent_integrals(
    faces: &[SurfaceFace],
    coords: &[Vector3<f64>],
) -> BTreeMap<usize, f64> {
    nodal_integrals(faces, coords, &|shape, xi| shape.values(xi).to_vec())
}

/// `Σ_e ∫_e f_k dA` per global node for the nodal functions `f(shape, ξ)`.
pub fn nodal_integrals(
    faces: &[SurfaceFace],
    coords: &[Vector3<f64>],
    f: &dyn Fn(FaceShape, [f64; 2]) -> Vec<f64>,
) -> BTreeMap<usize, f64> {
    let mut out = BTreeMap::new();
    for sf in faces {
        let face: MortarFace = sf.with_coordinates(coords).unwrap();
        let (points, weights) = sf.shape.quadrature();
        for (xi, w) in points.iter().zip(weights) {
            let da = w * face.area_normal(*xi).norm();
            for (node, n) in sf.nodes.iter().zip(f(sf.shape, *xi)) {
                *out.entry(*node).or_insert(0.0) += n * da;
            }
        }
    }
    out
}

/// A deterministic pseudo-random number in [−1, 1] from a seed (no `rand`
/// state needed across calls).
pub fn hash_unit(seed: f64) -> f64 {
    let s = (seed * 12.9898 + 78.233).sin() * 43758.5453;
    2.0 * (s - s.floor()) - 1.0
}

/// `(x, y, z)`.
pub fn v(x: f64, y: f64, z: f64) -> Vector3<f64> {
    Vector3::new(x, y, z)
}

/// A pseudo-random increment per node.
pub fn increments(n: usize, seed: f64) -> Vec<Vector3<f64>> {
    (0..n)
        .map(|i| {
            let s = seed + 3.1 * i as f64;
            v(hash_unit(s), hash_unit(s + 1.0), hash_unit(s + 2.0))
        })
        .collect()
}

/// `x + h δx` node by node.
pub fn shifted(xs: &[Vector3<f64>], dx: &[Vector3<f64>], h: f64) -> Vec<Vector3<f64>> {
    xs.iter().zip(dx).map(|(x, d)| x + d * h).collect()
}

/// A warped or curved face of each shape (corners out of plane, mid-side
/// nodes off their edges).
pub fn curved_face(shape: FaceShape) -> MortarFace {
    let mut xs = match shape.corner_count() {
        3 => vec![v(0.0, 0.0, 0.0), v(1.5, 0.2, 0.1), v(0.3, 1.2, -0.1)],
        _ => vec![
            v(0.0, 0.0, 0.0),
            v(1.6, 0.1, 0.15),
            v(1.8, 1.4, -0.1),
            v(-0.1, 1.2, 0.05),
        ],
    };
    let corners = xs.clone();
    for (m, [a, b]) in signorini::contact::mortar::quadratic::mid_side_edges(shape)
        .iter()
        .enumerate()
    {
        xs.push((corners[*a] + corners[*b]) * 0.5 + v(0.03 * m as f64, -0.04, 0.08));
    }
    MortarFace::new(shape, xs).unwrap()
}

/// The in-plane moves of interior corners: pseudo-random, up to 0.04, on
/// triangle meshes; none on quadrilateral ones.
pub fn in_plane_moves(shape: FaceShape) -> fn(f64, f64) -> [f64; 2] {
    fn perturb(x: f64, y: f64) -> [f64; 2] {
        [0.04 * hash_unit(x + 7.0 * y), 0.04 * hash_unit(5.0 * x - y)]
    }
    fn none(_: f64, _: f64) -> [f64; 2] {
        [0.0, 0.0]
    }
    if shape.is_triangle() {
        perturb
    } else {
        none
    }
}

/// The secondary surface of the stacked tests: `[0, 1] × [0, 0.8]` at
/// `z = 0` (normal +z) on the coarse graded grid `{0, 0.3, 0.55, 1} ×
/// {0, 0.45, 0.8}`, with [`in_plane_moves`].
pub fn graded_secondary(shape: FaceShape, coords: &mut Vec<Vector3<f64>>) -> Vec<SurfaceFace> {
    grid(
        &[0.0, 0.3, 0.55, 1.0],
        &[0.0, 0.45, 0.8],
        0.0,
        shape,
        false,
        &in_plane_moves(shape),
        coords,
    )
}

/// The four face shapes.
pub const SHAPES: [FaceShape; 4] = [
    FaceShape::Tri3,
    FaceShape::Quad4,
    FaceShape::Tri6,
    FaceShape::Quad8,
];
