//! Contact methods on Hertz: the `examples/hertz` hemisphere pressed on a
//! rigid plane, run end to end (`signorini::run::run`) with each of the four
//! normal-contact methods (`penalty`, `uzawa`, `rockafellar`, `slack`) on
//! meshes of several sizes, compared with Hertz.
//!
//! ```text
//! cargo bench --bench contact_methods                                   # small,medium
//! SIGNORINI_CONTACT_BENCH_SIZES=small cargo bench --bench contact_methods
//! SIGNORINI_CONTACT_BENCH_SIZES=small,medium,large cargo bench --bench contact_methods
//! SIGNORINI_CONTACT_BENCH_METHODS=rockafellar,slack cargo bench --bench contact_methods
//! ```
//!
//! The meshes are made at run time with `gmsh` (must be on `PATH`) from a
//! copy of `examples/hertz/hemisphere.geo` with the refinement field's
//! `SizeMin` and `SizeMax` scaled, in a temporary folder:
//! - `small`: the example's sizes (`SizeMin = 0.006`), about 26 k dofs;
//! - `medium`: `SizeMin = 0.0038`, about 100 k dofs;
//! - `large`: `SizeMin = 0.0024`, about 400 k dofs. Not run by default
//!   (it takes well over 10 minutes on a 2-core machine); ask for it.
//!
//! Per run the table gives: dofs, method, Newton iterations per increment,
//! their total, the Uzawa outer iterations (Newton restarts inferred from
//! the residual history, see [`outer_iterations`]), the largest penetration
//! over the contact element size `h`, the errors of the contact radius
//! (least-squares fit of `p²` against `r²`, as in `tests/cases.rs`) and of
//! the peak nodal pressure against Hertz with the measured force, and the
//! wall time of the run (total and per Newton iteration) with its split
//! from `summary.json`'s `phase_times` (element assembly, contact search and
//! assembly, numeric factorisation, triangular solves). A run that fails
//! is reported as such (with its error), which is a result too.

use signorini::contact::hertz::{fitted_contact_radius, radial_pressures, Hertz};
use signorini::run::{run, RunOptions};
use std::path::{Path, PathBuf};
use std::time::Instant;

const METHODS: [&str; 4] = ["penalty", "uzawa", "rockafellar", "slack"];

/// Mesh sizes: name, `SizeMin`, `SizeMax` of the threshold field.
const SIZES: [(&str, f64, f64); 3] = [
    ("small", 0.006, 0.15),
    ("medium", 0.0038, 0.095),
    ("large", 0.0024, 0.06),
];

/// One run's row.
struct Row {
    size: String,
    dofs: usize,
    method: String,
    per_increment: Vec<usize>,
    total: usize,
    outer: Vec<usize>,
    penetration_over_h: f64,
    radius_error: f64,
    peak_error: f64,
    wall: f64,
    /// `phase_times` of the run's summary: assembly, contact, factorisation,
    /// solve (seconds; NaN for a run that did not finish).
    phases: [f64; 4],
    failure: Option<String>,
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    // child: `--child SIZE METHOD DIR`, one run, its row as a JSON line
    if let Some(i) = args.iter().position(|a| a == "--child") {
        let case = std::fs::read_to_string(
            Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/hertz/case.toml"),
        )
        .expect("examples/hertz/case.toml");
        let row = run_one(&case, Path::new(&args[i + 3]), &args[i + 1], &args[i + 2]);
        println!("ROW {}", row.to_json());
        return;
    }
    let wanted: Vec<String> = std::env::var("SIGNORINI_CONTACT_BENCH_SIZES")
        .unwrap_or_else(|_| "small,medium".into())
        .split(',')
        .map(|s| s.trim().to_string())
        .filter(|s| !s.is_empty())
        .collect();
    for w in &wanted {
        assert!(
            SIZES.iter().any(|s| s.0 == w),
            "unknown size {w} (small, medium, large)"
        );
    }
    let methods: Vec<String> = std::env::var("SIGNORINI_CONTACT_BENCH_METHODS")
        .map(|v| v.split(',').map(|s| s.trim().to_string()).collect())
        .unwrap_or_else(|_| METHODS.iter().map(|m| m.to_string()).collect());
    for m in &methods {
        assert!(
            METHODS.contains(&m.as_str()),
            "unknown method {m} (penalty, uzawa, rockafellar, slack)"
        );
    }
    let timeout: f64 = std::env::var("SIGNORINI_CONTACT_BENCH_TIMEOUT")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(600.0);
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let geo = std::fs::read_to_string(root.join("examples/hertz/hemisphere.geo"))
        .expect("examples/hertz/hemisphere.geo");
    let tmp = tempfile::tempdir().expect("a temporary folder");
    println!("signorini contact methods on Hertz (examples/hertz)");
    println!(
        "threads: {}, time limit per run: {timeout} s",
        rayon::current_num_threads()
    );
    let mut rows = Vec::new();
    for &(name, size_min, size_max) in SIZES.iter().filter(|s| wanted.iter().any(|w| w == s.0)) {
        let dir = tmp.path().join(name);
        std::fs::create_dir_all(&dir).unwrap();
        let start = Instant::now();
        mesh(&geo, &dir, size_min, size_max);
        eprintln!(
            "[{name}] mesh SizeMin = {size_min}, SizeMax = {size_max}: {:.1} s",
            start.elapsed().as_secs_f64()
        );
        let first = rows.len();
        for method in &methods {
            let row = run_child(&dir, name, method, timeout);
            eprintln!("{}", format_row(&row));
            rows.push(row);
        }
        // a run killed before its first increment left no dof count: the
        // same mesh as the size's other runs
        let dofs = rows[first..].iter().map(|r| r.dofs).max().unwrap_or(0);
        rows[first..].iter_mut().for_each(|r| r.dofs = dofs);
    }
    println!();
    println!("{}", header());
    for row in &rows {
        println!("{}", format_row(row));
    }
    for row in rows.iter().filter(|r| r.failure.is_some()) {
        println!(
            "{} {}: {}",
            row.size,
            row.method,
            row.failure.as_deref().unwrap_or_default()
        );
    }
}

