//! The frictionless condensation: the one factorisation of `K̃` with the
//! contact dofs ordered last, the flexibility `W` over the candidate nodes
//! and the exact complementarity solve of an increment.

use super::{constraint_rows, Problem};
use crate::assembly::triangle::{self, LowerTriangle};
use crate::contact::laws::NormalEnforcement;
use crate::solve::complementarity::solve_lcp;
use crate::solve::decoupled::{decoupled_first, Decoupled};
use crate::solve::linear::{scaled_identity_rows, Precision, SparseLdlt};
use crate::solve::newton::IterationRecord;
use crate::solve::schur::{grow_flexibility, trailing_ordering, Direction, TrailingInverse};
use crate::solve::settings::LinearMethod;
use crate::{Error, Result};
use nalgebra::DMatrix;
use std::sync::Arc;

/// One column of `E`: a row of a secondary node's linearised constraint
/// ([`crate::contact::interface::ConstraintRow`]).
pub(super) struct ContactNode {
    pub(super) interface: usize,
    /// Index among the interface's nodes.
    pub(super) index: usize,
    /// The column on every unknown, `(dof, value)`: `∇g = Bᵀn` (the
    /// frictionless path), or a row of the lever `B` (the frictional one).
    pub(super) column: Vec<(usize, f64)>,
    /// `1/(A ε)` of a penalty law (0 for the exact laws): the diagonal
    /// added to `W`.
    pub(super) compliance: f64,
}

/// The condensed solver of a run: the factor of `K̃`, the contact nodes,
/// the candidates and their flexibility `W`.
pub(super) struct Condensation {
    pub(super) ldlt: SparseLdlt,
    /// `(K̃⁻¹)_TT` on the normal dofs of the contact nodes nearest to their
    /// planes, ordered last in the factorisation: `W` of those nodes
    /// without solves ([`crate::solve::schur`]).
    pub(super) trailing: TrailingInverse,
    pub(super) trailing_dofs: Vec<usize>,
    /// The lower triangle of the pattern, and on it `K` as assembled and
    /// `K̃` (prescribed rows, columns and multipliers a scaled identity
    /// `s`): what the factorisation and the products read.
    pub(super) lower: Arc<LowerTriangle>,
    pub(super) k: Arc<Vec<f64>>,
    pub(super) k_tilde: Vec<f64>,
    /// `K̃` without the couplings of its identity rows, as factorised.
    pub(super) decoupled: Decoupled,
    pub(super) scale: f64,
    pub(super) constrained: Vec<bool>,
    pub(super) nodes: Vec<ContactNode>,
    /// Candidate nodes (indices into `nodes`), `W` over them, and the
    /// last active set.
    pub(super) candidates: Vec<usize>,
    /// The candidates in the batches they joined in (a restart's replay).
    pub(super) batches: Vec<Vec<usize>>,
    pub(super) is_candidate: Vec<bool>,
    pub(super) w: DMatrix<f64>,
    pub(super) active: Vec<bool>,
    pub(super) active_set_iterations: usize,
    /// f32 factorisations refactorised in f64 when a refined solve stalled.
    pub(super) fallbacks: usize,
}

/// The nodes that join the candidates in one round penetrate by at least
/// this fraction of the deepest penetration ([`Condensation::entering`]).
/// On examples/hertz (335 closed nodes at the end) 0 gives 621 candidates,
/// 0.3 gives 530, 0.5 gives 431 and 0.8 the 335 closed nodes exactly but in
/// 68 active-set steps instead of 13 and more rounds of small solves:
/// 0.5 was the fastest.
const ENTERING_FRACTION: f64 = 0.5;

/// At most this many unknowns ordered last for `(K̃⁻¹)_TT` (a dense
/// block: `2c³/3` flops to read, `c²` entries): the normal dofs of the
/// contact nodes with the smallest gaps at `u = 0`; a node beyond them
/// gets its column of `W` by a solve.
const MAX_TRAILING: usize = 4000;

/// On the frictionless path the normal dofs of the nearest half of the
/// contact nodes are ordered last: each node there costs fill and its share
/// of the `c³` of `(K̃⁻¹)_TT`, a node outside it a column of `W` by a solve
/// once it becomes a candidate, and on Hertz about 36 % of the nodes close
/// (266 of 737 on the small race mesh, 848 of 2 436 on the large one, 335
/// of 925 on examples/hertz). Half instead of all: factor entries 10.2 →
/// 9.0 M (small), 137 → 121 M (large), 16.9 → 14.8 M (examples/hertz), the
/// same answers to 1e-10 and no longer solve phase. The frictional path
/// keeps every node (its nodes touch from the start).
const TRAILING_FRACTION: f64 = 0.5;

