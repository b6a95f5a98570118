//! The bad-input catalogue (issue 14): a table of hostile inputs — case
//! files, Gmsh meshes (2.2 and 4.1, ASCII and binary), STL files,
//! amplitudes, paths and the command line — each run through the binary as
//! a user meets it, asserting the exit code and the key words of the
//! message, and that nothing panics.
//!
//! Each entry is (name, files written to a fresh folder, arguments,
//! expected exit code, expected key words). Most use `check`; the base case
//! is a 27-element cube, so the whole table runs in seconds.

use std::path::{Path, PathBuf};
use std::process::Command;

/// A valid case on `cube.msh` (the 3 × 3 × 3 hexahedra of
/// `tests/data/cube_hex_41_ascii.msh`) using every table.
const BASE: &str = include_str!("data/cube_case.toml");

/// The plane obstacle of `BASE`, to be replaced by other shapes.
const WALL: &str = "shape = \"plane\"\npoint = [-0.01, 0.0, 0.0]\nnormal = [1.0, 0.0, 0.0]";

/// Something to put in the entry's folder.
#[derive(Clone)]
enum File {
    Bytes(Vec<u8>),
    Folder,
    Fifo,
}

struct Entry {
    name: String,
    files: Vec<(String, File)>,
    args: Vec<String>,
    code: i32,
    keywords: Vec<String>,
}

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
}

fn read_data(name: &str) -> Vec<u8> {
    std::fs::read(data(name)).unwrap()
}

/// The four flavours of the cube mesh: (label, file in `tests/data`).
const FLAVOURS: [(&str, &str); 4] = [
    ("4.1 ASCII", "cube_hex_41_ascii.msh"),
    ("4.1 binary", "cube_hex_41_bin.msh"),
    ("2.2 ASCII", "cube_hex_22_ascii.msh"),
    ("2.2 binary", "cube_hex_22_bin.msh"),
];

/// `text` with `from` replaced by `to`, which must occur.
#[track_caller]
fn replaced(text: &str, from: &str, to: &str) -> String {
    assert!(text.contains(from), "'{from}' is not in the text");
    text.replacen(from, to, 1)
}

/// `bytes` with `from` replaced by `to` (same length or not), which must occur.
#[track_caller]
fn replaced_bytes(bytes: &[u8], from: &[u8], to: &[u8]) -> Vec<u8> {
    let at = bytes
        .windows(from.len())
        .position(|w| w == from)
        .unwrap_or_else(|| panic!("{:?} not in the bytes", String::from_utf8_lossy(from)));
    [&bytes[..at], to, &bytes[at + from.len()..]].concat()
}

struct Catalogue(Vec<Entry>);

impl Catalogue {
    fn push(
        &mut self,
        name: &str,
        files: Vec<(&str, File)>,
        args: &[&str],
        code: i32,
        kw: &[&str],
    ) {
        self.0.push(Entry {
            name: name.to_string(),
            files: files.into_iter().map(|(n, f)| (n.to_string(), f)).collect(),
            args: args.iter().map(|s| s.to_string()).collect(),
            code,
            keywords: kw.iter().map(|s| s.to_string()).collect(),
        });
    }

    /// `case.toml` = `text` beside the cube mesh, `check`ed: exit code 1.
    fn case(&mut self, name: &str, text: String, kw: &[&str]) {
        self.push(
            name,
            vec![
                ("case.toml", File::Bytes(text.into_bytes())),
                ("cube.msh", File::Bytes(read_data("cube_hex_41_ascii.msh"))),
            ],
            &["check", "case.toml"],
            1,
            kw,
        );
    }

    /// `BASE` with `from` replaced by `to`.
    #[track_caller]
    fn edit(&mut self, name: &str, from: &str, to: &str, kw: &[&str]) {
        self.case(name, replaced(BASE, from, to), kw);
    }

    /// `BASE` with `extra` appended.
    fn append(&mut self, name: &str, extra: &str, kw: &[&str]) {
        self.case(name, format!("{BASE}\n{extra}\n"), kw);
    }

    /// `BASE` with the obstacle's shape keys replaced by `shape`.
    fn obstacle(&mut self, name: &str, shape: &str, kw: &[&str]) {
        self.edit(name, WALL, shape, kw);
    }

    /// `BASE` on the mesh `bytes`.
    fn mesh(&mut self, name: &str, bytes: Vec<u8>, kw: &[&str]) {
        self.push(
            name,
            vec![
                ("case.toml", File::Bytes(BASE.as_bytes().to_vec())),
                ("cube.msh", File::Bytes(bytes)),
            ],
            &["check", "case.toml"],
            1,
            kw,
        );
    }

    /// `BASE` with an STL obstacle `punch.stl` = `file`.
    fn stl(&mut self, name: &str, file: File, kw: &[&str]) {
        self.push(
            name,
            vec![
                (
                    "case.toml",
                    File::Bytes(
                        replaced(BASE, WALL, "shape = \"stl\"\nfile = \"punch.stl\"").into_bytes(),
                    ),
                ),
                ("cube.msh", File::Bytes(read_data("cube_hex_41_ascii.msh"))),
                ("punch.stl", file),
            ],
            &["check", "case.toml"],
            1,
            kw,
        );
    }

    /// The valid `BASE` run with the command line `args`.
    fn cli(&mut self, name: &str, args: &[&str], code: i32, kw: &[&str]) {
        self.push(
            name,
            vec![
                ("case.toml", File::Bytes(BASE.as_bytes().to_vec())),
                ("cube.msh", File::Bytes(read_data("cube_hex_41_ascii.msh"))),
            ],
            args,
            code,
            kw,
        );
    }
}

/// A fresh folder holding `entry`'s files.
fn folder(entry: &Entry) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    for (name, file) in &entry.files {
        let path = dir.path().join(name);
        match file {
            File::Bytes(b) => std::fs::write(&path, b).unwrap(),
            File::Folder => std::fs::create_dir(&path).unwrap(),
            File::Fifo => {
                let ok = Command::new("mkfifo").arg(&path).status().unwrap();
                assert!(ok.success());
            }
        }
    }
    dir
}

/// Run one entry; `Err` says what differs.
fn run(entry: &Entry) -> Result<(), String> {
    let dir = folder(entry);
    let out = Command::new(env!("CARGO_BIN_EXE_signorini"))
        .args(&entry.args)
        .current_dir(dir.path())
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    let code = out.status.code().unwrap_or(-1);
    let missing: Vec<&String> = entry
        .keywords
        .iter()
        .filter(|k| !stderr.contains(k.as_str()))
        .collect();
    if stderr.contains("panicked") || code != entry.code || !missing.is_empty() {
        return Err(format!(
            "{}: exit code {code} (expected {}), missing {missing:?} in:\n{}",
            entry.name,
            entry.code,
            stderr.chars().take(600).collect::<String>()
        ));
    }
    let rust = rust_words(&stderr);
    if !rust.is_empty() {
        return Err(format!(
            "{}: the message names Rust types {rust:?}:\n{stderr}",
            entry.name
        ));
    }
    if stderr.len() > 2000 {
        return Err(format!(
            "{}: a message of {} bytes",
            entry.name,
            stderr.len()
        ));
    }
    Ok(())
}

/// Rust's primitive and standard type names, which a user's message must
/// not show (a string for a number says "expected a number", not
/// "expected f64").
const RUST_TYPES: [&str; 16] = [
    "f64", "f32", "usize", "isize", "u64", "i64", "u32", "i32", "u8", "Option", "Vec", "String",
    "Some", "HashMap", "BTreeMap", "PathBuf",
];

/// Words in CamelCase that are not Rust types: proper names and the value
/// a case file writes `nan` (Gmsh's `$MeshFormat` sections start with `$`
/// and are not words here).
const CAMEL_NAMES: [&str; 4] = ["ParaView", "CalculiX", "McCalla", "NaN"];

/// The words of `message` that are Rust type names: one of [`RUST_TYPES`],
/// or CamelCase (`LinearElastic`, `MeshSpec`: an upper-case letter after a
/// lower-case one) other than [`CAMEL_NAMES`]; a word after `$` is Gmsh's.
fn rust_words(message: &str) -> Vec<String> {
    message
        .split(|c: char| !c.is_ascii_alphanumeric() && c != '$')
        .filter(|w| {
            let camel = w.starts_with(|c: char| c.is_ascii_uppercase())
                && w.as_bytes()
                    .windows(2)
                    .any(|p| p[0].is_ascii_lowercase() && p[1].is_ascii_uppercase());
            RUST_TYPES.contains(w) || (camel && !CAMEL_NAMES.contains(w))
        })
        .map(str::to_string)
        .collect()
}

#[test]
fn rust_words_are_found() {
    assert_eq!(
        rust_words("expected f64, found `Vec<u8>`"),
        ["f64", "Vec", "u8"]
    );
    assert_eq!(
        rust_words("does not apply to model LinearElastic"),
        ["LinearElastic"]
    );
    assert!(rust_words("open it in ParaView; expected $EndMeshFormat, got NaN").is_empty());
}

#[test]
fn the_base_case_is_valid() {
    let mut c = Catalogue(Vec::new());
    c.cli("base", &["check", "case.toml"], 0, &[]);
    run(&c.0[0]).unwrap();
}

/// Every entry of the catalogue.
fn catalogue() -> Vec<Entry> {
    let mut c = Catalogue(Vec::new());
    case_files(&mut c);
    arrays_of_three(&mut c);
    materials_and_obstacles(&mut c);
    steps_amplitudes_and_solver(&mut c);
    contacts_and_output(&mut c);
    refused_by_run_alone(&mut c);
    meshes(&mut c);
    stl_files(&mut c);
    command_line_and_paths(&mut c);
    restarts(&mut c);
    c.0
}

