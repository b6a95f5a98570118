//! The condensed Coulomb contact problem: the contact nodes of a body
//! against rigid obstacles whose normal `n_a` is fixed per node, with the
//! structure reduced to its flexibility on the contact dofs, solved by a
//! dense semismooth Newton method (Alart & Curnier, *A mixed formulation
//! for frictional contact problems prone to Newton like solution methods*,
//! CMAME 92 (1991) 353–375; Christensen, Klarbring, Pang & Strömberg,
//! IJNME 42 (1998) 145–173).
//!
//! ## Unknowns and equations
//! Per contact node `a` the traction `t_a ∈ ℝ³` the obstacle exerts on the
//! body (`t_N = n·t`, `t_T = T t`, `T = I − n nᵀ`) and the displacement of
//! its free dofs `u_F` (the prescribed components `ū_a` are given). The
//! structure, with the shifted stiffness `K̂ = K̃ + ρ Σ_{j∈S} e_j e_jᵀ` (the
//! shift on a set `S` of contact dofs, so that `K̂` is regular even where
//! only contact holds the body) and `Ŵ = Eᵀ K̂⁻¹ E` (`E` the unit columns
//! of the contact dofs), is exactly
//!
//! ```text
//! R_S = u_F − Ŵ (A t + ρ P_S u_F) − û₀ = 0,     û₀ = Eᵀ K̂⁻¹ b
//! ```
//!
//! (from `K̃ u = b + E A t`, adding `ρ P_S u` on both sides). Each node adds
//! three equations `L_a(u_a, t_a) = 0` ([`node_law`]): the normal law, with
//! the gap `g = g_a⁰ + n·u_a`,
//!
//! ```text
//! exact (Alart–Curnier):  t_N − max(0, t_N − r g) = 0     (g ≥ 0, t_N ≥ 0, t_N g = 0)
//! penalty:                t_N − ε ⟨−g⟩ = 0
//! ```
//!
//! and, where the node is closed (`ξ = t_N − r g > 0`, or `g ≤ 0` for
//! penalty; open nodes have `t_T = 0`), the tangential law on the pressure
//! `p = ξ` (penalty: `ε⟨−g⟩`):
//!
//! ```text
//! regularised:  T t − P_{μp}(T t_T,n − ε_T Δg_T) = 0
//! exact stick:  T t − P_{μp}(T t − r_T Δg_T) = 0
//! ```
//!
//! with `Δg_T = T d`, `d = (x_a − c(t)) − (x_a − c)ₙ` the node's motion
//! from its committed anchor, and `P_{μp}` the return mapping of
//! [`friction::return_map_on`] (the same kernel as the monolithic path, so
//! its first-contact anchoring and slip predictor too). The regularised
//! law is the monolithic one; exact stick's fixed point is Coulomb's law
//! (stick: `T d = 0`, `|t_T| ≤ μ t_N`; slip: `t_T = μ t_N m`, `T d ∥ −m`),
//! which the monolithic augmented Lagrangian reaches at its outer loop's
//! tolerance. A node that was open at the last commit with a positive gap
//! and closes now under an exact normal law carries `t_T = 0` (its
//! first-contact offset is zero at `g = 0`: the monolithic answer).
//!
//! ## Newton
//! The generalized Jacobian of `(R_S, L)` is dense, `(n_F + 3m)²`, factorised
//! by LU with partial pivoting; the structure rows are scaled to tractions
//! by `1/(Ŵ_ii A_i)`. A step that does not lower `½|R|²` is halved (at most
//! [`HALVINGS`] times, then taken whole). Converged when
//! `|R|∞ ≤ 1e-13` of the traction scale: the answer is exact up to
//! round-off.

use crate::contact::friction::{self, ContactStatus, Coulomb, NormalPressure, SlipKinematics};
use faer::linalg::solvers::Solve;
use nalgebra::{DMatrix, Matrix3, Vector3};

/// Most Newton iterations of one solve.
const MAX_ITERATIONS: usize = 200;

/// Most halvings of a step that does not lower the merit.
const HALVINGS: usize = 8;

/// `|n_d|` below which axis `d` lies in the tangent plane.
const AXIS_IN_PLANE: f64 = 1e-12;

/// Converged when the scaled residual is below this fraction of the
/// traction scale.
const TOLERANCE: f64 = 1e-13;

/// How the normal constraint of a node is enforced.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum NormalEnforcement {
    /// `g ≥ 0 ⊥ t_N ≥ 0` exactly, written with the parameter `r > 0`
    /// (traction per length; it only conditions Newton).
    Exact { r: f64 },
    /// `t_N = ε⟨−g⟩`.
    Penalty { epsilon: f64 },
}

