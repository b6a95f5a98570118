//! `examples/cattaneo-mindlin` on its coarse mesh (`coarse.toml`,
//! `coarse.msh`: `smin = 0.012` under the contact, 4 711 nodes; the
//! committed example, `case.toml`, uses `smin = 0.008`, see its README):
//! two identical elastic hemispheres pressed together, then sheared to
//! `Q/(μP) ≈ 0.5`, against Hertz and Mindlin (`examples/cattaneo-mindlin/mindlin.rs`).
//! Also the light press's coarse twin (`light-coarse.toml`, README "A light
//! press"), the case that shows issue 18's targets on its finer mesh.
//! Also the slip output of issue 18 item 5 (`slip_increment`,
//! `accumulated_slip`) and the log's note of a sparse-LU fallback.

#[path = "../examples/cattaneo-mindlin/mindlin.rs"]
mod mindlin;

use mindlin::Comparison;
use signorini::output::{ConvergedIncrement, NodalField, StepObserver, Summary};
use signorini::run::{run_observed, RunOptions};
use std::path::Path;

/// `(slip_increment, accumulated_slip, slip, contact_status)` of a node.
type Slips = ([f64; 3], [f64; 3], [f64; 3], f64);

/// Per increment: the comparison, and the secondary nodes' slip fields.
#[derive(Default)]
struct Record {
    comparisons: Vec<Comparison>,
    /// The [`Slips`] of every secondary node, per increment.
    slips: Vec<Vec<Slips>>,
    lu_solves: Vec<usize>,
    /// The last increment's displacements and nodal contact tractions.
    displacement: Vec<f64>,
    traction: Vec<f64>,
}

impl Record {
    /// The increments that end the press (`t = 1`) and the shear, after
    /// printing every increment's figures and the last one's diagnostics.
    fn ends(&self) -> (&Comparison, &Comparison) {
        for c in &self.comparisons {
            eprintln!("{}", c.describe());
        }
        let end_of_press = self
            .comparisons
            .iter()
            .find(|c| (c.time - 1.0).abs() < 1e-12)
            .expect("an increment ends the press");
        let last = self.comparisons.last().unwrap();
        eprintln!("{}", last.diagnostics());
        (end_of_press, last)
    }
}

impl Record {
    /// Every increment took at most `bound` iterations.
    fn assert_iterations_at_most(&self, bound: usize) {
        for c in &self.comparisons {
            assert!(
                c.iterations <= bound,
                "t = {}: {} iterations",
                c.time,
                c.iterations
            );
        }
    }
}

impl StepObserver for Record {
    fn on_increment(&mut self, inc: &ConvergedIncrement, _: &Summary) -> signorini::Result<()> {
        self.comparisons.push(Comparison::of(inc));
        let increment = inc.nodal(NodalField::SlipIncrement);
        let accumulated = inc.nodal(NodalField::AccumulatedSlip);
        let slip = inc.nodal(NodalField::Slip);
        let status = inc.nodal(NodalField::ContactStatus);
        let three = |v: &[f64], s: usize| [v[3 * s], v[3 * s + 1], v[3 * s + 2]];
        self.slips.push(
            inc.problem
                .contacts
                .interface(0)
                .nodes
                .iter()
                .map(|&s| {
                    (
                        three(&increment, s),
                        three(&accumulated, s),
                        three(&slip, s),
                        status[s],
                    )
                })
                .collect(),
        );
        self.lu_solves.push(inc.record.lu_solves);
        self.displacement = inc.displacement().to_vec();
        self.traction = inc.nodal(NodalField::ContactTraction).into_owned();
        Ok(())
    }
}

