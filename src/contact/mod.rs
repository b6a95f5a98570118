//! Contact: the kernels that turn a secondary node's position into a gap, a
//! normal and a curvature, the per-node normal-contact laws and Coulomb
//! friction, the node driver that carries them to the nodes' unknowns, and
//! the interfaces' life cycle and report. Imports point one way, in the
//! order of this list.
//!
//! - [`compensated`], [`projection`], [`obstacle`]: rigid obstacles (plane, sphere,
//!   cylinder, triangulated surface) and their [`Projection`] of a point:
//!   closest point `x̄`, unit outward normal `n`, signed gap `g` and
//!   curvature `∂²g/∂x²` (the gap to a sphere or a cylinder without
//!   cancellation by [`compensated`]); [`gap`]: that projection as the laws read it.
//! - [`triangle`]: the closest point on one triangle, with the Voronoi
//!   feature (face, edge, vertex) it lies on.
//! - [`triangulated`]: a triangulated surface with an R*-tree (`rstar`) for
//!   the closest-point search and pseudo-normals for the sign; read from
//!   STL or from a Gmsh surface set.
//! - [`triangle_gap`]: a secondary node's gap against a deforming primary
//!   triangle, with its exact gradient and Hessian in all four nodes.
//! - [`tributary`]: the tributary reference area `A_s` of each node of a
//!   surface.
//! - [`primary`]: a primary surface of a deformable body as triangles, and
//!   the per-increment search (an R*-tree of boxes) pairing secondary nodes
//!   with them; [`facet_walk`]: what a node's choice among them
//!   remembers within an increment.
//! - [`dimension`]: the size of a node's unknowns, fixed (`Const<N>`) or
//!   at run time (`Dyn`), and the allocator bound that goes with it.
//! - [`friction`]: Coulomb friction by return mapping, its consistent
//!   (nonsymmetric) linearisation and the history committed per increment.
//! - [`laws`]: per-node enforcement of the normal constraint (penalty, Uzawa
//!   augmented Lagrangian, Rockafellar augmented Lagrangian, the paper's
//!   slack-variable Lagrangian), residual and tangent blocks in `(u_s, λ_s)`.
//! - [`kinematics`]: the node driver's algebra: a node's gap over the
//!   unknowns of its contribution, its coupled nodes and primary weights,
//!   the laws' chain rule, and what a primary kind supplies
//!   ([`kinematics::GapProducer`]); its producers [`rigid`] (a rigid
//!   obstacle), [`surface_contact`] (a moving primary triangle) and
//!   [`mortar_contact`] (dual mortar between two bodies, on the kernels of
//!   [`mortar`]); [`mortar_rigid`] (dual mortar against a rigid obstacle,
//!   read through [`mortar_contact`]'s producer).
//! - [`interface`]: one secondary surface against its primary, and the
//!   node driver's loop; [`set`]: the interfaces of a problem and their
//!   life cycle; [`setup`]: building interfaces from a mesh; [`report`]:
//!   what contact reports of a converged increment, per node and per
//!   interface.
//! - [`hertz`]: Hertz's solution, the reference of the contact examples.
//!
//! ## Conventions (as in the crate root and `formulation.md` §2)
//! - The obstacle's outward normal `n` points from the obstacle toward the
//!   body.
//! - Signed gap `g = (x_s − x̄)·n`: `g ≥ 0` open, `g < 0` penetration.
//! - In two-body contact the surfaces are *primary* (projected onto) and
//!   *secondary* (whose nodes are projected).

pub mod compensated;
pub mod dimension;
pub mod facet_walk;
pub mod friction;
pub mod gap;
pub mod hertz;
pub mod interface;
pub mod kinematics;
pub mod laws;
pub mod mortar;
pub mod mortar_contact;
pub mod mortar_friction;
pub mod mortar_rigid;
pub mod obstacle;
pub mod primary;
pub mod projection;
pub mod report;
pub mod rigid;
pub mod set;
pub mod setup;
pub mod surface_contact;
pub mod sweep;
pub mod triangle;
pub mod triangle_gap;
pub mod triangulated;
pub mod tributary;

pub use obstacle::{Projection, RigidObstacle};
pub use triangle::{closest_point_on_triangle, Feature, TriangleProjection};
pub use triangulated::TriangulatedSurface;
pub use tributary::tributary_areas;