/// `check` on each entry, by two workers (the binary is the cost): what
/// failed.
fn failures(entries: &[Entry], check: fn(&Entry) -> Result<(), String>) -> Vec<String> {
    std::thread::scope(|s| {
        let workers: Vec<_> = (0..2)
            .map(|w| {
                s.spawn(move || {
                    entries
                        .iter()
                        .skip(w)
                        .step_by(2)
                        .filter_map(|e| check(e).err())
                        .collect::<Vec<_>>()
                })
            })
            .collect();
        workers
            .into_iter()
            .flat_map(|w| w.join().unwrap())
            .collect()
    })
}

#[test]
fn every_bad_input_is_rejected_with_a_clear_message() {
    let entries = catalogue();
    let mut names: Vec<&str> = entries.iter().map(|e| e.name.as_str()).collect();
    names.sort_unstable();
    let before = names.len();
    names.dedup();
    assert_eq!(names.len(), before, "entry names are unique");
    let failures = failures(&entries, run);
    assert!(
        failures.is_empty(),
        "{} of {} entries failed:\n{}",
        failures.len(),
        entries.len(),
        failures.join("\n")
    );
    println!("{} bad inputs rejected as expected", entries.len());
    assert!(entries.len() >= 200, "{} entries", entries.len());
}

/// `check` agrees with `run` (issue 31 item 4): every case of the
/// catalogue that `check` refuses, `run` refuses too, before it solves
/// (exit code 1, no result file but the folder's lock), with the same
/// message word for word.
#[test]
fn run_refuses_what_check_refuses_with_the_same_message() {
    let entries: Vec<Entry> = catalogue()
        .into_iter()
        .filter(|e| e.args.len() == 2 && e.args[0] == "check" && e.code == 1)
        .collect();
    let failures = failures(&entries, check_agrees_with_run);
    assert!(
        failures.is_empty(),
        "{} of {} entries disagree:\n{}",
        failures.len(),
        entries.len(),
        failures.join("\n")
    );
    println!("{} refusals of check and run agree", entries.len());
    assert!(entries.len() >= 150, "{} entries", entries.len());
}

/// `check CASE` and `run CASE --output out` on `entry`'s files: `Err` says
/// how they differ.
fn check_agrees_with_run(entry: &Entry) -> Result<(), String> {
    let dir = folder(entry);
    let case = entry.args[1].as_str();
    let command = |args: &[&str]| {
        let out = Command::new(env!("CARGO_BIN_EXE_signorini"))
            .args(args)
            .current_dir(dir.path())
            .output()
            .unwrap();
        (
            out.status.code(),
            String::from_utf8_lossy(&out.stderr).into_owned(),
        )
    };
    let check = command(&["check", case]);
    let run = command(&["run", case, "--quiet", "--threads", "1", "--output", "out"]);
    let written: Vec<String> = std::fs::read_dir(dir.path().join("out"))
        .into_iter()
        .flatten()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|f| f != ".signorini.lock")
        .collect();
    if check != run || !written.is_empty() {
        return Err(format!(
            "{}: check {:?} {:?}\n   run {:?} {:?}, wrote {written:?}",
            entry.name, check.0, check.1, run.0, run.1
        ));
    }
    Ok(())
}

fn case_files(c: &mut Catalogue) {
    // TOML syntax
    c.edit(
        "toml: unclosed array",
        "[0.0, 0.0, -1.0]",
        "[0.0, 0.0, -1.0",
        &["case.toml", "line 23", "invalid array"],
    );
    c.edit(
        "toml: unclosed string",
        "\"cube.msh\"",
        "\"cube.msh",
        &["case.toml", "line 2"],
    );
    c.edit(
        "toml: duplicate key",
        "poisson_ratio = 0.3",
        "poisson_ratio = 0.3\npoisson_ratio = 0.2",
        &["case.toml", "duplicate key"],
    );
    c.edit(
        "toml: bare word value",
        "value = 1.0",
        "value = one",
        &["case.toml", "line 18", "invalid string"],
    );
    c.edit(
        "toml: table header twice",
        "[solver]",
        "[solver]\n[solver]",
        &["case.toml", "solver"],
    );
    c.case("toml: empty file", String::new(), &["case.toml", "mesh"]);
    c.case(
        "toml: binary garbage",
        "\u{1}\u{2}\u{3}=\u{4}".into(),
        &["case.toml", "line 1"],
    );
    // structure
    c.edit("no [mesh]", "[mesh]\nfile = \"cube.msh\"\n", "", &["mesh"]);
    c.edit(
        "no mesh.file",
        "file = \"cube.msh\"\n",
        "",
        &["mesh", "file"],
    );
    c.case(
        "no [[step]]",
        BASE.replace(
            "[[step]]\nname = \"load\"\nend_time = 1.0\ninitial_increment = 0.5\n",
            "",
        ),
        &["step"],
    );
    c.case(
        "empty step array",
        format!(
            "step = []\n{}",
            BASE.replace(
                "[[step]]\nname = \"load\"\nend_time = 1.0\ninitial_increment = 0.5\n",
                ""
            )
        ),
        &["no [[step]]"],
    );
    c.edit("[[step]] misspelled", "[[step]]", "[[steps]]", &["steps"]);
    // [units]: labels only, two keys
    c.append(
        "[units] unknown key",
        "[units]\nlength = \"mm\"\ntime = \"s\"",
        &["units", "time", "length", "force"],
    );
    c.append(
        "[units] empty name",
        "[units]\nforce = \" \"",
        &["units.force", "\"N\""],
    );
    c.edit("[mesh] as an array", "[mesh]", "[[mesh]]", &["mesh"]);
    c.edit(
        "material as a table",
        "[[material]]",
        "[material]",
        &["material"],
    );
    // unknown keys in every table
    for (table, after) in [
        ("mesh", "file = \"cube.msh\""),
        ("material", "poisson_ratio = 0.3"),
        ("displacement", "surface = \"bottom\""),
        ("pressure", "value = 1.0"),
        ("body_force", "value = [0.0, 0.0, -1.0]"),
        ("obstacle", "name = \"wall\""),
        ("contact", "obstacle = \"wall\""),
        ("step", "end_time = 1.0"),
        ("solver", "max_iterations = 20"),
        ("output", "name = \"cube\""),
        ("output.history", "quantity = \"displacement_z\""),
        ("output.profile", "width = 10.0"),
    ] {
        c.edit(
            &format!("unknown key in {table}"),
            after,
            &format!("{after}\ncolour = 1"),
            &["colour"],
        );
    }
    c.case(
        "unknown top-level table",
        format!("{BASE}\n[graphics]\nx = 1\n"),
        &["graphics"],
    );
    // wrong types
    for (name, from, to, kw) in [
        (
            "mesh.file a number",
            "file = \"cube.msh\"",
            "file = 3",
            "mesh.file",
        ),
        (
            "youngs_modulus a string",
            "youngs_modulus = 100.0",
            "youngs_modulus = \"100\"",
            "material[0].youngs_modulus",
        ),
        (
            "region a number",
            "region = \"body\"",
            "region = 1",
            "region",
        ),
        (
            "displacement x a string",
            "x = 0.0",
            "x = \"0\"",
            "displacement[0].x",
        ),
        (
            "pressure value a string",
            "value = 1.0",
            "value = \"1\"",
            "pressure[0].value",
        ),
        (
            "pressure follower a number",
            "value = 1.0",
            "value = 1.0\nfollower = 1",
            "pressure[0].follower",
        ),
        (
            "body force of two components",
            "value = [0.0, 0.0, -1.0]",
            "value = [0.0, -1.0]",
            "body_force[0].value",
        ),
        (
            "plane point of two numbers",
            "point = [-0.01, 0.0, 0.0]",
            "point = [-0.01, 0.0]",
            "obstacle[0].point",
        ),
        (
            "plane normal a string",
            "normal = [1.0, 0.0, 0.0]",
            "normal = \"x\"",
            "obstacle[0].normal",
        ),
        (
            "end_time a string",
            "end_time = 1.0",
            "end_time = \"1\"",
            "step[0].end_time",
        ),
        (
            "max_iterations negative",
            "max_iterations = 20",
            "max_iterations = -1",
            "solver.max_iterations",
        ),
        (
            "max_iterations a float",
            "max_iterations = 20",
            "max_iterations = 2.5",
            "solver.max_iterations",
        ),
        (
            "line_search a string",
            "max_iterations = 20",
            "line_search = \"yes\"",
            "solver.line_search",
        ),
        (
            "history point a string",
            "point = [1.0, 1.0, 1.0]",
            "point = \"tip\"",
            "output.history[0].point",
        ),
        (
            "contact two_pass a string",
            "obstacle = \"wall\"",
            "obstacle = \"wall\"\ntwo_pass = \"yes\"",
            "contact[0].two_pass",
        ),
        (
            "contact method unknown",
            "obstacle = \"wall\"",
            "obstacle = \"wall\"\nmethod = \"lagrange\"",
            "contact[0].method",
        ),
        (
            "profile width a string",
            "width = 10.0",
            "width = \"wide\"",
            "output.profile[0].width",
        ),
        (
            "amplitude name a number",
            "surface = \"top\"\nvalue = 1.0",
            "surface = \"top\"\nvalue = 1.0\namplitude = 3",
            "pressure[0]",
        ),
    ] {
        c.edit(name, from, to, &[kw]);
    }
    // limits on sizes
    let long = "n".repeat(5000);
    c.edit(
        "a step name of 5000 characters",
        "name = \"load\"",
        &format!("name = \"{long}\""),
        &["step[0].name", "5000 characters", "at most 1024"],
    );
    c.edit(
        "a mesh path of 5000 characters",
        "file = \"cube.msh\"",
        &format!("file = \"{long}\""),
        &["mesh.file", "5000 characters"],
    );
    c.edit(
        "an amplitude name of 2000 characters",
        "ramp = [",
        &format!("{} = [", "r".repeat(2000)),
        &["2000 characters"],
    );
    let points: String = (0..100_001).map(|i| format!("[{i}, 0],")).collect();
    c.edit(
        "an amplitude table of 100001 points",
        "ramp = [[0.0, 0.0], [1.0, 1.0]]",
        &format!("ramp = [{points}]"),
        &["amplitudes.ramp", "100001 items", "at most 100000"],
    );
    c.case(
        "a case file of 5 MB",
        format!("{BASE}\n# {}\n", "x".repeat(5 << 20)),
        &["case.toml", "limit of"],
    );
    c.case(
        "a case file that is not UTF-8",
        format!("{BASE}\n# \u{0}"),
        &["case.toml"],
    );
}

