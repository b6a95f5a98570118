//! Why a frictional condensed increment has no answer, measured from the
//! load: a body that only its contact holds along the contact plane,
//! pulled along it beyond the friction capacity `μN`.
//!
//! ## The measure (Coulomb's law with the balance of forces)
//! Let `A` be the coordinate axes along which no dof of the model is
//! prescribed, `P` the projection onto them, and `F = Σ_a f_ext,a` the
//! total external force. Along a free translation the contact forces
//! `C = Σ_a (N_a n + T_a)` balance the load, `P (C + F) = 0`. With every
//! contact node on planes of one normal `n` lying in `span(A)`:
//! - the normal force is `N = Σ N_a = −n·P F`;
//! - the tangential load `F_T = P F − (n·P F) n` is carried by friction
//!   alone, `P T = −F_T`, and Coulomb's `|T_a| ≤ μ_a N_a` bounds it:
//!   `|F_T| ≤ |Σ T_a| ≤ μ_max N`.
//!
//! So `|F_T| > μ_max N` proves that no equilibrium exists: the increment
//! cannot converge, whatever its size, and the message says so (the
//! monolithic path finds the same from its statuses: every closed node
//! slipping, [`crate::solve::failure::ClosedContact::AllSlip`]).

use super::Problem;
use crate::solve::failure::IncrementFailure;
use nalgebra::Vector3;

/// Relative margin by which the tangential load must exceed `μN` to be
/// reported (round-off of the sums).
const MARGIN: f64 = 1e-9;

/// The overload of `force` (the total external force, components along
/// the axes not `free` ignored) on contact nodes of unit `normal` with
/// friction coefficient at most `coefficient`: `Some((F_T, N))` when
/// `|F_T| > μ N (1 + 1e-9)` (module docs), `None` when the load is within
/// the capacity or the normal is not along free axes (the normal force is
/// then a reaction the load does not give).
pub fn tangential_overload(
    force: Vector3<f64>,
    free: [bool; 3],
    normal: Vector3<f64>,
    coefficient: f64,
) -> Option<(Vector3<f64>, f64)> {
    let project = |v: Vector3<f64>| Vector3::from_fn(|k, _| if free[k] { v[k] } else { 0.0 });
    if (project(normal) - normal).norm() > 1e-12 {
        return None;
    }
    let load = project(force);
    let normal_force = -normal.dot(&load);
    let tangential = load + normal * normal_force;
    let capacity = coefficient * normal_force.max(0.0);
    (tangential.norm() > capacity * (1.0 + MARGIN) + f64::MIN_POSITIVE)
        .then_some((tangential, normal_force))
}

/// The failure of an increment at time `t` of `problem` whose contact
/// nodes have the unit normals and friction coefficients `nodes`, when
/// its load exceeds the friction capacity ([`tangential_overload`]): the
/// nodes must share one normal.
pub(super) fn overload_failure(
    problem: &Problem,
    t: f64,
    nodes: impl Iterator<Item = (Vector3<f64>, f64)>,
) -> Option<IncrementFailure> {
    let mut normal: Option<Vector3<f64>> = None;
    let mut coefficient = 0.0f64;
    for (n, mu) in nodes {
        if normal.is_some_and(|first| (first - n).norm() > 1e-9) {
            return None;
        }
        normal = Some(n);
        coefficient = coefficient.max(mu);
    }
    let normal = normal?;
    let dofs = problem.model.num_dofs();
    let constrained = problem.constrained_dofs();
    let free = [0, 1, 2].map(|k| (k..dofs).step_by(3).all(|d| !constrained[d]));
    let mut prescribed = vec![0.0; problem.num_unknowns()];
    problem.apply_prescribed(t, &mut prescribed);
    let f = problem.external_force(t, &prescribed[..dofs], None);
    let force = f
        .chunks_exact(3)
        .fold(Vector3::zeros(), |s, c| s + Vector3::new(c[0], c[1], c[2]));
    let (tangential, normal_force) = tangential_overload(force, free, normal, coefficient)?;
    let direction = tangential.normalize();
    Some(IncrementFailure::FrictionCapacity {
        tangential: tangential.norm(),
        normal_force,
        coefficient,
        direction: [direction.x, direction.y, direction.z],
    })
}

#[cfg(test)]
mod tests {
    use super::tangential_overload;
    use nalgebra::Vector3;

    /// examples/press-pull pulled to 1.2 μN: N = 20 pressed onto the
    /// plane z = 0 (normal +z, the block above it), y held (plane strain),
    /// μ = 0.3, so the capacity is 6; a pull of 6.02 along +x exceeds it,
    /// one of 5.98 does not; with z held the normal force is a reaction
    /// and nothing is measured.
    #[test]
    fn a_pull_beyond_mu_n_is_measured_from_the_load() {
        let free = [true, false, true];
        let n = Vector3::z();
        let over = tangential_overload(Vector3::new(6.02, 3.0, -20.0), free, n, 0.3);
        let (t, normal_force) = over.expect("6.02 > 0.3 × 20");
        assert!((normal_force - 20.0).abs() < 1e-12);
        assert!((t - Vector3::new(6.02, 0.0, 0.0)).norm() < 1e-12, "{t}");
        assert!(tangential_overload(Vector3::new(5.98, 0.0, -20.0), free, n, 0.3).is_none());
        let z_held = [true, true, false];
        assert!(tangential_overload(Vector3::new(9.0, 0.0, -20.0), z_held, n, 0.3).is_none());
        // frictionless: any tangential load is beyond μN = 0
        let (t, _) = tangential_overload(Vector3::new(0.0, -1e-3, -5.0), [true; 3], n, 0.0)
            .expect("frictionless");
        assert!((t.y + 1e-3).abs() < 1e-15);
        // pulled off the plane (N < 0) with a tangential load: no capacity
        assert!(tangential_overload(Vector3::new(1.0, 0.0, 5.0), [true; 3], n, 0.3).is_some());
        // an inclined plane, n = (0, −sin θ, cos θ) with tan θ = 0.5: a
        // vertical weight W has N = W cos θ and F_T = W sin θ, so it
        // slides iff μ < tan θ
        let theta = 0.5f64.atan();
        let n = Vector3::new(0.0, -theta.sin(), theta.cos());
        let weight = Vector3::new(0.0, 0.0, -10.0);
        let (t, normal_force) = tangential_overload(weight, [true; 3], n, 0.49).unwrap();
        assert!((normal_force - 10.0 * theta.cos()).abs() < 1e-12);
        assert!((t.norm() - 10.0 * theta.sin()).abs() < 1e-12);
        assert!(tangential_overload(weight, [true; 3], n, 0.51).is_none());
    }
}
