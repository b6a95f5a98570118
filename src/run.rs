//! A whole run through the library: a [`Simulation`] built from a case
//! (a file, a string, or a [`Case`] assembled in code around a mesh given as
//! arrays) runs its steps and tells a [`StepObserver`] about every converged
//! increment, in memory. The library prints nothing and writes files only
//! into the output folder it is given ([`RunOptions::output`]); the command
//! line adds its progress bar as another observer.
//!
//! ```
//! use signorini::output::{ConvergedIncrement, StepObserver, Summary};
//! use signorini::run::{RunOptions, Simulation};
//!
//! /// Keeps the normal contact force of every converged increment.
//! struct Forces(Vec<f64>);
//! impl StepObserver for Forces {
//!     fn on_increment(&mut self, inc: &ConvergedIncrement, _: &Summary) -> signorini::Result<()> {
//!         self.0.push(inc.contact_fields.summaries["base"].force[2]);
//!         Ok(())
//!     }
//! }
//!
//! let mut simulation = Simulation::from_file("examples/press-pull/case.toml".as_ref())?;
//! let options = RunOptions { threads: Some(2), ..Default::default() }; // in memory only
//! let mut forces = Forces(Vec::new());
//! let outcome = simulation.run(&options, &mut forces)?;
//! // the press of 20 (20 on 1 × 2, examples/press-pull/README.md) is carried by contact
//! assert!((forces.0.last().unwrap() - 20.0).abs() < 1e-9);
//! assert_eq!(forces.0.len(), outcome.summary.increments.len());
//! # Ok::<(), signorini::Error>(())
//! ```

use crate::case::{self, output::OutputRequests, Case};
use crate::contact::interface::NodeReport;
use crate::output::checkpoint::{self, CaseKey, Fnv1a};
use crate::output::contact_fields::ContactFields;
use crate::output::describe::describe_model;
use crate::output::fields::{CellField, ConvergedIncrement, NodalField};
use crate::output::log::LogWriter;
use crate::output::observer::Iteration;
use crate::output::observer::{Cut, Observers, StepObserver};
use crate::output::summary::{IncrementSummary, PhaseTimes, Summary};
use crate::output::writer::{Restored, ResultWriter, SeriesContent};
use crate::problem::condensed::{self, Path as SolvePath};
use crate::problem::{ContactState, Problem};
use crate::solve::backend::try_linear_solver;
use crate::solve::failure::IncrementFailure;
use crate::solve::linear_solver::SolverStatistics;
use crate::solve::newton::IterationRecord;
use crate::solve::nonlinear::Evaluation;
use crate::solve::stepping::{self, resume_steps, IncrementRecord, Resume, Stepping};
use crate::{Error, Result};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::Instant;

/// How a simulation runs.
#[derive(Clone, Debug, Default)]
pub struct RunOptions {
    /// The folder for the result files (VTU, PVD, `summary.json`, plots);
    /// `None`: nothing is written, the results reach the observer only.
    pub output: Option<PathBuf>,
    /// Worker threads of assembly and factorisation, in a thread pool of
    /// the run's own (`None`: one per core).
    pub threads: Option<usize>,
    /// Set it (from another thread, a signal handler) to stop the run
    /// between two Newton iterations: the run ends with
    /// [`Error::Interrupted`], `summary.json` says `"interrupted"`, and
    /// every converged increment stays written.
    pub cancel: Option<Arc<AtomicBool>>,
    /// Resume from the checkpoint (`NAME.checkpoint`) of the run whose
    /// output folder this is, instead of starting at `t = 0`: the run goes
    /// on from its last converged increment to the state an uninterrupted
    /// run reaches, and its results go on in that folder (the `.pvd` lists
    /// the earlier VTU files, `summary.json` and the histories keep their
    /// earlier increments). `output` must then be that folder or `None`
    /// (in memory only; [`run`] writes into it).
    pub restart: Option<PathBuf>,
}

/// What a finished run leaves.
#[derive(Debug)]
pub struct RunOutcome {
    /// The output folder (empty when the run wrote no files).
    pub output_dir: PathBuf,
    pub summary: Summary,
    /// Final displacement of every dof.
    pub displacement: Vec<f64>,
    /// Contact history committed with the last converged increment
    /// (Uzawa multipliers, slack unknowns, friction's tangential traction
    /// and slip).
    pub contact: ContactState,
}

