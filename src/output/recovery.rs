//! Nodal values of an element field by superconvergent patch recovery
//! (Zienkiewicz & Zhu, "The superconvergent patch recovery and a
//! posteriori error estimates", IJNME 33, 1992).
//!
//! Each node `a` has a patch: the elements that contain it. A linear
//! polynomial `p(X) = c₀ + c · (X − X_a)/ρ` is fitted by least squares to
//! the element values `σ_e` sampled at the element centroids `X_e` (the
//! mean of the element's nodes, in the reference configuration; the
//! elements' values are their volume averages, the one-point rule's
//! sampling point):
//!
//! `min Σ_e (p(X_e) − σ_e)²`, so `c = M⁻¹ Σ_e P_e σ_e`,
//! `M = Σ_e P_e P_eᵀ`, `P_e = [1, (X_e − X_a)/ρ]`,
//!
//! and the node's value is `p(X_a) = c₀`, with `ρ` the patch's largest
//! distance `|X_e − X_a|` (scaling that keeps `M` well conditioned). The
//! fit is linear in the samples, so it is stored once per mesh as weights
//! `σ_a = Σ_e w_ae σ_e` ([`PatchRecovery`]) and applied to every
//! increment's values.
//!
//! A patch whose centroids do not span 3D (too few, or coplanar: a node on
//! a face of a hexahedral mesh, a corner) is grown by one ring of elements
//! (those sharing a node with the patch) until the fit is well posed
//! (`M`'s smallest eigenvalue ≥ [`MIN_CONDITION`] of its largest and at
//! least [`MIN_SAMPLES`] samples). Boundary nodes use their own (grown)
//! patch, evaluated at the node: a one-sided extrapolation, which still
//! reproduces any linear field exactly. A mesh too small for any fit (fewer
//! than four non-coplanar centroids) falls back to the plain average of the
//! patch.
//!
//! Why SPR and not a lumped L2 projection: the projection averages the
//! element values at a node, which is first-order accurate at the boundary
//! (it is the mean of the one-sided values there) and only reproduces
//! constants; SPR reproduces linear fields at every node, boundary
//! included, and converges faster (the thick cylinder's table in
//! `examples/thick-cylinder/README.md`). Patches cross region boundaries:
//! a stress that jumps between materials is smoothed across the interface.

use crate::material::Mat3;
use crate::mesh::Mesh;
use nalgebra::{Matrix4, Vector4};
use rayon::prelude::*;

/// Least ratio of the smallest to the largest eigenvalue of a patch's
/// scaled normal matrix `M` for its fit to be used.
pub const MIN_CONDITION: f64 = 1e-3;
/// Least number of elements in a patch (more than the fit's four terms).
pub const MIN_SAMPLES: usize = 6;
/// Most rings a patch is grown by before falling back to the average.
const MAX_RINGS: usize = 3;

/// The recovery weights of a mesh: node `a`'s value is
/// `Σ_k weights[k] σ_{elements[k]}` over `k` in `offsets[a]..offsets[a+1]`.
#[derive(Clone, Debug)]
pub struct PatchRecovery {
    offsets: Vec<usize>,
    elements: Vec<usize>,
    weights: Vec<f64>,
}

impl PatchRecovery {
    /// The weights of every node of `mesh`.
    pub fn new(mesh: &Mesh) -> Self {
        Self::of_nodes(mesh, &vec![true; mesh.num_nodes()])
    }

