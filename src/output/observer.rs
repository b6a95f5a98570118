//! What a run tells the outside world as it goes: the [`StepObserver`]
//! trait. The library prints nothing and writes nothing by itself; the
//! result files are one observer ([`super::writer::ResultWriter`]), the
//! command line's progress bar and log lines another (in `main.rs`), a
//! script's callback a third.

use super::fields::ConvergedIncrement;
use super::summary::Summary;
use crate::solve::newton::IterationRecord;
use crate::Result;

/// An increment that failed and is cut (or, after `max_cuts`, ends the run).
#[derive(Clone, Debug)]
pub struct Cut<'a> {
    pub step: &'a str,
    /// The time the increment aimed at, and its size.
    pub time: f64,
    pub increment: f64,
    /// Why Newton failed.
    pub reason: &'a crate::solve::failure::IncrementFailure,
}

/// A Newton iteration that took its correction.
#[derive(Clone, Debug)]
pub struct Iteration<'a> {
    pub step: &'a str,
    /// The time the increment aims at.
    pub time: f64,
    /// Its residual (at the start), correction, step length and switches.
    pub record: &'a IterationRecord,
}

/// Receives a run's events. Every method but [`on_increment`](Self::on_increment)
/// does nothing by default.
pub trait StepObserver {
    /// The run starts; `summary` holds the model's sizes.
    fn on_start(&mut self, _summary: &Summary) -> Result<()> {
        Ok(())
    }
    /// An increment converged: its fields in memory, and the run's summary
    /// with this increment appended. An error stops the run.
    fn on_increment(&mut self, increment: &ConvergedIncrement, summary: &Summary) -> Result<()>;
    /// An increment failed and is cut.
    fn on_cut(&mut self, _cut: &Cut) {}
    /// A Newton iteration took its correction (the increment goes on).
    fn on_iteration(&mut self, _iteration: &Iteration) {}
    /// A line of information for a log (what a history reads, …).
    fn on_message(&mut self, _line: &str) {}
    /// The run ended (`summary.status` says how), its totals filled in.
    fn on_finish(&mut self, _summary: &Summary) -> Result<()> {
        Ok(())
    }
}

/// Several observers, told in order.
pub struct Observers<'a>(pub Vec<&'a mut dyn StepObserver>);

impl StepObserver for Observers<'_> {
    fn on_start(&mut self, summary: &Summary) -> Result<()> {
        self.0.iter_mut().try_for_each(|o| o.on_start(summary))
    }
    fn on_increment(&mut self, increment: &ConvergedIncrement, summary: &Summary) -> Result<()> {
        self.0
            .iter_mut()
            .try_for_each(|o| o.on_increment(increment, summary))
    }
    fn on_cut(&mut self, cut: &Cut) {
        self.0.iter_mut().for_each(|o| o.on_cut(cut));
    }
    fn on_message(&mut self, line: &str) {
        self.0.iter_mut().for_each(|o| o.on_message(line));
    }
    fn on_iteration(&mut self, iteration: &Iteration) {
        self.0.iter_mut().for_each(|o| o.on_iteration(iteration));
    }
    /// Every observer hears the end, even when an earlier one fails; the
    /// first error is returned.
    fn on_finish(&mut self, summary: &Summary) -> Result<()> {
        let results: Vec<Result<()>> = self.0.iter_mut().map(|o| o.on_finish(summary)).collect();
        results.into_iter().collect()
    }
}

/// An observer that ignores everything.
pub struct Silent;

impl StepObserver for Silent {
    fn on_increment(&mut self, _: &ConvergedIncrement, _: &Summary) -> Result<()> {
        Ok(())
    }
}
