//! The frictionless condensation of a [`Problem`]: its contact as the
//! columns of `E` (one per secondary node, the node driver's `∇g`, with a
//! penalty law's compliance), its constant stiffness and load, and its
//! gaps, handed to the algebra of [`Flexibility`].

use super::{constraint_rows, ContactState, Problem};
use crate::contact::interface::ConstraintRow;
use crate::contact::laws::NormalEnforcement;
use crate::contact::mortar::Derivatives;
use crate::solve::condensed::flexibility::{Column, Flexibility, Stiffness};
use crate::solve::linear::Precision;
use crate::solve::newton::IterationRecord;
use crate::solve::settings::LinearMethod;
use crate::{Error, Result};
use std::sync::Arc;

/// The secondary node a column of `E` belongs to.
pub(super) struct ContactNode {
    pub(super) interface: usize,
    /// Index among the interface's nodes.
    pub(super) index: usize,
}

/// The condensed solver of a run: the [`Flexibility`] and the owner of
/// each of its columns.
pub(super) struct Condensation {
    pub(super) flexibility: Flexibility,
    pub(super) nodes: Vec<ContactNode>,
}

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

/// The column of `E` of a node with constraint row `row` whose law's
/// converged state is `law`: the direction its normal force acts along,
/// `∇g = Bᵀn` (dual mortar: Popp's lever at fixed `D`, `M`, `n`,
/// [`ConstraintRow::force_direction`]), with the compliance `1/(A ε)` of
/// a penalty (0 for an exact law).
pub(super) fn normal_column(law: NormalEnforcement, row: &ConstraintRow) -> Column {
    let compliance = match law {
        NormalEnforcement::Penalty { epsilon } => 1.0 / (row.area * epsilon),
        NormalEnforcement::Exact { .. } => 0.0,
    };
    Column {
        entries: row.force_direction(),
        compliance,
    }
}

impl Condensation {
    /// The frictionless condensation: one column per secondary node of
    /// every interface with a row at `u = 0` (dual mortar has none beyond
    /// a node's margin), its gap gradient `∇g` from the node driver (the
    /// gaps are affine, [`super::not_applicable`]) and, for a penalty law,
    /// the compliance `1/(A ε)`; `K̃` unshifted, the columns of the nearest
    /// [`TRAILING_FRACTION`] of the contact nodes ordered last (of the
    /// nodes, not of the columns: on examples/hertz mortar has 611
    /// columns for 925 nodes, and half of them left nodes that close off
    /// the block, their columns of `W` by solves).
    pub(super) fn new(problem: &Problem) -> Result<Self> {
        let (mut nodes, mut columns) = (Vec::new(), Vec::new());
        let zero = vec![0.0; problem.num_unknowns()];
        let rows = constraint_rows(problem, 0.0, &zero, Derivatives::Without);
        for (ci, rows) in rows.iter().enumerate() {
            let c = problem.contacts.interface(ci);
            for (i, row) in rows.iter().enumerate() {
                let Some(row) = row else { continue };
                nodes.push(ContactNode {
                    interface: ci,
                    index: i,
                });
                columns.push(normal_column(c.law_at(i).converged(), row));
            }
        }
        // the nearest half of the contact nodes, not of the columns: dual
        // mortar gives no column to a node beyond its margin
        let contact_nodes: usize = problem.contacts.iter().map(|c| c.nodes.len()).sum();
        let fraction = TRAILING_FRACTION * contact_nodes as f64 / columns.len().max(1) as f64;
        Self::factorise(problem, nodes, columns, &[], fraction, true)
    }

