//! The distributed linear solve of `mpirun -np N signorini run case.toml`:
//! MPI's world (through PETSc, initialised once) as a [`Communicator`],
//! and a [`LinearSolver`] whose matrix is PETSc's distributed MPIAIJ.
//!
//! Every process holds the whole pattern and its part `K^p` of the
//! tangent (the elements it owns, [`crate::assembly::share`]). The nodes
//! are renumbered part after part (each part's nodes in mesh order, their
//! three dofs together; contact multipliers, if any, keep their places at
//! the end and belong to the last process), so that each process owns one
//! contiguous block of PETSc's rows: the rows of its nodes. Each process
//! adds the nonzero rows of its `K^p` into the matrix (`ADD_VALUES`; rows
//! of other processes travel through PETSc's stash) and sets the
//! right-hand side of its own rows; the KSP solves distributed and the
//! solution is scattered whole to every process (`VecScatterCreateToAll`),
//! so every process goes on with the same unknowns.

use super::fault::{self, Agreement};
use super::{make_ksp, message, RowPattern, Tally, MESSAGE, PETSC};
use crate::assembly::share::Communicator;
use crate::solve::linear::{pattern_fingerprint, Ordering};
use crate::solve::linear_solver::{LinearSolver, LinearSystem, SolverStatistics};
use crate::solve::partition::MeshPartition;
use crate::{Error, Result};
use faer::sparse::SymbolicSparseColMat;
use std::ffi::{c_char, c_int, c_void};
use std::time::Instant;

mod ffi {
    use std::ffi::{c_char, c_int, c_void};
    extern "C" {
        pub fn sg_mpi_world(
            rank: *mut c_int,
            size: *mut c_int,
            err: *mut c_char,
            len: usize,
        ) -> c_int;
        pub fn sg_mpi_sum(v: *mut f64, n: usize, err: *mut c_char, len: usize) -> c_int;
        pub fn sg_petsc_mpi_solver_new(
            out: *mut *mut c_void,
            options: *const c_char,
            err: *mut c_char,
            len: usize,
        ) -> c_int;
        pub fn sg_petsc_mpi_solver_free(handle: *mut c_void);
        pub fn sg_petsc_mpi_describe(
            handle: *mut c_void,
            text: *mut c_char,
            text_len: usize,
            err: *mut c_char,
            err_len: usize,
        ) -> c_int;
        pub fn sg_petsc_mpi_layout(
            handle: *mut c_void,
            layout: *const super::DistributedLayout,
            err: *mut c_char,
            len: usize,
        ) -> c_int;
        pub fn sg_petsc_mpi_solve(
            handle: *mut c_void,
            system: *const super::DistributedSystem,
            err: *mut c_char,
            len: usize,
        ) -> c_int;
    }
}

/// The matrix layout for the C layer (`DistributedLayout` in `shim.c`).
#[repr(C)]
struct DistributedLayout {
    global: c_int,
    first: c_int,
    local: c_int,
    block_size: c_int,
    row_start: *const c_int,
    columns: *const c_int,
    coordinates: *const f64,
}

/// This process's part of a system for the C layer (`DistributedSystem`).
#[repr(C)]
struct DistributedSystem {
    rows: c_int,
    row_index: *const c_int,
    row_start: *const c_int,
    columns: *const c_int,
    values: *const f64,
    b: *const f64,
    x: *mut f64,
    iterations: *mut c_int,
}

/// MPI's world, as PETSc initialised it.
pub struct MpiWorld {
    rank: usize,
    size: usize,
}

impl MpiWorld {
    /// Initialise PETSc (MPI with it) and read this process's rank and the
    /// number of processes.
    pub fn new() -> Result<Self> {
        super::initialise()?;
        let _lock = PETSC.lock().unwrap_or_else(|e| e.into_inner());
        let (mut rank, mut size) = (0 as c_int, 0 as c_int);
        let mut err = [0 as c_char; MESSAGE];
        // SAFETY: out-pointers and a buffer of the length given
        let code = unsafe { ffi::sg_mpi_world(&mut rank, &mut size, err.as_mut_ptr(), err.len()) };
        if code != 0 {
            return Err(Error::LinearSolver(message(&err)));
        }
        drop(_lock);
        super::fault::initialise(rank as usize, size as usize)?;
        Ok(MpiWorld {
            rank: rank as usize,
            size: size as usize,
        })
    }
}

