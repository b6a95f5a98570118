//! The direct solver: the LDLᵀ of `K` (faer's supernodal factorisation
//! without pivoting, [`SparseLdlt`]) with iterative refinement, and the
//! sparse LU with partial pivoting where the LDLᵀ breaks down.

use super::linear::{Ordering, SparseLdlt};
use super::linear_solver::{LinearSolver, LinearSystem, SolverStatistics};
use super::lu::SparseLu;

/// Refinement steps after the LDLᵀ solve.
const REFINEMENTS: usize = 3;

/// Largest relative residual `‖b − K x‖ / ‖b‖` the refined LDLᵀ solve may
/// leave before the LU solves again (digits lost beyond what refinement
/// recovers).
const LDLT_RESIDUAL: f64 = 1e-8;

/// `K = L D Lᵀ`, refined; the LU when the factorisation fails or leaves a
/// relative residual above 1e-8. An indefinite tangent that the LDLᵀ
/// without pivoting cannot factorise (the curvature term `f ∇²g` of
/// deformable contact after a large first step, examples/two-spheres) is
/// solved by the LU with partial pivoting, which also tells a singular one.
pub struct DirectLdlt {
    ldlt: SparseLdlt,
    lu: SparseLu,
}

impl DirectLdlt {
    /// With `ordering` and `threads` threads (0 = rayon's pool).
    pub fn new(ordering: Ordering, threads: usize) -> Self {
        DirectLdlt {
            ldlt: SparseLdlt::new(ordering, threads),
            lu: SparseLu::default(),
        }
    }
}

impl LinearSolver for DirectLdlt {
    fn set_ordering(&mut self, ordering: Ordering) {
        self.ldlt.set_ordering(ordering);
    }

    fn solve(
        &mut self,
        system: &LinearSystem<'_>,
        rhs: &[f64],
        x: &mut [f64],
    ) -> Result<(), String> {
        let (pattern, k) = (system.pattern, system.matrix);
        x.copy_from_slice(rhs);
        let direct = self
            .ldlt
            .factorize(pattern, k, system.pivot_signs)
            .and_then(|()| self.ldlt.solve_refined(pattern, k, x, REFINEMENTS))
            .and_then(|relative| {
                (relative <= LDLT_RESIDUAL).then_some(()).ok_or_else(|| {
                    crate::Error::LinearSolver(format!(
                        "the LDLᵀ solve left a relative residual of {relative:.1e}"
                    ))
                })
            });
        match direct {
            Ok(()) => Ok(()),
            Err(e) => self.lu.solve_after(&e, system, rhs, x),
        }
    }

    fn statistics(&self) -> SolverStatistics {
        SolverStatistics::of_ldlt(&self.ldlt) + self.lu.statistics()
    }
}
