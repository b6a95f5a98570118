//! The Josephy–Newton step: a Newton correction that solves the contact
//! constraints linearised at the iterate *exactly* (their complementarity
//! problem, not one active-set guess), so that the step lands on the
//! active set of the linearised problem (Josephy, *Newton's method for
//! generalized equations*, 1979; Facchinei & Pang, *Finite-Dimensional
//! Variational Inequalities and Complementarity Problems*, 2003, §7.3).
//! Newton's plain step on the monolithic system takes the active set of
//! the current iterate and corrects it one iteration at a time (a
//! primal–dual active-set step per iteration: on examples/hertz 160, 32,
//! 20, 14, 4, 2 nodes switched in its first increment).
//!
//! ## The linearised problem
//! With `K` the tangent without the constraints (prescribed rows and the
//! multipliers a scaled identity `s`), `b` Newton's right-hand side
//! (`−(r_f + K_fc d)` free, `s d` prescribed), `E` the matrix whose column
//! `a` is `sign_a e_{dof_a}` and `g⁰` the gaps at the iterate:
//!
//! ```text
//! K δ = b + E f,   g = g⁰ + Eᵀ δ ≥ 0,   f ≥ 0,   f_a g_a = 0.
//! ```
//!
//! `K` may be singular where only the contact holds a body (the Ogden
//! plate floats on its foundation), so it is shifted on the constrained
//! unknowns, `K̂ = K + ρ E Eᵀ` (`ρ = s`), which is regular, and the shift is
//! moved to the right: `K̂ δ = b − ρ E g⁰ + E (f + ρ g)`. With
//! `δ⁰ = K̂⁻¹ (b − ρ E g⁰)`, `q = g⁰ + Eᵀ δ⁰` and `Ŝ = (Eᵀ K̂⁻¹ E)⁻¹`, the
//! Schur complement of `K̂` on `T = {dof_a}` up to the signs (read off the
//! factor whose ordering puts `T` last, [`super::condensed::schur::trailing_schur`]),
//!
//! ```text
//! f = M g + c ≥ 0,   g ≥ 0,   f_a g_a = 0,   M = Ŝ − ρ I,   c = −Ŝ q,
//! ```
//!
//! an LCP in the gaps with `M` the stiffness of `K` condensed onto `T`
//! (positive semidefinite; singular along a floating body's rigid mode,
//! which no proper subset of open nodes contains), solved by block
//! principal pivoting ([`super::condensed::complementarity::solve_lcp`], with the
//! roles of its `λ` and `g` swapped). Then `δ = δ⁰ + K̂⁻¹ E (f + ρ g)` and
//! each multiplier takes the node's force, `λ_a = f_a / (A_a k)`. One
//! factorisation of `K̂` and two solves, as much as a plain step, plus the
//! dense `c³/3` of `Ŝ`.
//!
//! ## Its own factor, whatever the run's linear solver
//! The step factorises `K̂` with faer's sparse LDLᵀ ([`SparseLdlt`]) also
//! when the run's linear solver is PETSc (`linear = "petsc"`, serial: a
//! distributed run takes no contact predictor) or `linear = "lu"`.
//! It needs `Ŝ`, read off the trailing block of a factor whose ordering
//! puts `T` last, which a [`super::linear_solver::LinearSolver`] (solves
//! only) does not give; `K̂` is not Newton's tangent (the multipliers'
//! rows a scaled identity, shifted on `T`), so no factor of the run's solver could be reused for
//! it either, faer's own included. Taking `Ŝ` from PETSc would need MUMPS'
//! Schur complement (`MatFactorSetSchurIS`), a second Schur path beside
//! [`trailing_schur`] for one backend. So a serial run on PETSc takes the
//! predictor's step in faer, its PETSc options not applying to it, and
//! Newton's steps after it in PETSc; the answer is Newton's, to its
//! tolerances (`tests/petsc.rs`, the Hertz-like contact: MUMPS with the
//! contact predictor against faer's condensed path, to 1e-8).

use super::condensed::complementarity::solve_lcp;
use super::condensed::schur::{trailing_ordering, trailing_schur};
use super::linear::SparseLdlt;
use super::linear_solver::{LinearFigures, SolverStatistics};
use super::nonlinear::NormalConstraint;
use crate::assembly::pattern::SparsityPattern;
use nalgebra::DMatrix;

/// At most this many constraints in the condensed problem (a dense
/// `c × c` block): the nearest ones by their gap; the others stay as they
/// are for Newton's next steps.
const MAX_CONSTRAINTS: usize = 4000;

