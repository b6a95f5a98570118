//! `examples/indenter`: runs `case.toml` as `signorini run` does and draws
//! its force–indentation history (`force_indentation`, the reaction on the
//! block's bottom against the displacement `u_z` of the top face's centre,
//! `−δ`) on the same axes as Hertz's rigid sphere on an elastic half-space,
//! `F = (4/3) E* √R δ^{3/2}`, `E* = E/(1 − ν²)`, a quarter of it (the model
//! is a quarter, its reaction a quarter of the whole force). Besides the
//! usual result files it writes `force_indentation_hertz.svg` into the
//! output folder and prints the ratio `F / F_Hertz` of every increment.
//!
//! ```sh
//! cargo run --release --example indenter [-- OUTPUT]
//! ```

use signorini::output::history::History;
use signorini::output::line_plot::{write_line_plot, Curve, CurveStyle};
use signorini::output::{ConvergedIncrement, StepObserver, Summary};
use signorini::run::{run_observed, RunOptions};
use std::path::PathBuf;

/// The block's Young's modulus and Poisson's ratio and the sphere's
/// radius (`case.toml`).
const YOUNGS_MODULUS: f64 = 1000.0;
const POISSON_RATIO: f64 = 0.3;
const RADIUS: f64 = 1.0;
/// The model's share of the whole: a quarter (symmetry planes x = 0, y = 0).
const SHARE: f64 = 0.25;

/// Hertz's force at indentation `delta` of a rigid sphere into an elastic
/// half-space: `F = (4/3) E* √R δ^{3/2}`, `E* = E/(1 − ν²)`.
fn hertz_force(delta: f64) -> f64 {
    let e_star = YOUNGS_MODULUS / (1.0 - POISSON_RATIO * POISSON_RATIO);
    4.0 / 3.0 * e_star * RADIUS.sqrt() * delta.max(0.0).powf(1.5)
}

/// Records the history as the result files do.
struct Record(History);

impl StepObserver for Record {
    fn on_increment(&mut self, inc: &ConvergedIncrement, _: &Summary) -> signorini::Result<()> {
        let reports = &inc.contact_fields.reports;
        self.0
            .record(inc.record.time, inc.unknowns, inc.residual, reports);
        Ok(())
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let here = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("examples/indenter");
    let case_path = here.join("case.toml");
    let output = std::env::args()
        .nth(1)
        .map_or_else(|| here.join("results"), PathBuf::from);
    let case = signorini::case::load(&case_path)?;
    let (problem, _) = signorini::run::problem_as_run(&case)?;
    let history = case
        .output_requests(&problem)?
        .histories
        .into_iter()
        .find(|h| h.name == "force_indentation")
        .ok_or("case.toml has no history 'force_indentation'")?;
    drop(problem);
    let options = RunOptions {
        output: Some(output.clone()),
        ..Default::default()
    };
    let mut record = Record(history);
    run_observed(&case_path, &options, &mut record)?;
    let history = record.0;
    println!("    t      δ = −u_z     F = 4 × reaction    F Hertz     F / F Hertz");
    for (t, v) in &history.samples {
        let (delta, force) = (-v[0], v[1] / SHARE);
        let reference = hertz_force(delta);
        println!(
            "{t:7.4}  {delta:11.6}  {force:11.6}  {reference:11.6}  {:9.4}",
            force / reference
        );
    }
    let deepest = history
        .samples
        .iter()
        .map(|(_, v)| -v[0])
        .fold(0.0, f64::max);
    let mut plot = history.plot();
    plot.title = "Force against indentation: computed and Hertz".into();
    plot.curves[0].label = "computed (quarter model)".into();
    plot.curves.push(Curve {
        label: "Hertz: ¼ (4/3) E* √R δ^(3/2)".into(),
        points: (0..=16)
            .map(|k| {
                let delta = deepest * k as f64 / 16.0;
                (-delta, SHARE * hertz_force(delta))
            })
            .collect(),
        colour: 1,
        style: CurveStyle::Dashed,
    });
    let figure = output.join("force_indentation_hertz.svg");
    write_line_plot(&figure, &plot)?;
    println!("wrote {}", figure.display());
    Ok(())
}
