//! A failed run's message names the physics it measured, and its count of
//! cuts agrees with `summary.json` (issue 31 item 5), on
//! `examples/press-pull` (a block pressed with N = 20 onto a rigid plane,
//! then pulled sideways, Coulomb μ = 0.3):
//! - pulled to 1.2 μN (the traction −14.4 for −9.6): the pull exceeds the
//!   friction capacity from t = 1 + 1/1.2 ≈ 1.833 on, every closed node
//!   slips and the block moves off along +x: the message says so, on the
//!   monolithic path and on `auto`'s (condensed, falling back to Newton);
//!   on the condensed path the message gives the load and μN it measured;
//! - frictionless (no `friction_coefficient`): nothing holds the block
//!   along x, and the pull finds that direction unsupported — the message
//!   says so and does not speak of a tangential load beyond μN.

use signorini::run::{run, RunOptions};
use std::path::Path;

/// `examples/press-pull` with `replacements` made and `extra` appended,
/// run into a temporary folder: the error's message and the summary.
fn failed_press_pull(replacements: &[(&str, &str)], extra: &str) -> (String, serde_json::Value) {
    let example = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/press-pull");
    let mut case = std::fs::read_to_string(example.join("case.toml")).unwrap();
    for (old, new) in replacements {
        assert!(case.contains(old), "{old}");
        case = case.replace(old, new);
    }
    let dir = tempfile::tempdir().unwrap();
    std::fs::copy(example.join("block.msh"), dir.path().join("block.msh")).unwrap();
    let path = dir.path().join("case.toml");
    std::fs::write(&path, format!("{case}\n{extra}")).unwrap();
    let out = dir.path().join("out");
    let options = RunOptions {
        output: Some(out.clone()),
        threads: None,
        cancel: None,
        restart: None,
    };
    let Err(error) = run(&path, &options) else {
        panic!("press-pull with {replacements:?} ran to its end");
    };
    let summary = std::fs::read_to_string(out.join("summary.json")).unwrap();
    (error.to_string(), serde_json::from_str(&summary).unwrap())
}

/// press-pull's pull raised to 1.2 μN (−14.4 for −9.6), its increments
/// no smaller than 1/64 of the pull's quarter.
const PULL: [(&str, &str); 2] = [
    ("value = -9.6", "value = -14.4"),
    (
        "initial_increment = 0.25\n",
        "initial_increment = 0.25\nmin_increment = 0.004\n",
    ),
];

/// The pull's failure names the step, the friction capacity and the
/// direction of the motion (+x).
#[track_caller]
fn assert_pull_beyond_mu_n(message: &str) {
    assert!(
        message.contains("step 'pull' did not converge"),
        "{message}"
    );
    let capacity = "the tangential load exceeds the friction capacity μN";
    assert!(message.contains(capacity), "{message}");
    assert!(message.contains("along (1.00, 0.00, 0.00)"), "{message}");
}

/// The time the last converged increment reached.
fn reached(summary: &serde_json::Value) -> f64 {
    summary["increments"].as_array().unwrap().last().unwrap()["time"]
        .as_f64()
        .unwrap()
}

/// The step's cuts in the message ("N cuts in the step in all") and in
/// the summary (`steps[].cuts` of step `name`) are the same number.
#[track_caller]
fn assert_cuts_agree(message: &str, summary: &serde_json::Value, name: &str) {
    let (before, _) = message
        .split_once(" cuts in the step in all")
        .unwrap_or_else(|| panic!("no count of the step's cuts: {message}"));
    let said: u64 = before
        .rsplit(' ')
        .next()
        .unwrap()
        .parse()
        .unwrap_or_else(|_| panic!("{message}"));
    let step = summary["steps"]
        .as_array()
        .unwrap()
        .iter()
        .find(|s| s["name"] == name)
        .unwrap_or_else(|| panic!("no step {name} in the summary"));
    assert_eq!(step["cuts"].as_u64(), Some(said), "{message}");
    assert_eq!(summary["error"].as_str(), Some(message));
    assert!(said > 0, "{message}");
    assert!(!message.contains("-0.00"), "{message}");
}

