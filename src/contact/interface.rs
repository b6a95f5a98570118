//! A contact interface: a surface of the body (its nodes are the secondary
//! nodes) against a rigid obstacle that may translate with an amplitude, or
//! against a primary surface of another body; and the node driver that
//! assembles it through a [`NormalLaw`] and Coulomb [`friction`].
//!
//! Unknowns: the displacements of the nodes of each secondary node's
//! contribution and, for the laws with a multiplier
//! ([`NormalLaw::has_multiplier_dof`]), one scaled multiplier `λ` per node,
//! numbered after all displacements (global index
//! `3N + multiplier_offset + i`).
//!
//! ## The node driver
//! One loop ([`ContactInterface::for_each_node`]) visits the secondary
//! nodes: the node's state (its multiplier taken from the unknowns), then
//! its [`GapKinematics`] from the interface's [`GapProducer`] (a rigid
//! obstacle, [`RigidGap`]; a primary surface, [`SurfaceGap`]). Every
//! operation of the life cycle is that loop with its own visit: assembly
//! (the chain rule of [`kinematics`](super::kinematics), scattered by
//! [`crate::assembly::scatter`]), the commit of the friction history, the
//! stick preconditioner, the slack law's advance, the gaps, the initial
//! states and Uzawa's augmentation.

use super::friction::{
    self, ContactStatus, Coulomb, FrictionHistory, FrictionMultiplier, TangentialMultiplier,
    TangentialResponse,
};
use super::gap::GapGeometry;
use super::kinematics::{
    GapKinematics, GapProducer, NodeEvaluation, PrimaryWeights, QAllocator, SecondaryNode,
};
use super::laws::{NodeContactState, NormalLaw, Support};
use super::mortar::Derivatives;
use super::mortar_contact::{MortarGap, MortarSurfaces};
use super::mortar_rigid::MortarObstacle;
use super::obstacle::RigidObstacle;
use super::primary::PrimarySurface;
use super::rigid::RigidGap;
use super::surface_contact::SurfaceGap;
use crate::assembly::amplitude::Amplitude;
use crate::assembly::pattern::SparsityPattern;
use crate::assembly::scatter::{add_block, add_multiplier_block, add_nodal};
use nalgebra::{DefaultAllocator, Dim, OMatrix, OVector, Vector3, U3};

/// What the secondary nodes of an interface touch.
#[derive(Clone, Debug)]
pub enum Primary {
    /// A rigid obstacle, translated by the interface's `motion · amplitude(t)`.
    Rigid(RigidObstacle),
    /// A surface of another (deformable) body of the mesh.
    Surface(PrimarySurface),
    /// A surface of another body through dual mortar
    /// ([`mortar_contact`](super::mortar_contact)).
    Mortar(MortarSurfaces),
    /// A rigid obstacle through dual mortar over the secondary surface
    /// ([`mortar_rigid`](super::mortar_rigid)), translated as [`Primary::Rigid`].
    MortarRigid(Box<MortarObstacle>),
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
    /// The whole tributary area of each secondary node (`areas` before a
    /// two-pass interface halves them): what the report divides the node's
    /// force by for its pressure and traction.
    pub report_areas: Vec<f64>,
    /// The secondary surface as triangles (deformable interfaces only): the
    /// report measures the primary nodes' gaps against it
    /// ([`primary_gaps`](Self::primary_gaps)).
    pub secondary_surface: Option<PrimarySurface>,
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
    /// Friction with exact stick asked for (`[[contact]] exact_stick`);
    /// it applies where [`exact_stick`](Self::exact_stick) says.
    pub exact_stick_requested: bool,
    /// How exact stick finds its tangential multiplier (`[[contact]]
    /// friction_multiplier`): as unknowns of Newton where
    /// [`tangential_multipliers`](Self::tangential_multipliers) says.
    pub friction_multiplier: FrictionMultiplier,
    /// Each secondary node's prescribed components (empty: none), set by
    /// the problem ([`set_prescribed_axes`](Self::set_prescribed_axes)):
    /// exact stick holds the traction along a prescribed tangential axis
    /// ([`friction::HeldTangent`]).
    pub prescribed_axes: Vec<[bool; 3]>,
}

/// What one node of an interface looks like in a state, for output.
#[derive(Clone, Debug, Default, PartialEq)]
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
    /// The primary segment the node is projected on (node-to-surface
    /// only: [`GapKinematics::facet`]).
    pub facet: Option<usize>,
    /// The primary nodes the node's reaction acts on, with their weights
    /// (deformable interfaces only: [`GapKinematics::primary`]).
    pub primary: PrimaryWeights,
    /// The area the node's forces act on where the producer integrates
    /// its own ([`GapKinematics::area`]; mortar: the current `D_j`), so
    /// that `area t_T` is the tangential force assembled; `None` where it
    /// is the interface's `areas[i]`.
    pub area: Option<f64>,
}

