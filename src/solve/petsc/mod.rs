//! A [`LinearSolver`] on PETSc (`[solver] linear = "petsc"`, cargo feature
//! `petsc`): the tangent goes to PETSc as a sequential AIJ matrix (block
//! size 3 when every unknown is a nodal displacement), and a KSP with its
//! PC solves it, both set from PETSc's options database. The default is a
//! direct LU by MUMPS (`-ksp_type preonly -pc_type lu
//! -pc_factor_mat_solver_type mumps`), which also takes the indefinite
//! saddle-point tangents of the Lagrangian contact methods. Users choose
//! anything else PETSc offers, e.g. GAMG (`-ksp_type cg -pc_type gamg`,
//! with the rigid-body near-null space attached from the node coordinates)
//! or hypre BoomerAMG (`-pc_type hypre`), through
//! `[solver.petsc] options = "…"` or the environment's `PETSC_OPTIONS`.
//!
//! PETSc's interface is partly C macros, so the calls go through a small C
//! layer (`shim.c`, compiled by `build.rs` against the installed headers);
//! this module owns the bookkeeping of [`LinearSolver`]. The tangent goes
//! to PETSc column by column (`MatSetValues` of each compressed column,
//! straight from the tangent's own arrays, into a matrix preallocated
//! once per pattern by PETSc's `MATPREALLOCATOR`): PETSc holds one
//! compressed-row copy of it beside Newton's values, and no map from our
//! entries to its. Under `mpirun` ([`distributed`]) Newton assembles into
//! PETSc's matrix itself, which is then the only copy.
//!
//! Each solver reads its options (the environment's `PETSC_OPTIONS`, then
//! the case's) under a prefix of its own, `sg<k>_`, in PETSc's global
//! options database, so two runs in one process do not share options and
//! the solvers PETSc makes inside a solver (fieldsplit's, multigrid's)
//! read them too. With `-pc_type fieldsplit` and contact multipliers the
//! C layer gives fieldsplit two fields, the displacements ("0", block size
//! 3, the rigid-body near-null space) and the multipliers ("1"). The
//! matrix products' options (`-matptap_via`, …: `product_options`) are
//! read by matrices PETSc makes with no prefix, from its global database:
//! the C layer puts a solver's there around its set-up and solve only.
//! Each solve's `KSPSetUp` and `KSPSolve` are timed apart
//! (`summary.json`'s `petsc_setup` and `petsc_solve`).
//!
//! PETSc is initialised once per process (MPI as a singleton when the
//! program was not started by `mpirun`) and finalised at exit. Calls into
//! it are serialised by a lock: PETSc is not thread-safe.

use super::failure::IncrementFailure;
use super::linear::{pattern_fingerprint, Ordering};
use super::linear_solver::{LinearSolver, LinearSystem, SolverStatistics};
use crate::{Error, Result};
use faer::sparse::SymbolicSparseColMat;
use std::ffi::{c_char, c_int, c_void, CStr, CString};
use std::sync::Mutex;
use std::time::{Duration, Instant};

mod ffi {
    use std::ffi::{c_char, c_int, c_void};
    extern "C" {
        pub fn sg_petsc_initialise(
            version: *mut c_char,
            version_len: usize,
            err: *mut c_char,
            err_len: usize,
        ) -> c_int;
        pub fn sg_petsc_solver_new(
            out: *mut *mut c_void,
            options: *const c_char,
            err: *mut c_char,
            len: usize,
        ) -> c_int;
        pub fn sg_petsc_solver_free(handle: *mut c_void);
        pub fn sg_petsc_describe(
            handle: *mut c_void,
            text: *mut c_char,
            text_len: usize,
            err: *mut c_char,
            err_len: usize,
        ) -> c_int;
        pub fn sg_petsc_solve(
            handle: *mut c_void,
            system: *const super::SystemArguments,
            err: *mut c_char,
            err_len: usize,
        ) -> c_int;
        pub fn sg_petsc_global_option(
            handle: *mut c_void,
            name: *const c_char,
            value: *const c_char,
            err: *mut c_char,
            err_len: usize,
        ) -> c_int;
    }
}

/// The tangent's compressed columns for the C layer (`Columns` in
/// `shim.c`, the same layout): the pattern's arrays as faer holds them,
/// and PETSc's row of each row (negative: left out) and column of each
/// column (null: the identity).
#[repr(C)]
struct Columns {
    columns: usize,
    col_ptr: *const usize,
    row_idx: *const usize,
    row_map: *const c_int,
    column_map: *const c_int,
}

