//! Adaptive load stepping: each step's pseudo-time interval is covered by
//! increments that are cut (halved) when Newton fails — divergence, a NaN,
//! an inverted element, too many iterations — and grown after easy ones.
//! After `max_cuts` consecutive cuts the run stops with an error; every
//! increment converged before stays written, since output happens in the
//! `on_converged` callback as each increment converges.

use super::failure::IncrementFailure;
use super::josephy::Josephy;
use super::linear_solver::{LinearSolver, SolverStatistics};
use super::method::{Increment, IncrementMethod, Monolithic, WarmStart};
use super::nonlinear::{Evaluation, NonlinearProblem};
pub(crate) use super::record::converged_well;
use super::record::IterationRecord;
use super::settings::{SolverSettings, Step};
use crate::{Error, Result};
use std::path::PathBuf;

/// A converged increment.
#[derive(Clone, Debug, serde::Serialize)]
pub struct IncrementRecord {
    /// Index of the step (0-based) and its name.
    pub step: usize,
    pub step_name: String,
    /// Pseudo-time at the end of the increment.
    pub time: f64,
    /// Size of the increment.
    pub increment: f64,
    /// Newton iterations (the number of corrections solved).
    pub iterations: usize,
    /// Per-iteration residuals and corrections.
    pub newton: Vec<IterationRecord>,
    /// Cuts suffered before this increment converged.
    pub cuts: usize,
    /// Linear solves by the sparse LU during this increment, its cut
    /// attempts included (chosen by `[solver]`, or the fallback of GMRES or
    /// of an LDLᵀ that broke down).
    pub lu_solves: usize,
    /// The method that solved it (`"monolithic"` or `"condensed"`).
    pub method: &'static str,
    /// Why the run's own method failed it, when the fallback solved it
    /// (`auto`'s condensed path retried on Newton's).
    pub retried: Option<String>,
}

/// What the stepper carries from one converged increment to the next
/// besides the unknowns and the history state: with those, a run resumes
/// from here exactly as it would have gone on ([`resume_steps`], the
/// restart checkpoint of `src/output/checkpoint.rs`).
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Stepping {
    /// Index of the step of the last converged increment, and the time it
    /// reached.
    pub step: usize,
    pub time: f64,
    /// The size of the next increment within that step (after growth).
    pub increment: f64,
    /// The largest `max(‖f_int‖, ‖f_ext‖)` of the converged increments.
    pub force_scale: f64,
    /// The change of the unknowns over the last increment and its length
    /// (the secant predictor's).
    pub secant: Option<(Vec<f64>, f64)>,
    /// The largest nodal motion of the coupled nodes over the last
    /// increment and its length (the pair search's margin).
    pub last_motion: Option<(f64, f64)>,
    /// The method's warm start (the condensed path's candidates, active
    /// set and last answer), so that it resumes bit for bit.
    pub warm: Option<WarmStart>,
}

impl Stepping {
    /// Whether every number of the stepping state is finite: the time, the
    /// next increment, the force scale, the secant, the last motion and the
    /// warm start.
    pub fn is_finite(&self) -> bool {
        let secant = self
            .secant
            .as_ref()
            .is_none_or(|(du, length)| length.is_finite() && du.iter().all(|x| x.is_finite()));
        let motion = self
            .last_motion
            .is_none_or(|(m, length)| m.is_finite() && length.is_finite());
        [self.time, self.increment, self.force_scale]
            .iter()
            .all(|x| x.is_finite())
            && secant
            && motion
            && self.warm.as_ref().is_none_or(WarmStart::is_finite)
    }
}

/// A converged state to resume a run from: the unknowns, the committed
/// history and the stepper's own state.
#[derive(Clone, Debug)]
pub struct Resume<S> {
    pub unknowns: Vec<f64>,
    pub state: S,
    pub stepping: Stepping,
}