/// From this many unknowns the factorisation of `K̂` runs on the run's
/// threads, below on one (as the condensed path's,
/// `crate::problem::condensed`).
const PARALLEL_UNKNOWNS: usize = 50_000;

/// What a Josephy–Newton step found.
#[derive(Clone, Debug)]
pub struct JosephyStep {
    /// The correction of every unknown (the multipliers to the new forces).
    pub correction: Vec<f64>,
    /// Constraints closed (`g = 0`) by the step, and those it solved for.
    pub closed: usize,
    pub solved: usize,
    /// Active-set steps of the complementarity solve.
    pub active_set_iterations: usize,
    /// The factorisation's and the solves' seconds.
    pub figures: LinearFigures,
}

/// The tangent `K` without the constraints (`values` on `pattern`), whose
/// rows and columns of the `held` unknowns (the prescribed ones and every
/// multiplier) are a scaled identity `scale`; `single`: factorise `K̂` in
/// f32 and refine its solves against the f64 `K̂` (half the factor's
/// memory and time, as the linear solver's mixed precision; the Schur
/// complement then carries f32's error, which Newton's next correction
/// removes).
#[derive(Clone, Copy)]
pub struct HeldTangent<'a> {
    pub pattern: &'a SparsityPattern,
    pub values: &'a [f64],
    pub scale: f64,
    pub held: &'a [bool],
    pub single: bool,
}

/// Refinement steps of a solve with `K̂`'s factor: f64, f32.
const REFINEMENTS: [usize; 2] = [3, 10];

/// The factorisations of the Josephy–Newton steps of a run: the factor of
/// `K̂` with the constrained unknowns last, its ordering and symbolic
/// analysis kept while the pattern and those unknowns stay the same.
#[derive(Default)]
pub struct Josephy {
    ldlt: Option<SparseLdlt>,
    /// The pattern's id and the trailing unknowns the ordering was made for.
    ordered_for: Option<(u64, Vec<usize>)>,
    /// The statistics of factors replaced by a new ordering.
    earlier: SolverStatistics,
}

impl Josephy {
    /// Counts and times of every factorisation and solve so far.
    pub fn statistics(&self) -> SolverStatistics {
        self.earlier
            + self
                .ldlt
                .as_ref()
                .map(SolverStatistics::of_ldlt)
                .unwrap_or_default()
    }