fn materials_and_obstacles(c: &mut Catalogue) {
    let m = "model = \"neo_hookean\"\nyoungs_modulus = 100.0\npoisson_ratio = 0.3";
    // keys of another model
    for (model, foreign) in [
        ("neo_hookean", "alpha = [2.0]"),
        ("neo_hookean", "mu = [1.0]"),
        ("neo_hookean", "bulk_modulus = 10.0"),
        ("linear_elastic", "alpha = [2.0]"),
        ("saint_venant_kirchhoff", "bulk_modulus = 1.0"),
    ] {
        let key = foreign.split(' ').next().unwrap();
        c.edit(
            &format!("{model} with {key}"),
            m,
            &format!("model = \"{model}\"\nyoungs_modulus = 100.0\npoisson_ratio = 0.3\n{foreign}"),
            &[
                &format!("material[0].{key} does not apply to model"),
                "remove it",
            ],
        );
    }
    let ogden = "model = \"ogden\"\nmu = [1.0]\nalpha = [2.0]\nbulk_modulus = 50.0";
    c.edit(
        "ogden with youngs_modulus",
        m,
        &format!("{ogden}\nyoungs_modulus = 1.0"),
        &["material[0].youngs_modulus does not apply to model 'ogden'"],
    );
    c.edit(
        "ogden with poisson_ratio",
        m,
        &format!("{ogden}\npoisson_ratio = 0.3"),
        &["material[0].poisson_ratio does not apply to model 'ogden'"],
    );
    c.edit(
        "ogden without alpha",
        m,
        "model = \"ogden\"\nmu = [1.0]\nbulk_modulus = 50.0",
        &["material[0].alpha is required for model 'ogden'"],
    );
    c.edit(
        "ogden without bulk_modulus",
        m,
        "model = \"ogden\"\nmu = [1.0]\nalpha = [2.0]",
        &["material[0].bulk_modulus is required for model 'ogden'"],
    );
    c.edit(
        "ogden with mismatched lengths",
        m,
        "model = \"ogden\"\nmu = [1.0, 2.0]\nalpha = [2.0]\nbulk_modulus = 50.0",
        &["material[0]", "alpha"],
    );
    c.edit(
        "ogden with alpha 0",
        m,
        "model = \"ogden\"\nmu = [1.0]\nalpha = [0.0]\nbulk_modulus = 50.0",
        &["material[0].alpha[0]", "non-zero"],
    );
    c.edit(
        "ogden with negative mu",
        m,
        "model = \"ogden\"\nmu = [-1.0]\nalpha = [2.0]\nbulk_modulus = 50.0",
        &["material[0].mu[0]", "must be > 0"],
    );
    c.edit(
        "ogden with zero bulk modulus",
        m,
        "model = \"ogden\"\nmu = [1.0]\nalpha = [2.0]\nbulk_modulus = 0.0",
        &["material[0].bulk_modulus", "finite and > 0"],
    );
    c.edit(
        "ogden with empty mu",
        m,
        "model = \"ogden\"\nmu = []\nalpha = []\nbulk_modulus = 50.0",
        &["material[0]"],
    );
    c.edit(
        "neo_hookean without poisson_ratio",
        m,
        "model = \"neo_hookean\"\nyoungs_modulus = 100.0",
        &["material[0].poisson_ratio is required for model 'neo_hookean'"],
    );
    c.edit(
        "no model",
        m,
        "youngs_modulus = 100.0\npoisson_ratio = 0.3",
        &["material[0].model is required"],
    );
    c.edit(
        "unknown model",
        "\"neo_hookean\"",
        "\"mooney_rivlin\"",
        &["material[0].model", "unknown variant `mooney_rivlin`"],
    );
    c.edit(
        "no region",
        "region = \"body\"\n",
        "",
        &["material[0].region is required"],
    );
    for (name, from, to, kw) in [
        (
            "youngs_modulus 0",
            "youngs_modulus = 100.0",
            "youngs_modulus = 0.0",
            "material[0].youngs_modulus",
        ),
        (
            "youngs_modulus negative",
            "youngs_modulus = 100.0",
            "youngs_modulus = -5.0",
            "material[0].youngs_modulus",
        ),
        (
            "youngs_modulus inf",
            "youngs_modulus = 100.0",
            "youngs_modulus = inf",
            "finite",
        ),
        (
            "youngs_modulus nan",
            "youngs_modulus = 100.0",
            "youngs_modulus = nan",
            "finite",
        ),
        (
            "poisson_ratio 0.5",
            "poisson_ratio = 0.3",
            "poisson_ratio = 0.5",
            "ν = 0.5",
        ),
        (
            "poisson_ratio 0.7",
            "poisson_ratio = 0.3",
            "poisson_ratio = 0.7",
            "material[0].poisson_ratio",
        ),
        (
            "poisson_ratio -1",
            "poisson_ratio = 0.3",
            "poisson_ratio = -1.0",
            "material[0].poisson_ratio",
        ),
        (
            "poisson_ratio nan",
            "poisson_ratio = 0.3",
            "poisson_ratio = nan",
            "material[0].poisson_ratio",
        ),
        (
            "unknown region",
            "region = \"body\"",
            "region = \"rubber\"",
            "'rubber'",
        ),
    ] {
        c.edit(name, from, to, &[kw]);
    }
    c.edit(
        "two materials on one region",
        "[[displacement]]",
        "[[material]]\nregion = \"body\"\nmodel = \"linear_elastic\"\nyoungs_modulus = 1.0\npoisson_ratio = 0.2\n\n[[displacement]]",
        &["material[1].region", "already has the material of material[0]"],
    );
    c.case("no material", BASE.replacen("[[material]]\nregion = \"body\"\nmodel = \"neo_hookean\"\nyoungs_modulus = 100.0\npoisson_ratio = 0.3\n", "", 1), &["has no material", "[[material]]"]);
    // obstacles: keys of another shape, missing keys, bad geometry
    for (name, shape, kw) in [
        ("plane with radius", format!("{WALL}\nradius = 1.0"), "obstacle[0].radius does not apply to shape 'plane'"),
        ("plane with axis", format!("{WALL}\naxis = [0.0, 0.0, 1.0]"), "obstacle[0].axis does not apply to shape 'plane'"),
        ("plane with center", format!("{WALL}\ncenter = [0.0, 0.0, 1.0]"), "obstacle[0].center does not apply to shape 'plane'"),
        ("plane with file", format!("{WALL}\nfile = \"a.stl\""), "obstacle[0].file does not apply to shape 'plane'"),
        ("sphere with normal", "shape = \"sphere\"\ncenter = [-2.0, 0.5, 0.5]\nradius = 1.0\nnormal = [1.0, 0.0, 0.0]".into(), "obstacle[0].normal does not apply to shape 'sphere'"),
        ("sphere with point", "shape = \"sphere\"\ncenter = [-2.0, 0.5, 0.5]\nradius = 1.0\npoint = [1.0, 0.0, 0.0]".into(), "obstacle[0].point does not apply to shape 'sphere'"),
        ("cylinder with center", "shape = \"cylinder\"\npoint = [-2.0, 0.5, 0.5]\naxis = [0.0, 0.0, 1.0]\nradius = 1.0\ncenter = [0.0, 0.0, 0.0]".into(), "obstacle[0].center does not apply to shape 'cylinder'"),
        ("stl with radius", "shape = \"stl\"\nfile = \"p.stl\"\nradius = 1.0".into(), "obstacle[0].radius does not apply to shape 'stl'"),
        ("gmsh with normal", "shape = \"gmsh\"\nfile = \"p.msh\"\nsurface = \"s\"\nnormal = [1.0, 0.0, 0.0]".into(), "obstacle[0].normal does not apply to shape 'gmsh'"),
        ("stl with surface", "shape = \"stl\"\nfile = \"p.stl\"\nsurface = \"s\"".into(), "obstacle[0].surface does not apply to shape 'stl'"),
        ("sphere without radius", "shape = \"sphere\"\ncenter = [-2.0, 0.5, 0.5]".into(), "obstacle[0].radius is required for shape 'sphere'"),
        ("sphere without center", "shape = \"sphere\"\nradius = 1.0".into(), "obstacle[0].center is required for shape 'sphere'"),
        ("plane without normal", "shape = \"plane\"\npoint = [-0.01, 0.0, 0.0]".into(), "obstacle[0].normal is required for shape 'plane'"),
        ("cylinder without axis", "shape = \"cylinder\"\npoint = [-2.0, 0.5, 0.5]\nradius = 1.0".into(), "obstacle[0].axis is required for shape 'cylinder'"),
        ("stl without file", "shape = \"stl\"".into(), "obstacle[0].file is required for shape 'stl'"),
        ("gmsh without surface", "shape = \"gmsh\"\nfile = \"p.msh\"".into(), "obstacle[0].surface is required for shape 'gmsh'"),
        ("no shape", "point = [-0.01, 0.0, 0.0]\nnormal = [1.0, 0.0, 0.0]".into(), "obstacle[0].shape is required"),
        ("unknown shape", "shape = \"cone\"".into(), "unknown variant `cone`"),
        ("zero normal", "shape = \"plane\"\npoint = [-0.01, 0.0, 0.0]\nnormal = [0.0, 0.0, 0.0]".into(), "normal"),
        ("nan normal", "shape = \"plane\"\npoint = [-0.01, 0.0, 0.0]\nnormal = [nan, 0.0, 0.0]".into(), "obstacle[0]"),
        ("negative radius", "shape = \"sphere\"\ncenter = [-2.0, 0.5, 0.5]\nradius = -1.0".into(), "radius must be positive"),
        ("infinite radius", "shape = \"sphere\"\ncenter = [-2.0, 0.5, 0.5]\nradius = inf".into(), "radius must be positive and finite"),
        ("zero cylinder axis", "shape = \"cylinder\"\npoint = [-2.0, 0.5, 0.5]\naxis = [0.0, 0.0, 0.0]\nradius = 1.0".into(), "axis"),
        ("gmsh obstacle file missing", "shape = \"gmsh\"\nfile = \"absent.msh\"\nsurface = \"s\"".into(), "absent.msh"),
        ("gmsh obstacle surface missing", "shape = \"gmsh\"\nfile = \"cube.msh\"\nsurface = \"lid\"".into(), "'lid'"),
        ("stl obstacle file missing", "shape = \"stl\"\nfile = \"absent.stl\"".into(), "absent.stl"),
    ] {
        c.obstacle(&format!("obstacle: {name}"), &shape, &[kw]);
    }
    c.edit(
        "obstacle without name",
        "name = \"wall\"\n",
        "",
        &["obstacle[0]", "name"],
    );
    c.edit(
        "two obstacles of one name",
        "[[contact]]",
        "[[obstacle]]\nname = \"wall\"\nshape = \"sphere\"\ncenter = [0.0, 0.0, -5.0]\nradius = 1.0\n\n[[contact]]",
        &["obstacle[1] has the name 'wall' of obstacle[0]"],
    );
    c.edit(
        "obstacle motion of two numbers",
        "normal = [1.0, 0.0, 0.0]",
        "normal = [1.0, 0.0, 0.0]\nmotion = [1.0, 0.0]",
        &["obstacle[0].motion"],
    );
    c.edit(
        "obstacle amplitude unknown",
        "normal = [1.0, 0.0, 0.0]",
        "normal = [1.0, 0.0, 0.0]\nmotion = [1.0, 0.0, 0.0]\namplitude = \"push\"",
        &["obstacle[0].amplitude", "'push'"],
    );
    c.edit(
        "obstacle normal pointing into the body",
        "point = [-0.01, 0.0, 0.0]\nnormal = [1.0, 0.0, 0.0]",
        "point = [0.5, 0.0, 0.0]\nnormal = [1.0, 0.0, 0.0]",
        &["starts inside obstacle 'wall'"],
    );
    c.edit(
        "obstacle normal pointing away from the body",
        "normal = [1.0, 0.0, 0.0]",
        "normal = [-1.0, 0.0, 0.0]",
        &[
            "obstacle normal pointing away",
            "flip it: normal = [1, 0, 0]",
        ],
    );
}

