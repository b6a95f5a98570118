//! The assembled mortar rows that Newton needs, per secondary node `j`,
//! with their gradients with respect to every coupled node's coordinates
//! (Popp, Gee & Wall, IJNME 79, 2009, §4; Popp, Gitterle, Gee & Wall,
//! IJNME 83, 2010, §5):
//!
//! ```text
//! g̃_j = n_jᵀ v_j,   v_j = Σ_l M_jl x_l − D_j x̃_j,   x̃_j = Σ_k R_jk x_k,
//! b_j = (D_j n_j R_jk on secondary nodes k;  −M_jl n_j on primary nodes l),
//! ∇g̃_j = (∂n_j/∂x)ᵀ v_j + Σ_l (n_j·x_l) ∇M_jl − (n_j·x̃_j) ∇D_j − b_j,
//! ∂b_j/∂x = R_jk (n_j ⊗ ∇D_j + D_j ∂n_j/∂x)  on k,
//!          −(n_j ⊗ ∇M_jl + M_jl ∂n_j/∂x)     on l.
//! ```
//!
//! `b_j = −∂g̃_j/∂x` at fixed `D`, `M`, `n`: the multiplier `λ_j ≥ 0` adds
//! `λ_j b_j` to the residual (internal minus external forces; the contact
//! forces of [`super::MortarCoupling::contact_forces`] are `−λ_j b_j`), and
//! `λ_j ∂b_j/∂x` to the tangent. `Σ_nodes b_j = (D_j Σ_k R_jk − Σ_l M_jl)
//! n_j = 0`. Gradients are node-major over [`MortarRow::nodes`]: entry
//! `3a + i` is coordinate `i` of `nodes[a]`.
//!
//! Without derivatives ([`Derivatives::Without`]) the same pair loop
//! gives the same `g̃_j`, `D_j`, `M_jl`, `n_j` and `b_j`, bit for bit, with
//! the segment integration alone ([`integrate_pair`] instead of
//! [`linearise_pair`], which adds one directional derivative of the
//! segmentation per coordinate of the pair: `3 (n_s + n_m)` of them, the
//! bulk of a row's cost); [`mortar_row_values`] is that row's values.

use std::collections::BTreeMap;

use nalgebra::{DMatrix, DVector, Vector3};
use rayon::prelude::*;

use super::dual_basis::faces_and_duals;
use super::face::SurfaceFace;
use super::normals::nodal_normals;
use super::normals::{nodal_normal_gradient, NodalNormalGradient};
use super::pair_linearisation::linearise_pair;
use super::quadratic;
use super::segment::{integrate_pair, SegmentIntegrals};
use super::{Derivatives, MortarError};

/// One secondary node's mortar row (see the module doc); taken
/// [`Derivatives::Without`], every gradient is empty
/// ([`has_derivatives`](Self::has_derivatives)).
#[derive(Clone, Debug, PartialEq)]
pub struct MortarRow {
    pub node: usize,
    /// The coupled mesh nodes, sorted: every node the gradients reach, or
    /// without derivatives the nodes of the lever (`R_jk`, `M_jl`).
    pub nodes: Vec<usize>,
    pub weighted_gap: f64,
    pub weighted_gap_gradient: DVector<f64>,
    /// `D_j` and `∇D_j`.
    pub d: f64,
    pub d_gradient: DVector<f64>,
    /// `(l, M_jl)` sorted by the primary node `l`, and each `∇M_jl`.
    pub m: Vec<(usize, f64)>,
    pub m_gradients: Vec<DVector<f64>>,
    /// `n_j` and `∂n_j/∂x` (3 × 3·nodes).
    pub normal: Vector3<f64>,
    pub normal_gradient: DMatrix<f64>,
    /// `b_j` (3·nodes) and `∂b_j/∂x` (3·nodes × 3·nodes).
    pub lever: DVector<f64>,
    pub lever_gradient: DMatrix<f64>,
    /// `(k, R_jk)` of `x̃_j = Σ_k R_jk x_k` (`(j, 1)` on linear faces).
    pub transformation: Vec<(usize, f64)>,
}

impl MortarRow {
    /// Whether the row carries its gradients ([`Derivatives::With`]).
    pub fn has_derivatives(&self) -> bool {
        self.d_gradient.len() == 3 * self.nodes.len()
    }
}

/// One secondary node's row without derivatives: `g̃_j`, `D_j`, `M_jl`
/// and `n_j`, the values of the [`MortarRow`] at the same coordinates.
#[derive(Clone, Debug, PartialEq)]
pub struct RowValues {
    pub node: usize,
    pub weighted_gap: f64,
    pub d: f64,
    /// `(l, M_jl)` sorted by the primary node `l`.
    pub m: Vec<(usize, f64)>,
    pub normal: Vector3<f64>,
}

