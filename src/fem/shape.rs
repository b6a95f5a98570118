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
}
