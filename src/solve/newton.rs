//! Newton–Raphson for one load increment, with the consistent tangent, a
//! line search and its watchdog.
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
use super::watchdog::{self, Checkpoint, Judgement, Watchdog};

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
        let mut watchdog = Watchdog::default();
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
            let judgement = watchdog.judge(norm(&out_of_balance));
            let relax = match judgement {
                Judgement::Search { relax } => relax,
                // the watched steps did not lower ‖r‖: back to where they
                // started (this iterate is left, not judged)
                Judgement::Revert(back) => {
                    // the watched iterates are no part of Newton's path
                    chatter.rewind(back.chatter);
                    let (du, step) = self.step_back(back, u, state, &target, &mut tangent);
                    ahead = step.evaluation;
                    last_correction =
                        self.advance(u, &du, step.length, state, &target, increment_start);
                    if !self.report(&mut records, last_correction, step.length) {
                        return (Err(IncrementFailure::Cancelled), records);
                    }
                    iteration += 1;
                    continue;
                }
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
                relax: relax.then_some(&evaluation.statuses[..]),
            };
            let step = self.line_search(line, &out_of_balance, relative, state, &mut tangent);
            if step.relaxed {
                watchdog.start(Checkpoint {
                    u: u.clone(),
                    state: state.clone(),
                    du: du.clone(),
                    out_of_balance,
                    relative,
                    chatter: chatter.mark(),
                });
            }
            ahead = step.evaluation;
            last_correction = self.advance(u, &du, step.length, state, &target, increment_start);
            if !self.report(&mut records, last_correction, step.length) {
                return (Err(IncrementFailure::Cancelled), records);
            }
            iteration += 1;
        }
    }

    /// Complete this iteration's record with the correction taken and its
    /// step length, and tell `on_iteration`; `false`: the run is cancelled.
    fn report(&mut self, records: &mut [IterationRecord], correction: f64, length: f64) -> bool {
        let Some(rec) = records.last_mut() else {
            return true;
        };
        rec.correction = correction;
        rec.step_length = length;
        self.on_iteration.as_mut().is_none_or(|tell| tell(rec))
    }

    /// Back to the watchdog's checkpoint `back` (`u` and `state` restored)
    /// and the monotone line search along its correction, as it ran before
    /// the relaxed steps: the correction and the step taken.
    fn step_back(
        &self,
        back: Checkpoint<P::State>,
        u: &mut Vec<f64>,
        state: &mut P::State,
        target: &[f64],
        k: &mut TangentStore,
    ) -> (Vec<f64>, LineStep<P::Report>) {
        let Checkpoint {
            u: start,
            state: start_state,
            du,
            out_of_balance,
            relative,
            chatter: _,
        } = back;
        *state = start_state;
        let line = NewtonStep {
            u: &start,
            du: &du,
            target,
            predictor: false,
            relax: None,
        };
        let step = self.line_search(line, &out_of_balance, relative, state, k);
        *u = start;
        (du, step)
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
            problem.symmetric_neighbour(t, u, state, constrained, k.values(), &mut p);
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
        solved?;
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
    /// but lower the energy, as bending under large rotations needs), or
    /// by the watchdog (below). Otherwise, where the slope changed sign
    /// in `(0, 1)`, the search sections that bracket by the Illinois
    /// variant of regula falsi on `s` ([`Bracket`]; Crisfield, *Non-linear
    /// Finite Element Analysis of Solids and Structures*, vol. 1, 1991,
    /// §9.3) until a trial both lowers `‖r‖` and has `|s(α)| ≤ ½ |s(0)|`
    /// (the curvature half of Wolfe's conditions, as Crisfield's slope
    /// tolerance); where it did not change sign, `α` is halved and a trial
    /// that lowers `‖r‖` is kept. A trial that inverts an element counts
    /// as too long. Skipped near the tolerance, where the full step keeps
    /// the quadratic rate. At most six trials; if none passes, the one of
    /// least `|s|` is taken: the search's best approach to the slope's
    /// zero, which is what it sections for.
    ///
    /// Why not the trial of least `‖r‖` below `‖r(0)‖` (session 21's
    /// fallback): where the search failed far from the answer, the steps
    /// crept (`tests/hard_cases.rs`, the ball pressed into the block:
    /// `α = 0.012–0.076` for six iterations at a relative residual of
    /// 2.6–2.7e-2), and the ball's press ran out of cuts at t = 0.999 on
    /// stick/slip chattering. With the least `|s|` it runs to the end
    /// (111 iterations against main's 147; measured, not derived); neither ironing needs
    /// the other fallback (ironing 275 iterations, largest 9, with this
    /// one; ironing-mortar's first slide increment the same 7)
    /// (BENCHMARKS.md, "Session 22").
    ///
    /// Why the slope test inside the bracket: `‖r‖` falling alone accepted
    /// the secant's first zero, far short of the slope's zero where `s` is
    /// only piecewise smooth. On the Puso–Laursen ironing with mortar
    /// (first slide increment) `‖r(α)‖` fell as `1 − α` up to `α ≈ 0.7`
    /// and rose steeply after, so the first secant zero (0.41, then 0.28,
    /// …, 0.10) cut `‖r‖` by only `1 − α` per iteration: 18 iterations,
    /// 7 with the sectioning (BENCHMARKS.md, "Session 20").
    ///
    /// The watchdog ([`super::watchdog`]; Chamberlain, Powell, Lemaréchal
    /// & Pedersen 1982): where `relax` holds the iterate's contact
    /// statuses, the iterate is near the answer (`relative` below
    /// [`watchdog::NEAR`]), the search stalls (its step below
    /// [`watchdog::STALL`]) and the full step switches some of the
    /// statuses (it crosses a kink of the piecewise-smooth residual: a
    /// status, a primary facet), the full step is taken instead
    /// ([`LineStep::relaxed`]) and Newton's loop watches the next
    /// iterates; if none lowers `‖r‖` below the checkpoint's it goes back
    /// and takes the search's step. On node-to-surface ironing a node at
    /// a facet edge held `‖r‖` at 3.5e-5 for 7 iterations of steps of
    /// 0.01 to 0.001: 12–14 iterations in four increments, 8–9 with the
    /// watchdog (BENCHMARKS.md, "Session 21").
    ///
    /// The contact predictor's step (`predictor`: the Josephy–Newton step
    /// at the first correction, the linearised answer for the whole
    /// increment) is taken only where it lowers `‖r‖` (never by the
    /// watchdog): a step that raises the residual and overshoots the
    /// potential's minimum along it (`s(1) > 0 > s(0)`, the material
    /// stiffer than its tangent at the start) goes to the secant zero of
    /// `s` instead of being kept by the `½` rule. On examples/ogden-plate's
    /// first increment (rest to half the load) the full step raised `‖r‖`
    /// by 8 % with `s(1) = −0.33 s(0)`; `α = 0.754` took that increment
    /// from 6 Newton iterations to 5 (BENCHMARKS.md, "Session 10: the
    /// plate's first increment").
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
    ) -> LineStep<P::Report> {
        let NewtonStep {
            du,
            predictor,
            relax,
            ..
        } = line;
        let problem = self.problem;
        let settings = problem.settings();
        if !settings.line_search || relative < 1e3 * settings.residual_tolerance {
            return LineStep::full(None);
        }
        // the watchdog acts near the answer only, never on the predictor's step
        let relax = relax.filter(|_| relative < watchdog::NEAR && !predictor);
        let r0 = norm(r);
        // the slope of the potential along the line, over the displacements
        // only: a saddle point is not a minimum in the multipliers
        let dofs = problem.num_dofs();
        let slope = |r: &[f64]| dot(&du[..dofs], &r[..dofs]);
        let s0 = slope(r);
        let mut alpha = 1.0;
        // the trial of least |s|: the search's best approach to the slope's zero
        let mut best = (f64::INFINITY, 1.0);
        // where the slope changed sign: the secant's sectioning
        let mut bracket: Option<Bracket> = None;
        // the full step, where it switches a status or a facet
        let mut switching = None;
        let mut taken = None;
        for _ in 0..6 {
            let full = alpha == 1.0;
            let with_tangent = full || predictor;
            let tangent = with_tangent.then_some(&mut *k);
            let Ok(evaluation) = self.evaluate_trial(line, alpha, state, tangent) else {
                // an inverted element: shorter, and remember it in case all fail
                if best.0 == f64::INFINITY {
                    best.1 = 0.5 * alpha;
                }
                alpha = bracket.as_mut().map_or(0.5 * alpha, |b| b.inverted(alpha));
                continue;
            };
            let mut ra = evaluation.residual.clone();
            zero_constrained(&mut ra, self.constrained);
            let (ra, sa) = (norm(&ra), slope(&ra));
            let falls = ra < r0;
            let flat = s0 < 0.0 && sa.abs() <= 0.5 * s0.abs();
            let accept = match bracket {
                // inside the bracket: Crisfield's slope test as well
                Some(_) => falls && flat,
                _ => falls || (flat && !predictor),
            };
            if accept {
                taken = Some(LineStep {
                    length: alpha,
                    evaluation: with_tangent.then_some(evaluation),
                    relaxed: false,
                });
                break;
            }
            if full && relax.is_some_and(|before| before != &evaluation.statuses[..]) {
                switching = Some(evaluation);
            }
            if sa.abs() < best.0 {
                best = (sa.abs(), alpha);
            }
            if s0 < 0.0 && sa > 0.0 && bracket.is_none() {
                bracket = Some(Bracket::new(s0));
            }
            alpha = match bracket.as_mut() {
                Some(b) => b.next(alpha, sa),
                None => 0.5 * alpha,
            };
        }
        let step = taken.unwrap_or(LineStep {
            length: best.1,
            evaluation: None,
            relaxed: false,
        });
        match switching {
            // the search stalls at a kink the full step crosses: the watchdog's step
            Some(evaluation) if step.length < watchdog::STALL => LineStep {
                relaxed: true,
                ..LineStep::full(Some(evaluation))
            },
            _ => step,
        }
    }

    /// The evaluation at the line search's trial `u + α δu`, with the
    /// tangent into `k` where given: the local contact unknowns follow the
    /// step too, and the full step puts the prescribed dofs on their
    /// `target`, where Newton lands.
    fn evaluate_trial(
        &self,
        line: NewtonStep<'_>,
        alpha: f64,
        state: &P::State,
        k: Option<&mut TangentStore>,
    ) -> Result<Evaluation<P::Report>, IncrementFailure> {
        let NewtonStep { u, du, target, .. } = line;
        let step: Vec<f64> = du.iter().map(|d| alpha * d).collect();
        let mut trial: Vec<f64> = u.iter().zip(&step).map(|(u0, d)| u0 + d).collect();
        if alpha == 1.0 {
            for ((x, &c), v) in trial.iter_mut().zip(self.constrained).zip(target) {
                if c {
                    *x = *v;
                }
            }
        }
        let mut trial_state = state.clone();
        self.problem
            .advance_state(self.t, u, &step, &mut trial_state);
        match k {
            Some(k) => k.evaluate(self.problem, self.t, &trial, &trial_state),
            None => self.problem.evaluate(self.t, &trial, &trial_state, None),
        }
    }
}

