//! The contact of one round of the frictional condensed problem, linearised
//! at a point `x̂` of the unknowns: per secondary node its
//! [`ConstraintRow`] (gap `ĝ`, normal `n̂`, lever `B̂`) and [`SlipRow`]
//! (slip offset `d̂` from the committed anchor, committed traction), so
//! that the node's relative motion `v = B̂ u`, its gap and its slip are
//!
//! ```text
//! g(u) ≈ ĝ + n̂·B̂ (u − x̂),   d(u) ≈ d̂ + B̂ (u − x̂).
//! ```
//!
//! Against rigid planes these are exact for every `x̂` (`B = I`, a fixed
//! normal) and `x̂ = 0`. Between bodies the projections move with `u`,
//! against a rigid sphere or cylinder the normal (`B = I`):
//! `x̂` is the last answer, and the rounds repeat until the answer is the
//! point it was linearised at ([`Linearisation::defect`]), where every
//! value the node laws read is the exact one.

use super::{ContactState, Problem};
use crate::contact::interface::{ConstraintRow, ContactInterface, SlipRow};
use crate::contact::mortar::Derivatives;
use nalgebra::Vector3;

/// The contact linearised at a point (module docs).
pub(super) struct Linearisation {
    /// Per interface, per secondary node.
    pub(super) rows: Vec<Vec<Option<ConstraintRow>>>,
    pub(super) slips: Vec<Vec<Option<SlipRow>>>,
    /// `x̂`; `None`: `x̂ = 0` against rigid planes (the rows taken without
    /// the nodes' states, exact everywhere).
    pub(super) point: Option<Vec<f64>>,
}

/// `B_d x = x_s,d − Σ w_i x_{p_i},d`, row `d` of the lever applied to `x`.
pub(super) fn lever_product(row: &ConstraintRow, d: usize, x: &[f64]) -> f64 {
    row.lever_row(d).iter().map(|&(i, w)| w * x[i]).sum()
}

/// `B x` of a node, all three rows.
fn lever_vector(row: &ConstraintRow, x: &[f64]) -> Vector3<f64> {
    Vector3::from_fn(|d, _| lever_product(row, d, x))
}

impl Linearisation {
    /// Against rigid planes: the rows at `x̂ = 0`, time `t` (the slip from
    /// the committed histories in `states`).
    pub(super) fn at_rest(problem: &Problem, t: f64, states: &ContactState) -> Self {
        let zero = vec![0.0; problem.num_unknowns()];
        let rows = super::constraint_rows(problem, t, &zero, Derivatives::With);
        let slips = Self::slips(problem, t, &zero, states, Derivatives::With);
        Linearisation {
            rows,
            slips,
            point: None,
        }
    }

    /// Between bodies: the rows at `x̂ = x`, time `t`, each node on the
    /// primary triangle kept in `kept` (as Newton keeps it), which takes
    /// the row's triangle. Dual mortar's rows and weighted slips without
    /// their derivatives (the rounds read values and levers only).
    pub(super) fn at(problem: &Problem, t: f64, x: &[f64], kept: &mut ContactState) -> Self {
        let reference = &problem.model.mesh.nodes;
        let without = Derivatives::Without;
        let rows: Vec<Vec<Option<ConstraintRow>>> = (problem.contacts.iter().enumerate())
            .map(|(ci, c)| {
                let states = &mut kept.interfaces[ci];
                let rows = c.constraint_rows_with(reference, t, x, Some(states), without, None);
                for (state, row) in states.iter_mut().zip(&rows) {
                    if let Some(row) = row {
                        state.move_to_facet(row.facet);
                    }
                }
                rows
            })
            .collect();
        let slips = Self::slips(problem, t, x, kept, without);
        Linearisation {
            rows,
            slips,
            point: Some(x.to_vec()),
        }
    }

