//! The PETSc backend (`[solver] linear = "petsc"`, cargo feature `petsc`)
//! gives the faer solvers' answer: with its default (MUMPS LU) on the
//! frictional press-pull example (a nonsymmetric saddle-point tangent with
//! multipliers), and with MUMPS and GAMG (CG/GMRES on the penalty method,
//! where every unknown is a displacement, block size 3 and the rigid-body
//! near-null space) on the stacked blocks, on press-pull with penalty
//! contact and friction, and on a Hertz-like paraboloid pressed on a plane
//! (where `strategy = "auto"` takes monolithic Newton for PETSc, with the
//! contact predictor's step in faer, and faer the condensed path). GAMG cannot take the zero diagonal blocks of the
//! contact multipliers, so its cases use the penalty method, which has no
//! multiplier unknowns. Without the feature, asking for PETSc is a case
//! error that says how to get it.

mod common;

#[cfg(feature = "petsc")]
mod with_petsc {
    use super::common::{msh22, write_stacked_blocks_case};
    use signorini::mesh::{structured::box_mesh, ElementKind};
    use signorini::run::{run, RunOptions, RunOutcome};
    use std::path::Path;

    /// Run `case` with `[solver]` lines `solver` added.
    fn run_with(case: &Path, dir: &Path, solver: &str) -> RunOutcome {
        try_run_with(case, dir, solver).unwrap_or_else(|e| panic!("[solver] {solver}: {e}"))
    }

