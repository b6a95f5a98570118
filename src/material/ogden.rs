//! Compressible Ogden hyperelasticity, computed in principal stretches.

use super::eigen3::symmetric_eigen;
use super::{key_path, nan_response, voigt_from_sym, Mat3, Mat6, Material, Vec6};
use crate::input::number;
use crate::{Error, Result};
use nalgebra::Vector3;

/// Compressible Ogden material with `N ≥ 1` terms, split into an isochoric
/// and a volumetric part:
///
/// `W = Σ_p 2μ_p/α_p² (λ̄₁^α_p + λ̄₂^α_p + λ̄₃^α_p − 3) + κ/2 (J − 1)²`,
///
/// with `λ_i` the principal stretches (`c_i = λ_i²` the eigenvalues of
/// `C = FᵀF`, eigenvectors `N_i`), `J = λ₁λ₂λ₃ = det F` and
/// `λ̄_i = J^(−1/3) λ_i`. The initial shear modulus is `μ = Σ_p μ_p` (each
/// term contributes its `μ_p` whatever `α_p`), the bulk modulus is `κ`, so
/// at `F = I` the tangent is Hooke's with `λ = κ − 2μ/3`. With one term and
/// `α = 2` the isochoric part is neo-Hookean's `μ/2 (Ī₁ − 3)`.
///
/// ## Stress and tangent
/// `W` is written as a function `W(c₁, c₂, c₃)` of the eigenvalues of `C`
/// (cyclic Jacobi, [`symmetric_eigen`]), with `w_i = ∂W/∂c_i`,
/// `w_ij = ∂²W/∂c_i∂c_j`, `M_i = N_i⊗N_i` and
/// `B_ij = ½(N_i⊗N_j + N_j⊗N_i)`:
///
/// - `S = Σ_i 2 w_i M_i`,
/// - `𝔻 = ∂S/∂E = Σ_ij 4 w_ij M_i⊗M_j + Σ_{i<j} 8 θ_ij B_ij⊗B_ij`,
///   `θ_ij = (w_i − w_j)/(c_i − c_j)`.
///
/// Per term, with `a = α/2`, `φ = J^(−α/3)`, `A = Σ_k c_k^a`:
/// `w_i = (μ/α) φ (c_i^(a−1) − A/(3c_i))`; the volumetric part adds
/// `κ(J − 1) J/(2c_i)`.
///
/// ## Equal and nearly equal principal stretches
/// The quotient `θ_ij` is never formed as a difference of `w`'s. It is
/// simplified analytically to
/// `θ_ij = Σ_p (μ_p/α_p) φ_p [Δ(c^(a_p−1))(c_i, c_j) + A_p/(3 c_i c_j)] − κ(J − 1) J/(2 c_i c_j)`,
/// where `Δ(c^b)(x, y) = (x^b − y^b)/(x − y)` is evaluated without
/// cancellation as `y^(b−1) expm1(b ln1p(r))/r`, `r = (x − y)/y`, and as
/// `b y^(b−1)` when `x = y`. At `c_i = c_j` this is exactly the L'Hôpital
/// limit `w_ii − w_ij`, and it is accurate to rounding for any gap (no
/// perturbation of the eigenvalues and no switching tolerance), so `S` and
/// `𝔻` are smooth through coalescing stretches. Within a (nearly)
/// degenerate eigenspace the individual eigenvectors are arbitrary, but the
/// formulas depend on them only through quantities that are continuous there.
///
/// The terms share their logarithms: `c_i^(a−1) = exp((a − 1) ln c_i)`,
/// `φ = exp(−(α/3) ln J)`, and `ln(1 + r)` depends on the pair only, so a
/// point costs 7 logarithms once and 7 exponentials per term (before: 13
/// calls per term, 7 of them `powf`).
///
/// For `J ≤ 0` the energy is `+∞` and stress and tangent are NaN (a failed
/// iteration for the solver); it never panics. No allocation in
/// [`Material::stress_and_tangent`].
#[derive(Clone, Debug, PartialEq)]
pub struct Ogden {
    mu: Vec<f64>,
    alpha: Vec<f64>,
    bulk_modulus: f64,
    shear_modulus: f64,
}

