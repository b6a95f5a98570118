//! Dual mortar contact kernels (issue 28): pure functions of the faces'
//! current coordinates and their derivatives, not yet wired into Newton.
//!
//! - [`face`]: a contact face (Tri3, Quad4, Tri6, Quad8) and its map
//!   `x(ξ)`, tangents and normal.
//! - [`quadratic`]: the basis transformation `Ñ = T N` of quadratic
//!   secondary faces (Popp, Wohlmuth, Gee & Wall 2012), so every `∫ Ñ_j > 0`.
//! - [`dual_basis`]: the biorthogonal multiplier basis `Φ = A_e Ñ`,
//!   `A_e = D_e M_e⁻¹` (Wohlmuth 2000).
//! - [`auxiliary_plane`], [`clipping`], [`projection`]: the segmentation of
//!   a face pair in the secondary face's auxiliary plane (Puso & Laursen
//!   2004; Popp, Gitterle, Gee & Wall 2010).
//! - [`normals`]: averaged nodal normals and their derivatives.
//! - [`segment`]: one pair's contributions to `D` and `M`.
//! - [`weighted_gap`]: the assembled `D`, `M`, averaged nodal normals,
//!   weighted gaps `g̃_j` and the contact forces of the multipliers.
//! - [`clip_derivatives`], [`segment_derivatives`], [`pair_linearisation`]:
//!   the directional derivatives of the segmentation and of a pair's `D`
//!   and `M` (Popp, Gitterle, Gee & Wall 2010, §5), and a pair's gradients.
//! - [`obstacle_rows`]: the rows of a secondary surface against a rigid
//!   obstacle, integrated over the secondary faces alone.
//! - [`rows`]: per secondary node, `g̃_j`, `D_j`, `M_jl`, `n_j` and the
//!   lever `b_j` with their gradients, as Newton needs them.
//! - [`weighted_slip`]: the frame-indifferent weighted slip increment
//!   `w_j` from the change of `D`, `M` since the last converged increment
//!   (Gitterle, Popp, Gee & Wall 2010) and its derivative, for friction.
//!
//! Conventions as in `formulation.md`: `g̃_j ≥ 0` open, `λ_j ≥ 0`
//! compressive; the secondary surface's normals point outward (toward the
//! primary body). See DESIGN.md, "Mortar contact".

pub mod auxiliary_plane;
pub mod clip_derivatives;
pub mod clipping;
pub mod dual_basis;
pub mod face;
pub mod normals;
pub mod obstacle_rows;
pub mod pair_linearisation;
pub mod projection;
pub mod quadratic;
pub mod rows;
pub mod segment;
pub mod segment_derivatives;
pub mod weighted_gap;
pub mod weighted_slip;

pub use dual_basis::{node_integrals, DualBasis, FaceIntegrals};
pub use face::{FaceShape, MortarFace, SurfaceFace};
pub use normals::{nodal_normal_derivatives, nodal_normal_gradient, nodal_normals};
pub use rows::{mortar_row_values, mortar_rows, MortarRow, RowValues};
pub use segment::{integrate_pair, overlap, Overlap, SegmentIntegrals};
pub use weighted_gap::{all_pairs, mortar_coupling, MortarCoupling};

/// What a row producer ([`mortar_rows`], [`obstacle_rows::obstacle_rows`])
/// integrates: the values alone (`g̃_j`, `D_j`, `M_jl`, `n_j` and the lever
/// `b_j`), what a residual or a condensed solve reads, or those with
/// their complete first derivatives, what a tangent reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Derivatives {
    /// The values alone: every gradient of the row left empty.
    Without,
    /// The values and their complete first derivatives.
    With,
}

/// What went wrong in a mortar kernel, in the words of the face's data.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum MortarError {
    #[error("a {shape:?} contact face needs {} nodes, {given} were given", shape.node_count())]
    NodeCount { shape: FaceShape, given: usize },
    #[error("contact face node {node} is not among the {count} nodes given")]
    NodeIndex { node: usize, count: usize },
    #[error(
        "degenerate contact face: {what}; check that its nodes are distinct and not collinear"
    )]
    DegenerateFace { what: String },
    #[error("secondary node {node} is on none of the contact faces given for it")]
    NotOnFaces { node: usize },
    #[error("projection onto a contact face failed: {what}; check the face for distortion")]
    Projection { what: String },
}
