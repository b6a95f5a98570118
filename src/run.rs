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

mod distributed;
mod fallback;
pub mod huge_pages;
mod recorder;
mod restart;

use crate::case::{self, output::OutputRequests, Case};
use crate::output::checkpoint::CaseKey;
use crate::output::describe::describe_model;
use crate::output::fields::{CellField, NodalField};
use crate::output::lock::FolderLock;
use crate::output::log::LogWriter;
use crate::output::observer::{Observers, StepObserver};
use crate::output::provenance::RunHeader;
use crate::output::pvtu::PieceWriter;
use crate::output::summary::Summary;
use crate::output::vtu::VtuOptions;
use crate::output::writer::{MeshEncoding, Restored, ResultWriter, SeriesContent};
use crate::problem::condensed::{self, Path as SolvePath};
use crate::problem::{ContactPattern, ContactState, Problem};
use crate::solve::backend::try_linear_solver;
use crate::solve::josephy::Josephy;
use crate::solve::linear_solver::SolverStatistics;
use crate::solve::method::{IncrementMethod, Monolithic};
use crate::solve::settings::Strategy;
use crate::solve::stepping::{resume_steps, Resume};
use crate::{Error, Result};
use distributed::Distribution;
pub use distributed::{launched_processes, launched_rank};
use recorder::{update_totals, Recorder};
use restart::Restart;
use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;
use std::sync::Arc;

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
    /// The case file's SHA-256, for the log's header.
    case_sha256: String,
    /// The VTU points and cells of the mesh, encoding since the case was
    /// read ([`run_observed`]); `None`: the writer starts it.
    mesh_encoding: Option<MeshEncoding>,
}

/// The problem of `case` as a run solves it, and the path chosen for it
/// (`[solver] strategy`, [`condensed::choose`], with PETSc's own rule):
/// on the condensed path exact stick's tangential multipliers are kept in
/// the friction history ([`Problem::keep_friction_multipliers_in_history`]).
/// [`Simulation::from_case`] and `signorini check` both build it here, so
/// that the check describes the model the run solves.
pub fn problem_as_run(case: &Case) -> Result<(Problem, condensed::Choice)> {
    problem_as_run_noted(case, true).map(|(problem, strategy, _)| (problem, strategy))
}

/// [`problem_as_run`], and the notes for the log on what the run changed
/// of the case's model (exact stick's multipliers on PETSc,
/// [`distributed::friction_multipliers_for_petsc`]). Without
/// `whole_pattern` (a process of a distributed run) the pattern waits for
/// the partition ([`Case::build_distributed_problem`]).
fn problem_as_run_noted(
    case: &Case,
    whole_pattern: bool,
) -> Result<(Problem, condensed::Choice, Vec<String>)> {
    // the condensed path's pattern until the path is chosen: Newton's
    // contact couplings are built for Newton's path alone
    let mut problem = if whole_pattern {
        case.build_problem_with(ContactPattern::Condensed)?
    } else {
        case.build_distributed_problem()?
    };
    let strategy = condensed::choose(&problem).map_err(|message| Error::Case {
        path: case.path.clone(),
        message,
    })?;
    let strategy = distributed::strategy_for_petsc(&problem, strategy);
    if strategy.path == SolvePath::Condensed {
        problem.keep_friction_multipliers_in_history();
    } else {
        problem.newton_pattern();
    }
    let notes = distributed::friction_multipliers_for_petsc(&mut problem, case);
    Ok((problem, strategy, notes.into_iter().collect()))
}

