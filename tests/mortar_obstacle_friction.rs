//! Coulomb friction on dual mortar against a rigid obstacle (issue 28,
//! items 3 and 4): the slip of the transformed point relative to the
//! obstacle through the node driver's one friction law
//! (`contact::mortar_friction`, "Against a rigid obstacle"), on linear and
//! quadratic faces.
//!
//! Reference of the stick patch test: a linear elastic block (E = 100,
//! ν = 0.3, Lamé `λ`, `G`) on the plane z = 0 whose outer faces but the
//! bottom are given `u = (F − I) X`, pressed (`F_zz = 1 − δ`) and then
//! sheared (`F_xz = γ`). The bottom stays where it is, the stress is
//! uniform, `σ_zz = −(λ + 2G) δ`, `σ_xz = G γ`, and the bottom's traction
//! on the body (outward normal `−e_z`) is the pressure `t_N = (λ + 2G) δ`
//! and the tangential traction `t_T = −G γ e_x`. Exact stick must
//! transmit it at every secondary node.

mod common;

use common::{assert_open_stick_and_slip, assert_uniform, perturbed_state, problem, run};
use nalgebra::Vector3;
use signorini::assembly::amplitude::Amplitude;
use signorini::contact::friction::{ContactStatus, STICK_SHIFT};
use signorini::contact::interface::{ContactInterface, NodeReport};
use signorini::contact::laws::NormalLaw;
use signorini::contact::obstacle::RigidObstacle;
use signorini::contact::setup::Enforcement;
use signorini::material::LinearElastic;
use signorini::mesh::{structured::box_mesh, ElementKind};
use signorini::problem::{PrescribedDisplacement, Problem};
use std::sync::Arc;

const E: f64 = 100.0;
const NU: f64 = 0.3;
/// The press `δ` and the shear `γ` of the stick test.
const PRESS: f64 = 0.01;
const SHEAR: f64 = 0.004;

/// A block of `kind` (`cells` × `cells` × 2, 1 × 1 × 0.5) of linear
/// elastic material with two steps, `press` (t ∈ [0, 1]) and `shear`
/// (t ∈ [1, 2]), one increment each.
fn block(kind: ElementKind, cells: usize) -> Problem {
    let mesh = box_mesh(kind, [cells, cells, 2], [1.0, 1.0, 0.5]);
    let mut pr = problem(mesh, Arc::new(LinearElastic::new(E, NU, "m").unwrap()));
    pr.steps = common::press_then_shear_steps();
    pr.settings.residual_tolerance = 1e-12;
    pr
}

/// Mortar contact of the block's bottom with `obstacle` (Rockafellar,
/// p = k = 10E; Coulomb `mu`, ε_T = 5E, exact stick by tangential
/// multipliers in Newton).
fn frictional_mortar(pr: &Problem, obstacle: RigidObstacle, mu: f64) -> ContactInterface {
    let law = NormalLaw::Rockafellar {
        p: 10.0 * E,
        k: 10.0 * E,
    };
    let enforcement = Enforcement {
        friction_coefficient: Some(mu),
        tangential_penalty: Some(5.0 * E),
        exact_stick: true,
        youngs_modulus: E,
        ..Enforcement::from(law)
    };
    ContactInterface::mortar_rigid(&pr.model.mesh, "zmin", obstacle, &enforcement).unwrap()
}

/// The plane z = 0.
fn floor() -> RigidObstacle {
    RigidObstacle::plane(Vector3::zeros(), Vector3::z()).unwrap()
}

/// Node `n` given `u(t)` through the points `(t, u)` of each component.
fn prescribe(pr: &mut Problem, n: usize, [press, shear]: [[f64; 3]; 2]) {
    for (d, (p, s)) in press.into_iter().zip(shear).enumerate() {
        pr.prescribed.push(PrescribedDisplacement {
            surface: "outer faces".into(),
            nodes: vec![n],
            components: vec![(d, 1.0)],
            amplitude: Amplitude::new(vec![(0.0, 0.0), (1.0, p), (2.0, s)]),
        });
    }
}

/// The node reports of the run's last state, and Newton's iterations per
/// increment.
fn run_and_report(pr: &mut Problem) -> (Vec<NodeReport>, Vec<usize>) {
    let last = run(pr);
    let reports = common::interface_reports(pr, &last, 2.0);
    let iterations = last.increments.iter().map(|i| i.iterations).collect();
    (reports, iterations)
}