/// Run one case in a child process (this binary with `--child`), killed
/// after `timeout` seconds; a killed run is reported from the increments it
/// finished (as `summary.json` lists them: rewritten on a geometric
/// schedule, it lags the run by at most a ninth of its increments).
fn run_child(dir: &Path, size: &str, method: &str, timeout: f64) -> Row {
    let start = Instant::now();
    let mut child = std::process::Command::new(std::env::current_exe().unwrap())
        .arg("--child")
        .args([size, method])
        .arg(dir)
        .stdout(std::process::Stdio::piped())
        .spawn()
        .expect("the bench re-invoked as a child");
    loop {
        if let Some(status) = child.try_wait().unwrap() {
            let mut text = String::new();
            use std::io::Read;
            child
                .stdout
                .take()
                .unwrap()
                .read_to_string(&mut text)
                .unwrap();
            if let Some(line) = text.lines().find_map(|l| l.strip_prefix("ROW ")) {
                return Row::from_json(line);
            }
            let mut row = partial_row(dir, size, method, start.elapsed().as_secs_f64());
            row.failure = Some(format!("the child ended with {status} and no result"));
            return row;
        }
        if start.elapsed().as_secs_f64() > timeout {
            let _ = child.kill();
            let _ = child.wait();
            let mut row = partial_row(dir, size, method, start.elapsed().as_secs_f64());
            row.failure = Some(format!(
                "stopped after {timeout} s (SIGNORINI_CONTACT_BENCH_TIMEOUT); {} increments done",
                row.per_increment.len()
            ));
            return row;
        }
        std::thread::sleep(std::time::Duration::from_millis(200));
    }
}

/// A row from the `summary.json` a run left (converged increments only).
fn partial_row(dir: &Path, size: &str, method: &str, wall: f64) -> Row {
    let mut row = Row::empty(size, method, wall);
    let out = dir.join(format!("out-{method}"));
    if let Ok(text) = std::fs::read_to_string(out.join("summary.json")) {
        if let Ok(v) = serde_json::from_str::<serde_json::Value>(&text) {
            row.dofs = v["dofs"].as_u64().unwrap_or(0) as usize;
            for inc in v["increments"].as_array().into_iter().flatten() {
                let n = inc["iterations"].as_u64().unwrap_or(0) as usize;
                row.per_increment.push(n);
                let r: Vec<f64> = inc["residuals"]
                    .as_array()
                    .into_iter()
                    .flatten()
                    .filter_map(|x| x.as_f64())
                    .collect();
                row.outer.push(outer_iterations(&r));
            }
            row.total = row.per_increment.iter().sum();
        }
    }
    row
}

