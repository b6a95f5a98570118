//! The [`LinearSolver`] trait: what Newton asks of a linear solver. Each
//! Newton correction solves `K δu = b` once; a solver analyses the sparsity
//! pattern once (recognised by its fingerprint) and factorises every time.
//! The implementations, one file each: [`super::direct::DirectLdlt`],
//! [`super::krylov::PreconditionedGmres`], [`super::lu::SparseLu`]; the
//! `[solver] linear` key picks one in [`super::backend::linear_solver`].

use super::failure::IncrementFailure;
use super::linear::{FactorReport, Ordering};
use crate::assembly::sink::TangentSink;
use faer::sparse::SymbolicSparseColMat;
use std::sync::Arc;
use std::time::Duration;

/// One linear system `K x = b` of a Newton iteration.
pub struct LinearSystem<'a> {
    /// Full (both triangles) CSC pattern of `K`.
    pub pattern: &'a SymbolicSparseColMat<usize>,
    /// The values of `K` (prescribed rows and columns already replaced by a
    /// scaled identity); empty when the solver's own matrix holds `K`
    /// ([`LinearSolver::tangent_sink`]).
    pub matrix: &'a [f64],
    /// For a nonsymmetric `K`: a symmetric matrix on the same pattern that
    /// differs from `K` only in a few blocks (the preconditioner's). `None`
    /// when `K` is symmetric.
    pub symmetric_neighbour: Option<&'a [f64]>,
    /// The expected sign of each pivot (+1 displacement, −1 multiplier) of
    /// a saddle-point system, for the LDLᵀ's dynamic regularisation.
    pub pivot_signs: Option<&'a [i8]>,
}

/// Counts and times of a solver since it was made (summary.json's
/// `symbolic_analyses`, `phase_times`, `factor_nnz`, `krylov_*`,
/// `lu_solves`, `factorisations`, `single_factorisations`,
/// `refinement_steps`, `mixed_precision_fallbacks`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SolverStatistics {
    /// Symbolic analyses of the LDLᵀ.
    pub analyses: usize,
    pub symbolic: Duration,
    /// Numeric LDLᵀ factorisations and LU factorisations with their solves.
    pub factorisation: Duration,
    /// LDLᵀ triangular solves.
    pub solve: Duration,
    /// Stored entries of the LDLᵀ factor.
    pub factor_nnz: usize,
    /// Numeric LDLᵀ factorisations in f64 and in f32 (mixed precision).
    pub factorisations: usize,
    pub single_factorisations: usize,
    /// Iterative refinement steps after LDLᵀ solves.
    pub refinement_steps: usize,
    /// f32 factorisations whose refinement stalled (or that failed), solved
    /// again with an f64 factorisation.
    pub mixed_precision_fallbacks: usize,
    /// GMRES solves and their iterations in total.
    pub krylov_solves: usize,
    pub krylov_iterations: usize,
    /// Solves by the sparse LU (chosen, or as a fallback).
    pub lu_solves: usize,
    /// PETSc's share of `factorisation` (`linear = "petsc"`, zero for
    /// another solver): its KSP's set-up (`KSPSetUp`, the preconditioner's
    /// `PCSetUp`: MUMPS's factorisation, GAMG's or fieldsplit's set-up)
    /// and its `KSPSolve` (the Krylov iterations, MUMPS's triangular
    /// solves).
    pub petsc_setup: Duration,
    pub petsc_solve: Duration,
}

impl SolverStatistics {
    /// The analyses, times and factor size of an LDLᵀ.
    pub fn of_ldlt(ldlt: &impl FactorReport) -> Self {
        let t = &ldlt.timings();
        SolverStatistics {
            analyses: t.analyses,
            symbolic: t.symbolic_total,
            factorisation: t.numeric_total,
            solve: t.solve_total,
            factor_nnz: ldlt.factor_nnz(),
            factorisations: t.factorisations,
            single_factorisations: t.single_factorisations,
            refinement_steps: t.refinement_steps,
            ..Default::default()
        }
    }
}