/// Where the contact operations are evaluated: the mesh's reference
/// coordinates, pseudo-time `t`, the unknowns `x` and the global index of
/// the first multiplier (`3N`).
#[derive(Clone, Copy)]
pub struct ContactContext<'a> {
    pub reference: &'a [[f64; 3]],
    pub t: f64,
    pub x: &'a [f64],
    pub first_multiplier: usize,
}

/// Run `$body` with `$p` bound to the gap producer of `$iface` at the
/// context `$ctx` (the one dispatch on the primary kind); with
/// `$derivatives` ([`Derivatives`]) what the operation reads of a dual
/// mortar producer's rows (the other producers give their derivatives
/// always: they cost little), by default their derivatives too; with
/// `near $near` (`Option<BTreeSet<usize>>` of secondary mesh nodes) a dual
/// mortar producer between bodies has the rows of those nodes alone
/// ([`MortarGap::near`]), the others none.
macro_rules! with_producer {
    ($iface:expr, $ctx:expr, $p:ident => $body:expr) => {
        with_producer!($iface, $ctx, $crate::contact::mortar::Derivatives::With, $p => $body)
    };
    ($iface:expr, $ctx:expr, $derivatives:expr, $p:ident => $body:expr) => {
        with_producer!($iface, $ctx, $derivatives, near None, $p => $body)
    };
    ($iface:expr, $ctx:expr, $derivatives:expr, near $near:expr, $p:ident => $body:expr) => {
        match &$iface.primary {
            Primary::Rigid(obstacle) => {
                let $p = &RigidGap {
                    obstacle,
                    translation: $iface.translation_at($ctx.t),
                };
                $body
            }
            Primary::Surface(primary) => {
                let $p = &SurfaceGap { primary };
                $body
            }
            Primary::Mortar(surfaces) => {
                let $p = &MortarGap::near(surfaces, $ctx.reference, $ctx.x, $derivatives, $near);
                $body
            }
            Primary::MortarRigid(obstacle) => {
                let translation = $iface.translation_at($ctx.t);
                let $p = &obstacle.producer(&translation, $ctx.reference, $ctx.x, $derivatives);
                $body
            }
        }
    };
}

mod augmentation;
mod rows;
mod tangential;
pub use rows::{ConstraintRow, SlipRow};

impl ContactInterface {
    /// The law of secondary node `i` (the interface's law with the node's
    /// parameter factor).
    pub fn law_at(&self, i: usize) -> NormalLaw {
        let f = self.node_scale.get(i).copied().unwrap_or(1.0);
        self.law.scaled(f)
    }

    /// Number of multiplier unknowns this interface adds.
    pub fn num_multipliers(&self) -> usize {
        match (self.law.has_multiplier_dof(), self.tangential_multipliers()) {
            (false, _) => 0,
            (true, false) => self.nodes.len(),
            (true, true) => 3 * self.nodes.len(),
        }
    }

    /// The multipliers of node `i` (indices among the interface's own):
    /// its normal one, then its two tangential ones where they are
    /// unknowns; they couple to each other (one dense block).
    pub fn node_multipliers(&self, i: usize) -> Vec<usize> {
        let n = self.nodes.len();
        match self.num_multipliers() / n.max(1) {
            0 => Vec::new(),
            1 => vec![i],
            _ => vec![i, n + 2 * i, n + 2 * i + 1],
        }
    }

    /// Secondary node `i` with the primary nodes it may touch in this
    /// increment (itself alone against a rigid obstacle): one group of the
    /// sparsity pattern.
    pub fn coupled_nodes(&self, i: usize) -> Vec<usize> {
        let mut nodes = vec![self.nodes[i]];
        match &self.primary {
            Primary::Surface(p) => nodes.extend(p.candidate_nodes(i)),
            Primary::Mortar(m) => return m.coupled_nodes(i, self.nodes[i]),
            Primary::MortarRigid(m) => return m.coupled_nodes(i),
            Primary::Rigid(_) => {}
        }
        nodes
    }

    /// The groups of nodes whose displacements secondary node `i`'s
    /// contact tangent couples with each other, each one clique of the
    /// sparsity pattern: [`coupled_nodes`](Self::coupled_nodes) as one
    /// group, but frictionless dual mortar against a plane gives the node
    /// paired with each node of its faces where its lever lies on itself
    /// ([`MortarObstacle::coupled_groups`](super::mortar_rigid::MortarObstacle::coupled_groups)).
    /// Not with friction: the weighted slip's tangent reaches further
    /// (with the pairs, tests/mortar_obstacle_friction.rs's stick on Tet10
    /// faces chattered).
    pub fn coupled_groups(&self, i: usize) -> Vec<Vec<usize>> {
        match &self.primary {
            Primary::MortarRigid(m) if self.friction.is_none() => m.coupled_groups(i),
            _ => vec![self.coupled_nodes(i)],
        }
    }

