//! Frictionless contact with rigid obstacles, through the library API:
//! the contact patch test, exactness of the Lagrangian methods, penalty's
//! expected penetration, release, and a finite-difference check of the
//! assembled contact tangent — for every enforcement method on the one
//! assembly path.

mod common;

use common::{
    assert_tangent_matches_fd, every_method, fix, interface, perturbed_state, problem, run,
};
use nalgebra::Vector3;
use signorini::contact::interface::Primary;
use signorini::contact::laws::NormalLaw;
use signorini::contact::RigidObstacle;
use signorini::material::{LinearElastic, NeoHookean};
use signorini::mesh::structured::{box_mesh, perturb_interior};
use signorini::mesh::ElementKind;
use signorini::problem::{Amplitude, PressureLoad, Problem};
use std::sync::Arc;

const E: f64 = 100.0;
const H: f64 = 0.25; // cell size of the test blocks

/// A block on a rigid plane (its bottom face on z = 0), symmetry planes
/// x = 0 and y = 0, uniform dead pressure `p` on top.
fn pressed_block(kind: ElementKind, law: NormalLaw, p: f64) -> Problem {
    let (cells, lengths) = ([4, 4, 2], [1.0, 1.0, 0.5]);
    let mut mesh = box_mesh(kind, cells, lengths);
    perturb_interior(&mut mesh, cells, lengths, 0.2, 11);
    let mut pr = problem(mesh, Arc::new(LinearElastic::new(E, 0.3, "m").unwrap()));
    fix(&mut pr, "xmin", &[(0, 0.0)]);
    fix(&mut pr, "ymin", &[(1, 0.0)]);
    let facets = pr.model.mesh.surface("zmax").unwrap().facets.clone();
    pr.pressures.push(PressureLoad {
        surface: "zmax".into(),
        facets,
        pressure: p,
        follower: false,
        amplitude: Amplitude::ramp(),
    });
    let plane = RigidObstacle::plane(Vector3::zeros(), Vector3::z()).unwrap();
    let c = interface(&pr, H, "zmin", plane, law);
    pr.set_contacts(vec![c]);
    pr
}

/// Contact patch test (formulation note §2): a uniform pressure `p` on top
/// reaches the plane as a uniform contact pressure `p` at every closed node,
/// to 1e-8 relative, on irregular Tet4 and Hex8 meshes, for every method.
/// The Lagrangian methods leave a penetration below 1e-8 of the element
/// size; penalty leaves its expected `p/ε` (to 1e-8 relative).
#[test]
fn contact_patch_test_and_exactness() {
    let p = 2.0;
    for kind in [ElementKind::Tet4, ElementKind::Hex8] {
        for (name, law) in every_method(E / H) {
            let mut pr = pressed_block(kind, law, p);
            let last = run(&mut pr);
            let c = pr.contacts.interface(0);
            let (_, reports) = pr.residual_in(1.0, &last.x, &last.contact, None).unwrap();
            for (i, r) in reports[0].iter().enumerate() {
                assert!(r.active, "{kind:?} {name}: node {} open", c.nodes[i]);
                assert!(
                    (r.pressure - p).abs() < 1e-8 * p,
                    "{kind:?} {name}: t_N = {} at node {}",
                    r.pressure,
                    c.nodes[i]
                );
                match law {
                    NormalLaw::Penalty { epsilon } => {
                        let expected = -p / epsilon;
                        assert!(
                            (r.gap - expected).abs() < 1e-8 * expected.abs(),
                            "{kind:?} penalty gap {}",
                            r.gap
                        );
                    }
                    _ => assert!(r.gap.abs() < 1e-8 * H, "{kind:?} {name}: gap {}", r.gap),
                }
            }
            // total contact force balances the applied load p × area 1
            let total: f64 = reports[0].iter().map(|r| r.force[2]).sum();
            assert!(
                (total - p).abs() < 1e-8 * p,
                "{kind:?} {name}: total {total}"
            );
        }
    }
}

