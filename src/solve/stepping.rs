//! Adaptive load stepping: each step's pseudo-time interval is covered by
//! increments that are cut (halved) when Newton fails — divergence, a NaN,
//! an inverted element, too many iterations — and grown after easy ones.
//! After `max_cuts` consecutive cuts the run stops with an error; every
//! increment converged before stays written, since output happens in the
//! `on_converged` callback as each increment converges.

use super::linear::SparseLdlt;
use super::newton::{solve_increment, IterationRecord, NewtonOutcome};
use crate::problem::{ContactState, Problem};
use crate::{Error, Result};
use std::path::PathBuf;

/// A converged increment.
#[derive(Clone, Debug, serde::Serialize)]
pub struct IncrementRecord {
    /// Index of the step (0-based) and its name.
    pub step: usize,
    pub step_name: String,
    /// Pseudo-time at the end of the increment.
    pub time: f64,
    /// Size of the increment.
    pub increment: f64,
    /// Newton iterations (the number of corrections solved).
    pub iterations: usize,
    /// Per-iteration residuals and corrections.
    pub newton: Vec<IterationRecord>,
    /// Cuts suffered before this increment converged.
    pub cuts: usize,
}

/// What the stepper reports as it goes.
pub trait StepObserver {
    /// An increment converged; `u` holds the new unknowns (displacements,
    /// then contact multipliers), `residual` the `f_int − f_ext − f_contact`
    /// there (the reactions on prescribed dofs) and `contact` the committed
    /// contact states. Write output here.
    fn on_converged(
        &mut self,
        problem: &Problem,
        record: &IncrementRecord,
        u: &[f64],
        residual: &[f64],
        contact: &ContactState,
    ) -> Result<()>;
    /// An increment failed and is cut.
    fn on_cut(&mut self, _step: &str, _time: f64, _increment: f64, _reason: &str) {}
}

