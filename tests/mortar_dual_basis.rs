//! The dual multiplier basis of a secondary face (Wohlmuth 2000; Popp, Gee
//! & Wall 2009) and the quadratic basis transformation (Popp, Wohlmuth, Gee
//! & Wall 2012): the closed forms on flat faces, biorthogonality on
//! distorted faces, the partition of unity and positivity.

use nalgebra::Vector3;
use signorini::contact::mortar::quadratic::{self, mortar_values};
use signorini::contact::mortar::{DualBasis, FaceShape, MortarFace};
use signorini::fem::quadrature;

fn v(x: f64, y: f64, z: f64) -> Vector3<f64> {
    Vector3::new(x, y, z)
}

/// A flat face of `shape` through the reference nodes mapped by an affine
/// map (a parallelogram / general triangle), tilted in 3D.
fn affine_face(shape: FaceShape) -> MortarFace {
    let coords = shape
        .reference_nodes()
        .iter()
        .map(|p| {
            v(
                1.0 + 2.0 * p[0] + 0.7 * p[1],
                -0.5 + 0.3 * p[0] + 1.5 * p[1],
                0.4 * p[0] - 0.9 * p[1],
            )
        })
        .collect();
    MortarFace::new(shape, coords).unwrap()
}

/// A planar, distorted face: straight-edged quadrilaterals become general
/// (non-parallelogram) quadrilaterals, and the quadratic faces' mid-side
/// nodes are moved off the edges (curved edges in the plane `z = 0.3 x`).
fn distorted_planar_face(shape: FaceShape) -> MortarFace {
    let mut coords: Vec<Vector3<f64>> = match shape.corner_count() {
        3 => vec![v(0.0, 0.0, 0.0), v(2.0, 0.3, 0.0), v(0.4, 1.7, 0.0)],
        _ => vec![
            v(0.0, 0.0, 0.0),
            v(2.0, 0.2, 0.0),
            v(2.6, 1.9, 0.0),
            v(-0.3, 1.2, 0.0),
        ],
    };
    let corners = coords.clone();
    for (m, [a, b]) in quadratic::mid_side_edges(shape).iter().enumerate() {
        let bulge = [0.11, -0.08, 0.06, -0.05][m];
        let mid = (corners[*a] + corners[*b]) * 0.5;
        let t = corners[*b] - corners[*a];
        coords.push(mid + v(-t.y, t.x, 0.0) * bulge);
    }
    for x in &mut coords {
        x.z = 0.3 * x.x;
    }
    MortarFace::new(shape, coords).unwrap()
}

/// `∫_e f dA` with an independent rule of 8 points per direction (exact
/// for every integrand of these tests on planar faces).
fn integrate(face: &MortarFace, f: impl Fn([f64; 2]) -> f64) -> f64 {
    let (points, weights) = if face.shape.is_triangle() {
        quadrature::triangle_collapsed(8)
    } else {
        quadrature::quadrilateral_any(8)
    };
    points
        .iter()
        .zip(&weights)
        .map(|(xi, w)| w * face.area_normal(*xi).norm() * f(*xi))
        .sum()
}

const ALL: [FaceShape; 4] = [
    FaceShape::Tri3,
    FaceShape::Quad4,
    FaceShape::Tri6,
    FaceShape::Quad8,
];

#[test]
fn the_quadrature_rules_are_exact_to_their_degree() {
    // ∫_{unit triangle} ξ^a η^b = a! b! / (a + b + 2)!, total degree ≤ 2n − 2.
    let fact = |k: u32| (1..=k).map(f64::from).product::<f64>();
    let (p, w) = quadrature::triangle_collapsed(4);
    for (a, b) in [(0, 0), (3, 3), (6, 0), (2, 4), (1, 5)] {
        let numeric: f64 = p
            .iter()
            .zip(&w)
            .map(|(x, w)| w * x[0].powi(a) * x[1].powi(b))
            .sum();
        let exact = fact(a as u32) * fact(b as u32) / fact(a as u32 + b as u32 + 2);
        assert!(
            (numeric - exact).abs() < 1e-15,
            "ξ^{a} η^{b}: {numeric} vs {exact}"
        );
    }
    // Gauss–Legendre with 6 points: ∫_{−1}^{1} x^10 = 2/11.
    let (x, w) = quadrature::gauss_legendre_any(6);
    let numeric: f64 = x.iter().zip(&w).map(|(x, w)| w * x.powi(10)).sum();
    assert!((numeric - 2.0 / 11.0).abs() < 1e-15);
}

#[test]
fn flat_tri3_dual_basis_is_3n_j_minus_the_others() {
    // Φ_j = 3N_j − N_k − N_l on any flat triangle (Wohlmuth 2000).
    let dual = DualBasis::of_face(&affine_face(FaceShape::Tri3)).unwrap();
    for j in 0..3 {
        for k in 0..3 {
            let expected = if j == k { 3.0 } else { -1.0 };
            assert!(
                (dual.coefficients[(j, k)] - expected).abs() < 1e-12,
                "a_{j}{k} = {}",
                dual.coefficients[(j, k)]
            );
        }
    }
}