/// A value with a sparse gradient: per node, `∂/∂x_node`.
#[derive(Clone, Debug, Default)]
struct Sparse {
    value: f64,
    gradient: BTreeMap<usize, Vector3<f64>>,
}

/// `D_j` and `M_jl` of one secondary node, summed over its pairs.
#[derive(Clone, Debug, Default)]
struct Accumulated {
    d: Sparse,
    m: BTreeMap<usize, Sparse>,
}

/// The mortar rows of every secondary node that a segment touches, from
/// the candidate face `pairs` (secondary index, primary index), with their
/// gradients or without ([`Derivatives`]).
pub fn mortar_rows(
    secondary: &[SurfaceFace],
    primary: &[SurfaceFace],
    pairs: &[(usize, usize)],
    coordinates: &[Vector3<f64>],
    derivatives: Derivatives,
) -> Result<Vec<MortarRow>, MortarError> {
    let with = derivatives == Derivatives::With;
    let accumulated = accumulate_pairs(secondary, primary, pairs, coordinates, with)?;
    let holding = holding_faces(secondary);
    let normals = if with {
        BTreeMap::new()
    } else {
        nodal_normals(secondary, coordinates)?
    };
    accumulated
        .into_iter()
        .map(|(node, acc)| {
            let faces = &holding[&node];
            let r = transformation(faces[0], node);
            if !with {
                return Ok(value_row(node, acc, normals[&node], r, coordinates));
            }
            let normal = nodal_normal_gradient(faces, coordinates, node)?;
            Ok(assemble_row(node, acc, normal, r, coordinates))
        })
        .collect()
}

/// The values of [`mortar_rows`] (`g̃_j`, `D_j`, `M_jl`, `n_j`) without
/// their derivatives ([`Derivatives::Without`]), for what needs no tangent.
pub fn mortar_row_values(
    secondary: &[SurfaceFace],
    primary: &[SurfaceFace],
    pairs: &[(usize, usize)],
    coordinates: &[Vector3<f64>],
) -> Result<Vec<RowValues>, MortarError> {
    let rows = mortar_rows(secondary, primary, pairs, coordinates, Derivatives::Without)?;
    Ok(rows
        .into_iter()
        .map(|row| RowValues {
            node: row.node,
            weighted_gap: row.weighted_gap,
            d: row.d,
            m: row.m,
            normal: row.normal,
        })
        .collect())
}

/// The secondary faces that hold each node.
fn holding_faces(secondary: &[SurfaceFace]) -> BTreeMap<usize, Vec<&SurfaceFace>> {
    let mut holding: BTreeMap<usize, Vec<&SurfaceFace>> = BTreeMap::new();
    for face in secondary {
        for &n in &face.nodes {
            holding.entry(n).or_default().push(face);
        }
    }
    holding
}

/// `v_j = Σ_l M_jl x_l − D_j x̃_j`, `x̃_j = Σ_k R_jk x_k`.
fn gap_vector(
    m: &[(usize, f64)],
    d: f64,
    r: &[(usize, f64)],
    coordinates: &[Vector3<f64>],
) -> Vector3<f64> {
    let x_tilde: Vector3<f64> = r.iter().map(|(k, rk)| coordinates[*k] * *rk).sum();
    m.iter()
        .map(|(l, ml)| coordinates[*l] * *ml)
        .sum::<Vector3<f64>>()
        - x_tilde * d
}

/// `D_j`, `M_jl` over all pairs, with their sparse gradients where
/// `gradients` (else the gradients stay empty).
fn accumulate_pairs(
    secondary: &[SurfaceFace],
    primary: &[SurfaceFace],
    pairs: &[(usize, usize)],
    coordinates: &[Vector3<f64>],
    gradients: bool,
) -> Result<BTreeMap<usize, Accumulated>, MortarError> {
    let (faces, duals) = faces_and_duals(secondary, coordinates)?;
    let integrate = |&(s, p): &(usize, usize)| -> Result<Option<PairIntegrals>, MortarError> {
        let primary_face = primary[p].with_coordinates(coordinates)?;
        Ok(if gradients {
            linearise_pair(&faces[s], &duals[s], &primary_face)?
                .map(|lin| (lin.integrals, Some((lin.d_gradient, lin.m_gradient))))
        } else {
            integrate_pair(&faces[s], &duals[s], &primary_face)?.map(|seg| (seg, None))
        })
    };
    let mut out: BTreeMap<usize, Accumulated> = BTreeMap::new();
    for pairs in pairs.chunks(PAIRS_PER_CHUNK) {
        let integrated: Vec<_> = pairs.par_iter().map(integrate).collect();
        for (&(s, p), pair) in pairs.iter().zip(integrated) {
            let Some((integrals, gradient)) = pair? else {
                continue;
            };
            accumulate_pair(
                &mut out,
                &secondary[s],
                &primary[p],
                &integrals,
                gradient.as_ref(),
            );
        }
    }
    Ok(out)
}

