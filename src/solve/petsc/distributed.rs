//! The distributed linear solve of `mpirun -np N signorini run case.toml`:
//! MPI's world (through PETSc, initialised once) as a [`Communicator`],
//! and a [`LinearSolver`] whose matrix is PETSc's distributed MPIAIJ.
//!
//! Every process assembles its part `K^p` of the tangent (the rows of the
//! elements it owns, [`crate::assembly::share`]) on its own pattern. The
//! nodes are renumbered part after part (each part's nodes in mesh order,
//! their three dofs together; contact multipliers, if any, keep their
//! places at the end and belong to the last process), so that each
//! process owns one contiguous block of PETSc's rows: the rows of its
//! nodes. The matrix is preallocated once per pattern for the entries
//! every process gives (PETSc's `MATPREALLOCATOR`; [`RowLayout`]: the rows
//! of its pattern it owns, and those its elements or the contact
//! couplings touch) and is the tangent's one copy: Newton assembles into
//! it through [`LinearSolver::tangent_sink`] ([`MatrixSink`]: the element
//! blocks by `MatSetValues` with `ADD_VALUES` after `MatZeroEntries`,
//! contact and loads in the own rows, the prescribed rows by
//! `MatZeroRowsColumns`), and no process keeps a values array of `K^p`.
//! PETSc adds the processes' parts, sending the ghost rows' to their
//! owners at the assembly, and keeps no map from our entries to its. Each
//! process sets the right-hand side of its own rows; the KSP solves
//! distributed and the solution is scattered whole to every process
//! (`VecScatterCreateToAll`), so every process goes on with the same
//! unknowns. Without multipliers
//! the matrix has block size 3 and the rigid-body modes of each process's
//! own nodes; with them and `-pc_type fieldsplit`, fieldsplit's two fields
//! are each process's own displacement rows (those modes their near-null
//! space) and its own multiplier rows (the last process's).

use super::fault::{self, Agreement, Severity};
use super::{
    check_indices, make_ksp, message, solve_failure, Columns, Outcome, Tally, MESSAGE, PETSC,
};
use crate::assembly::share::Communicator;
use crate::assembly::sink::{Entries, TangentSink};
use crate::solve::failure::IncrementFailure;
use crate::solve::linear::{pattern_fingerprint, Ordering};
use crate::solve::linear_solver::{LinearSolver, LinearSystem, SolverStatistics};
use crate::solve::partition::MeshPartition;
use crate::{Error, Result};
use faer::sparse::SymbolicSparseColMat;
use std::ffi::{c_char, c_int, c_void};
use std::sync::{Arc, Mutex, PoisonError};
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
        pub fn sg_release_freed_memory();
        pub fn sg_petsc_mpi_solver_new(
            out: *mut *mut c_void,
            options: *const c_char,
            err: *mut c_char,
            len: usize,
        ) -> c_int;
        pub fn sg_petsc_mpi_solver_free(handle: *mut c_void);
        pub fn sg_petsc_mpi_layout(
            handle: *mut c_void,
            layout: *const super::DistributedLayout,
            err: *mut c_char,
            len: usize,
        ) -> c_int;
        pub fn sg_petsc_mpi_begin(handle: *mut c_void, err: *mut c_char, len: usize) -> c_int;
        pub fn sg_petsc_mpi_add_block(
            handle: *mut c_void,
            n: c_int,
            rows: *const c_int,
            columns: *const c_int,
            values: *const f64,
            err: *mut c_char,
            len: usize,
        ) -> c_int;
        pub fn sg_petsc_mpi_add_columns(
            handle: *mut c_void,
            columns: *const super::Columns,
            values: *const f64,
            mirrored: c_int,
            err: *mut c_char,
            len: usize,
        ) -> c_int;
        pub fn sg_petsc_mpi_finish(handle: *mut c_void, err: *mut c_char, len: usize) -> c_int;
        pub fn sg_petsc_mpi_multiply(
            handle: *mut c_void,
            x: *const f64,
            y: *mut f64,
            err: *mut c_char,
            len: usize,
        ) -> c_int;
        pub fn sg_petsc_mpi_identity_rows(
            handle: *mut c_void,
            n: c_int,
            rows: *const c_int,
            free_rows: *const c_char,
            scale: *mut f64,
            err: *mut c_char,
            len: usize,
        ) -> c_int;
        pub fn sg_petsc_mpi_solve(
            handle: *mut c_void,
            b: *const f64,
            x: *mut f64,
            iterations: *mut c_int,
            seconds: *mut f64,
            err: *mut c_char,
            len: usize,
        ) -> c_int;
    }
}