/// The coarse Cattaneo–Mindlin run (exact stick, issue 18 item 2; the
/// increments pinned to 0.25 in the press and 0.2 in the shear) on the
/// default path (`auto`: the condensed one, which equals Newton's,
/// [`newton_and_the_outer_loop_end_where_the_default_path_does`]), against
/// Hertz and Mindlin.
/// Tolerances (the figures measured on this mesh and on the committed one
/// are in the example's README; "measured" below: 2026-11-25, on Newton's
/// path):
/// - `Q/(μP)` within 0.45 … 0.55 at the end of the shear;
/// - the normal press: the contact radius (fit of `p²` against `r²`)
///   within 1 % of Hertz's for the computed `P` (measured −0.40 %; radii
///   in reference coordinates, as the small-strain theory has them: the
///   deformed ones are 1.3 % shorter, Johnson 1985 eq. 3.41b);
/// - the stick radius fitted to the deficit `μp − q` within 1 % of
///   Mindlin's `c = a (1 − Q/(μP))^{1/3}` (measured +0.31 %; the
///   regularised law gave −2.2 % in deformed coordinates), and within
///   1 % of Mindlin's ratio `c/a` with both radii fitted (measured
///   +0.67 %); Mindlin's `c` between the
///   outermost sticking node (at most 2 % beyond it) and the innermost
///   slipping one (at most 4 % inside it: stick and slip nodes interleave
///   over one element around `c`, measured 0.08786 and 0.08693 for
///   `c = 0.08829`);
/// - the tangential traction averaged over rings `a/10` wide, `r < 0.8a`,
///   within 9 % of `μp₀` of Mindlin's averaged over the same nodes
///   (measured 7.0 % in the ring that holds `c`, where Mindlin's `q` rises
///   with an infinite slope, so that the ring's mean follows `c`'s place
///   within the ring's few nodes; the regularised law gave 5.7 %; the
///   target of issue 18 is 2 %; about half of it is Mindlin's
///   approximation for `ν ≠ 0`: 3.7 % with `ν = 0` on this mesh, README
///   "Why the ring that holds `c` reads high").
///
/// The slip fields: at every secondary node and increment,
/// `accumulated_slip` = `slip` = the sum of the `slip_increment`s so far
/// (1e-14), and `slip_increment` is nonzero exactly at the nodes that
/// slip (`contact_status` 2); some do.
#[test]
fn cattaneo_mindlin_partial_slip() {
    let out = tempfile::tempdir().unwrap();
    let (_, record) = run_pinned("coarse.toml", out.path(), Solver::Auto);
    let (end_of_press, last) = record.ends();
    let m = &last.mindlin;
    assert!((0.45..=0.55).contains(&m.ratio), "Q/(μP) = {}", m.ratio);
    // the press: all closed nodes stick, the fit is the contact radius
    let press = &end_of_press.mindlin;
    assert!(
        (end_of_press.stick_radius / press.hertz.radius - 1.0).abs() < 0.01,
        "contact radius {} vs Hertz {}",
        end_of_press.stick_radius,
        press.hertz.radius
    );
    let c = m.stick_radius;
    assert!(
        (last.stick_radius / c - 1.0).abs() < 0.01,
        "stick radius {} vs Mindlin {c}",
        last.stick_radius
    );
    let ratio = last.stick_radius / last.contact_radius;
    let mindlin_ratio = (1.0 - m.ratio).cbrt();
    assert!(
        (ratio / mindlin_ratio - 1.0).abs() < 0.01,
        "c/a of the fits {ratio} vs Mindlin's {mindlin_ratio}"
    );
    assert!(
        last.outermost_stick < 1.02 * c && last.innermost_slip > 0.96 * c,
        "Mindlin's c = {c} outside the nodes' stick–slip boundary {} … {}",
        last.outermost_stick,
        last.innermost_slip
    );
    assert!(last.worst_ring() < 0.09, "ring error {}", last.worst_ring());

    // slip output
    let mut sum = vec![[0.0; 3]; record.slips[0].len()];
    let mut slipping = 0;
    for increment in &record.slips {
        for ((step, accumulated, slip, status), total) in increment.iter().zip(&mut sum) {
            for d in 0..3 {
                total[d] += step[d];
                assert!((accumulated[d] - total[d]).abs() < 1e-14);
                assert_eq!(accumulated[d].to_bits(), slip[d].to_bits());
            }
            let moved = step.iter().any(|v| *v != 0.0);
            assert_eq!(
                moved,
                *status == 2.0,
                "slip increment {step:?}, status {status}"
            );
            slipping += usize::from(moved);
        }
    }
    assert!(slipping > 0, "no node slipped");
}

