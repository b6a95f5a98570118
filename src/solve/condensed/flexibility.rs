//! The flexibility of the contact unknowns on one factorisation: `K̃`
//! (a constant stiffness whose prescribed rows and columns, and the
//! multipliers, are a scaled identity `s`, plus an optional shift `ρ = s`
//! on some diagonal entries) factorised once with the unknowns of the
//! contact columns nearest to contact ordered last, `W = Eᵀ K̃⁻¹ E` over
//! the candidate columns (from the trailing block `(K̃⁻¹)_TT`, else by
//! solves with the factor, [`super::schur`]), and the exact
//! complementarity solve of an increment ([`Flexibility::solve_increment`]).
//!
//! A column of `E` is any linear form on the unknowns, `(dof, value)`
//! pairs, with a compliance added to `W`'s diagonal (a penalty law's
//! `1/(A ε)`): the caller reads them from the contact's linearisation
//! ([`crate::contact::interface::ConstraintRow`]), so that the algebra
//! knows neither obstacles nor laws.

use super::complementarity::solve_lcp;
use super::decoupled::{decoupled_first, Decoupled};
use super::parts::PartedLdlt;
use super::schur::{
    grow_flexibility, refresh_flexibility, trailing_ordering, Direction, TrailingInverse,
};
use crate::assembly::pattern::SparsityPattern;
use crate::assembly::triangle::{self, LowerTriangle};
use crate::solve::linear::{scaled_identity_rows, IterativeRefinement, Precision};
use crate::solve::ordering::EarlyDissection;
use crate::solve::record::IterationRecord;
use crate::{Error, Result};
use nalgebra::DMatrix;
use std::sync::Arc;

/// One column of `E` on every unknown, and the compliance added to its
/// diagonal entry of `W` (0 for an exact constraint).
#[derive(Clone, Debug, PartialEq)]
pub struct Column {
    pub entries: Vec<(usize, f64)>,
    pub compliance: f64,
}

/// The constant stiffness a [`Flexibility`] factorises: `K` on the lower
/// triangle `lower` of the pattern, and the `constrained` unknowns (the
/// prescribed ones and every multiplier, the latter from `dofs` on).
pub struct Stiffness {
    pub lower: Arc<LowerTriangle>,
    pub k: Arc<Vec<f64>>,
    pub dofs: usize,
    pub constrained: Vec<bool>,
}

/// The ordering and symbolic analysis of a [`Flexibility`]: the trailing
/// unknowns, the decoupled structure and the analysed solver.
pub struct Analysis {
    pub trailing: Vec<usize>,
    pub decoupled: Decoupled,
    pub ldlt: PartedLdlt,
}

/// The condensed solver of a run: the factor of `K̃`, the columns of `E`,
/// the candidates and their flexibility `W`.
pub struct Flexibility {
    /// The factor of `K̃`, per body when there are two or more
    /// ([`PartedLdlt`]).
    pub ldlt: PartedLdlt,
    /// `(K̃⁻¹)_TT` on the trailing unknowns (the free dofs of the columns
    /// nearest to contact), ordered last in the factorisation: `W` of
    /// those columns without solves ([`super::schur`]).
    pub trailing: TrailingInverse,
    pub trailing_dofs: Vec<usize>,
    /// The lower triangle of the pattern, and on it `K` as assembled and
    /// `K̃` (prescribed rows, columns and multipliers a scaled identity
    /// `s`): what the factorisation and the products read.
    pub lower: Arc<LowerTriangle>,
    pub k: Arc<Vec<f64>>,
    pub k_tilde: Vec<f64>,
    /// `K̃` without the couplings of its identity rows, as factorised.
    pub decoupled: Decoupled,
    pub scale: f64,
    pub constrained: Vec<bool>,
    /// Unknowns before the multipliers.
    pub dofs: usize,
    pub columns: Vec<Column>,
    /// Candidate columns (indices into `columns`), `W` over them, and the
    /// last active set.
    pub candidates: Vec<usize>,
    /// The candidates in the batches they joined in (a restart's replay).
    pub batches: Vec<Vec<usize>>,
    pub is_candidate: Vec<bool>,
    pub w: DMatrix<f64>,
    pub active: Vec<bool>,
    pub active_set_iterations: usize,
    /// f32 factorisations refactorised in f64 when a refined solve stalled.
    pub fallbacks: usize,
}

/// The nodes that join the candidates in one round penetrate by at least
/// this fraction of the deepest penetration ([`Flexibility::entering`]).
/// On examples/hertz (335 closed nodes at the end) 0 gives 621 candidates,
/// 0.3 gives 530, 0.5 gives 431 and 0.8 the 335 closed nodes exactly but in
/// 68 active-set steps instead of 13 and more rounds of small solves:
/// 0.5 was the fastest.
const ENTERING_FRACTION: f64 = 0.5;

