//! Contact geometry: the kernels that turn a secondary node's position into
//! a gap, a normal and a curvature, and the weights that turn a contact
//! pressure into nodal forces.
//!
//! - [`obstacle`]: rigid obstacles (plane, sphere, cylinder, triangulated
//!   surface) and their [`Projection`] of a point:
//!   closest point `x̄`, unit outward normal `n`, signed gap `g` and
//!   curvature `∂²g/∂x²`.
//! - [`triangle`]: the closest point on one triangle, with the Voronoi
//!   feature (face, edge, vertex) it lies on.
//! - [`triangulated`]: a triangulated surface with a bounding-volume
//!   hierarchy for the closest-point search and pseudo-normals for the sign;
//!   read from STL or from a Gmsh surface set.
//! - [`tributary`]: the tributary reference area `A_s` of each secondary node.
//!
//! ## Conventions (as in the crate root and `formulation.md` §2)
//! - The obstacle's outward normal `n` points from the obstacle toward the
//!   body.
//! - Signed gap `g = (x_s − x̄)·n`: `g ≥ 0` open, `g < 0` penetration.
//! - In two-body contact the surfaces are *primary* (projected onto) and
//!   *secondary* (whose nodes are projected).
//!
//! Status: these are the geometric building blocks only. Nothing here is
//! called by the Newton solver yet; the contact residual, tangent and
//! enforcement methods come with the integration.

pub mod obstacle;
pub mod triangle;
pub mod triangulated;
pub mod tributary;

pub use obstacle::{Projection, RigidObstacle};
pub use triangle::{closest_point_on_triangle, Feature, TriangleProjection};
pub use triangulated::TriangulatedSurface;
pub use tributary::tributary_areas;