    /// The Josephy–Newton correction from `x` (see the module's doc) with
    /// the tangent `k`, `rhs` Newton's right-hand side. An error (a singular
    /// `K̂`, a complementarity problem without a solution) leaves the plain
    /// step to the caller.
    pub fn step(
        &mut self,
        k: HeldTangent,
        rhs: &[f64],
        x: &[f64],
        constraints: &[NormalConstraint],
    ) -> crate::Result<JosephyStep> {
        let HeldTangent {
            pattern,
            values: tangent,
            scale,
            held,
            single,
        } = k;
        let failed = |why: &str| crate::Error::LinearSolver(format!("Josephy–Newton step: {why}"));
        let n = pattern.dimension();
        // the constraints on free unknowns, nearest first, one per unknown
        let mut chosen: Vec<&NormalConstraint> =
            constraints.iter().filter(|c| !held[c.dof]).collect();
        chosen.sort_by(|a, b| a.gap.total_cmp(&b.gap));
        chosen.truncate(MAX_CONSTRAINTS);
        let mut marked = vec![false; n];
        for c in &chosen {
            if std::mem::replace(&mut marked[c.dof], true) {
                return Err(failed("two constraints on one unknown"));
            }
        }
        if chosen.is_empty() {
            return Err(failed("no constraint on a free unknown"));
        }
        let rho = scale;
        let mut shifted = tangent.to_vec();
        for c in &chosen {
            shifted[pattern.diagonal_entry(c.dof)] += rho;
        }
        let before = self.statistics();
        let ldlt = self.factor(pattern, &marked, &chosen)?;
        if single {
            ldlt.factorize_single(pattern.symbolic(), &shifted, None)?;
        } else {
            ldlt.factorize(pattern.symbolic(), &shifted, None)?;
        }
        let refinements = REFINEMENTS[usize::from(single)];
        let dofs: Vec<usize> = chosen.iter().map(|c| c.dof).collect();
        let schur = trailing_schur(ldlt, &dofs)?;
        let m = chosen.len();
        // δ⁰ = K̂⁻¹ (b − ρ E g⁰), q = g⁰ + Eᵀ δ⁰
        let mut delta = rhs.to_vec();
        for c in &chosen {
            delta[c.dof] -= rho * c.sign * c.gap;
        }
        ldlt.solve_refined(pattern.symbolic(), &shifted, &mut delta, refinements)?;
        let q: Vec<f64> = chosen
            .iter()
            .map(|c| c.gap + c.sign * delta[c.dof])
            .collect();
        // Ŝ in the constraints' signs, M = Ŝ − ρ I, c = −Ŝ q
        let s_hat = |a: usize, b: usize| chosen[a].sign * chosen[b].sign * schur[(a, b)];
        let stiffness = DMatrix::from_fn(m, m, |a, b| {
            let mean = 0.5 * (s_hat(a, b) + s_hat(b, a));
            if a == b {
                mean - rho
            } else {
                mean
            }
        });
        let constant: Vec<f64> = (0..m)
            .map(|a| -(0..m).map(|b| s_hat(a, b) * q[b]).sum::<f64>())
            .collect();
        let largest = |v: &[f64]| v.iter().fold(0.0f64, |l, x| l.max(x.abs()));
        let (force_tolerance, gap_tolerance) = (
            1e-12 * largest(&constant).max(f64::MIN_POSITIVE),
            1e-12 * largest(&q).max(f64::MIN_POSITIVE),
        );
        // the LCP in the gaps: its "active" unknowns are the open nodes; the
        // guess: open where the iterate is (a positive gap, no force)
        let open: Vec<bool> = chosen
            .iter()
            .map(|c| c.gap > 0.0 && x[c.multiplier] <= 0.0)
            .collect();
        let solution = solve_lcp(&stiffness, &constant, &open, force_tolerance, gap_tolerance)
            .map_err(|e| failed(&e))?;
        let (gaps, forces) = (&solution.lambda, &solution.gap);
        // δ = δ⁰ + K̂⁻¹ E (f + ρ g)
        let mut rest = vec![0.0; n];
        for (a, c) in chosen.iter().enumerate() {
            rest[c.dof] = c.sign * (forces[a].max(0.0) + rho * gaps[a]);
        }
        ldlt.solve_refined(pattern.symbolic(), &shifted, &mut rest, refinements)?;
        for (d, r) in delta.iter_mut().zip(&rest) {
            *d += r;
        }
        for (a, c) in chosen.iter().enumerate() {
            delta[c.multiplier] = forces[a].max(0.0) / c.force_per_multiplier - x[c.multiplier];
        }
        Ok(JosephyStep {
            correction: delta,
            closed: solution.active.iter().filter(|&&open| !open).count(),
            solved: m,
            active_set_iterations: solution.iterations,
            figures: self.statistics().since(&before),
        })
    }

