//! Constitutive laws: strain energy `W(F)` per unit reference volume, the
//! second Piola–Kirchhoff stress `S = ∂W/∂E` and the material tangent
//! `𝔻 = ∂S/∂E`, written as pure functions of the deformation gradient that
//! unit tests call directly.
//!
//! Laws: [`LinearElastic`] (small strain Hooke), [`SaintVenantKirchhoff`],
//! compressible [`NeoHookean`] and compressible [`Ogden`].
//!
//! Conventions: `F` deformation gradient, `C = FᵀF`, `E = ½(C − I)`,
//! `J = det F`. Voigt order (11, 22, 33, 12, 23, 13); stresses are stored
//! plainly, strains with engineering shear (`γ₁₂ = 2E₁₂`), so that
//! `dS_I = 𝔻_IJ dγ_J` with `𝔻_IJ = 𝔻_ijkl` (pairs `I = (ij)`, `J = (kl)`)
//! and `𝔻` is symmetric.
//!
//! Finite-strain laws return NaN stress and tangent (and `+∞` energy) for
//! `J ≤ 0` where their energy is undefined: the solver treats NaN as a
//! failed iteration. They never panic.

use nalgebra::{Matrix3, Matrix6, Vector6};

mod eigen3;
mod isotropic;
mod linear_elastic;
mod neo_hookean;
mod ogden;
mod saint_venant_kirchhoff;

#[cfg(test)]
pub(crate) mod check;

pub(crate) use isotropic::IsotropicParameters;
pub use linear_elastic::LinearElastic;
pub use neo_hookean::NeoHookean;
pub use ogden::Ogden;
pub use saint_venant_kirchhoff::SaintVenantKirchhoff;

/// 3×3 tensor.
pub type Mat3 = Matrix3<f64>;
/// 6×6 matrix in Voigt notation, order (11, 22, 33, 12, 23, 13).
pub type Mat6 = Matrix6<f64>;
/// Voigt vector, order (11, 22, 33, 12, 23, 13).
pub type Vec6 = Vector6<f64>;

/// Index pairs `(i, j)` of the Voigt components, order (11, 22, 33, 12, 23, 13).
pub const VOIGT_PAIRS: [(usize, usize); 6] = [(0, 0), (1, 1), (2, 2), (0, 1), (1, 2), (0, 2)];

/// How a material wants the element to measure strain.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kinematics {
    /// Infinitesimal strain `ε = sym(F) − I`; the element uses the linear
    /// strain–displacement operator and no geometric stiffness.
    SmallStrain,
    /// Total Lagrangian finite strain.
    FiniteStrain,
}

/// A hyperelastic material.
pub trait Material: Send + Sync + std::fmt::Debug {
    /// Short name for messages, e.g. `"neo_hookean"`.
    fn name(&self) -> &'static str;

    /// Which strain measure the element must use.
    fn kinematics(&self) -> Kinematics {
        Kinematics::FiniteStrain
    }

    /// Whether the element stiffness of this material does not depend on the
    /// displacement (a small-strain material with a constant `𝔻`): then
    /// `K` can be assembled once and `f_int = K u` (the assembly's cache).
    /// False for every finite-strain material (total Lagrangian: `B`
    /// depends on `F`, and there is a geometric stiffness).
    fn constant_tangent(&self) -> bool {
        false
    }

    /// The Lamé parameters `(λ, μ)` when this law is small-strain
    /// isotropic Hooke (`σ = λ tr(ε) I + 2μ ε`, constant
    /// `ℂ = λ I⊗I + 2μ 𝕀`), `None` for every other law: the assembly then
    /// writes the element stiffness in closed form (`assembly::hooke`)
    /// instead of contracting `ℂ` point by point.
    fn hooke_lame(&self) -> Option<(f64, f64)> {
        None
    }

    /// Strain energy per unit reference volume, `W(F)`.
    fn strain_energy(&self, f: &Mat3) -> f64;

    /// Second Piola–Kirchhoff stress `S = ∂W/∂E` and the material tangent
    /// `𝔻 = ∂S/∂E` (Voigt, order (11, 22, 33, 12, 23, 13), engineering shear
    /// strain, so `𝔻` is symmetric).
    ///
    /// For [`Kinematics::SmallStrain`] materials the "S" is the Cauchy stress
    /// `σ = ℂ : ε` with `ε = sym(F) − I`, and `𝔻 = ℂ`.
    fn stress_and_tangent(&self, f: &Mat3) -> (Mat3, Mat6);

    /// Second Piola–Kirchhoff stress alone.
    fn second_piola_kirchhoff(&self, f: &Mat3) -> Mat3 {
        self.stress_and_tangent(f).0
    }

