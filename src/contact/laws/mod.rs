//! Per-node normal-contact enforcement laws (formulation note §2, paper §3–4).
//!
//! Everything here is a pure function of one secondary node `s`:
//! its tributary reference area `A_s`, the signed gap `g` (`g ≥ 0` open,
//! `g < 0` penetration), the obstacle normal `n` (from the obstacle toward
//! the body), `∂g/∂x_s = n` and the gap Hessian `H = ∂²g/∂x_s²` (zero for a
//! plane, `(I − n nᵀ)/|x − c|` for a sphere centred at `c`). The geometry
//! arrives in a [`GapGeometry`]; obstacles and search live elsewhere.
//!
//! ## Signs (the crate's conventions, applied to contact)
//! - Residual `r = f_int − f_ext − f_contact`, tangent `K = ∂r/∂(u, λ)`;
//!   since `x_s = X_s + u_s`, `∂/∂u_s = ∂/∂x_s`.
//! - The contact force on the body is `A_s t_N n` with pressure `t_N ≥ 0`
//!   (compressive positive), so the node's residual receives `−A_s t_N n`.
//! - Where a potential `A_s Φ` exists, the residual is its gradient and the
//!   tangent its Hessian. The curvature term is therefore always
//!   `(∂(A_s Φ)/∂g) H = −A_s t H`, with `t` the (augmented) pressure of the
//!   active branch: it *softens* `K_uu` in the tangential directions of a
//!   convex obstacle.
//! - For the multiplier laws ([`rockafellar`], [`slack`]) the global
//!   multiplier `λ` is scaled so that `t_N = kλ` at a converged active node
//!   (formulation note §2.1 item 3). The slack law's own multiplier
//!   `λ_paper = −λ` is converted inside [`slack`], so one assembly path
//!   serves both.
//!
//! ## Laws, one per file
//! | law | file | unknowns per node | note |
//! |---|---|---|---|
//! | penalty | [`penalty`] | – | `t_N = ε⟨−g⟩` |
//! | augmented Lagrangian, Uzawa | [`uzawa`] | `λ` fixed in Newton, updated outside | `t_N = ⟨λ − εg⟩` |
//! | Rockafellar, monolithic | [`rockafellar`] | global `λ` | `t_N = ⟨kλ − pg⟩` |
//! | slack-variable Rockafellar (the paper) | [`slack`] | global `λ`, local `s`, `λ₁` | condensed to the shape of `rockafellar` |

use nalgebra::{Matrix3, Vector3};

mod converged;
pub mod penalty;
pub mod rockafellar;
pub mod slack;
pub mod uzawa;

pub use crate::contact::gap::GapGeometry;
pub use converged::NormalEnforcement;
pub use slack::SlackState;

/// What one secondary node adds to the residual and tangent of the global
/// `(u, λ)` system.
///
/// Rows/columns: `u` is the node's three displacement dofs, `λ` its (scaled)
/// multiplier when the law has one. Laws without a multiplier dof leave the
/// `λ` entries at zero.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NodeContribution {
    /// `∂(A_s Φ)/∂x_s`: for every law `−A_s t n`, `t` the branch's pressure.
    pub r_u: Vector3<f64>,
    /// Constraint residual `∂(A_s Φ)/∂λ` (0 without a multiplier dof).
    pub r_lambda: f64,
    /// `∂r_u/∂u` (symmetric).
    pub k_uu: Matrix3<f64>,
    /// `∂r_u/∂λ = (∂r_λ/∂u)ᵀ`.
    pub k_ulambda: Vector3<f64>,
    /// `∂r_λ/∂λ`.
    pub k_lambdalambda: f64,
    /// Contact pressure `t_N ≥ 0` (compressive positive) to report.
    pub pressure: f64,
    /// `∂t_N/∂x_s` where `t_N > 0` (zero elsewhere): what friction's bound
    /// `μ t_N` couples to.
    pub pressure_gradient: Vector3<f64>,
    /// `∂t_N/∂λ` where `t_N > 0` (zero elsewhere or without a multiplier).
    pub pressure_multiplier_derivative: f64,
    /// Whether the node transmits force in this state (the switch of the law).
    pub active: bool,
}

impl NodeContribution {
    /// No contribution at all: an open node of a law without multiplier.
    pub fn zero() -> Self {
        Self {
            r_u: Vector3::zeros(),
            r_lambda: 0.0,
            k_uu: Matrix3::zeros(),
            k_ulambda: Vector3::zeros(),
            k_lambdalambda: 0.0,
            pressure: 0.0,
            pressure_gradient: Vector3::zeros(),
            pressure_multiplier_derivative: 0.0,
            active: false,
        }
    }
}

