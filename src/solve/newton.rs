//! Newton–Raphson for one load increment, with the consistent tangent and a
//! backtracking line search.
//!
//! Prescribed displacements are imposed exactly on the iterate; their rows
//! and columns of `K` are replaced by a scaled identity, so the sparsity
//! pattern (and its symbolic factorisation) never changes.

use super::linear::SparseLdlt;
use crate::problem::{norm, ContactState, NonsymmetricSolver, Problem};
use crate::Result;

/// One Newton iteration as reported to the user.
#[derive(Clone, Debug, serde::Serialize)]
pub struct IterationRecord {
    /// `‖r_free‖ / max(‖f_ext‖, ‖f_int‖)` at the start of the iteration.
    pub residual: f64,
    /// `‖α δu‖ / ‖Δu‖` of the correction taken in this iteration (0 on the
    /// last, converged, evaluation).
    pub correction: f64,
    /// Line-search step length taken.
    pub step_length: f64,
    /// Contact nodes whose status (open/stick/slip) changed since the
    /// previous iteration.
    pub switched: usize,
}

/// How an increment ended.
#[derive(Clone, Debug)]
pub enum NewtonOutcome {
    /// Converged; `residual` is `r = f_int − f_ext` at the solution, over
    /// all dofs (its prescribed entries are the reactions), and
    /// `force_scale` the `max(‖f_int‖, ‖f_ext‖)` there.
    Converged {
        residual: Vec<f64>,
        force_scale: f64,
    },
    /// Not converged; the reason is for the log and the final error.
    Failed(String),
}

/// Relative tolerance of the Krylov solve of a nonsymmetric tangent.
const KRYLOV_TOLERANCE: f64 = 1e-12;

