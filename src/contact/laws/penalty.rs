//! Penalty law (formulation note §2.1 item 1; the paper's §3 lists it).
//!
//! ```text
//! t_N = ε ⟨−g⟩                                 pressure, ⟨·⟩ = max(0, ·)
//! A_s Φ(g) = A_s ε/2 ⟨−g⟩²                      potential
//! r_u  = ∂(A_s Φ)/∂x_s = −A_s t_N n
//! K_uu = ∂r_u/∂x_s     = A_s ε n nᵀ − A_s t_N H     (active, g < 0)
//! ```
//! The curvature term follows from `r_u = −A_s t_N(x) n(x)` and
//! `∂n/∂x = H`: it is `−A_s t_N H` (checked against finite differences in
//! `tests/contact_laws.rs`, where the opposite sign fails). The law leaves
//! a penetration `t_N/ε` at equilibrium.

use super::{uzawa, GapGeometry, NodeContribution};

/// Potential `A_s ε/2 ⟨−g⟩²` whose gradient is the residual.
pub fn potential(area: f64, gap: &GapGeometry, epsilon: f64) -> f64 {
    let pen = (-gap.signed_gap).max(0.0);
    0.5 * area * epsilon * pen * pen
}

/// Residual and tangent of one node; active iff `g ≤ 0`. A node exactly in
/// touch (`g = 0`) takes the closed branch's tangent, so that a body that
/// rests on the obstacle with no other support is not singular. The
/// formulas are Uzawa's with `λ = 0` ([`uzawa::contribution`]).
pub fn contribution(area: f64, gap: &GapGeometry, epsilon: f64) -> NodeContribution {
    uzawa::contribution(area, gap, 0.0, epsilon)
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Matrix3, Vector3};

    const AREA: f64 = 0.37;
    const EPS: f64 = 1.0e3;

    /// A node on a roller (tangential stiffness `k_t T` only), pushed into a
    /// tilted plane by `F` along `−n`: Newton converges to the penetration
    /// `−g = F/(A_s ε)`, in one step once active (the law is linear in `g`).
    #[test]
    fn equilibrium_penetration_is_force_over_area_times_epsilon() {
        let force = 12.5;
        let point = Vector3::zeros();
        let n = Vector3::new(0.3, -0.4, 1.0).normalize();
        let t_proj = Matrix3::identity() - n * n.transpose();
        let k_t = 50.0;
        let x0 = Vector3::new(0.3, 0.1, 0.0);
        let x0 = x0 - x0.dot(&n) * n; // on the plane, g = 0
        let mut x = x0 - 1e-6 * n; // just inside, so the first tangent is active
        let mut iterations = 0;
        loop {
            let c = contribution(AREA, &GapGeometry::plane(&x, &point, &n), EPS);
            // r = f_int − f_ext − f_contact, f_ext = −F n, f_int = k_t T (x − x0).
            let r = k_t * t_proj * (x - x0) + force * n + c.r_u;
            if r.norm() < 1e-12 * force {
                break;
            }
            let k = k_t * t_proj + c.k_uu;
            x -= k.lu().solve(&r).unwrap();
            iterations += 1;
            assert!(iterations < 10);
        }
        let g = GapGeometry::plane(&x, &point, &n).signed_gap;
        assert!((-g - force / (AREA * EPS)).abs() < 1e-12, "g = {g}");
        assert!(iterations <= 2, "{iterations}");
    }
}