impl Communicator for MpiWorld {
    fn rank(&self) -> usize {
        self.rank
    }
    fn size(&self) -> usize {
        self.size
    }
    /// A reduction to rank 0 and a broadcast (the same bits everywhere).
    /// An MPI failure here ends the process: the other processes would
    /// wait for this one forever.
    fn sum(&self, v: &mut [f64]) {
        if self.size <= 1 {
            return;
        }
        let _lock = PETSC.lock().unwrap_or_else(|e| e.into_inner());
        let mut err = [0 as c_char; MESSAGE];
        // SAFETY: v is valid for v.len() doubles, the buffer for its length
        let code = unsafe { ffi::sg_mpi_sum(v.as_mut_ptr(), v.len(), err.as_mut_ptr(), err.len()) };
        if code != 0 {
            drop(_lock);
            super::fault::fault(&message(&err));
        }
    }
}

/// The numbering of PETSc's rows: displacement dofs part after part,
/// multipliers last (on the last process).
struct Numbering {
    /// `global[old]`: PETSc's row of unknown `old`.
    global: Vec<usize>,
    /// This process's rows `[first, first + local)`, and the unknown of
    /// each (`owned[k]` is the unknown of row `first + k`).
    first: usize,
    owned: Vec<usize>,
}

impl Numbering {
    fn new(partition: &MeshPartition, rank: usize, unknowns: usize) -> Self {
        let nodes = partition.node_part.len();
        let mut order: Vec<usize> = (0..nodes).collect();
        order.sort_by_key(|&n| (partition.node_part[n], n));
        let mut global = vec![0; unknowns];
        for (new, &node) in order.iter().enumerate() {
            for c in 0..3 {
                global[3 * node + c] = 3 * new + c;
            }
        }
        for (g, m) in global.iter_mut().zip(0..unknowns).skip(3 * nodes) {
            *g = m;
        }
        let before: usize = partition.node_part.iter().filter(|&&p| p < rank).count();
        let mine = partition.node_part.iter().filter(|&&p| p == rank).count();
        let first = 3 * before;
        let mut end = first + 3 * mine;
        if rank + 1 == partition.parts {
            end = unknowns;
        }
        let mut owned = vec![0; end - first];
        for (old, &g) in global.iter().enumerate() {
            if (first..end).contains(&g) {
                owned[g - first] = old;
            }
        }
        Numbering {
            global,
            first,
            owned,
        }
    }
}

/// The pattern in compressed rows of PETSc's numbering, for one pattern
/// of the tangent (rebuilt when contact pairs change it).
struct RowLayout {
    fingerprint: u64,
    /// Every row (old numbering) in compressed rows: its start, the PETSc
    /// column of each entry and the entry's CSC position.
    row_start: Vec<usize>,
    columns: Vec<c_int>,
    position: Vec<usize>,
}

impl RowLayout {
    /// The compressed rows of [`RowPattern`] (the transpose of the CSC
    /// pattern) with PETSc's columns and each entry's CSC position.
    fn new(pattern: &SymbolicSparseColMat<usize>, numbering: &Numbering) -> Result<Self> {
        let rows = RowPattern::new(pattern)?;
        let mut csc = vec![0; rows.position.len()];
        for (k, &p) in rows.position.iter().enumerate() {
            csc[p] = k;
        }
        Ok(RowLayout {
            fingerprint: rows.fingerprint,
            row_start: rows.row_start.iter().map(|&s| s as usize).collect(),
            columns: rows
                .columns
                .iter()
                .map(|&j| numbering.global[j as usize] as c_int)
                .collect(),
            position: csc,
        })
    }

    /// The preallocation of this process's rows: their starts and sorted
    /// PETSc columns.
    fn owned_rows(&self, numbering: &Numbering) -> (Vec<c_int>, Vec<c_int>) {
        let mut start = vec![0 as c_int];
        let mut columns = Vec::new();
        for &old in &numbering.owned {
            let mut row = self.columns[self.row_start[old]..self.row_start[old + 1]].to_vec();
            row.sort_unstable();
            columns.extend(row);
            start.push(columns.len() as c_int);
        }
        (start, columns)
    }
}

