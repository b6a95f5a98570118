//! Dual mortar contact between two deformable bodies through the node
//! driver (issue 28): the contact patch test on non-matching meshes (the
//! stacked blocks of `tests/two_pass.rs`), either body as the secondary,
//! element-size ratios 1:1.6 and 1:3, linear and quadratic elements; the
//! case file's `discretisation = "mortar"` and its refusals.
//!
//! Reference: the uniform-pressure solution of two linear elastic blocks
//! (E = 100, ν = 0.3) under a dead pressure P = 2 on the upper top, with
//! symmetry planes x = 0, y = 0 and the lower bottom held in z: the
//! uniaxial stress `σ = −P e_z ⊗ e_z` in both blocks, lateral strain
//! `ν P/E`. The contact pressure `λ_j` is the dead load over the current
//! contact area, `P / (1 + ν P/E)²`, at every secondary node.

mod common;

use common::{
    assert_case_error, problem, run, stacked_blocks_case, support_stacked_blocks, two_bodies,
    write_stacked_blocks_case, CaseRun,
};
use signorini::assembly::pattern::SparsityPattern;
use signorini::contact::interface::{ContactContext, ContactInterface, NodeReport};
use signorini::contact::laws::NodeContactState;
use signorini::contact::laws::{NormalLaw, SlackState};
use signorini::material::LinearElastic;
use signorini::mesh::{structured::box_mesh, ElementKind, Mesh};
use signorini::problem::Problem;
use std::sync::Arc;

const E: f64 = 100.0;
const NU: f64 = 0.3;
const P: f64 = 2.0;

/// The upper block's material in the case files.
const LINEAR: &str = "model = \"linear_elastic\"\nyoungs_modulus = 100.0\npoisson_ratio = 0.3";

/// The stacked blocks of `kind`: lower `lower × lower × 2` cells, upper
/// `upper × upper × 2`, both 1 × 1 × 0.5, touching at z = 0.5.
fn blocks(kind: ElementKind, lower: usize, upper: usize) -> Mesh {
    let a = box_mesh(kind, [lower, lower, 2], [1.0, 1.0, 0.5]);
    let b = box_mesh(kind, [upper, upper, 2], [1.0, 1.0, 0.5]);
    two_bodies(a, "lower", b, "upper", [0.0, 0.0, 0.5])
}

/// The stacked blocks of `mesh` loaded and supported, with the mortar
/// interface of `secondary` on `primary` under `law`.
fn stacked(mesh: Mesh, secondary: &str, primary: &str, law: NormalLaw) -> Problem {
    let mut pr = problem(mesh, Arc::new(LinearElastic::new(E, NU, "m").unwrap()));
    support_stacked_blocks(&mut pr, P);
    let c = ContactInterface::mortar(&pr.model.mesh, secondary, primary, &law.into()).unwrap();
    pr.set_contacts(vec![c]);
    pr
}

/// The patch test of one configuration: the largest error of the
/// multipliers `λ_j` against `P/(1 + νP/E)²` and of every element's
/// Cauchy stress against `−P e_z ⊗ e_z`, relative to P; and Newton's
/// iterations.
fn patch_test(mesh: Mesh, secondary: &str, primary: &str, law: NormalLaw) -> (f64, f64, usize) {
    patch_test_to(1e-13, mesh, secondary, primary, law)
}

/// [`patch_test`] with Newton's residual tolerance `tolerance`.
fn patch_test_to(
    tolerance: f64,
    mesh: Mesh,
    secondary: &str,
    primary: &str,
    law: NormalLaw,
) -> (f64, f64, usize) {
    let mut pr = stacked(mesh, secondary, primary, law);
    pr.settings.residual_tolerance = tolerance;
    let last = run(&mut pr);
    let history: Vec<String> = last
        .increments
        .iter()
        .flat_map(|i| &i.newton)
        .map(|r| format!("{:.1e}", r.residual))
        .collect();
    println!("residuals {}", history.join(" "));
    let dofs = pr.model.num_dofs();
    let x = &last.x;
    let lambda = P / (1.0 + NU * P / E).powi(2);
    let reports = assemble_first(&pr, x, &last.contact.interfaces[0], None);
    let pressure_error = reports
        .iter()
        .map(|r| (r.pressure - lambda).abs() / P)
        .fold(0.0, f64::max);
    assert!(
        reports.iter().all(|r| r.active),
        "every secondary node in contact"
    );
    let stress_error = pr
        .model
        .cauchy_stresses(&x[..dofs])
        .iter()
        .map(|s| {
            let mut exact = nalgebra::Matrix3::zeros();
            exact[(2, 2)] = -P;
            (s - exact).abs().max() / P
        })
        .fold(0.0, f64::max);
    let iterations = last.increments.iter().map(|i| i.iterations).sum();
    (pressure_error, stress_error, iterations)
}

