//! Hooke's element stiffness in closed form: the tangent of
//! [`super::kernel`] for small-strain isotropic elasticity, contracted by
//! hand.
//!
//! With `ℂ_iJkL = λ δ_iJ δ_kL + μ (δ_ik δ_JL + δ_iL δ_Jk)` (the constant
//! tangent of `linear_elastic`, [`Material::hooke_lame`]) and the linear
//! strain–displacement operator (`F = I` in `B`, no geometric term), the
//! kernel's `K_ab,ik = Σ_q Σ_JL G_aJ ℂ_iJkL G_bL dV_q` is
//!
//! ```text
//! K_ab = Σ_q dV_q (λ G_a G_bᵀ + μ G_b G_aᵀ + μ (G_a · G_b) I),
//! ```
//!
//! `G_a = ∂N_a/∂X` at point `q`: about 25 operations a block and point
//! instead of forming and contracting `ℂ` (a third of the kernel's time,
//! `benches/element_kernel.rs`). On a Tet4 (one point) the gradients are constant: `G_1, G_2,
//! G_3` are the rows of `E⁻¹`, `E = [X_1 − X_0, X_2 − X_0, X_3 − X_0]` the
//! edge matrix (the Jacobian `∂X/∂ξ` of
//! [`reference_geometry`](super::kernel::reference_geometry)),
//! `G_0 = −G_1 − G_2 − G_3`, and `dV = V = det E / 6`.
//!
//! [`Material::hooke_lame`]: crate::material::Material::hooke_lame

use super::kernel::PointGeometry;

/// `K_ab += dV (λ G_a G_bᵀ + μ G_b G_aᵀ + μ (G_a · G_b) I)` for `a ≤ b` at
/// one point with gradients `g` (`N` nodes): block `(a, b)` of `blocks`
/// in the order `(0,0), (0,1), …, (0,N−1), (1,1), …` (`B = N(N+1)/2`),
/// row-major (`3i + k`: row a-dof `i`, column b-dof `k`).
#[inline]
pub fn add_point_stiffness<const N: usize, const B: usize>(
    g: &[[f64; 3]; N],
    dv: f64,
    lambda: f64,
    mu: f64,
    blocks: &mut [[f64; 9]; B],
) {
    const { assert!(B == N * (N + 1) / 2) };
    let mut block = 0;
    for a in 0..N {
        let la: [f64; 3] = std::array::from_fn(|i| lambda * dv * g[a][i]);
        let ma: [f64; 3] = std::array::from_fn(|i| mu * dv * g[a][i]);
        for g_b in &g[a..] {
            let k_ab = &mut blocks[block];
            let shear = ma[0] * g_b[0] + ma[1] * g_b[1] + ma[2] * g_b[2];
            for i in 0..3 {
                for k in 0..3 {
                    k_ab[3 * i + k] += la[i] * g_b[k] + ma[k] * g_b[i];
                }
                k_ab[4 * i] += shear;
            }
            block += 1;
        }
    }
}

/// The upper blocks `K_ab`, `a ≤ b`, of Hooke's stiffness
/// `Σ_q dV_q (λ G_a G_bᵀ + μ G_b G_aᵀ + μ (G_a · G_b) I)` of an element of
/// `N` nodes with reference geometry `geometry`
/// ([`reference_geometry`](super::kernel::reference_geometry)), in the
/// order and layout of [`add_point_stiffness`]; on the stack.
pub fn hooke_stiffness<const N: usize, const B: usize>(
    geometry: &[PointGeometry],
    lambda: f64,
    mu: f64,
) -> [[f64; 9]; B] {
    let mut blocks = [[0.0; 9]; B];
    for p in geometry {
        let g: [[f64; 3]; N] = std::array::from_fn(|a| p.gradients[a].into());
        add_point_stiffness(&g, p.dv, lambda, mu, &mut blocks);
    }
    blocks
}

#[cfg(test)]
mod tests {
    use super::super::kernel::{internal_force_and_tangent_into, reference_geometry};
    use super::*;
    use crate::material::{LinearElastic, Material};
    use crate::mesh::ElementKind;

    /// Block `(a, b)` of `blocks` (upper order), mirrored for `a > b`.
    fn block<const B: usize>(blocks: &[[f64; 9]; B], n: usize, a: usize, b: usize) -> [f64; 9] {
        let (r, c) = (a.min(b), a.max(b));
        let k = blocks[r * n - r * (r + 1) / 2 + c];
        if a <= b {
            k
        } else {
            std::array::from_fn(|m| k[3 * (m % 3) + m / 3])
        }
    }