impl Row {
    /// A row with nothing measured but the wall time.
    fn empty(size: &str, method: &str, wall: f64) -> Row {
        Row {
            size: size.into(),
            dofs: 0,
            method: method.into(),
            per_increment: vec![],
            total: 0,
            outer: vec![],
            penetration_over_h: f64::NAN,
            radius_error: f64::NAN,
            peak_error: f64::NAN,
            wall,
            phases: [f64::NAN; 4],
            failure: None,
        }
    }

    fn to_json(&self) -> String {
        serde_json::json!({
            "size": self.size, "dofs": self.dofs, "method": self.method,
            "per_increment": self.per_increment, "total": self.total, "outer": self.outer,
            "pen": num(self.penetration_over_h), "a": num(self.radius_error),
            "p0": num(self.peak_error), "wall": self.wall, "phases": self.phases.map(num), "failure": self.failure,
        })
        .to_string()
    }

    fn from_json(s: &str) -> Row {
        let v: serde_json::Value = serde_json::from_str(s).expect("a row");
        let list = |k: &str| -> Vec<usize> {
            v[k].as_array()
                .into_iter()
                .flatten()
                .filter_map(|x| x.as_u64().map(|n| n as usize))
                .collect()
        };
        let f = |k: &str| v[k].as_f64().unwrap_or(f64::NAN);
        Row {
            size: v["size"].as_str().unwrap_or_default().into(),
            dofs: v["dofs"].as_u64().unwrap_or(0) as usize,
            method: v["method"].as_str().unwrap_or_default().into(),
            per_increment: list("per_increment"),
            total: v["total"].as_u64().unwrap_or(0) as usize,
            outer: list("outer"),
            penetration_over_h: f("pen"),
            radius_error: f("a"),
            peak_error: f("p0"),
            wall: f("wall"),
            phases: std::array::from_fn(|i| v["phases"][i].as_f64().unwrap_or(f64::NAN)),
            failure: v["failure"].as_str().map(String::from),
        }
    }
}

/// NaN as JSON null.
fn num(x: f64) -> Option<f64> {
    x.is_finite().then_some(x)
}

