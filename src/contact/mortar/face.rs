//! A contact face as the mortar kernels see it: its shape (Tri3, Quad4,
//! Tri6, Quad8 in Gmsh/VTK node order) and its nodes' current coordinates,
//! with the map `x(ξ) = Σ_a N_a(ξ) x_a`, its tangents `x_,ξ`, `x_,η` and
//! its area normal `a = x_,ξ × x_,η` (outward when the nodes run
//! counter-clockwise seen from outside).

use nalgebra::Vector3;
use smallvec::SmallVec;

use super::MortarError;
use crate::fem::{quadrature, shape};

/// One value per node of a face (at most eight: Quad8), kept on the stack.
pub type FaceValues<T> = SmallVec<[T; 8]>;

/// The shape of a contact face: 3, 4, 6 or 8 nodes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FaceShape {
    Tri3,
    Quad4,
    Tri6,
    Quad8,
}

/// Reference nodes of the triangles (unit triangle, corners then mid-sides).
const TRI_NODES: [[f64; 2]; 6] = [
    [0.0, 0.0],
    [1.0, 0.0],
    [0.0, 1.0],
    [0.5, 0.0],
    [0.5, 0.5],
    [0.0, 0.5],
];

/// Reference nodes of the quadrilaterals ([−1, 1]², corners then mid-sides).
const QUAD_NODES: [[f64; 2]; 8] = [
    [-1.0, -1.0],
    [1.0, -1.0],
    [1.0, 1.0],
    [-1.0, 1.0],
    [0.0, -1.0],
    [1.0, 0.0],
    [0.0, 1.0],
    [-1.0, 0.0],
];

/// Points per direction of the face rule used for `∫_e N_j N_k dA`:
/// 5 (Gauss–Legendre degree 9 per direction on quadrilaterals, collapsed
/// rule of total degree 8 on triangles), exact for every planar face of the
/// four shapes.
const FACE_RULE_POINTS: usize = 5;

impl FaceShape {
    /// Number of nodes: 3, 4, 6 or 8.
    pub fn node_count(self) -> usize {
        match self {
            FaceShape::Tri3 => 3,
            FaceShape::Quad4 => 4,
            FaceShape::Tri6 => 6,
            FaceShape::Quad8 => 8,
        }
    }

    /// Number of corners: 3 or 4 (the corners come first in the node order).
    pub fn corner_count(self) -> usize {
        match self {
            FaceShape::Tri3 | FaceShape::Tri6 => 3,
            FaceShape::Quad4 | FaceShape::Quad8 => 4,
        }
    }

    /// Whether the face has mid-side nodes.
    pub fn is_quadratic(self) -> bool {
        matches!(self, FaceShape::Tri6 | FaceShape::Quad8)
    }

    /// Whether the face is a triangle (reference cell the unit triangle;
    /// otherwise [−1, 1]²).
    pub fn is_triangle(self) -> bool {
        self.corner_count() == 3
    }

    /// Whether `x(ξ) = Σ_a N_a(ξ) x_a` is affine in `ξ` whatever the
    /// nodes (Tri3): its gradients `N_a,ξ` are constants, so the tangents
    /// are the same at every `ξ`, to the bit.
    pub fn is_affine(self) -> bool {
        self == FaceShape::Tri3
    }

