//! Faults of a distributed run (`mpirun -np N`): what one process does
//! when it fails, so that no process waits forever for it.
//!
//! A process that fails (a bad input found late, a failed solve, a write
//! that fails) tells the others at the next *agreement* ([`agree`]): every
//! process gives its outcome, a flag (its failure's [`Severity`]) and a
//! message, in a non-blocking
//! gather on a communicator of its own (a duplicate of MPI's world, so
//! that it never matches the collectives of a process still inside a
//! solve). When every process arrives, they all know who failed, how
//! severely and why, and go on alike (a linear solve that failed on one
//! process fails on all, cut or ending the run as the most severe failure
//! says; a run ends with the same error on all, `summary.json` written by
//! rank 0). A failed process waits at most [`FAILED_WAIT`]: if another
//! process does not arrive, it is stuck in a collective that the failed
//! one left, and the failed process ends the run ([`fault`]: the message
//! on its standard error, `summary.json` marked failed by the hook the run
//! registered ([`on_fault`]), then `MPI_Abort`, after which `mpirun` ends
//! every process). A process killed outright is `mpirun`'s to notice: it
//! ends the others (SIGTERM, then SIGKILL a second later).

use super::{message, MESSAGE, PETSC};
use crate::{Error, Result};
use std::ffi::{c_char, c_int, CString};
use std::sync::{Mutex, OnceLock};
use std::time::Duration;

mod ffi {
    use std::ffi::{c_char, c_int};
    extern "C" {
        pub fn sg_mpi_fault_init(err: *mut c_char, len: usize) -> c_int;
        pub fn sg_mpi_agree(
            severity: c_int,
            message: *const c_char,
            records: *mut c_char,
            record: usize,
            timeout: f64,
            done: *mut c_int,
            err: *mut c_char,
            len: usize,
        ) -> c_int;
        pub fn sg_mpi_abort(code: c_int);
        pub fn sg_exit_now(code: c_int);
    }
}

/// How long a failed process waits for the others at an agreement before
/// it ends the run: they are stuck in a collective it left (processes
/// that agree arrive within milliseconds of each other).
pub const FAILED_WAIT: Duration = Duration::from_secs(5);

/// The bytes of one process's record at an agreement: a flag (0, or its
/// failure's [`Severity`]) and its message (cut to fit).
const RECORD: usize = 1024;

/// This process's rank and the number of processes.
static WORLD: OnceLock<(usize, usize)> = OnceLock::new();

/// Make the agreement's communicator (once per process, after PETSc's
/// initialisation), for process `rank` of `size`.
pub(super) fn initialise(rank: usize, size: usize) -> Result<()> {
    let _ = WORLD.set((rank, size));
    let _lock = PETSC.lock().unwrap_or_else(|e| e.into_inner());
    let mut err = [0 as c_char; MESSAGE];
    // SAFETY: a buffer of the length given
    let code = unsafe { ffi::sg_mpi_fault_init(err.as_mut_ptr(), err.len()) };
    if code != 0 {
        return Err(Error::LinearSolver(message(&err)));
    }
    Ok(())
}

/// How severe one process's failure is; at an agreement the most severe
/// wins, so that every process acts on it alike.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Severity {
    /// A smaller increment may mend it (a failed linear solve: the
    /// increment is cut).
    Mendable = 1,
    /// It ends the run (a linear solver that cannot be set up, a failed
    /// run).
    Final = 2,
}

impl Severity {
    /// The severity a record's flag byte says (a flag this build does not
    /// know is taken as final).
    fn of_flag(flag: c_char) -> Severity {
        if flag == Severity::Mendable as c_char {
            Severity::Mendable
        } else {
            Severity::Final
        }
    }
}

/// What the processes agreed on.
#[derive(Debug, PartialEq)]
pub enum Agreement {
    /// Every process succeeded.
    Succeeded,
    /// A process failed: the most severe failure, the first rank with it
    /// and its message.
    Failed {
        rank: usize,
        severity: Severity,
        message: String,
    },
    /// This process failed and another did not arrive within
    /// [`FAILED_WAIT`].
    NoAnswer,
}