/// A pair's segment integrals, with `(∂D/∂x, ∂M/∂x)` where taken.
type PairIntegrals = (SegmentIntegrals, Option<(DMatrix<f64>, DMatrix<f64>)>);

/// Pairs integrated side by side on the run's threads at once, before
/// their integrals are added in the pairs' order (so that the sums are
/// the same bit for bit on any number of threads): with gradients a pair
/// of Tri6 faces holds about 12 kB, of Quad8 faces 28 kB, so at most
/// 56 MB at once. Fewer pairs at once cost the threads' waits: on
/// two-spheres with mortar (2 threads) 128 at once took 1.13 of the
/// serial loop's CPU, 2 048 1.07, all at once 1.06.
const PAIRS_PER_CHUNK: usize = 2048;

/// Adds one pair's integrals (and gradients) to its secondary nodes' `D_j`
/// and `M_jl`.
fn accumulate_pair(
    out: &mut BTreeMap<usize, Accumulated>,
    secondary: &SurfaceFace,
    primary: &SurfaceFace,
    integrals: &SegmentIntegrals,
    gradient: Option<&(DMatrix<f64>, DMatrix<f64>)>,
) {
    let pair_nodes: Vec<usize> = secondary
        .nodes
        .iter()
        .chain(&primary.nodes)
        .copied()
        .collect();
    let nm = primary.nodes.len();
    for (j, &node_j) in secondary.nodes.iter().enumerate() {
        let acc = out.entry(node_j).or_default();
        let d_gradient = gradient.map(|(d, _)| (d, j));
        add_sparse(&mut acc.d, integrals.d[j], d_gradient, &pair_nodes);
        for (l, &node_l) in primary.nodes.iter().enumerate() {
            let m = acc.m.entry(node_l).or_default();
            let m_gradient = gradient.map(|(_, m)| (m, j * nm + l));
            add_sparse(m, integrals.m[(j, l)], m_gradient, &pair_nodes);
        }
    }
}

/// Adds `value` and, where given, the row `row` of a pair's `gradient`
/// (columns over `pair_nodes`, see
/// [`super::pair_linearisation::PairLinearisation`]) to `target`.
fn add_sparse(
    target: &mut Sparse,
    value: f64,
    gradient: Option<(&DMatrix<f64>, usize)>,
    pair_nodes: &[usize],
) {
    target.value += value;
    let Some((gradient, row)) = gradient else {
        return;
    };
    for (a, &node) in pair_nodes.iter().enumerate() {
        let g = Vector3::new(
            gradient[(row, 3 * a)],
            gradient[(row, 3 * a + 1)],
            gradient[(row, 3 * a + 2)],
        );
        *target.gradient.entry(node).or_insert_with(Vector3::zeros) += g;
    }
}

/// `x̃_j = Σ_k R_jk x_k` as global `(k, R_jk)`, from a face holding `node`.
pub(super) fn transformation(face: &SurfaceFace, node: usize) -> Vec<(usize, f64)> {
    let j = face.nodes.iter().position(|&n| n == node).unwrap_or(0);
    quadratic::nodal_transformation(face.shape)[j]
        .iter()
        .map(|&(k, r)| (face.nodes[k], r))
        .collect()
}

/// A sparse gradient as a dense vector over `nodes` (positions `index`).
fn dense(sparse: &Sparse, index: &BTreeMap<usize, usize>) -> DVector<f64> {
    let mut out = DVector::zeros(3 * index.len());
    for (node, g) in &sparse.gradient {
        out.fixed_rows_mut::<3>(3 * index[node]).copy_from(g);
    }
    out
}

