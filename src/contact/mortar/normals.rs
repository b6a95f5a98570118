//! Averaged outward nodal normals of a contact surface and their
//! directional derivatives (Popp, Gitterle, Gee & Wall 2010, §3.2 and
//! §5.2):
//!
//! ```text
//! s_j = Σ_{e ∋ j} n_e(ξ_j),   n_j = s_j / |s_j|,
//! δn_e = (I − n_e n_eᵀ) δa_e / |a_e|,   δn_j = (I − n_j n_jᵀ) δs_j / |s_j|,
//! ```
//!
//! with `ξ_j` the node's reference position in face `e`, `a_e` the face's
//! area normal there and `δa_e` its derivative ([`MortarFace::area_normal_derivative`]).

use std::collections::BTreeMap;

use nalgebra::{DMatrix, Vector3};

use super::face::{gather, MortarFace, SurfaceFace};
use super::MortarError;

/// The averaged outward nodal normals `n_j` of a surface: the unit face
/// normals at each node's reference position, summed over the faces that
/// hold the node, normalised.
pub fn nodal_normals(
    faces: &[SurfaceFace],
    coordinates: &[Vector3<f64>],
) -> Result<BTreeMap<usize, Vector3<f64>>, MortarError> {
    let mut sums: BTreeMap<usize, Vector3<f64>> = BTreeMap::new();
    for face in faces {
        let f = face.with_coordinates(coordinates)?;
        for (node, xi) in face.nodes.iter().zip(face.shape.reference_nodes()) {
            *sums.entry(*node).or_insert_with(Vector3::zeros) += f.unit_normal(*xi);
        }
    }
    Ok(sums.into_iter().map(|(n, s)| (n, s.normalize())).collect())
}

/// The directional derivatives `δn_j` of the averaged nodal normals for
/// increments `dx` of all coordinates (indexed like `coordinates`).
pub fn nodal_normal_derivatives(
    faces: &[SurfaceFace],
    coordinates: &[Vector3<f64>],
    dx: &[Vector3<f64>],
) -> Result<BTreeMap<usize, Vector3<f64>>, MortarError> {
    let mut sums: BTreeMap<usize, (Vector3<f64>, Vector3<f64>)> = BTreeMap::new();
    for face in faces {
        let f = face.with_coordinates(coordinates)?;
        let df: Vec<Vector3<f64>> = face.nodes.iter().map(|&n| dx[n]).collect();
        for (node, xi) in face.nodes.iter().zip(face.shape.reference_nodes()) {
            let (s, ds) = sums
                .entry(*node)
                .or_insert((Vector3::zeros(), Vector3::zeros()));
            let (n, dn) = unit_normal_derivative(&f, *xi, &df);
            *s += n;
            *ds += dn;
        }
    }
    Ok(sums
        .into_iter()
        .map(|(node, (s, ds))| (node, unit_derivative(&s, &ds)))
        .collect())
}

/// `n_e(ξ)` and `δn_e(ξ) = (I − n nᵀ) δa / |a|`.
fn unit_normal_derivative(
    face: &MortarFace,
    xi: [f64; 2],
    dx: &[Vector3<f64>],
) -> (Vector3<f64>, Vector3<f64>) {
    let a = face.area_normal(xi);
    let n = a / a.norm();
    (n, unit_derivative(&a, &face.area_normal_derivative(xi, dx)))
}

/// `δ(v/|v|) = (I − u uᵀ) δv / |v|` with `u = v/|v|`.
pub(super) fn unit_derivative(v: &Vector3<f64>, dv: &Vector3<f64>) -> Vector3<f64> {
    let u = v / v.norm();
    (dv - u * u.dot(dv)) / v.norm()
}

/// A node's averaged normal `n_j` and its gradient `∂n_j/∂x` (3 × 3k,
/// node-major over `nodes`, the sorted nodes of the faces that hold it).
#[derive(Clone, Debug, PartialEq)]
pub struct NodalNormalGradient {
    pub normal: Vector3<f64>,
    pub nodes: Vec<usize>,
    pub gradient: DMatrix<f64>,
}

/// `n_j` and `∂n_j/∂x` of one node: [`nodal_normal_derivatives`] along each
/// unit increment of the nodes of `faces`, the surface's faces that hold
/// `node`.
pub fn nodal_normal_gradient(
    faces: &[&SurfaceFace],
    coordinates: &[Vector3<f64>],
    node: usize,
) -> Result<NodalNormalGradient, MortarError> {
    let mut nodes: Vec<usize> = faces.iter().flat_map(|f| f.nodes.iter().copied()).collect();
    nodes.sort_unstable();
    nodes.dedup();
    let local = |n: usize| nodes.partition_point(|&m| m < n);
    let local_faces: Vec<SurfaceFace> = faces
        .iter()
        .map(|f| SurfaceFace {
            shape: f.shape,
            nodes: f.nodes.iter().map(|&n| local(n)).collect(),
        })
        .collect();
    let local_coordinates = gather(&nodes, coordinates)?;
    let j = nodes
        .binary_search(&node)
        .map_err(|_| MortarError::NotOnFaces { node })?;
    let normal = nodal_normals(&local_faces, &local_coordinates)?[&j];
    let mut gradient = DMatrix::zeros(3, 3 * nodes.len());
    for column in 0..3 * nodes.len() {
        let mut dx = vec![Vector3::zeros(); nodes.len()];
        dx[column / 3][column % 3] = 1.0;
        let dn = nodal_normal_derivatives(&local_faces, &local_coordinates, &dx)?[&j];
        gradient.set_column(column, &dn);
    }
    Ok(NodalNormalGradient {
        normal,
        nodes,
        gradient,
    })
}