/// Agree with every other process on an outcome: `local` this process's
/// (its error's severity and message). A process that succeeded waits as
/// long as it takes; one that failed waits [`FAILED_WAIT`] at most.
pub fn agree(local: std::result::Result<(), (Severity, &str)>) -> Agreement {
    let severity = local.map_or_else(|(s, _)| s as c_int, |_| 0);
    let text = local
        .err()
        .map(|(_, m)| CString::new(m.replace('\0', " ")).unwrap_or_default());
    let size = {
        let (_, size) = world();
        size
    };
    let mut records = vec![0 as c_char; RECORD * size];
    let timeout = if text.is_some() {
        FAILED_WAIT.as_secs_f64()
    } else {
        0.0
    };
    let mut done: c_int = 0;
    let mut err = [0 as c_char; MESSAGE];
    let code = {
        let _lock = PETSC.lock().unwrap_or_else(|e| e.into_inner());
        // SAFETY: records holds size × RECORD bytes, the message is
        // NUL-terminated, the buffers have the lengths given
        unsafe {
            ffi::sg_mpi_agree(
                severity,
                text.as_ref().map_or(std::ptr::null(), |t| t.as_ptr()),
                records.as_mut_ptr(),
                RECORD,
                timeout,
                &mut done,
                err.as_mut_ptr(),
                err.len(),
            )
        }
    };
    if code != 0 {
        fault(&message(&err));
    }
    if done == 0 {
        return Agreement::NoAnswer;
    }
    most_severe_failure(&records)
}

/// The most severe failure in the gathered records: its severity, the
/// first rank with it and its message.
fn most_severe_failure(records: &[c_char]) -> Agreement {
    let failed = records
        .chunks_exact(RECORD)
        .enumerate()
        .filter(|(_, r)| r[0] != 0);
    // the first of the most severe: max_by_key keeps the last of equals
    failed
        .rev()
        .max_by_key(|(_, r)| Severity::of_flag(r[0]))
        .map_or(Agreement::Succeeded, |(rank, r)| Agreement::Failed {
            rank,
            severity: Severity::of_flag(r[0]),
            message: message(&r[1..]),
        })
}

/// This process's rank and the number of processes.
fn world() -> (usize, usize) {
    WORLD.get().copied().unwrap_or((0, 1))
}

/// What a run does when one of its processes faults (marks its
/// `summary.json` failed), given the message.
type Hook = Box<dyn Fn(&str) + Send>;

static HOOK: Mutex<Option<Hook>> = Mutex::new(None);

/// Call `hook` with the message when this process ends the run
/// ([`fault`]).
pub fn on_fault(hook: impl Fn(&str) + Send + 'static) {
    *HOOK.lock().unwrap_or_else(|e| e.into_inner()) = Some(Box::new(hook));
}

/// End the whole run from this process: `message` on the standard error
/// (with the rank), the hook told, then `MPI_Abort` (`mpirun` ends every
/// process and exits with a non-zero code).
pub fn fault(message: &str) -> ! {
    let (rank, size) = world();
    eprintln!("error: process {rank} of {size} ends the distributed run: {message}");
    if let Some(hook) = HOOK.lock().unwrap_or_else(|e| e.into_inner()).as_ref() {
        hook(message);
    }
    // SAFETY: MPI is initialised (a fault comes after an agreement or a
    // sum); MPI_Abort does not return
    unsafe { ffi::sg_mpi_abort(1) };
    exit_now(1)
}

/// End this process at once with `code`, without PETSc's and MPI's
/// finalisation (which would wait for processes that are gone).
pub fn exit_now(code: i32) -> ! {
    // SAFETY: _exit ends the process
    unsafe { ffi::sg_exit_now(code) };
    unreachable!("_exit returned")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn record(flag: u8, text: &str) -> Vec<c_char> {
        let mut r = vec![0 as c_char; RECORD];
        r[0] = flag as c_char;
        for (k, b) in text.bytes().enumerate() {
            r[1 + k] = b as c_char;
        }
        r
    }

    #[test]
    fn the_first_failed_process_is_reported() {
        let mut records = record(0, "");
        records.extend(record(2, "write failed"));
        records.extend(record(2, "other"));
        assert_eq!(
            most_severe_failure(&records),
            Agreement::Failed {
                rank: 1,
                severity: Severity::Final,
                message: "write failed".into()
            }
        );
        assert_eq!(most_severe_failure(&record(0, "")), Agreement::Succeeded);
    }

    /// A process whose failure ends the run wins over an earlier rank's
    /// failure that a cut would mend (issue 29 item 6: the other process
    /// cut while this one ended its run).
    #[test]
    fn the_most_severe_failure_wins() {
        let mut records = record(Severity::Mendable as u8, "did not converge");
        records.extend(record(0, ""));
        records.extend(record(Severity::Final as u8, "PETSc error 92"));
        records.extend(record(Severity::Final as u8, "later"));
        assert_eq!(
            most_severe_failure(&records),
            Agreement::Failed {
                rank: 2,
                severity: Severity::Final,
                message: "PETSc error 92".into()
            }
        );
        let mendable = [record(0, ""), record(1, "a"), record(1, "b")].concat();
        assert_eq!(
            most_severe_failure(&mendable),
            Agreement::Failed {
                rank: 1,
                severity: Severity::Mendable,
                message: "a".into()
            }
        );
    }
}
