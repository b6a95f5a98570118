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
//! "displacement" is whatever motion the columns of `E` measure: the
//! node's own against a rigid obstacle, its motion relative to its
//! projection point between bodies (the caller's columns are the rows of
//! the lever `B`, and its gap and slip linearised in that motion). The
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
//! The structure rows are eliminated exactly: with `Ŵ` symmetric positive
//! definite (as `K̂` is), `R_S = 0` is `A t_F = Ŵ⁻¹ (u_F − û₀) − ρ P_S u_F`
//! (`S = Ŵ⁻¹ − ρ P_S` the condensed stiffness, singular where only
//! contact holds the body): the traction's free components follow from
//! `u_F`, by a solve with the Cholesky factor of `Ŵ` ([`Flexibility`],
//! from the caller once per `Ŵ`; `Ŵ⁻¹` is never formed). The unknowns are
//! `u_F` and the traction's prescribed components (no column of `Ŵ`; only
//! the node law fixes them), `3m` in all, and the equations the `3m` node
//! laws. The generalized Jacobian `J = D_u + D_t A⁻¹ S` is dense; Newton's
//! step `J δu = −L` is taken as `δu = Ŵ y` with
//!
//! ```text
//! (D_u Ŵ + D_t A⁻¹ (I − ρ P_S Ŵ)) y = −L        (J Ŵ, no inverse)
//! ```
//!
//! `3m × 3m` (half the size of the `(u_F, t)` system), factorised by LU
//! with partial pivoting (faer). A step that does not lower `½|L|²` is
//! halved (at most [`HALVINGS`] times, then taken whole). Converged when
//! `|L|∞ ≤ 1e-13` of the traction scale: the answer is exact up to
//! round-off.

use crate::contact::friction::{self, ContactStatus, Coulomb, NormalPressure, SlipKinematics};
pub use crate::contact::laws::NormalEnforcement;
use faer::linalg::solvers::Solve;
use nalgebra::{DMatrix, Matrix3, Vector3};

/// Most Newton iterations of one solve.
const MAX_ITERATIONS: usize = 200;

/// Most halvings of a step that does not lower the merit.
const HALVINGS: usize = 8;

/// Converged when the scaled residual is below this fraction of the
/// traction scale.
const TOLERANCE: f64 = 1e-13;

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
    /// The gap at the last commit, and whether the node was open then, at
    /// a gap above rounding (its first contact is anchored where its path
    /// meets the surface: [`friction::first_contact`]; the caller applies
    /// Newton's rule, `ContactInterface::first_contact_pending`: a
    /// committed gap within 1e-12 of the element size is touching).
    pub committed_gap: f64,
    pub was_open: bool,
    /// The node's prescribed components: along a prescribed axis near the
    /// tangent plane exact stick leaves the traction undetermined, and the
    /// rule of [`HeldTangent`](friction::HeldTangent) keeps the committed
    /// one there (the monolithic path's multiplier rows alike).
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
    /// Exact stick's multiplier `λ_T` at `t` (the trial's old traction,
    /// [`stick_multiplier`]: `T t` but along held directions); `T t` for
    /// the regularised law and where the node is open or closing.
    pub multiplier: Vector3<f64>,
}

/// A unit basis `(e₁, e₂)` of the plane normal to `n`.
fn tangent_basis(n: &Vector3<f64>) -> [Vector3<f64>; 2] {
    let axis = n.iamin();
    let e1 = Vector3::ith(axis, 1.0).cross(n).normalize();
    [e1, n.cross(&e1)]
}

/// A closed node's pressure `p` bounding the cone, with `∂p/∂u`, `∂p/∂t`.
type Pressure = (f64, Vector3<f64>, Vector3<f64>);

