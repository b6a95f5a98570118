//! The condensed path as the stepper's [`IncrementMethod`]: the solver of
//! an increment (frictionless or frictional), the check of its answer by
//! the problem's residual, and its warm state for a restart.

use super::{friction, has_friction, has_moving_rows, pairs, set_multipliers, zero_per_node};
use super::{Condensation, ContactState, Path, Problem};
use crate::contact::interface::NodeReport;
use crate::contact::mortar::Derivatives;
use crate::solve::failure::IncrementFailure;
use crate::solve::linear_solver::SolverStatistics;
use crate::solve::method::{Increment, IncrementMethod, WarmStart};
use crate::solve::newton::{IterationRecord, NewtonOutcome};
use crate::solve::nonlinear::NonlinearProblem;
use crate::Result;

/// The largest relative residual the condensed solution may leave when a
/// tighter `residual_tolerance` is asked for: the round-off of the solves
/// and of the residual's assembly (2e-12 measured on Hertz).
const RESIDUAL_FLOOR: f64 = 1e-10;

/// One increment of a condensed path: the unknowns `x` (displacements and
/// the multipliers of the laws that have them) and the trial contact state
/// at time `t` from the committed `state`, so that the problem's own
/// evaluation reports (and checks) the answer; the contact solve's
/// iterations pushed to `history`.
pub(super) trait IncrementSolver: Send {
    fn increment(
        &mut self,
        problem: &Problem,
        t: f64,
        state: &ContactState,
        x: &mut [f64],
        trial: &mut ContactState,
        history: &mut Vec<IterationRecord>,
    ) -> Result<()>;

    /// The factorisation's statistics and the iterations of the contact
    /// solves (active-set steps, semismooth Newton iterations).
    fn statistics(&self) -> (SolverStatistics, usize);

    /// The candidates in the order they joined, the active set and the
    /// last answer: what the next increment starts from.
    fn warm_start(&self) -> WarmStart;

    /// Take up a checkpointed warm start: the candidates added again in
    /// the same batches (so `W` is the same to the bit), the rest copied.
    fn resume(&mut self, warm: &WarmStart) -> Result<()>;

    /// Why the increment at time `t` failed, when the solver can tell:
    /// measured from the problem (its load against the friction capacity)
    /// or from the solve (an answer that left its contact pairs).
    fn diagnose(&self, _problem: &Problem, _t: f64) -> Option<IncrementFailure> {
        None
    }

    /// Whether the next increment grows after this one (`easy`: `[solver]
    /// easy_iterations`): by default always (a frictionless increment is
    /// solved exactly, and its answer does not depend on the increments).
    fn grows(&self, _easy: usize) -> bool {
        true
    }
}

impl IncrementSolver for Condensation {
    fn increment(
        &mut self,
        problem: &Problem,
        t: f64,
        _: &ContactState,
        x: &mut [f64],
        trial: &mut ContactState,
        history: &mut Vec<IterationRecord>,
    ) -> Result<()> {
        let (u, forces) = self.solve_increment(problem, t, None, history)?;
        let mut pressures = zero_per_node(problem);
        // the nodes' areas at `u` (dual mortar's `D_j` follows the surface)
        let rows = super::constraint_rows(problem, t, &u, Derivatives::Without);
        for (a, c) in self.nodes.iter().enumerate() {
            let area = rows[c.interface][c.index].as_ref().map(|r| r.area);
            let area = area.unwrap_or(problem.contacts.interface(c.interface).areas[c.index]);
            pressures[c.interface][c.index] = forces[a] / area;
        }
        set_multipliers(problem, &pressures, &u, t, x, trial);
        Ok(())
    }

    fn statistics(&self) -> (SolverStatistics, usize) {
        let statistics = SolverStatistics {
            mixed_precision_fallbacks: self.flexibility.fallbacks,
            ..SolverStatistics::of_ldlt(&self.flexibility.ldlt)
        };
        (statistics, self.flexibility.active_set_iterations)
    }