/// What the stepper reports as it goes.
pub trait StepObserver<P: NonlinearProblem> {
    /// An increment converged; `u` holds the new unknowns (displacements,
    /// then contact multipliers), `evaluation` the converged evaluation
    /// (the residual `f_int − f_ext − f_contact`, whose prescribed entries
    /// are the reactions, and the contact reports) and `state` the
    /// committed history. Write output here.
    fn on_converged(
        &mut self,
        problem: &P,
        record: &IncrementRecord,
        u: &[f64],
        evaluation: &Evaluation<P::Report>,
        state: &P::State,
    ) -> Result<()>;
    /// The run's method failed the increment aiming at `time` for
    /// `reason`, and method `by` solves it again before any cut.
    fn on_fallback(&mut self, _step: &str, _time: f64, _by: &str, _reason: &IncrementFailure) {}
    /// The increment aiming at `time` left the contact pairs it was
    /// searched with ([`IncrementFailure::PairsMoved`]): they are searched
    /// again, with those its answer reaches, and the same increment is
    /// solved again, before any cut.
    fn on_search_again(&mut self, _step: &str, _time: f64) {}
    /// An increment failed and is cut.
    fn on_cut(&mut self, _step: &str, _time: f64, _increment: f64, _reason: &IncrementFailure) {}
    /// A Newton iteration of the increment aiming at `time` took its
    /// correction.
    fn on_iteration(&mut self, _step: &str, _time: f64, _record: &IterationRecord) {}
    /// Whether the run is to stop now (asked between Newton iterations and
    /// before every increment); the run then ends with
    /// [`Error::Interrupted`], every converged increment kept.
    fn cancelled(&mut self) -> bool {
        false
    }
    /// An increment converged: the stepper's state after it (told just
    /// before [`on_converged`](Self::on_converged), with which a run can
    /// resume from it) and the linear solver's figures so far.
    fn on_stepping(&mut self, _stepping: &Stepping, _statistics: &SolverStatistics) {}
}

/// Run every step of `problem` from `u = 0` (except the prescribed values)
/// by Newton on the whole system ([`Monolithic`]). Returns the final
/// displacement. `problem` is mutable for the contact pairs of deformable
/// interfaces, searched again at the start of every increment attempt (and
/// the sparsity pattern with them).
pub fn run_steps<P: NonlinearProblem>(
    problem: &mut P,
    solver: &mut dyn LinearSolver,
    observer: &mut dyn StepObserver<P>,
    output: PathBuf,
) -> Result<Vec<f64>> {
    let mut josephy = Josephy::default();
    let repatterned = problem.newton_pattern();
    let mut newton = Monolithic::new(problem, solver, &mut josephy);
    if repatterned {
        newton.pattern_changed(problem)?;
    }
    resume_steps(problem, &mut newton, None, observer, output, None)
}

