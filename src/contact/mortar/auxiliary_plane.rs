//! The auxiliary plane of a secondary face (Puso & Laursen, CMAME 193,
//! 2004; Popp, Gitterle, Gee & Wall, IJNME 83, 2010, §4.2): through the
//! face's centre `x₀ = x(ξ_c)`, normal to its unit normal there
//! `n₀ = a(ξ_c)/|a(ξ_c)|`, with the in-plane frame
//! `e₁ = (x_,ξ − (x_,ξ·n₀) n₀)/|…|` and `e₂ = n₀ × e₁`. A point `x` has
//! the plane coordinates `p = ((x − x₀)·e₁, (x − x₀)·e₂)`: its projection
//! along `n₀`.

use nalgebra::Vector3;

use super::face::MortarFace;

/// A plane with its centre, unit normal and orthonormal in-plane frame.
#[derive(Clone, Debug, PartialEq)]
pub struct AuxiliaryPlane {
    pub centre: Vector3<f64>,
    pub normal: Vector3<f64>,
    pub frame: [Vector3<f64>; 2],
}

impl AuxiliaryPlane {
    /// The auxiliary plane of a secondary face at its reference centre.
    pub fn of_face(face: &MortarFace) -> AuxiliaryPlane {
        let centre_xi = face.shape.centre();
        let normal = face.unit_normal(centre_xi);
        let t = face.tangents(centre_xi)[0];
        let e1 = (t - normal * t.dot(&normal)).normalize();
        AuxiliaryPlane {
            centre: face.point(centre_xi),
            normal,
            frame: [e1, normal.cross(&e1)],
        }
    }

    /// The plane coordinates `p = ((x − x₀)·e₁, (x − x₀)·e₂)` of a spatial
    /// point (its projection along `n₀`).
    pub fn local_point(&self, x: &Vector3<f64>) -> [f64; 2] {
        let d = x - self.centre;
        [d.dot(&self.frame[0]), d.dot(&self.frame[1])]
    }

    /// The spatial point `x₀ + p₁ e₁ + p₂ e₂` of plane coordinates `p`.
    pub fn spatial_point(&self, p: [f64; 2]) -> Vector3<f64> {
        self.centre + self.frame[0] * p[0] + self.frame[1] * p[1]
    }
}
