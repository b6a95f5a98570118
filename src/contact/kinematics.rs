//! The contact node driver's algebra: a secondary node's gap as a function
//! of the `Q` unknowns `q` of its contribution ([`GapKinematics`], beside
//! friction's [`SlipKinematics`]), the normal law's chain rule to `q`
//! ([`GapKinematics::normal_response`]), and what a primary kind supplies
//! ([`GapProducer`]: a rigid obstacle, `Q = 3`, in [`rigid`](super::rigid);
//! a deformable primary surface, `Q = 21`, in
//! [`surface_contact`](super::surface_contact); a primary surface through
//! dual mortar, `Q` at run time, in [`mortar_contact`](super::mortar_contact)).
//!
//! ## One law, any geometry
//! Every normal law is a function of the scalar gap (and of the node's
//! multiplier): evaluated on a one-dimensional geometry
//! ([`GapGeometry::scalar`]: `n = e₁`, `H = 0`) it returns the force
//! conjugate to the gap, `f = ∂(A_s Φ)/∂g` (its `r_u[0]`), with `∂f/∂g`
//! (`K_uu[0,0]`), `∂f/∂λ` (`K_uλ[0]`), `r_λ` and `K_λλ`. The chain rule then
//! gives the node's contribution on `(q, λ)`, the force acting through a
//! lever `b` ([`GapKinematics::lever`]):
//! ```text
//! r_q  = f b                      K_qq = (∂f/∂g) b ∇gᵀ + f ∂b/∂q
//! K_qλ = (∂f/∂λ) b                K_λq = (∂r_λ/∂g) ∇gᵀ = (∂f/∂λ) ∇gᵀ
//! ∂t_N/∂q = (∂t_N/∂g) ∇g
//! ```
//! plus `(r_λ/A_s) ∇A_s` in `K_λq` where the area follows the nodes
//! (dual mortar's `D_j`: [`GapKinematics::area_gradient`]).
//! Node-to-surface and rigid obstacles take `b = ∇g` (the force is the
//! gradient of the law's potential, `∂b/∂q = ∇²g`, symmetric): against a
//! rigid obstacle `q = x_s`, `∇g = n`, `∇²g = H`; against a primary
//! triangle `q = (x_s, x1, x2, x3, …)` and `∇²g` holds the change of the
//! projection point and of the normal, so Newton keeps its quadratic rate.
//! Dual mortar ([`mortar_contact`](super::mortar_contact)) takes Popp, Gee
//! & Wall's (2009) form: the force `Σ_j λ_j b_j` with `b` the gap's
//! gradient at fixed `D`, `M` (the constraint row keeps the whole `∇g`).
//!
//! The size `Q` of `q` is a nalgebra dimension: `Const<N>` for the
//! producers of a fixed size (stack-allocated), `Dyn` where the coupling is
//! known at run time only ([`QAllocator`]).
//!
//! ## Friction on the same unknowns
//! A closed node's tangential traction `t_T` (the return mapping of
//! [`friction`]) acts through the lever `B = ∂(x_s − x̄)/∂q` at fixed
//! projection: `r_q −= A_s Bᵀ t_T`, `K_qq −= A_s Bᵀ ∂t_T/∂q` plus the
//! lever's own change ([`GapProducer::lever_stiffness`]), `K_qλ −= A_s Bᵀ ∂t_T/∂λ`.

pub use super::dimension::{natural_dim, QAllocator};
use super::friction::{
    self, Coulomb, FrictionHistory, MaterialPoint, NormalPressure, SlipKinematics,
    TangentialResponse,
};
use super::gap::GapGeometry;
use super::laws::{NodeContactState, NormalLaw, Support};
use nalgebra::{DefaultAllocator, Dim, OMatrix, OVector, Vector3, U3};
use smallvec::SmallVec;

/// The mesh nodes of one secondary node's contribution, in the order of
/// its unknowns `q` (three coordinates each, node-major): any number, the
/// first eight inline (a rigid obstacle's one node, a primary triangle's
/// four and its friction anchor's three fit without a heap allocation).
pub type CoupledNodes = SmallVec<[usize; 8]>;

/// The nodes of the primary side that a secondary node's reaction acts on,
/// with the weight of each: a force `f` on the secondary node is balanced
/// by `−w_i f` on primary node `i`. `N_i(ξ)` of the triangle the node is
/// projected on (node-to-surface), `M_jl/D_jj` (dual mortar); none against
/// a rigid obstacle.
pub type PrimaryWeights = SmallVec<[(usize, f64); 4]>;