/// Stick: the block pressed by `δ` and sheared by `γ` (module docs) with
/// μ = 2|t_T|/t_N: every secondary node inside the bottom sticks, its
/// pressure is `t_N` to 1e-10 and its tangential traction `t_T` to 1e-9
/// of `t_N` (the mortar patch test, tangentially; measured 1e-13 at
/// most, on Tet10), on Tri3, Quad4, Tri6 and Quad8 faces. The bottom's
/// boundary nodes lie on the side faces, whose displacements are
/// prescribed: the support takes their load, so their multipliers are
/// not checked.
#[test]
fn stick_on_a_rigid_plane_transmits_the_shear_traction_exactly() {
    let g = E / (2.0 * (1.0 + NU));
    let lambda = E * NU / ((1.0 + NU) * (1.0 - 2.0 * NU));
    let t_n = (lambda + 2.0 * g) * PRESS;
    let t_t = Vector3::new(-g * SHEAR, 0.0, 0.0);
    let mu = 2.0 * t_t.norm() / t_n;
    for (kind, cells) in [
        (ElementKind::Tet4, 3),
        (ElementKind::Hex8, 3),
        (ElementKind::Tet10, 2),
        (ElementKind::Hex20, 2),
    ] {
        let mut pr = block(kind, cells);
        let mesh = pr.model.mesh.clone();
        let mut outer: Vec<usize> = ["xmin", "xmax", "ymin", "ymax", "zmax"]
            .iter()
            .flat_map(|f| mesh.surface_nodes(mesh.surface(f).unwrap()))
            .collect();
        outer.sort_unstable();
        outer.dedup();
        for n in outer {
            let z = mesh.nodes[n][2];
            prescribe(
                &mut pr,
                n,
                [[0.0, 0.0, -PRESS * z], [SHEAR * z, 0.0, -PRESS * z]],
            );
        }
        pr.set_contacts(vec![frictional_mortar(&pr, floor(), mu)]);
        let (reports, iterations) = run_and_report(&mut pr);
        let nodes = &pr.contacts.interface(0).nodes;
        let inside = |i: &usize| {
            let [x, y, _] = mesh.nodes[nodes[*i]];
            [x, y].iter().all(|c| *c > 1e-9 && *c < 1.0 - 1e-9)
        };
        let worst = assert_uniform(
            reports.iter().enumerate().filter(|(i, _)| inside(i)),
            ContactStatus::Stick,
            (t_n, t_t),
            &format!("{kind:?} stick"),
        );
        println!("{kind:?} stick: t_N {t_n:.6} |t_T| {:.6}, worst {worst:.1e}, iterations {iterations:?}", t_t.norm());
    }
}

/// Full slip against a moving plane: the block's top pressed down by 0.01
/// and then held, the plane slid by 0.05 along −x under it (μ = 0.3, far
/// beyond the stick limit): every secondary node slips, its tangential
/// traction is on Coulomb's cone, `|t_T| = μ t_N` to 1e-10 of `t_N`, and
/// drags the body along the plane's motion (−x: it opposes the body's
/// slip relative to the plane); the plane's translation enters the slip,
/// not the gap. On Tri3, Tri6 and Quad8 faces.
#[test]
fn full_slip_on_a_moving_plane_is_on_the_coulomb_cone() {
    let mu = 0.3;
    for (kind, cells) in [
        (ElementKind::Tet4, 3),
        (ElementKind::Tet10, 2),
        (ElementKind::Hex20, 2),
    ] {
        let mut pr = block(kind, cells);
        let mesh = pr.model.mesh.clone();
        for n in mesh.surface_nodes(mesh.surface("zmax").unwrap()) {
            prescribe(&mut pr, n, [[0.0, 0.0, -0.01], [0.0, 0.0, -0.01]]);
        }
        let slide = Amplitude::new(vec![(0.0, 0.0), (1.0, 0.0), (2.0, 1.0)]);
        let c = frictional_mortar(&pr, floor(), mu).moving(Vector3::new(-0.05, 0.0, 0.0), slide);
        pr.set_contacts(vec![c]);
        let (reports, iterations) = run_and_report(&mut pr);
        // the body slips along +x relative to the plane: dragged along −x
        let body_slip = Vector3::x();
        let label = format!("{kind:?}");
        let worst = common::assert_slip_on_the_cone(&reports, mu, &body_slip, &label);
        println!("{kind:?} slip: |t_T|/t_N − μ ≤ {worst:.1e} μ, iterations {iterations:?}");
    }
}