/// The first interface's reports at unknowns `x` (time 1) with its
/// node `states`, its tangent added into `tangent` when given.
fn assemble_first(
    pr: &Problem,
    x: &[f64],
    states: &[NodeContactState],
    tangent: Option<(&SparsityPattern, &mut [f64])>,
) -> Vec<NodeReport> {
    assemble_first_residual(pr, x, states, tangent).0
}

/// [`assemble_first`], with the contact residual (over every unknown).
fn assemble_first_residual(
    pr: &Problem,
    x: &[f64],
    states: &[NodeContactState],
    tangent: Option<(&SparsityPattern, &mut [f64])>,
) -> (Vec<NodeReport>, Vec<f64>) {
    let ctx = ContactContext {
        reference: &pr.model.mesh.nodes,
        t: 1.0,
        x,
        first_multiplier: pr.model.num_dofs(),
    };
    let mut residual = vec![0.0; pr.num_unknowns()];
    let reports = (pr.contacts.interface(0)).assemble(&ctx, states, &mut residual, tangent);
    (reports, residual)
}

/// Rockafellar (the default law) on the weighted gaps.
fn rockafellar() -> NormalLaw {
    NormalLaw::Rockafellar {
        p: E / 0.25,
        k: E / 0.25,
    }
}

/// The patch test of every `kinds` × `cells` (lower, upper) × either body
/// as the secondary, rockafellar: pressures and stresses to 1e-10 of P,
/// Newton's iterations at most `iterations`.
fn assert_patch_tests_exact(
    kinds: &[ElementKind],
    cells: &[(usize, usize)],
    (tolerance, iterations): (f64, usize),
) {
    for &kind in kinds {
        for &(lower, upper) in cells {
            for (secondary, primary) in [("upper.zmin", "lower.zmax"), ("lower.zmax", "upper.zmin")]
            {
                let (p, s, n) = patch_test_to(
                    tolerance,
                    blocks(kind, lower, upper),
                    secondary,
                    primary,
                    rockafellar(),
                );
                let label = format!("{kind:?} {lower}:{upper} {secondary}");
                println!("{label}: pressure {p:.2e} stress {s:.2e} iterations {n}");
                assert!(p <= 1e-10, "{label}: pressure error {p:e}");
                assert!(s <= 1e-10, "{label}: stress error {s:e}");
                assert!(n <= iterations, "{label}: {n} iterations");
            }
        }
    }
}

/// The contact patch test on non-matching linear meshes (Hex8 and Tet4),
/// either body as the secondary, element-size ratios 1:1.6 (5 × 5 against
/// 8 × 8 cells) and 1:3 (2 × 2 against 6 × 6): every multiplier is the
/// pressure on the current area and both blocks' stresses are `−P` in z,
/// to 1e-10 of P (observed ≤ 3e-13). Newton reaches the residual 1e-13
/// in one increment in at most 6 iterations (3 to 5 observed): the
/// complete linearisation (`∂D`, `∂M`, the normals and the segmentation)
/// gives the quadratic rate; without `∂D`, `∂M` it took up to 12.
#[test]
fn patch_test_on_non_matching_linear_meshes() {
    let cells = [(8, 5), (5, 8), (6, 2), (2, 6)];
    assert_patch_tests_exact(&[ElementKind::Hex8, ElementKind::Tet4], &cells, (1e-13, 6));
}

/// The contact patch test on quadratic meshes (Hex20 and Tet10: Quad8 and
/// Tri6 faces, the basis transformation of Popp et al. 2012), ratios 1:1.5,
/// 1:1.6 and 1:3 with either body as the secondary: the same exactness,
/// 1e-10 of P (observed ≤ 8.1e-12); Newton to the residual 2e-13 in at
/// most 8 iterations (5 to 7 observed; without `∂D`, `∂M` it took 9 to 19
/// to 1e-11, and the Hex20 5:8 case stalled at 2e-11). The bound is
/// above these meshes' round-off floor: with the multiplier row's area
/// term (session 19) Hex20 8:5 went 1.4e-10, then 1.2e-13, 1.1e-13,
/// 1.0e-13, 1.1e-13, 9.4e-14 (quadratic to the floor, then noise about
/// 1e-13, where the bound was).
#[test]
fn patch_test_on_non_matching_quadratic_meshes() {
    let cells = [(3, 2), (2, 3), (8, 5), (5, 8), (6, 2), (2, 6)];
    assert_patch_tests_exact(
        &[ElementKind::Hex20, ElementKind::Tet10],
        &cells,
        (2e-13, 8),
    );
}

