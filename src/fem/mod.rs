//! Finite-element interpolation: shape functions and quadrature rules on the
//! reference cells, tabulated once per element type.
//!
//! Adding a Tet10 or Hex20 means adding its shape functions in
//! [`shape`] and choosing a rule in [`quadrature`]; the kernels in
//! [`crate::assembly`] only see the tabulated [`ReferenceElement`].

pub mod quadrature;
pub mod shape;

use crate::mesh::{ElementKind, FacetKind};
use std::sync::OnceLock;

/// Shape function values and reference gradients at the quadrature points
/// of one cell type.
#[derive(Debug)]
pub struct ReferenceElement<const D: usize> {
    /// Quadrature weights (the reference-cell measure is folded in).
    pub weights: Vec<f64>,
    /// Quadrature points in reference coordinates.
    pub points: Vec<[f64; D]>,
    /// `values[q][a]` = `N_a(ξ_q)`.
    pub values: Vec<Vec<f64>>,
    /// `gradients[q][a]` = `∂N_a/∂ξ (ξ_q)`.
    pub gradients: Vec<Vec<[f64; D]>>,
}

impl<const D: usize> ReferenceElement<D> {
    fn tabulate(
        rule: (Vec<[f64; D]>, Vec<f64>),
        values: impl Fn(&[f64; D]) -> Vec<f64>,
        gradients: impl Fn(&[f64; D]) -> Vec<[f64; D]>,
    ) -> Self {
        let (points, weights) = rule;
        ReferenceElement {
            values: points.iter().map(&values).collect(),
            gradients: points.iter().map(&gradients).collect(),
            weights,
            points,
        }
    }
    /// Number of quadrature points.
    pub fn num_points(&self) -> usize {
        self.weights.len()
    }
}

/// The tabulated reference element of a volume element type, with the
/// quadrature rule that integrates its stiffness exactly for an affine map.
pub fn volume_reference(kind: ElementKind) -> &'static ReferenceElement<3> {
    static TET4: OnceLock<ReferenceElement<3>> = OnceLock::new();
    static HEX8: OnceLock<ReferenceElement<3>> = OnceLock::new();
    match kind {
        ElementKind::Tet4 => TET4.get_or_init(|| {
            ReferenceElement::tabulate(
                quadrature::tetrahedron(1),
                |x| shape::tet4_values(x).to_vec(),
                |x| shape::tet4_gradients(x).to_vec(),
            )
        }),
        ElementKind::Hex8 => HEX8.get_or_init(|| {
            ReferenceElement::tabulate(
                quadrature::hexahedron(2),
                |x| shape::hex8_values(x).to_vec(),
                |x| shape::hex8_gradients(x).to_vec(),
            )
        }),
    }
}

/// The tabulated reference facet of a boundary facet type (for surface
/// loads). Exact for the load vector of a constant pressure on a flat facet.
pub fn facet_reference(kind: FacetKind) -> &'static ReferenceElement<2> {
    static TRI3: OnceLock<ReferenceElement<2>> = OnceLock::new();
    static QUAD4: OnceLock<ReferenceElement<2>> = OnceLock::new();
    match kind {
        FacetKind::Tri3 => TRI3.get_or_init(|| {
            ReferenceElement::tabulate(
                quadrature::triangle(3),
                |x| shape::tri3_values(x).to_vec(),
                |x| shape::tri3_gradients(x).to_vec(),
            )
        }),
        FacetKind::Quad4 => QUAD4.get_or_init(|| {
            ReferenceElement::tabulate(
                quadrature::quadrilateral(2),
                |x| shape::quad4_values(x).to_vec(),
                |x| shape::quad4_gradients(x).to_vec(),
            )
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Shape functions form a partition of unity, their gradients sum to
    /// zero, and the weights sum to the reference measure.
    #[test]
    fn partition_of_unity_and_measure() {
        for (kind, measure) in [(ElementKind::Tet4, 1.0 / 6.0), (ElementKind::Hex8, 8.0)] {
            let r = volume_reference(kind);
            assert!((r.weights.iter().sum::<f64>() - measure).abs() < 1e-14);
            for q in 0..r.num_points() {
                assert!((r.values[q].iter().sum::<f64>() - 1.0).abs() < 1e-14);
                for d in 0..3 {
                    let s: f64 = r.gradients[q].iter().map(|g| g[d]).sum();
                    assert!(s.abs() < 1e-14);
                }
            }
        }
        for (kind, measure) in [(FacetKind::Tri3, 0.5), (FacetKind::Quad4, 4.0)] {
            let r = facet_reference(kind);
            assert!((r.weights.iter().sum::<f64>() - measure).abs() < 1e-14);
            for q in 0..r.num_points() {
                assert!((r.values[q].iter().sum::<f64>() - 1.0).abs() < 1e-14);
            }
        }
    }
}