/// The sectioning of a line search once the slope `s(α)` has changed
/// sign: the Illinois variant of regula falsi on `s` (Dahlquist & Björck,
/// *Numerical Methods*, 1974, §6.2.3; Crisfield, *Non-linear Finite
/// Element Analysis of Solids and Structures*, vol. 1, 1991, §9.3),
/// between the last trial short of the zero (`s < 0`, from `α = 0`) and
/// the last past it (`s > 0`).
struct Bracket {
    short: (f64, f64),
    past: (f64, f64),
    /// Which end the last trial replaced (`true`: `past`).
    replaced_past: Option<bool>,
}

impl Bracket {
    fn new(s0: f64) -> Self {
        Bracket {
            short: (0.0, s0),
            past: (f64::NAN, 0.0),
            replaced_past: None,
        }
    }

    /// The next trial after `α` of slope `s`: the secant zero of `s`
    /// between the two ends, kept off them by a tenth of the bracket
    /// (where one end stays twice, its slope is halved: Illinois).
    fn next(&mut self, alpha: f64, s: f64) -> f64 {
        let past = s > 0.0;
        if self.replaced_past == Some(past) {
            let kept = if past {
                &mut self.short
            } else {
                &mut self.past
            };
            kept.1 *= 0.5;
        }
        if past {
            self.past = (alpha, s);
        } else {
            self.short = (alpha, s);
        }
        self.replaced_past = Some(past);
        let ((a, sa), (b, sb)) = (self.short, self.past);
        let width = b - a;
        (a + width * sa / (sa - sb)).clamp(a + 0.1 * width, b - 0.1 * width)
    }