/// The coarse run of [`cattaneo_mindlin_partial_slip`] on Newton's path,
/// with the tangential multipliers as unknowns of Newton and with
/// Simo–Laursen's outer loop (`friction_multiplier = "outer"`), on the
/// same increments; about 90 s of CPU, so not in the default suite:
/// `cargo test --release --test cattaneo_mindlin -- --ignored`.
/// - At most 8 Newton iterations per increment (measured 6, 7, 5, 5 in
///   the press and 5 in every shear increment; the outer loop took 6–17,
///   5–8 multiplier updates per increment; the target of issue 18 is 6).
/// - The log's increment lines carry the sparse-LU note exactly when the
///   increment had LU solves (the settings choose GMRES, so any LU solve
///   is a fallback).
/// - The outer loop ends at Newton's state: displacements within 1e-6
///   of the largest (measured 5.6e-10), nodal contact tractions within 5e-5
///   of `μ p₀` (measured 7.4e-6, 1.8e-7 at `60be7a3`: Newton's residual tolerance, 1e-8 of the
///   force scale, allows about 1e-5 of `μ p₀` at a node of this mesh), the
///   same stick and slip sets; the outer loop took 6–18 iterations per
///   increment (6, 14, 13, 12 in the press, 16–18 in the shear).
/// - The default path (condensed) ends at Newton's state: displacements
///   within 1e-8 of the largest, tractions within 1e-8 of `μ p₀`, the
///   same stick and slip sets (measured 3.0e-11 and 1.7e-9 at `60be7a3`;
///   on `case.toml`: 5.4e-12 and 5.7e-10 of the peak, BENCHMARKS.md
///   session 20).
#[test]
#[ignore = "about 90 s of CPU: cargo test --release --test cattaneo_mindlin -- --ignored"]
fn newton_and_the_outer_loop_end_where_the_default_path_does() {
    let out = tempfile::tempdir().unwrap();
    let (_, record) = run_pinned("coarse.toml", out.path(), Solver::Newton("newton"));
    let (_, last) = record.ends();
    let m = &last.mindlin;
    record.assert_iterations_at_most(8);

    // the log's note of a sparse-LU fallback, on the increments that had one
    let log = std::fs::read_to_string(out.path().join("newton/cattaneo.log")).unwrap();
    let lines: Vec<&str> = log
        .lines()
        .filter(|l| l.starts_with("step '") && l.contains("converged in"))
        .collect();
    assert_eq!(lines.len(), record.lu_solves.len());
    for (line, &lu) in lines.iter().zip(&record.lu_solves) {
        assert_eq!(line.contains("sparse LU fallback"), lu > 0, "{line}");
    }

    // the outer loop's answer, on the same increments
    let (_, outer) = run_pinned("coarse.toml", out.path(), Solver::Newton("outer"));
    let largest = |v: &[f64]| v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let difference = |a: &[f64], b: &[f64]| {
        a.iter()
            .zip(b)
            .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
    };
    let du = difference(&record.displacement, &outer.displacement) / largest(&outer.displacement);
    let mu_p0 = m.mu * m.hertz.peak_pressure;
    let dt = difference(&record.traction, &outer.traction) / mu_p0;
    eprintln!(
        "newton − outer: displacements {du:.1e} of the largest, tractions {dt:.1e} of μp0; \
         iterations {:?} against {:?}",
        record
            .comparisons
            .iter()
            .map(|c| c.iterations)
            .collect::<Vec<_>>(),
        outer
            .comparisons
            .iter()
            .map(|c| c.iterations)
            .collect::<Vec<_>>()
    );
    assert!(du < 1e-6, "displacements differ by {du:e}");
    assert!(dt < 5e-5, "tractions differ by {dt:e} of μp0");
    let statuses = |r: &Record| {
        r.slips
            .last()
            .unwrap()
            .iter()
            .map(|s| s.3)
            .collect::<Vec<_>>()
    };
    assert_eq!(statuses(&record), statuses(&outer), "stick and slip sets");

    let (_, auto) = run_pinned("coarse.toml", out.path(), Solver::Auto);
    let du = difference(&record.displacement, &auto.displacement) / largest(&record.displacement);
    let dt = difference(&record.traction, &auto.traction) / mu_p0;
    eprintln!("newton − auto: displacements {du:.1e} of the largest, tractions {dt:.1e} of μp0");
    assert!(du < 1e-8, "displacements differ by {du:e}");
    assert!(dt < 1e-8, "tractions differ by {dt:e} of μp0");
    assert_eq!(statuses(&record), statuses(&auto), "stick and slip sets");
}