/// The normal equation of `node` (row 0 of `law`) at gap `g` and normal
/// traction `t_n`: exact (Alart–Curnier) `t_N − max(0, t_N − r g)`, or
/// penalty `t_N − ε⟨−g⟩`; the pressure where the node is closed.
fn normal_equation(node: &ConeNode, g: f64, t_n: f64, law: &mut NodeLaw) -> Option<Pressure> {
    let n = node.normal;
    let (du, dt) = (
        &mut law.displacement_derivative,
        &mut law.traction_derivative,
    );
    match node.normal_law {
        NormalEnforcement::Exact { r } => {
            let xi = t_n - r * g;
            if xi > 0.0 {
                law.residual[0] = r * g;
                du.set_row(0, &(r * n.transpose()));
                Some((xi, -r * n, n))
            } else {
                law.residual[0] = t_n;
                dt.set_row(0, &n.transpose());
                None
            }
        }
        NormalEnforcement::Penalty { epsilon } => {
            dt.set_row(0, &n.transpose());
            if g <= 0.0 {
                law.residual[0] = t_n + epsilon * g;
                du.set_row(0, &(epsilon * n.transpose()));
                Some((-epsilon * g, -epsilon * n, Vector3::zeros()))
            } else {
                law.residual[0] = t_n;
                None
            }
        }
    }
}

/// Exact stick's multiplier `T t` under the rule of
/// [`HeldTangent`](friction::HeldTangent) (the committed traction along
/// the node's prescribed tangential axes, as the monolithic path's
/// multiplier rows have it: [`friction::held_multiplier`]), and its
/// derivative's left factor `free` (`∂multiplier/∂t = free T`).
fn stick_multiplier(node: &ConeNode, tangential: Vector3<f64>) -> (Vector3<f64>, Matrix3<f64>) {
    let held = friction::HeldTangent::of(&node.normal, node.prescribed);
    friction::held_multiplier(&held, &node.normal, &tangential, &node.committed_traction)
}

/// The equations of node `node` at displacement `u` and traction `t`
/// (see the module docs): the normal one ([`normal_equation`]) and, in a
/// basis `(e₁, e₂)` of the tangent plane, the tangential ones, `t_T = 0`
/// where the node is open or closing under an exact law, else
/// `T t − P_{μp}(trial)` by the monolithic return mapping.
pub fn node_law(node: &ConeNode, u: &Vector3<f64>, t: &Vector3<f64>) -> NodeLaw {
    let n = node.normal;
    let basis = tangent_basis(&n);
    let g = node.gap_at_rest + n.dot(u);
    let mut law = NodeLaw {
        residual: Vector3::zeros(),
        displacement_derivative: Matrix3::zeros(),
        traction_derivative: Matrix3::zeros(),
        status: ContactStatus::Open,
        multiplier: t - n * n.dot(t),
    };
    let closed = normal_equation(node, g, n.dot(t), &mut law);
    let exact_normal = matches!(node.normal_law, NormalEnforcement::Exact { .. });
    let closing = exact_normal && node.was_open && node.committed_gap > 0.0;
    let Some((p, dp_du, dp_dt)) = closed.filter(|_| !closing) else {
        // open, or closing under an exact law: t_T = 0
        for (k, e) in basis.iter().enumerate() {
            law.residual[k + 1] = e.dot(t);
            law.traction_derivative.set_row(k + 1, &e.transpose());
        }
        if closed.is_some() {
            law.status = ContactStatus::Stick;
        }
        return law;
    };
    let projector = Matrix3::identity() - n * n.transpose();
    let tangential = projector * t;
    let exact_stick = node.tangential_law == TangentialLaw::ExactStick;
    let (multiplier, free) = stick_multiplier(node, tangential);
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
    let (d_du, d_dt) = (-response.traction_gradient, projector - dtau_dt);
    for (k, e) in basis.iter().enumerate() {
        law.residual[k + 1] = e.dot(&equation);
        law.displacement_derivative
            .set_row(k + 1, &(e.transpose() * d_du));
        law.traction_derivative
            .set_row(k + 1, &(e.transpose() * d_dt));
    }
    law.status = response.status;
    if exact_stick {
        law.multiplier = multiplier;
    }
    law
}

