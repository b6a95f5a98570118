//! How one load increment is solved: the one seam between the stepper
//! (`resume_steps` of `solve/stepping.rs`, which owns cuts, growth, restart,
//! cancel and the reports) and a solution method. Newton on the whole
//! system ([`Monolithic`]) is one implementation; the condensed contact
//! path (`crate::problem::condensed`, frictionless and frictional) is the
//! other. Every method reports its iterations as [`IterationRecord`]s (the
//! last one the converged evaluation, `correction = 0`), so that the
//! progress line, the log, the convergence plot and `summary.json` read
//! the same figures whichever method ran.

use super::failure::IncrementFailure;
use super::josephy::Josephy;
use super::linear_solver::{LinearSolver, SolverStatistics};
use super::newton::{Newton, NewtonOutcome};
use super::nonlinear::NonlinearProblem;
use super::record::IterationRecord;
use super::settings::{Predictor, Step};
use crate::Result;

/// One increment to solve: its step, the time it starts from (the last
/// converged one) and the time it reaches, and what the stepper carries
/// into it.
pub struct Increment<'a> {
    pub step: &'a Step,
    pub start: f64,
    pub time: f64,
    /// The largest `max(‖f_int‖, ‖f_ext‖)` of the converged increments.
    pub force_scale: f64,
    /// The change of the unknowns over the last converged increment and
    /// its length (the secant predictor's).
    pub secant: Option<&'a (Vec<f64>, f64)>,
}

/// What a method keeps between increments that changes its answer's
/// round-off (the condensed path's candidate nodes, in the order they
/// joined, its last active set and the semismooth Newton start): stored in
/// the checkpoint with the stepper's `Stepping`, so that a restart
/// continues bit for bit.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct WarmStart {
    /// The batches of candidates in the order they were added.
    pub batches: Vec<Vec<usize>>,
    /// Per candidate: in the active set.
    pub active: Vec<bool>,
    /// The last answer's numbers that start the next solve.
    pub values: Vec<f64>,
    /// Which of `values` are set (the others are taken from the solve).
    pub set: Vec<bool>,
}

impl WarmStart {
    /// Whether the last answer's numbers are finite.
    pub fn is_finite(&self) -> bool {
        self.values.iter().all(|x| x.is_finite())
    }
}

/// A method that solves one increment.
pub trait IncrementMethod<P: NonlinearProblem> {
    /// `"monolithic"` or `"condensed"`: the log's and summary's name.
    fn name(&self) -> &'static str;

    /// The problem's pattern changed (new contact couplings) before the
    /// increment.
    fn pattern_changed(&mut self, _problem: &P) -> Result<()> {
        Ok(())
    }

    /// Solve `increment` from the converged unknowns `u`; `state` is the
    /// committed history on entry and the trial history on return, `x`
    /// the last iterate. `on_iteration` is told of every iteration once
    /// taken and returns whether to go on (else
    /// [`IncrementFailure::Cancelled`]).
    fn solve(
        &mut self,
        problem: &P,
        increment: &Increment<'_>,
        u: &[f64],
        state: &mut P::State,
        x: &mut Vec<f64>,
        on_iteration: &mut dyn FnMut(&IterationRecord) -> bool,
    ) -> NewtonOutcome<P::Report>;

    /// Whether the next increment grows after one that converged with
    /// `records` and no cut (`easy`: `[solver] easy_iterations`).
    fn grows(&self, records: &[IterationRecord], easy: usize) -> bool {
        super::record::converged_well(records, easy)
    }

    /// Whether the run's first search (before any increment measured a
    /// motion) covers the increment's prescribed motion: Newton's, which
    /// loses a whole solve where its answer leaves the pairs (two-spheres
    /// with mortar: 17 iterations). Not the condensed path's, whose
    /// rounds read every candidate: two-spheres' node-to-surface run took
    /// 21 rounds on the wider pairs against 19, 1.11× the CPU
    /// (BENCHMARKS.md, "Session 26: mortar Newton, the first search").
    fn first_search_covers_prescribed_motion(&self) -> bool {
        false
    }

    /// Counts and times of the method's factorisations and solves so far.
    fn statistics(&self) -> SolverStatistics;

    /// The warm start to checkpoint (`None`: the method has none).
    fn warm_start(&self) -> Option<WarmStart> {
        None
    }

    /// Resume from a checkpointed warm start.
    fn resume(&mut self, _problem: &P, _warm: &WarmStart) -> Result<()> {
        Ok(())
    }
}