/// A problem ready to run, with what its output asks for.
pub struct Simulation {
    problem: Problem,
    /// The case file (for the summary and messages).
    case_label: String,
    /// The file-name stem of the VTU series.
    name: String,
    /// The case's own output folder (`[output] folder`, beside the case).
    default_output: PathBuf,
    requests: OutputRequests,
    nodal_fields: Vec<NodalField>,
    cell_fields: Vec<CellField>,
    /// A VTU file every this many increments (and at the end of each step).
    every: usize,
    /// zlib compression of the VTU arrays.
    compress: bool,
    /// Notes on reading the case for the user (the ignored keywords of an
    /// `.inp` deck), told to the observers at the start of a run.
    notes: Vec<String>,
    /// Monolithic or condensed (`[solver] strategy`), and why.
    strategy: condensed::Choice,
    /// The model's likely causes of non-convergence
    /// ([`Case::diagnose`](case::Case::diagnose)), told at the start and
    /// named in the error of a failed run.
    warnings: Vec<String>,
    /// What ties a checkpoint to this case.
    case_key: CaseKey,
}

/// What a restart resumes from: the checkpoint's state and output.
struct Restart {
    resume: Resume<ContactState>,
    summary: Summary,
    histories: Vec<Vec<(f64, Vec<f64>)>>,
    profiles: Vec<Vec<crate::output::profile::StepProfile>>,
    /// The increments in the checkpoint, and the folder it was read from.
    increments: usize,
    dir: PathBuf,
}

impl Simulation {
    /// From a case: builds the problem and validates the output requests.
    pub fn from_case(case: &Case) -> Result<Self> {
        let problem = case.build_problem()?;
        let requests = case.output_requests(&problem)?;
        let (nodal_fields, cell_fields) = case.output_fields();
        let every = case.output_every()?;
        let strategy = condensed::choose(&problem).map_err(|message| Error::Case {
            path: case.path.clone(),
            message,
        })?;
        let case_key = CaseKey {
            nodes: problem.model.mesh.num_nodes(),
            dofs: problem.model.num_dofs(),
            unknowns: problem.num_unknowns(),
            physics: physics_hash(case),
            steps: problem
                .steps
                .iter()
                .map(|s| (s.name.clone(), s.end_time))
                .collect(),
        };
        Ok(Simulation {
            case_label: case.path.display().to_string(),
            name: case.output_name(),
            default_output: case.output_dir(None),
            requests,
            nodal_fields,
            cell_fields,
            every,
            compress: case.spec.output.compress.unwrap_or(true),
            notes: case.notes.clone(),
            strategy,
            warnings: case.diagnose(&problem),
            case_key,
            problem,
        })
    }

    /// From a case file (and the mesh it names).
    pub fn from_file(path: &Path) -> Result<Self> {
        Self::from_case(&case::load(path)?)
    }

    /// From a case file's text; its paths (the mesh, `[output] folder`) are
    /// relative to `base_dir`.
    pub fn from_toml(text: &str, base_dir: &Path) -> Result<Self> {
        Self::from_case(&case::from_toml(text, base_dir)?)
    }

    /// The problem as built.
    pub fn problem(&self) -> &Problem {
        &self.problem
    }

    /// The problem, to adjust before [`run`](Self::run) (the strategy
    /// chosen when it was built stays).
    pub fn problem_mut(&mut self) -> &mut Problem {
        &mut self.problem
    }

    /// The case's output folder (`[output] folder` relative to the case
    /// file, or `results` beside it).
    pub fn default_output_dir(&self) -> &Path {
        &self.default_output
    }

    /// Run every step: each converged increment goes to `observer` (and,
    /// with an output folder, to the result files). On failure the
    /// increments converged before stay written and `summary.json` says
    /// `"status": "failed"` with the error (`"interrupted"` when an
    /// observer stopped the run with [`Error::Interrupted`]).
    pub fn run(
        &mut self,
        options: &RunOptions,
        observer: &mut (dyn StepObserver + Send),
    ) -> Result<RunOutcome> {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(options.threads.unwrap_or(0))
            .build()
            .map_err(|e| Error::Case {
                path: PathBuf::from(&self.case_label),
                message: format!("cannot start the worker threads: {e}"),
            })?;
        pool.install(|| self.run_here(options, observer))
    }

