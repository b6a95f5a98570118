//! Compressible neo-Hookean hyperelasticity.

use super::{
    nan_response, outer_voigt, sym_product_voigt, IsotropicParameters, Mat3, Mat6, Material,
};
use crate::Result;

/// Compressible neo-Hookean material (Ciarlet / Simo–Pister form), with
/// `C = FᵀF`, `I₁ = tr C`, `J = det F` and `(λ, μ)` = [`lame`](super::lame)`(E, ν)`:
///
/// - energy `W = μ/2 (I₁ − 3) − μ ln J + λ/2 (ln J)²`,
/// - stress `S = μ (I − C⁻¹) + λ ln J C⁻¹`,
/// - tangent `𝔻 = λ C⁻¹⊗C⁻¹ + 2(μ − λ ln J) 𝕀_{C⁻¹}` with
///   `(𝕀_{C⁻¹})_ijkl = ½(C⁻¹_ik C⁻¹_jl + C⁻¹_il C⁻¹_jk)`.
///
/// At `F = I` it reduces to Hooke's law with the same `(λ, μ)`. For `J ≤ 0`
/// the energy is `+∞` and stress and tangent are NaN (a failed iteration for
/// the solver); it never panics.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NeoHookean {
    params: IsotropicParameters,
}

impl NeoHookean {
    /// Validates `E > 0` and `−1 < ν < 0.5` (finite); errors carry the key
    /// paths `{key_prefix}.youngs_modulus` / `{key_prefix}.poisson_ratio`.
    pub fn new(youngs_modulus: f64, poisson_ratio: f64, key_prefix: &str) -> Result<Self> {
        let params = IsotropicParameters::new(youngs_modulus, poisson_ratio, key_prefix)?;
        Ok(Self { params })
    }

    /// Young's modulus `E` (initial).
    pub fn youngs_modulus(&self) -> f64 {
        self.params.youngs_modulus()
    }

    /// Poisson's ratio `ν` (initial).
    pub fn poisson_ratio(&self) -> f64 {
        self.params.poisson_ratio()
    }

    /// Lamé parameters `(λ, μ)`.
    pub fn lame(&self) -> (f64, f64) {
        self.params.lame()
    }

    /// `S = μ(I − C⁻¹) + λ ln J C⁻¹` with the symmetrised `C⁻¹` and `ln J`
    /// that the tangent reuses; `None` where `J ≤ 0` or `C` is singular.
    fn stress(&self, f: &Mat3) -> Option<(Mat3, Mat3, f64)> {
        let (lambda, mu) = self.params.lame();
        let j = f.determinant();
        if !(j > 0.0 && j.is_finite()) {
            return None;
        }
        let c_inv = (f.transpose() * f).try_inverse()?;
        let c_inv = (c_inv + c_inv.transpose()) * 0.5;
        let ln_j = j.ln();
        let s = (Mat3::identity() - c_inv) * mu + c_inv * (lambda * ln_j);
        Some((s, c_inv, ln_j))
    }
}

