//! The recorder between the stepper and the observers: it turns each
//! converged increment into the in-memory results the observers read
//! ([`ConvergedIncrement`]), keeps the run's [`Summary`] and its totals, and
//! ends the run with its status.

use super::restart::Restart;
use super::RunOutcome;
use crate::contact::interface::NodeReport;
use crate::output::contact_fields::ContactFields;
use crate::output::fields::ConvergedIncrement;
use crate::output::observer::{Cut, Iteration, Observers, StepObserver as _};
use crate::output::summary::{IncrementSummary, PhaseTimes, StepSummary, Summary};
use crate::problem::{ContactState, Problem};
use crate::solve::failure::IncrementFailure;
use crate::solve::linear_solver::SolverStatistics;
use crate::solve::newton::IterationRecord;
use crate::solve::nonlinear::Evaluation;
use crate::solve::stepping::{self, IncrementRecord, Resume, Stepping};
use crate::{Error, Result};
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::Instant;

/// Turns the stepper's converged increments into the in-memory results that
/// observers read, and keeps the run's summary.
pub(super) struct Recorder<'a> {
    pub(super) summary: Summary,
    pub(super) observers: Observers<'a>,
    pub(super) name: String,
    /// `vtu`, or `pvtu` in a distributed run.
    pub(super) extension: &'static str,
    pub(super) every: usize,
    pub(super) cancel: Option<Arc<AtomicBool>>,
    pub(super) last: Instant,
    pub(super) start: Instant,
    pub(super) contact: ContactState,
    /// The stepper's state after the last converged increment, and the
    /// linear solver's figures then.
    pub(super) stepping: Stepping,
    pub(super) statistics: SolverStatistics,
    /// After a restart: the summary of the checkpoint, whose run totals
    /// the resumed run's add to.
    pub(super) earlier: Option<Summary>,
}

impl<'a> Recorder<'a> {
    /// A recorder at the start of a run (the clock starts now), passing the
    /// increments on to `observers`; a VTU file at every increment unless
    /// [`every`](Self::every) says otherwise.
    pub(super) fn new(
        case_label: &str,
        problem: &Problem,
        observers: Observers<'a>,
        name: &str,
    ) -> Self {
        let start = Instant::now();
        Recorder {
            summary: Summary::start(case_label, problem),
            observers,
            name: name.to_string(),
            extension: "vtu",
            every: 1,
            cancel: None,
            last: start,
            start,
            contact: ContactState::default(),
            stepping: Stepping::default(),
            statistics: SolverStatistics::default(),
            earlier: None,
        }
    }

    /// Take over a restart's summary and state (the run's clock counts the
    /// earlier run's time too); what the stepper resumes from.
    pub(super) fn restore(&mut self, restart: Restart) -> Resume<ContactState> {
        let Restart {
            resume,
            mut summary,
            increments,
            dir,
            ..
        } = restart;
        let stepping = &resume.stepping;
        self.observers.on_message(&format!(
            "restart: resuming from the checkpoint in {} after increment {increments} \
             (step '{}', t = {})",
            dir.display(),
            summary
                .increments
                .last()
                .map_or("", |i| i.step_name.as_str()),
            stepping.time
        ));
        summary.status = "running".into();
        summary.error = None;
        summary.threads = rayon::current_num_threads();
        self.earlier = Some(summary.clone());
        self.summary = summary;
        self.contact.clone_from(&resume.state);
        self.stepping.clone_from(&resume.stepping);
        resume
    }

    /// The end of a run: its status in the summary, the observers told,
    /// the outcome (or the error that ended the run, every converged
    /// increment kept).
    pub(super) fn finish(
        mut self,
        result: Result<Vec<f64>>,
        output: PathBuf,
    ) -> Result<RunOutcome> {
        match result {
            Ok(displacement) => {
                self.summary.status = "completed".into();
                self.observers.on_finish(&self.summary)?;
                Ok(RunOutcome {
                    output_dir: output,
                    summary: self.summary,
                    displacement,
                    contact: self.contact,
                })
            }
            Err(mut e) => {
                self.count_failed_cuts(&mut e);
                self.summary.status = match e {
                    Error::Interrupted { .. } => "interrupted",
                    _ => "failed",
                }
                .into();
                self.summary.error = Some(e.to_string());
                // keep what converged; the original error matters more than a
                // failure to write the failure report
                let _ = self.observers.on_finish(&self.summary);
                Err(e)
            }
        }
    }
}

