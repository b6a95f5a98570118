//! Verification of the normal-contact laws ([`signorini::contact::laws`])
//! through their public functions, on a tilted plane and a sphere
//! (`GapGeometry::plane`, `GapGeometry::sphere`): every law's residual
//! against the central-difference gradient of its potential and its tangent
//! against the central-difference Jacobian of its residual
//! ([`fd::check_state`]); the sign of the curvature term; Rockafellar's
//! potential C¹ across its switch; the slack law's local system against
//! its Lagrangian, and its condensation against Rockafellar's law and
//! against the full local Newton step. The laws' own files keep their small
//! checks (style rule 10).

/// Finite-difference twins for the contact laws, written once and used by
/// every law's checks.
///
/// A law is seen as a function of the node's spatial position `x_s` and its
/// multiplier `λ` through an analytic obstacle; the residual is compared with
/// the central-difference gradient of the potential, the tangent with the
/// central-difference Jacobian of the residual.
mod fd {
    use nalgebra::{DMatrix, DVector, Vector3};
    use signorini::contact::laws::{GapGeometry, NodeContribution};

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
}

mod penalty {
    use crate::fd::{self, check_state, Dofs, Obstacle};
    use nalgebra::{DMatrix, Matrix3, Vector3};
    use signorini::contact::laws::penalty::{contribution, potential};
    use signorini::contact::laws::{GapGeometry, NodeContribution};

    const AREA: f64 = 0.37;
    const EPS: f64 = 1.0e3;

    fn law(g: &GapGeometry, _l: f64) -> NodeContribution {
        contribution(AREA, g, EPS)
    }
    fn pot(g: &GapGeometry, _l: f64) -> f64 {
        potential(AREA, g, EPS)
    }

    #[test]
    fn residual_and_tangent_match_finite_differences() {
        let dir = Vector3::new(0.2, 0.3, 1.0);
        for obstacle in [Obstacle::tilted_plane(), Obstacle::unit_sphere()] {
            for (g, active) in [(-0.05, true), (-1e-3, true), (0.02, false)] {
                let x = obstacle.point_at_gap(g, &dir);
                let c = check_state(&obstacle, &x, 0.0, &law, Some(&pot), Dofs::Position, 1e-6);
                assert_eq!(c.active, active);
                if active {
                    assert!((c.pressure - EPS * (-g)).abs() < 1e-9 * EPS);
                } else {
                    assert_eq!(c, NodeContribution::zero());
                }
            }
        }
    }

    /// Evidence for the sign of the curvature term: with `+A_s t_N H` the
    /// tangent misses the FD Jacobian by about `2 A_s t_N |H| / |K|`.
    #[test]
    fn curvature_term_enters_with_a_minus_sign() {
        let obstacle = Obstacle::unit_sphere();
        let x = obstacle.point_at_gap(-0.05, &Vector3::new(0.2, 0.3, 1.0));
        let g = obstacle.geometry(&x);
        let right = contribution(AREA, &g, EPS);
        let mut wrong = right;
        wrong.k_uu += 2.0 * AREA * right.pressure * g.hessian;
        let f = |z: &nalgebra::DVector<f64>| {
            let c = contribution(
                AREA,
                &obstacle.geometry(&Vector3::new(z[0], z[1], z[2])),
                EPS,
            );
            fd::residual_vector(&c).rows(0, 3).into_owned()
        };
        let z = nalgebra::DVector::from_column_slice(x.as_slice());
        let jac = fd::jacobian(&f, &z, &[1e-6; 3]);
        let err = |k: &Matrix3<f64>| {
            fd::relative_error(&DMatrix::from_column_slice(3, 3, k.as_slice()), &jac)
        };
        assert!(err(&right.k_uu) < 1e-7, "{}", err(&right.k_uu));
        assert!(err(&wrong.k_uu) > 1e-2, "{}", err(&wrong.k_uu));
    }
}