/// At most this many unknowns ordered last for `(K̃⁻¹)_TT` (a dense
/// block: `2c³/3` flops to read, `c²` entries): the free dofs of the
/// columns nearest to contact; a column beyond them gets its column of `W`
/// by a solve.
pub const MAX_TRAILING: usize = 4000;

/// Below this many unknowns the one factorisation of `K̃`, its solves and
/// `(K̃⁻¹)_TT` run on one thread (faer's `Par::Seq`) whatever the run's
/// thread count, from it on the run's threads: the one constant of that
/// choice ([`crate::solve::linear::SparseLdlt::threads_as_given`]; the dense `(K̃⁻¹)_TT` follows
/// the factor's threads). On the small race mesh (19 100 unknowns, 9.0 M
/// factor entries) the f32 factorisation took 0.13–0.14 s on one thread at
/// any load, on two 0.11 s on an idle machine but 0.24–0.32 s beside two
/// compiling processes (1-minute load 4), the supernodes being too small
/// for the threads' synchronisation to pay; at 108 k unknowns (121 M
/// entries) two threads do pay. On an idle machine (1-minute load 1.7,
/// 2026-11-25 23:50, 10 + 10 alternating whole runs of the small race)
/// two threads took 0.92–0.96× the wall time of one and 1.13–1.16× its
/// CPU; issue 13 measures wall time, so from 10 000 unknowns the run's
/// threads are used (BENCHMARKS.md, "Session 9").
const PARALLEL_FACTOR_UNKNOWNS: usize = 10_000;

/// Refinement steps at most on an f32 factor before the f64 fallback.
const MIXED_REFINEMENTS: usize = 10;

/// Defect corrections of an increment
/// ([`Flexibility::solve_increment`]) before the splitting on an f32
/// `W̃` is taken as diverging.
const MAX_DEFECT_CORRECTIONS: usize = 50;

/// The unknowns ordered last: the free (not `constrained`) dofs of the
/// `groups` in turn, each dof once, a group whole or not at all, until the
/// next group would take them past `limit`.
pub fn take_trailing<G: IntoIterator<Item = usize>>(
    groups: impl IntoIterator<Item = G>,
    constrained: &[bool],
    limit: usize,
) -> Vec<usize> {
    let mut dofs = Vec::new();
    let mut taken = vec![false; constrained.len()];
    for group in groups {
        let free: Vec<usize> = (group.into_iter())
            .filter(|&d| !constrained[d] && !taken[d])
            .collect();
        if dofs.len() + free.len() > limit {
            break;
        }
        free.iter().for_each(|&d| taken[d] = true);
        dofs.extend(free);
    }
    dofs
}

/// A column on the free (not `constrained`) dofs, its zero entries left
/// out, as a direction.
fn direction_on(column: &Column, constrained: &[bool]) -> Direction {
    (column.entries.iter())
        .filter(|&&(i, n)| !constrained[i] && n != 0.0)
        .copied()
        .collect()
}

impl Flexibility {
    /// The free dofs of the `columns` taken in `order` (nearest to contact
    /// first), of the first `fraction` of them, at most [`MAX_TRAILING`]:
    /// the unknowns ordered last.
    pub fn trailing_dofs(
        columns: &[Column],
        order: &[usize],
        constrained: &[bool],
        fraction: f64,
    ) -> Vec<usize> {
        let limit = MAX_TRAILING.min((fraction * columns.len() as f64).ceil() as usize);
        let groups = order.iter().map(|&a| {
            (columns[a].entries.iter())
                .filter(|&&(_, n)| n != 0.0)
                .map(|&(i, _)| i)
        });
        take_trailing(groups, constrained, limit)
    }

    /// The factorisation's ordering and symbolic analysis: the `trailing`
    /// unknowns last (grouped by body, [`trailing_ordering`]), the
    /// decoupled identity rows of `constrained` first and without their
    /// couplings, and no entry between nodes that share no element
    /// ([`Decoupled::within_elements`]: `K` is the elements' alone); the
    /// nested dissection of the rest mostly done before (`dissection`).
    pub fn analyse(
        pattern: &SparsityPattern,
        lower: &LowerTriangle,
        trailing: Vec<usize>,
        constrained: &[bool],
        dissection: Option<&EarlyDissection>,
    ) -> Result<Analysis> {
        let dimension = pattern.dimension();
        let mut marked = vec![false; dimension];
        trailing.iter().for_each(|&i| marked[i] = true);
        // 1: one thread (`Par::Seq`), 0: the run's pool
        let threads = usize::from(dimension < PARALLEL_FACTOR_UNKNOWNS);
        // the structure first: the dissection may still be running
        let decoupled =
            Decoupled::within_elements(lower.symbolic(), constrained, pattern.element_neighbours());
        let ordering = trailing_ordering(pattern, &marked, dissection)?;
        let ordering = decoupled_first(ordering, constrained);
        let ldlt = PartedLdlt::analyse(decoupled.symbolic(), ordering, threads)?;
        Ok(Analysis {
            trailing,
            decoupled,
            ldlt,
        })
    }