/// Per-node contact state beyond the displacement.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct NodeContactState {
    /// Multiplier `λ`: a global unknown for [`NormalLaw::Rockafellar`] and
    /// [`NormalLaw::Slack`] (`t_N = kλ` at a converged active node); the
    /// multiplier held fixed during Newton for [`NormalLaw::Uzawa`]
    /// (a pressure); unused by [`NormalLaw::Penalty`].
    pub lambda: f64,
    /// Local slack unknowns `(s, λ₁)`, used only by [`NormalLaw::Slack`].
    pub slack: SlackState,
    /// Friction history committed at the last converged increment (also
    /// the status of frictionless nodes, for output).
    pub friction: crate::contact::friction::FrictionHistory,
    /// The primary triangle the node was last projected on (deformable
    /// interfaces): kept while the node stays over it, so that a node over
    /// a shared edge does not flip between two triangles from one Newton
    /// iteration to the next.
    pub facet: Option<usize>,
    /// The triangle at the last converged increment and the node's walk
    /// since: what the facet choice reads besides the position
    /// ([`FacetWalk`](crate::contact::facet_walk::FacetWalk)).
    #[serde(default)]
    pub facet_walk: crate::contact::facet_walk::FacetWalk,
    /// Signed gap at the last converged increment (at the start: the
    /// initial gap): where a node that was open finds its first contact
    /// ([`friction::first_contact`](crate::contact::friction::first_contact)).
    pub gap: f64,
    /// The coordinate axis nearest the node's normal at the start (2, `z`,
    /// without a primary then): the node's tangential multiplier
    /// ([`TangentialMultiplier`](crate::contact::friction::TangentialMultiplier))
    /// has its components on the other two axes.
    #[serde(default = "z_axis")]
    pub normal_axis: usize,
}

fn z_axis() -> usize {
    2
}

impl NodeContactState {
    /// The state of a node when it is first paired with an obstacle:
    /// `λ = 0` and, for [`NormalLaw::Slack`], the local unknowns that solve
    /// the node's own equations at gap `g` ([`SlackState::consistent`]:
    /// free with `s = −g` when open, clamped with `λ₁ = −p g/k` when
    /// penetrating). Starting from `s = λ₁ = 0` instead would sit on the
    /// switch and clamp every node, pulling open nodes onto the obstacle.
    pub fn initial(law: &NormalLaw, signed_gap: f64) -> Self {
        let slack = match *law {
            NormalLaw::Slack { p, k } => SlackState::consistent(signed_gap, 0.0, p, k),
            _ => SlackState::default(),
        };
        Self {
            lambda: 0.0,
            slack,
            friction: Default::default(),
            facet: None,
            facet_walk: Default::default(),
            gap: signed_gap,
            normal_axis: z_axis(),
        }
    }

    /// An iterate (a Newton iteration, a condensed round) projected the
    /// node on `facet`: recorded, and the walk stepped.
    pub fn move_to_facet(&mut self, facet: Option<usize>) {
        self.facet_walk.step(facet);
        self.facet = facet;
    }

    /// An increment converged (or the run starts) with the node on `facet`.
    pub fn commit_facet(&mut self, facet: Option<usize>) {
        self.facet = facet;
        self.facet_walk = crate::contact::facet_walk::FacetWalk::committed_on(facet);
    }

    /// Whether every number of the state is finite (`λ`, the slack
    /// unknowns, the friction history, the gap): a converged increment
    /// leaves them so, and a restart refuses a checkpoint that does not.
    pub fn is_finite(&self) -> bool {
        self.lambda.is_finite()
            && self.slack.is_finite()
            && self.friction.is_finite()
            && self.gap.is_finite()
    }
}

/// The normal-contact enforcement law (formulation note §2.1, items 1–4).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum NormalLaw {
    /// `t_N = ε⟨−g⟩`, `ε > 0` a pressure per unit penetration.
    Penalty { epsilon: f64 },
    /// `t_N = ⟨λ − εg⟩` with `λ` fixed during Newton, then `λ ← ⟨λ − εg⟩`.
    Uzawa { epsilon: f64 },
    /// Monolithic Rockafellar augmented Lagrangian, penalty `p`, scaling `k`.
    Rockafellar { p: f64, k: f64 },
    /// The paper's slack-variable Rockafellar Lagrangian, condensed per node.
    Slack { p: f64, k: f64 },
}

impl NormalLaw {
    /// Whether the law adds one multiplier dof `λ` per secondary node to the
    /// global system.
    pub fn has_multiplier_dof(&self) -> bool {
        matches!(self, Self::Rockafellar { .. } | Self::Slack { .. })
    }

