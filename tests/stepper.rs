//! One stepper for every path (issue 32 item 1): the condensed path runs
//! through the same stepper as Newton's, reports its contact iterations as
//! its iterations, and `auto` falls back to Newton's path for an increment
//! the condensed solve fails.

mod common;

use signorini::output::{ConvergedIncrement, StepObserver, Summary};
use signorini::run::{RunOptions, RunOutcome, Simulation};
use std::path::Path;

/// The floating block's case: a plane-strain block (4 × 0.5 × 1, E = 1000,
/// ν = 0.3) resting on a rigid floor with Coulomb friction μ = 0.3 and no
/// other support in x (64 × 2 × 16 Hex8), pressed by p = 10 on its top (N = 20) in step
/// "press", then pushed by a traction on its left side to F = 0.75 μN =
/// 4.5 in step "push", four increments each; `solver` is the `[solver]`
/// table's lines.
fn floating_block(contact: &str, solver: &str) -> String {
    format!(
        r#"
[mesh]
file = "block.msh"

[[material]]
region = "body"
model = "linear_elastic"
youngs_modulus = 1000.0
poisson_ratio = 0.3

[[displacement]]
surface = "ymin"
y = 0.0

[[displacement]]
surface = "ymax"
y = 0.0

[[pressure]]
surface = "zmax"
value = 10.0
amplitude = "press"

# F = 9 · (H = 1)(T = 0.5) = 4.5 = 0.75 μN, pushing in +x
[[pressure]]
surface = "xmin"
value = 9.0
amplitude = "push"

[amplitudes]
press = [[0.0, 0.0], [1.0, 1.0], [2.0, 1.0]]
push = [[0.0, 0.0], [1.0, 0.0], [2.0, 1.0]]

[[obstacle]]
name = "floor"
shape = "plane"
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]

[[contact]]
name = "base"
surface = "zmin"
obstacle = "floor"
friction_coefficient = 0.3
{contact}

[[step]]
name = "press"
end_time = 1.0
initial_increment = 0.25
max_increment = 0.25

[[step]]
name = "push"
end_time = 2.0
initial_increment = 0.25
max_increment = 0.25

[solver]
{solver}
"#
    )
}

/// Every increment's total contact force on the block (`force` plus
/// `tangential_force` of interface `base` in the summary).
#[derive(Default)]
struct Totals(Vec<[f64; 3]>);

impl StepObserver for Totals {
    fn on_increment(&mut self, _: &ConvergedIncrement, summary: &Summary) -> signorini::Result<()> {
        let last = summary.increments.last().unwrap();
        let base = &last.contact["base"];
        self.0
            .push([0, 1, 2].map(|i| base.force[i] + base.tangential_force[i]));
        Ok(())
    }
}

fn run_block(
    dir: &Path,
    kind: signorini::mesh::ElementKind,
    contact: &str,
    solver: &str,
) -> (RunOutcome, Totals) {
    let mesh = signorini::mesh::structured::box_mesh(kind, [64, 2, 16], [4.0, 0.5, 1.0]);
    std::fs::write(dir.join("block.msh"), common::msh22(&mesh)).unwrap();
    let mut simulation = Simulation::from_toml(&floating_block(contact, solver), dir).unwrap();
    let mut totals = Totals::default();
    let options = RunOptions {
        threads: Some(1),
        ..Default::default()
    };
    let outcome = simulation
        .run(&options, &mut totals)
        .unwrap_or_else(|e| panic!("{solver}: {e}"));
    (outcome, totals)
}

fn largest(a: &[f64]) -> f64 {
    a.iter().fold(0.0f64, |m, v| m.max(v.abs()))
}