mod uzawa {
    use crate::fd::{check_state, Dofs, Obstacle};
    use nalgebra::Vector3;
    use signorini::contact::laws::uzawa::{contribution, potential};
    use signorini::contact::laws::GapGeometry;

    const AREA: f64 = 0.37;
    const EPS: f64 = 1.0e3;

    #[test]
    fn residual_and_tangent_match_finite_differences() {
        let dir = Vector3::new(0.2, 0.3, 1.0);
        // (g, λ, active): penetrating, open but pre-loaded by λ, open and unloaded.
        let states = [
            (-0.05, 3.0, true),
            (0.002, 3.0, true),
            (0.02, 3.0, false),
            (-0.01, 0.0, true),
        ];
        for obstacle in [Obstacle::tilted_plane(), Obstacle::unit_sphere()] {
            for (g, lambda, active) in states {
                let x = obstacle.point_at_gap(g, &dir);
                let law = |geo: &GapGeometry, l: f64| contribution(AREA, geo, l, EPS);
                let pot = |geo: &GapGeometry, l: f64| potential(AREA, geo, l, EPS);
                let c = check_state(
                    &obstacle,
                    &x,
                    lambda,
                    &law,
                    Some(&pot),
                    Dofs::Position,
                    1e-6,
                );
                assert_eq!(c.active, active);
                assert!((c.pressure - (lambda - EPS * g).max(0.0)).abs() < 1e-9 * EPS);
                assert_eq!(c.r_lambda, 0.0);
                assert_eq!(c.k_ulambda, Vector3::zeros());
            }
        }
    }
}

mod rockafellar {
    use crate::fd::{self, check_state, Dofs, Obstacle};
    use nalgebra::Vector3;
    use signorini::contact::laws::rockafellar::*;
    use signorini::contact::laws::{GapGeometry, NodeContribution};

    const AREA: f64 = 0.37;
    const P: f64 = 2.0e3;
    const K: f64 = 7.0e2;

    fn law(g: &GapGeometry, l: f64) -> NodeContribution {
        contribution(AREA, g, l, P, K)
    }
    fn pot(g: &GapGeometry, l: f64) -> f64 {
        potential(AREA, g, l, P, K)
    }

    #[test]
    fn residual_and_tangent_match_finite_differences() {
        let dir = Vector3::new(0.2, 0.3, 1.0);
        // (g, λ, active); t̂ = 700 λ − 2000 g.
        let states = [
            (-0.01, 0.5, true),   // penetrating, pressed: t̂ = 370
            (0.005, 0.5, true),   // open but still pressed by λ: t̂ = 340
            (-0.05, -0.1, true),  // negative λ, penetration wins: t̂ = −70 + 100 = 30
            (0.02, 0.01, false),  // open, t̂ = −33
            (-0.01, -1.0, false), // penetrating but tensile λ: t̂ = −680
        ];
        for obstacle in [Obstacle::tilted_plane(), Obstacle::unit_sphere()] {
            for (g, lambda, active) in states {
                let x = obstacle.point_at_gap(g, &dir);
                let c = check_state(
                    &obstacle,
                    &x,
                    lambda,
                    &law,
                    Some(&pot),
                    Dofs::PositionAndMultiplier,
                    1e-6,
                );
                assert_eq!(c.active, active, "g = {g}, λ = {lambda}");
                let t_hat = K * lambda - P * g;
                assert!((c.pressure - t_hat.max(0.0)).abs() < 1e-9 * P);
            }
        }
    }

    /// At a KKT point of an active node (`g = 0`, `λ = t/k > 0`) the
    /// constraint residual vanishes and the node carries `t_N = kλ`.
    #[test]
    fn kkt_point_of_an_active_node() {
        let t = 12.0;
        let lambda = t / K;
        for obstacle in [Obstacle::tilted_plane(), Obstacle::unit_sphere()] {
            let x = obstacle.point_at_gap(0.0, &Vector3::new(-0.3, 0.1, 1.0));
            let geo = GapGeometry {
                signed_gap: 0.0,
                ..obstacle.geometry(&x)
            };
            let c = law(&geo, lambda);
            assert!(c.active);
            assert_eq!(c.r_lambda, 0.0);
            assert!((c.pressure - t).abs() < 1e-12 * t);
            assert!((c.r_u + AREA * t * geo.normal).norm() < 1e-12 * AREA * t);
        }
    }