    /// [`run`](Self::run) in the current thread pool.
    fn run_here(
        &mut self,
        options: &RunOptions,
        observer: &mut (dyn StepObserver + Send),
    ) -> Result<RunOutcome> {
        let start = Instant::now();
        let restart = match &options.restart {
            Some(dir) => Some(self.read_restart(dir, options.output.as_deref())?),
            None => None,
        };
        let (mut writer, mut log) = self.file_observers(options, restart.as_ref())?;
        let mut observers = Observers(vec![observer]);
        if let Some(w) = writer.as_mut() {
            observers.0.insert(0, w);
        }
        if let Some(l) = log.as_mut() {
            observers.0.insert(0, l);
        }
        self.describe_to(&mut observers);
        let mut recorder = Recorder {
            summary: Summary::start(&self.case_label, &self.problem),
            observers,
            name: &self.name,
            every: self.every,
            cancel: options.cancel.clone(),
            last: start,
            start,
            contact: ContactState::default(),
            stepping: Stepping::default(),
            statistics: SolverStatistics::default(),
            earlier: None,
        };
        let resume = restart.map(|r| recorder.restore(r));
        recorder.summary.strategy = self.strategy.path.name().into();
        recorder.summary.strategy_reason = self.strategy.reason.clone();
        recorder.observers.on_message(&format!(
            "strategy: {} ({})",
            self.strategy.path.name(),
            self.strategy.reason
        ));
        recorder.observers.on_start(&recorder.summary)?;
        let output = options.output.clone().unwrap_or_default();
        let (result, statistics) = match self.strategy.path {
            SolvePath::Monolithic => {
                let ordering = fill_reducing_ordering(&self.problem)?;
                let coordinates = self
                    .problem
                    .model
                    .mesh
                    .nodes
                    .iter()
                    .flatten()
                    .copied()
                    .collect();
                let mut solver =
                    try_linear_solver(&self.problem.settings, ordering, 0, Some(coordinates))?;
                let about_solver = solver.description();
                if !about_solver.is_empty() {
                    recorder
                        .observers
                        .on_message(&format!("linear solver: {about_solver}"));
                }
                let result = resume_steps(
                    &mut self.problem,
                    &mut *solver,
                    &mut recorder,
                    output.clone(),
                    resume,
                );
                (result, solver.statistics())
            }
            SolvePath::Condensed => {
                if resume.is_some() {
                    return Err(Error::Restart {
                        path: options.restart.clone().unwrap_or_default(),
                        message: format!(
                            "a restart resumes Newton's path, and this case runs on the \
                             condensed contact path ({}); set [solver] strategy = \
                             \"monolithic\" to restart it",
                            self.strategy.reason
                        ),
                    });
                }
                let (result, statistics, steps) =
                    condensed::run_steps(&mut self.problem, &mut recorder, output.clone());
                recorder.summary.active_set_iterations = steps;
                (result, statistics)
            }
        };
        let result = result.map_err(|e| case::diagnosis::explain_failure(e, &self.warnings));
        update_totals(
            &mut recorder.summary,
            &self.problem,
            &statistics,
            recorder.start,
            recorder.earlier.as_ref(),
        );
        recorder.finish(result, output)
    }

