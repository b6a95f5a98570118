//! Dual mortar rows of a secondary surface against a rigid obstacle (issue
//! 28 item 3). With a rigid primary the mortar integral lives on the
//! secondary side alone (Popp, Gee & Wall, IJNME 79, 2009, §3, with the
//! primary's `M` replaced by the obstacle's gap function): no segmentation,
//! each secondary face integrated by its own rule. Per secondary node `j`,
//! with the dual basis `Φ_j` of [`super::dual_basis`] on the mortar shape
//! functions `Ñ` of [`super::quadratic`], the obstacle's signed gap `g(x)`,
//! its normal `n = ∂g/∂x` and curvature `H = ∂²g/∂x²` at the current point
//! `x(ξ) = Σ_k N_k x_k` of the face:
//!
//! ```text
//! D_j  = Σ_e ∫_e Φ_j dA = Σ_e ∫_e Ñ_j dA          (biorthogonality, Σ_k Ñ_k = 1)
//! g̃_j = Σ_e ∫_e Φ_j g(x) dA                       (weighted gap, > 0 open)
//! L_jk = Σ_e ∫_e Φ_j N_k n(x) dA                  (∂g̃_j/∂x_k at fixed Φ_j dA)
//! ∂g̃_j/∂x_k = L_jk + Σ_e ∫_e g ∂(Φ_j dA)/∂x_k
//! ∂L_jk/∂x_m = Σ_e ∫_e Φ_j N_k N_m H dA + Σ_e ∫_e N_k n ⊗ ∂(Φ_j dA)/∂x_m
//! ∂D_j/∂x_m  = Σ_e ∫_e Ñ_j ∂(dA)/∂x_m
//! ```
//!
//! with `∂(Φ_j dA) = (∂A_e Ñ) dA + Φ_j ∂|a|` (the dual coefficients `A_e`
//! and the area element `|a|` follow the face's current geometry:
//! [`DualBasis::derivative`], [`MortarFace::area_normal_derivative`]).
//! The force of a multiplier `λ_j ≥ 0` is Popp's at fixed `D`: `λ_j L_jk`
//! on node `k` (the body pushed along `n`). On a flat obstacle
//! `∫Φ_j N_k dA = D_j R_jk` (`R` the nodal transformation, `x̃ = R x`), so
//! `L_jk = D_j R_jk n` and `g̃_j = D_j g(x̃_j)`: a uniform `λ` gives the
//! consistent loads `λ ∫ N_k n dA`, and the plane's integral is exact.
//!
//! The rows are returned as [`MortarRow`]s with no primary nodes (`M`
//! empty), in their conventions: the lever `b_j = −L_j` (`−∂g̃_j/∂x` at
//! fixed `D`), the normal `n_j = −n̄_j` on the secondary side, where
//! `n̄_j = w_j/|w_j|`, `w_j = Σ_k L_jk = ∫ Φ_j n dA` is the obstacle's
//! weighted normal at the node (`n̄_j = n` on a plane).

use std::collections::BTreeMap;

use nalgebra::{DMatrix, DVector, Vector3};

use super::dual_basis::{positive_integrals, DualBasis, FaceIntegrals};
use super::face::{FaceValues, MortarFace, SurfaceFace};
use super::normals::unit_derivative;
use super::quadratic::mortar_values;
use super::rows::MortarRow;
use super::{Derivatives, MortarError};
use crate::contact::projection::Projection;

/// One secondary face's contributions (local node order, gradients over
/// the face's `3n` coordinates, node-major): see the module doc. Taken
/// [`Derivatives::Without`], the gradients are empty.
#[derive(Clone, Debug, PartialEq)]
pub struct FaceObstacleIntegrals {
    /// `∫_e Ñ_j dA` and its gradient (`n × 3n`).
    pub d: Vec<f64>,
    pub d_gradient: DMatrix<f64>,
    /// `∫_e Φ_j g dA` and its complete gradient (`n × 3n`).
    pub weighted_gap: Vec<f64>,
    pub weighted_gap_gradient: DMatrix<f64>,
    /// `L_j`, row `j`: the blocks `∫_e Φ_j N_k n dA` over `k` (`n × 3n`).
    pub lever: DMatrix<f64>,
    /// `∂L_j/∂x` per `j` (`3n × 3n`).
    pub lever_gradient: Vec<DMatrix<f64>>,
}

