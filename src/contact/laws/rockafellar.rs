//! Monolithic Rockafellar augmented Lagrangian (formulation note §2.1
//! item 3; the family of the paper's §4, without the slack variable).
//!
//! One scaled multiplier `λ` per secondary node, penalty `p > 0`, scaling
//! `k > 0`, augmented pressure `t̂ = kλ − p g`:
//! ```text
//! Φ(g, λ) = −kλ g + (p/2) g²        if t̂ ≥ 0   (active)
//! Φ(g, λ) = −k² λ² / (2p)           if t̂ < 0   (inactive)
//! ```
//! `A_s Φ` is added to the total potential; the residual and tangent are its
//! gradient and Hessian with respect to `(x_s, λ)` through `g(x_s)`:
//! ```text
//! active:   r_u = −A_s t̂ n            r_λ = −A_s k g
//!           K_uu = A_s p n nᵀ − A_s t̂ H
//!           K_uλ = −A_s k n           K_λλ = 0
//! inactive: r_u = 0                   r_λ = −A_s k² λ / p
//!           K_uu = 0, K_uλ = 0        K_λλ = −A_s k² / p
//! ```
//! `Φ` is C¹ across the switch `t̂ = 0` (both branches equal `−p g²/2` there,
//! with equal gradients) but not C²: Newton re-evaluates the switch at every
//! iteration and needs no separate active-set loop. At a solution, active
//! nodes have `g = 0` and `t_N = kλ ≥ 0`; inactive ones have `λ = 0`,
//! `g > 0`. The reported pressure is `⟨t̂⟩`.

use super::{GapGeometry, NodeContribution};
use nalgebra::Vector3;

/// Augmented pressure `t̂ = kλ − p g` (negative when inactive).
pub fn augmented_pressure(signed_gap: f64, lambda: f64, p: f64, k: f64) -> f64 {
    k * lambda - p * signed_gap
}

/// The switch: active iff `kλ − p g ≥ 0`.
pub fn is_active(signed_gap: f64, lambda: f64, p: f64, k: f64) -> bool {
    augmented_pressure(signed_gap, lambda, p, k) >= 0.0
}

/// `Φ(g, λ)` per unit area.
pub fn potential_density(signed_gap: f64, lambda: f64, p: f64, k: f64) -> f64 {
    let g = signed_gap;
    if is_active(g, lambda, p, k) {
        -k * lambda * g + 0.5 * p * g * g
    } else {
        -k * k * lambda * lambda / (2.0 * p)
    }
}

/// The node's potential `A_s Φ(g, λ)`.
pub fn potential(area: f64, gap: &GapGeometry, lambda: f64, p: f64, k: f64) -> f64 {
    area * potential_density(gap.signed_gap, lambda, p, k)
}

/// Residual and tangent of one node, switch evaluated on `(g, λ)`.
pub fn contribution(area: f64, gap: &GapGeometry, lambda: f64, p: f64, k: f64) -> NodeContribution {
    let active = is_active(gap.signed_gap, lambda, p, k);
    branch_contribution(area, gap, lambda, p, k, active)
}

/// The formulas of one branch, whatever the switch says (for comparisons
/// and for the slack law's condensation).
pub fn branch_contribution(
    area: f64,
    gap: &GapGeometry,
    lambda: f64,
    p: f64,
    k: f64,
    active: bool,
) -> NodeContribution {
    let n = gap.normal;
    if active {
        let t = augmented_pressure(gap.signed_gap, lambda, p, k);
        NodeContribution {
            r_u: -area * t * n,
            r_lambda: -area * k * gap.signed_gap,
            k_uu: area * p * n * n.transpose() - area * t * gap.hessian,
            k_ulambda: -area * k * n,
            k_lambdalambda: 0.0,
            pressure: t.max(0.0),
            pressure_gradient: if t > 0.0 { -p * n } else { Vector3::zeros() },
            pressure_multiplier_derivative: if t > 0.0 { k } else { 0.0 },
            active: true,
        }
    } else {
        NodeContribution {
            r_lambda: -area * k * k * lambda / p,
            k_lambdalambda: -area * k * k / p,
            ..NodeContribution::zero()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::laws::fd::{self, check_state, Dofs, Obstacle};
    use nalgebra::Vector3;

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
