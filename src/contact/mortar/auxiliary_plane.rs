//! The auxiliary plane of a secondary face (Puso & Laursen, CMAME 193,
//! 2004; Popp, Gitterle, Gee & Wall, IJNME 83, 2010, §4.2): through the
//! face's centre `x₀ = x(ξ_c)`, normal to its unit normal there
//! `n₀ = a(ξ_c)/|a(ξ_c)|`, with the in-plane frame
//! `e₁ = (x_,ξ − (x_,ξ·n₀) n₀)/|…|` and `e₂ = n₀ × e₁`. A point `x` has
//! the plane coordinates `p = ((x − x₀)·e₁, (x − x₀)·e₂)`: its projection
//! along `n₀`.
//!
//! The directional derivatives for increments `δx_a` of the secondary
//! face's nodes (Popp et al. 2010, §5.2, the auxiliary plane's centre and
//! normal; the frame by the same rule):
//!
//! ```text
//! δx₀ = Σ_a N_a(ξ_c) δx_a,            δn₀ = (I − n₀n₀ᵀ) δa / |a|,
//! u = t − (t·n₀) n₀,  δu = δt − (δt·n₀ + t·δn₀) n₀ − (t·n₀) δn₀,
//! δe₁ = (I − e₁e₁ᵀ) δu / |u|,         δe₂ = δn₀ × e₁ + n₀ × δe₁,
//! δp_i = (δx − δx₀)·e_i + (x − x₀)·δe_i.
//! ```

use nalgebra::Vector3;

use super::face::MortarFace;
use super::normals::unit_derivative;

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

/// The directional derivative of an [`AuxiliaryPlane`] (see the module doc).
#[derive(Clone, Debug, PartialEq)]
pub struct PlaneDerivative {
    pub centre: Vector3<f64>,
    pub normal: Vector3<f64>,
    pub frame: [Vector3<f64>; 2],
}

impl AuxiliaryPlane {
    /// `(δx₀, δn₀, δe₁, δe₂)` for increments `dx` of the face's nodes.
    pub fn derivative(&self, face: &MortarFace, dx: &[Vector3<f64>]) -> PlaneDerivative {
        let xi = face.shape.centre();
        let a = face.area_normal(xi);
        let dn = unit_derivative(&a, &face.area_normal_derivative(xi, dx));
        let (n, t) = (self.normal, face.tangents(xi)[0]);
        let dt = face.tangents_derivative(xi, dx)[0];
        let u = t - n * t.dot(&n);
        let du = dt - n * (dt.dot(&n) + t.dot(&dn)) - dn * t.dot(&n);
        let de1 = unit_derivative(&u, &du);
        PlaneDerivative {
            centre: face.point_derivative(xi, dx),
            normal: dn,
            frame: [de1, dn.cross(&self.frame[0]) + n.cross(&de1)],
        }
    }

    /// `δp_i = (δx − δx₀)·e_i + (x − x₀)·δe_i`: the derivative of
    /// [`AuxiliaryPlane::local_point`] for a point moving by `dx_point`.
    pub fn local_point_derivative(
        &self,
        d: &PlaneDerivative,
        x: &Vector3<f64>,
        dx_point: &Vector3<f64>,
    ) -> [f64; 2] {
        let (r, dr) = (x - self.centre, dx_point - d.centre);
        [0, 1].map(|i| dr.dot(&self.frame[i]) + r.dot(&d.frame[i]))
    }

    /// `δx = δx₀ + Σ_i (δp_i e_i + p_i δe_i)`: the derivative of
    /// [`AuxiliaryPlane::spatial_point`].
    pub fn spatial_point_derivative(
        &self,
        d: &PlaneDerivative,
        p: [f64; 2],
        dp: [f64; 2],
    ) -> Vector3<f64> {
        d.centre
            + self.frame[0] * dp[0]
            + d.frame[0] * p[0]
            + self.frame[1] * dp[1]
            + d.frame[1] * p[1]
    }
}
