//! The nonlinear solve: Newton–Raphson with a backtracking line search,
//! chattering detection and adaptive load stepping with cuts over a
//! [`nonlinear::NonlinearProblem`]; the sparse linear solvers behind
//! [`linear_solver::LinearSolver`] (direct LDLᵀ, GMRES preconditioned by
//! an LDLᵀ, sparse LU, PETSc with the `petsc` feature) with their
//! orderings and the partition of distributed runs; and the algebra of
//! the condensed contact path (`K⁻¹` on the contact dofs read off the
//! factor, the frictionless complementarity problem, the condensed
//! Coulomb problem in `cone`, the Josephy–Newton step, the factor without
//! the couplings of decoupled unknowns).

pub mod backend;
pub mod chattering;
pub mod complementarity;
pub mod cone;
pub mod decoupled;
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
pub mod schur;
pub mod settings;
pub mod stepping;