    /// The obstacle's rigid translation at pseudo-time `t`.
    pub fn translation_at(&self, t: f64) -> Vector3<f64> {
        self.motion * self.amplitude.value(t)
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
        self.secondary_node(reference, x, i).position() - translation
    }

    fn secondary_node<'a>(
        &self,
        reference: &'a [[f64; 3]],
        x: &'a [f64],
        i: usize,
    ) -> SecondaryNode<'a> {
        SecondaryNode {
            reference,
            x,
            index: i,
            mesh_node: self.nodes[i],
        }
    }

    /// Global index of node `i`'s multiplier, where the law has one.
    fn multiplier(&self, ctx: &ContactContext, i: usize) -> Option<usize> {
        self.law
            .has_multiplier_dof()
            .then_some(ctx.first_multiplier + self.multiplier_offset + i)
    }

    /// Node `i`'s tangential multiplier from the unknowns at `ctx` with the
    /// global index of its first component, where it is an unknown of
    /// Newton ([`tangential_multipliers`](Self::tangential_multipliers)):
    /// components on the two coordinate axes other than the state's
    /// [`normal_axis`](NodeContactState::normal_axis), scaled by `ε_T`.
    fn tangential_multiplier(
        &self,
        ctx: &ContactContext,
        state: &NodeContactState,
        i: usize,
    ) -> Option<(usize, TangentialMultiplier)> {
        if !self.tangential_multipliers() {
            return None;
        }
        let coulomb = self.friction_at(i)?;
        let m = ctx.first_multiplier + self.multiplier_offset + self.nodes.len() + 2 * i;
        let axis = state.normal_axis % 3;
        let basis = [(axis + 1) % 3, (axis + 2) % 3].map(|j| {
            let mut e = Vector3::zeros();
            e[j] = 1.0;
            e
        });
        let values = [ctx.x[m], ctx.x[m + 1]];
        Some((
            m,
            TangentialMultiplier {
                basis,
                scale: coulomb.tangential_penalty,
                values,
            },
        ))
    }

    /// The node's state with its multipliers taken from the unknowns
    /// where the law has a multiplier dof (the tangential one, where it is
    /// an unknown, as the friction history's traction `λ_T`).
    pub fn node_state(
        &self,
        ctx: &ContactContext,
        states: &[NodeContactState],
        i: usize,
    ) -> NodeContactState {
        let mut state = states[i];
        if let Some(m) = self.multiplier(ctx, i) {
            state.lambda = ctx.x[m];
        }
        match self.tangential_multiplier(ctx, &state, i) {
            Some((_, t)) if !self.first_contact_pending(&state) => {
                state.friction.traction = t.vector()
            }
            _ => {}
        }
        state
    }

    /// The node loop: for every secondary node `i`, its state
    /// `state_of(i)` and its gap kinematics (`None`: no primary within the
    /// search margin) against `producer` at `ctx`, handed to `visit`.
    fn for_each_node<Q: Dim, G: GapProducer<Q>>(
        &self,
        producer: &G,
        ctx: &ContactContext,
        state_of: impl Fn(usize) -> NodeContactState,
        mut visit: impl FnMut(&SecondaryNode, NodeContactState, Option<GapKinematics<Q, G::Point>>),
    ) where
        DefaultAllocator: QAllocator<Q>,
    {
        for i in 0..self.nodes.len() {
            let node = self.secondary_node(ctx.reference, ctx.x, i);
            let state = state_of(i);
            let kinematics = producer.kinematics(&node, &state);
            debug_assert!(kinematics
                .as_ref()
                .is_none_or(|k| 3 * k.nodes.len() <= k.gradient.len()));
            visit(&node, state, kinematics);
        }
    }

    /// Node `i`'s kinematics through its normal law and, closed, its
    /// friction law (the chain rule of [`kinematics`](super::kinematics));
    /// with the node's `committed_history` where its tangential rows need
    /// the committed traction ([`NodeEvaluation::committed_traction`]).
    fn evaluate<Q: Dim, G: GapProducer<Q>>(
        &self,
        producer: &G,
        node: &SecondaryNode,
        mut kinematics: GapKinematics<Q, G::Point>,
        state: &NodeContactState,
        committed_history: Option<&FrictionHistory>,
    ) -> NodeEvaluation<Q, G::Point>
    where
        DefaultAllocator: QAllocator<Q>,
    {
        let area = kinematics.area.unwrap_or(self.areas[node.index]);
        let mut response = kinematics.normal_response(&self.law_at(node.index), area, state);
        let mut committed = None;
        // a closed node at zero pressure sticks at its anchor (the return
        // mapping with a zero bound): its tangential stiffness holds a body
        // whose only tangential support is friction before the load arrives
        let (tangential, frame) = match (response.active, self.friction_at(node.index)) {
            (false, _) => (None, None),
            (true, None) => {
                let stick = TangentialResponse {
                    status: ContactStatus::Stick,
                    ..TangentialResponse::none()
                };
                (Some(stick), None)
            }
            (true, Some(coulomb)) => {
                // the committed history where given (the state's traction is
                // λ_T with tangential multipliers; the rest is the same)
                let history = committed_history.unwrap_or(&state.friction);
                let mut frame = producer.slip(node, &mut kinematics, history);
                if self.tangential_multipliers() {
                    // the multiplier λ_T, an unknown (not carried by the surface);
                    // the committed traction as carried kept for HeldTangent's rule
                    let k = &mut frame.kinematics;
                    if committed_history.is_some() && self.holds_tangent(node.index) {
                        committed = Some((k.traction, k.traction_gradient.clone()));
                    }
                    k.traction = state.friction.traction;
                    k.traction_gradient.fill(0.0);
                }
                if self.first_contact_pending(state) {
                    if self.closes_exactly() {
                        friction::first_contact_at_solution(&mut frame.kinematics);
                    } else {
                        let (g, grad) = (kinematics.gap, &kinematics.gradient);
                        friction::first_contact(&mut frame.kinematics, state.gap, g, grad);
                    }
                }
                let t = friction::return_map_on(&coulomb, &frame.kinematics, &response.pressure);
                let lever_t = frame.lever.transpose();
                response.residual -= area * &lever_t * t.traction;
                response.stiffness -= area * &lever_t * &t.traction_gradient;
                if let Some(k) = producer.lever_stiffness(&kinematics, &(area * t.traction)) {
                    response.stiffness += k;
                }
                response.multiplier_column -= area * &lever_t * t.traction_multiplier_derivative;
                (Some(t), Some(frame))
            }
        };
        NodeEvaluation {
            kinematics,
            response,
            tangential,
            frame,
            committed_traction: committed,
        }
    }

    /// The signed gap of every secondary node at time `t` and unknowns `x`
    /// (the search margin for a node without primary candidates), with the
    /// nodes' states where given (a deformable interface then uses each
    /// node's kept triangle, as the assembly does): each producer's gap
    /// without its derivatives ([`GapProducer::gap`]; dual mortar's from
    /// its rows' values, node-to-surface's and a rigid obstacle's through
    /// their kinematics, which cost little more).
    pub fn gaps(
        &self,
        reference: &[[f64; 3]],
        t: f64,
        x: &[f64],
        states: Option<&[NodeContactState]>,
    ) -> Vec<f64> {
        let ctx = ContactContext {
            reference,
            t,
            x,
            first_multiplier: 0,
        };
        let mut gaps = Vec::with_capacity(self.nodes.len());
        with_producer!(self, &ctx, p => {
            let state_of = |i| {
                states.map_or_else(|| NodeContactState::initial(&self.law_at(i), p.open_gap()), |s| s[i])
            };
            for i in 0..self.nodes.len() {
                let node = self.secondary_node(reference, x, i);
                gaps.push(p.gap(&node, &state_of(i)).unwrap_or(p.open_gap()));
            }
        });
        gaps
    }

    /// The gap [`Self::gaps`] reports for a node without a constraint row
    /// (no primary within the search margin): the producer's
    /// [`GapProducer::open_gap`] at unknowns `x` (the margin between
    /// bodies, `∞` against a rigid obstacle; it does not move with `x`).
    pub fn open_gap(&self, reference: &[[f64; 3]], x: &[f64]) -> f64 {
        let ctx = ContactContext {
            reference,
            t: 0.0,
            x,
            first_multiplier: 0,
        };
        with_producer!(self, &ctx, p => p.open_gap())
    }

    /// The states of the nodes when the interface is set up at unknowns `x`
    /// (time 0): the normal law's initial state at the node's gap (open at
    /// the search margin where a node has no primary candidate), friction
    /// anchored where the node is (between bodies: at its primary material
    /// point).
    pub fn initial_states(&self, reference: &[[f64; 3]], x: &[f64]) -> Vec<NodeContactState> {
        let ctx = ContactContext {
            reference,
            t: 0.0,
            x,
            first_multiplier: 0,
        };
        let mut states = Vec::with_capacity(self.nodes.len());
        with_producer!(self, &ctx, self.reads_derivatives(false), p => {
            let blank = |i| NodeContactState::initial(&self.law_at(i), p.open_gap());
            self.for_each_node(p, &ctx, blank, |node, _, k| {
                let g = k.as_ref().map_or(p.open_gap(), |k| k.gap);
                let mut state = NodeContactState::initial(&self.law_at(node.index), g);
                if let Some(k) = &k {
                    state.normal_axis = k.normal.iamax();
                    state.commit_facet(k.facet);
                }
                state.friction = FrictionHistory::at(p.relative_position(node));
                state.friction.material_point = p.anchor(node, k.as_ref(), &Vector3::zeros());
                states.push(state);
            });
        });
        states
    }

    /// Add the contact residual (and tangent) at `ctx` with the per-node
    /// states `states`; returns the per-node report.
    pub fn assemble(
        &self,
        ctx: &ContactContext,
        states: &[NodeContactState],
        residual: &mut [f64],
        mut tangent: Option<(&SparsityPattern, &mut [f64])>,
    ) -> Vec<NodeReport> {
        let mut reports = Vec::with_capacity(self.nodes.len());
        let all = |_| true;
        let derivatives = self.reads_derivatives(tangent.is_some());
        with_producer!(self, ctx, derivatives, p => {
            let state_of = |i| self.node_state(ctx, states, i);
            self.for_each_node(p, ctx, state_of, |node, state, k| {
                let i = node.index;
                let multiplier = self.multiplier(ctx, i);
                let Some(k) = k else {
                    // no primary within the search margin (no mortar support):
                    // inactive whatever its multiplier, at a gap of the margin
                    let open = self.law_at(i).contribution(
                        Support::Unsupported,
                        self.areas[i],
                        &GapGeometry::scalar(p.open_gap()),
                        &state,
                    );
                    if let Some(m) = multiplier {
                        residual[m] += open.r_lambda;
                        if let Some((pattern, values)) = tangent.as_mut() {
                            values[pattern.multiplier_diagonal(m - ctx.first_multiplier)] +=
                                open.k_lambdalambda;
                        }
                    }
                    if let Some((m, t)) = self.tangential_multiplier(ctx, &state, i) {
                        let rows = friction::multiplier_rows::<U3>(&t, None, self.areas[i], None);
                        let tangent = tangent.as_mut().map(|(p, v)| (*p, &mut **v));
                        scatter_tangential(ctx, &rows, (m, multiplier), None, residual, tangent);
                    }
                    reports.push(NodeReport {
                        gap: p.open_gap(),
                        ..Default::default()
                    });
                    return;
                };
                let e = self.evaluate(p, node, k, &state, Some(&states[i].friction));
                let (nodes, c) = (e.kinematics.nodes(), &e.response);
                add_nodal(residual, nodes, |a| c.residual[a]);
                if let Some(m) = multiplier {
                    residual[m] += c.r_lambda;
                }
                if let Some((pattern, values)) = tangent.as_mut() {
                    add_block(pattern, values, nodes, |r, s| c.stiffness[(r, s)], all);
                    if let Some(m) = multiplier {
                        let m = m - ctx.first_multiplier;
                        let (column, row) = (&c.multiplier_column, &c.multiplier_row);
                        add_multiplier_block(pattern, values, m, nodes, |a| column[a], |a| row[a], all);
                        values[pattern.multiplier_diagonal(m)] += c.k_lambdalambda;
                    }
                }
                if let Some((m, t)) = self.tangential_multiplier(ctx, &state, i) {
                    let closed = e.frame.as_ref().zip(e.tangential.as_ref());
                    let closed = closed.filter(|_| !self.first_contact_pending(&state));
                    let held = closed.zip(e.committed_traction).map(|((f, _), c)| {
                        friction::HeldTraction {
                            held: self.held_tangent(i, &f.kinematics.normal),
                            committed: c.0,
                            committed_gradient: c.1,
                        }
                    });
                    let mut rows = friction::multiplier_rows(
                        &t,
                        closed.map(|(f, r)| (&f.kinematics, r)),
                        self.areas[i],
                        held.as_ref(),
                    );
                    // the node's force is on its own area where the producer
                    // integrates one (mortar: D_j): ∂r_q/∂ℓ = −A Bᵀ ∂t_T/∂ℓ
                    if let Some(area) = e.kinematics.area {
                        rows.force_gradient *= area / self.areas[i];
                    }
                    let lever = closed.map(|(f, _)| (nodes, &f.lever));
                    let tangent = tangent.as_mut().map(|(p, v)| (*p, &mut **v));
                    scatter_tangential(ctx, &rows, (m, multiplier), lever, residual, tangent);
                }
                let area = e.kinematics.area.unwrap_or(self.areas[i]);
                let force = e.kinematics.normal * (area * c.pressure.value);
                let t = e.tangential.unwrap_or_else(TangentialResponse::none);
                reports.push(NodeReport {
                    gap: e.kinematics.gap,
                    pressure: c.pressure.value,
                    active: c.active,
                    status: t.status,
                    force: force.into(),
                    tangential_traction: t.traction.into(),
                    facet: e.kinematics.facet,
                    primary: e.kinematics.primary,
                    area: e.kinematics.area,
                });
            });
        });
        reports
    }

    /// Commit the history of every node after an increment converged at
    /// `ctx` (formulation note §3): the traction, status and accumulated
    /// slip of the return mapping there, the new anchor (between bodies,
    /// the node's new primary material point) and the node's triangle.
    /// Frictionless nodes record their status only.
    pub fn commit_history(&self, ctx: &ContactContext, states: &mut [NodeContactState]) {
        let mut committed = Vec::with_capacity(self.nodes.len());
        with_producer!(self, ctx, self.reads_derivatives(false), p => {
            let state_of = |i| self.node_state(ctx, states, i);
            self.for_each_node(p, ctx, state_of, |node, state, k| {
                let facet = k.as_ref().and_then(|k| k.facet);
                let gap = k.as_ref().map_or(p.open_gap(), |k| k.gap);
                let e = k.map(|k| self.evaluate(p, node, k, &state, None));
                let response = e.as_ref().and_then(|e| e.tangential.as_ref());
                let mut history =
                    friction::commit(&state.friction, response, p.relative_position(node));
                history.material_point =
                    p.anchor(node, e.as_ref().map(|e| &e.kinematics), &history.traction);
                committed.push((facet, gap, history));
            });
        });
        for (state, (facet, gap, history)) in states.iter_mut().zip(committed) {
            state.commit_facet(facet);
            state.gap = gap;
            state.friction = history;
        }
    }

    /// Turn the symmetric part of the assembled tangent, `values`, into the
    /// preconditioner of the nonsymmetric frictional solve: at every
    /// closed node with friction, replace `sym(−A_s Bᵀ ∂t_T/∂(q, λ))` by the
    /// stick stiffness scaled by the slip ratio `β = μ t_N/|t_T*|` (1 in
    /// stick; [`GapProducer::stick_stiffness`]: `−A_s β J*`, the trial
    /// derivative, against a rigid obstacle, `A_s β ε_T T` on a plane;
    /// `A_s β ε_T Bᵀ T B` at the current projection between bodies).
    /// Slipping nodes then keep a positive tangential stiffness, where the
    /// symmetrised slip tangent has none along the slip direction and an
    /// indefinite coupling to the normal; across the slip direction it is
    /// the slip tangent's own, `β ε_T`, whatever `ε_T` (the unscaled `ε_T`
    /// made GMRES's work grow with `ε_T`: DESIGN.md, "A stiff tangential
    /// penalty"). The preconditioner stays a
    /// quasi-definite saddle matrix that the sign-aware LDLᵀ factorises, and
    /// differs from the tangent only in the contact blocks (so GMRES has
    /// little left to resolve; should its LDLᵀ still break down, Newton
    /// solves with the sparse LU). Entries of `constrained` dofs are skipped.
    pub fn shift_to_stick_preconditioner(
        &self,
        ctx: &ContactContext,
        states: &[NodeContactState],
        constrained: &[bool],
        pattern: &SparsityPattern,
        values: &mut [f64],
    ) {
        if self.friction.is_none() {
            return;
        }
        let keep = |dof: usize| !constrained[dof];
        with_producer!(self, ctx, p => {
            let state_of = |i| self.node_state(ctx, states, i);
            self.for_each_node(p, ctx, state_of, |node, state, k| {
                let Some(k) = k else { return };
                let e = self.evaluate(p, node, k, &state, None);
                let (Some(t), Some(frame), Some(coulomb)) =
                    (e.tangential, e.frame, self.friction_at(node.index))
                else {
                    return;
                };
                let area = e.kinematics.area.unwrap_or(self.areas[node.index]);
                let stick = p.stick_stiffness(&e.kinematics, &frame, &t, &coulomb, area);
                let (shift, half) = stick_shift(stick, &frame.lever, &t, area);
                let nodes = e.kinematics.nodes();
                add_block(pattern, values, nodes, |r, s| shift[(r, s)], keep);
                if let Some(m) = self.multiplier(ctx, node.index) {
                    // sym added ½(−A_s Bᵀ ∂t_T/∂λ) to both entries: remove it
                    let m = m - ctx.first_multiplier;
                    add_multiplier_block(pattern, values, m, nodes, |a| -half[a], |a| -half[a], keep);
                }
            });
        });
    }

    /// Make the multiplier couplings of the preconditioner (the symmetric
    /// part `values` of `tangent`) the tangent's columns `∂r_u/∂λ` on both
    /// sides, on a frictionless dual mortar interface between bodies. There
    /// the coupling is one-sided: the force column is `∂f/∂λ` times the
    /// lever at fixed `D`, `M`, `n` (`ConstraintRow::force`), while the
    /// constraint row `∂r_λ/∂u` is the gap's complete gradient, whose
    /// derivatives of `D_j`, `M_jl` and `n_j` act on the gap, plus
    /// `(r_λ/D_j) ∇D_j` ([`GapKinematics::area_gradient`]); so an inactive
    /// node with `λ ≠ 0` has a row (`−k²λ ∇D_j / p`) and no column. The symmetric part averages the two, far from both where
    /// the gaps are large: examples/two-spheres with mortar on Newton's
    /// path, at the iteration after the open start (penetrations up to the
    /// prescribed 0.023, `h = 0.009`), the rows' norm 4.2 times the
    /// columns', `cos` between them down to −0.59 at a node, and GMRES on
    /// that average reached 8e-8 in its 200 iterations (the sparse LU
    /// then, 1.7 s); on the columns, 149 iterations to 5e-13, and fewer at
    /// every later iteration (BENCHMARKS.md, "Session 27: mortar Newton's
    /// preconditioner"). The tangent is not changed: GMRES solves it.
    /// Node-to-surface's rows are its columns (`∇g = Bᵀ n`); with friction
    /// the stick shift reads the symmetric part's halves and is kept as it
    /// is.
    pub fn couple_multipliers_by_force(
        &self,
        ctx: &ContactContext,
        pattern: &SparsityPattern,
        tangent: &[f64],
        values: &mut [f64],
    ) {
        if !matches!(self.primary, Primary::Mortar(_)) || self.friction.is_some() {
            return;
        }
        for i in 0..self.nodes.len() {
            if let Some(m) = self.multiplier(ctx, i) {
                pattern.couple_multiplier_by_column(m - ctx.first_multiplier, tangent, values);
            }
        }
    }

    /// Record each node's triangle at `ctx` and carry the local unknowns of
    /// a law that has them (the slack law's) along a Newton step `dx` from
    /// `x`: the law's one-dimensional increment `Δg = ∇g · Δq`. Nothing
    /// else: the multipliers live in `x`.
    pub fn advance_states(
        &self,
        ctx: &ContactContext,
        dx: &[f64],
        states: &mut [NodeContactState],
    ) {
        let mut advanced = Vec::with_capacity(self.nodes.len());
        with_producer!(self, ctx, p => {
            let state_of = |i| self.node_state(ctx, states, i);
            self.for_each_node(p, ctx, state_of, |node, mut state, k| {
                let i = node.index;
                let law = self.law_at(i);
                let facet = k.as_ref().and_then(|k| k.facet);
                if !law.has_local_unknowns() {
                    advanced.push((facet, None));
                    return;
                }
                state.move_to_facet(facet);
                let area = k.as_ref().and_then(|k| k.area).unwrap_or(self.areas[i]);
                let support = if k.is_some() { Support::Supported } else { Support::Unsupported };
                let (g, dg) = k.map_or((p.open_gap(), 0.0), |k| (k.gap, k.gap_increment(dx)));
                let dlambda = self.multiplier(ctx, i).map_or(0.0, |m| dx[m]);
                let du = Vector3::new(dg, 0.0, 0.0);
                let geometry = GapGeometry::scalar(g);
                law.apply_increment(area, &geometry, support, &mut state, &du, dlambda);
                advanced.push((facet, Some(state)));
            });
        });
        for (state, (facet, new)) in states.iter_mut().zip(advanced) {
            match new {
                Some(new) => *state = new,
                None => state.move_to_facet(facet),
            }
        }
    }
}