/// From this many unknowns `[solver] linear = "auto"` factorises `K̃` in
/// f32 on the condensed path (refined in f64; the contact forces corrected
/// against the f64 gaps, [`Condensation::solve_increment`]): the one
/// factorisation is most of the run there.
const MIXED_PRECISION_UNKNOWNS: usize = 10_000;

/// Below this many unknowns the one factorisation of `K̃`, its solves and
/// `(K̃⁻¹)_TT` run on one thread (faer's `Par::Seq`) whatever the run's
/// thread count, from it on the run's threads: the one constant of that
/// choice ([`SparseLdlt::threads_as_given`]; the dense `(K̃⁻¹)_TT` follows
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

impl Condensation {
    /// The frictionless condensation: one column per secondary node of
    /// every interface, its gap gradient `∇g` from the node driver (at
    /// `u = 0`: the gaps are affine, [`super::not_applicable`]) and, for a
    /// penalty law, the compliance `1/(A ε)`; `K̃` unshifted.
    pub(super) fn new(problem: &Problem) -> Result<Self> {
        let mut nodes = Vec::new();
        let zero = vec![0.0; problem.num_unknowns()];
        for (ci, rows) in constraint_rows(problem, 0.0, &zero).iter().enumerate() {
            let c = problem.contacts.interface(ci);
            for (i, row) in rows.iter().enumerate() {
                let Some(row) = row else { continue };
                let compliance = match c.law_at(i).converged() {
                    NormalEnforcement::Penalty { epsilon } => 1.0 / (row.area * epsilon),
                    NormalEnforcement::Exact { .. } => 0.0,
                };
                nodes.push(ContactNode {
                    interface: ci,
                    index: i,
                    column: row.gradient(),
                    compliance,
                });
            }
        }
        Self::factorise(problem, nodes, &[], TRAILING_FRACTION, true)
    }

