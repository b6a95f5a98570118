//! A contact interface between a surface of the body (its nodes are the
//! secondary nodes) and a rigid obstacle that may translate with an
//! amplitude: the node-to-surface assembly of the contact residual and
//! tangent through a [`NormalLaw`].
//!
//! Unknowns: the displacement of each secondary node and, for the laws with
//! a multiplier ([`NormalLaw::has_multiplier_dof`]), one scaled multiplier
//! `λ` per node, numbered after all displacements (global index
//! `3N + multiplier_offset + i`). Per node the contribution is
//! `r_u += ∂(A_s Φ)/∂x_s = −A_s t n`, `r_λ += ∂(A_s Φ)/∂λ`, and the 4×4
//! tangent block of the law (formulation note §2.1).

use super::laws::{GapGeometry, NodeContactState, NodeContribution, NormalLaw};
use super::obstacle::RigidObstacle;
use crate::assembly::pattern::SparsityPattern;
use crate::problem::Amplitude;
use nalgebra::Vector3;

/// One secondary surface against one rigid obstacle.
#[derive(Clone, Debug)]
pub struct ContactInterface {
    /// Name for reports (the case file's `contact[i].name`).
    pub name: String,
    /// The secondary surface set.
    pub surface: String,
    /// Secondary nodes (sorted mesh node indices).
    pub nodes: Vec<usize>,
    /// Tributary reference area `A_s` of each secondary node.
    pub areas: Vec<f64>,
    /// The obstacle in its initial position.
    pub obstacle: RigidObstacle,
    /// Rigid translation of the obstacle: `motion · amplitude(t)`.
    pub motion: Vector3<f64>,
    pub amplitude: Amplitude,
    /// Enforcement of the normal constraint, with the interface's parameters.
    pub law: NormalLaw,
    /// Per-node factors on the law's parameters (empty: 1 everywhere). The
    /// automatic parameters use `E/h_s` with the node's own size
    /// `h_s = √A_s`, so that a locally refined surface gets locally stiffer
    /// enforcement.
    pub node_scale: Vec<f64>,
    /// Index of this interface's first multiplier among all multipliers.
    pub multiplier_offset: usize,
    /// A representative contact element size (for reports and tolerances).
    pub element_size: f64,
}

/// What one node of an interface looks like in a state, for output.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct NodeReport {
    pub gap: f64,
    pub pressure: f64,
    pub active: bool,
    pub force: [f64; 3],
}

impl ContactInterface {
    /// The law of secondary node `i` (the interface's law with the node's
    /// parameter factor).
    pub fn law_at(&self, i: usize) -> NormalLaw {
        let f = self.node_scale.get(i).copied().unwrap_or(1.0);
        match self.law {
            NormalLaw::Penalty { epsilon } => NormalLaw::Penalty {
                epsilon: epsilon * f,
            },
            NormalLaw::Uzawa { epsilon } => NormalLaw::Uzawa {
                epsilon: epsilon * f,
            },
            NormalLaw::Rockafellar { p, k } => NormalLaw::Rockafellar { p: p * f, k: k * f },
            NormalLaw::Slack { p, k } => NormalLaw::Slack { p: p * f, k: k * f },
        }
    }

    /// Number of multiplier unknowns this interface adds.
    pub fn num_multipliers(&self) -> usize {
        if self.law.has_multiplier_dof() {
            self.nodes.len()
        } else {
            0
        }
    }

    /// The node lists coupled to each multiplier (one node each), for the
    /// sparsity pattern.
    pub fn multiplier_couplings(&self) -> Vec<Vec<usize>> {
        (0..self.num_multipliers())
            .map(|i| vec![self.nodes[i]])
            .collect()
    }

    /// The obstacle's rigid translation at pseudo-time `t`.
    pub fn translation_at(&self, t: f64) -> Vector3<f64> {
        self.motion * self.amplitude.value(t)
    }