/// Solve the increment ending at time `t`, starting from the converged
/// state `u_start`. On return `u` holds the last iterate. The displacement
/// criterion compares each correction with the change since
/// `increment_start`, the state converged at the start of the increment
/// (`u_start` itself, except for the Uzawa re-solves of one increment,
/// whose own changes become tiny as the multipliers settle).
///
/// The prescribed displacements are not jumped to their new values before
/// the first iteration (that would distort the elements along the boundary
/// and start Newton far from the solution); the jump `d = ū(t) − u` on the
/// prescribed dofs is part of the first Newton correction instead:
/// `K_ff δu_f = −r_f − K_fc d`, `δu_c = d`, which is the linearisation
/// about the converged state (a consistent predictor).
///
/// `force_scale` is the largest `max(‖f_int‖, ‖f_ext‖)` of the converged
/// increments so far: residuals are measured relative to it too, so that a
/// state of vanishing load (unloading to zero) can converge.
///
/// A failure of the linear solve (a singular tangent at a limit point, a
/// Krylov solve that does not converge) is reported as a failed increment,
/// which the stepper cuts; only errors that no cut can mend are `Err`.
#[allow(clippy::too_many_arguments)]
pub fn solve_increment(
    problem: &Problem,
    solver: &mut SparseLdlt,
    constrained: &[bool],
    u_start: &[f64],
    increment_start: &[f64],
    t: f64,
    force_scale: f64,
    contact: &mut ContactState,
    u: &mut Vec<f64>,
) -> Result<(NewtonOutcome, Vec<IterationRecord>)> {
    let settings = &problem.settings;
    let pattern = problem.model.pattern.symbolic();
    u.clear();
    u.extend_from_slice(u_start);
    let mut target = u_start.to_vec();
    problem.apply_prescribed(t, &mut target);
    let mut records: Vec<IterationRecord> = Vec::new();
    let mut k_values = vec![0.0; problem.model.pattern.nnz()];
    let mut kd = vec![0.0; u.len()];
    let mut last_correction = f64::INFINITY;
    let nonsymmetric = problem.has_nonsymmetric_tangent();
    let signs = problem
        .has_multipliers()
        .then(|| problem.model.pattern.pivot_signs());
    let mut chatter = super::chattering::ChatterDetector::default();
    let failed = |reason: String, records: Vec<IterationRecord>| {
        Ok((NewtonOutcome::Failed(reason), records))
    };
    for iteration in 0..=settings.max_iterations {
        // the prescribed values still to be reached (all of the jump at first)
        let jump: Vec<f64> = (0..u.len())
            .map(|i| {
                if constrained[i] {
                    target[i] - u[i]
                } else {
                    0.0
                }
            })
            .collect();
        let at_target = jump.iter().all(|&d| d == 0.0);
        // the force alone first where it may show convergence (the first
        // evaluation, or after a residual already near the tolerance): the
        // tangent costs far more and is not needed then; otherwise both at once
        let may_converge = records
            .last()
            .is_none_or(|r| r.residual < 1e3 * settings.residual_tolerance);
        let mut have_tangent = !(at_target && may_converge);
        let evaluate =
            |u: &[f64], k: Option<&mut [f64]>, c: &ContactState| problem.residual_in(t, u, c, k);
        let (mut residual, reports) =
            match evaluate(u, have_tangent.then_some(&mut k_values[..]), contact) {
                Ok(r) => r,
                Err(f) => return failed(problem.describe_failure(&f), records),
            };
        let statuses = reports
            .iter()
            .flatten()
            .map(|n| n.status.code() as u64 + 4 * n.facet.map_or(0, |f| f as u64 + 1))
            .collect();
        let (switched, chattering) = chatter.observe(statuses);
        let mut r = residual.r.clone();
        zero_constrained(&mut r, constrained);
        // the out-of-balance force, with the linearised effect of the
        // prescribed values still to be reached: r_f + K_fc d
        if have_tangent {
            super::linear::multiply(pattern, &k_values, &jump, &mut kd);
        } else {
            kd.iter_mut().for_each(|x| *x = 0.0);
        }
        let out_of_balance: Vec<f64> = (0..u.len())
            .map(|i| if constrained[i] { 0.0 } else { r[i] + kd[i] })
            .collect();
        // the force scale: internal and external forces, those of earlier
        // increments, and the forces the prescribed jump sets up (all there
        // is at the first iteration of a displacement-driven run)
        let scale = residual
            .internal_norm
            .max(residual.external_norm)
            .max(force_scale)
            .max(norm(&kd))
            .max(f64::MIN_POSITIVE);
        let relative = norm(&out_of_balance) / scale;
        records.push(IterationRecord {
            residual: relative,
            correction: 0.0,
            step_length: 0.0,
            switched,
        });
        if !relative.is_finite() {
            return failed("the residual is not finite".into(), records);
        }
        // converged: prescribed values reached, a small residual, and a small
        // last correction; or a residual so far below its tolerance that the
        // next correction would be negligible (a linear problem converges in
        // one solve)
        let small_residual = relative <= settings.residual_tolerance || norm(&r) == 0.0;
        let negligible = relative <= 1e-3 * settings.residual_tolerance;
        if at_target
            && switched == 0
            && small_residual
            && (iteration == 0 || negligible || last_correction <= settings.displacement_tolerance)
        {
            let force_scale = residual.internal_norm.max(residual.external_norm);
            return Ok((
                NewtonOutcome::Converged {
                    residual: residual.r,
                    force_scale,
                },
                records,
            ));
        }
        if iteration == settings.max_iterations {
            break;
        }
        if let Some(c) = chattering {
            return failed(c.to_string(), records);
        }
        // diverging: far above the residual after the predictor (the first
        // residual may be ~0 when only prescribed displacements change)
        let reference = records[0].residual.max(records[1.min(iteration)].residual);
        if iteration >= 3 && relative > 1e3 * reference.max(settings.residual_tolerance) {
            return failed(
                format!("diverging (relative residual {relative:.3e})"),
                records,
            );
        }
        if !have_tangent {
            residual = match evaluate(u, Some(&mut k_values[..]), contact) {
                Ok((r, _)) => r,
                Err(f) => return failed(problem.describe_failure(&f), records),
            };
            have_tangent = true;
        }
        debug_assert!(have_tangent && residual.r.len() == u.len());
        // the preconditioner of a nonsymmetric solve: the symmetric part,
        // with friction's slip blocks replaced by stick blocks
        let preconditioner = nonsymmetric.then(|| {
            let mut p = problem.model.pattern.symmetric_part(&k_values);
            problem.stick_preconditioner(t, u, contact, constrained, &mut p);
            apply_identity_rows(problem, constrained, &mut p);
            p
        });
        // rhs: −(r_f + K_fc d) on the free dofs, (diagonal scale) · d on the prescribed ones
        let diagonal = apply_identity_rows(problem, constrained, &mut k_values);
        let rhs: Vec<f64> = (0..u.len())
            .map(|i| {
                if constrained[i] {
                    diagonal * jump[i]
                } else {
                    -out_of_balance[i]
                }
            })
            .collect();
        let mut du = rhs.clone();
        if let Err(reason) = solve_linear(
            solver,
            &problem.model.pattern,
            &k_values,
            preconditioner.as_deref(),
            settings.nonsymmetric,
            &rhs,
            signs.as_deref(),
            &mut du,
        ) {
            return failed(reason, records);
        }
        for (i, d) in du.iter_mut().enumerate() {
            if constrained[i] {
                *d = jump[i];
            }
        }
        // a correction far larger than the body: a rigid-body mode that the
        // saddle system's regularisation let through (the body lost contact,
        // slides as a whole, or supports are missing)
        let largest = du[..problem.model.num_dofs()]
            .iter()
            .fold(0.0f64, |m, d| m.max(d.abs()));
        if largest > 10.0 * problem.model.size() {
            return failed(
                format!(
                    "a correction of {largest:.3e} against a body of size {:.3e}: a rigid-body mode \
                     (the body lost contact, every contact node slips so that friction cannot hold a load \
                     beyond its capacity, or a support is missing)",
                    problem.model.size()
                ),
                records,
            );
        }
        let step_length = line_search(
            problem,
            constrained,
            t,
            u,
            &du,
            &out_of_balance,
            relative,
            contact,
        );
        let scaled: Vec<f64> = du.iter().map(|d| step_length * d).collect();
        problem.advance_contact_states(t, u, &scaled, contact);
        for (ui, di) in u.iter_mut().zip(&scaled) {
            *ui += di;
        }
        if step_length == 1.0 {
            // land exactly on the prescribed values
            for i in 0..u.len() {
                if constrained[i] {
                    u[i] = target[i];
                }
            }
        }
        let total: Vec<f64> = u.iter().zip(increment_start).map(|(a, b)| a - b).collect();
        last_correction = step_length * norm(&du) / norm(&total).max(f64::MIN_POSITIVE);
        let rec = records.last_mut().expect("pushed above");
        rec.correction = last_correction;
        rec.step_length = step_length;
    }
    let last = records.last().map(|r| r.residual).unwrap_or(f64::NAN);
    failed(
        format!(
            "no convergence in {} iterations (relative residual {last:.3e})",
            settings.max_iterations
        ),
        records,
    )
}