fn steps_amplitudes_and_solver(c: &mut Catalogue) {
    let step = "end_time = 1.0\ninitial_increment = 0.5";
    for (name, to, kw) in [
        (
            "end_time 0",
            "end_time = 0.0",
            "step[0].end_time = 0 must be greater",
        ),
        ("end_time negative", "end_time = -1.0", "step[0].end_time"),
        ("end_time inf", "end_time = inf", "not a finite number"),
        ("end_time nan", "end_time = nan", "not a finite number"),
        (
            "initial_increment 0",
            "end_time = 1.0\ninitial_increment = 0.0",
            "step[0].initial_increment = 0 must be positive",
        ),
        (
            "initial_increment inf",
            "end_time = 1.0\ninitial_increment = inf",
            "step[0].initial_increment = inf is not a finite number",
        ),
        (
            "initial_increment nan",
            "end_time = 1.0\ninitial_increment = nan",
            "step[0].initial_increment",
        ),
        (
            "min_increment negative",
            "end_time = 1.0\nmin_increment = -1.0",
            "step[0].min_increment = -1 must be positive",
        ),
        (
            "min_increment above initial",
            "end_time = 1.0\ninitial_increment = 0.1\nmin_increment = 0.5",
            "exceeds initial_increment",
        ),
        (
            "max_increment below min",
            "end_time = 1.0\ninitial_increment = 0.01\nmin_increment = 0.01\nmax_increment = 0.001",
            "max_increment = 0.001 is smaller than min_increment = 0.01",
        ),
        (
            "max_increment inf",
            "end_time = 1.0\nmax_increment = inf",
            "step[0].max_increment = inf is not a finite number",
        ),
        ("no end_time", "initial_increment = 0.5", "step[0]"),
    ] {
        c.edit(&format!("step: {name}"), step, to, &[kw]);
    }
    c.edit(
        "step without name",
        "name = \"load\"\n",
        "",
        &["step[0]", "name"],
    );
    c.append(
        "second step ending earlier",
        "[[step]]\nname = \"back\"\nend_time = 0.5",
        &["step[1].end_time = 0.5 must be greater than the previous step's end (1)"],
    );
    c.append(
        "two steps of one name",
        "[[step]]\nname = \"load\"\nend_time = 2.0",
        &["step[1] has the name 'load' of step[0]"],
    );
    c.append(
        "two step names giving one profile file",
        "[[step]]\nname = \"lo/ad\"\nend_time = 2.0\n\n[[step]]\nname = \"lo ad\"\nend_time = 3.0",
        &["step[2] ('lo ad') and step[1] ('lo/ad')", "line_lo_ad.csv"],
    );
    // amplitudes
    let ramp = "ramp = [[0.0, 0.0], [1.0, 1.0]]";
    let used = |c: &mut Catalogue, name: &str, table: &str, kw: &[&str]| {
        let text = replaced(
            &replaced(BASE, ramp, table),
            "value = 1.0\n",
            "value = 1.0\namplitude = \"ramp\"\n",
        );
        c.case(name, text, kw);
    };
    used(
        c,
        "amplitude point of three numbers",
        "ramp = [[0.0, 0.0], [1.0, 1.0, 5.0]]",
        &["amplitudes.ramp: point 1 has 3 numbers", "[time, value]"],
    );
    used(
        c,
        "amplitude point of one number",
        "ramp = [[0.0, 0.0], [1.0]]",
        &["amplitudes.ramp: point 1 has 1 numbers"],
    );
    used(
        c,
        "amplitude without points",
        "ramp = []",
        &["amplitudes.ramp", "at least one"],
    );
    used(
        c,
        "amplitude times decreasing",
        "ramp = [[0.0, 0.0], [1.0, 1.0], [0.5, 2.0]]",
        &["amplitudes.ramp", "increase strictly"],
    );
    used(
        c,
        "amplitude times repeated",
        "ramp = [[0.0, 0.0], [0.0, 1.0]]",
        &["amplitudes.ramp", "increase strictly"],
    );
    used(
        c,
        "amplitude value nan",
        "ramp = [[0.0, 0.0], [1.0, nan]]",
        &["amplitudes.ramp", "finite"],
    );
    used(
        c,
        "amplitude time inf",
        "ramp = [[0.0, 0.0], [inf, 1.0]]",
        &["amplitudes.ramp", "finite"],
    );
    used(
        c,
        "amplitude a string",
        "ramp = \"linear\"",
        &["amplitudes.ramp"],
    );
    c.edit(
        "unused amplitude with three numbers",
        ramp,
        "ramp = [[0.0, 0.0, 0.0]]",
        &["amplitudes.ramp: point 0 has 3 numbers"],
    );
    c.edit(
        "inline amplitude with three numbers",
        "value = 1.0\n",
        "value = 1.0\namplitude = [[0.0, 0.0, 1.0]]\n",
        &["pressure[0].amplitude: point 0 has 3 numbers"],
    );
    c.edit(
        "unknown amplitude name",
        "value = 1.0\n",
        "value = 1.0\namplitude = \"slow\"\n",
        &["pressure[0].amplitude", "no amplitude named 'slow'", "ramp"],
    );
    // loads
    c.edit(
        "displacement without components",
        "x = 0.0\ny = 0.0\nz = 0.0\n",
        "",
        &["displacement[0]", "at least one of x, y, z"],
    );
    c.edit(
        "displacement inf",
        "x = 0.0",
        "x = inf",
        &["displacement[0]", "finite"],
    );
    c.edit(
        "displacement on unknown surface",
        "surface = \"bottom\"",
        "surface = \"base\"",
        &["displacement[0].surface", "'base'", "bottom"],
    );
    c.edit(
        "pressure nan",
        "value = 1.0",
        "value = nan",
        &["pressure[0].value must be finite"],
    );
    c.edit(
        "pressure on unknown surface",
        "surface = \"top\"",
        "surface = \"lid\"",
        &["pressure[0].surface", "'lid'"],
    );
    c.edit(
        "body force inf",
        "value = [0.0, 0.0, -1.0]",
        "value = [0.0, inf, -1.0]",
        &["body_force[0].value must be finite"],
    );
    c.edit(
        "body force on unknown region",
        "value = [0.0, 0.0, -1.0]",
        "value = [0.0, 0.0, -1.0]\nregion = \"steel\"",
        &["body_force[0].region", "'steel'"],
    );
    // solver
    for (name, to, kw) in [
        (
            "residual_tolerance 0",
            "residual_tolerance = 0.0",
            "solver.residual_tolerance = 0 must be in (0, 1)",
        ),
        (
            "residual_tolerance 2",
            "residual_tolerance = 2.0",
            "solver.residual_tolerance = 2 must be in (0, 1)",
        ),
        (
            "displacement_tolerance nan",
            "displacement_tolerance = nan",
            "solver.displacement_tolerance",
        ),
        (
            "growth_factor 0.5",
            "growth_factor = 0.5",
            "solver.growth_factor = 0.5 must be ≥ 1",
        ),
        (
            "growth_factor inf",
            "growth_factor = inf",
            "solver.growth_factor = inf is not a finite number",
        ),
        (
            "max_iterations 0",
            "max_iterations = 0",
            "solver.max_iterations must be at least 1",
        ),
        (
            "nonsymmetric unknown",
            "nonsymmetric = \"bicgstab\"",
            "solver.nonsymmetric",
        ),
    ] {
        c.edit(&format!("solver: {name}"), "max_iterations = 20", to, &[kw]);
    }
}

