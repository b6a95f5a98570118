//! The frame-indifferent weighted slip increment of a secondary node
//! (Gitterle, Popp, Gee & Wall, IJNME 84, 2010, §3.2; Popp's thesis, TU
//! München 2012, §5.1): the change of the mortar matrices `D`, `M` since
//! the last converged increment `n`, applied to the current positions,
//! ```text
//! w_j = Σ_l (M_jl − M_jl,n) x_l − (D_j − D_j,n) x̃_j,     x̃_j = Σ_k R_jk x_k,
//! ```
//! the sum over every primary node `l` of either state (`M_jl = 0` where a
//! node does not couple). It is the weighted relative tangential motion
//! of the secondary node's support over the primary surface, measured in
//! the primary surface's material frame: `D`, `M` are integrals of shape
//! functions over the current surfaces, unchanged by a rigid motion of
//! both bodies, so `w_j = 0` under any rigid rotation (and, where
//! `Σ_l M_jl = D_j Σ_k R_jk` in both states, any translation); the
//! non-objective form `D_j Δx̃_j − Σ_l M_jl Δx_l` is not. On flat parallel
//! faces with the secondary node's support covered, `w_j = D_j s` for a
//! tangential slide `s` of the secondary body over the primary, so
//! `d_j = w_j / D_j` is the node's slip (the driver's offset
//! [`SlipKinematics::offset`](crate::contact::friction::SlipKinematics::offset)).
//!
//! Derivative, with `∇D_j`, `∇M_jl` of [`MortarRow`] (the segmentation,
//! the dual basis and the projections included) and the committed
//! `D_j,n`, `M_jl,n` fixed:
//! ```text
//! ∂w_j/∂x = Σ_l x_l ⊗ ∇M_jl − x̃_j ⊗ ∇D_j
//!         + (M_jl − M_jl,n) I  on l,     − (D_j − D_j,n) R_jk I  on k,
//! ∂d_j/∂x = (∂w_j/∂x − d_j ⊗ ∇D_j) / D_j.
//! ```

use nalgebra::{DMatrix, Vector3};

use super::rows::MortarRow;
use super::weighted_gap::MortarCoupling;

/// The weighted slip `w_j` of one secondary node and `∂w_j/∂x`.
#[derive(Clone, Debug, PartialEq)]
pub struct WeightedSlip {
    /// The gradient's nodes: the row's [`MortarRow::nodes`], then the
    /// committed primary nodes that no longer couple.
    pub nodes: Vec<usize>,
    /// `w_j`.
    pub value: Vector3<f64>,
    /// `∂w_j/∂x` (3 × 3·nodes, node-major over `nodes`).
    pub gradient: DMatrix<f64>,
}

/// Node `j`'s committed coupling: `D_j,n` and `(l, M_jl,n)`, from the
/// coupling integrated at the last converged increment (`None` where no
/// segment reached the node then).
pub fn committed_row(coupling: &MortarCoupling, j: usize) -> Option<(f64, Vec<(usize, f64)>)> {
    let d = *coupling.d.get(&j)?;
    let m = coupling
        .m
        .range((j, 0)..(j + 1, 0))
        .map(|(&(_, l), &v)| (l, v))
        .collect();
    Some((d, m))
}

/// `w_j` and `∂w_j/∂x` (see the module docs) of the current `row` against
/// the committed `(D_j,n, M_jl,n)`, with the nodes' current positions
/// `position(n)`.
pub fn weighted_slip(
    row: &MortarRow,
    (d_n, m_n): (f64, &[(usize, f64)]),
    position: impl Fn(usize) -> Vector3<f64>,
) -> WeightedSlip {
    let transformation = &row.transformation;
    let mut nodes = row.nodes.clone();
    for (l, _) in m_n {
        if !nodes.contains(l) {
            nodes.push(*l);
        }
    }
    let at = |n: usize| 3 * nodes.iter().position(|&m| m == n).unwrap_or(0);
    let width = 3 * row.nodes.len();
    let mut value = Vector3::zeros();
    let mut gradient = DMatrix::zeros(3, 3 * nodes.len());
    let add_identity = |gradient: &mut DMatrix<f64>, n: usize, scale: f64| {
        let c = at(n);
        for i in 0..3 {
            gradient[(i, c + i)] += scale;
        }
    };
    // a row without derivatives gives the value alone (its `∇D`, `∇M`
    // empty: the gradient then misses their terms)
    let with = row.has_derivatives();
    for (a, (l, m)) in row.m.iter().enumerate() {
        let x = position(*l);
        value += *m * x;
        if with {
            let mut block = gradient.columns_mut(0, width);
            block += x * row.m_gradients[a].transpose();
        }
        add_identity(&mut gradient, *l, *m);
    }
    for (l, m) in m_n {
        value -= *m * position(*l);
        add_identity(&mut gradient, *l, -m);
    }
    let x_tilde: Vector3<f64> = transformation.iter().map(|(k, r)| position(*k) * *r).sum();
    let change = row.d - d_n;
    value -= change * x_tilde;
    if with {
        let mut block = gradient.columns_mut(0, width);
        block -= x_tilde * row.d_gradient.transpose();
    }
    for (k, r) in transformation {
        add_identity(&mut gradient, *k, -change * r);
    }
    WeightedSlip {
        nodes,
        value,
        gradient,
    }
}