/// Release: the top face is pushed down by a prescribed displacement, then
/// the plane is lowered away from the block: every node opens and the
/// pressure returns to zero, for every method (this exercises the slack
/// law's switch).
#[test]
fn lifting_the_obstacle_releases_every_node() {
    for (name, law) in every_method(E / H) {
        let (cells, lengths) = ([3, 3, 2], [0.75, 0.75, 0.5]);
        let mesh = box_mesh(ElementKind::Hex8, cells, lengths);
        let mut pr = problem(mesh, Arc::new(NeoHookean::new(E, 0.3, "m").unwrap()));
        fix(&mut pr, "xmin", &[(0, 0.0)]);
        fix(&mut pr, "ymin", &[(1, 0.0)]);
        fix(&mut pr, "zmax", &[(2, -0.02)]);
        pr.prescribed.last_mut().unwrap().amplitude = Amplitude::new(vec![(0.0, 0.0), (1.0, 1.0)]);
        pr.steps.push(signorini::problem::Step {
            name: "lift".into(),
            end_time: 2.0,
            initial_increment: 0.5,
            min_increment: 1e-4,
            max_increment: 0.5,
        });
        let plane = RigidObstacle::plane(Vector3::zeros(), Vector3::z()).unwrap();
        let mut c = interface(&pr, H, "zmin", plane, law);
        c.motion = Vector3::new(0.0, 0.0, -0.1);
        c.amplitude = Amplitude::new(vec![(0.0, 0.0), (1.0, 0.0), (2.0, 1.0)]);
        pr.set_contacts(vec![c]);
        let last = run(&mut pr);
        // the press step closed the contact
        assert!(last.increments.iter().any(|i| i.time <= 1.0));
        let (_, reports) = pr.residual_in(2.0, &last.x, &last.contact, None).unwrap();
        for r in &reports[0] {
            assert!(
                !r.active,
                "{name}: a node stays closed (gap {}, t_N {})",
                r.gap, r.pressure
            );
            assert_eq!(r.pressure, 0.0, "{name}");
            assert!(r.gap > 0.0, "{name}: gap {}", r.gap);
        }
    }
}

/// The assembled tangent (elasticity + contact, displacements and
/// multipliers) is the derivative of the assembled residual, for a block
/// pressed into a rigid sphere (curved: the gap Hessian matters) with open
/// and closed nodes, by central differences, for every method. The slack
/// law's condensed tangent is the Newton matrix of its full local system,
/// which is this derivative at a consistent local state (its own tests check
/// it against the full system): there the multipliers start at 0 with the
/// local unknowns solved for the gap.
#[test]
fn assembled_contact_tangent_matches_finite_difference() {
    for (name, law) in every_method(E / H) {
        let mesh = box_mesh(ElementKind::Hex8, [2, 2, 1], [1.0, 1.0, 0.5]);
        let mut pr = problem(mesh, Arc::new(NeoHookean::new(E, 0.3, "m").unwrap()));
        let sphere = RigidObstacle::sphere(Vector3::new(0.4, 0.6, -1.0), 1.02).unwrap();
        let c = interface(&pr, H, "zmin", sphere, law);
        pr.set_contacts(vec![c]);
        let x = perturbed_state(&pr, 0.01, name == "slack");
        let state = pr.initial_contact_state(&x);
        let mut k = vec![0.0; pr.model.pattern.nnz()];
        let (_, reports) = pr.residual_in(0.5, &x, &state, Some(&mut k)).unwrap();
        assert!(
            reports[0].iter().any(|r| r.active) && reports[0].iter().any(|r| !r.active),
            "{name}: mixed state"
        );
        assert_tangent_matches_fd(&pr, 0.5, &x, &state, name);
    }
}

/// A finely triangulated plane gives the analytic plane's result: the
/// contact patch test again, with the plane as 2·6² triangles (flat facets:
/// no facetting error, so to 1e-10).
#[test]
fn triangulated_plane_matches_the_analytic_plane() {
    let law = NormalLaw::Rockafellar { p: E / H, k: E / H };
    let mut pr = pressed_block(ElementKind::Hex8, law, 2.0);
    let n = 6;
    let vertices: Vec<Vector3<f64>> = (0..=n)
        .flat_map(|j| {
            (0..=n).map(move |i| {
                Vector3::new(
                    -1.0 + 3.0 * i as f64 / n as f64,
                    -1.0 + 3.0 * j as f64 / n as f64,
                    0.0,
                )
            })
        })
        .collect();
    let at = |i: usize, j: usize| i + (n + 1) * j;
    let triangles: Vec<[usize; 3]> = (0..n)
        .flat_map(|j| {
            (0..n).flat_map(move |i| {
                [
                    [at(i, j), at(i + 1, j), at(i + 1, j + 1)],
                    [at(i, j), at(i + 1, j + 1), at(i, j + 1)],
                ]
            })
        })
        .collect();
    let surface = signorini::contact::TriangulatedSurface::new(vertices, triangles).unwrap();
    let mut contacts: Vec<_> = pr.contacts.iter().cloned().collect();
    contacts[0].primary = Primary::Rigid(RigidObstacle::Triangulated(surface));
    pr.set_contacts(contacts);
    let last = run(&mut pr);
    let (_, reports) = pr.residual_in(1.0, &last.x, &last.contact, None).unwrap();
    for r in &reports[0] {
        assert!(
            r.active && (r.pressure - 2.0).abs() < 1e-10 * 2.0,
            "t_N = {}",
            r.pressure
        );
        assert!(r.gap.abs() < 1e-10 * H);
    }
}