/// What `run` refused (or failed on after solving) while `check` said ok
/// (issue 31 item 4): `check` refuses them now, with `run`'s message
/// (`run_refuses_what_check_refuses_with_the_same_message`).
fn refused_by_run_alone(c: &mut Catalogue) {
    let long = "a".repeat(300);
    c.edit(
        "output: every = 0",
        "name = \"cube\"",
        "name = \"cube\"\nevery = 0",
        &["line 46", "output.every = 0", "N ≥ 1"],
    );
    c.edit(
        "output: a field named twice",
        "name = \"cube\"",
        "name = \"cube\"\nfields = [\"displacement\", \"von_mises\", \"displacement\"]",
        &["output.fields names 'displacement' twice", "once"],
    );
    c.edit(
        "output: a name of 300 bytes",
        "name = \"cube\"",
        &format!("name = \"{long}\""),
        &["output.name", "300 bytes", "at most 200"],
    );
    c.edit(
        "output: a history name of 300 bytes",
        "name = \"tip\"",
        &format!("name = \"{long}\""),
        &["output.history 'aaa", "300 bytes", "at most 200"],
    );
    // issue 31: the VTU files had no arrays at all
    let without_contact = BASE.split("[[obstacle]]").next().unwrap().to_string()
        + &BASE[BASE.find("[amplitudes]").unwrap()..BASE.find("[[output.profile]]").unwrap()];
    c.case(
        "output: contact fields without contact",
        replaced(
            &without_contact,
            "name = \"cube\"",
            "name = \"cube\"\nfields = [\"contact_pressure\", \"gap\"]",
        ),
        &[
            "output.fields names 'contact_pressure', a contact field",
            "no [[contact]]",
        ],
    );
    // issue 31: accepted, it constrained nothing
    let mut deck = read_data("cube_hex.inp");
    deck.extend_from_slice(b"*NSET, NSET=empty\n");
    c.push(
        "displacement: an empty node set",
        vec![
            (
                "case.toml",
                File::Bytes(
                    replaced(
                        &replaced(BASE, "file = \"cube.msh\"", "file = \"cube.inp\""),
                        "[[pressure]]",
                        "[[displacement]]\nnodes = \"empty\"\nx = 0.0\n\n[[pressure]]",
                    )
                    .into_bytes(),
                ),
            ),
            ("cube.inp", File::Bytes(deck)),
        ],
        &["check", "case.toml"],
        1,
        &[
            "displacement[1].nodes = 'empty'",
            "has no nodes",
            "act on nothing",
        ],
    );
}

fn contacts_and_output(c: &mut Catalogue) {
    let contact = "surface = \"contact\"\nobstacle = \"wall\"";
    for (name, to, kw) in [
        ("unknown obstacle", "surface = \"contact\"\nobstacle = \"floor\"", "contact[0].obstacle: no [[obstacle]] named 'floor'"),
        ("unknown surface", "surface = \"sole\"\nobstacle = \"wall\"", "contact[0].surface"),
        ("neither obstacle nor primary", "surface = \"contact\"", "neither"),
        ("both obstacle and primary", "surface = \"contact\"\nobstacle = \"wall\"\nprimary = \"top\"", "both"),
        ("primary is the surface itself", "surface = \"contact\"\nprimary = \"contact\"", "is the secondary surface itself"),
        // the cube's 'contact' and 'top' are the same facets (two physical groups)
        ("primary is the surface itself under another name", "surface = \"contact\"\nprimary = \"top\"", "self-paired surface"),
        ("unknown primary", "surface = \"contact\"\nprimary = \"lid\"", "contact[0].primary"),
        ("two_pass with an obstacle", "surface = \"contact\"\nobstacle = \"wall\"\ntwo_pass = true", "two_pass applies to contact between deformable bodies only"),
        ("two_pass with rockafellar", "surface = \"contact\"\nprimary = \"top\"\ntwo_pass = true", "two_pass needs method"),
        ("negative friction", "surface = \"contact\"\nobstacle = \"wall\"\nfriction_coefficient = -0.1", "friction_coefficient = -0.1 must be zero or positive"),
        ("nan friction", "surface = \"contact\"\nobstacle = \"wall\"\nfriction_coefficient = nan", "friction_coefficient"),
        ("infinite friction", "surface = \"contact\"\nobstacle = \"wall\"\nfriction_coefficient = inf", "friction_coefficient = inf is not a finite number; give zero or a positive value"),
        ("tangential penalty without friction", "surface = \"contact\"\nobstacle = \"wall\"\ntangential_penalty = 10.0", "without contact[0].friction_coefficient"),
        ("penalty 0", "surface = \"contact\"\nobstacle = \"wall\"\npenalty = 0.0", "contact[0].penalty = 0 must be positive"),
        ("penalty inf", "surface = \"contact\"\nobstacle = \"wall\"\npenalty = inf", "contact[0].penalty = inf is not a finite number"),
        ("scaling negative", "surface = \"contact\"\nobstacle = \"wall\"\nscaling = -1.0", "contact[0].scaling = -1 must be positive"),
        ("tangential penalty nan", "surface = \"contact\"\nobstacle = \"wall\"\nfriction_coefficient = 0.2\ntangential_penalty = nan", "contact[0].tangential_penalty = NaN is not a finite number"),
        ("negative penetration tolerance", "surface = \"contact\"\nobstacle = \"wall\"\ninitial_penetration_tolerance = -1.0", "initial_penetration_tolerance = -1 must be zero or positive"),
        ("infinite penetration tolerance", "surface = \"contact\"\nobstacle = \"wall\"\ninitial_penetration_tolerance = inf", "initial_penetration_tolerance = inf is not a finite number"),
        ("exact stick without friction", "surface = \"contact\"\nobstacle = \"wall\"\nexact_stick = true", "exact_stick = true: it needs friction"),
        ("exact stick with penalty", "surface = \"contact\"\nobstacle = \"wall\"\nfriction_coefficient = 0.2\nmethod = \"penalty\"\nexact_stick = true", "penalty method keeps the regularised law"),
        ("friction multiplier with the regularised law", "surface = \"contact\"\nobstacle = \"wall\"\nfriction_coefficient = 0.2\nexact_stick = false\nfriction_multiplier = \"outer\"", "friction_multiplier: it applies to exact stick only: remove exact_stick = false"),
        ("friction multiplier without friction", "surface = \"contact\"\nobstacle = \"wall\"\nfriction_multiplier = \"outer\"", "friction_multiplier: it applies to exact stick only, which needs friction"),
        ("friction multiplier with penalty", "surface = \"contact\"\nobstacle = \"wall\"\nmethod = \"penalty\"\nfriction_coefficient = 0.2\nfriction_multiplier = \"outer\"", "friction_multiplier: it applies to exact stick only, which needs friction and method rockafellar"),
        ("newton friction multiplier with uzawa", "surface = \"contact\"\nobstacle = \"wall\"\nfriction_coefficient = 0.2\nmethod = \"uzawa\"\nexact_stick = true\nfriction_multiplier = \"newton\"", "friction_multiplier = \"outer\" or method = \"rockafellar\""),
    ] {
        c.edit(&format!("contact: {name}"), contact, to, &[kw]);
    }
    c.append(
        "two contacts of one name",
        "[[contact]]\nsurface = \"top\"\nobstacle = \"wall\"\nname = \"contact\"",
        &["contact[1] has the name 'contact' of contact[0]"],
    );
    c.append("a contact named like a reverse pass", "[[contact]]\nname = \"pair\"\nsurface = \"top\"\nprimary = \"bottom\"\ntwo_pass = true\nmethod = \"uzawa\"\n\n[[contact]]\nname = \"pair.reverse\"\nsurface = \"bottom\"\nprimary = \"top\"\nmethod = \"uzawa\"", &["pair.reverse"]);
    // output names
    for (name, to, kw) in [
        (
            "output name escaping the folder",
            "name = \"../../x\"",
            "output.name = '../../x'",
        ),
        (
            "output name absolute",
            "name = \"/tmp/x\"",
            "output.name = '/tmp/x'",
        ),
        ("output name empty", "name = \"\"", "output.name = ''"),
        ("output name hidden", "name = \".x\"", "output.name = '.x'"),
        (
            "output name with a space",
            "name = \"my run\"",
            "output.name = 'my run'",
        ),
        // the rule is ASCII: an accented letter is a letter, so say which
        (
            "output name with an accented letter",
            "name = \"résultat\"",
            "so use ASCII letters",
        ),
        (
            "output name of 2000 characters",
            &format!("name = \"{}\"", "c".repeat(2000)),
            "2000 characters",
        ),
    ] {
        c.edit(&format!("output: {name}"), "name = \"cube\"", to, &[kw]);
    }
    let history = "name = \"tip\"";
    for (name, to, kw) in [
        (
            "history name escaping",
            "name = \"../tip\"",
            "output.history[0].name = '../tip'",
        ),
        (
            "history name absolute",
            "name = \"/tip\"",
            "output.history[0].name = '/tip'",
        ),
        (
            "history name empty",
            "name = \"\"",
            "output.history[0].name = ''",
        ),
        (
            "history named convergence",
            "name = \"convergence\"",
            "already used",
        ),
        (
            "history named like the profile",
            "name = \"line\"",
            "output.profile[0].name = 'line' is already used",
        ),
        (
            "history named like a profile's step file",
            "name = \"line_load\"",
            "line_load.csv",
        ),
    ] {
        c.edit(&format!("output: {name}"), history, to, &[kw]);
    }
    c.edit(
        "output: profile name escaping",
        "name = \"line\"",
        "name = \"../line\"",
        &["output.profile[0].name = '../line'"],
    );
    c.edit(
        "output: profile name empty",
        "name = \"line\"",
        "name = \"\"",
        &["output.profile[0].name = ''"],
    );
    c.append("output: two histories of one name", "[[output.history]]\nname = \"tip\"\npoint = [0.0, 0.0, 1.0]\nquantity = \"displacement_x\"", &["output.history[1].name = 'tip' is already used"]);
    c.append("output: two profiles of one name", "[[output.profile]]\nname = \"line\"\ninterface = \"contact\"\nfrom = [0.0, 0.0, 0.0]\nto = [0.0, 1.0, 1.0]\nwidth = 10.0", &["output.profile[1].name = 'line' is already used"]);
    for (name, from, to, kw) in [
        (
            "history point nan",
            "point = [1.0, 1.0, 1.0]",
            "point = [nan, 1.0, 1.0]",
            "output.history[0].point must be finite",
        ),
        (
            "history without point",
            "point = [1.0, 1.0, 1.0]\n",
            "",
            "output.history[0].point is required",
        ),
        (
            "history gap without interface",
            "quantity = \"displacement_z\"",
            "quantity = \"gap\"",
            "output.history[0].interface is required",
        ),
        (
            "history displacement with interface",
            "quantity = \"displacement_z\"",
            "quantity = \"displacement_z\"\ninterface = \"contact\"",
            "output.history[0].interface applies to gap",
        ),
        (
            "history reaction without surface",
            "point = [1.0, 1.0, 1.0]\nquantity = \"displacement_z\"",
            "quantity = \"reaction_force\"",
            "output.history[0].surface is required",
        ),
        (
            "history reaction on a surface and a node set",
            "point = [1.0, 1.0, 1.0]\nquantity = \"displacement_z\"",
            "quantity = \"reaction_force_x\"\nsurface = \"bottom\"\nnodes = \"corner\"",
            "not both",
        ),
        (
            "history reaction on an unknown node set",
            "point = [1.0, 1.0, 1.0]\nquantity = \"displacement_z\"",
            "quantity = \"reaction_force_z\"\nnodes = \"corner\"",
            "output.history[0].nodes: the mesh has no node set",
        ),
        (
            "history nodes on a displacement",
            "quantity = \"displacement_z\"",
            "quantity = \"displacement_z\"\nnodes = \"corner\"",
            "output.history[0].nodes applies to reaction_force only",
        ),
        (
            "history unknown quantity",
            "quantity = \"displacement_z\"",
            "quantity = \"stress\"",
            "output.history[0].quantity",
        ),
        (
            "history unknown interface",
            "quantity = \"displacement_z\"",
            "quantity = \"gap\"\ninterface = \"sole\"",
            "no contact interface named 'sole'",
        ),
        (
            "profile unknown interface",
            "interface = \"contact\"\nfrom",
            "interface = \"sole\"\nfrom",
            "output.profile[0].interface",
        ),
        (
            "profile zero length",
            "to = [1.0, 1.0, 1.0]",
            "to = [0.0, 0.0, 0.0]",
            "the same point",
        ),
        (
            "profile width 0",
            "width = 10.0",
            "width = 0.0",
            "output.profile[0].width = 0 must be positive",
        ),
        (
            "profile width inf",
            "width = 10.0",
            "width = inf",
            "output.profile[0].width = inf is not a finite number",
        ),
        (
            "profile from nan",
            "from = [0.0, 0.0, 0.0]",
            "from = [nan, 0.0, 0.0]",
            "must be finite",
        ),
        (
            "profile band empty",
            "from = [0.0, 0.0, 0.0]\nto = [1.0, 1.0, 1.0]\nwidth = 10.0",
            "from = [5.0, 5.0, 5.0]\nto = [6.0, 6.0, 6.0]\nwidth = 0.1",
            "no secondary node",
        ),
    ] {
        c.edit(&format!("output: {name}"), from, to, &[kw]);
    }
}

