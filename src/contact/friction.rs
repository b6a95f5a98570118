//! Coulomb friction by return mapping (formulation note §3, the paper's §6),
//! per secondary node.
//!
//! ## Signs and kinematics
//! `t_T` is the tangential traction the obstacle exerts on the body; it
//! opposes the body's slip. The nodal force on the body is
//! `A_s (t_N n + t_T)`, so the node's residual receives `−A_s t_T`.
//! With the tangent projector `T = I − n nᵀ`, the slip increment from the
//! last converged increment is measured relative to the obstacle:
//! ```text
//! d    = (x_s − c(t)) − (x_s − c)ₙ          c(t): the obstacle's translation
//! Δg_T = T d
//! ```
//! (`(x_s − c)ₙ` is the node's *anchor*, [`FrictionHistory::anchor`]).
//!
//! ## Return mapping (tangential penalty `ε_T`, coefficient `μ`)
//! ```text
//! t_T* = T t_T,n − ε_T Δg_T                   trial (old traction projected
//!                                              on the current tangent plane)
//! f    = |t_T*| − μ t_N
//! stick (f ≤ 0):  t_T = t_T*
//! slip  (f > 0):  t_T = μ t_N m,   m = t_T*/|t_T*|
//! ```
//! The paper's eq. 35 writes `+ε_T` with the opposite sign for `t_T`.
//!
//! ## Consistent linearisation
//! With `H = ∂n/∂x_s` (the gap Hessian, symmetric, `H n = 0`), the
//! derivative of the projection `T v` of a fixed vector `v` is
//! `−(n·v) H − n (H v)ᵀ`, so
//! ```text
//! J* = ∂t_T*/∂x_s = −(n·t_T,n) H − n (H t_T,n)ᵀ − ε_T [T − (n·d) H − n (H d)ᵀ]
//! stick:  ∂t_T/∂x_s = J*,                           ∂t_T/∂λ = 0
//! slip:   ∂t_T/∂x_s = μ t_N/|t_T*| (I − m mᵀ) J* + μ m ⊗ ∂t_N/∂x_s,
//!         ∂t_T/∂λ   = μ m ∂t_N/∂λ
//! ```
//! The last terms couple friction to the normal pressure; the paper's
//! eq. 51 leaves them out, and Newton then loses its quadratic rate while
//! slipping. The tangent is nonsymmetric. On a plane (`H = 0`) stick gives
//! `∂t_T/∂x_s = −ε_T T`, i.e. `+A_s ε_T T` in `K`: positive semi-definite.
//!
//! ## Status at the start of an increment (slip predictor)
//! A trial on the cone to a relative [`ON_THE_CONE`] slips: a node that
//! slipped at the last commit and has not moved yet (its trial the
//! committed traction, `|t_T*| = μ t_N` to rounding) starts the increment
//! with the slip tangent, free along `m`, instead of the stick tangent
//! `ε_T T`, which held it in place for the first Newton step and made the
//! next trial overshoot the cone by `ε_T` times its motion (DESIGN.md, "A
//! stiff tangential penalty").
//!
//! ## Exact stick: the augmented Lagrangian (Simo–Laursen)
//! With a law that enforces the normal constraint exactly
//! ([`NormalLaw::augments_friction`](super::laws::NormalLaw::augments_friction):
//! Uzawa, Rockafellar, slack), where asked for
//! ([`ContactInterface::exact_stick`](super::interface::ContactInterface::exact_stick)),
//! the old traction of the trial becomes a
//! tangential multiplier `λ_T`; with [`FrictionMultiplier::Outer`] (and
//! always with Uzawa, which has no multiplier unknowns) it is held fixed
//! during Newton and updated after
//! each converged Newton solve, nested with Uzawa's normal update when the
//! law has one (Simo & Laursen, *An augmented Lagrangian treatment of
//! contact problems involving friction*, Comput. Struct. 42 (1992) 97–116;
//! Laursen & Simo, IJNME 36 (1993) 3451–3485; Laursen, *Computational
//! Contact and Impact Mechanics*, 2002, §6.4):
//! ```text
//! t_T = P_μt_N(T λ_T − ε_T Δg_T)      (the return mapping above, λ_T for t_T,n)
//! λ_T ← t_T                           (augment), until max |t_T − T λ_T|/ε_T ≤ 1e-9 h
//! ```
//! `λ_T` starts each increment at the committed traction. Between
//! deformable bodies it is kept where the slip frame reads the committed
//! traction, as components `τ^α` on the anchor triangle's edges, with
//! `T (τ^α a_α) = t_T` exactly ([`GapProducer::augment`](super::kinematics::GapProducer::augment)
//! of [`SurfaceGap`](super::surface_contact::SurfaceGap)): a multiplier
//! kept in `traction` alone was never read there, and the outer loop could
//! not converge. At the fixed
//! point a sticking node has `T Δg_T = 0` (it does not move), a slipping
//! node `t_T = μ t_N m` with `Δg_T` along `−m`: Coulomb's law exactly, and
//! `ε_T` only sets how fast the outer loop converges (each update leaves
//! about `k_T/(k_T + A_s ε_T)` of the stick error, `k_T` the structure's
//! tangential stiffness at the node). Within Newton the law is the return
//! mapping above with `λ_T` fixed, so its consistent tangent is unchanged.
//! The penalty law keeps the regularised law (elastic slip `t_T/ε_T`).
//!
//! ## Exact stick in one Newton solve: the multiplier as an unknown (Alart–Curnier)
//! By default ([`FrictionMultiplier::Newton`], with the laws that have a
//! normal multiplier dof: Rockafellar, slack) `λ_T` is not held and
//! updated but solved for: two unknowns `ℓ` per node beside the normal
//! multiplier, `λ_T = ε_T (ℓ¹ e₁ + ℓ² e₂)` on two fixed coordinate axes
//! ([`TangentialMultiplier`]), with the equations of Alart and Curnier's
//! complementarity function (Alart & Curnier, *A mixed formulation for
//! frictional contact problems prone to Newton like solution methods*,
//! CMAME 92 (1991) 353–375; Wriggers, *Computational Contact Mechanics*,
//! 2006, §6.3)
//! ```text
//! C_T = T λ_T − P_μt_N(T λ_T − ε_T T d) = T λ_T − t_T,    r_ℓ = −A_s Eᵀ C_T
//! ```
//! ([`multiplier_rows`]), Newton on `(u, λ, ℓ)` together: at a solution
//! the fixed point of the outer loop, in one Newton solve. The force on
//! the node stays the return mapping's `t_T` with `λ_T` for `t_T,n`, so
//! the displacement rows, the stick/slip switch and the slip predictor
//! are this module's return mapping; what the multiplier adds is
//! `∂t_T/∂λ_T` ([`TangentialResponse::multiplier_gradient`]). The
//! multiplier block of a node (normal and tangential) is dense in slip
//! (`∂r_ℓ/∂ℓ` couples `ℓ¹, ℓ²` unless `m` lies on an axis, `∂r_ℓ/∂λ ≠ 0`):
//! the sparsity pattern holds a 3 × 3 block per node
//! ([`SparsityPattern::with_multiplier_groups`](crate::assembly::pattern::SparsityPattern::with_multiplier_groups)),
//! so the tangent is exact (a diagonal block on a slip-aligned basis, the
//! other way, needs a basis that turns with `m` within the increment). A
//! node that was open at the last commit keeps `λ_T = 0` for the increment
//! (its stick equation after [`first_contact`] is met by `g = 0` alone, see
//! `ContactInterface`'s `first_contact_pending`), as the outer loop's
//! fixed point has it.
//!
//! ## History
//! [`FrictionHistory`] (traction, anchor, accumulated slip, status) is read,
//! never written, during the Newton iterations of an increment; the outer
//! loop of exact stick augments its traction ([`augment`]); it is
//! committed once the increment has converged ([`commit`]). Updating it per
//! iteration (as the paper says) breaks path independence.