/// Solve `K δu = rhs` (`du` holds `rhs` on entry). A symmetric tangent is
/// factorised and solved directly (with iterative refinement). A
/// nonsymmetric one (follower loads, friction) is solved by GMRES
/// preconditioned with the LDLᵀ of `preconditioner`, a symmetric matrix
/// that differs from `K` only on the loaded facets and the contact nodes,
/// so a few Krylov iterations suffice; the sparse LU solves the tangent
/// when the LDLᵀ of the preconditioner breaks down or GMRES does not
/// converge. Returns the reason on failure (singular tangent).
#[allow(clippy::too_many_arguments)]
fn solve_linear(
    solver: &mut SparseLdlt,
    blocks: &crate::assembly::pattern::SparsityPattern,
    k_values: &[f64],
    preconditioner: Option<&[f64]>,
    method: NonsymmetricSolver,
    rhs: &[f64],
    signs: Option<&[i8]>,
    du: &mut [f64],
) -> std::result::Result<(), String> {
    let pattern = blocks.symbolic();
    let lu = |solver: &mut SparseLdlt, du: &mut [f64]| {
        du.copy_from_slice(rhs);
        solver.timings.lu_solves += 1;
        solver
            .lu
            .solve(pattern, k_values, du)
            .map_err(|e| e.to_string())
    };
    let Some(k_sym) = preconditioner else {
        let direct = solver
            .factorize(pattern, k_values, signs)
            .and_then(|()| solver.solve_refined(pattern, k_values, du, 3))
            .and_then(|relative| {
                // digits lost beyond what refinement recovers
                (relative <= 1e-8).then_some(()).ok_or_else(|| {
                    crate::Error::LinearSolver(format!(
                        "the LDLᵀ solve left a relative residual of {relative:.1e}"
                    ))
                })
            });
        if let Err(e) = direct {
            // an indefinite tangent that the LDLᵀ without pivoting cannot
            // factorise (the curvature term `f ∇²g` of deformable contact
            // after a large first step, examples/two-spheres): the sparse
            // LU with partial pivoting solves it, or tells it is singular
            return lu(solver, du).map_err(|lu_error| format!("{e}; then {lu_error}"));
        }
        return Ok(());
    };
    if method == NonsymmetricSolver::Lu {
        return lu(solver, du);
    }
    if let Err(e) = solver.factorize(pattern, k_sym, signs) {
        // the LDLᵀ without pivoting of the symmetric saddle-point part can
        // break down (a wrong-sign pivot, regularised, then growth to a
        // non-finite one) where the tangent is regular: the sparse LU with
        // partial pivoting solves it, as for a symmetric tangent above
        // (examples/ironing, rockafellar p = k = 10, tangential penalty
        // 1000: 156 cuts in 643 increments without it, 4 in 109 with it)
        return lu(solver, du).map_err(|lu_error| format!("{e}; then {lu_error}"));
    }
    du.iter_mut().for_each(|x| *x = 0.0);
    let report = match super::gmres::gmres(
        |v, y| super::linear::multiply(pattern, k_values, v, y),
        |z| solver.solve_in_place(z),
        rhs,
        du,
        KRYLOV_TOLERANCE,
        50,
        200,
    ) {
        Ok(report) => report,
        // the preconditioner's solve overflowed: solve directly
        Err(e) => return lu(solver, du).map_err(|lu_error| format!("{e}; then {lu_error}")),
    };
    solver.timings.krylov_solves += 1;
    solver.timings.krylov_iterations += report.iterations;
    if !(report.relative_residual <= 1e3 * KRYLOV_TOLERANCE) {
        // the preconditioner is too far from the tangent: solve directly
        return lu(solver, du).map_err(|e| {
            format!(
                "the nonsymmetric linear solve failed (GMRES relative residual {:.1e} after {} iterations; then {e})",
                report.relative_residual, report.iterations
            )
        });
    }
    Ok(())
}