/// First and second derivatives of `W(c₁, c₂, c₃)` and the quotients
/// `θ_ij` (filled for `i < j`).
struct Derivatives {
    w: [f64; 3],
    ww: [[f64; 3]; 3],
    theta: [[f64; 3]; 3],
}

/// The part of `(x^b − y^b)/(x − y)` that does not depend on `b`, shared
/// by the Ogden terms: `r = (x − y)/y` and `ln(1 + r) = ln(x/y)`.
#[derive(Clone, Copy, Debug, Default)]
struct LogRatio {
    r: f64,
    ln1p: f64,
}

impl LogRatio {
    fn of(x: f64, y: f64) -> Self {
        let r = (x - y) / y;
        LogRatio { r, ln1p: r.ln_1p() }
    }
}

/// `(x^b − y^b)/(x − y)` for `x, y > 0`, free of cancellation, as
/// `y^(b−1) expm1(b ln(1 + r))/r` from `y_power = y^(b−1)` and the pair's
/// [`LogRatio`]; `b y^(b−1)` at `x = y` (`r = 0`).
fn divided_difference_with(y_power: f64, ratio: LogRatio, b: f64) -> f64 {
    if ratio.r == 0.0 {
        return b * y_power;
    }
    y_power * (b * ratio.ln1p).exp_m1() / ratio.r
}

/// `(x^b − y^b)/(x − y)` for `x, y > 0` ([`divided_difference_with`]).
#[cfg(test)]
fn power_divided_difference(x: f64, y: f64, b: f64) -> f64 {
    divided_difference_with(y.powf(b - 1.0), LogRatio::of(x, y), b)
}

impl Ogden {
    /// `mu[p]`, `alpha[p]`: the terms `(μ_p, α_p)`; `bulk_modulus`: `κ`.
    ///
    /// Requires equal lengths ≥ 1, all values finite, `α_p ≠ 0`, `μ_p > 0`
    /// and `κ > 0`. In this normalisation (`2μ_p/α_p²`), `μ_p > 0` is the
    /// usual stability condition `μ'_p α_p > 0` of the `μ'_p/α_p` form
    /// (`μ'_p = 2μ_p/α_p`); it allows negative `α_p`. Errors name
    /// `{key_prefix}.mu`, `{key_prefix}.alpha` (with the index) or
    /// `{key_prefix}.bulk_modulus`.
    pub fn new(mu: Vec<f64>, alpha: Vec<f64>, bulk_modulus: f64, key_prefix: &str) -> Result<Self> {
        let err = |name: String, message: String| Error::MaterialParameter {
            key: key_path(key_prefix, &name),
            message,
        };
        if mu.is_empty() {
            return Err(err(
                "mu".into(),
                "an Ogden material needs at least one term: give `mu` and `alpha` as \
                 arrays of the same length ≥ 1, e.g. mu = [0.5], alpha = [2.0]"
                    .into(),
            ));
        }
        if alpha.len() != mu.len() {
            return Err(err(
                "alpha".into(),
                format!(
                    "`alpha` has {} entries but `mu` has {}: give one exponent per term",
                    alpha.len(),
                    mu.len()
                ),
            ));
        }
        for (p, (&m, &a)) in mu.iter().zip(&alpha).enumerate() {
            if !(a.is_finite() && a != 0.0) {
                return Err(err(
                    format!("alpha[{p}]"),
                    format!("exponent α_{p} must be finite and non-zero, got {a}"),
                ));
            }
            if !m.is_finite() {
                return Err(err(
                    format!("mu[{p}]"),
                    format!("modulus μ_{p} must be finite, got {m}"),
                ));
            }
            if m <= 0.0 {
                return Err(err(
                    format!("mu[{p}]"),
                    format!(
                        "modulus μ_{p} = {m} (with α_{p} = {a}) must be > 0: in the form \
                         2μ_p/α_p² (Σλ̄^α_p − 3) each μ_p is that term's contribution to the \
                         shear modulus; this is the stability condition μ'_p α_p > 0 of the \
                         μ'_p/α_p form, where μ_p = μ'_p α_p / 2 (flip the sign of μ_{p} if it \
                         came from that form with a negative α)"
                    ),
                ));
            }
        }
        if !(bulk_modulus.is_finite() && bulk_modulus > 0.0) {
            return Err(err(
                "bulk_modulus".into(),
                format!(
                    "bulk modulus κ must be finite and > 0, got {bulk_modulus}; for a nearly \
                     incompressible rubber take κ ≈ 100-1000 × the shear modulus"
                ),
            ));
        }
        let shear_modulus = mu.iter().sum();
        Ok(Self {
            mu,
            alpha,
            bulk_modulus,
            shear_modulus,
        })
    }