    /// The checkpoint in `dir` (`NAME.checkpoint`), checked against this
    /// case, with the output it restores; `output` must be `dir` or none.
    fn read_restart(&self, dir: &Path, output: Option<&Path>) -> Result<Restart> {
        if let Some(out) = output.filter(|out| !same_folder(out, dir)) {
            return Err(Error::Restart {
                path: dir.to_path_buf(),
                message: format!(
                    "a restart goes on writing into the folder it resumes from, not into '{}'; \
                     leave out --output (or give the same folder), or copy the folder first \
                     to keep the interrupted run's files",
                    out.display()
                ),
            });
        }
        let c = checkpoint::read(dir, &self.name)?;
        let path = checkpoint::path(dir, &self.name);
        c.check_case(&self.case_key, &path)?;
        let fail = |message: String| Error::Restart {
            path: path.clone(),
            message,
        };
        let (histories, profiles) = (&self.requests.histories, &self.requests.profiles);
        if c.histories.len() != histories.len() || c.profiles.len() != profiles.len() {
            return Err(fail(format!(
                "the checkpoint has {} histories and {} profiles, the case asks for {} and {}; \
                 a restart needs the same [[output.history]] and [[output.profile]] tables",
                c.histories.len(),
                c.profiles.len(),
                histories.len(),
                profiles.len()
            )));
        }
        let summary: Summary = serde_json::from_str(&c.summary)
            .map_err(|e| fail(format!("corrupted: its summary does not read back ({e})")))?;
        Ok(Restart {
            increments: summary.increments.len(),
            summary,
            histories: c.histories.into_iter().map(|h| h.into_owned()).collect(),
            profiles: c.profiles.into_iter().map(|p| p.into_owned()).collect(),
            resume: Resume {
                unknowns: c.unknowns.into_owned(),
                state: c.contact.into_owned(),
                stepping: c.stepping.into_owned(),
            },
            dir: dir.to_path_buf(),
        })
    }

    /// The result files and the log, when the run has an output folder
    /// (going on with the restored ones after a restart).
    fn file_observers(
        &self,
        options: &RunOptions,
        restart: Option<&Restart>,
    ) -> Result<(Option<ResultWriter>, Option<LogWriter>)> {
        let Some(dir) = &options.output else {
            return Ok((None, None));
        };
        let content = SeriesContent {
            nodal: self.nodal_fields.clone(),
            cells: self.cell_fields.clone(),
            histories: self.requests.histories.clone(),
            profiles: self.requests.profiles.clone(),
        };
        let (writer, log) = match restart {
            None => (
                ResultWriter::new(dir, &self.name, content)?,
                LogWriter::new(dir, &self.name)?,
            ),
            Some(r) => {
                let restored = Restored {
                    summary: &r.summary,
                    histories: r.histories.clone(),
                    profiles: r.profiles.clone(),
                };
                (
                    ResultWriter::resume(dir, &self.name, content, restored)?,
                    LogWriter::append(dir, &self.name)?,
                )
            }
        };
        let writer = writer
            .compress(self.compress)
            .checkpoint(self.case_key.clone());
        Ok((Some(writer), Some(log)))
    }

    /// The model in words, the notes on reading it and what the histories
    /// and profiles read, for the observers' logs.
    fn describe_to(&self, observers: &mut Observers) {
        let notes = self.notes.iter().map(|n| format!("note: {n}"));
        let warnings = self.warnings.iter().map(|w| format!("warning: {w}"));
        for line in describe_model(&self.problem)
            .into_iter()
            .chain(notes)
            .chain(warnings)
            .chain(self.request_lines())
        {
            observers.on_message(&line);
        }
    }

    /// Which node each history reads and which nodes each profile, for the log.
    fn request_lines(&self) -> Vec<String> {
        let nodes = &self.problem.model.mesh.nodes;
        let histories = self
            .requests
            .histories
            .iter()
            .map(|h| format!("history '{}': {} {}", h.name, h.label, h.location(nodes)));
        let profiles = self.requests.profiles.iter().map(|p| {
            format!(
                "profile '{}': {} nodes of interface '{}'",
                p.name,
                p.nodes.len(),
                p.interface_name
            )
        });
        histories.chain(profiles).collect()
    }
}

/// Whether `a` and `b` name the same folder (compared as given when
/// either does not exist).
fn same_folder(a: &Path, b: &Path) -> bool {
    match (a.canonicalize(), b.canonicalize()) {
        (Ok(a), Ok(b)) => a == b,
        _ => a == b,
    }
}

