//! `Problem::builder` (issue 32 item 4): a library user builds a problem
//! without filling its public fields, and gets the case file's physics
//! checks of the reference configuration as typed errors of
//! `contact::setup`: a node starting inside a rigid plane, a plane whose
//! normal points away from the body.

use nalgebra::Vector3;
use signorini::assembly::Model;
use signorini::contact::interface::ContactInterface;
use signorini::contact::laws::NormalLaw;
use signorini::contact::setup::{Enforcement, SetupError};
use signorini::contact::RigidObstacle;
use signorini::material::LinearElastic;
use signorini::mesh::structured::box_mesh;
use signorini::mesh::{ElementKind, Mesh};
use signorini::problem::Problem;
use std::sync::Arc;

/// The unit cube of 2 × 2 × 2 Hex8.
fn cube() -> Arc<Mesh> {
    Arc::new(box_mesh(ElementKind::Hex8, [2, 2, 2], [1.0; 3]))
}

fn model(mesh: &Arc<Mesh>) -> Model {
    let steel = Arc::new(LinearElastic::new(210e3, 0.3, "steel").unwrap());
    Model::new(mesh.clone(), vec![steel], vec![0; mesh.elements.len()]).unwrap()
}

/// The cube's bottom `zmin` against the plane through `(0, 0, height)`
/// with normal `(0, 0, nz)`.
fn on_plane(mesh: &Mesh, height: f64, nz: f64) -> ContactInterface {
    let plane = RigidObstacle::plane(Vector3::new(0.0, 0.0, height), Vector3::new(0.0, 0.0, nz));
    let law = Enforcement::from(NormalLaw::Penalty { epsilon: 1e3 });
    ContactInterface::rigid(mesh, "zmin", plane.unwrap(), &law).unwrap()
}

/// On the plane z = 0 (normal up) the cube is touching: built, with the
/// default step `[0, 1]` and the contact installed.
#[test]
fn a_cube_on_a_plane_builds() {
    let mesh = cube();
    let problem = Problem::builder(model(&mesh))
        .contact(on_plane(&mesh, 0.0, 1.0))
        .build()
        .unwrap();
    assert_eq!(problem.steps.len(), 1);
    assert_eq!(problem.steps[0].end_time, 1.0);
    assert_eq!(problem.contacts.len(), 1);
    assert!(problem.prescribed.is_empty());
}

/// The plane raised to z = 0.25: every node of `zmin` starts 0.25 inside
/// (gap −0.25 exactly), beyond the default tolerance `0.01 h` (`h =
/// √(mean A_s)`, the bottom's area 1 over its 9 nodes: 1/3), so refused;
/// a tolerance of 0.3 accepts it.
#[test]
fn initial_penetration_is_a_typed_error() {
    let mesh = cube();
    let interface = on_plane(&mesh, 0.25, 1.0);
    let tolerance = interface.default_penetration_tolerance();
    assert_eq!(tolerance, 0.01 * interface.element_size);
    let err = Problem::builder(model(&mesh))
        .contact(interface.clone())
        .build()
        .err()
        .expect("refused");
    match &err {
        SetupError::InitialPenetration {
            surface,
            gap,
            tolerance: t,
            ..
        } => {
            assert_eq!(surface, "zmin");
            assert!((gap + 0.25).abs() < 1e-15, "{gap}");
            assert_eq!(*t, tolerance);
        }
        other => panic!("{other:?}"),
    }
    assert!(err.to_string().contains("starts inside"), "{err}");
    Problem::builder(model(&mesh))
        .contact_within(interface, 0.3)
        .build()
        .unwrap();
}

/// The plane z = 2 with its normal up has the whole cube behind it (the
/// nearest node at height −1): its normal points away, which is said
/// rather than that every node starts inside.
#[test]
fn a_plane_facing_away_is_a_typed_error() {
    let mesh = cube();
    let err = Problem::builder(model(&mesh))
        .contact(on_plane(&mesh, 2.0, 1.0))
        .build()
        .err()
        .expect("refused");
    assert_eq!(
        err,
        SetupError::PlaneNormalAway {
            surface: "zmin".into(),
            nearest: -1.0
        }
    );
    assert!(err.to_string().contains("flip it"), "{err}");
    // flipped, the body is in front of it, 1 away: open, accepted
    Problem::builder(model(&mesh))
        .contact(on_plane(&mesh, -1.0, 1.0))
        .build()
        .unwrap();
}
