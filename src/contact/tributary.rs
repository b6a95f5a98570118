//! Tributary reference areas of the secondary nodes (formulation.md §2).
//!
//! Each node of a secondary surface set gets a third of the reference area
//! of every adjacent linear triangle and a quarter of every adjacent
//! bilinear quadrangle:
//!
//! ```text
//! A_s = Σ_{Tri3 ∋ s} A_e/3 + Σ_{Quad4 ∋ s} A_e/4,    A_e = ∫ |X,ξ × X,η| dξ dη
//! ```
//!
//! (the facet area by the same quadrature as the pressure loads: exact for
//! flat facets). The `A_s` sum to the surface's area, and a nodal contact
//! force `A_s t_N n` then carries the pressure `t_N`.
//!
//! A uniform pressure `p` on a flat facet has consistent nodal loads
//! `p ∫ N_a dA`. For a triangle that is exactly `p A_e/3`; for a quadrangle
//! it is `p A_e/4` when the quadrangle is a parallelogram, and only
//! approximately otherwise (a trapezoid loads its longer side more). So the
//! weights transmit a uniform pressure exactly on triangles and on
//! parallelogram quadrangles; on distorted quadrangles they keep the total
//! force exact but shift it slightly between nodes.

use crate::fem::facet_reference;
use crate::mesh::{Mesh, SurfaceSet};
use nalgebra::Vector3;

/// Reference area `∫ |X,ξ × X,η| dξ dη` of a facet with nodal positions
/// `coords` (Tri3 or Quad4, from `kind`).
pub fn facet_area(kind: crate::mesh::FacetKind, coords: &[[f64; 3]]) -> f64 {
    let r = facet_reference(kind);
    (0..r.num_points())
        .map(|q| {
            let mut a1 = Vector3::zeros();
            let mut a2 = Vector3::zeros();
            for (x, g) in coords.iter().zip(&r.gradients[q]) {
                a1 += Vector3::from(*x) * g[0];
                a2 += Vector3::from(*x) * g[1];
            }
            r.weights[q] * a1.cross(&a2).norm()
        })
        .sum()
}

/// The nodes of `surface` (sorted mesh node indices) and their tributary
/// reference areas `A_s` (same order), from the reference coordinates of
/// `mesh`. See the module documentation.
pub fn tributary_areas(mesh: &Mesh, surface: &SurfaceSet) -> (Vec<usize>, Vec<f64>) {
    let nodes = mesh.surface_nodes(surface);
    let mut areas = vec![0.0; nodes.len()];
    for facet in &surface.facets {
        let coords: Vec<[f64; 3]> = facet.nodes.iter().map(|&n| mesh.nodes[n]).collect();
        let share = facet_area(facet.kind, &coords) / facet.nodes.len() as f64;
        for n in &facet.nodes {
            // `nodes` is sorted and holds every facet node
            if let Ok(i) = nodes.binary_search(n) {
                areas[i] += share;
            }
        }
    }
    (nodes, areas)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::FacetKind;

    #[test]
    fn facet_areas() {
        let tri = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 3.0, 0.0]];
        assert!((facet_area(FacetKind::Tri3, &tri) - 3.0).abs() < 1e-14);
        let trapezoid = [
            [0.0, 0.0, 1.0],
            [4.0, 0.0, 1.0],
            [3.0, 2.0, 1.0],
            [1.0, 2.0, 1.0],
        ];
        assert!((facet_area(FacetKind::Quad4, &trapezoid) - 6.0).abs() < 1e-14);
    }
}
