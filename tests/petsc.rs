//! The PETSc backend (`[solver] linear = "petsc"`, cargo feature `petsc`)
//! gives the faer solvers' answer: with its default (MUMPS LU) on the
//! frictional press-pull example (a nonsymmetric saddle-point tangent with
//! multipliers), and with MUMPS and GAMG (CG/GMRES on the penalty method,
//! where every unknown is a displacement, block size 3 and the rigid-body
//! near-null space) on the stacked blocks. Without the feature, asking for
//! PETSc is a case error that says how to get it.

mod common;

#[cfg(feature = "petsc")]
mod with_petsc {
    use super::common::write_stacked_blocks_case;
    use signorini::run::{run, RunOptions, RunOutcome};
    use std::path::Path;

    /// Run `case` with `[solver]` lines `solver` added.
    fn run_with(case: &Path, dir: &Path, solver: &str) -> RunOutcome {
        let text = std::fs::read_to_string(case).unwrap();
        let text = if text.contains("[solver]\n") {
            text.replace("[solver]\n", &format!("[solver]\n{solver}\n"))
        } else {
            format!("{text}\n[solver]\n{solver}\n")
        };
        let path = case.with_file_name(format!(
            "petsc-{}.toml",
            dir.file_name().unwrap().to_string_lossy()
        ));
        std::fs::write(&path, text).unwrap();
        let outcome = run(
            &path,
            &RunOptions {
                output: Some(dir.to_path_buf()),
                ..Default::default()
            },
        );
        std::fs::remove_file(&path).unwrap();
        outcome.unwrap_or_else(|e| panic!("[solver] {solver}: {e}"))
    }

    /// Displacements equal to `tolerance` of the largest one, and the same
    /// Newton iterations.
    fn assert_same(a: &RunOutcome, b: &RunOutcome, tolerance: f64, what: &str) {
        let scale = a.displacement.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        assert!(scale > 0.0);
        let worst = a
            .displacement
            .iter()
            .zip(&b.displacement)
            .map(|(x, y)| (x - y).abs())
            .fold(0.0f64, f64::max);
        println!("{what}: largest difference {:.2e} of {scale:.3e}", worst);
        assert!(
            worst <= tolerance * scale,
            "{what}: {worst} > {tolerance} × {scale}"
        );
    }

    #[test]
    fn mumps_gives_the_faer_answer_on_press_pull() {
        let dir = tempfile::tempdir().unwrap();
        let example = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/press-pull");
        let work = dir.path().join("case");
        std::fs::create_dir(&work).unwrap();
        for f in std::fs::read_dir(&example).unwrap() {
            let f = f.unwrap().path();
            if f.extension().is_some_and(|e| e == "msh" || e == "toml") {
                std::fs::copy(&f, work.join(f.file_name().unwrap())).unwrap();
            }
        }
        let case = work.join("case.toml");
        let faer = run_with(&case, &dir.path().join("faer"), "linear = \"auto\"");
        let petsc = run_with(&case, &dir.path().join("mumps"), "linear = \"petsc\"");
        assert_same(&faer, &petsc, 1e-8, "press-pull, MUMPS");
        assert!(petsc.summary.krylov_solves > 0);
    }

    #[test]
    fn mumps_and_gamg_give_the_faer_answer_with_penalty_contact() {
        let dir = tempfile::tempdir().unwrap();
        let case = write_stacked_blocks_case(
            dir.path(),
            "model = \"linear_elastic\"\nyoungs_modulus = 50.0\npoisson_ratio = 0.3",
            "method = \"penalty\"",
        );
        let faer = run_with(&case, &dir.path().join("faer"), "linear = \"ldlt\"");
        let mumps = run_with(&case, &dir.path().join("mumps"), "linear = \"petsc\"");
        assert_same(&faer, &mumps, 1e-8, "stacked blocks, MUMPS");
        let gamg = run_with(
            &case,
            &dir.path().join("gamg"),
            "linear = \"petsc\"\npetsc = { options = \"-ksp_type gmres -pc_type gamg -ksp_rtol 1e-13 -ksp_max_it 500\" }",
        );
        assert_same(&faer, &gamg, 1e-8, "stacked blocks, GAMG");
        assert!(
            gamg.summary.krylov_iterations > gamg.summary.krylov_solves,
            "GAMG iterates ({} iterations in {} solves)",
            gamg.summary.krylov_iterations,
            gamg.summary.krylov_solves
        );
    }
}

#[cfg(not(feature = "petsc"))]
#[test]
fn petsc_without_the_feature_says_how_to_get_it() {
    let dir = tempfile::tempdir().unwrap();
    let case = common::write_stacked_blocks_case(
        dir.path(),
        "model = \"linear_elastic\"\nyoungs_modulus = 50.0\npoisson_ratio = 0.3",
        "",
    );
    let text = std::fs::read_to_string(&case)
        .unwrap()
        .replace("[solver]\n", "[solver]\nlinear = \"petsc\"\n");
    common::assert_case_error(dir.path(), &text, &["--features petsc", "petsc-dev"]);
}

#[test]
fn petsc_options_without_the_petsc_solver_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let case = common::write_stacked_blocks_case(
        dir.path(),
        "model = \"linear_elastic\"\nyoungs_modulus = 50.0\npoisson_ratio = 0.3",
        "",
    );
    let text =
        std::fs::read_to_string(&case).unwrap() + "\n[solver.petsc]\noptions = \"-pc_type gamg\"\n";
    common::assert_case_error(dir.path(), &text, &["[solver.petsc]", "linear = \"petsc\""]);
}