use super::dimension::{natural_dim, QAllocator};
use super::gap::GapGeometry;
use nalgebra::{
    DefaultAllocator, Dim, Matrix2, Matrix3, OMatrix, OVector, SMatrix, Vector2, Vector3, U1, U2,
    U3,
};

/// Coulomb's law with its regularising tangential penalty.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Coulomb {
    /// Friction coefficient `μ ≥ 0`.
    pub coefficient: f64,
    /// Tangential penalty `ε_T > 0` (traction per unit elastic slip).
    pub tangential_penalty: f64,
}

/// State of a secondary node for output: the integers of the VTU field
/// `contact_status`.
#[derive(
    Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize,
)]
pub enum ContactStatus {
    /// Not in contact (`0`).
    #[default]
    Open,
    /// In contact and sticking; every closed node of a frictionless
    /// interface (`1`).
    Stick,
    /// In contact and slipping (`2`).
    Slip,
}

impl ContactStatus {
    /// `0` open, `1` stick (or closed without friction), `2` slip.
    pub fn code(self) -> u8 {
        match self {
            Self::Open => 0,
            Self::Stick => 1,
            Self::Slip => 2,
        }
    }
}

/// What a node remembers from the last converged increment.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct FrictionHistory {
    /// Tangential traction `t_T,n` at the last commit; during an increment
    /// of a law with exact stick, the tangential multiplier `λ_T` its
    /// outer loop augments ([`augment`]).
    pub traction: Vector3<f64>,
    /// The node's position relative to the obstacle's translation,
    /// `(x_s − c)ₙ`: where the slip increment is measured from.
    pub anchor: Vector3<f64>,
    /// Accumulated slip `Σ Δg_T^slip` (a vector; zero where the node always stuck).
    pub slip: Vector3<f64>,
    /// Status at the last converged increment.
    pub status: ContactStatus,
    /// Between deformable bodies: the primary material point the node was
    /// over at the last converged increment, where its slip is measured
    /// from (`None` against a rigid obstacle, or when the node had no
    /// primary triangle).
    pub material_point: Option<MaterialPoint>,
}

/// A material point of a primary surface: a triangle and the weights
/// `N_i(ξ)` of its three nodes. Its current position `Σ N_i x_i` follows
/// the primary body's deformation.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct MaterialPoint {
    /// Index of the primary triangle.
    pub triangle: usize,
    /// Shape functions `N = (1 − ξ1 − ξ2, ξ1, ξ2)` of the point.
    pub shape: [f64; 3],
    /// The committed tangential traction's components `τ^α` on the
    /// triangle's edges `a1 = y2 − y1`, `a2 = y3 − y1`: the traction is
    /// carried (rotated and stretched) with the primary surface,
    /// `t_T,n = τ^α a_α`, so that a sticking pair that turns as a whole
    /// keeps its traction in the tangent plane.
    pub traction: [f64; 2],
}

impl FrictionHistory {
    /// A node that has not moved yet: anchored at `relative_position`.
    pub fn at(relative_position: Vector3<f64>) -> Self {
        Self {
            anchor: relative_position,
            ..Self::default()
        }
    }

    /// Whether every number of the history is finite: the traction, the
    /// anchor, the slip and the material point's weights and traction.
    pub fn is_finite(&self) -> bool {
        let finite = |v: &Vector3<f64>| v.iter().all(|x| x.is_finite());
        finite(&self.traction)
            && finite(&self.anchor)
            && finite(&self.slip)
            && self
                .material_point
                .as_ref()
                .is_none_or(|p| p.shape.iter().chain(&p.traction).all(|x| x.is_finite()))
    }
}

/// The normal pressure the friction law is bounded by, with its derivatives
/// (from the normal law's [`NodeContribution`](super::laws::NodeContribution))
/// with respect to the `K` unknowns of the node's kinematics (`x_s` alone
/// against a rigid obstacle, `K = 3`).
#[derive(Clone, Debug, PartialEq)]
pub struct NormalPressure<K: Dim = U3>
where
    DefaultAllocator: QAllocator<K>,
{
    /// `t_N > 0`.
    pub value: f64,
    /// `∂t_N/∂q`.
    pub gradient: OVector<f64, K>,
    /// `∂t_N/∂λ` (zero without a multiplier dof).
    pub multiplier_derivative: f64,
}

/// Where a node is relative to the point it slips from, and the tangent
/// plane, with their derivatives with respect to `K` unknowns `q`.
#[derive(Clone, Debug, PartialEq)]
pub struct SlipKinematics<K: Dim>
where
    DefaultAllocator: QAllocator<K>,
{
    /// The committed traction `t_T,n` as it is now: a fixed vector against
    /// a rigid obstacle; between bodies carried by the primary surface
    /// (`τ^α a_α`, its components on the anchor triangle's edges).
    pub traction: Vector3<f64>,
    /// `∂t_T,n/∂q` (zero against a rigid obstacle).
    pub traction_gradient: OMatrix<f64, U3, K>,
    /// `d`: the node's position relative to its anchor (against a rigid
    /// obstacle `(x_s − c(t)) − (x_s − c)ₙ`; between bodies `x_s − x̄ₙ`, the
    /// current position of the primary material point `x̄ₙ` the node was
    /// over at the last converged increment).
    pub offset: Vector3<f64>,
    /// `∂d/∂q`.
    pub offset_gradient: OMatrix<f64, U3, K>,
    /// Unit normal `n` of the tangent plane.
    pub normal: Vector3<f64>,
    /// `∂n/∂q` (the gap Hessian `H` against a rigid obstacle).
    pub normal_gradient: OMatrix<f64, U3, K>,
}

/// The tangential response of one closed node, with derivatives with
/// respect to the `K` unknowns of its kinematics.
#[derive(Clone, Debug, PartialEq)]
pub struct TangentialResponse<K: Dim = U3>
where
    DefaultAllocator: QAllocator<K>,
{
    /// `t_T`.
    pub traction: Vector3<f64>,
    /// [`ContactStatus::Stick`] or [`ContactStatus::Slip`].
    pub status: ContactStatus,
    /// `∂t_T/∂q` (not symmetric in slip or on a curved obstacle).
    pub traction_gradient: OMatrix<f64, U3, K>,
    /// `∂t_T/∂λ`.
    pub traction_multiplier_derivative: Vector3<f64>,
    /// `∂t_T/∂t_T,n`, the derivative with respect to the committed traction
    /// (the tangential multiplier `λ_T` of exact stick): `T` in stick,
    /// `β (I − m mᵀ) T` in slip.
    pub multiplier_gradient: Matrix3<f64>,
    /// `J* = ∂t_T*/∂q`, the trial (stick) derivative, whatever the
    /// status: the tangential stiffness a preconditioner may use in slip.
    pub trial_gradient: OMatrix<f64, U3, K>,
    /// `β = |t_T|/|t_T*| = μ t_N/|t_T*|` in slip, 1 in stick: the slip
    /// tangent is `β (I − m mᵀ) J*` plus the normal coupling, so `β J*` is
    /// the stiffness the preconditioner gives a slipping node (exact across
    /// the slip direction, where `ε_T` cancels out of `β ε_T`).
    pub stick_scale: f64,
    /// Residual of the multiplier equation of the augmented Lagrangian,
    /// `(t_T − T λ_T)/ε_T` (`λ_T` the multiplier, `t_T,n` in the module
    /// docs): a length, `−T d` in stick, zero at an exact solution.
    pub multiplier_residual: Vector3<f64>,
    /// Slip part of the increment, `Δg_T + (t_T − T t_T,n)/ε_T`
    /// (`−(|t_T*| − μ t_N) m / ε_T` in slip, exactly zero in stick).
    pub slip_increment: Vector3<f64>,
}

