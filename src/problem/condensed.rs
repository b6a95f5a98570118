//! The condensed contact path (`[solver] strategy`, issue 13 item 1): for
//! a body whose stiffness `K` is constant (small-strain linear elasticity,
//! dead loads) against rigid planes, the contact problem of every
//! increment is solved exactly on the contact nodes alone, with one
//! factorisation of `K` per run.
//!
//! ## The equations
//! With `K̃` the stiffness whose prescribed rows and columns are a scaled
//! identity (as in Newton, [`crate::solve::tangent_store::apply_identity_rows`];
//! the multiplier unknowns too, at zero), `E` the matrix whose column `a`
//! is the plane's normal `n` on the free dofs of contact node `a`, and
//! `λ_a = A_a t_N,a` the normal contact force of node `a`, equilibrium at
//! time `t` is
//!
//! ```text
//! K̃ u = b(t) + E λ,   b_f = f_ext(t) − K_fp ū(t),   b_p = s ū(t)
//! ```
//!
//! (`f_int = K u` exactly for a small-strain linear material). The gap of a
//! node on a plane is linear in `u`: `g = g(u₀) + Eᵀ(u − u₀)`, so with
//! `u₀ = K̃⁻¹ b(t)` and the flexibility `W = Eᵀ K̃⁻¹ E` (m × m, dense, one
//! solve with the factor per contact node, once per run)
//!
//! ```text
//! g = g(u₀) + W λ ≥ 0,   λ ≥ 0,   λ_a g_a = 0
//! ```
//!
//! a linear complementarity problem solved exactly
//! ([`crate::solve::condensed::complementarity`]); `u = K̃⁻¹ (b + E λ)` follows from one
//! more solve. The exact laws (Rockafellar, slack) converge to this very
//! solution (their `p`, `k` only condition Newton); penalty's
//! `t_N = ε⟨−g⟩` is the same problem with `W + diag(1/(A_a ε_a))`. Uzawa
//! meets `g ≥ 0` only to its outer loop's tolerance, so it is not
//! condensed. The monolithic answer is reproduced to round-off: the
//! converged state is checked by a full residual evaluation of the problem,
//! which must be within the Newton tolerance.
//!
//! ## Candidate nodes
//! `W` is built for the candidate nodes only: those that penetrate at
//! `u₀` (the answer without contact) or were candidates before. After the
//! complementarity solve every other node's gap is checked at `u`; a node
//! that penetrates joins the candidates (its column of `W` is one more
//! solve with the same factor) and the increment is solved again. The
//! factorisation is never repeated.
//!
//! ## Coulomb friction
//! With friction on some interface the run takes [`friction`]: three
//! unknowns per contact node, a dense semismooth Newton solve per
//! increment ([`crate::solve::condensed::cone`]), and a shifted `K̂` where only the
//! contact holds a body.
//!
//! ## Where it applies ([`not_applicable`])
//! Every material small-strain (`linear_elastic`: the total-Lagrangian
//! laws are geometrically nonlinear, their `K` changes with `u`), no
//! follower pressure, every contact against a rigid plane (translating or
//! not) or a rigid sphere or cylinder, frictionless or with Coulomb friction, with an exact or penalty
//! law (dual mortar on a plane: frictionless, exact; its gap
//! `g_j = Σ_k R_jk g(x_k)` is affine, its columns `R_jk n` over a face's
//! nodes, [`ConstraintRow::node_gradients`]), and every body held by its prescribed displacements (`K̃` regular:
//! a body held only by contact has a rigid-body mode) or, with friction,
//! by those and the nodes touching the plane at the start. `auto` takes it
//! exactly then; otherwise the run is monolithic and the log and
//! `summary.json` say why. Contact between bodies (node-to-surface or
//! dual mortar, frictionless or with Coulomb friction) is condensed under
//! `auto` too (dual mortar with exact stick at a secondary node whose
//! components are all prescribed only by name, `strategy = "condensed"`):
//! frictionless by [`pairs`], with Coulomb friction by [`friction`] on the
//! rows of [`linearisation`], both at the current projections. So is
//! contact against a rigid sphere or cylinder, under `auto` too, its rows
//! at the current normals (`ContactInterface::rows_move`).

use super::{ContactState, Problem};
use crate::contact::interface::{ConstraintRow, ContactInterface};
use crate::contact::mortar::Derivatives;

mod applicability;
mod capacity;
mod condensation;
mod friction;
mod linearisation;
mod method;
mod pairs;

use applicability::free_rigid_body_mode;
pub use applicability::{choose, not_applicable, Choice, Path};
use condensation::{Condensation, ContactNode};
pub use method::Condensed;
use method::IncrementSolver;

/// Whether any interface has Coulomb friction (`μ > 0`).
fn has_friction(problem: &Problem) -> bool {
    problem.contacts.iter().any(|c| c.has_friction())
}

/// Whether some interface is between bodies (its rows follow projections:
/// [`pairs`]).
fn has_pairs(problem: &Problem) -> bool {
    problem.contacts.iter().any(|c| c.projected_gap())
}

/// Whether some interface's rows move with the unknowns (between bodies,
/// or against a rigid sphere or cylinder): its increments are solved in
/// rounds at the current rows until they settle ([`pairs`], [`friction`]).
fn has_moving_rows(problem: &Problem) -> bool {
    problem.contacts.iter().any(|c| c.rows_move())
}

/// A zero per secondary node of every interface.
fn zero_per_node(problem: &Problem) -> Vec<Vec<f64>> {
    problem
        .contacts
        .iter()
        .map(|c| vec![0.0; c.nodes.len()])
        .collect()
}

/// The unknowns `x` of the monolithic system at the condensed solution:
/// the displacements `u` and, for the multiplier laws, `λ = t_N / k` with
/// `t_N = pressures[interface][node]` (the slack law's local unknowns
/// consistent with them), so that the problem's own evaluation reports the
/// state.
fn set_multipliers(
    problem: &Problem,
    pressures: &[Vec<f64>],
    u: &[f64],
    t: f64,
    x: &mut [f64],
    state: &mut ContactState,
) {
    let dofs = problem.model.num_dofs();
    x[..dofs].copy_from_slice(&u[..dofs]);
    let reference = &problem.model.mesh.nodes;
    for (ci, interface) in problem.contacts.iter().enumerate() {
        let gaps = interface.gaps(reference, t, u, None);
        for (i, &pressure) in pressures[ci].iter().enumerate() {
            let node = &mut state.interfaces[ci][i];
            let law = interface.law_at(i);
            if let Some(lambda) = law.set_converged_pressure(pressure, gaps[i], node) {
                x[dofs + interface.multiplier_offset + i] = lambda;
            }
        }
    }
}

/// The node driver's [`ConstraintRow`] of every secondary node of every
/// interface at time `t` and unknowns `x` (the contact's linearisation, the
/// one thing the condensed path reads of the obstacles), dual mortar's
/// with `derivatives` or without
/// ([`ContactInterface::constraint_rows_with`](crate::contact::interface::ContactInterface::constraint_rows_with):
/// what the frictionless path reads).
fn constraint_rows(
    problem: &Problem,
    t: f64,
    x: &[f64],
    derivatives: Derivatives,
) -> Vec<Vec<Option<ConstraintRow>>> {
    let reference = &problem.model.mesh.nodes;
    let rows =
        |c: &ContactInterface| c.constraint_rows_with(reference, t, x, None, derivatives, None);
    problem.contacts.iter().map(rows).collect()
}