    /// Assemble `K` at `u = 0` (its lower triangle), make `K̃` (prescribed rows and columns a
    /// scaled identity `s`, plus `ρ = s` on the diagonal of the `shifted`
    /// dofs) and factorise it once; `nodes` are the columns of `E`, the
    /// nearest `fraction` of them ordered last. The assembly and the
    /// ordering with its symbolic analysis (which read only the pattern)
    /// run side by side on the run's threads, the ordering's nested
    /// dissection mostly done before ([`Problem::dissection`]). In f32
    /// (from [`MIXED_PRECISION_UNKNOWNS`], or `linear = "mixed"`) only where
    /// `single_allowed`: the frictionless solve corrects the contact
    /// forces for the f32 `W̃` ([`Self::solve_increment`]); the frictional
    /// one has no such correction and factorises in f64 (on a 10 k-dof
    /// floating block the f32 `Ŵ` left a residual of 5.7e-7).
    pub(super) fn factorise(
        problem: &Problem,
        nodes: Vec<ContactNode>,
        shifted: &[usize],
        fraction: f64,
        single_allowed: bool,
    ) -> Result<Self> {
        let pattern = &problem.model.pattern;
        let dimension = pattern.dimension();
        let mut constrained = problem.constrained_dofs();
        let dofs = problem.model.num_dofs();
        constrained[dofs..].iter_mut().for_each(|c| *c = true);
        let lower = problem.model.lower_triangle();
        let (k, analysed) = rayon::join(
            || match problem.model.constant_stiffness() {
                Some(k) => Ok(k),
                None => {
                    let mut k = vec![0.0; lower.nnz()];
                    let mut force = vec![0.0; dimension];
                    problem
                        .model
                        .assemble_internal_lower(&vec![0.0; dimension], &mut force, &mut k)
                        .map_err(|f| Error::LinearSolver(problem.describe_failure(&f)))
                        .map(|()| Arc::new(k))
                }
            },
            || Self::analyse(problem, &lower, &nodes, &constrained, fraction),
        );
        let (k, (trailing, decoupled, mut ldlt)) = (k?, analysed?);
        let count = nodes.len();
        let single = single_allowed
            && match problem.settings.linear {
                LinearMethod::Mixed => true,
                LinearMethod::Auto => dimension >= MIXED_PRECISION_UNKNOWNS,
                _ => false,
            };
        let precision = if single {
            Precision::Single
        } else {
            Precision::Double
        };
        // the factor's storage sized (its pages touched) on one thread
        // while the other makes `K̃` and its values
        let (_, (k_tilde, scale, values)) = rayon::join(
            || ldlt.reserve(precision),
            || {
                let mut k_tilde = k.to_vec();
                let diagonal = |d: usize| lower.diagonal_entry(d);
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
        if single {
            ldlt.factorize_single(decoupled.symbolic(), &values, None)?;
        } else {
            ldlt.factorize(decoupled.symbolic(), &values, None)?;
        }
        let trailing_dofs = trailing;
        let trailing = TrailingInverse::of(&ldlt, &trailing_dofs)?;
        Ok(Condensation {
            ldlt,
            trailing,
            trailing_dofs,
            lower,
            k,
            k_tilde,
            decoupled,
            scale,
            constrained,
            nodes,
            candidates: Vec::new(),
            batches: Vec::new(),
            is_candidate: vec![false; count],
            w: DMatrix::zeros(0, 0),
            active: Vec::new(),
            active_set_iterations: 0,
            fallbacks: 0,
        })
    }

    /// The factorisation's ordering and symbolic analysis: the normal dofs
    /// of the nearest contact nodes last ([`Self::nearest_normal_dofs`]),
    /// the decoupled identity rows of `constrained` first and without
    /// their couplings ([`Decoupled`]). Returns those trailing dofs, the
    /// decoupled structure and the analysed solver.
    pub(super) fn analyse(
        problem: &Problem,
        lower: &LowerTriangle,
        nodes: &[ContactNode],
        constrained: &[bool],
        fraction: f64,
    ) -> Result<(Vec<usize>, Decoupled, SparseLdlt)> {
        let pattern = &problem.model.pattern;
        let dimension = pattern.dimension();
        let trailing = Self::nearest_normal_dofs(problem, nodes, constrained, fraction);
        let mut marked = vec![false; dimension];
        trailing.iter().for_each(|&i| marked[i] = true);
        // 1: one thread (`Par::Seq`), 0: the run's pool
        let threads = usize::from(dimension < PARALLEL_FACTOR_UNKNOWNS);
        // the structure first: the dissection may still be running
        // ([`crate::problem::dissects_element_graph`])
        let decoupled = Decoupled::new(lower.symbolic(), constrained);
        let ordering = trailing_ordering(pattern, &marked, problem.dissection.as_ref())?;
        let ordering = decoupled_first(ordering, constrained);
        let mut ldlt = SparseLdlt::new(ordering, threads).threads_as_given();
        ldlt.analyse(decoupled.symbolic())?;
        Ok((trailing, decoupled, ldlt))
    }

    /// The free dofs of the columns of the contact nodes nearest to their
    /// obstacles (gap at `u = 0`, the smallest over the steps' ends), of the nearest `fraction` of the nodes, at most
    /// [`MAX_TRAILING`].
    pub(super) fn nearest_normal_dofs(
        problem: &Problem,
        nodes: &[ContactNode],
        constrained: &[bool],
        fraction: f64,
    ) -> Vec<usize> {
        let dimension = constrained.len();
        let limit = MAX_TRAILING.min((fraction * nodes.len() as f64).ceil() as usize);
        let zero = vec![0.0; dimension];
        let reference = &problem.model.mesh.nodes;
        let mut gap = vec![f64::INFINITY; nodes.len()];
        let times = std::iter::once(0.0).chain(problem.steps.iter().map(|s| s.end_time));
        for t in times {
            let per_interface: Vec<Vec<f64>> = problem
                .contacts
                .iter()
                .map(|c| c.gaps(reference, t, &zero, None))
                .collect();
            for (g, c) in gap.iter_mut().zip(nodes) {
                *g = g.min(per_interface[c.interface][c.index]);
            }
        }
        let mut order: Vec<usize> = (0..nodes.len()).collect();
        order.sort_by(|&a, &b| gap[a].total_cmp(&gap[b]));
        let mut dofs = Vec::new();
        let mut taken = vec![false; dimension];
        for a in order {
            let c = &nodes[a];
            let free: Vec<usize> = (c.column.iter())
                .filter(|&&(i, n)| !constrained[i] && n != 0.0 && !taken[i])
                .map(|&(i, _)| i)
                .collect();
            if dofs.len() + free.len() > limit {
                break;
            }
            free.iter().for_each(|&i| taken[i] = true);
            dofs.extend(free);
        }
        dofs
    }

    /// `E e_a`: column `a` on the free dofs, as a direction.
    pub(super) fn direction(&self, a: usize) -> Direction {
        (self.nodes[a].column.iter())
            .filter(|&&(i, n)| !self.constrained[i] && n != 0.0)
            .copied()
            .collect()
    }

    /// `v += factor E e_a`.
    pub(super) fn add_column(&self, a: usize, factor: f64, v: &mut [f64]) {
        for &(i, n) in &self.nodes[a].column {
            if !self.constrained[i] {
                v[i] += factor * n;
            }
        }
    }

    /// `(E e_a)ᵀ v`.
    pub(super) fn column_dot(&self, a: usize, v: &[f64]) -> f64 {
        (self.nodes[a].column.iter())
            .filter(|&&(i, _)| !self.constrained[i])
            .map(|&(i, n)| n * v[i])
            .sum()
    }

    /// Add the nodes `new` to the candidates: their columns of `W` from
    /// `(K̃⁻¹)_TT` or by block solves with the factor
    /// ([`grow_flexibility`]).
    pub(super) fn grow(&mut self, new: &[usize]) -> Result<()> {
        if !new.is_empty() {
            self.batches.push(new.to_vec());
        }
        self.candidates.extend_from_slice(new);
        new.iter().for_each(|&a| self.is_candidate[a] = true);
        let directions: Vec<Direction> =
            self.candidates.iter().map(|&a| self.direction(a)).collect();
        let n = self.constrained.len();
        self.w = grow_flexibility(&mut self.ldlt, &self.trailing, &self.w, &directions, n)?;
        self.active.resize(self.candidates.len(), false);
        Ok(())
    }

    /// The nodes that join the candidates at gaps `g`: those outside them
    /// that penetrate by more than `tolerance` and by at least
    /// [`ENTERING_FRACTION`] of the deepest such penetration (the deepest
    /// first: a node that penetrates only a little without contact is
    /// often lifted off by its neighbours' forces, and every candidate
    /// costs a solve).
    pub(super) fn entering(&self, g: &[f64], tolerance: f64) -> Vec<usize> {
        let outside = |a: &usize| !self.is_candidate[*a] && g[*a] < -tolerance;
        let deepest = (0..self.nodes.len())
            .filter(outside)
            .map(|a| g[a])
            .fold(0.0f64, f64::min);
        // a node on the trailing block costs no solve: every one that
        // penetrates enters
        (0..self.nodes.len())
            .filter(|a| {
                outside(a)
                    && (g[*a] <= ENTERING_FRACTION * deepest
                        || self.trailing.covers(&self.direction(*a)))
            })
            .collect()
    }

    /// `K̃ u = rhs`, refined ([`Self::solve_from`] the factor's solution).
    pub(super) fn solve(&mut self, rhs: &mut [f64]) -> Result<()> {
        let b = rhs.to_vec();
        self.ldlt.solve_in_place(rhs)?;
        self.solve_from(&b, rhs)
    }

    /// `K̃ x = b` refined from the approximate solution `x` (from the
    /// solution for a nearby `b` it takes fewer refinement steps than a
    /// fresh solve); on an f32 factor whose refinement stalls above 1e-12,
    /// `K̃` factorised again in f64 (and `W` made again from it) and
    /// solved with that.
    pub(super) fn solve_from(&mut self, b: &[f64], x: &mut [f64]) -> Result<()> {
        let single = self.ldlt.precision() == Precision::Single;
        let refinements = if single { MIXED_REFINEMENTS } else { 3 };
        let (lower, k_tilde) = (&self.lower, &self.k_tilde);
        let product =
            |v: &[f64], y: &mut [f64]| triangle::multiply(lower.symbolic(), k_tilde, v, y);
        let mut relative = self.ldlt.refine_with(product, b, x, refinements, single)?;
        if single && relative > 1e-12 {
            self.fallbacks += 1;
            let values = self.decoupled.values(&self.k_tilde);
            self.ldlt
                .factorize(self.decoupled.symbolic(), &values, None)?;
            self.trailing = TrailingInverse::of(&self.ldlt, &self.trailing_dofs)?;
            let directions: Vec<Direction> =
                self.candidates.iter().map(|&a| self.direction(a)).collect();
            let n = self.constrained.len();
            let none = DMatrix::zeros(0, 0);
            self.w = grow_flexibility(&mut self.ldlt, &self.trailing, &none, &directions, n)?;
            x.copy_from_slice(b);
            self.ldlt.solve_in_place(x)?;
            relative = self.ldlt.refine_with(product, b, x, 3, false)?;
        }
        if relative > 1e-10 {
            return Err(Error::LinearSolver(format!(
                "the condensed stiffness solve left a relative residual of {relative:.1e}"
            )));
        }
        Ok(())
    }

    /// `b(t)`: `f_ext(t) − K_fp ū(t)` on the free dofs, `s ū(t)` on the
    /// prescribed ones, 0 on the multipliers.
    pub(super) fn load(&self, problem: &Problem, t: f64) -> Vec<f64> {
        let dimension = self.constrained.len();
        let mut prescribed = vec![0.0; dimension];
        problem.apply_prescribed(t, &mut prescribed);
        let dofs = problem.model.num_dofs();
        let mut k_prescribed = vec![0.0; dimension];
        triangle::multiply(
            self.lower.symbolic(),
            &self.k,
            &prescribed,
            &mut k_prescribed,
        );
        let f = problem.external_force(t, &prescribed[..dofs], None);
        (0..dimension)
            .map(|i| {
                if i >= dofs {
                    0.0
                } else if self.constrained[i] {
                    self.scale * prescribed[i]
                } else {
                    f[i] - k_prescribed[i]
                }
            })
            .collect()
    }

    /// The gaps of every contact node at unknowns `x`, time `t`.
    pub(super) fn gaps(&self, problem: &Problem, t: f64, x: &[f64]) -> Vec<f64> {
        let reference = &problem.model.mesh.nodes;
        let per_interface: Vec<Vec<f64>> = problem
            .contacts
            .iter()
            .map(|c| c.gaps(reference, t, x, None))
            .collect();
        self.nodes
            .iter()
            .map(|c| per_interface[c.interface][c.index])
            .collect()
    }

    /// The displacements and contact forces (per node, `λ_a = A_a t_N`) at
    /// time `t`.
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
    /// round-off and one pass is enough.
    pub(super) fn solve_increment(
        &mut self,
        problem: &Problem,
        t: f64,
        history: &mut Vec<IterationRecord>,
    ) -> Result<(Vec<f64>, Vec<f64>)> {
        let b = self.load(problem, t);
        // the factor's solution, unrefined: `g₀` enters the complementarity
        // problem only in `q = g₀ + d`, and the defect `d` of the refined
        // `u` takes up its error exactly, as it does `W̃`'s
        let mut u0 = b.clone();
        self.ldlt.solve_in_place(&mut u0)?;
        let g0 = self.gaps(problem, t, &u0);
        let tolerance = 1e-12 * problem.model.size();
        let entering = self.entering(&g0, tolerance);
        self.grow(&entering)?;
        let mut defect = vec![0.0; self.nodes.len()];
        // defect corrections before the splitting is taken as diverging
        const MAX_CORRECTIONS: usize = 50;
        let mut previous_change = f64::INFINITY;
        let mut previous = u0;
        for _ in 0..MAX_CORRECTIONS {
            let q: Vec<f64> = self.candidates.iter().map(|&a| g0[a] + defect[a]).collect();
            let mut w = self.w.clone();
            for (i, &a) in self.candidates.iter().enumerate() {
                w[(i, i)] += self.nodes[a].compliance;
            }
            let lambda_scale = (0..q.len()).map(|i| w[(i, i)]).fold(0.0f64, f64::max);
            let solution = solve_lcp(
                &w,
                &q,
                &self.active,
                tolerance,
                1e-14 * tolerance / lambda_scale.max(f64::MIN_POSITIVE),
            )
            .map_err(Error::LinearSolver)?;
            self.active_set_iterations += solution.iterations;
            self.active = solution.active;
            history.extend(solution.history);
            let mut rhs = b.clone();
            let mut forces = vec![0.0; self.nodes.len()];
            for (i, &a) in self.candidates.iter().enumerate() {
                forces[a] = solution.lambda[i];
                self.add_column(a, solution.lambda[i], &mut rhs);
            }
            // from the last pass's displacements: its forces differ by
            // the defect's correction only
            let mut u = previous;
            self.solve_from(&rhs, &mut u)?;
            previous = u.clone();
            let g = self.gaps(problem, t, &u);
            let mut change = 0.0f64;
            for (i, &a) in self.candidates.iter().enumerate() {
                let predicted = g0[a]
                    + (0..self.candidates.len())
                        .map(|j| self.w[(i, j)] * solution.lambda[j])
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
                return Ok((u, forces));
            }
            self.grow(&entering)?;
        }
        Err(Error::LinearSolver(format!(
            "the condensed contact forces did not settle in {MAX_CORRECTIONS} corrections of \
             the flexibility; run with [solver] linear = \"ldlt\""
        )))
    }
}
