//! Tensors derived for output from the stress and the deformation
//! gradient: principal values, the Green–Lagrange strain and the
//! logarithmic (Hencky) strain. Pure kernels of one 3×3 matrix.

use crate::material::Mat3;

/// The principal values of the symmetric part `½(A + Aᵀ)` of `a`, largest
/// first (`σ₁ ≥ σ₂ ≥ σ₃` for a stress): the roots of
/// `det(A − λI) = −λ³ + I₁λ² − I₂λ + I₃ = 0`.
pub fn principal_values(a: &Mat3) -> [f64; 3] {
    let sym = 0.5 * (a + a.transpose());
    let mut values: Vec<f64> = sym.symmetric_eigenvalues().iter().copied().collect();
    values.sort_by(|x, y| y.total_cmp(x));
    [values[0], values[1], values[2]]
}

/// Green–Lagrange strain `E = ½(FᵀF − I)` (material frame).
pub fn green_lagrange_strain(f: &Mat3) -> Mat3 {
    0.5 * (f.transpose() * f - Mat3::identity())
}

/// Logarithmic (Hencky) strain in the spatial frame,
/// `ε = ln V = ½ ln(F Fᵀ) = Σᵢ ln λᵢ nᵢ ⊗ nᵢ`, with `λᵢ` the principal
/// stretches and `nᵢ` the spatial principal directions (the left stretch
/// `V` of `F = V R`; what Abaqus reports as `LE`). NaN entries if `F` is
/// singular.
pub fn logarithmic_strain(f: &Mat3) -> Mat3 {
    let b = f * f.transpose();
    let eigen = b.symmetric_eigen();
    let mut strain = Mat3::zeros();
    for (i, &mu) in eigen.eigenvalues.iter().enumerate() {
        let n = eigen.eigenvectors.column(i);
        strain += (0.5 * mu.ln()) * n * n.transpose();
    }
    strain
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Rotation3, Vector3};

    /// A symmetric matrix with entries in [-1, 1] from a fixed sequence.
    fn symmetric(seed: u64) -> Mat3 {
        let mut state = seed.wrapping_mul(6364136223846793005).wrapping_add(1);
        let mut next = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        let a = Mat3::from_fn(|_, _| next());
        a + a.transpose()
    }

    /// The principal values are the eigenvalues of the tensor: each makes
    /// `det(σ − λI)` vanish (to 1e-12 of `|σ|³`), their sum, pair sum and
    /// product are the invariants `I₁ = tr σ`, `I₂ = ½(tr²σ − tr σ²)`,
    /// `I₃ = det σ`, and they come largest first.
    #[test]
    fn principal_values_are_the_eigenvalues() {
        for seed in 0..50 {
            let s = symmetric(seed) * 100.0;
            let [l1, l2, l3] = principal_values(&s);
            assert!(l1 >= l2 && l2 >= l3);
            let scale = s.norm();
            for l in [l1, l2, l3] {
                let det = (s - l * Mat3::identity()).determinant();
                assert!(det.abs() <= 1e-12 * scale.powi(3), "{det} for {l}");
            }
            let i1 = s.trace();
            let i2 = 0.5 * (i1 * i1 - (s * s).trace());
            let i3 = s.determinant();
            assert!((l1 + l2 + l3 - i1).abs() <= 1e-12 * scale);
            assert!((l1 * l2 + l2 * l3 + l3 * l1 - i2).abs() <= 1e-12 * scale * scale);
            assert!((l1 * l2 * l3 - i3).abs() <= 1e-12 * scale.powi(3));
        }
    }

    /// A homogeneous deformation `F = R U` with `U = diag(λ₁, λ₂, λ₃)`:
    /// `E = ½ diag(λᵢ² − 1)` and `ln V = R diag(ln λᵢ) Rᵀ`, to 1e-14.
    #[test]
    fn strains_of_a_stretch_and_rotation() {
        let stretches = [1.7, 0.6, 1.05];
        let u = Mat3::from_diagonal(&Vector3::from(stretches));
        let r = Rotation3::from_scaled_axis(Vector3::new(0.3, -0.7, 0.5)).into_inner();
        let f = r * u;
        let e = green_lagrange_strain(&f);
        let e_exact = Mat3::from_diagonal(&Vector3::from(stretches.map(|l| 0.5 * (l * l - 1.0))));
        assert!((e - e_exact).norm() < 1e-14, "{e} vs {e_exact}");
        let log = logarithmic_strain(&f);
        let log_exact =
            r * Mat3::from_diagonal(&Vector3::from(stretches.map(f64::ln))) * r.transpose();
        assert!((log - log_exact).norm() < 1e-14, "{log} vs {log_exact}");
        // small strain: both tend to the symmetric gradient
        let h = Mat3::new(1.0, 2.0, 0.0, -1.0, 0.5, 3.0, 0.0, 1.0, -2.0) * 1e-7;
        let small = 0.5 * (h + h.transpose());
        let f = Mat3::identity() + h;
        assert!((green_lagrange_strain(&f) - small).norm() < 1e-12);
        assert!((logarithmic_strain(&f) - small).norm() < 1e-12);
    }
}