impl WeightedSlip {
    /// The node's slip `d_j = w_j / D_j` and `∂d_j/∂x = (∂w_j/∂x − d_j ⊗
    /// ∇D_j) / D_j` over [`nodes`](Self::nodes), with `D_j`, `∇D_j` of `row`
    /// (`D_j > 0`).
    pub fn per_area(&self, row: &MortarRow) -> (Vector3<f64>, DMatrix<f64>) {
        let d = self.value / row.d;
        let mut gradient = self.gradient.clone();
        let mut block = gradient.columns_mut(0, row.d_gradient.len());
        block -= d * row.d_gradient.transpose();
        (d, gradient / row.d)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::mortar::rows::mortar_rows;
    use crate::contact::mortar::weighted_gap::{all_pairs, mortar_coupling};
    use crate::contact::mortar::{Derivatives, FaceShape, SurfaceFace};
    use crate::mesh::structured::box_mesh;
    use crate::mesh::{ElementKind, FacetKind, Mesh};
    use nalgebra::Rotation3;

    /// A lower block's top (3 × 3 faces, primary) under an upper block's
    /// bottom (2 × 2 faces over `[0.1, 0.9]²`, secondary), touching at
    /// `z = 0.5`: the faces and the reference coordinates.
    fn pair(kind: ElementKind) -> (Vec<SurfaceFace>, Vec<SurfaceFace>, Vec<Vector3<f64>>) {
        let lower = box_mesh(kind, [3, 3, 1], [1.0, 1.0, 0.5]);
        let upper = box_mesh(kind, [2, 2, 1], [0.8, 0.8, 0.5]);
        let offset = lower.nodes.len();
        let mut xs: Vec<Vector3<f64>> = lower.nodes.iter().map(|x| Vector3::from(*x)).collect();
        xs.extend(
            upper
                .nodes
                .iter()
                .map(|x| Vector3::new(x[0] + 0.1, x[1] + 0.1, x[2] + 0.5)),
        );
        let faces = |mesh: &Mesh, name: &str, by: usize| -> Vec<SurfaceFace> {
            let shape = |k| match k {
                FacetKind::Tri3 => FaceShape::Tri3,
                FacetKind::Quad4 => FaceShape::Quad4,
                FacetKind::Tri6 => FaceShape::Tri6,
                FacetKind::Quad8 => FaceShape::Quad8,
            };
            let set = mesh.surface(name).unwrap();
            set.facets
                .iter()
                .map(|f| SurfaceFace {
                    shape: shape(f.kind),
                    nodes: f.nodes.iter().map(|n| n + by).collect(),
                })
                .collect()
        };
        (faces(&upper, "zmin", offset), faces(&lower, "zmax", 0), xs)
    }

    /// `x` warped and the secondary body pressed in by 0.02 and slid by
    /// `(0.03, −0.02)`.
    fn moved(xs: &[Vector3<f64>], secondary: &[usize], seed: f64) -> Vec<Vector3<f64>> {
        xs.iter()
            .enumerate()
            .map(|(n, x)| {
                let i = n as f64;
                let warp = 0.004 * Vector3::new((seed * i).sin(), (0.7 * i).cos(), (1.3 * i).sin());
                let slide = if secondary.contains(&n) {
                    Vector3::new(0.03, -0.02, -0.02)
                } else {
                    Vector3::zeros()
                };
                x + warp + slide
            })
            .collect()
    }

    fn secondary_nodes(faces: &[SurfaceFace]) -> Vec<usize> {
        let mut nodes: Vec<usize> = faces.iter().flat_map(|f| f.nodes.clone()).collect();
        nodes.sort_unstable();
        nodes.dedup();
        nodes
    }

    /// Node `j`'s weighted slip at `xs` against the coupling `committed`.
    fn slip_at(
        (secondary, primary): (&[SurfaceFace], &[SurfaceFace]),
        committed: &MortarCoupling,
        xs: &[Vector3<f64>],
        j: usize,
    ) -> Option<(MortarRow, WeightedSlip)> {
        let pairs = all_pairs(secondary.len(), primary.len());
        let rows = mortar_rows(secondary, primary, &pairs, xs, Derivatives::With).unwrap();
        let row = rows.into_iter().find(|r| r.node == j)?;
        let (d_n, m_n) = committed_row(committed, j)?;
        let slip = weighted_slip(&row, (d_n, &m_n), |n| xs[n]);
        Some((row, slip))
    }

    /// `∂w_j/∂x` and `∂d_j/∂x` against central differences (step 1e-6) of
    /// the kernel with `D`, `M` re-integrated at each perturbed state, to
    /// 1e-6 of the gradient's size (the differences' `O(h²)` error is
    /// about 1e-8 here; a missing term is off by its own size, `O(1)`),
    /// on linear and quadratic faces.
    #[test]
    fn weighted_slip_gradient_matches_finite_differences() {
        for kind in [ElementKind::Hex8, ElementKind::Hex20] {
            let (secondary, primary, reference) = pair(kind);
            let faces = (&secondary[..], &primary[..]);
            let nodes = secondary_nodes(&secondary);
            let committed = coupling_at(&secondary, &primary, &moved(&reference, &[], 0.3));
            let x = moved(&reference, &nodes, 0.9);
            let mut checked = 0;
            for &j in nodes.iter().skip(nodes.len() / 3).take(2) {
                let Some((row, slip)) = slip_at(faces, &committed, &x, j) else {
                    continue;
                };
                let (_, d_gradient) = slip.per_area(&row);
                let h = 1e-6;
                for (a, &node) in slip.nodes.iter().enumerate() {
                    for c in 0..3 {
                        let at = |s: f64| {
                            let mut y = x.clone();
                            y[node][c] += s * h;
                            let (row, slip) = slip_at(faces, &committed, &y, j).unwrap();
                            (slip.value, slip.per_area(&row).0)
                        };
                        let ((wp, dp), (wm, dm)) = (at(1.0), at(-1.0));
                        for i in 0..3 {
                            let fd = (wp[i] - wm[i]) / (2.0 * h);
                            let exact = slip.gradient[(i, 3 * a + c)];
                            let scale = slip.gradient.amax();
                            assert!(
                                (fd - exact).abs() <= 1e-6 * scale,
                                "{kind:?} j {j} node {node}.{c}: ∂w{i} fd {fd:e} exact {exact:e}"
                            );
                            let fd = (dp[i] - dm[i]) / (2.0 * h);
                            let exact = d_gradient[(i, 3 * a + c)];
                            let scale = d_gradient.amax();
                            assert!(
                                (fd - exact).abs() <= 1e-6 * scale,
                                "{kind:?} j {j} node {node}.{c}: ∂d{i} fd {fd:e} exact {exact:e}"
                            );
                        }
                    }
                }
                checked += 1;
            }
            assert!(checked == 2, "{kind:?}: {checked} nodes checked");
        }
    }

    /// Objectivity: from a warped, pressed committed state, a rigid rotation
    /// (0.4 rad about a skew axis) and translation of both bodies together
    /// gives `w_j = 0` at every secondary node to 1e-12 of `D_j` (rounding),
    /// where the non-objective `D_j Δx̃_j − Σ M_jl Δx_l` is of the size of
    /// the motion; a slide `s` of the secondary body alone over flat
    /// faces gives `w_j / D_j = s` at every fully covered node to 1e-12.
    #[test]
    fn rigid_motion_gives_no_slip_and_a_slide_its_length() {
        for kind in [ElementKind::Hex8, ElementKind::Hex20, ElementKind::Tet10] {
            let (secondary, primary, reference) = pair(kind);
            let faces = (&secondary[..], &primary[..]);
            let nodes = secondary_nodes(&secondary);
            let x_n = moved(&reference, &nodes, 0.3);
            let committed = coupling_at(&secondary, &primary, &x_n);
            let rotation = Rotation3::new(Vector3::new(0.1, -0.3, 0.25).normalize() * 0.4);
            let c = Vector3::new(0.3, -0.1, 0.7);
            let x: Vec<Vector3<f64>> = x_n.iter().map(|p| rotation * p + c).collect();
            let mut seen = 0;
            for &j in &nodes {
                let Some((row, slip)) = slip_at(faces, &committed, &x, j) else {
                    continue;
                };
                let d = slip.value.norm() / row.d;
                assert!(
                    d < 1e-12,
                    "{kind:?} node {j}: |w|/D = {d:e} under a rigid motion"
                );
                seen += 1;
            }
            assert_eq!(seen, nodes.len(), "{kind:?}: nodes without a row");
            // a slide of the secondary body over flat, touching faces
            let s = Vector3::new(0.05, -0.03, 0.0);
            let flat = coupling_at(&secondary, &primary, &reference);
            let slid: Vec<Vector3<f64>> = reference
                .iter()
                .enumerate()
                .map(|(n, p)| if nodes.contains(&n) { p + s } else { *p })
                .collect();
            for &j in &nodes {
                let (row, slip) = slip_at(faces, &flat, &slid, j).unwrap();
                let err = (slip.per_area(&row).0 - s).norm();
                assert!(err < 1e-12, "{kind:?} node {j}: slip off by {err:e}");
            }
        }
    }

    /// The coupling of every face pair at `xs`.
    fn coupling_at(
        secondary: &[SurfaceFace],
        primary: &[SurfaceFace],
        xs: &[Vector3<f64>],
    ) -> MortarCoupling {
        let pairs = all_pairs(secondary.len(), primary.len());
        mortar_coupling(secondary, primary, &pairs, xs).unwrap()
    }
}
