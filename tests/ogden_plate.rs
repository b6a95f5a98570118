//! `examples/ogden-plate`: the paper's large-deformation example (§7.2), an
//! Ogden plate pressed on a rigid foundation by a pressure on two edge
//! strips. The example itself (`plate.msh`, about 3 s a run) for the final
//! state and the cut-backs; the coarse `plate-coarse.msh` (same geometry
//! script, N = 3, NZ = 2) for the comparison of the contact methods. The
//! expected behaviour and the numbers are in the example's README.

use nalgebra::{Matrix3, Vector3};
use signorini::run::{run, RunOptions, RunOutcome};
use std::path::{Path, PathBuf};

mod common;

/// Total pressure load on the quarter model: `p · A`, `p = 0.45`, strip
/// `1.5 × 2` (a dead load on the reference area, so exact).
const EDGE_LOAD: f64 = 0.45 * 1.5 * 2.0;

fn example_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/ogden-plate")
}

/// The example's case file on `mesh` (a file of the example's folder) with
/// `edit` applied, run in a temporary folder; returns the folder (case file
/// and results), the case file and the outcome.
fn run_case(
    mesh: &str,
    edit: impl Fn(String) -> String,
) -> (tempfile::TempDir, PathBuf, RunOutcome) {
    let text = std::fs::read_to_string(example_dir().join("case.toml")).unwrap();
    let mesh = example_dir().join(mesh);
    assert!(text.contains("file = \"plate.msh\""));
    let text = edit(text.replace(
        "file = \"plate.msh\"",
        &format!("file = {:?}", mesh.display().to_string()),
    ));
    let dir = tempfile::tempdir().unwrap();
    let case = dir.path().join("case.toml");
    std::fs::write(&case, text).unwrap();
    let outcome = run(
        &case,
        &RunOptions {
            output: Some(dir.path().join("results")),
            threads: None,
            cancel: None,
            restart: None,
        },
    )
    .expect("the plate converges");
    (dir, case, outcome)
}

/// Largest rotation (degrees, of `R` in `F = RU`), largest principal
/// strain `|λ − 1|` and smallest `det F` over the quadrature points of
/// every element.
fn deformation_extremes(mesh: &signorini::mesh::Mesh, u: &[f64]) -> (f64, f64, f64) {
    let (mut rotation, mut strain, mut det) = (0.0f64, 0.0f64, f64::INFINITY);
    for element in &mesh.elements {
        let reference = signorini::fem::volume_reference(element.kind);
        for gradients in &reference.gradients {
            let (mut dx, mut dxx) = (Matrix3::zeros(), Matrix3::zeros());
            for (&n, g) in element.nodes.iter().zip(gradients) {
                let x0 = Vector3::from(mesh.nodes[n]);
                let x = x0 + Vector3::new(u[3 * n], u[3 * n + 1], u[3 * n + 2]);
                let g = Vector3::from(*g);
                dxx += x0 * g.transpose();
                dx += x * g.transpose();
            }
            let f = dx * dxx.try_inverse().unwrap();
            let svd = f.svd(true, true);
            let r = svd.u.unwrap() * svd.v_t.unwrap();
            let angle = ((r.trace() - 1.0) / 2.0).clamp(-1.0, 1.0).acos();
            rotation = rotation.max(angle.to_degrees());
            strain = svd
                .singular_values
                .iter()
                .fold(strain, |s, l| s.max((l - 1.0).abs()));
            det = det.min(f.determinant());
        }
    }
    (rotation, strain, det)
}

/// The final state of the example: the centre lifts off, the edge stays
/// closed, the contact force balances the edge load to 1e-6 relative, no
/// element is inverted, the deformation is large (rotation above 20°,
/// principal strain above 20 %), and the history and profile files are
/// written.
#[test]
fn plate_lifts_off_in_the_middle() {
    let (dir, case_path, outcome) = run_case("plate.msh", |t| t);
    assert!(common::assert_contact_pressure_nonnegative(&outcome) > 0.0);
    let case = signorini::case::load(&case_path).unwrap();
    let problem = case.build_problem().unwrap();
    let u = &outcome.displacement;
    // the element kernel also rejects det F ≤ 0 at any quadrature point
    let (_, reports) = problem
        .residual_in(1.0, u, &outcome.contact, None)
        .expect("no inverted element");
    let interface = problem.contacts.interface(0);
    let mesh = &case.mesh;
    let at = |x: f64| {
        interface
            .nodes
            .iter()
            .zip(&reports[0])
            .filter(move |(&n, _)| (mesh.nodes[n][0] - x).abs() < 1e-9)
    };
    // the centre of the plate (the origin of the quarter model)
    let (_, centre) = at(0.0)
        .find(|(&n, _)| mesh.nodes[n][1].abs() < 1e-9)
        .unwrap();
    assert!(
        centre.gap > 0.1 && !centre.active,
        "centre gap {}",
        centre.gap
    );
    // the plate's edge x = L/2, under the loaded strip
    let edge: Vec<_> = at(5.0).collect();
    assert_eq!(edge.len(), 13);
    for (&n, r) in edge {
        assert!(
            r.active && r.pressure > 0.0 && r.gap.abs() < 1e-8,
            "edge node {}: {r:?}",
            mesh.node_ids[n]
        );
    }
    let last = outcome.summary.increments.last().unwrap();
    let force = last.contact["foundation"].force;
    assert!(
        (force[2] - EDGE_LOAD).abs() < 1e-6 * EDGE_LOAD,
        "contact force {force:?} vs edge load {EDGE_LOAD}"
    );
    let (rotation, strain, det) = deformation_extremes(mesh, u);
    assert!(det > 0.5, "smallest det F {det}");
    assert!(rotation > 20.0, "largest rotation {rotation}°");
    assert!(strain > 0.2, "largest principal strain {strain}");
    // the history reads the centre node; one profile table per step
    let results = dir.path().join("results");
    let history = std::fs::read_to_string(results.join("centre_lift.csv")).unwrap();
    let final_gap: f64 = history
        .lines()
        .last()
        .unwrap()
        .split(',')
        .nth(1)
        .unwrap()
        .parse()
        .unwrap();
    assert_eq!(final_gap, centre.gap);
    assert_eq!(
        history.lines().count(),
        outcome.summary.increments.len() + 1
    );
    for step in ["half", "three_quarters", "full"] {
        let table =
            std::fs::read_to_string(results.join(format!("centre_line_pressure_{step}.csv")))
                .unwrap();
        // header and one row per node on the centre line y = 0
        assert_eq!(table.lines().count(), 1 + 31, "{step}");
    }
    assert!(results.join("centre_line_pressure.svg").exists());
}