/// The tangential law of a node.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TangentialLaw {
    /// The return mapping from the committed traction with the law's `ε_T`.
    Regularised,
    /// Coulomb's law, written with the parameter `r_T > 0` (the law's
    /// `ε_T`: it only conditions Newton).
    ExactStick,
}

/// One contact node of the condensed problem.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ConeNode {
    /// Unit normal of the obstacle, toward the body.
    pub normal: Vector3<f64>,
    /// Tributary area `A_a`: the nodal force is `A_a t_a`.
    pub area: f64,
    pub normal_law: NormalEnforcement,
    pub tangential_law: TangentialLaw,
    /// `μ` and `ε_T` (`ε_T` is exact stick's `r_T`).
    pub coulomb: Coulomb,
    /// The traction committed at the last converged increment, `t_T,n`.
    pub committed_traction: Vector3<f64>,
    /// `g_a⁰`: the gap at `u_a = 0` (`g = g_a⁰ + n·u_a`).
    pub gap_at_rest: f64,
    /// `d` at `u_a = 0` (`d = d⁰ + u_a`).
    pub offset_at_rest: Vector3<f64>,
    /// The gap at the last commit, and whether the node was open then
    /// (its first contact is anchored where its path meets the surface:
    /// [`friction::first_contact`]).
    pub committed_gap: f64,
    pub was_open: bool,
    /// The node's prescribed components: along a prescribed axis in the
    /// tangent plane the node cannot slip, and exact stick leaves its
    /// traction there undetermined; it keeps the committed one (as the
    /// monolithic outer loop, which starts from it, does in stick).
    pub prescribed: [bool; 3],
}

/// The three equations of a node and their derivatives.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NodeLaw {
    /// `(normal, e₁·tangential, e₂·tangential)`.
    pub residual: Vector3<f64>,
    /// `∂L/∂u_a`.
    pub displacement_derivative: Matrix3<f64>,
    /// `∂L/∂t_a`.
    pub traction_derivative: Matrix3<f64>,
    /// Open, stick or slip.
    pub status: ContactStatus,
}

/// A unit basis `(e₁, e₂)` of the plane normal to `n`.
fn tangent_basis(n: &Vector3<f64>) -> [Vector3<f64>; 2] {
    let axis = n.iamin();
    let e1 = Vector3::ith(axis, 1.0).cross(n).normalize();
    [e1, n.cross(&e1)]
}

/// The equations of node `node` at displacement `u` and traction `t`
/// (see the module docs).
pub fn node_law(node: &ConeNode, u: &Vector3<f64>, t: &Vector3<f64>) -> NodeLaw {
    let n = node.normal;
    let basis = tangent_basis(&n);
    let g = node.gap_at_rest + n.dot(u);
    let t_n = n.dot(t);
    let mut residual = Vector3::zeros();
    let mut du = Matrix3::zeros();
    let mut dt = Matrix3::zeros();
    // the pressure p the cone is bounded by, ∂p/∂u and ∂p/∂t
    let closed = match node.normal_law {
        NormalEnforcement::Exact { r } => {
            let xi = t_n - r * g;
            if xi > 0.0 {
                residual[0] = r * g;
                du.set_row(0, &(r * n.transpose()));
                Some((xi, -r * n, n))
            } else {
                residual[0] = t_n;
                dt.set_row(0, &n.transpose());
                None
            }
        }
        NormalEnforcement::Penalty { epsilon } => {
            dt.set_row(0, &n.transpose());
            if g <= 0.0 {
                residual[0] = t_n + epsilon * g;
                du.set_row(0, &(epsilon * n.transpose()));
                Some((-epsilon * g, -epsilon * n, Vector3::zeros()))
            } else {
                residual[0] = t_n;
                None
            }
        }
    };
    let exact_normal = matches!(node.normal_law, NormalEnforcement::Exact { .. });
    let closing = exact_normal && node.was_open && node.committed_gap > 0.0;
    let Some((p, dp_du, dp_dt)) = closed.filter(|_| !closing) else {
        // open, or closing under an exact law: t_T = 0
        for (k, e) in basis.iter().enumerate() {
            residual[k + 1] = e.dot(t);
            dt.set_row(k + 1, &e.transpose());
        }
        let status = if closed.is_some() {
            ContactStatus::Stick
        } else {
            ContactStatus::Open
        };
        return NodeLaw {
            residual,
            displacement_derivative: du,
            traction_derivative: dt,
            status,
        };
    };
    let projector = Matrix3::identity() - n * n.transpose();
    let tangential = projector * t;
    let exact_stick = node.tangential_law == TangentialLaw::ExactStick;
    // exact stick's multiplier: T t, but the committed traction along the
    // prescribed tangential axes; its derivative `free T`
    let mut free = Matrix3::identity();
    let mut multiplier = tangential;
    for d in (0..3).filter(|&d| node.prescribed[d] && n[d].abs() <= AXIS_IN_PLANE) {
        free[(d, d)] = 0.0;
        multiplier[d] = node.committed_traction[d];
    }
    let mut kinematics = SlipKinematics {
        traction: if exact_stick {
            multiplier
        } else {
            node.committed_traction
        },
        traction_gradient: Matrix3::zeros(),
        offset: node.offset_at_rest + u,
        offset_gradient: Matrix3::identity(),
        normal: n,
        normal_gradient: Matrix3::zeros(),
    };
    if node.was_open {
        friction::first_contact(&mut kinematics, node.committed_gap, g, &n);
    }
    let pressure = NormalPressure {
        value: p,
        gradient: dp_du,
        multiplier_derivative: 1.0,
    };
    let response = friction::return_map_on(&node.coulomb, &kinematics, &pressure);
    // ∂τ/∂t: through the pressure, and for exact stick through the trial
    let mut dtau_dt = response.traction_multiplier_derivative * dp_dt.transpose();
    if exact_stick {
        let size = response.traction.norm();
        dtau_dt += match response.status {
            ContactStatus::Slip if size > 0.0 => {
                let m = response.traction / size;
                response.stick_scale * (Matrix3::identity() - m * m.transpose()) * free * projector
            }
            ContactStatus::Slip => Matrix3::zeros(),
            _ => free * projector,
        };
    }
    let equation = tangential - response.traction;
    let d_du = -response.traction_gradient;
    let d_dt = projector - dtau_dt;
    for (k, e) in basis.iter().enumerate() {
        residual[k + 1] = e.dot(&equation);
        du.set_row(k + 1, &(e.transpose() * d_du));
        dt.set_row(k + 1, &(e.transpose() * d_dt));
    }
    NodeLaw {
        residual,
        displacement_derivative: du,
        traction_derivative: dt,
        status: response.status,
    }
}

