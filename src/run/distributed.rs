//! Runs on PETSc: the strategy rule of `[solver] linear = "petsc"`, and
//! the distributed run of `mpirun -np N signorini run case.toml` (cargo
//! feature `petsc`).
//!
//! A distributed run reads the case and mesh on every process and cuts
//! the elements into N parts with METIS ([`MeshPartition`]); each process
//! assembles its own elements ([`Share`]), the internal force is summed
//! over the processes, and the contact surfaces, contact states, Newton
//! and the stepping are replicated: every process computes them alike
//! from the same whole unknowns. PETSc solves each Newton system on the
//! distributed matrix ([`DistributedPetscSolver`]) and hands the whole
//! correction back to every process. Output: each process writes the
//! `.vtu` piece of its elements, rank 0 the `.pvtu` over them, the `.pvd`,
//! `summary.json` and the log.

use crate::problem::condensed::{Choice, Path as SolvePath};
use crate::problem::{LinearMethod, Problem};
use crate::solve::partition::MeshPartition;
use crate::solve::settings::Strategy;
use crate::{Error, Result};

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
    #[cfg(feature = "petsc")]
    world: std::sync::Arc<crate::solve::petsc::distributed::MpiWorld>,
}

impl Distribution {
    /// Under `mpirun`: join MPI's world (through PETSc), partition the
    /// mesh and give the model this process's elements. `None` without
    /// `mpirun`.
    pub fn start(problem: &mut Problem, case_label: &str) -> Result<Option<Self>> {
        let Some(processes) = launched_processes() else {
            return Ok(None);
        };
        Self::join(problem, case_label, processes)
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
        let world = std::sync::Arc::new(MpiWorld::new()?);
        let (rank, size) = (world.rank(), world.size());
        let partition = MeshPartition::new(&problem.model.mesh, size).map_err(|e| Error::Case {
            path: case_label.into(),
            message: e.to_string(),
        })?;
        problem.model.set_share(Share {
            owned: partition.owned_elements(rank),
            communicator: world.clone(),
        });
        Ok(Some(Distribution {
            rank,
            partition,
            world,
        }))
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
            "distributed: {} processes, elements partitioned by METIS (PartMeshDual)",
            self.partition.parts
        )];
        for p in 0..self.partition.parts {
            lines.push(format!(
                "partition: rank {p}: {} elements, {} nodes, {} contact nodes",
                elements[p], nodes[p], contact[p]
            ));
        }
        lines
    }
}