    /// Assemble `K` at `u = 0` (its lower triangle) and factorise `K̃`
    /// once ([`Flexibility::factorise`]: prescribed rows and columns a
    /// scaled identity `s`, plus `ρ = s` on the diagonal of the `shifted`
    /// dofs); `columns` are those of `E`, owned by `nodes`, the nearest
    /// `fraction` of them ordered last. The assembly and the ordering with
    /// its symbolic analysis (which read only the pattern) run side by
    /// side on the run's threads, the ordering's nested dissection mostly
    /// done before ([`Problem::dissection`]). In f32 (from
    /// [`MIXED_PRECISION_UNKNOWNS`], or `linear = "mixed"`) only where
    /// `single_allowed`: the frictionless solve corrects the contact
    /// forces for the f32 `W̃` ([`Flexibility::solve_increment`]; between
    /// bodies on the block, the rounds correct the block's response,
    /// `pairs::PairCondensation::corrected`); the
    /// frictional one has no such correction and factorises in f64 (on a
    /// 10 k-dof floating block the f32 `Ŵ` left a residual of 5.7e-7).
    pub(super) fn factorise(
        problem: &Problem,
        nodes: Vec<ContactNode>,
        columns: Vec<Column>,
        shifted: &[usize],
        fraction: f64,
        single_allowed: bool,
    ) -> Result<Self> {
        let mut constrained = problem.constrained_dofs();
        let dofs = problem.model.num_dofs();
        constrained[dofs..].iter_mut().for_each(|c| *c = true);
        let order = Self::nearest_first(problem, &nodes);
        let trailing = Flexibility::trailing_dofs(&columns, &order, &constrained, fraction);
        Self::factorise_on(problem, nodes, columns, shifted, trailing, single_allowed)
    }

    /// [`Self::factorise`] with the `trailing` unknowns given.
    pub(super) fn factorise_on(
        problem: &Problem,
        nodes: Vec<ContactNode>,
        columns: Vec<Column>,
        shifted: &[usize],
        trailing: Vec<usize>,
        single_allowed: bool,
    ) -> Result<Self> {
        let pattern = &problem.model.pattern;
        let dimension = pattern.dimension();
        let mut constrained = problem.constrained_dofs();
        let dofs = problem.model.num_dofs();
        constrained[dofs..].iter_mut().for_each(|c| *c = true);
        let lower = problem.model.lower_triangle();
        let dissection = problem.dissection.as_ref();
        let (k, analysis) = rayon::join(
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
            || Flexibility::analyse(pattern, &lower, trailing, &constrained, dissection),
        );
        let (k, analysis) = (k?, analysis?);
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
        let stiffness = Stiffness {
            lower,
            k,
            dofs,
            constrained,
        };
        let flexibility = Flexibility::factorise(stiffness, columns, shifted, analysis, precision)?;
        Ok(Condensation { flexibility, nodes })
    }

    /// The columns ordered by their node's gap at `u = 0`, the smallest
    /// over the start and the steps' ends first.
    fn nearest_first(problem: &Problem, nodes: &[ContactNode]) -> Vec<usize> {
        let zero = vec![0.0; problem.num_unknowns()];
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
        order
    }

    /// `b(t)`: `f_ext(t) − K_fp ū(t)` on the free dofs, `s ū(t)` on the
    /// prescribed ones, 0 on the multipliers.
    pub(super) fn load(&self, problem: &Problem, t: f64) -> Vec<f64> {
        let mut prescribed = vec![0.0; self.flexibility.constrained.len()];
        problem.apply_prescribed(t, &mut prescribed);
        let dofs = problem.model.num_dofs();
        let f = problem.external_force(t, &prescribed[..dofs], None);
        self.flexibility.load(&prescribed, &f)
    }

    /// The gap of every column's node at unknowns `x`, time `t` (on the
    /// primary triangles kept in `states`, where given).
    pub(super) fn gaps(
        nodes: &[ContactNode],
        problem: &Problem,
        t: f64,
        x: &[f64],
        states: Option<&ContactState>,
    ) -> Vec<f64> {
        let reference = &problem.model.mesh.nodes;
        let per_interface: Vec<Vec<f64>> = (problem.contacts.iter().enumerate())
            .map(|(ci, c)| c.gaps(reference, t, x, states.map(|s| &s.interfaces[ci][..])))
            .collect();
        nodes
            .iter()
            .map(|c| per_interface[c.interface][c.index])
            .collect()
    }

    /// The displacements and contact forces (per node, `λ_a = A_a t_N`) at
    /// time `t` ([`Flexibility::solve_increment`]), the gaps on the primary
    /// triangles kept in `states` where given.
    pub(super) fn solve_increment(
        &mut self,
        problem: &Problem,
        t: f64,
        states: Option<&ContactState>,
        history: &mut Vec<IterationRecord>,
    ) -> Result<(Vec<f64>, Vec<f64>)> {
        let b = self.load(problem, t);
        let nodes = &self.nodes;
        let gaps = |u: &[f64]| Self::gaps(nodes, problem, t, u, states);
        let tolerance = 1e-12 * problem.model.size();
        self.flexibility
            .solve_increment(&b, &gaps, tolerance, history)
    }
}
