//! What a method reports of each iteration of an increment
//! ([`IterationRecord`]: Newton's, or the condensed path's contact solve's
//! steps), and whether an increment converged well enough to grow the next
//! ([`converged_well`]).

use super::linear_solver::LinearFigures;

/// One Newton iteration as reported to the user.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct IterationRecord {
    /// `‖r_free‖ / max(‖f_ext‖, ‖f_int‖)` at the start of the iteration
    /// (Newton's; the condensed path's steps report their own measure,
    /// DESIGN.md "The condensed contact path").
    pub residual: f64,
    /// `‖α δu‖ / ‖Δu‖` of the correction taken in this iteration (0 on the
    /// last, converged, evaluation).
    pub correction: f64,
    /// Line-search step length taken.
    pub step_length: f64,
    /// Contact nodes whose status (open/stick/slip) changed since the
    /// previous iteration.
    pub switched: usize,
    /// What the linear solver did for the correction (zero on the last,
    /// converged, evaluation).
    pub linear: LinearFigures,
}

/// Whether Newton converged well enough over an increment (its
/// `records`, the last one the converged evaluation) for the next
/// increment to grow: in at most `easy` iterations, or with the contact
/// statuses settled and Newton's rate then fast. A contact increment
/// starts from a large residual whatever its size (the prescribed jump,
/// the contact set to find), so the iteration count alone would keep an
/// increment that was cut small for the rest of the step. Settled and
/// fast: the last status switch (`switched > 0`) at iteration `s ≤ easy`,
/// at most `easy` iterations after it, every one a full Newton step
/// (line-search step length 1), and the residual falling from `r_s` to
/// `r_n` at a mean rate `(r_n / r_s)^(1/(n−s)) ≤ 0.1` per iteration (a
/// superlinear or steep linear rate: a stagnating or line-searched path
/// is not easy).
pub(crate) fn converged_well(records: &[IterationRecord], easy: usize) -> bool {
    let iterations = records.len().saturating_sub(1);
    if iterations <= easy {
        return true;
    }
    let settled = records.iter().rposition(|r| r.switched > 0).unwrap_or(0);
    let after = iterations - settled;
    if settled > easy || after > easy {
        return false;
    }
    let full_steps = records[settled..iterations]
        .iter()
        .all(|r| r.step_length == 1.0);
    let (first, last) = (records[settled].residual, records[iterations].residual);
    let rate = if first > 0.0 {
        (last / first).powf(1.0 / after as f64)
    } else {
        0.0
    };
    full_steps && rate <= 0.1
}
