//! `NAME.log`: a run's log in the output folder — a header that says what
//! the run came from ([`RunHeader`]: version, commit, features, date,
//! command line, cores, the case file's SHA-256), the model in words, one
//! line per Newton iteration, every increment and every cut with its
//! reason, and the final summary. Appended and flushed line by line, so a
//! run that dies leaves its log up to that moment.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use super::describe::counted;
use super::fields::ConvergedIncrement;
use super::observer::{Cut, Iteration, StepObserver};
use super::provenance::RunHeader;
use super::summary::Summary;
use crate::solve::linear_solver::LinearFigures;
use crate::{Error, Result};

/// What the increment's line says when some of its linear solves fell back
/// to the sparse LU ([`ConvergedIncrement::lu_fallbacks`]), e.g.
/// `"  (sparse LU fallback: 2 solves)"`; empty otherwise. The console's
/// increment line and `NAME.log` both carry it: a fallback is slower and
/// says that GMRES or the LDLᵀ struggled, which should not go unseen.
pub fn lu_fallback_note(increment: &ConvergedIncrement) -> String {
    match increment.lu_fallbacks() {
        0 => String::new(),
        1 => "  (sparse LU fallback: 1 solve)".into(),
        n => format!("  (sparse LU fallback: {n} solves)"),
    }
}

/// Writes the log of a run.
pub struct LogWriter {
    path: PathBuf,
    file: BufWriter<File>,
    /// The first write error, reported at the end (a log line that cannot
    /// be written must not stop the solve).
    failed: Option<std::io::Error>,
}

impl LogWriter {
    /// A new log `dir/NAME.log` (an earlier one is replaced).
    pub fn new(dir: &Path, name: &str) -> Result<Self> {
        let path = dir.join(format!("{name}.log"));
        let file = File::create(&path).map_err(|e| Error::io("create", &path, e))?;
        Ok(LogWriter {
            path,
            file: BufWriter::new(file),
            failed: None,
        })
    }

    /// The log `dir/NAME.log` of a run that resumes (a restart): the
    /// lines go on after the earlier run's.
    pub fn append(dir: &Path, name: &str) -> Result<Self> {
        let path = dir.join(format!("{name}.log"));
        let file = std::fs::OpenOptions::new()
            .create(true)
            .append(true)
            .open(&path)
            .map_err(|e| Error::io("open", &path, e))?;
        Ok(LogWriter {
            path,
            file: BufWriter::new(file),
            failed: None,
        })
    }

    /// Write `header`'s lines (at the start of a run, or of a restart's
    /// part of the log).
    pub fn header(&mut self, header: &RunHeader) {
        for line in header.lines() {
            self.line(&line);
        }
    }

    fn line(&mut self, text: &str) {
        if self.failed.is_some() {
            return;
        }
        if let Err(e) = writeln!(self.file, "{text}").and_then(|()| self.file.flush()) {
            self.failed = Some(e);
        }
    }
}

impl StepObserver for LogWriter {
    fn on_message(&mut self, line: &str) {
        self.line(line);
    }

    fn on_iteration(&mut self, it: &Iteration) {
        let r = it.record;
        self.line(&format!(
            "  step '{}' t = {:.6}  residual {:.3e}  correction {:.3e}  step length {:.3}  switched {}  {}",
            it.step,
            it.time,
            r.residual,
            r.correction,
            r.step_length,
            r.switched,
            linear_figures(&r.linear)
        ));
    }

    fn on_increment(&mut self, increment: &ConvergedIncrement, _: &Summary) -> Result<()> {
        let record = increment.record;
        let residual = record.newton.last().map_or(0.0, |r| r.residual);
        self.line(&format!(
            "step '{}'  t = {:.6}  Δt = {:.3e}  converged in {} iterations, residual {:.2e}{}",
            record.step_name,
            record.time,
            record.increment,
            record.iterations,
            residual,
            lu_fallback_note(increment)
        ));
        for (name, c) in &increment.contact_fields.summaries {
            self.line(&format!(
                "  contact '{name}': force [{:.6e}, {:.6e}, {:.6e}], tangential [{:.6e}, {:.6e}, {:.6e}], {} closed ({} stick, {} slip), largest penetration {:.3e}",
                c.force[0], c.force[1], c.force[2],
                c.tangential_force[0], c.tangential_force[1], c.tangential_force[2],
                c.closed_nodes, c.stick_nodes, c.slip_nodes, c.largest_penetration
            ));
            if let Some(warning) = &c.warning {
                self.line(&format!("  warning: {warning}"));
            }
        }
        Ok(())
    }

    fn on_cut(&mut self, cut: &Cut) {
        self.line(&format!(
            "step '{}'  t = {:.6}  Δt = {:.3e}  not converged ({}): cutting the increment",
            cut.step, cut.time, cut.increment, cut.reason
        ));
    }

    fn on_finish(&mut self, s: &Summary) -> Result<()> {
        let iterations: usize = s.increments.iter().map(|i| i.iterations).sum();
        let cuts: usize = s.increments.iter().map(|i| i.cuts).sum();
        self.line(&format!(
            "{}: {}, {}, {}, {:.2} s on {} threads",
            s.status,
            counted(s.increments.len(), "increment"),
            counted(iterations, "Newton iteration"),
            counted(cuts, "cut"),
            s.wall_time,
            s.threads
        ));
        if let Some(e) = &s.error {
            self.line(&format!("error: {e}"));
        }
        let t = &s.phase_times;
        self.line(&format!(
            "time: assembly {:.2} s, contact {:.2} s, symbolic analysis {:.2} s, factorisation {:.2} s, solve {:.2} s",
            t.assembly, t.contact, t.symbolic, t.factorisation, t.solve
        ));
        self.line(&format!(
            "linear solver: {} symbolic analyses, {} matrix entries, {} factor entries, {} GMRES solves ({} iterations), {} LU solves",
            s.symbolic_analyses, s.matrix_nnz, s.factor_nnz, s.krylov_solves, s.krylov_iterations, s.lu_solves
        ));
        match self.failed.take() {
            Some(e) => Err(Error::io("write", &self.path, e)),
            None => Ok(()),
        }
    }
}

/// The linear solve of one Newton iteration in words: `linear solve:
/// factorisation 1.2e-3 s, solve 4.0e-4 s` and, where there were any, the
/// refinement steps, GMRES iterations, LU solves and f32 → f64 fallbacks.
fn linear_figures(f: &LinearFigures) -> String {
    let mut text = format!(
        "linear solve: factorisation {:.1e} s, solve {:.1e} s",
        f.factorisation, f.solve
    );
    let counts = [
        (f.refinement_steps, "refinement steps"),
        (f.krylov_iterations, "GMRES iterations"),
        (f.lu_solves, "LU solves"),
        (f.mixed_precision_fallbacks, "f32 → f64 fallbacks"),
    ];
    for (n, what) in counts {
        if n > 0 {
            text.push_str(&format!(", {n} {what}"));
        }
    }
    text
}