impl ContactInterface {
    /// What an operation reads of a dual mortar producer's rows: their
    /// derivatives where it assembles a `tangent`; else their values alone
    /// (a residual, a commit, the initial states, friction's weighted slip
    /// and anchor, whose values need no `∇D`, `∇M`: the frictional
    /// condensed path's evaluations read them so, bit for bit the values
    /// of the rows with derivatives), which cost a fraction of those.
    fn reads_derivatives(&self, tangent: bool) -> Derivatives {
        if tangent {
            Derivatives::With
        } else {
            Derivatives::Without
        }
    }

    /// Whether the node was open at the last commit, at a positive gap: it
    /// may close in this increment, its slip counted from its first contact
    /// ([`friction::first_contact`]), which leaves its stick equation
    /// `(1 − α) T d = 0` met by `g = 0` whatever its tangential motion, so
    /// its tangential multiplier stays zero for the increment, as the outer
    /// loop's does (`λ_T ← t_T = 0`): the node carries no friction until
    /// the commit anchors it. A committed gap within rounding of zero
    /// (1e-12 of the element size: dual mortar's weighted gaps of touching
    /// flat faces read ±2e-16) is touching, not open: the first-contact
    /// fraction `α = g_n/(g_n − g)` would jump from 1 to 0 as `g` crosses
    /// `−g_n`, and Newton hunt around the exact constraint `g = 0`. The
    /// condensed path's node law reads the same rule
    /// (`solve::condensed::cone::ConeNode::was_open`).
    pub fn first_contact_pending(&self, state: &NodeContactState) -> bool {
        state.friction.status == ContactStatus::Open && state.gap > 1e-12 * self.element_size
    }