impl Columns {
    /// The columns of `pattern`, with PETSc's `rows` and `columns` (empty:
    /// the identity); they borrow the arrays until the C call returns.
    fn of(pattern: &SymbolicSparseColMat<usize>, rows: &[c_int], columns: &[c_int]) -> Self {
        let map = |m: &[c_int]| {
            if m.is_empty() {
                std::ptr::null()
            } else {
                m.as_ptr()
            }
        };
        Columns {
            columns: pattern.ncols(),
            col_ptr: pattern.col_ptr().as_ptr(),
            row_idx: pattern.row_idx().as_ptr(),
            row_map: map(rows),
            column_map: map(columns),
        }
    }
}

/// One linear system for the C layer (`SystemArguments` in `shim.c`, the
/// same layout): the tangent's columns and their values, the right-hand
/// side, the solution and the Krylov iterations written back.
#[repr(C)]
struct SystemArguments {
    n: c_int,
    columns: Columns,
    values: *const f64,
    same_pattern: c_int,
    block_size: c_int,
    coordinates: *const f64,
    displacements: c_int,
    b: *const f64,
    x: *mut f64,
    iterations: *mut c_int,
    seconds: *mut f64,
}

/// Serialises every call into PETSc.
static PETSC: Mutex<()> = Mutex::new(());

pub mod distributed;
pub mod fault;
pub mod partitioning;

const MESSAGE: usize = 1024;

/// A message buffer the C layer writes into, as a Rust string.
pub(crate) fn message(buffer: &[c_char]) -> String {
    // SAFETY: the C layer writes a NUL-terminated string (snprintf) into a
    // zeroed buffer of this length, so there is a NUL within it
    unsafe { CStr::from_ptr(buffer.as_ptr()) }
        .to_string_lossy()
        .into_owned()
}

/// PETSc's error codes of a numerical failure that a smaller increment
/// may mend (`petscerror.h`): a zero pivot in LU and in Cholesky
/// (`PETSC_ERR_MAT_LU_ZRPVT`, `PETSC_ERR_MAT_CH_ZRPVT`), a floating-point
/// exception (`PETSC_ERR_FP`), a Krylov method that failed or did not
/// converge (`PETSC_ERR_CONV_FAILED`, `PETSC_ERR_NOT_CONVERGED`).
const NUMERICAL: [c_int; 5] = [71, 81, 72, 82, 91];

/// The range of PETSc's error codes (`PETSC_ERR_MIN_VALUE` + 1 to
/// `PETSC_ERR_MAX_VALUE` − 1).
const PETSC_CODES: std::ops::RangeInclusive<c_int> = 55..=99;

/// Why a PETSc solve failed, from the C layer's return `code` and its
/// `message`, decided by PETSc's error code, not by the message's text:
///
/// - a KSP that did not converge (a negative converged reason, which the
///   C layer returns as 1, no PETSc code) and the codes of [`NUMERICAL`]
///   are the matrix's: [`IncrementFailure::LinearSolve`], the increment
///   is cut. A singular tangent comes this way: with PETSc's
///   error-if-failure flags off (their default), a zero pivot or a failed
///   MUMPS factorisation is the PC's failed reason, so KSPSolve returns
///   `KSP_DIVERGED_PC_FAILED`; with `-ksp_error_if_not_converged` it is a
///   numerical code;
/// - every other PETSc code is the solver's settings, the same at every
///   increment: an unknown type (`PETSC_ERR_ARG_UNKNOWN_TYPE`), a value
///   out of range or wrong, a factorisation package PETSc lacks
///   (`PETSC_ERR_MISSING_FACTOR`, found at the first `KSPSetUp`), an
///   operation the matrix type does not support, memory:
///   [`IncrementFailure::LinearSolverSetUp`], PETSc's message with the
///   `options` the solver was made from and where to change them; the
///   run ends at once.
///
/// Anything else the C layer returns (its own checks) is cut as before.
fn solve_failure(code: c_int, message: String, options: &str) -> IncrementFailure {
    if !PETSC_CODES.contains(&code) || NUMERICAL.contains(&code) {
        return IncrementFailure::LinearSolve(message);
    }
    let environment = std::env::var("PETSC_OPTIONS")
        .ok()
        .filter(|e| !e.trim().is_empty())
        .map(|e| format!(" after PETSC_OPTIONS `{e}`"))
        .unwrap_or_default();
    IncrementFailure::LinearSolverSetUp(format!(
        "{message}. PETSc cannot set up the linear solver with the options `{}`{environment}, \
         and no smaller increment changes that: check the PETSc options after `--`, in \
         [solver.petsc] options and in PETSC_OPTIONS",
        options.trim()
    ))
}

