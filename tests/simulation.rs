//! The library's `Simulation`: runs in one process with thread pools of
//! their own, results in memory, nothing written without an output folder.

use signorini::output::{ConvergedIncrement, NodalField, StepObserver, Summary};
use signorini::run::{RunOptions, Simulation};
use std::path::Path;

/// What an observer keeps of every converged increment.
#[derive(Default)]
struct Kept {
    times: Vec<f64>,
    displacement: Vec<Vec<f64>>,
    pressure: Vec<Vec<f64>>,
    /// The residual and tangent assembled at each converged state, in the
    /// run's own thread pool.
    residual: Vec<Vec<f64>>,
    tangent: Vec<Vec<f64>>,
    threads: Vec<usize>,
}

impl StepObserver for Kept {
    fn on_increment(&mut self, inc: &ConvergedIncrement, _: &Summary) -> signorini::Result<()> {
        self.times.push(inc.record.time);
        self.displacement.push(inc.displacement().to_vec());
        self.pressure
            .push(inc.nodal(NodalField::ContactPressure).into_owned());
        let problem = inc.problem;
        let mut k = vec![0.0; problem.model.pattern.nnz()];
        let (r, _) = problem
            .residual_in(inc.record.time, inc.unknowns, inc.contact, Some(&mut k))
            .expect("a converged state assembles");
        self.residual.push(r.r);
        self.tangent.push(k);
        self.threads.push(rayon::current_num_threads());
        Ok(())
    }
}

fn press_pull(threads: usize) -> (Kept, Summary) {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/press-pull");
    let text = std::fs::read_to_string(dir.join("case.toml")).unwrap();
    let mut simulation = Simulation::from_toml(&text, &dir).unwrap();
    let mut kept = Kept::default();
    let options = RunOptions {
        output: None,
        threads: Some(threads),
        cancel: None,
        restart: None,
    };
    let outcome = simulation.run(&options, &mut kept).unwrap();
    (kept, outcome.summary)
}

/// One run with one worker thread and one with two, in one process: the
/// pools are the runs' own (the summary and the observer see 1 and 2), the
/// assembled residual and tangent at every converged state are bitwise
/// equal (assembly reduces in a fixed order), and the solutions agree to
/// round-off (the parallel factorisation may sum in another order).
#[test]
fn two_runs_with_one_and_two_threads_agree() {
    let (one, one_summary) = press_pull(1);
    let (two, two_summary) = press_pull(2);
    assert_eq!(one_summary.threads, 1);
    assert_eq!(two_summary.threads, 2);
    assert!(one.threads.iter().all(|&t| t == 1), "{:?}", one.threads);
    assert!(two.threads.iter().all(|&t| t == 2), "{:?}", two.threads);
    assert_eq!(one.times, two.times);
    assert_eq!(one.times.len(), one_summary.increments.len());
    assert!(one.times.len() >= 2);
    for k in 0..one.times.len() {
        let (a, b) = (&one.displacement[k], &two.displacement[k]);
        let largest = a.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let worst = a
            .iter()
            .zip(b)
            .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
        assert!(
            worst <= 1e-12 * largest,
            "increment {k}: displacements differ by {worst:.3e}"
        );
        let pmax = one.pressure[k].iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let pworst = one.pressure[k]
            .iter()
            .zip(&two.pressure[k])
            .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
        assert!(
            pworst <= 1e-10 * pmax,
            "increment {k}: pressures differ by {pworst:.3e}"
        );
    }
    // the same state assembled with one and with two threads: bitwise equal
    let problem_dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/press-pull");
    let simulation = Simulation::from_file(&problem_dir.join("case.toml")).unwrap();
    let problem = simulation.problem();
    let last = one.times.len() - 1;
    let state = &one.displacement[last];
    let mut x = vec![0.0; problem.num_unknowns()];
    x[..state.len()].copy_from_slice(state);
    let assemble = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            let mut k = vec![0.0; problem.model.pattern.nnz()];
            let r = problem.residual(one.times[last], &x, Some(&mut k)).unwrap();
            (r.r, k)
        })
    };
    let (r1, k1) = assemble(1);
    let (r2, k2) = assemble(2);
    assert!(r1.iter().zip(&r2).all(|(a, b)| a.to_bits() == b.to_bits()));
    assert!(k1.iter().zip(&k2).all(|(a, b)| a.to_bits() == b.to_bits()));
    // and the runs' own assemblies at the converged states: the same
    // numbers to round-off of the states they were assembled at
    let rmax = one.residual[last]
        .iter()
        .fold(0.0f64, |m, v| m.max(v.abs()));
    let rworst = one.residual[last]
        .iter()
        .zip(&two.residual[last])
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    assert!(rworst <= 1e-8 * rmax, "{rworst:.3e} of {rmax:.3e}");
    assert_eq!(one.tangent[last].len(), two.tangent[last].len());
}

