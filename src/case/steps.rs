//! The `[[step]]` tables: load steps in pseudo-time, each with its
//! increment controls, validated, and the run's output within its budget.

use super::schema::StepSpec;
use super::{budget, not_positive, Case};
use crate::problem::Step;
use crate::Result;

impl Case {
    /// The load steps, in order; the VTU files they would write counted
    /// against the output budget.
    pub(super) fn steps(&self) -> Result<Vec<Step>> {
        let spec = &self.spec;
        if spec.step.is_empty() {
            return Err(self.err("no [[step]]: add at least one step with name and end_time"));
        }
        let mut steps = Vec::new();
        let mut t0 = 0.0;
        let mut output = budget::Output::new(spec, &self.mesh);
        for (i, s) in spec.step.iter().enumerate() {
            let key = format!("step[{i}]");
            let step = self.step(&key, s, t0)?;
            let length = s.end_time - t0;
            if let Some(fault) = output.add_step(length, step.max_increment) {
                return Err(self.err(format!("{key}: {fault}")));
            }
            steps.push(step);
            t0 = s.end_time;
        }
        Ok(steps)
    }

    /// Step `s` (key `key`) after the step ending at `t0`: its end after
    /// `t0`, its increments positive, `min ≤ initial`, `min ≤ max`, and no
    /// more than its limit of increments. Defaults: the initial and the
    /// largest increment the whole step, the smallest 1/1024 of the
    /// initial one.
    fn step(&self, key: &str, s: &StepSpec, t0: f64) -> Result<Step> {
        let length = s.end_time - t0;
        if !s.end_time.is_finite() {
            return Err(self.err(not_positive(&format!("{key}.end_time"), s.end_time)));
        }
        if !(length > 0.0) {
            return Err(self.err(format!(
                "{key}.end_time = {} must be greater than the previous step's end ({t0})",
                s.end_time
            )));
        }
        let initial = s.initial_increment.unwrap_or(length);
        let max = s.max_increment.unwrap_or(length);
        let min = s.min_increment.unwrap_or(initial / 1024.0);
        for (name, v) in [
            ("initial_increment", initial),
            ("max_increment", max),
            ("min_increment", min),
        ] {
            if !(v > 0.0) || !v.is_finite() {
                return Err(self.err(not_positive(&format!("{key}.{name}"), v)));
            }
        }
        if max < min {
            return Err(self.err(format!(
                "{key}.max_increment = {max} is smaller than min_increment = {min}; \
                 give max_increment ≥ min_increment"
            )));
        }
        if min > initial {
            return Err(self.err(format!(
                "{key}.min_increment = {min} exceeds initial_increment = {initial}"
            )));
        }
        let limit = s.max_increments.unwrap_or(budget::MAX_INCREMENTS);
        if let Some(fault) = budget::increments_fault(length, max, limit) {
            let max = crate::input::number(max);
            return Err(self.err(format!("{key}.max_increment = {max}: {fault}")));
        }
        Ok(Step {
            name: s.name.clone(),
            end_time: s.end_time,
            initial_increment: initial.min(max),
            min_increment: min,
            max_increment: max,
        })
    }
}