    /// Moduli `μ_p`.
    pub fn mu(&self) -> &[f64] {
        &self.mu
    }

    /// Exponents `α_p`.
    pub fn alpha(&self) -> &[f64] {
        &self.alpha
    }

    /// Bulk modulus `κ`.
    pub fn bulk_modulus(&self) -> f64 {
        self.bulk_modulus
    }

    /// Initial shear modulus `μ = Σ_p μ_p`.
    pub fn shear_modulus(&self) -> f64 {
        self.shear_modulus
    }

    /// Initial Lamé parameters `(λ, μ) = (κ − 2μ/3, Σ μ_p)`.
    pub fn lame(&self) -> (f64, f64) {
        (
            self.bulk_modulus - 2.0 * self.shear_modulus / 3.0,
            self.shear_modulus,
        )
    }

    /// `W(c)`, given `J` (with `J² = c₁c₂c₃`).
    fn energy(&self, c: &Vector3<f64>, j: f64) -> f64 {
        let mut w = 0.5 * self.bulk_modulus * (j - 1.0) * (j - 1.0);
        for (&mu, &alpha) in self.mu.iter().zip(&self.alpha) {
            let a = 0.5 * alpha;
            let phi = j.powf(-alpha / 3.0);
            let sum: f64 = c.iter().map(|ci| ci.powf(a)).sum();
            w += 2.0 * mu / (alpha * alpha) * (phi * sum - 3.0);
        }
        w
    }

