//! The mortar patch identities on flat, non-matching surfaces (Popp, Gee &
//! Wall 2009; Puso & Laursen 2004): with a secondary surface fully covered
//! by a non-matching primary one and segment-exact integration,
//!
//! - `Σ_l M_jl = D_j` and `D_j = ∫ Ñ_j dA` (the dual basis' biorthogonality);
//! - a uniform gap `g` gives the weighted gaps `g̃_j = g D_j`;
//! - a uniform pressure `λ` gives nodal forces equal to the consistent
//!   pressure loads `∓λ ∫ N_k dA n` on both sides, node by node — the
//!   patch test that node-to-surface contact fails by tens of per cent
//!   (`tests/two_pass.rs`).
//!
//! Tolerances are round-off: 1e-13 relative to the surface area.

mod mortar_common;

use std::collections::BTreeMap;

use mortar_common::{
    consistent_integrals, graded_secondary, grid, in_plane_moves, linspace, nodal_integrals,
};
use nalgebra::{Rotation3, Vector3};
use signorini::contact::mortar::quadratic::mortar_values;
use signorini::contact::mortar::{all_pairs, mortar_coupling, FaceShape, SurfaceFace};

/// Height of the primary surface above the secondary one.
const GAP: f64 = 0.05;

/// A non-matching pair over [0, 1] × [0, 0.8]: the secondary surface at
/// `z = 0` (normal +z) on a coarse graded grid, the primary at `z = GAP`
/// (normal −z) on a finer one (size ratio about 1:1.6). Triangle meshes
/// get their interior corners moved in the plane.
fn stacked(
    secondary: FaceShape,
    primary: FaceShape,
) -> (Vec<SurfaceFace>, Vec<SurfaceFace>, Vec<Vector3<f64>>) {
    let mut coords = Vec::new();
    let s = graded_secondary(secondary, &mut coords);
    let p = grid(
        &linspace(0.0, 1.0, 5),
        &linspace(0.0, 0.8, 4),
        GAP,
        primary,
        true,
        &in_plane_moves(primary),
        &mut coords,
    );
    (s, p, coords)
}

const AREA: f64 = 0.8;

fn check_patch(secondary_shape: FaceShape, primary_shape: FaceShape) {
    check_patch_rotated(secondary_shape, primary_shape, Rotation3::identity());
}

/// The patch checks on the stacked pair turned by `rotation` (the
/// pressure then acts along `rotation · e_z`).
fn check_patch_rotated(
    secondary_shape: FaceShape,
    primary_shape: FaceShape,
    rotation: Rotation3<f64>,
) {
    let (s, p, mut coords) = stacked(secondary_shape, primary_shape);
    for x in &mut coords {
        *x = rotation * *x;
    }
    let normal = rotation * Vector3::z();
    let coupling = mortar_coupling(&s, &p, &all_pairs(s.len(), p.len()), &coords).unwrap();
    let tol = 1e-13 * AREA;
    let label = format!("{secondary_shape:?} on {primary_shape:?}");

    // Σ_l M_jl = D_j and D_j = ∫ Ñ_j dA
    let mortar_integrals = nodal_integrals(&s, &coords, &|shape, xi| mortar_values(shape, xi));
    let mut row_sums: BTreeMap<usize, f64> = BTreeMap::new();
    for ((j, _), m) in &coupling.m {
        *row_sums.entry(*j).or_insert(0.0) += m;
    }
    for (j, d) in &coupling.d {
        assert!(
            (row_sums[j] - d).abs() < tol,
            "{label}: node {j}: Σ M = {} vs D = {d}",
            row_sums[j]
        );
        assert!(
            (mortar_integrals[j] - d).abs() < tol,
            "{label}: node {j}: D = {d} vs ∫Ñ = {}",
            mortar_integrals[j]
        );
    }
    assert_eq!(
        coupling.d.len(),
        mortar_integrals.len(),
        "{label}: every secondary node is coupled"
    );

    // uniform gap: g̃_j = g D_j
    for (j, g) in coupling.weighted_gaps(&coords) {
        assert!(
            (g - GAP * coupling.d[&j]).abs() < tol * GAP,
            "{label}: g̃_{j} = {g}"
        );
    }

    // uniform pressure: consistent loads on both sides, node by node
    let lambda = 2.5;
    let pressure: BTreeMap<usize, f64> = coupling.d.keys().map(|j| (*j, lambda)).collect();
    let forces = coupling.contact_forces(&pressure);
    let secondary_loads = consistent_integrals(&s, &coords);
    let primary_loads = consistent_integrals(&p, &coords);
    let sum_s = check_loads(&label, &forces, &secondary_loads, normal * -lambda);
    let sum_p = check_loads(&label, &forces, &primary_loads, normal * lambda);
    assert!(
        (sum_s + normal * (lambda * AREA)).norm() < lambda * tol,
        "{label}: secondary total {sum_s:?}"
    );
    assert!(
        (sum_p - normal * (lambda * AREA)).norm() < lambda * tol,
        "{label}: primary total {sum_p:?}"
    );
}

/// Asserts `f_k = t ∫ N_k dA` (`t` the traction) at every node of `loads` and
/// returns the sum of those forces.
fn check_loads(
    label: &str,
    forces: &BTreeMap<usize, Vector3<f64>>,
    loads: &BTreeMap<usize, f64>,
    traction: Vector3<f64>,
) -> Vector3<f64> {
    let tol = 1e-13 * AREA * traction.norm();
    let mut sum = Vector3::zeros();
    for (node, load) in loads {
        let f = forces.get(node).copied().unwrap_or_else(Vector3::zeros);
        let expected = traction * *load;
        assert!(
            (f - expected).norm() < tol,
            "{label}: node {node}: {f:?} vs {expected:?}"
        );
        sum += f;
    }
    sum
}

#[test]
fn patch_tri3_on_tri3() {
    check_patch(FaceShape::Tri3, FaceShape::Tri3);
}

#[test]
fn patch_quad4_on_quad4() {
    check_patch(FaceShape::Quad4, FaceShape::Quad4);
}

#[test]
fn patch_tri3_on_quad4_and_quad4_on_tri3() {
    check_patch(FaceShape::Tri3, FaceShape::Quad4);
    check_patch(FaceShape::Quad4, FaceShape::Tri3);
}

#[test]
fn patch_tri6_on_tri6() {
    check_patch(FaceShape::Tri6, FaceShape::Tri6);
}

#[test]
fn patch_quad8_on_quad8() {
    check_patch(FaceShape::Quad8, FaceShape::Quad8);
}

#[test]
fn patch_mixed_quadratic() {
    check_patch(FaceShape::Tri6, FaceShape::Quad8);
    check_patch(FaceShape::Quad8, FaceShape::Tri6);
}

#[test]
fn patch_on_a_tilted_pair() {
    let rotation = Rotation3::from_euler_angles(0.4, -0.7, 1.1);
    check_patch_rotated(FaceShape::Tri3, FaceShape::Quad4, rotation);
    check_patch_rotated(FaceShape::Quad8, FaceShape::Tri6, rotation);
}