/// One secondary node in a configuration: where the producers look.
pub struct SecondaryNode<'a> {
    /// Reference coordinates of every mesh node.
    pub reference: &'a [[f64; 3]],
    /// The unknowns (displacements first).
    pub x: &'a [f64],
    /// Index of the node in its interface.
    pub index: usize,
    /// Its mesh node `s`.
    pub mesh_node: usize,
}

impl SecondaryNode<'_> {
    /// Current position `x_s = X_s + u_s`.
    pub fn position(&self) -> Vector3<f64> {
        current_position(self.reference, self.x, self.mesh_node)
    }
}

/// Current position `X_n + u_n` of mesh node `n` at unknowns `x`.
pub fn current_position(reference: &[[f64; 3]], x: &[f64], n: usize) -> Vector3<f64> {
    Vector3::new(
        reference[n][0] + x[3 * n],
        reference[n][1] + x[3 * n + 1],
        reference[n][2] + x[3 * n + 2],
    )
}

/// The gap of one secondary node as a function of the unknowns `q` (three
/// coordinates of each of its mesh nodes, node-major), held in vectors and
/// matrices of the producer's size `Q ≥ 3 × nodes.len()` (fixed or run
/// time; entries beyond the nodes zero).
#[derive(Clone, Debug)]
pub struct GapKinematics<Q: Dim, P = ()>
where
    DefaultAllocator: QAllocator<Q>,
{
    /// Mesh nodes of `q`, any number with `3 nodes.len() ≤ Q`.
    pub nodes: CoupledNodes,
    /// Signed gap `g`.
    pub gap: f64,
    /// `∇g = ∂g/∂q`.
    pub gradient: OVector<f64, Q>,
    /// The lever `b` the normal force acts through, `r_q = f b`, where it
    /// differs from `∇g` (dual mortar: `∂g/∂q` at fixed `D`, `M`; see the
    /// module docs); `None`: `b = ∇g`.
    pub lever: Option<OVector<f64, Q>>,
    /// `∂b/∂q`: `∇²g` (symmetric) where `b = ∇g`.
    pub hessian: OMatrix<f64, Q, Q>,
    /// The node's area `A_s` where the producer integrates it (dual mortar:
    /// `D_j`); `None`: the interface's tributary area.
    pub area: Option<f64>,
    /// `∂A_s/∂q` where the producer's area follows the nodes (dual mortar:
    /// `∇D_j`); `None`: a constant area. The multiplier row takes it in
    /// ([`normal_response`](Self::normal_response)).
    pub area_gradient: Option<OVector<f64, Q>>,
    /// Unit normal `n` of the tangent plane.
    pub normal: Vector3<f64>,
    /// `∂n/∂q`.
    pub normal_gradient: OMatrix<f64, U3, Q>,
    /// The primary segment the node is projected on and keeps while it
    /// stays over it (node-to-surface only, recorded in
    /// [`NodeContactState::facet`]).
    pub facet: Option<usize>,
    /// The primary nodes of the node's reaction and their weights.
    pub primary: PrimaryWeights,
    /// What the producer keeps of the projection beyond that.
    pub point: P,
}

