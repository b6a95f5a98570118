//! Causes of non-convergence that show before a solve (issue 14 item 3):
//! material constants outside the range of floating-point arithmetic, a
//! load implausible for the material (a strain far beyond any material's
//! range, or below round-off), a first increment asking a huge strain, and
//! a nearly incompressible material on linear elements (volumetric
//! locking). `signorini check` prints them, a run prints them at its start
//! and, when it fails, names them as the likely cause
//! ([`explain_failure`]). Each message says what was found and the fix.
//!
//! ## The strain of a load
//! With `L` the body's size (the diagonal of its bounding box) and `E`
//! the softest material's Young's modulus, a load's strain is estimated as
//! its force over `E·L²`, the force that strains a body of size `L` by one:
//! a pressure `p` strains it by `ε = p/E`, a body force `b` (per volume) by
//! `|b|·L/E`, point forces of total `F` by `F/(E·L²)`, and a prescribed
//! displacement `u` by `|u|/L`. The estimates are at each load's largest
//! amplitude over the steps (the whole load) and at the end of the first
//! increment.

use super::Case;
use crate::assembly::amplitude::Amplitude;
use crate::material::Material;
use crate::problem::Problem;

/// A whole load straining the body by more than this is implausible.
pub const LARGEST_STRAIN: f64 = 10.0;
/// A first increment straining the body by more than this asks Newton to
/// jump too far at once.
pub const LARGEST_FIRST_STRAIN: f64 = 1.0;
/// A whole load straining the body by less than this is lost in the
/// round-off of the coordinates.
pub const SMALLEST_STRAIN: f64 = 1e-10;
/// Material constants outside `[1/LARGEST_MODULUS, LARGEST_MODULUS]`:
/// forces, stiffnesses and their products leave the range of `f64`.
pub const LARGEST_MODULUS: f64 = 1e30;
/// A bulk-to-shear modulus ratio `κ/μ` above this (`ν > 0.495`) locks
/// linear elements.
pub const LOCKING_RATIO: f64 = 100.0;

/// Young's modulus `E`, Poisson's ratio `ν` and the bulk-to-shear ratio
/// `κ/μ` of a material in the reference state, from its tangent at
/// `F = I`: `λ = 𝔻₁₂`, `μ = 𝔻₄₄`, `E = μ(3λ + 2μ)/(λ + μ)`,
/// `ν = λ/(2(λ + μ))`, `κ = λ + 2μ/3`.
pub fn initial_constants(material: &dyn Material) -> (f64, f64, f64) {
    let (_, d) = material.stress_and_tangent(&crate::material::Mat3::identity());
    let (lambda, mu) = (d[(0, 1)], d[(3, 3)]);
    let youngs = mu * (3.0 * lambda + 2.0 * mu) / (lambda + mu);
    let poisson = lambda / (2.0 * (lambda + mu));
    (youngs, poisson, (lambda + 2.0 * mu / 3.0) / mu)
}