/// Run every step of `problem` from `u = 0` (except the prescribed values).
/// Returns the final displacement. `problem` is mutable for the contact
/// pairs of deformable interfaces, searched again at the start of every
/// increment attempt (and the sparsity pattern with them).
pub fn run_steps(
    problem: &mut Problem,
    solver: &mut SparseLdlt,
    observer: &mut dyn StepObserver,
    output: PathBuf,
) -> Result<Vec<f64>> {
    let constrained = problem.constrained_dofs();
    let mut u = vec![0.0; problem.num_unknowns()];
    problem.apply_prescribed(0.0, &mut u);
    let mut contact = problem.initial_contact_state(&u);
    let mut trial = Vec::with_capacity(u.len());
    let mut t = 0.0;
    let mut force_scale = 0.0f64;
    let mut any_converged = false;
    // largest nodal displacement of the last converged increment, and its length
    let mut last_motion: Option<(f64, f64)> = None;
    let steps = problem.steps.clone();
    for (s, step) in steps.iter().enumerate() {
        let mut dt = step.initial_increment.min(step.end_time - t);
        let mut cuts = 0;
        while t < step.end_time - 1e-12 * step.end_time.abs().max(1.0) {
            dt = dt.min(step.end_time - t);
            // no sliver of an increment at the end of a step
            if step.end_time - (t + dt) < 0.25 * dt {
                dt = step.end_time - t;
            }
            let t_new = if dt >= step.end_time - t {
                step.end_time
            } else {
                t + dt
            };
            let motion = last_motion.map_or(0.0, |(m, last_dt)| m * (t_new - t) / last_dt);
            if problem.refresh_contact_pairs(&u, motion) {
                // new couplings: order them (each multiplier after its nodes)
                solver.set_ordering(super::ordering::fill_reducing_ordering(problem)?);
            }
            let problem: &Problem = problem;
            let mut trial_contact = contact.clone();
            let (outcome, newton) = solve_with_augmentation(
                problem,
                solver,
                &constrained,
                &u,
                t_new,
                force_scale,
                &mut trial_contact,
                &mut trial,
            )?;
            let outcome = match outcome {
                NewtonOutcome::Converged { .. } if !problem.contact_pairs_hold(&trial, &trial_contact) => {
                    NewtonOutcome::Failed(
                        "a contact node slid beyond the primary triangles it was paired with at the \
                         start of the increment"
                            .into(),
                    )
                }
                other => other,
            };
            match outcome {
                NewtonOutcome::Converged {
                    residual,
                    force_scale: scale,
                } => {
                    let moved = problem
                        .deformable_contact_nodes()
                        .into_iter()
                        .map(|n| {
                            (0..3)
                                .map(|d| (trial[3 * n + d] - u[3 * n + d]).powi(2))
                                .sum::<f64>()
                                .sqrt()
                        })
                        .fold(0.0f64, f64::max);
                    last_motion = Some((moved, t_new - t));
                    std::mem::swap(&mut u, &mut trial);
                    problem.commit_contact_history(t_new, &u, &mut trial_contact);
                    contact = trial_contact;
                    force_scale = force_scale.max(scale);
                    any_converged = true;
                    let record = IncrementRecord {
                        step: s,
                        step_name: step.name.clone(),
                        time: t_new,
                        increment: t_new - t,
                        iterations: newton.len() - 1,
                        newton,
                        cuts,
                    };
                    t = t_new;
                    observer.on_converged(problem, &record, &u, &residual, &contact)?;
                    if record.iterations <= problem.settings.easy_iterations && cuts == 0 {
                        dt = (dt * problem.settings.growth_factor).min(step.max_increment);
                    }
                    cuts = 0;
                }
                NewtonOutcome::Failed(reason) => {
                    observer.on_cut(&step.name, t_new, dt, &reason);
                    cuts += 1;
                    if cuts > problem.settings.max_cuts || 0.5 * dt < step.min_increment {
                        return Err(Error::NoConvergence {
                            step: step.name.clone(),
                            time: t_new,
                            cuts: cuts - 1,
                            increment: dt,
                            reason,
                            last_converged_time: any_converged.then_some(t),
                            output,
                        });
                    }
                    dt *= 0.5;
                }
            }
        }
    }
    Ok(u)
}

/// Most outer (Uzawa) augmentations of one increment.
const MAX_AUGMENTATIONS: usize = 200;

/// Newton for one increment; for Uzawa interfaces, followed by multiplier
/// updates and new Newton solves at the same time until the largest
/// penetration is within tolerance (formulation note §2.1 item 2).
#[allow(clippy::too_many_arguments)]
fn solve_with_augmentation(
    problem: &Problem,
    solver: &mut SparseLdlt,
    constrained: &[bool],
    u_start: &[f64],
    t: f64,
    force_scale: f64,
    contact: &mut ContactState,
    u: &mut Vec<f64>,
) -> Result<(NewtonOutcome, Vec<IterationRecord>)> {
    let (mut outcome, mut records) = solve_increment(
        problem,
        solver,
        constrained,
        u_start,
        u_start,
        t,
        force_scale,
        contact,
        u,
    )?;
    let mut augmentations = 0;
    while matches!(outcome, NewtonOutcome::Converged { .. })
        && problem.augment_multipliers(t, u, contact)
    {
        augmentations += 1;
        if augmentations > MAX_AUGMENTATIONS {
            return Ok((
                NewtonOutcome::Failed(format!(
                    "the Uzawa multipliers did not reach the penetration tolerance in {MAX_AUGMENTATIONS} updates"
                )),
                records,
            ));
        }
        let start = u.clone();
        let (next, more) = solve_increment(
            problem,
            solver,
            constrained,
            &start,
            u_start,
            t,
            force_scale,
            contact,
            u,
        )?;
        outcome = next;
        records.extend(more);
    }
    Ok((outcome, records))
}