/// A finely triangulated sphere (icosphere, 81 920 facets, edge ≈ 0.019,
/// gap error ≤ h²/(6R) ≈ 6e-5 against an indentation of 0.03) indenting a
/// block gives the analytic sphere's total force within 1 % (the force goes
/// as depth^{3/2}: 1.5 × 6e-5/0.03 ≈ 0.3 % expected).
#[test]
fn triangulated_sphere_matches_the_analytic_sphere() {
    let force = |obstacle: RigidObstacle| {
        let mesh = box_mesh(ElementKind::Hex8, [8, 8, 6], [0.5, 0.5, 0.375]);
        let mut pr = problem(mesh, Arc::new(LinearElastic::new(E, 0.3, "m").unwrap()));
        fix(&mut pr, "xmin", &[(0, 0.0)]);
        fix(&mut pr, "ymin", &[(1, 0.0)]);
        fix(&mut pr, "zmin", &[(2, 0.0)]);
        let mut c = interface(
            &pr,
            H,
            "zmax",
            obstacle,
            NormalLaw::Rockafellar { p: E / H, k: E / H },
        );
        c.motion = Vector3::new(0.0, 0.0, -0.03);
        pr.set_contacts(vec![c]);
        pr.steps[0].initial_increment = 0.5;
        let last = run(&mut pr);
        let (_, reports) = pr.residual_in(1.0, &last.x, &last.contact, None).unwrap();
        reports[0].iter().map(|r| r.force[2]).sum::<f64>()
    };
    let center = Vector3::new(0.0, 0.0, 0.375 + 1.0);
    let analytic = force(RigidObstacle::sphere(center, 1.0).unwrap());
    let (vertices, triangles) = common::icosphere(1.0, 6);
    let vertices = vertices.into_iter().map(|v| v + center).collect();
    let faceted = force(RigidObstacle::Triangulated(
        signorini::contact::TriangulatedSurface::new(vertices, triangles).unwrap(),
    ));
    assert!(analytic < 0.0, "the sphere pushes down: {analytic}");
    assert!(
        (faceted - analytic).abs() < 0.01 * analytic.abs(),
        "faceted {faceted} vs analytic {analytic}"
    );
}

/// End to end through the case file, with the obstacle a surface set of a
/// Gmsh mesh (a square of quadrangles, split into triangles): a block under
/// a uniform pressure `p` on it reports a total contact force `p × area`
/// (1e-8), every bottom node closed, the contact area, and writes the
/// contact fields into the VTU.
#[test]
fn gmsh_surface_obstacle_through_the_case_file() {
    let dir = tempfile::tempdir().unwrap();
    let body = box_mesh(ElementKind::Hex8, [3, 3, 2], [1.0, 1.0, 0.5]);
    std::fs::write(dir.path().join("block.msh"), common::msh22(&body)).unwrap();
    // the obstacle: a square [−1, 2]² at z = 0, normals +z, and no volume
    let mut floor = signorini::mesh::Mesh::default();
    for j in 0..4 {
        for i in 0..4 {
            floor.nodes.push([-1.0 + i as f64, -1.0 + j as f64, 0.0]);
            floor.node_ids.push(floor.nodes.len() as u64);
        }
    }
    let facets = (0..3)
        .flat_map(|j| (0..3).map(move |i| (i, j)))
        .map(|(i, j)| signorini::mesh::Facet {
            kind: signorini::mesh::FacetKind::Quad4,
            nodes: vec![
                i + 4 * j,
                i + 1 + 4 * j,
                i + 1 + 4 * (j + 1),
                i + 4 * (j + 1),
            ],
            id: 0,
        })
        .collect();
    floor.surfaces.push(signorini::mesh::SurfaceSet {
        name: "floor".into(),
        facets,
    });
    std::fs::write(dir.path().join("floor.msh"), common::msh22(&floor)).unwrap();
    let case = common::SYMMETRIC_BLOCK.to_string()
        + r#"
[[pressure]]
surface = "zmax"
value = 3.0

[[obstacle]]
name = "ground"
shape = "gmsh"
file = "floor.msh"
surface = "floor"

[[contact]]
name = "sole"
surface = "zmin"
obstacle = "ground"

[[step]]
name = "press"
end_time = 1.0
"#;
    std::fs::write(dir.path().join("case.toml"), case).unwrap();
    let outcome = signorini::run::run(
        &dir.path().join("case.toml"),
        &signorini::run::RunOptions {
            output: None,
            threads: None,
            cancel: None,
            restart: None,
        },
    )
    .unwrap();
    let sole = &outcome.summary.increments.last().unwrap().contact["sole"];
    assert!(
        (sole.force[2] - 3.0).abs() < 1e-8 * 3.0,
        "contact force {:?}",
        sole.force
    );
    assert_eq!(sole.closed_nodes, 16);
    assert!((sole.area - 1.0).abs() < 1e-12);
    let vtu = std::fs::read_to_string(outcome.output_dir.join(&outcome.summary.increments[0].file))
        .unwrap();
    for field in [
        "\"contact_pressure\"",
        "\"gap\"",
        "\"contact_status\"",
        "\"displacement\"",
    ] {
        assert!(vtu.contains(field), "{field} missing from the VTU");
    }
}