/// One row from its accumulated `D`, `M`, its normal and `R_jk`.
fn assemble_row(
    node: usize,
    acc: Accumulated,
    normal: NodalNormalGradient,
    r: Vec<(usize, f64)>,
    coordinates: &[Vector3<f64>],
) -> MortarRow {
    let mut nodes: Vec<usize> = acc.d.gradient.keys().copied().collect();
    nodes.extend(acc.m.keys());
    nodes.extend(acc.m.values().flat_map(|m| m.gradient.keys()));
    nodes.extend(&normal.nodes);
    nodes.extend(r.iter().map(|(k, _)| k));
    nodes.sort_unstable();
    nodes.dedup();
    let index: BTreeMap<usize, usize> = nodes.iter().enumerate().map(|(a, &n)| (n, a)).collect();
    let mut normal_gradient = DMatrix::zeros(3, 3 * nodes.len());
    for (a, n) in normal.nodes.iter().enumerate() {
        normal_gradient
            .fixed_columns_mut::<3>(3 * index[n])
            .copy_from(&normal.gradient.fixed_columns::<3>(3 * a));
    }
    let n = normal.normal;
    let x_tilde: Vector3<f64> = r.iter().map(|(k, rk)| coordinates[*k] * *rk).sum();
    let d_gradient = dense(&acc.d, &index);
    let m: Vec<(usize, f64)> = acc.m.iter().map(|(l, s)| (*l, s.value)).collect();
    let m_gradients: Vec<DVector<f64>> = acc.m.values().map(|s| dense(s, &index)).collect();
    let v = gap_vector(&m, acc.d.value, &r, coordinates);
    let (lever, lever_gradient) = lever(
        &index,
        (acc.d.value, &d_gradient),
        (&m, &m_gradients),
        (&n, &normal_gradient),
        &r,
    );
    let mut weighted_gap_gradient =
        normal_gradient.transpose() * v - &d_gradient * n.dot(&x_tilde) - &lever;
    for ((l, _), g) in m.iter().zip(&m_gradients) {
        weighted_gap_gradient += g * n.dot(&coordinates[*l]);
    }
    MortarRow {
        node,
        nodes,
        weighted_gap: n.dot(&v),
        weighted_gap_gradient,
        d: acc.d.value,
        d_gradient,
        m,
        m_gradients,
        normal: n,
        normal_gradient,
        lever,
        lever_gradient,
        transformation: r,
    }
}

/// One row without derivatives from its accumulated `D`, `M`, its normal
/// `n` and `R_jk`: the values of [`assemble_row`], by the same operations.
fn value_row(
    node: usize,
    acc: Accumulated,
    n: Vector3<f64>,
    r: Vec<(usize, f64)>,
    coordinates: &[Vector3<f64>],
) -> MortarRow {
    let m: Vec<(usize, f64)> = acc.m.iter().map(|(l, s)| (*l, s.value)).collect();
    let mut nodes: Vec<usize> = (r.iter().chain(&m)).map(|(k, _)| *k).collect();
    nodes.sort_unstable();
    nodes.dedup();
    let index: BTreeMap<usize, usize> = nodes.iter().enumerate().map(|(a, &n)| (n, a)).collect();
    let v = gap_vector(&m, acc.d.value, &r, coordinates);
    MortarRow {
        node,
        weighted_gap: n.dot(&v),
        weighted_gap_gradient: DVector::zeros(0),
        d: acc.d.value,
        d_gradient: DVector::zeros(0),
        lever: lever_values(&index, acc.d.value, &m, &n, &r),
        m,
        m_gradients: Vec::new(),
        normal: n,
        normal_gradient: DMatrix::zeros(3, 0),
        lever_gradient: DMatrix::zeros(0, 0),
        transformation: r,
        nodes,
    }
}

/// `b_j` over the nodes of `index` (see the module doc).
fn lever_values(
    index: &BTreeMap<usize, usize>,
    d: f64,
    m: &[(usize, f64)],
    n: &Vector3<f64>,
    r: &[(usize, f64)],
) -> DVector<f64> {
    let mut b = DVector::zeros(3 * index.len());
    let terms = (r.iter().map(|&(k, rk)| (k, rk * d))).chain(m.iter().map(|&(l, ml)| (l, -ml)));
    for (node, scaled) in terms {
        let mut rows = b.fixed_rows_mut::<3>(3 * index[&node]);
        rows += n * scaled;
    }
    b
}

/// `b_j` and `∂b_j/∂x` (see the module doc).
fn lever(
    index: &BTreeMap<usize, usize>,
    (d, d_gradient): (f64, &DVector<f64>),
    (m, m_gradients): (&[(usize, f64)], &[DVector<f64>]),
    (n, n_gradient): (&Vector3<f64>, &DMatrix<f64>),
    r: &[(usize, f64)],
) -> (DVector<f64>, DMatrix<f64>) {
    let size = 3 * index.len();
    let b = lever_values(index, d, m, n, r);
    let mut db = DMatrix::zeros(size, size);
    let mut add = |node: usize, scale: f64, value: f64, gradient: &DVector<f64>| {
        let at = 3 * index[&node];
        let block = (n * gradient.transpose() + n_gradient * value) * scale;
        let mut rows = db.rows_mut(at, 3);
        rows += block;
    };
    for &(k, rk) in r {
        add(k, rk, d, d_gradient);
    }
    for ((l, ml), g) in m.iter().zip(m_gradients) {
        add(*l, -1.0, *ml, g);
    }
    (b, db)
}
