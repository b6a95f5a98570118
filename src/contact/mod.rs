//! Contact: the kernels that turn a secondary node's position into a gap, a
//! normal and a curvature, the weights that turn a contact pressure into
//! nodal forces, and the per-node normal-contact laws.
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
//! - [`triangle_gap`]: a secondary node's gap against a deforming primary
//!   triangle, with its exact gradient and Hessian in all four nodes.
//! - [`tributary`]: the tributary reference area `A_s` of each secondary node.
//! - [`primary`]: a primary surface of a deformable body as triangles, and
//!   the per-increment search pairing secondary nodes with them;
//!   [`surface_contact`] assembles a secondary node against a moving primary
//!   triangle through the normal laws.
//! - [`laws`]: per-node enforcement of the normal constraint (penalty, Uzawa
//!   augmented Lagrangian, Rockafellar augmented Lagrangian, the paper's
//!   slack-variable Lagrangian), residual and tangent blocks in `(u_s, λ_s)`.
//! - [`friction`]: Coulomb friction by return mapping, its consistent
//!   (nonsymmetric) linearisation and the history committed per increment.
//!
//! ## Conventions (as in the crate root and `formulation.md` §2)
//! - The obstacle's outward normal `n` points from the obstacle toward the
//!   body.
//! - Signed gap `g = (x_s − x̄)·n`: `g ≥ 0` open, `g < 0` penetration.
//! - In two-body contact the surfaces are *primary* (projected onto) and
//!   *secondary* (whose nodes are projected).
//!
//! [`interface`] ties them together: a secondary surface against a rigid
//! obstacle, assembled into the Newton system (see DESIGN.md, "Contact
//! with rigid obstacles").

pub mod friction;
pub mod gap;
pub mod hertz;
pub mod interface;
pub mod kinematics;
pub mod laws;
pub mod mortar;
pub mod obstacle;
pub mod primary;
pub mod projection;
pub mod rigid;
pub mod set;
pub mod setup;
pub mod surface_contact;
pub mod triangle;
pub mod triangle_gap;
pub mod triangulated;
pub mod tributary;

pub use obstacle::{Projection, RigidObstacle};
pub use triangle::{closest_point_on_triangle, Feature, TriangleProjection};
pub use triangulated::TriangulatedSurface;
pub use tributary::tributary_areas;