/// The light press on its coarse mesh (`light-coarse.toml`,
/// `light-coarse.msh`: `case.toml`'s contact scaled by 1/5, so
/// `a/R ≈ 0.022` and `p₀/E ≈ 0.014`, `smin = 0.0024 ≈ 0.11 a`; `ν = 0`,
/// where Mindlin's solution is exact; README "A light press"), on the
/// pinned increments, on the default path (`auto`: condensed), against
/// Hertz and Mindlin. Tolerances ("measured": 2026-11-26, on Newton's path):
/// - `Q/(μP)` within 0.45 … 0.55 (measured 0.5101);
/// - the contact radius (fit of `p²`) at the end of the press within 2 %
///   of Hertz's (measured +1.33 %; `light.toml`, `smin = 0.0014`, +0.62 %);
/// - the stick radius within 1 % of Mindlin's `c` (measured −0.23 %;
///   `light.toml` +0.52 %), Mindlin's `c` between the
///   outermost sticking node (at most 2 % beyond it) and the innermost
///   slipping one (at most 4 % inside it);
/// - the ring means of `q` within 2 % of `μp₀` in every ring but the one
///   that holds `c` (measured 1.56 %; `light.toml` 0.85 %),
///   and within 7.5 % in that one (measured 6.00 %; `light.toml` 1.62 %,
///   issue 18's target is 2 %).
#[test]
fn cattaneo_mindlin_light_press() {
    let out = tempfile::tempdir().unwrap();
    let (_, record) = run_pinned("light-coarse.toml", out.path(), Solver::Auto);
    let (end_of_press, last) = record.ends();
    let m = &last.mindlin;
    assert!((0.45..=0.55).contains(&m.ratio), "Q/(μP) = {}", m.ratio);
    let a = end_of_press.mindlin.hertz.radius;
    assert!(
        (end_of_press.contact_radius / a - 1.0).abs() < 0.02,
        "contact radius {} vs Hertz {a}",
        end_of_press.contact_radius
    );
    let c = m.stick_radius;
    assert!(
        (last.stick_radius / c - 1.0).abs() < 0.01,
        "stick radius {} vs Mindlin {c}",
        last.stick_radius
    );
    assert!(
        last.outermost_stick < 1.02 * c && last.innermost_slip > 0.96 * c,
        "Mindlin's c = {c} outside the nodes' stick–slip boundary {} … {}",
        last.outermost_stick,
        last.innermost_slip
    );
    let scale = m.mu * m.hertz.peak_pressure;
    let width = 0.1 * m.hertz.radius;
    for (r, mean, reference) in last.rings() {
        let holds_c = (r - c).abs() <= 0.5 * width;
        let bound = if holds_c { 0.075 } else { 0.02 };
        let error = (mean - reference).abs() / scale;
        assert!(
            error < bound,
            "ring r = {r}: {error} of μp0 (holds c: {holds_c})"
        );
    }
}