/// `discretisation = "mortar"` through the CLI's `run` (the stacked
/// blocks, Hex8 4 × 4 against 3 × 3, rockafellar, residual tolerance
/// 1e-13): `summary.json`'s force is P × its area (1e-10), the area the
/// whole contact surface (1, 1e-12), `primary_force` minus the force
/// (1e-10 of P), `contact_pressure` is `λ_j =
/// P/(1 + νP/E)²` at every secondary node (1e-10 of P); `auto` takes the
/// monolithic path because the upper block is held only by contact (mortar
/// between bodies is condensed under `auto` since session 21).
#[test]
fn mortar_through_the_case_file() {
    let dir = tempfile::tempdir().unwrap();
    let path = write_stacked_blocks_case(dir.path(), LINEAR, "discretisation = \"mortar\"");
    let text = std::fs::read_to_string(&path)
        .unwrap()
        .replace("residual_tolerance = 1e-10", "residual_tolerance = 1e-13");
    std::fs::write(&path, text).unwrap();
    let run = CaseRun::new(&path, &dir.path().join("out"));
    let contact = &run.outcome.summary.increments.last().unwrap().contact["interface"];
    assert!((contact.area - 1.0).abs() < 1e-12, "area {}", contact.area);
    let force = contact.force[2];
    assert!(
        (force - P * contact.area).abs() < 1e-10 * P,
        "force {force}"
    );
    // Newton's third law through M (every secondary face fully covered,
    // Σ_l M_jl = D_j): the force on the primary surface is minus the
    // secondary's
    let primary = contact
        .primary_force
        .expect("mortar reports the primary force");
    for d in 0..3 {
        let secondary = contact.force[d] + contact.tangential_force[d];
        assert!(
            (primary[d] + secondary).abs() < 1e-10 * P,
            "primary_force {primary:?}, secondary force {:?}",
            contact.force
        );
    }
    let why = signorini::problem::condensed::not_applicable(&run.problem).unwrap();
    assert!(why.contains("held only by contact"), "{why}");
    let pressure = run.last_field("contact_pressure");
    let mesh = &run.problem.model.mesh;
    let lambda = P / (1.0 + NU * P / E).powi(2);
    for n in mesh.surface_nodes(mesh.surface("upper.zmin").unwrap()) {
        assert!(
            (pressure[n] - lambda).abs() < 1e-10 * P,
            "node {n}: {}",
            pressure[n]
        );
    }
}

/// The case file's refusals of mortar, each naming `contact[0]` and the
/// key: `two_pass`, and an unknown discretisation (friction is accepted
/// between two bodies, `tests/mortar_friction.rs`, and against an
/// obstacle, `tests/mortar_obstacle_friction.rs`).
#[test]
fn mortar_refusals_name_the_key() {
    let dir = tempfile::tempdir().unwrap();
    write_stacked_blocks_case(dir.path(), LINEAR, "");
    let mortar = "discretisation = \"mortar\"";
    let case = |extra: &str| stacked_blocks_case(LINEAR, &format!("{mortar}\n{extra}"));
    let expect = ["contact[0].discretisation = \"mortar\"", "two_pass"];
    assert_case_error(
        dir.path(),
        &case("method = \"uzawa\"\ntwo_pass = true"),
        &expect,
    );
    let unknown = stacked_blocks_case(LINEAR, "discretisation = \"segment\"");
    assert_case_error(
        dir.path(),
        &unknown,
        &["segment", "node_to_surface", "mortar"],
    );
}

/// Every normal law on the weighted gaps (penalty, uzawa, rockafellar,
/// slack; parameter 4E, the automatic E/h of the 1:1.6 blocks' finer side
/// is 8E): the patch test stays exact (1e-10 of P), since a uniform
/// pressure needs no exact gap, only a uniform one.
#[test]
fn patch_test_with_every_law() {
    for (name, law) in common::every_method(4.0 * E) {
        let (p, s, iterations) = patch_test(
            blocks(ElementKind::Hex8, 8, 5),
            "upper.zmin",
            "lower.zmax",
            law,
        );
        println!("{name}: pressure {p:.2e} stress {s:.2e} iterations {iterations}");
        assert!(p <= 1e-10, "{name}: pressure error {p:e}");
        assert!(s <= 1e-10, "{name}: stress error {s:e}");
    }
}

