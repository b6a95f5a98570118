//! Lagrange shape functions `N_a(ξ)` and their reference gradients
//! `∂N_a/∂ξ`, with Gmsh's node numbering.

use crate::mesh::{topology, ElementKind};

/// Hex8 / Quad4 corner signs in Gmsh order.
const HEX8_CORNERS: [[f64; 3]; 8] = [
    [-1.0, -1.0, -1.0],
    [1.0, -1.0, -1.0],
    [1.0, 1.0, -1.0],
    [-1.0, 1.0, -1.0],
    [-1.0, -1.0, 1.0],
    [1.0, -1.0, 1.0],
    [1.0, 1.0, 1.0],
    [-1.0, 1.0, 1.0],
];

/// Tet4 on the unit tetrahedron: `N = (1 − ξ − η − ζ, ξ, η, ζ)`.
pub fn tet4_values(x: &[f64; 3]) -> [f64; 4] {
    [1.0 - x[0] - x[1] - x[2], x[0], x[1], x[2]]
}

/// Reference gradients of the Tet4 shape functions (constant).
pub fn tet4_gradients(_x: &[f64; 3]) -> [[f64; 3]; 4] {
    [
        [-1.0, -1.0, -1.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
    ]
}

/// Hex8 on [−1, 1]³: `N_a = ⅛ (1 + ξ ξ_a)(1 + η η_a)(1 + ζ ζ_a)`.
pub fn hex8_values(x: &[f64; 3]) -> [f64; 8] {
    HEX8_CORNERS.map(|c| 0.125 * (1.0 + x[0] * c[0]) * (1.0 + x[1] * c[1]) * (1.0 + x[2] * c[2]))
}

/// Reference gradients of the Hex8 shape functions.
pub fn hex8_gradients(x: &[f64; 3]) -> [[f64; 3]; 8] {
    HEX8_CORNERS.map(|c| {
        let (a, b, d) = (1.0 + x[0] * c[0], 1.0 + x[1] * c[1], 1.0 + x[2] * c[2]);
        [
            0.125 * c[0] * b * d,
            0.125 * a * c[1] * d,
            0.125 * a * b * c[2],
        ]
    })
}

/// Tri3 on the unit triangle: `N = (1 − ξ − η, ξ, η)`.
pub fn tri3_values(x: &[f64; 2]) -> [f64; 3] {
    [1.0 - x[0] - x[1], x[0], x[1]]
}

/// Reference gradients of the Tri3 shape functions (constant).
pub fn tri3_gradients(_x: &[f64; 2]) -> [[f64; 2]; 3] {
    [[-1.0, -1.0], [1.0, 0.0], [0.0, 1.0]]
}

/// Quad4 on [−1, 1]²: `N_a = ¼ (1 + ξ ξ_a)(1 + η η_a)`.
pub fn quad4_values(x: &[f64; 2]) -> [f64; 4] {
    let c = &HEX8_CORNERS[..4];
    [0, 1, 2, 3].map(|a| 0.25 * (1.0 + x[0] * c[a][0]) * (1.0 + x[1] * c[a][1]))
}

/// Reference gradients of the Quad4 shape functions.
pub fn quad4_gradients(x: &[f64; 2]) -> [[f64; 2]; 4] {
    let c = &HEX8_CORNERS[..4];
    [0, 1, 2, 3].map(|a| {
        [
            0.25 * c[a][0] * (1.0 + x[1] * c[a][1]),
            0.25 * (1.0 + x[0] * c[a][0]) * c[a][1],
        ]
    })
}

/// Tri6 mid-side nodes `3‥5` (Gmsh and VTK order): between corners
/// `(0, 1)`, `(1, 2)` and `(2, 0)`.
const TRI6_EDGES: [[usize; 2]; 3] = [[0, 1], [1, 2], [2, 0]];

/// Tri6 on the unit triangle, with the area coordinates
/// `L = (1 − ξ − η, ξ, η)`: corners `N_i = L_i (2 L_i − 1)`, mid-side nodes
/// `N = 4 L_i L_j` on the edge `(i, j)`.
pub fn tri6_values(x: &[f64; 2]) -> [f64; 6] {
    let l = tri3_values(x);
    let mut n = [0.0; 6];
    for i in 0..3 {
        n[i] = l[i] * (2.0 * l[i] - 1.0);
    }
    for (m, [i, j]) in TRI6_EDGES.iter().enumerate() {
        n[3 + m] = 4.0 * l[*i] * l[*j];
    }
    n
}

/// Reference gradients of the Tri6 shape functions:
/// `∇N_i = (4 L_i − 1) ∇L_i` at the corners, `4 (L_i ∇L_j + L_j ∇L_i)` on
/// the edges.
pub fn tri6_gradients(x: &[f64; 2]) -> [[f64; 2]; 6] {
    let l = tri3_values(x);
    let dl = tri3_gradients(x);
    let mut g = [[0.0; 2]; 6];
    for i in 0..3 {
        g[i] = dl[i].map(|d| (4.0 * l[i] - 1.0) * d);
    }
    for (m, [i, j]) in TRI6_EDGES.iter().enumerate() {
        g[3 + m] = [0, 1].map(|d| 4.0 * (l[*i] * dl[*j][d] + l[*j] * dl[*i][d]));
    }
    g
}

/// Quad8 mid-side nodes `4‥7` (Gmsh and VTK order) in reference
/// coordinates: between corners `(0, 1)`, `(1, 2)`, `(2, 3)` and `(3, 0)`.
const QUAD8_MID_SIDES: [[f64; 2]; 4] = [[0.0, -1.0], [1.0, 0.0], [0.0, 1.0], [-1.0, 0.0]];

/// Quad8 (serendipity) on [−1, 1]²: corners
/// `N_a = ¼ (1 + ξ ξ_a)(1 + η η_a)(ξ ξ_a + η η_a − 1)`, mid-side nodes
/// `N = ½ (1 − ξ²)(1 + η η_a)` where `ξ_a = 0` and
/// `N = ½ (1 + ξ ξ_a)(1 − η²)` where `η_a = 0`.
pub fn quad8_values(x: &[f64; 2]) -> [f64; 8] {
    let (xi, eta) = (x[0], x[1]);
    let mut n = [0.0; 8];
    for (a, c) in HEX8_CORNERS[..4].iter().enumerate() {
        let (p, q) = (xi * c[0], eta * c[1]);
        n[a] = 0.25 * (1.0 + p) * (1.0 + q) * (p + q - 1.0);
    }
    for (m, c) in QUAD8_MID_SIDES.iter().enumerate() {
        n[4 + m] = if c[0] == 0.0 {
            0.5 * (1.0 - xi * xi) * (1.0 + eta * c[1])
        } else {
            0.5 * (1.0 + xi * c[0]) * (1.0 - eta * eta)
        };
    }
    n
}

/// Reference gradients of the Quad8 shape functions: at the corners
/// `∂N_a/∂ξ = ¼ ξ_a (1 + η η_a)(2 ξ ξ_a + η η_a)` and
/// `∂N_a/∂η = ¼ η_a (1 + ξ ξ_a)(ξ ξ_a + 2 η η_a)`.
pub fn quad8_gradients(x: &[f64; 2]) -> [[f64; 2]; 8] {
    let (xi, eta) = (x[0], x[1]);
    let mut g = [[0.0; 2]; 8];
    for (a, c) in HEX8_CORNERS[..4].iter().enumerate() {
        let (p, q) = (xi * c[0], eta * c[1]);
        g[a] = [
            0.25 * c[0] * (1.0 + q) * (2.0 * p + q),
            0.25 * c[1] * (1.0 + p) * (p + 2.0 * q),
        ];
    }
    for (m, c) in QUAD8_MID_SIDES.iter().enumerate() {
        g[4 + m] = if c[0] == 0.0 {
            [-xi * (1.0 + eta * c[1]), 0.5 * (1.0 - xi * xi) * c[1]]
        } else {
            [0.5 * c[0] * (1.0 - eta * eta), -eta * (1.0 + xi * c[0])]
        };
    }
    g
}

/// The reference coordinates of the nodes of `kind` (the corners of the
/// unit tetrahedron, of [−1, 1]³, or of the wedge `{ξ, η ≥ 0, ξ + η ≤ 1} ×
/// [−1, 1]`; the mid-side nodes halfway along their edges,
/// [`topology::edges`]).
pub fn reference_nodes(kind: ElementKind) -> Vec<[f64; 3]> {
    let mut nodes: Vec<[f64; 3]> = match topology::linear(kind) {
        ElementKind::Hex8 => HEX8_CORNERS.to_vec(),
        ElementKind::Wedge6 => WEDGE6_CORNERS.to_vec(),
        _ => vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
    };
    for [a, b] in topology::edges(kind) {
        let (xa, xb) = (nodes[*a], nodes[*b]);
        nodes.push(std::array::from_fn(|d| 0.5 * (xa[d] + xb[d])));
    }
    nodes
}

/// The shape function values `N_a(ξ)` and reference gradients
/// `∂N_a/∂ξ` of `kind` at `xi` (any point, not only the quadrature
/// points of [`super::volume_reference`]).
pub fn evaluate(kind: ElementKind, xi: &[f64; 3]) -> (Vec<f64>, Vec<[f64; 3]>) {
    match kind {
        ElementKind::Tet4 => (tet4_values(xi).to_vec(), tet4_gradients(xi).to_vec()),
        ElementKind::Hex8 => (hex8_values(xi).to_vec(), hex8_gradients(xi).to_vec()),
        ElementKind::Tet10 => (tet10_values(xi), tet10_gradients(xi)),
        ElementKind::Hex20 | ElementKind::Hex20R => (hex20_values(xi), hex20_gradients(xi)),
        ElementKind::Wedge6 => (wedge6_values(xi), wedge6_gradients(xi)),
        ElementKind::Wedge15 => (wedge15_values(xi), wedge15_gradients(xi)),
    }
}

/// Wedge6 corners: the unit triangle at `ζ = −1`, then at `ζ = 1`.
const WEDGE6_CORNERS: [[f64; 3]; 6] = [
    [0.0, 0.0, -1.0],
    [1.0, 0.0, -1.0],
    [0.0, 1.0, -1.0],
    [0.0, 0.0, 1.0],
    [1.0, 0.0, 1.0],
    [0.0, 1.0, 1.0],
];

/// The barycentric coordinates `L = (1 − ξ − η − ζ, ξ, η, ζ)` of the unit
/// tetrahedron and their (constant) gradients.
fn tet_barycentric(x: &[f64; 3]) -> ([f64; 4], [[f64; 3]; 4]) {
    (tet4_values(x), tet4_gradients(x))
}

/// Tet10: corners `N_i = L_i (2 L_i − 1)`, mid-side nodes `N = 4 L_i L_j`
/// on the edge `(i, j)` ([`topology::edges`]).
pub fn tet10_values(x: &[f64; 3]) -> Vec<f64> {
    let (l, _) = tet_barycentric(x);
    let mut n: Vec<f64> = l.iter().map(|li| li * (2.0 * li - 1.0)).collect();
    for [i, j] in topology::edges(ElementKind::Tet10) {
        n.push(4.0 * l[*i] * l[*j]);
    }
    n
}

/// Reference gradients of the Tet10 shape functions: `(4 L_i − 1) ∇L_i`
/// at the corners, `4 (L_i ∇L_j + L_j ∇L_i)` on the edges.
pub fn tet10_gradients(x: &[f64; 3]) -> Vec<[f64; 3]> {
    let (l, dl) = tet_barycentric(x);
    let mut g: Vec<[f64; 3]> = (0..4)
        .map(|i| dl[i].map(|d| (4.0 * l[i] - 1.0) * d))
        .collect();
    for [i, j] in topology::edges(ElementKind::Tet10) {
        g.push(std::array::from_fn(|d| {
            4.0 * (l[*i] * dl[*j][d] + l[*j] * dl[*i][d])
        }));
    }
    g
}

/// Hex20 (serendipity) on [−1, 1]³: corners
/// `N_a = ⅛ (1 + ξ ξ_a)(1 + η η_a)(1 + ζ ζ_a)(ξ ξ_a + η η_a + ζ ζ_a − 2)`;
/// a mid-side node with `ξ_a = 0` (and likewise in η, ζ)
/// `N_a = ¼ (1 − ξ²)(1 + η η_a)(1 + ζ ζ_a)`.
pub fn hex20_values(x: &[f64; 3]) -> Vec<f64> {
    hex20_nodes()
        .iter()
        .map(|c| match c.iter().position(|&v| v == 0.0) {
            None => {
                let p = [0, 1, 2].map(|d| x[d] * c[d]);
                0.125 * (1.0 + p[0]) * (1.0 + p[1]) * (1.0 + p[2]) * (p[0] + p[1] + p[2] - 2.0)
            }
            Some(d) => {
                let mut n = 0.25 * (1.0 - x[d] * x[d]);
                for e in (0..3).filter(|&e| e != d) {
                    n *= 1.0 + x[e] * c[e];
                }
                n
            }
        })
        .collect()
}

/// Reference gradients of the Hex20 shape functions: at a corner
/// `∂N_a/∂ξ = ⅛ ξ_a (1 + η η_a)(1 + ζ ζ_a)(2 ξ ξ_a + η η_a + ζ ζ_a − 1)`;
/// at a mid-side node with `ξ_a = 0`, `∂N_a/∂ξ = −½ ξ (1 + η η_a)(1 + ζ ζ_a)`
/// and `∂N_a/∂η = ¼ (1 − ξ²) η_a (1 + ζ ζ_a)`.
pub fn hex20_gradients(x: &[f64; 3]) -> Vec<[f64; 3]> {
    hex20_nodes()
        .iter()
        .map(|c| match c.iter().position(|&v| v == 0.0) {
            None => {
                let p = [0, 1, 2].map(|d| x[d] * c[d]);
                let s = p[0] + p[1] + p[2];
                std::array::from_fn(|d| {
                    let others: f64 = (0..3).filter(|&e| e != d).map(|e| 1.0 + p[e]).product();
                    0.125 * c[d] * others * (s + p[d] - 1.0)
                })
            }
            Some(d) => std::array::from_fn(|k| {
                let mut v = if k == d {
                    -0.5 * x[d]
                } else {
                    0.25 * (1.0 - x[d] * x[d]) * c[k]
                };
                for e in (0..3).filter(|&e| e != d && e != k) {
                    v *= 1.0 + x[e] * c[e];
                }
                v
            }),
        })
        .collect()
}

/// The Hex20 nodes in reference coordinates (tabulated once).
fn hex20_nodes() -> &'static [[f64; 3]] {
    static NODES: std::sync::OnceLock<Vec<[f64; 3]>> = std::sync::OnceLock::new();
    NODES.get_or_init(|| reference_nodes(ElementKind::Hex20))
}