    /// Make `K̃` from `stiffness` (prescribed rows and columns a scaled
    /// identity `s`, plus `ρ = s` on the diagonal of the `shifted` dofs)
    /// and factorise it once, in `precision`, on the `analysis`; `(K̃⁻¹)_TT`
    /// read off the factor. No candidates yet.
    pub fn factorise(
        stiffness: Stiffness,
        columns: Vec<Column>,
        shifted: &[usize],
        analysis: Analysis,
        precision: Precision,
    ) -> Result<Self> {
        let Stiffness {
            lower,
            k,
            dofs,
            constrained,
        } = stiffness;
        let Analysis {
            trailing: trailing_dofs,
            decoupled,
            mut ldlt,
        } = analysis;
        // the factor's storage sized (its pages touched) on one thread
        // while the other makes `K̃` and its values
        let (_, (k_tilde, scale, values)) = rayon::join(
            || ldlt.reserve(precision),
            || {
                let mut k_tilde = k.to_vec();
                let diagonal = |d: usize| Some(lower.diagonal_entry(d));
                let scale = scaled_identity_rows(
                    lower.symbolic(),
                    diagonal,
                    dofs,
                    &constrained,
                    &mut k_tilde,
                );
                for &d in shifted {
                    k_tilde[lower.diagonal_entry(d)] += scale;
                }
                let values = decoupled.values(&k_tilde);
                (k_tilde, scale, values)
            },
        );
        if decoupled.couples_across(&k_tilde) {
            return Err(Error::LinearSolver(
                "the condensed stiffness couples nodes that share no element".into(),
            ));
        }
        ldlt.factorize(&values, precision)?;
        let trailing = ldlt.trailing_inverse(&trailing_dofs)?;
        let count = columns.len();
        Ok(Flexibility {
            ldlt,
            trailing,
            trailing_dofs,
            lower,
            k,
            k_tilde,
            decoupled,
            scale,
            constrained,
            dofs,
            columns,
            candidates: Vec::new(),
            batches: Vec::new(),
            is_candidate: vec![false; count],
            w: DMatrix::zeros(0, 0),
            active: Vec::new(),
            active_set_iterations: 0,
            fallbacks: 0,
        })
    }

    /// `E e_a`: column `a` on the free dofs, as a direction.
    pub fn direction(&self, a: usize) -> Direction {
        direction_on(&self.columns[a], &self.constrained)
    }

    /// `v += factor E e_a`.
    pub fn add_column(&self, a: usize, factor: f64, v: &mut [f64]) {
        for &(i, n) in &self.columns[a].entries {
            if !self.constrained[i] {
                v[i] += factor * n;
            }
        }
    }

    /// `(E e_a)ᵀ v`.
    pub fn column_dot(&self, a: usize, v: &[f64]) -> f64 {
        (self.columns[a].entries.iter())
            .filter(|&&(i, _)| !self.constrained[i])
            .map(|&(i, n)| n * v[i])
            .sum()
    }

    /// Add the columns `new` to the candidates: their columns of `W` from
    /// `(K̃⁻¹)_TT` or by block solves with the factor
    /// ([`grow_flexibility`]).
    pub fn grow(&mut self, new: &[usize]) -> Result<()> {
        if !new.is_empty() {
            self.batches.push(new.to_vec());
        }
        self.candidates.extend_from_slice(new);
        new.iter().for_each(|&a| self.is_candidate[a] = true);
        let directions: Vec<Direction> =
            self.candidates.iter().map(|&a| self.direction(a)).collect();
        let n = self.constrained.len();
        let solve = |z: &mut [f64], k| self.ldlt.solve_columns_in_place(z, k);
        self.w = grow_flexibility(solve, &self.trailing, &self.w, &directions, n)?;
        self.active.resize(self.candidates.len(), false);
        Ok(())
    }

