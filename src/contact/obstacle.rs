//! Rigid obstacles and the projection of a point onto them.
//!
//! For a point `x` (a secondary node's current position) the projection
//! gives the closest point `x̄` on the obstacle's surface, the unit outward
//! normal `n` there (from the obstacle toward the body), the signed gap
//!
//! ```text
//! g(x) = (x − x̄)·n        g ≥ 0 open, g < 0 penetration
//! ```
//!
//! and its curvature `H = ∂²g/∂x²` (the gradient is `∂g/∂x = n`), which the
//! consistent contact tangent needs:
//!
//! | obstacle | `g` | `n` | `H` |
//! |---|---|---|---|
//! | plane through `p`, unit normal `m` | `(x − p)·m` | `m` | `0` |
//! | sphere, centre `c`, radius `R` (body outside) | `|x − c| − R` | `(x − c)/|x − c|` | `(I − n nᵀ)/|x − c|` |
//! | cylinder, axis through `p` along unit `a`, radius `R` (body outside) | `|r⊥| − R`, `r⊥ = (I − a aᵀ)(x − p)` | `r⊥/|r⊥|` | `(I − a aᵀ − n nᵀ)/|r⊥|` |
//! | triangulated surface | see [`TriangulatedSurface::project`] | | |
//!
//! The gap `|r| − R` is evaluated without the cancellation of its two
//! terms ([`compensated`](super::compensated)): against a sphere of radius
//! 100 the naive difference was off by an ulp of 100, and Newton stood
//! still at that floor.
//!
//! At the sphere's centre or on the cylinder's axis the normal is not
//! defined and the curvature is unbounded: there the projection picks a
//! fixed normal (`+z` for the sphere; for the cylinder the unit vector
//! `a × e_k / |a × e_k|`, `e_k` the coordinate axis least aligned with `a`)
//! and returns `H = 0`. Such a point is a penetration by a full radius, far
//! outside anything a converging contact iteration visits.
//!
//! Only the outside of spheres and cylinders is modelled (a body inside a
//! spherical cavity or a pipe is not).

use crate::contact::compensated::ExactVector;
pub use crate::contact::projection::Projection;
use crate::contact::triangulated::TriangulatedSurface;
use crate::error::{Error, Result};
use nalgebra::{Matrix3, Vector3};

/// A rigid obstacle. Build the analytic shapes with [`RigidObstacle::plane`],
/// [`RigidObstacle::sphere`] and [`RigidObstacle::cylinder`], which check the
/// input and normalise the directions; [`RigidObstacle::project`] relies on
/// `normal` and `axis` being unit vectors and `radius > 0`.
#[derive(Clone, Debug)]
pub enum RigidObstacle {
    /// A half-space whose boundary passes through `point`; `normal` (unit)
    /// points out of the obstacle, toward the body.
    Plane {
        point: Vector3<f64>,
        normal: Vector3<f64>,
    },
    /// A solid sphere; the body is outside.
    Sphere { center: Vector3<f64>, radius: f64 },
    /// A solid infinite circular cylinder; the body is outside. `axis` is a
    /// unit vector.
    Cylinder {
        point_on_axis: Vector3<f64>,
        axis: Vector3<f64>,
        radius: f64,
    },
    /// A triangulated surface (a closed solid, or an open sheet whose
    /// triangles' right-hand normals face the body).
    Triangulated(TriangulatedSurface),
}

/// `v/|v|`, or an error naming `name` if `v` is zero or not finite.
fn unit(v: Vector3<f64>, what: &str, name: &str) -> Result<Vector3<f64>> {
    let len = v.norm();
    if !(len > 0.0) || !len.is_finite() {
        return Err(Error::contact_input(
            what,
            format!(
                "the {name} must be a non-zero finite vector, got [{}, {}, {}]",
                v[0], v[1], v[2]
            ),
        ));
    }
    Ok(v / len)
}

fn positive_radius(radius: f64, what: &str) -> Result<f64> {
    if !(radius > 0.0) || !radius.is_finite() {
        return Err(Error::contact_input(
            what,
            format!("the radius must be positive and finite, got {radius}"),
        ));
    }
    Ok(radius)
}

fn finite_point(p: Vector3<f64>, what: &str, name: &str) -> Result<Vector3<f64>> {
    if !p.iter().all(|x| x.is_finite()) {
        return Err(Error::contact_input(
            what,
            format!("the {name} must be finite"),
        ));
    }
    Ok(p)
}

impl RigidObstacle {
    /// A plane through `point` with outward normal `normal` (normalised
    /// here). Errors if the normal is zero or anything is not finite.
    pub fn plane(point: Vector3<f64>, normal: Vector3<f64>) -> Result<Self> {
        let what = "plane obstacle";
        Ok(RigidObstacle::Plane {
            point: finite_point(point, what, "point")?,
            normal: unit(normal, what, "normal")?,
        })
    }

    /// A sphere (body outside). Errors if the radius is not positive.
    pub fn sphere(center: Vector3<f64>, radius: f64) -> Result<Self> {
        let what = "sphere obstacle";
        Ok(RigidObstacle::Sphere {
            center: finite_point(center, what, "centre")?,
            radius: positive_radius(radius, what)?,
        })
    }

    /// An infinite cylinder (body outside). `axis` is normalised here.
    /// Errors if the axis is zero or the radius is not positive.
    pub fn cylinder(point_on_axis: Vector3<f64>, axis: Vector3<f64>, radius: f64) -> Result<Self> {
        let what = "cylinder obstacle";
        Ok(RigidObstacle::Cylinder {
            point_on_axis: finite_point(point_on_axis, what, "point on the axis")?,
            axis: unit(axis, what, "axis")?,
            radius: positive_radius(radius, what)?,
        })
    }

