//! The dual (biorthogonal) Lagrange-multiplier basis of a secondary face
//! (Wohlmuth, SINUM 38, 2000; Popp, Gee & Wall, IJNME 79, 2009, eq. 18–20):
//!
//! ```text
//! Φ_j = Σ_k a_jk Ñ_k,   A_e = D_e M_e⁻¹,
//! (D_e)_jk = δ_jk ∫_e Ñ_k dA,   (M_e)_jk = ∫_e Ñ_j Ñ_k dA,
//! ```
//!
//! on the face's current coordinates, so that
//! `∫_e Φ_j Ñ_k dA = δ_jk ∫_e Ñ_k dA` and `Σ_j Φ_j = 1`. `Ñ` are the mortar
//! shape functions of [`super::quadratic`] (the Lagrange functions on Tri3
//! and Quad4). On a flat Tri3, `Φ_j = 3N_j − N_k − N_l`; on a
//! parallelogram Quad4, `Φ_1 = 4N_1 − 2N_2 + N_3 − 2N_4` and cyclic.

use nalgebra::{DMatrix, DVector, Vector3};

use super::face::{FaceShape, MortarFace, SurfaceFace};
use super::quadratic;
use super::MortarError;

/// The coefficients `A_e` of a secondary face's dual basis.
#[derive(Clone, Debug, PartialEq)]
pub struct DualBasis {
    pub shape: FaceShape,
    /// `a_jk`: row `j` is `Φ_j` in the mortar shape functions `Ñ_k`.
    pub coefficients: DMatrix<f64>,
}

impl DualBasis {
    /// `A_e = D_e M_e⁻¹` on the face's current coordinates, with the face
    /// rule of [`FaceShape::quadrature`]. A degenerate face (zero area or
    /// a non-positive `∫ Ñ_j`) is an error.
    pub fn of_face(face: &MortarFace) -> Result<DualBasis, MortarError> {
        let (mass, integrals) = face_matrices(face, area_element(face));
        let area = positive_integrals(&integrals)?;
        let inverse = mass
            .try_inverse()
            .ok_or_else(|| MortarError::DegenerateFace {
                what: format!("the face's mass matrix is singular (area {area:e})"),
            })?;
        let coefficients =
            DMatrix::from_diagonal(&nalgebra::DVector::from_vec(integrals)) * inverse;
        Ok(DualBasis {
            shape: face.shape,
            coefficients,
        })
    }

    /// The directional derivative of `A_e` for node increments `δx_a`
    /// (Popp et al. 2010, §5.1): `δA = (δD − A δM) M⁻¹`, where `δD` and
    /// `δM` are `D_e` and `M_e` with the area element `|a|` replaced by its
    /// derivative `δ|a| = (a/|a|)·δa`.
    pub fn derivative(
        &self,
        face: &MortarFace,
        dx: &[Vector3<f64>],
    ) -> Result<DMatrix<f64>, MortarError> {
        let (mass, _) = face_matrices(face, area_element(face));
        let (d_mass, d_integrals) = face_matrices(face, |xi| {
            face.unit_normal(xi)
                .dot(&face.area_normal_derivative(xi, dx))
        });
        let inverse = mass
            .try_inverse()
            .ok_or_else(|| MortarError::DegenerateFace {
                what: "the face's mass matrix is singular".to_string(),
            })?;
        let d_d = DMatrix::from_diagonal(&DVector::from_vec(d_integrals));
        Ok((d_d - &self.coefficients * d_mass) * inverse)
    }

    /// `Φ_j = Σ_k a_jk Ñ_k` from the mortar shape function values `Ñ`.
    pub fn values_from(&self, mortar_values: &[f64]) -> Vec<f64> {
        let n = mortar_values.len();
        (0..n)
            .map(|j| {
                (0..n)
                    .map(|k| self.coefficients[(j, k)] * mortar_values[k])
                    .sum()
            })
            .collect()
    }

    /// `Φ_j(ξ)` at a reference point of the face.
    pub fn values(&self, xi: [f64; 2]) -> Vec<f64> {
        self.values_from(&quadratic::mortar_values(self.shape, xi))
    }
}

/// `∫_e Ñ_j dA` of every node `j` of a face on its current coordinates
/// (the diagonal of `D_e`, with the face rule of [`FaceShape::quadrature`]):
/// a node's `D_j` where the primary surface covers all of its faces.
pub fn node_integrals(face: &MortarFace) -> Vec<f64> {
    face_matrices(face, area_element(face)).1
}

/// The face's area `Σ_j ∫ Ñ_j dA` from its nodes' `integrals`, each of
/// which must be positive (beyond 1e-12 of the area): else the face is
/// degenerate.
pub fn positive_integrals(integrals: &[f64]) -> Result<f64, MortarError> {
    let area: f64 = integrals.iter().sum();
    if integrals.iter().any(|i| *i <= 1e-12 * area.abs()) {
        return Err(MortarError::DegenerateFace {
            what: format!("∫ Ñ_j dA = {integrals:?} must all be positive"),
        });
    }
    Ok(area)
}

/// The area element `|a(ξ)|` of a face.
fn area_element(face: &MortarFace) -> impl Fn([f64; 2]) -> f64 + '_ {
    |xi| face.area_normal(xi).norm()
}

/// `(M_e)_jk = Σ_q w_q Ñ_j Ñ_k α(ξ_q)` and `(∫ Ñ_j)_j = Σ_q w_q Ñ_j α(ξ_q)`
/// on the face rule, for an area element `α(ξ)` (`|a|`, or its derivative).
fn face_matrices(
    face: &MortarFace,
    area_element: impl Fn([f64; 2]) -> f64,
) -> (DMatrix<f64>, Vec<f64>) {
    let n = face.shape.node_count();
    let (points, weights) = face.shape.quadrature();
    let mut mass = DMatrix::<f64>::zeros(n, n);
    let mut integrals = vec![0.0; n];
    for (xi, w) in points.iter().zip(&weights) {
        let da = w * area_element(*xi);
        let nt = quadratic::mortar_values(face.shape, *xi);
        for j in 0..n {
            integrals[j] += nt[j] * da;
            for k in 0..n {
                mass[(j, k)] += nt[j] * nt[k] * da;
            }
        }
    }
    (mass, integrals)
}

/// The faces of a surface with their coordinates, and their dual bases.
pub fn faces_and_duals(
    faces: &[SurfaceFace],
    coordinates: &[Vector3<f64>],
) -> Result<(Vec<MortarFace>, Vec<DualBasis>), MortarError> {
    let faces = faces
        .iter()
        .map(|f| f.with_coordinates(coordinates))
        .collect::<Result<Vec<_>, _>>()?;
    let duals = faces
        .iter()
        .map(DualBasis::of_face)
        .collect::<Result<Vec<_>, _>>()?;
    Ok((faces, duals))
}
