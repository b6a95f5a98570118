//! The paper's slack-variable Rockafellar Lagrangian (§4, eqs. 22–26), as
//! the formulation note §2.1 item 4 reads it, condensed node by node to the
//! `(u, λ)` shape of [`rockafellar`].
//!
//! ## The Lagrangian (paper's variables)
//! Per secondary node: slack `s`, multipliers `λ_p` (the paper's `λ`) and
//! `λ₁`, penalty `p`, scaling `k`, and `φ = g + s` (the paper's `u_N` is the
//! gap `g`; admissible slack `s ≤ 0`, note §2.1 item 4):
//! ```text
//! clamped:  L_s = A_s [ k λ_p φ + (p/2) φ² + k λ₁ s ]
//! free:     L_s = A_s [ k λ_p φ + (p/2) φ² + (k/2) λ₁² ]
//! ```
//! The free branch's `(k/2) λ₁²` is what the last row of the paper's eq. 25
//! (`k Δλ₁ = −k λ₁`) is the Hessian of: it sends `λ₁` to zero in one step.
//! With `c = k λ_p + p φ` and unknowns ordered `(x_s, s, λ_p, λ₁)` as in the
//! paper, the gradient and Hessian are ([`local_system`]):
//! ```text
//!            clamped (eq. 24)              free (eq. 25)
//! ∂L/∂x    = A c n                          A c n
//! ∂L/∂s    = A (c + k λ₁)                   A c
//! ∂L/∂λ_p  = A k φ                          A k φ
//! ∂L/∂λ₁   = A k s                          A k λ₁
//!
//!            x              s     λ_p   λ₁           x           s    λ_p   λ₁
//! x   [ A(p nnᵀ + cH)      A p n  A k n  0  ]     same, and
//! s   [ A p nᵀ             A p    A k    A k]     s–λ₁ = 0,
//! λ_p [ A k nᵀ             A k    0      0  ]     λ₁–λ₁ = A k
//! λ₁  [ 0                  A k    0      0  ]
//! ```
//! (the paper's `B` is `n`; its eq. 24/25 right-hand sides are these
//! gradients, to be taken with a minus sign for Newton; the curvature term
//! `c H` is absent in the paper's flat-facet setting).
//!
//! At a clamped solution `s = 0`, `g = 0`, `λ₁ = −λ_p` and `t_N = −k λ_p`;
//! at a free one `λ_p = 0`, `s = −g ≤ 0`, `λ₁ = 0`.
//!
//! ## The switch
//! The paper switches on the sign of `s` alone. A clamped Newton step gives
//! `Δs = −s` exactly (last row of eq. 24), so `s = 0` after it and a literal
//! implementation never releases a node. This module uses the consistent
//! switch for the complementarity pair `(s ≤ 0, λ₁ ≥ 0, s λ₁ = 0)`:
//! **clamped iff `k λ₁ + p s ≥ 0`** ([`SlackSwitch::Consistent`]). It reduces to
//! the paper's test when `λ₁ = 0`, and releases a node whose clamp reaction
//! turns tensile (`λ₁ < 0`). The paper's test is kept as
//! [`SlackSwitch::PaperSignOfSlack`] for comparisons.
//!
//! ## State kept per node
//! [`SlackState`] `{ s, λ₁ }`, updated after every global Newton solve by
//! back-substitution ([`SlackRecovery::apply`]); the branch is not stored,
//! it is the switch evaluated on `(s, λ₁)` at assembly. `λ` is a global dof.
//!
//! ## Condensation and the global multiplier
//! `s` and `λ₁` are eliminated from the node's Newton system by a Schur
//! complement. The global multiplier is `λ = −λ_p`, so that `t_N = kλ` as in
//! [`rockafellar`] and one assembly path serves both.
//! The condensed contribution is
//! ```text
//! clamped:  r_u = −A (kλ − p g) n,  r_λ = −A k g,
//!           K_uu = A p nnᵀ + A c H,  K_uλ = −A k n,  K_λλ = 0
//! free:     r_u = 0,  r_λ = −A k² λ / p,
//!           K_uu = A c H,  K_uλ = 0,  K_λλ = −A k² / p
//! ```
//! with `c = −kλ + p (g + s)`: exactly Rockafellar's active / inactive rows
//! when the local state is consistent (`s = 0` clamped, `c = 0` free), which
//! it is after one Newton step on a flat obstacle (and always for `H = 0`).
//! After a step, `λ₁ = (kλ − p g)/k` (clamped) or `s = (kλ − p g)/p` (free)
//! with `g` linearised, so `kλ₁ + p s = kλ − p g`: the consistent switch is
//! Rockafellar's switch, one iteration behind.

