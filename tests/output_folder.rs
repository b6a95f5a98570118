//! A run owns its output folder: the files an earlier run of the same case
//! wrote (listed in `NAME.manifest`) and leftover temporary files are gone
//! after the next run, which leaves only its own files, and the `.pvd` and
//! `summary.json` name only files that are there.

use signorini::output::observer::Silent;
use signorini::run::{RunOptions, Simulation};
use std::collections::BTreeSet;
use std::path::Path;

/// The files in `dir`.
fn listing(dir: &Path) -> BTreeSet<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect()
}

/// Run examples/press-pull with its case text changed by `edit` into `out`.
fn run(out: &Path, edit: impl Fn(String) -> String) -> serde_json::Value {
    let example = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/press-pull");
    let text = edit(std::fs::read_to_string(example.join("case.toml")).unwrap());
    let mut simulation = Simulation::from_toml(&text, &example).unwrap();
    let options = RunOptions {
        output: Some(out.to_path_buf()),
        threads: Some(1),
        cancel: None,
        restart: None,
    };
    simulation.run(&options, &mut Silent).unwrap();
    serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap()
}

#[test]
fn a_new_run_removes_the_files_of_the_earlier_run_of_the_same_case() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path();
    // the earlier run: smaller increments (more VTU files) and a history
    // under another name; both runs' pull increments held (max_increment),
    // so that the counts do not depend on the growth rule
    let earlier = run(out, |t| {
        t.replace(
            "initial_increment = 0.25",
            "initial_increment = 0.125\nmax_increment = 0.125",
        )
        .replace("right_end_displacement", "old_history")
    });
    let earlier_files = earlier["increments"].as_array().unwrap().len();
    assert_eq!(earlier_files, 2 + 8);
    assert!(out.join("old_history.csv").is_file());
    assert!(out.join("press-pull_0010.vtu").is_file());
    // a file of the user's and a temporary file left by a killed run
    std::fs::write(out.join("notes.txt"), "mine").unwrap();
    std::fs::write(out.join(".press-pull_0011.vtu.4242-3.tmp"), "half").unwrap();

    let summary = run(out, |t| {
        t.replace(
            "initial_increment = 0.25",
            "initial_increment = 0.25\nmax_increment = 0.25",
        )
    });
    let increments = summary["increments"].as_array().unwrap();
    assert_eq!(increments.len(), 2 + 4);
    let vtus: BTreeSet<String> = increments
        .iter()
        .map(|i| i["file"].as_str().unwrap().to_string())
        .collect();
    let mut expected: BTreeSet<String> = [
        "press-pull.pvd",
        "press-pull.log",
        "press-pull.manifest",
        // the state a restart resumes from (issue 15 item 3)
        "press-pull.checkpoint",
        // the reference state (t = 0)
        "press-pull_0000.vtu",
        "summary.json",
        "convergence.svg",
        "contact_line.svg",
        "contact_line_press.csv",
        "contact_line_pull.csv",
        "right_end_displacement.csv",
        "right_end_displacement.svg",
    ]
    .iter()
    .map(|s| s.to_string())
    .chain(vtus.iter().cloned())
    .collect();
    // the manifest lists exactly the run's files
    let manifest: BTreeSet<String> = std::fs::read_to_string(out.join("press-pull.manifest"))
        .unwrap()
        .lines()
        .map(str::to_string)
        .collect();
    assert_eq!(manifest, expected);
    // nothing stale is left: no old history, no VTU past the sixth, no
    // temporary file; the user's file stays, and the folder's lock file
    // (tests/folder_lock.rs)
    expected.insert("notes.txt".into());
    expected.insert(".signorini.lock".into());
    assert_eq!(listing(out), expected);
    // the .pvd lists exactly the reference state and the VTU files of
    // summary.json, all there
    let pvd = std::fs::read_to_string(out.join("press-pull.pvd")).unwrap();
    let listed: BTreeSet<String> = pvd
        .split("file=\"")
        .skip(1)
        .map(|s| s[..s.find('"').unwrap()].to_string())
        .collect();
    let mut series = vtus.clone();
    series.insert("press-pull_0000.vtu".into());
    assert_eq!(listed, series);
    assert!(listed.iter().all(|f| out.join(f).is_file()));
}
