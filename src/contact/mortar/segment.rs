//! Segmentation and integration of one secondary–primary face pair (Puso &
//! Laursen 2004; Popp, Gitterle, Gee & Wall 2010, §4):
//!
//! 1. both faces' corners are projected along `n₀` onto the secondary
//!    face's [`AuxiliaryPlane`];
//! 2. the primary polygon is clipped by the secondary one
//!    (Sutherland–Hodgman, [`clipping`]);
//! 3. the clip polygon is split into triangles about its centroid;
//! 4. each triangle carries a collapsed Gauss rule whose points go back
//!    along `n₀` to both faces ([`Projector`]), and
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
use super::clipping::{self, ClipTrace, Polygon};
use super::dual_basis::DualBasis;
use super::face::{FaceShape, FaceValues, MortarFace};
use super::projection::{FacePoint, ProjectionJacobian, Projector};
use super::MortarError;
use crate::fem::quadrature;

/// Points per direction of the cells' collapsed rule: 4, exact for total
/// degree 6 (the product `Φ_j N_l` of two Quad8 functions on flat
/// rectangular faces).
const CELL_RULE_POINTS: usize = 4;

/// Points per direction of the cells' collapsed rule between two Tri3
/// faces: 2, exact for total degree 2. Both faces are flat, so a point of
/// the plane reaches each along `n₀` by an affine map, `J_q` is constant
/// on a cell and `Φ_j N_l` is of degree 2 in the plane's coordinates: the
/// integrals are those of the 4-point rule to round-off, with a quarter of
/// the projections (which were half of a condensed mortar run's samples).
const LINEAR_CELL_RULE_POINTS: usize = 2;

/// The cells' rule for a face pair: [`LINEAR_CELL_RULE_POINTS`] between
/// two Tri3 faces, else [`CELL_RULE_POINTS`]; each computed once.
fn cell_rule(secondary: FaceShape, primary: FaceShape) -> (Vec<[f64; 2]>, Vec<f64>) {
    type Rule = (Vec<[f64; 2]>, Vec<f64>);
    static LINEAR: std::sync::OnceLock<Rule> = std::sync::OnceLock::new();
    static GENERAL: std::sync::OnceLock<Rule> = std::sync::OnceLock::new();
    if secondary == FaceShape::Tri3 && primary == FaceShape::Tri3 {
        (LINEAR.get_or_init(|| quadrature::triangle_collapsed(LINEAR_CELL_RULE_POINTS))).clone()
    } else {
        (GENERAL.get_or_init(|| quadrature::triangle_collapsed(CELL_RULE_POINTS))).clone()
    }
}

/// The overlap of a face pair in the secondary face's auxiliary plane.
#[derive(Clone, Debug, PartialEq)]
pub struct Overlap {
    pub plane: AuxiliaryPlane,
    /// The clip polygon (counter-clockwise about `n₀`); empty if none.
    pub polygon: Polygon,
    /// The projected secondary corners, counter-clockwise (the clip polygon
    /// of the clipping), and the corner index of each.
    pub secondary_polygon: Polygon,
    pub secondary_corners: Vec<usize>,
    /// The corner index of each projected primary corner, in the
    /// counter-clockwise order the clipping took them (its subject).
    pub primary_corners: Vec<usize>,
    /// The clipping with the origin of every vertex.
    pub trace: ClipTrace,
}

impl Overlap {
    /// The overlap's area in the auxiliary plane.
    pub fn area(&self) -> f64 {
        clipping::signed_area(&self.polygon)
    }
}

/// A face's corners projected onto the plane, counter-clockwise, with the
/// corner index of each.
fn projected_corners(plane: &AuxiliaryPlane, face: &MortarFace) -> (Polygon, Vec<usize>) {
    let points: Polygon = face
        .corners()
        .iter()
        .map(|x| plane.local_point(x))
        .collect();
    let order = clipping::counter_clockwise_order(&points);
    (order.iter().map(|&i| points[i]).collect(), order)
}

