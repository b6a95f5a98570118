//! Every `[solver] linear` backend through the case file: the stacked
//! blocks with Coulomb friction (a nonsymmetric tangent) give the same
//! solution whichever solver takes the Newton corrections, and each backend
//! reports what it did (Krylov solves, LU solves, LDLᵀ analyses).

mod common;

use common::{assert_case_error, write_stacked_blocks_case};

const UPPER: &str = "model = \"neo_hookean\"\nyoungs_modulus = 50.0\npoisson_ratio = 0.3";

/// Run the frictional stacked blocks with `[solver] linear = method`.
fn run(method: &str) -> signorini::run::RunOutcome {
    let dir = tempfile::tempdir().unwrap();
    // node-to-surface named (its counts below; mortar is the default)
    let path = write_stacked_blocks_case(
        dir.path(),
        UPPER,
        "friction_coefficient = 0.3\ndiscretisation = \"node_to_surface\"",
    );
    let text = std::fs::read_to_string(&path).unwrap();
    let text = text.replace("[solver]\n", &format!("[solver]\nlinear = \"{method}\"\n"));
    std::fs::write(&path, text).unwrap();
    signorini::run::run(
        &path,
        &signorini::run::RunOptions {
            output: Some(dir.path().join("out")),
            threads: None,
            cancel: None,
            restart: None,
        },
    )
    .unwrap_or_else(|e| panic!("linear = {method}: {e}"))
}

/// The four backends agree to 1e-8 of the largest displacement, and their
/// statistics show which solver worked: GMRES (auto's choice for this
/// nonsymmetric tangent) solves by Krylov iterations on one LDLᵀ analysis,
/// the LU once per Newton correction without any LDLᵀ, the direct LDLᵀ
/// without Krylov iterations.
#[test]
fn every_linear_solver_gives_the_same_solution() {
    let auto = run("auto");
    let scale = auto.displacement.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    assert!(scale > 0.0);
    let corrections: usize = auto.summary.increments.iter().map(|i| i.iterations).sum();
    assert!(corrections > 0);
    assert!(auto.summary.krylov_solves > 0);
    assert_eq!(auto.summary.symbolic_analyses, 1);
    for method in ["ldlt", "gmres", "lu"] {
        let other = run(method);
        for (a, b) in auto.displacement.iter().zip(&other.displacement) {
            assert!((a - b).abs() <= 1e-8 * scale, "{method}: {a} vs {b}");
        }
        let s = &other.summary;
        match method {
            "gmres" => {
                assert_eq!(s.krylov_solves, auto.summary.krylov_solves);
                assert_eq!(s.krylov_iterations, auto.summary.krylov_iterations);
                assert_eq!(s.lu_solves, auto.summary.lu_solves);
            }
            "lu" => {
                let corrections: usize = s.increments.iter().map(|i| i.iterations).sum();
                assert_eq!(s.lu_solves, corrections);
                assert_eq!((s.krylov_solves, s.symbolic_analyses), (0, 0));
            }
            _ => {
                assert_eq!(s.krylov_solves, 0);
                assert_eq!(s.symbolic_analyses, 1);
            }
        }
    }
}

/// An unknown linear solver is an error naming the key and the value.
#[test]
fn an_unknown_linear_solver_is_an_error() {
    let dir = tempfile::tempdir().unwrap();
    let path = write_stacked_blocks_case(dir.path(), UPPER, "");
    let text = std::fs::read_to_string(path).unwrap();
    let text = text.replace("[solver]\n", "[solver]\nlinear = \"cholesky\"\n");
    assert_case_error(dir.path(), &text, &["solver.linear", "cholesky"]);
}