/// The face's integrals against the obstacle `obstacle` (the projection of
/// a spatial point: `g`, `n`, `H`), on the face rule
/// ([`FaceShape::quadrature`](super::FaceShape::quadrature)), with their
/// gradients or without ([`Derivatives::Without`]: the values by the same
/// sums, without the `3n` derivatives of the dual basis).
pub fn face_obstacle_integrals(
    face: &MortarFace,
    obstacle: &impl Fn(&Vector3<f64>) -> Projection,
    derivatives: Derivatives,
) -> Result<FaceObstacleIntegrals, MortarError> {
    let n = face.shape.node_count();
    let size = 3 * n;
    let dual = DualBasis::of_face(face)?;
    let with = derivatives == Derivatives::With;
    let columns = if with { size } else { 0 };
    let mut out = FaceObstacleIntegrals {
        d: vec![0.0; n],
        d_gradient: DMatrix::zeros(n, columns),
        weighted_gap: vec![0.0; n],
        weighted_gap_gradient: DMatrix::zeros(n, columns),
        lever: DMatrix::zeros(n, size),
        lever_gradient: vec![DMatrix::zeros(size, size); if with { n } else { 0 }],
    };
    // ∂A_e along each unit increment c = 3m + d
    let coefficient_derivatives = (0..columns)
        .map(|c| {
            let mut dx = vec![Vector3::zeros(); n];
            dx[c / 3][c % 3] = 1.0;
            dual.derivative(face, &dx)
        })
        .collect::<Result<Vec<_>, _>>()?;
    let (points, weights) = face.shape.quadrature();
    for (xi, w) in points.iter().zip(weights) {
        let point = FacePoint::at(face, *xi, &dual, obstacle);
        for j in 0..n {
            point.add_values_to(&mut out, j, *w);
        }
        if !with {
            continue;
        }
        let dj = point.area_element_gradient(face);
        for j in 0..n {
            // δ(Φ_j |a|) along each c
            let d_phi_da: Vec<f64> = (0..size)
                .map(|c| {
                    let d_phi: f64 = (0..n)
                        .map(|i| coefficient_derivatives[c][(j, i)] * point.mortar[i])
                        .sum();
                    d_phi * point.da + point.phi[j] * dj[c]
                })
                .collect();
            point.add_derivatives_to(&mut out, j, *w, &dj, &d_phi_da);
        }
    }
    Ok(out)
}

/// What the rule needs at one point `ξ` of a face.
struct FacePoint {
    /// The Lagrange values `N_k`, the mortar values `Ñ_i`, the dual `Φ_j`.
    lagrange: FaceValues<f64>,
    gradients: FaceValues<[f64; 2]>,
    mortar: Vec<f64>,
    phi: Vec<f64>,
    /// The area element `|a|`, the unit normal `a/|a|`, the tangents.
    da: f64,
    unit: Vector3<f64>,
    tangents: [Vector3<f64>; 2],
    /// The obstacle at `x(ξ)`.
    obstacle: Projection,
}

impl FacePoint {
    fn at(
        face: &MortarFace,
        xi: [f64; 2],
        dual: &DualBasis,
        obstacle: &impl Fn(&Vector3<f64>) -> Projection,
    ) -> Self {
        let a = face.area_normal(xi);
        let mortar = mortar_values(face.shape, xi);
        FacePoint {
            lagrange: face.shape.values(xi),
            gradients: face.shape.gradients(xi),
            phi: dual.values_from(&mortar),
            mortar,
            da: a.norm(),
            unit: a / a.norm(),
            tangents: face.tangents(xi),
            obstacle: obstacle(&face.point(xi)),
        }
    }