/// Newton–Raphson on the whole system with a linear solver (and the
/// Josephy–Newton steps of `[solver] predictor = "contact"`).
pub struct Monolithic<'a> {
    pub solver: &'a mut dyn LinearSolver,
    /// The factor of the Josephy–Newton steps, kept over the run.
    pub josephy: &'a mut Josephy,
    /// `[solver] predictor` resolved ([`Predictor::chosen`]).
    pub predictor: Predictor,
}

impl<'a> Monolithic<'a> {
    /// Newton for `problem` with `solver`, the predictor as the problem's
    /// settings choose it.
    pub fn new<P: NonlinearProblem>(
        problem: &P,
        solver: &'a mut dyn LinearSolver,
        josephy: &'a mut Josephy,
    ) -> Self {
        let (predictor, _) = problem
            .settings()
            .predictor
            .chosen(problem.constraints_linearise());
        Monolithic {
            solver,
            josephy,
            predictor,
        }
    }
}

impl<P: NonlinearProblem> IncrementMethod<P> for Monolithic<'_> {
    fn name(&self) -> &'static str {
        "monolithic"
    }

    fn first_search_covers_prescribed_motion(&self) -> bool {
        true
    }

    fn pattern_changed(&mut self, problem: &P) -> Result<()> {
        // new couplings: order them (each multiplier after its nodes)
        self.solver
            .set_ordering(super::ordering::fill_reducing_ordering(
                problem.pattern(),
                problem.num_dofs(),
                None,
            )?);
        Ok(())
    }

    fn solve(
        &mut self,
        problem: &P,
        increment: &Increment<'_>,
        u: &[f64],
        state: &mut P::State,
        x: &mut Vec<f64>,
        on_iteration: &mut dyn FnMut(&IterationRecord) -> bool,
    ) -> NewtonOutcome<P::Report> {
        let constrained = problem.constrained_dofs();
        let t = increment.time;
        let mut newton = Newton {
            problem,
            solver: &mut *self.solver,
            constrained: &constrained,
            t,
            force_scale: increment.force_scale,
            on_iteration: Some(on_iteration),
            josephy: &mut *self.josephy,
            predictor: self.predictor,
        };
        let extrapolate = increment.secant.filter(|_| self.predictor.extrapolates());
        let start = predict(problem, t, u, extrapolate, t - increment.start, state);
        solve_with_augmentation(&mut newton, &start, u, state, x)
    }

    fn statistics(&self) -> SolverStatistics {
        self.solver.statistics() + self.josephy.statistics()
    }
}

/// The secant predictor ([`Predictor::Secant`]): the first Newton iterate
/// of an increment of length `dt` from the converged `u` is
/// `u + (dt / Δt) Δu`, the last converged increment `Δu` (length `Δt`)
/// scaled by the ratio of the increments (the history `state` carried
/// along it); `u` itself at the first increment or without `secant`
/// ([`Predictor::None`]). Newton then starts near the solution of a
/// smoothly loaded path; the converged state is the same (only Newton's
/// path changes).
fn predict<P: NonlinearProblem>(
    problem: &P,
    t: f64,
    u: &[f64],
    secant: Option<&(Vec<f64>, f64)>,
    dt: f64,
    state: &mut P::State,
) -> Vec<f64> {
    let mut start = u.to_vec();
    if let Some((change, last_dt)) = secant {
        let ratio = dt / last_dt;
        let step: Vec<f64> = change.iter().map(|c| ratio * c).collect();
        problem.advance_state(t, u, &step, state);
        start.iter_mut().zip(&step).for_each(|(x, d)| *x += d);
    }
    start
}

/// Most outer (Uzawa) augmentations of one increment.
const MAX_AUGMENTATIONS: usize = 200;

/// Newton for one increment from the predicted `start` (the increment
/// starting at the converged `u_start`); for Uzawa interfaces, followed
/// by multiplier updates and new Newton solves at the same time until the
/// largest penetration is within tolerance (formulation note §2.1 item 2).
fn solve_with_augmentation<P: NonlinearProblem>(
    newton: &mut Newton<'_, P>,
    start: &[f64],
    u_start: &[f64],
    state: &mut P::State,
    u: &mut Vec<f64>,
) -> NewtonOutcome<P::Report> {
    let (mut outcome, mut records) = newton.solve(start, u_start, state, u);
    let mut augmentations = 0;
    while outcome.is_ok() && newton.problem.augment(newton.t, u, state) {
        augmentations += 1;
        if augmentations > MAX_AUGMENTATIONS {
            let updates = MAX_AUGMENTATIONS;
            return (Err(IncrementFailure::OuterLoopLimit { updates }), records);
        }
        let start = u.clone();
        let (next, more) = newton.solve(&start, u_start, state, u);
        outcome = next;
        records.extend(more);
    }
    (outcome, records)
}