/// [`run_steps`] with `method` solving each increment (and `fallback`
/// retrying an increment that `method` failed, before any cut), from a
/// converged increment `from` (`None`: from the start): the steps before
/// `from.stepping.step` are skipped, the step in progress goes on from its
/// time with its next increment size (and the method from its warm start),
/// and every later increment is the one an uninterrupted run would have
/// taken. `from.unknowns` has the pattern's dimension (the caller checks
/// it).
pub fn resume_steps<P: NonlinearProblem>(
    problem: &mut P,
    method: &mut dyn IncrementMethod<P>,
    mut fallback: Option<&mut dyn IncrementMethod<P>>,
    observer: &mut dyn StepObserver<P>,
    output: PathBuf,
    from: Option<Resume<P::State>>,
) -> Result<Vec<f64>> {
    let resuming = from.is_some();
    let (mut u, mut state, resumed) = match from {
        Some(r) => (r.unknowns, r.state, r.stepping),
        None => {
            let mut u = vec![0.0; problem.pattern().dimension()];
            problem.apply_prescribed(0.0, &mut u);
            let state = problem.initial_state(&u);
            (u, state, Stepping::default())
        }
    };
    if let Some(warm) = &resumed.warm {
        method.resume(problem, warm)?;
    }
    let mut any_converged = resuming;
    let mut trial = Vec::with_capacity(u.len());
    let mut t = resumed.time;
    let mut force_scale = resumed.force_scale;
    // largest nodal displacement of the last converged increment, and its length
    let mut last_motion: Option<(f64, f64)> = resumed.last_motion;
    let steps = problem.steps().to_vec();
    // the change of the unknowns over the last converged increment, and its
    // length (the predictor's secant)
    let mut secant: Option<(Vec<f64>, f64)> = resumed.secant;
    let statistics = |method: &dyn IncrementMethod<P>,
                      fallback: &Option<&mut dyn IncrementMethod<P>>| {
        method.statistics()
            + fallback
                .as_ref()
                .map(|f| f.statistics())
                .unwrap_or_default()
    };
    // the LU solves counted when the last increment converged
    let mut lu_solves = statistics(method, &fallback).lu_solves;
    for (s, step) in steps.iter().enumerate() {
        if resuming && s < resumed.step {
            continue;
        }
        let mut dt = if resuming && s == resumed.step {
            resumed.increment
        } else {
            step.initial_increment.min(step.end_time - t)
        };
        let mut cuts = 0;
        // every cut of the step (summary.json's steps[].cuts)
        let mut step_cuts = 0u32;
        // an answer that left its pairs, the increment's pairs then
        // searched again with those it reaches ([`search_again`])
        let mut reached: Option<Vec<f64>> = None;
        while t < step.end_time - 1e-12 * step.end_time.abs().max(1.0) {
            let t_new;
            (dt, t_new) = next_increment(step, t, dt);
            let motion = search_motion(problem, &*method, last_motion, (t, t_new), &u);
            if problem.refresh_pattern(&u, motion, reached.as_deref()) {
                method.pattern_changed(problem)?;
                if let Some(f) = fallback.as_deref_mut() {
                    f.pattern_changed(problem)?;
                }
            }
            if observer.cancelled() {
                return Err(cancelled(t));
            }
            let increment = Increment {
                step,
                start: t,
                time: t_new,
                force_scale,
                secant: secant.as_ref(),
            };
            let mut trial_state = state.clone();
            let Tried {
                outcome,
                iterations,
                solved_by,
                retried,
            } = attempt_with_fallback(
                problem,
                (method, &mut fallback),
                &increment,
                (&u, &state),
                &mut trial_state,
                &mut trial,
                observer,
            );
            let problem: &P = problem;
            match outcome {
                Ok(evaluation) => {
                    reached = None;
                    last_motion = Some((coupled_motion(problem, &trial, &u), t_new - t));
                    let change = trial.iter().zip(&u).map(|(a, b)| a - b).collect();
                    secant = Some((change, t_new - t));
                    std::mem::swap(&mut u, &mut trial);
                    problem.commit(t_new, &u, &mut trial_state);
                    state = trial_state;
                    force_scale = force_scale.max(evaluation.force_scale());
                    any_converged = true;
                    let totals = statistics(method, &fallback);
                    let record = IncrementRecord {
                        step: s,
                        step_name: step.name.clone(),
                        time: t_new,
                        increment: t_new - t,
                        // corrections solved: every record but the converged
                        // evaluation that ends each Newton solve (one per
                        // outer-loop update, plus the first)
                        iterations: iterations.iter().filter(|r| r.correction > 0.0).count(),
                        newton: iterations,
                        cuts,
                        lu_solves: totals.lu_solves - lu_solves,
                        method: solved_by,
                        retried,
                    };
                    lu_solves += record.lu_solves;
                    t = t_new;
                    dt = grown(method, &record, problem.settings(), dt, step);
                    cuts = 0;
                    let stepping = Stepping {
                        step: s,
                        time: t,
                        increment: dt,
                        force_scale,
                        secant: secant.clone(),
                        last_motion,
                        warm: method.warm_start(),
                    };
                    observer.on_stepping(&stepping, &totals);
                    observer.on_converged(problem, &record, &u, &evaluation, &state)?;
                }
                Err(IncrementFailure::Cancelled) => return Err(cancelled(t)),
                Err(IncrementFailure::LinearSolverSetUp(message)) => {
                    return Err(Error::LinearSolver(message))
                }
                Err(failure) => {
                    if reached.is_none() && search_again(&failure, &trial) {
                        reached = Some(trial.clone());
                        observer.on_search_again(&step.name, t_new);
                        continue;
                    }
                    reached = None;
                    let at_smallest = 0.5 * dt < step.min_increment;
                    if cuts >= problem.settings().max_cuts || at_smallest {
                        return Err(Error::NoConvergence {
                            step: step.name.clone(),
                            time: t_new,
                            cuts: cuts as u32,
                            step_cuts,
                            at_smallest,
                            increment: dt,
                            reason: failure.to_string(),
                            last_converged_time: any_converged.then_some(t),
                            output,
                        });
                    }
                    observer.on_cut(&step.name, t_new, dt, &failure);
                    cuts += 1;
                    step_cuts += 1;
                    dt *= 0.5;
                }
            }
        }
    }
    Ok(u)
}

