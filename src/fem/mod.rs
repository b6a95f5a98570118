//! Finite-element interpolation: shape functions and quadrature rules on the
//! reference cells, tabulated once per element type.
//!
//! Each element kind has its shape functions in [`shape`] and a rule in
//! [`quadrature`]; the kernels in [`crate::assembly`] only see the
//! tabulated [`ReferenceElement`].

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
/// quadrature rule that integrates its stiffness exactly for an affine map:
/// Tet4 1 point, Tet10 4 points (degree 2), Hex8 and Hex20R 2×2×2, Hex20
/// 3×3×3, Wedge6 3×2 (triangle × line), Wedge15 6×3 (degree 4 × 5).
pub fn volume_reference(kind: ElementKind) -> &'static ReferenceElement<3> {
    static TABLES: [OnceLock<ReferenceElement<3>>; 7] = [const { OnceLock::new() }; 7];
    let slot = match kind {
        ElementKind::Tet4 => 0,
        ElementKind::Hex8 => 1,
        ElementKind::Tet10 => 2,
        ElementKind::Hex20 => 3,
        ElementKind::Hex20R => 4,
        ElementKind::Wedge6 => 5,
        ElementKind::Wedge15 => 6,
    };
    TABLES[slot].get_or_init(|| match kind {
        ElementKind::Tet4 => ReferenceElement::tabulate(
            quadrature::tetrahedron(1),
            |x| shape::tet4_values(x).to_vec(),
            |x| shape::tet4_gradients(x).to_vec(),
        ),
        ElementKind::Hex8 => ReferenceElement::tabulate(
            quadrature::hexahedron(2),
            |x| shape::hex8_values(x).to_vec(),
            |x| shape::hex8_gradients(x).to_vec(),
        ),
        ElementKind::Tet10 => ReferenceElement::tabulate(
            quadrature::tetrahedron(4),
            shape::tet10_values,
            shape::tet10_gradients,
        ),
        ElementKind::Hex20 | ElementKind::Hex20R => ReferenceElement::tabulate(
            quadrature::hexahedron(if kind == ElementKind::Hex20 { 3 } else { 2 }),
            shape::hex20_values,
            shape::hex20_gradients,
        ),
        ElementKind::Wedge6 => ReferenceElement::tabulate(
            quadrature::wedge(3, 2),
            shape::wedge6_values,
            shape::wedge6_gradients,
        ),
        ElementKind::Wedge15 => ReferenceElement::tabulate(
            quadrature::wedge(6, 3),
            shape::wedge15_values,
            shape::wedge15_gradients,
        ),
    })
}

/// The tabulated reference facet of a boundary facet type (for surface
/// loads). Exact for the load vector of a constant pressure on a flat
/// facet, and on a curved Tri6 (degree 4).
pub fn facet_reference(kind: FacetKind) -> &'static ReferenceElement<2> {
    static TABLES: [OnceLock<ReferenceElement<2>>; 4] = [const { OnceLock::new() }; 4];
    let slot = match kind {
        FacetKind::Tri3 => 0,
        FacetKind::Quad4 => 1,
        FacetKind::Tri6 => 2,
        FacetKind::Quad8 => 3,
    };
    TABLES[slot].get_or_init(|| match kind {
        FacetKind::Tri3 => ReferenceElement::tabulate(
            quadrature::triangle(3),
            |x| shape::tri3_values(x).to_vec(),
            |x| shape::tri3_gradients(x).to_vec(),
        ),
        FacetKind::Quad4 => ReferenceElement::tabulate(
            quadrature::quadrilateral(2),
            |x| shape::quad4_values(x).to_vec(),
            |x| shape::quad4_gradients(x).to_vec(),
        ),
        FacetKind::Tri6 => ReferenceElement::tabulate(
            quadrature::triangle(6),
            |x| shape::tri6_values(x).to_vec(),
            |x| shape::tri6_gradients(x).to_vec(),
        ),
        FacetKind::Quad8 => ReferenceElement::tabulate(
            quadrature::quadrilateral(3),
            |x| shape::quad8_values(x).to_vec(),
            |x| shape::quad8_gradients(x).to_vec(),
        ),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Shape functions form a partition of unity, their gradients sum to
    /// zero, and the weights sum to the reference measure.
    #[test]
    fn partition_of_unity_and_measure() {
        let volumes = [
            (ElementKind::Tet4, 1.0 / 6.0),
            (ElementKind::Hex8, 8.0),
            (ElementKind::Tet10, 1.0 / 6.0),
            (ElementKind::Hex20, 8.0),
            (ElementKind::Hex20R, 8.0),
            (ElementKind::Wedge6, 1.0),
            (ElementKind::Wedge15, 1.0),
        ];
        for (kind, measure) in volumes {
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
        let facets = [
            (FacetKind::Tri3, 0.5),
            (FacetKind::Quad4, 4.0),
            (FacetKind::Tri6, 0.5),
            (FacetKind::Quad8, 4.0),
        ];
        for (kind, measure) in facets {
            let r = facet_reference(kind);
            assert!((r.weights.iter().sum::<f64>() - measure).abs() < 1e-14);
            for q in 0..r.num_points() {
                assert!((r.values[q].iter().sum::<f64>() - 1.0).abs() < 1e-14);
            }
        }
    }
}
