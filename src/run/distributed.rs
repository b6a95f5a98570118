//! Runs on PETSc: the strategy rule of `[solver] linear = "petsc"`, and
//! the distributed run of `mpirun -np N signorini run case.toml` (cargo
//! feature `petsc`).
//!
//! A distributed run reads the case and mesh on every process and cuts
//! the elements into N parts in parallel by PETSc's partitioner, or
//! serial METIS where it has none ([`MeshPartition`],
//! `crate::solve::petsc::partitioning`), after which each process lets
//! go of the elements it does not read ([`Distribution::hold`]); each
//! process assembles its own elements ([`Share`]) on a pattern of their rows
//! ([`Problem::set_share`]), the internal force is summed
//! over the processes, and the contact surfaces, contact states, Newton
//! and the stepping are replicated: every process computes them alike
//! from the same whole unknowns. PETSc solves each Newton system on the
//! distributed matrix ([`DistributedPetscSolver`]) and hands the whole
//! correction back to every process. Output: each process writes the
//! `.vtu` piece of its elements, rank 0 the `.pvtu` over them, the `.pvd`,
//! `summary.json` and the log. The processes agree on how the run ended
//! ([`Distribution::conclude`]); a process that fails alone, or a signal,
//! ends every process within seconds with `summary.json` marked failed
//! (`crate::solve::petsc::fault`).

use super::{RunOptions, RunOutcome};
use crate::case::schema::FrictionMultiplierSpec;
use crate::case::Case;
use crate::output::pvtu::Pieces;
use crate::output::recovery::PatchRecovery;
use crate::problem::condensed::{Choice, Path as SolvePath};
use crate::problem::{LinearMethod, Problem};
use crate::solve::partition::MeshPartition;
use crate::solve::settings::Strategy;
use crate::{Error, Result};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

/// `[solver] linear = "petsc"` with `strategy = "auto"`: monolithic
/// Newton, whose systems PETSc solves, where `auto` would have taken the
/// condensed path (which factorises with faer, not PETSc).
pub(super) fn strategy_for_petsc(problem: &Problem, choice: Choice) -> Choice {
    let petsc = problem.settings.linear == LinearMethod::Petsc;
    if petsc && problem.settings.strategy == Strategy::Auto && choice.path == SolvePath::Condensed {
        return Choice {
            path: SolvePath::Monolithic,
            reason: "[solver] linear = \"petsc\": PETSc solves the monolithic Newton systems \
                     (the condensed path factorises with faer)"
                .into(),
        };
    }
    choice
}

/// Exact stick's tangential multipliers on PETSc (`[solver] linear =
/// "petsc"`, or any run under `mpirun`): updated by the outer loop
/// ([`Problem::keep_friction_multipliers_in_history`], Simo–Laursen;
/// still exact stick) rather than solved by Newton beside the
/// displacements, where the case does not ask for `friction_multiplier =
/// "newton"`. As Newton unknowns their rows have a zero diagonal in stick
/// (`∂r_ℓ/∂ℓ = 0`, Alart–Curnier), which PETSc's preconditioners (ILU,
/// GAMG, MUMPS's default pivoting on the distributed matrix) do not take:
/// `DIVERGED_PC_FAILED` at the first increment. Returns the note for the
/// log when it changed the problem.
pub(super) fn friction_multipliers_for_petsc(problem: &mut Problem, case: &Case) -> Option<String> {
    let on_petsc = problem.settings.linear == LinearMethod::Petsc
        || (cfg!(feature = "petsc") && launched_processes().is_some());
    let asked = case
        .spec
        .contact
        .iter()
        .any(|c| c.friction_multiplier == Some(FrictionMultiplierSpec::Newton));
    if !on_petsc || asked || !problem.contacts.has_tangential_multipliers() {
        return None;
    }
    problem.keep_friction_multipliers_in_history();
    Some(
        "exact stick's tangential multipliers are updated by an outer loop after each Newton \
         solve (friction_multiplier = \"outer\"), not solved by Newton: PETSc's \
         preconditioners fail on them as unknowns; friction_multiplier = \"newton\" asks for \
         them anyway"
            .into(),
    )
}

