//! Scaling benchmark: Newton increments on a structured Hex8 neo-Hookean
//! cube (bottom face fixed, top face pushed down), timed phase by phase.
//!
//! ```text
//! cargo bench --bench scaling
//! SIGNORINI_BENCH_SIZES=25,40 cargo bench --bench scaling   # quick run
//! ```
//!
//! Environment:
//! - `SIGNORINI_BENCH_SIZES`: cells per edge, comma separated
//!   (default `25,40,69` ≈ 53 k, 207 k, 1.0 M dofs).
//! - `SIGNORINI_BENCH_ITERS`: Newton iterations per case (default 2, ≥ 2).
//! - `SIGNORINI_BENCH_THREADS`: threads of the main runs (default: all
//!   cores); the thread comparison runs 1 thread against it.
//! - `SIGNORINI_BENCH_MAX_GIB`: largest factor + matrix estimate for which
//!   the numeric factorisation is attempted (default 20 GiB; it is also
//!   capped by `MemAvailable`).
//!
//! Every case runs in a child process (this binary re-invoked with
//! `--child SPEC`), so the peak resident memory (`VmHWM`) is per case. The
//! ordering comparison (AMD vs METIS ND) runs on the smallest size, the
//! thread comparison (1 vs 2 threads) on the second smallest.

use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, SymbolicCholesky, SymbolicCholeskyRaw,
    SymmetricOrdering,
};
use faer::{Par, Side};
use serde_json::{json, Value};
use signorini::assembly::Model;
use signorini::material::{Material, NeoHookean};
use signorini::mesh::structured::box_mesh;
use signorini::mesh::ElementKind;
use signorini::problem::{norm, Amplitude, PrescribedDisplacement, Problem, SolverSettings, Step};
use signorini::solve::linear::{multiply, Ordering, SparseLdlt};
use signorini::solve::ordering::nested_dissection;
use std::process::Command;
use std::sync::Arc;
use std::time::{Duration, Instant};

const GIB: f64 = 1024.0 * 1024.0 * 1024.0;
const MIB: f64 = 1024.0 * 1024.0;
/// Edge length of the cube.
const LENGTH: f64 = 1.0;
/// Prescribed vertical displacement of the top face (2 % compression).
const TOP_DISPLACEMENT: f64 = -0.02 * LENGTH;

/// One case, as passed to a child: `n=25,ord=nd,threads=2,iters=2,max_gib=20`.
#[derive(Clone, Debug)]
struct Spec {
    cells: usize,
    nested_dissection: bool,
    threads: usize,
    iterations: usize,
    max_gib: f64,
}

impl Spec {
    fn encode(&self) -> String {
        format!(
            "n={},ord={},threads={},iters={},max_gib={}",
            self.cells,
            if self.nested_dissection { "nd" } else { "amd" },
            self.threads,
            self.iterations,
            self.max_gib
        )
    }

