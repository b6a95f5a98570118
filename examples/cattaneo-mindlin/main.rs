//! `examples/cattaneo-mindlin`: runs `case.toml` (or the case given) as
//! `signorini run` does, and compares every converged increment with
//! Mindlin's partial slip (see `mindlin.rs` and README.md). Besides the
//! usual result files it writes, in the output folder:
//!
//! - `mindlin_traction.svg`: the tangential traction `q` of the nodes on the
//!   load axis (the symmetry plane) at the end of the shear, against
//!   Mindlin's `q(r)` and the slip bound `μp`;
//! - `stick_radius.svg`: the fitted stick radius of every shear increment
//!   against `c = a (1 − Q/(μP))^{1/3}`;
//! - `mindlin.csv`: the figures of every increment;
//! - `mindlin_nodes.csv`: the secondary nodes at the end of the shear
//!   (reference `x` from the contact's centre and `y`, `r`, `p`, `q`, `q_y`,
//!   status).
//!
//! ```sh
//! cargo run --release --example cattaneo-mindlin [-- CASE [OUTPUT]]
//! ```

#[path = "mindlin.rs"]
mod mindlin;

use mindlin::Comparison;
use signorini::contact::friction::ContactStatus;
use signorini::output::line_plot::{write_line_plot, Curve, CurveStyle, LinePlot};
use signorini::output::units::{Dimension, Units};
use signorini::output::{ConvergedIncrement, StepObserver, Summary};
use signorini::run::{run_observed, RunOptions};
use std::path::PathBuf;

/// Keeps the comparison of every converged increment.
struct Compare(Vec<Comparison>);