impl<Q: Dim, P> GapKinematics<Q, P>
where
    DefaultAllocator: QAllocator<Q>,
{
    /// The mesh nodes of `q`.
    pub fn nodes(&self) -> &[usize] {
        &self.nodes
    }

    /// The gap's change along a step `dx` of the unknowns, `Δg = ∇g · Δq`.
    pub fn gap_increment(&self, dx: &[f64]) -> f64 {
        self.nodes()
            .iter()
            .enumerate()
            .map(|(a, &n)| {
                (0..3)
                    .map(|d| self.gradient[3 * a + d] * dx[3 * n + d])
                    .sum::<f64>()
            })
            .sum()
    }

    /// The normal law `law` of a node of tributary area `area` in `state`,
    /// carried to `q` by the chain rule (see the module docs).
    pub fn normal_response(
        &self,
        law: &NormalLaw,
        area: f64,
        state: &NodeContactState,
    ) -> NormalResponse<Q> {
        let c = law.contribution(
            Support::Supported,
            area,
            &GapGeometry::scalar(self.gap),
            state,
        );
        let (f, df_dg, df_dlambda) = (c.r_u[0], c.k_uu[(0, 0)], c.k_ulambda[0]);
        let grad = &self.gradient;
        let lever = self.lever.as_ref().unwrap_or(grad);
        NormalResponse {
            residual: f * lever,
            stiffness: df_dg * lever * grad.transpose() + f * &self.hessian,
            multiplier_column: df_dlambda * lever,
            multiplier_row: self.multiplier_row(df_dlambda, c.r_lambda, area),
            r_lambda: c.r_lambda,
            k_lambdalambda: c.k_lambdalambda,
            pressure: NormalPressure {
                value: c.pressure,
                gradient: c.pressure_gradient[0] * grad,
                multiplier_derivative: c.pressure_multiplier_derivative,
            },
            active: c.active,
        }
    }

    /// `∂r_λ/∂q` of a law whose multiplier row is `r_λ = A_s c(g, λ)`
    /// (every law: `∂(A_s Φ)/∂λ`, `Φ` per unit area), at `∂r_λ/∂g =
    /// ∂f/∂λ`:
    /// ```text
    /// ∂r_λ/∂q = (∂f/∂λ) ∇g + (r_λ / A_s) ∇A_s
    /// ```
    /// the second term where the area follows the nodes
    /// ([`area_gradient`](Self::area_gradient): dual mortar's `D_j`,
    /// whose multiplier row is then `−k g̃_j` when active).
    fn multiplier_row(&self, df_dlambda: f64, r_lambda: f64, area: f64) -> OVector<f64, Q> {
        let mut row = df_dlambda * &self.gradient;
        if let Some(area_gradient) = &self.area_gradient {
            row.axpy(r_lambda / area, area_gradient, 1.0);
        }
        row
    }
}

/// What one secondary node adds to the residual and tangent over its
/// unknowns `(q, λ)`.
#[derive(Clone, Debug)]
pub struct NormalResponse<Q: Dim>
where
    DefaultAllocator: QAllocator<Q>,
{
    /// `r_q`.
    pub residual: OVector<f64, Q>,
    /// `∂r_q/∂q` (nonsymmetric with friction).
    pub stiffness: OMatrix<f64, Q, Q>,
    /// `∂r_q/∂λ`.
    pub multiplier_column: OVector<f64, Q>,
    /// `∂r_λ/∂q`.
    pub multiplier_row: OVector<f64, Q>,
    /// `r_λ` (0 without a multiplier dof).
    pub r_lambda: f64,
    /// `∂r_λ/∂λ`.
    pub k_lambdalambda: f64,
    /// The contact pressure `t_N` with `∂t_N/∂q`, `∂t_N/∂λ`.
    pub pressure: NormalPressure<Q>,
    /// Whether the node transmits force (the law's switch).
    pub active: bool,
}

/// A closed node's slip frame from its committed history: the kinematics
/// of [`friction::return_map_on`] and the lever `B = ∂(x_s − x̄)/∂q` that
/// carries the traction to the nodes.
pub struct SlipFrame<Q: Dim>
where
    DefaultAllocator: QAllocator<Q>,
{
    pub kinematics: SlipKinematics<Q>,
    pub lever: OMatrix<f64, U3, Q>,
}

