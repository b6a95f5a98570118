//! Newton's tangent between its evaluation and its solve: values on the
//! problem's pattern (every faer path, and PETSc without `mpirun`), or
//! the linear solver's own matrix where it offers one
//! ([`LinearSolver::tangent_sink`]: PETSc's distributed matrix), which
//! then holds the one copy of the tangent and the values array is not
//! allocated. What Newton does with the tangent besides solving goes
//! through here: the product `K d` of the prescribed jump, and the
//! prescribed rows and columns made a scaled identity.

use super::failure::IncrementFailure;
use super::linear_solver::LinearSolver;
use super::nonlinear::{Evaluation, NonlinearProblem};
use crate::assembly::sink::{Tangent, TangentSink};
use std::sync::Arc;

/// Where Newton's tangent lives over one increment (the pattern does not
/// change within one).
pub struct TangentStore {
    /// The tangent on the problem's pattern; empty with a sink.
    values: Vec<f64>,
    sink: Option<Arc<dyn TangentSink>>,
}

impl TangentStore {
    /// The solver's sink for `problem`'s pattern if it has one, else
    /// values on the pattern.
    pub fn new<P: NonlinearProblem>(
        problem: &P,
        solver: &mut dyn LinearSolver,
    ) -> Result<Self, IncrementFailure> {
        let pattern = problem.pattern();
        let sink = solver
            .tangent_sink(pattern.symbolic())
            .map_err(IncrementFailure::LinearSolve)?;
        let values = match sink {
            Some(_) => Vec::new(),
            None => vec![0.0; pattern.nnz()],
        };
        Ok(TangentStore { values, sink })
    }

    /// `problem`'s evaluation at time `t`, unknowns `x` and history
    /// `state`, its tangent written here (a sink's fill begun and
    /// finished around it).
    pub fn evaluate<P: NonlinearProblem>(
        &mut self,
        problem: &P,
        t: f64,
        x: &[f64],
        state: &P::State,
    ) -> Result<Evaluation<P::Report>, IncrementFailure> {
        let Some(sink) = &self.sink else {
            return problem.evaluate(t, x, state, Some(Tangent::Values(&mut self.values)));
        };
        sink.begin();
        let evaluation = problem.evaluate(t, x, state, Some(Tangent::Sink(&**sink)))?;
        sink.finish().map_err(IncrementFailure::LinearSolve)?;
        Ok(evaluation)
    }

    /// `y = K x`, completed over the processes of a distributed run.
    pub fn multiply<P: NonlinearProblem>(
        &self,
        problem: &P,
        x: &[f64],
        y: &mut [f64],
    ) -> Result<(), IncrementFailure> {
        match &self.sink {
            None => {
                super::linear::multiply(problem.pattern().symbolic(), &self.values, x, y);
                // distributed: K x from every process's part of K
                problem.sum_over_processes(y);
                Ok(())
            }
            Some(sink) => sink.multiply(x, y).map_err(IncrementFailure::LinearSolve),
        }
    }

    /// The rows and columns of the `constrained` unknowns made a scaled
    /// identity ([`apply_identity_rows`]); its scale.
    pub fn identity_rows<P: NonlinearProblem>(
        &mut self,
        problem: &P,
        constrained: &[bool],
    ) -> Result<f64, IncrementFailure> {
        match &self.sink {
            None => Ok(apply_identity_rows(problem, constrained, &mut self.values)),
            Some(sink) => sink
                .identity_rows(constrained, problem.num_dofs())
                .map_err(IncrementFailure::LinearSolve),
        }
    }

    /// The values on the problem's pattern (empty with a sink: the
    /// solver's matrix holds them).
    pub fn values(&self) -> &[f64] {
        &self.values
    }
}

/// Replace the rows and columns of prescribed dofs by a scaled identity
/// (the scale is the mean absolute diagonal of the free dofs); returns the
/// scale.
pub fn apply_identity_rows<P: NonlinearProblem>(
    problem: &P,
    constrained: &[bool],
    k: &mut [f64],
) -> f64 {
    let blocks = problem.pattern();
    let diagonal = |d: usize| blocks.stored_diagonal(d);
    super::linear::scaled_identity_rows(
        blocks.symbolic(),
        diagonal,
        problem.num_dofs(),
        constrained,
        k,
    )
}