    /// Inactive and open: `r_λ = −A_s k² λ/p`, zero only at `λ = 0`.
    #[test]
    fn inactive_constraint_residual_drives_lambda_to_zero() {
        let geo = Obstacle::tilted_plane().geometry(&Vector3::new(0.3, 0.2, 0.5));
        assert!(geo.signed_gap > 0.0);
        for lambda in [0.1, 1e-3, -0.2] {
            let c = law(&geo, lambda);
            assert!(!c.active);
            let expected = -AREA * K * K * lambda / P;
            assert!((c.r_lambda - expected).abs() < 1e-12 * expected.abs());
            assert!(c.r_lambda != 0.0);
            assert_eq!(c.r_u, Vector3::zeros());
            assert_eq!(c.pressure, 0.0);
        }
        let c = law(&geo, 0.0);
        assert!(!c.active);
        assert_eq!(c.r_lambda, 0.0);
    }

    /// On the switch line `kλ = p g` both branches give the same potential
    /// (`−p g²/2`) and the same gradient (`∂Φ/∂g = 0`, `∂Φ/∂λ = −k g`):
    /// `Φ` is C¹. Its second derivatives jump (not C²).
    fn fd_residual_gap(a: &NodeContribution, b: &NodeContribution) -> f64 {
        (fd::residual_vector(a) - fd::residual_vector(b)).norm()
    }

    #[test]
    fn potential_is_c1_across_the_switch() {
        let geo0 = Obstacle::unit_sphere().geometry(&Vector3::new(0.4, -0.2, 0.3));
        for g in [0.013, -0.007, 0.0] {
            let lambda = P * g / K;
            let geo = GapGeometry {
                signed_gap: g,
                ..geo0
            };
            let act = branch_contribution(AREA, &geo, lambda, P, K, true);
            let ina = branch_contribution(AREA, &geo, lambda, P, K, false);
            let phi_act = -K * lambda * g + 0.5 * P * g * g;
            let phi_ina = -K * K * lambda * lambda / (2.0 * P);
            assert!(
                (phi_act - phi_ina).abs() < 1e-10,
                "Φ: {phi_act} vs {phi_ina}"
            );
            assert!(
                (act.r_u - ina.r_u).norm() < 1e-10,
                "r_u: {} vs {}",
                act.r_u,
                ina.r_u
            );
            assert!(
                (act.r_lambda - ina.r_lambda).abs() < 1e-10,
                "r_λ: {} vs {}",
                act.r_lambda,
                ina.r_lambda
            );
            // The public functions a distance d on either side of the switch:
            // the potential changes by its common gradient, the residual by O(d).
            let d = 1e-7;
            assert!(is_active(g, lambda + d, P, K) && !is_active(g, lambda - d, P, K));
            let jump =
                potential(AREA, &geo, lambda + d, P, K) - potential(AREA, &geo, lambda - d, P, K);
            assert!((jump - 2.0 * d * act.r_lambda).abs() < 1e-12, "{jump}");
            let (a, b) = (law(&geo, lambda + d), law(&geo, lambda - d));
            assert!(fd_residual_gap(&a, &b) <= 1.01 * AREA * K * d * 2.0);
            // Not C²: K_λλ jumps from 0 to −A_s k²/p.
            assert!((act.k_lambdalambda - ina.k_lambdalambda).abs() > 1.0);
        }
    }
}

mod slack {
    use crate::fd::{self, check_state, Dofs, Obstacle};
    use nalgebra::{DMatrix, DVector, Matrix4, SMatrix, Vector3, Vector4};
    use signorini::contact::laws::slack::*;
    use signorini::contact::laws::{rockafellar, GapGeometry, NodeContribution};

