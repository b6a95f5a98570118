//! First-contact anchoring of friction (issue 18 item 1): a node that closes
//! during an increment starts sticking where its path meets the primary
//! surface, so that a pure normal press carries no friction whatever the
//! number of increments.

mod common;

use common::{assert_tangent_matches_fd, fix, perturbed_state, problem, run, surface_interface};
use signorini::contact::friction::{ContactStatus, Coulomb};
use signorini::contact::laws::NormalLaw;
use signorini::material::NeoHookean;
use signorini::mesh::structured::box_mesh;
use signorini::mesh::{ElementKind, Mesh};
use signorini::problem::{Problem, Step};
use std::sync::Arc;

const E: f64 = 100.0;
const MU: f64 = 0.3;
/// Radius of the domes.
const R: f64 = 1.0;
/// Height and half-width of each body.
const H: f64 = 0.3;
const W: f64 = 0.5;

/// Two identical neo-Hookean bodies (a quarter, symmetry planes x = 0 and
/// y = 0) mirrored across the plane z = H where their domes touch,
/// `z = H ∓ (x² + y²)/(2R)` at the facing faces, pressed together by
/// `±0.03` on their far faces in `increments` equal increments (`cells`
/// Hex8 each), with
/// Coulomb friction μ = 0.3 (Rockafellar, exact normal constraint): the
/// upper body's dome (secondary) on the lower's (primary).
fn mirrored_domes(increments: usize, cells: [usize; 3]) -> Problem {
    let dome = |up: bool| -> Mesh {
        let mut m = box_mesh(ElementKind::Hex8, cells, [W, W, H]);
        for x in &mut m.nodes {
            let r2 = x[0] * x[0] + x[1] * x[1];
            // the facing face bent onto the dome, the far face flat
            x[2] = if up {
                x[2] + (1.0 - x[2] / H) * r2 / (2.0 * R)
            } else {
                x[2] - (x[2] / H) * r2 / (2.0 * R)
            };
        }
        m
    };
    let mesh = common::two_bodies(dome(false), "lower", dome(true), "upper", [0.0, 0.0, H]);
    let mut pr = problem(mesh, Arc::new(NeoHookean::new(E, 0.3, "m").unwrap()));
    for body in ["lower", "upper"] {
        fix(&mut pr, &format!("{body}.xmin"), &[(0, 0.0)]);
        fix(&mut pr, &format!("{body}.ymin"), &[(1, 0.0)]);
    }
    fix(&mut pr, "lower.zmin", &[(2, 0.03)]);
    fix(&mut pr, "upper.zmax", &[(2, -0.03)]);
    let dt = 1.0 / increments as f64;
    pr.steps = vec![Step {
        name: "press".into(),
        end_time: 1.0,
        initial_increment: dt,
        min_increment: 1e-4,
        max_increment: dt,
    }];
    let law = NormalLaw::Rockafellar {
        p: 4.0 * E,
        k: 4.0 * E,
    };
    let mut c = surface_interface(&pr, "upper.zmin", "lower.zmax", law);
    c.friction = Some(Coulomb {
        coefficient: MU,
        tangential_penalty: 4.0 * E,
    });
    pr.set_contacts(vec![c]);
    pr
}

/// A pure normal press of two identical bodies mirrored across the contact
/// plane carries no tangential traction (identical materials uncouple the
/// normal and tangential problems): after 1, 2 and 8 press increments every
/// closed node's committed tangential traction is below 1e-8 μ p_max and
/// no node slips. Anchored at its position when last open, a closing node
/// was charged its approach as slip (measured before the fix: up to
/// 4.4 % of μP on the two spheres).
#[test]
fn a_normal_press_of_mirrored_bodies_carries_no_friction() {
    for increments in [1, 2, 8] {
        let mut pr = mirrored_domes(increments, [10, 10, 4]);
        let last = run(&mut pr);
        let (_, reports) = pr.residual_in(1.0, &last.x, &last.contact, None).unwrap();
        let p_max = reports[0].iter().map(|r| r.pressure).fold(0.0, f64::max);
        let closed = reports[0].iter().filter(|r| r.active).count();
        assert!(
            p_max > 0.0 && closed >= 10,
            "{increments} increments: {closed} closed nodes, p_max {p_max}"
        );
        let states = &last.contact.interfaces[0];
        let worst = states
            .iter()
            .filter(|s| s.friction.status != ContactStatus::Open)
            .map(|s| s.friction.traction.norm())
            .fold(0.0, f64::max);
        assert!(
            worst < 1e-8 * MU * p_max,
            "{increments} increments: tangential traction {worst:.3e} against μ p_max = {:.3e}",
            MU * p_max
        );
        let slipping = states
            .iter()
            .filter(|s| s.friction.status == ContactStatus::Slip)
            .count();
        assert_eq!(slipping, 0, "{increments} increments: slipping nodes");
    }
}

/// The first-contact offset `d' = (1 − α) d` is differentiated exactly:
/// the assembled tangent of the pressed domes (perturbed by 1e-3, so that
/// closed nodes sit through the surface, `α < 1`, or short of it, `α = 1`;
/// the upper body pushed 3e-3 further)
/// evaluated against the history of the start (every node open at its
/// initial gap) matches central differences.
#[test]
fn first_contact_tangent_matches_finite_differences() {
    let mut pr = mirrored_domes(1, [3, 3, 1]);
    let last = run(&mut pr);
    let zero = vec![0.0; pr.num_unknowns()];
    let state = pr.initial_contact_state(&zero);
    let mut x: Vec<f64> = last
        .x
        .iter()
        .zip(perturbed_state(&pr, 1e-3, false))
        .map(|(a, b)| a + b)
        .collect();
    // the upper body (the second half of the nodes) 3e-3 further down
    let n = pr.model.mesh.num_nodes();
    for node in n / 2..n {
        x[3 * node + 2] -= 3e-3;
    }
    let (_, reports) = pr.residual_in(1.0, &x, &state, None).unwrap();
    let through = reports[0]
        .iter()
        .zip(&state.interfaces[0])
        .filter(|(r, s)| r.active && r.gap < 0.0 && s.gap > 0.0)
        .count();
    assert!(through > 0, "no closing node through the surface");
    assert_tangent_matches_fd(&pr, 1.0, &x, &state, "first contact");
}
