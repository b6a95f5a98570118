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