    /// The solver for the trailing unknowns `marked` (the `chosen`
    /// constraints') on `pattern`: the last one, or a new nested-dissection
    /// ordering with them last.
    fn factor(
        &mut self,
        pattern: &SparsityPattern,
        marked: &[bool],
        chosen: &[&NormalConstraint],
    ) -> crate::Result<&mut SparseLdlt> {
        let mut dofs: Vec<usize> = chosen.iter().map(|c| c.dof).collect();
        dofs.sort_unstable();
        let key = (pattern.id(), dofs);
        if self.ordered_for.as_ref() != Some(&key) || self.ldlt.is_none() {
            let threads = usize::from(pattern.dimension() < PARALLEL_UNKNOWNS);
            let ldlt = SparseLdlt::new(trailing_ordering(pattern, marked, None)?, threads);
            if let Some(old) = self.ldlt.replace(ldlt) {
                self.earlier = self.earlier + SolverStatistics::of_ldlt(&old);
            }
            self.ordered_for = Some(key);
        }
        self.ldlt
            .as_mut()
            .ok_or_else(|| crate::Error::LinearSolver("no Josephy–Newton factor".into()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solve::linear::multiply;

    /// `n` nodes in a row joined by springs of stiffness 1 in every
    /// direction, each with a multiplier; x and y held by springs of 0.1
    /// to the ground, z free: `K` is singular along the rigid z
    /// translation unless `ground > 0` ties node 0 in z too. Returns the
    /// pattern and `K` (multiplier rows a unit identity).
    fn chain(n: usize, ground: f64) -> (SparsityPattern, Vec<f64>) {
        let edges: Vec<[usize; 2]> = (0..n - 1).map(|a| [a, a + 1]).collect();
        let multipliers: Vec<Vec<usize>> = (0..n).map(|a| vec![a]).collect();
        let pattern =
            SparsityPattern::with_multipliers(n, edges.iter().map(|e| &e[..]), &multipliers);
        let mut k = vec![0.0; pattern.nnz()];
        let s = pattern.symbolic();
        let (cp, ri) = (s.col_ptr(), s.row_idx());
        for j in 0..s.ncols() {
            for p in cp[j]..cp[j + 1] {
                let i = ri[p];
                if i >= 3 * n || j >= 3 * n {
                    k[p] = f64::from(u8::from(i == j));
                } else if i % 3 == j % 3 {
                    let (a, b) = (i / 3, j / 3);
                    let neighbours = usize::from(a > 0) + usize::from(a + 1 < n);
                    k[p] = if a == b {
                        neighbours as f64
                            + if i % 3 < 2 { 0.1 } else { 0.0 }
                            + if a == 0 && i % 3 == 2 { ground } else { 0.0 }
                    } else {
                        -1.0
                    };
                }
            }
        }
        (pattern, k)
    }

    /// The Josephy step on a chain pulled down onto a curved floor (node
    /// `a` at gap `g⁰_a = (a − c)²/50 − 0.05`, a downward force on every
    /// node) meets the linearised problem exactly: `K δ = b + E f` to
    /// round-off, `g = g⁰ + δ_z ≥ 0`, `f ≥ 0`, `f g = 0`, the forces
    /// balance the load (`Σ f = −Σ b_z`), the multipliers hold `f / (A k)`;
    /// with `K` singular (the chain floats: only the floor holds it in z)
    /// and regular (node 0 tied to the ground).
    #[test]
    fn the_step_solves_the_linearised_contact_problem() {
        let n = 21;
        for ground in [0.0, 0.5] {
            let (pattern, k) = chain(n, ground);
            let dim = pattern.dimension();
            let mut held = vec![false; dim];
            held[3 * n..].iter_mut().for_each(|h| *h = true);
            let constraints: Vec<NormalConstraint> = (0..n)
                .map(|a| NormalConstraint {
                    dof: 3 * a + 2,
                    sign: 1.0,
                    gap: (a as f64 - 10.0).powi(2) / 50.0 - 0.05,
                    multiplier: 3 * n + a,
                    force_per_multiplier: 2.0,
                })
                .collect();
            let mut rhs = vec![0.0; dim];
            for a in 0..n {
                rhs[3 * a + 2] = -0.01;
                rhs[3 * a] = 0.003 * a as f64;
            }
            let x = vec![0.0; dim];
            let mut josephy = Josephy::default();
            let step = josephy
                .step(
                    HeldTangent {
                        pattern: &pattern,
                        values: &k,
                        scale: 1.0,
                        held: &held,
                        single: false,
                    },
                    &rhs,
                    &x,
                    &constraints,
                )
                .unwrap();
            let delta = &step.correction;
            let force: Vec<f64> = constraints
                .iter()
                .map(|c| c.force_per_multiplier * delta[c.multiplier])
                .collect();
            // K δ − E f = b on the displacements
            let mut displacements = delta.clone();
            displacements[3 * n..].iter_mut().for_each(|v| *v = 0.0);
            let mut kd = vec![0.0; dim];
            multiply(pattern.symbolic(), &k, &displacements, &mut kd);
            for (a, c) in constraints.iter().enumerate() {
                kd[c.dof] -= c.sign * force[a];
            }
            for i in 0..3 * n {
                assert!((kd[i] - rhs[i]).abs() < 1e-12, "{ground}: row {i}");
            }
            let (mut closed, mut total) = (0, 0.0);
            for (a, c) in constraints.iter().enumerate() {
                let g = c.gap + c.sign * delta[c.dof];
                assert!(g > -1e-12 && force[a] > -1e-12, "{ground}: node {a}");
                assert!((g * force[a]).abs() < 1e-13, "{ground}: node {a}");
                closed += usize::from(g.abs() < 1e-12);
                total += force[a];
            }
            assert_eq!(closed, step.closed);
            assert!(closed > 1 && closed < n, "{ground}: {closed} closed");
            // every node's load reaches the floor when nothing else holds z
            if ground == 0.0 {
                assert!((total - 0.01 * n as f64).abs() < 1e-12, "{total}");
            } else {
                assert!(total < 0.01 * n as f64);
            }
        }
    }
}