/// A run without an output folder writes nothing; with one, its summary
/// holds what the observer saw.
/// Three runs of press-pull on Newton's path with one thread each: one
/// alone, then two side by side in one process. All three solutions are
/// bitwise equal. Before METIS calls were serialised
/// (`solve::ordering::metis_lock`), the two side by side differed from the
/// lone run by 2e-16 to 5e-16: METIS's random-number state is global, and
/// interleaved calls returned different orderings.
#[test]
fn runs_side_by_side_equal_a_lone_run_bit_for_bit() {
    fn run() -> Vec<f64> {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/press-pull");
        let text = std::fs::read_to_string(dir.join("case.toml")).unwrap()
            + "\n[solver]\nstrategy = \"monolithic\"\n";
        let mut simulation = Simulation::from_toml(&text, &dir).unwrap();
        let options = RunOptions {
            threads: Some(1),
            ..Default::default()
        };
        let outcome = simulation.run(&options, &mut Kept::default()).unwrap();
        outcome.displacement
    }
    let alone = run();
    let (a, b) = (std::thread::spawn(run), std::thread::spawn(run));
    for side_by_side in [a.join().unwrap(), b.join().unwrap()] {
        assert!(
            side_by_side
                .iter()
                .zip(&alone)
                .all(|(x, y)| x.to_bits() == y.to_bits()),
            "largest difference {:e}",
            side_by_side
                .iter()
                .zip(&alone)
                .map(|(x, y)| (x - y).abs())
                .fold(0.0, f64::max)
        );
    }
}

#[test]
fn a_run_without_output_folder_writes_nothing() {
    let tmp = tempfile::tempdir().unwrap();
    let example = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/rubber-tension");
    for file in ["case.toml", "cube.msh"] {
        std::fs::copy(example.join(file), tmp.path().join(file)).unwrap();
    }
    let mut simulation = Simulation::from_file(&tmp.path().join("case.toml")).unwrap();
    let mut kept = Kept::default();
    let outcome = simulation.run(&RunOptions::default(), &mut kept).unwrap();
    let mut files: Vec<_> = std::fs::read_dir(tmp.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    files.sort();
    assert_eq!(files, ["case.toml", "cube.msh"]);
    assert_eq!(kept.times.len(), outcome.summary.increments.len());
    assert_eq!(outcome.summary.status, "completed");
    // the last increment's displacement is the outcome's
    assert_eq!(
        kept.displacement.last().unwrap(),
        &outcome.displacement[..kept.displacement[0].len()]
    );

    let out = tmp.path().join("out");
    let options = RunOptions {
        output: Some(out.clone()),
        threads: Some(1),
        cancel: None,
        restart: None,
    };
    let written = simulation.run(&options, &mut Kept::default()).unwrap();
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["status"], "completed");
    assert_eq!(
        summary["increments"].as_array().unwrap().len(),
        written.summary.increments.len()
    );
}

/// `[output] fields` chooses the VTU arrays; an unknown name is an error
/// naming its line and the fields there are.
#[test]
fn output_fields_choose_the_vtu_arrays() {
    let example = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/rubber-tension");
    let text = std::fs::read_to_string(example.join("case.toml")).unwrap();
    let chosen = text.replace(
        "[output]\nname = \"rubber\"",
        "[output]\nname = \"rubber\"\nfields = [\"displacement\", \"von_mises\"]",
    );
    assert_ne!(chosen, text);
    let tmp = tempfile::tempdir().unwrap();
    let mut simulation = Simulation::from_toml(&chosen, &example).unwrap();
    let options = RunOptions {
        output: Some(tmp.path().to_path_buf()),
        threads: Some(1),
        cancel: None,
        restart: None,
    };
    let outcome = simulation.run(&options, &mut Kept::default()).unwrap();
    let vtu =
        std::fs::read_to_string(tmp.path().join(&outcome.summary.increments[0].file)).unwrap();
    let arrays: Vec<&str> = vtu
        .split("Name=\"")
        .skip(1)
        .map(|s| &s[..s.find('"').unwrap()])
        .collect();
    assert_eq!(
        arrays,
        [
            "Points",
            "connectivity",
            "offsets",
            "types",
            "displacement",
            "von_mises"
        ]
    );

    let bad = text.replace(
        "[output]\nname = \"rubber\"",
        "[output]\nname = \"rubber\"\nfields = [\"stress\"]",
    );
    let error = Simulation::from_toml(&bad, &example)
        .err()
        .unwrap()
        .to_string();
    let line = bad.lines().position(|l| l.starts_with("fields")).unwrap() + 1;
    for word in [
        &format!("line {line}"),
        "output.fields",
        "'stress'",
        "cauchy_stress",
        "contact_pressure",
    ] {
        assert!(error.contains(word), "{word} not in: {error}");
    }
}