use super::{rockafellar, GapGeometry, NodeContribution};
use nalgebra::{Matrix2, Matrix3, SMatrix, SVector, Vector2, Vector3};

/// Local slack unknowns of one secondary node.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct SlackState {
    /// Slack `s` (admissible `s ≤ 0`; `s = −g` on a free node).
    pub s: f64,
    /// Clamp multiplier `λ₁` (admissible `λ₁ ≥ 0`; `t_N = kλ₁` on a clamped node).
    pub lambda1: f64,
}

/// Which test decides the branch.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SlackSwitch {
    /// Clamped iff `k λ₁ + p s ≥ 0` (formulation note §2.1 item 4).
    Consistent,
    /// Clamped iff `s ≥ 0`, the paper's eq. 23 taken literally: never
    /// releases a clamped node (kept to document and compare).
    PaperSignOfSlack,
}

impl SlackSwitch {
    /// Whether the node is clamped in `state`.
    pub fn is_clamped(&self, state: &SlackState, p: f64, k: f64) -> bool {
        match self {
            Self::Consistent => k * state.lambda1 + p * state.s >= 0.0,
            Self::PaperSignOfSlack => state.s >= 0.0,
        }
    }
}

/// Gradient and Hessian of the node's slack Lagrangian in the paper's
/// unknowns `(x_s, s, λ_p, λ₁)` (eqs. 24/25).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LocalSystem {
    pub gradient: SVector<f64, 6>,
    pub hessian: SMatrix<f64, 6, 6>,
}

/// Back-substitution data: `Δ(s, λ₁) = −(v + M Δ(x_s, λ_p))`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SlackRecovery {
    /// `v = K_bb⁻¹ r_b`.
    v: Vector2<f64>,
    /// `M = K_bb⁻¹ K_ba`, columns `(x, y, z, λ_p)`.
    m: SMatrix<f64, 2, 4>,
}

impl SlackRecovery {
    /// The local state after the global increment `(Δu_s, Δλ)`.
    pub fn apply(&self, state: &SlackState, du: &Vector3<f64>, dlambda: f64) -> SlackState {
        let da = SVector::<f64, 4>::new(du.x, du.y, du.z, -dlambda);
        let db = -(self.v + self.m * da);
        SlackState {
            s: state.s + db[0],
            lambda1: state.lambda1 + db[1],
        }
    }
}

/// The node's slack Lagrangian `L_s` in one branch (paper's `λ_p`).
pub fn lagrangian(
    area: f64,
    gap: &GapGeometry,
    state: &SlackState,
    lambda_paper: f64,
    p: f64,
    k: f64,
    clamped: bool,
) -> f64 {
    let phi = gap.signed_gap + state.s;
    let last = if clamped {
        k * state.lambda1 * state.s
    } else {
        0.5 * k * state.lambda1 * state.lambda1
    };
    area * (k * lambda_paper * phi + 0.5 * p * phi * phi + last)
}

/// Gradient and Hessian of [`lagrangian`] in `(x_s, s, λ_p, λ₁)`.
pub fn local_system(
    area: f64,
    gap: &GapGeometry,
    state: &SlackState,
    lambda_paper: f64,
    p: f64,
    k: f64,
    clamped: bool,
) -> LocalSystem {
    let n = gap.normal;
    let phi = gap.signed_gap + state.s;
    let c = k * lambda_paper + p * phi;
    let mut gradient = SVector::<f64, 6>::zeros();
    gradient.fixed_rows_mut::<3>(0).copy_from(&(area * c * n));
    gradient[3] = area * (c + if clamped { k * state.lambda1 } else { 0.0 });
    gradient[4] = area * k * phi;
    gradient[5] = area * k * if clamped { state.s } else { state.lambda1 };

    let mut h = SMatrix::<f64, 6, 6>::zeros();
    let kxx: Matrix3<f64> = area * (p * n * n.transpose() + c * gap.hessian);
    h.fixed_view_mut::<3, 3>(0, 0).copy_from(&kxx);
    for i in 0..3 {
        h[(i, 3)] = area * p * n[i];
        h[(3, i)] = area * p * n[i];
        h[(i, 4)] = area * k * n[i];
        h[(4, i)] = area * k * n[i];
    }
    h[(3, 3)] = area * p;
    h[(3, 4)] = area * k;
    h[(4, 3)] = area * k;
    if clamped {
        h[(3, 5)] = area * k;
        h[(5, 3)] = area * k;
    } else {
        h[(5, 5)] = area * k;
    }
    LocalSystem {
        gradient,
        hessian: h,
    }
}