    /// [`run_with`], its error returned.
    fn try_run_with(case: &Path, dir: &Path, solver: &str) -> signorini::Result<RunOutcome> {
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
        outcome
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

    /// Every increment's normal and tangential contact force on interface
    /// `name` equal to `tolerance` of the normal force's size.
    fn assert_same_forces(a: &RunOutcome, b: &RunOutcome, name: &str, tolerance: f64, what: &str) {
        assert_eq!(
            a.summary.increments.len(),
            b.summary.increments.len(),
            "{what}"
        );
        for (x, y) in a.summary.increments.iter().zip(&b.summary.increments) {
            let (x, y) = (&x.contact[name], &y.contact[name]);
            let size = x.force.iter().map(|f| f * f).sum::<f64>().sqrt();
            assert!(size > 0.0, "{what}: no contact force");
            for i in 0..3 {
                for (f, g) in [
                    (x.force[i], y.force[i]),
                    (x.tangential_force[i], y.tangential_force[i]),
                ] {
                    assert!((f - g).abs() <= tolerance * size, "{what}: {f} against {g}");
                }
            }
        }
    }

    /// The press-pull example's mesh and case copied into `dir/case`.
    fn press_pull(dir: &Path) -> std::path::PathBuf {
        let example = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/press-pull");
        let work = dir.join("case");
        std::fs::create_dir(&work).unwrap();
        for f in std::fs::read_dir(&example).unwrap() {
            let f = f.unwrap().path();
            if f.extension().is_some_and(|e| e == "msh" || e == "toml") {
                std::fs::copy(&f, work.join(f.file_name().unwrap())).unwrap();
            }
        }
        work.join("case.toml")
    }

    /// [`press_pull`] with each line `l` of its case replaced by `edit(l)`
    /// (its lines, each ending in a newline).
    fn press_pull_with(dir: &Path, edit: impl Fn(&str) -> String) -> std::path::PathBuf {
        let case = press_pull(dir);
        let text = std::fs::read_to_string(&case).unwrap();
        assert!(text.contains("exact_stick = true"));
        let text: String = text.lines().map(edit).collect();
        std::fs::write(&case, text).unwrap();
        case
    }

    /// faer on Newton's path, as PETSc runs: `auto` would take the
    /// condensed path for press-pull, whose answer equals Newton's only to
    /// Newton's residual tolerance, not to the 1e-8 compared here.
    const FAER_MONOLITHIC: &str = "linear = \"auto\"\nstrategy = \"monolithic\"";

    /// MUMPS on the saddle point with exact stick's tangential
    /// multipliers as unknowns (asked for: a run on PETSc keeps them in
    /// the outer loop by default), the faer run likewise.
    #[test]
    fn mumps_gives_the_faer_answer_on_press_pull() {
        let dir = tempfile::tempdir().unwrap();
        let case = press_pull_with(dir.path(), |l| {
            if l.starts_with("exact_stick") {
                format!("friction_multiplier = \"newton\"\n{l}\n")
            } else {
                format!("{l}\n")
            }
        });
        let faer = run_with(&case, &dir.path().join("faer"), FAER_MONOLITHIC);
        let petsc = run_with(&case, &dir.path().join("mumps"), "linear = \"petsc\"");
        assert_same(&faer, &petsc, 1e-8, "press-pull, MUMPS");
        assert_same_forces(&faer, &petsc, "base", 1e-8, "press-pull, MUMPS");
        assert!(petsc.summary.krylov_solves > 0);
    }

    /// A frictional case with default keys (press-pull without its
    /// `exact_stick` line: exact stick is the default) on `linear =
    /// "petsc"`: the tangential multipliers are updated in the outer loop
    /// (the log says so, and `friction_multiplier = "newton"` would be
    /// needed for PETSc to see them as unknowns), and the answer is the
    /// direct solver's (faer LDLᵀ/LU, the multipliers solved by Newton)
    /// exact-stick answer on the same increments to 1e-8 of the contact
    /// element size `h` in the displacements (1e-8 h/|u|max of the
    /// normal force in the contact forces): the outer loop stops at a
    /// stick error of 1e-9 h.
    #[test]
    fn default_keys_with_friction_on_petsc_give_the_direct_exact_stick_answer() {
        let dir = tempfile::tempdir().unwrap();
        // the increments pinned (friction's answer depends on the path,
        // and the two forms grow the increments differently)
        let case = press_pull_with(dir.path(), |l| {
            if l.starts_with("exact_stick") {
                return String::new();
            }
            match l.strip_prefix("initial_increment = ") {
                Some(dt) => format!("{l}\nmax_increment = {dt}\n"),
                None => format!("{l}\n"),
            }
        });
        let faer = run_with(&case, &dir.path().join("faer"), FAER_MONOLITHIC);
        let out = dir.path().join("petsc");
        let petsc = run_with(&case, &out, "linear = \"petsc\"");
        let log = std::fs::read_dir(&out)
            .unwrap()
            .flatten()
            .find(|e| e.path().extension().is_some_and(|x| x == "log"))
            .map(|e| std::fs::read_to_string(e.path()).unwrap())
            .expect("a log");
        assert!(log.contains("updated by an outer loop"), "{log}");
        assert!(
            !log.contains("tangential multipliers solved by Newton"),
            "{log}"
        );
        // to 1e-8 h: the outer loop stops at a stick error of 1e-9 h
        let h: f64 = log
            .split("contact element size ")
            .nth(1)
            .and_then(|rest| rest.split([';', ' ', '\n']).next())
            .and_then(|h| h.parse().ok())
            .unwrap_or_else(|| panic!("no contact element size in the log: {log}"));
        let scale = faer.displacement.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let what = "default friction keys, PETSc";
        assert_same(&faer, &petsc, 1e-8 * h / scale, what);
        assert_same_forces(&faer, &petsc, "base", 1e-8 * h / scale, what);
        // the pull reached 0.8 μN = 4.8 of friction
        let last = &petsc.summary.increments.last().unwrap().contact["base"];
        assert!((last.tangential_force[0] + 4.8).abs() < 1e-6, "{last:?}");
    }

    #[test]
    fn mumps_and_gamg_give_the_faer_answer_on_press_pull_with_penalty_contact() {
        let dir = tempfile::tempdir().unwrap();
        // the penalty method (GAMG takes no multiplier blocks), friction by
        // its tangential penalty (exact stick needs multipliers)
        let case = press_pull_with(dir.path(), |l| {
            if l.starts_with("exact_stick") {
                "method = \"penalty\"\n".to_string()
            } else {
                format!("{l}\n")
            }
        });
        let faer = run_with(&case, &dir.path().join("faer"), FAER_MONOLITHIC);
        let mumps = run_with(&case, &dir.path().join("mumps"), "linear = \"petsc\"");
        assert_same(&faer, &mumps, 1e-8, "press-pull penalty, MUMPS");
        assert_same_forces(&faer, &mumps, "base", 1e-8, "press-pull penalty, MUMPS");
        let gamg = run_with(
            &case,
            &dir.path().join("gamg"),
            "linear = \"petsc\"\npetsc = { options = \"-ksp_type gmres -pc_type gamg -ksp_rtol 1e-12 -ksp_max_it 1000\" }",
        );
        assert_same(&faer, &gamg, 1e-8, "press-pull penalty, GAMG");
        assert_same_forces(&faer, &gamg, "base", 1e-8, "press-pull penalty, GAMG");
        assert!(gamg.summary.krylov_iterations > gamg.summary.krylov_solves);
        // the pull reached 0.8 μN = 4.8 of friction
        let last = &faer.summary.increments.last().unwrap().contact["base"];
        assert!((last.tangential_force[0] + 4.8).abs() < 1e-6, "{last:?}");
    }

    /// A Hertz-like contact in `dir`: a quarter of a 1 × 1 × 1 block
    /// (8 × 8 × 4 Hex8, E = 1000, ν = 0.3) whose bottom is the paraboloid
    /// z = (x² + y²)/(2R), R = 2, touching the plane z = 0 at the origin,
    /// its top pushed down by 0.05 in two increments; frictionless,
    /// node-to-surface (named: these tests check the PETSc backend), with
    /// the `[[contact]]` keys `contact`.
    fn paraboloid_case(dir: &Path, contact: &str) -> std::path::PathBuf {
        let mut mesh = box_mesh(ElementKind::Hex8, [8, 8, 4], [1.0, 1.0, 1.0]);
        for x in &mut mesh.nodes {
            x[2] += (1.0 - x[2]) * (x[0] * x[0] + x[1] * x[1]) / 4.0;
        }
        std::fs::write(dir.join("paraboloid.msh"), msh22(&mesh)).unwrap();
        let path = dir.join(format!("paraboloid-{}.toml", contact.len()));
        std::fs::write(
            &path,
            format!(
                r#"[mesh]
file = "paraboloid.msh"

[[material]]
region = "body"
model = "linear_elastic"
youngs_modulus = 1000.0
poisson_ratio = 0.3

[[displacement]]
surface = "xmin"
x = 0.0

[[displacement]]
surface = "ymin"
y = 0.0

[[displacement]]
surface = "zmax"
z = -0.05

[[obstacle]]
name = "floor"
shape = "plane"
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]

[[contact]]
name = "pole"
surface = "zmin"
obstacle = "floor"
discretisation = "node_to_surface"
{contact}

[[step]]
name = "press"
end_time = 1.0
initial_increment = 0.5
"#
            ),
        )
        .unwrap();
        path
    }

