//! GMRES preconditioned by an LDLᵀ, for nonsymmetric tangents (follower
//! loads, friction): the preconditioner is the LDLᵀ of the tangent's
//! symmetric neighbour, a matrix that differs from `K` only on the loaded
//! facets and the contact nodes, so a few Krylov iterations suffice. The
//! sparse LU solves the tangent when that LDLᵀ breaks down or GMRES does
//! not converge.

use super::failure::IncrementFailure;
use super::gmres::gmres;
use super::linear::{multiply, Ordering, SparseLdlt};
use super::linear_solver::{LinearSolver, LinearSystem, SolverStatistics};
use super::lu::SparseLu;

/// Relative tolerance of the Krylov solve.
const KRYLOV_TOLERANCE: f64 = 1e-12;
/// Krylov iterations between restarts, and at most in all.
const RESTART: usize = 50;
const MAX_KRYLOV_ITERATIONS: usize = 200;

/// Right-preconditioned restarted GMRES with `M = L D Lᵀ` of the symmetric
/// neighbour (of `K` itself when `K` is symmetric).
pub struct PreconditionedGmres {
    ldlt: SparseLdlt,
    lu: SparseLu,
    krylov_solves: usize,
    krylov_iterations: usize,
}

impl PreconditionedGmres {
    /// With `ordering` and `threads` threads (0 = rayon's pool) for the LDLᵀ.
    pub fn new(ordering: Ordering, threads: usize) -> Self {
        PreconditionedGmres {
            ldlt: SparseLdlt::new(ordering, threads),
            lu: SparseLu::default(),
            krylov_solves: 0,
            krylov_iterations: 0,
        }
    }
}

impl LinearSolver for PreconditionedGmres {
    fn set_ordering(&mut self, ordering: Ordering) {
        self.ldlt.set_ordering(ordering);
    }

    fn solve(
        &mut self,
        system: &LinearSystem<'_>,
        rhs: &[f64],
        x: &mut [f64],
    ) -> Result<(), IncrementFailure> {
        let (pattern, k) = (system.pattern, system.matrix);
        let neighbour = system.symmetric_neighbour.unwrap_or(k);
        if let Err(e) = self.ldlt.factorize(pattern, neighbour, system.pivot_signs) {
            // the LDLᵀ without pivoting of the symmetric saddle-point part can
            // break down (a wrong-sign pivot, regularised, then growth to a
            // non-finite one) where the tangent is regular: the sparse LU with
            // partial pivoting solves it (examples/ironing, rockafellar
            // p = k = 10, tangential penalty 1000: 156 cuts in 643 increments
            // without it, 4 in 109 with it)
            return self.lu.solve_after(&e, system, rhs, x);
        }
        x.iter_mut().for_each(|v| *v = 0.0);
        let ldlt = &mut self.ldlt;
        let report = match gmres(
            |v, y| multiply(pattern, k, v, y),
            |z| ldlt.solve_in_place(z),
            rhs,
            x,
            KRYLOV_TOLERANCE,
            RESTART,
            MAX_KRYLOV_ITERATIONS,
        ) {
            Ok(report) => report,
            // the preconditioner's solve overflowed: solve directly
            Err(e) => return self.lu.solve_after(&e, system, rhs, x),
        };
        self.krylov_solves += 1;
        self.krylov_iterations += report.iterations;
        if !(report.relative_residual <= 1e3 * KRYLOV_TOLERANCE) {
            // the preconditioner is too far from the tangent: solve directly
            return LinearSolver::solve(&mut self.lu, system, rhs, x).map_err(|e| {
                IncrementFailure::LinearSolve(format!(
                    "the nonsymmetric linear solve failed (GMRES relative residual {:.1e} after {} iterations; then {e})",
                    report.relative_residual, report.iterations
                ))
            });
        }
        Ok(())
    }

    fn statistics(&self) -> SolverStatistics {
        SolverStatistics {
            krylov_solves: self.krylov_solves,
            krylov_iterations: self.krylov_iterations,
            ..(SolverStatistics::of_ldlt(&self.ldlt) + self.lu.statistics())
        }
    }
}
