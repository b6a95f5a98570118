//! Dual mortar contact (issue 28): the final state of a frictionless
//! problem does not depend on the load increments, and the row cache
//! integrates each configuration once.
//!
//! The problem: two neo-Hookean blocks (E = 100, ν = 0.3), non-matching
//! (the lower 1 × 1 × 0.5 block in 6 × 6 × 2 Hex8, the upper one in
//! 4 × 4 × 2), symmetry planes x = 0 and y = 0, the lower bottom held in
//! z, and a dead pressure P = 12 on a quarter of the upper top (x, y ≤ ½,
//! by the symmetry planes a central patch): the contact pressure is far
//! from uniform, the upper block bends and lifts off at its far corner,
//! and the strains (≈ 15 % under the patch) make the path nonlinear.
//! Frictionless contact of a hyperelastic body has no history: the
//! converged state at the full load is one and the same however the load
//! got there.

mod common;

use common::{problem, run, support_stacked_blocks, two_bodies, Last};
use signorini::contact::interface::{ContactInterface, Primary};
use signorini::contact::laws::NormalLaw;
use signorini::material::NeoHookean;
use signorini::mesh::{structured::box_mesh, ElementKind};
use signorini::problem::{Problem, Step};
use std::sync::Arc;

const E: f64 = 100.0;
const P: f64 = 12.0;

/// The blocks loaded on a quarter of the upper top, with the mortar
/// interface (upper bottom secondary, rockafellar), in `increments` equal
/// increments of the pressure's ramp; Newton to the residual 1e-12 and
/// the relative correction 1e-12.
fn punched_blocks(increments: usize) -> Problem {
    let lower = box_mesh(ElementKind::Hex8, [6, 6, 2], [1.0, 1.0, 0.5]);
    let upper = box_mesh(ElementKind::Hex8, [4, 4, 2], [1.0, 1.0, 0.5]);
    let mesh = two_bodies(lower, "lower", upper, "upper", [0.0, 0.0, 0.5]);
    let mut pr = problem(mesh, Arc::new(NeoHookean::new(E, 0.3, "m").unwrap()));
    // the stacked blocks' supports and pressure, on the quarter only
    support_stacked_blocks(&mut pr, P);
    let mesh = &pr.model.mesh;
    let patch = mesh
        .surface("upper.zmax")
        .unwrap()
        .facets
        .iter()
        .filter(|f| {
            f.nodes
                .iter()
                .all(|&n| mesh.nodes[n][0] <= 0.5 + 1e-12 && mesh.nodes[n][1] <= 0.5 + 1e-12)
        });
    let facets: Vec<_> = patch.cloned().collect();
    assert_eq!(facets.len(), 4, "a quarter of the 4 × 4 top");
    pr.pressures[0].facets = facets;
    let law = NormalLaw::Rockafellar {
        p: E / 0.25,
        k: E / 0.25,
    };
    let mesh = &pr.model.mesh;
    let c = ContactInterface::mortar(mesh, "upper.zmin", "lower.zmax", &law.into()).unwrap();
    pr.set_contacts(vec![c]);
    let h = 1.0 / increments as f64;
    pr.steps = vec![Step {
        name: "load".into(),
        end_time: 1.0,
        initial_increment: h,
        min_increment: 1e-3 * h,
        max_increment: h,
    }];
    pr.settings.residual_tolerance = 1e-12;
    pr.settings.displacement_tolerance = 1e-12;
    pr.settings.max_iterations = 50;
    pr
}

/// The mortar interface's row counts after a run.
fn row_counts(pr: &Problem) -> signorini::contact::mortar_contact::RowCounts {
    match &pr.contacts.interface(0).primary {
        Primary::Mortar(m) => m.row_counts(),
        _ => unreachable!("a mortar interface"),
    }
}

/// `max |a − b| / max |b|` over `range` of two runs' unknowns.
fn difference(a: &Last, b: &Last, range: std::ops::Range<usize>) -> f64 {
    common::relative_difference(&a.x[range.clone()], &b.x[range])
}

/// 1, 4 and 10 increments end in the same state: displacements and
/// multipliers agree to 1e-12 of their largest value (Newton to the
/// residual 1e-14 in each increment). The contact is partial (some
/// secondary nodes open, some closed) and the multipliers non-uniform, so
/// the agreement is not that of a patch test. Each run integrates the
/// mortar rows once per configuration Newton visits: at most once per
/// residual evaluation at a new iterate (the increment's start and one per
/// iteration), where the driver asks for them about three times as often.
#[test]
fn final_state_is_independent_of_the_increments() {
    let mut runs = Vec::new();
    for increments in [1, 4, 10] {
        let mut pr = punched_blocks(increments);
        let last = run(&mut pr);
        assert_eq!(last.increments.len(), increments, "no cut-backs");
        let iterations: usize = last.increments.iter().map(|i| i.iterations).sum();
        let counts = row_counts(&pr);
        println!("{increments} increments: {iterations} Newton iterations, rows {counts:?}");
        assert!(
            counts.integrated <= iterations + increments + 1,
            "{counts:?} for {iterations} iterations"
        );
        assert!(counts.requested >= 2 * counts.integrated, "{counts:?}");
        runs.push((pr.model.num_dofs(), last));
    }
    let (dofs, one) = &runs[0];
    let lambda = &one.x[*dofs..];
    let closed = lambda.iter().filter(|l| **l > 1e-8 * P).count();
    assert!(
        closed > 4 && closed < lambda.len(),
        "partial contact: {closed} of {} closed",
        lambda.len()
    );
    let (lo, hi) = lambda
        .iter()
        .filter(|l| **l > 1e-8 * P)
        .fold((f64::INFINITY, 0.0f64), |(lo, hi), l| {
            (lo.min(*l), hi.max(*l))
        });
    assert!(hi > 2.0 * lo, "non-uniform pressure: {lo} to {hi}");
    for (_, other) in &runs[1..] {
        let n = other.increments.len();
        let du = difference(other, one, 0..*dofs);
        let dl = difference(other, one, *dofs..one.x.len());
        println!("{n} increments against 1: displacements {du:.1e}, multipliers {dl:.1e}");
        assert!(
            du <= 1e-12,
            "{n} increments: displacements differ by {du:e}"
        );
        assert!(dl <= 1e-12, "{n} increments: multipliers differ by {dl:e}");
    }
}