/// The matrix layout for the C layer (`DistributedLayout` in `shim.c`):
/// the columns of the entries this process gives, rows mapped to PETSc's
/// (negative: left out); the coordinates of its own nodes, and the
/// number of displacement unknowns (the multipliers after them).
#[repr(C)]
struct DistributedLayout {
    global: c_int,
    first: c_int,
    local: c_int,
    block_size: c_int,
    columns: Columns,
    coordinates: *const f64,
    displacements: c_int,
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

/// Give the pages of memory freed so far back to the system (glibc's
/// `malloc_trim`; nothing elsewhere): after a distributed run's set-up
/// (each process's share of the model), the other processes' element
/// geometry and the whole element graph, freed in small pieces, would
/// otherwise stay resident.
pub fn release_freed_memory() {
    // SAFETY: no arguments; malloc_trim only returns free pages
    unsafe { ffi::sg_release_freed_memory() };
}

/// The numbering of PETSc's rows: displacement dofs part after part,
/// multipliers last (on the last process).
struct Numbering {
    /// `global[old]`: PETSc's row of unknown `old`.
    global: Vec<usize>,
    /// The same, as PETSc's indices (its column of column `old`).
    columns: Vec<c_int>,
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
            columns: global.iter().map(|&g| g as c_int).collect(),
            global,
            first,
            owned,
        }
    }
}

/// Which rows this process gives PETSc for one pattern of the tangent
/// (rebuilt when contact pairs change it). The pattern is this process's
/// own ([`crate::assembly::share`]): its elements' rows and the contact
/// couplings (the other processes' nodes it does not touch have empty
/// columns). It gives every entry of its own rows and of the rows it
/// touches (a node coupled to another node or to a multiplier: a ghost
/// node, a contact node). Every process adds the contact and loads in its
/// own rows only ([`crate::assembly::Model::foreign_entries`]), so the
/// rows left out are the diagonal blocks of contact nodes it does not
/// otherwise touch (zero, or the scaled identity of a prescribed dof,
/// which its owner gives) and the other processes' multiplier rows (zero:
/// the last process owns the multipliers and adds their rows).
struct RowLayout {
    fingerprint: u64,
    /// `rows[old]`: PETSc's row of row `old` (old numbering) if this
    /// process gives its entries, else -1.
    rows: Vec<c_int>,
}

impl RowLayout {
    /// The rows this process (of `numbering`) gives of `pattern` (of
    /// `nodes` nodes, their dofs first, then the multipliers).
    fn new(pattern: &SymbolicSparseColMat<usize>, numbering: &Numbering, nodes: usize) -> Self {
        let end = numbering.first + numbering.owned.len();
        let col_ptr = pattern.col_ptr();
        // the pattern is symmetric: row i holds column i's rows
        let touched = |i: usize| {
            let first = 3 * (i / 3);
            col_ptr[first + 1] - col_ptr[first] > 3
        };
        let rows = (0..pattern.nrows())
            .map(|i| {
                let given = (numbering.first..end).contains(&numbering.global[i])
                    || (i < 3 * nodes && touched(i));
                if given {
                    numbering.columns[i]
                } else {
                    -1
                }
            })
            .collect();
        RowLayout {
            fingerprint: pattern_fingerprint(pattern),
            rows,
        }
    }

