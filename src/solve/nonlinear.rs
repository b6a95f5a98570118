//! What Newton and the stepper need of a problem: the
//! [`NonlinearProblem`] trait. `solve/` knows residuals, tangents,
//! prescribed dofs and an opaque history state; it does not know contact
//! (the state and the per-node reports are associated types), so the
//! boundary-value problem of [`crate::problem`] is one implementation and a
//! test problem or a future binding may be another.

use super::failure::IncrementFailure;
use super::settings::{SolverSettings, Step};
use crate::assembly::pattern::SparsityPattern;
use crate::assembly::sink::Tangent;

/// One evaluation at time `t` and unknowns `x`: the residual
/// `r = f_int − f_ext − f_contact` over all unknowns (displacements, then
/// multipliers; its prescribed entries are the reactions), the norms that
/// scale it, one status code per contact node (for the chattering
/// detector) and the problem's per-node reports (for output).
#[derive(Clone, Debug)]
pub struct Evaluation<R> {
    pub residual: Vec<f64>,
    /// `‖f_int + f_contact‖` and `‖f_ext‖`.
    pub internal_norm: f64,
    pub external_norm: f64,
    /// Per contact node: `0` open, `1` stick, `2` slip, plus
    /// 4 × (1 + the primary triangle) on a deformable interface
    /// ([`super::chattering::ChatterDetector::observe`]).
    pub statuses: Vec<u64>,
    pub reports: R,
}

impl<R> Evaluation<R> {
    /// `max(‖f_int‖, ‖f_ext‖)`, the force scale of the residual.
    pub fn force_scale(&self) -> f64 {
        self.internal_norm.max(self.external_norm)
    }
}

/// One unilateral constraint of a problem, linearised at an iterate `x`:
/// the gap `g(x + δ) ≈ gap + sign · δ[dof] ≥ 0` along one displacement
/// unknown, and the force `f = force_per_multiplier · x[multiplier] ≥ 0`
/// that acts along `sign · e_dof` where the gap closes (`f g = 0`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NormalConstraint {
    pub dof: usize,
    pub sign: f64,
    pub gap: f64,
    pub multiplier: usize,
    pub force_per_multiplier: f64,
}

/// The problem at `x` without its unilateral constraints (the residual
/// `f_int − f_ext` over all unknowns, zero on the multipliers; the
/// tangent alongside) and those constraints linearised there: what a
/// Josephy–Newton step solves ([`super::josephy`]).
#[derive(Clone, Debug)]
pub struct Linearisation {
    pub residual: Vec<f64>,
    pub constraints: Vec<NormalConstraint>,
}

/// A nonlinear problem `r(t, x; state) = 0` solved by Newton in load
/// increments. `State` is the history carried between increments (contact
/// multipliers held by an outer loop, friction's committed slip), advanced
/// along Newton steps, augmented by the outer loop and committed when an
/// increment converges.
pub trait NonlinearProblem {
    /// History state: cloned for every trial increment and line-search step.
    type State: Clone;
    /// What an evaluation reports besides the residual (per contact node).
    type Report;