    const AREA: f64 = 0.37;
    const P: f64 = 2.0e3;
    const K: f64 = 7.0e2;

    fn obstacles() -> [Obstacle; 2] {
        [Obstacle::tilted_plane(), Obstacle::unit_sphere()]
    }

    /// Gradient and Hessian of both branches against finite differences of
    /// the branch Lagrangian in all six local unknowns.
    #[test]
    fn local_system_is_the_gradient_and_hessian_of_the_lagrangian() {
        let dir = Vector3::new(0.2, 0.3, 1.0);
        for obstacle in obstacles() {
            for clamped in [true, false] {
                for (g, s, lp, l1) in [(-0.01, -0.003, -0.4, 0.2), (0.02, 0.004, 0.3, -0.1)] {
                    let x = obstacle.point_at_gap(g, &dir);
                    let split = |z: &DVector<f64>| {
                        let geo = obstacle.geometry(&Vector3::new(z[0], z[1], z[2]));
                        (
                            geo,
                            SlackState {
                                s: z[3],
                                lambda1: z[5],
                            },
                            z[4],
                        )
                    };
                    let z = DVector::from_column_slice(&[x.x, x.y, x.z, s, lp, l1]);
                    let h = [1e-6; 6];
                    let lag = |z: &DVector<f64>| {
                        let (geo, st, lp) = split(z);
                        lagrangian(AREA, &geo, &st, lp, P, K, clamped)
                    };
                    let grad = |z: &DVector<f64>| {
                        let (geo, st, lp) = split(z);
                        let g = local_system(AREA, &geo, &st, lp, P, K, clamped).gradient;
                        DVector::from_column_slice(g.as_slice())
                    };
                    let (geo, st, lp) = split(&z);
                    let sys = local_system(AREA, &geo, &st, lp, P, K, clamped);
                    let what = format!("{obstacle:?} clamped={clamped} g={g}");
                    fd::assert_relative(
                        &DMatrix::from_column_slice(6, 1, sys.gradient.as_slice()),
                        &DMatrix::from_column_slice(6, 1, fd::gradient(&lag, &z, &h).as_slice()),
                        1e-6,
                        &format!("gradient, {what}"),
                    );
                    fd::assert_relative(
                        &DMatrix::from_column_slice(6, 6, sys.hessian.as_slice()),
                        &fd::jacobian(&grad, &z, &h),
                        1e-6,
                        &format!("Hessian, {what}"),
                    );
                }
            }
        }
    }

    /// The paper's flat-facet matrices (24)/(25) with `B = n`: the
    /// Hessian reproduces them entry by entry when `H = 0`.
    #[test]
    fn hessians_are_the_papers_eqs_24_and_25_on_a_flat_facet() {
        let geo = Obstacle::tilted_plane().geometry(&Vector3::new(0.1, 0.2, 0.3));
        let n = geo.normal;
        let st = SlackState {
            s: -0.01,
            lambda1: 0.3,
        };
        for clamped in [true, false] {
            let h = local_system(1.0, &geo, &st, 0.2, P, K, clamped).hessian;
            let mut paper = SMatrix::<f64, 6, 6>::zeros();
            paper
                .fixed_view_mut::<3, 3>(0, 0)
                .copy_from(&(P * n * n.transpose()));
            for i in 0..3 {
                paper[(i, 3)] = P * n[i];
                paper[(3, i)] = P * n[i];
                paper[(i, 4)] = K * n[i];
                paper[(4, i)] = K * n[i];
            }
            paper[(3, 3)] = P;
            paper[(3, 4)] = K;
            paper[(4, 3)] = K;
            if clamped {
                paper[(3, 5)] = K; // eq. 24: s–λ₁ = k, λ₁–λ₁ = 0
                paper[(5, 3)] = K;
            } else {
                paper[(5, 5)] = K; // eq. 25: s–λ₁ = 0, λ₁–λ₁ = k
            }
            assert_eq!(h, paper, "clamped = {clamped}");
        }
    }

