//! A run owns its output folder (issue 31 item 2): it holds the lock of
//! `.signorini.lock` in the folder for its whole life, so that a second
//! run into the folder (another case, or a restart) is refused at once
//! while the first completes alone; a lock left by a killed run is taken
//! over by the next.

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::time::{Duration, Instant};

const LOCK: &str = ".signorini.lock";

/// examples/press-pull in `dir` (its mesh by absolute path) under the
/// series name `name`, with increments of `increment` in both steps.
fn case(dir: &Path, name: &str, increment: Option<f64>) -> PathBuf {
    let example = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/press-pull");
    let mut text = std::fs::read_to_string(example.join("case.toml"))
        .unwrap()
        .replacen(
            "file = \"block.msh\"",
            &format!("file = {:?}", example.join("block.msh")),
            1,
        )
        .replacen("name = \"press-pull\"", &format!("name = \"{name}\""), 1);
    if let Some(h) = increment {
        for initial in ["initial_increment = 0.5", "initial_increment = 0.25"] {
            text = text.replacen(
                initial,
                &format!("initial_increment = {h}\nmax_increment = {h}"),
                1,
            );
        }
    }
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(&path, text).unwrap();
    path
}

/// `signorini run CASE` with `args` (`--output DIR`, `--restart DIR`), started.
fn start(case: &Path, args: &[&Path]) -> Child {
    Command::new(env!("CARGO_BIN_EXE_signorini"))
        .arg("run")
        .arg(case)
        .args(["--quiet", "--threads", "1"])
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap()
}

/// `signorini run CASE --output OUT`, started.
fn run_into(case: &Path, out: &Path) -> Child {
    start(case, &[Path::new("--output"), out])
}

/// The VTU files of the series `name` in `out`.
fn series_vtus(out: &Path, name: &str) -> usize {
    std::fs::read_dir(out)
        .unwrap()
        .filter(|e| {
            let f = e
                .as_ref()
                .unwrap()
                .file_name()
                .to_string_lossy()
                .into_owned();
            f.starts_with(&format!("{name}_")) && f.ends_with(".vtu")
        })
        .count()
}

/// Waits (at most 2 minutes) until the lock file of `out` names `pid`:
/// the run holds the folder.
fn wait_for_holder(out: &Path, pid: u32) {
    let start = Instant::now();
    while std::fs::read_to_string(out.join(LOCK)).map_or(true, |t| t.trim() != pid.to_string()) {
        assert!(
            start.elapsed() < Duration::from_secs(120),
            "the run never took the lock"
        );
        std::thread::sleep(Duration::from_millis(10));
    }
}

fn finished(child: Child) -> (Output, String) {
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(!stderr.contains("panicked"), "{stderr}");
    (out, stderr)
}

fn summary(out: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap()
}

#[test]
fn a_second_run_into_a_held_folder_is_refused_and_the_first_completes_alone() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("results");
    // the first run: 500 increments, long enough to be under way while
    // the others start
    let long = case(tmp.path(), "first", Some(0.004));
    let first = run_into(&long, &out);
    wait_for_holder(&out, first.id());
    // another case into the same folder, and a restart of the first from
    // it: refused at once
    let other = case(tmp.path(), "second", None);
    let attempts = [
        run_into(&other, &out),
        start(&long, &[Path::new("--restart"), &out]),
    ];
    for attempt in attempts {
        let (refused, stderr) = finished(attempt);
        assert_eq!(refused.status.code(), Some(1), "{stderr}");
        for k in [
            format!("process {}", first.id()),
            "is writing into this folder".into(),
            LOCK.into(),
            "another folder".into(),
        ] {
            assert!(stderr.contains(&k), "'{k}' is not in:\n{stderr}");
        }
    }
    let (first_out, stderr) = finished(first);
    assert!(first_out.status.success(), "{stderr}");
    // the folder holds the first run's files only: its 500 VTU files, listed
    let summary = summary(&out);
    assert_eq!(summary["status"], "completed");
    let increments = summary["increments"].as_array().unwrap();
    assert_eq!(increments.len(), 250 + 250);
    for entry in std::fs::read_dir(&out).unwrap() {
        let file = entry.unwrap().file_name().to_string_lossy().into_owned();
        assert!(
            !file.starts_with("second") && !file.ends_with(".tmp"),
            "{file} is in the folder"
        );
    }
    // and its reference state (t = 0, `first_0000.vtu`)
    assert_eq!(series_vtus(&out, "first"), increments.len() + 1);
    // released at the end: emptied, and free for the next run
    assert_eq!(std::fs::read_to_string(out.join(LOCK)).unwrap(), "");
}

#[cfg(unix)]
#[test]
fn the_lock_of_a_killed_run_is_taken_over() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("results");
    let long = case(tmp.path(), "first", Some(0.004));
    let mut killed = run_into(&long, &out);
    wait_for_holder(&out, killed.id());
    std::thread::sleep(Duration::from_millis(200));
    let status = Command::new("kill")
        .args(["-KILL", &killed.id().to_string()])
        .status()
        .unwrap();
    assert!(status.success());
    killed.wait().unwrap();
    // the kernel released the lock; the file still names the killed run
    let pid = killed.id().to_string();
    assert_eq!(std::fs::read_to_string(out.join(LOCK)).unwrap().trim(), pid);
    // the next run takes the folder over, says so in its log, and completes
    let short = case(tmp.path(), "first", None);
    let (next, stderr) = finished(run_into(&short, &out));
    assert!(next.status.success(), "{stderr}");
    let log = std::fs::read_to_string(out.join("first.log")).unwrap();
    assert!(
        log.contains(&format!("left locked by run {pid}")) && log.contains("took it over"),
        "{log}"
    );
    let summary = summary(&out);
    assert_eq!(summary["status"], "completed");
    // the short run's VTU files only: the killed run's are gone
    let increments = summary["increments"].as_array().unwrap().len();
    assert!(increments < 20, "{increments}");
    // and its reference state (t = 0, `first_0000.vtu`)
    assert_eq!(series_vtus(&out, "first"), increments + 1);
    assert_eq!(std::fs::read_to_string(out.join(LOCK)).unwrap(), "");
}