/// The triangle's area coordinates at `(ξ, η)` and their gradients in
/// `(ξ, η, ζ)`, and the level `ζ_a = ∓1` of corner `i` of a wedge.
fn wedge_parts(x: &[f64; 3]) -> ([f64; 3], [[f64; 3]; 3]) {
    let l = tri3_values(&[x[0], x[1]]);
    let dl = tri3_gradients(&[x[0], x[1]]).map(|g| [g[0], g[1], 0.0]);
    (l, dl)
}

/// Wedge6: `N_i = ½ L_t (1 + ζ ζ_i)`, `L` the area coordinates of the
/// triangle, `t = i mod 3`, `ζ_i = −1` for `i < 3`, `+1` above.
pub fn wedge6_values(x: &[f64; 3]) -> Vec<f64> {
    let (l, _) = wedge_parts(x);
    (0..6)
        .map(|i| 0.5 * l[i % 3] * (1.0 + x[2] * WEDGE6_CORNERS[i][2]))
        .collect()
}

/// Reference gradients of the Wedge6 shape functions.
pub fn wedge6_gradients(x: &[f64; 3]) -> Vec<[f64; 3]> {
    let (l, dl) = wedge_parts(x);
    (0..6)
        .map(|i| {
            let (t, z) = (i % 3, WEDGE6_CORNERS[i][2]);
            let mut g = dl[t].map(|d| 0.5 * d * (1.0 + x[2] * z));
            g[2] = 0.5 * l[t] * z;
            g
        })
        .collect()
}

