//! Output control (issue 15 item 4): `[output] every = N` (and always the
//! last increment of a step), zlib-compressed VTU arrays by default, read
//! back by our reader and by an independent one (Python's zlib, in
//! `scripts/compare_examples.py`), `node_id` and `region` arrays, and
//! `contact_status` as an integer array.

use signorini::output::vtu::read_point_field;
use signorini::run::{RunOptions, Simulation};
use std::path::{Path, PathBuf};

fn example(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("examples")
        .join(name)
}

/// Run `example`'s case with `extra` lines added to its `[output]` table
/// into `out`; returns the summary as JSON.
fn run_with(name: &str, output_table: &str, extra: &str, out: &Path) -> serde_json::Value {
    let dir = example(name);
    let text = std::fs::read_to_string(dir.join("case.toml")).unwrap();
    let changed = text.replace(output_table, &format!("{output_table}\n{extra}"));
    assert_ne!(changed, text, "no {output_table} in {name}");
    let mut simulation = Simulation::from_toml(&changed, &dir).unwrap();
    let options = RunOptions {
        output: Some(out.to_path_buf()),
        threads: Some(1),
        cancel: None,
        restart: None,
    };
    simulation
        .run(&options, &mut signorini::output::observer::Silent)
        .unwrap();
    serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap()
}