    fn decode(s: &str) -> Spec {
        let mut spec = Spec {
            cells: 10,
            nested_dissection: true,
            threads: 2,
            iterations: 2,
            max_gib: 20.0,
        };
        for kv in s.split(',') {
            let (k, v) = kv.split_once('=').expect("key=value");
            match k {
                "n" => spec.cells = v.parse().expect("cells"),
                "ord" => spec.nested_dissection = v == "nd",
                "threads" => spec.threads = v.parse().expect("threads"),
                "iters" => spec.iterations = v.parse().expect("iterations"),
                "max_gib" => spec.max_gib = v.parse().expect("max_gib"),
                _ => panic!("unknown key {k}"),
            }
        }
        spec
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if let Some(i) = args.iter().position(|a| a == "--child") {
        let spec = Spec::decode(&args[i + 1]);
        let result = run_case(&spec);
        println!("RESULT {result}");
        return;
    }
    parent();
}

// ---------------------------------------------------------------- parent

fn env_list(name: &str, default: &str) -> Vec<usize> {
    std::env::var(name)
        .unwrap_or_else(|_| default.into())
        .split(',')
        .filter(|s| !s.trim().is_empty())
        .map(|s| s.trim().parse().expect("a list of integers"))
        .collect()
}

fn parent() {
    let sizes = env_list("SIGNORINI_BENCH_SIZES", "25,40,69");
    let iterations = env_list("SIGNORINI_BENCH_ITERS", "2")[0].max(2);
    let max_gib: f64 = std::env::var("SIGNORINI_BENCH_MAX_GIB")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(20.0);
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let threads = env_list("SIGNORINI_BENCH_THREADS", &cores.to_string())[0].max(1);
    println!("signorini scaling benchmark");
    println!(
        "Hex8 unit cube, neo-Hookean (E = 1, nu = 0.3), bottom (zmin) fixed, top (zmax) u = (0, 0, {TOP_DISPLACEMENT}) (2 % compression), predictor u_z = d z / L; {iterations} full Newton iterations per case"
    );
    println!(
        "machine: {cores} logical cores, {:.1} GiB RAM ({:.1} GiB available at start)",
        meminfo_kib("MemTotal") as f64 * 1024.0 / GIB,
        meminfo_kib("MemAvailable") as f64 * 1024.0 / GIB
    );
    println!("each case in its own child process; peak RSS = VmHWM of that process\n");

    let spec = |cells, nd, threads| Spec {
        cells,
        nested_dissection: nd,
        threads,
        iterations,
        max_gib,
    };
    let mut scaling = Vec::new();
    for &n in &sizes {
        scaling.push(run_child(&spec(n, true, threads)));
    }
    print_scaling(&scaling);

    let mut sorted = sizes.clone();
    sorted.sort_unstable();
    sorted.dedup();
    if let Some(&small) = sorted.first() {
        let nd = scaling
            .iter()
            .find(|r| r["cells"] == small)
            .cloned()
            .expect("ran above");
        let amd = run_child(&spec(small, false, threads));
        print_orderings(&[amd, nd]);
    }
    if let Some(&mid) = sorted.get(1).or(sorted.first()) {
        let two = scaling
            .iter()
            .find(|r| r["cells"] == mid)
            .cloned()
            .expect("ran above");
        let one = run_child(&spec(mid, true, 1));
        print_threads(&[one, two], cores);
    }
}

fn run_child(spec: &Spec) -> Value {
    let exe = std::env::current_exe().expect("own path");
    eprintln!("[bench] running {}", spec.encode());
    let out = Command::new(exe)
        .arg("--child")
        .arg(spec.encode())
        .stderr(std::process::Stdio::inherit())
        .output()
        .expect("child process starts");
    let stdout = String::from_utf8_lossy(&out.stdout);
    match stdout.lines().find_map(|l| l.strip_prefix("RESULT ")) {
        Some(json) if out.status.success() => serde_json::from_str(json).expect("valid json"),
        _ => json!({
            "cells": spec.cells,
            "failed": format!("child exited with {}", out.status),
        }),
    }
}

fn f(v: &Value, key: &str) -> f64 {
    v[key].as_f64().unwrap_or(f64::NAN)
}

fn secs(v: &Value, key: &str) -> String {
    let s = f(v, key);
    if s.is_nan() {
        "-".into()
    } else if s < 1.0 {
        format!("{:.0} ms", s * 1e3)
    } else {
        format!("{s:.2} s")
    }
}

fn iter_secs(v: &Value, i: usize, key: &str) -> String {
    match v["iterations"].get(i) {
        Some(it) => secs(it, key),
        None => "-".into(),
    }
}

fn count(x: f64) -> String {
    if x.is_nan() {
        "-".into()
    } else if x >= 1e9 {
        format!("{:.2} G", x / 1e9)
    } else if x >= 1e6 {
        format!("{:.2} M", x / 1e6)
    } else if x >= 1e3 {
        format!("{:.1} k", x / 1e3)
    } else {
        format!("{x:.0}")
    }
}

fn bytes(x: f64) -> String {
    if x.is_nan() {
        "-".into()
    } else if x >= GIB {
        format!("{:.2} GiB", x / GIB)
    } else {
        format!("{:.0} MiB", x / MIB)
    }
}

/// Print rows (label, one cell per column) as an aligned table.
fn table(header: &[String], rows: &[(String, Vec<String>)]) {
    let w0 = rows.iter().map(|r| r.0.chars().count()).max().unwrap_or(0);
    let widths: Vec<usize> = (0..header.len())
        .map(|c| {
            rows.iter()
                .map(|r| r.1[c].chars().count())
                .chain([header[c].chars().count()])
                .max()
                .unwrap_or(0)
        })
        .collect();
    let line = |label: &str, cells: &[String]| {
        let mut s = format!("{label:<w0$}");
        for (c, w) in cells.iter().zip(&widths) {
            s.push_str(&format!(" | {c:>w$}"));
        }
        println!("{}", s.trim_end());
    };
    line("", header);
    println!(
        "{}",
        "-".repeat(w0 + widths.iter().map(|w| w + 3).sum::<usize>())
    );
    for (label, cells) in rows {
        line(label, cells);
    }
    println!();
}

/// Rows common to all tables, one column per result.
fn rows(results: &[Value]) -> Vec<(String, Vec<String>)> {
    let col = |g: &dyn Fn(&Value) -> String| results.iter().map(g).collect::<Vec<_>>();
    let max_iters = results
        .iter()
        .map(|r| r["iterations"].as_array().map_or(0, |a| a.len()))
        .max()
        .unwrap_or(0);
    let mut rows: Vec<(String, Vec<String>)> = vec![
        ("elements".into(), col(&|r| count(f(r, "elements")))),
        ("dofs".into(), col(&|r| count(f(r, "dofs")))),
        (
            "matrix nnz (both triangles)".into(),
            col(&|r| count(f(r, "nnz"))),
        ),
        ("threads".into(), col(&|r| format!("{}", r["threads"]))),
        ("mesh + model setup".into(), col(&|r| secs(r, "setup_s"))),
        (
            "ordering (METIS ND, node graph)".into(),
            col(&|r| secs(r, "ordering_s")),
        ),
        (
            "symbolic analysis (incl. AMD)".into(),
            col(&|r| secs(r, "symbolic_s")),
        ),
        ("factor nnz".into(), col(&|r| count(f(r, "factor_nnz")))),
        (
            "factor memory (8 B x nnz)".into(),
            col(&|r| bytes(8.0 * f(r, "factor_nnz"))),
        ),
        (
            "factor flops (sum c_j^2)".into(),
            col(&|r| count(f(r, "flops"))),
        ),
        (
            "estimate factor + matrix".into(),
            col(&|r| bytes(f(r, "estimate_bytes"))),
        ),
        (
            "faer numeric scratch".into(),
            col(&|r| bytes(f(r, "scratch_bytes"))),
        ),
        (
            "estimate whole process".into(),
            col(&|r| bytes(f(r, "process_estimate_bytes"))),
        ),
    ];
    for i in 0..max_iters {
        let n = i + 1;
        rows.push((
            format!("it {n}: assembly (f + K)"),
            col(&|r| iter_secs(r, i, "assembly_s")),
        ));
        rows.push((
            format!("it {n}: BC rows/cols"),
            col(&|r| iter_secs(r, i, "bc_s")),
        ));
        rows.push((
            format!("it {n}: factorize() call"),
            col(&|r| iter_secs(r, i, "factorize_s")),
        ));
        rows.push((
            format!("it {n}:   of which numeric"),
            col(&|r| iter_secs(r, i, "numeric_s")),
        ));
        rows.push((
            format!("it {n}: solve (1 rhs)"),
            col(&|r| iter_secs(r, i, "solve_s")),
        ));
        rows.push((
            format!("it {n}: Newton residual before"),
            col(&|r| match r["iterations"].get(i) {
                Some(it) => format!("{:.2e}", f(it, "residual")),
                None => "-".into(),
            }),
        ));
        rows.push((
            format!("it {n}: |K du + r| / |r|"),
            col(&|r| match r["iterations"].get(i) {
                Some(it) => format!("{:.1e}", f(it, "linear_residual")),
                None => "-".into(),
            }),
        ));
    }
    rows.push((
        "residual after last iteration".into(),
        col(&|r| {
            let x = f(r, "final_residual");
            if x.is_nan() {
                "-".into()
            } else {
                format!("{x:.2e}")
            }
        }),
    ));
    rows.push((
        "numeric rate (flops / time)".into(),
        col(&|r| {
            let it = r["iterations"].as_array().and_then(|a| a.last());
            match it {
                Some(it) => format!("{:.1} GFlop/s", f(r, "flops") / f(it, "numeric_s") / 1e9),
                None => "-".into(),
            }
        }),
    ));
    rows.push((
        "peak RSS after setup".into(),
        col(&|r| bytes(f(r, "hwm_setup"))),
    ));
    rows.push((
        "peak RSS after analysis".into(),
        col(&|r| bytes(f(r, "hwm_symbolic"))),
    ));
    rows.push((
        "peak RSS (VmHWM, whole case)".into(),
        col(&|r| bytes(f(r, "hwm_end"))),
    ));
    rows.push(("case wall time".into(), col(&|r| secs(r, "wall_s"))));
    rows.push((
        "load average (1 min) start / end".into(),
        col(&|r| format!("{:.1} / {:.1}", f(r, "load_start"), f(r, "load_end"))),
    ));
    rows.push((
        "note".into(),
        col(&|r| {
            if r["failed"].is_string() || r["skipped"].is_string() {
                "see below".into()
            } else {
                String::new()
            }
        }),
    ));
    rows
}

/// The notes of failed or skipped cases, below a table.
fn notes(header: &[String], results: &[Value]) {
    for (h, r) in header.iter().zip(results) {
        if let Some(note) = r["failed"].as_str().or(r["skipped"].as_str()) {
            println!("note ({h}): {note}");
        }
    }
    if results
        .iter()
        .any(|r| r["failed"].is_string() || r["skipped"].is_string())
    {
        println!();
    }
}

fn print_scaling(results: &[Value]) {
    println!(
        "== Scaling (METIS nested dissection, {} threads) ==",
        results
            .first()
            .map_or(0, |r| r["threads"].as_u64().unwrap_or(0))
    );
    let header: Vec<String> = results
        .iter()
        .map(|r| format!("{}^3 cells", r["cells"]))
        .collect();
    table(&header, &rows(results));
    notes(&header, results);
}

fn print_orderings(results: &[Value]) {
    println!("== Ordering ({}^3 cells) ==", results[0]["cells"]);
    let header = vec!["AMD (faer)".to_string(), "METIS ND".to_string()];
    table(&header, &rows(results));
    notes(&header, results);
}

fn print_threads(results: &[Value], cores: usize) {
    println!(
        "== Threads ({}^3 cells, METIS ND; the machine has {cores} cores) ==",
        results[0]["cells"]
    );
    let header: Vec<String> = results
        .iter()
        .map(|r| format!("{} thread(s)", r["threads"]))
        .collect();
    table(&header, &rows(results));
    notes(&header, results);
}

// ----------------------------------------------------------------- child

/// A `kB` field of `/proc/self/status` (e.g. `VmHWM`), in bytes.
fn status_bytes(field: &str) -> f64 {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    proc_field(&status, field) as f64 * 1024.0
}

/// A `kB` field of `/proc/meminfo`, in kB.
fn meminfo_kib(field: &str) -> u64 {
    let info = std::fs::read_to_string("/proc/meminfo").unwrap_or_default();
    proc_field(&info, field)
}

fn proc_field(text: &str, field: &str) -> u64 {
    text.lines()
        .find_map(|l| {
            let rest = l.strip_prefix(field)?.strip_prefix(':')?;
            rest.split_whitespace().next()?.parse().ok()
        })
        .unwrap_or(0)
}

/// `Σ_j c_j²` over the columns of `L` (`c_j` = entries of column `j`
/// including the diagonal): the usual flop estimate of a Cholesky/LDLᵀ.
fn factor_flops(symbolic: &SymbolicCholesky<usize>) -> f64 {
    match symbolic.raw() {
        SymbolicCholeskyRaw::Supernodal(s) => {
            let begin = s.supernode_begin();
            let end = s.supernode_end();
            (0..s.n_supernodes())
                .map(|k| {
                    let w = end[k] - begin[k];
                    let r = s.supernode(k).pattern().len();
                    (0..w).map(|i| ((w - i + r) as f64).powi(2)).sum::<f64>()
                })
                .sum()
        }
        SymbolicCholeskyRaw::Simplicial(s) => {
            let cp = s.col_ptr();
            cp.windows(2).map(|w| ((w[1] - w[0]) as f64).powi(2)).sum()
        }
    }
}

fn dur(d: Duration) -> f64 {
    d.as_secs_f64()
}

fn prescribe(problem: &mut Problem, surface: &str, components: &[(usize, f64)]) {
    let mesh = &problem.model.mesh;
    let s = mesh.surface(surface).expect("surface exists");
    problem.prescribed.push(PrescribedDisplacement {
        surface: surface.into(),
        nodes: mesh.surface_nodes(s),
        components: components.to_vec(),
        amplitude: Amplitude::ramp(),
    });
}

/// The 1-minute load average of the machine.
fn load_average() -> f64 {
    std::fs::read_to_string("/proc/loadavg")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse().ok())
        .unwrap_or(f64::NAN)
}