impl<K: Dim> TangentialResponse<K>
where
    DefaultAllocator: QAllocator<K>,
{
    /// No tangential traction and no stiffness (an open node, status
    /// [`ContactStatus::Open`]).
    pub fn none() -> Self {
        Self {
            traction: Vector3::zeros(),
            status: ContactStatus::Open,
            traction_gradient: OMatrix::zeros_generic(U3, natural_dim()),
            traction_multiplier_derivative: Vector3::zeros(),
            multiplier_gradient: Matrix3::zeros(),
            trial_gradient: OMatrix::zeros_generic(U3, natural_dim()),
            stick_scale: 1.0,
            multiplier_residual: Vector3::zeros(),
            slip_increment: Vector3::zeros(),
        }
    }
}

/// Derivative of the projection `T v = v − n (n·v)` of a fixed vector `v`:
/// `−(n·v) ∂n/∂q − n (vᵀ ∂n/∂q)` (with `∂n/∂x_s = H` symmetric against a
/// rigid obstacle: `−(n·v) H − n (H v)ᵀ`).
fn projection_derivative<K: Dim>(
    kinematics: &SlipKinematics<K>,
    v: &Vector3<f64>,
) -> OMatrix<f64, U3, K>
where
    DefaultAllocator: QAllocator<K>,
{
    let n_prime = &kinematics.normal_gradient;
    -kinematics.normal.dot(v) * n_prime - kinematics.normal * (v.transpose() * n_prime)
}

/// The return mapping of one closed node (`t_N ≥ 0`) against a rigid
/// obstacle, at its current `relative_position = x_s − c(t)`, from the
/// committed `history` ([`return_map_on`] with `q = x_s`, `∂d/∂x_s = I`,
/// `∂n/∂x_s = H`).
pub fn return_map(
    law: &Coulomb,
    history: &FrictionHistory,
    relative_position: &Vector3<f64>,
    gap: &GapGeometry,
    pressure: &NormalPressure,
) -> TangentialResponse {
    let kinematics = SlipKinematics::rigid(history, relative_position, &gap.normal, &gap.hessian);
    return_map_on(law, &kinematics, pressure)
}

impl SlipKinematics<U3> {
    /// Against a rigid obstacle, `q = x_s`: the committed traction fixed,
    /// `d = (x_s − c(t)) − (x_s − c)ₙ` from the node's `relative_position`
    /// and the `history`'s anchor, `∂d/∂x_s = I`, `∂n/∂x_s = H`.
    pub fn rigid(
        history: &FrictionHistory,
        relative_position: &Vector3<f64>,
        normal: &Vector3<f64>,
        hessian: &Matrix3<f64>,
    ) -> Self {
        SlipKinematics {
            traction: history.traction,
            traction_gradient: Matrix3::zeros(),
            offset: relative_position - history.anchor,
            offset_gradient: Matrix3::identity(),
            normal: *normal,
            normal_gradient: *hessian,
        }
    }
}

/// Factor on the automatic `E/h_s` for the tangential penalty of the laws
/// with exact stick ([`NormalLaw::augments_friction`](super::laws::NormalLaw::augments_friction)).
///
/// Why: their answer does not depend on `ε_T`, only the outer loop's speed
/// does (each update leaves about `k_T/(k_T + A_s ε_T)` of the stick
/// error). Measured on examples/press-pull (2026-11-23, rockafellar):
/// factors 1, 10, 100, 1000 took 508, 149, 152 (one cut) and 618 (four
/// cuts) Newton iterations to the same stick and slip sets; beyond 10 a
/// stiff `ε_T` makes Newton itself cut increments (DESIGN.md, "A stiff
/// tangential penalty").
pub const AUGMENTED_FACTOR: f64 = 10.0;

/// Relative distance to the cone within which a trial slips: a node that
/// slipped at the last commit and has not moved yet (`d = 0`, its trial the
/// committed traction, on the cone to rounding) takes the slip branch and
/// its tangent, free along the slip direction (the *slip predictor*: see
/// the module docs, "Status at the start of an increment").
pub const ON_THE_CONE: f64 = 1e-9;

/// The return mapping (see the module docs) of one closed node with the
/// committed traction and slip of `kinematics` and normal `pressure`,
/// differentiated with respect to the `K` unknowns they depend on.
pub fn return_map_on<K: Dim>(
    law: &Coulomb,
    kinematics: &SlipKinematics<K>,
    pressure: &NormalPressure<K>,
) -> TangentialResponse<K>
where
    DefaultAllocator: QAllocator<K>,
{
    let n = kinematics.normal;
    let projector = Matrix3::identity() - n * n.transpose();
    let eps = law.tangential_penalty;
    let d = kinematics.offset;
    let old_traction = &kinematics.traction;
    let old = projector * old_traction;
    let slip = projector * d;
    let trial = old - eps * slip;
    let trial_gradient = projection_derivative(kinematics, old_traction)
        + projector * &kinematics.traction_gradient
        - eps * (projector * &kinematics.offset_gradient + projection_derivative(kinematics, &d));
    let bound = law.coefficient * pressure.value;
    let size = trial.norm();
    if size == 0.0 || size < (1.0 - ON_THE_CONE) * bound {
        return TangentialResponse {
            traction: trial,
            status: ContactStatus::Stick,
            traction_gradient: trial_gradient.clone(),
            traction_multiplier_derivative: Vector3::zeros(),
            multiplier_gradient: projector,
            trial_gradient,
            stick_scale: 1.0,
            multiplier_residual: -slip,
            slip_increment: Vector3::zeros(),
        };
    }
    let m = trial / size;
    let traction = bound * m;
    let mu = law.coefficient;
    TangentialResponse {
        traction,
        status: ContactStatus::Slip,
        traction_gradient: (bound / size)
            * (Matrix3::identity() - m * m.transpose())
            * &trial_gradient
            + mu * m * pressure.gradient.transpose(),
        traction_multiplier_derivative: mu * pressure.multiplier_derivative * m,
        multiplier_gradient: (bound / size) * (Matrix3::identity() - m * m.transpose()) * projector,
        trial_gradient,
        stick_scale: bound / size,
        multiplier_residual: (traction - old) / eps,
        slip_increment: slip + (traction - old) / eps,
    }
}

/// First-contact anchoring: the slip of a node that was open at the last
/// converged increment (committed gap `g_n > 0`, no traction) counts from
/// where its path meets the surface, not from where it was. Along the
/// straight path from its committed position the gap falls from `g_n` to
/// `g`; it meets the surface at the fraction `α = g_n/(g_n − g)` (`α = 1`
/// while `g ≥ 0`: not through yet), so the offset after first contact is
/// ```text
/// d' = (1 − α) d,     ∂d'/∂q = (1 − α) ∂d/∂q − d ⊗ ∂α/∂q,
/// ∂α/∂q = g_n/(g_n − g)² ∇g   (g < 0 < g_n; zero otherwise)
/// ```
/// With an exact normal constraint (`g = 0` at convergence) a closing node
/// carries no tangential traction and no slip from its approach; with a
/// penalty it slips only along the part of its path beyond the surface.
/// A node that touched at the last commit (`g_n ≤ 0`) keeps `d`.
pub fn first_contact<K: Dim>(
    kinematics: &mut SlipKinematics<K>,
    committed_gap: f64,
    gap: f64,
    gap_gradient: &OVector<f64, K>,
) where
    DefaultAllocator: QAllocator<K>,
{
    if !(committed_gap > 0.0) {
        return;
    }
    let d = kinematics.offset;
    let (alpha, alpha_gradient) = if gap < 0.0 {
        let denominator = committed_gap - gap;
        (
            committed_gap / denominator,
            (committed_gap / (denominator * denominator)) * gap_gradient,
        )
    } else {
        (
            1.0,
            OVector::zeros_generic(gap_gradient.shape_generic().0, U1),
        )
    };
    kinematics.offset = (1.0 - alpha) * d;
    kinematics.offset_gradient =
        (1.0 - alpha) * &kinematics.offset_gradient - d * alpha_gradient.transpose();
}