    /// Gap geometry of secondary node `i` at unknowns `x` against the
    /// obstacle translated by `translation`: the point is moved back by the
    /// translation and projected on the stored obstacle (no copy of a
    /// triangulated surface and its tree), then the closest point moved
    /// forward again; gap, normal and curvature are unchanged by it.
    pub fn gap_geometry(
        &self,
        reference: &[[f64; 3]],
        translation: &Vector3<f64>,
        x: &[f64],
        i: usize,
    ) -> GapGeometry {
        let s = self.nodes[i];
        let position =
            Vector3::from(reference[s]) + Vector3::new(x[3 * s], x[3 * s + 1], x[3 * s + 2]);
        let p = self.obstacle.project(&(position - translation));
        GapGeometry {
            signed_gap: p.gap,
            normal: p.normal,
            hessian: p.curvature,
        }
    }

    /// The node's state with its multiplier taken from the unknowns `x`
    /// where the law has a multiplier dof.
    pub fn node_state(
        &self,
        states: &[NodeContactState],
        x: &[f64],
        first_multiplier: usize,
        i: usize,
    ) -> NodeContactState {
        let mut state = states[i];
        if self.law.has_multiplier_dof() {
            state.lambda = x[first_multiplier + self.multiplier_offset + i];
        }
        state
    }

    /// Add the contact residual (and tangent) at pseudo-time `t` and
    /// unknowns `x`, with the per-node states `states`. `first_multiplier`
    /// is `3N`. Returns the per-node report.
    #[allow(clippy::too_many_arguments)]
    pub fn assemble(
        &self,
        reference: &[[f64; 3]],
        t: f64,
        x: &[f64],
        states: &[NodeContactState],
        first_multiplier: usize,
        residual: &mut [f64],
        mut tangent: Option<(&SparsityPattern, &mut [f64])>,
    ) -> Vec<NodeReport> {
        let translation = self.translation_at(t);
        let mut reports = Vec::with_capacity(self.nodes.len());
        for (i, (&s, &area)) in self.nodes.iter().zip(&self.areas).enumerate() {
            let gap = self.gap_geometry(reference, &translation, x, i);
            let state = self.node_state(states, x, first_multiplier, i);
            let c: NodeContribution = self.law_at(i).contribution(area, &gap, &state);
            for d in 0..3 {
                residual[3 * s + d] += c.r_u[d];
            }
            let multiplier = self
                .law
                .has_multiplier_dof()
                .then_some(first_multiplier + self.multiplier_offset + i);
            if let Some(m) = multiplier {
                residual[m] += c.r_lambda;
            }
            if let Some((pattern, k)) = tangent.as_mut() {
                if let Some(columns) = pattern.block_columns(s, s) {
                    for (j, col) in columns.iter().enumerate() {
                        for r in 0..3 {
                            k[col + r] += c.k_uu[(r, j)];
                        }
                    }
                }
                if multiplier.is_some() {
                    let m = self.multiplier_offset + i;
                    if let Some(e) = pattern.multiplier_entries(m, s) {
                        for d in 0..3 {
                            k[e.node_rows[d]] += c.k_ulambda[d];
                            k[e.multiplier_row[d]] += c.k_ulambda[d];
                        }
                    }
                    k[pattern.multiplier_diagonal(m)] += c.k_lambdalambda;
                }
            }
            let f = gap.normal * (area * c.pressure);
            reports.push(NodeReport {
                gap: gap.signed_gap,
                pressure: c.pressure,
                active: c.active,
                force: [f[0], f[1], f[2]],
            });
        }
        reports
    }

    /// Carry the per-node states along a Newton step `dx` taken from `x`
    /// (the back-substitution of the slack law's local unknowns; nothing
    /// for the other laws, whose multipliers live in `x`).
    pub fn advance_states(
        &self,
        reference: &[[f64; 3]],
        t: f64,
        x: &[f64],
        dx: &[f64],
        first_multiplier: usize,
        states: &mut [NodeContactState],
    ) {
        if !matches!(self.law, NormalLaw::Slack { .. }) {
            return;
        }
        let translation = self.translation_at(t);
        for i in 0..self.nodes.len() {
            let s = self.nodes[i];
            let gap = self.gap_geometry(reference, &translation, x, i);
            let mut state = self.node_state(states, x, first_multiplier, i);
            let du = Vector3::new(dx[3 * s], dx[3 * s + 1], dx[3 * s + 2]);
            let dlambda = dx[first_multiplier + self.multiplier_offset + i];
            self.law_at(i)
                .apply_increment(self.areas[i], &gap, &mut state, &du, dlambda);
            states[i] = state;
        }
    }
}
