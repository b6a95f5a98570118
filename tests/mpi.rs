//! Distributed runs (`mpirun -np 2 signorini run case.toml`, cargo
//! feature `petsc`): the built binary under `mpirun` gives the serial
//! (faer) run's displacements and contact forces to 1e-8, with the same
//! Newton iterations, on a block pressed on a rigid plane without friction,
//! and to 1e-8 of the element size with Coulomb friction (pressed, then
//! pulled sideways by a quarter of μN; exact stick's multipliers in the
//! outer loop on PETSc), whose partition cuts the contact zone (contact
//! nodes on both processes, read from the log); each process holds only
//! its share of the tangent (the log's `rows:` lines). The displacements
//! are read from the `.pvtu` pieces, each node through the pieces'
//! `global_node` array.

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
    /// Node-to-surface contact unless `contact` names the discretisation
    /// (named: these tests check the distributed backend against the
    /// serial run, with the counts of node-to-surface's rows).
    fn block_case(dir: &Path, friction: bool, contact: &str, solver: &str) -> std::path::PathBuf {
        let mesh = box_mesh(ElementKind::Hex8, [8, 4, 2], [2.0, 1.0, 0.5]);
        std::fs::write(dir.join("block.msh"), common::msh22(&mesh)).unwrap();
        let (supports, friction_keys, pull) = if friction {
            (
                "[[displacement]]\nsurface = \"ymin\"\ny = 0.0\n\n\
                 [[displacement]]\nsurface = \"ymax\"\ny = 0.0\n",
                // default keys: exact stick, whose tangential
                // multipliers a run on PETSc updates in the outer loop
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
        // node-to-surface unless `contact` names the discretisation
        let discretisation = match contact.contains("discretisation") {
            true => "",
            false => "discretisation = \"node_to_surface\"\n",
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
{discretisation}{friction_keys}{contact}

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
        let mut command = mpirun_alone();
        command.args(["-np", "2"]);
        command
    }

    /// `mpirun` with the flags Open MPI needs as root and on a machine
    /// with fewer cores, without a process count.
    fn mpirun_alone() -> Command {
        let version = Command::new("mpirun")
            .arg("--version")
            .output()
            .expect("mpirun (Debian: apt-get install openmpi-bin; petsc-dev brings it)");
        let mut command = Command::new("mpirun");
        if String::from_utf8_lossy(&version.stdout).contains("Open MPI") {
            command.args(["--allow-run-as-root", "--oversubscribe"]);
        }
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

    /// How a bounded `mpirun` ended: its exit status, standard error,
    /// wall time and the run's `summary.json`.
    struct Ended {
        status: std::process::ExitStatus,
        stderr: String,
        summary: serde_json::Value,
    }

    /// Run `command` (an `mpirun`), its output into files in `out`, and
    /// fail the test if it has not ended after `limit` (killing it: a
    /// hang must fail, not block the suite); `during` is called every
    /// 10 ms with the child while it runs.
    fn bounded(
        mut command: Command,
        out: &Path,
        limit: std::time::Duration,
        mut during: impl FnMut(&std::process::Child),
    ) -> Ended {
        std::fs::create_dir_all(out).unwrap();
        let stderr_path = out.join("stderr.txt");
        let mut child = command
            .stdout(std::fs::File::create(out.join("stdout.txt")).unwrap())
            .stderr(std::fs::File::create(&stderr_path).unwrap())
            .spawn()
            .unwrap();
        let start = std::time::Instant::now();
        let status = loop {
            if let Some(status) = child.try_wait().unwrap() {
                break status;
            }
            if start.elapsed() > limit {
                let _ = child.kill();
                let _ = child.wait();
                panic!(
                    "mpirun still running after {limit:?}: {}",
                    std::fs::read_to_string(&stderr_path).unwrap_or_default()
                );
            }
            during(&child);
            std::thread::sleep(std::time::Duration::from_millis(10));
        };
        let summary = std::fs::read_to_string(out.join("summary.json"))
            .ok()
            .and_then(|t| serde_json::from_str(&t).ok())
            .unwrap_or(serde_json::Value::Null);
        Ended {
            status,
            stderr: std::fs::read_to_string(&stderr_path).unwrap(),
            summary,
        }
    }

    /// `signorini run case --output out` with `args`, after `prefix` (an
    /// `env VAR=value` for one process) in an `mpirun` app context.
    fn app(command: &mut Command, prefix: &[&str], case: &Path, out: &Path, args: &[&str]) {
        command
            .args(prefix)
            .arg(env!("CARGO_BIN_EXE_signorini"))
            .args(["run", case.to_str().unwrap(), "--quiet", "--threads", "1"])
            .arg("--output")
            .arg(out)
            .args(args);
    }

    /// `mpirun` with rank 0 and rank 1 started apart (an MPMD launch:
    /// `prefix0` and `prefix1` before each), both on `case`.
    fn mpirun_apart(case: &Path, out: &Path, prefix0: &[&str], prefix1: &[&str]) -> Command {
        let mut command = mpirun_alone();
        command.args(["-np", "1"]);
        app(&mut command, prefix0, case, out, &[]);
        command.args([":", "-np", "1"]);
        app(&mut command, prefix1, case, out, &[]);
        command
    }

    /// A failed run as the user sees it: a non-zero exit, `message` on
    /// the standard error and in `summary.json`, which says `failed`.
    fn assert_failed(ended: &Ended, message: &str, what: &str) {
        println!("{what}: {:?}\n{}", ended.status, ended.stderr);
        assert!(!ended.status.success(), "{what}: {:?}", ended.status);
        assert!(ended.stderr.contains(message), "{what}: {}", ended.stderr);
        assert_eq!(
            ended.summary["status"], "failed",
            "{what}: {}",
            ended.summary
        );
        let error = ended.summary["error"].as_str().unwrap_or_default();
        assert!(error.contains(message), "{what}: {error}");
    }

    /// A process that fails alone, while the other waits in a collective
    /// for it, ends the run within seconds (it waits `FAILED_WAIT`, 5 s,
    /// for the others to agree, then aborts): here rank 1's PETSc options
    /// name a KSP that does not exist, found when its solver is made, and
    /// rank 0 is already in the first assembly's sum.
    #[test]
    fn a_process_that_fails_alone_ends_the_run() {
        let dir = tempfile::tempdir().unwrap();
        let case = block_case(dir.path(), false, "", "");
        let out = dir.path().join("out");
        let command = mpirun_apart(
            &case,
            &out,
            &[],
            &["env", "PETSC_OPTIONS=-ksp_type no_such_krylov_method"],
        );
        let start = std::time::Instant::now();
        let ended = bounded(command, &out, std::time::Duration::from_secs(60), |_| {});
        assert_failed(&ended, "Unknown type", "one process's bad input");
        assert!(ended.stderr.contains("process 1 of 2"), "{}", ended.stderr);
        println!("ended after {:?}", start.elapsed());
    }

    /// A linear solve that fails on one process (rank 1 allows GMRES one
    /// iteration, rank 0 iterates on) ends the run: rank 1 leaves the
    /// solve's collectives, rank 0 waits in them, rank 1 ends the run.
    #[test]
    fn a_solve_that_fails_on_one_process_ends_the_run() {
        let dir = tempfile::tempdir().unwrap();
        let case = block_case(dir.path(), false, "method = \"penalty\"", "");
        let out = dir.path().join("out");
        let both = "-ksp_type gmres -pc_type jacobi -ksp_rtol 1e-12";
        let one = format!("PETSC_OPTIONS={both} -ksp_max_it 1");
        let all = format!("PETSC_OPTIONS={both}");
        let command = mpirun_apart(&case, &out, &["env", &all], &["env", &one]);
        let ended = bounded(command, &out, std::time::Duration::from_secs(60), |_| {});
        assert_failed(&ended, "did not converge", "one process's failed solve");
        assert!(ended.stderr.contains("process 1 of 2"), "{}", ended.stderr);
    }

    /// A solve that fails on every process (GMRES without a
    /// preconditioner, one iteration) fails every increment alike: the
    /// processes agree, cut the increment together, and end together with
    /// Newton's error, rank 0 writing it into `summary.json`: exit code 1
    /// and no abort.
    #[test]
    fn a_solve_that_fails_everywhere_ends_the_run_cleanly() {
        let dir = tempfile::tempdir().unwrap();
        let case = block_case(dir.path(), false, "", "");
        let text = std::fs::read_to_string(&case).unwrap().replace(
            "initial_increment = 0.5\n",
            "initial_increment = 0.5\nmin_increment = 0.2\n",
        );
        std::fs::write(&case, text).unwrap();
        let out = dir.path().join("out");
        let mut command = mpirun();
        app(
            &mut command,
            &[],
            &case,
            &out,
            &[
                "--",
                "-ksp_type",
                "gmres",
                "-pc_type",
                "none",
                "-ksp_max_it",
                "1",
            ],
        );
        let ended = bounded(command, &out, std::time::Duration::from_secs(120), |_| {});
        assert_failed(&ended, "did not converge", "a failed solve everywhere");
        assert_eq!(ended.status.code(), Some(1), "{}", ended.stderr);
        assert!(!ended.stderr.contains("MPI_ABORT"), "{}", ended.stderr);
    }

    /// A PETSc option that the solver's set-up rejects: a factorisation
    /// package PETSc lacks, found at the first `KSPSetUp` (PETSc error 92,
    /// `PETSC_ERR_MISSING_FACTOR`), not when the solver is made.
    const BAD_OPTION: [&str; 2] = ["-pc_factor_mat_solver_type", "no_such_package"];

    /// A run that PETSc's set-up failed, as the user sees it
    /// ([`assert_failed`]): exit code 1, the message names the option and
    /// where to change it, and the increment was not cut (no "cutting" in
    /// the log `log`).
    fn assert_set_up_failed(ended: &Ended, log: &Path, what: &str) {
        assert_failed(ended, &BAD_OPTION.join(" "), what);
        assert_eq!(ended.status.code(), Some(1), "{what}: {}", ended.stderr);
        assert!(
            ended.stderr.contains("check the PETSc options after `--`"),
            "{what}: {}",
            ended.stderr
        );
        let log = std::fs::read_to_string(log).unwrap();
        assert!(log.contains("PETSc error 92"), "{what}: {log}");
        assert!(!log.contains("cutting"), "{what}: {log}");
    }

    /// A PETSc option that the solver's set-up rejects ends a serial run
    /// at its first solve, not after `max_cuts` cuts of the increment:
    /// no increment mends it (`IncrementFailure::LinearSolverSetUp`).
    /// Without a predictor, so that Newton's first solve is PETSc's (the
    /// contact predictor solves this block's increments with faer).
    #[test]
    fn a_rejected_petsc_option_ends_a_serial_run_without_cuts() {
        let dir = tempfile::tempdir().unwrap();
        let solver = "linear = \"petsc\"\npredictor = \"none\"";
        let case = block_case(dir.path(), false, "", solver);
        let out = dir.path().join("out");
        let mut command = Command::new(env!("CARGO_BIN_EXE_signorini"));
        command
            .args(["run", case.to_str().unwrap(), "--quiet", "--output"])
            .arg(&out)
            .arg("--")
            .args(BAD_OPTION);
        let ended = bounded(command, &out, std::time::Duration::from_secs(60), |_| {});
        assert_set_up_failed(&ended, &out.join("block.log"), "serial");
    }

    /// Under `mpirun -np 2` the same option ends both processes at their
    /// first solve, each with the message, by their own exit (no
    /// `MPI_Abort`), within 10 s (issue 29: a fault ends every process
    /// within seconds).
    #[test]
    fn a_rejected_petsc_option_ends_every_process_without_cuts() {
        let dir = tempfile::tempdir().unwrap();
        let case = block_case(dir.path(), false, "", "");
        let out = dir.path().join("out");
        let mut command = mpirun();
        app(&mut command, &[], &case, &out, &["--"]);
        command.args(BAD_OPTION);
        let start = std::time::Instant::now();
        let ended = bounded(command, &out, std::time::Duration::from_secs(60), |_| {});
        let after = start.elapsed();
        println!("ended after {after:?}");
        assert_set_up_failed(&ended, &out.join("block.log"), "mpirun -np 2");
        assert_eq!(
            ended.stderr.matches("check the PETSc options").count(),
            2,
            "{}",
            ended.stderr
        );
        assert!(!ended.stderr.contains("MPI_ABORT"), "{}", ended.stderr);
        assert!(after < std::time::Duration::from_secs(10), "{after:?}");
    }

    /// When only rank 1's set-up fails (only it sees the option, in its
    /// own `PETSC_OPTIONS`), the run ends within seconds and no process
    /// cuts the increment (issue 29 item 6). Rank 0 is then inside MUMPS'
    /// factorisation, a collective rank 1 never joins, so rank 1 ends the
    /// run after `FAILED_WAIT` (`MPI_Abort`); when both reach the
    /// agreement, its kind of failure travels with its message and ends
    /// rank 0's run too (the unit tests of `fault` and of the distributed
    /// solver's `settled`). Both exit non-zero, `summary.json` says failed
    /// with rank 1's message, and the log (rank 0's) has no cut.
    #[test]
    fn a_set_up_that_fails_on_one_process_ends_the_run_without_cuts() {
        let dir = tempfile::tempdir().unwrap();
        let case = block_case(dir.path(), false, "", "");
        let out = dir.path().join("out");
        let one = format!("PETSC_OPTIONS={}", BAD_OPTION.join(" "));
        let command = mpirun_apart(&case, &out, &[], &["env", &one]);
        let start = std::time::Instant::now();
        let ended = bounded(command, &out, std::time::Duration::from_secs(60), |_| {});
        println!("ended after {:?}", start.elapsed());
        assert_failed(&ended, &BAD_OPTION.join(" "), "rank 1's set-up");
        assert!(
            ended.stderr.contains("process 1 of 2") && ended.stderr.contains("PETSc error 92"),
            "{}",
            ended.stderr
        );
        let log = std::fs::read_to_string(out.join("block.log")).unwrap();
        assert!(!log.contains("cutting"), "{log}");
    }

    /// The pid of rank `rank` among the processes started with `mark` in
    /// their environment (read from /proc).
    fn rank_pid(mark: &str, rank: usize) -> Option<u32> {
        let want = format!("OMPI_COMM_WORLD_RANK={rank}");
        std::fs::read_dir("/proc")
            .ok()?
            .flatten()
            .find_map(|entry| {
                let pid: u32 = entry.file_name().to_str()?.parse().ok()?;
                let environ = std::fs::read(entry.path().join("environ")).ok()?;
                let vars: Vec<&[u8]> = environ.split(|&b| b == 0).collect();
                let has = |v: &str| vars.contains(&v.as_bytes());
                (has(mark) && has(&want)).then_some(pid)
            })
    }

    /// A distributed run of `case` into `out` whose rank 1 is killed
    /// (SIGKILL) once `increments` increments are in `summary.json`: how
    /// it ended and when the kill was sent.
    fn killed_after(case: &Path, out: &Path, increments: usize) -> (Ended, std::time::Instant) {
        let mark = format!("SIGNORINI_TEST_MARK={}", out.display());
        let mut command = mpirun();
        command.env("SIGNORINI_TEST_MARK", out);
        app(&mut command, &[], case, out, &[]);
        let mut killed: Option<std::time::Instant> = None;
        let ended = bounded(command, out, std::time::Duration::from_secs(120), |_| {
            if killed.is_some() {
                return;
            }
            let done = std::fs::read_to_string(out.join("summary.json"))
                .ok()
                .and_then(|t| serde_json::from_str::<serde_json::Value>(&t).ok())
                .and_then(|s| s["increments"].as_array().map(Vec::len))
                .unwrap_or(0);
            if done >= increments {
                if let Some(pid) = rank_pid(&mark, 1) {
                    Command::new("kill")
                        .args(["-KILL", &pid.to_string()])
                        .status()
                        .unwrap();
                    killed = Some(std::time::Instant::now());
                }
            }
        });
        (ended, killed.expect("rank 1 was not found and killed"))
    }

    /// A case of `increments` equal increments in its first step.
    fn fine_steps(case: &Path, increments: usize) {
        let dt = 1.0 / increments as f64;
        let text = std::fs::read_to_string(case).unwrap().replacen(
            "initial_increment = 0.5\n",
            &format!("initial_increment = {dt}\nmax_increment = {dt}\n"),
            1,
        );
        std::fs::write(case, text).unwrap();
    }

    /// Restart under mpirun: a distributed run killed in the middle of its
    /// first step (rank 1 killed, rank 0 stopped by mpirun) and resumed
    /// with `--restart` on two processes ends where an uninterrupted
    /// distributed run does, with the same increments and Newton
    /// iterations, contact forces and displacements to 1e-10 of the
    /// largest. Not bit for bit: every process holds the whole state and
    /// rank 0 checkpoints it exactly, but two uninterrupted 2-process runs
    /// already differ in the last bits (~1e-16 relative: MUMPS' dynamic
    /// scheduling between the processes orders its sums by their load).
    #[test]
    fn a_killed_distributed_run_restarts_and_ends_as_an_uninterrupted_one() {
        let dir = tempfile::tempdir().unwrap();
        // the model of a distributed run (exact stick's multipliers in the
        // outer loop), so that the serial resumption solves the same one
        let case = block_case(dir.path(), true, "friction_multiplier = \"outer\"", "");
        fine_steps(&case, 20);
        let full = run_distributed(&case, &dir.path().join("full"), &[]);
        let cut = dir.path().join("cut");
        let (ended, _) = killed_after(&case, &cut, 4);
        assert_failed(&ended, "signal", "killed before the restart");
        let kept = ended.summary["increments"].as_array().unwrap().len();
        let total = full.summary["increments"].as_array().unwrap().len();
        assert!(kept >= 4 && kept < total, "{kept} of {total}");
        // a copy to resume on one process
        let alone = dir.path().join("alone");
        std::fs::create_dir(&alone).unwrap();
        for entry in std::fs::read_dir(&cut).unwrap().flatten() {
            std::fs::copy(entry.path(), alone.join(entry.file_name())).unwrap();
        }
        let resumed = run_distributed(&case, &cut, &["--restart", cut.to_str().unwrap()]);
        assert_eq!(resumed.summary["status"], "completed");
        assert!(
            resumed
                .log
                .contains("restart: resuming from the checkpoint"),
            "{}",
            resumed.log
        );
        // the same increments (times, files, Newton iterations) and, to
        // 1e-10 of the largest, the same contact forces and displacements
        let increments = |s: &serde_json::Value| -> Vec<(String, String, u64)> {
            s["increments"]
                .as_array()
                .unwrap()
                .iter()
                .map(|i| {
                    (
                        i["time"].to_string(),
                        i["file"].to_string(),
                        i["iterations"].as_u64().unwrap(),
                    )
                })
                .collect()
        };
        assert_eq!(increments(&full.summary), increments(&resumed.summary));
        let forces = |s: &serde_json::Value| -> Vec<f64> {
            let list = s["increments"].as_array().unwrap().iter();
            list.flat_map(|i| {
                let base = &i["contact"]["base"];
                let (f, t) = (&base["force"], &base["tangential_force"]);
                (0..3).flat_map(move |k| [f[k].as_f64().unwrap(), t[k].as_f64().unwrap()])
            })
            .collect()
        };
        let close = |a: &[f64], b: &[f64], what: &str| {
            assert_eq!(a.len(), b.len(), "{what}");
            let scale = a.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let worst = a
                .iter()
                .zip(b)
                .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
            println!("{what}: largest difference {worst:.1e} of {scale:.3e}");
            assert!(worst <= 1e-10 * scale, "{what}: {worst:e} of {scale:e}");
        };
        close(
            &forces(&full.summary),
            &forces(&resumed.summary),
            "contact forces",
        );
        close(&full.displacement, &resumed.displacement, "displacements");
        // another process count: the checkpoint holds the whole state, so
        // one process (faer's solve) resumes it too, to the 1e-8 of the
        // serial equality above
        let one = run(
            &case,
            &RunOptions {
                output: Some(alone.clone()),
                restart: Some(alone.clone()),
                ..Default::default()
            },
        )
        .unwrap();
        assert_eq!(one.summary.status, "completed");
        assert_same(&one, &full, 1e-8, true, "resumed on one process");
    }

    /// A process killed (SIGKILL) in the middle of a run: mpirun ends the
    /// other within 10 s with a non-zero code and says which process
    /// died; rank 0 marks `summary.json` failed.
    #[test]
    fn a_killed_process_ends_the_run() {
        let dir = tempfile::tempdir().unwrap();
        let case = block_case(dir.path(), false, "", "");
        fine_steps(&case, 100);
        let out = dir.path().join("out");
        let (ended, killed) = killed_after(&case, &out, 3);
        let after = killed.elapsed();
        println!("ended {after:?} after the kill");
        assert!(after < std::time::Duration::from_secs(10), "{after:?}");
        assert!(ended.summary["increments"].as_array().unwrap().len() < 100);
        assert_failed(&ended, "signal", "a killed process");
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

    /// The log of a 2-process run on the 64-element block says the
    /// elements were cut in parallel by PETSc's partitioner (PT-Scotch on
    /// Debian's PETSc, ParMETIS where built with it), and the partition
    /// lines own every element once, balanced within 5 % (+1 element) of
    /// the mean (`partitioning::IMBALANCE`).
    fn assert_parallel_partition(log: &str) {
        let method = log
            .lines()
            .find_map(|l| l.split("elements partitioned by ").nth(1))
            .unwrap_or_else(|| panic!("no partition method in the log: {log}"));
        println!("partitioned by {method}");
        assert!(
            method.ends_with("through PETSc's MatPartitioning, in parallel"),
            "{method}"
        );
        let elements: Vec<usize> = log
            .lines()
            .filter_map(|l| {
                let rest = l.split("partition: rank ").nth(1)?;
                rest.split(": ").nth(1)?.split(' ').next()?.parse().ok()
            })
            .collect();
        assert_eq!(elements.len(), 2, "{log}");
        assert_eq!(elements.iter().sum::<usize>(), 64, "{elements:?}");
        assert!(
            elements.iter().all(|&e| e as f64 <= 1.05 * 32.0 + 1.0),
            "{elements:?}"
        );
    }

    /// The log's `rows:` lines (issue 29 item 1): per rank, the tangent
    /// entries it holds and the residual values, and the entries and
    /// nodes of its own rows and of its ghost rows.
    fn rows_held(log: &str) -> Vec<[usize; 6]> {
        log.lines()
            .filter(|l| l.starts_with("rows: rank "))
            .map(|l| {
                let numbers: Vec<usize> = l
                    .split(|c: char| !c.is_ascii_digit())
                    .filter_map(|w| w.parse().ok())
                    .collect();
                // rank, held entries, residual values, own entries, own
                // nodes, ghost entries, ghost nodes
                assert_eq!(numbers.len(), 7, "{l}");
                std::array::from_fn(|k| numbers[k + 1])
            })
            .collect()
    }

    /// Each process of a 2-process run on the 8 × 4 × 2 block (135 nodes,
    /// penalty contact on a rigid plane: no multipliers, no couplings
    /// beyond the elements) holds only its share of the tangent: at most
    /// its own rows and its ghost rows (no entry of the other nodes, not
    /// even their diagonal blocks, 9 entries for each other node, which
    /// would fail it), and at most 0.55 of
    /// the whole pattern (the own rows of
    /// both processes, which make the whole once: a count that fails if a
    /// row is lost or counted twice; measured 11 187 of 20 475, 0.546);
    /// its own and ghost rows, whole as the partition counts them, at
    /// most 0.6 (measured 0.560). The residual is still whole (every
    /// dof).
    fn assert_rows_measured(log: &str) {
        let rows = rows_held(log);
        assert_eq!(rows.len(), 2, "{log}");
        let whole = rows[0][2] + rows[1][2];
        for (rank, r) in rows.iter().enumerate() {
            let [held, dofs, own, own_nodes, ghost, ghost_nodes] = *r;
            let others = 135 - own_nodes - ghost_nodes;
            println!(
                "rank {rank}: holds {held} entries ({:.3} of {whole}) and {dofs} residual \
                 values; own rows {own} entries ({own_nodes} nodes), ghost rows {ghost} \
                 ({ghost_nodes} nodes), {others} other nodes; own + ghost {:.3}",
                held as f64 / whole as f64,
                (own + ghost) as f64 / whole as f64
            );
            assert_eq!(dofs, 3 * 135);
            assert!(others > 0 && held <= own + ghost, "{r:?}");
            assert!(held as f64 <= 0.55 * whole as f64, "{r:?} of {whole}");
            assert!(
                (own + ghost) as f64 <= 0.6 * whole as f64,
                "{r:?} of {whole}"
            );
        }
        // the nodes the partition cuts through are one side's ghosts
        assert!(rows[0][5] + rows[1][5] > 0, "{rows:?}");
        assert_eq!(rows[0][3] + rows[1][3], 135);
        // the mesh: its own elements and the ghost layer of its rows (the
        // other part's elements at one of its nodes; none for a part that
        // owns none of the nodes between the parts), not the whole 64
        let (held, owned) = (elements_held(log), elements_owned(log));
        assert_eq!(held.len(), 2, "{log}");
        for (&(held, whole), own) in held.iter().zip(owned) {
            println!("holds the connectivity of {held} of {whole} elements, owns {own}");
            assert!(own <= held && held < whole, "{held} of {whole}, {own} own");
        }
        assert!(held[0].0 + held[1].0 > 64, "no ghost layer: {held:?}");
        // summary.json's and the log's matrix entries: rank 0's
        assert!(
            log.contains(&format!("{} matrix entries", rows[0][0])),
            "{log}"
        );
    }

    /// The serial (faer) run of `case` and its 2-process MUMPS run, in
    /// `dir`: equal to 1e-8 after the same Newton iterations
    /// ([`assert_same`]); the distributed run's outcome.
    fn assert_mumps_as_serial(case: &Path, dir: &Path, what: &str) -> Distributed {
        let faer = serial(case, &dir.join("serial"));
        let mumps = run_distributed(case, &dir.join("mpi"), &[]);
        assert_same(&faer, &mumps, 1e-8, true, what);
        mumps
    }

    #[test]
    fn two_processes_give_the_serial_answer_without_friction() {
        let dir = tempfile::tempdir().unwrap();
        // Newton's own start in both runs: `auto` takes the contact
        // predictor in a serial run only, in other iterations
        let case = block_case(dir.path(), false, "", "predictor = \"none\"");
        let mumps = assert_mumps_as_serial(&case, dir.path(), "frictionless, MUMPS on 2 processes");
        assert!(mumps.log.contains("distributed over 2 processes"));
        assert_parallel_partition(&mumps.log);
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
        assert_rows_measured(&gamg.log);
    }

    /// A follower pressure on the top (its load stiffness, nonsymmetric,
    /// couples each face's nodes) and the multipliers of the default
    /// Rockafellar contact: each process adds the load's and the
    /// contact's tangent in the rows it owns only (the last process the
    /// multipliers' rows), and the 2-process MUMPS run equals the serial
    /// faer one to 1e-8, increment for increment.
    #[test]
    fn two_processes_give_the_serial_answer_with_a_follower_pressure() {
        let dir = tempfile::tempdir().unwrap();
        let case = block_case(dir.path(), false, "", "predictor = \"none\"");
        let text = std::fs::read_to_string(&case).unwrap();
        let text = text.replacen("value = 10.0\n", "value = 10.0\nfollower = true\n", 1);
        assert!(text.contains("follower = true"), "{text}");
        std::fs::write(&case, text).unwrap();
        let what = "follower pressure, MUMPS on 2 processes";
        assert_mumps_as_serial(&case, dir.path(), what);
    }

    /// Dual mortar contact (its rows: the weighted gaps of the secondary
    /// nodes, `D` and `M` integrated over the segments) under PETSc: the
    /// frictionless block on 2 processes with MUMPS equals the serial faer
    /// run to 1e-8, increment for increment.
    #[test]
    fn two_processes_give_the_serial_answer_with_dual_mortar() {
        let dir = tempfile::tempdir().unwrap();
        let case = block_case(
            dir.path(),
            false,
            "discretisation = \"mortar\"",
            "predictor = \"none\"",
        );
        let mumps = assert_mumps_as_serial(&case, dir.path(), "dual mortar, MUMPS on 2 processes");
        assert!(mumps.log.contains("dual mortar"), "{}", mumps.log);
    }

    /// The log's `mesh:` lines (issue 29 item 3): the elements whose
    /// connectivity each rank holds, and the mesh's.
    fn elements_held(log: &str) -> Vec<(usize, usize)> {
        log.lines()
            .filter_map(|l| {
                let rest = l.strip_prefix("mesh: rank ")?;
                let numbers: Vec<usize> = rest
                    .split(|c: char| !c.is_ascii_digit())
                    .filter_map(|w| w.parse().ok())
                    .collect();
                Some((numbers[1], numbers[2]))
            })
            .collect()
    }

    /// The elements each rank owns, from the log's `partition:` lines.
    fn elements_owned(log: &str) -> Vec<usize> {
        log.lines()
            .filter_map(|l| {
                let rest = l.split("partition: rank ").nth(1)?;
                rest.split(": ").nth(1)?.split(' ').next()?.parse().ok()
            })
            .collect()
    }

    /// Point array `name` of the last data set's pieces of a distributed
    /// run in `out`, each node through `global_node` (NaN where no piece
    /// has the node).
    fn merged_point_field(out: &Path, summary: &serde_json::Value, name: &str) -> Vec<f64> {
        let last = summary["increments"].as_array().unwrap().last().unwrap();
        let file = last["file"].as_str().unwrap();
        let mut whole = Vec::new();
        for rank in 0..2 {
            let piece = out.join(format!("{}_p{rank}.vtu", file.trim_end_matches(".pvtu")));
            let nodes = read_point_field(&piece, "global_node").unwrap();
            let values = read_point_field(&piece, name).unwrap();
            let c = values.len() / nodes.len();
            for (k, &n) in nodes.iter().enumerate() {
                let n = n as usize;
                if whole.len() < c * (n + 1) {
                    whole.resize(c * (n + 1), f64::NAN);
                }
                whole[c * n..c * (n + 1)].copy_from_slice(&values[c * k..c * (k + 1)]);
            }
        }
        whole
    }

    /// Issue 29 item 3, first part: each process of a 2-process run
    /// holds the connectivity of its own elements, the ghost layer of its
    /// rows and the patches its recovered stresses read, not the whole
    /// mesh, and its output is the serial run's: on a 16 × 4 × 2 block
    /// (128 Hex8) pressed on a plane, MUMPS on 2 processes gives the
    /// serial displacements and contact forces to 1e-8 (as above) and
    /// the recovered von Mises stress and Cauchy stress of every node
    /// (Zienkiewicz–Zhu patches that cross the partition, grown by up to
    /// three rings at the boundary) to 1e-8 of their largest — a process
    /// that let go of an element a patch of its piece reads would write a
    /// value off by that element's share (its stress taken as zero).
    /// Without recovered fields (the GAMG run of the frictionless test)
    /// each holds its own elements and the ghost layer only.
    #[test]
    fn each_process_holds_the_elements_it_reads_and_writes_the_serial_output() {
        let dir = tempfile::tempdir().unwrap();
        let case = block_case(dir.path(), false, "", "predictor = \"none\"");
        let mesh = box_mesh(ElementKind::Hex8, [16, 4, 2], [2.0, 1.0, 0.5]);
        std::fs::write(dir.path().join("block.msh"), common::msh22(&mesh)).unwrap();
        let text = std::fs::read_to_string(&case).unwrap();
        let fields = "fields = [\"displacement\", \"recovered_von_mises\", \
                      \"recovered_cauchy_stress\"]\n";
        std::fs::write(&case, format!("{text}{fields}")).unwrap();
        let faer = serial(&case, &dir.path().join("serial"));
        let out = dir.path().join("mpi");
        let mumps = run_distributed(&case, &out, &[]);
        assert_same(
            &faer,
            &mumps,
            1e-8,
            true,
            "recovered fields, MUMPS on 2 processes",
        );
        let last = &faer.summary.increments.last().unwrap().file;
        for name in ["recovered_von_mises", "recovered_cauchy_stress"] {
            let whole = read_point_field(&dir.path().join("serial").join(last), name).unwrap();
            let pieces = merged_point_field(&out, &mumps.summary, name);
            assert_eq!(pieces.len(), whole.len(), "{name}");
            let scale = whole.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let worst = whole.iter().zip(&pieces).fold(0.0f64, |m, (a, b)| {
                if b.is_nan() {
                    f64::INFINITY
                } else {
                    m.max((a - b).abs())
                }
            });
            println!("{name}: largest difference {worst:.2e} of {scale:.3e}");
            assert!(
                scale > 0.0 && worst <= 1e-8 * scale,
                "{name}: {worst} of {scale}"
            );
        }
        let (held, owned) = (elements_held(&mumps.log), elements_owned(&mumps.log));
        println!("elements held {held:?}, owned {owned:?}");
        assert_eq!(held.len(), 2, "{}", mumps.log);
        for ((held, whole), own) in held.into_iter().zip(owned) {
            assert_eq!(whole, 128);
            assert!(own < held && held < whole, "{held} of {whole}, {own} own");
        }
    }

    /// The largest penetration of interface `base` over the increments
    /// of a distributed run, and the contact element size `h` its log
    /// states.
    fn penetration_and_size(mpi: &Distributed) -> (f64, f64) {
        let increments = mpi.summary["increments"].as_array().unwrap();
        let penetration = increments
            .iter()
            .map(|i| {
                i["contact"]["base"]["largest_penetration"]
                    .as_f64()
                    .unwrap()
            })
            .fold(0.0f64, f64::max);
        let size = mpi
            .log
            .split("contact element size ")
            .nth(1)
            .and_then(|rest| rest.split([';', ' ', '\n']).next())
            .and_then(|h| h.parse().ok())
            .unwrap_or_else(|| panic!("no contact element size in the log: {}", mpi.log));
        (penetration, size)
    }

    /// Exact contact with GAMG (issue 29 item 7): Uzawa's outer loop on
    /// the penalty path (no multiplier unknowns, so block size 3 and the
    /// rigid-body near-null space) on 2 processes, each correction by
    /// GMRES + GAMG, ends with a penetration below 1e-8 of the element
    /// size `h` and the Lagrangian answer: the serial direct (faer LDLᵀ)
    /// run of the default Rockafellar method, exact by its multiplier
    /// unknowns, to 1e-8 h in the displacements (1e-8 h/|u|max of the
    /// contact forces), without and with Coulomb friction (both laws'
    /// default `ε_T = E/h_s`).
    #[test]
    fn uzawa_with_gamg_on_two_processes_gives_the_lagrangian_answer() {
        let gamg = [
            "--",
            "-ksp_type",
            "gmres",
            "-pc_type",
            "gamg",
            "-ksp_rtol",
            "1e-12",
        ];
        for friction in [false, true] {
            let dir = tempfile::tempdir().unwrap();
            let lagrangian = block_case(dir.path(), friction, "", "");
            let faer = serial(&lagrangian, &dir.path().join("serial"));
            let case = block_case(dir.path(), friction, "method = \"uzawa\"", "");
            let uzawa = run_distributed(&case, &dir.path().join("mpi"), &gamg);
            let what = if friction {
                "with friction"
            } else {
                "frictionless"
            };
            assert!(uzawa.log.contains("pc gamg"), "{}", uzawa.log);
            assert!(uzawa.log.contains("Uzawa"), "{}", uzawa.log);
            let (penetration, h) = penetration_and_size(&uzawa);
            println!("Uzawa + GAMG {what}: largest penetration {penetration:.2e}, h = {h:.3e}");
            assert!(penetration < 1e-8 * h, "{what}: {penetration} ≥ 1e-8 × {h}");
            // to 1e-8 h: the outer loop stops at a penetration of 1e-9 h,
            // and the displacements here are h/40 (penalty is 1e-2 h off)
            let scale = faer.displacement.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let what = format!("Uzawa + GAMG on 2 processes against serial Rockafellar, {what}");
            assert_same(&faer, &uzawa, 1e-8 * h / scale, false, &what);
        }
    }

    /// Exact contact by fieldsplit on 2 processes (issue 29 item 7): the
    /// default Rockafellar method (a multiplier unknown per contact node,
    /// the last process's rows) with Coulomb friction (regularised stick,
    /// `exact_stick = false`, as `benches/million`), each correction by
    /// FGMRES on PETSc's fieldsplit Schur complement, GAMG on the
    /// displacement block and Jacobi on `selfp`. The C layer gives
    /// fieldsplit each process's own displacement rows and own multiplier
    /// rows: the displacement block is all 405 displacement rows (135
    /// nodes), with block size 3 and the rigid-body modes (its KSPView).
    /// Largest penetration below 1e-8 of the element size `h`, and the
    /// serial direct (faer) run's displacements and contact forces to
    /// 1e-8 (the same discrete problem; FGMRES to 1e-12).
    #[test]
    fn fieldsplit_on_two_processes_gives_the_serial_exact_answer() {
        let dir = tempfile::tempdir().unwrap();
        let case = block_case(dir.path(), true, "exact_stick = false", "");
        let faer = serial(&case, &dir.path().join("serial"));
        let view = dir.path().join("split0.txt");
        let view_option = format!("ascii:{}", view.display());
        let fieldsplit = [
            "--",
            "-ksp_type",
            "fgmres",
            "-ksp_rtol",
            "1e-12",
            "-ksp_max_it",
            "500",
            "-pc_type",
            "fieldsplit",
            "-pc_fieldsplit_type",
            "schur",
            "-pc_fieldsplit_schur_fact_type",
            "full",
            "-pc_fieldsplit_schur_precondition",
            "selfp",
            "-fieldsplit_0_ksp_type",
            "preonly",
            "-fieldsplit_0_pc_type",
            "gamg",
            "-fieldsplit_1_ksp_type",
            "preonly",
            "-fieldsplit_1_pc_type",
            "jacobi",
            "-fieldsplit_0_ksp_view",
            &view_option,
        ];
        let mpi = run_distributed(&case, &dir.path().join("mpi"), &fieldsplit);
        assert!(mpi.log.contains("pc fieldsplit"), "{}", mpi.log);
        let text = std::fs::read_to_string(&view).expect("the displacement block's KSPView");
        assert!(text.contains("type: gamg"), "{text}");
        assert!(text.contains("rows=405, cols=405, bs=3"), "{text}");
        assert!(text.contains("near null space"), "rigid-body modes: {text}");
        let (penetration, h) = penetration_and_size(&mpi);
        println!("fieldsplit on 2 processes: largest penetration {penetration:.2e}, h = {h:.3e}");
        assert!(penetration < 1e-8 * h, "{penetration} ≥ 1e-8 × {h}");
        let what = "Rockafellar + fieldsplit on 2 processes against serial faer";
        assert_same(&faer, &mpi, 1e-8, false, what);
    }

    /// With Coulomb friction and default keys (exact stick): the serial
    /// run solves the tangential multipliers by Newton (Alart–Curnier),
    /// the distributed one updates them in the outer loop (Simo–Laursen,
    /// the log says so), in other Newton iterations; both reach exact
    /// stick's answer, to 1e-8 of the contact element size `h`.
    #[test]
    fn two_processes_give_the_serial_answer_with_friction() {
        let dir = tempfile::tempdir().unwrap();
        let case = block_case(dir.path(), true, "", "");
        let faer = serial(&case, &dir.path().join("serial"));
        let mpi = run_distributed(&case, &dir.path().join("mpi"), &[]);
        assert!(mpi.log.contains("updated by an outer loop"), "{}", mpi.log);
        // to 1e-8 h: the outer loop stops at a stick error of 1e-9 h
        let (_, h) = penetration_and_size(&mpi);
        let scale = faer.displacement.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        assert_same(
            &faer,
            &mpi,
            1e-8 * h / scale,
            false,
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
