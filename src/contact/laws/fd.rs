//! Finite-difference twins for the contact laws (tests only), written once
//! and used by every law's tests.
//!
//! A law is seen as a function of the node's spatial position `x_s` and its
//! multiplier `λ` through an analytic obstacle; the residual is compared with
//! the central-difference gradient of the potential, the tangent with the
//! central-difference Jacobian of the residual.

use super::{GapGeometry, NodeContribution};
use nalgebra::{DMatrix, DVector, Vector3};

/// Analytic obstacles with exact gap, normal and gap Hessian.
#[derive(Clone, Copy, Debug)]
pub enum Obstacle {
    /// `g = (x − x₀)·n`.
    Plane {
        point: Vector3<f64>,
        normal: Vector3<f64>,
    },
    /// `g = |x − c| − R`.
    Sphere { centre: Vector3<f64>, radius: f64 },
}

impl Obstacle {
    /// A tilted plane through the origin.
    pub fn tilted_plane() -> Self {
        Self::Plane {
            point: Vector3::new(0.1, -0.2, 0.05),
            normal: Vector3::new(0.3, -0.4, 1.0).normalize(),
        }
    }

    /// A unit sphere away from the origin.
    pub fn unit_sphere() -> Self {
        Self::Sphere {
            centre: Vector3::new(0.2, 0.1, -1.0),
            radius: 1.0,
        }
    }

    pub fn geometry(&self, x: &Vector3<f64>) -> GapGeometry {
        match *self {
            Self::Plane { point, normal } => GapGeometry::plane(x, &point, &normal),
            Self::Sphere { centre, radius } => GapGeometry::sphere(x, &centre, radius),
        }
    }

    /// The spatial point at signed gap `g` along the direction `dir` (roughly
    /// normal) from the obstacle: a convenient way to pick states.
    pub fn point_at_gap(&self, g: f64, dir: &Vector3<f64>) -> Vector3<f64> {
        match *self {
            Self::Plane { point, normal } => {
                // Some tangential offset, then move to the requested gap.
                let x = point + dir;
                x + (g - (x - point).dot(&normal)) * normal
            }
            Self::Sphere { centre, radius } => centre + dir.normalize() * (radius + g),
        }
    }
}

/// Central-difference gradient of `f` at `z` with steps `h[i]`.
pub fn gradient(f: &dyn Fn(&DVector<f64>) -> f64, z: &DVector<f64>, h: &[f64]) -> DVector<f64> {
    DVector::from_fn(z.len(), |i, _| {
        let mut zp = z.clone();
        let mut zm = z.clone();
        zp[i] += h[i];
        zm[i] -= h[i];
        (f(&zp) - f(&zm)) / (2.0 * h[i])
    })
}

/// Central-difference Jacobian of `f` at `z` with steps `h[j]`.
pub fn jacobian(
    f: &dyn Fn(&DVector<f64>) -> DVector<f64>,
    z: &DVector<f64>,
    h: &[f64],
) -> DMatrix<f64> {
    let m = f(z).len();
    let mut jac = DMatrix::zeros(m, z.len());
    for j in 0..z.len() {
        let mut zp = z.clone();
        let mut zm = z.clone();
        zp[j] += h[j];
        zm[j] -= h[j];
        let col = (f(&zp) - f(&zm)) / (2.0 * h[j]);
        jac.set_column(j, &col);
    }
    jac
}

/// Relative error `‖a − b‖ / ‖b‖` (Frobenius); 0 when both vanish.
pub fn relative_error(a: &DMatrix<f64>, b: &DMatrix<f64>) -> f64 {
    let d = (a - b).norm();
    let s = a.norm().max(b.norm());
    if s == 0.0 {
        0.0
    } else {
        d / s
    }
}

/// Assert `‖a − b‖ ≤ rel · max(‖a‖, ‖b‖)`.
#[track_caller]
pub fn assert_relative(a: &DMatrix<f64>, b: &DMatrix<f64>, rel: f64, what: &str) {
    let e = relative_error(a, b);
    assert!(
        e <= rel,
        "{what}: relative error {e:.3e} > {rel:.1e}\n analytic {a}\n reference {b}"
    );
}