/// `x` to 12 significant digits, without trailing zeros (`0.4999999999`,
/// not `0.49999999989999994`).
fn significant(x: f64) -> String {
    let text = format!("{x:.12}");
    text.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// The largest `|amplitude|` over the steps and its value at the end of
/// the first increment (`t₁`).
fn amplitude_range(amplitude: &Amplitude, end: f64, t1: f64) -> (f64, f64) {
    let samples = 200;
    let peak = (0..=samples)
        .map(|i| amplitude.value(end * i as f64 / samples as f64).abs())
        .fold(0.0f64, f64::max);
    (peak, amplitude.value(t1).abs())
}

/// A load's strain (whole, first increment) and its name in messages.
struct LoadStrain {
    what: String,
    whole: f64,
    first: f64,
}

/// Every load's strain estimate (see the module's documentation).
fn load_strains(problem: &Problem, youngs: f64, size: f64) -> Vec<LoadStrain> {
    let end = problem.steps.last().map_or(1.0, |s| s.end_time);
    let t1 = problem
        .steps
        .first()
        .map_or(end, |s| s.initial_increment.min(s.end_time));
    let mut out = Vec::new();
    let mut push = |what: String, strain: f64, amplitude: &Amplitude| {
        let (peak, first) = amplitude_range(amplitude, end, t1);
        out.push(LoadStrain {
            what,
            whole: strain * peak,
            first: strain * first,
        });
    };
    for p in &problem.pressures {
        push(
            format!("the pressure {:.3e} on surface '{}'", p.pressure, p.surface),
            p.pressure.abs() / youngs,
            &p.amplitude,
        );
    }
    for b in &problem.body_forces {
        let f = b.force;
        let norm = (f[0] * f[0] + f[1] * f[1] + f[2] * f[2]).sqrt();
        push(
            format!("the body force {norm:.3e} on region '{}'", b.region),
            norm * size / youngs,
            &b.amplitude,
        );
    }
    for n in &problem.nodal_forces {
        let f = n.force;
        let total = (f[0] * f[0] + f[1] * f[1] + f[2] * f[2]).sqrt() * n.nodes.len() as f64;
        push(
            format!("the force {total:.3e} on node set '{}'", n.set),
            total / (youngs * size * size),
            &n.amplitude,
        );
    }
    for d in &problem.prescribed {
        let largest = d
            .components
            .iter()
            .map(|(_, v)| v.abs())
            .fold(0.0f64, f64::max);
        if largest > 0.0 {
            push(
                format!(
                    "the prescribed displacement {largest:.3e} on '{}'",
                    d.surface
                ),
                largest / size,
                &d.amplitude,
            );
        }
    }
    out
}

impl Case {
    /// The warnings on `problem` (built from this case): each names the
    /// case-file key, what was found and the fix. Empty for a plausible
    /// model.
    pub fn diagnose(&self, problem: &Problem) -> Vec<String> {
        let mut out = Vec::new();
        let mut softest = f64::INFINITY;
        for (i, m) in problem.model.materials.iter().enumerate() {
            let region = self
                .spec
                .material
                .get(i)
                .map_or(String::new(), |s| format!(" (region '{}')", s.region));
            let key = format!("material[{i}]{region}");
            let (_, poisson, ratio) = initial_constants(m.as_ref());
            let youngs = m.reference_youngs_modulus();
            softest = softest.min(youngs);
            if !(1.0 / LARGEST_MODULUS..=LARGEST_MODULUS).contains(&youngs) {
                out.push(format!(
                    "implausible material scale: {key} has Young's modulus {youngs:.3e}, outside \
                     {:.0e} … {LARGEST_MODULUS:.0e}, where forces and stiffnesses leave the range of \
                     floating-point numbers (the residual overflows or underflows); give the model \
                     in units that bring E near 1–1e6 (e.g. mm, N, MPa: steel E = 2.1e5)",
                    1.0 / LARGEST_MODULUS
                ));
            }
            if ratio > LOCKING_RATIO {
                out.push(format!(
                    "incompressibility locking: {key} is nearly incompressible (ν = {}, \
                     bulk/shear modulus κ/μ = {ratio:.3e}); the linear elements (Tet4, Hex8) lock: \
                     their volume constraint makes the body far too stiff and the tangent \
                     ill-conditioned, so Newton stalls or fails; use ν ≤ 0.49 (for Ogden, \
                     bulk_modulus ≤ 50 × the initial shear modulus)",
                    significant(poisson)
                ));
            }
        }
        let size = problem.model.size();
        if !(softest > 0.0 && softest.is_finite() && size > 0.0 && size.is_finite()) {
            return out;
        }
        let strains = load_strains(problem, softest, size);
        let scale = format!(
            "E·L² = {:.3e}, E = {softest:.3e}, L = {size:.3e}",
            softest * size * size
        );
        if let Some(s) = strains
            .iter()
            .filter(|s| s.whole > LARGEST_STRAIN)
            .max_by(|a, b| a.whole.total_cmp(&b.whole))
        {
            out.push(format!(
                "implausible load scale: {} strains the body by about {:.3e} ({scale}: the softest \
                 material's Young's modulus and the body's size), beyond any material's range; \
                 check the units of the load and of the Young's modulus",
                s.what, s.whole
            ));
        } else if let Some(s) = strains
            .iter()
            .filter(|s| s.first > LARGEST_FIRST_STRAIN)
            .max_by(|a, b| a.first.total_cmp(&b.first))
        {
            out.push(format!(
                "first increment too large: {} strains the body by about {:.3e} in the first \
                 increment ({scale}); take a smaller initial_increment in the first [[step]] \
                 (at most {:.2e} of the load)",
                s.what,
                s.first,
                LARGEST_FIRST_STRAIN / s.whole.max(s.first),
            ));
        }
        let largest = strains.iter().map(|s| s.whole).fold(0.0f64, f64::max);
        if largest > 0.0 && largest < SMALLEST_STRAIN {
            let s = strains
                .iter()
                .max_by(|a, b| a.whole.total_cmp(&b.whole))
                .map_or(String::new(), |s| s.what.clone());
            out.push(format!(
                "implausible load scale: the largest load, {s}, strains the body by about \
                 {largest:.3e} ({scale}), below the round-off of the coordinates; check the units \
                 of the load and of the Young's modulus"
            ));
        }
        out
    }
}

/// The error of a failed run with the warnings of the model named as its
/// likely cause (the error unchanged without warnings, or for any error
/// but a failed convergence).
pub fn explain_failure(mut error: crate::Error, warnings: &[String]) -> crate::Error {
    if let crate::Error::NoConvergence { reason, .. } = &mut error {
        if !warnings.is_empty() {
            *reason = format!("{reason}; likely cause: {}", warnings.join("; "));
        }
    }
    error
}
