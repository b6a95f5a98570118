//! Errors a user can act on. Every variant names the file, the entity or the
//! key path involved and, where it helps, the fix.

use std::path::PathBuf;

pub mod suggest;
pub mod words;

/// The crate's error type: everything that can go wrong with user input or a
/// solve. The library never panics on user input; it returns one of these.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A file could not be opened, read or written; the message names the
    /// path resolved ([`resolved`]: absolute, from the working folder).
    #[error("cannot {action} '{}': {source}", resolved(path).display())]
    Io {
        action: &'static str,
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },

    /// A mesh file is malformed; `line` is 1-based (or the byte offset for
    /// binary sections, stated in `message`).
    #[error("malformed mesh '{path}' at line {line}: {message}")]
    MeshSyntax {
        path: PathBuf,
        line: usize,
        message: String,
    },

    /// An Abaqus/CalculiX deck run as it is whose model cannot be read or
    /// is not supported; `line` is 1-based.
    #[error("deck '{path}' at line {line}: {message}")]
    Deck {
        path: PathBuf,
        line: usize,
        message: String,
    },

    /// A mesh that parses but cannot be used (unsupported element, a facet
    /// that is not on the boundary of any volume element, ...).
    #[error("invalid mesh '{path}': {message}")]
    Mesh { path: PathBuf, message: String },

    /// The case file refers to a physical group that the mesh does not have.
    #[error("{key}: the mesh has no {kind} named '{name}'; it has: {}{}", available.join(", "), suggest::hint(name, available))]
    UnknownGroup {
        key: String,
        kind: &'static str,
        name: String,
        available: Vec<String>,
    },

    /// The case file is not valid TOML or does not match the schema.
    #[error("case file '{path}': {message}")]
    Case { path: PathBuf, message: String },

    /// Contact input that cannot be used: an obstacle with a zero normal or
    /// axis or a non-positive radius, an unreadable or degenerate STL file.
    /// `what` names the obstacle or the file.
    #[error("{what}: {message}")]
    ContactInput { what: String, message: String },

    /// A material parameter outside its admissible range.
    #[error("{key}: {message}")]
    MaterialParameter { key: String, message: String },

    /// An element whose Jacobian determinant is not positive.
    #[error("element {element} (mesh id) is {what}: det J = {det_j:.3e} at quadrature point {quadrature_point}{}", if *in_reference { " in the reference configuration; check the node ordering and the geometry" } else { " in the deformed configuration" })]
    InvertedElement {
        element: u64,
        quadrature_point: usize,
        det_j: f64,
        in_reference: bool,
        what: &'static str,
    },

    /// The linear solver failed (singular matrix: usually missing boundary
    /// conditions, i.e. a rigid-body mode).
    #[error("linear solve failed: {0}")]
    LinearSolver(String),

    /// Newton did not converge even after the allowed number of step cuts
    /// (`cuts` in a row, `max_cuts`) or at the smallest increment
    /// (`at_smallest`, `min_increment`); `step_cuts` counts every cut of
    /// the step, this increment's included, as `summary.json`'s
    /// `steps[].cuts` does after the failure. Every step converged before
    /// this one is on disk.
    #[error("step '{step}' did not converge at time {time:.6} {}; {step_cuts} cuts in the step in all: {reason}. {}", if *at_smallest {
        format!("with the smallest increment allowed (min_increment), {increment:.3e}, after {cuts} cuts in a row")
    } else {
        format!("after {cuts} cuts of the increment in a row, the most allowed (max_cuts), down to {increment:.3e}")
    }, match last_converged_time {
        Some(t) => format!("The increments converged up to time {t:.6} are written in '{}'", output.display()),
        None => "No increment had converged, so no result was written; try a smaller initial_increment".to_string(),
    })]
    NoConvergence {
        step: String,
        time: f64,
        cuts: u32,
        step_cuts: u32,
        at_smallest: bool,
        increment: f64,
        reason: String,
        /// `None` if no increment converged at all.
        last_converged_time: Option<f64>,
        output: PathBuf,
    },

    /// The run was stopped from outside between two increments (an
    /// observer asked for it: a script's callback, Ctrl-C). The increments
    /// converged before stay with the observers and, with an output folder,
    /// on disk; `summary.json` says `"status": "interrupted"`.
    #[error("the run was stopped: {reason}")]
    Interrupted { reason: String },

    /// A restart (`--restart DIR`, [`crate::run::RunOptions::restart`])
    /// cannot resume: the folder or its checkpoint is missing, unreadable,
    /// of another format version, or of another case.
    #[error("cannot restart from '{}': {message}", resolved(path).display())]
    Restart { path: PathBuf, message: String },

    /// Another process of a distributed run (`mpirun -np N`) failed: its
    /// rank and message.
    #[error("the distributed run failed on {0}")]
    Distributed(String),
}

/// `path` made absolute against the working folder (without following
/// links or touching the file system), as messages name a file: the user
/// sees which file was looked for, whatever folder the run started in.
pub fn resolved(path: &std::path::Path) -> PathBuf {
    std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf())
}

/// Result with the crate's [`Error`].
pub type Result<T, E = Error> = std::result::Result<T, E>;

impl Error {
    /// An I/O error with the path and what was being done.
    pub fn io(action: &'static str, path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        Error::Io {
            action,
            path: path.into(),
            source,
        }
    }

    /// Contact input that cannot be used, naming the obstacle or file `what`.
    pub fn contact_input(what: &str, message: String) -> Self {
        Error::ContactInput {
            what: what.to_string(),
            message,
        }
    }
}
