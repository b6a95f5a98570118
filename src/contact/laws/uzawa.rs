//! Augmented Lagrangian with Uzawa updates (formulation note §2.1 item 2).
//!
//! Inner Newton iterations hold the multiplier `λ` (a pressure) fixed:
//! ```text
//! t_N = ⟨λ − ε g⟩
//! A_s Φ(g; λ) = A_s/(2ε) ⟨λ − ε g⟩²            (up to a constant in λ)
//! r_u  = −A_s t_N n
//! K_uu = A_s ε n nᵀ − A_s t_N H                 (active, λ − εg > 0)
//! ```
//! After the inner Newton converges, [`update_multiplier`] sets
//! `λ ← ⟨λ − ε g⟩`, and the outer loop stops when [`largest_penetration`]
//! is below a tolerance ([`penetration_converged`]). `λ` is not a dof of the
//! global system: `r_λ`, `K_uλ`, `K_λλ` stay zero.

use super::{GapGeometry, NodeContribution};

/// Factor on the automatic `E/h_s` for Uzawa's `ε` (the case file's
/// default; a user's `penalty` is taken as given).
///
/// Why: Uzawa's solution does not depend on `ε`, only the speed of its
/// outer loop does. Each multiplier update leaves roughly the fraction
/// `k/(k + ε)` of the penetration (`k` the structure's stiffness per unit
/// contact area, of order `E/h`), so `ε = E/h` halves it per update and
/// needs ~30 full Newton solves per increment to reach the 1e-9·h
/// tolerance. Measured (2026-11-22): on `examples/hertz` (26 k dofs) the
/// factors 1, 10, 100 took 440, 97 and 46 Newton iterations (152 s, 38 s,
/// 25 s) to the same answer; on `examples/ogden-plate` factor 10 failed
/// near full load and 100 completed in 50 iterations without a cut. The
/// price is the conditioning of a penalty 100 times stiffer than an element
/// inside each Newton solve, which the direct solver absorbs.
pub const AUTOMATIC_FACTOR: f64 = 100.0;

/// Augmented pressure `t_N = ⟨λ − εg⟩`.
pub fn pressure(signed_gap: f64, lambda: f64, epsilon: f64) -> f64 {
    (lambda - epsilon * signed_gap).max(0.0)
}

/// Potential `A_s/(2ε) ⟨λ − εg⟩²` of the inner problem (λ fixed).
pub fn potential(area: f64, gap: &GapGeometry, lambda: f64, epsilon: f64) -> f64 {
    let t = pressure(gap.signed_gap, lambda, epsilon);
    0.5 * area * t * t / epsilon
}

/// Residual and tangent of one node with `λ` fixed; active iff `λ − εg ≥ 0`
/// (a node exactly in touch takes the closed branch's tangent).
pub fn contribution(area: f64, gap: &GapGeometry, lambda: f64, epsilon: f64) -> NodeContribution {
    if !(lambda - epsilon * gap.signed_gap >= 0.0) {
        return NodeContribution::zero();
    }
    let t = pressure(gap.signed_gap, lambda, epsilon);
    let n = gap.normal;
    NodeContribution {
        r_u: -area * t * n,
        k_uu: area * epsilon * n * n.transpose() - area * t * gap.hessian,
        pressure: t,
        pressure_gradient: -epsilon * n,
        active: true,
        ..NodeContribution::zero()
    }
}

/// Uzawa multiplier update after a converged inner Newton: `λ ← ⟨λ − εg⟩`.
pub fn update_multiplier(lambda: f64, signed_gap: f64, epsilon: f64) -> f64 {
    pressure(signed_gap, lambda, epsilon)
}

/// Largest penetration `max(0, max_s −g_s)` over the secondary nodes.
pub fn largest_penetration(signed_gaps: impl IntoIterator<Item = f64>) -> f64 {
    signed_gaps.into_iter().fold(0.0, |m, g| m.max(-g))
}

/// Outer-loop stopping test: the largest penetration is at most `tolerance`.
pub fn penetration_converged(signed_gaps: impl IntoIterator<Item = f64>, tolerance: f64) -> bool {
    largest_penetration(signed_gaps) <= tolerance
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector3;

    const AREA: f64 = 0.37;
    const EPS: f64 = 1.0e3;

    #[test]
    fn stopping_test_uses_the_largest_penetration() {
        let gaps = [0.3, -1e-4, -2e-3, 0.0];
        assert_eq!(largest_penetration(gaps), 2e-3);
        assert_eq!(largest_penetration([0.1, 0.2]), 0.0);
        assert!(penetration_converged(gaps, 2e-3));
        assert!(!penetration_converged(gaps, 1e-3));
    }

    /// One dof pressed into a rigid wall: spring `k_s` anchored at `u = 0`,
    /// initial gap `g₀`, force `F` toward the wall, `g = g₀ + u`, `n = e_z`.
    ///
    /// Equilibrium `k_s u + F − A_s t_N = 0` with `g = 0` gives the exact
    /// multiplier `λ* = (F − k_s g₀)/A_s` (contact needs `F > k_s g₀`).
    /// The inner solve with `λ` fixed gives `g = A_s(λ − λ*)/(k_s + A_s ε)`,
    /// so each update contracts the error by `k_s/(k_s + A_s ε)`.
    #[test]
    fn updates_converge_to_the_exact_multiplier_of_a_spring_against_a_wall() {
        let (k_s, g0, force) = (40.0, 0.01, 25.0);
        let lambda_exact = (force - k_s * g0) / AREA;
        let rate = k_s / (k_s + AREA * EPS);
        let wall = Vector3::zeros();
        let n = Vector3::z();
        let mut lambda = 0.0;
        let mut u = 0.0;
        let mut updates = 0;
        let tolerance = 1e-8;
        loop {
            // Inner Newton on u with λ fixed (piecewise linear: a few steps).
            for _ in 0..20 {
                let geo = GapGeometry::plane(&Vector3::new(0.0, 0.0, g0 + u), &wall, &n);
                let c = contribution(AREA, &geo, lambda, EPS);
                let r = k_s * u + force + c.r_u.z;
                if r.abs() < 1e-13 * force {
                    break;
                }
                u -= r / (k_s + c.k_uu[(2, 2)]);
            }
            let g = g0 + u;
            if g < 0.0 {
                // The contraction holds exactly while in contact.
                let predicted = AREA * (lambda - lambda_exact) / (k_s + AREA * EPS);
                assert!(
                    (g - predicted).abs() < 1e-12,
                    "g = {g}, predicted {predicted}"
                );
            }
            if penetration_converged([g], tolerance) {
                break;
            }
            let before = (lambda - lambda_exact).abs();
            lambda = update_multiplier(lambda, g, EPS);
            if lambda > 0.0 {
                assert!(((lambda - lambda_exact).abs() / before - rate).abs() < 1e-6);
            }
            updates += 1;
            assert!(updates < 20, "no convergence, λ = {lambda}");
        }
        // rate = 40/410 ≈ 0.098: one decimal digit per update.
        assert!(updates <= 8, "{updates} updates");
        assert!(
            (lambda - lambda_exact).abs() < 1e-6 * lambda_exact,
            "λ = {lambda}, λ* = {lambda_exact}"
        );
    }
}