    /// The weights of the nodes in `nodes` (a mask over the nodes of
    /// `mesh`), the same as [`Self::new`]'s for them; the other nodes have
    /// none (their recovered value is zero). A process of a distributed
    /// run makes those of its piece's nodes on the whole mesh, before it
    /// lets go of the elements its output does not read
    /// ([`Self::elements`]).
    pub fn of_nodes(mesh: &Mesh, nodes: &[bool]) -> Self {
        let node_elements = node_elements(mesh);
        let centroids: Vec<[f64; 3]> = mesh
            .elements
            .iter()
            .map(|el| {
                let mut c = [0.0; 3];
                for &n in &el.nodes {
                    for (ci, xi) in c.iter_mut().zip(mesh.nodes[n]) {
                        *ci += xi;
                    }
                }
                c.map(|x| x / el.nodes.len() as f64)
            })
            .collect();
        let mut on_boundary = vec![false; mesh.num_nodes()];
        for face in crate::mesh::boundary::boundary_faces(mesh).values() {
            for &n in &face.nodes {
                on_boundary[n] = true;
            }
        }
        let patches = Patches {
            mesh,
            node_elements: &node_elements,
            centroids: &centroids,
        };
        let per_node: Vec<Vec<(usize, f64)>> = (0..mesh.num_nodes())
            .into_par_iter()
            .map(|a| {
                if !nodes[a] {
                    return Vec::new();
                }
                let interior: Vec<usize> = if on_boundary[a] {
                    patches.interior_near(a, &on_boundary)
                } else {
                    Vec::new()
                };
                if interior.is_empty() {
                    patches.weights(a, a)
                } else {
                    patches.averaged(&interior, a)
                }
            })
            .collect();
        let mut offsets = Vec::with_capacity(per_node.len() + 1);
        offsets.push(0);
        let (mut elements, mut weights) = (Vec::new(), Vec::new());
        for node in per_node {
            for (e, w) in node {
                elements.push(e);
                weights.push(w);
            }
            offsets.push(elements.len());
        }
        PatchRecovery {
            offsets,
            elements,
            weights,
        }
    }

    /// The elements whose values the recovered nodal values read (with
    /// repeats): the patches of the nodes that have weights.
    pub fn elements(&self) -> &[usize] {
        &self.elements
    }

    /// The recovered nodal values of the element values `values` (one per
    /// element).
    pub fn recover(&self, values: &[Mat3]) -> Vec<Mat3> {
        (0..self.offsets.len() - 1)
            .into_par_iter()
            .map(|a| {
                let range = self.offsets[a]..self.offsets[a + 1];
                self.elements[range.clone()]
                    .iter()
                    .zip(&self.weights[range])
                    .fold(Mat3::zeros(), |sum, (&e, &w)| sum + values[e] * w)
            })
            .collect()
    }
}

/// The elements that contain each node.
fn node_elements(mesh: &Mesh) -> Vec<Vec<usize>> {
    let mut of = vec![Vec::new(); mesh.num_nodes()];
    for (e, el) in mesh.elements.iter().enumerate() {
        for &n in &el.nodes {
            of[n].push(e);
        }
    }
    of
}

/// A mesh's patches: the elements of each node and their centroids.
struct Patches<'a> {
    mesh: &'a Mesh,
    node_elements: &'a [Vec<usize>],
    centroids: &'a [[f64; 3]],
}