impl Simulation {
    /// From a case: builds the problem and validates the output requests.
    pub fn from_case(case: &Case) -> Result<Self> {
        // under mpirun (a build with PETSc, which gives every process its
        // share before the run starts): no whole pattern
        let distributed = cfg!(feature = "petsc") && launched_processes().is_some();
        let (problem, strategy, run_notes) = problem_as_run_noted(case, !distributed)?;
        let requests = case.output_requests(&problem)?;
        let (nodal_fields, cell_fields) = case.output_fields();
        let every = case.output_every()?;
        let case_key = restart::case_key(case, &problem);
        Ok(Simulation {
            case_sha256: case.source_sha256(),
            case_label: case.path.display().to_string(),
            name: case.output_name(),
            default_output: case.output_dir(None),
            requests,
            nodal_fields,
            cell_fields,
            every,
            compress: case.spec.output.compress.unwrap_or(true),
            notes: case.notes.iter().cloned().chain(run_notes).collect(),
            strategy,
            warnings: case.diagnose(&problem),
            case_key,
            problem,
            mesh_encoding: None,
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

    /// The histories and profiles the run writes, validated.
    pub fn requests(&self) -> &OutputRequests {
        &self.requests
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
        // under mpirun: this process's elements, its rank's share of the
        // files, and the processes agree on how the run ended
        let recovered = self.nodal_fields.iter().any(|f| f.is_recovered());
        let distribution =
            Distribution::start(&mut self.problem, &self.case_label, options, recovered)?;
        let result = self.run_with(options, observer, distribution.as_ref());
        match &distribution {
            Some(d) => d.conclude(result),
            None => result,
        }
    }

    /// [`run_here`](Self::run_here) for this process's `distribution`, if any.
    fn run_with(
        &mut self,
        options: &RunOptions,
        observer: &mut (dyn StepObserver + Send),
        distribution: Option<&Distribution>,
    ) -> Result<RunOutcome> {
        let strategy = match distribution {
            Some(d) => d.strategy(&self.problem, self.strategy.clone(), &self.case_label)?,
            None => self.strategy.clone(),
        };
        // the output folder is this run's for its whole life, before its
        // checkpoint is read or any file removed
        let _folder = lock_output_folder(options, distribution, &mut self.notes)?;
        let restart = match &options.restart {
            Some(dir) => Some(self.read_restart(dir, options.output.as_deref())?),
            None => None,
        };
        let (mut writer, mut log, mut piece) =
            self.file_observers(options, restart.as_ref(), distribution)?;
        let mut observers = Observers(vec![observer]);
        if let Some(w) = writer.as_mut() {
            observers.0.insert(0, w);
        }
        if let Some(l) = log.as_mut() {
            observers.0.insert(0, l);
        }
        if let Some(p) = piece.as_mut() {
            observers.0.insert(0, p);
        }
        self.describe_to(&mut observers);
        for line in distribution.iter().flat_map(|d| d.describe(&self.problem)) {
            observers.on_message(&line);
        }
        let mut recorder = Recorder::new(&self.case_label, &self.problem, observers, &self.name);
        recorder.every = self.every;
        // a distributed run ends on a signal at once (Distribution::watch)
        recorder.cancel = options.cancel.clone().filter(|_| distribution.is_none());
        if distribution.is_some() {
            recorder.extension = "pvtu";
        }
        let resume = restart.map(|r| recorder.restore(r));
        announce_strategy(&strategy, &mut recorder)?;
        let output = options.output.clone().unwrap_or_default();
        let (result, statistics) = match strategy.path {
            SolvePath::Monolithic => {
                self.run_monolithic(&mut recorder, resume, &output, distribution)?
            }
            SolvePath::Condensed => match condensed::Condensed::new(&self.problem) {
                Ok(method) => self.run_condensed(method, &mut recorder, resume, &output),
                Err(e) if self.problem.settings.strategy == Strategy::Auto => {
                    // `auto` is never worse off than monolithic: the run
                    // goes on Newton's path
                    let reason = format!("the condensed path could not start: {e}");
                    let choice = condensed::Choice {
                        path: SolvePath::Monolithic,
                        reason,
                    };
                    announce_strategy(&choice, &mut recorder)?;
                    self.run_monolithic(&mut recorder, resume, &output, None)?
                }
                Err(e) => (Err(e), SolverStatistics::default()),
            },
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

    /// Newton's load steps on the whole system with the `[solver] linear`
    /// backend (distributed under mpirun; resumed from a checkpoint's state when given); the result
    /// and the linear solver's figures.
    fn run_monolithic(
        &mut self,
        recorder: &mut Recorder,
        resume: Option<Resume<ContactState>>,
        output: &Path,
        distribution: Option<&Distribution>,
    ) -> Result<(Result<Vec<f64>>, SolverStatistics)> {
        self.problem.newton_pattern();
        let mut solver = match distribution {
            Some(d) => d.linear_solver(&self.problem)?,
            None => {
                let ordering = fill_reducing_ordering(&self.problem)?;
                let mesh = &self.problem.model.mesh;
                let coordinates = mesh.nodes.iter().flatten().copied().collect();
                try_linear_solver(&self.problem.settings, ordering, 0, Some(coordinates))?
            }
        };
        let (predictor, reason) = self
            .problem
            .settings
            .predictor
            .chosen(self.problem.contact_linearisation());
        recorder.summary.predictor = predictor.name().into();
        recorder.summary.predictor_reason = reason.clone();
        recorder
            .observers
            .on_message(&format!("predictor: {} ({reason})", predictor.name()));
        let about_solver = solver.description();
        if !about_solver.is_empty() {
            recorder
                .observers
                .on_message(&format!("linear solver: {about_solver}"));
        }
        let mut josephy = Josephy::default();
        let mut newton = Monolithic::new(&self.problem, &mut *solver, &mut josephy);
        let result = resume_steps(
            &mut self.problem,
            &mut newton,
            None,
            recorder,
            output.to_path_buf(),
            resume,
        );
        Ok((result, IncrementMethod::<Problem>::statistics(&newton)))
    }

    /// The condensed path's load steps (`method`, its one factorisation
    /// made) by the same stepper as Newton's; under
    /// `strategy = "auto"` an increment it fails is solved again on
    /// Newton's path ([`fallback`]). The result and the figures of both.
    fn run_condensed(
        &mut self,
        mut method: condensed::Condensed,
        recorder: &mut Recorder,
        resume: Option<Resume<ContactState>>,
        output: &Path,
    ) -> (Result<Vec<f64>>, SolverStatistics) {
        let auto = self.problem.settings.strategy == Strategy::Auto;
        let mut newton = fallback::NewtonOnDemand::default();
        let fallback = auto.then_some(&mut newton as &mut dyn IncrementMethod<Problem>);
        let result = resume_steps(
            &mut self.problem,
            &mut method,
            fallback,
            recorder,
            output.to_path_buf(),
            resume,
        );
        let statistics = method.statistics() + newton.statistics();
        // the factor (tens of MB) is freed on another thread, beside the
        // run's last writes
        rayon::spawn(move || drop(method));
        (result, statistics)
    }

    /// The result files and the log, when the run has an output folder
    /// (going on with the restored ones after a restart); in a distributed
    /// run, those of rank 0 with its piece of each `.pvtu`, and the other
    /// processes' pieces.
    fn file_observers(
        &self,
        options: &RunOptions,
        restart: Option<&Restart>,
        distribution: Option<&Distribution>,
    ) -> Result<(Option<ResultWriter>, Option<LogWriter>, Option<PieceWriter>)> {
        let Some(dir) = &options.output else {
            return Ok((None, None, None));
        };
        let pieces = distribution.map(Distribution::pieces);
        if let Some(pieces) = pieces
            .clone()
            .filter(|_| distribution.is_some_and(|d| !d.is_lead()))
        {
            let piece = PieceWriter {
                dir: dir.clone(),
                pieces,
                nodal: self.nodal_fields.clone(),
                cells: self.cell_fields.clone(),
                options: VtuOptions {
                    compress: self.compress,
                },
            };
            return Ok((None, None, Some(piece)));
        }
        let content = SeriesContent {
            nodal: self.nodal_fields.clone(),
            cells: self.cell_fields.clone(),
            histories: self.requests.histories.clone(),
            profiles: self.requests.profiles.clone(),
        };
        let header = RunHeader::now(
            Path::new(&self.case_label),
            self.case_sha256.clone(),
            rayon::current_num_threads(),
        );
        let (writer, mut log) = match restart {
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
        log.header(&header);
        let mut writer = writer
            .compress(self.compress)
            .checkpoint(self.case_key.clone())
            .residual_tolerance(self.problem.settings.residual_tolerance);
        writer = match pieces {
            Some(pieces) => writer.pieces(pieces),
            // the mesh's points and cells encoded beside the set-up (or
            // the solve)
            None => match &self.mesh_encoding {
                Some(encoding) => writer.encoded_mesh(encoding.clone()),
                None => writer.prepare_mesh(Arc::clone(&self.problem.model.mesh)),
            },
        };
        Ok((Some(writer), Some(log), None))
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

/// The lock of the run's output folder ([`FolderLock`]), taken by the
/// process that writes the folder's files (under mpirun the lead; the
/// others write their pieces under its lock); a lock taken over from a
/// killed run is told in `notes`.
fn lock_output_folder(
    options: &RunOptions,
    distribution: Option<&Distribution>,
    notes: &mut Vec<String>,
) -> Result<Option<FolderLock>> {
    let Some(dir) = options.output.as_deref() else {
        return Ok(None);
    };
    // a restart from a folder that is not there is refused by the restart,
    // which says so, rather than resumed from a folder the lock made
    let missing_restart = options.restart.is_some() && !dir.is_dir();
    if missing_restart || distribution.is_some_and(|d| !d.is_lead()) {
        return Ok(None);
    }
    let lock = FolderLock::acquire(dir)?;
    if let Some(pid) = lock.taken_over() {
        notes.push(format!(
            "the output folder was left locked by run {pid}, which ended without finishing \
             (killed); this run took it over"
        ));
    }
    Ok(Some(lock))
}

/// The path (monolithic or condensed) and why, in the summary and the
/// log; the observers are told the run starts.
fn announce_strategy(strategy: &condensed::Choice, recorder: &mut Recorder) -> Result<()> {
    let (path, reason) = (strategy.path.name(), &strategy.reason);
    recorder.summary.strategy = path.into();
    recorder.summary.strategy_reason = reason.clone();
    recorder
        .observers
        .on_message(&format!("strategy: {path} ({reason})"));
    recorder.observers.on_start(&recorder.summary)
}

/// The fill-reducing ordering of `problem`'s pattern
/// ([`crate::solve::ordering::fill_reducing_ordering`]).
pub fn fill_reducing_ordering(problem: &Problem) -> Result<crate::solve::linear::Ordering> {
    crate::solve::ordering::fill_reducing_ordering(
        &problem.model.pattern,
        problem.model.num_dofs(),
        problem.dissection.as_ref(),
    )
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
    let case = case::load(case_path)?;
    // the VTU points and cells are encoded on the core that building the
    // problem leaves idle (not under mpirun: each rank writes its piece)
    let compress = case.spec.output.compress.unwrap_or(true);
    let encoding = launched_rank()
        .is_none()
        .then(|| MeshEncoding::start(Arc::clone(&case.mesh), VtuOptions { compress }));
    let mut simulation = Simulation::from_case(&case)?;
    simulation.mesh_encoding = encoding;
    // the model holds the mesh alone from here (under mpirun each process
    // then lets go of the elements it does not read)
    drop(case);
    // a restart goes on in the folder it resumes from
    let folder = options
        .restart
        .clone()
        .unwrap_or_else(|| simulation.default_output_dir().to_path_buf());
    let options = RunOptions {
        output: Some(options.output.clone().unwrap_or(folder)),
        ..options.clone()
    };
    let outcome = simulation.run(&options, observer);
    // the problem (mesh, pattern, matrices) is freed on another thread:
    // the caller has its outcome without waiting for that (here if no
    // thread can be started)
    let _ = std::thread::Builder::new().spawn(move || drop(simulation));
    outcome
}