    /// `w_i`, and with `second` also `w_ij` and `θ_ij` (`i < j` only: the
    /// tangent reads those). `w` is summed in the same order either way, so
    /// the stress alone equals the stress of the full evaluation bit for bit.
    fn derivatives(&self, c: &Vector3<f64>, j: f64, second: bool) -> Derivatives {
        let mut d = Derivatives {
            w: [0.0; 3],
            ww: [[0.0; 3]; 3],
            theta: [[0.0; 3]; 3],
        };
        // the logarithms every term shares: its powers are exponentials of
        // them (`c_i^(a−1) = exp((a − 1) ln c_i)`, `J^(−α/3)` likewise),
        // and its divided differences need `ln(c_i/c_j)` (pairs i < j)
        let ln_c = [c[0].ln(), c[1].ln(), c[2].ln()];
        let ln_j = j.ln();
        // 1/c_i, 1/(3 c_i): products instead of the many quotients below
        let inv_c = [1.0 / c[0], 1.0 / c[1], 1.0 / c[2]];
        let third_inv_c = inv_c.map(|v| v / 3.0);
        let mut ratios = [[LogRatio::default(); 3]; 3];
        if second {
            for (i, jj) in [(0, 1), (0, 2), (1, 2)] {
                ratios[i][jj] = LogRatio::of(c[i], c[jj]);
            }
        }
        for (&mu, &alpha) in self.mu.iter().zip(&self.alpha) {
            let a = 0.5 * alpha;
            let k = mu / alpha * (-alpha / 3.0 * ln_j).exp(); // (2μ/α²)·a·φ
            let pm1 = ln_c.map(|l| ((a - 1.0) * l).exp());
            let sum: f64 = (0..3).map(|i| pm1[i] * c[i]).sum();
            let g: [f64; 3] = std::array::from_fn(|i| pm1[i] - sum * third_inv_c[i]);
            for i in 0..3 {
                d.w[i] += k * g[i];
                if !second {
                    continue;
                }
                for jj in 0..3 {
                    let mut v = -a * (g[i] * third_inv_c[jj] + pm1[jj] * third_inv_c[i]);
                    if i == jj {
                        v += ((a - 1.0) * pm1[i] + sum * third_inv_c[i]) * inv_c[i];
                    }
                    d.ww[i][jj] += k * v;
                    if i < jj {
                        // Δ(c^(a−1))(c_i, c_j), with c_j^(a−2) = pm1[j]/c_j
                        let dd =
                            divided_difference_with(pm1[jj] * inv_c[jj], ratios[i][jj], a - 1.0);
                        d.theta[i][jj] += k * (dd + sum * third_inv_c[i] * inv_c[jj]);
                    }
                }
            }
        }
        let kappa = self.bulk_modulus;
        let up = kappa * (j - 1.0); // U'(J)
        for i in 0..3 {
            d.w[i] += 0.5 * up * j * inv_c[i];
            if !second {
                continue;
            }
            for jj in 0..3 {
                let inv_cc = inv_c[i] * inv_c[jj];
                d.ww[i][jj] += 0.25 * (kappa * j * j + up * j) * inv_cc;
                if i == jj {
                    d.ww[i][jj] -= 0.5 * up * j * inv_cc;
                } else if i < jj {
                    d.theta[i][jj] -= 0.5 * up * j * inv_cc;
                }
            }
        }
        d
    }
}

impl Material for Ogden {
    fn name(&self) -> &'static str {
        "ogden"
    }

    fn strain_energy(&self, f: &Mat3) -> f64 {
        let j = f.determinant();
        if !(j > 0.0 && j.is_finite()) {
            return f64::INFINITY;
        }
        let c = (f.transpose() * f).symmetric_eigenvalues();
        if !c.iter().all(|&ci| ci > 0.0) {
            return f64::INFINITY;
        }
        self.energy(&c, j)
    }

    fn stress_and_tangent(&self, f: &Mat3) -> (Mat3, Mat6) {
        let j = f.determinant();
        if !(j > 0.0 && j.is_finite()) {
            return nan_response();
        }
        let (c, n) = symmetric_eigen(&(f.transpose() * f));
        if !c.iter().all(|&ci| ci > 0.0) {
            return nan_response();
        }
        let d = self.derivatives(&c, j, true);

        let m: [Mat3; 3] = std::array::from_fn(|i| {
            let ni = n.column(i);
            ni * ni.transpose()
        });
        let mv: [Vec6; 3] = std::array::from_fn(|i| voigt_from_sym(&m[i]));
        let mut s = Mat3::zeros();
        for (mi, wi) in m.iter().zip(d.w) {
            s += mi * (2.0 * wi);
        }
        // 𝔻_rc = Σ_i M_i,r u_i,c + Σ_{i<j} 8 θ_ij B_ij,r B_ij,c with
        // u_i = Σ_j 4 w_ij M_j: the upper triangle r ≤ c, mirrored (exactly
        // symmetric)
        let u: [Vec6; 3] = std::array::from_fn(|i| {
            (0..3).fold(Vec6::zeros(), |acc, jj| acc + mv[jj] * (4.0 * d.ww[i][jj]))
        });
        let pairs = [(0, 1), (1, 2), (0, 2)];
        // Voigt of ½(N_i⊗N_j + N_j⊗N_i)
        let b: [Vec6; 3] =
            pairs.map(|(i, jj)| voigt_from_sym(&(n.column(i) * n.column(jj).transpose())));
        let theta8 = pairs.map(|(i, jj)| 8.0 * d.theta[i][jj]);
        let tangent = Mat6::from_fn(|r, c| {
            let (r, c) = (r.min(c), r.max(c));
            (0..3)
                .map(|i| mv[i][r] * u[i][c] + theta8[i] * b[i][r] * b[i][c])
                .sum()
        });
        (s, tangent)
    }

    /// `S = Σ_i 2 w_i M_i` alone (no `w_ij`, `θ_ij` or `𝔻`): what a
    /// force-only evaluation (line search, convergence check) needs; equal
    /// bit for bit to the `S` of [`Material::stress_and_tangent`].
    fn second_piola_kirchhoff(&self, f: &Mat3) -> Mat3 {
        let j = f.determinant();
        if !(j > 0.0 && j.is_finite()) {
            return nan_response().0;
        }
        let (c, n) = symmetric_eigen(&(f.transpose() * f));
        if !c.iter().all(|&ci| ci > 0.0) {
            return nan_response().0;
        }
        let d = self.derivatives(&c, j, false);
        let mut s = Mat3::zeros();
        for i in 0..3 {
            let ni = n.column(i);
            s += (ni * ni.transpose()) * (2.0 * d.w[i]);
        }
        s
    }

    fn reference_youngs_modulus(&self) -> f64 {
        let (kappa, mu) = (self.bulk_modulus, self.shear_modulus);
        9.0 * kappa * mu / (3.0 * kappa + mu)
    }

    fn parameters(&self) -> String {
        format!(
            "μ = [{}], α = [{}], κ = {} (initial shear modulus {})",
            list(&self.mu),
            list(&self.alpha),
            number(self.bulk_modulus),
            number(self.shear_modulus)
        )
    }
}