/// The condensed problem of one increment.
pub struct ConeProblem<'a> {
    /// `Ŵ` over the contact dofs (`n_F × n_F`, symmetric).
    pub flexibility: &'a DMatrix<f64>,
    /// Contact dof `i` is component `columns[i].1` of node `columns[i].0`.
    pub columns: &'a [(usize, usize)],
    /// Whether contact dof `i` carries the shift `ρ`.
    pub shifted: &'a [bool],
    /// `ρ`.
    pub shift: f64,
    /// `û₀` on the contact dofs.
    pub free_displacement: &'a [f64],
    /// Per node the prescribed displacement (its free components unused).
    pub prescribed: &'a [Vector3<f64>],
    pub nodes: &'a [ConeNode],
}

/// The solution of one condensed problem.
#[derive(Clone, Debug, PartialEq)]
pub struct ConeSolution {
    /// `u_F`, the displacement of the contact dofs.
    pub displacement: Vec<f64>,
    /// `t_a` per node.
    pub traction: Vec<Vector3<f64>>,
    /// Per node open, stick or slip.
    pub status: Vec<ContactStatus>,
    /// Newton iterations (dense LU solves).
    pub iterations: usize,
}

impl ConeProblem<'_> {
    /// Each node's full displacement at `u_F`.
    fn node_displacements(&self, u: &[f64]) -> Vec<Vector3<f64>> {
        let mut full = self.prescribed.to_vec();
        for (i, &(a, d)) in self.columns.iter().enumerate() {
            full[a][d] = u[i];
        }
        full
    }

    /// `1/(Ŵ_ii A_i)`: the structure rows in traction units.
    fn row_scales(&self) -> Vec<f64> {
        self.columns
            .iter()
            .enumerate()
            .map(|(i, &(a, _))| 1.0 / (self.flexibility[(i, i)] * self.nodes[a].area))
            .collect()
    }

    /// The scaled residual `(s R_S, L)` at `(u, t)` with the node laws.
    fn residual(&self, scales: &[f64], u: &[f64], t: &[Vector3<f64>]) -> (Vec<f64>, Vec<NodeLaw>) {
        let f = self.columns.len();
        // A t + ρ P_S u on the contact dofs
        let load: Vec<f64> = self
            .columns
            .iter()
            .enumerate()
            .map(|(i, &(a, d))| {
                let shift = if self.shifted[i] {
                    self.shift * u[i]
                } else {
                    0.0
                };
                self.nodes[a].area * t[a][d] + shift
            })
            .collect();
        let load = nalgebra::DVector::from_vec(load);
        let w_load = self.flexibility * load;
        let mut r = vec![0.0; f + 3 * self.nodes.len()];
        for i in 0..f {
            r[i] = scales[i] * (u[i] - w_load[i] - self.free_displacement[i]);
        }
        let displacements = self.node_displacements(u);
        let laws: Vec<NodeLaw> = self
            .nodes
            .iter()
            .zip(&displacements)
            .zip(t)
            .map(|((node, u_a), t_a)| node_law(node, u_a, t_a))
            .collect();
        for (a, law) in laws.iter().enumerate() {
            for k in 0..3 {
                r[f + 3 * a + k] = law.residual[k];
            }
        }
        (r, laws)
    }

    /// The generalized Jacobian of the scaled residual.
    fn jacobian(&self, scales: &[f64], laws: &[NodeLaw]) -> faer::Mat<f64> {
        let f = self.columns.len();
        let size = f + 3 * self.nodes.len();
        let w = self.flexibility;
        let mut j = faer::Mat::<f64>::zeros(size, size);
        for (col, &(a, d)) in self.columns.iter().enumerate() {
            let area = self.nodes[a].area;
            let shift = if self.shifted[col] { self.shift } else { 0.0 };
            for row in 0..f {
                let s = scales[row];
                let identity = if row == col { 1.0 } else { 0.0 };
                j[(row, col)] = s * (identity - shift * w[(row, col)]);
                j[(row, f + 3 * a + d)] = -s * w[(row, col)] * area;
            }
            for k in 0..3 {
                j[(f + 3 * a + k, col)] = laws[a].displacement_derivative[(k, d)];
            }
        }
        for (a, law) in laws.iter().enumerate() {
            for k in 0..3 {
                for d in 0..3 {
                    j[(f + 3 * a + k, f + 3 * a + d)] = law.traction_derivative[(k, d)];
                }
            }
        }
        j
    }
}

