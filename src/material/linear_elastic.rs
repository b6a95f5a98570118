//! Small-strain isotropic Hooke's law.

use super::{IsotropicParameters, Kinematics, Mat3, Mat6, Material};
use crate::Result;

/// Small-strain isotropic linear elasticity (Hooke).
///
/// With the infinitesimal strain `ε = sym(F) − I` (`sym(A) = ½(A + Aᵀ)`):
///
/// - energy `W = ½ ε : ℂ : ε = λ/2 (tr ε)² + μ ε : ε`,
/// - stress `σ = ℂ : ε = λ tr(ε) I + 2μ ε`,
/// - tangent `∂σ/∂ε = ℂ = λ I⊗I + 2μ 𝕀` (constant),
///
/// with Lamé parameters `(λ, μ)` = [`lame`](super::lame)`(E, ν)`. Its
/// [`Kinematics`] is [`Kinematics::SmallStrain`]: the returned "S" is the
/// Cauchy stress σ, which the caller uses as is (no push-forward). The law is
/// not objective under large rotations, by design.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LinearElastic {
    params: IsotropicParameters,
}

impl LinearElastic {
    /// Validates `E > 0` and `−1 < ν < 0.5` (finite); errors carry the key
    /// paths `{key_prefix}.youngs_modulus` / `{key_prefix}.poisson_ratio`.
    pub fn new(youngs_modulus: f64, poisson_ratio: f64, key_prefix: &str) -> Result<Self> {
        let params = IsotropicParameters::new(youngs_modulus, poisson_ratio, key_prefix)?;
        Ok(Self { params })
    }

    /// Young's modulus `E`.
    pub fn youngs_modulus(&self) -> f64 {
        self.params.youngs_modulus()
    }

    /// Poisson's ratio `ν`.
    pub fn poisson_ratio(&self) -> f64 {
        self.params.poisson_ratio()
    }

    /// Lamé parameters `(λ, μ)`.
    pub fn lame(&self) -> (f64, f64) {
        self.params.lame()
    }

    fn strain(f: &Mat3) -> Mat3 {
        (f + f.transpose()) * 0.5 - Mat3::identity()
    }
}

impl Material for LinearElastic {
    fn name(&self) -> &'static str {
        "linear_elastic"
    }

    fn kinematics(&self) -> Kinematics {
        Kinematics::SmallStrain
    }

    /// `σ = ℂ : ε` with `ε = sym(∇u)` and the linear `B`: `K = ∫ Bᵀ ℂ B dV`
    /// does not depend on `u`.
    fn constant_tangent(&self) -> bool {
        true
    }

    fn hooke_lame(&self) -> Option<(f64, f64)> {
        Some(self.params.lame())
    }

    fn strain_energy(&self, f: &Mat3) -> f64 {
        self.params.hooke_energy(&Self::strain(f))
    }

    fn stress_and_tangent(&self, f: &Mat3) -> (Mat3, Mat6) {
        self.params.hooke_stress_and_tangent(&Self::strain(f))
    }

    fn reference_youngs_modulus(&self) -> f64 {
        self.params.youngs_modulus()
    }

    fn parameters(&self) -> String {
        self.params.describe()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::{check, isotropic_elasticity, lame};

    fn steel() -> LinearElastic {
        LinearElastic::new(210.0, 0.3, "materials[0]").unwrap()
    }

    #[test]
    fn derivatives_match_finite_differences() {
        check::check_derivatives(&steel());
        check::check_derivatives(&LinearElastic::new(3.0, -0.4, "m").unwrap());
        check::check_derivatives(&LinearElastic::new(3.0, 0.49, "m").unwrap());
    }

    #[test]
    fn tangent_is_hooke_and_stress_is_linear() {
        let m = steel();
        assert_eq!(m.kinematics(), Kinematics::SmallStrain);
        let (lambda, mu) = lame(210.0, 0.3);
        let f = Mat3::new(1.01, 0.002, 0.0, 0.004, 0.99, 0.001, 0.0, -0.001, 1.003);
        let (sigma, d) = m.stress_and_tangent(&f);
        assert_eq!(d, isotropic_elasticity(lambda, mu));
        // Uniaxial stress state: ε = diag(e, −νe, −νe) gives σ = diag(E e, 0, 0).
        let e = 1e-3;
        let f = check::diag(1.0 + e, 1.0 - 0.3 * e, 1.0 - 0.3 * e);
        let (sigma_u, _) = m.stress_and_tangent(&f);
        assert!((sigma_u[(0, 0)] - 210.0 * e).abs() < 1e-12);
        assert!(sigma_u[(1, 1)].abs() < 1e-12 && sigma_u[(2, 2)].abs() < 1e-12);
        // Rigid infinitesimal rotation (skew part) produces no stress.
        let w = Mat3::new(0.0, 0.01, -0.02, -0.01, 0.0, 0.03, 0.02, -0.03, 0.0);
        let (s_skew, _) = m.stress_and_tangent(&(f + w));
        assert!((s_skew - sigma_u).amax() < 1e-12);
        assert!(sigma.iter().all(|x| x.is_finite()));
        assert_eq!(m.reference_youngs_modulus(), 210.0);
        assert_eq!(m.hooke_lame(), Some((lambda, mu)));
    }

    #[test]
    fn invalid_parameters_name_the_key() {
        let err = LinearElastic::new(210.0, 0.5, "materials[0]")
            .unwrap_err()
            .to_string();
        assert!(err.contains("materials[0].poisson_ratio"), "{err}");
        assert!(err.contains("0.49"), "{err}");
        let err = LinearElastic::new(-1.0, 0.3, "materials[2]")
            .unwrap_err()
            .to_string();
        assert!(err.contains("materials[2].youngs_modulus"), "{err}");
        let err = LinearElastic::new(f64::NAN, 0.3, "m")
            .unwrap_err()
            .to_string();
        assert!(err.contains("m.youngs_modulus"), "{err}");
        let err = LinearElastic::new(1.0, -1.0, "m").unwrap_err().to_string();
        assert!(
            err.contains("m.poisson_ratio") && err.contains("-1 < ν < 0.5"),
            "{err}"
        );
        let err = LinearElastic::new(1.0, f64::INFINITY, "m")
            .unwrap_err()
            .to_string();
        assert!(err.contains("m.poisson_ratio"), "{err}");
    }
}