/// The case with its three steps replaced by one step to `end_time` that
/// starts with an increment as large as the step.
fn one_step(end_time: f64) -> impl Fn(String) -> String {
    move |text: String| {
        let at = text.find("[[step]]").unwrap();
        let end = text.find("[output]").unwrap();
        format!(
            "{}[[step]]\nname = \"full\"\nend_time = {end_time:?}\ninitial_increment = {end_time:?}\n\n{}",
            &text[..at],
            &text[end..]
        )
    }
}

/// The whole load in one increment: the trial states of so large an
/// increment have an indefinite tangent. The LDLᵀ factorises it as it is
/// (its displacement pivots are not regularised towards a sign, only the
/// multipliers'), so no iteration needs the sparse LU (before, the
/// regularised factor was another matrix and the LU solved those
/// iterations; before that fallback the stepper cut the increment). From
/// the plain start (`predictor = "none"`, every correction by the linear
/// solver), the run equals the one solved by the LU with partial pivoting
/// in every iteration to 1e-10 of the largest displacement, in as many
/// iterations; the default start (the contact predictor: its
/// Josephy–Newton steps factorise their own shifted tangent) ends on the
/// same state to 1e-10, and the three-step run to 1e-6 (the problem is
/// path independent: hyperelastic, frictionless).
#[test]
fn whole_load_at_once_converges() {
    let (_dir, _case, at_once) = run_case("plate.msh", one_step(1.0));
    let summary = &at_once.summary;
    assert_eq!(summary.status, "completed");
    assert_eq!(summary.predictor, "contact");
    assert_eq!(summary.steps.len(), 1);
    assert_eq!(summary.increments.last().unwrap().time, 1.0);
    assert_eq!(summary.lu_solves, 0, "{:?}", summary.steps);
    let plain_with = |linear: &'static str| {
        move |t| one_step(1.0)(t) + &format!("\n[solver]\npredictor = \"none\"\n{linear}\n")
    };
    let (_dir, _case, plain) = run_case("plate.msh", plain_with(""));
    assert_eq!(plain.summary.lu_solves, 0, "{:?}", plain.summary.steps);
    let (_dir, _case, by_lu) = run_case("plate.msh", plain_with("linear = \"lu\""));
    let iterations = |o: &RunOutcome| -> Vec<usize> {
        o.summary.increments.iter().map(|i| i.iterations).collect()
    };
    assert_eq!(iterations(&by_lu), iterations(&plain));
    let newton: usize = iterations(&by_lu).iter().sum();
    assert_eq!(by_lu.summary.lu_solves, newton);
    let scale = max_abs(&by_lu.displacement);
    let difference = max_difference(&plain.displacement, &by_lu.displacement);
    assert!(difference < 1e-10 * scale, "against the LU: {difference:e}");
    let difference = max_difference(&at_once.displacement, &plain.displacement);
    assert!(
        difference < 1e-10 * scale,
        "default against plain: {difference:e}"
    );
    let (_dir, _case, stepped) = run_case("plate.msh", |t| t);
    let scale = max_abs(&stepped.displacement);
    let difference = max_difference(&at_once.displacement, &stepped.displacement);
    assert!(difference < 1e-6 * scale, "difference {difference}");
}

fn max_abs(u: &[f64]) -> f64 {
    u.iter().fold(0.0f64, |m, v| m.max(v.abs()))
}

fn max_difference(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
}

/// The displacements (multipliers left out) of the coarse case run to
/// `end_time` in one step with each of `methods`.
fn method_fields(methods: &[&str], end_time: f64) -> Vec<Vec<f64>> {
    methods
        .iter()
        .map(|method| {
            let (_dir, case, outcome) = run_case("plate-coarse.msh", |t| {
                one_step(end_time)(t).replace(
                    "method = \"rockafellar\"",
                    &format!("method = \"{method}\""),
                )
            });
            let dofs = 3 * signorini::case::load(&case).unwrap().mesh.num_nodes();
            outcome.displacement[..dofs].to_vec()
        })
        .collect()
}

/// Largest nodal difference of every field from the first, relative to
/// the first's largest displacement.
fn spread(fields: &[Vec<f64>]) -> f64 {
    let scale = max_abs(&fields[0]);
    fields[1..]
        .iter()
        .map(|f| max_difference(f, &fields[0]) / scale)
        .fold(0.0, f64::max)
}

/// The Lagrangian methods reach the same displacement field to the solver
/// tolerance (largest nodal difference below 1e-6 of the largest
/// displacement): Uzawa, Rockafellar and slack at the full load, in one
/// step from a large first increment (the centre lifted off).
#[test]
fn lagrangian_methods_agree() {
    let full = method_fields(&["rockafellar", "uzawa", "slack"], 1.0);
    assert!(spread(&full) < 1e-6, "full load: {}", spread(&full));
}
