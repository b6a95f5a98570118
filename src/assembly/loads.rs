//! Load kernels: pressure on boundary facets (dead or follower) and body
//! force.
//!
//! A pressure `p` (positive pushes into the body) on a facet parametrised by
//! `ξ, η` gives the nodal external forces
//!
//! ```text
//! f_a = −p ∫ N_a (x,ξ × x,η) dξ dη
//! ```
//!
//! evaluated on the reference positions for a dead load, on the current ones
//! for a follower load. For the follower load the residual `r = f_int − f_ext`
//! gets the load stiffness
//!
//! ```text
//! K_ab = −∂f_a/∂x_b = p ∫ N_a (N_b,η [x,ξ]× − N_b,ξ [x,η]×) dξ dη
//! ```
//!
//! (`[v]×` is the cross-product matrix). It is not symmetric on an open
//! surface.

use crate::fem::facet_reference;
use crate::mesh::FacetKind;
use nalgebra::{Matrix3, Vector3};

fn cross_matrix(v: &Vector3<f64>) -> Matrix3<f64> {
    Matrix3::new(0.0, -v[2], v[1], v[2], 0.0, -v[0], -v[1], v[0], 0.0)
}

/// External nodal forces (length `3n`) of a pressure `p` on a facet with
/// nodal positions `coords`, and, if `with_tangent`, the load stiffness
/// `−∂f/∂x` (`3n × 3n`, row-major).
pub fn pressure_facet(
    kind: FacetKind,
    coords: &[[f64; 3]],
    p: f64,
    with_tangent: bool,
) -> (Vec<f64>, Vec<f64>) {
    let r = facet_reference(kind);
    let n = coords.len();
    let mut force = vec![0.0; 3 * n];
    let mut k = if with_tangent {
        vec![0.0; 9 * n * n]
    } else {
        Vec::new()
    };
    for q in 0..r.num_points() {
        let mut a1 = Vector3::zeros();
        let mut a2 = Vector3::zeros();
        for (x, g) in coords.iter().zip(&r.gradients[q]) {
            a1 += Vector3::from(*x) * g[0];
            a2 += Vector3::from(*x) * g[1];
        }
        let normal_area = a1.cross(&a2);
        let w = r.weights[q];
        for a in 0..n {
            let fa = -p * r.values[q][a] * w * normal_area;
            for i in 0..3 {
                force[3 * a + i] += fa[i];
            }
        }
        if with_tangent {
            let (c1, c2) = (cross_matrix(&a1), cross_matrix(&a2));
            for a in 0..n {
                for b in 0..n {
                    let g = r.gradients[q][b];
                    let kab = (c1 * g[1] - c2 * g[0]) * (p * r.values[q][a] * w);
                    for i in 0..3 {
                        for j in 0..3 {
                            k[(3 * a + i) * 3 * n + 3 * b + j] += kab[(i, j)];
                        }
                    }
                }
            }
        }
    }
    (force, k)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit pressure on a flat facet gives total force −p A n, shared
    /// equally between the nodes of a square.
    #[test]
    fn uniform_pressure_on_flat_facets() {
        let quad = [
            [0.0, 0.0, 1.0],
            [2.0, 0.0, 1.0],
            [2.0, 2.0, 1.0],
            [0.0, 2.0, 1.0],
        ];
        let (f, _) = pressure_facet(FacetKind::Quad4, &quad, 3.0, false);
        for a in 0..4 {
            assert!((f[3 * a + 2] + 3.0).abs() < 1e-13);
            assert!(f[3 * a].abs() < 1e-14 && f[3 * a + 1].abs() < 1e-14);
        }
        let tri = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        let (f, _) = pressure_facet(FacetKind::Tri3, &tri, 6.0, false);
        for a in 0..3 {
            assert!((f[3 * a + 2] + 1.0).abs() < 1e-13);
        }
    }

    /// The follower load stiffness is −∂f/∂x by central differences.
    #[test]
    fn follower_tangent_matches_finite_difference() {
        for (kind, coords) in [
            (
                FacetKind::Quad4,
                vec![
                    [0.1, 0.0, 1.0],
                    [2.0, 0.3, 1.2],
                    [2.2, 2.0, 0.8],
                    [0.0, 1.9, 1.0],
                ],
            ),
            (
                FacetKind::Tri3,
                vec![[0.0, 0.1, 0.2], [1.1, 0.0, 0.3], [0.2, 0.9, -0.1]],
            ),
        ] {
            let n = coords.len();
            let (_, k) = pressure_facet(kind, &coords, 2.5, true);
            let h = 1e-6;
            for b in 0..n {
                for j in 0..3 {
                    let (mut cp, mut cm) = (coords.clone(), coords.clone());
                    cp[b][j] += h;
                    cm[b][j] -= h;
                    let (fp, _) = pressure_facet(kind, &cp, 2.5, false);
                    let (fm, _) = pressure_facet(kind, &cm, 2.5, false);
                    for r in 0..3 * n {
                        let fd = -(fp[r] - fm[r]) / (2.0 * h);
                        assert!(
                            (fd - k[r * 3 * n + 3 * b + j]).abs() < 1e-7,
                            "{kind:?} {r} {b} {j}"
                        );
                    }
                }
            }
        }
    }
}
