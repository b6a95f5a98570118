//! The constant stiffness of Hooke's law in closed form
//! (`assembly::hooke`, taken by `Model::constant_stiffness` when every
//! material is `linear_elastic`) against the general kernel (the first
//! elasticity tensor contracted point by point at `u = 0`), entry by entry
//! on whole meshes: the Hertz example's hemisphere and distorted Tet4 and
//! Hex8 boxes.
//!
//! The general path is reached with the same law behind a wrapper that
//! does not say it is Hooke's ([`Material::hooke_lame`] left `None`): the
//! model then assembles its constant `K` with the general kernel.

use signorini::assembly::Model;
use signorini::material::{LinearElastic, Mat3, Mat6, Material};
use signorini::mesh::structured::box_mesh;
use signorini::mesh::{read_mesh, ElementKind, Mesh};
use std::path::Path;
use std::sync::Arc;

/// Hooke's law that does not say so: every method delegated except
/// `hooke_lame`.
#[derive(Debug)]
struct Unnamed(LinearElastic);

impl Material for Unnamed {
    fn name(&self) -> &'static str {
        self.0.name()
    }
    fn kinematics(&self) -> signorini::material::Kinematics {
        self.0.kinematics()
    }
    fn constant_tangent(&self) -> bool {
        self.0.constant_tangent()
    }
    fn strain_energy(&self, f: &Mat3) -> f64 {
        self.0.strain_energy(f)
    }
    fn stress_and_tangent(&self, f: &Mat3) -> (Mat3, Mat6) {
        self.0.stress_and_tangent(f)
    }
    fn reference_youngs_modulus(&self) -> f64 {
        self.0.reference_youngs_modulus()
    }
    fn parameters(&self) -> String {
        self.0.parameters()
    }
}

/// The constant `K` (lower triangle) of `mesh` with `material` on every
/// element.
fn constant_stiffness(mesh: &Arc<Mesh>, material: Arc<dyn Material>) -> Vec<f64> {
    let elements = mesh.elements.len();
    let model = Model::new(Arc::clone(mesh), vec![material], vec![0; elements]).unwrap();
    model.constant_stiffness().unwrap().to_vec()
}

/// The closed form against the general kernel: every entry within 1e-13
/// of the largest; and the general path is really the other one (not
/// bitwise the same).
fn assert_closed_form_is_the_kernels(mesh: Mesh, what: &str) {
    let mesh = Arc::new(mesh);
    let hooke = LinearElastic::new(1000.0, 0.3, "m").unwrap();
    let closed = constant_stiffness(&mesh, Arc::new(hooke));
    let general = constant_stiffness(&mesh, Arc::new(Unnamed(hooke)));
    assert_eq!(closed.len(), general.len(), "{what}");
    let scale = general.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    assert!(scale > 0.0, "{what}: all zero");
    for (i, (c, g)) in closed.iter().zip(&general).enumerate() {
        assert!(
            (c - g).abs() <= 1e-13 * scale,
            "{what}: entry {i}: {c:e} against {g:e} (scale {scale:e})"
        );
    }
    assert_ne!(closed, general, "{what}: the same path twice");
}

#[test]
fn hertz_hemisphere() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/hertz/hemisphere.msh");
    let (mesh, _) = read_mesh(&path).unwrap();
    assert!(mesh.elements.len() > 10_000);
    assert_closed_form_is_the_kernels(mesh, "hertz");
}

#[test]
fn distorted_boxes() {
    for kind in [ElementKind::Tet4, ElementKind::Hex8] {
        let mut mesh = box_mesh(kind, [4, 3, 5], [1.0, 2.0, 1.5]);
        for (n, x) in mesh.nodes.iter_mut().enumerate() {
            let t = n as f64;
            x[0] += 0.04 * (1.3 * t).sin();
            x[1] += 0.05 * (0.7 * t).cos();
            x[2] += 0.03 * (2.1 * t).sin();
        }
        assert_closed_form_is_the_kernels(mesh, &format!("{kind:?} box"));
    }
}