    /// `∂|a|/∂x_c = (a/|a|)·(N_m,ξ e_d × x_,η + x_,ξ × N_m,η e_d)`,
    /// `c = 3m + d`.
    fn area_element_gradient(&self, face: &MortarFace) -> Vec<f64> {
        let [t1, t2] = self.tangents;
        (0..3 * face.shape.node_count())
            .map(|c| {
                let mut e = Vector3::zeros();
                e[c % 3] = 1.0;
                let g = self.gradients[c / 3];
                self.unit
                    .dot(&((e * g[0]).cross(&t2) + t1.cross(&(e * g[1]))))
            })
            .collect()
    }

    /// Node `j`'s values at this point, weight `w`: `w Ñ_j |a|` to `d`,
    /// `w Φ_j g |a|` to `weighted_gap`, `w Φ_j N_k n |a|` to the lever (the
    /// one place that sums them, so that the rows without derivatives are
    /// those with, to the bit).
    fn add_values_to(&self, out: &mut FaceObstacleIntegrals, j: usize, w: f64) {
        let (phi, da, n) = (self.phi[j], self.da, self.obstacle.normal);
        out.d[j] += w * self.mortar[j] * da;
        out.weighted_gap[j] += w * phi * self.obstacle.gap * da;
        for (k, nk) in self.lagrange.iter().enumerate() {
            for r in 0..3 {
                out.lever[(j, 3 * k + r)] += w * phi * nk * n[r] * da;
            }
        }
    }

    /// Node `j`'s derivative terms at this point, weight `w`, with `∂|a|`
    /// (`dj`) and `∂(Φ_j |a|)` (`d_phi_da`) along every coordinate.
    fn add_derivatives_to(
        &self,
        out: &mut FaceObstacleIntegrals,
        j: usize,
        w: f64,
        dj: &[f64],
        d_phi_da: &[f64],
    ) {
        let (g, n, h) = (
            self.obstacle.gap,
            self.obstacle.normal,
            self.obstacle.curvature,
        );
        let (phi, da) = (self.phi[j], self.da);
        let size = dj.len();
        for c in 0..size {
            let (m, d) = (c / 3, c % 3);
            out.d_gradient[(j, c)] += w * self.mortar[j] * dj[c];
            out.weighted_gap_gradient[(j, c)] +=
                w * (phi * self.lagrange[m] * n[d] * da + g * d_phi_da[c]);
        }
        let lever_gradient = &mut out.lever_gradient[j];
        for (k, nk) in self.lagrange.iter().enumerate() {
            for r in 0..3 {
                for c in 0..size {
                    let (m, d) = (c / 3, c % 3);
                    lever_gradient[(3 * k + r, c)] += w
                        * (phi * nk * self.lagrange[m] * h[(r, d)] * da + nk * n[r] * d_phi_da[c]);
                }
            }
        }
    }
}

/// The mortar row of every node of the faces `selected` (indices into
/// `faces`) against `obstacle`, at the nodes' current `coordinates`: each
/// node's sums over the selected faces that hold it (complete where all
/// its faces are selected), as [`MortarRow`]s with no primary nodes (see
/// the module doc), keyed by mesh node; with their gradients or without
/// ([`Derivatives`]: the same values to the bit).
pub fn obstacle_rows(
    faces: &[SurfaceFace],
    selected: &[usize],
    coordinates: &[Vector3<f64>],
    obstacle: &impl Fn(&Vector3<f64>) -> Projection,
    derivatives: Derivatives,
) -> Result<BTreeMap<usize, MortarRow>, MortarError> {
    let mut rows = empty_rows(faces, selected, derivatives);
    for &e in selected {
        let face = &faces[e];
        let geometry = face.with_coordinates(coordinates)?;
        let integrals = face_obstacle_integrals(&geometry, obstacle, derivatives)?;
        for (j, &node) in face.nodes.iter().enumerate() {
            if let Some(row) = rows.get_mut(&node) {
                scatter(row, &face.nodes, &integrals, j);
            }
        }
    }
    for row in rows.values_mut() {
        finish_normal(row);
    }
    Ok(rows)
}