impl std::ops::Add for SolverStatistics {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        SolverStatistics {
            analyses: self.analyses + o.analyses,
            symbolic: self.symbolic + o.symbolic,
            factorisation: self.factorisation + o.factorisation,
            solve: self.solve + o.solve,
            factor_nnz: self.factor_nnz + o.factor_nnz,
            factorisations: self.factorisations + o.factorisations,
            single_factorisations: self.single_factorisations + o.single_factorisations,
            refinement_steps: self.refinement_steps + o.refinement_steps,
            mixed_precision_fallbacks: self.mixed_precision_fallbacks + o.mixed_precision_fallbacks,
            krylov_solves: self.krylov_solves + o.krylov_solves,
            krylov_iterations: self.krylov_iterations + o.krylov_iterations,
            lu_solves: self.lu_solves + o.lu_solves,
            petsc_setup: self.petsc_setup + o.petsc_setup,
            petsc_solve: self.petsc_solve + o.petsc_solve,
        }
    }
}

/// What the linear solver did for one Newton correction: the change of
/// its [`SolverStatistics`] over the solve ([`SolverStatistics::since`]),
/// for the log's iteration lines.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct LinearFigures {
    /// Seconds in numeric factorisations (LDLᵀ and LU, with the LU's
    /// solve) and in the LDLᵀ's triangular solves.
    pub factorisation: f64,
    pub solve: f64,
    /// Iterative refinement steps after an f32 LDLᵀ (mixed precision).
    pub refinement_steps: usize,
    /// GMRES iterations.
    pub krylov_iterations: usize,
    /// Solves by the sparse LU: the fallback when the LDLᵀ or GMRES
    /// failed, or the chosen nonsymmetric solver.
    pub lu_solves: usize,
    /// f32 factorisations replaced by an f64 one.
    pub mixed_precision_fallbacks: usize,
}

impl SolverStatistics {
    /// The figures of the solves since `before` (an earlier snapshot of
    /// the same solver): `self − before`, counter by counter.
    pub fn since(&self, before: &SolverStatistics) -> LinearFigures {
        let seconds = |now: Duration, then: Duration| now.saturating_sub(then).as_secs_f64();
        LinearFigures {
            factorisation: seconds(self.factorisation, before.factorisation),
            solve: seconds(self.solve, before.solve),
            refinement_steps: self
                .refinement_steps
                .saturating_sub(before.refinement_steps),
            krylov_iterations: self
                .krylov_iterations
                .saturating_sub(before.krylov_iterations),
            lu_solves: self.lu_solves.saturating_sub(before.lu_solves),
            mixed_precision_fallbacks: self
                .mixed_precision_fallbacks
                .saturating_sub(before.mixed_precision_fallbacks),
        }
    }
}

/// A sparse linear solver for Newton's corrections.
pub trait LinearSolver {
    /// Use `ordering` from the next factorisation on (a new symbolic
    /// analysis): after the pattern changed, e.g. new contact pairs.
    fn set_ordering(&mut self, ordering: Ordering);
    /// Solve `K x = rhs` (analysing the pattern if it is new, factorising
    /// `K` or its symmetric neighbour). The error says why it failed:
    /// [`IncrementFailure::LinearSolve`] for this matrix (a singular
    /// tangent: the stepper cuts the increment), or
    /// [`IncrementFailure::LinearSolverSetUp`] for the solver's own
    /// settings (the run ends).
    fn solve(
        &mut self,
        system: &LinearSystem<'_>,
        rhs: &[f64],
        x: &mut [f64],
    ) -> Result<(), IncrementFailure>;
    /// Counts and times so far.
    fn statistics(&self) -> SolverStatistics;
    /// What the log should say of the solver beyond `[solver] linear`
    /// (an external library's version and settings); empty by default.
    fn description(&self) -> String {
        String::new()
    }
    /// Whether [`LinearSystem::symmetric_neighbour`] is read (a
    /// preconditioner of ours); a solver that ignores it (PETSc's) spares
    /// Newton a tangent-sized array and its mirror positions per solve.
    fn reads_symmetric_neighbour(&self) -> bool {
        true
    }
    /// The solver's own matrix as the place Newton's tangent is assembled
    /// into ([`TangentSink`]), laid out for `pattern`, where the solver has
    /// one (PETSc's distributed matrix): Newton then keeps no values array
    /// and hands [`LinearSolver::solve`] an empty
    /// [`LinearSystem::matrix`]. `None` (the default): the solver reads the
    /// values.
    fn tangent_sink(
        &mut self,
        _pattern: &SymbolicSparseColMat<usize>,
    ) -> Result<Option<Arc<dyn TangentSink>>, String> {
        Ok(None)
    }
}