    /// The law with its parameters scaled by `f` (a node's factor on the
    /// interface's parameters).
    pub fn scaled(&self, f: f64) -> Self {
        match *self {
            Self::Penalty { epsilon } => Self::Penalty {
                epsilon: epsilon * f,
            },
            Self::Uzawa { epsilon } => Self::Uzawa {
                epsilon: epsilon * f,
            },
            Self::Rockafellar { p, k } => Self::Rockafellar { p: p * f, k: k * f },
            Self::Slack { p, k } => Self::Slack { p: p * f, k: k * f },
        }
    }

    /// Whether the law keeps local unknowns per node that a Newton step
    /// carries along ([`apply_increment`](Self::apply_increment)): the
    /// slack law's `(s, λ₁)`.
    pub fn has_local_unknowns(&self) -> bool {
        matches!(self, Self::Slack { .. })
    }

    /// Whether the law has an outer loop around Newton that updates the
    /// multipliers ([`augmented_multiplier`](Self::augmented_multiplier)):
    /// Uzawa's.
    pub fn has_outer_loop(&self) -> bool {
        matches!(self, Self::Uzawa { .. })
    }

    /// Whether Coulomb friction on the law's nodes is the augmented
    /// Lagrangian (exact stick, an outer loop on the tangential multiplier,
    /// [`friction`](crate::contact::friction) "Exact stick"): every law
    /// with an exact normal constraint, Uzawa's, Rockafellar's and the
    /// slack law; the penalty law keeps the regularised Coulomb law.
    pub fn augments_friction(&self) -> bool {
        !matches!(self, Self::Penalty { .. })
    }

    /// The multiplier after an outer-loop update at gap `g`: Uzawa's
    /// `λ ← ⟨λ − εg⟩`; unchanged for the laws without an outer loop.
    pub fn augmented_multiplier(&self, lambda: f64, signed_gap: f64) -> f64 {
        match *self {
            Self::Uzawa { epsilon } => uzawa::update_multiplier(lambda, signed_gap, epsilon),
            _ => lambda,
        }
    }

    /// The node's residual and tangent contribution in the current state,
    /// with `support` a primary to be in contact with ([`Support`]). A node
    /// without one (no primary within the search margin, or, in dual
    /// mortar, no mortar support: `D_j ≤ 0`, or less than half of
    /// `∫ Ñ_j dA` covered) is inactive by definition (Hüeber & Wohlmuth
    /// 2005; Popp, Gee & Wall 2009), whatever its state says: the law's
    /// inactive branch at `gap` (the search margin), for the multiplier
    /// laws `r_λ = −A k²λ/p`, `K_λλ = −A k²/p`, which sends `λ` to 0 in
    /// one step; no force for the others. The switch alone would keep a
    /// node that lost its support with its pressure (`kλ ≥ p g`) active,
    /// and the active row `r_λ = −A k g` has `∂r_λ/∂λ = 0` and no
    /// `∂r_λ/∂q` without the gap's gradient: a zero row, a singular
    /// tangent.
    pub fn contribution(
        &self,
        support: Support,
        area: f64,
        gap: &GapGeometry,
        state: &NodeContactState,
    ) -> NodeContribution {
        let (lambda, supported) = (state.lambda, support == Support::Supported);
        match *self {
            Self::Penalty { .. } | Self::Uzawa { .. } if !supported => NodeContribution::zero(),
            Self::Penalty { epsilon } => penalty::contribution(area, gap, epsilon),
            Self::Uzawa { epsilon } => uzawa::contribution(area, gap, lambda, epsilon),
            Self::Rockafellar { p, k } => {
                let active = supported && rockafellar::is_active(gap.signed_gap, lambda, p, k);
                rockafellar::branch_contribution(area, gap, lambda, p, k, active)
            }
            Self::Slack { p, k } => slack_condensed(area, gap, state, p, k, support).0,
        }
    }

    /// Apply a Newton increment `(Δu_s, Δλ)` to the node's own unknowns:
    /// `λ += Δλ` for the multiplier laws, plus the back-substitution of the
    /// condensed slack unknowns `(s, λ₁)`. `gap` must be the geometry the
    /// contribution was assembled with (the previous iterate), and
    /// `support` the node's then ([`contribution`](Self::contribution)).
    pub fn apply_increment(
        &self,
        area: f64,
        gap: &GapGeometry,
        support: Support,
        state: &mut NodeContactState,
        du: &Vector3<f64>,
        dlambda: f64,
    ) {
        match *self {
            Self::Penalty { .. } | Self::Uzawa { .. } => {}
            Self::Rockafellar { .. } => state.lambda += dlambda,
            Self::Slack { p, k } => {
                let (_, recovery) = slack_condensed(area, gap, state, p, k, support);
                state.slack = recovery.apply(&state.slack, du, dlambda);
                state.lambda += dlambda;
            }
        }
    }
}