    #[test]
    fn mumps_and_gamg_give_the_faer_answer_on_a_hertz_like_contact() {
        let dir = tempfile::tempdir().unwrap();
        // the Lagrangian default: faer's `auto` takes the condensed path,
        // PETSc's monolithic Newton (the same discrete problem)
        let case = paraboloid_case(dir.path(), "");
        let faer = run_with(&case, &dir.path().join("faer"), "linear = \"auto\"");
        assert_eq!(faer.summary.strategy, "condensed");
        let mumps = run_with(&case, &dir.path().join("mumps"), "linear = \"petsc\"");
        assert_eq!(mumps.summary.strategy, "monolithic");
        // its first corrections the contact predictor's, factorised in faer
        // whatever the linear solver (src/solve/josephy.rs)
        assert_eq!(mumps.summary.predictor, "contact");
        assert!(
            mumps.summary.strategy_reason.contains("linear = \"petsc\""),
            "{}",
            mumps.summary.strategy_reason
        );
        assert_same(&faer, &mumps, 1e-8, "paraboloid, MUMPS");
        assert_same_forces(&faer, &mumps, "pole", 1e-8, "paraboloid, MUMPS");
        assert_petsc_phases(&mumps, "paraboloid, MUMPS");
        let t = &faer.summary.phase_times;
        assert!(t.petsc_setup.is_none() && t.petsc_solve.is_none(), "{t:?}");
        let closed = mumps.summary.increments.last().unwrap().contact["pole"].closed_nodes;
        assert!(closed > 3, "a contact zone of {closed} nodes");
        // GAMG on the penalty method, against faer on it
        let case = paraboloid_case(dir.path(), "method = \"penalty\"");
        let faer = run_with(&case, &dir.path().join("faer-penalty"), "linear = \"auto\"");
        let gamg = run_with(
            &case,
            &dir.path().join("gamg"),
            "linear = \"petsc\"\npetsc = { options = \"-ksp_type cg -pc_type gamg -ksp_rtol 1e-13 -ksp_max_it 1000\" }",
        );
        assert_same(&faer, &gamg, 1e-8, "paraboloid penalty, GAMG");
        assert_same_forces(&faer, &gamg, "pole", 1e-8, "paraboloid penalty, GAMG");
    }