    /// Whether a closing node's first-contact fraction is taken at its
    /// value at the solution, `α = 1` ([`friction::first_contact_at_solution`]):
    /// dual mortar between bodies with a normal multiplier in Newton, whose
    /// constraint `g_j = 0` holds exactly at every converged closed node
    /// (see [`mortar_friction`](super::mortar_friction), "A node that
    /// closes in the increment").
    fn closes_exactly(&self) -> bool {
        matches!(self.primary, Primary::Mortar(_)) && self.law.has_multiplier_dof()
    }
}

/// The preconditioner's shift of one closed node with friction (see
/// [`ContactInterface::shift_to_stick_preconditioner`]): the symmetric
/// `sym(K_stick + A_s Bᵀ ∂t_T/∂q)` with the lever `B`, and the half
/// `−½ A_s Bᵀ ∂t_T/∂λ` that `sym` put in both multiplier entries.
fn stick_shift<Q: Dim>(
    stick: OMatrix<f64, Q, Q>,
    lever: &OMatrix<f64, U3, Q>,
    t: &TangentialResponse<Q>,
    area: f64,
) -> (OMatrix<f64, Q, Q>, OVector<f64, Q>)
where
    DefaultAllocator: QAllocator<Q>,
{
    let lever_t = lever.transpose();
    let shift = stick + area * &lever_t * &t.traction_gradient;
    let shift = 0.5 * (&shift + shift.transpose());
    let half = -0.5 * area * &lever_t * t.traction_multiplier_derivative;
    (shift, half)
}