    /// The reference coordinates of the nodes, in node order.
    pub fn reference_nodes(self) -> &'static [[f64; 2]] {
        let n = self.node_count();
        if self.is_triangle() {
            &TRI_NODES[..n]
        } else {
            &QUAD_NODES[..n]
        }
    }

    /// The reference centre: `(⅓, ⅓)` on triangles, `(0, 0)` on quadrilaterals.
    pub fn centre(self) -> [f64; 2] {
        if self.is_triangle() {
            [1.0 / 3.0; 2]
        } else {
            [0.0; 2]
        }
    }

    /// Shape function values `N_a(ξ)` (on the stack: at most eight, and
    /// asked for at every projection step and every derivative direction,
    /// where a heap vector's allocation and release were 12 % of a
    /// condensed mortar run's samples).
    pub fn values(self, xi: [f64; 2]) -> FaceValues<f64> {
        match self {
            FaceShape::Tri3 => FaceValues::from_slice(&shape::tri3_values(&xi)),
            FaceShape::Quad4 => FaceValues::from_slice(&shape::quad4_values(&xi)),
            FaceShape::Tri6 => FaceValues::from_slice(&shape::tri6_values(&xi)),
            FaceShape::Quad8 => FaceValues::from_slice(&shape::quad8_values(&xi)),
        }
    }

    /// Reference gradients `∂N_a/∂ξ` (on the stack, as [`Self::values`]).
    pub fn gradients(self, xi: [f64; 2]) -> FaceValues<[f64; 2]> {
        match self {
            FaceShape::Tri3 => FaceValues::from_slice(&shape::tri3_gradients(&xi)),
            FaceShape::Quad4 => FaceValues::from_slice(&shape::quad4_gradients(&xi)),
            FaceShape::Tri6 => FaceValues::from_slice(&shape::tri6_gradients(&xi)),
            FaceShape::Quad8 => FaceValues::from_slice(&shape::quad8_gradients(&xi)),
        }
    }

    /// The face rule: points and weights on the reference cell, computed
    /// once per cell shape (the Gauss–Legendre roots by Newton's method
    /// were 4 % of a condensed mortar run's samples, asked for per face
    /// and per dual-basis derivative), lent, not copied.
    pub fn quadrature(self) -> &'static (Vec<[f64; 2]>, Vec<f64>) {
        type Rule = (Vec<[f64; 2]>, Vec<f64>);
        static TRIANGLE: std::sync::OnceLock<Rule> = std::sync::OnceLock::new();
        static QUADRILATERAL: std::sync::OnceLock<Rule> = std::sync::OnceLock::new();
        if self.is_triangle() {
            TRIANGLE.get_or_init(|| quadrature::triangle_collapsed(FACE_RULE_POINTS))
        } else {
            QUADRILATERAL.get_or_init(|| quadrature::quadrilateral_any(FACE_RULE_POINTS))
        }
    }

    /// Whether `ξ` lies in the reference cell, up to `tol`.
    pub fn contains(self, xi: [f64; 2], tol: f64) -> bool {
        if self.is_triangle() {
            xi[0] >= -tol && xi[1] >= -tol && xi[0] + xi[1] <= 1.0 + tol
        } else {
            xi[0].abs() <= 1.0 + tol && xi[1].abs() <= 1.0 + tol
        }
    }
}

/// A face with its nodes' current coordinates.
#[derive(Clone, Debug, PartialEq)]
pub struct MortarFace {
    pub shape: FaceShape,
    pub coordinates: Vec<Vector3<f64>>,
}

impl MortarFace {
    /// A face of `shape` through `coordinates` (one per node, node order).
    pub fn new(shape: FaceShape, coordinates: Vec<Vector3<f64>>) -> Result<Self, MortarError> {
        if coordinates.len() != shape.node_count() {
            return Err(MortarError::NodeCount {
                shape,
                given: coordinates.len(),
            });
        }
        Ok(MortarFace { shape, coordinates })
    }

    /// The spatial point `x(ξ) = Σ_a N_a(ξ) x_a`.
    pub fn point(&self, xi: [f64; 2]) -> Vector3<f64> {
        let n = self.shape.values(xi);
        self.coordinates.iter().zip(&n).map(|(x, n)| x * *n).sum()
    }

    /// The tangents `x_,ξ = Σ_a N_a,ξ x_a` and `x_,η = Σ_a N_a,η x_a`.
    pub fn tangents(&self, xi: [f64; 2]) -> [Vector3<f64>; 2] {
        let g = self.shape.gradients(xi);
        let mut t = [Vector3::zeros(); 2];
        for (x, g) in self.coordinates.iter().zip(&g) {
            t[0] += x * g[0];
            t[1] += x * g[1];
        }
        t
    }

    /// The area normal `a = x_,ξ × x_,η` (`|a|` is the area element).
    pub fn area_normal(&self, xi: [f64; 2]) -> Vector3<f64> {
        let [t1, t2] = self.tangents(xi);
        t1.cross(&t2)
    }

