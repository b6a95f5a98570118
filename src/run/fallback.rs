//! Newton's path as the fallback of `auto`'s condensed path: an increment
//! that the condensed solve fails (an ill-conditioned floating body, a
//! contact solve that does not settle) is solved again by Newton on the
//! whole system before any cut, so that `auto` never leaves a user worse
//! off than `strategy = "monolithic"`. The linear solver is made at the
//! first fallback only (most condensed runs never need it).

use super::fill_reducing_ordering;
use crate::contact::interface::NodeReport;
use crate::problem::{ContactState, Problem};
use crate::solve::backend::try_linear_solver;
use crate::solve::failure::IncrementFailure;
use crate::solve::josephy::Josephy;
use crate::solve::linear_solver::{LinearSolver, SolverStatistics};
use crate::solve::method::{Increment, IncrementMethod, Monolithic};
use crate::solve::newton::{IterationRecord, NewtonOutcome};
use crate::Result;

/// Newton on the whole system, its linear solver made when first needed.
#[derive(Default)]
pub(super) struct NewtonOnDemand {
    solver: Option<Box<dyn LinearSolver>>,
    josephy: Josephy,
}

/// The linear solver of Newton's path for `problem`'s pattern.
fn linear_solver(problem: &Problem) -> Result<Box<dyn LinearSolver>> {
    let ordering = fill_reducing_ordering(problem)?;
    let mesh = &problem.model.mesh;
    let coordinates = mesh.nodes.iter().flatten().copied().collect();
    try_linear_solver(&problem.settings, ordering, 0, Some(coordinates))
}

impl IncrementMethod<Problem> for NewtonOnDemand {
    fn name(&self) -> &'static str {
        "monolithic"
    }

    fn pattern_changed(&mut self, problem: &Problem) -> Result<()> {
        if let Some(solver) = self.solver.as_mut() {
            solver.set_ordering(fill_reducing_ordering(problem)?);
        }
        Ok(())
    }

    fn solve(
        &mut self,
        problem: &Problem,
        increment: &Increment<'_>,
        u: &[f64],
        state: &mut ContactState,
        x: &mut Vec<f64>,
        on_iteration: &mut dyn FnMut(&IterationRecord) -> bool,
    ) -> NewtonOutcome<Vec<Vec<NodeReport>>> {
        let solver = match self.solver.take() {
            Some(solver) => solver,
            None => match linear_solver(problem) {
                Ok(solver) => solver,
                Err(e) => {
                    return (
                        Err(IncrementFailure::LinearSolve(e.to_string())),
                        Vec::new(),
                    )
                }
            },
        };
        let solver = self.solver.insert(solver);
        let mut newton = Monolithic::new(problem, &mut **solver, &mut self.josephy);
        newton.solve(problem, increment, u, state, x, on_iteration)
    }

    fn statistics(&self) -> SolverStatistics {
        self.solver
            .as_ref()
            .map(|s| s.statistics())
            .unwrap_or_default()
            + self.josephy.statistics()
    }
}