    /// A representative Young's modulus (initial stiffness), used for
    /// automatic penalty and scaling parameters.
    fn reference_youngs_modulus(&self) -> f64;

    /// The parameters in words, for logs and `signorini check`
    /// (`"E = 10, ν = 0.3"`).
    fn parameters(&self) -> String;
}

/// Lamé parameters `(λ, μ)` from Young's modulus `E` and Poisson's ratio `ν`:
/// `λ = Eν / ((1 + ν)(1 − 2ν))`, `μ = E / (2(1 + ν))`.
pub fn lame(youngs_modulus: f64, poisson_ratio: f64) -> (f64, f64) {
    let (e, nu) = (youngs_modulus, poisson_ratio);
    let lambda = e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
    let mu = e / (2.0 * (1.0 + nu));
    (lambda, mu)
}

/// Isotropic linear elasticity tensor `ℂ = λ I⊗I + 2μ 𝕀` in Voigt form
/// (engineering shear strain, so the shear diagonal is `μ`).
pub fn isotropic_elasticity(lambda: f64, mu: f64) -> Mat6 {
    let mut d = Mat6::zeros();
    for i in 0..3 {
        for j in 0..3 {
            d[(i, j)] = lambda;
        }
        d[(i, i)] += 2.0 * mu;
        d[(i + 3, i + 3)] = mu;
    }
    d
}

/// Voigt vector `(a₁₁, a₂₂, a₃₃, a₁₂, a₂₃, a₁₃)` of a symmetric tensor
/// (stress-like: no factor 2 on the shear terms). Off-diagonal entries are
/// taken from the symmetric part `½(a_ij + a_ji)`.
pub fn voigt_from_sym(a: &Mat3) -> Vec6 {
    Vec6::from_fn(|k, _| {
        let (i, j) = VOIGT_PAIRS[k];
        0.5 * (a[(i, j)] + a[(j, i)])
    })
}

/// Symmetric tensor from its (stress-like) Voigt vector; inverse of
/// [`voigt_from_sym`].
pub fn sym_from_voigt(v: &Vec6) -> Mat3 {
    Mat3::new(v[0], v[3], v[5], v[3], v[1], v[4], v[5], v[4], v[2])
}

/// Cauchy stress `σ = J⁻¹ F S Fᵀ` from the deformation gradient and the
/// second Piola–Kirchhoff stress.
///
/// For [`Kinematics::SmallStrain`] materials the stress returned by
/// [`Material::stress_and_tangent`] already *is* the Cauchy stress; callers
/// must use it as is and not push it forward with this function.
pub fn cauchy_stress(f: &Mat3, s: &Mat3) -> Mat3 {
    let j = f.determinant();
    f * s * f.transpose() / j
}

/// Von Mises equivalent stress
/// `√(½[(σ₁₁−σ₂₂)² + (σ₂₂−σ₃₃)² + (σ₃₃−σ₁₁)²] + 3(σ₁₂² + σ₂₃² + σ₁₃²))`
/// (of the symmetric part of `sigma`).
pub fn von_mises(sigma: &Mat3) -> f64 {
    let v = voigt_from_sym(sigma);
    let normal = (v[0] - v[1]).powi(2) + (v[1] - v[2]).powi(2) + (v[2] - v[0]).powi(2);
    let shear = v[3] * v[3] + v[4] * v[4] + v[5] * v[5];
    (0.5 * normal + 3.0 * shear).sqrt()
}

/// `(A ⊗ B)` in Voigt form for symmetric `A`, `B`: entry `(I, J)` is
/// `A_I B_J`.
pub(crate) fn outer_voigt(a: &Mat3, b: &Mat3) -> Mat6 {
    voigt_from_sym(a) * voigt_from_sym(b).transpose()
}

/// `𝕀_A` with `(𝕀_A)_ijkl = ½(A_ik A_jl + A_il A_jk)` in Voigt form, for a
/// symmetric `A`. With `A = C⁻¹` this is `−∂C⁻¹/∂C`.
pub(crate) fn sym_product_voigt(a: &Mat3) -> Mat6 {
    Mat6::from_fn(|p, q| {
        let (i, j) = VOIGT_PAIRS[p];
        let (k, l) = VOIGT_PAIRS[q];
        0.5 * (a[(i, k)] * a[(j, l)] + a[(i, l)] * a[(j, k)])
    })
}

/// The response of a finite-strain law where its energy is undefined
/// (`J ≤ 0`): NaN stress and tangent, which the solver treats as a failed
/// iteration.
pub(crate) fn nan_response() -> (Mat3, Mat6) {
    (Mat3::from_element(f64::NAN), Mat6::from_element(f64::NAN))
}