/// The first node coordinate line of an ASCII mesh `text` (2.2: `tag x y z`
/// after the node count; 4.1: `x y z` after the first block's tags).
fn first_coordinate(text: &str, v22: bool) -> (usize, String) {
    let lines: Vec<&str> = text.lines().collect();
    let start = lines.iter().position(|l| *l == "$Nodes").unwrap();
    let n = if v22 { 4 } else { 3 };
    (start + 1..lines.len())
        .skip(if v22 { 1 } else { 2 })
        .find(|&i| lines[i].split_whitespace().count() == n)
        .map(|i| (i, lines[i].to_string()))
        .unwrap()
}

/// `text` with its first node's x coordinate set to `x`; returns the text
/// and the 1-based line changed.
fn with_x(text: &str, v22: bool, x: &str) -> (String, usize) {
    let (i, line) = first_coordinate(text, v22);
    let mut parts: Vec<&str> = line.split_whitespace().collect();
    parts[usize::from(v22)] = x;
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    lines[i] = parts.join(" ");
    (lines.join("\n") + "\n", i + 1)
}

fn meshes(c: &mut Catalogue) {
    for (label, file) in FLAVOURS {
        let bytes = read_data(file);
        let binary = label.contains("binary");
        for fraction in [0.1, 0.35, 0.6, 0.9] {
            let cut = (bytes.len() as f64 * fraction) as usize;
            c.mesh(
                &format!("mesh {label} truncated at {fraction}"),
                bytes[..cut].to_vec(),
                &["cube.msh"],
            );
        }
        let header = &bytes[..bytes
            .windows(15)
            .position(|w| w == b"$EndMeshFormat\n")
            .unwrap()];
        let version = String::from_utf8_lossy(header)
            .lines()
            .nth(1)
            .unwrap()
            .to_string();
        c.mesh(
            &format!("mesh {label} version 3.0"),
            replaced_bytes(
                &bytes,
                version.as_bytes(),
                version.replacen(&version[..3], "3.0", 1).as_bytes(),
            ),
            &["cube.msh", "3.0"],
        );
        c.mesh(
            &format!("mesh {label} file type 7"),
            replaced_bytes(
                &bytes,
                version.as_bytes(),
                version
                    .replacen(if binary { " 1 " } else { " 0 " }, " 7 ", 1)
                    .as_bytes(),
            ),
            &["cube.msh", "line 2"],
        );
        c.mesh(
            &format!("mesh {label} without $Nodes"),
            replaced_bytes(
                &replaced_bytes(&bytes, b"$Nodes\n", b"$Nodez\n"),
                b"$EndNodes",
                b"$EndNodez",
            ),
            &["cube.msh", "$Elements comes before $Nodes"],
        );
        c.mesh(
            &format!("mesh {label} without $Elements"),
            replaced_bytes(
                &replaced_bytes(&bytes, b"$Elements\n", b"$Elementz\n"),
                b"$EndElements",
                b"$EndElementz",
            ),
            &["cube.msh", "no $Elements section"],
        );
        c.mesh(
            &format!("mesh {label} group name without closing quote"),
            replaced_bytes(&bytes, b"\"body\"", b"\"body "),
            &["cube.msh", "closing quote"],
        );
        c.mesh(
            &format!("mesh {label} without $EndMeshFormat"),
            replaced_bytes(&bytes, b"$EndMeshFormat", b"$EndMeshFormax"),
            &["cube.msh"],
        );
        c.mesh(
            &format!("mesh {label} with a second $MeshFormat"),
            replaced_bytes(
                &bytes,
                b"$PhysicalNames",
                format!("$MeshFormat\n{version}\n$EndMeshFormat\n$PhysicalNames").as_bytes(),
            ),
            &["cube.msh", "$MeshFormat"],
        );
        c.mesh(
            &format!("mesh {label} physical volume renamed"),
            replaced_bytes(&bytes, b"\"body\"", b"\"bulk\""),
            &["material[0].region", "'body'", "bulk"],
        );
        if !binary {
            let text = String::from_utf8(bytes.clone()).unwrap();
            let v22 = label.starts_with("2.2");
            for (what, x, kw) in [
                ("NaN", "nan", "is NaN"),
                ("inf", "inf", "is inf"),
                ("-1e155", "-1e155", "beyond"),
                ("1e101", "1e101", "beyond"),
                ("a word", "zero", "'zero'"),
            ] {
                let (damaged, line) = with_x(&text, v22, x);
                c.mesh(
                    &format!("mesh {label} x coordinate {what}"),
                    damaged.into_bytes(),
                    &["cube.msh", &format!("line {line}:"), kw],
                );
            }
        }
    }
    // 2.2 ASCII element lines: `id type ntags tags... nodes`
    let text = String::from_utf8(read_data("cube_hex_22_ascii.msh")).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let hexes: Vec<usize> = (0..lines.len())
        .filter(|&i| {
            lines[i].split_whitespace().nth(1) == Some("5")
                && lines[i].split_whitespace().count() > 10
        })
        .collect();
    let edit_line = |i: usize, f: &dyn Fn(&mut Vec<String>)| {
        let mut ls: Vec<String> = lines.iter().map(|s| s.to_string()).collect();
        let mut parts: Vec<String> = ls[i].split_whitespace().map(String::from).collect();
        f(&mut parts);
        ls[i] = parts.join(" ");
        ls.join("\n") + "\n"
    };
    let mirror = |p: &mut Vec<String>| {
        let n = p.len();
        for k in 0..4 {
            p.swap(n - 8 + k, n - 4 + k);
        }
    };
    let id = |i: usize| lines[i].split_whitespace().next().unwrap().to_string();
    c.mesh(
        "mesh 2.2 element with an unknown node",
        edit_line(hexes[0], &|p| *p.last_mut().unwrap() = "9999".into()).into_bytes(),
        &["cube.msh", "9999"],
    );
    c.mesh(
        "mesh 2.2 element of unknown type",
        edit_line(hexes[0], &|p| p[1] = "1234".into()).into_bytes(),
        &["cube.msh", "1234"],
    );
    c.mesh(
        "mesh 2.2 element with a repeated node",
        edit_line(hexes[0], &|p| {
            let n = p.len();
            p[n - 1] = p[n - 2].clone();
        })
        .into_bytes(),
        &["cube.msh"],
    );
    c.mesh(
        "mesh 2.2 element with too few nodes",
        edit_line(hexes[0], &|p| {
            p.pop();
        })
        .into_bytes(),
        &["cube.msh"],
    );
    c.mesh(
        "mesh 2.2 inverted element",
        edit_line(hexes[4], &mirror).into_bytes(),
        &[&format!("element {} (mesh id) is inverted", id(hexes[4]))],
    );
    {
        // several inverted elements: the first in the file is named, every time
        let mut ls: Vec<String> = lines.iter().map(|s| s.to_string()).collect();
        for &i in &[hexes[20], hexes[3], hexes[11]] {
            let mut parts: Vec<String> = ls[i].split_whitespace().map(String::from).collect();
            mirror(&mut parts);
            ls[i] = parts.join(" ");
        }
        let damaged = ls.join("\n") + "\n";
        for k in 0..3 {
            c.mesh(
                &format!("mesh 2.2 three inverted elements ({k})"),
                damaged.clone().into_bytes(),
                &[&format!("element {} (mesh id) is inverted", id(hexes[3]))],
            );
        }
    }
    c.mesh(
        "mesh 2.2 flattened element",
        edit_line(hexes[0], &|p| {
            let n = p.len();
            for k in 0..4 {
                p[n - 4 + k] = p[n - 8 + k].clone();
            }
        })
        .into_bytes(),
        &["element"],
    );
    // other files
    c.mesh("mesh empty", Vec::new(), &["cube.msh", "end of file"]);
    c.mesh(
        "mesh garbage",
        b"hello world\n".to_vec(),
        &["cube.msh", "line 1"],
    );
    c.mesh(
        "mesh only its format",
        b"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n".to_vec(),
        &["cube.msh", "no $Nodes section"],
    );
    c.mesh(
        "mesh random bytes",
        (0..4000u32)
            .map(|i| (i.wrapping_mul(2654435761) >> 13) as u8)
            .collect(),
        &["cube.msh"],
    );
    let bin = read_data("cube_hex_22_bin.msh");
    c.mesh(
        "mesh 2.2 binary wrong endianness marker",
        replaced_bytes(&bin, b"8\n\x01\x00\x00\x00", b"8\n\x02\x00\x00\x00"),
        &["cube.msh"],
    );
    {
        // the first node's x in the 2.2 binary file: after "$Nodes\n64\n" and its 4-byte tag
        let at = bin.windows(10).position(|w| w == b"$Nodes\n64\n").unwrap() + 14;
        let mut big = bin.clone();
        big[at..at + 8].copy_from_slice(&(-1e155f64).to_le_bytes());
        c.mesh(
            "mesh 2.2 binary x coordinate -1e155",
            big,
            &["cube.msh", "beyond"],
        );
        let mut nan = bin.clone();
        nan[at..at + 8].copy_from_slice(&f64::NAN.to_le_bytes());
        c.mesh(
            "mesh 2.2 binary x coordinate NaN",
            nan,
            &["cube.msh", "NaN"],
        );
    }
    c.mesh("mesh of surfaces only", b"$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0 0\n2 1 0 0\n3 0 1 0\n$EndNodes\n$Elements\n1\n1 2 2 1 1 1 2 3\n$EndElements\n".to_vec(), &["cube.msh", "no volume elements (Tet4, Tet10, Hex8"]);
}