/// The next increment's size after the converged `record` of size `dt`:
/// grown by the growth factor (up to the step's largest increment) where
/// it needed no cut and the method that solved it found it easy (the
/// fallback by Newton's measure), else `dt`.
fn grown<P: NonlinearProblem>(
    method: &dyn IncrementMethod<P>,
    record: &IncrementRecord,
    settings: &SolverSettings,
    dt: f64,
    step: &Step,
) -> f64 {
    let grows = if record.method == method.name() {
        method.grows(&record.newton, settings.easy_iterations)
    } else {
        converged_well(&record.newton, settings.easy_iterations)
    };
    if record.cuts == 0 && grows {
        (dt * settings.growth_factor).min(step.max_increment)
    } else {
        dt
    }
}

/// What an increment's attempts gave: the outcome and iterations of the
/// last attempt, the name of the method that made it, and the failure
/// that sent the increment to the fallback (`None`: no retry).
struct Tried<R> {
    outcome: Result<Evaluation<R>, IncrementFailure>,
    iterations: Vec<IterationRecord>,
    solved_by: &'static str,
    retried: Option<String>,
}

/// [`attempt`] by the first of `methods`, and where it fails (but for a
/// failure no cut mends, [`IncrementFailure::mended_by_a_cut`]) once more
/// by the second, the fallback, from the converged
/// `start` (unknowns and state) again, on Newton's pattern
/// ([`NonlinearProblem::newton_pattern`]); the observer is told of the
/// retry.
#[allow(clippy::too_many_arguments)]
fn attempt_with_fallback<P: NonlinearProblem>(
    problem: &mut P,
    methods: (
        &mut dyn IncrementMethod<P>,
        &mut Option<&mut dyn IncrementMethod<P>>,
    ),
    increment: &Increment<'_>,
    start: (&[f64], &P::State),
    trial_state: &mut P::State,
    trial: &mut Vec<f64>,
    observer: &mut dyn StepObserver<P>,
) -> Tried<P::Report> {
    let (method, fallback) = methods;
    let (u, state) = start;
    let (outcome, iterations) =
        attempt(problem, method, increment, u, trial_state, trial, observer);
    let first = Tried {
        outcome,
        iterations,
        solved_by: method.name(),
        retried: None,
    };
    let (Err(failure), Some(f)) = (&first.outcome, fallback.as_deref_mut()) else {
        return first;
    };
    // the fallback would solve it on the same pairs
    if !failure.mended_by_a_cut() || matches!(failure, IncrementFailure::PairsMoved) {
        return first;
    }
    let (step, time) = (&increment.step.name, increment.time);
    observer.on_fallback(step, time, f.name(), failure);
    let retried = Some(failure.to_string());
    if problem.newton_pattern() {
        let ordered = (method.pattern_changed(problem)).and_then(|()| f.pattern_changed(problem));
        if let Err(e) = ordered {
            let outcome = Err(IncrementFailure::LinearSolverSetUp(e.to_string()));
            return Tried {
                outcome,
                retried,
                ..first
            };
        }
    }
    *trial_state = state.clone();
    let (outcome, iterations) = attempt(problem, f, increment, u, trial_state, trial, observer);
    Tried {
        outcome,
        iterations,
        solved_by: f.name(),
        retried,
    }
}