    fn warm_start(&self) -> WarmStart {
        WarmStart {
            batches: self.flexibility.batches.clone(),
            active: self.flexibility.active.clone(),
            ..WarmStart::default()
        }
    }

    fn resume(&mut self, warm: &WarmStart) -> Result<()> {
        for batch in &warm.batches {
            self.flexibility.grow(batch)?;
        }
        self.flexibility.active.clone_from(&warm.active);
        Ok(())
    }
}

/// The condensed contact path as a method of the stepper
/// ([`crate::solve::stepping::resume_steps`]): each increment solved
/// exactly (frictional contact by [`friction`], frictionless by the
/// complementarity problem) with the one factorisation of the run,
/// evaluated once by the problem for its residual (within the Newton
/// tolerance, else the increment fails: `auto` then retries it on Newton's
/// path) and reports. Its iterations are the contact solve's (active-set
/// steps, semismooth Newton iterations), the last record the evaluation.
/// Frictionless increments grow after every increment (each is solved
/// exactly); frictional ones after an increment whose first contact solve
/// was easy ([`friction`], "Increments").
pub struct Condensed {
    solver: Box<dyn IncrementSolver>,
}

impl Condensed {
    /// The condensation of `problem` (the caller checked
    /// [`not_applicable`]): `K̃` assembled and factorised once.
    pub fn new(problem: &Problem) -> Result<Self> {
        let solver: Box<dyn IncrementSolver> = if has_friction(problem) {
            Box::new(friction::FrictionalCondensation::new(problem)?)
        } else if has_moving_rows(problem) {
            Box::new(pairs::PairCondensation::new(problem)?)
        } else {
            Box::new(Condensation::new(problem)?)
        };
        Ok(Condensed { solver })
    }
}

impl IncrementMethod<Problem> for Condensed {
    fn name(&self) -> &'static str {
        Path::Condensed.name()
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
        let t = increment.time;
        let committed = state.clone();
        x.clear();
        x.extend_from_slice(u);
        let mut history = Vec::new();
        let solved = self
            .solver
            .increment(problem, t, &committed, x, state, &mut history);
        for record in &history {
            if !on_iteration(record) {
                return (Err(IncrementFailure::Cancelled), history);
            }
        }
        if let Err(e) = solved {
            let failure = (self.solver.diagnose(problem, t))
                .unwrap_or_else(|| IncrementFailure::Condensed(e.to_string()));
            return (Err(failure), history);
        }
        let evaluation = match problem.evaluate(t, x, state, None) {
            Ok(e) => e,
            Err(f) => return (Err(f), history),
        };
        let constrained = problem.constrained_dofs();
        let free: f64 = (evaluation.residual.iter().zip(&constrained))
            .filter(|(_, &c)| !c)
            .map(|(r, _)| r * r)
            .sum();
        let scale = evaluation
            .force_scale()
            .max(increment.force_scale)
            .max(f64::MIN_POSITIVE);
        let relative = free.sqrt() / scale;
        // the solution is exact: only round-off (≈ 1e-12 on Hertz) remains
        let tolerance = problem.settings.residual_tolerance.max(RESIDUAL_FLOOR);
        let record = IterationRecord {
            residual: relative,
            correction: 0.0,
            step_length: 1.0,
            switched: 0,
            linear: Default::default(),
        };
        // the converged evaluation, as Newton's, is not an iteration told
        history.push(record);
        if !(relative <= tolerance) {
            let failure = IncrementFailure::CondensedResidual {
                relative,
                tolerance,
            };
            return (Err(failure), history);
        }
        (Ok(evaluation), history)
    }

    fn grows(&self, _: &[IterationRecord], easy: usize) -> bool {
        self.solver.grows(easy)
    }

    fn statistics(&self) -> SolverStatistics {
        self.solver.statistics().0
    }

    fn warm_start(&self) -> Option<WarmStart> {
        Some(self.solver.warm_start())
    }

    fn resume(&mut self, _: &Problem, warm: &WarmStart) -> Result<()> {
        self.solver.resume(warm)
    }
}
