//! Newton–Raphson for one load increment, with the consistent tangent and a
//! backtracking line search.
//!
//! Prescribed displacements are imposed exactly on the iterate; their rows
//! and columns of `K` are replaced by a scaled identity, so the sparsity
//! pattern (and its symbolic factorisation) never changes.

use super::backend::mixed_precision;
use super::chattering::Chatter;
use super::failure::{closed_contact, largest_motion, ClosedContact, IncrementFailure};
use super::gmres::{dot, norm};
use super::josephy::{HeldTangent, Josephy, JosephyStep};
use super::linear_solver::{LinearFigures, LinearSolver, LinearSystem};
use super::nonlinear::{Evaluation, NonlinearProblem};
use super::settings::{Predictor, SolverSettings};
pub use super::tangent_store::apply_identity_rows;
use super::tangent_store::TangentStore;

pub use super::record::IterationRecord;

/// How an increment ended: the converged evaluation (its residual's
/// prescribed entries are the reactions) or why it failed, and the
/// iterations either way.
pub type NewtonOutcome<R> = (
    Result<Evaluation<R>, IncrementFailure>,
    Vec<IterationRecord>,
);

/// Newton for one increment ending at time `t`: the problem, the linear
/// solver and what stays fixed over the increment.
pub struct Newton<'a, P: NonlinearProblem> {
    pub problem: &'a P,
    pub solver: &'a mut dyn LinearSolver,
    /// Which unknowns are prescribed.
    pub constrained: &'a [bool],
    pub t: f64,
    /// The largest `max(‖f_int‖, ‖f_ext‖)` of the converged increments so
    /// far: residuals are measured relative to it too, so that a state of
    /// vanishing load (unloading to zero) can converge.
    pub force_scale: f64,
    /// Told of every iteration once its correction is taken (progress,
    /// logs); returns whether to go on (`false`: the run is cancelled, and
    /// the increment ends with [`IncrementFailure::Cancelled`]).
    pub on_iteration: Option<&'a mut dyn FnMut(&IterationRecord) -> bool>,
    /// The factor of the Josephy–Newton steps (`[solver] predictor =
    /// "contact"`), kept over the run.
    pub josephy: &'a mut Josephy,
    /// The predictor that runs (`[solver] predictor` resolved:
    /// [`Predictor::chosen`]): [`Predictor::Contact`] takes the
    /// Josephy–Newton steps.
    pub predictor: Predictor,
}

