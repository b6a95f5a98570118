//! Distributed runs (`mpirun -np 2 signorini run case.toml`, cargo
//! feature `petsc`): the built binary under `mpirun` gives the serial
//! (faer) run's displacements and contact forces to 1e-8, with the same
//! Newton iterations, on a block pressed on a rigid plane without friction
//! and with Coulomb friction (pressed, then pulled sideways by a
//! quarter of μN), whose METIS partition cuts the contact zone (contact nodes on both
//! processes, read from the log). The displacements are read from the
//! `.pvtu` pieces, each node through the pieces' `global_node` array.

mod common;

#[cfg(feature = "petsc")]
mod with_petsc {
    use super::common;
    use signorini::mesh::{structured::box_mesh, ElementKind};
    use signorini::output::vtu::read_point_field;
    use signorini::run::{run, RunOptions, RunOutcome};
    use std::path::Path;
    use std::process::Command;

    /// A 2 × 1 × 0.5 block (8 × 4 × 2 Hex8, E = 1000, ν = 0.3) on the
    /// plane z = 0, pressed by 10 on its top; `friction`: μ = 0.3 and a
    /// second step pulling its right side by 3 (1.5 in all, a quarter of μN), y held on both
    /// sides; without: x and y held on the symmetry planes x = 0, y = 0.
    fn block_case(dir: &Path, friction: bool, contact: &str, solver: &str) -> std::path::PathBuf {
        let mesh = box_mesh(ElementKind::Hex8, [8, 4, 2], [2.0, 1.0, 0.5]);
        std::fs::write(dir.join("block.msh"), common::msh22(&mesh)).unwrap();
        let (supports, friction_keys, pull) = if friction {
            (
                "[[displacement]]\nsurface = \"ymin\"\ny = 0.0\n\n\
                 [[displacement]]\nsurface = \"ymax\"\ny = 0.0\n",
                "friction_coefficient = 0.3\n",
                "[[pressure]]\nsurface = \"xmax\"\nvalue = -3.0\namplitude = \"pull\"\n\n\
                 [[step]]\nname = \"pull\"\nend_time = 2.0\ninitial_increment = 0.5\n",
            )
        } else {
            (
                "[[displacement]]\nsurface = \"xmin\"\nx = 0.0\n\n\
                 [[displacement]]\nsurface = \"ymin\"\ny = 0.0\n",
                "",
                "",
            )
        };
        let text = format!(
            r#"[mesh]
file = "block.msh"

[[material]]
region = "body"
model = "linear_elastic"
youngs_modulus = 1000.0
poisson_ratio = 0.3

{supports}
[[pressure]]
surface = "zmax"
value = 10.0
amplitude = "press"

[amplitudes]
press = [[0.0, 0.0], [1.0, 1.0], [2.0, 1.0]]
pull = [[0.0, 0.0], [1.0, 0.0], [2.0, 1.0]]

[[obstacle]]
name = "floor"
shape = "plane"
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]

[[contact]]
name = "base"
surface = "zmin"
obstacle = "floor"
{friction_keys}{contact}

[[step]]
name = "press"
end_time = 1.0
initial_increment = 0.5

{pull}
[solver]
residual_tolerance = 1e-10
# Newton's path in serial too (auto would condense the frictional case,
# equal to Newton only to its residual tolerance, in other iterations)
strategy = "monolithic"
{solver}

[output]
name = "block"
"#
        );
        let path = dir.join("case.toml");
        std::fs::write(&path, text).unwrap();
        path
    }

    /// `mpirun -np 2` with the flags Open MPI needs as root and on a
    /// machine with fewer cores.
    fn mpirun() -> Command {
        let version = Command::new("mpirun")
            .arg("--version")
            .output()
            .expect("mpirun (Debian: apt-get install openmpi-bin; petsc-dev brings it)");
        let mut command = Command::new("mpirun");
        if String::from_utf8_lossy(&version.stdout).contains("Open MPI") {
            command.args(["--allow-run-as-root", "--oversubscribe"]);
        }
        command.args(["-np", "2"]);
        command
    }

    /// What the distributed run left: its summary, the log and the whole
    /// displacement assembled from the last data set's pieces.
    struct Distributed {
        summary: serde_json::Value,
        log: String,
        displacement: Vec<f64>,
    }

    fn run_distributed(case: &Path, out: &Path, extra: &[&str]) -> Distributed {
        let result = mpirun()
            .arg(env!("CARGO_BIN_EXE_signorini"))
            .args(["run", case.to_str().unwrap(), "--threads", "1", "--output"])
            .arg(out)
            .args(extra)
            .output()
            .unwrap();
        assert!(
            result.status.success(),
            "mpirun failed: {}\n{}",
            String::from_utf8_lossy(&result.stdout),
            String::from_utf8_lossy(&result.stderr)
        );
        let summary: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap())
                .unwrap();
        let last = summary["increments"].as_array().unwrap().last().unwrap();
        let file = last["file"].as_str().unwrap().to_string();
        assert!(file.ends_with(".pvtu"), "{file}");
        let pvtu = std::fs::read_to_string(out.join(&file)).unwrap();
        let mut displacement = Vec::new();
        for rank in 0..2 {
            let piece = format!("{}_p{rank}.vtu", file.trim_end_matches(".pvtu"));
            assert!(pvtu.contains(&format!("Source=\"{piece}\"")), "{pvtu}");
            let nodes = read_point_field(&out.join(&piece), "global_node").unwrap();
            let u = read_point_field(&out.join(&piece), "displacement").unwrap();
            for (k, &n) in nodes.iter().enumerate() {
                let n = n as usize;
                if displacement.len() < 3 * (n + 1) {
                    displacement.resize(3 * (n + 1), f64::NAN);
                }
                displacement[3 * n..3 * n + 3].copy_from_slice(&u[3 * k..3 * k + 3]);
            }
        }
        Distributed {
            summary,
            log: std::fs::read_to_string(out.join("block.log")).unwrap(),
            displacement,
        }
    }

    /// The distributed run's displacements and every increment's normal
    /// and tangential contact forces equal the serial run's to `tolerance`
    /// of the largest (with a direct solve, `same_iterations`: after the
    /// same Newton iterations); the partition puts contact nodes on both
    /// processes.
    fn assert_same(
        serial: &RunOutcome,
        mpi: &Distributed,
        tolerance: f64,
        same_iterations: bool,
        what: &str,
    ) {
        let dofs = mpi.displacement.len();
        assert_eq!(dofs, serial.displacement.len().min(dofs));
        let scale = serial.displacement[..dofs]
            .iter()
            .fold(0.0f64, |m, v| m.max(v.abs()));
        let worst = serial.displacement[..dofs]
            .iter()
            .zip(&mpi.displacement)
            .map(|(a, b)| (a - b).abs())
            .fold(
                0.0f64,
                |m, d| if d.is_nan() { f64::INFINITY } else { m.max(d) },
            );
        println!("{what}: displacement difference {worst:.2e} of {scale:.3e}");
        assert!(
            worst <= tolerance * scale,
            "{what}: {worst} > {tolerance} × {scale}"
        );
        let increments = mpi.summary["increments"].as_array().unwrap();
        assert_eq!(increments.len(), serial.summary.increments.len(), "{what}");
        for (s, m) in serial.summary.increments.iter().zip(increments) {
            if same_iterations {
                assert_eq!(
                    s.iterations as u64,
                    m["iterations"].as_u64().unwrap(),
                    "{what}"
                );
            }
            let base = &s.contact["base"];
            let norm = base.force.iter().map(|f| f * f).sum::<f64>().sqrt();
            assert!(norm > 0.0, "{what}: no contact at t = {}", s.time);
            for (key, force) in [
                ("force", base.force),
                ("tangential_force", base.tangential_force),
            ] {
                for (i, f) in force.iter().enumerate() {
                    let g = m["contact"]["base"][key][i].as_f64().unwrap();
                    assert!(
                        (f - g).abs() <= tolerance * norm,
                        "{what}: contact {key} {i} at t = {}: {f} against {g}",
                        s.time
                    );
                }
            }
        }
        let contact_nodes: Vec<usize> = mpi
            .log
            .lines()
            .filter_map(|l| {
                let rest = l.split("partition: rank ").nth(1)?;
                let nodes = rest.split(", ").nth(2)?.split(' ').next()?;
                nodes.parse().ok()
            })
            .collect();
        assert_eq!(contact_nodes.len(), 2, "{}", mpi.log);
        assert!(
            contact_nodes.iter().all(|&c| c > 0),
            "{what}: the partition does not cut the contact zone: {contact_nodes:?}"
        );
    }

    fn serial(case: &Path, out: &Path) -> RunOutcome {
        run(
            case,
            &RunOptions {
                output: Some(out.to_path_buf()),
                ..Default::default()
            },
        )
        .unwrap()
    }

    #[test]
    fn two_processes_give_the_serial_answer_without_friction() {
        let dir = tempfile::tempdir().unwrap();
        // Newton's own start in both runs: `auto` takes the contact
        // predictor in a serial run only, in other iterations
        let case = block_case(dir.path(), false, "", "predictor = \"none\"");
        let faer = serial(&case, &dir.path().join("serial"));
        let mumps = run_distributed(&case, &dir.path().join("mpi"), &[]);
        assert_same(
            &faer,
            &mumps,
            1e-8,
            true,
            "frictionless, MUMPS on 2 processes",
        );
        assert!(mumps.log.contains("distributed over 2 processes"));
        // GAMG on the penalty method (no multiplier unknowns: block size 3
        // and the rigid-body near-null space), its options on the command line
        let case = block_case(dir.path(), false, "method = \"penalty\"", "");
        let faer = serial(&case, &dir.path().join("serial-penalty"));
        let gamg = run_distributed(
            &case,
            &dir.path().join("mpi-gamg"),
            &[
                "--",
                "-ksp_type",
                "cg",
                "-pc_type",
                "gamg",
                "-ksp_rtol",
                "1e-13",
            ],
        );
        assert_same(
            &faer,
            &gamg,
            1e-8,
            false,
            "frictionless penalty, GAMG on 2 processes",
        );
        assert!(gamg.log.contains("pc gamg"), "{}", gamg.log);
    }

    #[test]
    fn two_processes_give_the_serial_answer_with_friction() {
        let dir = tempfile::tempdir().unwrap();
        let case = block_case(dir.path(), true, "", "");
        let faer = serial(&case, &dir.path().join("serial"));
        let mpi = run_distributed(&case, &dir.path().join("mpi"), &[]);
        assert_same(
            &faer,
            &mpi,
            1e-8,
            true,
            "Coulomb friction, MUMPS on 2 processes",
        );
        // the pull reached the right side: a tangential contact force
        let last = &faer.summary.increments.last().unwrap().contact["base"];
        assert!(
            (last.tangential_force[0] + 1.5).abs() < 1e-6,
            "{:?}",
            last.tangential_force
        );
    }
}