/// Values as a message lists them, `1, 2.5e-9`.
fn list(values: &[f64]) -> String {
    values
        .iter()
        .map(|&v| number(v))
        .collect::<Vec<_>>()
        .join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::{
        cauchy_stress, check, isotropic_elasticity, outer_voigt, sym_product_voigt,
    };

    /// Neo-Hookean isochoric part plus Ogden's volumetric part, in closed
    /// form (Holzapfel §6.4):
    /// `W = μ/2 (J^(−2/3) I₁ − 3) + κ/2 (J − 1)²`,
    /// `S = μ J^(−2/3) (I − I₁/3 C⁻¹) + κ J (J − 1) C⁻¹`,
    /// `𝔻 = 2μ J^(−2/3) [−⅓(I⊗C⁻¹ + C⁻¹⊗I) + I₁/9 C⁻¹⊗C⁻¹ + I₁/3 𝕀_{C⁻¹}]
    ///    + J(p + J κ) C⁻¹⊗C⁻¹ − 2 J p 𝕀_{C⁻¹}`, `p = κ(J − 1)`.
    #[derive(Debug)]
    struct IsochoricNeoHookean {
        mu: f64,
        kappa: f64,
    }

    impl Material for IsochoricNeoHookean {
        fn name(&self) -> &'static str {
            "isochoric_neo_hookean"
        }
        fn strain_energy(&self, f: &Mat3) -> f64 {
            let j = f.determinant();
            let i1 = f.norm_squared();
            0.5 * self.mu * (j.powf(-2.0 / 3.0) * i1 - 3.0) + 0.5 * self.kappa * (j - 1.0).powi(2)
        }
        fn stress_and_tangent(&self, f: &Mat3) -> (Mat3, Mat6) {
            let (mu, kappa) = (self.mu, self.kappa);
            let j = f.determinant();
            let c = f.transpose() * f;
            let ci = c.try_inverse().unwrap();
            let ci = (ci + ci.transpose()) * 0.5;
            let i1 = c.trace();
            let id = Mat3::identity();
            let jm = j.powf(-2.0 / 3.0);
            let p = kappa * (j - 1.0);
            let s = (id - ci * (i1 / 3.0)) * (mu * jm) + ci * (p * j);
            let d = (-(outer_voigt(&id, &ci) + outer_voigt(&ci, &id)) / 3.0
                + outer_voigt(&ci, &ci) * (i1 / 9.0)
                + sym_product_voigt(&ci) * (i1 / 3.0))
                * (2.0 * mu * jm)
                + outer_voigt(&ci, &ci) * (j * (p + j * kappa))
                - sym_product_voigt(&ci) * (2.0 * j * p);
            (s, d)
        }
        fn reference_youngs_modulus(&self) -> f64 {
            9.0 * self.kappa * self.mu / (3.0 * self.kappa + self.mu)
        }

        fn parameters(&self) -> String {
            String::new()
        }
    }

    /// Treloar-type rubber: three terms, one with a negative exponent.
    fn rubber() -> Ogden {
        // μ'_p/α_p form (0.63, 1.3), (0.0012, 5.0), (−0.01, −2.0) converted
        // to μ_p = μ'_p α_p / 2.
        Ogden::new(
            vec![0.63 * 1.3 / 2.0, 0.0012 * 5.0 / 2.0, 0.01],
            vec![1.3, 5.0, -2.0],
            50.0,
            "materials[0]",
        )
        .unwrap()
    }

    fn materials() -> Vec<Ogden> {
        vec![
            rubber(),
            Ogden::new(vec![1.0], vec![2.0], 10.0, "m").unwrap(),
            Ogden::new(vec![0.4, 0.2], vec![3.0, -1.5], 2.0, "m").unwrap(),
            Ogden::new(vec![80.0], vec![0.7], 160.0, "m").unwrap(),
        ]
    }

    #[test]
    fn divided_difference_is_accurate() {
        for &b in &[-2.0, -0.35, 0.0, 0.5, 1.0, 1.5, 3.0] {
            for &(x, y) in &[(1.44, 1.2), (0.5, 2.0), (1.0, 1.0 + 1e-12), (3.0, 3.0)] {
                let dd = power_divided_difference(x, y, b);
                let reference = if x == y {
                    b * f64::powf(y, b - 1.0)
                } else if (x - y).abs() > 1e-3 {
                    (f64::powf(x, b) - f64::powf(y, b)) / (x - y)
                } else {
                    b * f64::powf(0.5 * (x + y), b - 1.0)
                };
                assert!(
                    (dd - reference).abs() <= 1e-12 * reference.abs().max(1e-300),
                    "b = {b}, x = {x}, y = {y}: {dd} vs {reference}"
                );
                let swapped = power_divided_difference(y, x, b);
                assert!((dd - swapped).abs() <= 1e-14 * dd.abs().max(1e-300));
            }
        }
    }

    #[test]
    fn derivatives_match_finite_differences() {
        for m in materials() {
            check::check_derivatives(&m);
        }
    }

    /// The stress-only path (no `w_ij`, `θ_ij`, `𝔻`) returns the `S` of
    /// the full evaluation bit for bit, so a force-only assembly (line
    /// search, convergence check) gives the force of the full one; and NaN
    /// where `J ≤ 0`.
    #[test]
    fn stress_alone_equals_the_full_evaluation() {
        for m in materials() {
            for (label, f) in check::deformations() {
                let (s, _) = m.stress_and_tangent(&f);
                assert_eq!(m.second_piola_kirchhoff(&f), s, "{label}");
            }
            assert!(m
                .second_piola_kirchhoff(&(-Mat3::identity()))
                .iter()
                .all(|x| x.is_nan()));
        }
    }

    #[test]
    fn reference_is_correct() {
        check::check_derivatives(&IsochoricNeoHookean {
            mu: 1.0,
            kappa: 10.0,
        });
    }

    #[test]
    fn reduces_to_hooke_at_identity() {
        for m in materials() {
            let (s, d) = m.stress_and_tangent(&Mat3::identity());
            assert!(s.amax() < 1e-13 * m.bulk_modulus(), "{s}");
            let mu: f64 = m.mu().iter().sum();
            let lambda = m.bulk_modulus() - 2.0 * mu / 3.0;
            assert_eq!(m.lame(), (lambda, mu));
            let c = isotropic_elasticity(lambda, mu);
            assert!((d - c).amax() < 1e-12 * c.amax(), "{d}\n{c}");
            assert_eq!(m.strain_energy(&Mat3::identity()), 0.0);
        }
    }

    #[test]
    fn one_term_alpha_two_is_isochoric_neo_hookean() {
        let (mu, kappa) = (1.7, 23.0);
        let ogden = Ogden::new(vec![mu], vec![2.0], kappa, "m").unwrap();
        let reference = IsochoricNeoHookean { mu, kappa };
        for (label, f) in check::deformations() {
            let (w0, w1) = (ogden.strain_energy(&f), reference.strain_energy(&f));
            assert!(
                (w0 - w1).abs() <= 1e-10 * w1.abs().max(1e-3 * mu),
                "{label}: {w0} vs {w1}"
            );
            let (s0, d0) = ogden.stress_and_tangent(&f);
            let (s1, d1) = reference.stress_and_tangent(&f);
            assert!(
                check::rel_err(&s0, &s1, 1e-3 * mu) < 1e-10,
                "{label}: {s0} vs {s1}"
            );
            assert!(
                check::rel_err(&d0, &d1, 1e-3 * mu) < 1e-10,
                "{label}: {d0} vs {d1}"
            );
        }
    }

    #[test]
    fn terms_add_up() {
        // The volumetric part is linear in κ, so a two-term material with
        // κ₁ + κ₂ is exactly the sum of the one-term materials.
        let both = Ogden::new(vec![0.4, 0.2], vec![3.0, -1.5], 5.0, "m").unwrap();
        let first = Ogden::new(vec![0.4], vec![3.0], 2.0, "m").unwrap();
        let second = Ogden::new(vec![0.2], vec![-1.5], 3.0, "m").unwrap();
        for (label, f) in check::deformations() {
            let w = first.strain_energy(&f) + second.strain_energy(&f);
            assert!((both.strain_energy(&f) - w).abs() <= 1e-12 * w.abs().max(1e-3));
            let (s1, d1) = first.stress_and_tangent(&f);
            let (s2, d2) = second.stress_and_tangent(&f);
            let (s, d) = both.stress_and_tangent(&f);
            assert!(check::rel_err(&s, &(s1 + s2), 1e-3) < 1e-12, "{label}");
            assert!(check::rel_err(&d, &(d1 + d2), 1e-3) < 1e-12, "{label}");
        }
    }

    #[test]
    fn continuous_through_equal_stretches() {
        let m = rubber();
        let base = m.stress_and_tangent(&check::diag(1.2, 1.2, 0.8));
        for gap in [1e-14, 1e-12, 1e-9, 1e-7, 1e-5] {
            let (s, d) = m.stress_and_tangent(&check::diag(1.2, 1.2 + gap, 0.8));
            let tol = 1e-12 + 10.0 * gap;
            assert!(check::rel_err(&s, &base.0, 1e-3) < tol, "gap {gap}");
            assert!(check::rel_err(&d, &base.1, 1e-3) < tol, "gap {gap}");
        }
        // Three equal stretches, rotated: 𝔻 of a pure dilatation is isotropic.
        let q = check::random_rotation(3);
        let (_, d0) = m.stress_and_tangent(&(Mat3::identity() * 1.1));
        let (_, d1) = m.stress_and_tangent(&(q * 1.1));
        assert!(check::rel_err(&d1, &d0, 1e-3) < 1e-12);
    }

    #[test]
    fn objective_and_isotropic() {
        for m in materials() {
            check::check_objectivity(&m);
            check::check_isotropy(&m);
        }
    }

    #[test]
    fn inverted_or_degenerate_gives_nan_not_panic() {
        check::check_nan_where_undefined(&rubber(), check::diag(1.0, 0.0, 1.0));
    }

    /// Uniaxial stress, one term: principal Kirchhoff stresses
    /// `τ_i = (2μ/α)(λ̄_i^α − ⅓ Σ_k λ̄_k^α) + κ J (J − 1)`. At
    /// `F = diag(l, t, t)` the lateral condition `τ₂ = 0` reads
    /// `(2μ/3α)(λ̄₂^α − λ̄₁^α) + κ J (J − 1) = 0`, and then
    /// `σ₁₁ = (2μ/α)(λ̄₁^α − λ̄₂^α)/J`, `λ̄₁ = J^(−1/3) l`, `λ̄₂ = J^(−1/3) t`.
    #[test]
    fn uniaxial_stress_closed_form() {
        for (mu, alpha, kappa) in [(1.0, 2.0, 10.0), (0.5, 5.0, 20.0), (0.3, -2.0, 5.0)] {
            let m = Ogden::new(vec![mu], vec![alpha], kappa, "m").unwrap();
            let lateral = |l: f64, t: f64| {
                let j = l * t * t;
                let (b1, b2) = (j.powf(-1.0 / 3.0) * l, j.powf(-1.0 / 3.0) * t);
                2.0 * mu / (3.0 * alpha) * (b2.powf(alpha) - b1.powf(alpha)) + kappa * j * (j - 1.0)
            };
            for l in [0.6, 0.9, 1.0, 1.3, 2.0] {
                let mut t: f64 = 1.0;
                for _ in 0..100 {
                    let h = 1e-7;
                    let g = lateral(l, t);
                    let dg = (lateral(l, t + h) - lateral(l, t - h)) / (2.0 * h);
                    t -= g / dg;
                }
                assert!(lateral(l, t).abs() < 1e-13 * kappa);
                let f = check::diag(l, t, t);
                let j = l * t * t;
                let (b1, b2) = (j.powf(-1.0 / 3.0) * l, j.powf(-1.0 / 3.0) * t);
                let closed = 2.0 * mu / alpha * (b1.powf(alpha) - b2.powf(alpha)) / j;
                let sigma = cauchy_stress(&f, &m.second_piola_kirchhoff(&f));
                let scale = mu * 1e-12;
                assert!(
                    (sigma[(0, 0)] - closed).abs() < scale,
                    "α = {alpha}, l = {l}"
                );
                assert!(sigma[(1, 1)].abs() < scale && sigma[(2, 2)].abs() < scale);
                assert!((sigma - sigma.transpose()).amax() < scale);
            }
        }
    }

    #[test]
    fn invalid_parameters_name_the_key() {
        let k = "materials[4]";
        let err = Ogden::new(vec![-1.0], vec![2.0], 10.0, k)
            .unwrap_err()
            .to_string();
        assert!(err.contains("materials[4].mu[0]"), "{err}");
        let err = Ogden::new(vec![1.0, -0.5], vec![2.0, -2.0], 10.0, k)
            .unwrap_err()
            .to_string();
        assert!(err.contains("materials[4].mu[1]"), "{err}");
        let err = Ogden::new(vec![1.0, 2.0], vec![2.0], 10.0, k)
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("materials[4].alpha") && err.contains("1 entries"),
            "{err}"
        );
        let err = Ogden::new(vec![], vec![], 10.0, k).unwrap_err().to_string();
        assert!(err.contains("materials[4].mu"), "{err}");
        let err = Ogden::new(vec![1.0], vec![0.0], 10.0, k)
            .unwrap_err()
            .to_string();
        assert!(err.contains("materials[4].alpha[0]"), "{err}");
        let err = Ogden::new(vec![f64::NAN], vec![2.0], 10.0, k)
            .unwrap_err()
            .to_string();
        assert!(err.contains("materials[4].mu[0]"), "{err}");
        let err = Ogden::new(vec![1.0], vec![2.0], 0.0, k)
            .unwrap_err()
            .to_string();
        assert!(err.contains("materials[4].bulk_modulus"), "{err}");
        // Negative exponents are fine with a positive modulus.
        assert!(Ogden::new(vec![1.0], vec![-2.0], 10.0, k).is_ok());
    }
}