    /// Newton and stepping controls.
    fn settings(&self) -> &SolverSettings;
    /// The load steps.
    fn steps(&self) -> &[Step];
    /// The sparsity pattern of the tangent (displacements, then multipliers).
    fn pattern(&self) -> &SparsityPattern;
    /// Number of displacement unknowns (the multipliers follow them).
    fn num_dofs(&self) -> usize;
    /// A length of the body: a correction beyond 10 × this is a rigid-body mode.
    fn size(&self) -> f64;
    /// Whether the problem has contact (a correction far beyond
    /// [`size`](Self::size) is then read as a lost contact rather than a
    /// near-singular tangent of the body alone).
    fn has_contact(&self) -> bool {
        true
    }
    /// Whether any contact has friction (a rigid-body mode through closed
    /// contact nodes is then read against the friction capacity, else as
    /// an unsupported tangential direction).
    fn has_friction(&self) -> bool {
        false
    }
    /// Whether the tangent is nonsymmetric (a symmetric neighbour is then
    /// built for the preconditioner).
    fn has_nonsymmetric_tangent(&self) -> bool;
    /// Which unknowns are prescribed (in any step).
    fn constrained_dofs(&self) -> Vec<bool>;
    /// Write the prescribed values at time `t` into `x`.
    fn apply_prescribed(&self, t: f64, x: &mut [f64]);
    /// The history before the first increment, at unknowns `x`.
    fn initial_state(&self, x: &[f64]) -> Self::State;
    /// Residual (and the tangent `K = ∂r/∂x` into `tangent`, if given:
    /// values on [`pattern`](Self::pattern), or a linear solver's matrix)
    /// at time `t`, unknowns `x` and history `state`.
    fn evaluate(
        &self,
        t: f64,
        x: &[f64],
        state: &Self::State,
        tangent: Option<Tangent<'_>>,
    ) -> Result<Evaluation<Self::Report>, IncrementFailure>;
    /// Turn the symmetric part `values` of a nonsymmetric tangent
    /// `tangent` into the preconditioner's matrix (e.g. friction's slip
    /// blocks by stick blocks, dual mortar's multiplier couplings by the
    /// tangent's force columns); entries of `constrained` unknowns are
    /// skipped.
    fn symmetric_neighbour(
        &self,
        t: f64,
        x: &[f64],
        state: &Self::State,
        constrained: &[bool],
        tangent: &[f64],
        values: &mut [f64],
    );
    /// Carry `state` along a Newton step `dx` from `x`.
    fn advance_state(&self, t: f64, x: &[f64], dx: &[f64], state: &mut Self::State);
    /// After a converged Newton solve: update the outer-loop unknowns
    /// (Uzawa multipliers) and return `true` to solve again, `false` when
    /// within tolerance.
    fn augment(&self, t: f64, x: &[f64], state: &mut Self::State) -> bool;
    /// Commit the history once an increment converged at `t`, `x`.
    fn commit(&self, t: f64, x: &[f64], state: &mut Self::State);
    /// Update couplings (contact pairs) at `x` for an increment expected to
    /// move nodes by up to `motion`, and (`reached`) those the unknowns of
    /// an answer that left the last ones reach; `true` if the pattern
    /// changed.
    fn refresh_pattern(&mut self, x: &[f64], motion: f64, reached: Option<&[f64]>) -> bool;
    /// Make the pattern Newton's tangent needs where it was made for
    /// another path (the condensed path's leaves out the contact couplings
    /// its factor does not read), before Newton first solves; `true` if
    /// the pattern changed. By default the pattern is Newton's.
    fn newton_pattern(&mut self) -> bool {
        false
    }
    /// Whether the couplings used for the increment still hold at the
    /// converged `x` (else the increment is cut).
    fn couplings_hold(&self, x: &[f64], state: &Self::State) -> bool;
    /// Why the increment from `(t0, x0)` to the converged `(t1, x1)` must
    /// be cut although it converged (a node that passed through a rigid
    /// obstacle on the way), if it must.
    fn passed_through(
        &self,
        _start: (f64, &[f64]),
        _end: (f64, &[f64]),
    ) -> Option<super::failure::IncrementFailure> {
        None
    }
    /// The nodes whose motion sets the search margin of
    /// [`NonlinearProblem::refresh_pattern`].
    fn moving_coupled_nodes(&self) -> Vec<usize>;
    /// Whether [`linearise_constraints`](Self::linearise_constraints)
    /// writes the problem's constraints (`Ok`) or why it cannot (the
    /// default: it never does).
    fn constraints_linearise(&self) -> Result<(), String> {
        Err("the problem does not linearise its constraints".into())
    }
    /// The problem at `x` without its unilateral constraints, its tangent
    /// written into `tangent`, and the constraints linearised at `x`
    /// ([`Linearisation`]); `Ok(None)` where they cannot be written so
    /// (the default: Newton then takes its plain step).
    fn linearise_constraints(
        &self,
        _t: f64,
        _x: &[f64],
        _state: &Self::State,
        _tangent: &mut [f64],
    ) -> Result<Option<Linearisation>, IncrementFailure> {
        Ok(None)
    }
    /// In a distributed run, where each process holds its part `K^p` of
    /// the tangent: complete a product with it, `v ← Σ_p v^p`
    /// (`v = K^p w` on entry). Nothing to do in a serial run.
    fn sum_over_processes(&self, _v: &mut [f64]) {}
}