    /// The unit right tetrahedron `(0,0,0), (1,0,0), (0,1,0), (0,0,1)`:
    /// `V = 1/6`, `G_0 = (−1, −1, −1)`, `G_a = e_a`, so by hand
    /// `K_11 = V diag(λ + 2μ, μ, μ)`, `K_12 = V (λ e_1 e_2ᵀ + μ e_2 e_1ᵀ)`,
    /// `K_00 = V ((λ + μ) 𝟙𝟙ᵀ + 3μ I)`,
    /// `K_01 = −V (λ 𝟙 e_1ᵀ + μ e_1 𝟙ᵀ + μ I)`; and every block row sums
    /// to zero (a rigid translation is free of stress).
    #[test]
    fn unit_right_tetrahedron_by_hand() {
        let corners = [[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        let geometry = reference_geometry(ElementKind::Tet4, &corners).unwrap();
        let (lambda, mu) = (3.0, 2.0);
        let k = hooke_stiffness::<4, 10>(&geometry, lambda, mu);
        let v = 1.0 / 6.0;
        let (l, m) = (lambda * v, mu * v);
        let expected: [(usize, usize, [f64; 9]); 4] = [
            (1, 1, [l + 2.0 * m, 0.0, 0.0, 0.0, m, 0.0, 0.0, 0.0, m]),
            (1, 2, [0.0, l, 0.0, m, 0.0, 0.0, 0.0, 0.0, 0.0]),
            (
                0,
                0,
                [
                    l + 4.0 * m,
                    l + m,
                    l + m,
                    l + m,
                    l + 4.0 * m,
                    l + m,
                    l + m,
                    l + m,
                    l + 4.0 * m,
                ],
            ),
            (0, 1, [-l - 2.0 * m, -m, -m, -l, -m, 0.0, -l, 0.0, -m]),
        ];
        for (a, b, e) in expected {
            let got = block(&k, 4, a, b);
            for (x, y) in got.iter().zip(&e) {
                assert!((x - y).abs() <= 1e-15, "K_{a}{b}: {got:?} against {e:?}");
            }
        }
        for a in 0..4 {
            for i in 0..3 {
                for c in 0..3 {
                    let sum: f64 = (0..4).map(|b| block(&k, 4, a, b)[3 * i + c]).sum();
                    assert!(sum.abs() <= 1e-15, "row {a}{i}: {sum}");
                }
            }
        }
    }

    /// The closed form equals the general kernel's tangent (first
    /// elasticity tensor per point) at `u = 0` to 1e-13 relative, entry by
    /// entry, on a distorted Tet4 and Hex8.
    #[test]
    fn equals_the_general_kernel() {
        let material = LinearElastic::new(1000.0, 0.3, "m").unwrap();
        let Some((lambda, mu)) = material.hooke_lame() else {
            panic!("linear_elastic is Hooke")
        };
        let tet: Vec<[f64; 3]> = vec![[0.0; 3], [1.0, 0.1, 0.0], [0.2, 0.9, 0.1], [0.1, 0.2, 1.1]];
        let hex: Vec<[f64; 3]> = (0..8)
            .map(|a| {
                let (x, y, z) = ((a & 1) ^ (a >> 1 & 1), a >> 1 & 1, a >> 2);
                [
                    x as f64 + 0.05 * a as f64,
                    y as f64 * 0.9,
                    z as f64 * 1.1 + 0.02 * x as f64,
                ]
            })
            .collect();
        for (kind, corners) in [(ElementKind::Tet4, tet), (ElementKind::Hex8, hex)] {
            let n = corners.len();
            let geometry = reference_geometry(kind, &corners).unwrap();
            let mut force = vec![0.0; 3 * n];
            let mut general = vec![0.0; 9 * n * n];
            internal_force_and_tangent_into(
                &geometry,
                &vec![[0.0; 3]; n],
                &material,
                &mut force,
                Some(&mut general),
            )
            .unwrap();
            let closed: Vec<[f64; 9]> = match kind {
                ElementKind::Tet4 => hooke_stiffness::<4, 10>(&geometry, lambda, mu).to_vec(),
                ElementKind::Hex8 => hooke_stiffness::<8, 36>(&geometry, lambda, mu).to_vec(),
                other => unreachable!("{other:?} has no closed form"),
            };
            let scale = general.iter().fold(0.0f64, |s, v| s.max(v.abs()));
            let mut blocks = closed.iter();
            for a in 0..n {
                for b in a..n {
                    let k_ab = blocks.next().unwrap();
                    for i in 0..3 {
                        for k in 0..3 {
                            let g = general[(3 * a + i) * 3 * n + 3 * b + k];
                            assert!(
                                (k_ab[3 * i + k] - g).abs() <= 1e-13 * scale,
                                "{kind:?} K_{a}{b}[{i}{k}]: {} against {g}",
                                k_ab[3 * i + k]
                            );
                        }
                    }
                }
            }
            assert!(blocks.next().is_none());
        }
    }
}