/// The pull at 1.2 μN: the message names the friction capacity and the
/// direction of the motion (+x), and its cut count is the summary's, on
/// both paths. The smallest increment is 1/64 of the pull's quarter
/// (the run stops within a few cuts of t ≈ 1.833).
#[test]
fn a_pull_beyond_mu_n_says_so_and_counts_its_cuts_as_the_summary() {
    for strategy in ["monolithic", "auto"] {
        let (message, summary) =
            failed_press_pull(&PULL, &format!("[solver]\nstrategy = \"{strategy}\"\n"));
        eprintln!("{strategy}: {message}");
        assert_pull_beyond_mu_n(&message);
        assert!(
            message.contains("every closed contact node slips"),
            "{message}"
        );
        assert!(!message.contains("reduce the tangential load"), "{message}");
        assert_cuts_agree(&message, &summary, "pull");
        // the failure is where the pull passes μN: t = 1 + 1/1.2
        let reached = reached(&summary);
        assert!((reached - (1.0 + 1.0 / 1.2)).abs() < 0.01, "{reached}");
    }
}

/// The same pull on the condensed path (`strategy = "condensed"`, which
/// cuts as Newton's does): the message names the friction capacity it
/// measured from the load — the pull along +x against μN = 0.3 × 20 (the
/// press, p = 10 on the 4 × 0.5 top) — not the contact solve's iteration
/// count, and its cut count is the summary's.
#[test]
fn a_pull_beyond_mu_n_on_the_condensed_path_names_the_capacity() {
    let (message, summary) = failed_press_pull(&PULL, "[solver]\nstrategy = \"condensed\"\n");
    eprintln!("condensed: {message}");
    assert_pull_beyond_mu_n(&message);
    assert!(
        message.contains("μN = 0.3 × 2.0000e1 = 6.0000e0"),
        "{message}"
    );
    assert!(!message.contains("Newton iterations"), "{message}");
    assert!(!message.contains("strategy"), "{message}");
    assert_cuts_agree(&message, &summary, "pull");
    // the load measured is the pull at the failed time, F = 14.4 × 0.5 ×
    // (t − 1), beyond 6 from t = 1 + 1/1.2 on
    let (_, tail) = message.split_once("the contact plane is ").unwrap();
    let load: f64 = tail.split(' ').next().unwrap().parse().unwrap();
    let (_, tail) = message.split_once("did not converge at time ").unwrap();
    let failed: f64 = tail.split(' ').next().unwrap().parse().unwrap();
    assert!(
        (load - 7.2 * (failed - 1.0)).abs() < 1e-3 * load,
        "{load} at {failed}"
    );
    assert!(load > 6.0, "{load}");
    let reached = reached(&summary);
    assert!((reached - (1.0 + 1.0 / 1.2)).abs() < 0.01, "{reached}");
}

/// Frictionless, the pull finds x unsupported: "an unsupported direction"
/// along x, with the fix (a support, or friction); not a load beyond μN.
#[test]
fn a_frictionless_pull_names_the_unsupported_direction() {
    let frictionless = [
        ("friction_coefficient = 0.3\n", ""),
        ("exact_stick = true", "# exact_stick = true"),
    ];
    let (message, summary) =
        failed_press_pull(&frictionless, "[solver]\nstrategy = \"monolithic\"\n");
    eprintln!("{message}");
    assert!(message.contains("an unsupported direction"), "{message}");
    // Newton's correction of a free mode may take either sign
    assert!(
        message.contains("along (1.00, 0.00, 0.00)")
            || message.contains("along (-1.00, 0.00, 0.00)"),
        "{message}"
    );
    assert!(message.contains("frictionless"), "{message}");
    assert!(message.contains("friction_coefficient"), "{message}");
    assert!(!message.contains("μN"), "{message}");
    assert!(!message.contains("tangential load"), "{message}");
    let step = summary["steps"].as_array().unwrap().last().unwrap()["name"]
        .as_str()
        .unwrap()
        .to_string();
    assert_cuts_agree(&message, &summary, &step);
}