fn run_case(spec: &Spec) -> Value {
    let wall = Instant::now();
    let load_start = load_average();
    rayon::ThreadPoolBuilder::new()
        .num_threads(spec.threads)
        .build_global()
        .expect("first pool of this process");
    let n = spec.cells;
    let log = |msg: String| eprintln!("[n={n} t={:7.1}s] {msg}", wall.elapsed().as_secs_f64());

    // --- mesh, model (geometry, sparsity pattern), boundary conditions
    let start = Instant::now();
    let mesh = box_mesh(ElementKind::Hex8, [n, n, n], [LENGTH; 3]);
    let num_elements = mesh.elements.len();
    let material: Arc<dyn Material> =
        Arc::new(NeoHookean::new(1.0, 0.3, "material").expect("valid material"));
    let model =
        Model::new(Arc::new(mesh), vec![material], vec![0; num_elements]).expect("valid mesh");
    let mut problem = Problem {
        model,
        prescribed: Vec::new(),
        rotations: Vec::new(),
        pressures: Vec::new(),
        body_forces: Vec::new(),
        nodal_forces: Vec::new(),
        contacts: Default::default(),
        timings: Default::default(),
        dissection: None,
        steps: vec![Step {
            name: "load".into(),
            end_time: 1.0,
            initial_increment: 1.0,
            min_increment: 1.0,
            max_increment: 1.0,
        }],
        settings: SolverSettings::default(),
    };
    prescribe(&mut problem, "zmin", &[(0, 0.0), (1, 0.0), (2, 0.0)]);
    prescribe(
        &mut problem,
        "zmax",
        &[(0, 0.0), (1, 0.0), (2, TOP_DISPLACEMENT)],
    );
    let constrained = problem.constrained_dofs();
    let setup = start.elapsed();
    let dofs = problem.model.num_dofs();
    let nnz = problem.model.pattern.nnz();
    let hwm_setup = status_bytes("VmHWM");
    log(format!(
        "setup {:.2} s: {num_elements} elements, {dofs} dofs, nnz {nnz}",
        dur(setup)
    ));

    let mut result = json!({
        "cells": n,
        "threads": spec.threads,
        "ordering": if spec.nested_dissection { "nd" } else { "amd" },
        "elements": num_elements,
        "dofs": dofs,
        "nnz": nnz,
        "setup_s": dur(setup),
        "hwm_setup": hwm_setup,
        "load_start": load_start,
    });

    // --- fill-reducing ordering
    let ordering = if spec.nested_dissection {
        let start = Instant::now();
        let (xadj, adjncy) = problem.model.pattern.node_graph();
        let nodes = nested_dissection(&xadj, &adjncy).expect("METIS");
        let perm = problem.model.pattern.dof_ordering(&nodes);
        result["ordering_s"] = json!(dur(start.elapsed()));
        log(format!("METIS ND ordering {:.2} s", dur(start.elapsed())));
        Ordering::Custom(perm)
    } else {
        Ordering::Amd
    };

    // --- symbolic analysis alone, to size the factor before the numeric
    // phase (SparseLdlt only analyses inside factorize(), so this is done
    // here with faer directly and repeated inside the first factorize()).
    let pattern = problem.model.pattern.symbolic();
    let start = Instant::now();
    let symbolic = match &ordering {
        Ordering::Amd => factorize_symbolic_cholesky(
            pattern.as_ref(),
            Side::Lower,
            SymmetricOrdering::Amd,
            CholeskySymbolicParams::default(),
        ),
        Ordering::Custom(fwd) => {
            let mut inv = vec![0usize; fwd.len()];
            for (new, &old) in fwd.iter().enumerate() {
                inv[old] = new;
            }
            let perm = faer::perm::Perm::new_checked(
                fwd.clone().into_boxed_slice(),
                inv.into_boxed_slice(),
                fwd.len(),
            );
            factorize_symbolic_cholesky(
                pattern.as_ref(),
                Side::Lower,
                SymmetricOrdering::Custom(perm.as_ref()),
                CholeskySymbolicParams::default(),
            )
        }
    }
    .expect("symbolic analysis");
    let precheck = start.elapsed();
    let factor_nnz = symbolic.len_val();
    let flops = factor_flops(&symbolic);
    let par = if spec.threads == 1 {
        Par::Seq
    } else {
        Par::rayon(spec.threads)
    };
    let scratch = symbolic
        .factorize_numeric_ldlt_scratch::<f64>(par, Default::default())
        .size_bytes() as f64;
    drop(symbolic);
    // factor values + matrix values + matrix row indices (8 B each)
    let estimate = 8.0 * factor_nnz as f64 + 16.0 * nnz as f64;
    // what the process will hold at the numeric factorisation: what it has
    // now (mesh, model, pattern), the tangent values, SparseLdlt's copy of
    // the pattern, the factor and faer's scratch
    let process_estimate = status_bytes("VmRSS")
        + 8.0 * factor_nnz as f64
        + 8.0 * nnz as f64
        + 8.0 * (nnz + dofs) as f64
        + scratch;
    let available = meminfo_kib("MemAvailable") as f64 * 1024.0;
    // keep 1 GiB of what is available for the rest of the machine
    let limit = (spec.max_gib * GIB).min(available - GIB);
    result["symbolic_precheck_s"] = json!(dur(precheck));
    result["symbolic_s"] = json!(dur(precheck));
    result["factor_nnz"] = json!(factor_nnz);
    result["flops"] = json!(flops);
    result["estimate_bytes"] = json!(estimate);
    result["scratch_bytes"] = json!(scratch);
    result["process_estimate_bytes"] = json!(process_estimate);
    result["available_bytes"] = json!(available);
    result["hwm_symbolic"] = json!(status_bytes("VmHWM"));
    log(format!(
        "symbolic {:.2} s: factor nnz {factor_nnz}, {:.3e} flops, factor + matrix {:.2} GiB, process {:.2} GiB (scratch {:.2} GiB; limit {:.2} GiB, available {:.2} GiB)",
        dur(precheck),
        flops,
        estimate / GIB,
        process_estimate / GIB,
        scratch / GIB,
        spec.max_gib,
        available / GIB
    ));
    if estimate.max(process_estimate) > limit {
        result["skipped"] = json!(format!(
            "does not fit: factor + matrix ~ {:.1} GiB, whole process ~ {:.1} GiB > limit {:.1} GiB (min of {:.0} GiB and MemAvailable {:.1} GiB - 1 GiB); numeric factorisation skipped",
            estimate / GIB,
            process_estimate / GIB,
            limit / GIB,
            spec.max_gib,
            available / GIB
        ));
        result["hwm_end"] = json!(status_bytes("VmHWM"));
        result["wall_s"] = json!(dur(wall.elapsed()));
        result["load_end"] = json!(load_average());
        log("skipped the numeric factorisation".into());
        return result;
    }

    // --- Newton iterations driven by hand, timing each phase
    let mut solver = SparseLdlt::new(ordering, spec.threads);
    // predictor: the homogeneous compression u_z = d z / L (the top and
    // bottom faces then hold exactly their prescribed values); Newton
    // corrects the lateral (Poisson) response that the clamped faces resist
    let mut u = vec![0.0; dofs];
    for (node, x) in problem.model.mesh.nodes.iter().enumerate() {
        u[3 * node + 2] = TOP_DISPLACEMENT * x[2] / LENGTH;
    }
    problem.apply_prescribed(1.0, &mut u);
    let mut k_values = vec![0.0; nnz];
    let mut iterations = Vec::new();
    for it in 0..spec.iterations {
        let start = Instant::now();
        let residual = problem
            .residual(1.0, &u, Some(&mut k_values))
            .expect("no inverted element");
        let assembly = start.elapsed();
        let mut r = residual.r;
        for (x, &c) in r.iter_mut().zip(&constrained) {
            if c {
                *x = 0.0;
            }
        }
        let relative = norm(&r)
            / residual
                .internal_norm
                .max(residual.external_norm)
                .max(f64::MIN_POSITIVE);

        let start = Instant::now();
        signorini::solve::newton::apply_identity_rows(&problem, &constrained, &mut k_values);
        let bc = start.elapsed();

        let start = Instant::now();
        solver
            .factorize(pattern, &k_values, None)
            .expect("factorisation");
        let factorize = start.elapsed();

        let mut du: Vec<f64> = r.iter().map(|x| -x).collect();
        solver.solve_in_place(&mut du).expect("solve");
        // check of the linear solve: ‖K δu + r‖ / ‖r‖ (not timed)
        let mut kdu = vec![0.0; dofs];
        multiply(pattern, &k_values, &du, &mut kdu);
        let linear = norm(&kdu.iter().zip(&r).map(|(a, b)| a + b).collect::<Vec<_>>())
            / norm(&r).max(f64::MIN_POSITIVE);
        for (x, &c) in du.iter_mut().zip(&constrained) {
            if c {
                *x = 0.0;
            }
        }
        for (ui, di) in u.iter_mut().zip(&du) {
            *ui += di;
        }
        let t = solver.timings;
        log(format!(
            "iteration {}: residual {relative:.2e}, assembly {:.2} s, factorize {:.2} s (symbolic {:.2} s, numeric {:.2} s), solve {:.3} s",
            it + 1,
            dur(assembly),
            dur(factorize),
            if it == 0 { dur(t.symbolic) } else { 0.0 },
            dur(t.numeric),
            dur(t.solve)
        ));
        if it == 0 {
            // the analysis the library really does (same as the pre-check)
            result["symbolic_s"] = json!(dur(t.symbolic));
            assert_eq!(solver.factor_nnz(), factor_nnz);
        }
        iterations.push(json!({
            "residual": relative,
            "assembly_s": dur(assembly),
            "bc_s": dur(bc),
            "factorize_s": dur(factorize),
            "numeric_s": dur(t.numeric),
            "solve_s": dur(t.solve),
            "linear_residual": linear,
            "analyses": t.analyses,
        }));
    }
    assert_eq!(
        solver.timings.analyses, 1,
        "the symbolic analysis is reused"
    );
    let residual = problem
        .residual(1.0, &u, None)
        .expect("no inverted element");
    let mut r = residual.r;
    for (x, &c) in r.iter_mut().zip(&constrained) {
        if c {
            *x = 0.0;
        }
    }
    result["final_residual"] = json!(norm(&r) / residual.internal_norm.max(residual.external_norm));
    result["iterations"] = Value::Array(iterations);
    result["hwm_end"] = json!(status_bytes("VmHWM"));
    result["wall_s"] = json!(dur(wall.elapsed()));
    result["load_end"] = json!(load_average());
    result
}