/// An error when `pattern`'s unknowns, or with `local` its entries (one
/// process's compressed rows), do not fit PETSc's 32-bit indices.
fn check_indices(pattern: &SymbolicSparseColMat<usize>, local: bool) -> Result<()> {
    let nnz = pattern.row_idx().len();
    if pattern.nrows() > c_int::MAX as usize || (local && nnz > c_int::MAX as usize) {
        return Err(Error::LinearSolver(format!(
            "{} unknowns and {nnz} matrix entries exceed PETSc's 32-bit indices (this \
             PETSc was configured without --with-64-bit-indices)",
            pattern.nrows()
        )));
    }
    Ok(())
}

/// Initialise PETSc (and MPI: the world of `mpirun`, or a singleton) once
/// per process; PETSc's version.
pub fn initialise() -> Result<String> {
    let _lock = PETSC.lock().unwrap_or_else(|e| e.into_inner());
    let mut err = [0 as c_char; MESSAGE];
    let mut version = [0 as c_char; 256];
    // SAFETY: buffers of the lengths given
    let code = unsafe {
        ffi::sg_petsc_initialise(
            version.as_mut_ptr(),
            version.len(),
            err.as_mut_ptr(),
            err.len(),
        )
    };
    if code != 0 {
        return Err(Error::LinearSolver(message(&err)));
    }
    Ok(message(&version))
}

/// PETSc options given on the command line (`signorini run case.toml --
/// -ksp_type cg -pc_type gamg`), read after the case's.
static COMMAND_LINE: Mutex<String> = Mutex::new(String::new());

/// Set the PETSc options of the command line: every PETSc solver made
/// after this reads them after `PETSC_OPTIONS` and the case's
/// `[solver.petsc] options`, so the command line wins.
pub fn set_command_line_options(options: &[String]) {
    *COMMAND_LINE.lock().unwrap_or_else(|e| e.into_inner()) = options.join(" ");
}

/// A solver's options: the case's, then the command line's, as a C string.
fn with_command_line(options: &str) -> Result<CString> {
    let command_line = COMMAND_LINE.lock().unwrap_or_else(|e| e.into_inner());
    let text = if command_line.is_empty() {
        options.to_string()
    } else {
        format!("{options} {command_line}")
    };
    CString::new(text)
        .map_err(|_| Error::LinearSolver("the PETSc options contain a NUL character".into()))
}

/// What a PETSc solver did: its time (all of it, and of it the KSP's
/// set-up and solve), solves and Krylov iterations.
#[derive(Default)]
struct Tally {
    total: Duration,
    setup: Duration,
    solve: Duration,
    solves: usize,
    iterations: usize,
}

/// What the C layer writes back from one solve: the Krylov iterations and
/// the seconds of `KSPSetUp` and of `KSPSolve`.
#[derive(Default)]
struct Outcome {
    iterations: c_int,
    seconds: [f64; 2],
}

impl Tally {
    /// One solve begun at `start` with its `outcome` and the C layer's
    /// `result` (its message if it failed); `x` the solution. Why it
    /// failed, if it did (the C layer's message, or a solution that is not
    /// finite).
    fn record(
        &mut self,
        start: Instant,
        outcome: &Outcome,
        result: std::result::Result<(), IncrementFailure>,
        x: &[f64],
    ) -> std::result::Result<(), IncrementFailure> {
        self.solves += 1;
        self.iterations += outcome.iterations.max(0) as usize;
        self.total += start.elapsed();
        let [setup, solve] = outcome.seconds.map(|s| Duration::from_secs_f64(s.max(0.0)));
        self.setup += setup;
        self.solve += solve;
        result?;
        if x.iter().any(|v| !v.is_finite()) {
            return Err(IncrementFailure::LinearSolve(
                "PETSc's solution is not finite: the tangent is singular".into(),
            ));
        }
        Ok(())
    }

    fn statistics(&self) -> SolverStatistics {
        SolverStatistics {
            factorisation: self.total,
            petsc_setup: self.setup,
            petsc_solve: self.solve,
            krylov_solves: self.solves,
            krylov_iterations: self.iterations,
            ..Default::default()
        }
    }
}

