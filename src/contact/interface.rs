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
//! tangent block of the law (formulation note §2.1). With Coulomb friction
//! ([`friction`]) a closed node adds `r_u += −A_s t_T` and the
//! nonsymmetric blocks `−A_s ∂t_T/∂x_s`, `−A_s ∂t_T/∂λ`.

use super::friction::{self, ContactStatus, Coulomb, NormalPressure, TangentialResponse};
use super::laws::{GapGeometry, NodeContactState, NodeContribution, NormalLaw};
use super::obstacle::RigidObstacle;
use super::primary::PrimarySurface;
use crate::assembly::pattern::SparsityPattern;
use crate::problem::Amplitude;
use nalgebra::Vector3;

/// What the secondary nodes of an interface touch.
#[derive(Clone, Debug)]
pub enum Primary {
    /// A rigid obstacle, translated by the interface's `motion · amplitude(t)`.
    Rigid(RigidObstacle),
    /// A surface of another (deformable) body of the mesh.
    Surface(PrimarySurface),
}

/// One secondary surface against a rigid obstacle or a primary surface.
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
    /// The rigid obstacle in its initial position, or the primary surface.
    pub primary: Primary,
    /// Rigid translation of the obstacle: `motion · amplitude(t)`.
    pub motion: Vector3<f64>,
    pub amplitude: Amplitude,
    /// Enforcement of the normal constraint, with the interface's parameters.
    pub law: NormalLaw,
    /// Coulomb friction (`None`: frictionless).
    pub friction: Option<Coulomb>,
    /// Per-node factors on the tangential penalty (empty: 1 everywhere);
    /// the automatic default follows [`node_scale`](Self::node_scale).
    pub tangential_scale: Vec<f64>,
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
    /// Open, stick (or closed without friction), slip.
    pub status: ContactStatus,
    /// Normal force on the body, `A_s t_N n`.
    pub force: [f64; 3],
    /// Tangential traction `t_T` (zero without friction).
    pub tangential_traction: [f64; 3],
    /// The primary triangle the node is projected on (deformable
    /// interfaces only).
    pub facet: Option<usize>,
}

/// One node evaluated in a state: geometry, normal law, tangential response.
struct NodeEvaluation {
    gap: GapGeometry,
    relative_position: Vector3<f64>,
    normal: NodeContribution,
    /// `None` when the node is open; a zero traction in stick when the
    /// interface is frictionless.
    tangential: Option<TangentialResponse>,
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

    /// The friction law of secondary node `i` (its tangential penalty
    /// with the node's factor).
    pub fn friction_at(&self, i: usize) -> Option<Coulomb> {
        let f = self.tangential_scale.get(i).copied().unwrap_or(1.0);
        self.friction.map(|c| Coulomb {
            tangential_penalty: c.tangential_penalty * f,
            ..c
        })
    }

    /// Whether friction makes the tangent nonsymmetric.
    pub fn has_friction(&self) -> bool {
        self.friction.is_some_and(|c| c.coefficient > 0.0)
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
            .map(|i| self.coupled_nodes(i))
            .collect()
    }

    /// Secondary node `i` with the primary nodes it may touch in this
    /// increment (itself alone against a rigid obstacle): one group of the
    /// sparsity pattern.
    pub fn coupled_nodes(&self, i: usize) -> Vec<usize> {
        let mut nodes = vec![self.nodes[i]];
        if let Primary::Surface(p) = &self.primary {
            nodes.extend(p.candidate_nodes(i));
        }
        nodes
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
        self.geometry_at(&self.relative_position(reference, translation, x, i))
    }

    /// The signed gap of every secondary node at time `t` and unknowns `x`
    /// (the search margin for a node without primary candidates), with the
    /// nodes' states where given (a deformable interface then uses each
    /// node's kept triangle, as the assembly does).
    pub fn gaps(
        &self,
        reference: &[[f64; 3]],
        t: f64,
        x: &[f64],
        states: Option<&[NodeContactState]>,
    ) -> Vec<f64> {
        let translation = self.translation_at(t);
        (0..self.nodes.len())
            .map(|i| match &self.primary {
                Primary::Rigid(_) => self.gap_geometry(reference, &translation, x, i).signed_gap,
                Primary::Surface(p) => {
                    let state = states.map_or_else(
                        || NodeContactState::initial(&self.law_at(i), p.margin),
                        |s| s[i],
                    );
                    self.surface_node(p, reference, x, i, &state)
                        .map_or(p.margin, |n| n.gap.gap)
                }
            })
            .collect()
    }