/// The number of processes `mpirun` (Open MPI, MPICH) started, from the
/// environment it gives each process; `None` without `mpirun`.
pub fn launched_processes() -> Option<usize> {
    [
        "OMPI_COMM_WORLD_SIZE",
        "PMI_SIZE",
        "PMIX_SIZE",
        "MPI_LOCALNRANKS",
    ]
    .iter()
    .find_map(|v| std::env::var(v).ok()?.trim().parse().ok())
}

/// This process's rank under `mpirun`, from the environment; `None`
/// without `mpirun`.
pub fn launched_rank() -> Option<usize> {
    ["OMPI_COMM_WORLD_RANK", "PMI_RANK", "PMIX_RANK"]
        .iter()
        .find_map(|v| std::env::var(v).ok()?.trim().parse().ok())
}

/// This process's place in a distributed run.
pub(super) struct Distribution {
    pub rank: usize,
    pub partition: MeshPartition,
    /// The patch recovery of this process's piece's nodes, made before it
    /// let go of the elements it does not read ([`Distribution::hold`]);
    /// `None` when no recovered field is written.
    recovery: Option<Arc<PatchRecovery>>,
    #[cfg(feature = "petsc")]
    world: std::sync::Arc<crate::solve::petsc::distributed::MpiWorld>,
    /// The run's `summary.json`, which a fault marks failed.
    summary: Option<PathBuf>,
    /// Set when the run has ended (the signal watcher stops).
    ended: Arc<AtomicBool>,
}

impl Distribution {
    /// Under `mpirun`: join MPI's world (through PETSc), partition the
    /// mesh, give the model this process's elements and let go of the
    /// others it does not read ([`Distribution::hold`]; `recovered`: the
    /// output writes recovered nodal fields); a fault of any
    /// process marks `summary.json` in `options.output` failed, and a
    /// signal ([`Distribution::watch`]) ends this process. `None` without
    /// `mpirun`.
    pub fn start(
        problem: &mut Problem,
        case_label: &str,
        options: &RunOptions,
        recovered: bool,
    ) -> Result<Option<Self>> {
        let Some(processes) = launched_processes() else {
            return Ok(None);
        };
        let Some(mut distribution) = Self::join(problem, case_label, processes)? else {
            return Ok(None);
        };
        distribution.hold(problem, recovered);
        distribution.summary = options.output.as_ref().map(|d| d.join("summary.json"));
        distribution.watch(options.cancel.clone());
        #[cfg(feature = "petsc")]
        if let Some(path) = distribution.summary.clone() {
            let (rank, size) = (distribution.rank, distribution.partition.parts);
            crate::solve::petsc::fault::on_fault(move |message| {
                mark_failed(&path, &format!("process {rank} of {size}: {message}"));
            });
        }
        Ok(Some(distribution))
    }

    /// A signal (SIGINT, SIGTERM: the `cancel` flag the command line sets)
    /// ends a distributed run at once: `mpirun` sends SIGTERM to every
    /// process when one fails or is killed, and SIGKILL a second later,
    /// and a process waiting in a collective for a process that is gone
    /// would never see the flag between two Newton iterations (nor could
    /// the processes stop at the same iteration). Rank 0 marks
    /// `summary.json` failed (the increments converged so far stay
    /// written), and the process exits with code 1.
    fn watch(&self, cancel: Option<Arc<AtomicBool>>) {
        let Some(cancel) = cancel else {
            return;
        };
        let (ended, rank, summary) = (self.ended.clone(), self.rank, self.summary.clone());
        let watcher = move || loop {
            std::thread::sleep(std::time::Duration::from_millis(20));
            if ended.load(Ordering::Relaxed) {
                return;
            }
            if cancel.load(Ordering::Relaxed) {
                let message = "stopped by a signal: under mpirun this means that another \
                               process of the run failed or was killed (mpirun's message says \
                               which), or that the run was interrupted";
                eprintln!("error: process {rank}: {message}");
                if let (0, Some(path)) = (rank, &summary) {
                    mark_failed(path, message);
                }
                exit_now(1);
            }
        };
        let _ = std::thread::Builder::new()
            .name("signal watcher".into())
            .spawn(watcher);
    }