/// Wedge15: corners `N_i = ½ L_t (1 + ζ ζ_i)(2 L_t + ζ ζ_i − 2)`; a
/// mid-side node on a triangle edge `(s, t)` at level `ζ_a`
/// `N = 2 L_s L_t (1 + ζ ζ_a)`; on a vertical edge above corner `t`
/// `N = L_t (1 − ζ²)`.
pub fn wedge15_values(x: &[f64; 3]) -> Vec<f64> {
    let (l, _) = wedge_parts(x);
    let z = x[2];
    let mut n: Vec<f64> = (0..6)
        .map(|i| {
            let (t, za) = (i % 3, WEDGE6_CORNERS[i][2]);
            0.5 * l[t] * (1.0 + z * za) * (2.0 * l[t] + z * za - 2.0)
        })
        .collect();
    for [a, b] in topology::edges(ElementKind::Wedge15) {
        let (s, t) = (a % 3, b % 3);
        n.push(if s == t {
            l[t] * (1.0 - z * z)
        } else {
            2.0 * l[s] * l[t] * (1.0 + z * WEDGE6_CORNERS[*a][2])
        });
    }
    n
}

/// Reference gradients of the Wedge15 shape functions: at a corner
/// `∂N/∂ξ_k = ½ ∂L_t/∂ξ_k (1 + ζ ζ_i)(4 L_t + ζ ζ_i − 2)`,
/// `∂N/∂ζ = ½ L_t ζ_i (2 L_t + 2 ζ ζ_i − 1)`; the mid-side nodes by the
/// product rule.
pub fn wedge15_gradients(x: &[f64; 3]) -> Vec<[f64; 3]> {
    let (l, dl) = wedge_parts(x);
    let z = x[2];
    let mut g: Vec<[f64; 3]> = (0..6)
        .map(|i| {
            let (t, za) = (i % 3, WEDGE6_CORNERS[i][2]);
            let mut g = dl[t].map(|d| 0.5 * d * (1.0 + z * za) * (4.0 * l[t] + z * za - 2.0));
            g[2] = 0.5 * l[t] * za * (2.0 * l[t] + 2.0 * z * za - 1.0);
            g
        })
        .collect();
    for [a, b] in topology::edges(ElementKind::Wedge15) {
        let (s, t) = (a % 3, b % 3);
        g.push(if s == t {
            let mut v = dl[t].map(|d| d * (1.0 - z * z));
            v[2] = -2.0 * z * l[t];
            v
        } else {
            let za = WEDGE6_CORNERS[*a][2];
            let mut v: [f64; 3] =
                std::array::from_fn(|d| 2.0 * (dl[s][d] * l[t] + l[s] * dl[t][d]) * (1.0 + z * za));
            v[2] = 2.0 * l[s] * l[t] * za;
            v
        });
    }
    g
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each shape function is 1 at its own node and 0 at the others, and the
    /// gradients match central finite differences.
    #[test]
    fn hex8_kronecker_and_gradient() {
        for (a, c) in HEX8_CORNERS.iter().enumerate() {
            let n = hex8_values(c);
            for (b, v) in n.iter().enumerate() {
                assert!((v - if a == b { 1.0 } else { 0.0 }).abs() < 1e-15);
            }
        }
        let x = [0.3, -0.2, 0.7];
        let g = hex8_gradients(&x);
        let h = 1e-6;
        for d in 0..3 {
            let (mut xp, mut xm) = (x, x);
            xp[d] += h;
            xm[d] -= h;
            let (np, nm) = (hex8_values(&xp), hex8_values(&xm));
            for a in 0..8 {
                assert!(((np[a] - nm[a]) / (2.0 * h) - g[a][d]).abs() < 1e-9);
            }
        }
    }

    #[test]
    fn quad4_gradient_matches_finite_difference() {
        let x = [0.4, -0.1];
        let g = quad4_gradients(&x);
        let h = 1e-6;
        for d in 0..2 {
            let (mut xp, mut xm) = (x, x);
            xp[d] += h;
            xm[d] -= h;
            let (np, nm) = (quad4_values(&xp), quad4_values(&xm));
            for a in 0..4 {
                assert!(((np[a] - nm[a]) / (2.0 * h) - g[a][d]).abs() < 1e-9);
            }
        }
    }
    /// The nodes of a 2D Lagrange face in reference coordinates.
    fn face_nodes(n: usize) -> Vec<[f64; 2]> {
        match n {
            6 => vec![
                [0.0, 0.0],
                [1.0, 0.0],
                [0.0, 1.0],
                [0.5, 0.0],
                [0.5, 0.5],
                [0.0, 0.5],
            ],
            _ => {
                let mut v: Vec<[f64; 2]> = HEX8_CORNERS[..4].iter().map(|c| [c[0], c[1]]).collect();
                v.extend(QUAD8_MID_SIDES);
                v
            }
        }
    }

    /// Kronecker property at the nodes, and gradients equal to central
    /// finite differences, for a quadratic face's shape functions.
    fn check_quadratic_face<const N: usize>(
        values: fn(&[f64; 2]) -> [f64; N],
        gradients: fn(&[f64; 2]) -> [[f64; 2]; N],
        x: [f64; 2],
    ) {
        for (a, node) in face_nodes(N).iter().enumerate() {
            for (b, v) in values(node).iter().enumerate() {
                assert!(
                    (v - if a == b { 1.0 } else { 0.0 }).abs() < 1e-15,
                    "N_{b} at node {a}"
                );
            }
        }
        let g = gradients(&x);
        let h = 1e-6;
        for d in 0..2 {
            let (mut xp, mut xm) = (x, x);
            xp[d] += h;
            xm[d] -= h;
            let (np, nm) = (values(&xp), values(&xm));
            for a in 0..N {
                assert!(((np[a] - nm[a]) / (2.0 * h) - g[a][d]).abs() < 1e-9);
            }
        }
    }

    #[test]
    fn tri6_and_quad8_kronecker_and_gradient() {
        check_quadratic_face(tri6_values, tri6_gradients, [0.2, 0.3]);
        check_quadratic_face(quad8_values, quad8_gradients, [0.4, -0.3]);
    }

    /// The integrals that make node-to-surface fail on quadratic faces
    /// (DESIGN.md, mortar): on the flat Tri6 a corner's `∫N dA` is 0 and a
    /// mid-side node's is A/3; on the Quad8 a corner's is −A/12 and a
    /// mid-side node's A/3 (A the reference area: ½ and 4).
    #[test]
    fn quadratic_face_nodal_integrals() {
        let (p, w) = crate::fem::quadrature::triangle(3);
        let mut tri = [0.0; 6];
        for (x, wq) in p.iter().zip(&w) {
            tri.iter_mut()
                .zip(tri6_values(x))
                .for_each(|(s, n)| *s += wq * n);
        }
        for (a, s) in tri.iter().enumerate() {
            assert!(
                (s - if a < 3 { 0.0 } else { 1.0 / 6.0 }).abs() < 1e-15,
                "Tri6 {a}: {s}"
            );
        }
        let (p, w) = crate::fem::quadrature::quadrilateral(3);
        let mut quad = [0.0; 8];
        for (x, wq) in p.iter().zip(&w) {
            quad.iter_mut()
                .zip(quad8_values(x))
                .for_each(|(s, n)| *s += wq * n);
        }
        for (a, s) in quad.iter().enumerate() {
            let exact = if a < 4 { -1.0 / 3.0 } else { 4.0 / 3.0 };
            assert!((s - exact).abs() < 1e-14, "Quad8 {a}: {s}");
        }
    }

    /// Every volume kind: Kronecker property at its reference nodes,
    /// partition of unity, and gradients equal to central finite
    /// differences at an interior point.
    #[test]
    fn volume_kinds_kronecker_and_gradient() {
        type Values = fn(&[f64; 3]) -> Vec<f64>;
        type Gradients = fn(&[f64; 3]) -> Vec<[f64; 3]>;
        let kinds: [(ElementKind, Values, Gradients); 4] = [
            (ElementKind::Tet10, tet10_values, tet10_gradients),
            (ElementKind::Hex20, hex20_values, hex20_gradients),
            (ElementKind::Wedge6, wedge6_values, wedge6_gradients),
            (ElementKind::Wedge15, wedge15_values, wedge15_gradients),
        ];
        for (kind, values, gradients) in kinds {
            let nodes = reference_nodes(kind);
            assert_eq!(nodes.len(), kind.num_nodes());
            for (a, node) in nodes.iter().enumerate() {
                for (b, v) in values(node).iter().enumerate() {
                    let exact = if a == b { 1.0 } else { 0.0 };
                    assert!((v - exact).abs() < 1e-14, "{kind:?} N_{b} at node {a}: {v}");
                }
            }
            let x = [0.21, 0.17, 0.3];
            assert!((values(&x).iter().sum::<f64>() - 1.0).abs() < 1e-14);
            let g = gradients(&x);
            let h = 1e-6;
            for d in 0..3 {
                let (mut xp, mut xm) = (x, x);
                xp[d] += h;
                xm[d] -= h;
                let (np, nm) = (values(&xp), values(&xm));
                for a in 0..kind.num_nodes() {
                    let fd = (np[a] - nm[a]) / (2.0 * h);
                    assert!((fd - g[a][d]).abs() < 1e-9, "{kind:?} dN_{a}/dx_{d}");
                }
            }
        }
    }
}