/// [`first_contact`] where the normal constraint is exact at the solution
/// (`g = 0` at every converged closed node: a normal multiplier in
/// Newton): `α = 1`, `d' = 0`, `∂d'/∂q = 0`, the value [`first_contact`]
/// takes there, in every iteration. A closing node then carries no
/// tangential traction in the increment it closes (as at the converged
/// state of [`first_contact`]), without the fraction's kink at `g = 0`:
/// `∂d'/∂q` jumps there by `d ⊗ ∇g / g_n` (zero for `g ≥ 0`), a tangential
/// stiffness `ε_T |d| / g_n` on one side only, exactly where the converged
/// state lies.
pub fn first_contact_at_solution<K: Dim>(kinematics: &mut SlipKinematics<K>)
where
    DefaultAllocator: QAllocator<K>,
{
    kinematics.offset = Vector3::zeros();
    kinematics.offset_gradient.fill(0.0);
}

/// The history with its tangential multiplier augmented (Simo–Laursen's
/// update `λ_T ← t_T`, see the module docs) to the traction of `response`
/// (`None`: the node is open, `λ_T ← 0`); anchor, slip and status stay
/// those of the last commit.
pub fn augment<K: Dim>(
    history: &FrictionHistory,
    response: Option<&TangentialResponse<K>>,
) -> FrictionHistory
where
    DefaultAllocator: QAllocator<K>,
{
    FrictionHistory {
        traction: response.map_or_else(Vector3::zeros, |r| r.traction),
        ..*history
    }
}

/// How exact stick finds its tangential multiplier `λ_T` (`[[contact]]
/// friction_multiplier`; see the module docs, "Exact stick").
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum FrictionMultiplier {
    /// Two unknowns of Newton per node beside the normal multiplier
    /// (Alart–Curnier's monolithic form, [`multiplier_rows`]): one Newton
    /// solve per increment. The laws with a multiplier dof (Rockafellar,
    /// slack).
    #[default]
    Newton,
    /// Simo–Laursen's outer loop: `λ_T` held fixed during Newton, updated
    /// after each converged solve ([`augment`]).
    Outer,
}

/// Relative size of the diagonal shift `−δ`, `δ = 1e-6 A_s ε_T`, that
/// [`multiplier_rows`] puts in the Jacobian (not the residual) of a closed
/// node's tangential rows: their block `∂r_ℓ/∂ℓ` is zero in stick, and
/// `(β − 1) A_s ε_T → 0` across the slip direction when a node has just
/// reached the cone (`β → 1`), so where the node's tangential motion is
/// prescribed (a node on a symmetry plane: no coupling to its
/// displacement either) the rows would be singular. Newton's step changes
/// by `O(1e-6)` relative, its rate stays.
pub const STICK_SHIFT: f64 = 1e-6;

/// The tangential multiplier of a node as two unknowns of Newton: scaled
/// components `ℓ = (ℓ¹, ℓ²)` on a fixed orthonormal pair `(e₁, e₂)`,
/// `λ_T = ε_T (ℓ¹ e₁ + ℓ² e₂)` (a length, like the normal `λ = t_N/k`:
/// `ε_T` is a pure scaling, as `k` is). The return mapping reads the
/// projection `T λ_T` on the current tangent plane, so the pair need not
/// be tangent, only not normal to it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TangentialMultiplier {
    /// `(e₁, e₂)`.
    pub basis: [Vector3<f64>; 2],
    /// `ε_T`.
    pub scale: f64,
    /// `(ℓ¹, ℓ²)`.
    pub values: [f64; 2],
}

impl TangentialMultiplier {
    /// `λ_T = ε_T (ℓ¹ e₁ + ℓ² e₂)`.
    pub fn vector(&self) -> Vector3<f64> {
        self.scale * (self.values[0] * self.basis[0] + self.values[1] * self.basis[1])
    }

    /// `ε_T E`, `E = [e₁ e₂]`: `∂λ_T/∂ℓ`.
    fn gradient(&self) -> SMatrix<f64, 3, 2> {
        self.scale * SMatrix::<f64, 3, 2>::from_columns(&self.basis)
    }
}

/// `|n_d|` below which a prescribed axis `d` counts as tangential: the
/// rule of [`HeldTangent`] holds the traction along `T e_d` there (above
/// it the axis is nearer the normal, and what its prescription leaves
/// undetermined is the normal traction, which the normal law fixes).
pub const AXIS_NEAR_PLANE: f64 = 0.5;

/// The tangential directions along which a sticking secondary node's
/// traction is not determined by the equations, and the rule that fixes
/// it there (DESIGN.md, "Coulomb friction", "An undetermined tangential
/// traction").
///
/// A node with a prescribed component `d` (a symmetry plane's `u_y`, a
/// held face) has `3 − p` free dofs, `p` the number prescribed, but exact
/// stick imposes three equations on its motion `d`: `g = 0` and `T d = 0`,
/// rows `[n  τ_d  τ⊥]ᵀ` of an orthonormal frame restricted to the free
/// columns. Their left null vector is `(n_d, |T e_d|, 0)`: the
/// combination `n_d g + |T e_d| τ_d·d` is the prescribed component
/// `e_d·d`, which no free dof moves. Dually, the node's force `A t` enters
/// only the free rows, so the traction is known up to `s e_d = s (n_d n +
/// T e_d)`: where `|n_d| < `[`AXIS_NEAR_PLANE`] that is the tangential
/// component along
/// ```text
/// τ_d = T e_d / |T e_d|
/// ```
/// (and a little normal traction). Replacing the stick row along `τ_d` by
/// ```text
/// τ_d·(λ_T − t_T,n) = 0            (the undetermined component keeps its committed value)
/// ```
/// leaves rows `n`, `τ⊥` on the free dofs, of determinant `±|T e_d|`: the
/// node's motion is determined by `g = 0` and the stick across `τ_d`, its
/// multiplier along `τ_d` by the rule. `λ_T` is the trial's old traction
/// (the multiplier of exact stick), so the traction there is `τ_d·t_T =
/// τ_d·t_T,n − ε_T τ_d·T d` in stick. Two such axes: the whole tangent
/// plane, `T (λ_T − t_T,n) = 0`. The rule holds in stick and slip alike
/// (the multiplier, not the status, is what is held), on both paths: the
/// monolithic one replaces the rows of Alart–Curnier's `ℓ`
/// ([`multiplier_rows`]), the condensed one the multiplier inside its
/// node law ([`held_multiplier`]). A node with no prescribed tangential
/// axis is unchanged. On dual mortar the node is the secondary node `j`
/// with its normal `n_j` and its own prescribed components, except where
/// all three are prescribed (Newton keeps its stick rows there: they move
/// the primary; `ContactInterface::holds_tangent`). The clash is the one 4C's manual names "contact and
/// symmetry conditions" (a contact surface touching a Dirichlet plane):
/// it drops the contact condition at those nodes (`RemoveDBCSlaveNodes`)
/// or flags the Dirichlet directions per node ("mortar symmetry
/// conditions", `ONOFF`) so that the two coexist; the rule here is the
/// second kind, kept to the one component the equations leave free.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum HeldTangent {
    /// No prescribed axis near the tangent plane: the rule does not apply.
    None,
    /// One, axis `d`: `τ_d = T e_d/|T e_d|`, `P = τ_d τ_dᵀ`.
    Axis(usize),
    /// Two or more: the whole tangent plane, `P = T`.
    Plane,
}

