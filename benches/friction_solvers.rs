//! Nonsymmetric linear solves of the frictional tangent, compared on the
//! `examples/press-pull` case (press, then pull to 0.8 μN; 3/4 of the
//! contact nodes slip at the end) at several mesh sizes:
//!
//! - `gmres`: GMRES preconditioned by the LDLᵀ (nested-dissection order) of
//!   the symmetric part of the tangent with friction's slip blocks replaced
//!   by stick blocks (the default; sparse LU as its fallback);
//! - `lu`: faer's sparse LU with partial pivoting (COLAMD order) every time.
//!
//! ```text
//! cargo bench --bench friction_solvers                          # small,medium
//! SIGNORINI_FRICTION_BENCH_SIZES=small,medium,large cargo bench --bench friction_solvers
//! ```
//!
//! The meshes are made at run time with `gmsh` (must be on `PATH`) from
//! `examples/press-pull/block.geo` with the characteristic length replaced:
//! `small` 0.12 (the example's, 5 k dofs), `medium` 0.06 (about 30 k
//! dofs), `large` 0.035 (about 130 k dofs). Per run: dofs, Newton
//! iterations, nonsymmetric solves, Krylov iterations per solve, LU solves
//! (fallbacks included), wall time and its split (factorisations, solves),
//! and the friction force as a check that both paths find the same answer.

use signorini::run::{run, RunOptions};
use std::path::Path;
use std::time::Instant;

const SIZES: [(&str, f64); 3] = [("small", 0.12), ("medium", 0.06), ("large", 0.035)];
const SOLVERS: [&str; 2] = ["gmres", "lu"];

fn main() {
    let wanted: Vec<String> = std::env::var("SIGNORINI_FRICTION_BENCH_SIZES")
        .unwrap_or_else(|_| "small,medium".into())
        .split(',')
        .map(|s| s.trim().to_string())
        .collect();
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/press-pull");
    let geo = std::fs::read_to_string(root.join("block.geo")).expect("block.geo");
    let case = std::fs::read_to_string(root.join("case.toml")).expect("case.toml");
    let tmp = tempfile::tempdir().expect("a temporary folder");
    println!("signorini nonsymmetric solvers on examples/press-pull");
    println!("threads: {}", rayon::current_num_threads());
    println!();
    println!("| size | dofs | solver | Newton | solves | Krylov/solve | LU solves | wall s | factor s | solve s | friction x |");
    println!("|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|");
    for &(name, h) in SIZES.iter().filter(|s| wanted.iter().any(|w| w == s.0)) {
        let dir = tmp.path().join(name);
        std::fs::create_dir_all(&dir).unwrap();
        assert!(
            geo.contains("CharacteristicLengthMax = 0.12;"),
            "the characteristic length lines of block.geo"
        );
        let text = geo.replace("= 0.12;", &format!("= {h};"));
        std::fs::write(dir.join("block.geo"), text).unwrap();
        let status = std::process::Command::new("gmsh")
            .current_dir(&dir)
            .args([
                "-3",
                "block.geo",
                "-format",
                "msh41",
                "-o",
                "block.msh",
                "-v",
                "0",
            ])
            .status()
            .expect("gmsh on PATH");
        assert!(status.success(), "gmsh failed");
        for solver in SOLVERS {
            let text = case.replace(
                "[output]",
                &format!("[solver]\nnonsymmetric = \"{solver}\"\n\n[output]"),
            );
            let case_path = dir.join(format!("case-{solver}.toml"));
            std::fs::write(&case_path, text).unwrap();
            let start = Instant::now();
            let outcome = run(
                &case_path,
                &RunOptions {
                    output: Some(dir.join(format!("out-{solver}"))),
                    threads: None,
                    cancel: None,
                    restart: None,
                },
            );
            let wall = start.elapsed().as_secs_f64();
            match outcome {
                Ok(o) => {
                    let s = &o.summary;
                    let newton: usize = s.increments.iter().map(|i| i.iterations).sum();
                    let solves = s.krylov_solves + s.lu_solves;
                    let friction = s.increments.last().unwrap().contact["base"].tangential_force[0];
                    println!(
                        "| {name} | {} | {solver} | {newton} | {solves} | {} | {} | {wall:.1} | {:.1} | {:.1} | {friction:.6} |",
                        s.dofs,
                        if s.krylov_solves > 0 {
                            format!("{:.1}", s.krylov_iterations as f64 / s.krylov_solves as f64)
                        } else {
                            "-".into()
                        },
                        s.lu_solves,
                        s.phase_times.factorisation,
                        s.phase_times.solve,
                    );
                }
                Err(e) => println!(
                    "| {name} | - | {solver} FAILED | - | - | - | - | {wall:.1} | - | - | {e} |"
                ),
            }
        }
    }
}