/// The rows of [`obstacle_rows`] without their gradients against a
/// plane, in closed form: on a flat obstacle `∫ Φ_j N_k dA = D_j R_jk`
/// (module doc), so `g̃_j = D_j g(x̃_j)` and `L_jk = D_j R_jk n`, with
/// `D_j` the sum of the selected faces' `∫ Ñ_j dA`
/// ([`node_integrals`](super::dual_basis::node_integrals), read from `integrals` where a face is where they
/// were taken); no dual basis and no projection per face point.
/// The same rows as the integrated ones to round-off (the lever's entries
/// off `R_j`, round-off there, are zero here); `plane` the plane's
/// projection (`g` affine, `n` constant). A degenerate face is the
/// error [`DualBasis::of_face`] gives.
pub fn plane_rows(
    faces: &[SurfaceFace],
    integrals: &FaceIntegrals,
    selected: &[usize],
    coordinates: &[Vector3<f64>],
    plane: &impl Fn(&Vector3<f64>) -> Projection,
) -> Result<BTreeMap<usize, MortarRow>, MortarError> {
    let mut rows = empty_rows(faces, selected, Derivatives::Without);
    for &e in selected {
        let face = &faces[e];
        let integrals = integrals.at(faces, e, coordinates)?;
        positive_integrals(&integrals)?;
        for (&node, d) in face.nodes.iter().zip(integrals) {
            if let Some(row) = rows.get_mut(&node) {
                row.d += d;
            }
        }
    }
    for row in rows.values_mut() {
        let x = row
            .transformation
            .iter()
            .map(|&(k, r)| r * coordinates[k])
            .sum();
        let at = plane(&x);
        row.weighted_gap = row.d * at.gap;
        for &(k, r) in &row.transformation {
            let a = 3 * row.nodes.partition_point(|m| *m < k);
            for i in 0..3 {
                row.lever[a + i] -= row.d * r * at.normal[i];
            }
        }
        finish_normal(row);
    }
    Ok(rows)
}

/// Every node of the faces `selected` with its row over the nodes of its
/// selected faces (sorted), every sum zero, `x̃_j`'s transformation from
/// the first selected face that holds it ([`empty_row`]).
fn empty_rows(
    faces: &[SurfaceFace],
    selected: &[usize],
    derivatives: Derivatives,
) -> BTreeMap<usize, MortarRow> {
    let mut coupled: BTreeMap<usize, (usize, Vec<usize>)> = BTreeMap::new();
    for &e in selected {
        for &j in &faces[e].nodes {
            let entry = coupled.entry(j).or_insert((e, Vec::new()));
            entry.1.extend(&faces[e].nodes);
        }
    }
    coupled
        .into_iter()
        .map(|(j, (e, mut nodes))| {
            nodes.sort_unstable();
            nodes.dedup();
            let transformation = super::rows::transformation(&faces[e], j);
            (j, empty_row(j, nodes, transformation, derivatives))
        })
        .collect()
}

/// A row of `node` over `nodes` with every sum zero, `x̃_j`'s
/// `transformation` from a face holding it; its gradients empty
/// [`Derivatives::Without`].
fn empty_row(
    node: usize,
    nodes: Vec<usize>,
    transformation: Vec<(usize, f64)>,
    derivatives: Derivatives,
) -> MortarRow {
    let size = 3 * nodes.len();
    let columns = if derivatives == Derivatives::With {
        size
    } else {
        0
    };
    MortarRow {
        node,
        nodes,
        weighted_gap: 0.0,
        weighted_gap_gradient: DVector::zeros(columns),
        d: 0.0,
        d_gradient: DVector::zeros(columns),
        m: Vec::new(),
        m_gradients: Vec::new(),
        normal: Vector3::zeros(),
        normal_gradient: DMatrix::zeros(3, columns),
        lever: DVector::zeros(size),
        lever_gradient: DMatrix::zeros(columns, columns),
        transformation,
    }
}