impl HeldTangent {
    /// The held directions of a node with unit normal `n` and `prescribed`
    /// components.
    pub fn of(n: &Vector3<f64>, prescribed: [bool; 3]) -> Self {
        let mut axes = (0..3).filter(|&d| prescribed[d] && n[d].abs() < AXIS_NEAR_PLANE);
        match (axes.next(), axes.next()) {
            (None, _) => HeldTangent::None,
            (Some(d), None) => HeldTangent::Axis(d),
            _ => HeldTangent::Plane,
        }
    }

    /// `P w`, `P` the projector on the held directions at normal `n`
    /// (zero, `τ_d τ_dᵀ` or `T`), and `∂(P w)/∂q` at fixed `w` with
    /// `∂n/∂q = n_prime`:
    /// ```text
    /// Axis(d):  v = e_d − n n_d,  P w = v (v·w)/(v·v),
    ///           ∂(P w)/∂q = [((v·w) I + v wᵀ)/(v·v) − 2 (v·w) v vᵀ/(v·v)²] ∂v/∂q,
    ///           ∂v/∂q = −(n (∂n/∂q)_d + n_d ∂n/∂q)
    /// Plane:    T w,  −(n·w) ∂n/∂q − n (wᵀ ∂n/∂q)
    /// ```
    pub fn project<K: Dim>(
        &self,
        n: &Vector3<f64>,
        n_prime: &OMatrix<f64, U3, K>,
        w: &Vector3<f64>,
    ) -> (Vector3<f64>, OMatrix<f64, U3, K>)
    where
        DefaultAllocator: QAllocator<K>,
    {
        match *self {
            HeldTangent::None => (Vector3::zeros(), n_prime * 0.0),
            HeldTangent::Plane => (
                w - n * n.dot(w),
                -n.dot(w) * n_prime - n * (w.transpose() * n_prime),
            ),
            HeldTangent::Axis(d) => {
                let v = unit_axis(d) - n * n[d];
                let (s, vw) = (v.norm_squared(), v.dot(w));
                let dv = -(n * n_prime.row(d) + n[d] * n_prime);
                let m = (vw * Matrix3::identity() + v * w.transpose()) / s
                    - (2.0 * vw / (s * s)) * v * v.transpose();
                (v * (vw / s), m * dv)
            }
        }
    }

    /// The projector `P` on the held directions at normal `n`.
    pub fn projector(&self, n: &Vector3<f64>) -> Matrix3<f64> {
        let fixed = Matrix3::<f64>::zeros();
        Matrix3::from_columns(&[0, 1, 2].map(|j| self.project(n, &fixed, &unit_axis(j)).0))
    }
}

/// `e_d`.
fn unit_axis(d: usize) -> Vector3<f64> {
    Vector3::ith(d, 1.0)
}

/// The multiplier of exact stick under the rule of [`HeldTangent`]: `λ`
/// with its held components replaced by the committed traction's,
/// `λ + P (t_T,n − λ)`, and `I − P` (its derivative with respect to `λ`).
/// The condensed path's node law takes `λ = T t`.
pub fn held_multiplier(
    held: &HeldTangent,
    n: &Vector3<f64>,
    lambda: &Vector3<f64>,
    committed: &Vector3<f64>,
) -> (Vector3<f64>, Matrix3<f64>) {
    let p = held.projector(n);
    (lambda + p * (committed - lambda), Matrix3::identity() - p)
}

/// What [`multiplier_rows`] needs of a node under the rule of
/// [`HeldTangent`]: the held directions and the committed traction
/// `t_T,n` as the producer carries it, with `∂t_T,n/∂q` (zero against a
/// rigid obstacle).
#[derive(Clone, Debug, PartialEq)]
pub struct HeldTraction<K: Dim>
where
    DefaultAllocator: QAllocator<K>,
{
    pub held: HeldTangent,
    pub committed: Vector3<f64>,
    pub committed_gradient: OMatrix<f64, U3, K>,
}

/// The equations of a tangential multiplier ([`multiplier_rows`]) and
/// their derivatives.
#[derive(Clone, Debug, PartialEq)]
pub struct MultiplierRows<K: Dim>
where
    DefaultAllocator: QAllocator<K>,
{
    /// `r_ℓ = A_s Eᵀ (t_T − T λ_T)`.
    pub residual: Vector2<f64>,
    /// `∂r_ℓ/∂q`.
    pub gradient: OMatrix<f64, U2, K>,
    /// `∂r_ℓ/∂ℓ` (with the shift [`STICK_SHIFT`] where closed).
    pub multiplier: Matrix2<f64>,
    /// `∂r_ℓ/∂λ` (the normal multiplier; nonzero in slip).
    pub normal_multiplier: Vector2<f64>,
    /// `A_s ∂t_T/∂ℓ = A_s (∂t_T/∂λ_T) ε_T E`: the node's rows get `−Bᵀ`
    /// of it (`B` the lever of [`SlipFrame`](super::kinematics::SlipFrame)).
    pub force_gradient: SMatrix<f64, 3, 2>,
}

/// Alart–Curnier's tangential equations of one node of area `A_s` with
/// the multiplier `λ_T` of `multiplier`, at the return mapping (the
/// response) of the kinematics in `closed`, whose committed traction is
/// `λ_T` (`None`: the node is open). The complementarity function
/// ```text
/// C_T(λ_T, q) = λ_T − P_{μ t_N}(T λ_T − ε_T T d) = T λ_T − t_T
/// r_ℓ = −A_s Eᵀ C_T = A_s Eᵀ (t_T − T λ_T)       (closed)
/// r_ℓ = −A_s ε_T ℓ                                (open: λ_T = 0)
/// ```
/// vanishes in stick where `T d = 0` (the node does not move: `r_ℓ =
/// −A_s ε_T Eᵀ T d`), in slip where `T λ_T = μ t_N m` on the cone with the
/// slip `T d` along `−m`: Coulomb's law exactly, whatever `ε_T`. The force
/// on the node is the return mapping's `t_T`, so in stick on a plane the
/// blocks `∂r_q/∂ℓ = −A_s ε_T T E` and `∂r_ℓ/∂q = −A_s ε_T Eᵀ T` are each
/// other's transpose. Derivatives (`T' = ∂(T v)/∂q` at fixed `v`,
/// `projection_derivative`):
/// ```text
/// ∂r_ℓ/∂q = A_s Eᵀ (∂t_T/∂q − T' λ_T − T ∂λ_T/∂q)
/// ∂r_ℓ/∂ℓ = A_s ε_T Eᵀ (∂t_T/∂λ_T − T) E      (0 in stick; −A_s ε_T along m and
///                                              (β − 1) A_s ε_T across it in slip)
/// ∂r_ℓ/∂λ = A_s Eᵀ ∂t_T/∂λ
/// ```
/// Where `held` is given (a closed node with a prescribed tangential
/// axis, [`HeldTangent`]), the rows along the held directions (projector
/// `P`) are the rule `P (t_T,n − λ_T) = 0`:
/// ```text
/// r_ℓ = A_s Eᵀ [(I − P)(t_T − T λ_T) + P (t_T,n − λ_T)]
/// ```
/// differentiated with `P(q)` and `t_T,n(q)` ([`HeldTangent::project`]).
pub fn multiplier_rows<K: Dim>(
    multiplier: &TangentialMultiplier,
    closed: Option<(&SlipKinematics<K>, &TangentialResponse<K>)>,
    area: f64,
    held: Option<&HeldTraction<K>>,
) -> MultiplierRows<K>
where
    DefaultAllocator: QAllocator<K>,
{
    let e = multiplier.gradient() / multiplier.scale;
    let dlambda = multiplier.gradient();
    let Some((kinematics, r)) = closed else {
        let block = -area * multiplier.scale * e.transpose() * e;
        return MultiplierRows {
            residual: block * Vector2::from(multiplier.values),
            gradient: OMatrix::zeros_generic(U2, natural_dim()),
            multiplier: block,
            normal_multiplier: Vector2::zeros(),
            force_gradient: SMatrix::zeros(),
        };
    };
    let lambda = multiplier.vector();
    let n = kinematics.normal;
    let projector = Matrix3::identity() - n * n.transpose();
    let projected_gradient =
        projection_derivative(kinematics, &lambda) + projector * &kinematics.traction_gradient;
    let inner = r.traction - projector * lambda;
    let inner_gradient = &r.traction_gradient - projected_gradient;
    let mut inner_lambda = r.multiplier_gradient - projector;
    let mut normal = r.traction_multiplier_derivative;
    let (residual, gradient) = match held.filter(|h| h.held != HeldTangent::None) {
        None => (inner, inner_gradient),
        Some(h) => {
            let p = h.held.projector(&n);
            let w = h.committed - lambda - inner;
            let (pw, dpw) = h.held.project(&n, &kinematics.normal_gradient, &w);
            let free = Matrix3::identity() - p;
            inner_lambda = free * inner_lambda - p;
            normal = free * normal;
            let gradient = free * inner_gradient + dpw + p * &h.committed_gradient;
            (inner + pw, gradient)
        }
    };
    let block = area * e.transpose() * inner_lambda * dlambda
        - STICK_SHIFT * area * multiplier.scale * Matrix2::identity();
    MultiplierRows {
        residual: area * e.transpose() * residual,
        gradient: area * e.transpose() * gradient,
        multiplier: block,
        normal_multiplier: area * e.transpose() * normal,
        force_gradient: area * r.multiplier_gradient * dlambda,
    }
}