/// Write `hemisphere.geo` with the threshold sizes replaced into `dir` and
/// mesh it with gmsh into `dir/hemisphere.msh`.
fn mesh(geo: &str, dir: &Path, size_min: f64, size_max: f64) {
    let mut replaced = (false, false);
    let text: String = geo
        .lines()
        .map(|line| {
            if line.starts_with("Field[2].SizeMin") {
                replaced.0 = true;
                format!("Field[2].SizeMin = {size_min};")
            } else if line.starts_with("Field[2].SizeMax") {
                replaced.1 = true;
                format!("Field[2].SizeMax = {size_max};")
            } else {
                line.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("\n");
    assert!(
        replaced.0 && replaced.1,
        "SizeMin/SizeMax lines not found in hemisphere.geo"
    );
    let geo_path = dir.join("hemisphere.geo");
    std::fs::write(&geo_path, text + "\n").unwrap();
    let status = std::process::Command::new("gmsh")
        .arg("-3")
        .arg(&geo_path)
        .args(["-format", "msh41", "-o"])
        .arg(dir.join("hemisphere.msh"))
        .stdout(std::process::Stdio::null())
        .status()
        .expect("gmsh on PATH (the meshes are made at run time)");
    assert!(status.success(), "gmsh failed");
}

/// Run the example's case with `method` on the mesh in `dir`.
fn run_one(case_text: &str, dir: &Path, size: &str, method: &str) -> Row {
    let text = case_text.replace(
        "method = \"rockafellar\"",
        &format!("method = \"{method}\""),
    );
    assert!(text.contains(&format!("method = \"{method}\"")));
    let case_path = dir.join(format!("case-{method}.toml"));
    std::fs::write(&case_path, text).unwrap();
    let out: PathBuf = dir.join(format!("out-{method}"));
    let start = Instant::now();
    let result = run(
        &case_path,
        &RunOptions {
            output: Some(out.clone()),
            threads: None,
            cancel: None,
            restart: None,
        },
    );
    let wall = start.elapsed().as_secs_f64();
    let case = signorini::case::load(&case_path).expect("the case loads");
    let problem = case.build_problem().expect("the problem builds");
    let interface = problem.contacts.interface(0);
    let h = interface.element_size;
    let dofs = problem.model.num_dofs();
    let mut row = Row {
        dofs,
        ..Row::empty(size, method, wall)
    };
    let outcome = match result {
        Ok(outcome) => outcome,
        Err(e) => {
            let mut partial = partial_row(dir, size, method, wall);
            partial.dofs = dofs;
            partial.failure = Some(e.to_string());
            return partial;
        }
    };
    let t = &outcome.summary.phase_times;
    row.phases = [t.assembly, t.contact, t.factorisation, t.solve];
    let incs = &outcome.summary.increments;
    row.per_increment = incs.iter().map(|i| i.iterations).collect();
    row.total = row.per_increment.iter().sum();
    row.outer = incs
        .iter()
        .map(|i| outer_iterations(&i.residuals))
        .collect();
    let last = incs.last().expect("an increment");
    let name = interface.name.clone();
    row.penetration_over_h = last.contact[&name].largest_penetration / h;
    let force = last.contact[&name].force[2];
    // Hertz with the measured force (`signorini::contact::hertz`)
    let reference = Hertz::new(4.0 * force.abs(), 1.0, 1000.0 / (1.0 - 0.09)); // quarter model
    let (a, p0) = (reference.radius, reference.peak_pressure);
    let x = &outcome.displacement;
    let (_, reports) = problem
        .residual_in(1.0, x, &outcome.contact, None)
        .expect("the residual at the solution");
    let nodes = radial_pressures(
        &interface.nodes,
        &case.mesh.nodes,
        x,
        reports[0].iter().map(|r| r.pressure),
    );
    let peak = nodes.iter().map(|n| n.1).fold(0.0, f64::max);
    row.peak_error = (peak - p0) / p0;
    let a_fit = fitted_contact_radius(&nodes, 0.2 * p0);
    row.radius_error = (a_fit - a) / a;
    row
}

/// Newton solves in one increment's residual history. The summary
/// concatenates the Newton runs of every Uzawa multiplier update of an
/// increment; a new run starts where the residual jumps up from a converged
/// value (≤ 1e-8, the default tolerance). For the other methods this is 1.
fn outer_iterations(residuals: &[f64]) -> usize {
    1 + residuals
        .windows(2)
        .filter(|w| w[0] <= 1e-8 && w[1] > 10.0 * w[0].max(1e-14))
        .count()
}

fn header() -> String {
    format!(
        "| {:>6} | {:>7} | {:<11} | {:<18} | {:>5} | {:<16} | {:>9} | {:>8} | {:>8} | {:>8} | {:>8} | {:>7} | {:>9} | {:>8} | {:>7} |",
        "size",
        "dofs",
        "method",
        "Newton/increment",
        "total",
        "outer/increment",
        "pen/h",
        "a err",
        "p0 err",
        "wall s",
        "s/iter",
        "asm s",
        "contact s",
        "factor s",
        "solve s"
    ) + "\n|---:|---:|---|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
}

fn format_row(r: &Row) -> String {
    let list = |v: &[usize]| {
        v.iter()
            .map(|n| n.to_string())
            .collect::<Vec<_>>()
            .join(",")
    };
    let pct = |x: f64| {
        if x.is_finite() {
            format!("{:+.2}%", 100.0 * x)
        } else {
            "-".into()
        }
    };
    let method = if r.failure.is_some() {
        format!("{} FAILED", r.method)
    } else {
        r.method.clone()
    };
    format!(
        "| {:>6} | {:>7} | {:<11} | {:<18} | {:>5} | {:<16} | {:>9} | {:>8} | {:>8} | {:>8.1} | {:>8} | {:>7} | {:>9} | {:>8} | {:>7} |",
        r.size,
        r.dofs,
        method,
        list(&r.per_increment),
        r.total,
        list(&r.outer),
        if r.penetration_over_h.is_finite() {
            format!("{:.1e}", r.penetration_over_h)
        } else {
            "-".into()
        },
        pct(r.radius_error),
        pct(r.peak_error),
        r.wall,
        if r.total > 0 {
            format!("{:.2}", r.wall / r.total as f64)
        } else {
            "-".into()
        },
        seconds(r.phases[0]),
        seconds(r.phases[1]),
        seconds(r.phases[2]),
        seconds(r.phases[3]),
    )
}

fn seconds(x: f64) -> String {
    if x.is_finite() {
        format!("{x:.1}")
    } else {
        "-".into()
    }
}