    /// Condensed tangent against the FD Jacobian of the condensed residual
    /// with `(s, λ₁)` eliminated exactly, in each branch, flat and curved.
    /// The residual is also the gradient of the Rockafellar potential:
    /// eliminating `s`, `λ₁` from `L_s` gives `A_s Φ` back.
    #[test]
    fn condensed_contribution_matches_finite_differences() {
        let dir = Vector3::new(0.2, 0.3, 1.0);
        let law = |geo: &GapGeometry, l: f64| {
            let st = SlackState::consistent(geo.signed_gap, l, P, K);
            st.condense(AREA, geo, l, P, K).0
        };
        let pot = |geo: &GapGeometry, l: f64| rockafellar::potential(AREA, geo, l, P, K);
        // (g, λ, clamped); t̂ = 700 λ − 2000 g.
        for (g, lambda, clamped) in [
            (-0.01, 0.5, true),
            (0.005, 0.5, true),
            (0.02, 0.01, false),
            (-0.01, -1.0, false),
        ] {
            for obstacle in obstacles() {
                let x = obstacle.point_at_gap(g, &dir);
                let c = check_state(
                    &obstacle,
                    &x,
                    lambda,
                    &law,
                    Some(&pot),
                    Dofs::PositionAndMultiplier,
                    1e-6,
                );
                assert_eq!(c.active, clamped);
            }
        }
    }

    fn assert_same(a: &NodeContribution, b: &NodeContribution, rel: f64) {
        fd::assert_relative(
            &DMatrix::from_column_slice(4, 1, fd::residual_vector(a).as_slice()),
            &DMatrix::from_column_slice(4, 1, fd::residual_vector(b).as_slice()),
            rel,
            "residual",
        );
        fd::assert_relative(
            &fd::tangent_matrix(a),
            &fd::tangent_matrix(b),
            rel,
            "tangent",
        );
        assert!((a.pressure - b.pressure).abs() <= rel * a.pressure.abs().max(1.0));
        assert_eq!(a.active, b.active);
    }

    /// Clamped states give Rockafellar's contribution: for any consistent
    /// state (`s = 0`, `λ₁ = t̂/k ≥ 0`), flat or curved; on a flat obstacle
    /// for any clamped `(s, λ₁)`, consistent or not.
    #[test]
    fn clamped_condensation_equals_rockafellar() {
        let dir = Vector3::new(-0.4, 0.3, 1.0);
        for obstacle in obstacles() {
            for (g, lambda) in [(-0.01, 0.5), (0.005, 0.5), (0.0, 0.02), (-0.05, -0.1)] {
                let geo = obstacle.geometry(&obstacle.point_at_gap(g, &dir));
                let st = SlackState::consistent(geo.signed_gap, lambda, P, K);
                assert_eq!(st.s, 0.0);
                let (slack, _) = st.condense(AREA, &geo, lambda, P, K);
                let rock = rockafellar::contribution(AREA, &geo, lambda, P, K);
                assert!(slack.active && rock.active);
                assert_same(&slack, &rock, 1e-12);
            }
        }
        let geo = Obstacle::tilted_plane().geometry(&Vector3::new(0.3, -0.1, 0.02));
        for (s, lambda1, lambda) in [(0.01, 0.2, 0.4), (0.0, 0.0, -0.3), (-0.002, 0.5, 0.1)] {
            let st = SlackState { s, lambda1 };
            assert!(SlackSwitch::Consistent.is_clamped(&st, P, K));
            let (slack, _) = st.condense(AREA, &geo, lambda, P, K);
            let rock = rockafellar::branch_contribution(AREA, &geo, lambda, P, K, true);
            assert_same(&slack, &rock, 1e-12);
        }
    }