/// The history after an increment converged with the node in `response`
/// (`None`: the node is open) at `relative_position` (the caller of a
/// deformable interface then records the node's new material point).
pub fn commit<K: Dim>(
    history: &FrictionHistory,
    response: Option<&TangentialResponse<K>>,
    relative_position: Vector3<f64>,
) -> FrictionHistory
where
    DefaultAllocator: QAllocator<K>,
{
    let r = response.cloned().unwrap_or_else(TangentialResponse::none);
    FrictionHistory {
        traction: r.traction,
        anchor: relative_position,
        slip: history.slip + r.slip_increment,
        status: r.status,
        material_point: None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const MU: f64 = 0.3;
    const EPS_T: f64 = 500.0;
    const P: f64 = 800.0;
    const K: f64 = 300.0;

    /// A Rockafellar-like pressure `t_N = kλ − p g` around a state.
    fn pressure_at(gap: &GapGeometry, lambda: f64) -> NormalPressure {
        NormalPressure {
            value: K * lambda - P * gap.signed_gap,
            gradient: -P * gap.normal,
            multiplier_derivative: K,
        }
    }

    fn sphere(x: &Vector3<f64>) -> GapGeometry {
        GapGeometry::sphere(x, &Vector3::new(0.1, -0.2, -1.0), 1.0)
    }

    fn plane(x: &Vector3<f64>) -> GapGeometry {
        GapGeometry::plane(x, &Vector3::zeros(), &Vector3::new(0.1, 0.2, 1.0))
    }

    fn law() -> Coulomb {
        Coulomb {
            coefficient: MU,
            tangential_penalty: EPS_T,
        }
    }

    /// `∂t_T/∂x_s` and `∂t_T/∂λ` against central differences of the return
    /// mapping (geometry re-evaluated at each perturbed point).
    fn check_tangent(
        geometry: fn(&Vector3<f64>) -> GapGeometry,
        x: Vector3<f64>,
        lambda: f64,
        history: &FrictionHistory,
        expect: ContactStatus,
    ) {
        let response = |x: &Vector3<f64>, l: f64| {
            let g = geometry(x);
            return_map(&law(), history, x, &g, &pressure_at(&g, l))
        };
        let r0 = response(&x, lambda);
        assert_eq!(r0.status, expect);
        let h = 1e-7;
        let scale = r0.traction_gradient.norm().max(1.0);
        for j in 0..3 {
            let mut e = Vector3::zeros();
            e[j] = h;
            let fd = (response(&(x + e), lambda).traction - response(&(x - e), lambda).traction)
                / (2.0 * h);
            let err = (fd - r0.traction_gradient.column(j)).norm();
            assert!(
                err < 1e-6 * scale,
                "{expect:?} column {j}: fd {fd:?} vs {:?}",
                r0.traction_gradient.column(j).into_owned()
            );
        }
        let fd =
            (response(&x, lambda + h).traction - response(&x, lambda - h).traction) / (2.0 * h);
        let err = (fd - r0.traction_multiplier_derivative).norm();
        assert!(
            err < 1e-6 * scale.max(K),
            "λ: fd {fd:?} vs {:?}",
            r0.traction_multiplier_derivative
        );
    }

    #[test]
    fn stick_and_slip_tangents_match_finite_differences() {
        for geometry in [plane as fn(&Vector3<f64>) -> GapGeometry, sphere] {
            let x = Vector3::new(0.05, 0.02, -0.003);
            let n = geometry(&x).normal;
            // an old traction in the current tangent plane and a small move
            let t_old = Vector3::new(1.0, -0.5, 0.0);
            let t_old = t_old - n * n.dot(&t_old);
            let small = FrictionHistory {
                traction: t_old,
                anchor: x - Vector3::new(1e-4, 2e-4, 0.0),
                ..Default::default()
            };
            check_tangent(geometry, x, 0.1, &small, ContactStatus::Stick);
            // a long move slips
            let far = FrictionHistory {
                anchor: x - Vector3::new(0.02, -0.01, 0.0),
                ..small
            };
            check_tangent(geometry, x, 0.1, &far, ContactStatus::Slip);
        }
    }

    /// Near the cone's tip (`t_N` a thousandth of `|t_T*|/μ`): the slip
    /// branch with `β = μ t_N/|t_T*| ≈ 1e-3`, whose tangent is dominated by
    /// the normal coupling `μ m ⊗ ∂t_N/∂(x, λ)`; and a node on the cone to
    /// rounding, which slips (the slip predictor).
    #[test]
    fn tangents_at_the_cone_tip_match_finite_differences() {
        for geometry in [plane as fn(&Vector3<f64>) -> GapGeometry, sphere] {
            let x = Vector3::new(0.05, 0.02, -0.003);
            let g = geometry(&x);
            let moved = x - Vector3::new(0.01, -0.005, 0.0);
            let trial = EPS_T * (x - moved - g.normal * g.normal.dot(&(x - moved))).norm();
            // t_N = K λ − P g = 1e-3 |t*|/μ
            let lambda = (1e-3 * trial / MU + P * g.signed_gap) / K;
            let history = FrictionHistory::at(moved);
            let r = return_map(&law(), &history, &x, &g, &pressure_at(&g, lambda));
            assert!((r.stick_scale - 1e-3).abs() < 1e-4, "β = {}", r.stick_scale);
            check_tangent(geometry, x, lambda, &history, ContactStatus::Slip);
        }
        // on the cone to rounding: the committed traction of a slipping node
        let x = Vector3::new(0.0, 0.0, -0.001);
        let g = plane(&x);
        let p = pressure_at(&g, 0.01);
        let n = g.normal;
        let m = Vector3::new(0.6, 0.8, 0.0);
        let m = (m - n * n.dot(&m)).normalize();
        let on_cone = FrictionHistory {
            traction: MU * p.value * m * (1.0 - 1e-12),
            ..FrictionHistory::at(x)
        };
        let r = return_map(&law(), &on_cone, &x, &g, &p);
        assert_eq!(r.status, ContactStatus::Slip);
        assert!((r.traction - on_cone.traction).norm() < 1e-9 * MU * p.value);
        // free along the slip direction m (the stick tangent holds it with ε_T)
        assert!((r.traction_gradient * m).norm() < 1e-9 * EPS_T);
    }

    /// The augmented Lagrangian's outer loop on one node between a
    /// tangential spring `k_s` (anchored at the origin, loaded by `F` along
    /// x) and a plane: Newton on `x` with `λ_T` fixed, then `λ_T ← t_T`.
    /// Stuck (`|F| < μ t_N`), the node ends where it started to 1e-12 and
    /// carries `t_T = F`, whatever `ε_T`; each update leaves
    /// `k_s/(k_s + A ε_T)` of the error (here `A = 1`).
    #[test]
    fn augmented_stick_is_exact_whatever_the_penalty() {
        let (k_s, force) = (200.0, 1.5);
        let p = NormalPressure {
            value: 10.0,
            gradient: Vector3::zeros(),
            multiplier_derivative: 0.0,
        };
        for eps in [50.0, 500.0, 5000.0] {
            let coulomb = Coulomb {
                coefficient: MU,
                tangential_penalty: eps,
            };
            let mut history = FrictionHistory::default();
            let mut x = Vector3::zeros();
            let mut updates = 0;
            loop {
                // Newton on k_s x − F e_x − t_T(x) = 0 (linear in stick)
                for _ in 0..5 {
                    let g = plane(&x);
                    let r = return_map(&coulomb, &history, &x, &g, &p);
                    let residual = k_s * x - Vector3::new(force, 0.0, 0.0) - r.traction;
                    let tangent = k_s * Matrix3::identity() - r.traction_gradient;
                    x -= tangent.lu().solve(&residual).unwrap();
                }
                let g = plane(&x);
                let r = return_map(&coulomb, &history, &x, &g, &p);
                assert_eq!(r.status, ContactStatus::Stick);
                if r.multiplier_residual.norm() < 1e-13 {
                    break;
                }
                let before = r.multiplier_residual.norm();
                history = augment(&history, Some(&r));
                assert_eq!(history.traction, r.traction, "λ_T ← t_T");
                updates += 1;
                assert!(updates < 1000, "ε_T = {eps}: {before:e}");
            }
            // T x = 0, and the traction balances the load's tangential part
            let n = plane(&x).normal;
            let projector = Matrix3::identity() - n * n.transpose();
            assert!((projector * x).norm() < 1e-12, "ε_T = {eps}: moved {x}");
            let load = projector * Vector3::new(force, 0.0, 0.0);
            assert!((history.traction + load).norm() < 1e-9 * force);
            let rate = k_s / (k_s + eps);
            let expected = (1e-13_f64.ln() / rate.ln()).ceil() as usize + 3;
            assert!(updates <= expected, "ε_T = {eps}: {updates} updates");
        }
    }

    /// The tangential multiplier's equations ([`multiplier_rows`]) of one
    /// node against a rigid obstacle, with `λ_T` from `ℓ` (basis `x`, `y`):
    /// `(r_ℓ, r_q)`, `r_q = −A_s t_T` the node's friction force.
    fn multiplier_equations(
        geometry: fn(&Vector3<f64>) -> GapGeometry,
        x: &Vector3<f64>,
        l: [f64; 2],
        lambda: f64,
        anchor: &Vector3<f64>,
        held: Option<(HeldTangent, Vector3<f64>)>,
    ) -> (
        Vector2<f64>,
        Vector3<f64>,
        MultiplierRows<U3>,
        TangentialResponse,
    ) {
        let area = 0.7;
        let multiplier = TangentialMultiplier {
            basis: [Vector3::x(), Vector3::y()],
            scale: EPS_T,
            values: l,
        };
        let history = FrictionHistory {
            traction: multiplier.vector(),
            ..FrictionHistory::at(*anchor)
        };
        let g = geometry(x);
        let kinematics = SlipKinematics::rigid(&history, x, &g.normal, &g.hessian);
        let t = return_map_on(&law(), &kinematics, &pressure_at(&g, lambda));
        let held = held.map(|(held, committed)| HeldTraction {
            held,
            committed,
            committed_gradient: Matrix3::zeros(),
        });
        let rows = multiplier_rows(&multiplier, Some((&kinematics, &t)), area, held.as_ref());
        (rows.residual, -area * t.traction, rows, t)
    }

    /// `∂r_ℓ/∂(x, ℓ, λ)` and `∂r_q/∂ℓ` of [`multiplier_rows`] against
    /// central differences (the shift `−δ` of the `ℓ` block taken out).
    fn check_multiplier_rows(
        geometry: fn(&Vector3<f64>) -> GapGeometry,
        x: Vector3<f64>,
        l: [f64; 2],
        lambda: f64,
        anchor: Vector3<f64>,
        expect: ContactStatus,
        held: Option<(HeldTangent, Vector3<f64>)>,
    ) {
        let (_, _, rows, t) = multiplier_equations(geometry, &x, l, lambda, &anchor, held);
        assert_eq!(t.status, expect);
        let h = 1e-8;
        let scale = rows.gradient.norm().max(rows.multiplier.norm()).max(1.0);
        let close = |fd: Vector2<f64>, exact: Vector2<f64>, what: &str| {
            assert!(
                (fd - exact).norm() < 1e-6 * scale,
                "{expect:?} {what}: fd {fd:?} vs {exact:?}"
            );
        };
        for j in 0..3 {
            let mut e = Vector3::zeros();
            e[j] = h;
            let (rp, _, _, _) = multiplier_equations(geometry, &(x + e), l, lambda, &anchor, held);
            let (rm, _, _, _) = multiplier_equations(geometry, &(x - e), l, lambda, &anchor, held);
            close(
                (rp - rm) / (2.0 * h),
                rows.gradient.column(j).into(),
                "∂r_ℓ/∂x",
            );
        }
        let shift = STICK_SHIFT * 0.7 * EPS_T * Matrix2::identity();
        for j in 0..2 {
            let (mut lp, mut lm) = (l, l);
            lp[j] += h;
            lm[j] -= h;
            let (rp, fp, _, _) = multiplier_equations(geometry, &x, lp, lambda, &anchor, held);
            let (rm, fm, _, _) = multiplier_equations(geometry, &x, lm, lambda, &anchor, held);
            let exact = (rows.multiplier + shift).column(j).into();
            close((rp - rm) / (2.0 * h), exact, "∂r_ℓ/∂ℓ");
            let fd = (fp - fm) / (2.0 * h);
            let exact = -rows.force_gradient.column(j);
            assert!(
                (fd - exact).norm() < 1e-6 * scale,
                "∂r_q/∂ℓ: {fd:?} vs {exact:?}"
            );
        }
        let (rp, _, _, _) = multiplier_equations(geometry, &x, l, lambda + h, &anchor, held);
        let (rm, _, _, _) = multiplier_equations(geometry, &x, l, lambda - h, &anchor, held);
        close((rp - rm) / (2.0 * h), rows.normal_multiplier, "∂r_ℓ/∂λ");
    }

    /// The tangential multiplier's equations in stick (a multiplier inside
    /// the cone, a small motion), in slip (a long motion), at the cone's
    /// tip (`t_N` a thousandth of the trial's bound) and at its edge (a
    /// trial `1e-6` outside the cone, and one `1e-6` inside), on a plane
    /// and on a sphere; and their solution is Coulomb's law: in stick
    /// `r_ℓ = −A_s ε_T Eᵀ T d`.
    #[test]
    fn tangential_multiplier_rows_match_finite_differences() {
        for geometry in [plane as fn(&Vector3<f64>) -> GapGeometry, sphere] {
            let x = Vector3::new(0.05, 0.02, -0.003);
            let (near, far) = (
                Vector3::new(1e-5, 2e-5, 0.0),
                Vector3::new(0.02, -0.01, 0.0),
            );
            check_multiplier_rows(
                geometry,
                x,
                [2e-4, -1e-4],
                0.1,
                x - near,
                ContactStatus::Stick,
                None,
            );
            check_multiplier_rows(
                geometry,
                x,
                [2e-4, -1e-4],
                0.1,
                x - far,
                ContactStatus::Slip,
                None,
            );
            // the tip: t_N = K λ − P g = 1e-3 |t*|/μ
            let g = geometry(&x);
            let (_, _, _, t) =
                multiplier_equations(geometry, &x, [0.0, 0.0], 0.1, &(x - far), None);
            let size = t.traction.norm() / t.stick_scale;
            let lambda = (1e-3 * size / MU + P * g.signed_gap) / K;
            check_multiplier_rows(
                geometry,
                x,
                [0.0, 0.0],
                lambda,
                x - far,
                ContactStatus::Slip,
                None,
            );
            // the edge: |t*| = (1 ± 1e-6) μ t_N
            for (factor, status) in [
                (1.0 + 1e-6, ContactStatus::Slip),
                (1.0 - 1e-6, ContactStatus::Stick),
            ] {
                let lambda = (size / (MU * factor) + P * g.signed_gap) / K;
                check_multiplier_rows(geometry, x, [0.0, 0.0], lambda, x - far, status, None);
            }
            // stick: the equations say the node does not move
            let (r, _, _, _) =
                multiplier_equations(geometry, &x, [2e-4, -1e-4], 0.1, &(x - near), None);
            let n = g.normal;
            let slip = near - n * n.dot(&near);
            let expected = -0.7 * EPS_T * Vector2::new(slip.x, slip.y);
            assert!(
                (r - expected).norm() < 1e-12 * EPS_T,
                "{r:?} vs {expected:?}"
            );
        }
    }

    /// The rows under the rule of [`HeldTangent`] (one held axis, `y`,
    /// and the whole plane) against central differences in stick and slip
    /// on a plane and a sphere (whose `P` turns with the node); and their
    /// solution: in stick the held component of `λ_T` is the committed
    /// traction's, the other row still says the node does not move.
    #[test]
    fn held_tangential_rows_match_finite_differences() {
        for geometry in [plane as fn(&Vector3<f64>) -> GapGeometry, sphere] {
            let x = Vector3::new(0.05, 0.02, -0.003);
            let (near, far) = (
                Vector3::new(1e-5, 2e-5, 0.0),
                Vector3::new(0.02, -0.01, 0.0),
            );
            let n = geometry(&x).normal;
            let held = HeldTangent::of(&n, [false, true, false]);
            assert_eq!(held, HeldTangent::Axis(1));
            assert_eq!(HeldTangent::of(&n, [false, false, true]), HeldTangent::None);
            assert_eq!(HeldTangent::of(&n, [true, true, false]), HeldTangent::Plane);
            let committed = Vector3::new(3.0, -7.0, 0.5);
            for h in [held, HeldTangent::Plane] {
                let l = [2e-4, -1e-4];
                let stick = ContactStatus::Stick;
                check_multiplier_rows(geometry, x, l, 0.1, x - near, stick, Some((h, committed)));
                let slip = ContactStatus::Slip;
                check_multiplier_rows(geometry, x, l, 0.1, x - far, slip, Some((h, committed)));
            }
            // stick: P (t_T,n − λ_T) plus (I − P) of the plain rows
            let l = [2e-4, -1e-4];
            let (r, _, _, _) =
                multiplier_equations(geometry, &x, l, 0.1, &(x - near), Some((held, committed)));
            let lambda = EPS_T * Vector3::new(l[0], l[1], 0.0);
            let p = held.projector(&n);
            let slip = near - n * n.dot(&near);
            let expected =
                0.7 * ((Matrix3::identity() - p) * (-EPS_T * slip) + p * (committed - lambda));
            let expected = Vector2::new(expected.x, expected.y);
            assert!(
                (r - expected).norm() < 1e-12 * EPS_T,
                "{r:?} vs {expected:?}"
            );
            // the projector: symmetric, idempotent, tangent, along T e_y
            let tau = (Vector3::y() - n * n.y).normalize();
            assert!((p - tau * tau.transpose()).norm() < 1e-15);
        }
    }

    #[test]
    fn slip_lies_on_the_coulomb_cone_against_the_slip() {
        let x = Vector3::new(0.0, 0.0, -0.001);
        let g = plane(&x);
        let history = FrictionHistory::at(x - Vector3::new(0.05, 0.0, 0.0));
        let p = pressure_at(&g, 0.01);
        let r = return_map(&law(), &history, &x, &g, &p);
        assert_eq!(r.status, ContactStatus::Slip);
        assert!((r.traction.norm() - MU * p.value).abs() < 1e-12 * p.value);
        assert!(r.traction.dot(&g.normal).abs() < 1e-12);
        // the traction opposes the motion (+x projected), the slip follows it
        let motion = x - history.anchor;
        assert!(r.traction.dot(&motion) < 0.0);
        assert!(r.slip_increment.dot(&motion) > 0.0);
        // elastic part + slip part = the tangential motion
        let tangential_motion = motion - g.normal * g.normal.dot(&motion);
        let elastic = -r.traction / EPS_T;
        assert!((elastic + r.slip_increment - tangential_motion).norm() < 1e-15);
    }

    #[test]
    fn stick_is_elastic_and_commits_no_slip() {
        let x = Vector3::new(0.0, 0.0, -0.001);
        let g = plane(&x);
        let history = FrictionHistory::at(x - Vector3::new(1e-6, 0.0, 0.0));
        let p = pressure_at(&g, 0.01);
        let r = return_map(&law(), &history, &x, &g, &p);
        assert_eq!(r.status, ContactStatus::Stick);
        let projector = Matrix3::identity() - g.normal * g.normal.transpose();
        assert!((r.traction + EPS_T * projector * Vector3::new(1e-6, 0.0, 0.0)).norm() < 1e-15);
        let committed = commit(&history, Some(&r), x);
        assert_eq!(committed.slip, Vector3::zeros());
        assert_eq!(committed.anchor, x);
        // re-evaluated at the committed state: the same traction, still stick
        let again = return_map(&law(), &committed, &x, &g, &p);
        assert!((again.traction - r.traction).norm() < 1e-15);
        assert_eq!(again.status, ContactStatus::Stick);
    }

    #[test]
    fn open_nodes_forget_their_traction_and_keep_their_slip() {
        let h = FrictionHistory {
            traction: Vector3::new(1.0, 2.0, 0.0),
            anchor: Vector3::zeros(),
            slip: Vector3::new(0.1, 0.0, 0.0),
            status: ContactStatus::Slip,
            material_point: None,
        };
        let c = commit::<U3>(&h, None, Vector3::new(1.0, 1.0, 1.0));
        assert_eq!(c.traction, Vector3::zeros());
        assert_eq!(c.slip, h.slip);
        assert_eq!(c.status, ContactStatus::Open);
        assert_eq!(ContactStatus::Slip.code(), 2);
    }
}
