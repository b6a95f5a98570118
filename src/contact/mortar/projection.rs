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

/// A 3 × 3 LU with partial pivoting, nalgebra's `LU::new` and
/// `LU::solve` written out for three rows: the same pivots and the same
/// floating-point operations in the same order, so the same bits (a unit
/// test holds it to them). nalgebra's generic one, not inlined, was 24 % of
/// the samples of two-spheres' `mortar.toml` (Tet10, Tri6 faces: a new
/// matrix at every projection step).
#[derive(Clone, Copy, Debug)]
struct Lu3 {
    /// `L` (unit diagonal, below) and `U` (on and above), by rows.
    lu: [[f64; 3]; 3],
    /// The row swaps `(i, pivot)` of the factorisation, in order.
    swaps: [Option<usize>; 3],
}

impl Lu3 {
    /// Factorises `a`: in column `i`, the first row from `i` down with the
    /// largest `|a_ri|` is the pivot; a zero column is skipped (a singular
    /// `U`, which [`solve`](Self::solve) reports).
    fn new(a: &Matrix3<f64>) -> Self {
        let mut lu = [0, 1, 2].map(|r| [0, 1, 2].map(|c| a[(r, c)]));
        let mut swaps = [None; 3];
        for i in 0..3 {
            let mut pivot = i;
            let mut largest = lu[i][i].abs();
            for (r, row) in lu.iter().enumerate().skip(i + 1) {
                if row[i].abs() > largest {
                    largest = row[i].abs();
                    pivot = r;
                }
            }
            let diagonal = lu[pivot][i];
            if diagonal == 0.0 {
                continue;
            }
            if pivot != i {
                swaps[i] = Some(pivot);
                lu.swap(i, pivot);
            }
            let inverse = 1.0 / diagonal;
            for row in &mut lu[i + 1..] {
                row[i] *= inverse;
            }
            let pivot_row = lu[i];
            for row in &mut lu[i + 1..] {
                let multiplier = row[i];
                for (entry, upper) in row[i + 1..].iter_mut().zip(&pivot_row[i + 1..]) {
                    *entry += -upper * multiplier;
                }
            }
        }
        Lu3 { lu, swaps }
    }

    /// `A⁻¹ b` (the swaps, then `L`, then `U`); `None` where `U` has a zero
    /// on its diagonal.
    fn solve(&self, b: &Vector3<f64>) -> Option<Vector3<f64>> {
        let lu = &self.lu;
        let mut x = [b[0], b[1], b[2]];
        for (i, pivot) in self.swaps.iter().enumerate() {
            if let Some(p) = *pivot {
                x.swap(i, p);
            }
        }
        for i in 0..2 {
            let coefficient = x[i];
            for r in i + 1..3 {
                x[r] += -coefficient * lu[r][i];
            }
        }
        for i in (0..3).rev() {
            if lu[i][i] == 0.0 {
                return None;
            }
            let coefficient = x[i] / lu[i][i];
            x[i] = coefficient;
            for r in 0..i {
                x[r] += -coefficient * lu[r][i];
            }
        }
        Some(Vector3::from(x))
    }
}

/// Newton iterations allowed before the projection is declared failed.
const MAX_ITERATIONS: usize = 30;

/// Steps in `ξ` below this are at round-off when they stop shrinking.
const ROUND_OFF_STEP: f64 = 1e-11;

/// Projects `point` onto `face` along `direction` (see the module doc):
/// [`Projector::project`] for a single point.
pub fn project_along(
    face: &MortarFace,
    point: &Vector3<f64>,
    direction: &Vector3<f64>,
) -> Result<FacePoint, MortarError> {
    Projector::new(face, direction).project(point)
}

/// Projections of points onto one face along one direction (a cell's
/// integration points onto either face along `n₀`), the Newton matrix
/// `[x_,ξ  x_,η  −d]` and its LU kept from step to step and point to
/// point where the matrix is the same to the bit: on an affine face
/// (Tri3, [`crate::contact::mortar::face::FaceShape::is_affine`]) it is
/// formed and factorised once for all the points, and each point's steps
/// are the ones a new LU gives.
pub struct Projector<'a> {
    face: &'a MortarFace,
    direction: Vector3<f64>,
    factored: Option<(Matrix3<f64>, Lu3)>,
}

impl<'a> Projector<'a> {
    pub fn new(face: &'a MortarFace, direction: &Vector3<f64>) -> Self {
        Projector {
            face,
            direction: *direction,
            factored: None,
        }
    }