/// `Ŵ`, the flexibility over the contact dofs (`n_F × n_F`, symmetric
/// positive definite), with its Cholesky factor `Ŵ = L Lᵀ` (faer's blocked
/// dense one): the condensed solve works with `Ŵ` and solves by the
/// factor and never forms `Ŵ⁻¹` (nalgebra's unblocked Cholesky inverse of
/// `Ŵ` took 58 % of examples/cattaneo-mindlin's press, `n_F` ≈ 1 100,
/// BENCHMARKS.md session 15).
pub struct Flexibility {
    w: faer::Mat<f64>,
    factor: faer::linalg::solvers::Llt<f64>,
}

impl Flexibility {
    /// `Ŵ` factorised; an error when it is not positive definite.
    pub fn new(w: &DMatrix<f64>) -> Result<Self, String> {
        let w = faer::Mat::<f64>::from_fn(w.nrows(), w.ncols(), |r, c| w[(r, c)]);
        let factor = w.llt(faer::Side::Lower).map_err(|_| {
            "the condensed contact flexibility is not positive definite".to_string()
        })?;
        Ok(Flexibility { w, factor })
    }

    /// `Ŵ⁻¹ v`.
    fn solve(&self, v: &[f64]) -> Vec<f64> {
        let mut x = faer::Mat::<f64>::from_fn(v.len(), 1, |i, _| v[i]);
        self.factor.solve_in_place(x.as_mut());
        x.col_as_slice(0).to_vec()
    }

    /// Row `i` of `Ŵ` (its column: `Ŵ` is symmetric).
    fn row(&self, i: usize) -> &[f64] {
        self.w.col_as_slice(i)
    }

    /// `Ŵ y`.
    fn apply(&self, y: &[f64]) -> Vec<f64> {
        let mut v = vec![0.0; y.len()];
        for (j, &yj) in y.iter().enumerate() {
            if yj != 0.0 {
                for (vi, wij) in v.iter_mut().zip(self.row(j)) {
                    *vi += wij * yj;
                }
            }
        }
        v
    }
}

/// The condensed problem of one increment.
pub struct ConeProblem<'a> {
    /// `Ŵ` and its factor (once per `Ŵ`, by the caller).
    pub flexibility: &'a Flexibility,
    /// Contact dof `i` is component `columns[i].1` of node `columns[i].0`.
    pub columns: &'a [(usize, usize)],
    /// Whether contact dof `i` carries the shift `ρ`.
    pub shifted: &'a [bool],
    /// `ρ`.
    pub shift: f64,
    /// `û₀` on the contact dofs.
    pub free_displacement: &'a [f64],
    /// Per node the part of its motion `u_a` that is not an unknown: the
    /// prescribed components, and on a free component what its column
    /// leaves out (between bodies the prescribed dofs of the lever; zero
    /// against a rigid obstacle): `u_a,d = prescribed_a,d + u_F,i`.
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
    /// Per node exact stick's multiplier `λ_T` ([`NodeLaw::multiplier`]):
    /// what the problem's own evaluation takes for the committed traction
    /// of the trial to return the solved traction.
    pub multiplier: Vec<Vector3<f64>>,
    /// Newton iterations (dense LU solves).
    pub iterations: usize,
    /// Per Newton iteration, as reported to the user
    /// ([`crate::solve::method`]): `|L|∞` relative to the traction scale
    /// at its start, the step `α |δz|∞` relative to the largest `|z|∞`
    /// (at least ε: a solve was taken), `α`, and the nodes whose status
    /// (open, stick, slip) the step changed.
    pub history: Vec<crate::solve::record::IterationRecord>,
}

