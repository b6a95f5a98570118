//! Stopping a run: the `cancel` flag of `RunOptions` (what Ctrl-C and
//! SIGTERM set in the command line, and the Python package on Ctrl-C) ends
//! the run between two Newton iterations, keeps every converged increment
//! written and consistent, and `summary.json` says `"interrupted"`.

use signorini::output::{ConvergedIncrement, Iteration, StepObserver, Summary};
use signorini::run::{RunOptions, Simulation};
use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

/// Sets the flag at the second Newton iteration of the second increment.
struct StopInSecondIncrement {
    flag: Arc<AtomicBool>,
    increments: usize,
    iterations: usize,
    iterations_after_flag: usize,
}

impl StepObserver for StopInSecondIncrement {
    fn on_increment(&mut self, _: &ConvergedIncrement, _: &Summary) -> signorini::Result<()> {
        self.increments += 1;
        self.iterations = 0;
        Ok(())
    }
    fn on_iteration(&mut self, _: &Iteration) {
        if self.flag.load(Ordering::Relaxed) {
            self.iterations_after_flag += 1;
        }
        self.iterations += 1;
        if self.increments == 1 && self.iterations == 2 {
            self.flag.store(true, Ordering::Relaxed);
        }
    }
}

#[test]
fn a_cancelled_run_stops_between_newton_iterations_and_keeps_what_converged() {
    let example = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/press-pull");
    let tmp = tempfile::tempdir().unwrap();
    let flag = Arc::new(AtomicBool::new(false));
    let mut observer = StopInSecondIncrement {
        flag: Arc::clone(&flag),
        increments: 0,
        iterations: 0,
        iterations_after_flag: 0,
    };
    let options = RunOptions {
        output: Some(tmp.path().to_path_buf()),
        threads: Some(1),
        cancel: Some(flag),
        restart: None,
    };
    // on Newton's path (auto would take the condensed one, without Newton
    // iterations to stop between)
    let text = std::fs::read_to_string(example.join("case.toml")).unwrap();
    let text = format!("{text}\n[solver]\nstrategy = \"monolithic\"\n");
    let mut simulation = Simulation::from_toml(&text, &example).unwrap();
    let error = simulation.run(&options, &mut observer).unwrap_err();
    assert!(
        matches!(error, signorini::Error::Interrupted { .. }),
        "{error}"
    );
    // no iteration after the one that set the flag, one converged increment
    assert_eq!(observer.iterations_after_flag, 0);
    assert_eq!(observer.increments, 1);
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(tmp.path().join("summary.json")).unwrap())
            .unwrap();
    assert_eq!(summary["status"], "interrupted");
    let increments = summary["increments"].as_array().unwrap();
    assert_eq!(increments.len(), 1);
    // the .pvd lists exactly the files there are
    let pvd = std::fs::read_to_string(tmp.path().join("press-pull.pvd")).unwrap();
    let listed: Vec<&str> = pvd
        .split("file=\"")
        .skip(1)
        .map(|s| &s[..s.find('"').unwrap()])
        .collect();
    // the reference state (t = 0), then the converged increment
    assert_eq!(
        listed,
        [
            "press-pull_0000.vtu",
            increments[0]["file"].as_str().unwrap()
        ]
    );
    for file in listed {
        assert!(tmp.path().join(file).is_file());
    }
}

/// The command line on SIGINT: exit code 130, `summary.json` says
/// `"interrupted"`, and every VTU the `.pvd` lists is there.
#[test]
fn sigint_stops_the_command_line_cleanly() {
    let example = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/hertz/case.toml");
    let tmp = tempfile::tempdir().unwrap();
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_signorini"))
        .args([
            "run",
            example.to_str().unwrap(),
            "--quiet",
            "--threads",
            "1",
            "--output",
        ])
        .arg(tmp.path())
        .spawn()
        .unwrap();
    // wait until the run is under way (its log has the model), then stop it
    let log = tmp.path().join("hertz.log");
    let start = std::time::Instant::now();
    while !std::fs::read_to_string(&log).is_ok_and(|l| l.contains("model:")) {
        assert!(start.elapsed().as_secs() < 120, "the run did not start");
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    std::thread::sleep(std::time::Duration::from_millis(300));
    let killed = std::process::Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(killed.success());
    let status = child.wait().unwrap();
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(tmp.path().join("summary.json")).unwrap())
            .unwrap();
    if summary["status"] == "completed" {
        // the whole run fitted in the 300 ms: nothing to stop (a very fast machine)
        assert!(status.success());
        return;
    }
    assert_eq!(status.code(), Some(130), "{status:?}");
    assert_eq!(summary["status"], "interrupted");
    let pvd = std::fs::read_to_string(tmp.path().join("hertz.pvd")).unwrap();
    let listed: Vec<&str> = pvd
        .split("file=\"")
        .skip(1)
        .map(|s| &s[..s.find('"').unwrap()])
        .collect();
    // every converged increment, after the reference state (t = 0), which
    // is written with the first increment's file
    let increments = summary["increments"].as_array().unwrap().len();
    assert_eq!(listed.len(), increments + usize::from(increments > 0));
    for file in listed {
        assert!(tmp.path().join(file).is_file(), "{file}");
    }
}