/// The FNV-1a hash of a case's physics ([`CaseKey::physics`]): the mesh's
/// coordinates (their bits), elements and sets, and the debug form of the
/// case's materials, loads, amplitudes, obstacles and contacts.
fn physics_hash(case: &Case) -> u64 {
    use std::fmt::Write;
    use std::hash::Hasher;
    let mut h = Fnv1a::default();
    let mesh = &case.mesh;
    for x in mesh.nodes.iter().flatten() {
        h.write(&x.to_bits().to_le_bytes());
    }
    for e in &mesh.elements {
        let _ = write!(h, "{:?}", e.kind);
        for &n in &e.nodes {
            h.write(&(n as u64).to_le_bytes());
        }
    }
    let s = &case.spec;
    let _ = write!(
        h,
        "{:?}{:?}{:?}{:?}{:?}{:?}{:?}{:?}{:?}{:?}{:?}",
        mesh.regions,
        mesh.surfaces,
        mesh.node_sets,
        s.material,
        s.displacement,
        s.pressure,
        s.body_force,
        s.nodal_force,
        s.obstacle,
        s.contact,
        s.amplitudes
    );
    h.finish()
}

/// The fill-reducing ordering of `problem`'s pattern
/// ([`crate::solve::ordering::fill_reducing_ordering`]).
pub fn fill_reducing_ordering(problem: &Problem) -> Result<crate::solve::linear::Ordering> {
    crate::solve::ordering::fill_reducing_ordering(&problem.model.pattern, problem.model.num_dofs())
}

/// Run a case file end to end, writing the results into `options.output`
/// or, without one, into the case's own output folder.
pub fn run(case_path: &Path, options: &RunOptions) -> Result<RunOutcome> {
    run_observed(case_path, options, &mut crate::output::observer::Silent)
}

/// [`run`] with an observer of the increments beside the result files.
pub fn run_observed(
    case_path: &Path,
    options: &RunOptions,
    observer: &mut (dyn StepObserver + Send),
) -> Result<RunOutcome> {
    let mut simulation = Simulation::from_file(case_path)?;
    // a restart goes on in the folder it resumes from
    let folder = options
        .restart
        .clone()
        .unwrap_or_else(|| simulation.default_output_dir().to_path_buf());
    let options = RunOptions {
        output: Some(options.output.clone().unwrap_or(folder)),
        ..options.clone()
    };
    simulation.run(&options, observer)
}

/// Turns the stepper's converged increments into the in-memory results that
/// observers read, and keeps the run's summary.
struct Recorder<'a> {
    summary: Summary,
    observers: Observers<'a>,
    name: &'a str,
    every: usize,
    cancel: Option<Arc<AtomicBool>>,
    last: Instant,
    start: Instant,
    contact: ContactState,
    /// The stepper's state after the last converged increment, and the
    /// linear solver's figures then.
    stepping: Stepping,
    statistics: SolverStatistics,
    /// After a restart: the summary of the checkpoint, whose run totals
    /// the resumed run's add to.
    earlier: Option<Summary>,
}

impl Recorder<'_> {
    /// Take over a restart's summary and state (the run's clock counts the
    /// earlier run's time too); what the stepper resumes from.
    fn restore(&mut self, restart: Restart) -> Resume<ContactState> {
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
    fn finish(mut self, result: Result<Vec<f64>>, output: PathBuf) -> Result<RunOutcome> {
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
            Err(e) => {
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

/// The run's totals in the summary so far ([`record_totals`]), with those
/// of the run a restart resumed (`earlier`) added: in `summary.json` after
/// every increment, and so in the checkpoint.
fn update_totals(
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
    summary.krylov_solves += earlier.krylov_solves;
    summary.krylov_iterations += earlier.krylov_iterations;
    summary.lu_solves += earlier.lu_solves;
    summary.factorisations += earlier.factorisations;
    summary.single_factorisations += earlier.single_factorisations;
    summary.refinement_steps += earlier.refinement_steps;
    summary.mixed_precision_fallbacks += earlier.mixed_precision_fallbacks;
    summary.wall_time += earlier.wall_time;
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
    };
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
            format!("{}_{index:04}.vtu", self.name)
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
        });
        self.summary.update_step_totals();
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

    fn on_cut(&mut self, step: &str, time: f64, increment: f64, reason: &IncrementFailure) {
        self.observers.on_cut(&Cut {
            step,
            time,
            increment,
            reason,
        });
    }
}