    /// The end of a distributed run: the processes agree on its outcome
    /// ([`crate::solve::petsc::fault::agree`]). A failure on any process
    /// is the run's failure on every process (rank 0 marks `summary.json`
    /// failed if its own run succeeded); a process that failed while
    /// another is stuck ends the run.
    pub fn conclude(&self, result: Result<RunOutcome>) -> Result<RunOutcome> {
        self.ended.store(true, Ordering::Relaxed);
        #[cfg(feature = "petsc")]
        {
            use crate::solve::petsc::fault::{agree, fault, Agreement, Severity};
            let local = result.as_ref().map(|_| ()).map_err(|e| e.to_string());
            let failed = local.as_ref().map(|_| ());
            match agree(failed.map_err(|m| (Severity::Final, m.as_str()))) {
                Agreement::Succeeded => result,
                Agreement::Failed { rank, message, .. } => result.and_then(|_| {
                    let message = format!("process {rank} of {}: {message}", self.partition.parts);
                    if let (true, Some(path)) = (self.is_lead(), &self.summary) {
                        mark_failed(path, &message);
                    }
                    Err(Error::Distributed(message))
                }),
                Agreement::NoAnswer => fault(local.err().as_deref().unwrap_or("no answer")),
            }
        }
        #[cfg(not(feature = "petsc"))]
        result
    }

    #[cfg(not(feature = "petsc"))]
    fn join(_: &mut Problem, case_label: &str, processes: usize) -> Result<Option<Self>> {
        if processes <= 1 {
            return Ok(None);
        }
        Err(Error::Case {
            path: case_label.into(),
            message: format!(
                "started by mpirun on {processes} processes, but this signorini was built \
                 without PETSc, so every process would run the whole case alone: build it \
                 with `cargo build --release --features petsc` (PETSc and MPI from \
                 `apt-get install petsc-dev`), or run it without mpirun"
            ),
        })
    }

    #[cfg(feature = "petsc")]
    fn join(problem: &mut Problem, case_label: &str, _: usize) -> Result<Option<Self>> {
        use crate::assembly::share::{Communicator, Share};
        use crate::solve::petsc::distributed::MpiWorld;
        if problem.model.is_shared() {
            // its mesh holds this process's elements only
            return Err(Error::Case {
                path: case_label.into(),
                message: "a simulation runs once under mpirun: its model holds only this \
                          process's part of the mesh after its first run; build the \
                          simulation again for another run"
                    .into(),
            });
        }
        let world = std::sync::Arc::new(MpiWorld::new()?);
        let (rank, size) = (world.rank(), world.size());
        let mesh = &problem.model.mesh;
        let partition =
            crate::solve::petsc::partitioning::partition(mesh, rank, size).map_err(|e| {
                Error::Case {
                    path: case_label.into(),
                    message: e.to_string(),
                }
            })?;
        problem.set_share(Share {
            owned: partition.owned_elements(rank),
            own_nodes: partition.node_part.iter().map(|&p| p == rank).collect(),
            communicator: world.clone(),
        });
        Ok(Some(Distribution {
            rank,
            partition,
            recovery: None,
            world,
            summary: None,
            ended: Arc::new(AtomicBool::new(false)),
        }))
    }