/// PETSc's KSP and PC on the tangent.
pub struct PetscSolver {
    handle: *mut c_void,
    /// The fingerprint of the pattern PETSc's matrix was preallocated for.
    fingerprint: Option<u64>,
    /// Reference coordinates of the nodes (3 per node) for GAMG's
    /// rigid-body near-null space, when every unknown is a displacement.
    coordinates: Option<Vec<f64>>,
    /// PETSc's version and the KSP/PC in use, for the log.
    description: String,
    /// The options it was made from (the case's, then the command
    /// line's), for the message of a failed set-up.
    options: String,
    tally: Tally,
}

// SAFETY: the handle is only used under the `PETSC` lock, and PETSc's
// sequential objects do not belong to a thread
unsafe impl Send for PetscSolver {}

impl PetscSolver {
    /// Initialise PETSc and make a KSP set from `options` (a PETSc options
    /// string, read after the environment's `PETSC_OPTIONS`).
    /// `coordinates` (3 per node, reference) are attached as GAMG's
    /// rigid-body near-null space when every unknown is a displacement.
    pub fn new(options: &str, coordinates: Option<Vec<f64>>) -> Result<Self> {
        let (handle, description, options) = make_ksp(
            options,
            ffi::sg_petsc_solver_new,
            ffi::sg_petsc_solver_free,
            ffi::sg_petsc_describe,
        )?;
        Ok(PetscSolver {
            handle,
            fingerprint: None,
            coordinates,
            description,
            options,
            tally: Tally::default(),
        })
    }
}

impl PetscSolver {
    /// How a system of `n` unknowns is laid out for PETSc: block size 3
    /// with the coordinates (GAMG's rigid-body modes) when every unknown
    /// is a displacement; block size 1, the coordinates and the number of
    /// displacement unknowns (3 per node, numbered first, the contact
    /// multipliers after them: `Pattern::pivot_signs`) when there are
    /// multipliers too, for fieldsplit's two fields; else nothing.
    fn layout(&self, n: usize) -> (c_int, *const f64, c_int) {
        match &self.coordinates {
            Some(c) if c.len() == n => (3, c.as_ptr(), 0),
            Some(c) if c.len() < n => (1, c.as_ptr(), c.len() as c_int),
            _ => (1, std::ptr::null(), 0),
        }
    }
}

/// The C layer's constructor, destructor and description of a solver.
type MakeFn = unsafe extern "C" fn(*mut *mut c_void, *const c_char, *mut c_char, usize) -> c_int;
type FreeFn = unsafe extern "C" fn(*mut c_void);
type DescribeFn =
    unsafe extern "C" fn(*mut c_void, *mut c_char, usize, *mut c_char, usize) -> c_int;

/// Initialise PETSc and make a solver with the C layer's `make` from
/// `options` (then the command line's): its handle, PETSc's version
/// with the KSP and PC in words (`describe`) and the options in use.
fn make_ksp(
    options: &str,
    make: MakeFn,
    free: FreeFn,
    describe: DescribeFn,
) -> Result<(*mut c_void, String, String)> {
    let options = with_command_line(options)?;
    let version = initialise()?;
    let _lock = PETSC.lock().unwrap_or_else(|e| e.into_inner());
    let mut err = [0 as c_char; MESSAGE];
    let mut handle = std::ptr::null_mut();
    // SAFETY: out-pointer, NUL-terminated options and buffer valid
    let code = unsafe { make(&mut handle, options.as_ptr(), err.as_mut_ptr(), err.len()) };
    let code = if code == 0 {
        add_global_options(handle, &options.to_string_lossy(), &mut err)
    } else {
        code
    };
    if code != 0 {
        // SAFETY: the C layer sets `handle` before anything can fail
        unsafe { free(handle) };
        return Err(Error::LinearSolver(message(&err)));
    }
    let mut text = [0 as c_char; 256];
    // SAFETY: handle made above, buffers valid
    let code = unsafe {
        describe(
            handle,
            text.as_mut_ptr(),
            text.len(),
            err.as_mut_ptr(),
            err.len(),
        )
    };
    let solver_text = message(if code == 0 { &text } else { &err });
    let options = options.to_string_lossy().into_owned();
    Ok((handle, format!("{version}, {solver_text}"), options))
}

