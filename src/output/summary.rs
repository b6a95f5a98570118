//! `summary.json`: the machine-readable record of a run, rewritten
//! (atomically) after every converged increment so that it is valid
//! whatever happens later.

use serde::Serialize;
use std::collections::BTreeMap;
use std::path::Path;

/// One converged increment.
#[derive(Clone, Debug, Serialize)]
pub struct IncrementSummary {
    /// Step index (0-based) and name.
    pub step: usize,
    pub step_name: String,
    /// Pseudo-time at the end of the increment, and its size.
    pub time: f64,
    pub increment: f64,
    /// Newton iterations (linear solves) of the increment.
    pub iterations: usize,
    /// Relative force residual at the start of every iteration, the last
    /// one being the converged value.
    pub residuals: Vec<f64>,
    /// Relative size of each Newton correction.
    pub corrections: Vec<f64>,
    /// Cuts of the increment before it converged.
    pub cuts: usize,
    /// Wall time of the increment, seconds.
    pub wall_time: f64,
    /// VTU file of the increment (relative to the output folder).
    pub file: String,
    /// `Σ (f_int − f_ext)` over the nodes of each surface set: the reaction
    /// force where displacements are prescribed.
    pub reaction_forces: BTreeMap<String, [f64; 3]>,
}

/// The whole run.
#[derive(Clone, Debug, Serialize)]
pub struct Summary {
    /// The case file.
    pub case: String,
    /// `running`, `completed` or `failed`.
    pub status: String,
    /// The error, if the run failed.
    pub error: Option<String>,
    pub nodes: usize,
    pub elements: usize,
    pub dofs: usize,
    /// Prescribed (constrained) dofs.
    pub constrained_dofs: usize,
    pub threads: usize,
    /// Wall time since the start of the run, seconds.
    pub wall_time: f64,
    /// Symbolic analyses of the tangent's pattern (1 on a fixed mesh).
    pub symbolic_analyses: usize,
    /// Stored entries of the tangent and of its LDLᵀ factor.
    pub matrix_nnz: usize,
    pub factor_nnz: usize,
    pub increments: Vec<IncrementSummary>,
}

impl Summary {
    /// Write as pretty JSON, atomically (temporary file + rename).
    pub fn write(&self, path: &Path) -> crate::Result<()> {
        let text = serde_json::to_string_pretty(self).expect("the summary serialises");
        super::write_atomically(path, |w| std::io::Write::write_all(w, text.as_bytes()))
    }
}
