//! Every shipped example, run end to end through the library as the CLI
//! runs it, and compared with the reference stated in its README.

use signorini::run::{run, RunOptions};
use std::path::Path;

fn run_example(name: &str) -> (tempfile::TempDir, signorini::run::RunOutcome) {
    let out = tempfile::tempdir().unwrap();
    let case = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("examples")
        .join(name)
        .join("case.toml");
    let outcome = run(
        &case,
        &RunOptions {
            output: Some(out.path().to_path_buf()),
            quiet: true,
        },
    )
    .expect("the example runs");
    (out, outcome)
}

/// `examples/thick-cylinder`: Lamé's plane-strain solution
/// `u_r(r) = (1+ν) p a² / (E (b² − a²)) · ((1 − 2ν) r + b²/r)`.
/// Radial displacement within 2 % at every node (Tet4, h ≈ 0.12); the
/// reaction on the symmetry plane x = 0 balances the pressure, `−p a h`, to
/// 1e-8 relative (equilibrium holds exactly for the discrete problem).
#[test]
fn thick_cylinder_matches_lame() {
    let (out, outcome) = run_example("thick-cylinder");
    let (a, b, h, p, e, nu) = (1.0, 2.0, 0.5, 10.0, 1000.0, 0.3);
    let lame = |r: f64| {
        (1.0 + nu) * p * a * a / (e * (b * b - a * a)) * ((1.0 - 2.0 * nu) * r + b * b / r)
    };
    let case = signorini::case::load(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/thick-cylinder/case.toml"),
    )
    .unwrap();
    let u = &outcome.displacement;
    let mut worst: f64 = 0.0;
    for (n, x) in case.mesh.nodes.iter().enumerate() {
        let r = (x[0] * x[0] + x[1] * x[1]).sqrt();
        let ur = (u[3 * n] * x[0] + u[3 * n + 1] * x[1]) / r;
        worst = worst.max((ur - lame(r)).abs() / lame(r));
        // plane strain: u_z = 0 exactly; the unstructured Tet4 mesh gives a small discretisation error
        assert!(
            u[3 * n + 2].abs() < 0.01 * lame(b),
            "u_z = {}",
            u[3 * n + 2]
        );
    }
    assert!(worst < 0.02, "largest relative error of u_r: {worst}");
    let last = outcome.summary.increments.last().unwrap();
    let reaction = last.reaction_forces["symmetry_x"][0];
    assert!(
        (reaction + p * a * h).abs() < 1e-8 * p * a * h,
        "reaction {reaction}"
    );
    // the run wrote its series, summary and plot
    for f in [
        "cylinder.pvd",
        "summary.json",
        "convergence.svg",
        &last.file,
    ] {
        assert!(out.path().join(f).exists(), "{f} missing");
    }
}

/// `examples/rubber-tension`: homogeneous uniaxial tension of Ogden rubber
/// to stretch 3 and back; closed-form values from the example's README.
#[test]
fn rubber_tension_matches_closed_form() {
    let (_out, outcome) = run_example("rubber-tension");
    let incs = &outcome.summary.increments;
    let peak = incs
        .iter()
        .find(|i| (i.time - 1.0).abs() < 1e-12)
        .expect("an increment ends at t = 1");
    let (t, s11) = (0.589116143815, 2.47040956270);
    let reaction = peak.reaction_forces["xmax"][0];
    assert!(
        (reaction - s11 * t * t).abs() < 1e-6 * s11 * t * t,
        "reaction {reaction}"
    );
    // released: back to the reference configuration
    assert!(outcome.displacement.iter().all(|u| u.abs() < 1e-10));
    // one symbolic analysis for the whole run (the pattern never changes)
    assert_eq!(outcome.summary.symbolic_analyses, 1);
    // Newton's rate: every increment within 6 iterations
    assert!(
        incs.iter().all(|i| i.iterations <= 6),
        "{:?}",
        incs.iter().map(|i| i.iterations).collect::<Vec<_>>()
    );
}
