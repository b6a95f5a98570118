//! The directional derivatives of one face pair's segmentation and
//! integrals for increments `δx_s` of the secondary face's nodes and `δx_m`
//! of the primary face's (Popp, Gitterle, Gee & Wall, IJNME 83, 2010, §5),
//! chained through the kernels of [`super::segment`]:
//!
//! 1. the auxiliary plane `(δx₀, δn₀, δe_i)` ([`AuxiliaryPlane::derivative`]);
//! 2. the projected corners `δp = (δx − δx₀)·e_i + (x − x₀)·δe_i`;
//! 3. the clip polygon's vertices along the clipping's trace
//!    ([`super::clip_derivatives`]), hence the centroid and the cells;
//! 4. each Gauss point: `δp_q = Σ_c η_c δc_c` in the plane, its spatial
//!    point `δx_q = δx₀ + Σ_i (δp_i e_i + p_i δe_i)`, and its parameter
//!    coordinates `δξ_s`, `δξ_m` on both faces by the implicit function
//!    theorem on `x(ξ) − x_q − α n₀ = 0` ([`projection_derivative`]);
//! 5. the cell Jacobian `J = 2A_c r`, `r = |a_s| / |n₀·a_s|`:
//!    `δ(2A_c) = δ[(c₁ − c₀) × (c₂ − c₀)]`,
//!    `δr = r (a_s·δa_s / |a_s|² − (δn₀·a_s + n₀·δa_s) / (n₀·a_s))`,
//!    `δa_s = δa_s|_ξ + Σ_k ∂a_s/∂ξ_k δξ_s,k`;
//! 6. the dual basis `δΦ_j = Σ_k (δa_jk Ñ_k + a_jk ∇Ñ_k·δξ_s)` ([`DualBasis::derivative`])
//!    and the primary functions `δN_l = ∇N_l·δξ_m`;
//! 7. `δD_j = Σ_q w_q (δΦ_j J + Φ_j δJ)`,
//!    `δM_jl = Σ_q w_q ((δΦ_j N_l + Φ_j δN_l) J + Φ_j N_l δJ)`.

use nalgebra::{DMatrix, Vector3};

use super::auxiliary_plane::{AuxiliaryPlane, PlaneDerivative};
use super::clip_derivatives::cross_derivative;
use super::clipping;
use super::dual_basis::DualBasis;
use super::face::MortarFace;
use super::projection::projection_derivative;
use super::quadratic;
use super::segment::{cell_point, CellPoint, Overlap, PointJacobians};
use super::MortarError;

/// The derivative of an [`Overlap`]: its plane's, and its clip polygon's
/// vertices' in polygon order.
#[derive(Clone, Debug, PartialEq)]
pub struct OverlapDerivative {
    pub plane: PlaneDerivative,
    pub polygon: Vec<[f64; 2]>,
}

impl Overlap {
    /// Steps 1–3 of the module doc for node increments `dxs`, `dxm`.
    pub fn derivative(
        &self,
        secondary: &MortarFace,
        primary: &MortarFace,
        dxs: &[Vector3<f64>],
        dxm: &[Vector3<f64>],
    ) -> OverlapDerivative {
        let plane = self.plane.derivative(secondary, dxs);
        let corners = |face: &MortarFace, order: &[usize], dx: &[Vector3<f64>]| -> Vec<[f64; 2]> {
            order
                .iter()
                .map(|&c| {
                    self.plane
                        .local_point_derivative(&plane, &face.coordinates[c], &dx[c])
                })
                .collect()
        };
        let d_clip = corners(secondary, &self.secondary_corners, dxs);
        let d_subject = corners(primary, &self.primary_corners, dxm);
        let polygon = self
            .trace
            .polygon_derivatives(&d_subject, &self.secondary_polygon, &d_clip);
        OverlapDerivative { plane, polygon }
    }
}

/// The derivative of a [`CellPoint`]: its plane coordinates, its parameter
/// coordinates on both faces and its Jacobian `J_q`.
#[derive(Clone, Debug, PartialEq)]
pub struct CellPointDerivative {
    pub plane_point: [f64; 2],
    pub secondary_xi: [f64; 2],
    pub primary_xi: [f64; 2],
    pub jacobian: f64,
}