/// PETSc's KSP and PC on the distributed tangent.
pub struct DistributedPetscSolver {
    handle: *mut c_void,
    partition: MeshPartition,
    rank: usize,
    /// Reference coordinates (3 per node) for GAMG's near-null space.
    coordinates: Vec<f64>,
    numbering: Option<Numbering>,
    layout: Option<RowLayout>,
    description: String,
    tally: Tally,
}

// SAFETY: the handle is only used under the `PETSC` lock
unsafe impl Send for DistributedPetscSolver {}

impl DistributedPetscSolver {
    /// A KSP on MPI's world set from `options` (after `PETSC_OPTIONS`,
    /// before the command line's), for the rows of `partition`'s part
    /// `rank`; `coordinates` (3 per node) give GAMG the rigid-body modes.
    pub fn new(
        options: &str,
        partition: MeshPartition,
        rank: usize,
        coordinates: Vec<f64>,
    ) -> Result<Self> {
        let (handle, description) = make_ksp(
            options,
            ffi::sg_petsc_mpi_solver_new,
            ffi::sg_petsc_mpi_solver_free,
            ffi::sg_petsc_mpi_describe,
        )?;
        let parts = partition.parts;
        Ok(DistributedPetscSolver {
            handle,
            partition,
            rank,
            coordinates,
            numbering: None,
            layout: None,
            description: format!("{description}, distributed over {parts} processes"),
            tally: Tally::default(),
        })
    }

    /// A new pattern: the numbering (when the unknowns changed), the row
    /// layout and PETSc's matrix, vectors and near-null space.
    fn lay_out(
        &mut self,
        pattern: &SymbolicSparseColMat<usize>,
    ) -> std::result::Result<(), String> {
        let unknowns = pattern.nrows();
        if self
            .numbering
            .as_ref()
            .is_none_or(|n| n.global.len() != unknowns)
        {
            self.numbering = Some(Numbering::new(&self.partition, self.rank, unknowns));
        }
        let Some(numbering) = &self.numbering else {
            return Err("no numbering".into());
        };
        let layout = RowLayout::new(pattern, numbering).map_err(|e| e.to_string())?;
        let (row_start, columns) = layout.owned_rows(numbering);
        let displacement_only = 3 * self.partition.node_part.len() == unknowns;
        let coordinates: Vec<f64> = if displacement_only {
            numbering
                .owned
                .iter()
                .map(|&old| self.coordinates[old])
                .collect()
        } else {
            Vec::new()
        };
        let arguments = DistributedLayout {
            global: unknowns as c_int,
            first: numbering.first as c_int,
            local: numbering.owned.len() as c_int,
            block_size: if displacement_only { 3 } else { 1 },
            row_start: row_start.as_ptr(),
            columns: columns.as_ptr(),
            coordinates: if displacement_only {
                coordinates.as_ptr()
            } else {
                std::ptr::null()
            },
        };
        let mut err = [0 as c_char; MESSAGE];
        let _lock = PETSC.lock().unwrap_or_else(|e| e.into_inner());
        // SAFETY: the arrays live until the call returns; PETSc copies them
        let code = unsafe {
            ffi::sg_petsc_mpi_layout(self.handle, &arguments, err.as_mut_ptr(), err.len())
        };
        if code != 0 {
            return Err(message(&err));
        }
        self.layout = Some(layout);
        Ok(())
    }
}

impl Drop for DistributedPetscSolver {
    fn drop(&mut self) {
        let _lock = PETSC.lock().unwrap_or_else(|e| e.into_inner());
        // SAFETY: the handle came from sg_petsc_mpi_solver_new, freed once
        unsafe { ffi::sg_petsc_mpi_solver_free(self.handle) };
    }
}

impl LinearSolver for DistributedPetscSolver {
    /// PETSc orders the unknowns itself.
    fn set_ordering(&mut self, _ordering: Ordering) {}

    /// `system.matrix` is this process's part `K^p`; `rhs` the whole
    /// right-hand side (the same on every process); `x` the whole solution.
    /// The processes agree on the outcome ([`fault::agree`]): a solve that
    /// failed on one fails on every one, with its message.
    fn solve(
        &mut self,
        system: &LinearSystem<'_>,
        rhs: &[f64],
        x: &mut [f64],
    ) -> std::result::Result<(), String> {
        let local = self.solve_here(system, rhs, x);
        agreed(local)
    }