    /// Make `columns` the columns of `E` (as many as before: the same
    /// contact nodes, at new projections) and form `W` anew over the
    /// candidates (from `(K̃⁻¹)_TT` where they lie on the trailing block).
    pub fn replace_columns(&mut self, columns: Vec<Column>) -> Result<()> {
        if columns.len() != self.columns.len() {
            return Err(Error::LinearSolver(format!(
                "{} condensed contact columns replaced by {}",
                self.columns.len(),
                columns.len()
            )));
        }
        self.columns = columns;
        let directions: Vec<Direction> =
            self.candidates.iter().map(|&a| self.direction(a)).collect();
        if directions.iter().all(|e| self.trailing.covers(e)) {
            // every column from the block, on the run's threads
            let every: Vec<usize> = (0..directions.len()).collect();
            self.w = DMatrix::zeros(every.len(), every.len());
            refresh_flexibility(&self.trailing, &mut self.w, &directions, &every);
            return Ok(());
        }
        let n = self.constrained.len();
        let none = DMatrix::zeros(0, 0);
        let solve = |z: &mut [f64], k| self.ldlt.solve_columns_in_place(z, k);
        self.w = grow_flexibility(solve, &self.trailing, &none, &directions, n)?;
        Ok(())
    }

    /// [`Self::replace_columns`] keeping `W`'s entries between candidates
    /// whose columns did not change (the same entries): the rows and
    /// columns of the changed ones formed anew from `(K̃⁻¹)_TT`
    /// ([`refresh_flexibility`], one response `z_j` per changed `j`),
    /// nothing when none changed; anew as there when a candidate is off the
    /// trailing block.
    pub fn update_columns(&mut self, columns: Vec<Column>) -> Result<()> {
        if columns.len() != self.columns.len() {
            return self.replace_columns(columns);
        }
        let changed: Vec<usize> = (self.candidates.iter().enumerate())
            .filter(|(_, &a)| columns[a].entries != self.columns[a].entries)
            .map(|(i, _)| i)
            .collect();
        if changed.is_empty() {
            self.columns = columns;
            return Ok(());
        }
        let directions: Vec<Direction> = (self.candidates.iter())
            .map(|&a| direction_on(&columns[a], &self.constrained))
            .collect();
        if !directions.iter().all(|e| self.trailing.covers(e)) {
            return self.replace_columns(columns);
        }
        self.columns = columns;
        refresh_flexibility(&self.trailing, &mut self.w, &directions, &changed);
        Ok(())
    }

    /// The columns that join the candidates at gaps `g`: those outside them
    /// that penetrate by more than `tolerance` and by at least
    /// [`ENTERING_FRACTION`] of the deepest such penetration (the deepest
    /// first: a node that penetrates only a little without contact is
    /// often lifted off by its neighbours' forces, and every candidate
    /// costs a solve).
    pub fn entering(&self, g: &[f64], tolerance: f64) -> Vec<usize> {
        let outside = |a: &usize| !self.is_candidate[*a] && g[*a] < -tolerance;
        let deepest = (0..self.columns.len())
            .filter(outside)
            .map(|a| g[a])
            .fold(0.0f64, f64::min);
        // a node on the trailing block costs no solve: every one that
        // penetrates enters
        (0..self.columns.len())
            .filter(|a| {
                outside(a)
                    && (g[*a] <= ENTERING_FRACTION * deepest
                        || self.trailing.covers(&self.direction(*a)))
            })
            .collect()
    }

    /// Whether the factor is in f32 (its block's response then off by the
    /// f32 Schur complement's round-off).
    pub fn is_single(&self) -> bool {
        self.ldlt.precision() == Precision::Single
    }

    /// `K̃ u = rhs`, refined ([`Self::solve_from`] the factor's solution).
    pub fn solve(&mut self, rhs: &mut [f64]) -> Result<()> {
        let b = rhs.to_vec();
        self.ldlt.solve_in_place(rhs)?;
        self.solve_from(&b, rhs)
    }

    /// `K̃ x = b` refined from the approximate solution `x` (from the
    /// solution for a nearby `b` it takes fewer refinement steps than a
    /// fresh solve); on an f32 factor whose refinement stalls above 1e-12,
    /// `K̃` factorised again in f64 (and `W` made again from it) and
    /// solved with that.
    pub fn solve_from(&mut self, b: &[f64], x: &mut [f64]) -> Result<()> {
        let single = self.is_single();
        let refinements = if single { MIXED_REFINEMENTS } else { 3 };
        let (lower, k_tilde) = (&self.lower, &self.k_tilde);
        let product =
            |v: &[f64], y: &mut [f64]| triangle::multiply(lower.symbolic(), k_tilde, v, y);
        let mut relative = self.ldlt.refine_with(product, b, x, refinements, single)?;
        if single && relative > 1e-12 {
            self.refactorise_double()?;
            x.copy_from_slice(b);
            self.ldlt.solve_in_place(x)?;
            let (lower, k_tilde) = (&self.lower, &self.k_tilde);
            let product =
                |v: &[f64], y: &mut [f64]| triangle::multiply(lower.symbolic(), k_tilde, v, y);
            relative = self.ldlt.refine_with(product, b, x, 3, false)?;
        }
        if relative > 1e-10 {
            return Err(Error::LinearSolver(format!(
                "the condensed stiffness solve left a relative residual of {relative:.1e}"
            )));
        }
        Ok(())
    }