/// `½|r|²`.
fn merit(r: &[f64]) -> f64 {
    0.5 * r.iter().map(|v| v * v).sum::<f64>()
}

/// Solve `problem` by semismooth Newton from `(u, t)` (the last
/// increment's answer is a good start). Errors when Newton does not
/// converge in [`MAX_ITERATIONS`] or its Jacobian is singular.
pub fn solve_cone(
    problem: &ConeProblem,
    mut u: Vec<f64>,
    mut t: Vec<Vector3<f64>>,
) -> Result<ConeSolution, String> {
    let f = problem.columns.len();
    let scales = problem.row_scales();
    let (mut r, mut laws) = problem.residual(&scales, &u, &t);
    for iteration in 1..=MAX_ITERATIONS {
        let traction_scale = t
            .iter()
            .map(|v| v.amax())
            .chain(
                problem
                    .free_displacement
                    .iter()
                    .zip(&scales)
                    .map(|(v, s)| (v * s).abs()),
            )
            .fold(f64::MIN_POSITIVE, f64::max);
        let largest = r.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        if largest <= TOLERANCE * traction_scale {
            return Ok(ConeSolution {
                displacement: u,
                traction: t,
                status: laws.iter().map(|l| l.status).collect(),
                iterations: iteration - 1,
            });
        }
        let jacobian = problem.jacobian(&scales, &laws);
        let rhs = faer::Mat::<f64>::from_fn(r.len(), 1, |i, _| -r[i]);
        let step = jacobian.partial_piv_lu().solve(&rhs);
        if (0..r.len()).any(|i| !step[(i, 0)].is_finite()) {
            return Err(format!(
                "the condensed Coulomb problem's Jacobian is singular (Newton iteration \
                 {iteration})"
            ));
        }
        let old = merit(&r);
        let trial = |alpha: f64| {
            let trial_u: Vec<f64> = (0..f).map(|i| u[i] + alpha * step[(i, 0)]).collect();
            let trial_t: Vec<Vector3<f64>> = t
                .iter()
                .enumerate()
                .map(|(a, v)| {
                    let s = |k: usize| step[(f + 3 * a + k, 0)];
                    v + alpha * Vector3::new(s(0), s(1), s(2))
                })
                .collect();
            let (trial_r, trial_laws) = problem.residual(&scales, &trial_u, &trial_t);
            (trial_u, trial_t, trial_r, trial_laws)
        };
        let mut alpha = 1.0;
        let mut accepted = None;
        for _ in 0..=HALVINGS {
            let candidate = trial(alpha);
            if merit(&candidate.2) < old {
                accepted = Some(candidate);
                break;
            }
            alpha *= 0.5;
        }
        // no decrease along the step: take it whole
        (u, t, r, laws) = accepted.unwrap_or_else(|| trial(1.0));
    }
    Err(format!(
        "the condensed Coulomb problem did not converge in {MAX_ITERATIONS} Newton iterations"
    ))
}