    /// The directional derivative of the area normal for node increments
    /// `δx_a`: `δa = δx_,ξ × x_,η + x_,ξ × δx_,η`, `δx_,ξ = Σ_a N_a,ξ δx_a`.
    pub fn area_normal_derivative(&self, xi: [f64; 2], dx: &[Vector3<f64>]) -> Vector3<f64> {
        let [t1, t2] = self.tangents(xi);
        let dt = self.tangents_derivative(xi, dx);
        dt[0].cross(&t2) + t1.cross(&dt[1])
    }

    /// The directional derivative of the tangents at a fixed `ξ` for node
    /// increments `δx_a`: `δx_,ξ = Σ_a N_a,ξ δx_a`, `δx_,η = Σ_a N_a,η δx_a`.
    pub fn tangents_derivative(&self, xi: [f64; 2], dx: &[Vector3<f64>]) -> [Vector3<f64>; 2] {
        let g = self.shape.gradients(xi);
        let mut dt = [Vector3::zeros(); 2];
        for (d, g) in dx.iter().zip(&g) {
            dt[0] += d * g[0];
            dt[1] += d * g[1];
        }
        dt
    }

    /// The directional derivative of `x(ξ)` at a fixed `ξ`: `Σ_a N_a(ξ) δx_a`.
    pub fn point_derivative(&self, xi: [f64; 2], dx: &[Vector3<f64>]) -> Vector3<f64> {
        let n = self.shape.values(xi);
        dx.iter().zip(&n).map(|(d, n)| d * *n).sum()
    }

    /// The derivative of the area normal along the reference coordinates,
    /// `∂a/∂ξ_k = x_,ξk × x_,η + x_,ξ × x_,ηk` (Popp et al. 2010, §5.3: the
    /// area element at a moving Gauss point), with the second derivatives
    /// `x_,ξk = Σ_a ∂²N_a/∂ξ∂ξ_k x_a` by central differences of the
    /// gradients. Those are exact up to round-off: the gradients of the four
    /// shapes are at most quadratic in each reference coordinate, for which
    /// the central difference is exact.
    pub fn area_normal_gradient(&self, xi: [f64; 2]) -> [Vector3<f64>; 2] {
        const STEP: f64 = 1e-3;
        [0, 1].map(|k| {
            let shift = |s: f64| {
                let mut p = xi;
                p[k] += s;
                self.tangents(p)
            };
            let (plus, minus) = (shift(STEP), shift(-STEP));
            let [t1, t2] = self.tangents(xi);
            let dt1 = (plus[0] - minus[0]) / (2.0 * STEP);
            let dt2 = (plus[1] - minus[1]) / (2.0 * STEP);
            dt1.cross(&t2) + t1.cross(&dt2)
        })
    }

    /// The unit normal `n = a / |a|`.
    pub fn unit_normal(&self, xi: [f64; 2]) -> Vector3<f64> {
        self.area_normal(xi).normalize()
    }

    /// The area `∫_e dA = Σ_q w_q |a(ξ_q)|` with the face rule.
    pub fn area(&self) -> f64 {
        let (points, weights) = self.shape.quadrature();
        points
            .iter()
            .zip(weights)
            .map(|(xi, w)| w * self.area_normal(*xi).norm())
            .sum()
    }

    /// The corner coordinates (the first 3 or 4 nodes).
    pub fn corners(&self) -> &[Vector3<f64>] {
        &self.coordinates[..self.shape.corner_count()]
    }
}

/// A face of a contact surface: its shape and its global node numbers.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SurfaceFace {
    pub shape: FaceShape,
    pub nodes: Vec<usize>,
}

impl SurfaceFace {
    /// The face with its nodes' coordinates taken from `coordinates`.
    pub fn with_coordinates(
        &self,
        coordinates: &[Vector3<f64>],
    ) -> Result<MortarFace, MortarError> {
        MortarFace::new(self.shape, gather(&self.nodes, coordinates)?)
    }
}

/// The coordinates of `nodes`, in order; a node beyond `coordinates` is an
/// error.
pub fn gather(
    nodes: &[usize],
    coordinates: &[Vector3<f64>],
) -> Result<Vec<Vector3<f64>>, MortarError> {
    nodes
        .iter()
        .map(|&n| {
            coordinates.get(n).copied().ok_or(MortarError::NodeIndex {
                node: n,
                count: coordinates.len(),
            })
        })
        .collect()
}