    /// Whether this process gives the entries of row `old`.
    #[cfg(test)]
    fn gives(&self, old: usize) -> bool {
        self.rows[old] >= 0
    }
}

/// The C layer's distributed solver (its KSP, matrix and vectors), freed
/// when the solver and every sink of it are gone.
struct Handle(*mut c_void);

// SAFETY: the handle is only used under the `PETSC` lock
unsafe impl Send for Handle {}
// SAFETY: as above: every call through it holds the `PETSC` lock
unsafe impl Sync for Handle {}

impl Drop for Handle {
    fn drop(&mut self) {
        let _lock = PETSC.lock().unwrap_or_else(|e| e.into_inner());
        // SAFETY: the handle came from sg_petsc_mpi_solver_new, freed once
        unsafe { ffi::sg_petsc_mpi_solver_free(self.0) };
    }
}

impl Handle {
    /// Call the C layer's `f` with the handle and an error buffer, under
    /// the `PETSC` lock; its message if it failed.
    fn call(
        &self,
        f: impl FnOnce(*mut c_void, *mut c_char, usize) -> c_int,
    ) -> std::result::Result<(), String> {
        self.call_coded(f).map_err(|(_, message)| message)
    }

    /// [`Handle::call`], with the C layer's return code beside the message.
    fn call_coded(
        &self,
        f: impl FnOnce(*mut c_void, *mut c_char, usize) -> c_int,
    ) -> std::result::Result<(), (c_int, String)> {
        let mut err = [0 as c_char; MESSAGE];
        let _lock = PETSC.lock().unwrap_or_else(|e| e.into_inner());
        match f(self.0, err.as_mut_ptr(), err.len()) {
            0 => Ok(()),
            code => Err((code, message(&err))),
        }
    }
}

/// PETSc's KSP and PC on the distributed tangent.
pub struct DistributedPetscSolver {
    handle: Arc<Handle>,
    partition: MeshPartition,
    rank: usize,
    /// Reference coordinates (3 per node) for GAMG's near-null space.
    coordinates: Vec<f64>,
    numbering: Option<Arc<Numbering>>,
    layout: Option<RowLayout>,
    /// The matrix as Newton's sink, for the current layout.
    sink: Option<Arc<MatrixSink>>,
    description: String,
    /// The options it was made from, for the message of a failed set-up.
    options: String,
    tally: Tally,
}

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
        let (handle, description, options) = make_ksp(
            options,
            ffi::sg_petsc_mpi_solver_new,
            ffi::sg_petsc_mpi_solver_free,
            super::ffi::sg_petsc_describe,
        )?;
        let parts = partition.parts;
        Ok(DistributedPetscSolver {
            handle: Arc::new(Handle(handle)),
            partition,
            rank,
            coordinates,
            numbering: None,
            layout: None,
            sink: None,
            description: format!("{description}, distributed over {parts} processes"),
            options,
            tally: Tally::default(),
        })
    }

    /// A new pattern: the numbering (when the unknowns changed), the rows
    /// this process gives and PETSc's matrix preallocated for the entries
    /// every process gives, its vectors and near-null space.
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
            self.numbering = Some(Arc::new(Numbering::new(
                &self.partition,
                self.rank,
                unknowns,
            )));
        }
        let Some(numbering) = &self.numbering else {
            return Err("no numbering".into());
        };
        check_indices(pattern, false).map_err(|e| e.to_string())?;
        let displacements = 3 * self.partition.node_part.len();
        let layout = RowLayout::new(pattern, numbering, self.partition.node_part.len());
        let displacement_only = displacements == unknowns;
        // the coordinates of this process's own nodes: its displacement
        // rows come first among its rows, its multipliers' (if last) after
        let coordinates: Vec<f64> = numbering
            .owned
            .iter()
            .filter(|&&old| old < displacements)
            .map(|&old| self.coordinates[old])
            .collect();
        let arguments = DistributedLayout {
            global: unknowns as c_int,
            first: numbering.first as c_int,
            local: numbering.owned.len() as c_int,
            block_size: if displacement_only { 3 } else { 1 },
            columns: Columns::of(pattern, &layout.rows, &numbering.columns),
            coordinates: coordinates.as_ptr(),
            displacements: displacements as c_int,
        };
        // SAFETY: the pattern's arrays and the maps (one per unknown) live
        // until the call returns; PETSc keeps none of them
        self.handle
            .call(|h, err, len| unsafe { ffi::sg_petsc_mpi_layout(h, &arguments, err, len) })?;
        self.sink = Some(Arc::new(MatrixSink::new(
            Arc::clone(&self.handle),
            Arc::clone(numbering),
            &layout,
        )));
        self.layout = Some(layout);
        Ok(())
    }
}