impl Patches<'_> {
    /// The nodes that share an element with `a` (`a` itself excluded).
    fn neighbours(&self, a: usize) -> impl Iterator<Item = usize> + '_ {
        let mut nodes: Vec<usize> = self.node_elements[a]
            .iter()
            .flat_map(|&e| self.mesh.elements[e].nodes.iter().copied())
            .filter(|&n| n != a)
            .collect();
        nodes.sort_unstable();
        nodes.dedup();
        nodes.into_iter()
    }

    /// The interior nodes that share an element with boundary node `a`,
    /// else those that share an element with its neighbours (a node on an
    /// edge or at a corner of the boundary).
    fn interior_near(&self, a: usize, on_boundary: &[bool]) -> Vec<usize> {
        let near: Vec<usize> = self.neighbours(a).filter(|&b| !on_boundary[b]).collect();
        if !near.is_empty() {
            return near;
        }
        let mut second: Vec<usize> = self
            .neighbours(a)
            .flat_map(|b| self.neighbours(b))
            .filter(|&c| !on_boundary[c])
            .collect();
        second.sort_unstable();
        second.dedup();
        second
    }

    /// The weights of node `a`'s value as the mean of the fits of the
    /// patches of `centres` evaluated at `a`.
    fn averaged(&self, centres: &[usize], a: usize) -> Vec<(usize, f64)> {
        let mut all: Vec<(usize, f64)> = centres
            .iter()
            .flat_map(|&b| self.weights(b, a))
            .map(|(e, w)| (e, w / centres.len() as f64))
            .collect();
        all.sort_unstable_by_key(|&(e, _)| e);
        let mut merged: Vec<(usize, f64)> = Vec::with_capacity(all.len());
        for (e, w) in all {
            match merged.last_mut() {
                Some(last) if last.0 == e => last.1 += w,
                _ => merged.push((e, w)),
            }
        }
        merged
    }

    /// The weights of the fit over node `b`'s patch, grown ring by ring
    /// until the fit is well posed, evaluated at node `a` (else the plain
    /// average of `b`'s first patch).
    fn weights(&self, b: usize, a: usize) -> Vec<(usize, f64)> {
        let mut patch = self.node_elements[b].clone();
        for _ in 0..=MAX_RINGS {
            if let Some(w) = fit_weights(
                self.mesh.nodes[b],
                self.mesh.nodes[a],
                &patch,
                self.centroids,
            ) {
                return patch.into_iter().zip(w).collect();
            }
            let mut grown: Vec<usize> = patch
                .iter()
                .flat_map(|&e| &self.mesh.elements[e].nodes)
                .flat_map(|&n| self.node_elements[n].iter().copied())
                .collect();
            grown.sort_unstable();
            grown.dedup();
            if grown.len() == patch.len() {
                break;
            }
            patch = grown;
        }
        let first = &self.node_elements[b];
        let w = 1.0 / first.len() as f64;
        first.iter().map(|&e| (e, w)).collect()
    }
}