/// What a primary kind supplies to the node driver.
pub trait GapProducer<Q: Dim>
where
    DefaultAllocator: QAllocator<Q>,
{
    /// What the producer keeps of a projection beyond [`GapKinematics`].
    type Point;

    /// The gap kinematics of `node` in `state`; `None` when the node has no
    /// primary within the search margin (open at [`open_gap`](Self::open_gap)).
    fn kinematics(
        &self,
        node: &SecondaryNode,
        state: &NodeContactState,
    ) -> Option<GapKinematics<Q, Self::Point>>;

    /// The node's gap alone, without its derivatives: what a solve that
    /// reads only gaps asks for (the condensed path's contact solve);
    /// `None` where [`kinematics`](Self::kinematics) is `None` (open at
    /// [`open_gap`](Self::open_gap)). The default takes it from
    /// `kinematics`; a producer whose derivatives cost much more than its
    /// values (dual mortar: a pass over the segmentation per coupled
    /// coordinate) gives it from its values, equal to `kinematics`' gap.
    fn gap(&self, node: &SecondaryNode, state: &NodeContactState) -> Option<f64> {
        self.kinematics(node, state).map(|k| k.gap)
    }

    /// The gap reported for a node without kinematics.
    fn open_gap(&self) -> f64;

    /// The node's position in the frame its friction anchor is kept in
    /// (`x_s − c(t)` against a translating obstacle, `x_s` between bodies).
    fn relative_position(&self, node: &SecondaryNode) -> Vector3<f64>;

    /// The slip frame of a closed node from its committed `history`; may
    /// add the anchor's nodes to `kinematics.nodes`.
    fn slip(
        &self,
        node: &SecondaryNode,
        kinematics: &mut GapKinematics<Q, Self::Point>,
        history: &FrictionHistory,
    ) -> SlipFrame<Q>;

    /// `Σ_k (∂B_kᵀ/∂q) t` for a traction `t` at fixed `q`-derivative of `t`:
    /// the lever's own change (`None`, the default: a constant lever, as
    /// against a rigid obstacle).
    fn lever_stiffness(
        &self,
        kinematics: &GapKinematics<Q, Self::Point>,
        traction: &Vector3<f64>,
    ) -> Option<OMatrix<f64, Q, Q>> {
        let _ = (kinematics, traction);
        None
    }

    /// The node's lever `B = Σ_k w_k e_k ⊗ I` as its weights `(k, w_k)`,
    /// where it is not `e_s − Σ_i w_i e_{p_i}` of
    /// [`GapKinematics::primary`] (`None`, the default): dual mortar's
    /// `R_jk` on the secondary nodes and `−M_jl/D_j` on the primary ones
    /// (the quadratic basis transformation spreads it over the face).
    fn lever_weights(
        &self,
        kinematics: &GapKinematics<Q, Self::Point>,
    ) -> Option<Vec<(usize, f64)>> {
        let _ = kinematics;
        None
    }

    /// The stick stiffness `−A_s ∂t_T/∂q` in stick, scaled by the slip
    /// ratio [`TangentialResponse::stick_scale`] in slip, that the
    /// preconditioner of the frictional solve uses for every closed node.
    fn stick_stiffness(
        &self,
        kinematics: &GapKinematics<Q, Self::Point>,
        frame: &SlipFrame<Q>,
        response: &TangentialResponse<Q>,
        law: &Coulomb,
        area: f64,
    ) -> OMatrix<f64, Q, Q>;

    /// The history with its tangential multiplier augmented to the
    /// traction `t_T` of the node's `response` at the current unit normal
    /// `n` (`None`: the node is open, `λ_T ← 0`): Simo–Laursen's update
    /// `λ_T ← t_T` ([`friction::augment`], the default) in the form the
    /// producer's [`slip`](Self::slip) reads it back, so that `T λ_T = t_T`
    /// at the next evaluation in this configuration.
    fn augment(
        &self,
        node: &SecondaryNode,
        history: &FrictionHistory,
        response: Option<(&TangentialResponse<Q>, &Vector3<f64>)>,
    ) -> FrictionHistory {
        let _ = node;
        friction::augment(history, response.map(|(r, _)| r))
    }

    /// The material point a node anchors its friction to after an increment
    /// converged, with the committed `traction` carried by it (`None`, the
    /// default: none, as against a rigid obstacle).
    fn anchor(
        &self,
        node: &SecondaryNode,
        kinematics: Option<&GapKinematics<Q, Self::Point>>,
        traction: &Vector3<f64>,
    ) -> Option<MaterialPoint> {
        let _ = (node, kinematics, traction);
        None
    }
}

/// One secondary node evaluated: its kinematics, the normal law and the
/// friction law on its unknowns, and the totals.
pub struct NodeEvaluation<Q: Dim, P>
where
    DefaultAllocator: QAllocator<Q>,
{
    pub kinematics: GapKinematics<Q, P>,
    /// Normal law plus friction on `(q, λ)` (the row `∂r_λ/∂q` is the
    /// normal law's alone).
    pub response: NormalResponse<Q>,
    /// `None` when the node is open; a zero traction in stick without
    /// friction.
    pub tangential: Option<TangentialResponse<Q>>,
    /// The slip frame where the node is closed with friction.
    pub frame: Option<SlipFrame<Q>>,
    /// With exact stick's tangential multipliers as unknowns: the
    /// committed traction `t_T,n` as the producer carries it and
    /// `∂t_T,n/∂q` (the frame's traction is the multiplier `λ_T` then).
    pub committed_traction: Option<(Vector3<f64>, OMatrix<f64, U3, Q>)>,
}