impl LinearSolver for DistributedPetscSolver {
    /// PETSc orders the unknowns itself.
    fn set_ordering(&mut self, _ordering: Ordering) {}

    /// `system.matrix` is this process's part `K^p`; `rhs` the whole
    /// right-hand side (the same on every process); `x` the whole solution.
    /// The processes agree on the outcome ([`fault::agree`]): a solve that
    /// failed on one fails on every one, with its message and its kind,
    /// the most severe winning ([`settled`]). A set-up failure
    /// ([`IncrementFailure::LinearSolverSetUp`]) on any process ends the
    /// run on every one at once.
    fn solve(
        &mut self,
        system: &LinearSystem<'_>,
        rhs: &[f64],
        x: &mut [f64],
    ) -> std::result::Result<(), IncrementFailure> {
        let local = self.solve_here(system, rhs, x);
        agreed(local)
    }

    fn description(&self) -> String {
        self.description.clone()
    }

    fn statistics(&self) -> SolverStatistics {
        self.tally.statistics()
    }

    /// PETSc's preconditioners are its own.
    fn reads_symmetric_neighbour(&self) -> bool {
        false
    }

    /// The distributed matrix, laid out for `pattern` (preallocated anew
    /// when the pattern changed): Newton assembles into it.
    fn tangent_sink(
        &mut self,
        pattern: &SymbolicSparseColMat<usize>,
    ) -> std::result::Result<Option<Arc<dyn TangentSink>>, String> {
        let fingerprint = pattern_fingerprint(pattern);
        if self
            .layout
            .as_ref()
            .is_none_or(|l| l.fingerprint != fingerprint)
        {
            self.lay_out(pattern)?;
        }
        let sink = self.sink.as_ref().ok_or("no matrix layout")?;
        Ok(Some(Arc::clone(sink) as Arc<dyn TangentSink>))
    }
}

/// The outcome every process agreed on, given this process's `local` one
/// ([`settled`]); a process that failed alone while another is stuck ends
/// the run ([`fault::fault`]).
fn agreed(
    local: std::result::Result<(), IncrementFailure>,
) -> std::result::Result<(), IncrementFailure> {
    let text = local.as_ref().err().map(|f| (severity(f), f.to_string()));
    let agreement = fault::agree(text.as_ref().map_or(Ok(()), |(s, m)| Err((*s, m.as_str()))));
    if agreement == Agreement::NoAnswer {
        fault::fault(text.as_ref().map_or("no answer", |(_, m)| m.as_str()));
    }
    settled(local, agreement)
}

/// How severe a failed solve is at the agreement: final when no cut
/// mends it ([`IncrementFailure::mended_by_a_cut`]).
fn severity(failure: &IncrementFailure) -> Severity {
    if failure.mended_by_a_cut() {
        Severity::Mendable
    } else {
        Severity::Final
    }
}

