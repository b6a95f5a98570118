//! Plots fit for a report (issue 15 item 6): the `[units]` of the case in
//! the axis labels of the histories and profiles (names of the dimensions
//! without them), a friction profile in two panels (the contact pressure,
//! the tangential traction below it). Layout (legends beside the data, the
//! colour bar of the convergence plot) is tested in `src/output`.

use signorini::run::{run, RunOptions};
use std::path::Path;

/// The bad-input catalogue's cube case (a history, a profile) with
/// friction, `extra` appended, run in a fresh folder; returns the texts of
/// `tip.svg` (history of `displacement_z`) and `line.svg` (profile).
fn plots(extra: &str) -> (String, String) {
    let dir = tempfile::tempdir().unwrap();
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data");
    std::fs::copy(
        data.join("cube_hex_41_ascii.msh"),
        dir.path().join("cube.msh"),
    )
    .unwrap();
    let base = std::fs::read_to_string(data.join("cube_case.toml")).unwrap();
    let case = base.replace(
        "obstacle = \"wall\"\n",
        "obstacle = \"wall\"\nfriction_coefficient = 0.3\n",
    );
    assert_ne!(case, base);
    let path = dir.path().join("case.toml");
    std::fs::write(&path, format!("{case}\n{extra}\n")).unwrap();
    let out = dir.path().join("results");
    let options = RunOptions {
        output: Some(out.clone()),
        threads: Some(1),
        cancel: None,
        restart: None,
    };
    run(&path, &options).expect("the cube runs");
    let read = |name: &str| std::fs::read_to_string(out.join(name)).unwrap();
    (read("tip.svg"), read("line.svg"))
}

#[test]
fn units_label_the_axes() {
    let (history, profile) = plots("[units]\nlength = \"mm\"\nforce = \"N\"");
    assert!(history.contains("displacement_z (mm)"), "history labels");
    for label in [
        "abscissa along the line, reference configuration (mm)",
        "contact pressure t_N (N/mm²)",
        "tangential traction t_T along the line (N/mm²)",
    ] {
        assert_eq!(profile.matches(label).count(), 1, "{label}");
    }
}

#[test]
fn without_units_the_labels_name_the_dimensions() {
    let (history, profile) = plots("");
    assert!(history.contains("displacement_z (length)"));
    assert!(profile.contains("contact pressure t_N (force/length²)"));
    assert!(profile.contains("tangential traction t_T along the line (force/length²)"));
    assert!(!profile.contains("(mm)") && !history.contains("(N"));
}