/// The options of `text` that PETSc reads without a prefix, each with its
/// value (`None`: none given), in order: those of its matrix products,
/// `-mat<product>_via` (`-matptap_via`, `-matmatmult_via`,
/// `-mattransposematmult_via`, …) and `-mat_product_…` (`-mat_product_clear`,
/// `-mat_product_algorithm`). GAMG's Galerkin products `PᵀAP` and
/// fieldsplit's Schur complement are matrices PETSc makes with no options
/// prefix, so they read these from PETSc's global options database, not
/// under the solver's prefix.
fn product_options(text: &str) -> Vec<(String, Option<String>)> {
    let is_product = |name: &str| {
        name.starts_with("mat_product_")
            || name
                .strip_prefix("mat")
                .and_then(|n| n.strip_suffix("_via"))
                .is_some_and(|p| !p.is_empty() && p.chars().all(|c| c.is_ascii_lowercase()))
    };
    let tokens: Vec<&str> = text.split_whitespace().collect();
    tokens
        .iter()
        .enumerate()
        .filter(|(_, t)| t.strip_prefix('-').is_some_and(is_product))
        .map(|(k, t)| {
            let value = tokens.get(k + 1).filter(|v| !v.starts_with('-'));
            (t.to_string(), value.map(|v| v.to_string()))
        })
        .collect()
}

/// Give the solver at `handle` the product options of its `options`
/// ([`product_options`]), which the C layer puts into PETSc's global
/// database around each of its set-ups and solves only (the earlier
/// values restored after), so that they reach the products and stay the
/// solver's own. The C layer's code (0: done; else its message in `err`).
fn add_global_options(handle: *mut c_void, options: &str, err: &mut [c_char]) -> c_int {
    for (name, value) in product_options(options) {
        // no NUL inside: they come from a C string
        let name = CString::new(name).unwrap_or_default();
        let value = value.map(|v| CString::new(v).unwrap_or_default());
        let value_ptr = value.as_ref().map_or(std::ptr::null(), |v| v.as_ptr());
        // SAFETY: a handle of either kind (both begin with the C layer's
        // `Common`), NUL-terminated strings the C layer copies, a buffer
        // of its length
        let code = unsafe {
            ffi::sg_petsc_global_option(
                handle,
                name.as_ptr(),
                value_ptr,
                err.as_mut_ptr(),
                err.len(),
            )
        };
        if code != 0 {
            return code;
        }
    }
    0
}

impl Drop for PetscSolver {
    fn drop(&mut self) {
        let _lock = PETSC.lock().unwrap_or_else(|e| e.into_inner());
        // SAFETY: the handle came from sg_petsc_solver_new and is freed once
        unsafe { ffi::sg_petsc_solver_free(self.handle) };
    }
}

impl LinearSolver for PetscSolver {
    /// PETSc orders the unknowns itself (MUMPS' analysis, or none for an
    /// iterative method).
    fn set_ordering(&mut self, _ordering: Ordering) {}