    /// Let go of the connectivity of the elements this process does not
    /// read (issue 29 item 3, first part): it keeps its own elements, the
    /// ghost layer of its rows (the others' elements at its nodes,
    /// [`MeshPartition::row_elements`]) and, when `recovered`, the patches
    /// of its piece's nodes, whose recovery it makes here on the whole
    /// mesh ([`PatchRecovery::of_nodes`]). Nodes, regions and surface sets
    /// stay whole (the whole vectors are indexed by node; the reaction
    /// forces of `summary.json` sum every surface set's nodes; the contact
    /// surfaces are replicated by design), and every element its index.
    /// Then the pages freed at the set-up go back to the system.
    fn hold(&mut self, problem: &mut Problem, recovered: bool) {
        let mesh = &problem.model.mesh;
        let mut keep = self.partition.row_elements(mesh, self.rank);
        if recovered {
            let mut piece = vec![false; mesh.num_nodes()];
            for (el, &own) in mesh.elements.iter().zip(&self.partition.element_part) {
                if own == self.rank {
                    el.nodes.iter().for_each(|&n| piece[n] = true);
                }
            }
            let recovery = PatchRecovery::of_nodes(mesh, &piece);
            recovery.elements().iter().for_each(|&e| keep[e] = true);
            self.recovery = Some(Arc::new(recovery));
        }
        problem.model.hold_elements(&keep);
        #[cfg(feature = "petsc")]
        crate::solve::petsc::distributed::release_freed_memory();
    }

    /// This process's piece of every `.pvtu`: its elements, and the
    /// recovery of their nodes.
    pub fn pieces(&self) -> Pieces {
        Pieces {
            rank: self.rank,
            parts: self.partition.parts,
            elements: self.owned_elements(),
            recovery: self.recovery.clone(),
        }
    }

    /// Rank 0 writes the run's files and its log.
    pub fn is_lead(&self) -> bool {
        self.rank == 0
    }

    /// The strategy of a distributed run: monolithic Newton (the condensed
    /// path is serial); an error when the case asks for the condensed one.
    pub fn strategy(&self, problem: &Problem, choice: Choice, case_label: &str) -> Result<Choice> {
        if choice.path == SolvePath::Monolithic {
            return Ok(choice);
        }
        if problem.settings.strategy == Strategy::Condensed {
            return Err(Error::Case {
                path: case_label.into(),
                message: format!(
                    "solver.strategy = \"condensed\" runs on one process; this run has {} \
                     (mpirun -np): use strategy = \"auto\" or \"monolithic\"",
                    self.partition.parts
                ),
            });
        }
        Ok(Choice {
            path: SolvePath::Monolithic,
            reason: format!(
                "distributed over {} processes: PETSc solves the monolithic Newton systems",
                self.partition.parts
            ),
        })
    }

    /// The linear solver: PETSc's KSP on the distributed matrix, set from
    /// `[solver.petsc] options` (whatever `[solver] linear` says).
    pub fn linear_solver(
        &self,
        problem: &Problem,
    ) -> Result<Box<dyn crate::solve::linear_solver::LinearSolver>> {
        #[cfg(feature = "petsc")]
        {
            let _ = &self.world;
            let coordinates = problem.model.mesh.nodes.iter().flatten().copied().collect();
            Ok(Box::new(
                crate::solve::petsc::distributed::DistributedPetscSolver::new(
                    &problem.settings.petsc_options,
                    self.partition.clone(),
                    self.rank,
                    coordinates,
                )?,
            ))
        }
        #[cfg(not(feature = "petsc"))]
        {
            let _ = problem;
            Err(Error::LinearSolver(
                crate::solve::backend::PETSC_MISSING.into(),
            ))
        }
    }

    /// The elements this process writes (its piece of each `.pvtu`).
    pub fn owned_elements(&self) -> Vec<usize> {
        (0..self.partition.element_part.len())
            .filter(|&e| self.partition.element_part[e] == self.rank)
            .collect()
    }