/// The light press of [`cattaneo_mindlin_light_press`] on Newton's path
/// (about 30 s of CPU, so not in the default suite: `cargo test --release
/// --test cattaneo_mindlin -- --ignored`): at most 7 Newton iterations per
/// increment (measured 7, 5, 6, 6 in the press and 5, 4, 4, 4, 4 in the
/// shear; `light.toml`, from a first press increment of 0.0625, at most 6).
#[test]
#[ignore = "about 30 s of CPU: cargo test --release --test cattaneo_mindlin -- --ignored"]
fn light_press_on_newtons_path_takes_at_most_7_iterations() {
    let out = tempfile::tempdir().unwrap();
    let (_, record) = run_pinned("light-coarse.toml", out.path(), Solver::Newton("newton"));
    record.assert_iterations_at_most(7);
}

/// How a run of [`pinned`] solves: the default (`auto`, which takes the
/// condensed path for these linear elastic bodies), or Newton's path
/// with the tangential multiplier of exact stick in the given form
/// (`newton` or `outer`).
#[derive(Clone, Copy)]
enum Solver {
    Auto,
    Newton(&'static str),
}

/// A copy of the case `case` in `folder` (named after `solver`) with the
/// increments pinned to the first of each step (0.25 in the press, 0.2 in
/// the shear: friction is path dependent, so two runs compare on the same
/// increments), solved on `path`, its mesh named by its full path.
fn pinned(case: &Path, folder: &Path, solver: Solver) -> std::path::PathBuf {
    let text = std::fs::read_to_string(case).unwrap();
    let line = text
        .lines()
        .find(|l| l.starts_with("file = \""))
        .expect("the case names its mesh");
    let mesh = case.with_file_name(line.trim_start_matches("file = ").trim_matches('"'));
    let mut text = text.replace(line, &format!("file = {:?}", mesh.display().to_string()));
    let form = match solver {
        Solver::Auto => "auto",
        Solver::Newton(form) => {
            text = text.replace(
                "exact_stick = true",
                &format!("exact_stick = true\nfriction_multiplier = {form:?}"),
            );
            form
        }
    };
    for first in ["0.25", "0.2"] {
        let line = format!("initial_increment = {first}\n");
        assert!(text.contains(&line), "{line}");
        text = text.replace(&line, &format!("{line}max_increment = {first}\n"));
    }
    assert!(!text.contains("[solver]"));
    if let Solver::Newton(_) = solver {
        text.push_str("\n[solver]\nstrategy = \"monolithic\"\n");
    }
    let path = folder.join(format!("{form}.toml"));
    std::fs::write(&path, text).unwrap();
    path
}

/// The example's case `file` (in `examples/cattaneo-mindlin`) on pinned
/// increments ([`pinned`]) solved by `solver`, run into `folder/<solver>`;
/// and the case's path.
fn run_pinned(file: &str, folder: &Path, solver: Solver) -> (std::path::PathBuf, Record) {
    let case = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("examples/cattaneo-mindlin")
        .join(file);
    let pinned = pinned(&case, folder, solver);
    let output = folder.join(pinned.file_stem().unwrap());
    let record = run_recorded(&pinned, &output);
    (case, record)
}

/// Run the case `case` into `output`, recording every increment.
fn run_recorded(case: &Path, output: &Path) -> Record {
    let mut record = Record::default();
    let options = RunOptions {
        output: Some(output.to_path_buf()),
        threads: None,
        cancel: None,
        restart: None,
    };
    run_observed(case, &options, &mut record).expect("the example runs");
    record
}

/// The reference reads `E` and `ν` back from the material's tangent at
/// `F = I` (`mindlin::elastic_constants`): exact to rounding for the
/// example's `ν = 0.3`, for `ν = 0` and for one near incompressibility.
#[test]
fn elastic_constants_read_back_from_the_tangent() {
    for (e, nu) in [(1000.0, 0.3), (1000.0, 0.0), (2.5e5, 0.49)] {
        let material = signorini::material::LinearElastic::new(e, nu, "material").unwrap();
        let (e_read, nu_read) = mindlin::elastic_constants(&material);
        assert!((e_read / e - 1.0).abs() < 1e-12, "E {e_read} for {e}");
        assert!((nu_read - nu).abs() < 1e-12, "ν {nu_read} for {nu}");
    }
}