#[test]
fn parallelogram_quad4_dual_basis_is_the_tensor_product_of_2n_minus_n() {
    // Φ_1 = 4N_1 − 2N_2 + N_3 − 2N_4 and cyclic on a parallelogram.
    let dual = DualBasis::of_face(&affine_face(FaceShape::Quad4)).unwrap();
    let row = [4.0, -2.0, 1.0, -2.0];
    for j in 0..4 {
        for k in 0..4 {
            let expected = row[(k + 4 - j) % 4];
            assert!(
                (dual.coefficients[(j, k)] - expected).abs() < 1e-12,
                "a_{j}{k} = {}",
                dual.coefficients[(j, k)]
            );
        }
    }
}

#[test]
fn the_dual_basis_is_biorthogonal_on_distorted_faces() {
    // ∫ Φ_j Ñ_k dA = δ_jk ∫ Ñ_k dA, checked with an independent 8-point
    // rule, relative to the face area, to 1e-12.
    for shape in ALL {
        let face = distorted_planar_face(shape);
        let dual = DualBasis::of_face(&face).unwrap();
        let area = face.area();
        let n = shape.node_count();
        for j in 0..n {
            for k in 0..n {
                let ijk = integrate(&face, |xi| dual.values(xi)[j] * mortar_values(shape, xi)[k]);
                let expected = if j == k {
                    integrate(&face, |xi| mortar_values(shape, xi)[k])
                } else {
                    0.0
                };
                assert!(
                    (ijk - expected).abs() < 1e-12 * area,
                    "{shape:?} j={j} k={k}: {ijk} vs {expected}"
                );
            }
        }
    }
}

#[test]
fn the_dual_basis_is_a_partition_of_unity() {
    for shape in ALL {
        let dual = DualBasis::of_face(&distorted_planar_face(shape)).unwrap();
        for xi in [[0.1, 0.2], [0.3, 0.6], [-0.7, 0.05], [0.25, 0.25]] {
            let sum: f64 = dual.values(xi).iter().sum();
            assert!(
                (sum - 1.0).abs() < 1e-12,
                "{shape:?} at {xi:?}: Σ Φ = {sum}"
            );
        }
    }
}

#[test]
fn the_transformed_quadratic_basis_has_positive_integrals() {
    // Flat faces, α = 1/5: Tri6 corners 2A/15 and mid-sides A/5 (Lagrange:
    // corners 0); Quad8 corners A/20 and mid-sides A/5 (Lagrange: −A/12).
    for (shape, corner, mid) in [
        (FaceShape::Tri6, 2.0 / 15.0, 0.2),
        (FaceShape::Quad8, 0.05, 0.2),
    ] {
        let face = affine_face(shape);
        let area = face.area();
        for j in 0..shape.node_count() {
            let expected = if j < shape.corner_count() {
                corner
            } else {
                mid
            } * area;
            let integral = integrate(&face, |xi| mortar_values(shape, xi)[j]);
            assert!(
                (integral - expected).abs() < 1e-13 * area,
                "{shape:?} node {j}: {integral} vs {expected}"
            );
        }
        // and on the distorted faces every ∫ Ñ_j stays positive
        let face = distorted_planar_face(shape);
        for j in 0..shape.node_count() {
            let integral = integrate(&face, |xi| mortar_values(shape, xi)[j]);
            assert!(
                integral > 0.02 * face.area(),
                "{shape:?} node {j}: ∫ Ñ = {integral}"
            );
        }
    }
}

#[test]
fn the_transformed_coordinates_reproduce_the_geometry() {
    // Σ_j Ñ_j(ξ) x̃_j = Σ_k N_k(ξ) x_k with x̃_j = Σ_k R_jk x_k.
    for shape in ALL {
        let face = distorted_planar_face(shape);
        let rows = quadratic::nodal_transformation(shape);
        let transformed: Vec<Vector3<f64>> = rows
            .iter()
            .map(|row| row.iter().map(|(k, r)| face.coordinates[*k] * *r).sum())
            .collect();
        for xi in [[0.1, 0.2], [0.6, 0.3], [-0.4, 0.9]] {
            let mortar: Vector3<f64> = mortar_values(shape, xi)
                .iter()
                .zip(&transformed)
                .map(|(n, x)| x * *n)
                .sum();
            assert!(
                (mortar - face.point(xi)).norm() < 1e-14,
                "{shape:?} at {xi:?}"
            );
        }
    }
}

#[test]
fn a_collapsed_face_is_an_error() {
    let face = MortarFace::new(
        FaceShape::Tri3,
        vec![v(0.0, 0.0, 0.0), v(1.0, 0.0, 0.0), v(2.0, 0.0, 0.0)],
    )
    .unwrap();
    let message = DualBasis::of_face(&face).unwrap_err().to_string();
    assert!(message.contains("degenerate contact face"), "{message}");
    let wrong = MortarFace::new(FaceShape::Quad8, vec![v(0.0, 0.0, 0.0); 4])
        .unwrap_err()
        .to_string();
    assert!(wrong.contains("needs 8 nodes, 4 were given"), "{wrong}");
}
