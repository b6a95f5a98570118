//! Test helpers shared by the material tests: a set of deformation
//! gradients (identity, random, equal and nearly equal principal stretches,
//! rotated ones) and central-difference checks of `S = ∂W/∂E` and
//! `𝔻 = ∂S/∂E` (or `σ = ∂W/∂ε`, `ℂ = ∂σ/∂ε` for small-strain laws).
//!
//! Strains are perturbed directly in Voigt components (engineering shear):
//! for finite strain `F' = F L⁻ᵀ L'ᵀ` with the Cholesky factors
//! `C = L Lᵀ`, `C + 2 δE = L' L'ᵀ`, so that `F'ᵀF' = C + 2 δE` exactly; for
//! small strain `F' = F + δε`.

use super::{sym_from_voigt, voigt_from_sym, Kinematics, Mat3, Mat6, Material, Vec6};
use nalgebra::{Rotation3, Unit, Vector3};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// Central-difference step on strain components.
const H: f64 = 1e-5;
/// Tolerance on `S` vs `∂W/∂E`.
pub const TOL_STRESS: f64 = 1e-6;
/// Tolerance on `𝔻` vs `∂S/∂E`.
pub const TOL_TANGENT: f64 = 1e-5;

/// Rotation by `angle` about `axis`.
pub fn rotation(axis: [f64; 3], angle: f64) -> Mat3 {
    let axis = Unit::new_normalize(Vector3::from(axis));
    Rotation3::from_axis_angle(&axis, angle).into_inner()
}

/// Diagonal tensor.
pub fn diag(a: f64, b: f64, c: f64) -> Mat3 {
    Mat3::from_diagonal(&Vector3::new(a, b, c))
}

/// `n` random deformation gradients `F = I + amplitude·R` with entries of `R`
/// uniform in [−1, 1] and `det F > 0.3`, from a fixed seed.
pub fn random_deformations(seed: u64, n: usize, amplitude: f64) -> Vec<Mat3> {
    let mut rng = StdRng::seed_from_u64(seed);
    let mut out = Vec::with_capacity(n);
    while out.len() < n {
        let f = Mat3::identity() + Mat3::from_fn(|_, _| amplitude * rng.gen_range(-1.0..1.0));
        if f.determinant() > 0.3 {
            out.push(f);
        }
    }
    out
}

/// A random proper rotation from a fixed seed.
pub fn random_rotation(seed: u64) -> Mat3 {
    let mut rng = StdRng::seed_from_u64(seed);
    let axis = [
        rng.gen_range(-1.0..1.0),
        rng.gen_range(-1.0..1.0),
        rng.gen_range(-1.0..1.0),
    ];
    rotation(axis, rng.gen_range(0.1..3.0))
}

/// The deformation gradients every material is checked at, with labels.
pub fn deformations() -> Vec<(String, Mat3)> {
    let q = rotation([1.0, 2.0, -0.5], 0.8);
    let mut out = vec![
        ("identity".to_string(), Mat3::identity()),
        ("diag(1.2, 1.2, 0.9)".to_string(), diag(1.2, 1.2, 0.9)),
        ("1.1 I".to_string(), Mat3::identity() * 1.1),
        ("0.9 I".to_string(), Mat3::identity() * 0.9),
        ("Q diag(1.2, 1.2, 0.9)".to_string(), q * diag(1.2, 1.2, 0.9)),
        (
            "Q diag(0.9, 1.2, 1.2) Qᵀ".to_string(),
            q * diag(0.9, 1.2, 1.2) * q.transpose(),
        ),
        ("Q 1.1 I".to_string(), q * 1.1),
        (
            "diag(1.2, 1.2 + 1e-9, 0.8)".to_string(),
            diag(1.2, 1.2 + 1e-9, 0.8),
        ),
        (
            "Q diag(1.2, 1.2 + 1e-9, 0.8)".to_string(),
            q * diag(1.2, 1.2 + 1e-9, 0.8),
        ),
        (
            "diag(1.1, 1.1 + 1e-7, 1.1 - 1e-7)".to_string(),
            diag(1.1, 1.1 + 1e-7, 1.1 - 1e-7),
        ),
        (
            "simple shear 0.5".to_string(),
            Mat3::new(1.0, 0.5, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0),
        ),
    ];
    for (k, f) in random_deformations(42, 8, 0.3).into_iter().enumerate() {
        out.push((format!("random #{k}"), f));
    }
    out
}

