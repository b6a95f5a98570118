//! Restart (issue 15 item 3): a run stopped after `k` converged increments
//! and resumed from its checkpoint (`RunOptions::restart`, the command
//! line's `--restart DIR`) ends in the state of an uninterrupted run, to
//! 1e-10: displacements, multipliers and the contact and friction history
//! (tractions, slip, anchors, status); its output folder reads as one run
//! (the `.pvd` lists every increment, `summary.json` and the histories keep
//! the earlier increments).

use signorini::output::{ConvergedIncrement, StepObserver, Summary};
use signorini::problem::ContactState;
use signorini::run::{RunOptions, RunOutcome, Simulation};
use std::path::{Path, PathBuf};

fn example() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/press-pull")
}

/// One comparison at a time. Two runs solving at once in one process used
/// to differ in round-off (6e-13 in `u` on press-pull: METIS's global
/// random-number state gave them different orderings; its calls are now
/// serialised and `tests/simulation.rs` checks side-by-side runs bit for
/// bit); the lock stays so that a difference here can only come from the
/// restart. Alone, uninterrupted and resumed agree bit for bit.
static ALONE: std::sync::Mutex<()> = std::sync::Mutex::new(());

/// Stops the run after its `n`-th converged increment (as a script's
/// callback returning `False` does).
struct StopAfter {
    n: usize,
    seen: usize,
}

impl StepObserver for StopAfter {
    fn on_increment(&mut self, _: &ConvergedIncrement, _: &Summary) -> signorini::Result<()> {
        self.seen += 1;
        if self.seen == self.n {
            return Err(signorini::Error::Interrupted {
                reason: "stopped by the test".into(),
            });
        }
        Ok(())
    }
}

/// The case on Newton's path (`strategy = "monolithic"`): a restart
/// resumes Newton's increments (press-pull's default, the condensed path,
/// resumes too: tests/stepper.rs).
fn simulation(case: &str) -> Simulation {
    let case = format!("{case}\n[solver]\nstrategy = \"monolithic\"\n");
    Simulation::from_toml(&case, &example()).unwrap()
}

fn options(output: &Path, restart: Option<&Path>) -> RunOptions {
    RunOptions {
        output: Some(output.to_path_buf()),
        threads: Some(1),
        restart: restart.map(Path::to_path_buf),
        ..Default::default()
    }
}

/// Every number of a contact state (multipliers, slack unknowns, gap,
/// friction traction, anchor and slip) and the statuses.
fn flatten(contact: &ContactState) -> (Vec<f64>, Vec<u8>) {
    let mut values = Vec::new();
    let mut statuses = Vec::new();
    for s in contact.interfaces.iter().flatten() {
        values.extend([s.lambda, s.slack.s, s.slack.lambda1, s.gap]);
        let f = &s.friction;
        values.extend(f.traction.iter().chain(&f.anchor).chain(&f.slip));
        statuses.push(f.status.code());
    }
    (values, statuses)
}