    /// Free states consistent with `(g, λ)` give Rockafellar's inactive rows.
    #[test]
    fn free_condensation_equals_rockafellar_inactive() {
        for obstacle in obstacles() {
            let geo = obstacle.geometry(&obstacle.point_at_gap(0.02, &Vector3::new(0.1, 0.1, 1.0)));
            let lambda = 0.01;
            let st = SlackState::consistent(geo.signed_gap, lambda, P, K);
            assert!(st.s < 0.0 && st.lambda1 == 0.0);
            let (slack, _) = st.condense(AREA, &geo, lambda, P, K);
            let rock = rockafellar::contribution(AREA, &geo, lambda, P, K);
            assert!(!rock.active);
            assert_same(&slack, &rock, 1e-12);
        }
    }

    /// Solving the node's full 6-unknown Newton system (plus a spring on
    /// `x_s`) and solving the condensed 4-unknown one followed by
    /// back-substitution give the same increments, in both branches, for an
    /// inconsistent state on a curved obstacle.
    #[test]
    fn condensation_and_recovery_reproduce_the_full_newton_step() {
        let obstacle = Obstacle::unit_sphere();
        let geo = obstacle.geometry(&obstacle.point_at_gap(-0.004, &Vector3::new(0.3, -0.2, 1.0)));
        let k_s = 150.0;
        let f_spring = Vector3::new(1.0, -2.0, 3.0);
        let lambda = 0.2;
        for st in [
            SlackState {
                s: 0.003,
                lambda1: 0.4,
            },
            SlackState {
                s: -0.01,
                lambda1: -0.2,
            },
        ] {
            let clamped = SlackSwitch::Consistent.is_clamped(&st, P, K);
            // Full system in (x, s, λ_p, λ₁).
            let sys = local_system(AREA, &geo, &st, -lambda, P, K, clamped);
            let mut kf = sys.hessian;
            let mut rf = sys.gradient;
            for i in 0..3 {
                kf[(i, i)] += k_s;
                rf[i] += f_spring[i];
            }
            let full = -kf.lu().solve(&rf).unwrap();
            // Condensed in (x, λ).
            let (c, rec) = st.condense(AREA, &geo, lambda, P, K);
            let mut kc = fd::tangent_matrix(&c);
            let mut rc = fd::residual_vector(&c);
            for i in 0..3 {
                kc[(i, i)] += k_s;
                rc[i] += f_spring[i];
            }
            let kc = Matrix4::from_iterator(kc.iter().copied());
            let rc = Vector4::from_iterator(rc.iter().copied());
            let da = -kc.lu().solve(&rc).unwrap();
            let du = Vector3::new(da[0], da[1], da[2]);
            let next = rec.apply(&st, &du, da[3]);
            let scale = full.norm();
            assert!((du - full.fixed_rows::<3>(0)).norm() < 1e-12 * scale);
            assert!((-da[3] - full[4]).abs() < 1e-12 * scale, "λ_p = −λ");
            assert!((next.s - st.s - full[3]).abs() < 1e-12 * scale);
            assert!((next.lambda1 - st.lambda1 - full[5]).abs() < 1e-12 * scale);
        }
    }

    #[test]
    fn switch_releases_a_node_whose_clamp_reaction_turns_tensile() {
        let tensile = SlackState {
            s: 0.0,
            lambda1: -0.01,
        };
        assert!(!SlackSwitch::Consistent.is_clamped(&tensile, P, K));
        assert!(SlackSwitch::PaperSignOfSlack.is_clamped(&tensile, P, K));
        // With λ₁ = 0 the two tests agree.
        for s in [-0.1, 0.0, 0.1] {
            let st = SlackState { s, lambda1: 0.0 };
            assert_eq!(
                SlackSwitch::Consistent.is_clamped(&st, P, K),
                SlackSwitch::PaperSignOfSlack.is_clamped(&st, P, K)
            );
        }
        let geo = Obstacle::tilted_plane().geometry(&Vector3::new(0.0, 0.0, 0.0));
        let (c, _) = tensile.condense(AREA, &geo, 0.3, P, K);
        assert!(!c.active);
        assert!(
            c.r_u.norm() < 1e-12 * AREA * P,
            "free: no force on u, {}",
            c.r_u
        );
        assert_eq!(c.pressure, 0.0);
    }
}