/// Symmetric tensor from a strain Voigt vector with engineering shear.
pub fn sym_from_strain_voigt(d: &Vec6) -> Mat3 {
    let mut v = *d;
    for k in 3..6 {
        v[k] *= 0.5;
    }
    sym_from_voigt(&v)
}

/// A deformation gradient whose strain (E, or ε for small strain) is that of
/// `f` plus `d` (Voigt, engineering shear).
pub fn perturbed(kinematics: Kinematics, f: &Mat3, d: &Vec6) -> Mat3 {
    let de = sym_from_strain_voigt(d);
    match kinematics {
        Kinematics::SmallStrain => f + de,
        Kinematics::FiniteStrain => {
            // C = L Lᵀ, C' = C + 2δE = L' L'ᵀ (Cholesky, smooth in C and
            // accurate even for repeated eigenvalues); F' = F L⁻ᵀ L'ᵀ has
            // F'ᵀF' = C' and F' = F at δE = 0.
            let c = f.transpose() * f;
            let l = c.cholesky().expect("C must be positive definite").l();
            let lp = (c + de * 2.0)
                .cholesky()
                .expect("C' must be positive definite")
                .l();
            let lt_inv = l.transpose().try_inverse().expect("F must be invertible");
            f * lt_inv * lp.transpose()
        }
    }
}

fn unit(k: usize, h: f64) -> Vec6 {
    let mut d = Vec6::zeros();
    d[k] = h;
    d
}

/// `∂W/∂E` (Voigt, stress-like) by central differences.
pub fn fd_stress(m: &dyn Material, f: &Mat3) -> Vec6 {
    let kin = m.kinematics();
    Vec6::from_fn(|k, _| {
        let wp = m.strain_energy(&perturbed(kin, f, &unit(k, H)));
        let wm = m.strain_energy(&perturbed(kin, f, &unit(k, -H)));
        (wp - wm) / (2.0 * H)
    })
}

/// `∂S/∂E` (Voigt, columns per engineering strain component) by central
/// differences of the analytic stress.
pub fn fd_tangent(m: &dyn Material, f: &Mat3) -> Mat6 {
    let kin = m.kinematics();
    let mut d = Mat6::zeros();
    for k in 0..6 {
        let sp = m.stress_and_tangent(&perturbed(kin, f, &unit(k, H))).0;
        let sm = m.stress_and_tangent(&perturbed(kin, f, &unit(k, -H))).0;
        d.set_column(
            k,
            &((voigt_from_sym(&sp) - voigt_from_sym(&sm)) / (2.0 * H)),
        );
    }
    d
}

/// `max |a − b| / max(max |b|, floor)`.
pub fn rel_err<const R: usize, const C: usize>(
    a: &nalgebra::SMatrix<f64, R, C>,
    b: &nalgebra::SMatrix<f64, R, C>,
    floor: f64,
) -> f64 {
    (a - b).amax() / b.amax().max(floor)
}

/// Checks, at every deformation of [`deformations`], that the analytic
/// stress is the derivative of the energy, the analytic tangent the
/// derivative of the stress, that the tangent is symmetric and that the
/// stress is symmetric. Panics with the label and the error otherwise.
pub fn check_derivatives(m: &dyn Material) {
    check_derivatives_at(m, &deformations());
}

