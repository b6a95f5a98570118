//! Finite-difference twins of the mortar kernels' directional derivatives
//! (Popp, Gitterle, Gee & Wall 2010, §5): the dual basis coefficients, the
//! averaged nodal normals and the projection of a point onto a face, on
//! warped and curved faces. Central differences with `h = 1e-6`; the
//! derivatives agree to 1e-7 relative (the differences' truncation error
//! is O(h²) ≈ 1e-12 of the second derivatives, round-off ≈ 1e-10/h).

mod mortar_common;

use mortar_common::{curved_face, grid, increments, linspace, shifted, v};
use nalgebra::DMatrix;
use signorini::contact::mortar::projection::{project_along, projection_derivative};
use signorini::contact::mortar::{
    nodal_normal_derivatives, nodal_normals, DualBasis, FaceShape, MortarFace,
};

const H: f64 = 1e-6;

#[test]
fn dual_basis_derivative_matches_central_differences() {
    for shape in [
        FaceShape::Tri3,
        FaceShape::Quad4,
        FaceShape::Tri6,
        FaceShape::Quad8,
    ] {
        let face = curved_face(shape);
        let dx = increments(shape.node_count(), 0.3);
        let exact = DualBasis::of_face(&face)
            .unwrap()
            .derivative(&face, &dx)
            .unwrap();
        let at = |h: f64| -> DMatrix<f64> {
            let f = MortarFace::new(shape, shifted(&face.coordinates, &dx, h)).unwrap();
            DualBasis::of_face(&f).unwrap().coefficients
        };
        let fd = (at(H) - at(-H)) / (2.0 * H);
        let error = (&fd - &exact).norm() / exact.norm().max(1.0);
        assert!(error < 1e-7, "{shape:?}: relative error {error:e}");
        if shape == FaceShape::Tri3 {
            // Φ_j = 3N_j − N_k − N_l on every triangle: A_e does not move.
            assert!(exact.norm() < 1e-12, "Tri3: δA = {exact}");
        } else {
            assert!(
                exact.norm() > 1e-3,
                "{shape:?}: the derivative is not trivially zero"
            );
        }
    }
}

#[test]
fn nodal_normal_derivatives_match_central_differences() {
    for shape in [
        FaceShape::Tri3,
        FaceShape::Quad4,
        FaceShape::Tri6,
        FaceShape::Quad8,
    ] {
        let mut coords = Vec::new();
        let none = |_: f64, _: f64| [0.0, 0.0];
        let faces = grid(
            &linspace(0.0, 1.0, 3),
            &linspace(0.0, 1.0, 2),
            0.0,
            shape,
            false,
            &none,
            &mut coords,
        );
        for x in &mut coords {
            x.z = 0.3 * (2.0 * x.x).sin() * (1.0 + x.y) + 0.1 * x.y * x.y;
        }
        let dx = increments(coords.len(), 1.7);
        let exact = nodal_normal_derivatives(&faces, &coords, &dx).unwrap();
        let plus = nodal_normals(&faces, &shifted(&coords, &dx, H)).unwrap();
        let minus = nodal_normals(&faces, &shifted(&coords, &dx, -H)).unwrap();
        for (node, d) in &exact {
            let fd = (plus[node] - minus[node]) / (2.0 * H);
            assert!(
                (fd - d).norm() < 1e-7 * d.norm().max(1.0),
                "{shape:?} node {node}: {fd:?} vs {d:?}"
            );
        }
    }
}

#[test]
fn projection_derivative_matches_central_differences() {
    let face = curved_face(FaceShape::Quad8);
    let point = v(0.8, 0.6, 1.0);
    let direction = v(0.1, -0.2, 1.0).normalize();
    let dx = increments(8, 4.2);
    let (dp, dd) = (v(0.3, -0.5, 0.2), v(-0.2, 0.1, 0.05));
    let hit = project_along(&face, &point, &direction).unwrap();
    let jacobian = hit.jacobian(&face, &direction).unwrap();
    let (dxi, dalpha) = projection_derivative(&face, &hit, &jacobian, &dx, &dp, &dd);
    let at = |h: f64| {
        let f = MortarFace::new(FaceShape::Quad8, shifted(&face.coordinates, &dx, h)).unwrap();
        project_along(&f, &(point + dp * h), &(direction + dd * h)).unwrap()
    };
    let (p, m) = (at(H), at(-H));
    let fd_xi = [0, 1].map(|i| (p.xi[i] - m.xi[i]) / (2.0 * H));
    let fd_alpha = (p.distance - m.distance) / (2.0 * H);
    for i in 0..2 {
        assert!(
            (fd_xi[i] - dxi[i]).abs() < 1e-7,
            "δξ_{i}: {} vs {}",
            fd_xi[i],
            dxi[i]
        );
    }
    assert!(
        (fd_alpha - dalpha).abs() < 1e-7,
        "δα: {fd_alpha} vs {dalpha}"
    );
    assert!(
        dxi[0].abs() + dxi[1].abs() > 1e-2,
        "a non-trivial derivative"
    );
}