fn largest_difference(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

fn summary(dir: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap()
}

fn pvd_files(dir: &Path) -> Vec<String> {
    let pvd = std::fs::read_to_string(dir.join("press-pull.pvd")).unwrap();
    pvd.split("file=\"")
        .skip(1)
        .map(|s| s[..s.find('"').unwrap()].to_string())
        .collect()
}

/// The numbers of a CSV file (its header dropped).
fn csv_numbers(path: &Path) -> Vec<f64> {
    let text = std::fs::read_to_string(path).unwrap();
    text.lines()
        .skip(1)
        .flat_map(|l| l.split(',').map(|v| v.parse::<f64>().unwrap()))
        .collect()
}

/// The GMRES iterations the log's iteration lines report (`, N GMRES
/// iterations`), in total.
fn logged_krylov_iterations(lines: &[&str]) -> u64 {
    lines
        .iter()
        .filter_map(|l| {
            let head = &l[..l.find(" GMRES iterations")?];
            head.rsplit(' ').next()?.parse::<u64>().ok()
        })
        .sum()
}

/// Runs `case` uninterrupted into one folder and, into another, stopped
/// after `k` increments then restarted; asserts the two agree and returns
/// (uninterrupted, resumed, the resumed folder's increments on resuming).
fn uninterrupted_and_resumed(case: &str, k: usize) -> (RunOutcome, RunOutcome) {
    let _alone = ALONE.lock().unwrap_or_else(|e| e.into_inner());
    let full_dir = tempfile::tempdir().unwrap();
    let cut_dir = tempfile::tempdir().unwrap();
    let (full, cut) = (full_dir.path(), cut_dir.path());
    let uninterrupted = simulation(case)
        .run(
            &options(full, None),
            &mut signorini::output::observer::Silent,
        )
        .unwrap();
    let n = uninterrupted.summary.increments.len();
    assert!(k < n, "{k} of {n} increments");

    let mut stop = StopAfter { n: k, seen: 0 };
    let error = simulation(case)
        .run(&options(cut, None), &mut stop)
        .unwrap_err();
    assert!(
        matches!(error, signorini::Error::Interrupted { .. }),
        "{error}"
    );
    assert_eq!(summary(cut)["increments"].as_array().unwrap().len(), k);
    assert!(cut.join("press-pull.checkpoint").is_file());
    let manifest = std::fs::read_to_string(cut.join("press-pull.manifest")).unwrap();
    assert!(manifest.lines().any(|l| l == "press-pull.checkpoint"));

    // a new Simulation, as a new process would build
    let mut seen = StopAfter {
        n: usize::MAX,
        seen: 0,
    };
    let resumed = simulation(case)
        .run(&options(cut, Some(cut)), &mut seen)
        .unwrap();
    // only the increments after the checkpoint were solved again
    assert_eq!(seen.seen, n - k);

    let du = largest_difference(&uninterrupted.displacement, &resumed.displacement);
    let (a, sa) = flatten(&uninterrupted.contact);
    let (b, sb) = flatten(&resumed.contact);
    let dc = largest_difference(&a, &b);
    println!("k = {k}: |Δu| = {du:.1e}, |Δ contact state| = {dc:.1e}");
    assert!(du <= 1e-10, "displacements differ by {du:e}");
    assert!(dc <= 1e-10, "contact states differ by {dc:e}");
    assert_eq!(sa, sb);

    // the folder reads as one run
    let (s_full, s_cut) = (summary(full), summary(cut));
    assert_eq!(s_cut["status"], "completed");
    let times = |s: &serde_json::Value| -> Vec<(f64, String)> {
        s["increments"]
            .as_array()
            .unwrap()
            .iter()
            .map(|i| {
                (
                    i["time"].as_f64().unwrap(),
                    i["file"].as_str().unwrap().to_string(),
                )
            })
            .collect()
    };
    assert_eq!(times(&s_full), times(&s_cut));
    // the run totals carry over: the resumed run's add to the checkpoint's
    for key in [
        "krylov_solves",
        "krylov_iterations",
        "lu_solves",
        "factorisations",
    ] {
        assert_eq!(s_full[key], s_cut[key], "{key}");
    }
    assert_eq!(pvd_files(full), pvd_files(cut));
    // the reference state (t = 0) stays first in the resumed series
    assert_eq!(pvd_files(cut)[0], "press-pull_0000.vtu");
    for f in pvd_files(cut) {
        assert!(cut.join(&f).is_file(), "{f}");
    }
    for csv in [
        "right_end_displacement.csv",
        "contact_line_press.csv",
        "contact_line_pull.csv",
    ] {
        let (x, y) = (csv_numbers(&full.join(csv)), csv_numbers(&cut.join(csv)));
        assert!(largest_difference(&x, &y) <= 1e-10, "{csv}");
    }
    let log = std::fs::read_to_string(cut.join("press-pull.log")).unwrap();
    assert!(log.contains(&format!("after increment {k}")), "{log}");
    // each Newton iteration line tells its linear solve: the GMRES
    // iterations of the lines add up to the run's total
    for (dir, s) in [(full, &s_full), (cut, &s_cut)] {
        let log = std::fs::read_to_string(dir.join("press-pull.log")).unwrap();
        let lines: Vec<&str> = log.lines().filter(|l| l.contains("correction")).collect();
        assert!(!lines.is_empty());
        assert!(lines
            .iter()
            .all(|l| l.contains("linear solve: factorisation")));
        assert_eq!(
            logged_krylov_iterations(&lines),
            s["krylov_iterations"].as_u64().unwrap()
        );
    }
    (uninterrupted, resumed)
}

/// Coulomb friction (μ = 0.3), stopped in the middle of the pull step,
/// where nodes stick and slip: the friction history (traction, anchor,
/// slip) carries over.
#[test]
fn a_frictional_run_resumed_mid_step_ends_where_an_uninterrupted_one_does() {
    let case = std::fs::read_to_string(example().join("case.toml")).unwrap();
    let (full, _) = uninterrupted_and_resumed(&case, 3);
    // the pull step slips somewhere: the test exercises friction's history
    let (_, statuses) = flatten(&full.contact);
    assert!(statuses.contains(&1) || statuses.contains(&2));
    let slip = full
        .contact
        .interfaces
        .iter()
        .flatten()
        .map(|s| s.friction.slip.norm())
        .fold(0.0, f64::max);
    assert!(slip > 0.0, "no slip");
}

/// Frictionless, stopped at the end of the first step: the next step
/// starts with its own initial increment, as without the stop.
#[test]
fn a_frictionless_run_resumed_at_a_step_boundary_ends_where_an_uninterrupted_one_does() {
    let case = std::fs::read_to_string(example().join("case.toml"))
        .unwrap()
        .lines()
        .filter(|l| !l.starts_with("friction_coefficient") && !l.starts_with("exact_stick"))
        .collect::<Vec<_>>()
        .join("\n");
    // the pull would slide the block away without friction: hold its left end
    let case = case.replace(
        "[[pressure]]\nsurface = \"top\"",
        "[[displacement]]\nsurface = \"left\"\nx = 0.0\n\n[[pressure]]\nsurface = \"top\"",
    );
    let (full, _) = uninterrupted_and_resumed(&case, 2);
    // the base is pressed on the foundation: closed nodes (status 1)
    let (_, statuses) = flatten(&full.contact);
    assert!(statuses.contains(&1), "{statuses:?}");
    assert!(!statuses.contains(&2));
}

/// The command line: `--restart` on the folder of a completed run solves
/// nothing more and leaves it complete, with the same increments.
#[test]
fn the_command_line_restarts_from_a_folder() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("case.toml"), include_str!("data/cube_case.toml")).unwrap();
    std::fs::copy(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/cube_hex_41_ascii.msh"),
        d.join("cube.msh"),
    )
    .unwrap();
    let run = |args: &[&str]| {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_signorini"))
            .args(args)
            .current_dir(d)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
    };
    run(&["run", "case.toml", "--quiet"]);
    let first = summary(&d.join("results"));
    run(&["run", "case.toml", "--quiet", "--restart", "results"]);
    let again = summary(&d.join("results"));
    assert_eq!(again["status"], "completed");
    assert_eq!(first["increments"], again["increments"]);
    assert!(d.join("results/cube.checkpoint").is_file());
}
