//! Lagrange shape functions `N_a(ξ)` and their reference gradients
//! `∂N_a/∂ξ`, with Gmsh's node numbering.

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
}