/// A face pair the mortar kernels cannot integrate leaves every node of
/// the interface open (`MortarSurfaces::covered_rows`); the report says
/// so, as `summary.json`'s `warning` of the interface (which the log
/// prints as a `warning:` line), instead of an open interface without a
/// word. One secondary face of the stacked blocks is collapsed onto a
/// line (zero area: its integrals are NaN, which leave its nodes open;
/// 3 of its 4 measured): the warning names the interface, the failure and
/// how many nodes are left open, some of the face's 4, and at least that
/// many are no longer closed; in the pressed state before, every node is
/// closed and there is none.
#[test]
fn a_face_pair_that_cannot_be_integrated_is_reported() {
    let pr = stacked(
        blocks(ElementKind::Hex8, 3, 2),
        "upper.zmin",
        "lower.zmax",
        rockafellar(),
    );
    let mesh = &pr.model.mesh;
    let secondary = mesh.surface_nodes(mesh.surface("upper.zmin").unwrap());
    let at = |x: f64, y: f64| {
        (secondary.iter().copied())
            .find(|&n| mesh.nodes[n][0] == x && mesh.nodes[n][1] == y)
            .expect("a node of the upper bottom")
    };
    let totals = |x: &[f64]| {
        let state = pr.initial_contact_state(x);
        let reports = assemble_first(&pr, x, &state.interfaces[0], None);
        let report = pr
            .contacts
            .report(&mesh.nodes, x, &state, &state, vec![reports]);
        report.totals[0].1.clone()
    };
    // pressed in by 1e-3: every node closed
    let mut x = vec![0.0; pr.num_unknowns()];
    secondary.iter().for_each(|&n| x[3 * n + 2] = -1e-3);
    let pressed = totals(&x);
    assert!(pressed.warning.is_none(), "{:?}", pressed.warning);
    assert_eq!(pressed.closed_nodes, secondary.len());
    // the corner face's nodes (0, 0), (0.5, 0), (0.5, 0.5), (0, 0.5) put on
    // the line x = 0.5: (0, 0) onto (0.5, 0.5), (0, 0.5) onto (0.5, 0)
    let (corner, edge) = (at(0.0, 0.0), at(0.0, 0.5));
    x[3 * corner] = 0.5;
    x[3 * corner + 1] = 0.5;
    x[3 * edge] = 0.5;
    x[3 * edge + 1] = -0.5;
    let folded = totals(&x);
    let warning = folded
        .warning
        .clone()
        .expect("a warning on the folded face");
    println!("{warning}");
    assert!(
        warning.contains("contact 'upper.zmin'")
            && warning.contains("not finite")
            && warning.contains("left open"),
        "{warning}"
    );
    // the nodes named are among the face's 4, and they are open (the
    // distorted neighbouring face may open more: 5 of 9 closed measured)
    let open: usize = (warning.split("integrals of ").nth(1))
        .and_then(|w| w.split(' ').next())
        .and_then(|n| n.parse().ok())
        .expect("the count of nodes left open");
    assert!((1..=4).contains(&open), "{warning}");
    assert!(folded.closed_nodes <= secondary.len() - open, "{folded:?}");
}

/// Dual mortar's tangent is nonsymmetric (Popp, Gee & Wall 2009: the force
/// acts through the gap's gradient at fixed `D`, `M`, the constraint row
/// keeps the whole gradient), and the problem says so, so that Newton
/// solves it as nonsymmetric instead of factorising its lower triangle
/// alone (which left two-spheres with mortar to the LU after every LDLᵀ).
/// At the converged patch test on non-matching Tet4 blocks (3 and 5 cells)
/// with the faces waved by 0.02 (a trial state), `K_uλ` and `K_λuᵀ` differ
/// by more than 1e-3 of the largest entry of `K_λu`: the asymmetry is the
/// formulation's, not round-off.
#[test]
fn mortar_between_bodies_has_a_nonsymmetric_tangent() {
    let mesh = blocks(ElementKind::Tet4, 3, 5);
    let mut pr = stacked(mesh, "upper.zmin", "lower.zmax", rockafellar());
    assert!(pr.has_nonsymmetric_tangent());
    let last = run(&mut pr);
    // the contact faces waved (a trial state of Newton): at the converged
    // flat state the two differ by round-off only, the derivatives of `D`
    // and `M` acting on gaps and offsets that are zero there
    let mut x = last.x.clone();
    for (n, p) in pr.model.mesh.nodes.iter().enumerate() {
        x[3 * n + 2] += 0.02 * (3.0 * p[0]).sin() * (2.0 * p[1]).cos();
    }
    let pattern = &pr.model.pattern;
    let mut k = vec![0.0; pattern.nnz()];
    assemble_first(
        &pr,
        &x,
        &last.contact.interfaces[0],
        Some((pattern, &mut k)),
    );
    let (mut asymmetry, mut scale) = (0.0f64, 0.0f64);
    for m in 0..pattern.num_multipliers() {
        for a in 0..pattern.num_nodes() {
            let Some(e) = pattern.multiplier_entries(m, a) else {
                continue;
            };
            for i in 0..3 {
                let (column, row) = (k[e.node_rows[i]], k[e.multiplier_row[i]]);
                asymmetry = asymmetry.max((column - row).abs());
                scale = scale.max(row.abs());
            }
        }
    }
    assert!(scale > 0.0, "the multiplier rows are assembled");
    assert!(
        asymmetry > 1e-3 * scale,
        "asymmetry {asymmetry:e} of {scale:e}"
    );
}