    /// `K̃` factorised again in f64 (an f32 factor's refinement stalled,
    /// or its `W̃` did not let the defect corrections settle), the trailing
    /// inverse and `W` made again from it; the run goes on in f64.
    fn refactorise_double(&mut self) -> Result<()> {
        self.fallbacks += 1;
        let values = self.decoupled.values(&self.k_tilde);
        self.ldlt.factorize(&values, Precision::Double)?;
        self.trailing = self.ldlt.trailing_inverse(&self.trailing_dofs)?;
        let directions: Vec<Direction> =
            self.candidates.iter().map(|&a| self.direction(a)).collect();
        let n = self.constrained.len();
        let none = DMatrix::zeros(0, 0);
        let solve = |z: &mut [f64], k| self.ldlt.solve_columns_in_place(z, k);
        self.w = grow_flexibility(solve, &self.trailing, &none, &directions, n)?;
        Ok(())
    }

    /// `b`: `f_ext − K_fp ū` on the free dofs, `s ū` on the prescribed
    /// ones, 0 on the multipliers, from the `prescribed` values `ū` (zero
    /// elsewhere) and the external force `f_ext` on the displacements.
    pub fn load(&self, prescribed: &[f64], f_ext: &[f64]) -> Vec<f64> {
        let dimension = self.constrained.len();
        let mut k_prescribed = vec![0.0; dimension];
        triangle::multiply(
            self.lower.symbolic(),
            &self.k,
            prescribed,
            &mut k_prescribed,
        );
        (0..dimension)
            .map(|i| {
                if i >= self.dofs {
                    0.0
                } else if self.constrained[i] {
                    self.scale * prescribed[i]
                } else {
                    f_ext[i] - k_prescribed[i]
                }
            })
            .collect()
    }

    /// The contact forces (per column, `λ_a`) and the displacements `u`
    /// on the trailing unknowns (elsewhere those of `u_b`) for the free
    /// solution `u_b = K̃⁻¹ b` and affine gaps `gaps(u)`, every candidate
    /// column on the trailing block: `u_T = (u_b)_T + (K̃⁻¹)_TT (E λ)_T`,
    /// without a solve with the factor. The candidates grow by the nodes
    /// that penetrate below `−tolerance` at the answer until none does;
    /// the active-set steps pushed to `history`. An error if a candidate
    /// leaves the block (the caller solves with the factor then).
    pub fn solve_on_block(
        &mut self,
        u_b: &[f64],
        gaps: &dyn Fn(&[f64]) -> Vec<f64>,
        tolerance: f64,
        history: &mut Vec<IterationRecord>,
    ) -> Result<(Vec<f64>, Vec<f64>)> {
        let g0 = gaps(u_b);
        let mut entering = self.entering(&g0, tolerance);
        loop {
            self.grow(&entering)?;
            if let Some(&a) =
                (self.candidates.iter()).find(|&&a| !self.trailing.covers(&self.direction(a)))
            {
                return Err(Error::LinearSolver(format!(
                    "condensed contact column {a} is not on the trailing block"
                )));
            }
            let q: Vec<f64> = self.candidates.iter().map(|&a| g0[a]).collect();
            let forces = self.complementarity(&q, tolerance, history)?;
            let mut load: Direction = Vec::new();
            for &a in &self.candidates {
                if forces[a] != 0.0 {
                    load.extend(self.direction(a).iter().map(|&(i, e)| (i, forces[a] * e)));
                }
            }
            let mut u = u_b.to_vec();
            self.trailing.add_response(&load, &mut u);
            entering = self.entering(&gaps(&u), tolerance);
            if entering.is_empty() {
                return Ok((u, forces));
            }
        }
    }