/// A node's mesh nodes with its friction lever `B`.
type NodesAndLever<'a, Q> = (&'a [usize], &'a OMatrix<f64, U3, Q>);

/// Scatter a node's tangential multiplier equations `rows` (global
/// indices `m`, `m + 1`; its normal multiplier `normal`): their residual,
/// the rows `∂r_ℓ/∂q` and the columns `∂r_q/∂ℓ = −A_s Bᵀ ∂t_T/∂ℓ` over the
/// node's mesh `nodes` with its lever `B` (`lever`, `None` when the node
/// is open), and the block among the node's multipliers.
fn scatter_tangential<Q: Dim>(
    ctx: &ContactContext,
    rows: &friction::MultiplierRows<Q>,
    (m, normal): (usize, Option<usize>),
    lever: Option<NodesAndLever<Q>>,
    residual: &mut [f64],
    tangent: Option<(&SparsityPattern, &mut [f64])>,
) where
    DefaultAllocator: QAllocator<Q>,
{
    residual[m] += rows.residual[0];
    residual[m + 1] += rows.residual[1];
    let Some((pattern, values)) = tangent else {
        return;
    };
    let first = m - ctx.first_multiplier;
    let column = lever.map(|(nodes, b)| (nodes, -(b.transpose() * rows.force_gradient)));
    for alpha in 0..2 {
        if let Some((nodes, column)) = &column {
            let (c, r) = (column.column(alpha), rows.gradient.row(alpha));
            add_multiplier_block(
                pattern,
                values,
                first + alpha,
                nodes,
                |a| c[a],
                |a| r[a],
                |_| true,
            );
        }
        for beta in 0..2 {
            if let Some(k) = pattern.multiplier_pair(first + alpha, first + beta) {
                values[k] += rows.multiplier[(alpha, beta)];
            }
        }
        if let Some(k) =
            normal.and_then(|n| pattern.multiplier_pair(first + alpha, n - ctx.first_multiplier))
        {
            values[k] += rows.normal_multiplier[alpha];
        }
    }
}