    /// Projects `point`. The start is the face's reference centre; the
    /// iteration stops when the step is below `1e-14` in `ξ`, or below
    /// [`ROUND_OFF_STEP`] and no less than half the step before: Newton's
    /// quadratic rate would have cut it far more, so the iteration sits at
    /// its round-off floor (a face steeply inclined to the direction, far
    /// from the origin: the die's arc of `examples/ironing-mortar` at 60°,
    /// coordinates ≈ 5, hovered at 2e-14). A face parallel to the
    /// direction or a non-converging iteration is an error.
    pub fn project(&mut self, point: &Vector3<f64>) -> Result<FacePoint, MortarError> {
        let (face, direction) = (self.face, self.direction);
        let mut xi = face.shape.centre();
        let mut alpha = 0.0;
        let mut previous = f64::INFINITY;
        for _ in 0..MAX_ITERATIONS {
            let r = face.point(xi) - point - direction * alpha;
            let step = newton_step(face, xi, &direction, &r, &mut self.factored)?;
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
/// tangents do not depend on `ξ`, and are not formed again), so the step
/// is the one a new LU gives.
fn newton_step(
    face: &MortarFace,
    xi: [f64; 2],
    direction: &Vector3<f64>,
    r: &Vector3<f64>,
    factored: &mut Option<(Matrix3<f64>, Lu3)>,
) -> Result<Vector3<f64>, MortarError> {
    let (jacobian, lu) = match factored.take() {
        Some(kept) if face.shape.is_affine() => kept,
        kept => {
            let [t1, t2] = face.tangents(xi);
            let jacobian = Matrix3::from_columns(&[t1, t2, -direction]);
            match kept {
                Some(kept) if kept.0 == jacobian => kept,
                _ => (jacobian, Lu3::new(&jacobian)),
            }
        }
    };
    *factored = Some((jacobian, lu));
    lu.solve(&-r).ok_or_else(|| MortarError::Projection {
        what: format!("the face is parallel to the direction {direction:?}"),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    /// The written-out LU gives nalgebra's answer to the bit: on random
    /// matrices, on matrices whose every pivot order occurs (rows scaled
    /// apart), and on ones with equal candidates and zero columns.
    #[test]
    fn lu3_is_nalgebras_to_the_bit() {
        let mut rng = rand::rngs::StdRng::seed_from_u64(28);
        let mut matrices: Vec<Matrix3<f64>> = Vec::new();
        for _ in 0..2000 {
            let mut a = Matrix3::from_fn(|_, _| rng.gen_range(-1.0..1.0));
            for r in 0..3 {
                let scale = 10f64.powi(rng.gen_range(-3..4));
                a.row_mut(r).scale_mut(scale);
            }
            matrices.push(a);
        }
        matrices.push(Matrix3::new(1.0, 2.0, 3.0, 1.0, 5.0, 6.0, -1.0, 8.0, 10.0));
        matrices.push(Matrix3::new(0.0, 2.0, 3.0, 0.0, 5.0, 6.0, 0.0, 8.0, 10.0));
        matrices.push(Matrix3::new(1.0, 2.0, 3.0, 2.0, 4.0, 6.0, 0.5, 1.0, 7.0));
        let mut checked = 0;
        for a in &matrices {
            let b = Vector3::new(rng.gen_range(-1.0..1.0), 0.25, -3.0);
            let theirs = a.lu().solve(&b);
            let ours = Lu3::new(a).solve(&b);
            assert_eq!(theirs.is_some(), ours.is_some(), "{a}");
            if let (Some(t), Some(o)) = (theirs, ours) {
                let bits = |v: Vector3<f64>| v.map(f64::to_bits);
                assert_eq!(bits(t), bits(o), "{a}");
                checked += 1;
            }
        }
        assert!(checked > 2000);
    }

    /// One [`Projector`] kept over many points (a cell's integration
    /// points) gives, to the bit, the projections of a new one per point
    /// ([`project_along`]): on every face shape, curved and tilted, away
    /// from the origin, along oblique directions.
    #[test]
    fn a_kept_projector_projects_as_a_new_one_to_the_bit() {
        use super::super::face::{FaceShape, MortarFace};
        let mut rng = rand::rngs::StdRng::seed_from_u64(7);
        let mut checked = 0;
        for shape in [
            FaceShape::Tri3,
            FaceShape::Quad4,
            FaceShape::Tri6,
            FaceShape::Quad8,
        ] {
            for _ in 0..200 {
                let coords: Vec<Vector3<f64>> = shape
                    .reference_nodes()
                    .iter()
                    .map(|x| {
                        Vector3::new(
                            x[0] * 1.3 + rng.gen_range(-0.05..0.05) + 5.0,
                            x[1] * 0.9 + rng.gen_range(-0.05..0.05) - 3.0,
                            rng.gen_range(-0.1..0.1) + 0.3 * x[0],
                        )
                    })
                    .collect();
                let face = MortarFace::new(shape, coords).unwrap();
                let d = Vector3::new(rng.gen_range(-0.2..0.2), rng.gen_range(-0.2..0.2), 1.0)
                    .normalize();
                let mut shared = Projector::new(&face, &d);
                for _ in 0..20 {
                    let xi = [rng.gen_range(0.0..0.3), rng.gen_range(0.0..0.3)];
                    let p = face.point(xi) + d * rng.gen_range(-0.2..0.2);
                    let a = Projector::new(&face, &d).project(&p);
                    let b = shared.project(&p);
                    match (a, b) {
                        (Ok(a), Ok(b)) => {
                            assert_eq!(a.xi.map(f64::to_bits), b.xi.map(f64::to_bits));
                            assert_eq!(a.distance.to_bits(), b.distance.to_bits());
                            checked += 1;
                        }
                        (Err(_), Err(_)) => {}
                        (a, b) => panic!("{shape:?}: {:?} against {:?}", a.is_ok(), b.is_ok()),
                    }
                }
            }
        }
        assert!(checked > 15000, "{checked}");
    }
}