/// Whether the increment whose answer `trial` failed by `failure` is
/// solved again before any cut, on the pairs of its start and those a
/// search at `trial` finds: where the answer left the pairs it was
/// searched with ([`IncrementFailure::PairsMoved`]: a node reached faces
/// the search at the start did not pair it with, bodies that start apart
/// and close within the increment). Once per increment (the caller):
/// where the answer on those pairs leaves them too, the increment is cut.
fn search_again(failure: &IncrementFailure, trial: &[f64]) -> bool {
    matches!(failure, IncrementFailure::PairsMoved) && trial.iter().all(|x| x.is_finite())
}

/// The motion `d` the search at the start of the increment `(t, t_new)`
/// from `u` covers (`src/contact/primary.rs`, search rule): the last
/// converged increment's `(motion, length)` scaled to this one, else, on
/// Newton's path, the increment's prescribed motion ([`prescribed_motion`]).
fn search_motion<P: NonlinearProblem>(
    problem: &P,
    method: &dyn IncrementMethod<P>,
    last_motion: Option<(f64, f64)>,
    (t, t_new): (f64, f64),
    u: &[f64],
) -> f64 {
    match last_motion {
        Some((m, last_dt)) => m * (t_new - t) / last_dt,
        None if method.first_search_covers_prescribed_motion() => {
            prescribed_motion(problem, t_new, u)
        }
        None => 0.0,
    }
}

/// The largest change of a prescribed displacement over the increment
/// from `u` to time `t_new`: the motion the run's first search covers on
/// Newton's path, before any increment has measured one
/// ([`IncrementMethod::first_search_covers_prescribed_motion`]).
fn prescribed_motion<P: NonlinearProblem>(problem: &P, t_new: f64, u: &[f64]) -> f64 {
    let mut target = u.to_vec();
    problem.apply_prescribed(t_new, &mut target);
    (0..problem.num_dofs() / 3)
        .map(|n| node_motion(&target, u, n))
        .fold(0.0f64, f64::max)
}

/// `|a_n − b_n|`: how far node `n` moves from `b` to `a`.
fn node_motion(a: &[f64], b: &[f64], n: usize) -> f64 {
    (0..3)
        .map(|d| (a[3 * n + d] - b[3 * n + d]).powi(2))
        .sum::<f64>()
        .sqrt()
}

/// The largest displacement over an increment, from `u` to `trial`, of
/// the nodes whose couplings (contact pairs) move with them.
fn coupled_motion<P: NonlinearProblem>(problem: &P, trial: &[f64], u: &[f64]) -> f64 {
    (problem.moving_coupled_nodes().into_iter())
        .map(|n| node_motion(trial, u, n))
        .fold(0.0f64, f64::max)
}