    /// Position of secondary node `i` relative to the obstacle's
    /// translation, `x_s − c(t)`: the point projected on the stored
    /// obstacle, and where friction measures slip from.
    pub fn relative_position(
        &self,
        reference: &[[f64; 3]],
        translation: &Vector3<f64>,
        x: &[f64],
        i: usize,
    ) -> Vector3<f64> {
        let s = self.nodes[i];
        Vector3::from(reference[s]) + Vector3::new(x[3 * s], x[3 * s + 1], x[3 * s + 2])
            - translation
    }

    fn geometry_at(&self, relative_position: &Vector3<f64>) -> GapGeometry {
        let Primary::Rigid(obstacle) = &self.primary else {
            unreachable!("rigid-obstacle geometry asked of a deformable interface")
        };
        let p = obstacle.project(relative_position);
        GapGeometry {
            signed_gap: p.gap,
            normal: p.normal,
            hessian: p.curvature,
        }
    }

    /// The states of the nodes when the interface is set up at unknowns `x`
    /// (time 0): the normal law's initial state, friction anchored where the
    /// node is.
    pub fn initial_states(&self, reference: &[[f64; 3]], x: &[f64]) -> Vec<NodeContactState> {
        if let Primary::Surface(p) = &self.primary {
            return self.initial_surface_states(p, reference, x);
        }
        let translation = self.translation_at(0.0);
        (0..self.nodes.len())
            .map(|i| {
                let relative = self.relative_position(reference, &translation, x, i);
                let g = self.geometry_at(&relative).signed_gap;
                NodeContactState {
                    friction: friction::FrictionHistory::at(relative),
                    ..NodeContactState::initial(&self.law_at(i), g)
                }
            })
            .collect()
    }

    /// Node `i` in state `state` (multiplier already taken from the
    /// unknowns) at `relative_position`.
    fn evaluate(
        &self,
        i: usize,
        relative_position: Vector3<f64>,
        state: &NodeContactState,
    ) -> NodeEvaluation {
        let gap = self.geometry_at(&relative_position);
        let normal = self.law_at(i).contribution(self.areas[i], &gap, state);
        // a closed node at zero pressure sticks at its anchor (the return
        // mapping with a zero bound): its tangential stiffness holds a body
        // whose only tangential support is friction before the load arrives
        let tangential = normal.active.then(|| match self.friction_at(i) {
            Some(coulomb) => friction::return_map(
                &coulomb,
                &state.friction,
                &relative_position,
                &gap,
                &NormalPressure {
                    value: normal.pressure,
                    gradient: normal.pressure_gradient,
                    multiplier_derivative: normal.pressure_multiplier_derivative,
                },
            ),
            None => TangentialResponse {
                status: ContactStatus::Stick,
                ..TangentialResponse::none()
            },
        });
        NodeEvaluation {
            gap,
            relative_position,
            normal,
            tangential,
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
        if let Primary::Surface(p) = &self.primary {
            return self.assemble_on_surface(
                p,
                reference,
                x,
                states,
                first_multiplier,
                residual,
                tangent,
            );
        }
        let translation = self.translation_at(t);
        let mut reports = Vec::with_capacity(self.nodes.len());
        for (i, (&s, &area)) in self.nodes.iter().zip(&self.areas).enumerate() {
            let state = self.node_state(states, x, first_multiplier, i);
            let relative = self.relative_position(reference, &translation, x, i);
            let NodeEvaluation {
                gap,
                normal: c,
                tangential,
                ..
            } = self.evaluate(i, relative, &state);
            let t_t = tangential.unwrap_or_else(TangentialResponse::none);
            // r_u = −A_s (t_N n + t_T); K_uu = K_N − A_s ∂t_T/∂x_s
            let r_u = c.r_u - area * t_t.traction;
            let k_uu = c.k_uu - area * t_t.traction_gradient;
            for d in 0..3 {
                residual[3 * s + d] += r_u[d];
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
                            k[col + r] += k_uu[(r, j)];
                        }
                    }
                }
                if multiplier.is_some() {
                    let m = self.multiplier_offset + i;
                    if let Some(e) = pattern.multiplier_entries(m, s) {
                        for d in 0..3 {
                            // ∂r_u/∂λ carries friction's coupling; ∂r_λ/∂u does not
                            k[e.node_rows[d]] +=
                                c.k_ulambda[d] - area * t_t.traction_multiplier_derivative[d];
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
                status: t_t.status,
                force: [f[0], f[1], f[2]],
                tangential_traction: [t_t.traction[0], t_t.traction[1], t_t.traction[2]],
                facet: None,
            });
        }
        reports
    }