/// A failure on any process is a failure on all, of the most severe kind
/// any process met: this process's own when it is that severe, else the
/// failed process's message with its rank, a failed solve (cut) or a
/// linear solver that cannot be set up (the run ends: issue 29 item 6, a
/// set-up that failed on one process only).
fn settled(
    local: std::result::Result<(), IncrementFailure>,
    agreement: Agreement,
) -> std::result::Result<(), IncrementFailure> {
    let Agreement::Failed {
        rank,
        severity: agreed,
        message,
    } = agreement
    else {
        return local;
    };
    match local {
        Err(mine) if severity(&mine) >= agreed => Err(mine),
        _ => {
            let message = format!("process {rank}: {message}");
            Err(match agreed {
                Severity::Mendable => IncrementFailure::LinearSolve(message),
                Severity::Final => IncrementFailure::LinearSolverSetUp(message),
            })
        }
    }
}

impl DistributedPetscSolver {
    /// This process's part of [`LinearSolver::solve`]: the system's
    /// matrix is the one Newton filled through the sink
    /// ([`LinearSolver::tangent_sink`]).
    fn solve_here(
        &mut self,
        system: &LinearSystem<'_>,
        rhs: &[f64],
        x: &mut [f64],
    ) -> std::result::Result<(), IncrementFailure> {
        let start = Instant::now();
        let fingerprint = pattern_fingerprint(system.pattern);
        let (Some(numbering), Some(layout)) = (&self.numbering, &self.layout) else {
            return Err(IncrementFailure::LinearSolve(
                "the distributed matrix was not filled before the solve".into(),
            ));
        };
        if layout.fingerprint != fingerprint || !system.matrix.is_empty() {
            return Err(IncrementFailure::LinearSolve(
                "the distributed solver takes the tangent through its matrix \
                        (LinearSolver::tangent_sink), not as values"
                    .into(),
            ));
        }
        let b: Vec<f64> = numbering.owned.iter().map(|&old| rhs[old]).collect();
        let mut solution = vec![0.0; rhs.len()];
        let mut outcome = Outcome::default();
        let (iterations, seconds) = (&mut outcome.iterations, outcome.seconds.as_mut_ptr());
        // SAFETY: b holds this process's rows, `solution` the n unknowns
        // PETSc writes, the outcome's fields live until the call returns
        let result = self.handle.call_coded(|h, err, len| unsafe {
            ffi::sg_petsc_mpi_solve(
                h,
                b.as_ptr(),
                solution.as_mut_ptr(),
                iterations,
                seconds,
                err,
                len,
            )
        });
        numbering.to_ours(&solution, x);
        let result = result.map_err(|(code, m)| solve_failure(code, m, &self.options));
        self.tally.record(start, &outcome, result, x)
    }
}

impl Numbering {
    /// `ours[old] = petsc[global[old]]`: a whole vector in PETSc's
    /// numbering into ours.
    fn to_ours(&self, petsc: &[f64], ours: &mut [f64]) {
        for (old, v) in ours.iter_mut().enumerate() {
            *v = petsc[self.global[old]];
        }
    }
}

/// The distributed matrix as Newton's [`TangentSink`]: our unknowns mapped
/// to PETSc's rows and columns ([`Numbering`], [`RowLayout`]), every call
/// under the `PETSC` lock. The first failure is kept and reported by the
/// next collective call that returns a result.
struct MatrixSink {
    handle: Arc<Handle>,
    numbering: Arc<Numbering>,
    /// PETSc's row of each of our rows this process gives (-1: none).
    given: Vec<c_int>,
    /// PETSc's row of each of our rows this process owns (-1: another's).
    own: Vec<c_int>,
    failure: Mutex<Option<String>>,
}

impl MatrixSink {
    fn new(handle: Arc<Handle>, numbering: Arc<Numbering>, layout: &RowLayout) -> Self {
        let end = numbering.first + numbering.owned.len();
        let own = numbering
            .global
            .iter()
            .map(|&g| {
                if (numbering.first..end).contains(&g) {
                    g as c_int
                } else {
                    -1
                }
            })
            .collect();
        MatrixSink {
            handle,
            numbering,
            given: layout.rows.clone(),
            own,
            failure: Mutex::new(None),
        }
    }