    /// After a trial at `α` that inverted an element: halfway back to the
    /// short end, and `α` the new far end (its slope unknown: the secant
    /// then halves).
    fn inverted(&mut self, alpha: f64) -> f64 {
        let a = self.short.0;
        self.past = (alpha, f64::INFINITY);
        a + 0.5 * (alpha - a)
    }
}

/// The step a line search took: its length `α`, the evaluation at the
/// trial taken where it was evaluated with its tangent, and whether it is
/// a full step kept by the watchdog though it failed the monotone test.
struct LineStep<R> {
    length: f64,
    evaluation: Option<Evaluation<R>>,
    relaxed: bool,
}

impl<R> LineStep<R> {
    /// The full step, with its evaluation where there is one.
    fn full(evaluation: Option<Evaluation<R>>) -> Self {
        LineStep {
            length: 1.0,
            evaluation,
            relaxed: false,
        }
    }
}

/// The line a line search walks: from the iterate `u` along Newton's
/// correction `δu`; a full step puts the prescribed dofs on `target`;
/// `predictor`: `δu` is the contact predictor's step; `relax`: the
/// contact statuses at `u` where the watchdog allows a full step that
/// fails the monotone test but switches some of them.
#[derive(Clone, Copy)]
struct NewtonStep<'a> {
    u: &'a [f64],
    du: &'a [f64],
    target: &'a [f64],
    predictor: bool,
    relax: Option<&'a [u64]>,
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
        if iteration >= settings.max_iterations {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solve::backend::linear_solver;
    use crate::solve::linear::Ordering;
    use crate::solve::springs::{Spring, Springs};

    /// One spring that stiffens tenfold past `x = ½`: `r(x) = f(x) − 1`,
    /// `f = x` below and `½ + 10 (x − ½)` above, so that the root is
    /// `x = 0.55` while Newton's step from the soft side aims at `x = 1`,
    /// where `r = 4.5`. With `statuses`, the side is the spring's contact
    /// status (1 soft, 2 stiff), as a contact node's stick or slip. (The
    /// other two dofs of its node are unit springs at rest.)
    fn kinked(statuses: bool) -> Springs {
        let settings = SolverSettings {
            residual_tolerance: 1e-12,
            ..SolverSettings::default()
        };
        let law = move |_t: f64, i: usize, x: f64| {
            let stiff = i == 0 && x > 0.5;
            let (internal, stiffness) = if stiff {
                (0.5 + 10.0 * (x - 0.5), 10.0)
            } else {
                (x, 1.0)
            };
            Spring {
                internal,
                external: if i == 0 { 1.0 } else { 0.0 },
                stiffness,
                status: (i == 0 && statuses).then_some(1 + u64::from(stiff)),
            }
        };
        Springs::new(settings, Vec::new(), Box::new(law))
    }

    /// Newton on [`kinked`] from `x = 0`: the root found and the records.
    fn solve_kinked(statuses: bool) -> (f64, Vec<IterationRecord>) {
        let problem = kinked(statuses);
        let mut solver = linear_solver(&problem.settings, Ordering::Amd, 1);
        let mut josephy = Josephy::default();
        let mut newton = Newton {
            problem: &problem,
            solver: &mut *solver,
            constrained: &[false; 3],
            t: 1.0,
            force_scale: 0.0,
            on_iteration: None,
            josephy: &mut josephy,
            predictor: Predictor::None,
        };
        let mut u = Vec::new();
        let (outcome, records) = newton.solve(&[0.0; 3], &[0.0; 3], &mut (), &mut u);
        assert!(outcome.is_ok(), "{:?}", outcome.err());
        (u[0], records)
    }

    /// Past a kink the full step raises `‖r‖` from 1 to 4.5. Sectioning
    /// the slope's sign change (Illinois) takes a step that halves `‖r‖`
    /// and lands past the kink: two iterations. The secant's first zero
    /// alone, kept because `‖r‖` fell, crept towards the kink (α = 0.18,
    /// 0.15, 0.13, 0.12, 0.10: six iterations, the rule before session 20).
    #[test]
    fn sectioning_crosses_a_kink_the_secant_creeps_to() {
        let (x, records) = solve_kinked(false);
        assert!((x - 0.55).abs() < 1e-12, "{x}");
        assert_eq!(records.len() - 1, 2, "{records:#?}");
        assert!(records[0].step_length < 1.0 && records[1].residual <= 0.5);
    }

    /// Far from the answer (the first iterate's relative residual is 1,
    /// above [`watchdog::NEAR`]) the watchdog leaves the search alone
    /// though the full step switches the spring's status: the same steps
    /// as without statuses (session 20's rule took the full step there).
    #[test]
    fn the_watchdog_leaves_the_first_iterates_to_the_search() {
        let (x, records) = solve_kinked(true);
        let (_, plain) = solve_kinked(false);
        assert!((x - 0.55).abs() < 1e-12, "{x}");
        let lengths = |r: &[IterationRecord]| r.iter().map(|r| r.step_length).collect::<Vec<_>>();
        assert_eq!(lengths(&records), lengths(&plain), "{records:#?}");
        assert!(records[0].step_length < 1.0);
    }
}