impl<P: NonlinearProblem> Newton<'_, P> {
    /// Solve the increment from the converged state `u_start`. On return
    /// `u` holds the last iterate. The displacement criterion compares each
    /// correction with the change since `increment_start`, the state
    /// converged at the start of the increment (`u_start` itself, except
    /// for the Uzawa re-solves of one increment, whose own changes become
    /// tiny as the multipliers settle).
    ///
    /// The prescribed displacements are not jumped to their new values
    /// before the first iteration (that would distort the elements along
    /// the boundary and start Newton far from the solution); the jump
    /// `d = ū(t) − u` on the prescribed dofs is part of the first Newton
    /// correction instead: `K_ff δu_f = −r_f − K_fc d`, `δu_c = d`, which
    /// is the linearisation about the converged state (a consistent
    /// predictor).
    ///
    /// A failure of the linear solve (a singular tangent at a limit point,
    /// a Krylov solve that does not converge) is a failed increment, which
    /// the stepper cuts.
    pub fn solve(
        &mut self,
        u_start: &[f64],
        increment_start: &[f64],
        state: &mut P::State,
        u: &mut Vec<f64>,
    ) -> NewtonOutcome<P::Report> {
        let (problem, constrained, t) = (self.problem, self.constrained, self.t);
        let settings = problem.settings();
        let blocks = problem.pattern();
        u.clear();
        u.extend_from_slice(u_start);
        let mut target = u_start.to_vec();
        problem.apply_prescribed(t, &mut target);
        let mut records: Vec<IterationRecord> = Vec::new();
        let mut tangent = match TangentStore::new(problem, &mut *self.solver) {
            Ok(tangent) => tangent,
            Err(f) => return (Err(f), records),
        };
        let mut kd = vec![0.0; u.len()];
        let mut last_correction = f64::INFINITY;
        // the largest force the prescribed jump set up in this increment
        // (`‖K d‖` at the first iteration), kept as a scale for the later ones
        let mut jump_scale = 0.0f64;
        let signs = (blocks.dimension() > problem.num_dofs()).then(|| blocks.pivot_signs());
        let mut chatter = super::chattering::ChatterDetector::default();
        // the line search's trial that was taken, evaluated with its tangent
        // (the full step, or a shorter step of the contact predictor): the
        // next iteration's evaluation
        let mut ahead: Option<Evaluation<P::Report>> = None;
        let mut iteration = 0;
        loop {
            let jump = remaining_jump(&target, u, constrained);
            let at_target = jump.iter().all(|&d| d == 0.0);
            // the force alone first where it may show convergence (the first
            // evaluation, or after a residual already near the tolerance): the
            // tangent costs far more and is not needed then; otherwise both at once
            let may_converge = records
                .last()
                .is_none_or(|r| r.residual < 1e3 * settings.residual_tolerance);
            let have_tangent = !(at_target && may_converge);
            let evaluation = match ahead.take() {
                Some(e) if have_tangent => e,
                _ => {
                    let evaluated = if have_tangent {
                        tangent.evaluate(problem, t, u, state)
                    } else {
                        problem.evaluate(t, u, state, None)
                    };
                    match evaluated {
                        Ok(e) => e,
                        Err(f) => return (Err(f), records),
                    }
                }
            };
            // every contact node open (status 0 mod 4): nothing but supports holds the body
            let all_open = evaluation.statuses.iter().all(|s| s % 4 == 0);
            let all_open = all_open && !evaluation.statuses.is_empty();
            let closed = closed_contact(&evaluation.statuses, problem.has_friction());
            let (switched, chattering) = chatter.observe(evaluation.statuses.clone());
            let mut r = evaluation.residual.clone();
            zero_constrained(&mut r, constrained);
            let known = have_tangent.then_some(&tangent);
            let out_of_balance = match self.out_of_balance(&r, known, &jump, at_target, &mut kd) {
                Ok(v) => v,
                Err(f) => return (Err(f), records),
            };
            // the force scale: internal and external forces, those of earlier
            // increments, and the forces the prescribed jump sets up (all there
            // is at the first iteration of a displacement-driven run), kept
            // over the increment: a prescribed rigid motion, e.g. a rotation,
            // converges to a state with no force at all
            jump_scale = jump_scale.max(norm(&kd));
            let scale = [evaluation.force_scale(), self.force_scale, jump_scale];
            let scale = scale.into_iter().fold(f64::MIN_POSITIVE, f64::max);
            let relative = norm(&out_of_balance) / scale;
            records.push(IterationRecord {
                residual: relative,
                correction: 0.0,
                step_length: 0.0,
                switched,
                linear: LinearFigures::default(),
            });
            let verdict = Verdict {
                iteration,
                at_target,
                switched,
                relative,
                balanced: norm(&r) == 0.0,
                last_correction,
            };
            if let Some(end) = verdict.ends(settings, &records, chattering) {
                return (end.map(|()| evaluation), records);
            }
            let solve = TangentSolve {
                jump: &jump,
                out_of_balance: &out_of_balance,
                signs: signs.as_deref(),
                have_tangent,
            };
            let (du, predictor) =
                match self.correction(iteration, solve, u, state, &mut tangent, &mut records) {
                    Ok(c) => c,
                    Err(f) => return (Err(f), records),
                };
            if let Some(f) = rigid_body_mode(problem, &du, constrained, all_open, closed) {
                return (Err(f), records);
            }
            let line = NewtonStep {
                u,
                du: &du,
                target: &target,
                predictor,
            };
            let (step_length, taken) =
                self.line_search(line, &out_of_balance, relative, state, &mut tangent);
            ahead = taken;
            last_correction = self.advance(u, &du, step_length, state, &target, increment_start);
            if let Some(rec) = records.last_mut() {
                rec.correction = last_correction;
                rec.step_length = step_length;
                if let Some(tell) = self.on_iteration.as_mut() {
                    if !tell(rec) {
                        return (Err(IncrementFailure::Cancelled), records);
                    }
                }
            }
            iteration += 1;
        }
    }

    /// This iteration's correction and whether it is the contact
    /// predictor's: the first correction as a Josephy–Newton step where
    /// asked for and where the problem linearises its constraints, else
    /// Newton's step from the tangent; the prescribed dofs take their jump.
    fn correction(
        &mut self,
        iteration: usize,
        solve: TangentSolve<'_>,
        u: &[f64],
        state: &P::State,
        k: &mut TangentStore,
        records: &mut [IterationRecord],
    ) -> Result<(Vec<f64>, bool), IncrementFailure> {
        let contact_step = (iteration == 0 && self.predictor == Predictor::Contact)
            .then(|| self.josephy_correction(solve.jump, u, state))
            .flatten();
        let predictor = contact_step.is_some();
        let mut du = match contact_step {
            Some(step) => {
                if let Some(rec) = records.last_mut() {
                    rec.linear = step.figures;
                }
                step.correction
            }
            None => self.tangent_correction(solve, u, state, k, records)?,
        };
        for (d, (&c, &j)) in du.iter_mut().zip(self.constrained.iter().zip(solve.jump)) {
            if c {
                *d = j;
            }
        }
        Ok((du, predictor))
    }

    /// The out-of-balance force on the free dofs, with the linearised
    /// effect of the prescribed values still to be reached: `r_f + K_fc d`
    /// (`k`: the tangent where it was evaluated; without it, or with
    /// `at_target`, `K_fc d = 0`). `kd` is scratch of `u`'s length.
    fn out_of_balance(
        &self,
        r: &[f64],
        k: Option<&TangentStore>,
        jump: &[f64],
        at_target: bool,
        kd: &mut [f64],
    ) -> Result<Vec<f64>, IncrementFailure> {
        kd.iter_mut().for_each(|x| *x = 0.0);
        if let (Some(k), false) = (k, at_target) {
            k.multiply(self.problem, jump, kd)?;
        }
        Ok((0..r.len())
            .map(|i| {
                if self.constrained[i] {
                    0.0
                } else {
                    r[i] + kd[i]
                }
            })
            .collect())
    }

    /// Newton's correction from the tangent `k` (evaluated first unless
    /// `have_tangent`): `K_ff δu_f = −(r_f + K_fc d)`, with the prescribed
    /// rows a scaled identity on the jump `d`, and for a nonsymmetric
    /// tangent the symmetric neighbour the solver's preconditioner reads
    /// (friction's slip blocks replaced by stick blocks). The linear
    /// solver's figures go into the last of `records`.
    fn tangent_correction(
        &mut self,
        solve: TangentSolve<'_>,
        u: &[f64],
        state: &P::State,
        k: &mut TangentStore,
        records: &mut [IterationRecord],
    ) -> Result<Vec<f64>, IncrementFailure> {
        let (problem, constrained, t) = (self.problem, self.constrained, self.t);
        let blocks = problem.pattern();
        if !solve.have_tangent {
            k.evaluate(problem, t, u, state)?;
        }
        let nonsymmetric = problem.has_nonsymmetric_tangent();
        let neighbour = (nonsymmetric && self.solver.reads_symmetric_neighbour()).then(|| {
            let mut p = blocks.symmetric_part(k.values());
            problem.symmetric_neighbour(t, u, state, constrained, &mut p);
            apply_identity_rows(problem, constrained, &mut p);
            p
        });
        // rhs: −(r_f + K_fc d) on the free dofs, (diagonal scale) · d on the prescribed ones
        let diagonal = k.identity_rows(problem, constrained)?;
        let rhs: Vec<f64> = (0..u.len())
            .map(|i| {
                if constrained[i] {
                    diagonal * solve.jump[i]
                } else {
                    -solve.out_of_balance[i]
                }
            })
            .collect();
        let mut du = rhs.clone();
        let system = LinearSystem {
            pattern: blocks.symbolic(),
            matrix: k.values(),
            symmetric_neighbour: neighbour.as_deref(),
            pivot_signs: solve.signs,
        };
        let before = self.solver.statistics();
        let solved = self.solver.solve(&system, &rhs, &mut du);
        if let Some(record) = records.last_mut() {
            record.linear = self.solver.statistics().since(&before);
        }
        solved.map_err(IncrementFailure::LinearSolve)?;
        Ok(du)
    }

    /// Take `step_length` of the correction `du` from `u` (and the local
    /// contact unknowns in `state` with it), landing exactly on the
    /// prescribed `target` after a full step; returns the correction's
    /// size relative to the change since `increment_start`.
    fn advance(
        &self,
        u: &mut [f64],
        du: &[f64],
        step_length: f64,
        state: &mut P::State,
        target: &[f64],
        increment_start: &[f64],
    ) -> f64 {
        let scaled: Vec<f64> = du.iter().map(|d| step_length * d).collect();
        self.problem.advance_state(self.t, u, &scaled, state);
        for (ui, di) in u.iter_mut().zip(&scaled) {
            *ui += di;
        }
        if step_length == 1.0 {
            for i in 0..u.len() {
                if self.constrained[i] {
                    u[i] = target[i];
                }
            }
        }
        let total: Vec<f64> = u.iter().zip(increment_start).map(|(a, b)| a - b).collect();
        step_length * norm(du) / norm(&total).max(f64::MIN_POSITIVE)
    }

    /// The first correction of an increment as a Josephy–Newton step
    /// ([`super::josephy`]) from `u`, with `jump` the prescribed values
    /// still to be reached; `None` (Newton's plain step then) where the
    /// problem does not linearise its constraints or the step fails. Its
    /// `K̂` is factorised in f32 where the linear solver would factorise
    /// the tangent so ([`mixed_precision`]: `linear = "mixed"`, or `"auto"`
    /// from `MIXED_PRECISION_DOFS` unknowns). Only the first: once the step
    /// has found the linearised problem's contact set, Newton's plain
    /// steps (one factorisation of the saddle-point tangent each, smaller
    /// than `K̂`'s with the contact dofs last) took as many iterations on
    /// every case measured (BENCHMARKS.md, "Issue 13 item 4, fourth
    /// round").
    fn josephy_correction(
        &mut self,
        jump: &[f64],
        u: &[f64],
        state: &P::State,
    ) -> Option<JosephyStep> {
        let problem = self.problem;
        let blocks = problem.pattern();
        let mut k = vec![0.0; blocks.nnz()];
        let linearisation = problem
            .linearise_constraints(self.t, u, state, &mut k)
            .ok()??;
        // K_fc d, then the prescribed unknowns and every multiplier held
        let mut kd = vec![0.0; u.len()];
        super::linear::multiply(blocks.symbolic(), &k, jump, &mut kd);
        let mut held = self.constrained.to_vec();
        held[problem.num_dofs()..]
            .iter_mut()
            .for_each(|h| *h = true);
        let scale = apply_identity_rows(problem, &held, &mut k);
        let rhs: Vec<f64> = (0..u.len())
            .map(|i| {
                if self.constrained[i] {
                    scale * jump[i]
                } else if held[i] {
                    0.0
                } else {
                    -(linearisation.residual[i] + kd[i])
                }
            })
            .collect();
        let tangent = HeldTangent {
            pattern: blocks,
            values: &k,
            scale,
            held: &held,
            single: mixed_precision(problem.settings().linear).applies(blocks.dimension()),
        };
        self.josephy
            .step(tangent, &rhs, u, &linearisation.constraints)
            .ok()
    }

    /// Line search along the Newton direction `δu`.
    ///
    /// The slope of the potential along the line, `s(α) = δu · r(u + α δu)`
    /// (free dofs), is negative at `α = 0` for a descent direction. The
    /// full step is taken if `|s(1)| ≤ ½ |s(0)|` or if the residual norm
    /// decreases (Crisfield's test, which accepts steps that raise `‖r‖`
    /// but lower the energy, as bending under large rotations needs);
    /// otherwise `α` moves to the zero of the secant of `s` (regula falsi,
    /// bounded to [0.1α, 0.9α]), or is halved when the trial state inverts
    /// an element. Skipped near the tolerance, where the full step keeps
    /// the quadratic rate. At most six trials; the one with the smallest
    /// `|s|` is taken if none passes.
    ///
    /// The contact predictor's step (`predictor`: the Josephy–Newton step
    /// at the first correction, the linearised answer for the whole
    /// increment) is taken only where it lowers `‖r‖`: a step that raises
    /// the residual and overshoots the potential's minimum along it
    /// (`s(1) > 0 > s(0)`, the material stiffer than its tangent at the
    /// start) goes to the secant zero of `s` instead of being kept by the
    /// `½` rule. On examples/ogden-plate's first increment (rest to half
    /// the load) the full step raised `‖r‖` by 8 % with `s(1) = −0.33 s(0)`;
    /// `α = 0.754` took that increment from 6 Newton iterations to 5
    /// (BENCHMARKS.md, "Session 10: the plate's first increment").
    ///
    /// The full step is tried first and evaluated with its tangent (into
    /// `k`, the prescribed dofs on their `target`): when it is taken, that
    /// evaluation is returned as the next iteration's, which needs the
    /// tangent there anyway (the line search runs only far from the
    /// tolerance), so a taken full step costs no evaluation of its own.
    /// The predictor's shorter trials are evaluated with their tangent
    /// too, and the one taken likewise serves as the next iteration's.
    fn line_search(
        &self,
        line: NewtonStep<'_>,
        r: &[f64],
        relative: f64,
        state: &P::State,
        k: &mut TangentStore,
    ) -> (f64, Option<Evaluation<P::Report>>) {
        let NewtonStep {
            u,
            du,
            target,
            predictor,
        } = line;
        let (problem, t) = (self.problem, self.t);
        let settings = problem.settings();
        if !settings.line_search || relative < 1e3 * settings.residual_tolerance {
            return (1.0, None);
        }
        let r0 = norm(r);
        // the slope of the potential along the line, over the displacements
        // only: a saddle point is not a minimum in the multipliers
        let dofs = problem.num_dofs();
        let slope = |r: &[f64]| dot(&du[..dofs], &r[..dofs]);
        let s0 = slope(r);
        let mut trial = u.to_vec();
        let mut alpha = 1.0;
        let mut best = (f64::INFINITY, 1.0);
        for _ in 0..6 {
            let step: Vec<f64> = du.iter().map(|d| alpha * d).collect();
            for ((x, u0), d) in trial.iter_mut().zip(u).zip(&step) {
                *x = u0 + d;
            }
            let full = alpha == 1.0;
            if full {
                // where Newton lands after a full step
                for ((x, &c), v) in trial.iter_mut().zip(self.constrained).zip(target) {
                    if c {
                        *x = *v;
                    }
                }
            }
            // the local contact unknowns follow the trial step too
            let mut trial_state = state.clone();
            problem.advance_state(t, u, &step, &mut trial_state);
            let with_tangent = full || predictor;
            let evaluated = if with_tangent {
                k.evaluate(problem, t, &trial, &trial_state)
            } else {
                problem.evaluate(t, &trial, &trial_state, None)
            };
            let Ok(evaluation) = evaluated else {
                // an inverted element: shorter, and remember it in case all fail
                if best.0 == f64::INFINITY {
                    best.1 = 0.5 * alpha;
                }
                alpha *= 0.5;
                continue;
            };
            let mut ra = evaluation.residual.clone();
            zero_constrained(&mut ra, self.constrained);
            let sa = slope(&ra);
            let energy_test = !predictor && s0 < 0.0 && sa.abs() <= 0.5 * s0.abs();
            if norm(&ra) < r0 || energy_test {
                return (alpha, with_tangent.then_some(evaluation));
            }
            if sa.abs() < best.0 {
                best = (sa.abs(), alpha);
            }
            alpha = if s0 < 0.0 && sa > 0.0 {
                // the slope changed sign in (0, α): its secant zero
                (alpha * s0 / (s0 - sa)).clamp(0.1 * alpha, 0.9 * alpha)
            } else {
                0.5 * alpha
            };
        }
        (best.1, None)
    }
}