/// The tangent of mortar friction against a rigid sphere (its normal and
/// curvature vary over the face), Tet10 and Hex8 (Tri6 and Quad4 faces):
/// the displacement and tangential multiplier rows of the assembled
/// tangent are the central differences of the residual, every column
/// ([`common::assert_tangent_rows_match_fd`]), at a state with open,
/// sticking and slipping nodes: committed at a pressed state and again
/// after a small slide, then the bottom's nodes moved tangentially by
/// different amounts. The diagonal of a closed node's tangential rows
/// may differ by the Jacobian's shift `STICK_SHIFT A ε_T`; the normal
/// multiplier rows are left out, as in `tests/mortar_friction.rs`.
#[test]
fn frictional_mortar_on_a_sphere_matches_finite_differences() {
    for kind in [ElementKind::Hex8, ElementKind::Tet10] {
        let mesh = box_mesh(kind, [3, 3, 1], [1.0, 1.0, 0.5]);
        let mut pr = problem(mesh, Arc::new(LinearElastic::new(E, NU, "m").unwrap()));
        let sphere = RigidObstacle::sphere(Vector3::new(0.4, 0.5, -2.0), 2.0).unwrap();
        pr.set_contacts(vec![frictional_mortar(&pr, sphere, 0.3)]);
        let dofs = pr.model.num_dofs();
        let normal = pr.contacts.interface(0).nodes.len();
        let mut x = perturbed_state(&pr, 0.01, false);
        let bottom = pr.contacts.interface(0).nodes.clone();
        for n in &bottom {
            x[3 * n + 2] -= 0.05;
        }
        for (m, v) in x.iter_mut().enumerate().skip(dofs) {
            let scale = if m < dofs + normal { 2e-3 } else { 2e-5 };
            *v = scale * ((m as f64) * 1.3).cos().abs();
        }
        let amount = |n| common::uneven_slide(n).map(|v| 5.0 * v);
        let state = common::slid_history(&mut pr, &mut x, &bottom, amount);
        let (_, reports) = pr.residual_in(0.5, &x, &state, None).unwrap();
        let label = format!("{kind:?}");
        assert_open_stick_and_slip(&reports[0], &label);
        let rows = |i: usize| i < dofs || i >= dofs + normal;
        let area = pr
            .contacts
            .interface(0)
            .areas
            .iter()
            .fold(0.0, |m: f64, a| m.max(*a));
        let shift = |i: usize, j: usize| {
            if i == j && i >= dofs {
                STICK_SHIFT * area * 5.0 * E
            } else {
                0.0
            }
        };
        common::assert_tangent_rows_match_fd(&pr, 0.5, &x, &state, &label, |_| {}, rows, shift);
    }
}

/// `discretisation = "mortar"` with `friction_coefficient` against an
/// obstacle through the case file: a Hex20 block (3 × 3 × 2, symmetry
/// planes x = 0 and y = 0) pressed by P = 2 onto the plane z = 0 with
/// μ = 0.3, so that friction holds back the bottom's lateral (Poisson)
/// expansion: the run on the default strategy equals the monolithic one
/// to 1e-8 of the largest displacement, the normal force is P × the
/// bottom's area to 1e-10 (equilibrium), and the tangential contact force
/// is not zero (the bottom's nodes off the symmetry planes stick or
/// slip against the plane).
#[test]
fn mortar_friction_against_an_obstacle_through_the_case_file() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = box_mesh(ElementKind::Hex20, [3, 3, 2], [1.0, 1.0, 0.5]);
    std::fs::write(dir.path().join("block.msh"), common::msh22(&mesh)).unwrap();
    let run = |name: &str, strategy: &str| {
        let path = dir.path().join(format!("{name}.toml"));
        let case = common::mortar_block_on_floor_case("friction_coefficient = 0.3", strategy);
        std::fs::write(&path, case).unwrap();
        common::CaseRun::new(&path, &dir.path().join(name)).outcome
    };
    // 1e-12: at 1e-13 the residual stalls at 5.7e-11 (cut 8 times)
    let default = run("default", "residual_tolerance = 1e-12");
    let monolithic = run(
        "monolithic",
        "residual_tolerance = 1e-12\nstrategy = \"monolithic\"",
    );
    let scale = monolithic
        .displacement
        .iter()
        .fold(0.0_f64, |m, v| m.max(v.abs()));
    let difference = common::relative_difference(&default.displacement, &monolithic.displacement);
    println!("default against monolithic: {difference:.1e} of {scale:.3e}");
    assert!(difference <= 1e-8, "{difference:e}");
    let contact = &monolithic.summary.increments.last().unwrap().contact["bottom"];
    assert!(
        (contact.force[2] - 2.0).abs() < 1e-10 * 2.0,
        "{:?}",
        contact.force
    );
    let tangential = Vector3::from(contact.tangential_force).norm();
    assert!(tangential > 1e-3, "tangential force {tangential}");
}