    /// Keep the first failure of `result`.
    fn keep(&self, result: std::result::Result<(), String>) {
        if let Err(e) = result {
            let mut failure = self.failure.lock().unwrap_or_else(PoisonError::into_inner);
            failure.get_or_insert(e);
        }
    }

    /// The failure kept so far (taken), or `result`.
    fn kept_or(&self, result: std::result::Result<(), String>) -> std::result::Result<(), String> {
        let kept = self
            .failure
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .take();
        kept.map_or(result, Err)
    }
}

impl TangentSink for MatrixSink {
    fn begin(&self) {
        // SAFETY: the handle and the buffer are valid
        let result = self
            .handle
            .call(|h, err, len| unsafe { ffi::sg_petsc_mpi_begin(h, err, len) });
        self.keep(result);
    }

    fn add_element(&self, dofs: &[usize], values: &[f64]) {
        let mut rows = [0 as c_int; 3 * crate::assembly::kernel::MAX_NODES];
        let mut columns = rows;
        let n = dofs.len().min(rows.len());
        for (k, &d) in dofs.iter().take(n).enumerate() {
            rows[k] = self.given[d];
            columns[k] = self.numbering.columns[d];
        }
        // SAFETY: n rows and columns, n² values (the caller's dense block)
        let result = self.handle.call(|h, err, len| unsafe {
            ffi::sg_petsc_mpi_add_block(
                h,
                n as c_int,
                rows.as_ptr(),
                columns.as_ptr(),
                values.as_ptr(),
                err,
                len,
            )
        });
        self.keep(result);
    }

    fn add_columns(&self, pattern: &SymbolicSparseColMat<usize>, values: &[f64], which: Entries) {
        let rows = match which {
            Entries::LowerMirrored => &self.given,
            Entries::OwnRows => &self.own,
        };
        let columns = Columns::of(pattern, rows, &self.numbering.columns);
        let mirrored = (which == Entries::LowerMirrored) as c_int;
        // SAFETY: the pattern's arrays, the maps (one per unknown) and the
        // values (one per entry) live until the call returns
        let result = self.handle.call(|h, err, len| unsafe {
            ffi::sg_petsc_mpi_add_columns(h, &columns, values.as_ptr(), mirrored, err, len)
        });
        self.keep(result);
    }

    fn finish(&self) -> std::result::Result<(), String> {
        // SAFETY: the handle and the buffer are valid
        let result = self
            .handle
            .call(|h, err, len| unsafe { ffi::sg_petsc_mpi_finish(h, err, len) });
        self.kept_or(result)
    }

    fn multiply(&self, x: &[f64], y: &mut [f64]) -> std::result::Result<(), String> {
        let own: Vec<f64> = self.numbering.owned.iter().map(|&old| x[old]).collect();
        let mut whole = vec![0.0; y.len()];
        // SAFETY: `own` holds this process's rows, `whole` every unknown
        let result = self.handle.call(|h, err, len| unsafe {
            ffi::sg_petsc_mpi_multiply(h, own.as_ptr(), whole.as_mut_ptr(), err, len)
        });
        self.numbering.to_ours(&whole, y);
        self.kept_or(result)
    }