/// A secondary node without mortar support (no segment with the primary
/// surface, or `D_j ≤ 0`) is inactive by definition (Hüeber & Wohlmuth
/// 2005; Popp, Gee & Wall 2009), whatever its multiplier: its multiplier
/// row is the inactive one, `r_λ = −A k²λ/p` and `K_λλ = −A k²/p` with
/// nothing on the displacements (Newton's step then sets `λ` to 0), to
/// 1e-12, for Rockafellar's law and the slack law (its local unknowns
/// clamped). The upper block's bottom (Hex8, 2 × 2 cells over 3 × 3) slid
/// by 0.75 in x: its 6 nodes at x ≥ 0.5 have no primary face under them
/// (x ≥ 1.25) or only the far half of one face (`D_j < 0`). With `λ = 1`,
/// `kλ = 400` is above `p` times the open gap (the search margin, 2/3),
/// where the law's switch alone calls the node active: its row was then
/// `r_λ = −A k g` with `K_λλ = 0` and no `∂r_λ/∂q`, a zero row (the
/// singular tangent two-spheres with mortar met on Newton's path).
#[test]
fn a_node_without_mortar_support_is_inactive() {
    let slack = NormalLaw::Slack {
        p: E / 0.25,
        k: E / 0.25,
    };
    for law in [rockafellar(), slack] {
        let (NormalLaw::Rockafellar { p, k } | NormalLaw::Slack { p, k }) = law else {
            unreachable!("a law with a multiplier");
        };
        let pr = stacked(
            blocks(ElementKind::Hex8, 3, 2),
            "upper.zmin",
            "lower.zmax",
            law,
        );
        let mesh = &pr.model.mesh;
        let interface = pr.contacts.interface(0);
        let dofs = pr.model.num_dofs();
        let mut x = vec![0.0; pr.num_unknowns()];
        for &n in &interface.nodes {
            x[3 * n] = 0.75;
        }
        let lambda = 1.0;
        x[dofs..dofs + interface.nodes.len()].fill(lambda);
        let mut states = pr.initial_contact_state(&x).interfaces[0].clone();
        states.iter_mut().for_each(|s| {
            s.slack = SlackState {
                s: 0.0,
                lambda1: 1.0,
            }
        });
        let pattern = &pr.model.pattern;
        let mut tangent = vec![0.0; pattern.nnz()];
        let (reports, residual) =
            assemble_first_residual(&pr, &x, &states, Some((pattern, &mut tangent)));
        let mut unsupported = 0;
        for (i, &n) in interface.nodes.iter().enumerate() {
            if mesh.nodes[n][0] < 0.5 {
                continue;
            }
            unsupported += 1;
            assert!(!reports[i].active, "{law:?} node {n}: {:?}", reports[i]);
            let area = interface.areas[i];
            let diagonal = tangent[pattern.multiplier_diagonal(i)];
            let expected = -area * k * k / p;
            assert!(
                (diagonal - expected).abs() <= 1e-12 * expected.abs(),
                "{law:?} node {n}: K_λλ {diagonal:e}, inactive {expected:e}"
            );
            let r = residual[dofs + i];
            assert!(
                (r - expected * lambda).abs() <= 1e-12 * expected.abs(),
                "{law:?} node {n}: r_λ {r:e}, inactive {:e}",
                expected * lambda
            );
            let row = (0..pattern.num_nodes())
                .filter_map(|a| pattern.multiplier_entries(i, a))
                .flat_map(|e| e.multiplier_row)
                .map(|e| tangent[e].abs())
                .fold(0.0, f64::max);
            assert_eq!(row, 0.0, "{law:?} node {n}: ∂r_λ/∂q");
        }
        assert_eq!(unsupported, 6, "{law:?}");
    }
}