/// The line a line search walks: from the iterate `u` along Newton's
/// correction `δu`; a full step puts the prescribed dofs on `target`;
/// `predictor`: `δu` is the contact predictor's step.
#[derive(Clone, Copy)]
struct NewtonStep<'a> {
    u: &'a [f64],
    du: &'a [f64],
    target: &'a [f64],
    predictor: bool,
}

/// What decides whether an increment ends at an iterate: its index, the
/// prescribed values reached, the status switches, the relative residual
/// (and whether the residual is exactly zero), and the last correction.
struct Verdict {
    iteration: usize,
    at_target: bool,
    switched: usize,
    relative: f64,
    balanced: bool,
    last_correction: f64,
}

impl Verdict {
    /// `Some(Ok(()))`: converged (prescribed values reached, no switch, a
    /// small residual and a small last correction; or a residual so far
    /// below its tolerance that the next correction would be negligible: a
    /// linear problem converges in one solve). `Some(Err(_))`: a residual
    /// not finite, the iteration limit, chattering, or divergence (far
    /// above the residual after the predictor; the first residual may be
    /// ~0 when only prescribed displacements change). `None`: go on.
    fn ends(
        &self,
        settings: &SolverSettings,
        records: &[IterationRecord],
        chattering: Option<Chatter>,
    ) -> Option<Result<(), IncrementFailure>> {
        let Verdict {
            iteration,
            relative,
            ..
        } = *self;
        if !relative.is_finite() {
            return Some(Err(IncrementFailure::NotFinite));
        }
        let small_residual = relative <= settings.residual_tolerance || self.balanced;
        let negligible = relative <= 1e-3 * settings.residual_tolerance;
        if self.at_target
            && self.switched == 0
            && small_residual
            && (iteration == 0
                || negligible
                || self.last_correction <= settings.displacement_tolerance)
        {
            return Some(Ok(()));
        }
        if iteration == settings.max_iterations {
            let iterations = settings.max_iterations;
            return Some(Err(IncrementFailure::MaxIterations {
                iterations,
                relative,
            }));
        }
        if let Some(c) = chattering {
            return Some(Err(IncrementFailure::Chattering(c)));
        }
        let reference = records[0].residual.max(records[1.min(iteration)].residual);
        if iteration >= 3 && relative > 1e3 * reference.max(settings.residual_tolerance) {
            return Some(Err(IncrementFailure::Diverging { relative }));
        }
        None
    }
}

