//! The nonlinear solve: Newton–Raphson with a backtracking line search,
//! chattering detection and adaptive load stepping with cuts over a
//! [`nonlinear::NonlinearProblem`]; the sparse linear solvers behind
//! [`linear_solver::LinearSolver`] (direct LDLᵀ, GMRES preconditioned by
//! an LDLᵀ, sparse LU, PETSc with the `petsc` feature) with their
//! orderings and the partition of distributed runs; the algebra of the
//! condensed contact path in [`condensed`] (one factorisation, `K⁻¹` on
//! the contact dofs read off it, the frictionless complementarity problem,
//! the condensed Coulomb problem, the factor without the couplings of
//! decoupled unknowns); and the Josephy–Newton step in [`josephy`].

pub mod backend;
pub mod chattering;
pub mod condensed;
pub mod direct;
pub mod failure;
pub mod gmres;
pub mod josephy;
pub mod krylov;
pub mod linear;
pub mod linear_solver;
pub mod lu;
pub mod method;
pub mod newton;
pub mod nonlinear;
pub mod ordering;
pub mod partition;
#[cfg(feature = "petsc")]
pub mod petsc;
pub mod record;
pub mod settings;
#[cfg(test)]
pub(crate) mod springs;
pub mod stepping;
pub mod tangent_store;
pub mod watchdog;
