//! The projection of a point onto a rigid obstacle's surface (see
//! [`obstacle`](super::obstacle) for each shape's formulas).

use nalgebra::{Matrix3, Vector3};

/// The projection of a point onto an obstacle's surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Projection {
    /// Closest point `x̄` on the surface.
    pub point: Vector3<f64>,
    /// Unit outward normal `n` at `x̄`, pointing toward the body; `∂g/∂x = n`.
    pub normal: Vector3<f64>,
    /// Signed gap `g = (x − x̄)·n`.
    pub gap: f64,
    /// Curvature of the gap function, `∂²g/∂x²` (symmetric).
    pub curvature: Matrix3<f64>,
}