impl Recorder<'_> {
    /// A failed increment's cuts added to its step's in the summary
    /// (`steps[].cuts`, a new entry if no increment of the step
    /// converged), and the error's count of the step's cuts set to that
    /// total, so that the message and `summary.json` agree (after a
    /// restart, the earlier run's cuts included).
    fn count_failed_cuts(&mut self, e: &mut Error) {
        let Error::NoConvergence {
            step,
            cuts,
            step_cuts,
            ..
        } = e
        else {
            return;
        };
        let reached = self.summary.increments.last().map_or(0.0, |i| i.time);
        let steps = &mut self.summary.steps;
        if steps.last().is_none_or(|s| s.name != *step) {
            steps.push(StepSummary {
                name: step.clone(),
                time: reached,
                increments: 0,
                iterations: 0,
                cuts: 0,
                wall_time: 0.0,
            });
        }
        if let Some(s) = steps.last_mut() {
            s.cuts += *cuts as usize;
            *step_cuts = s.cuts as u32;
        }
    }
}

/// The run's totals in the summary so far ([`record_totals`]), with those
/// of the run a restart resumed (`earlier`) added: in `summary.json` after
/// every increment, and so in the checkpoint.
pub(super) fn update_totals(
    summary: &mut Summary,
    problem: &Problem,
    statistics: &SolverStatistics,
    start: Instant,
    earlier: Option<&Summary>,
) {
    record_totals(summary, problem, statistics, start);
    if let Some(earlier) = earlier {
        add_earlier_totals(summary, earlier);
    }
}

/// After a restart: the run totals of the earlier run (`earlier`, the
/// checkpoint's summary) added to the resumed run's (wall time included).
fn add_earlier_totals(summary: &mut Summary, earlier: &Summary) {
    summary.symbolic_analyses += earlier.symbolic_analyses;
    let (t, e) = (&mut summary.phase_times, &earlier.phase_times);
    t.assembly += e.assembly;
    t.contact += e.contact;
    t.symbolic += e.symbolic;
    t.factorisation += e.factorisation;
    t.solve += e.solve;
    t.petsc_setup = sum_present(t.petsc_setup, e.petsc_setup);
    t.petsc_solve = sum_present(t.petsc_solve, e.petsc_solve);
    summary.krylov_solves += earlier.krylov_solves;
    summary.krylov_iterations += earlier.krylov_iterations;
    summary.lu_solves += earlier.lu_solves;
    summary.factorisations += earlier.factorisations;
    summary.single_factorisations += earlier.single_factorisations;
    summary.refinement_steps += earlier.refinement_steps;
    summary.mixed_precision_fallbacks += earlier.mixed_precision_fallbacks;
    summary.wall_time += earlier.wall_time;
}

/// The sum of the times present (`None` when neither is).
fn sum_present(a: Option<f64>, b: Option<f64>) -> Option<f64> {
    a.into_iter().chain(b).reduce(|a, b| a + b)
}

/// The run's totals in the summary: where the time went and what the
/// linear solver did.
fn record_totals(
    summary: &mut Summary,
    problem: &Problem,
    statistics: &SolverStatistics,
    start: Instant,
) {
    summary.symbolic_analyses = statistics.analyses;
    summary.phase_times = PhaseTimes {
        assembly: problem.timings.assembly(),
        contact: problem.timings.contact(),
        symbolic: statistics.symbolic.as_secs_f64(),
        factorisation: statistics.factorisation.as_secs_f64(),
        solve: statistics.solve.as_secs_f64(),
        petsc_setup: None,
        petsc_solve: None,
    };
    // PETSc's set-up and solve, in runs on PETSc only
    if !(statistics.petsc_setup + statistics.petsc_solve).is_zero() {
        summary.phase_times.petsc_setup = Some(statistics.petsc_setup.as_secs_f64());
        summary.phase_times.petsc_solve = Some(statistics.petsc_solve.as_secs_f64());
    }
    summary.factor_nnz = statistics.factor_nnz;
    summary.krylov_solves = statistics.krylov_solves;
    summary.krylov_iterations = statistics.krylov_iterations;
    summary.lu_solves = statistics.lu_solves;
    summary.factorisations = statistics.factorisations + statistics.single_factorisations;
    summary.single_factorisations = statistics.single_factorisations;
    summary.refinement_steps = statistics.refinement_steps;
    summary.mixed_precision_fallbacks = statistics.mixed_precision_fallbacks;
    summary.wall_time = start.elapsed().as_secs_f64();
}

