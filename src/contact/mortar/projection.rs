//! The projection of a point onto a face along a given direction (Popp et
//! al. 2010, §4.3: the integration points of a cell in the auxiliary plane
//! go back to both faces along `n₀`): find `ξ` and `α` with
//!
//! ```text
//! r(ξ, α) = x(ξ) − X − α d = 0,
//! ```
//!
//! by Newton's method on `[x_,ξ  x_,η  −d] (Δξ, Δη, Δα) = −r`, exact in one
//! step on flat affine faces and quadratic-convergent on curved ones.

use nalgebra::{Matrix3, Vector3};

use super::face::MortarFace;
use super::MortarError;

/// A point on a face reached along a direction: reference coordinates `ξ`
/// and the distance `α` with `x(ξ) = X + α d`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FacePoint {
    pub xi: [f64; 2],
    pub distance: f64,
}

impl FacePoint {
    /// The projection's Jacobian at this point of `face` along `direction`,
    /// for its derivatives ([`projection_derivative`]): formed once per
    /// point by the callers that differentiate (one per point, not one per
    /// derivative direction), not by [`project_along`], whose points are
    /// mostly integrated without derivatives (the condensed path's
    /// rounds).
    pub fn jacobian(
        &self,
        face: &MortarFace,
        direction: &Vector3<f64>,
    ) -> Result<ProjectionJacobian, MortarError> {
        ProjectionJacobian::at(face, self.xi, direction)
    }
}

/// The projection's Jacobian `A = [x_,ξ(ξ)  x_,η(ξ)  −d]` at a point, held
/// as its adjugate (Cramer's rule): for `A = [a b c]`,
///
/// ```text
/// A⁻¹ = [b×c  c×a  a×b]ᵀ / (a·(b×c)),
/// ```
///
/// each column's scale cancelling in its row. (A generic 3 × 3 LU with
/// pivoting, not inlined, formed anew for every projection step and every
/// derivative direction, was 17 % of a condensed mortar run's samples.)
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ProjectionJacobian {
    rows: [Vector3<f64>; 3],
    determinant: f64,
}

impl ProjectionJacobian {
    /// `A` at `ξ` on `face` along `direction`; a face parallel to the
    /// direction (a zero or non-finite determinant) is an error.
    pub fn at(
        face: &MortarFace,
        xi: [f64; 2],
        direction: &Vector3<f64>,
    ) -> Result<Self, MortarError> {
        let [a, b] = face.tangents(xi);
        let c = -direction;
        let rows = [b.cross(&c), c.cross(&a), a.cross(&b)];
        let determinant = a.dot(&rows[0]);
        if determinant == 0.0 || !determinant.is_finite() {
            return Err(MortarError::Projection {
                what: format!("the face is parallel to the direction {direction:?}"),
            });
        }
        Ok(ProjectionJacobian { rows, determinant })
    }

    /// `A⁻¹ v`.
    pub fn solve(&self, v: &Vector3<f64>) -> Vector3<f64> {
        Vector3::from(self.rows.map(|row| row.dot(v) / self.determinant))
    }
}

/// A 3 × 3 LU with partial pivoting.
type Lu3 = nalgebra::LU<f64, nalgebra::U3, nalgebra::U3>;

/// Newton iterations allowed before the projection is declared failed.
const MAX_ITERATIONS: usize = 30;

/// Steps in `ξ` below this are at round-off when they stop shrinking.
const ROUND_OFF_STEP: f64 = 1e-11;

/// Projects `point` onto `face` along `direction` (see the module doc).
/// The start is the face's reference centre; the iteration stops when the
/// step is below `1e-14` in `ξ`, or below [`ROUND_OFF_STEP`] and no less
/// than half the step before: Newton's quadratic rate would have cut it
/// far more, so the iteration sits at its round-off floor (a face steeply
/// inclined to `direction`, far from the origin: the die's arc of
/// `examples/ironing-mortar` at 60°, coordinates ≈ 5, hovered at
/// 2e-14). A face parallel to `direction` or a non-converging iteration is
/// an error.
pub fn project_along(
    face: &MortarFace,
    point: &Vector3<f64>,
    direction: &Vector3<f64>,
) -> Result<FacePoint, MortarError> {
    let mut xi = face.shape.centre();
    let mut alpha = 0.0;
    let mut previous = f64::INFINITY;
    let mut factored = None;
    for _ in 0..MAX_ITERATIONS {
        let r = face.point(xi) - point - direction * alpha;
        let step = newton_step(face, xi, direction, &r, &mut factored)?;
        xi = [xi[0] + step[0], xi[1] + step[1]];
        alpha += step[2];
        let size = step[0].abs().max(step[1].abs());
        let floor = size < ROUND_OFF_STEP && size >= 0.5 * previous;
        previous = size;
        if size < 1e-14 || floor {
            return Ok(FacePoint {
                xi,
                distance: alpha,
            });
        }
    }
    Err(MortarError::Projection {
        what: format!(
            "Newton did not converge in {MAX_ITERATIONS} iterations projecting {point:?}"
        ),
    })
}

/// The directional derivative `(δξ, δα)` of a projection `hit` for
/// increments `dx` of the face's nodes, `d_point` of the projected point
/// and `d_direction` of the direction (Popp et al. 2010, §5.3, by the
/// implicit function theorem on `r = 0`), `jacobian` the projection's
/// there ([`FacePoint::jacobian`]):
///
/// ```text
/// [x_,ξ  x_,η  −d] (δξ, δη, δα) = −(Σ_a N_a(ξ) δx_a − δX − α δd).
/// ```
pub fn projection_derivative(
    face: &MortarFace,
    hit: &FacePoint,
    jacobian: &ProjectionJacobian,
    dx: &[Vector3<f64>],
    d_point: &Vector3<f64>,
    d_direction: &Vector3<f64>,
) -> ([f64; 2], f64) {
    let n = face.shape.values(hit.xi);
    let dr: Vector3<f64> = dx.iter().zip(&n).map(|(d, n)| d * *n).sum::<Vector3<f64>>()
        - d_point
        - d_direction * hit.distance;
    let step = jacobian.solve(&-dr);
    ([step[0], step[1]], step[2])
}

/// Solves `[x_,ξ(ξ)  x_,η(ξ)  −d] s = −r` by LU with pivoting (the
/// projection itself, as before the adjugate: its gaps decide the
/// touching nodes' ties at a zero gap); a face parallel to `d` is an
/// error. `factored` is the last step's matrix and its LU, reused where
/// the matrix is the same to the bit (an affine face, a Tri3's: its
/// tangents do not depend on `ξ`), so the step is the one a new LU gives.
fn newton_step(
    face: &MortarFace,
    xi: [f64; 2],
    direction: &Vector3<f64>,
    r: &Vector3<f64>,
    factored: &mut Option<(Matrix3<f64>, Lu3)>,
) -> Result<Vector3<f64>, MortarError> {
    let [t1, t2] = face.tangents(xi);
    let jacobian = Matrix3::from_columns(&[t1, t2, -direction]);
    if factored.as_ref().is_some_and(|(last, _)| *last != jacobian) {
        *factored = None;
    }
    let (_, lu) = factored.get_or_insert_with(|| (jacobian, jacobian.lu()));
    lu.solve(&-r).ok_or_else(|| MortarError::Projection {
        what: format!("the face is parallel to the direction {direction:?}"),
    })
}