    /// The complementarity problem over the candidates, `q + (W + C)λ ≥ 0
    /// ⊥ λ ≥ 0` (`C` the compliances), from the last active set: the
    /// forces per column (zero off the candidates).
    fn complementarity(
        &mut self,
        q: &[f64],
        tolerance: f64,
        history: &mut Vec<IterationRecord>,
    ) -> Result<Vec<f64>> {
        let mut w = self.w.clone();
        for (i, &a) in self.candidates.iter().enumerate() {
            w[(i, i)] += self.columns[a].compliance;
        }
        // a candidate whose column is empty (its node lost its row between
        // rounds: dual mortar's node that fell below half covered) has a
        // zero row of `W` and carries no force: it starts open, and its
        // gap (the search margin) keeps it so
        for (i, active) in self.active.iter_mut().enumerate() {
            *active &= w[(i, i)] > 0.0;
        }
        let lambda_scale = (0..q.len()).map(|i| w[(i, i)]).fold(0.0f64, f64::max);
        let solution = solve_lcp(
            &w,
            q,
            &self.active,
            tolerance,
            1e-14 * tolerance / lambda_scale.max(f64::MIN_POSITIVE),
        )
        .map_err(Error::LinearSolver)?;
        self.active_set_iterations += solution.iterations;
        self.active = solution.active;
        history.extend(solution.history);
        let mut forces = vec![0.0; self.columns.len()];
        for (i, &a) in self.candidates.iter().enumerate() {
            forces[a] = solution.lambda[i];
        }
        Ok(forces)
    }

    /// The displacements and the contact forces (per column, `λ_a`) at
    /// the load `b`, `gaps(u)` the gap of every column at displacements `u`
    /// (`g(u) = g(0) + Eᵀu` up to round-off: the gaps are affine), a node
    /// taken as penetrating below `−tolerance`; the active-set steps pushed
    /// to `history`.
    ///
    /// `W` may be inexact (from an f32 factor): the complementarity problem
    /// is solved on `W̃` with the gaps shifted by the defect
    /// `d = g(u(λ)) − (g₀ + W̃λ) = (W − W̃)λ + (g(K̃⁻¹b) − g₀)` of the last
    /// solution, `g(u)` the gaps of the refined (f64) displacements and `g₀`
    /// those of the factor's unrefined `u₀` (its error, constant, is taken
    /// up by the first defect; refining `u₀` took two of the small race's
    /// eight solves with the factor), until `d` changes by
    /// less than a thousandth of the gap tolerance: then `g(u) = g₀ + Wλ` and the solution
    /// is the one of the exact `W` (a splitting iteration, contracting
    /// while `‖W̃⁻¹(W − W̃)‖ < 1`). With an f64 `W` the first `d` is
    /// round-off and one pass is enough. Where the splitting does not
    /// settle on an f32 factor (a nearly incompressible body: Hertz with
    /// ν = 0.49999 failed 4 of its increments over to Newton's path, 73 s
    /// against Newton's own 20 s), `K̃` is factorised again in f64 and the
    /// increment solved on it.
    pub fn solve_increment(
        &mut self,
        b: &[f64],
        gaps: &dyn Fn(&[f64]) -> Vec<f64>,
        tolerance: f64,
        history: &mut Vec<IterationRecord>,
    ) -> Result<(Vec<f64>, Vec<f64>)> {
        if let Some(answer) = self.corrected_increment(b, gaps, tolerance, history)? {
            return Ok(answer);
        }
        if self.is_single() {
            self.refactorise_double()?;
            if let Some(answer) = self.corrected_increment(b, gaps, tolerance, history)? {
                return Ok(answer);
            }
        }
        Err(Error::LinearSolver(format!(
            "the condensed contact forces did not settle in {MAX_DEFECT_CORRECTIONS} \
             corrections of the flexibility; run with [solver] strategy = \"monolithic\""
        )))
    }

