//! `[solver] predictor = "contact"`: Newton's first correction of an
//! increment solves the contact problem linearised at the iterate
//! exactly, a
//! Josephy–Newton step (`src/solve/josephy.rs`). It changes Newton's path,
//! not the answer, and takes at most 5 iterations per increment where the
//! plain start takes more. The default, `predictor = "auto"`, takes it
//! where it applies (frictionless Rockafellar contact against axis-aligned
//! rigid planes) and the plain start elsewhere, and says which in the
//! summary.

use signorini::output::{ConvergedIncrement, StepObserver, Summary};
use signorini::run::{RunOptions, RunOutcome, Simulation};
use std::path::Path;

mod common;
use common::relative_difference;

/// Nothing to observe: the outcome's summary has the iterations.
struct Quiet;

impl StepObserver for Quiet {
    fn on_increment(&mut self, _: &ConvergedIncrement, _: &Summary) -> signorini::Result<()> {
        Ok(())
    }
}

/// `examples/<example>/case.toml` on the mesh `mesh` (relative to the
/// crate), with `replacements` made and `solver` as its `[solver]`
/// section, run in memory on one thread.
fn run(
    example: &str,
    mesh: (&str, &str),
    replacements: &[(&str, &str)],
    solver: &str,
) -> RunOutcome {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let folder = root.join("examples").join(example);
    let mut text = std::fs::read_to_string(folder.join("case.toml")).unwrap();
    let file = root.join(mesh.1);
    let mut all = vec![(mesh.0, format!("file = {:?}", file.display().to_string()))];
    all.extend(replacements.iter().map(|(a, b)| (*a, b.to_string())));
    for (old, new) in all {
        assert!(text.contains(old), "{old}");
        text = text.replace(old, &new);
    }
    assert!(!text.contains("[solver]"));
    text.push_str(&format!("\n[solver]\n{solver}\n"));
    let mut simulation = Simulation::from_toml(&text, &folder).unwrap();
    let options = RunOptions {
        threads: Some(1),
        output: None,
        cancel: None,
        restart: None,
    };
    simulation
        .run(&options, &mut Quiet)
        .unwrap_or_else(|e| panic!("{solver}: {e}"))
}

/// The `[solver]` line of `predictor`; none for `"default"` (the
/// default, `auto`, then runs).
fn predictor_line(predictor: &str) -> String {
    match predictor {
        "default" => String::new(),
        p => format!("predictor = \"{p}\""),
    }
}

/// The coarse Hertz hemisphere (2.4 k dofs, Rockafellar, frictionless,
/// linear elastic, node-to-surface named: the contact predictor is
/// node-to-surface's, and the example takes dual mortar by default),
/// monolithic, with `predictor` and the first increment `first`.
fn hertz(predictor: &str, first: &str) -> RunOutcome {
    hertz_with(predictor, &[("initial_increment = 0.25", first)])
}

/// [`hertz`] with the case's `replacements` made.
fn hertz_with(predictor: &str, replacements: &[(&str, &str)]) -> RunOutcome {
    let node_to_surface = (
        "method = \"rockafellar\"",
        "method = \"rockafellar\"\ndiscretisation = \"node_to_surface\"",
    );
    let replacements: Vec<(&str, &str)> = std::iter::once(node_to_surface)
        .chain(replacements.iter().copied())
        .collect();
    run(
        "hertz",
        (
            "file = \"hemisphere.msh\"",
            "tests/data/hemisphere_coarse.msh",
        ),
        &replacements,
        &format!("strategy = \"monolithic\"\n{}", predictor_line(predictor)),
    )
}

/// The coarse Ogden plate (same geometry as examples/ogden-plate, N = 3,
/// NZ = 2; finite strain, lifting off in the middle), three steps of one
/// increment each.
fn plate(predictor: &str) -> RunOutcome {
    run(
        "ogden-plate",
        (
            "file = \"plate.msh\"",
            "examples/ogden-plate/plate-coarse.msh",
        ),
        &[],
        &predictor_line(predictor),
    )
}

fn iterations(outcome: &RunOutcome) -> Vec<usize> {
    outcome
        .summary
        .increments
        .iter()
        .map(|i| i.iterations)
        .collect()
}

/// Hertz is linear but for the contact set, so the Josephy step from the
/// converged state is the increment's answer: one step and one Newton
/// correction that only confirms it (of round-off size) per increment,
/// against 4, 4, 3 from the plain start; the final state is the plain
/// start's to round-off (1e-12), and independent of the increments (one
/// increment, or 0.1 growing) to round-off too.
#[test]
fn hertz_takes_two_iterations_per_increment_and_the_same_answer() {
    let plain = hertz("none", "initial_increment = 0.25");
    let contact = hertz("contact", "initial_increment = 0.25");
    let (its_plain, its_contact) = (iterations(&plain), iterations(&contact));
    eprintln!("hertz: plain {its_plain:?}, contact {its_contact:?}");
    assert!(its_contact.iter().all(|&n| n <= 2), "{its_contact:?}");
    assert!(its_plain.iter().sum::<usize>() > its_contact.iter().sum::<usize>());
    let du = relative_difference(&contact.displacement, &plain.displacement);
    eprintln!("hertz: contact − plain final displacements {du:.1e}");
    assert!(du < 1e-12, "{du:e}");
    for first in ["initial_increment = 1.0", "initial_increment = 0.1"] {
        let other = hertz("contact", first);
        assert!(iterations(&other).iter().all(|&n| n <= 2));
        let d = relative_difference(&other.displacement, &contact.displacement);
        eprintln!("hertz, {first}: {d:.1e}");
        assert!(d < 1e-12, "{first}: {d:e}");
    }
}

