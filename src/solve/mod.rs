//! The nonlinear solve: Newton–Raphson with a backtracking line search and
//! adaptive load stepping over a [`nonlinear::NonlinearProblem`], and the
//! sparse linear solvers behind [`linear_solver::LinearSolver`].

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
