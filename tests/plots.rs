//! Plots fit for a report (issues 15 and 30): the `[units]` of the case in
//! the axis labels of the histories and profiles (no unit without them),
//! a friction profile in two panels (the contact pressure, the tangential
//! traction below it), a history against another history's quantity (a
//! force–displacement curve), the Newton tolerance in the convergence plot.
//! Layout (legends beside the data, the colour bar of the convergence
//! plot, where the tolerance line is) is tested in `src/output`.

mod common;

use common::{cube_case, cube_folder};
use signorini::run::{run, RunOptions};
use std::path::Path;

/// The bad-input catalogue's cube case (a history, a profile) with
/// friction, `extra` appended, run in a fresh folder; returns the texts of
/// `tip.svg` (history of `displacement_z`) and `line.svg` (profile).
fn plots(extra: &str) -> (String, String) {
    let (dir, out) = run_cube(extra);
    let read = |name: &str| std::fs::read_to_string(out.join(name)).unwrap();
    let texts = (read("tip.svg"), read("line.svg"));
    drop(dir);
    texts
}

/// The cube case of [`plots`] run in a fresh folder: the folder (removed
/// when dropped) and the output folder in it.
fn run_cube(extra: &str) -> (tempfile::TempDir, std::path::PathBuf) {
    let base = cube_case();
    let case = base.replace(
        "obstacle = \"wall\"\n",
        "obstacle = \"wall\"\nfriction_coefficient = 0.3\n",
    );
    assert_ne!(case, base);
    let (dir, path) = cube_folder(&format!("{case}\n{extra}\n"));
    let out = dir.path().join("results");
    let options = RunOptions {
        output: Some(out.clone()),
        threads: Some(1),
        cancel: None,
        restart: None,
    };
    run(&path, &options).expect("the cube runs");
    (dir, out)
}

#[test]
fn units_label_the_axes() {
    let (history, profile) = plots("[units]\nlength = \"mm\"\nforce = \"N\"");
    assert!(history.contains("displacement u_z (mm)"), "history labels");
    // the two slip bounds named once (one step)
    assert_eq!(profile.matches("±μ t_N").count(), 1);
    assert!(!profile.contains("−μ t_N"));
    for label in [
        "abscissa along the line, reference configuration (mm)",
        "contact pressure t_N (N/mm²)",
        "tangential traction t_T along the line (N/mm²)",
    ] {
        assert_eq!(profile.matches(label).count(), 1, "{label}");
    }
}

/// Without `[units]` the labels name no unit: no `()`, no `(length)`.
#[test]
fn without_units_the_labels_have_none() {
    let (history, profile) = plots("");
    // the y label (the title says "Displacement u_z")
    assert!(history.contains("displacement u_z"));
    assert!(
        history.contains("Displacement u_z at node"),
        "title in words"
    );
    assert!(profile.contains("contact pressure t_N"));
    assert!(profile.contains("tangential traction t_T along the line"));
    for svg in [&history, &profile] {
        assert!(!svg.contains("(length") && !svg.contains("(force") && !svg.contains("()"));
    }
}

/// The columns of a CSV file: header → the fields of every row, as text.
fn columns(path: &Path) -> std::collections::BTreeMap<String, Vec<String>> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    header
        .iter()
        .enumerate()
        .map(|(i, h)| {
            (
                h.to_string(),
                rows.iter().map(|r| r[i].to_string()).collect(),
            )
        })
        .collect()
}

/// `x = "tip"`: the reaction on the cube's held bottom against the tip's
/// displacement. The CSV's `tip` column is the `tip` history's
/// `displacement_z` to the last digit, at the same times, and the plot
/// draws (u_z, F_z) from the origin, labelled in words and units.
#[test]
fn a_history_against_another_has_its_quantity_as_x() {
    let extra = "[units]\nlength = \"mm\"\nforce = \"N\"\n\n\
                 [[output.history]]\nname = \"push\"\nquantity = \"reaction_force_z\"\n\
                 surface = \"bottom\"\nx = \"tip\"\n";
    let (_dir, out) = run_cube(extra);
    let push = columns(&out.join("push.csv"));
    let tip = columns(&out.join("tip.csv"));
    assert_eq!(
        push.keys().collect::<Vec<_>>(),
        ["reaction_force_z", "time", "tip"]
    );
    assert_eq!(push["time"], tip["time"]);
    assert_eq!(push["tip"], tip["displacement_z"]);
    assert!(push["tip"].len() >= 2, "{:?}", push["tip"]);
    // the load pushes the tip down (u_z < 0); the bottom holds it up
    let last = |c: &Vec<String>| c.last().unwrap().parse::<f64>().unwrap();
    assert!(last(&push["tip"]) < 0.0 && last(&push["reaction_force_z"]) != 0.0);
    let svg = std::fs::read_to_string(out.join("push.svg")).unwrap();
    for text in [
        "Reaction force F_z on set &apos;bottom&apos; against displacement u_z at node",
        "displacement u_z (mm)",
        "reaction force F_z (N)",
    ] {
        assert!(svg.contains(text), "missing {text}");
    }
    // the origin and one point per increment
    assert_eq!(svg.matches("<circle").count(), push["time"].len() + 1);
    // and the convergence plot names Newton's tolerance, 1e-8 by default
    let convergence = std::fs::read_to_string(out.join("convergence.svg")).unwrap();
    assert!(convergence.contains("Newton tolerance 1e-8"));
}

/// A history's `x` must name another history of one column.
#[test]
fn a_history_x_axis_is_validated() {
    for (x, says) in [
        (
            "nothing",
            "no [[output.history]] has that name; the histories are: tip, push",
        ),
        ("push", "is this history itself"),
    ] {
        let (_dir, path) = cube_folder(&format!(
            "{}\n[[output.history]]\nname = \"push\"\nquantity = \"reaction_force_z\"\n\
             surface = \"bottom\"\nx = \"{x}\"\n",
            cube_case()
        ));
        let message = match signorini::run::Simulation::from_file(&path) {
            Ok(_) => panic!("x = {x:?} was accepted"),
            Err(e) => e.to_string(),
        };
        assert!(message.contains("output.history[1].x"), "{message}");
        assert!(message.contains(says), "{message}");
    }
}