/// Where component `d` of a node's traction comes from.
#[derive(Clone, Copy, Debug)]
enum Component {
    /// A free dof, contact dof `i`: `A t = (S u_F − q)_i`.
    Free(usize),
    /// A prescribed dof: unknown `j` after `u_F`.
    Prescribed(usize),
}

/// The structure condensed onto the contact dofs:
/// `A t_F = Ŵ⁻¹ (u_F − û₀) − ρ P_S u_F`.
struct Condensed {
    /// `q = Ŵ⁻¹ û₀` (its size sets the traction scale).
    load: Vec<f64>,
    /// Per node, per component.
    components: Vec<[Component; 3]>,
    /// Number of prescribed components (unknowns after `u_F`).
    prescribed: usize,
}

impl ConeProblem<'_> {
    /// Each node's full motion at `u_F`.
    fn node_displacements(&self, u: &[f64]) -> Vec<Vector3<f64>> {
        let mut full = self.prescribed.to_vec();
        for (i, &(a, d)) in self.columns.iter().enumerate() {
            full[a][d] += u[i];
        }
        full
    }

    /// `q` and the numbering of the unknowns.
    fn condense(&self) -> Condensed {
        let load = self.flexibility.solve(self.free_displacement);
        let mut components = vec![[Component::Prescribed(usize::MAX); 3]; self.nodes.len()];
        for (i, &(a, d)) in self.columns.iter().enumerate() {
            components[a][d] = Component::Free(i);
        }
        let mut prescribed = 0;
        for node in components.iter_mut() {
            for c in node.iter_mut() {
                if let Component::Prescribed(j) = c {
                    *j = prescribed;
                    prescribed += 1;
                }
            }
        }
        Condensed {
            load,
            components,
            prescribed,
        }
    }

    /// The tractions at the unknowns `z = (u_F, t_prescribed)`.
    fn tractions(&self, c: &Condensed, z: &[f64]) -> Vec<Vector3<f64>> {
        let f = self.columns.len();
        let relative: Vec<f64> = (z[..f].iter().zip(self.free_displacement))
            .map(|(u, u0)| u - u0)
            .collect();
        let mut force = self.flexibility.solve(&relative);
        for (i, &shifted) in self.shifted.iter().enumerate() {
            if shifted {
                force[i] -= self.shift * z[i];
            }
        }
        c.components
            .iter()
            .zip(self.nodes)
            .map(|(components, node)| {
                Vector3::from_fn(|d, _| match components[d] {
                    Component::Free(i) => force[i] / node.area,
                    Component::Prescribed(j) => z[f + j],
                })
            })
            .collect()
    }

    /// The node laws at `z`, the residual and the tractions.
    fn residual(&self, c: &Condensed, z: &[f64]) -> (Vec<f64>, Vec<NodeLaw>, Vec<Vector3<f64>>) {
        let t = self.tractions(c, z);
        let displacements = self.node_displacements(&z[..self.columns.len()]);
        let laws: Vec<NodeLaw> = self
            .nodes
            .iter()
            .zip(&displacements)
            .zip(&t)
            .map(|((node, u_a), t_a)| node_law(node, u_a, t_a))
            .collect();
        let r = laws
            .iter()
            .flat_map(|l| l.residual.iter().copied())
            .collect();
        (r, laws, t)
    }

    /// The generalized Jacobian of the node laws with respect to
    /// `(y, t_p)`, `δu_F = Ŵ y`: `J Ŵ = D_u Ŵ + D_t A⁻¹ (I − ρ P_S Ŵ)` on
    /// the free components, `∂L_a/∂t_p = D_t` on the prescribed ones.
    fn jacobian(&self, c: &Condensed, laws: &[NodeLaw]) -> faer::Mat<f64> {
        let f = self.columns.len();
        let size = f + c.prescribed;
        let mut j = faer::Mat::<f64>::zeros(3 * self.nodes.len(), size);
        for (a, law) in laws.iter().enumerate() {
            let area = self.nodes[a].area;
            for k in 0..3 {
                let row = 3 * a + k;
                for d in 0..3 {
                    let dt = law.traction_derivative[(k, d)];
                    match c.components[a][d] {
                        Component::Free(i) => {
                            let shift = if self.shifted[i] { self.shift } else { 0.0 };
                            let factor = law.displacement_derivative[(k, d)] - shift * dt / area;
                            if factor != 0.0 {
                                for (col, w) in self.flexibility.row(i).iter().enumerate() {
                                    j[(row, col)] += factor * w;
                                }
                            }
                            j[(row, i)] += dt / area;
                        }
                        Component::Prescribed(p) => j[(row, f + p)] += dt,
                    }
                }
            }
        }
        j
    }

    /// The step `δz = (Ŵ y, δt_p)` from the solution `(y, δt_p)` of the
    /// system of [`Self::jacobian`].
    fn step(&self, solution: &faer::Mat<f64>) -> Vec<f64> {
        let f = self.columns.len();
        let all = solution.col_as_slice(0);
        let mut step = self.flexibility.apply(&all[..f]);
        step.extend_from_slice(&all[f..]);
        step
    }
}