/// Adds face node `j`'s integrals to its row (`b = −L`, `∂b = −∂L`).
fn scatter(row: &mut MortarRow, face_nodes: &[usize], f: &FaceObstacleIntegrals, j: usize) {
    let at: Vec<usize> = face_nodes
        .iter()
        .map(|n| 3 * row.nodes.partition_point(|m| m < n))
        .collect();
    row.d += f.d[j];
    row.weighted_gap += f.weighted_gap[j];
    let with = !f.lever_gradient.is_empty();
    for (a, &ra) in at.iter().enumerate() {
        for r in 0..3 {
            let fa = 3 * a + r;
            row.lever[ra + r] -= f.lever[(j, fa)];
            if !with {
                continue;
            }
            row.d_gradient[ra + r] += f.d_gradient[(j, fa)];
            row.weighted_gap_gradient[ra + r] += f.weighted_gap_gradient[(j, fa)];
            for (b, &rb) in at.iter().enumerate() {
                for s in 0..3 {
                    row.lever_gradient[(ra + r, rb + s)] -= f.lever_gradient[j][(fa, 3 * b + s)];
                }
            }
        }
    }
}

/// `n_j = −w_j/|w_j|` from the summed lever (`w_j = Σ_k L_jk = −Σ_k b_jk`)
/// and, where the row has derivatives, `∂n_j = −(I − n̄ n̄ᵀ) ∂w_j / |w_j|`.
fn finish_normal(row: &mut MortarRow) {
    let size = row.lever.len();
    let columns = row.normal_gradient.ncols();
    let mut w = Vector3::zeros();
    let mut dw = DMatrix::zeros(3, columns);
    for a in 0..size / 3 {
        for r in 0..3 {
            w[r] -= row.lever[3 * a + r];
            for c in 0..columns {
                dw[(r, c)] -= row.lever_gradient[(3 * a + r, c)];
            }
        }
    }
    if w.norm() == 0.0 {
        return;
    }
    row.normal = -w.normalize();
    for c in 0..columns {
        let dn = unit_derivative(&w, &Vector3::new(dw[(0, c)], dw[(1, c)], dw[(2, c)]));
        row.normal_gradient.set_column(c, &(-dn));
    }
}

/// Whether `node`'s transformed point on `face` (which holds it) is the
/// node itself, `x̃_j = x_j` (linear faces, the corners of quadratic
/// ones): then against a plane its lever `L_jk = D_j R_jk n` lies on the
/// node alone in every configuration.
pub fn transforms_to_itself(face: &SurfaceFace, node: usize) -> bool {
    super::rows::transformation(face, node) == [(node, 1.0)]
}

/// The transformed point `x̃_j = Σ_k R_jk x_k` of `node` on `face` (which
/// holds it) at `coordinates`. Against a plane, whose gap `g` is affine,
/// biorthogonality gives `g̃_j = Σ_k g(x_k) ∫ Φ_j N_k dA = D_j g(x̃_j)`
/// (module docs), so the normalised gap is `g̃_j / D_j = g(x̃_j)` in
/// closed form, with no integration.
pub fn transformed_point(
    face: &SurfaceFace,
    node: usize,
    coordinates: &[Vector3<f64>],
) -> Vector3<f64> {
    transformed_position(face, node, |k| coordinates[k])
}

/// `x̃_j = Σ_k R_jk x_k` of `node` on `face` (which holds it), `position`
/// giving `x_k` of mesh node `k`.
pub fn transformed_position(
    face: &SurfaceFace,
    node: usize,
    position: impl Fn(usize) -> Vector3<f64>,
) -> Vector3<f64> {
    super::rows::transformation(face, node)
        .iter()
        .map(|&(k, r)| r * position(k))
        .sum()
}