impl SlackState {
    /// Whether `s` and `λ₁` are finite.
    pub fn is_finite(&self) -> bool {
        self.s.is_finite() && self.lambda1.is_finite()
    }

    /// The local unknowns that solve the node's own equations for given
    /// `(g, λ)` (global sign `λ = −λ_p`): with `t̂ = kλ − p g`, clamped
    /// `(s, λ₁) = (0, t̂/k)` if `t̂ ≥ 0`, else free `(t̂/p, 0)`. Use it to
    /// start a node (e.g. when it is first paired with the obstacle).
    pub fn consistent(signed_gap: f64, lambda: f64, p: f64, k: f64) -> Self {
        let t = rockafellar::augmented_pressure(signed_gap, lambda, p, k);
        if t >= 0.0 {
            Self {
                s: 0.0,
                lambda1: t / k,
            }
        } else {
            Self {
                s: t / p,
                lambda1: 0.0,
            }
        }
    }

    /// Condensed contribution with the consistent switch, and the data to
    /// recover `(Δs, Δλ₁)` after the global solve. `lambda` is the global
    /// multiplier (`t_N = kλ`).
    pub fn condense(
        &self,
        area: f64,
        gap: &GapGeometry,
        lambda: f64,
        p: f64,
        k: f64,
    ) -> (NodeContribution, SlackRecovery) {
        self.condense_with(SlackSwitch::Consistent, area, gap, lambda, p, k)
    }

    /// [`condense`](Self::condense) with a chosen switch.
    pub fn condense_with(
        &self,
        switch: SlackSwitch,
        area: f64,
        gap: &GapGeometry,
        lambda: f64,
        p: f64,
        k: f64,
    ) -> (NodeContribution, SlackRecovery) {
        let clamped = switch.is_clamped(self, p, k);
        self.condense_in_branch(area, gap, lambda, p, k, clamped)
    }

