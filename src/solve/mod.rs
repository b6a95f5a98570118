//! The nonlinear solve: sparse direct linear solves, Newton–Raphson with a
//! backtracking line search, and adaptive load stepping.

pub mod chattering;
pub mod gmres;
pub mod linear;
pub mod lu;
pub mod newton;
pub mod ordering;
pub mod stepping;