impl StepObserver for Compare {
    fn on_increment(&mut self, inc: &ConvergedIncrement, _: &Summary) -> signorini::Result<()> {
        let comparison = Comparison::of(inc);
        eprintln!("{}", comparison.describe());
        self.0.push(comparison);
        Ok(())
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let here = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("examples/cattaneo-mindlin");
    let mut args = std::env::args().skip(1);
    let case = args
        .next()
        .map_or_else(|| here.join("case.toml"), PathBuf::from);
    let output = args.next().map_or_else(
        || case.parent().unwrap_or(&here).join("results"),
        PathBuf::from,
    );
    let options = RunOptions {
        output: Some(output.clone()),
        threads: None,
        cancel: None,
        restart: None,
    };
    let mut compare = Compare(Vec::new());
    run_observed(&case, &options, &mut compare)?;
    let Some(last) = compare.0.last() else {
        return Err("no increment converged".into());
    };
    // the case's [units], for the axis labels (nothing is converted)
    let spec = signorini::case::parse(&case, &std::fs::read_to_string(&case)?)?.units;
    let units = Units {
        length: spec.length,
        force: spec.force,
    };
    write_traction_plot(last, &units, &output)?;
    write_stick_radius_plot(&compare.0, &output)?;
    let mut csv = String::from(
        "time,iterations,force,tangential,ratio,contact_radius,peak_pressure,stick_radius_fit,\
         stick_radius_mindlin,contact_radius_fit,outermost_stick,innermost_slip,worst_ring\n",
    );
    for c in &compare.0 {
        let m = &c.mindlin;
        csv += &format!(
            "{},{},{},{},{},{},{},{},{},{},{},{},{}\n",
            c.time,
            c.iterations,
            c.force,
            c.tangential,
            m.ratio,
            m.hertz.radius,
            m.hertz.peak_pressure,
            c.stick_radius,
            m.stick_radius,
            c.contact_radius,
            c.outermost_stick,
            c.innermost_slip,
            c.worst_ring()
        );
    }
    std::fs::write(output.join("mindlin.csv"), csv)?;
    let mut nodes = String::from("x,y,r,pressure,traction,traction_y,status\n");
    for n in &last.nodes {
        nodes += &format!(
            "{},{},{},{},{},{},{:?}\n",
            n.x, n.y_reference, n.r, n.pressure, n.traction, n.traction_y, n.status
        );
    }
    std::fs::write(output.join("mindlin_nodes.csv"), nodes)?;
    println!("{}", last.describe());
    println!("{}", last.diagnostics());
    for (r, mean, reference) in last.rings() {
        println!(
            "  ring r = {r:.4}: mean q {mean:.4}, Mindlin {reference:.4} ({:+.2} % of μp0)",
            100.0 * (mean - reference) / (last.mindlin.mu * last.mindlin.hertz.peak_pressure)
        );
    }
    println!("{}", verdict(&compare.0, last));
    println!(
        "wrote {}, {}, mindlin.csv and mindlin_nodes.csv",
        output.join("mindlin_traction.svg").display(),
        output.join("stick_radius.svg").display()
    );
    Ok(())
}

/// Issue 18's three figures at the end of the shear, each with its bound
/// and whether this run meets it: the fitted stick radius within 1 % of
/// Mindlin's `c = a (1 − Q/(μP))^{1/3}`, every ring mean of `q` within 2 %
/// of `μ p₀`, at most 6 Newton iterations in any increment (README,
/// "A light press": `light.toml` meets the three, `case.toml` not the ring).
fn verdict(all: &[Comparison], last: &Comparison) -> String {
    let stick = (last.stick_radius - last.mindlin.stick_radius) / last.mindlin.stick_radius;
    let ring = last.worst_ring();
    let iterations = all.iter().map(|c| c.iterations).max().unwrap_or(0);
    let mark = |met: bool| if met { "met" } else { "NOT met" };
    format!(
        "targets at Q/(μP) = {:.3}: stick radius {:+.2} % of Mindlin's (≤ 1 %: {}), \
         worst ring {:.2} % of μp0 (≤ 2 %: {}), at most {} Newton iterations in an increment \
         (≤ 6: {})",
        last.mindlin.ratio,
        100.0 * stick,
        mark(stick.abs() <= 0.01),
        100.0 * ring,
        mark(ring <= 0.02),
        iterations,
        mark(iterations <= 6)
    )
}

/// `q` of the nodes on the load axis against Mindlin's `q(r)` and `μ p(r)`,
/// labelled in words with the case's `units`.
fn write_traction_plot(
    c: &Comparison,
    units: &Units,
    dir: &std::path::Path,
) -> signorini::Result<()> {
    let m = &c.mindlin;
    let a = m.hertz.radius;
    let mut axis: Vec<(f64, f64, ContactStatus)> = c
        .nodes
        .iter()
        .filter(|n| n.y_reference.abs() < 1e-9 && n.r < 1.3 * a)
        .map(|n| (n.x, n.traction, n.status))
        .collect();
    axis.sort_by(|p, q| p.0.total_cmp(&q.0));
    let line = |f: &dyn Fn(f64) -> f64| -> Vec<(f64, f64)> {
        (0..=130)
            .map(|i| {
                let x = -1.3 * a + 2.6 * a * i as f64 / 130.0;
                (x, f(x.abs()))
            })
            .collect()
    };
    let length = units
        .of(Dimension::Length)
        .map_or(String::new(), |u| format!(" {u}"));
    let plot = LinePlot {
        title: format!(
            "Cattaneo–Mindlin at Q/(μP) = {:.3}: stick radius {:.4}{length} fitted, \
             Mindlin's c = {:.4}{length}",
            m.ratio, c.stick_radius, m.stick_radius
        ),
        x_label: units.label(
            "distance from the contact centre along the load axis",
            Dimension::Length,
        ),
        y_label: units.label("tangential traction along the load", Dimension::Stress),
        curves: vec![
            Curve {
                label: "Mindlin q(r)".into(),
                points: line(&|r| m.traction(r)),
                colour: 0,
                style: CurveStyle::Solid,
            },
            Curve {
                label: "slip bound μ p(r) (Hertz)".into(),
                points: line(&|r| m.mu * m.hertz.pressure(r)),
                colour: 1,
                style: CurveStyle::Dashed,
            },
            Curve {
                label: "signorini, sticking nodes".into(),
                points: axis
                    .iter()
                    .filter(|n| n.2 == ContactStatus::Stick)
                    .map(|n| (n.0, n.1))
                    .collect(),
                colour: 2,
                style: CurveStyle::Markers,
            },
            Curve {
                label: "signorini, slipping nodes".into(),
                points: axis
                    .iter()
                    .filter(|n| n.2 == ContactStatus::Slip)
                    .map(|n| (n.0, n.1))
                    .collect(),
                colour: 3,
                style: CurveStyle::Markers,
            },
        ],
        below: Vec::new(),
    };
    write_line_plot(&dir.join("mindlin_traction.svg"), &plot)
}

/// The fitted stick radius of every shear increment against Mindlin's.
fn write_stick_radius_plot(all: &[Comparison], dir: &std::path::Path) -> signorini::Result<()> {
    let shear: Vec<&Comparison> = all
        .iter()
        .filter(|c| c.mindlin.ratio > 1e-3 && c.stick_radius.is_finite())
        .collect();
    let plot = LinePlot {
        title: "Cattaneo–Mindlin: stick radius against the shear force".into(),
        x_label: "shear force over its slip limit, Q/(μP)".into(),
        y_label: "stick radius over the contact radius, c/a".into(),
        curves: vec![
            Curve {
                label: "Mindlin: c/a = (1 − Q/(μP))^(1/3)".into(),
                points: (0..=100)
                    .map(|i| {
                        let q = i as f64 / 100.0;
                        (q, (1.0 - q).cbrt())
                    })
                    .collect(),
                colour: 0,
                style: CurveStyle::Solid,
            },
            Curve {
                label: "signorini: fitted stick radius / Hertz a".into(),
                points: shear
                    .iter()
                    .map(|c| (c.mindlin.ratio, c.stick_radius / c.mindlin.hertz.radius))
                    .collect(),
                colour: 3,
                style: CurveStyle::Markers,
            },
        ],
        below: Vec::new(),
    };
    write_line_plot(&dir.join("stick_radius.svg"), &plot)
}