/// [`check_derivatives`] at the given labelled deformations.
pub fn check_derivatives_at(m: &dyn Material, cases: &[(String, Mat3)]) {
    let e_ref = m.reference_youngs_modulus();
    for (label, f) in cases {
        let (s, d) = m.stress_and_tangent(f);
        assert!(
            s.iter().chain(d.iter()).all(|x| x.is_finite()),
            "{}: non-finite response at {label}",
            m.name()
        );
        assert!(
            (s - s.transpose()).amax() <= 1e-12 * s.amax().max(e_ref * 1e-3),
            "{}: S not symmetric at {label}",
            m.name()
        );
        assert!(
            (d - d.transpose()).amax() <= 1e-12 * d.amax(),
            "{}: 𝔻 not symmetric at {label}: {d}",
            m.name()
        );
        // Where S ≈ 0 (identity) compare against the stress of a 1e-3 strain.
        let floor = 1e-3 * d.amax().max(e_ref);
        let s_fd = fd_stress(m, f);
        let es = rel_err(&s_fd, &voigt_from_sym(&s), floor);
        assert!(
            es < TOL_STRESS,
            "{}: S ≠ ∂W/∂E at {label}: rel. error {es:.2e}\nanalytic {}\nfinite differences {}",
            m.name(),
            voigt_from_sym(&s).transpose(),
            s_fd.transpose()
        );
        let d_fd = fd_tangent(m, f);
        let ed = rel_err(&d_fd, &d, floor);
        assert!(
            ed < TOL_TANGENT,
            "{}: 𝔻 ≠ ∂S/∂E at {label}: rel. error {ed:.2e}\nanalytic {d}\nfinite differences {d_fd}",
            m.name()
        );
    }
}

/// `W(QF) = W(F)`, `S(QF) = S(F)` and `𝔻(QF) = 𝔻(F)` for rotations `Q`, at
/// every deformation of [`deformations`].
pub fn check_objectivity(m: &dyn Material) {
    let e_ref = m.reference_youngs_modulus();
    for (label, f) in deformations() {
        for seed in 0..3 {
            let q = random_rotation(seed);
            let qf = q * f;
            let (w0, w1) = (m.strain_energy(&f), m.strain_energy(&qf));
            assert!(
                (w0 - w1).abs() <= 1e-12 * e_ref.max(w0.abs()),
                "{}: W not objective at {label}: {w0} vs {w1}",
                m.name()
            );
            let (s0, d0) = m.stress_and_tangent(&f);
            let (s1, d1) = m.stress_and_tangent(&qf);
            assert!(
                rel_err(&s1, &s0, 1e-3 * e_ref) < 1e-10,
                "{}: S not objective at {label}",
                m.name()
            );
            assert!(
                rel_err(&d1, &d0, 1e-3 * e_ref) < 1e-10,
                "{}: 𝔻 not objective at {label}",
                m.name()
            );
        }
    }
}

/// Isotropy: `S(FQ) = Qᵀ S(F) Q` for rotations `Q`.
pub fn check_isotropy(m: &dyn Material) {
    let e_ref = m.reference_youngs_modulus();
    for (label, f) in deformations() {
        let q = random_rotation(7);
        let s0 = m.second_piola_kirchhoff(&f);
        let s1 = m.second_piola_kirchhoff(&(f * q));
        let expect = q.transpose() * s0 * q;
        assert!(
            rel_err(&s1, &expect, 1e-3 * e_ref) < 1e-10,
            "{}: not isotropic at {label}",
            m.name()
        );
    }
}

/// Where the energy is undefined: NaN stress and tangent and `+∞` energy,
/// no panic, for an inverted `F`, the zero `F`, the singular `degenerate`
/// and an all-NaN `F`.
pub fn check_nan_where_undefined(m: &dyn Material, degenerate: Mat3) {
    for f in [
        diag(1.0, 1.0, -1.0),
        Mat3::zeros(),
        degenerate,
        Mat3::from_element(f64::NAN),
    ] {
        let (s, d) = m.stress_and_tangent(&f);
        assert!(s.iter().all(|x| x.is_nan()) && d.iter().all(|x| x.is_nan()));
        assert!(m.strain_energy(&f) == f64::INFINITY);
    }
}