/// `every = 3` on the rubber cube (two steps of 4 increments each): files
/// for increments 3, 4 (end of the first step), 6 and 8 (end of the
/// second), the `.pvd` lists exactly those, the others have `file = ""`.
#[test]
fn every_third_increment_and_each_step_end_is_written() {
    let tmp = tempfile::tempdir().unwrap();
    let summary = run_with(
        "rubber-tension",
        "[output]\nname = \"rubber\"",
        "every = 3",
        tmp.path(),
    );
    let increments = summary["increments"].as_array().unwrap();
    // the reference state (t = 0) first, then the increments written
    let mut expected = vec!["rubber_0000.vtu".to_string()];
    for (k, inc) in increments.iter().enumerate() {
        let index = k + 1;
        let last_of_step = increments
            .get(k + 1)
            .is_none_or(|next| next["step"] != inc["step"]);
        let file = inc["file"].as_str().unwrap();
        if index % 3 == 0 || last_of_step {
            assert_eq!(file, format!("rubber_{index:04}.vtu"));
            assert!(tmp.path().join(file).is_file());
            expected.push(file.to_string());
        } else {
            assert_eq!(file, "", "increment {index}");
        }
    }
    assert!(increments.len() >= 6 && expected.len() < increments.len());
    let pvd = std::fs::read_to_string(tmp.path().join("rubber.pvd")).unwrap();
    let listed: Vec<String> = pvd
        .split("file=\"")
        .skip(1)
        .map(|s| s[..s.find('"').unwrap()].to_string())
        .collect();
    assert_eq!(listed, expected);
    assert!(pvd.contains(r#"timestep="0.0" group="" part="0" file="rubber_0000.vtu""#));
    let reference = tmp.path().join("rubber_0000.vtu");
    let u = signorini::output::vtu::read_point_field(&reference, "displacement").unwrap();
    assert!(!u.is_empty() && u.iter().all(|&x| x == 0.0));
    let on_disk = std::fs::read_dir(tmp.path())
        .unwrap()
        .filter(|e| {
            e.as_ref()
                .unwrap()
                .path()
                .extension()
                .is_some_and(|x| x == "vtu")
        })
        .count();
    assert_eq!(on_disk, expected.len());
}

/// The compressed files (the default) hold the same numbers, bit for bit,
/// as the uncompressed ones, read by our reader and by Python's zlib; they
/// are smaller; `node_id` holds the mesh's node tags, `region` the region
/// index, `contact_status` is an `Int64` array of 0/1/2.
#[test]
fn compressed_vtu_reads_back_exactly_with_ids_regions_and_integer_status() {
    let (zipped, plain) = (tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap());
    let table = "[output]";
    let a = run_with("press-pull", table, "", zipped.path());
    let b = run_with("press-pull", table, "compress = false", plain.path());
    let file = a["increments"].as_array().unwrap().last().unwrap()["file"]
        .as_str()
        .unwrap()
        .to_string();
    assert_eq!(
        file,
        b["increments"].as_array().unwrap().last().unwrap()["file"]
    );
    let (zip_file, plain_file) = (zipped.path().join(&file), plain.path().join(&file));
    let zip_text = std::fs::read_to_string(&zip_file).unwrap();
    assert!(zip_text.contains(r#"compressor="vtkZLibDataCompressor""#));
    assert!(!std::fs::read_to_string(&plain_file)
        .unwrap()
        .contains("compressor"));
    let (zip_size, plain_size) = (
        std::fs::metadata(&zip_file).unwrap().len(),
        std::fs::metadata(&plain_file).unwrap().len(),
    );
    assert!(zip_size < plain_size, "{zip_size} vs {plain_size}");
    for name in [
        "displacement",
        "contact_pressure",
        "contact_traction",
        "slip",
        "contact_status",
        "node_id",
    ] {
        let (x, y) = (
            read_point_field(&zip_file, name).unwrap(),
            read_point_field(&plain_file, name).unwrap(),
        );
        assert_eq!(x.len(), y.len(), "{name}");
        assert!(
            x.iter()
                .zip(&y)
                .all(|(p, q)| p.to_bits() == q.to_bits() || (p.is_nan() && q.is_nan())),
            "{name}"
        );
    }
    // integer arrays
    assert!(zip_text.contains(r#"<DataArray type="Int64" Name="contact_status""#));
    assert!(zip_text.contains(r#"<DataArray type="Int64" Name="node_id""#));
    assert!(zip_text.contains(r#"<DataArray type="Int64" Name="region""#));
    let status = read_point_field(&zip_file, "contact_status").unwrap();
    assert!(status.iter().all(|s| [0.0, 1.0, 2.0].contains(s)));
    assert!(status.contains(&2.0), "the pulled block slips somewhere");
    let mesh = signorini::case::load(&example("press-pull").join("case.toml"))
        .unwrap()
        .mesh;
    let ids = read_point_field(&zip_file, "node_id").unwrap();
    assert_eq!(
        ids,
        mesh.node_ids.iter().map(|&i| i as f64).collect::<Vec<_>>()
    );

    // an independent reader: Python's base64 and zlib
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("scripts");
    let python = std::process::Command::new("python3")
        .arg("-c")
        .arg(format!(
            "import sys; sys.path.insert(0, {script:?}); import compare_examples as c\n\
             for name in ['displacement', 'contact_status']:\n\
             \u{20}   print(name, repr(sum(c.read_point_field({zip:?}, name))), repr(sum(c.read_point_field({plain:?}, name))))",
            script = script.display().to_string(),
            zip = zip_file.display().to_string(),
            plain = plain_file.display().to_string(),
        ))
        .output();
    let Ok(python) = python else {
        eprintln!("python3 not found: the independent reader was not run");
        return;
    };
    let out = String::from_utf8_lossy(&python.stdout);
    assert!(
        python.status.success(),
        "{}",
        String::from_utf8_lossy(&python.stderr)
    );
    for line in out.lines() {
        let parts: Vec<&str> = line.split_whitespace().collect();
        assert_eq!(parts.len(), 3, "{line}");
        assert_eq!(
            parts[1], parts[2],
            "{line}: compressed and plain differ for Python"
        );
        let ours: f64 = read_point_field(&zip_file, parts[0]).unwrap().iter().sum();
        assert_eq!(parts[1].parse::<f64>().unwrap(), ours, "{line}");
    }
    assert_eq!(out.lines().count(), 2);
}

/// `every = 0` is an error naming the key and the fix.
#[test]
fn every_zero_is_refused() {
    let dir = example("rubber-tension");
    let text = std::fs::read_to_string(dir.join("case.toml")).unwrap();
    let bad = text.replace(
        "[output]\nname = \"rubber\"",
        "[output]\nname = \"rubber\"\nevery = 0",
    );
    let error = Simulation::from_toml(&bad, &dir).err().unwrap().to_string();
    assert!(
        error.contains("output.every = 0") && error.contains("N ≥ 1"),
        "{error}"
    );
}

/// `NAME.log` (issue 15 item 5): after its header, the model in words, a line per Newton
/// iteration (as many as the summary counts), a line per increment with
/// its contact totals, and the final line with the run's figures.
#[test]
fn the_log_tells_the_model_every_iteration_and_the_end() {
    let tmp = tempfile::tempdir().unwrap();
    let summary = run_with("press-pull", "[output]", "", tmp.path());
    let log = std::fs::read_to_string(tmp.path().join("press-pull.log")).unwrap();
    let lines: Vec<&str> = log.lines().collect();
    let nodes = summary["nodes"].as_u64().unwrap();
    // after the header's six lines (tests/provenance.rs)
    assert!(lines[0].starts_with("signorini "), "{}", lines[0]);
    assert!(
        lines[6].starts_with(&format!("model: {nodes} nodes")),
        "{}",
        lines[6]
    );
    assert!(log.contains(
        "region 'block': 6368 elements, linear elastic (small strain) (E = 1000, ν = 0.3)"
    ));
    assert!(log.contains("contact 'base': 221 secondary nodes of 'bottom' against a rigid plane; monolithic Rockafellar augmented Lagrangian"));
    assert!(log.contains("Coulomb friction μ = 0.3"));
    let increments = summary["increments"].as_array().unwrap();
    let iterations: u64 = increments
        .iter()
        .map(|i| i["iterations"].as_u64().unwrap())
        .sum();
    let iteration_lines = lines
        .iter()
        .filter(|l| l.starts_with("  step '") && l.contains("correction"))
        .count();
    assert_eq!(iteration_lines as u64, iterations);
    let converged = lines.iter().filter(|l| l.contains("converged in")).count();
    assert_eq!(converged, increments.len());
    let last = lines
        .iter()
        .rev()
        .find(|l| l.starts_with("completed:"))
        .unwrap();
    assert!(
        last.contains(&format!(
            "{} increments, {iterations} Newton iterations",
            increments.len()
        )),
        "{last}"
    );
    // the contact force of the last increment, as the summary has it
    let force = increments.last().unwrap()["contact"]["base"]["force"][2]
        .as_f64()
        .unwrap();
    assert!(log.contains(&format!("{force:.6e}]")), "{force}");
}