/// A binary STL: 80-byte header, `count` announced, `records` 50-byte
/// triangle records (`triangles` written first).
fn binary_stl(count: u32, records: usize, triangles: &[[[f32; 3]; 3]]) -> Vec<u8> {
    let mut d = vec![b' '; 80];
    d.extend_from_slice(&count.to_le_bytes());
    for r in 0..records {
        d.extend_from_slice(&[0u8; 12]);
        let t = triangles.get(r).copied().unwrap_or_default();
        for v in t {
            for x in v {
                d.extend_from_slice(&x.to_le_bytes());
            }
        }
        d.extend_from_slice(&[0u8; 2]);
    }
    d
}

fn stl_files(c: &mut Catalogue) {
    let tri = [[0.0, 0.0, -2.0], [1.0, 0.0, -2.0], [0.0, 1.0, -2.0]];
    c.stl(
        "stl empty",
        File::Bytes(Vec::new()),
        &["punch.stl", "empty"],
    );
    c.stl(
        "stl of 10 bytes",
        File::Bytes(b"0123456789".to_vec()),
        &["punch.stl", "not an STL file", "10 bytes"],
    );
    c.stl(
        "stl truncated",
        File::Bytes(binary_stl(5, 2, &[tri, tri])),
        &["punch.stl", "truncated binary STL", "5 triangles"],
    );
    c.stl(
        "stl truncated in its header",
        File::Bytes(binary_stl(5, 0, &[])[..60].to_vec()),
        &["punch.stl", "84-byte header"],
    );
    c.stl(
        "stl longer than announced",
        File::Bytes(binary_stl(1, 3, &[tri])),
        &["punch.stl", "not an STL file", "1 triangles"],
    );
    c.stl(
        "stl of zero triangles",
        File::Bytes(binary_stl(0, 0, &[])),
        &["punch.stl", "no triangles"],
    );
    c.stl(
        "stl of degenerate triangles",
        File::Bytes(binary_stl(2, 2, &[])),
        &["punch.stl"],
    );
    c.stl("stl of text", File::Bytes(b"this is not a mesh, just some text that is long enough to pass the 84-byte binary header...".to_vec()), &["punch.stl", "not an STL file"]);
    c.stl(
        "stl ascii with garbage",
        File::Bytes(
            b"solid x\n  facet normal 0 0 1\n    outer loop\n      vertex a b c\n".to_vec(),
        ),
        &["punch.stl", "cannot be read as STL"],
    );
    let ascii = read_data("tetrahedron_ascii.stl");
    c.stl(
        "stl ascii truncated",
        File::Bytes(ascii[..ascii.len() / 2].to_vec()),
        &["punch.stl", "cannot be read as STL"],
    );
    c.stl(
        "stl ascii nan vertex",
        File::Bytes(
            String::from_utf8(ascii.clone())
                .unwrap()
                .replacen("vertex 0.0000000e+00", "vertex nan", 1)
                .into_bytes(),
        ),
        &["punch.stl"],
    );
    c.stl(
        "stl a folder",
        File::Folder,
        &["punch.stl", "not a regular file"],
    );
    c.stl(
        "stl a FIFO",
        File::Fifo,
        &["punch.stl", "not a regular file"],
    );
}