/// Started by `mpirun` on two processes (Open MPI's environment, faked),
/// a build without PETSc refuses to run the whole case twice and says how
/// to build it.
#[cfg(not(feature = "petsc"))]
#[test]
fn mpirun_without_the_feature_says_how_to_build_it() {
    let dir = tempfile::tempdir().unwrap();
    let case = dir.path().join("case.toml");
    std::fs::write(
        &case,
        "[mesh]\nfile = \"cube.msh\"\n\n[[material]]\nregion = \"body\"\nmodel = \"linear_elastic\"\n\
         youngs_modulus = 1.0\npoisson_ratio = 0.3\n\n[[step]]\nname = \"s\"\nend_time = 1.0\n",
    )
    .unwrap();
    let mesh = signorini::mesh::structured::box_mesh(
        signorini::mesh::ElementKind::Hex8,
        [1, 1, 1],
        [1.0, 1.0, 1.0],
    );
    std::fs::write(dir.path().join("cube.msh"), common::msh22(&mesh)).unwrap();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_signorini"))
        .args(["run", case.to_str().unwrap(), "--quiet"])
        .env("OMPI_COMM_WORLD_SIZE", "2")
        .env("OMPI_COMM_WORLD_RANK", "0")
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let text = String::from_utf8_lossy(&out.stderr);
    assert!(
        text.contains("mpirun on 2 processes") && text.contains("--features petsc"),
        "{text}"
    );
    assert!(!dir.path().join("results/summary.json").exists());
}
