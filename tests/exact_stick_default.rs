//! Exact stick is the default where the method has multipliers (issue 31
//! item 6): `examples/press-pull` (Rockafellar, μ = 0.3) without its
//! `exact_stick = true` line gives an answer that does not depend on the
//! tangential penalty `ε_T`, on the condensed path (its default) and the
//! monolithic one; `exact_stick = false` keeps the regularised law, whose
//! answer does.

use signorini::run::{run, RunOptions, RunOutcome};
use std::path::Path;

/// `examples/press-pull` with its `[[contact]]` given `keys` (after the
/// friction coefficient) and `extra` appended, run in a temporary folder.
fn press_pull(keys: &str, extra: &str) -> RunOutcome {
    let example = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/press-pull");
    let case = std::fs::read_to_string(example.join("case.toml")).unwrap();
    // the default law: the example's `exact_stick = true` line removed
    let line = case
        .lines()
        .find(|l| l.starts_with("exact_stick"))
        .unwrap()
        .to_string();
    let case = case.replace(&format!("{line}\n"), "");
    assert!(!case.contains("exact_stick"));
    let case = case.replace(
        "friction_coefficient = 0.3\n",
        &format!("friction_coefficient = 0.3\n{keys}\n"),
    );
    let dir = tempfile::tempdir().unwrap();
    std::fs::copy(example.join("block.msh"), dir.path().join("block.msh")).unwrap();
    let path = dir.path().join("case.toml");
    std::fs::write(&path, format!("{case}\n{extra}")).unwrap();
    let options = RunOptions {
        output: Some(dir.path().join("out")),
        threads: None,
        cancel: None,
        restart: None,
    };
    run(&path, &options).unwrap_or_else(|e| panic!("press-pull with {keys:?}: {e}"))
}

/// The largest change of a nodal displacement between `a` and `b`,
/// relative to the largest of `a` (the outcome's vector also holds the
/// monolithic path's multipliers after the `3n` displacements).
fn relative_change(a: &RunOutcome, b: &RunOutcome) -> f64 {
    let case = signorini::case::load(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/press-pull/case.toml"),
    )
    .unwrap();
    let dofs = 3 * case.build_problem().unwrap().model.mesh.num_nodes();
    let (a, b) = (&a.displacement[..dofs], &b.displacement[..dofs]);
    let size = a.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let change = a
        .iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
    assert!(size > 0.0);
    change / size
}

/// ε_T = E and 100 E (E = 1000; the automatic ε_T is 10 E/h_s): the final
/// displacements agree to 1e-8 of the largest, on both paths; the pull
/// ends in partial slip (stick and slip nodes both present), so the
/// tangential law acts. The regularised law (`exact_stick = false`) moves
/// by more than 1e-6 for the same ×100 (its stick is elastic, `t_T/ε_T`).
#[test]
fn press_pull_does_not_depend_on_the_tangential_penalty() {
    for strategy in ["", "[solver]\nstrategy = \"monolithic\""] {
        let soft = press_pull("tangential_penalty = 1000.0", strategy);
        let stiff = press_pull("tangential_penalty = 100000.0", strategy);
        let last = &soft.summary.increments.last().unwrap().contact["base"];
        assert!(last.stick_nodes > 0 && last.slip_nodes > 0, "partial slip");
        let change = relative_change(&soft, &stiff);
        eprintln!("exact stick, {strategy:?}: ε_T ×100 changes u by {change:.3e}");
        assert!(change < 1e-8, "{strategy:?}: {change:.3e}");
    }
    let soft = press_pull("tangential_penalty = 1000.0\nexact_stick = false", "");
    let stiff = press_pull("tangential_penalty = 100000.0\nexact_stick = false", "");
    let change = relative_change(&soft, &stiff);
    eprintln!("regularised: ε_T ×100 changes u by {change:.3e}");
    assert!(change > 1e-6, "regularised, yet {change:.3e}");
}