/// One attempt at `increment` by `method`, its iterations told to
/// `observer` (which may cancel the run between them); the increment
/// solved is then checked for the contact pairs it was searched with.
#[allow(clippy::too_many_arguments)]
fn attempt<P: NonlinearProblem>(
    problem: &P,
    method: &mut dyn IncrementMethod<P>,
    increment: &Increment<'_>,
    u: &[f64],
    state: &mut P::State,
    trial: &mut Vec<f64>,
    observer: &mut dyn StepObserver<P>,
) -> super::newton::NewtonOutcome<P::Report> {
    let (name, time) = (&increment.step.name, increment.time);
    let mut tell = |record: &IterationRecord| {
        observer.on_iteration(name, time, record);
        !observer.cancelled()
    };
    let (outcome, iterations) = method.solve(problem, increment, u, state, trial, &mut tell);
    let outcome = outcome.and_then(|evaluation| {
        if !problem.couplings_hold(trial, state) {
            Err(IncrementFailure::PairsMoved)
        } else if let Some(failure) =
            problem.passed_through((increment.start, u), (increment.time, trial))
        {
            Err(failure)
        } else {
            Ok(evaluation)
        }
    });
    (outcome, iterations)
}

/// The next increment of `step` from `t` when `dt` is asked for: `dt`
/// bounded by the step's end, the whole rest when less than `dt/4` would
/// remain (no sliver at the end of a step); returns it and its end time
/// (the step's end exactly when it reaches it).
pub fn next_increment(step: &Step, t: f64, dt: f64) -> (f64, f64) {
    let mut dt = dt.min(step.end_time - t);
    if step.end_time - (t + dt) < 0.25 * dt {
        dt = step.end_time - t;
    }
    let t_new = if dt >= step.end_time - t {
        step.end_time
    } else {
        t + dt
    };
    (dt, t_new)
}

