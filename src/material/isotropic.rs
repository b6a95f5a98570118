//! The elastic constants shared by the isotropic laws ([`LinearElastic`],
//! [`SaintVenantKirchhoff`], [`NeoHookean`]): Young's modulus, Poisson's
//! ratio and the Lamé parameters derived from them.
//!
//! [`LinearElastic`]: super::LinearElastic
//! [`SaintVenantKirchhoff`]: super::SaintVenantKirchhoff
//! [`NeoHookean`]: super::NeoHookean

use super::{isotropic_elasticity, key_path, lame, Mat3, Mat6};
use crate::input::number;
use crate::{Error, Result};

/// Validated `(E, ν)` with their Lamé parameters `(λ, μ)` = [`lame`]`(E, ν)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct IsotropicParameters {
    youngs_modulus: f64,
    poisson_ratio: f64,
    lambda: f64,
    mu: f64,
}

impl IsotropicParameters {
    /// Validates `E > 0` and `−1 < ν < 0.5` (finite); errors carry the key
    /// paths `{key_prefix}.youngs_modulus` / `{key_prefix}.poisson_ratio`.
    pub(crate) fn new(youngs_modulus: f64, poisson_ratio: f64, key_prefix: &str) -> Result<Self> {
        validate_youngs_poisson(youngs_modulus, poisson_ratio, key_prefix)?;
        let (lambda, mu) = lame(youngs_modulus, poisson_ratio);
        Ok(Self {
            youngs_modulus,
            poisson_ratio,
            lambda,
            mu,
        })
    }

    /// `"E = …, ν = …"`.
    pub(crate) fn describe(&self) -> String {
        format!(
            "E = {}, ν = {}",
            number(self.youngs_modulus),
            number(self.poisson_ratio)
        )
    }

    /// Young's modulus `E`.
    pub(crate) fn youngs_modulus(&self) -> f64 {
        self.youngs_modulus
    }

    /// Poisson's ratio `ν`.
    pub(crate) fn poisson_ratio(&self) -> f64 {
        self.poisson_ratio
    }

    /// Lamé parameters `(λ, μ)`.
    pub(crate) fn lame(&self) -> (f64, f64) {
        (self.lambda, self.mu)
    }

    /// Hooke's energy in the strain `e`: `λ/2 (tr e)² + μ e : e`.
    pub(crate) fn hooke_energy(&self, e: &Mat3) -> f64 {
        let tr = e.trace();
        0.5 * self.lambda * tr * tr + self.mu * e.component_mul(e).sum()
    }

    /// Hooke's stress `λ tr(e) I + 2μ e` in the strain `e` and the constant
    /// tangent `ℂ = λ I⊗I + 2μ 𝕀`.
    pub(crate) fn hooke_stress_and_tangent(&self, e: &Mat3) -> (Mat3, Mat6) {
        let stress = Mat3::identity() * (self.lambda * e.trace()) + e * (2.0 * self.mu);
        (stress, isotropic_elasticity(self.lambda, self.mu))
    }
}

/// Checks `E > 0` and `−1 < ν < 0.5`, both finite; errors name
/// `{key_prefix}.youngs_modulus` / `{key_prefix}.poisson_ratio`.
fn validate_youngs_poisson(
    youngs_modulus: f64,
    poisson_ratio: f64,
    key_prefix: &str,
) -> Result<()> {
    if !(youngs_modulus.is_finite() && youngs_modulus > 0.0) {
        return Err(Error::MaterialParameter {
            key: key_path(key_prefix, "youngs_modulus"),
            message: format!(
                "Young's modulus must be finite and > 0, got {youngs_modulus}; \
                 give a positive value in your unit system (e.g. 210000 for steel in MPa)"
            ),
        });
    }
    if !poisson_ratio.is_finite() || poisson_ratio <= -1.0 {
        return Err(Error::MaterialParameter {
            key: key_path(key_prefix, "poisson_ratio"),
            message: format!(
                "Poisson's ratio must be finite with -1 < ν < 0.5, got {poisson_ratio}; \
                 typical values are 0.3 for metals and 0.45-0.49 for rubbers"
            ),
        });
    }
    if poisson_ratio >= 0.5 {
        return Err(Error::MaterialParameter {
            key: key_path(key_prefix, "poisson_ratio"),
            message: format!(
                "Poisson's ratio must satisfy -1 < ν < 0.5, got {poisson_ratio}; \
                 incompressible materials (ν = 0.5) are not supported by this \
                 displacement formulation: use a nearly incompressible value such as 0.49"
            ),
        });
    }
    Ok(())
}
