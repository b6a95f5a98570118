//! The basis transformation of quadratic secondary faces (Popp, Wohlmuth,
//! Gee & Wall, SISC 34, 2012; Wohlmuth, Popp, Gee & Wall, Comput. Mech.
//! 49, 2012): on Tri6, `∫_e N_corner dA = 0`, and on Quad8 it is `−A/12`,
//! so a dual basis of the Lagrange functions does not exist or is not
//! positive. The transformed functions
//!
//! ```text
//! Ñ_c = N_c + α Σ_{m ∋ c} N_m      (corner c; the two mid-side nodes of its edges)
//! Ñ_m = (1 − 2α) N_m               (mid-side node m)
//! ```
//!
//! keep the partition of unity `Σ Ñ = Σ N = 1` and span the same space,
//! and with `α = 1/5` every `∫_e Ñ_j dA > 0` (flat faces: Tri6 corners
//! `2A/15`, mid-sides `A/5`; Quad8 corners `A/20`, mid-sides `A/5`). The
//! multipliers are dual to `Ñ`. Since `N = T⁻¹ Ñ`, a field
//! `x = Σ_k N_k x_k = Σ_j Ñ_j x̃_j` with the transformed nodal values
//!
//! ```text
//! x̃_c = x_c,   x̃_m = (x_m − α (x_a + x_b)) / (1 − 2α)   (m on the edge (a, b))
//! ```
//!
//! which depend only on the edge, so they agree between the two faces that
//! share it. Linear faces are left as they are (`Ñ = N`, `x̃ = x`).

use super::face::FaceShape;

/// The transformation's `α` (1/5 in Popp et al. 2012 for Tri6; CalculiX's
/// quadratic mortar uses the same value on Quad8).
pub const ALPHA: f64 = 0.2;

/// The corners `(a, b)` of each mid-side node, in node order from the first
/// mid-side node (3 on Tri6, 4 on Quad8); empty on linear faces.
pub fn mid_side_edges(shape: FaceShape) -> &'static [[usize; 2]] {
    match shape {
        FaceShape::Tri6 => &[[0, 1], [1, 2], [2, 0]],
        FaceShape::Quad8 => &[[0, 1], [1, 2], [2, 3], [3, 0]],
        FaceShape::Tri3 | FaceShape::Quad4 => &[],
    }
}

/// The mortar (transformed) shape functions `Ñ(ξ)` of a secondary face.
pub fn mortar_values(shape: FaceShape, xi: [f64; 2]) -> Vec<f64> {
    transformed(shape, &shape.values(xi))
}

/// The reference gradients `∂Ñ/∂ξ = T ∂N/∂ξ` of the mortar shape functions.
pub fn mortar_gradients(shape: FaceShape, xi: [f64; 2]) -> Vec<[f64; 2]> {
    let g = shape.gradients(xi);
    let column = |d: usize| transformed(shape, &g.iter().map(|g| g[d]).collect::<Vec<_>>());
    let (gx, gy) = (column(0), column(1));
    gx.into_iter().zip(gy).map(|(a, b)| [a, b]).collect()
}

/// `Ñ = T N` from the Lagrange values `N`.
pub fn transformed(shape: FaceShape, n: &[f64]) -> Vec<f64> {
    let mut t = n.to_vec();
    let first_mid = shape.corner_count();
    for (m, [a, b]) in mid_side_edges(shape).iter().enumerate() {
        let nm = n[first_mid + m];
        t[*a] += ALPHA * nm;
        t[*b] += ALPHA * nm;
        t[first_mid + m] = (1.0 - 2.0 * ALPHA) * nm;
    }
    t
}

/// The rows of `x̃_j = Σ_k R_jk x_k` (face-local `(k, R_jk)`): `(j, 1)` at
/// corners and linear faces; `(m, 1/(1 − 2α))`, `(a, −α/(1 − 2α))`,
/// `(b, −α/(1 − 2α))` at a mid-side node `m` on the edge `(a, b)`.
pub fn nodal_transformation(shape: FaceShape) -> Vec<Vec<(usize, f64)>> {
    let mut rows: Vec<Vec<(usize, f64)>> =
        (0..shape.node_count()).map(|j| vec![(j, 1.0)]).collect();
    let first_mid = shape.corner_count();
    let scale = 1.0 / (1.0 - 2.0 * ALPHA);
    for (m, [a, b]) in mid_side_edges(shape).iter().enumerate() {
        rows[first_mid + m] = vec![
            (first_mid + m, scale),
            (*a, -ALPHA * scale),
            (*b, -ALPHA * scale),
        ];
    }
    rows
}