    /// [`Self::solve_increment`] on the factor as it is: `None` where the
    /// defect corrections did not settle in [`MAX_DEFECT_CORRECTIONS`].
    fn corrected_increment(
        &mut self,
        b: &[f64],
        gaps: &dyn Fn(&[f64]) -> Vec<f64>,
        tolerance: f64,
        history: &mut Vec<IterationRecord>,
    ) -> Result<Option<(Vec<f64>, Vec<f64>)>> {
        // the factor's solution, unrefined: `g₀` enters the complementarity
        // problem only in `q = g₀ + d`, and the defect `d` of the refined
        // `u` takes up its error exactly, as it does `W̃`'s
        let mut u0 = b.to_vec();
        self.ldlt.solve_in_place(&mut u0)?;
        let g0 = gaps(&u0);
        let entering = self.entering(&g0, tolerance);
        self.grow(&entering)?;
        let mut defect = vec![0.0; self.columns.len()];
        let mut previous_change = f64::INFINITY;
        let mut previous = u0;
        for _ in 0..MAX_DEFECT_CORRECTIONS {
            let q: Vec<f64> = self.candidates.iter().map(|&a| g0[a] + defect[a]).collect();
            let forces = self.complementarity(&q, tolerance, history)?;
            let mut rhs = b.to_vec();
            for &a in &self.candidates {
                self.add_column(a, forces[a], &mut rhs);
            }
            // from the last pass's displacements: its forces differ by
            // the defect's correction only
            let mut u = previous;
            self.solve_from(&rhs, &mut u)?;
            previous = u.clone();
            let g = gaps(&u);
            let mut change = 0.0f64;
            for (i, &a) in self.candidates.iter().enumerate() {
                let predicted = g0[a]
                    + (self.candidates.iter().enumerate())
                        .map(|(j, &b)| self.w[(i, j)] * forces[b])
                        .sum::<f64>();
                let d = g[a] - predicted;
                change = change.max((d - defect[a]).abs());
                defect[a] = d;
            }
            let entering = self.entering(&g, tolerance);
            // settled: far below the gap tolerance (a gap error `δ` is a
            // force residual `k δ` in the augmented laws), or within it and
            // no longer contracting (round-off)
            let settled = change <= 1e-3 * tolerance
                || change <= tolerance && change >= 0.5 * previous_change;
            previous_change = change;
            if entering.is_empty() && settled {
                return Ok(Some((u, forces)));
            }
            self.grow(&entering)?;
        }
        Ok(None)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `n` nodes in a row joined by unit springs in every direction, node
    /// 0 held (prescribed): `K` on its lower triangle, the constrained
    /// unknowns and the pattern.
    fn chain(n: usize) -> (SparsityPattern, Stiffness) {
        let edges: Vec<[usize; 2]> = (0..n - 1).map(|a| [a, a + 1]).collect();
        let pattern = SparsityPattern::from_elements(n, edges.iter().map(|e| &e[..]));
        let mut k = vec![0.0; pattern.nnz()];
        let s = pattern.symbolic();
        let (cp, ri) = (s.col_ptr(), s.row_idx());
        for j in 0..s.ncols() {
            for p in cp[j]..cp[j + 1] {
                let (i, a, b) = (ri[p], ri[p] / 3, j / 3);
                if i % 3 == j % 3 {
                    let neighbours = usize::from(a > 0) + usize::from(a + 1 < n);
                    k[p] = if a == b { neighbours as f64 } else { -1.0 };
                }
            }
        }
        let lower = Arc::new(LowerTriangle::of(&pattern));
        let k = Arc::new(lower.values(&k));
        let constrained = (0..3 * n).map(|d| d < 3).collect();
        let stiffness = Stiffness {
            lower,
            k,
            dofs: 3 * n,
            constrained,
        };
        (pattern, stiffness)
    }

    /// A chain held at node 0 and pushed down (`f_z = −0.1` per node)
    /// onto a tilted floor, `g_a = 0.02 a − 0.05 + u_z,a` (or pressed on
    /// an oblique column `(u_x + u_z)/√2`), solved by the flexibility with
    /// half the columns on the trailing block: the answer meets the
    /// contact problem, `K̃ u = b + E λ` to 1e-12, `g + c λ ≥ −1e-12`,
    /// `λ ≥ 0`, `λ (g + c λ) = 0` to 1e-12 — exactly (`c = 0`) and with
    /// a penalty's compliance `c = 0.5`.
    #[test]
    fn the_increment_meets_the_contact_problem() {
        let n = 12;
        for (compliance, oblique) in [(0.0, false), (0.5, false), (0.0, true)] {
            let (pattern, stiffness) = chain(n);
            let weight = if oblique {
                std::f64::consts::FRAC_1_SQRT_2
            } else {
                1.0
            };
            let columns: Vec<Column> = (1..n)
                .map(|a| {
                    let mut entries = vec![(3 * a + 2, weight)];
                    if oblique {
                        entries.insert(0, (3 * a, weight));
                    }
                    Column {
                        entries,
                        compliance,
                    }
                })
                .collect();
            let order: Vec<usize> = (0..columns.len()).collect();
            let constrained = stiffness.constrained.clone();
            let trailing = Flexibility::trailing_dofs(&columns, &order, &constrained, 0.5);
            let analysis =
                Flexibility::analyse(&pattern, &stiffness.lower, trailing, &constrained, None)
                    .unwrap();
            let mut flexibility =
                Flexibility::factorise(stiffness, columns, &[], analysis, Precision::Double)
                    .unwrap();
            let f_ext: Vec<f64> = (0..3 * n)
                .map(|d| if d % 3 == 2 { -0.1 } else { 0.0 })
                .collect();
            let b = flexibility.load(&vec![0.0; 3 * n], &f_ext);
            let gap0: Vec<f64> = (1..n).map(|a| 0.02 * a as f64 - 0.05).collect();
            let gaps = |u: &[f64]| -> Vec<f64> {
                (0..n - 1)
                    .map(|c| gap0[c] + flexibility_dot(weight, oblique, c + 1, u))
                    .collect()
            };
            let mut history = Vec::new();
            let (u, lambda) = flexibility
                .solve_increment(&b, &gaps, 1e-14, &mut history)
                .unwrap();
            let mut ku = vec![0.0; 3 * n];
            triangle::multiply(
                flexibility.lower.symbolic(),
                &flexibility.k_tilde,
                &u,
                &mut ku,
            );
            let mut rhs = b.clone();
            for (c, &l) in lambda.iter().enumerate() {
                flexibility.add_column(c, l, &mut rhs);
            }
            for d in 0..3 * n {
                assert!((ku[d] - rhs[d]).abs() < 1e-12, "K u − b − Eλ at {d}");
            }
            let g = gaps(&u);
            assert!(lambda.iter().any(|&l| l > 1e-3), "some node closes");
            for c in 0..n - 1 {
                let gc = g[c] + compliance * lambda[c];
                assert!(
                    gc >= -1e-12 && lambda[c] >= 0.0,
                    "node {c}: {gc}, {}",
                    lambda[c]
                );
                assert!(
                    (gc * lambda[c]).abs() < 1e-12,
                    "node {c}: g λ = {}",
                    gc * lambda[c]
                );
            }
        }
    }

    /// A node that closed in one round and lost its column in the next
    /// (dual mortar's node that fell below half covered: an empty column,
    /// its gap the search margin) starts the next round open: the chain of
    /// [`the_increment_meets_the_contact_problem`] solved, then solved
    /// again with the deepest closed node's column emptied and its gap
    /// `+0.01`. Before, the last active set kept it active, its row of
    /// `W` zero, and the solve failed ("W is not positive definite", the
    /// matching two-spheres caps through mortar on the condensed path);
    /// now its force is 0 and every other node's answer meets the contact
    /// problem (`λ ≥ 0`, `g ≥ −1e-12`, `g λ = 0` to 1e-12).
    #[test]
    fn a_column_emptied_between_rounds_starts_open() {
        let n = 12;
        let (pattern, stiffness) = chain(n);
        let column = |a: usize| Column {
            entries: vec![(3 * a + 2, 1.0)],
            compliance: 0.0,
        };
        let columns: Vec<Column> = (1..n).map(column).collect();
        let order: Vec<usize> = (0..columns.len()).collect();
        let constrained = stiffness.constrained.clone();
        let trailing = Flexibility::trailing_dofs(&columns, &order, &constrained, 1.0);
        let analysis =
            Flexibility::analyse(&pattern, &stiffness.lower, trailing, &constrained, None).unwrap();
        let mut flexibility =
            Flexibility::factorise(stiffness, columns.clone(), &[], analysis, Precision::Double)
                .unwrap();
        let f_ext: Vec<f64> = (0..3 * n)
            .map(|d| if d % 3 == 2 { -0.1 } else { 0.0 })
            .collect();
        let b = flexibility.load(&vec![0.0; 3 * n], &f_ext);
        let gap0 = |c: usize| 0.02 * (c + 1) as f64 - 0.05;
        let floor =
            |u: &[f64]| -> Vec<f64> { (0..n - 1).map(|c| gap0(c) + u[3 * c + 5]).collect() };
        let mut history = Vec::new();
        let (_, lambda) = flexibility
            .solve_increment(&b, &floor, 1e-14, &mut history)
            .unwrap();
        let deepest = (0..n - 1)
            .max_by(|&a, &b| lambda[a].total_cmp(&lambda[b]))
            .unwrap();
        assert!(lambda[deepest] > 1e-3, "some node closes");
        let mut emptied = columns;
        emptied[deepest].entries.clear();
        flexibility.replace_columns(emptied).unwrap();
        let gaps = |u: &[f64]| -> Vec<f64> {
            let mut g = floor(u);
            g[deepest] = 0.01;
            g
        };
        let (u, lambda) = flexibility
            .solve_increment(&b, &gaps, 1e-14, &mut history)
            .unwrap();
        assert_eq!(lambda[deepest], 0.0);
        let g = gaps(&u);
        assert!(lambda.iter().any(|&l| l > 1e-3), "the others close");
        for c in 0..n - 1 {
            assert!(
                g[c] >= -1e-12 && lambda[c] >= 0.0,
                "node {c}: {} {}",
                g[c],
                lambda[c]
            );
            assert!((g[c] * lambda[c]).abs() < 1e-12, "node {c}");
        }
    }

    /// The column of node `a` applied to `u`.
    fn flexibility_dot(weight: f64, oblique: bool, a: usize, u: &[f64]) -> f64 {
        weight * u[3 * a + 2] + if oblique { weight * u[3 * a] } else { 0.0 }
    }
}