    /// `summary.json`'s PETSc phases of a run on PETSc: its set-up
    /// (`KSPSetUp`, MUMPS's factorisation or GAMG's set-up) and its
    /// `KSPSolve`, both spent, are parts of `factorisation` (all of
    /// PETSc's time, the matrix's values handed over too).
    fn assert_petsc_phases(run: &RunOutcome, what: &str) {
        let t = &run.summary.phase_times;
        let (Some(setup), Some(solve)) = (t.petsc_setup, t.petsc_solve) else {
            panic!("{what}: no PETSc phases in {t:?}");
        };
        println!(
            "{what}: PETSc set-up {setup:.3} s, solve {solve:.3} s of {:.3} s",
            t.factorisation
        );
        assert!(setup > 0.0 && solve > 0.0, "{what}: {t:?}");
        assert!(setup + solve <= t.factorisation, "{what}: {t:?}");
    }

    /// A matrix product's option in the case's options reaches GAMG's
    /// Galerkin products `PᵀAP`, matrices PETSc makes with no options
    /// prefix, which read PETSc's global options database (the C layer
    /// puts the solver's product options there around its set-up and solve
    /// only): an algorithm the product does not have is PETSc's error
    /// naming the option and its choices (before, the option never reached
    /// the product and the run went through), and a run after it in this
    /// process, with the option unset and another product option given,
    /// is unaffected: faer's answer to 1e-8, its phases spent.
    #[test]
    fn product_options_reach_the_galerkin_products_and_stay_the_solvers() {
        let dir = tempfile::tempdir().unwrap();
        let case = paraboloid_case(dir.path(), "method = \"penalty\"");
        let gamg = "linear = \"petsc\"\npetsc = { options = \"-ksp_type cg -pc_type gamg \
                    -ksp_rtol 1e-13 -ksp_max_it 1000";
        let error = try_run_with(
            &case,
            &dir.path().join("unknown"),
            &format!("{gamg} -matptap_via unknown\" }}"),
        )
        .map(|_| ())
        .expect_err("an unknown PtAP algorithm is an error")
        .to_string();
        println!("{error}");
        assert!(
            error.contains("Unknown option unknown for -matptap_via"),
            "{error}"
        );
        let faer = run_with(&case, &dir.path().join("faer"), "linear = \"auto\"");
        let after = run_with(
            &case,
            &dir.path().join("after"),
            &format!("{gamg} -mat_product_clear\" }}"),
        );
        assert_same(&faer, &after, 1e-8, "paraboloid penalty, GAMG after");
        assert_petsc_phases(&after, "paraboloid penalty, GAMG");
    }

