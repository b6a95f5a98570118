//! Segmentation and integration of one secondary–primary face pair (Puso &
//! Laursen 2004; Popp, Gitterle, Gee & Wall 2010, §4):
//!
//! 1. both faces' corners are projected along `n₀` onto the secondary
//!    face's [`AuxiliaryPlane`];
//! 2. the primary polygon is clipped by the secondary one
//!    (Sutherland–Hodgman, [`clipping`]);
//! 3. the clip polygon is split into triangles about its centroid;
//! 4. each triangle carries a collapsed Gauss rule whose points go back
//!    along `n₀` to both faces ([`project_along`]), and
//!
//! ```text
//! D_j  += Σ_q w_q Φ_j(ξ_s) J_q,            (lumped: ∫_cells Φ_j Σ_k Ñ_k dA)
//! M_jl += Σ_q w_q Φ_j(ξ_s) N_l(ξ_m) J_q,
//! J_q   = 2 A_cell · |a_s(ξ_s)| / |n₀ · a_s(ξ_s)|,
//! ```
//!
//! `A_cell` the triangle's area in the plane and `a_s = x_,ξ × x_,η` the
//! secondary area normal: the ratio carries the plane's area element to
//! the secondary surface's (it is 1 on a flat face, where the cells are
//! exactly the overlap on the face). With this lumping,
//! `Σ_l M_jl = D_j` on every cell since `Σ_l N_l = 1`, and on a secondary
//! face fully covered by primary faces `D_j = ∫_e Φ_j dA = ∫_e Ñ_j dA`.
//!
//! The clip uses the faces' corners: on a quadratic face with curved edges
//! the polygon is the straight-edged approximation of its projection.

use nalgebra::DMatrix;

use super::auxiliary_plane::AuxiliaryPlane;
use super::clipping::{self, Polygon};
use super::dual_basis::DualBasis;
use super::face::MortarFace;
use super::projection::project_along;
use super::MortarError;
use crate::fem::quadrature;

/// Points per direction of the cells' collapsed rule: 4, exact for total
/// degree 6 (the product `Φ_j N_l` of two Quad8 functions on flat
/// rectangular faces).
const CELL_RULE_POINTS: usize = 4;

/// The overlap of a face pair in the secondary face's auxiliary plane.
#[derive(Clone, Debug, PartialEq)]
pub struct Overlap {
    pub plane: AuxiliaryPlane,
    /// The clip polygon (counter-clockwise about `n₀`); empty if none.
    pub polygon: Polygon,
}

impl Overlap {
    /// The overlap's area in the auxiliary plane.
    pub fn area(&self) -> f64 {
        clipping::signed_area(&self.polygon)
    }
}

/// Projects both faces' corners onto the secondary face's auxiliary plane
/// and clips the primary polygon by the secondary one.
pub fn overlap(secondary: &MortarFace, primary: &MortarFace) -> Overlap {
    let plane = AuxiliaryPlane::of_face(secondary);
    let project = |face: &MortarFace| -> Polygon {
        clipping::counter_clockwise(
            face.corners()
                .iter()
                .map(|x| plane.local_point(x))
                .collect(),
        )
    };
    let polygon = clipping::clip_convex(&project(primary), &project(secondary));
    Overlap { plane, polygon }
}

/// The contributions of one face pair: `d[j] = D_j`, `m[(j, l)] = M_jl`
/// (secondary-local `j`, primary-local `l`) and the overlap's area on the
/// secondary surface `Σ_q w_q J_q`.
#[derive(Clone, Debug, PartialEq)]
pub struct SegmentIntegrals {
    pub d: Vec<f64>,
    pub m: DMatrix<f64>,
    pub area: f64,
}

/// Segments and integrates a pair (see the module doc); `None` when the
/// projected faces do not overlap.
pub fn integrate_pair(
    secondary: &MortarFace,
    dual: &DualBasis,
    primary: &MortarFace,
) -> Result<Option<SegmentIntegrals>, MortarError> {
    let overlap = overlap(secondary, primary);
    if overlap.polygon.is_empty() {
        return Ok(None);
    }
    let (ns, nm) = (secondary.shape.node_count(), primary.shape.node_count());
    let mut out = SegmentIntegrals {
        d: vec![0.0; ns],
        m: DMatrix::zeros(ns, nm),
        area: 0.0,
    };
    let (points, weights) = quadrature::triangle_collapsed(CELL_RULE_POINTS);
    let n0 = overlap.plane.normal;
    for cell in clipping::centroid_triangles(&overlap.polygon) {
        let cell_jacobian = 2.0 * clipping::signed_area(&cell);
        for (eta, w) in points.iter().zip(&weights) {
            let p = cell_point(&cell, *eta);
            let x = overlap.plane.spatial_point(p);
            let xi_s = project_along(secondary, &x, &n0)?.xi;
            let xi_m = project_along(primary, &x, &n0)?.xi;
            let a_s = secondary.area_normal(xi_s);
            let jacobian = cell_jacobian * a_s.norm() / n0.dot(&a_s).abs();
            add_point(
                &mut out,
                dual.values(xi_s),
                primary.shape.values(xi_m),
                w * jacobian,
            );
        }
    }
    Ok(Some(out))
}

/// The point `c₀ + η₁ (c₁ − c₀) + η₂ (c₂ − c₀)` of a cell.
fn cell_point(cell: &clipping::Triangle, eta: [f64; 2]) -> [f64; 2] {
    let [c0, c1, c2] = *cell;
    [0, 1].map(|d| c0[d] + eta[0] * (c1[d] - c0[d]) + eta[1] * (c2[d] - c0[d]))
}

/// Adds one integration point's `Φ_j w J` to `D_j` and `Φ_j N_l w J` to `M_jl`.
fn add_point(out: &mut SegmentIntegrals, phi: Vec<f64>, n_primary: Vec<f64>, weight: f64) {
    out.area += weight;
    for (j, phi_j) in phi.iter().enumerate() {
        out.d[j] += phi_j * weight;
        for (l, n_l) in n_primary.iter().enumerate() {
            out.m[(j, l)] += phi_j * n_l * weight;
        }
    }
}
