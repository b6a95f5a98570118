//! The gap of a secondary node against a rigid obstacle as the normal laws
//! read it: signed gap, normal and curvature at the node.

use nalgebra::{Matrix3, Vector3};

/// The gap of one secondary node and its derivatives with respect to the
/// node's spatial position `x_s`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GapGeometry {
    /// Signed gap `g = (x_s − x̄)·n`; `g > 0` open, `g < 0` penetration.
    pub signed_gap: f64,
    /// Unit obstacle normal `n = ∂g/∂x_s`, pointing from the obstacle toward the body.
    pub normal: Vector3<f64>,
    /// Gap Hessian `H = ∂²g/∂x_s² = ∂n/∂x_s` (symmetric; zero for a plane).
    pub hessian: Matrix3<f64>,
}

impl GapGeometry {
    /// The one-dimensional geometry of a scalar gap `g` (`n = e₁`, `H = 0`):
    /// on it a normal law returns the force conjugate to the gap,
    /// `f = ∂(A_s Φ)/∂g`, as its `r_u[0]` (see [`kinematics`](super::kinematics)).
    pub fn scalar(g: f64) -> Self {
        Self {
            signed_gap: g,
            normal: Vector3::x(),
            hessian: Matrix3::zeros(),
        }
    }

    /// A plane through `point` with unit normal `normal`: `g = (x − x₀)·n`, `H = 0`.
    pub fn plane(
        spatial_point: &Vector3<f64>,
        point: &Vector3<f64>,
        normal: &Vector3<f64>,
    ) -> Self {
        let n = normal.normalize();
        Self {
            signed_gap: (spatial_point - point).dot(&n),
            normal: n,
            hessian: Matrix3::zeros(),
        }
    }

    /// Outside of a rigid sphere (centre `c`, radius `R`): `g = |x − c| − R`,
    /// `n = (x − c)/|x − c|`, `H = (I − n nᵀ)/|x − c|`.
    ///
    /// Undefined at the centre (the normal has no direction there).
    pub fn sphere(spatial_point: &Vector3<f64>, centre: &Vector3<f64>, radius: f64) -> Self {
        let d = spatial_point - centre;
        let dist = d.norm();
        let n = d / dist;
        Self {
            signed_gap: dist - radius,
            normal: n,
            hessian: (Matrix3::identity() - n * n.transpose()) / dist,
        }
    }
}