/// Projects both faces' corners onto the secondary face's auxiliary plane
/// and clips the primary polygon by the secondary one.
pub fn overlap(secondary: &MortarFace, primary: &MortarFace) -> Overlap {
    let plane = AuxiliaryPlane::of_face(secondary);
    let (secondary_polygon, secondary_corners) = projected_corners(&plane, secondary);
    let (primary_polygon, primary_corners) = projected_corners(&plane, primary);
    let trace = clipping::clip_convex_traced(&primary_polygon, &secondary_polygon);
    Overlap {
        plane,
        polygon: trace.polygon_points(),
        secondary_polygon,
        secondary_corners,
        primary_corners,
        trace,
    }
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

/// An integration point of a pair's cells: cell `cell` (the triangle
/// `(c, p_cell, p_cell+1)`), its rule point `eta` and weight `w_q`, its
/// plane coordinates, its projections onto both faces along `n₀`, the
/// cell's `2 A_cell` and `J_q` (see the module doc).
#[derive(Clone, Debug, PartialEq)]
pub struct CellPoint {
    pub cell: usize,
    pub eta: [f64; 2],
    pub weight: f64,
    pub plane_point: [f64; 2],
    pub secondary: FacePoint,
    pub primary: FacePoint,
    pub cell_jacobian: f64,
    pub jacobian: f64,
}

/// The integration points of an overlap's cells, projected onto both faces.
pub fn cell_points(
    overlap: &Overlap,
    secondary: &MortarFace,
    primary: &MortarFace,
) -> Result<Vec<CellPoint>, MortarError> {
    let (points, weights) = cell_rule(secondary.shape, primary.shape);
    let n0 = overlap.plane.normal;
    let (mut onto_secondary, mut onto_primary) =
        (Projector::new(secondary, &n0), Projector::new(primary, &n0));
    let mut out = Vec::new();
    for (cell, triangle) in clipping::centroid_triangles(&overlap.polygon)
        .iter()
        .enumerate()
    {
        let cell_jacobian = 2.0 * clipping::signed_area(triangle);
        for (eta, w) in points.iter().zip(&weights) {
            let p = cell_point(triangle, *eta);
            let x = overlap.plane.spatial_point(p);
            let hit_s = onto_secondary.project(&x)?;
            let a_s = secondary.area_normal(hit_s.xi);
            out.push(CellPoint {
                cell,
                eta: *eta,
                weight: *w,
                plane_point: p,
                secondary: hit_s,
                primary: onto_primary.project(&x)?,
                cell_jacobian,
                jacobian: cell_jacobian * a_s.norm() / n0.dot(&a_s).abs(),
            });
        }
    }
    Ok(out)
}

/// The projections' Jacobians of a cell point on both faces along `n₀`,
/// for its derivatives ([`FacePoint::jacobian`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointJacobians {
    pub secondary: ProjectionJacobian,
    pub primary: ProjectionJacobian,
}

/// The [`PointJacobians`] of an overlap's integration points `points`
/// ([`cell_points`]), formed once for all the derivative directions of a
/// pair; an integration without derivatives forms none.
pub fn point_jacobians(
    overlap: &Overlap,
    points: &[CellPoint],
    secondary: &MortarFace,
    primary: &MortarFace,
) -> Result<Vec<PointJacobians>, MortarError> {
    let n0 = overlap.plane.normal;
    points
        .iter()
        .map(|q| {
            Ok(PointJacobians {
                secondary: q.secondary.jacobian(secondary, &n0)?,
                primary: q.primary.jacobian(primary, &n0)?,
            })
        })
        .collect()
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
    let points = cell_points(&overlap, secondary, primary)?;
    Ok(Some(integrate_points(&points, secondary, dual, primary)))
}

/// `D_j` and `M_jl` summed over a pair's integration points.
pub fn integrate_points(
    points: &[CellPoint],
    secondary: &MortarFace,
    dual: &DualBasis,
    primary: &MortarFace,
) -> SegmentIntegrals {
    let (ns, nm) = (secondary.shape.node_count(), primary.shape.node_count());
    let mut out = SegmentIntegrals {
        d: vec![0.0; ns],
        m: DMatrix::zeros(ns, nm),
        area: 0.0,
    };
    for q in points {
        add_point(
            &mut out,
            dual.values(q.secondary.xi),
            primary.shape.values(q.primary.xi),
            q.weight * q.jacobian,
        );
    }
    out
}

/// The point `c₀ + η₁ (c₁ − c₀) + η₂ (c₂ − c₀)` of a cell (linear in the
/// corners, so it maps the corners' derivatives to the point's).
pub fn cell_point(cell: &clipping::Triangle, eta: [f64; 2]) -> [f64; 2] {
    let [c0, c1, c2] = *cell;
    [0, 1].map(|d| c0[d] + eta[0] * (c1[d] - c0[d]) + eta[1] * (c2[d] - c0[d]))
}

/// Adds one integration point's `Φ_j w J` to `D_j` and `Φ_j N_l w J` to `M_jl`.
fn add_point(out: &mut SegmentIntegrals, phi: Vec<f64>, n_primary: FaceValues<f64>, weight: f64) {
    out.area += weight;
    for (j, phi_j) in phi.iter().enumerate() {
        out.d[j] += phi_j * weight;
        for (l, n_l) in n_primary.iter().enumerate() {
            out.m[(j, l)] += phi_j * n_l * weight;
        }
    }
}