    /// The obstacle moved rigidly by `d` (prescribed obstacle motion).
    pub fn translated(&self, d: &Vector3<f64>) -> Self {
        let mut moved = self.clone();
        match &mut moved {
            RigidObstacle::Plane { point, .. } => *point += d,
            RigidObstacle::Sphere { center, .. } => *center += d,
            RigidObstacle::Cylinder { point_on_axis, .. } => *point_on_axis += d,
            RigidObstacle::Triangulated(surface) => *surface = surface.translated(d),
        }
        moved
    }

    /// [`project`](Self::project) for a contact node that keeps the
    /// triangle `kept` of a triangulated obstacle (the facet choice of
    /// [`TriangulatedSurface::project_keeping`]), with the triangle it is
    /// on (`None` for the other shapes, which have no facets).
    pub fn project_keeping(
        &self,
        x: &Vector3<f64>,
        kept: Option<usize>,
    ) -> (Option<usize>, Projection) {
        match self {
            RigidObstacle::Triangulated(surface) => {
                let (t, p) = surface.project_keeping(x, kept);
                (Some(t), p)
            }
            _ => (None, self.project(x)),
        }
    }

    /// Projects the spatial point `x` onto the obstacle (see the module
    /// documentation for the formulas).
    pub fn project(&self, x: &Vector3<f64>) -> Projection {
        // a sphere or a cylinder: the centre `c` (on the axis) nearest `x`,
        // `r = x − c` across the axis (kept exactly, see `compensated`),
        // the projector `P` on the directions across it (`I`, `I − a aᵀ`)
        // and the normal at the centre
        let (centre, r, projector, radius, at_centre) = match self {
            RigidObstacle::Plane { point, normal } => {
                let gap = (x - point).dot(normal);
                return Projection {
                    point: x - normal * gap,
                    normal: *normal,
                    gap,
                    curvature: Matrix3::zeros(),
                };
            }
            RigidObstacle::Sphere { center, radius } => (
                *center,
                ExactVector::difference(x, center),
                Matrix3::identity(),
                radius,
                Vector3::z(),
            ),
            RigidObstacle::Cylinder {
                point_on_axis,
                axis,
                radius,
            } => {
                let r = ExactVector::difference(x, point_on_axis);
                let along = axis.dot(&r.hi);
                let projector = Matrix3::identity() - axis * axis.transpose();
                let centre = point_on_axis + axis * along;
                (
                    centre,
                    r.across(axis),
                    projector,
                    radius,
                    perpendicular_unit(axis),
                )
            }
            RigidObstacle::Triangulated(surface) => return surface.project(x),
        };
        // n = r/|r|, H = (P − n nᵀ)/|r|, x̄ = c + R n, g = |r| − R
        let d = r.hi.norm();
        let (normal, curvature) = if d > 1e-14 * radius {
            let n = r.hi / d;
            (n, (projector - n * n.transpose()) / d)
        } else {
            (at_centre, Matrix3::zeros())
        };
        let point = centre + normal * *radius;
        let gap = if d > 1e-14 * radius {
            r.distance_minus(*radius)
        } else {
            (x - point).dot(&normal)
        };
        Projection {
            point,
            normal,
            gap,
            curvature,
        }
    }
}

/// A unit vector perpendicular to the unit vector `a`, chosen
/// deterministically: `a × e_k` normalised, `e_k` the coordinate axis with
/// the smallest `|a_k|`.
fn perpendicular_unit(a: &Vector3<f64>) -> Vector3<f64> {
    let k = (0..3)
        .min_by(|&i, &j| a[i].abs().total_cmp(&a[j].abs()))
        .unwrap_or(0);
    let mut e = Vector3::zeros();
    e[k] = 1.0;
    a.cross(&e).normalize()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn constructors_reject_bad_input_and_name_it() {
        let e = RigidObstacle::plane(Vector3::zeros(), Vector3::zeros()).unwrap_err();
        assert!(e.to_string().contains("plane obstacle"), "{e}");
        assert!(e.to_string().contains("normal"), "{e}");
        let e = RigidObstacle::sphere(Vector3::zeros(), 0.0).unwrap_err();
        assert!(e.to_string().contains("radius"), "{e}");
        let e = RigidObstacle::sphere(Vector3::zeros(), f64::NAN).unwrap_err();
        assert!(e.to_string().contains("radius"), "{e}");
        let e = RigidObstacle::cylinder(Vector3::zeros(), Vector3::zeros(), 1.0).unwrap_err();
        assert!(e.to_string().contains("axis"), "{e}");
        let e = RigidObstacle::cylinder(Vector3::zeros(), Vector3::x(), -1.0).unwrap_err();
        assert!(e.to_string().contains("cylinder obstacle") && e.to_string().contains("radius"));
    }

    #[test]
    fn singular_points_give_finite_deterministic_projections() {
        let s = RigidObstacle::sphere(Vector3::new(1.0, 2.0, 3.0), 2.0).unwrap();
        let p = s.project(&Vector3::new(1.0, 2.0, 3.0));
        assert_eq!(p.normal, Vector3::z());
        assert!((p.gap + 2.0).abs() < 1e-15);
        for axis in [Vector3::x(), Vector3::new(1.0, 1.0, 1.0), Vector3::z()] {
            let c = RigidObstacle::cylinder(Vector3::zeros(), axis, 0.5).unwrap();
            let p = c.project(&(axis * 3.0));
            assert!((p.normal.norm() - 1.0).abs() < 1e-15);
            assert!(p.normal.dot(&axis).abs() < 1e-15);
            assert!((p.gap + 0.5).abs() < 1e-15);
            assert!(p.curvature.iter().all(|x| x.is_finite()));
        }
    }
}
