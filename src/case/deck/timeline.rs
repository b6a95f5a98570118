//! A prescribed quantity of a deck (one dof of a `*BOUNDARY` node set, one
//! component of a `*CLOAD`, one pressure) as a piecewise-linear function of
//! the total time, which is what a case's amplitude is.
//!
//! Abaqus's rules for a static step, as applied here: a quantity given in
//! a step without `AMPLITUDE=` ramps linearly from its value at the end of
//! the previous step to the new value over the step; with `AMPLITUDE=a` it
//! is `value × a(t)`, `t` the step time (or the total time with
//! `TIME=TOTAL TIME`), `a` held at its last point after it; a quantity not
//! given in a step keeps its value (it is propagated); with `OP=NEW` the
//! loads not given again ramp down to zero over the step (a boundary
//! condition that `OP=NEW` would release is an error: a case cannot free a
//! prescribed dof).

use crate::mesh::inp::physics::{AmplitudeDef, Located};
use crate::Result;

/// The span `[start, end]` of each step in total time.
pub(super) type Spans = [(f64, f64)];

/// What happens to a quantity in a step.
#[derive(Clone, Debug)]
pub(super) enum InStep<'a> {
    /// Given: value, amplitude name, where.
    Given(f64, Option<&'a str>, &'a Located),
    /// Removed by `OP=NEW` (loads only).
    Removed,
    /// Propagated.
    Held,
}

/// `(total time, value)` points, times strictly increasing, from
/// `(0, initial)`; `steps[k]` says what step `k` does.
pub(super) fn timeline(
    initial: f64,
    steps: &[InStep],
    spans: &Spans,
    amplitudes: &[AmplitudeDef],
) -> Result<Vec<(f64, f64)>> {
    let mut points = vec![(0.0, initial)];
    let mut current = initial;
    for (step, &(t0, t1)) in steps.iter().zip(spans) {
        match *step {
            InStep::Held => points.push((t1, current)),
            InStep::Removed => {
                points.push((t1, 0.0));
                current = 0.0;
            }
            InStep::Given(value, None, _) => {
                points.push((t1, value));
                current = value;
            }
            InStep::Given(value, Some(name), at) => {
                let a = amplitudes
                    .iter()
                    .find(|a| a.name.eq_ignore_ascii_case(name))
                    .ok_or_else(|| {
                        at.error(format!("AMPLITUDE={name}: no *AMPLITUDE of that name"))
                    })?;
                let shift = if a.total_time { 0.0 } else { t0 };
                let at_start = value * interpolate(&a.points, t0 - shift);
                let tolerance = 1e-12 * (value.abs() + current.abs());
                if (at_start - current).abs() > tolerance {
                    return Err(at.error(format!(
                        "AMPLITUDE={name} gives {at_start} at the start of the step, where the value is \
                         {current} (from time 0 or the step before): a jump cannot be followed; start the \
                         amplitude where the value is"
                    )));
                }
                for &(t, v) in &a.points {
                    let t = t + shift;
                    if t > t0 && t < t1 {
                        points.push((t, value * v));
                    }
                }
                current = value * interpolate(&a.points, t1 - shift);
                points.push((t1, current));
            }
        }
    }
    Ok(simplify(points))
}

/// Piecewise-linear interpolation, held before the first and after the
/// last point (as the case's amplitudes are).
fn interpolate(points: &[(f64, f64)], t: f64) -> f64 {
    crate::problem::Amplitude::new(points.to_vec()).value(t)
}

/// Drops the points inside a constant stretch and the trailing constant
/// ones (a held value needs no point).
fn simplify(points: Vec<(f64, f64)>) -> Vec<(f64, f64)> {
    let mut out: Vec<(f64, f64)> = Vec::with_capacity(points.len());
    for p in points {
        let n = out.len();
        if n >= 2 && out[n - 1].1 == p.1 && out[n - 2].1 == p.1 {
            out[n - 1] = p;
        } else {
            out.push(p);
        }
    }
    while out.len() >= 2 && out[out.len() - 1].1 == out[out.len() - 2].1 {
        out.pop();
    }
    out
}

/// A timeline as a scale and an amplitude: `(scale, None)` when it is
/// `scale` times the case's default amplitude (0 at time 0, 1 at the end
/// of the first step, then held) or zero throughout; else the scale is the
/// value of largest magnitude and the amplitude the points over it.
pub(super) fn scaled(points: &[(f64, f64)], first_end: f64) -> (f64, Option<Vec<(f64, f64)>>) {
    let scale = points
        .iter()
        .map(|p| p.1)
        .fold(0.0f64, |m, v| if v.abs() > m.abs() { v } else { m });
    if scale == 0.0 {
        return (0.0, None);
    }
    let normalised: Vec<(f64, f64)> = points.iter().map(|&(t, v)| (t, v / scale)).collect();
    if normalised == [(0.0, 0.0), (first_end, 1.0)] {
        return (scale, None);
    }
    (scale, Some(normalised))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at() -> Located {
        Located {
            path: "deck.inp".into(),
            line: 1,
        }
    }

    /// Press then pull: a dof fixed at 0 in step 1 (ramps nowhere), moved
    /// to 2 in step 2 (ramps 0 → 2 over [1, 3]); a load given in step 1,
    /// held in step 2, removed in step 3; an amplitude in step time.
    #[test]
    fn abaqus_step_rules() {
        let spans = [(0.0, 1.0), (1.0, 3.0), (3.0, 4.0)];
        let here = at();
        let held = timeline(
            0.0,
            &[
                InStep::Given(0.0, None, &here),
                InStep::Given(2.0, None, &here),
                InStep::Held,
            ],
            &spans,
            &[],
        )
        .unwrap();
        assert_eq!(held, [(0.0, 0.0), (1.0, 0.0), (3.0, 2.0)]);
        assert_eq!(
            scaled(&held, 1.0),
            (2.0, Some(vec![(0.0, 0.0), (1.0, 0.0), (3.0, 1.0)]))
        );
        let load = timeline(
            0.0,
            &[
                InStep::Given(-5.0, None, &here),
                InStep::Held,
                InStep::Removed,
            ],
            &spans,
            &[],
        )
        .unwrap();
        assert_eq!(load, [(0.0, 0.0), (1.0, -5.0), (3.0, -5.0), (4.0, 0.0)]);
        let ramp = timeline(
            0.0,
            &[InStep::Given(7.0, None, &here), InStep::Held, InStep::Held],
            &spans,
            &[],
        )
        .unwrap();
        assert_eq!(scaled(&ramp, 1.0), (7.0, None));
        let a = AmplitudeDef {
            name: "Up".into(),
            points: vec![(0.0, 0.0), (0.5, 1.0), (2.0, 0.5)],
            total_time: false,
            at: at(),
        };
        let shaped = timeline(
            0.0,
            &[
                InStep::Held,
                InStep::Given(4.0, Some("UP"), &here),
                InStep::Held,
            ],
            &spans,
            &[a],
        )
        .unwrap();
        assert_eq!(shaped, [(0.0, 0.0), (1.0, 0.0), (1.5, 4.0), (3.0, 2.0)]);
        // an amplitude that would jump from the value held
        let jump = timeline(
            0.0,
            &[
                InStep::Given(1.0, None, &here),
                InStep::Given(4.0, Some("up"), &here),
                InStep::Held,
            ],
            &spans,
            &[AmplitudeDef {
                name: "up".into(),
                points: vec![(0.0, 0.0), (1.0, 1.0)],
                total_time: false,
                at: at(),
            }],
        );
        assert!(jump
            .unwrap_err()
            .to_string()
            .contains("a jump cannot be followed"));
    }
}