/// Residual `[r_u; r_λ]` as a 4-vector.
pub fn residual_vector(c: &NodeContribution) -> DVector<f64> {
    DVector::from_column_slice(&[c.r_u.x, c.r_u.y, c.r_u.z, c.r_lambda])
}

/// Tangent `[[K_uu, K_uλ], [K_uλᵀ, K_λλ]]` as a 4×4 matrix.
pub fn tangent_matrix(c: &NodeContribution) -> DMatrix<f64> {
    let mut k = DMatrix::zeros(4, 4);
    k.view_mut((0, 0), (3, 3)).copy_from(&c.k_uu);
    k.view_mut((0, 3), (3, 1)).copy_from(&c.k_ulambda);
    k.view_mut((3, 0), (1, 3))
        .copy_from(&c.k_ulambda.transpose());
    k[(3, 3)] = c.k_lambdalambda;
    k
}

/// A law evaluated at `(gap geometry, λ)`.
pub type Law<'a> = &'a dyn Fn(&GapGeometry, f64) -> NodeContribution;
/// Its potential `A_s Φ(g, λ)`.
pub type Potential<'a> = &'a dyn Fn(&GapGeometry, f64) -> f64;

/// Which `(x, λ)` dofs the law differentiates with respect to.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Dofs {
    /// `x_s` only (penalty, Uzawa with λ fixed).
    Position,
    /// `x_s` and `λ`.
    PositionAndMultiplier,
}

/// Check one state: the residual against the FD gradient of the potential
/// (when given) and the tangent against the FD Jacobian of the residual,
/// both to relative `rel`. Returns the contribution for further asserts.
#[track_caller]
pub fn check_state(
    obstacle: &Obstacle,
    x: &Vector3<f64>,
    lambda: f64,
    law: Law,
    potential: Option<Potential>,
    dofs: Dofs,
    rel: f64,
) -> NodeContribution {
    let n = match dofs {
        Dofs::Position => 3,
        Dofs::PositionAndMultiplier => 4,
    };
    let z = DVector::from_column_slice(&[x.x, x.y, x.z, lambda]);
    let h = [1e-6, 1e-6, 1e-6, 1e-6 * lambda.abs().max(1.0)];
    let split = |z: &DVector<f64>| (Vector3::new(z[0], z[1], z[2]), z[3]);
    let at = |z: &DVector<f64>| {
        let (x, l) = split(z);
        law(&obstacle.geometry(&x), l)
    };
    let c = at(&z);
    let r = residual_vector(&c).rows(0, n).into_owned();
    let k = tangent_matrix(&c).view((0, 0), (n, n)).into_owned();
    let state = format!("{obstacle:?} x={x:?} λ={lambda} active={}", c.active);

    if let Some(pot) = potential {
        let f = |z: &DVector<f64>| {
            let (x, l) = split(z);
            pot(&obstacle.geometry(&x), l)
        };
        let g = gradient(&f, &z, &h).rows(0, n).into_owned();
        assert_relative(
            &DMatrix::from_column_slice(n, 1, r.as_slice()),
            &DMatrix::from_column_slice(n, 1, g.as_slice()),
            rel,
            &format!("residual vs FD gradient of the potential, {state}"),
        );
    }

    let f = |z: &DVector<f64>| residual_vector(&at(z));
    let jac = jacobian(&f, &z, &h).view((0, 0), (n, n)).into_owned();
    assert_relative(&k, &jac, rel, &format!("tangent vs FD Jacobian, {state}"));

    // the pressure's derivatives (friction's coupling to the normal law)
    if c.pressure > 0.0 {
        let p = |z: &DVector<f64>| at(z).pressure;
        let fd = gradient(&p, &z, &h).rows(0, n).into_owned();
        let g = c.pressure_gradient;
        let exact = [g.x, g.y, g.z, c.pressure_multiplier_derivative];
        assert_relative(
            &DMatrix::from_column_slice(n, 1, &exact[..n]),
            &DMatrix::from_column_slice(n, 1, fd.as_slice()),
            rel,
            &format!("pressure derivatives vs FD, {state}"),
        );
    }
    c
}
