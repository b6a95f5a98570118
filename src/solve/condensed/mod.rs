//! The algebra of the condensed contact path: for a stiffness that does
//! not change with the displacement, the contact problem of an increment
//! written on the contact unknowns alone, with one factorisation per run.
//!
//! - [`anderson`]: Anderson acceleration of a fixed point (the rounds of
//!   the projections between bodies);
//! - [`flexibility`]: `K̃` factorised once with the contact unknowns
//!   ordered last, `W = Eᵀ K̃⁻¹ E` over the candidate columns of `E`, and
//!   the frictionless increment solved exactly;
//! - [`schur`]: the ordering that puts chosen unknowns last, and
//!   `(K̃⁻¹)_TT` or the Schur complement read off the factor's trailing
//!   block;
//! - [`complementarity`]: the dense LCP `g = q + Wλ ≥ 0 ⊥ λ ≥ 0` by block
//!   principal pivoting;
//! - [`cone`]: the condensed Coulomb problem (three unknowns per node), a
//!   dense semismooth Newton method;
//! - [`decoupled`]: the factor without the couplings of the unknowns whose
//!   rows are a scaled identity;
//! - [`parts`]: that factor as its independent diagonal blocks (the
//!   bodies), factorised side by side.
//!
//! The columns of `E` are linear forms on the unknowns read by the caller
//! from the contact's linearisation
//! ([`crate::contact::interface::ConstraintRow`]): nothing here knows an
//! obstacle or a law (the normal law enters as
//! [`crate::contact::laws::NormalEnforcement`]).

pub mod anderson;
pub mod complementarity;
pub mod cone;
pub mod decoupled;
pub mod flexibility;
pub mod parts;
pub mod schur;