/// The Ogden plate: at most 5 iterations per increment (the plain start
/// takes 6 in the first, where the contact set is found: 403 bottom nodes
/// closed at rest, most of them open at the end), and the plain start's
/// final state to 1e-8 (Newton's tolerances; 2e-12 measured).
#[test]
fn plate_takes_at_most_five_iterations_per_increment() {
    let plain = plate("none");
    let contact = plate("contact");
    let (its_plain, its_contact) = (iterations(&plain), iterations(&contact));
    eprintln!("plate: plain {its_plain:?}, contact {its_contact:?}");
    assert!(its_plain[0] > 5, "{its_plain:?}");
    assert!(its_contact.iter().all(|&n| n <= 5), "{its_contact:?}");
    let du = relative_difference(&contact.displacement, &plain.displacement);
    eprintln!("plate: contact − plain final displacements {du:.1e}");
    assert!(du < 1e-8, "{du:e}");
}

/// The example's own plate (`plate.msh`, 6 k unknowns): at most 5
/// iterations per increment by default (5, 4, 5; 6, 4, 5 before the
/// predictor's step was held to a falling residual: in the first
/// increment, rest to half the load, its full step raised `‖r‖` and
/// overshot the potential's minimum along it, and Newton now takes the
/// secant's `α = 0.75`), at most as many in all, and the plain start's
/// final state (7, 4, 7) to 1e-10.
#[test]
fn the_example_plate_takes_at_most_five_iterations_per_increment() {
    let fine = |predictor: &str| {
        run(
            "ogden-plate",
            ("file = \"plate.msh\"", "examples/ogden-plate/plate.msh"),
            &[],
            &predictor_line(predictor),
        )
    };
    let (default, plain) = (fine("default"), fine("none"));
    let (its, its_plain) = (iterations(&default), iterations(&plain));
    eprintln!("example plate: default {its:?}, plain {its_plain:?}");
    assert_eq!(default.summary.predictor, "contact");
    assert!(its.iter().all(|&n| n <= 5), "{its:?}");
    assert!(its.iter().sum::<usize>() <= 14, "{its:?}");
    let du = relative_difference(&default.displacement, &plain.displacement);
    eprintln!("example plate: default − plain final displacements {du:.1e}");
    assert!(du < 1e-10, "{du:e}");
}

/// The default predictor (`auto`) is the contact predictor on the coarse
/// Hertz hemisphere and the coarse plate (frictionless Rockafellar contact
/// against the plane z = 0): the same iterations as asking for it (hertz
/// 2, 2, 2; plate 5, 4, 3, against the plain start's 4, 4, 3 and 6, 4,
/// 4), the summary says so, and the plain start's final state to 1e-12
/// (hertz: 3.7e-14 measured) and 1e-11 (the plate, converged from another
/// start through its soft, nearly floating modes: 1.9e-12).
#[test]
fn the_default_takes_the_contact_predictor_where_it_applies() {
    for (name, default, contact, plain) in [
        (
            "hertz",
            hertz("default", "initial_increment = 0.25"),
            hertz("contact", "initial_increment = 0.25"),
            hertz("none", "initial_increment = 0.25"),
        ),
        ("plate", plate("default"), plate("contact"), plate("none")),
    ] {
        let its = iterations(&default);
        eprintln!(
            "{name}: default {its:?} ({}: {}), plain {:?}",
            default.summary.predictor,
            default.summary.predictor_reason,
            iterations(&plain)
        );
        assert_eq!(default.summary.predictor, "contact", "{name}");
        assert!(default.summary.predictor_reason.starts_with("auto"));
        assert_eq!(contact.summary.predictor, "contact", "{name}");
        assert_eq!(plain.summary.predictor, "none", "{name}");
        assert_eq!(its, iterations(&contact), "{name}");
        let expected: &[usize] = if name == "hertz" {
            &[2, 2, 2]
        } else {
            &[5, 4, 3]
        };
        assert_eq!(its, expected, "{name}");
        let du = relative_difference(&default.displacement, &plain.displacement);
        eprintln!("{name}: default − plain final displacements {du:.1e}");
        let bound = if name == "hertz" { 1e-12 } else { 1e-11 };
        assert!(du < bound, "{name}: {du:e}");
    }
}

/// Where the contact predictor does not apply (friction, another law),
/// the default is the plain start: the summary names it and why, and the
/// run is the plain start's, iteration for iteration and bit for bit.
#[test]
fn the_default_is_the_plain_start_elsewhere() {
    for (change, why) in [
        (
            ("method = \"rockafellar\"", "method = \"penalty\""),
            "Rockafellar",
        ),
        (
            (
                "method = \"rockafellar\"",
                "method = \"rockafellar\"\nfriction_coefficient = 0.2",
            ),
            "friction",
        ),
    ] {
        let default = hertz_with("default", &[change]);
        let plain = hertz_with("none", &[change]);
        eprintln!(
            "{why}: {} ({})",
            default.summary.predictor, default.summary.predictor_reason
        );
        assert_eq!(default.summary.predictor, "none", "{why}");
        assert!(
            default.summary.predictor_reason.contains(why),
            "{}",
            default.summary.predictor_reason
        );
        assert_eq!(iterations(&default), iterations(&plain), "{why}");
        assert_eq!(default.displacement, plain.displacement, "{why}");
    }
}