impl Material for NeoHookean {
    fn name(&self) -> &'static str {
        "neo_hookean"
    }

    fn strain_energy(&self, f: &Mat3) -> f64 {
        let (lambda, mu) = self.params.lame();
        let j = f.determinant();
        if !(j > 0.0 && j.is_finite()) {
            return f64::INFINITY;
        }
        let i1 = f.norm_squared(); // tr(FᵀF)
        let ln_j = j.ln();
        0.5 * mu * (i1 - 3.0) - mu * ln_j + 0.5 * lambda * ln_j * ln_j
    }

    fn stress_and_tangent(&self, f: &Mat3) -> (Mat3, Mat6) {
        let (lambda, mu) = self.params.lame();
        let Some((s, c_inv, ln_j)) = self.stress(f) else {
            return nan_response();
        };
        let d = outer_voigt(&c_inv, &c_inv) * lambda
            + sym_product_voigt(&c_inv) * (2.0 * (mu - lambda * ln_j));
        (s, d)
    }

    /// `S` alone, without `𝔻` (the same numbers as [`Self::stress_and_tangent`]).
    fn second_piola_kirchhoff(&self, f: &Mat3) -> Mat3 {
        self.stress(f)
            .map_or_else(|| nan_response().0, |(s, _, _)| s)
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
    use crate::material::{cauchy_stress, check, isotropic_elasticity, lame};

    fn rubber() -> NeoHookean {
        NeoHookean::new(10.0, 0.45, "materials[0]").unwrap()
    }

    #[test]
    fn derivatives_match_finite_differences() {
        check::check_derivatives(&rubber());
        check::check_derivatives(&NeoHookean::new(200.0, 0.3, "m").unwrap());
        check::check_derivatives(&NeoHookean::new(1.0, -0.2, "m").unwrap());
    }

    #[test]
    fn reduces_to_hooke_at_identity() {
        let m = rubber();
        let (s, d) = m.stress_and_tangent(&Mat3::identity());
        assert!(s.amax() < 1e-14);
        let (lambda, mu) = lame(10.0, 0.45);
        assert!((d - isotropic_elasticity(lambda, mu)).amax() < 1e-12 * d.amax());
        assert_eq!(m.strain_energy(&Mat3::identity()), 0.0);
    }

    #[test]
    fn objective_and_isotropic() {
        check::check_objectivity(&rubber());
        check::check_isotropy(&rubber());
    }

    #[test]
    fn inverted_or_degenerate_gives_nan_not_panic() {
        check::check_nan_where_undefined(&rubber(), check::diag(1.0, 1.0, 0.0));
    }

    /// Uniaxial stress: `F = diag(l, t, t)` with `t` such that the lateral
    /// stress vanishes, `μ(t² − 1) + λ ln J = 0` (`J = l t²`). Then
    /// `σ₁₁ = (μ(l² − 1) + λ ln J)/J = μ(l² − t²)/J`.
    #[test]
    fn uniaxial_stress_closed_form() {
        let m = rubber();
        let (lambda, mu) = m.lame();
        for l in [0.7, 0.9, 1.0, 1.1, 1.5, 2.0] {
            // Newton on g(t) = μ(t² − 1) + λ ln(l t²).
            let mut t: f64 = 1.0;
            for _ in 0..50 {
                let g = mu * (t * t - 1.0) + lambda * (l * t * t).ln();
                let dg = 2.0 * mu * t + 2.0 * lambda / t;
                t -= g / dg;
            }
            let f = check::diag(l, t, t);
            let j = l * t * t;
            let sigma = cauchy_stress(&f, &m.second_piola_kirchhoff(&f));
            let closed = (mu * (l * l - 1.0) + lambda * j.ln()) / j;
            let closed_lateral = mu * (l * l - t * t) / j;
            assert!((closed - closed_lateral).abs() < 1e-12 * mu);
            assert!((sigma[(0, 0)] - closed).abs() < 1e-12 * mu, "l = {l}");
            assert!(sigma[(1, 1)].abs() < 1e-12 * mu && sigma[(2, 2)].abs() < 1e-12 * mu);
            // Small stretch: the slope is Young's modulus.
            if l == 1.0 {
                assert!(sigma.amax() < 1e-14);
            }
        }
        let l: f64 = 1.0 + 1e-7;
        let nu = m.poisson_ratio();
        let t = 1.0 - nu * 1e-7;
        let f = check::diag(l, t, t);
        let sigma = cauchy_stress(&f, &m.second_piola_kirchhoff(&f));
        assert!((sigma[(0, 0)] / 1e-7 - 10.0).abs() < 1e-5);
    }

    #[test]
    fn invalid_parameters_name_the_key() {
        let err = NeoHookean::new(1.0, 0.5, "materials[3]")
            .unwrap_err()
            .to_string();
        assert!(err.contains("materials[3].poisson_ratio"), "{err}");
        assert!(
            err.contains("incompressib") && err.contains("0.49"),
            "{err}"
        );
        let err = NeoHookean::new(-1.0, 0.3, "materials[3]")
            .unwrap_err()
            .to_string();
        assert!(err.contains("materials[3].youngs_modulus"), "{err}");
    }
}