/// The error of a run cancelled after the increments converged up to `t`.
fn cancelled(t: f64) -> Error {
    Error::Interrupted {
        reason: format!("cancelled; the increments converged up to time {t:.6} are kept"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solve::backend::linear_solver;
    use crate::solve::linear::Ordering;
    use crate::solve::settings::{Predictor, SolverSettings, Step};
    use crate::solve::springs::{Spring, Springs};

    /// The hardening springs' constants: `r_i = K x_i + C x_i³ − t F_i`.
    const K: f64 = 2.0;
    const C: f64 = 5.0;
    const F: [f64; 3] = [1.0, -3.0, 40.0];

    /// The converged residual of every increment.
    #[derive(Default)]
    struct Residuals(Vec<(f64, Vec<f64>)>);

    impl StepObserver<Springs> for Residuals {
        fn on_converged(
            &mut self,
            _p: &Springs,
            record: &IncrementRecord,
            _u: &[f64],
            evaluation: &Evaluation<()>,
            _state: &(),
        ) -> Result<()> {
            self.0.push((record.time, evaluation.residual.clone()));
            Ok(())
        }
    }

    /// The springs `k x + c x³ = t f` (k = 2, c = 5, f = (1, −3, 40)) in
    /// one step of increments `increment`, solved to a residual of 1e-12.
    fn springs(increment: f64, predictor: Predictor) -> Springs {
        let settings = SolverSettings {
            residual_tolerance: 1e-12,
            predictor,
            ..SolverSettings::default()
        };
        let steps = vec![Step {
            name: "load".into(),
            end_time: 1.0,
            initial_increment: increment,
            min_increment: 1e-3,
            max_increment: increment,
        }];
        let law = |t: f64, i: usize, x: f64| Spring {
            internal: K * x + C * x.powi(3),
            external: t * F[i],
            stiffness: K + 3.0 * C * x * x,
            status: None,
        };
        Springs::new(settings, steps, Box::new(law))
    }

    /// Newton and the stepper solve a problem that is not the finite-element
    /// one: each spring ends at the root of `k x + c x³ = f` (found here by
    /// bisection to 1e-14), and the observer receives the converged
    /// evaluation of every increment, whose residual is within tolerance.
    #[test]
    fn the_stepper_solves_any_nonlinear_problem() {
        let mut springs = springs(0.5, SolverSettings::default().predictor);
        let mut solver = linear_solver(&springs.settings, Ordering::Amd, 1);
        let mut residuals = Residuals::default();
        let x = run_steps(&mut springs, &mut *solver, &mut residuals, PathBuf::new()).unwrap();
        for (xi, fi) in x.iter().zip(F) {
            let (mut lo, mut hi) = (-10.0f64, 10.0f64);
            while hi - lo > 1e-14 {
                let mid = 0.5 * (lo + hi);
                if K * mid + C * mid.powi(3) < fi {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            assert!((xi - lo).abs() < 1e-10, "{xi} vs {lo}");
        }
        assert_eq!(
            residuals.0.iter().map(|r| r.0).collect::<Vec<_>>(),
            [0.5, 1.0]
        );
        for (_, r) in &residuals.0 {
            assert!(super::super::gmres::norm(r) < 1e-10, "{r:?}");
        }
    }

    /// A method that fails every increment ending after `from` (as a
    /// condensed solve whose residual is too large), and solves the others
    /// by Newton.
    struct FailsAfter<'a> {
        newton: Monolithic<'a>,
        from: f64,
    }

    impl IncrementMethod<Springs> for FailsAfter<'_> {
        fn name(&self) -> &'static str {
            "condensed"
        }
        fn solve(
            &mut self,
            problem: &Springs,
            increment: &Increment<'_>,
            u: &[f64],
            state: &mut (),
            x: &mut Vec<f64>,
            on_iteration: &mut dyn FnMut(&IterationRecord) -> bool,
        ) -> super::super::newton::NewtonOutcome<()> {
            if increment.time > self.from {
                let failure = IncrementFailure::CondensedResidual {
                    relative: 1e-6,
                    tolerance: 1e-8,
                };
                return (Err(failure), Vec::new());
            }
            self.newton
                .solve(problem, increment, u, state, x, on_iteration)
        }
        fn statistics(&self) -> SolverStatistics {
            IncrementMethod::<Springs>::statistics(&self.newton)
        }
    }

    /// Which method solved each increment, whether it was retried, and
    /// the fallbacks told.
    #[derive(Default)]
    struct Methods(Vec<(&'static str, bool)>, usize);

    impl StepObserver<Springs> for Methods {
        fn on_converged(
            &mut self,
            _p: &Springs,
            record: &IncrementRecord,
            _u: &[f64],
            _evaluation: &Evaluation<()>,
            _state: &(),
        ) -> Result<()> {
            self.0.push((record.method, record.retried.is_some()));
            Ok(())
        }
        fn on_fallback(&mut self, _: &str, _: f64, by: &str, _: &IncrementFailure) {
            assert_eq!(by, "monolithic");
            self.1 += 1;
        }
    }

    /// An increment the run's method fails is solved again by the
    /// fallback before any cut: the springs end at their roots (1e-10),
    /// the increments are the ones of an undisturbed run (no cut), and
    /// each retried increment says so.
    #[test]
    fn the_fallback_solves_what_the_method_fails_without_a_cut() {
        let mut springs = springs(0.25, SolverSettings::default().predictor);
        let mut first = linear_solver(&springs.settings, Ordering::Amd, 1);
        let mut second = linear_solver(&springs.settings, Ordering::Amd, 1);
        let (mut j1, mut j2) = (Josephy::default(), Josephy::default());
        let mut method = FailsAfter {
            newton: Monolithic::new(&springs, &mut *first, &mut j1),
            from: 0.5,
        };
        let mut fallback = Monolithic::new(&springs, &mut *second, &mut j2);
        let mut methods = Methods::default();
        let x = resume_steps(
            &mut springs,
            &mut method,
            Some(&mut fallback),
            &mut methods,
            PathBuf::new(),
            None,
        )
        .unwrap();
        let mut reference = Residuals::default();
        let mut solver = linear_solver(&springs.settings, Ordering::Amd, 1);
        let y = run_steps(&mut springs, &mut *solver, &mut reference, PathBuf::new()).unwrap();
        for (a, b) in x.iter().zip(&y) {
            assert!((a - b).abs() < 1e-10, "{a} vs {b}");
        }
        assert_eq!(
            methods.0,
            [
                ("condensed", false),
                ("condensed", false),
                ("monolithic", true),
                ("monolithic", true)
            ]
        );
        assert_eq!(methods.1, 2);
    }

    /// Iteration records from residuals, switch counts and step lengths.
    fn records(residuals: &[f64], switched: &[usize], steps: &[f64]) -> Vec<IterationRecord> {
        (0..residuals.len())
            .map(|k| IterationRecord {
                residual: residuals[k],
                correction: 0.0,
                step_length: steps.get(k).copied().unwrap_or(0.0),
                switched: switched[k],
                linear: Default::default(),
            })
            .collect()
    }

    /// An increment grows the next one after at most `easy` iterations, or
    /// after a contact set that settled early followed by a fast rate —
    /// not after late switches, a slow rate or line-searched steps.
    #[test]
    fn growth_follows_the_rate_once_the_statuses_settle() {
        let full = [1.0; 8];
        // 7 iterations: switches in the first two, then quadratic: grows
        // (the iteration count alone, > 5, would not)
        let r = [1.0, 0.3, 0.05, 2e-3, 4e-6, 1e-10, 1e-12, 1e-16];
        let settled = records(&r, &[0, 4, 2, 0, 0, 0, 0, 0], &full);
        assert!(converged_well(&settled, 5));
        // the same residuals with a switch at iteration 6: the contact set
        // was still searched, no growth
        assert!(!converged_well(
            &records(&r, &[0, 4, 2, 0, 0, 0, 1, 0], &full),
            5
        ));
        // a line-searched step after settling: no growth
        let mut damped = full;
        damped[4] = 0.5;
        assert!(!converged_well(
            &records(&r, &[0, 4, 2, 0, 0, 0, 0, 0], &damped),
            5
        ));
        // settled at once but a linear rate of 0.3: no growth
        let slow: Vec<f64> = (0..8).map(|k| 0.3f64.powi(k)).collect();
        assert!(!converged_well(&records(&slow, &[0; 8], &full), 5));
        // five iterations or fewer: easy whatever the rate
        assert!(converged_well(&records(&slow[..6], &[0; 6], &full), 5));
    }

    /// Newton iterations of every converged increment.
    #[derive(Default)]
    struct Iterations(Vec<usize>);

    impl StepObserver<Springs> for Iterations {
        fn on_converged(
            &mut self,
            _p: &Springs,
            record: &IncrementRecord,
            _u: &[f64],
            _evaluation: &Evaluation<()>,
            _state: &(),
        ) -> Result<()> {
            self.0.push(record.iterations);
            Ok(())
        }
    }

    /// The secant predictor changes Newton's path, not the answer: the
    /// springs `k x + c x³ = t f` in ten increments end at the same roots
    /// (1e-12) in fewer Newton iterations than from the converged state.
    #[test]
    fn the_secant_predictor_saves_iterations_and_keeps_the_solution() {
        let solve = |predictor: Predictor| {
            let mut springs = springs(0.1, predictor);
            let mut solver = linear_solver(&springs.settings, Ordering::Amd, 1);
            let mut iterations = Iterations::default();
            let x = run_steps(&mut springs, &mut *solver, &mut iterations, PathBuf::new()).unwrap();
            (x, iterations.0)
        };
        let (x0, plain) = solve(Predictor::None);
        let (x1, secant) = solve(Predictor::Secant);
        for (a, b) in x0.iter().zip(&x1) {
            assert!((a - b).abs() < 1e-12, "{a} vs {b}");
        }
        assert_eq!((plain.len(), secant.len()), (10, 10));
        let (p, q): (usize, usize) = (plain.iter().sum(), secant.iter().sum());
        assert!(q < p, "secant {secant:?} vs {plain:?}");
    }
}