/// `½|r|²`.
fn merit(r: &[f64]) -> f64 {
    0.5 * r.iter().map(|v| v * v).sum::<f64>()
}

/// Solve `problem` by semismooth Newton from `(u, t)` (the last
/// increment's answer is a good start; only the prescribed components of
/// `t` are unknowns, the free ones follow from `u`). Errors when Newton
/// does not converge in [`MAX_ITERATIONS`] or its Jacobian is singular.
pub fn solve_cone(
    problem: &ConeProblem,
    u: Vec<f64>,
    t: Vec<Vector3<f64>>,
) -> Result<ConeSolution, String> {
    let f = problem.columns.len();
    let condensed = problem.condense();
    let mut z = u;
    z.resize(f + condensed.prescribed, 0.0);
    for (a, components) in condensed.components.iter().enumerate() {
        for d in 0..3 {
            if let Component::Prescribed(j) = components[d] {
                z[f + j] = t[a][d];
            }
        }
    }
    let load_scale = condensed
        .load
        .iter()
        .enumerate()
        .map(|(i, q)| (q / problem.nodes[problem.columns[i].0].area).abs())
        .fold(f64::MIN_POSITIVE, f64::max);
    let (mut r, mut laws, mut t) = problem.residual(&condensed, &z);
    let mut history = Vec::new();
    for iteration in 1..=MAX_ITERATIONS {
        let scale = t.iter().map(|v| v.amax()).fold(load_scale, f64::max);
        let largest = r.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        if largest <= TOLERANCE * scale {
            return Ok(ConeSolution {
                displacement: z[..f].to_vec(),
                traction: t,
                status: laws.iter().map(|l| l.status).collect(),
                multiplier: laws.iter().map(|l| l.multiplier).collect(),
                iterations: iteration - 1,
                history,
            });
        }
        let jacobian = problem.jacobian(&condensed, &laws);
        let rhs = faer::Mat::<f64>::from_fn(r.len(), 1, |i, _| -r[i]);
        let step = problem.step(&jacobian.partial_piv_lu().solve(&rhs));
        if step.iter().any(|v| !v.is_finite()) {
            return Err(format!(
                "the condensed Coulomb problem's Jacobian is singular (Newton iteration \
                 {iteration})"
            ));
        }
        let old = merit(&r);
        let trial = |alpha: f64| {
            let trial_z: Vec<f64> = (0..z.len()).map(|i| z[i] + alpha * step[i]).collect();
            let (trial_r, trial_laws, trial_t) = problem.residual(&condensed, &trial_z);
            (trial_z, trial_r, trial_laws, trial_t)
        };
        let mut alpha = 1.0;
        let mut accepted = None;
        for _ in 0..=HALVINGS {
            let candidate = trial(alpha);
            if merit(&candidate.1) < old {
                accepted = Some(candidate);
                break;
            }
            alpha *= 0.5;
        }
        // no decrease along the step: take it whole
        let (length, next) = match accepted {
            Some(next) => (alpha, next),
            None => (1.0, trial(1.0)),
        };
        let size = z.iter().fold(f64::MIN_POSITIVE, |m, v| m.max(v.abs()));
        let moved = (0..z.len()).fold(0.0f64, |m, i| m.max((next.0[i] - z[i]).abs()));
        let switched = laws
            .iter()
            .zip(&next.2)
            .filter(|(a, b)| a.status != b.status)
            .count();
        history.push(crate::solve::record::IterationRecord {
            residual: largest / scale,
            correction: (moved / size).max(f64::EPSILON),
            step_length: length,
            switched,
            linear: Default::default(),
        });
        (z, r, laws, t) = next;
    }
    Err(format!(
        "the condensed Coulomb problem did not converge in {MAX_ITERATIONS} Newton iterations"
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    const MU: f64 = 0.3;

    fn node(normal_law: NormalEnforcement, tangential_law: TangentialLaw) -> ConeNode {
        ConeNode {
            normal: Vector3::new(0.1, -0.2, 1.0).normalize(),
            area: 0.7,
            normal_law,
            tangential_law,
            coulomb: Coulomb {
                coefficient: MU,
                tangential_penalty: 500.0,
            },
            committed_traction: Vector3::new(0.4, -0.3, 0.0),
            gap_at_rest: 0.0,
            offset_at_rest: Vector3::zeros(),
            committed_gap: 0.0,
            was_open: false,
            prescribed: [false; 3],
        }
    }

    /// `∂L/∂u` and `∂L/∂t` of [`node_law`] against central differences, for
    /// exact and penalty normal laws, regularised and exact stick, in stick
    /// and in slip (states away from the switches).
    #[test]
    fn node_law_derivatives_match_finite_differences() {
        let exact = NormalEnforcement::Exact { r: 800.0 };
        let penalty = NormalEnforcement::Penalty { epsilon: 800.0 };
        let cases = [
            (
                exact,
                TangentialLaw::Regularised,
                1e-4,
                ContactStatus::Stick,
            ),
            (exact, TangentialLaw::Regularised, 3e-2, ContactStatus::Slip),
            (exact, TangentialLaw::ExactStick, 1e-4, ContactStatus::Stick),
            (exact, TangentialLaw::ExactStick, 3e-2, ContactStatus::Slip),
            (
                penalty,
                TangentialLaw::Regularised,
                1e-4,
                ContactStatus::Stick,
            ),
            (
                penalty,
                TangentialLaw::Regularised,
                3e-2,
                ContactStatus::Slip,
            ),
        ];
        // a prescribed y off the tangent plane (n_y ≠ 0): exact stick keeps
        // the committed traction along `τ = T e_y/|T e_y|`
        let axes = [[false; 3], [false, true, false]];
        for ((normal_law, tangential_law, motion, status), prescribed) in
            cases.into_iter().flat_map(|c| axes.map(|p| (c, p)))
        {
            let n = ConeNode {
                prescribed,
                ..node(normal_law, tangential_law)
            };
            let u = Vector3::new(motion, 0.5 * motion, -0.01);
            let t = Vector3::new(0.2, 0.1, 5.0);
            let law = node_law(&n, &u, &t);
            assert!(
                prescribed[1] || law.status == status,
                "{normal_law:?} {tangential_law:?} {motion}"
            );
            let h = 1e-7;
            for j in 0..3 {
                let e = Vector3::ith(j, h);
                let du = (node_law(&n, &(u + e), &t).residual
                    - node_law(&n, &(u - e), &t).residual)
                    / (2.0 * h);
                let dt = (node_law(&n, &u, &(t + e)).residual
                    - node_law(&n, &u, &(t - e)).residual)
                    / (2.0 * h);
                let scale = law.displacement_derivative.amax().max(1.0);
                assert!(
                    (du - law.displacement_derivative.column(j)).amax() < 1e-6 * scale,
                    "{normal_law:?} {tangential_law:?} {status:?} ∂/∂u_{j}: {du} vs {}",
                    law.displacement_derivative.column(j)
                );
                assert!(
                    (dt - law.traction_derivative.column(j)).amax() < 1e-6,
                    "{normal_law:?} {tangential_law:?} {status:?} ∂/∂t_{j}: {dt} vs {}",
                    law.traction_derivative.column(j)
                );
            }
        }
    }

    /// One node on a spring `k` (`Ŵ = I/k`) resting on the plane z = 0,
    /// loaded by `F = (F_x, 0, −F_z)` (`û₀ = F/k`): `t_N = F_z`, `u_z = 0`;
    /// with exact stick it sticks (`u_x = 0`, `t_x = −F_x`) while
    /// `F_x ≤ μ F_z` and slips beyond (`t_x = −μ F_z`,
    /// `u_x = (F_x − μ F_z)/k`); with the regularised law it sticks
    /// elastically, `u_x = F_x/(k + A ε_T)`. The same with every dof
    /// shifted by `ρ` (`Ŵ = I/(k + ρ)`, the shift carried in `J Ŵ`).
    #[test]
    fn a_spring_on_the_plane_sticks_and_slips_by_coulomb() {
        let (k, f_z) = (200.0, 10.0);
        let columns = [(0, 0), (0, 1), (0, 2)];
        let mut n = node(
            NormalEnforcement::Exact { r: 500.0 },
            TangentialLaw::ExactStick,
        );
        n.normal = Vector3::z();
        n.area = 1.0;
        n.committed_traction = Vector3::zeros();
        for (f_x, law, u_x, t_x) in [
            (2.0, TangentialLaw::ExactStick, 0.0, -2.0),
            (
                5.0,
                TangentialLaw::ExactStick,
                (5.0 - MU * f_z) / k,
                -MU * f_z,
            ),
            (
                2.0,
                TangentialLaw::Regularised,
                2.0 / (k + 500.0),
                -500.0 * 2.0 / (k + 500.0),
            ),
        ] {
            let nodes = [ConeNode {
                tangential_law: law,
                ..n
            }];
            // unshifted, and shifted by ρ on every dof (a floating body's
            // `K̂ = K + ρ I`, `Ŵ = I/(k + ρ)`, `û₀ = F/(k + ρ)`): the same answer
            for rho in [0.0, 300.0] {
                let flexibility = Flexibility::new(&(DMatrix::identity(3, 3) / (k + rho))).unwrap();
                let u0 = [f_x / (k + rho), 0.0, -f_z / (k + rho)];
                let problem = ConeProblem {
                    flexibility: &flexibility,
                    columns: &columns,
                    shifted: &[rho > 0.0; 3],
                    shift: rho,
                    free_displacement: &u0,
                    prescribed: &[Vector3::zeros()],
                    nodes: &nodes,
                };
                let s = solve_cone(&problem, u0.to_vec(), vec![Vector3::zeros()]).unwrap();
                let (u, t) = (&s.displacement, s.traction[0]);
                assert!(
                    (u[0] - u_x).abs() < 1e-15,
                    "{law:?} F_x = {f_x}, ρ = {rho}: u_x {}",
                    u[0]
                );
                assert!(u[1].abs() < 1e-15 && u[2].abs() < 1e-15, "{u:?}");
                assert!(
                    (t.x - t_x).abs() < 1e-12,
                    "{law:?} F_x = {f_x}, ρ = {rho}: t_x {}",
                    t.x
                );
                assert!((t.z - f_z).abs() < 1e-12 && t.y.abs() < 1e-12, "{t}");
            }
        }
    }
}
