//! The cost of an increment over a long run (issue 31 item 3): the
//! 27-hexahedron cube of `tests/data` (linear elastic, a pressure ramp, no
//! contact) run for 20 000 increments of 5e-5 into an output folder, with
//! every file a run writes (VTU every increment unless
//! `SIGNORINI_RATE_BENCH_EVERY` says otherwise, `summary.json`, the
//! checkpoint, the log). Prints the increments per second of the first and
//! of the last thousand increments and their ratio: with a cost per
//! increment that does not grow with the run it is 1 (the target: within
//! 20 %, a ratio of at least 0.8). Each increment's files are written
//! before the observer hears of it, so the time between two `on_increment`
//! calls is the whole cost of an increment.
//!
//! ```text
//! cargo bench --bench increment_rate
//! SIGNORINI_RATE_BENCH_INCREMENTS=5000 cargo bench --bench increment_rate
//! ```

use signorini::output::{ConvergedIncrement, StepObserver, Summary};
use signorini::run::{RunOptions, Simulation};
use std::path::Path;
use std::time::Instant;

/// The times of the converged increments since the run started.
struct Clock {
    start: Instant,
    times: Vec<f64>,
}

impl StepObserver for Clock {
    fn on_increment(&mut self, _: &ConvergedIncrement, _: &Summary) -> signorini::Result<()> {
        self.times.push(self.start.elapsed().as_secs_f64());
        Ok(())
    }
}

fn setting(name: &str, default: usize) -> usize {
    std::env::var(name)
        .ok()
        .and_then(|v| v.trim().parse().ok())
        .unwrap_or(default)
}

fn main() {
    let increments = setting("SIGNORINI_RATE_BENCH_INCREMENTS", 20_000).max(2_000);
    let every = setting("SIGNORINI_RATE_BENCH_EVERY", 1);
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data");
    let h = 1.0 / increments as f64;
    let case = format!(
        r#"
[mesh]
file = "cube_hex_41_ascii.msh"

[[material]]
region = "body"
model = "linear_elastic"
youngs_modulus = 100.0
poisson_ratio = 0.3

[[displacement]]
surface = "bottom"
x = 0.0
y = 0.0
z = 0.0

[[pressure]]
surface = "top"
value = 1.0

[[step]]
name = "load"
end_time = 1.0
initial_increment = {h}
max_increment = {h}
min_increment = {h}

[output]
name = "rate"
every = {every}
"#
    );
    let mut simulation = Simulation::from_toml(&case, &data).expect("the bench's case");
    let out = tempfile::tempdir().unwrap();
    let options = RunOptions {
        output: Some(out.path().to_path_buf()),
        threads: Some(1),
        cancel: None,
        restart: None,
    };
    let mut clock = Clock {
        start: Instant::now(),
        times: Vec::new(),
    };
    let outcome = simulation
        .run(&options, &mut clock)
        .expect("the bench's run");
    let t = &clock.times;
    assert_eq!(t.len(), outcome.summary.increments.len());
    let n = t.len();
    let rate = |from: usize, to: usize| (to - from) as f64 / (t[to - 1] - t[from.max(1) - 1]);
    let first = rate(1, 1001);
    let last = rate(n - 1000, n);
    println!("increment_rate: {n} increments, a VTU file every {every}");
    println!("  increments/s, increments 2-1001:        {first:.1}");
    println!("  increments/s, the last 1000:            {last:.1}");
    println!(
        "  ratio last/first: {:.3} (target: ≥ 0.8, within 20 %)",
        last / first
    );
    let summary = std::fs::metadata(out.path().join("summary.json")).map_or(0, |m| m.len());
    let checkpoint = std::fs::metadata(out.path().join("rate.checkpoint")).map_or(0, |m| m.len());
    println!("  summary.json {summary} bytes, rate.checkpoint {checkpoint} bytes at the end");
}
