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
/// a node's `D_j` where the primary surface covers all of its faces. On a
/// Tri3 face (flat, `Ñ_j = N_j` linear) in closed form, `A_e/3` each with
/// `A_e = ½|(x₂ − x₁) × (x₃ − x₁)|`: the face rule's value to round-off,
/// without its 25 points.
pub fn node_integrals(face: &MortarFace) -> Vec<f64> {
    if let (FaceShape::Tri3, [x1, x2, x3]) = (face.shape, face.coordinates.as_slice()) {
        return vec![(x2 - x1).cross(&(x3 - x1)).norm() / 6.0; 3];
    }
    face_matrices(face, area_element(face)).1
}

/// Each face's [`node_integrals`] in one configuration (the reference
/// one, taken at set-up for the nodes' areas), with its nodes'
/// coordinates there: a face found at those coordinates again (the
/// condensed path's columns at `u = 0`) is read, not integrated again —
/// the same numbers to the bit, since the integrals are a function of
/// the coordinates alone. Shared by the clones of its surfaces.
#[derive(Clone, Debug, Default)]
pub struct FaceIntegrals(std::sync::Arc<Vec<Option<TakenAt>>>);

/// A face's node coordinates and its [`node_integrals`] there.
type TakenAt = (Vec<Vector3<f64>>, Vec<f64>);

impl FaceIntegrals {
    /// Every face's integrals at `coordinates` (none for a face that
    /// cannot be formed there).
    pub fn of(faces: &[SurfaceFace], coordinates: &[Vector3<f64>]) -> Self {
        let taken = |face: &SurfaceFace| {
            let geometry = face.with_coordinates(coordinates).ok()?;
            let integrals = node_integrals(&geometry);
            Some((geometry.coordinates, integrals))
        };
        Self(std::sync::Arc::new(faces.iter().map(taken).collect()))
    }

    /// [`node_integrals`] of face `e` of `faces` (those this was taken
    /// of) at `coordinates`: the stored ones where each of its nodes is
    /// where they were taken (bit for bit), else integrated.
    pub fn at(
        &self,
        faces: &[SurfaceFace],
        e: usize,
        coordinates: &[Vector3<f64>],
    ) -> Result<Vec<f64>, MortarError> {
        let face = &faces[e];
        if let Some(Some((at, integrals))) = self.0.get(e) {
            let bits = |v: &Vector3<f64>| v.map(f64::to_bits);
            let here = |(&n, p): (&usize, &Vector3<f64>)| {
                coordinates.get(n).is_some_and(|x| bits(x) == bits(p))
            };
            if face.nodes.iter().zip(at).all(here) {
                return Ok(integrals.clone());
            }
        }
        Ok(node_integrals(&face.with_coordinates(coordinates)?))
    }
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
    for (xi, w) in points.iter().zip(weights) {
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A skewed, tilted Tri3 and a warped Quad4 face.
    fn faces() -> Vec<SurfaceFace> {
        vec![
            SurfaceFace {
                shape: FaceShape::Tri3,
                nodes: vec![0, 1, 2],
            },
            SurfaceFace {
                shape: FaceShape::Quad4,
                nodes: vec![0, 1, 3, 2],
            },
        ]
    }

    fn coordinates() -> Vec<Vector3<f64>> {
        vec![
            Vector3::new(0.1, -0.2, 0.3),
            Vector3::new(1.3, 0.1, 0.5),
            Vector3::new(0.4, 0.9, -0.2),
            Vector3::new(1.5, 1.2, 0.4),
        ]
    }

    /// On a Tri3 face the closed form `A_e/3` is the face rule's
    /// `∫ N_j dA` to round-off (1e-14 of the area), and the three sum to
    /// the face's area (half the cross product's norm, computed apart).
    #[test]
    fn tri3_node_integrals_are_the_face_rule() {
        let xs = coordinates();
        let face = faces()[0].with_coordinates(&xs).unwrap();
        let closed = node_integrals(&face);
        let rule = face_matrices(&face, area_element(&face)).1;
        let area = 0.5 * (xs[1] - xs[0]).cross(&(xs[2] - xs[0])).norm();
        for (c, r) in closed.iter().zip(&rule) {
            assert!((c - r).abs() <= 1e-14 * area, "{closed:?} against {rule:?}");
        }
        let sum: f64 = closed.iter().sum();
        assert!((sum - area).abs() <= 1e-14 * area, "{sum} against {area}");
    }

    /// [`FaceIntegrals`] reads a face's stored integrals only where each of
    /// its nodes is where they were taken: at those coordinates the stored
    /// numbers (equal to integrating there), and once one node moved, the
    /// integrals at the new coordinates, not the stale ones.
    #[test]
    fn face_integrals_are_read_only_where_taken() {
        let faces = faces();
        let xs = coordinates();
        let taken = FaceIntegrals::of(&faces, &xs);
        let mut moved = xs.clone();
        moved[2].z += 0.25;
        for (e, face) in faces.iter().enumerate() {
            let here = node_integrals(&face.with_coordinates(&xs).unwrap());
            let there = node_integrals(&face.with_coordinates(&moved).unwrap());
            assert_ne!(here, there, "face {e}: the move changes its integrals");
            assert_eq!(taken.at(&faces, e, &xs).unwrap(), here, "face {e}");
            assert_eq!(taken.at(&faces, e, &moved).unwrap(), there, "face {e}");
        }
        let none = FaceIntegrals::default();
        assert_eq!(
            none.at(&faces, 1, &moved).unwrap(),
            node_integrals(&faces[1].with_coordinates(&moved).unwrap())
        );
    }
}