/// Whether a node has a primary to be in contact with
/// ([`NormalLaw::contribution`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Support {
    /// Gap kinematics there: the law's switch decides.
    Supported,
    /// No primary within the search margin, or no mortar support: inactive.
    Unsupported,
}

/// The slack law condensed in the branch its consistent switch gives, or
/// free without `support`.
fn slack_condensed(
    area: f64,
    gap: &GapGeometry,
    state: &NodeContactState,
    p: f64,
    k: f64,
    support: Support,
) -> (NodeContribution, slack::SlackRecovery) {
    let clamped = support == Support::Supported
        && slack::SlackSwitch::Consistent.is_clamped(&state.slack, p, k);
    (state.slack).condense_in_branch(area, gap, state.lambda, p, k, clamped)
}

/// Default penalty `p` and scaling `k` for the Rockafellar laws from the
/// body's Young's modulus `E` and a contact element size `h`: `p = k = E/h`.
///
/// Why (formulation note §2.1 item 3, "start from `p ≈ k ≈ E/h`"): the
/// solution does not depend on `p` and `k`, they only condition the system.
/// With `A_s ~ h²`, the contact blocks `A_s p n nᵀ` and `A_s k n` are then
/// of order `E h`, the size of a linear element's stiffness, and the scaled
/// multiplier `λ = t_N/k` is a length comparable to the displacements.
///
/// # Panics
/// If `E` or `h` is not positive and finite.
pub fn automatic_parameters(youngs_modulus: f64, element_size: f64) -> (f64, f64) {
    assert!(
        youngs_modulus > 0.0 && youngs_modulus.is_finite(),
        "Young's modulus must be positive, got {youngs_modulus}"
    );
    assert!(
        element_size > 0.0 && element_size.is_finite(),
        "contact element size must be positive, got {element_size}"
    );
    let p = youngs_modulus / element_size;
    (p, p)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn automatic_parameters_are_e_over_h() {
        let (p, k) = automatic_parameters(210_000.0, 2.0);
        assert_eq!(p, 105_000.0);
        assert_eq!(k, 105_000.0);
    }

    #[test]
    fn sphere_geometry_matches_its_definition() {
        let c = Vector3::new(1.0, -2.0, 0.5);
        let x = Vector3::new(2.0, 0.0, 3.0);
        let g = GapGeometry::sphere(&x, &c, 2.5);
        let d = (x - c).norm();
        assert!((g.signed_gap - (d - 2.5)).abs() < 1e-15);
        assert!((g.normal.norm() - 1.0).abs() < 1e-15);
        // H n = 0 and tr H = 2/|x − c|.
        assert!((g.hessian * g.normal).norm() < 1e-15);
        assert!((g.hessian.trace() - 2.0 / d).abs() < 1e-15);
    }

    #[test]
    fn dispatch_reaches_each_law() {
        let gap = GapGeometry::plane(
            &Vector3::new(0.0, 0.0, -0.01),
            &Vector3::zeros(),
            &Vector3::z(),
        );
        let slack_law = NormalLaw::Slack { p: 100.0, k: 50.0 };
        let state = NodeContactState {
            lambda: 0.5,
            ..NodeContactState::initial(&slack_law, gap.signed_gap)
        };
        let area = 2.0;
        let pen = NormalLaw::Penalty { epsilon: 100.0 }.contribution(
            Support::Supported,
            area,
            &gap,
            &state,
        );
        assert_eq!(pen, penalty::contribution(area, &gap, 100.0));
        let uz = NormalLaw::Uzawa { epsilon: 100.0 }.contribution(
            Support::Supported,
            area,
            &gap,
            &state,
        );
        assert_eq!(uz, uzawa::contribution(area, &gap, 0.5, 100.0));
        let rock = NormalLaw::Rockafellar { p: 100.0, k: 50.0 }.contribution(
            Support::Supported,
            area,
            &gap,
            &state,
        );
        assert_eq!(
            rock,
            rockafellar::contribution(area, &gap, 0.5, 100.0, 50.0)
        );
        let sl = slack_law.contribution(Support::Supported, area, &gap, &state);
        assert_eq!(sl, state.slack.condense(area, &gap, 0.5, 100.0, 50.0).0);
        assert!(!NormalLaw::Penalty { epsilon: 1.0 }.has_multiplier_dof());
        assert!(!NormalLaw::Uzawa { epsilon: 1.0 }.has_multiplier_dof());
        assert!(NormalLaw::Rockafellar { p: 1.0, k: 1.0 }.has_multiplier_dof());
        assert!(NormalLaw::Slack { p: 1.0, k: 1.0 }.has_multiplier_dof());
    }
}