/// The weights `w_e = P(x)ᵀ M⁻¹ P_e` of the linear least-squares fit over
/// `patch` centred at `centre`, evaluated at `x` (the centre itself, or a
/// boundary node beside it), or `None` if the fit is ill posed.
pub fn fit_weights(
    centre: [f64; 3],
    x: [f64; 3],
    patch: &[usize],
    centroids: &[[f64; 3]],
) -> Option<Vec<f64>> {
    if patch.len() < MIN_SAMPLES {
        return None;
    }
    let offset = |c: [f64; 3]| [c[0] - centre[0], c[1] - centre[1], c[2] - centre[2]];
    let rho = patch
        .iter()
        .map(|&e| {
            offset(centroids[e])
                .iter()
                .map(|d| d * d)
                .sum::<f64>()
                .sqrt()
        })
        .fold(0.0, f64::max);
    if rho <= 0.0 {
        return None;
    }
    let terms = |c: [f64; 3]| {
        let d = offset(c);
        Vector4::new(1.0, d[0] / rho, d[1] / rho, d[2] / rho)
    };
    let m: Matrix4<f64> = patch
        .iter()
        .map(|&e| terms(centroids[e]) * terms(centroids[e]).transpose())
        .sum();
    let eigenvalues = m.symmetric_eigenvalues();
    let (lo, hi) = (eigenvalues.min(), eigenvalues.max());
    if lo < MIN_CONDITION * hi {
        return None;
    }
    let at = m.try_inverse()? * terms(x);
    Some(
        patch
            .iter()
            .map(|&e| at.dot(&terms(centroids[e])))
            .collect(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::structured::{box_mesh, perturb_interior};
    use crate::mesh::ElementKind;

    /// The field `σ(X) = A + Σ_i X_i B_i` at `x`.
    fn linear_field(x: [f64; 3]) -> Mat3 {
        let a = Mat3::new(1.0, 2.0, 3.0, 2.0, -4.0, 0.5, 3.0, 0.5, 7.0);
        let b = [
            Mat3::new(0.3, 0.0, 1.0, 0.0, 2.0, 0.0, 1.0, 0.0, -1.0),
            Mat3::new(-1.0, 0.5, 0.0, 0.5, 0.0, 0.0, 0.0, 0.0, 4.0),
            Mat3::new(0.0, 0.0, 0.0, 0.0, 1.5, -2.0, 0.0, -2.0, 0.0),
        ];
        a + b[0] * x[0] + b[1] * x[1] + b[2] * x[2]
    }

    /// SPR reproduces a linear field sampled at the centroids at every
    /// node, corners and faces included (to 1e-11), on Tet4 and Hex8
    /// meshes with moved interior nodes; the weights of each node sum to 1.
    #[test]
    fn reproduces_a_linear_field_at_every_node() {
        for kind in [ElementKind::Tet4, ElementKind::Hex8] {
            let mut mesh = box_mesh(kind, [4, 3, 2], [2.0, 1.5, 1.0]);
            perturb_interior(&mut mesh, [4, 3, 2], [2.0, 1.5, 1.0], 0.2, 7);
            let samples: Vec<Mat3> = mesh
                .elements
                .iter()
                .map(|el| {
                    let mut c = [0.0; 3];
                    for &n in &el.nodes {
                        for (ci, xi) in c.iter_mut().zip(mesh.nodes[n]) {
                            *ci += xi / el.nodes.len() as f64;
                        }
                    }
                    linear_field(c)
                })
                .collect();
            let recovery = PatchRecovery::new(&mesh);
            for (a, value) in recovery.recover(&samples).iter().enumerate() {
                let exact = linear_field(mesh.nodes[a]);
                assert!(
                    (value - exact).norm() < 1e-11 * exact.norm(),
                    "{kind:?} node {a}: {value} vs {exact}"
                );
                let range = recovery.offsets[a]..recovery.offsets[a + 1];
                let sum: f64 = recovery.weights[range].iter().sum();
                assert!((sum - 1.0).abs() < 1e-12);
            }
        }
    }

    /// The weights of some nodes only (a process's piece): bit for bit
    /// the whole mesh's at those nodes and zero elsewhere, and reading
    /// only [`PatchRecovery::elements`] (every other element's value NaN,
    /// which would show in any value that read one).
    #[test]
    fn the_weights_of_some_nodes_read_only_their_patches() {
        let mut mesh = box_mesh(ElementKind::Hex8, [6, 4, 3], [3.0, 2.0, 1.5]);
        perturb_interior(&mut mesh, [6, 4, 3], [3.0, 2.0, 1.5], 0.2, 3);
        let values: Vec<Mat3> = (0..mesh.elements.len())
            .map(|e| Mat3::from_fn(|i, j| (e * 3 + i * j + 1) as f64))
            .collect();
        let whole = PatchRecovery::new(&mesh).recover(&values);
        // the nodes of the first elements: a corner of the block
        let mut piece = vec![false; mesh.num_nodes()];
        for el in &mesh.elements[..10] {
            el.nodes.iter().for_each(|&n| piece[n] = true);
        }
        let some = PatchRecovery::of_nodes(&mesh, &piece);
        let mut read = vec![false; mesh.elements.len()];
        some.elements().iter().for_each(|&e| read[e] = true);
        let count = read.iter().filter(|&&r| r).count();
        assert!(count < mesh.elements.len(), "{count}");
        let only: Vec<Mat3> = (0..values.len())
            .map(|e| {
                if read[e] {
                    values[e]
                } else {
                    Mat3::from_element(f64::NAN)
                }
            })
            .collect();
        for (a, value) in some.recover(&only).iter().enumerate() {
            match piece[a] {
                true => assert_eq!(*value, whole[a], "node {a}"),
                false => assert_eq!(*value, Mat3::zeros(), "node {a}"),
            }
        }
    }

    /// One element: no fit is possible, and each node gets the element's
    /// value.
    #[test]
    fn one_element_falls_back_to_its_value() {
        let mesh = box_mesh(ElementKind::Hex8, [1, 1, 1], [1.0, 1.0, 1.0]);
        let value = Mat3::new(1.0, 2.0, 3.0, 2.0, 5.0, 6.0, 3.0, 6.0, 9.0);
        for v in PatchRecovery::new(&mesh).recover(&[value]) {
            assert_eq!(v, value);
        }
    }
}