    fn description(&self) -> String {
        self.description.clone()
    }

    fn statistics(&self) -> SolverStatistics {
        self.tally.statistics()
    }
}

/// The outcome every process agreed on, given this process's `local` one:
/// a failure on any process is a failure on all (this process's message,
/// or the failed one's with its rank); a process that failed alone while
/// another is stuck ends the run ([`fault::fault`]).
fn agreed(local: std::result::Result<(), String>) -> std::result::Result<(), String> {
    match fault::agree(local.as_ref().map(|_| ()).map_err(String::as_str)) {
        Agreement::Succeeded => Ok(()),
        Agreement::Failed { rank, message } => match local {
            Err(mine) => Err(mine),
            Ok(()) => Err(format!("process {rank}: {message}")),
        },
        Agreement::NoAnswer => fault::fault(local.err().as_deref().unwrap_or("no answer")),
    }
}

impl DistributedPetscSolver {
    /// This process's part of [`LinearSolver::solve`].
    fn solve_here(
        &mut self,
        system: &LinearSystem<'_>,
        rhs: &[f64],
        x: &mut [f64],
    ) -> std::result::Result<(), String> {
        let start = Instant::now();
        let fingerprint = pattern_fingerprint(system.pattern);
        if self
            .layout
            .as_ref()
            .is_none_or(|l| l.fingerprint != fingerprint)
        {
            self.lay_out(system.pattern)?;
        }
        let (Some(numbering), Some(layout)) = (&self.numbering, &self.layout) else {
            return Err("no matrix layout".into());
        };
        // the nonzero rows of K^p (a row of another process's node where
        // this process's elements touch it goes through PETSc's stash)
        let n = rhs.len();
        let mut row_index = Vec::new();
        let mut row_start = vec![0 as c_int];
        let mut columns = Vec::new();
        let mut values = Vec::new();
        for old in 0..n {
            let range = layout.row_start[old]..layout.row_start[old + 1];
            if layout.position[range.clone()]
                .iter()
                .all(|&k| system.matrix[k] == 0.0)
            {
                continue;
            }
            row_index.push(numbering.global[old] as c_int);
            columns.extend_from_slice(&layout.columns[range.clone()]);
            values.extend(layout.position[range].iter().map(|&k| system.matrix[k]));
            row_start.push(columns.len() as c_int);
        }
        let b: Vec<f64> = numbering.owned.iter().map(|&old| rhs[old]).collect();
        let mut solution = vec![0.0; n];
        let mut iterations: c_int = 0;
        let arguments = DistributedSystem {
            rows: row_index.len() as c_int,
            row_index: row_index.as_ptr(),
            row_start: row_start.as_ptr(),
            columns: columns.as_ptr(),
            values: values.as_ptr(),
            b: b.as_ptr(),
            x: solution.as_mut_ptr(),
            iterations: &mut iterations,
        };
        let mut err = [0 as c_char; MESSAGE];
        let code = {
            let _lock = PETSC.lock().unwrap_or_else(|e| e.into_inner());
            // SAFETY: the arrays live until the call returns; `solution`
            // holds the n unknowns PETSc writes
            unsafe { ffi::sg_petsc_mpi_solve(self.handle, &arguments, err.as_mut_ptr(), err.len()) }
        };
        for (old, xi) in x.iter_mut().enumerate() {
            *xi = solution[numbering.global[old]];
        }
        self.tally.record(start, iterations, code, &err, x)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_numbering_gives_each_part_a_block_and_multipliers_go_last() {
        let partition = MeshPartition {
            parts: 2,
            element_part: vec![0, 1],
            node_part: vec![1, 0, 1, 0],
        };
        // 4 nodes (12 dofs) and 2 multipliers
        let zero = Numbering::new(&partition, 0, 14);
        let one = Numbering::new(&partition, 1, 14);
        assert_eq!(zero.first, 0);
        assert_eq!(zero.owned, vec![3, 4, 5, 9, 10, 11]);
        assert_eq!(one.first, 6);
        assert_eq!(one.owned, vec![0, 1, 2, 6, 7, 8, 12, 13]);
        assert_eq!(zero.global, one.global);
        let mut seen = zero.global.clone();
        seen.sort_unstable();
        assert_eq!(seen, (0..14).collect::<Vec<_>>());
    }
}