/// A block held only by a frictional floor, pressed then pushed sideways
/// to 0.75 μN (64 × 2 × 16 hexahedra, 10 k unknowns: before this test the
/// condensed path factorised it in f32 and stopped at a residual of
/// 5.7e-7): with default settings it runs on the condensed path, equals the monolithic answer to
/// 1e-8 (displacements relative to the largest, contact forces relative to
/// N), and ends with F_T / (μ N) = 0.75 (equilibrium: the floor's
/// tangential force balances the push exactly, 1e-8).
#[test]
fn a_block_held_only_by_friction_runs_with_default_settings() {
    let (kind, contact) = (signorini::mesh::ElementKind::Hex8, "");
    let dir = tempfile::tempdir().unwrap();
    let (auto, auto_totals) = run_block(dir.path(), kind, contact, "");
    let (mono, mono_totals) = run_block(dir.path(), kind, contact, "strategy = \"monolithic\"");
    let s = &auto.summary;
    eprintln!(
        "auto: {} ({} increments retried on Newton's path)",
        s.strategy, s.fallback_increments
    );
    assert_eq!(s.strategy, "condensed");
    // the condensed path solved every increment itself, to Newton's
    // tolerance, and reported its semismooth iterations with their
    // residuals (the last one the evaluation's)
    assert_eq!(s.fallback_increments, 0);
    for i in &s.increments {
        assert_eq!(i.method, "condensed");
        assert!(i.iterations >= 1 && i.residuals.len() == i.iterations + 1);
        assert!(*i.residuals.last().unwrap() <= 1e-8, "{:?}", i.residuals);
    }
    assert_eq!(s.increments.len(), 8);
    let du: Vec<f64> = auto
        .displacement
        .iter()
        .zip(&mono.displacement)
        .map(|(a, b)| a - b)
        .collect();
    let relative = largest(&du) / largest(&mono.displacement);
    eprintln!("condensed − monolithic displacements {relative:.1e}");
    assert!(relative < 1e-8, "{relative:e}");
    let n = 20.0;
    assert_eq!(auto_totals.0.len(), mono_totals.0.len());
    for (a, m) in auto_totals.0.iter().zip(&mono_totals.0) {
        let d = (0..3).map(|i| (a[i] - m[i]).abs()).fold(0.0, f64::max) / n;
        assert!(d < 1e-8, "{a:?} vs {m:?}");
    }
    let last = auto_totals.0.last().unwrap();
    let ratio = last[0].abs() / (0.3 * last[2].abs());
    eprintln!("F_T / μN = {ratio}, N = {}", last[2]);
    assert!((ratio - 0.75).abs() < 1e-8, "{ratio}");
    assert!((last[2].abs() - n).abs() < 1e-8 * n, "{last:?}");
}

/// Stops the run after its `n`-th converged increment (as a script's
/// callback returning `False` does, or a kill after the checkpoint).
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

/// Every number of a run's final state as bits: the unknowns, then per
/// contact node its multiplier, slack unknowns, gap, friction traction,
/// anchor and slip, and its status.
fn bits(outcome: &RunOutcome) -> Vec<u64> {
    let mut values: Vec<f64> = outcome.displacement.clone();
    let mut statuses = Vec::new();
    for s in outcome.contact.interfaces.iter().flatten() {
        values.extend([s.lambda, s.slack.s, s.slack.lambda1, s.gap]);
        let f = &s.friction;
        values.extend(f.traction.iter().chain(&f.anchor).chain(&f.slip));
        statuses.push(u64::from(f.status.code()));
    }
    values.iter().map(|v| v.to_bits()).chain(statuses).collect()
}

/// `examples/<example>/case.toml` as it ships, run uninterrupted into one
/// folder and, into another, stopped after half its increments and
/// resumed from the checkpoint (`--restart`): the final states are equal
/// bit for bit, and so are the increments' times, iterations and
/// residuals. Returns the uninterrupted run's summary.
fn resumes_bitwise(example: &str) -> Summary {
    let folder = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("examples")
        .join(example);
    resumes_bitwise_at(&folder.join("case.toml"), example)
}

/// [`resumes_bitwise`] of the case file `case` (`label` in messages).
fn resumes_bitwise_at(case: &Path, example: &str) -> Summary {
    let simulation = || Simulation::from_file(case).unwrap();
    let (full_dir, cut_dir) = (tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap());
    let options = |dir: &Path, restart: bool| RunOptions {
        output: Some(dir.to_path_buf()),
        threads: Some(1),
        restart: restart.then(|| dir.to_path_buf()),
        ..Default::default()
    };
    let silent = &mut signorini::output::observer::Silent;
    let full = simulation()
        .run(&options(full_dir.path(), false), silent)
        .unwrap();
    let n = full.summary.increments.len();
    let k = n / 2;
    assert!(k >= 1, "{n} increments");
    let mut stop = StopAfter { n: k, seen: 0 };
    let error = simulation()
        .run(&options(cut_dir.path(), false), &mut stop)
        .unwrap_err();
    assert!(
        matches!(error, signorini::Error::Interrupted { .. }),
        "{error}"
    );
    let mut seen = StopAfter {
        n: usize::MAX,
        seen: 0,
    };
    let resumed = simulation()
        .run(&options(cut_dir.path(), true), &mut seen)
        .unwrap();
    assert_eq!(seen.seen, n - k);
    assert_eq!(resumed.summary.strategy, full.summary.strategy);
    assert!(
        bits(&full) == bits(&resumed),
        "{example}: not bitwise equal"
    );
    let figures = |s: &Summary| -> Vec<(u64, usize, Vec<u64>)> {
        s.increments
            .iter()
            .map(|i| {
                let residuals = i.residuals.iter().map(|r| r.to_bits()).collect();
                (i.time.to_bits(), i.iterations, residuals)
            })
            .collect()
    };
    assert_eq!(figures(&full.summary), figures(&resumed.summary));
    assert_eq!(
        full.summary.active_set_iterations,
        resumed.summary.active_set_iterations
    );
    full.summary
}

