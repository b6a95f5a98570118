//! Saint Venant–Kirchhoff: Hooke's law in the Green–Lagrange strain.

use super::{IsotropicParameters, Mat3, Mat6, Material};
use crate::Result;

/// Saint Venant–Kirchhoff hyperelasticity, with `E = ½(FᵀF − I)`:
///
/// - energy `W = λ/2 (tr E)² + μ E : E`,
/// - stress `S = λ tr(E) I + 2μ E`,
/// - tangent `𝔻 = ∂S/∂E = ℂ = λ I⊗I + 2μ 𝕀` (constant),
///
/// with `(λ, μ)` = [`lame`](super::lame)`(E, ν)`. Objective and valid for large
/// rotations, but only for moderate strains (it softens and loses stability
/// in strong compression). Defined for every `F`, so no NaN guard.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SaintVenantKirchhoff {
    params: IsotropicParameters,
}

impl SaintVenantKirchhoff {
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

    fn green_lagrange(f: &Mat3) -> Mat3 {
        (f.transpose() * f - Mat3::identity()) * 0.5
    }
}

impl Material for SaintVenantKirchhoff {
    fn name(&self) -> &'static str {
        "saint_venant_kirchhoff"
    }

    fn strain_energy(&self, f: &Mat3) -> f64 {
        self.params.hooke_energy(&Self::green_lagrange(f))
    }

    fn stress_and_tangent(&self, f: &Mat3) -> (Mat3, Mat6) {
        self.params
            .hooke_stress_and_tangent(&Self::green_lagrange(f))
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
    use crate::material::{check, isotropic_elasticity, lame, Kinematics};

    fn material() -> SaintVenantKirchhoff {
        SaintVenantKirchhoff::new(200.0, 0.3, "materials[1]").unwrap()
    }

    #[test]
    fn derivatives_match_finite_differences() {
        check::check_derivatives(&material());
    }

    #[test]
    fn reduces_to_hooke_at_identity() {
        let m = material();
        assert_eq!(m.kinematics(), Kinematics::FiniteStrain);
        let (s, d) = m.stress_and_tangent(&Mat3::identity());
        assert_eq!(s, Mat3::zeros());
        let (lambda, mu) = lame(200.0, 0.3);
        assert!((d - isotropic_elasticity(lambda, mu)).amax() < 1e-12);
    }

    #[test]
    fn objective_and_isotropic() {
        check::check_objectivity(&material());
        check::check_isotropy(&material());
    }

    #[test]
    fn invalid_parameters_name_the_key() {
        let err = SaintVenantKirchhoff::new(1.0, 0.5, "materials[1]")
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("materials[1].poisson_ratio") && err.contains("0.49"),
            "{err}"
        );
        let err = SaintVenantKirchhoff::new(-1.0, 0.3, "materials[1]")
            .unwrap_err()
            .to_string();
        assert!(err.contains("materials[1].youngs_modulus"), "{err}");
    }
}