    /// Schur complement of `(s, λ₁)` in the branch's [`local_system`],
    /// written in the global multiplier `λ = −λ_p`.
    pub fn condense_in_branch(
        &self,
        area: f64,
        gap: &GapGeometry,
        lambda: f64,
        p: f64,
        k: f64,
        clamped: bool,
    ) -> (NodeContribution, SlackRecovery) {
        let sys = local_system(area, gap, self, -lambda, p, k, clamped);
        // a = (x, y, z, λ_p) = rows 0, 1, 2, 4; b = (s, λ₁) = rows 3, 5.
        const A: [usize; 4] = [0, 1, 2, 4];
        const B: [usize; 2] = [3, 5];
        let k_aa = SMatrix::<f64, 4, 4>::from_fn(|i, j| sys.hessian[(A[i], A[j])]);
        let k_ab = SMatrix::<f64, 4, 2>::from_fn(|i, j| sys.hessian[(A[i], B[j])]);
        let k_bb = Matrix2::from_fn(|i, j| sys.hessian[(B[i], B[j])]);
        let r_a = SVector::<f64, 4>::from_fn(|i, _| sys.gradient[A[i]]);
        let r_b = Vector2::from_fn(|i, _| sys.gradient[B[i]]);
        // K_bb = A[[p, k], [k, 0]] (clamped) or A[[p, 0], [0, k]] (free): det ≠ 0.
        #[allow(clippy::expect_used)]
        // K_bb = A[[p, k], [k, 0]] or A[[p, 0], [0, k]] has det ≠ 0 for p, k, A_s > 0, which the case file validates
        let k_bb_inv = k_bb
            .try_inverse()
            .expect("slack block is invertible for p, k, A_s > 0");
        let v = k_bb_inv * r_b;
        let m = k_bb_inv * k_ab.transpose();
        let k_red = k_aa - k_ab * m;
        let r_red = r_a - k_ab * v;

        // Convert λ_p = −λ: the λ row and column change sign.
        let r_u = Vector3::new(r_red[0], r_red[1], r_red[2]);
        let t = rockafellar::augmented_pressure(gap.signed_gap, lambda, p, k);
        let pressing = clamped && t > 0.0;
        let contribution = NodeContribution {
            r_u,
            r_lambda: -r_red[3],
            k_uu: k_red.fixed_view::<3, 3>(0, 0).into_owned(),
            k_ulambda: -k_red.fixed_view::<3, 1>(0, 3).into_owned(),
            k_lambdalambda: k_red[(3, 3)],
            pressure: if clamped { t.max(0.0) } else { 0.0 },
            pressure_gradient: if pressing {
                -p * gap.normal
            } else {
                Vector3::zeros()
            },
            pressure_multiplier_derivative: if pressing { k } else { 0.0 },
            active: clamped,
        };
        (contribution, SlackRecovery { v, m })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const AREA: f64 = 0.37;
    const P: f64 = 2.0e3;
    const K: f64 = 7.0e2;

    /// One dof between a spring (`k_s`, anchored at `u = 0`) and a wall
    /// (`g = g₀ + u`, `n = e_z`), force `F` toward the wall. Newton on the
    /// condensed `(u, λ)` system with back-substitution of `(s, λ₁)`.
    fn newton(
        switch: SlackSwitch,
        force: f64,
        u: &mut f64,
        lambda: &mut f64,
        st: &mut SlackState,
        iterations: usize,
    ) -> bool {
        let (k_s, g0) = (40.0, 0.01);
        let wall = Vector3::zeros();
        for _ in 0..iterations {
            let geo = GapGeometry::plane(&Vector3::new(0.0, 0.0, g0 + *u), &wall, &Vector3::z());
            let (c, rec) = st.condense_with(switch, AREA, &geo, *lambda, P, K);
            let r = Vector2::new(k_s * *u + force + c.r_u.z, c.r_lambda);
            let kt = Matrix2::new(
                k_s + c.k_uu[(2, 2)],
                c.k_ulambda.z,
                c.k_ulambda.z,
                c.k_lambdalambda,
            );
            if r.norm() < 1e-12 {
                return true;
            }
            let d = -kt.lu().solve(&r).unwrap();
            *st = rec.apply(st, &Vector3::new(0.0, 0.0, d[0]), d[1]);
            *u += d[0];
            *lambda += d[1];
        }
        false
    }

    /// Push, then pull: the consistent switch releases the node and finds
    /// the free equilibrium; the paper's switch keeps it clamped with `s = 0`
    /// and a tensile reaction (`λ₁ < 0`, `kλ < 0`) forever.
    #[test]
    fn paper_switch_never_releases_a_node_pulled_off_the_wall() {
        let (k_s, g0) = (40.0, 0.01);
        for switch in [SlackSwitch::Consistent, SlackSwitch::PaperSignOfSlack] {
            let (mut u, mut lambda) = (0.0, 0.0);
            let mut st = SlackState::consistent(g0, 0.0, P, K);
            // Push with F = 25: contact, t_N = (F − k_s g₀)/A_s.
            assert!(
                newton(switch, 25.0, &mut u, &mut lambda, &mut st, 30),
                "{switch:?} push"
            );
            let t = (25.0 - k_s * g0) / AREA;
            assert!((u + g0).abs() < 1e-12);
            assert!((K * lambda - t).abs() < 1e-9 * t);
            assert!(st.s == 0.0 && (K * st.lambda1 - t).abs() < 1e-9 * t);
            // Pull with F = −5.
            let converged = newton(switch, -5.0, &mut u, &mut lambda, &mut st, 30);
            match switch {
                SlackSwitch::Consistent => {
                    assert!(converged);
                    assert!((u - 5.0 / k_s).abs() < 1e-12, "free: u = −F/k_s");
                    assert!(lambda.abs() < 1e-12);
                    assert!((st.s + g0 + u).abs() < 1e-12 && st.lambda1 == 0.0, "s = −g");
                }
                SlackSwitch::PaperSignOfSlack => {
                    // Newton "converges", to a glued node pulling on the wall.
                    assert!(converged);
                    assert_eq!(st.s, 0.0);
                    assert!((u + g0).abs() < 1e-12, "stuck at g = 0");
                    assert!(st.lambda1 < 0.0 && lambda < 0.0, "tensile reaction");
                    assert!(switch.is_clamped(&st, P, K));
                    assert!(!SlackSwitch::Consistent.is_clamped(&st, P, K));
                }
            }
        }
    }
}