/// `--restart` on examples/press-pull as it ships: the default path is
/// the frictional condensed one, and it resumes bit for bit.
#[test]
fn press_pull_on_the_default_path_resumes_bitwise() {
    let summary = resumes_bitwise("press-pull");
    assert_eq!(summary.strategy, "condensed");
}

/// `--restart` on examples/hertz as it ships (frictionless condensed, an
/// f32 factor): bit for bit; its iterations are the active-set steps, the
/// summary's count is the residuals' less the converged evaluation.
#[test]
fn hertz_on_the_default_path_resumes_bitwise() {
    let summary = resumes_bitwise("hertz");
    assert_eq!(summary.strategy, "condensed");
    for i in &summary.increments {
        assert!(i.iterations > 1, "{}", i.iterations);
        assert_eq!(i.residuals.len(), i.iterations + 1);
        assert_eq!(i.method, "condensed");
    }
}

/// examples/cattaneo-mindlin on the tiny mesh of tests/condensed.rs
/// (tests/data/cattaneo_tiny.msh), on the condensed path between bodies,
/// with `changes` made, written into `folder`.
fn tiny_cattaneo_case(folder: &Path, changes: &[(&str, &str)]) -> std::path::PathBuf {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut text =
        std::fs::read_to_string(root.join("examples/cattaneo-mindlin/case.toml")).unwrap();
    let mesh = root.join("tests/data/cattaneo_tiny.msh");
    text = text.replace(
        "file = \"spheres.msh\"",
        &format!("file = {:?}", mesh.display().to_string()),
    );
    for (old, new) in changes {
        assert!(text.contains(old), "{old}");
        text = text.replace(old, new);
    }
    text.push_str("\n[solver]\nstrategy = \"condensed\"\n");
    let path = folder.join("case.toml");
    std::fs::write(&path, text).unwrap();
    path
}

/// `--restart` on the condensed path between bodies (issue 32): the
/// Cattaneo–Mindlin spheres on a tiny mesh, with Coulomb friction (exact
/// stick) and frictionless, stopped after half their increments and
/// resumed: bit for bit the uninterrupted run (the candidates replayed in
/// their batches, `W` formed anew at the checkpoint's projections as at
/// every increment's start); frictionless also on an f32 factor (each
/// increment's corrections of the block start afresh).
#[test]
fn bodies_in_contact_on_the_condensed_path_resume_bitwise() {
    let dir = tempfile::tempdir().unwrap();
    let frictional = tiny_cattaneo_case(dir.path(), &[]);
    let summary = resumes_bitwise_at(&frictional, "frictional pair");
    assert_eq!(summary.strategy, "condensed");
    let last = summary.increments.last().unwrap();
    assert!(last.contact["poles"].slip_nodes > 0);
    let dir = tempfile::tempdir().unwrap();
    let frictionless = tiny_cattaneo_case(
        dir.path(),
        &[
            ("friction_coefficient = 0.3", "friction_coefficient = 0.0"),
            ("exact_stick = true ", "# "),
        ],
    );
    let summary = resumes_bitwise_at(&frictionless, "frictionless pair");
    assert_eq!(summary.strategy, "condensed");
    // the same on an f32 factor, whose block response the rounds correct
    let mut text = std::fs::read_to_string(&frictionless).unwrap();
    text.push_str("linear = \"mixed\"\n");
    std::fs::write(&frictionless, text).unwrap();
    let summary = resumes_bitwise_at(&frictionless, "frictionless pair on an f32 factor");
    assert_eq!(summary.strategy, "condensed");
    assert_eq!(summary.single_factorisations, 1);
}