    /// The partition for the log: elements, nodes and contact nodes of
    /// each process (a contact zone cut by the partition has contact
    /// nodes on several processes).
    pub fn describe(&self, problem: &Problem) -> Vec<String> {
        let elements = self.partition.element_counts();
        let nodes = self.partition.node_counts();
        let mut contact = vec![0; self.partition.parts];
        for c in &problem.contacts {
            for &n in &c.nodes {
                contact[self.partition.node_part[n]] += 1;
            }
        }
        let mut lines = vec![format!(
            "distributed: {} processes, elements partitioned by {}",
            self.partition.parts, self.partition.method
        )];
        for p in 0..self.partition.parts {
            lines.push(format!(
                "partition: rank {p}: {} elements, {} nodes, {} contact nodes",
                elements[p], nodes[p], contact[p]
            ));
        }
        lines.extend(self.rows_held(problem));
        lines
    }
}

impl Distribution {
    /// What each process holds of the tangent (the entries of its own
    /// pattern, [`Problem::set_share`], gathered from every process: a
    /// collective) and of the residual (every dof, still whole), beside its
    /// own rows and ghost layer as the partition counts them
    /// ([`MeshPartition::local_sizes`], issue 29 item 1), for the log.
    fn rows_held(&self, problem: &Problem) -> Vec<String> {
        let mesh = &problem.model.mesh;
        // per rank: tangent entries, own and ghost rows' entries and
        // nodes, elements held; each process counts its own
        const COUNTS: usize = 6;
        let mut held = vec![0.0; COUNTS * self.partition.parts];
        let s = self.partition.local_sizes(mesh, self.rank);
        let mine = [
            problem.model.pattern.nnz(),
            s.own_entries,
            s.own_nodes,
            s.ghost_entries,
            s.ghost_nodes,
            mesh.held_elements(),
        ];
        for (k, count) in mine.into_iter().enumerate() {
            held[COUNTS * self.rank + k] = count as f64;
        }
        if let Some(share) = problem.model.share() {
            share.communicator.sum(&mut held);
        }
        let dofs = problem.model.pattern.dimension();
        let elements = mesh.elements.len();
        let rows = (0..self.partition.parts).map(|p| {
            let c: Vec<usize> = held[COUNTS * p..COUNTS * (p + 1)]
                .iter()
                .map(|&v| v as usize)
                .collect();
            format!(
                "rows: rank {p}: holds {} tangent entries and {dofs} residual values; \
                 its own rows {} entries ({} nodes), ghost rows {} entries ({} nodes)",
                c[0], c[1], c[2], c[3], c[4]
            )
        });
        let meshes = (0..self.partition.parts).map(|p| {
            format!(
                "mesh: rank {p}: holds the connectivity of {} of {elements} elements \
                 (its own, the ghost layer of its rows and the patches its recovered fields read)",
                held[COUNTS * p + 5] as usize
            )
        });
        rows.chain(meshes).collect()
    }
}

/// Mark the run's `summary.json` at `path` failed with `message`, unless
/// it says so already (rank 0 wrote its own error): the status a process
/// that ends the run leaves for the user. Nothing when there is no
/// summary yet or it does not read.
fn mark_failed(path: &Path, message: &str) {
    let Ok(text) = std::fs::read_to_string(path) else {
        return;
    };
    let Ok(mut summary) = serde_json::from_str::<serde_json::Value>(&text) else {
        return;
    };
    if summary["status"] == "failed" {
        return;
    }
    summary["status"] = "failed".into();
    summary["error"] = message.into();
    let Ok(text) = serde_json::to_string_pretty(&summary) else {
        return;
    };
    let _ = crate::output::write_atomically(path, |w| w.write_all(text.as_bytes()));
}

/// End this process at once (no finalisation that would wait for
/// processes that are gone).
fn exit_now(code: i32) -> ! {
    #[cfg(feature = "petsc")]
    crate::solve::petsc::fault::exit_now(code);
    #[cfg(not(feature = "petsc"))]
    std::process::exit(code)
}