    /// Commit the friction history of every node after an increment
    /// converged at time `t` and unknowns `x` (formulation note §3): the
    /// traction, status and accumulated slip of the return mapping there,
    /// and the new anchor. Frictionless nodes record their status only.
    pub fn commit_history(
        &self,
        reference: &[[f64; 3]],
        t: f64,
        x: &[f64],
        first_multiplier: usize,
        states: &mut [NodeContactState],
    ) {
        if let Primary::Surface(p) = &self.primary {
            return self.commit_surface_history(p, reference, x, first_multiplier, states);
        }
        let translation = self.translation_at(t);
        for i in 0..self.nodes.len() {
            let state = self.node_state(states, x, first_multiplier, i);
            let relative = self.relative_position(reference, &translation, x, i);
            let e = self.evaluate(i, relative, &state);
            states[i].friction =
                friction::commit(&state.friction, e.tangential.as_ref(), e.relative_position);
        }
    }

    /// Turn the symmetric part of the assembled tangent, `values`, into the
    /// preconditioner of the nonsymmetric frictional solve: at every
    /// closed node with friction, replace `sym(−A_s ∂t_T/∂(x_s, λ))` by the
    /// stick stiffness `sym(−A_s J*)` (the trial derivative, `A_s ε_T T` on
    /// a plane). Slipping nodes then keep a positive tangential stiffness,
    /// where the symmetrised slip tangent has none along the slip direction
    /// and an indefinite coupling to the normal: the preconditioner stays a
    /// quasi-definite saddle matrix that the sign-aware LDLᵀ factorises, and
    /// differs from the tangent only in the contact blocks (so GMRES has
    /// little left to resolve; should its LDLᵀ still break down, Newton
    /// solves with the sparse LU). A deformable interface shifts to
    /// `A_s ε_T Bᵀ T B` at the current projection
    /// (`ContactInterface::shift_surface_to_stick`). Entries of
    /// `constrained` dofs are skipped.
    #[allow(clippy::too_many_arguments)]
    pub fn shift_to_stick_preconditioner(
        &self,
        reference: &[[f64; 3]],
        t: f64,
        x: &[f64],
        states: &[NodeContactState],
        first_multiplier: usize,
        constrained: &[bool],
        pattern: &SparsityPattern,
        values: &mut [f64],
    ) {
        if self.friction.is_none() {
            return;
        }
        if let Primary::Surface(p) = &self.primary {
            return self.shift_surface_to_stick(
                p,
                reference,
                x,
                states,
                first_multiplier,
                constrained,
                pattern,
                values,
            );
        }
        let translation = self.translation_at(t);
        for (i, (&s, &area)) in self.nodes.iter().zip(&self.areas).enumerate() {
            let state = self.node_state(states, x, first_multiplier, i);
            let relative = self.relative_position(reference, &translation, x, i);
            let Some(r) = self.evaluate(i, relative, &state).tangential else {
                continue;
            };
            let consistent = -area * r.traction_gradient;
            let stick = -area * r.trial_gradient;
            let shift = 0.5 * ((stick - consistent) + (stick - consistent).transpose());
            if let Some(columns) = pattern.block_columns(s, s) {
                for (j, col) in columns.iter().enumerate() {
                    for q in 0..3 {
                        if !constrained[3 * s + q] && !constrained[3 * s + j] {
                            values[col + q] += shift[(q, j)];
                        }
                    }
                }
            }
            if self.law.has_multiplier_dof() {
                let m = self.multiplier_offset + i;
                if let Some(e) = pattern.multiplier_entries(m, s) {
                    for d in 0..3 {
                        if !constrained[3 * s + d] {
                            // sym added ½(−A_s ∂t_T/∂λ) to both entries: remove it
                            let half = -0.5 * area * r.traction_multiplier_derivative[d];
                            values[e.node_rows[d]] -= half;
                            values[e.multiplier_row[d]] -= half;
                        }
                    }
                }
            }
        }
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
        if let Primary::Surface(p) = &self.primary {
            return self.advance_surface_states(p, reference, x, dx, first_multiplier, states);
        }
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