/// Steps 4–5 of the module doc for every integration point, `jacobians`
/// their projections' ([`super::segment::point_jacobians`]).
pub fn cell_point_derivatives(
    overlap: &Overlap,
    d_overlap: &OverlapDerivative,
    (points, jacobians): (&[CellPoint], &[PointJacobians]),
    (secondary, primary): (&MortarFace, &MortarFace),
    (dxs, dxm): (&[Vector3<f64>], &[Vector3<f64>]),
) -> Result<Vec<CellPointDerivative>, MortarError> {
    let cells = clipping::centroid_triangles(&overlap.polygon);
    let d_cells = clipping::centroid_triangles(&d_overlap.polygon);
    let (plane, d_plane) = (&overlap.plane, &d_overlap.plane);
    if jacobians.len() != points.len() {
        return Err(MortarError::Projection {
            what: format!(
                "the derivatives were given {} projection Jacobians for {} integration points",
                jacobians.len(),
                points.len()
            ),
        });
    }
    points
        .iter()
        .zip(jacobians)
        .map(|(q, a)| {
            let dp = cell_point(&d_cells[q.cell], q.eta);
            let dx = plane.spatial_point_derivative(d_plane, q.plane_point, dp);
            let dn0 = &d_plane.normal;
            let (dxi_s, _) =
                projection_derivative(secondary, &q.secondary, &a.secondary, dxs, &dx, dn0);
            let (dxi_m, _) = projection_derivative(primary, &q.primary, &a.primary, dxm, &dx, dn0);
            let d_cell = cross_derivative(cells[q.cell], d_cells[q.cell]);
            Ok(CellPointDerivative {
                plane_point: dp,
                secondary_xi: dxi_s,
                primary_xi: dxi_m,
                jacobian: jacobian_derivative(secondary, plane, d_plane, q, dxs, dxi_s, d_cell),
            })
        })
        .collect()
}

/// `δJ = δ(2A_c) r + 2A_c δr` (step 5 of the module doc).
fn jacobian_derivative(
    secondary: &MortarFace,
    plane: &AuxiliaryPlane,
    d_plane: &PlaneDerivative,
    q: &CellPoint,
    dxs: &[Vector3<f64>],
    dxi_s: [f64; 2],
    d_cell_jacobian: f64,
) -> f64 {
    let xi = q.secondary.xi;
    let a = secondary.area_normal(xi);
    let [a1, a2] = secondary.area_normal_gradient(xi);
    let da = secondary.area_normal_derivative(xi, dxs) + a1 * dxi_s[0] + a2 * dxi_s[1];
    let c = plane.normal.dot(&a);
    let r = a.norm() / c.abs();
    let dr =
        r * (a.dot(&da) / a.norm_squared() - (d_plane.normal.dot(&a) + plane.normal.dot(&da)) / c);
    d_cell_jacobian * r + q.cell_jacobian * dr
}

/// `(δD_j, δM_jl)` of a pair (step 6–7 of the module doc) from its overlap
/// and integration points (with their projections' Jacobians).
pub fn integrals_derivative(
    overlap: &Overlap,
    (points, jacobians): (&[CellPoint], &[PointJacobians]),
    (secondary, dual, primary): (&MortarFace, &DualBasis, &MortarFace),
    (dxs, dxm): (&[Vector3<f64>], &[Vector3<f64>]),
) -> Result<(Vec<f64>, DMatrix<f64>), MortarError> {
    let d_overlap = overlap.derivative(secondary, primary, dxs, dxm);
    let faces = (secondary, primary);
    let linearised = (points, jacobians);
    let dq = cell_point_derivatives(overlap, &d_overlap, linearised, faces, (dxs, dxm))?;
    let d_coefficients = dual.derivative(secondary, dxs)?;
    let (ns, nm) = (secondary.shape.node_count(), primary.shape.node_count());
    let (mut dd, mut dm) = (vec![0.0; ns], DMatrix::zeros(ns, nm));
    for (q, dq) in points.iter().zip(&dq) {
        let (phi, dphi) =
            dual_values_derivative(dual, &d_coefficients, q.secondary.xi, dq.secondary_xi);
        let n = primary.shape.values(q.primary.xi);
        let dn: Vec<f64> = primary
            .shape
            .gradients(q.primary.xi)
            .iter()
            .map(|g| g[0] * dq.primary_xi[0] + g[1] * dq.primary_xi[1])
            .collect();
        let (wj, dwj) = (q.weight * q.jacobian, q.weight * dq.jacobian);
        for j in 0..ns {
            dd[j] += dphi[j] * wj + phi[j] * dwj;
            for l in 0..nm {
                dm[(j, l)] += (dphi[j] * n[l] + phi[j] * dn[l]) * wj + phi[j] * n[l] * dwj;
            }
        }
    }
    Ok((dd, dm))
}

/// `Φ_j(ξ)` and `δΦ_j = Σ_k (δa_jk Ñ_k + a_jk ∇Ñ_k·δξ)`.
fn dual_values_derivative(
    dual: &DualBasis,
    d_coefficients: &DMatrix<f64>,
    xi: [f64; 2],
    dxi: [f64; 2],
) -> (Vec<f64>, Vec<f64>) {
    let nt = quadratic::mortar_values(dual.shape, xi);
    let dnt: Vec<f64> = quadratic::mortar_gradients(dual.shape, xi)
        .iter()
        .map(|g| g[0] * dxi[0] + g[1] * dxi[1])
        .collect();
    let n = nt.len();
    let dphi = (0..n)
        .map(|j| {
            (0..n)
                .map(|k| d_coefficients[(j, k)] * nt[k] + dual.coefficients[(j, k)] * dnt[k])
                .sum()
        })
        .collect();
    (dual.values_from(&nt), dphi)
}