fn command_line_and_paths(c: &mut Catalogue) {
    c.cli("cli: no arguments", &[], 2, &["Usage"]);
    c.cli(
        "cli: unknown subcommand",
        &["solve", "case.toml"],
        2,
        &["solve"],
    );
    c.cli("cli: check without a case", &["check"], 2, &["<CASE>"]);
    c.cli("cli: run without a case", &["run"], 2, &["<CASE>"]);
    c.cli(
        "cli: unknown flag",
        &["run", "case.toml", "--fast"],
        2,
        &["--fast"],
    );
    c.cli(
        "cli: threads 0",
        &["run", "case.toml", "--threads", "0"],
        2,
        &["--threads"],
    );
    c.cli(
        "cli: threads negative",
        &["run", "case.toml", "--threads", "-1"],
        2,
        &["'-1'"],
    );
    c.cli(
        "cli: threads a word",
        &["run", "case.toml", "--threads", "many"],
        2,
        &["--threads", "many"],
    );
    c.cli(
        "cli: threads 100000",
        &["run", "case.toml", "--threads", "100000", "--quiet"],
        2,
        &["--threads 100000", "at most"],
    );
    c.cli(
        "cli: threads 2^32",
        &["run", "case.toml", "--threads", "4294967296"],
        2,
        &["--threads"],
    );
    c.cli(
        "cli: threads without a value",
        &["run", "case.toml", "--threads"],
        2,
        &["--threads"],
    );
    c.cli(
        "cli: output without a value",
        &["run", "case.toml", "--output"],
        2,
        &["--output"],
    );
    c.cli(
        "cli: check with --quiet",
        &["check", "case.toml", "--quiet"],
        2,
        &["--quiet"],
    );
    c.cli(
        "cli: missing case file",
        &["check", "absent.toml"],
        1,
        &["absent.toml", "cannot read case file"],
    );
    c.cli(
        "cli: case file a folder",
        &["check", "."],
        1,
        &["not a regular file"],
    );
    c.cli(
        "cli: case file /dev/zero",
        &["check", "/dev/zero"],
        1,
        &["/dev/zero", "not a regular file"],
    );
    c.cli(
        "cli: case file /dev/null",
        &["check", "/dev/null"],
        1,
        &["/dev/null", "not a regular file"],
    );
    c.cli(
        "cli: case file is the mesh",
        &["check", "cube.msh"],
        1,
        &["cube.msh"],
    );
    c.cli(
        "cli: run output folder is a file",
        &["run", "case.toml", "--quiet", "--output", "cube.msh"],
        1,
        &["cube.msh"],
    );
    // paths in the case file
    c.edit(
        "path: mesh file missing",
        "file = \"cube.msh\"",
        "file = \"absent.msh\"",
        &["absent.msh"],
    );
    c.edit(
        "path: mesh file a folder",
        "file = \"cube.msh\"",
        "file = \".\"",
        &["not a regular file"],
    );
    c.edit(
        "path: mesh file /dev/zero",
        "file = \"cube.msh\"",
        "file = \"/dev/zero\"",
        &["/dev/zero", "not a regular file"],
    );
    c.edit(
        "path: mesh file /dev/urandom",
        "file = \"cube.msh\"",
        "file = \"/dev/urandom\"",
        &["/dev/urandom", "not a regular file"],
    );
    c.edit(
        "path: mesh file empty name",
        "file = \"cube.msh\"",
        "file = \"\"",
        &["case.toml", "mesh.file is empty"],
    );
    c.edit(
        "path: mesh file is the case",
        "file = \"cube.msh\"",
        "file = \"case.toml\"",
        &["case.toml"],
    );
    c.push(
        "path: mesh file a FIFO",
        vec![
            (
                "case.toml",
                File::Bytes(replaced(BASE, "cube.msh", "pipe.msh").into_bytes()),
            ),
            ("pipe.msh", File::Fifo),
        ],
        &["check", "case.toml"],
        1,
        &["pipe.msh", "not a regular file"],
    );
}

fn arrays_of_three(c: &mut Catalogue) {
    for (name, from, to, kw) in [
        (
            "body force of four components",
            "value = [0.0, 0.0, -1.0]",
            "value = [0.0, 0.0, 0.0, -1.0]",
            "body_force[0].value",
        ),
        (
            "plane point of four numbers",
            "point = [-0.01, 0.0, 0.0]",
            "point = [-0.01, 0.0, 0.0, 1.0]",
            "obstacle[0].point",
        ),
        (
            "plane normal of four numbers",
            "normal = [1.0, 0.0, 0.0]",
            "normal = [1.0, 0.0, 0.0, 0.0]",
            "obstacle[0].normal",
        ),
        (
            "history point of four numbers",
            "point = [1.0, 1.0, 1.0]",
            "point = [1.0, 1.0, 1.0, 1.0]",
            "output.history[0].point",
        ),
        (
            "profile to of four numbers",
            "to = [1.0, 1.0, 1.0]",
            "to = [1.0, 1.0, 1.0, 1.0]",
            "output.profile[0].to",
        ),
        (
            "obstacle motion of four numbers",
            "normal = [1.0, 0.0, 0.0]",
            "normal = [1.0, 0.0, 0.0]\nmotion = [1.0, 0.0, 0.0, 0.0]",
            "obstacle[0].motion",
        ),
    ] {
        c.edit(name, from, to, &[kw, "invalid length 4", "3 numbers"]);
    }
}

/// The checkpoint the base case writes (`results/cube.checkpoint`), run
/// through the library.
fn base_checkpoint() -> Vec<u8> {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("case.toml"), BASE).unwrap();
    std::fs::write(
        dir.path().join("cube.msh"),
        read_data("cube_hex_41_ascii.msh"),
    )
    .unwrap();
    let options = signorini::run::RunOptions {
        threads: Some(1),
        ..Default::default()
    };
    let outcome = signorini::run::run(&dir.path().join("case.toml"), &options).unwrap();
    std::fs::read(outcome.output_dir.join("cube.checkpoint")).unwrap()
}

/// The checkpoint `good` read back, changed by `forge` and written again
/// by the checkpoint writer (so its checksum is right).
fn forged(
    good: &[u8],
    forge: impl FnOnce(&mut signorini::output::checkpoint::Checkpoint<'static>),
) -> Vec<u8> {
    use signorini::output::checkpoint;
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(checkpoint::path(dir.path(), "cube"), good).unwrap();
    let mut c = checkpoint::read(dir.path(), "cube").unwrap();
    forge(&mut c);
    let path = checkpoint::path(dir.path(), "cube");
    checkpoint::write(&path, &c).unwrap();
    std::fs::read(path).unwrap()
}

/// `run --restart old` on the base case (or `case`), the folder `old`
/// holding `cube.checkpoint` = `checkpoint` (no file: `None`).
fn restart_entry(
    c: &mut Catalogue,
    name: &str,
    case: String,
    checkpoint: Option<Vec<u8>>,
    kw: &[&str],
) {
    let mut files = vec![
        ("case.toml", File::Bytes(case.into_bytes())),
        ("cube.msh", File::Bytes(read_data("cube_hex_41_ascii.msh"))),
        ("old", File::Folder),
    ];
    if let Some(bytes) = checkpoint {
        files.push(("old/cube.checkpoint", File::Bytes(bytes)));
    }
    c.push(
        name,
        files,
        &["run", "case.toml", "--quiet", "--restart", "old"],
        1,
        kw,
    );
}

/// `--restart` (issue 15 item 3): no folder, no checkpoint, a file that is
/// not one, truncated, corrupted, of another version, of another case, and
/// an output folder other than the restart's.
fn restarts(c: &mut Catalogue) {
    let good = base_checkpoint();
    let base = || BASE.to_string();
    c.cli(
        "restart: no such folder",
        &["run", "case.toml", "--restart", "nowhere"],
        1,
        &["cannot restart from", "nowhere", "no such folder"],
    );
    restart_entry(
        c,
        "restart: no checkpoint",
        base(),
        None,
        &["/old'", "no cube.checkpoint", "no checkpoint in it"],
    );
    restart_entry(
        c,
        "restart: not a checkpoint",
        base(),
        Some(b"<?xml version=\"1.0\"?>".to_vec()),
        &["cube.checkpoint", "not a signorini checkpoint"],
    );
    // the first record (the whole state: magic, version, length, payload,
    // hash) cut or damaged; a later record cut short is a kill's torn
    // write, which a restart drops (src/output/checkpoint.rs tests)
    let length = u64::from_le_bytes(good[12..20].try_into().unwrap()) as usize;
    restart_entry(
        c,
        "restart: truncated",
        base(),
        Some(good[..20 + length / 2].to_vec()),
        &["cube.checkpoint", "truncated"],
    );
    let mut flipped = good.clone();
    flipped[20 + length / 2] ^= 0x10;
    restart_entry(
        c,
        "restart: corrupted",
        base(),
        Some(flipped),
        &["cube.checkpoint", "corrupted", "checksum"],
    );
    let mut future = good.clone();
    future[8] = 99;
    restart_entry(
        c,
        "restart: another format version",
        base(),
        Some(future),
        &["format version 99", "reads version 3"],
    );
    restart_entry(
        c,
        "restart: another case",
        replaced(BASE, "youngs_modulus = 100.0", "youngs_modulus = 200.0"),
        Some(good.clone()),
        &["cube.checkpoint", "physics", "changed", "from the start"],
    );
    restart_entry(
        c,
        "restart: another step",
        replaced(BASE, "end_time = 1.0", "end_time = 2.0"),
        Some(good.clone()),
        &[
            "step 1 is 'load' ending at t = 2",
            "t = 1 in the checkpoint",
        ],
    );
    // issue 31: a checkpoint whose state is NaN, its checksum right (the
    // file written by the checkpoint writer itself)
    restart_entry(
        c,
        "restart: a forged checkpoint with NaN state",
        base(),
        Some(forged(&good, |c| c.unknowns.to_mut()[0] = f64::NAN)),
        &[
            "cube.checkpoint",
            "state (the unknowns) is not finite",
            "from the start",
        ],
    );
    // the contact history and the stepping, checked by their own
    // `is_finite` (a NaN gap, an infinite force scale)
    restart_entry(
        c,
        "restart: a forged checkpoint with a NaN contact gap",
        base(),
        Some(forged(&good, |c| {
            c.contact.to_mut().interfaces[0][0].gap = f64::NAN
        })),
        &["cube.checkpoint", "contact history is not finite"],
    );
    restart_entry(
        c,
        "restart: a forged checkpoint with an infinite force scale",
        base(),
        Some(forged(&good, |c| {
            c.stepping.to_mut().force_scale = f64::INFINITY
        })),
        &["cube.checkpoint", "stepping state", "is not finite"],
    );
    // issue 31: the .pvd listed files that were gone (the checkpoint's
    // folder `old` holds no VTU file)
    restart_entry(
        c,
        "restart: its VTU files deleted",
        base(),
        Some(good.clone()),
        &[
            "VTU files it wrote are gone",
            "cube_0001.vtu",
            "put them back",
        ],
    );
    let mut files = vec![
        ("case.toml", File::Bytes(BASE.as_bytes().to_vec())),
        ("cube.msh", File::Bytes(read_data("cube_hex_41_ascii.msh"))),
        ("old", File::Folder),
    ];
    files.push(("old/cube.checkpoint", File::Bytes(good)));
    c.push(
        "restart: into another folder",
        files,
        &["run", "case.toml", "--restart", "old", "--output", "new"],
        1,
        &["'new'", "folder it resumes from", "--output"],
    );
}