/// What a tangent solve of [`Newton::tangent_correction`] reads besides
/// the tangent: the prescribed values still to be reached (`jump`), the
/// out-of-balance force, the saddle system's pivot signs, and whether the
/// tangent was evaluated at this iterate.
#[derive(Clone, Copy)]
struct TangentSolve<'a> {
    jump: &'a [f64],
    out_of_balance: &'a [f64],
    signs: Option<&'a [i8]>,
    have_tangent: bool,
}

/// A correction `du` far larger than the body (`10 ×` its size): a
/// rigid-body mode that the saddle system's regularisation let through
/// (the body lost contact, slides as a whole, or supports are missing),
/// or without contact a near-singular tangent (an element near
/// inversion, a huge load); `None` otherwise.
fn rigid_body_mode<P: NonlinearProblem>(
    problem: &P,
    du: &[f64],
    constrained: &[bool],
    open: bool,
    closed: ClosedContact,
) -> Option<IncrementFailure> {
    let dofs = problem.num_dofs();
    let (largest, prescribed) =
        du[..dofs]
            .iter()
            .zip(constrained)
            .fold((0.0f64, false), |m, (d, &c)| {
                if d.abs() > m.0 {
                    (d.abs(), c)
                } else {
                    m
                }
            });
    (largest > 10.0 * problem.size()).then(|| IncrementFailure::RigidBodyMode {
        largest,
        size: problem.size(),
        contact: problem.has_contact(),
        prescribed,
        open,
        direction: largest_motion(&du[..dofs]),
        closed,
    })
}

/// The prescribed values still to be reached from `u` (all of the jump
/// at first): `target − u` on the prescribed dofs, zero elsewhere.
fn remaining_jump(target: &[f64], u: &[f64], constrained: &[bool]) -> Vec<f64> {
    (target.iter().zip(u).zip(constrained))
        .map(|((&t, &x), &c)| if c { t - x } else { 0.0 })
        .collect()
}

fn zero_constrained(v: &mut [f64], constrained: &[bool]) {
    for (x, &c) in v.iter_mut().zip(constrained) {
        if c {
            *x = 0.0;
        }
    }
}