/// Line search along the Newton direction `δu`.
///
/// The slope of the potential along the line, `s(α) = δu · r(u + α δu)`
/// (free dofs), is negative at `α = 0` for a descent direction. The full
/// step is taken if `|s(1)| ≤ ½ |s(0)|` or if the residual norm decreases
/// (Crisfield's test, which accepts steps that raise `‖r‖` but lower the
/// energy, as bending under large rotations needs); otherwise `α` moves to
/// the zero of the secant of `s` (regula falsi, bounded to [0.1α, 0.9α]),
/// or is halved when the trial state inverts an element. Skipped near the
/// tolerance, where the full step keeps the quadratic rate. At most six
/// trials; the one with the smallest `|s|` is taken if none passes.
#[allow(clippy::too_many_arguments)]
fn line_search(
    problem: &Problem,
    constrained: &[bool],
    t: f64,
    u: &[f64],
    du: &[f64],
    r: &[f64],
    relative: f64,
    contact: &ContactState,
) -> f64 {
    if !problem.settings.line_search || relative < 1e3 * problem.settings.residual_tolerance {
        return 1.0;
    }
    let r0 = norm(r);
    // the slope of the potential along the line, over the displacements
    // only: a saddle point is not a minimum in the multipliers
    let dofs = problem.model.num_dofs();
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
        // the local contact unknowns follow the trial step too
        let mut trial_contact = contact.clone();
        problem.advance_contact_states(t, u, &step, &mut trial_contact);
        let Ok((res, _)) = problem.residual_in(t, &trial, &trial_contact, None) else {
            // an inverted element: shorter, and remember it in case all fail
            if best.0 == f64::INFINITY {
                best.1 = 0.5 * alpha;
            }
            alpha *= 0.5;
            continue;
        };
        let mut ra = res.r;
        zero_constrained(&mut ra, constrained);
        let sa = slope(&ra);
        if norm(&ra) < r0 || (s0 < 0.0 && sa.abs() <= 0.5 * s0.abs()) {
            return alpha;
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
    best.1
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

fn zero_constrained(v: &mut [f64], constrained: &[bool]) {
    for (x, &c) in v.iter_mut().zip(constrained) {
        if c {
            *x = 0.0;
        }
    }
}

/// Replace the rows and columns of prescribed dofs by a scaled identity
/// (the scale is the mean absolute diagonal of the free dofs); returns the
/// scale.
pub fn apply_identity_rows(problem: &Problem, constrained: &[bool], k: &mut [f64]) -> f64 {
    let pattern = problem.model.pattern.symbolic();
    let (cp, ri) = (pattern.col_ptr(), pattern.row_idx());
    let (mut sum, mut count) = (0.0, 0usize);
    // the displacement dofs set the scale (multiplier diagonals may be 0)
    for (d, &c) in constrained
        .iter()
        .enumerate()
        .take(problem.model.num_dofs())
    {
        if !c {
            sum += k[problem.model.pattern.diagonal_entry(d)].abs();
            count += 1;
        }
    }
    let scale = if count > 0 && sum > 0.0 {
        sum / count as f64
    } else {
        1.0
    };
    for j in 0..pattern.ncols() {
        for idx in cp[j]..cp[j + 1] {
            let i = ri[idx];
            if constrained[i] || constrained[j] {
                k[idx] = if i == j { scale } else { 0.0 };
            }
        }
    }
    scale
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::assembly::pattern::SparsityPattern;

    /// Solve `K du = rhs` for one node (a dense 3 × 3 block, column-major,
    /// full pattern) with `preconditioner` as [`solve_linear`] does, and
    /// assert `du = expected` (1e-14) reached through one LU solve.
    fn assert_solved_by_the_lu(
        k: &[f64; 9],
        preconditioner: Option<&[f64]>,
        rhs: [f64; 3],
        expected: [f64; 3],
    ) {
        let nodes = [0usize];
        let blocks = SparsityPattern::from_elements(1, std::iter::once(&nodes[..]));
        assert_eq!(blocks.nnz(), 9);
        let mut solver = SparseLdlt::new(super::super::linear::Ordering::Amd, 1);
        let mut du = rhs;
        solve_linear(
            &mut solver,
            &blocks,
            k,
            preconditioner,
            NonsymmetricSolver::Gmres,
            &rhs,
            None,
            &mut du,
        )
        .unwrap();
        for (d, e) in du.iter().zip(expected) {
            assert!((d - e).abs() < 1e-14, "{du:?}");
        }
        assert_eq!(solver.timings.lu_solves, 1);
    }

    /// `[[0, 1, 0], [1, 0, 0], [0, 0, 1]]`: regular, symmetric, but its
    /// first pivot is 0, which the LDLᵀ without pivoting cannot take.
    const ZERO_FIRST_PIVOT: [f64; 9] = [0.0, 1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0];

    /// A nonsymmetric tangent whose symmetric preconditioner the LDLᵀ
    /// without pivoting cannot factorise (zero pivots) is solved by the LU.
    #[test]
    fn a_preconditioner_the_ldlt_cannot_factorise_falls_back_to_the_lu() {
        let nodes = [0usize];
        let blocks = SparsityPattern::from_elements(1, std::iter::once(&nodes[..]));
        let mut solver = SparseLdlt::new(super::super::linear::Ordering::Amd, 1);
        assert!(solver
            .factorize(blocks.symbolic(), &ZERO_FIRST_PIVOT, None)
            .is_err());
        // K du = rhs: du₁ = 1, 2 du₀ = 4, du₂ = 3
        let k = [0.0, 2.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0];
        assert_solved_by_the_lu(
            &k,
            Some(&ZERO_FIRST_PIVOT),
            [1.0, 4.0, 3.0],
            [2.0, 1.0, 3.0],
        );
    }

    /// A symmetric tangent the LDLᵀ without pivoting cannot factorise (an
    /// indefinite one with a zero leading pivot) is solved by the LU.
    #[test]
    fn a_symmetric_tangent_the_ldlt_cannot_factorise_falls_back_to_the_lu() {
        assert_solved_by_the_lu(&ZERO_FIRST_PIVOT, None, [1.0, 4.0, 3.0], [4.0, 1.0, 3.0]);
    }
}