/// `prefix.name`, or `name` alone for an empty prefix.
pub(crate) fn key_path(prefix: &str, name: &str) -> String {
    if prefix.is_empty() {
        name.to_string()
    } else {
        format!("{prefix}.{name}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lame_and_elasticity_are_consistent() {
        let (e, nu) = (200.0, 0.3);
        let (lambda, mu) = lame(e, nu);
        assert!((mu - 200.0 / 2.6).abs() < 1e-12);
        assert!((lambda - 200.0 * 0.3 / (1.3 * 0.4)).abs() < 1e-12);
        // The compliance of ℂ has 1/E on the normal diagonal, −ν/E off it
        // and 1/μ on the shear diagonal.
        let s = isotropic_elasticity(lambda, mu).try_inverse().unwrap();
        assert!((s[(0, 0)] - 1.0 / e).abs() < 1e-14);
        assert!((s[(0, 1)] + nu / e).abs() < 1e-14);
        assert!((s[(3, 3)] - 1.0 / mu).abs() < 1e-14);
    }

    #[test]
    fn voigt_round_trip() {
        let a = Mat3::new(1.0, 4.0, 6.0, 4.0, 2.0, 5.0, 6.0, 5.0, 3.0);
        let v = voigt_from_sym(&a);
        assert_eq!(v, Vec6::new(1.0, 2.0, 3.0, 4.0, 5.0, 6.0));
        assert_eq!(sym_from_voigt(&v), a);
    }

    #[test]
    fn voigt_products_match_index_definitions() {
        let a = Mat3::new(2.0, 0.3, -0.1, 0.3, 1.5, 0.2, -0.1, 0.2, 1.1);
        let b = Mat3::new(1.0, -0.4, 0.5, -0.4, 0.7, 0.0, 0.5, 0.0, 3.0);
        let o = outer_voigt(&a, &b);
        let s = sym_product_voigt(&a);
        for p in 0..6 {
            let (i, j) = VOIGT_PAIRS[p];
            for q in 0..6 {
                let (k, l) = VOIGT_PAIRS[q];
                assert_eq!(o[(p, q)], a[(i, j)] * b[(k, l)]);
                let expect = 0.5 * (a[(i, k)] * a[(j, l)] + a[(i, l)] * a[(j, k)]);
                assert!((s[(p, q)] - expect).abs() < 1e-15);
            }
        }
        // 𝕀_I is the identity on stresses with engineering shear strains:
        // diag(1, 1, 1, ½, ½, ½).
        let id = sym_product_voigt(&Mat3::identity());
        let expect = Mat6::from_diagonal(&Vec6::new(1.0, 1.0, 1.0, 0.5, 0.5, 0.5));
        assert_eq!(id, expect);
    }

    #[test]
    fn cauchy_and_von_mises() {
        // Pure rotation: σ = R S Rᵀ.
        let r = nalgebra::Rotation3::from_euler_angles(0.3, -0.2, 0.7).into_inner();
        let s = Mat3::new(1.0, 0.2, 0.0, 0.2, -0.5, 0.1, 0.0, 0.1, 0.3);
        let sigma = cauchy_stress(&r, &s);
        assert!((sigma - r * s * r.transpose()).norm() < 1e-14);
        // Volume change divides by J.
        let f = Mat3::from_diagonal_element(2.0);
        let sigma = cauchy_stress(&f, &Mat3::identity());
        assert!((sigma - Mat3::identity() * 0.5).norm() < 1e-14);
        // Von Mises: uniaxial → |σ|, pure shear τ → √3 τ, hydrostatic → 0,
        // invariant under rotation.
        let uni = Mat3::from_diagonal(&nalgebra::Vector3::new(-7.0, 0.0, 0.0));
        assert!((von_mises(&uni) - 7.0).abs() < 1e-14);
        let shear = Mat3::new(0.0, 2.0, 0.0, 2.0, 0.0, 0.0, 0.0, 0.0, 0.0);
        assert!((von_mises(&shear) - 2.0 * 3f64.sqrt()).abs() < 1e-14);
        assert!(von_mises(&Mat3::from_diagonal_element(5.0)).abs() < 1e-14);
        let rotated = r * s * r.transpose();
        assert!((von_mises(&rotated) - von_mises(&s)).abs() < 1e-13);
    }

    #[test]
    fn key_paths() {
        assert_eq!(
            key_path("materials[0]", "poisson_ratio"),
            "materials[0].poisson_ratio"
        );
        assert_eq!(key_path("", "poisson_ratio"), "poisson_ratio");
    }
}