    fn identity_rows(&self, constrained: &[bool], dofs: usize) -> std::result::Result<f64, String> {
        let owned = &self.numbering.owned;
        let rows: Vec<c_int> = owned
            .iter()
            .filter(|&&old| constrained[old])
            .map(|&old| self.own[old])
            .collect();
        let free: Vec<c_char> = owned
            .iter()
            .map(|&old| (old < dofs && !constrained[old]) as c_char)
            .collect();
        let mut scale = 1.0;
        // SAFETY: the rows and the flags (one per own row) live until the
        // call returns
        let result = self.handle.call(|h, err, len| unsafe {
            ffi::sg_petsc_mpi_identity_rows(
                h,
                rows.len() as c_int,
                rows.as_ptr(),
                free.as_ptr(),
                &mut scale,
                err,
                len,
            )
        });
        self.kept_or(result).map(|()| scale)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The outcome a process acts on after an agreement: a set-up that
    /// failed on another process ends this one's run too, even when its
    /// own solve succeeded or failed in a way a cut mends (issue 29 item
    /// 6: it used to cut); a mendable failure elsewhere is a failed solve
    /// here; this process's own failure stands when it is that severe.
    #[test]
    fn the_most_severe_failure_of_any_process_is_this_ones() {
        let failed = |severity, message: &str| Agreement::Failed {
            rank: 1,
            severity,
            message: message.into(),
        };
        let set_up = || failed(Severity::Final, "PETSc error 92");
        let diverged = || IncrementFailure::LinearSolve("diverged".into());
        for local in [Ok(()), Err(diverged())] {
            let outcome = settled(local, set_up());
            let Err(IncrementFailure::LinearSolverSetUp(message)) = &outcome else {
                panic!("{outcome:?}");
            };
            assert_eq!(message, "process 1: PETSc error 92");
        }
        let outcome = settled(Ok(()), failed(Severity::Mendable, "diverged"));
        assert!(
            matches!(&outcome, Err(IncrementFailure::LinearSolve(m)) if m == "process 1: diverged"),
            "{outcome:?}"
        );
        let mine = IncrementFailure::LinearSolverSetUp("mine".into());
        let outcome = settled(Err(mine), set_up());
        assert!(
            matches!(&outcome, Err(IncrementFailure::LinearSolverSetUp(m)) if m == "mine"),
            "{outcome:?}"
        );
        let outcome = settled(Err(diverged()), failed(Severity::Mendable, "other"));
        assert!(
            matches!(&outcome, Err(IncrementFailure::LinearSolve(m)) if m == "diverged"),
            "{outcome:?}"
        );
        assert!(settled(Ok(()), Agreement::Succeeded).is_ok());
    }

    /// Process `rank` of two (nodes 0 and 1 part 0's, 2 to 4 part 1's)
    /// on its own pattern: its element couples nodes 1 and 2 (node 2 a
    /// ghost of part 0, node 1 of part 1), a contact multiplier couples
    /// node 3, node 4 only its diagonal block. Part 0 gives its own rows,
    /// the ghost's and the contact node's, not node 4's diagonal block nor
    /// the multiplier's row; part 1 (which owns the multiplier, last) its
    /// own and the ghost's, not node 0's diagonal block.
    #[test]
    fn a_process_gives_its_rows_and_the_ones_it_touches() {
        use crate::assembly::pattern::SparsityPattern;
        let partition = MeshPartition {
            parts: 2,
            method: "test".into(),
            element_part: vec![0, 1],
            node_part: vec![0, 0, 1, 1, 1],
        };
        let element: &[usize] = &[1, 2];
        let pattern = SparsityPattern::with_multipliers(5, [element].into_iter(), &[vec![3]]);
        let given = |rank: usize| -> Vec<usize> {
            let numbering = Numbering::new(&partition, rank, 16);
            let layout = RowLayout::new(pattern.symbolic(), &numbering, 5);
            (0..16).filter(|&i| layout.gives(i)).collect()
        };
        let dofs = |nodes: &[usize]| -> Vec<usize> {
            nodes.iter().flat_map(|&a| 3 * a..3 * a + 3).collect()
        };
        assert_eq!(given(0), dofs(&[0, 1, 2, 3]));
        let mut one = dofs(&[1, 2, 3, 4]);
        one.push(15);
        assert_eq!(given(1), one);
    }

    #[test]
    fn the_numbering_gives_each_part_a_block_and_multipliers_go_last() {
        let partition = MeshPartition {
            parts: 2,
            method: "test".into(),
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
