//! # signorini — nonlinear 3D contact mechanics by the finite-element method
//!
//! The crate reads like the method, and its imports point one way in this
//! order (`tests/layering.rs`): [`error`] → [`input`] (bounded reads of
//! user files) → [`mesh`] (Gmsh and `.inp` readers, sets), [`material`]
//! (hyperelastic laws) → [`fem`] (shape functions, quadrature) →
//! [`assembly`] (element kernels, one scatter, parallel assembly into a
//! fixed sparsity pattern) → [`contact`] (obstacles, search, the node
//! driver, normal laws, friction, the `ContactSet` life cycle) → [`solve`]
//! (the `NonlinearProblem` and `LinearSolver` traits, Newton, load
//! stepping) → [`problem`] (loads, steps; implements `NonlinearProblem`) →
//! [`output`] (fields by name, observers, VTU/PVD, `summary.json`, log,
//! plots) → [`case`] (the TOML case file) → [`run`] (the library's
//! `Simulation`).
//!
//! ## Conventions (fixed once, used everywhere)
//! - Total Lagrangian: reference position `X`, displacement `u`, current
//!   position `x = X + u`, `F = I + ∂u/∂X`, `C = FᵀF`, `E = ½(C − I)`,
//!   `J = det F`.
//! - `S` is the second Piola–Kirchhoff stress, `P = F S` the first,
//!   `σ = J⁻¹ F S Fᵀ` the Cauchy stress.
//! - Voigt order for symmetric tensors: (11, 22, 33, 12, 23, 13); strains
//!   carry engineering shear (`2E₁₂`), stresses do not.
//! - Residual `r(u) = f_int(u) − f_ext(u)`, tangent `K = ∂r/∂u`, Newton
//!   solves `K δu = −r`.
//! - Gap `g ≥ 0` is open; contact pressure `t_N ≥ 0` is compressive
//!   (contact work, see `design` notes in the README).
//!
//! Units are whatever the user chooses, consistently (e.g. mm, N, MPa).

// `!(x > 0.0)` is written on purpose throughout: it rejects NaN too.
#![allow(clippy::neg_cmp_op_on_partial_ord)]
// No panic on user input (issue 14): `unwrap`, `expect` and `panic!` are
// denied outside tests, and allowed only where an invariant of the code
// (not the input) holds, each with an `#[allow]` saying which.
#![cfg_attr(
    not(test),
    deny(clippy::unwrap_used, clippy::expect_used, clippy::panic)
)]

pub mod error;
pub mod fem;
pub mod input;
pub mod material;
pub mod mesh;
pub mod output;

pub use error::{Error, Result};
pub mod assembly;
pub mod case;
pub mod contact;
pub mod problem;
pub mod run;
pub mod solve;

/// The README's Rust snippet, compiled as a doc-test (`cargo test --doc
/// ReadmeDoctests`), so that the library's front page stays true.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