    fn solve(
        &mut self,
        system: &LinearSystem<'_>,
        rhs: &[f64],
        x: &mut [f64],
    ) -> std::result::Result<(), IncrementFailure> {
        let start = Instant::now();
        let n = rhs.len();
        let fingerprint = pattern_fingerprint(system.pattern);
        let same_pattern = self.fingerprint == Some(fingerprint);
        if !same_pattern {
            check_indices(system.pattern, true)
                .map_err(|e| IncrementFailure::LinearSolverSetUp(e.to_string()))?;
        }
        self.fingerprint = Some(fingerprint);
        let (block_size, coordinates, displacements) = self.layout(n);
        let mut outcome = Outcome::default();
        let mut err = [0 as c_char; MESSAGE];
        let _lock = PETSC.lock().unwrap_or_else(|e| e.into_inner());
        let system = SystemArguments {
            n: n as c_int,
            columns: Columns::of(system.pattern, &[], &[]),
            values: system.matrix.as_ptr(),
            same_pattern: same_pattern as c_int,
            block_size,
            coordinates,
            displacements,
            b: rhs.as_ptr(),
            x: x.as_mut_ptr(),
            iterations: &mut outcome.iterations,
            seconds: outcome.seconds.as_mut_ptr(),
        };
        // SAFETY: the pattern's arrays, the values (one per entry), b and x
        // (n each) live until the call returns
        let code =
            unsafe { ffi::sg_petsc_solve(self.handle, &system, err.as_mut_ptr(), err.len()) };
        let result = if code == 0 {
            Ok(())
        } else {
            Err(solve_failure(code, message(&err), &self.options))
        };
        self.tally.record(start, &outcome, result, x)
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
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::sparse::{SparseColMat, Triplet};

    fn system(triplets: &[(usize, usize, f64)], n: usize) -> SparseColMat<usize, f64> {
        let t: Vec<_> = triplets
            .iter()
            .map(|&(i, j, v)| Triplet::new(i, j, v))
            .collect();
        SparseColMat::try_new_from_triplets(n, n, &t).unwrap()
    }

    /// The matrix products' options, with their values or none, and no
    /// other option (a KSP's, GAMG's, a matrix's own `-mat_…`).
    #[test]
    fn product_options_are_the_matrix_products_and_nothing_else() {
        let text = "-ksp_type cg -pc_type gamg -matptap_via allatonce -mat_product_clear \
                    -mat_mumps_icntl_7 5 -mattransposematmult_via scalable -pc_gamg_threshold \
                    0.05 -mat_view -matptap_via scalable";
        let owned = |name: &str, value: Option<&str>| (name.to_string(), value.map(String::from));
        assert_eq!(
            product_options(text),
            vec![
                owned("-matptap_via", Some("allatonce")),
                owned("-mat_product_clear", None),
                owned("-mattransposematmult_via", Some("scalable")),
                owned("-matptap_via", Some("scalable")),
            ]
        );
        assert!(product_options("-via x -mat_via y -matptap_vias z").is_empty());
    }

    #[test]
    fn mumps_solves_a_nonsymmetric_indefinite_system() {
        // A = [[4, 1, 0], [2, 0, 1], [0, 3, 6]] (zero pivot at (1, 1)), x = (1, −2, 3)
        let a = system(
            &[
                (0, 0, 4.0),
                (1, 0, 2.0),
                (0, 1, 1.0),
                (2, 1, 3.0),
                (1, 2, 1.0),
                (2, 2, 6.0),
            ],
            3,
        );
        let x_exact = [1.0, -2.0, 3.0];
        let b = [
            4.0 * x_exact[0] + x_exact[1],
            2.0 * x_exact[0] + x_exact[2],
            3.0 * x_exact[1] + 6.0 * x_exact[2],
        ];
        let pattern = a.symbolic().to_owned().unwrap();
        let mut solver = PetscSolver::new("", None).unwrap();
        assert!(
            solver.description().contains("mumps"),
            "{}",
            solver.description()
        );
        for _ in 0..2 {
            let mut x = [0.0; 3];
            let sys = LinearSystem {
                pattern: &pattern,
                matrix: a.val(),
                symmetric_neighbour: None,
                pivot_signs: None,
            };
            solver.solve(&sys, &b, &mut x).unwrap();
            for i in 0..3 {
                assert!((x[i] - x_exact[i]).abs() < 1e-14, "{x:?}");
            }
        }
        assert_eq!(solver.statistics().krylov_solves, 2);
    }

    /// A singular matrix is a failed solve, which a smaller increment may
    /// mend (MUMPS' zero pivot is the PC's failed reason, not a PETSc
    /// error code); a factorisation package PETSc lacks is a failed
    /// set-up (PETSc error 92 at `KSPSetUp`), which ends the run, and
    /// its message names the option.
    #[test]
    fn a_singular_matrix_is_a_failed_solve_and_a_missing_package_a_failed_set_up() {
        // rank 1: [[1, 1], [1, 1]]
        let singular = system(&[(0, 0, 1.0), (1, 0, 1.0), (0, 1, 1.0), (1, 1, 1.0)], 2);
        let regular = system(&[(0, 0, 2.0), (1, 1, 3.0)], 2);
        let solve = |options: &str, a: &SparseColMat<usize, f64>| {
            let pattern = a.symbolic().to_owned().unwrap();
            let sys = LinearSystem {
                pattern: &pattern,
                matrix: a.val(),
                symmetric_neighbour: None,
                pivot_signs: None,
            };
            let mut x = [0.0; 2];
            PetscSolver::new(options, None)
                .unwrap()
                .solve(&sys, &[1.0, 2.0], &mut x)
        };
        let failed = solve("", &singular).unwrap_err();
        assert!(
            matches!(failed, IncrementFailure::LinearSolve(_)),
            "{failed:?}"
        );
        assert!(failed.mended_by_a_cut());
        let option = "-pc_factor_mat_solver_type no_such_package";
        let failed = solve(option, &regular).unwrap_err();
        let IncrementFailure::LinearSolverSetUp(message) = &failed else {
            panic!("{failed:?}");
        };
        assert!(message.contains("PETSc error 92"), "{message}");
        assert!(message.contains(option), "{message}");
        assert!(!failed.mended_by_a_cut());
        assert!(solve("", &regular).is_ok());
    }
}