    /// Rockafellar's saddle point (a multiplier per contact node) by
    /// fieldsplit's Schur complement, the case's options reaching the
    /// sub-solvers. With LU on the displacement block and the Schur
    /// complement solved to 1e-14 the factorisation is exact, so FGMRES
    /// converges in one or two iterations per solve (the sub-solvers'
    /// defaults, ILU and GMRES to 1e-5, would need more); with GAMG on the
    /// displacement block that block has block size 3 and the rigid-body
    /// near-null space (its KSPView, written by the sub-solver's own
    /// option). Both give faer's answer to 1e-8, no penetration.
    #[test]
    fn fieldsplit_sub_solvers_take_the_case_options_and_the_rigid_body_modes() {
        let dir = tempfile::tempdir().unwrap();
        let case = paraboloid_case(dir.path(), "");
        let faer = run_with(&case, &dir.path().join("faer"), FAER_MONOLITHIC);
        let schur = "-ksp_type fgmres -ksp_rtol 1e-12 -ksp_max_it 200 -pc_type fieldsplit \
                     -pc_fieldsplit_type schur -pc_fieldsplit_schur_fact_type full \
                     -pc_fieldsplit_schur_precondition selfp";
        let exact = run_with(
            &case,
            &dir.path().join("exact"),
            &format!(
                "linear = \"petsc\"\npetsc = {{ options = \"{schur} -fieldsplit_0_ksp_type preonly \
                 -fieldsplit_0_pc_type lu -fieldsplit_1_ksp_type gmres -fieldsplit_1_ksp_rtol 1e-14 \
                 -fieldsplit_1_pc_type lu\" }}"
            ),
        );
        let (solves, iterations) = (exact.summary.krylov_solves, exact.summary.krylov_iterations);
        assert!(
            solves > 0 && iterations <= 2 * solves,
            "exact sub-solvers: {iterations} FGMRES iterations in {solves} solves"
        );
        let view = dir.path().join("split0.txt");
        let gamg = run_with(
            &case,
            &dir.path().join("gamg"),
            &format!(
                "linear = \"petsc\"\npetsc = {{ options = \"{schur} -fieldsplit_0_ksp_type preonly \
                 -fieldsplit_0_pc_type gamg -fieldsplit_1_ksp_type gmres -fieldsplit_1_pc_type jacobi \
                 -fieldsplit_0_ksp_view ascii:{}\" }}",
                view.display()
            ),
        );
        let text = std::fs::read_to_string(&view).expect("the displacement block's KSPView");
        assert!(text.contains("type: gamg"), "{text}");
        assert!(text.contains("bs=3"), "block size 3: {text}");
        assert!(text.contains("near null space"), "rigid-body modes: {text}");
        for (run, what) in [(&exact, "fieldsplit, LU"), (&gamg, "fieldsplit, GAMG")] {
            assert_same(&faer, run, 1e-8, what);
            assert_same_forces(&faer, run, "pole", 1e-8, what);
            let last = &run.summary.increments.last().unwrap().contact["pole"];
            assert!(
                last.closed_nodes > 3,
                "{what}: {} closed",
                last.closed_nodes
            );
            // h = 1/8, the mesh's element size: exact below 1e-8 h
            assert!(
                last.largest_penetration < 1e-8 / 8.0,
                "{what}: {}",
                last.largest_penetration
            );
        }
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

/// PETSc options after `--` on the command line: without the feature an
/// error that says how to get PETSc (exit code 2, usage); an argument that
/// is not an option is refused in every build.
#[test]
fn petsc_options_on_the_command_line_are_checked() {
    let dir = tempfile::tempdir().unwrap();
    let case = common::write_stacked_blocks_case(
        dir.path(),
        "model = \"linear_elastic\"\nyoungs_modulus = 50.0\npoisson_ratio = 0.3",
        "",
    );
    let run = |extra: &[&str]| {
        std::process::Command::new(env!("CARGO_BIN_EXE_signorini"))
            .args(["run", case.to_str().unwrap(), "--quiet", "--"])
            .args(extra)
            .output()
            .unwrap()
    };
    let out = run(&["ksp_type", "cg"]);
    assert_eq!(out.status.code(), Some(2));
    let text = String::from_utf8_lossy(&out.stderr);
    assert!(
        text.contains("'ksp_type'") && text.contains("start with '-'"),
        "{text}"
    );
    if cfg!(not(feature = "petsc")) {
        let out = run(&["-ksp_type", "cg"]);
        assert_eq!(out.status.code(), Some(2));
        let text = String::from_utf8_lossy(&out.stderr);
        assert!(text.contains("--features petsc"), "{text}");
    }
}