    fn slips(
        problem: &Problem,
        t: f64,
        x: &[f64],
        states: &ContactState,
        derivatives: Derivatives,
    ) -> Vec<Vec<Option<SlipRow>>> {
        let reference = &problem.model.mesh.nodes;
        let slips = |(ci, c): (usize, &ContactInterface)| {
            c.slip_rows(reference, t, x, &states.interfaces[ci], derivatives)
        };
        problem.contacts.iter().enumerate().map(slips).collect()
    }

    /// `(ĝ − n̂·B̂x̂, d̂ − B̂x̂)` of node `index` of `interface`: its gap and
    /// slip offset at `u = 0` of the linearisation; `None` without a
    /// primary in reach.
    pub(super) fn at_zero(&self, interface: usize, index: usize) -> Option<(f64, Vector3<f64>)> {
        let row = self.rows[interface][index].as_ref()?;
        let slip = self.slips[interface][index].as_ref()?;
        Some(match &self.point {
            None => (row.gap, slip.offset),
            Some(x) => {
                let motion = lever_vector(row, x);
                (row.gap - row.normal.dot(&motion), slip.offset - motion)
            }
        })
    }

    /// The part of node `index`'s relative motion `v_d = B_d u` that is not
    /// its column's unknown: on a component with a column (`columned[d]`)
    /// the prescribed entries `Σ w_i ū_i` (`ū` in `prescribed`); on one
    /// without, every entry (the free ones at `x̂`: between bodies a
    /// primary node off a symmetry plane the node lies on).
    pub(super) fn fixed_motion(
        &self,
        interface: usize,
        index: usize,
        columned: [bool; 3],
        constrained: &[bool],
        prescribed: &[f64],
    ) -> Vector3<f64> {
        let Some(row) = &self.rows[interface][index] else {
            return Vector3::zeros();
        };
        let at = |i: usize| match (&self.point, constrained[i]) {
            (_, true) => prescribed[i],
            (Some(x), false) => x[i],
            (None, false) => 0.0,
        };
        Vector3::from_fn(|d, _| {
            (row.lever_row(d).iter())
                .filter(|&&(i, _)| !columned[d] || constrained[i])
                .map(|&(i, w)| w * at(i))
                .sum()
        })
    }

    /// How far `next`, the rows at the answer `u` of this linearisation,
    /// is from it over the `nodes` (interface, index, whether it carries a
    /// force): the largest change of a normal or of a primary weight (of
    /// the loaded nodes), and the largest error of the linearised gap (all)
    /// and slip offset (loaded) at `u`, in lengths. `None` where a node
    /// lost its primary.
    pub(super) fn defect(
        &self,
        next: &Linearisation,
        u: &[f64],
        nodes: impl Iterator<Item = (usize, usize, bool)>,
    ) -> Option<(f64, f64)> {
        let (mut geometry, mut length) = (0.0f64, 0.0f64);
        for (ci, i, loaded) in nodes {
            let (old, new) = (self.rows[ci][i].as_ref()?, next.rows[ci][i].as_ref()?);
            let (gap, offset) = self.at_zero(ci, i)?;
            let motion = lever_vector(old, u);
            length = length.max((new.gap - gap - old.normal.dot(&motion)).abs());
            if !loaded {
                continue;
            }
            let slip = next.slips[ci][i].as_ref()?;
            length = length.max((slip.offset - offset - motion).amax());
            geometry = geometry.max((new.normal - old.normal).amax());
            geometry = geometry.max(weight_change(old, new));
        }
        Some((geometry, length))
    }
}

/// The largest change of a primary weight between two rows of one node
/// (a weight on a node of only one of them against zero).
fn weight_change(old: &ConstraintRow, new: &ConstraintRow) -> f64 {
    let weight = |row: &ConstraintRow, p: usize| {
        (row.primary.iter())
            .filter(|&&(q, _)| q == p)
            .map(|&(_, w)| w)
            .sum::<f64>()
    };
    (old.primary.iter().chain(new.primary.iter()))
        .map(|&(p, _)| (weight(old, p) - weight(new, p)).abs())
        .fold(0.0, f64::max)
}
