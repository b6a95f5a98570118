//! The gradients of one face pair's `D_j` and `M_jl` with respect to all
//! of its nodes' coordinates (Popp, Gitterle, Gee & Wall 2010, §5): the
//! directional derivatives of [`super::segment_derivatives`] along each
//! unit increment `δx_a = e_i` of the pair's nodes.
//!
//! Columns are node-major over the pair's nodes, secondary face first:
//! column `3a + i` is coordinate `i` of the secondary node `a`, and
//! column `3(n_s + b) + i` that of the primary node `b`.

use nalgebra::{DMatrix, Vector3};

use super::dual_basis::DualBasis;
use super::face::MortarFace;
use super::segment::{cell_points, integrate_points, overlap, point_jacobians, SegmentIntegrals};
use super::segment_derivatives::integrals_derivative;
use super::MortarError;

/// A pair's integrals and their gradients.
#[derive(Clone, Debug, PartialEq)]
pub struct PairLinearisation {
    pub integrals: SegmentIntegrals,
    /// `∂D_j/∂x`: row `j`, columns as in the module doc.
    pub d_gradient: DMatrix<f64>,
    /// `∂M_jl/∂x`: row `j n_m + l`, columns as in the module doc.
    pub m_gradient: DMatrix<f64>,
}

/// Segments, integrates and differentiates a pair; `None` when the
/// projected faces do not overlap.
pub fn linearise_pair(
    secondary: &MortarFace,
    dual: &DualBasis,
    primary: &MortarFace,
) -> Result<Option<PairLinearisation>, MortarError> {
    let overlap = overlap(secondary, primary);
    if overlap.polygon.is_empty() {
        return Ok(None);
    }
    let points = cell_points(&overlap, secondary, primary)?;
    let jacobians = point_jacobians(&overlap, &points, secondary, primary)?;
    let (ns, nm) = (secondary.shape.node_count(), primary.shape.node_count());
    let columns = 3 * (ns + nm);
    let mut out = PairLinearisation {
        integrals: integrate_points(&points, secondary, dual, primary),
        d_gradient: DMatrix::zeros(ns, columns),
        m_gradient: DMatrix::zeros(ns * nm, columns),
    };
    let faces = (secondary, dual, primary);
    for column in 0..columns {
        let mut dx = vec![Vector3::zeros(); ns + nm];
        dx[column / 3][column % 3] = 1.0;
        let (dxs, dxm) = dx.split_at(ns);
        let (dd, dm) = integrals_derivative(&overlap, (&points, &jacobians), faces, (dxs, dxm))?;
        for j in 0..ns {
            out.d_gradient[(j, column)] = dd[j];
            for l in 0..nm {
                out.m_gradient[(j * nm + l, column)] = dm[(j, l)];
            }
        }
    }
    Ok(Some(out))
}