impl stepping::StepObserver<Problem> for Recorder<'_> {
    fn on_converged(
        &mut self,
        problem: &Problem,
        record: &IncrementRecord,
        u: &[f64],
        evaluation: &Evaluation<Vec<Vec<NodeReport>>>,
        contact: &ContactState,
    ) -> Result<()> {
        let previous = std::mem::replace(&mut self.contact, contact.clone());
        let increment = ConvergedIncrement {
            problem,
            record,
            unknowns: u,
            residual: &evaluation.residual,
            contact,
            stepping: &self.stepping,
            contact_fields: ContactFields::new(
                problem,
                u,
                contact,
                &previous,
                evaluation.reports.clone(),
            ),
        };
        let now = Instant::now();
        // deformable contact may have rebuilt the pattern with new pairs
        self.summary.matrix_nnz = problem.model.pattern.nnz();
        let index = self.summary.increments.len() + 1;
        let end_of_step = record.time == problem.steps[record.step].end_time;
        let file = if index.is_multiple_of(self.every) || end_of_step {
            format!("{}_{index:04}.{}", self.name, self.extension)
        } else {
            String::new()
        };
        self.summary.increments.push(IncrementSummary {
            step: record.step,
            step_name: record.step_name.clone(),
            time: record.time,
            increment: record.increment,
            iterations: record.iterations,
            residuals: record.newton.iter().map(|r| r.residual).collect(),
            corrections: record.newton.iter().map(|r| r.correction).collect(),
            cuts: record.cuts,
            wall_time: (now - self.last).as_secs_f64(),
            switched: record.newton.iter().map(|r| r.switched).collect(),
            contact: increment.contact_fields.summaries.clone(),
            file,
            reaction_forces: increment.reaction_forces().into_iter().collect(),
            method: record.method.into(),
            retried: record.retried.clone(),
        });
        self.summary.fallback_increments += usize::from(record.retried.is_some());
        // the condensed path's iterations are its contact solve's steps
        if record.method == crate::problem::condensed::Path::Condensed.name() {
            self.summary.active_set_iterations += record.iterations;
        }
        self.summary.add_last_to_step_totals();
        self.last = now;
        // the totals so far (fields apart: `increment` borrows `stepping`)
        let earlier = self.earlier.as_ref();
        update_totals(
            &mut self.summary,
            problem,
            &self.statistics,
            self.start,
            earlier,
        );
        self.observers.on_increment(&increment, &self.summary)
    }

    fn on_stepping(&mut self, stepping: &Stepping, statistics: &SolverStatistics) {
        self.stepping.clone_from(stepping);
        self.statistics = *statistics;
    }

    fn cancelled(&mut self) -> bool {
        self.cancel
            .as_ref()
            .is_some_and(|c| c.load(Ordering::Relaxed))
    }

    fn on_iteration(&mut self, step: &str, time: f64, record: &IterationRecord) {
        self.observers
            .on_iteration(&Iteration { step, time, record });
    }

    fn on_fallback(&mut self, step: &str, time: f64, by: &str, reason: &IncrementFailure) {
        self.observers.on_message(&format!(
            "step '{step}'  t = {time:.6}: the condensed path failed the increment ({reason}); \
             solving it again on the {by} path"
        ));
    }

    fn on_search_again(&mut self, step: &str, time: f64) {
        self.observers.on_message(&format!(
            "step '{step}'  t = {time:.6}: {}; searching the contact pairs again where its \
             answer reached and solving it again",
            IncrementFailure::PairsMoved
        ));
    }

    fn on_cut(&mut self, step: &str, time: f64, increment: f64, reason: &IncrementFailure) {
        self.observers.on_cut(&Cut {
            step,
            time,
            increment,
            reason,
        });
    }
}
