//! Messages in the user's words (issue 30, item 2), run through the binary
//! as a user meets them:
//! - every misspelling of a list — keys, model and shape names, other
//!   values, set names, obstacle, amplitude and interface names — gets a
//!   "did you mean" naming the right word (edit distance,
//!   `signorini::error::suggest`);
//! - the set names of a case on an `.inp` deck compare without regard to
//!   case, as Abaqus's do;
//! - a file that cannot be read is named by its key and its resolved
//!   (absolute) path.
//!
//! The bad-input catalogue (`tests/bad_inputs.rs`) checks that no message
//! names a Rust type.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The valid case of the bad-input catalogue on `cube.msh`.
const BASE: &str = include_str!("data/cube_case.toml");

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
}

/// `signorini check case.toml` in `dir`.
fn check(dir: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_signorini"))
        .args(["check", "case.toml"])
        .current_dir(dir)
        .output()
        .unwrap()
}

/// A folder with `case.toml` = `text` beside the cube mesh.
fn cube_case(text: &str) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("case.toml"), text).unwrap();
    std::fs::copy(data("cube_hex_41_ascii.msh"), dir.path().join("cube.msh")).unwrap();
    dir
}

/// `BASE` with `from` replaced by `to`, which must occur.
fn edited(from: &str, to: &str) -> String {
    assert!(BASE.contains(from), "'{from}' is not in the base case");
    BASE.replacen(from, to, 1)
}

/// (what is misspelt, text of the base case, its misspelling, the word the
/// message must suggest).
const MISSPELLINGS: [(&str, &str, &str, &str); 28] = [
    // keys
    (
        "top-level table",
        "[[material]]",
        "[[materail]]",
        "material",
    ),
    (
        "mesh key",
        "file = \"cube.msh\"",
        "flie = \"cube.msh\"",
        "file",
    ),
    (
        "material key",
        "poisson_ratio = 0.3",
        "poison_ratio = 0.3",
        "poisson_ratio",
    ),
    (
        "material key, transposed",
        "youngs_modulus = 100.0",
        "youngs_modlusu = 100.0",
        "youngs_modulus",
    ),
    (
        "material key, a letter short",
        "youngs_modulus = 100.0",
        "young_modulus = 100.0",
        "youngs_modulus",
    ),
    ("obstacle key", "normal = [1.0", "normall = [1.0", "normal"),
    (
        "pressure key",
        "surface = \"top\"",
        "surfce = \"top\"",
        "surface",
    ),
    (
        "contact key",
        "obstacle = \"wall\"",
        "obstcle = \"wall\"",
        "obstacle",
    ),
    ("step key", "end_time = 1.0", "end_tme = 1.0", "end_time"),
    (
        "step key, a letter short",
        "initial_increment = 0.5",
        "initial_incremnt = 0.5",
        "initial_increment",
    ),
    (
        "solver key",
        "max_iterations = 20",
        "max_iteration = 20",
        "max_iterations",
    ),
    ("output key", "name = \"cube\"", "nmae = \"cube\"", "name"),
    (
        "history key",
        "quantity = \"displacement_z\"",
        "quantiy = \"displacement_z\"",
        "quantity",
    ),
    ("profile key", "width = 10.0", "widht = 10.0", "width"),
    // model, shape and other values
    (
        "model name",
        "\"neo_hookean\"",
        "\"neo_hookian\"",
        "neo_hookean",
    ),
    (
        "model name, capitals",
        "\"neo_hookean\"",
        "\"Neo_Hookean\"",
        "neo_hookean",
    ),
    (
        "shape name",
        "shape = \"plane\"",
        "shape = \"plnae\"",
        "plane",
    ),
    (
        "history quantity",
        "\"displacement_z\"",
        "\"displacment_z\"",
        "displacement_z",
    ),
    (
        "contact method",
        "obstacle = \"wall\"",
        "obstacle = \"wall\"\nmethod = \"rockafeller\"",
        "rockafellar",
    ),
    (
        "solver predictor",
        "max_iterations = 20",
        "max_iterations = 20\npredictor = \"secnat\"",
        "secant",
    ),
    (
        "output field",
        "name = \"cube\"",
        "name = \"cube\"\nfields = [\"von_mise\"]",
        "von_mises",
    ),
    // set names of the mesh
    (
        "region name",
        "region = \"body\"",
        "region = \"bdy\"",
        "body",
    ),
    (
        "surface name",
        "surface = \"bottom\"",
        "surface = \"botom\"",
        "bottom",
    ),
    (
        "surface name, capitals (Gmsh)",
        "surface = \"top\"",
        "surface = \"Top\"",
        "top",
    ),
    (
        "contact surface name",
        "surface = \"contact\"",
        "surface = \"contcat\"",
        "contact",
    ),
    // obstacle, amplitude and interface names
    (
        "obstacle name",
        "obstacle = \"wall\"",
        "obstacle = \"wal\"",
        "wall",
    ),
    (
        "amplitude name",
        "value = 1.0",
        "value = 1.0\namplitude = \"rmap\"",
        "ramp",
    ),
    (
        "interface name",
        "interface = \"contact\"",
        "interface = \"contatc\"",
        "contact",
    ),
];

#[test]
fn every_misspelling_gets_the_right_word() {
    let failures: Vec<String> = MISSPELLINGS
        .iter()
        .filter_map(|&(what, from, to, right)| {
            let dir = cube_case(&edited(from, to));
            let out = check(dir.path());
            let stderr = String::from_utf8_lossy(&out.stderr).to_string();
            let hint = format!("did you mean '{right}'?");
            (out.status.code() != Some(1) || !stderr.contains(&hint))
                .then(|| format!("{what}: no \"{hint}\" in: {stderr}"))
        })
        .collect();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn a_name_far_from_every_other_gets_no_suggestion() {
    let dir = cube_case(&edited("region = \"body\"", "region = \"housing\""));
    let stderr = String::from_utf8_lossy(&check(dir.path()).stderr).to_string();
    assert!(stderr.contains("no volume region"), "{stderr}");
    assert!(!stderr.contains("did you mean"), "{stderr}");
}

/// The `inp-import` example's case with its set names in lower case: the
/// deck's `*ELSET BLOCK`, `*NSET SYMMETRY_X`, `*SURFACE TOP`, ….
#[test]
fn inp_set_names_compare_without_case() {
    let example = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/inp-import");
    let dir = tempfile::tempdir().unwrap();
    for file in ["block.inp", "block_nodes.inp"] {
        std::fs::copy(example.join(file), dir.path().join(file)).unwrap();
    }
    let case = std::fs::read_to_string(example.join("case.toml")).unwrap();
    let lower = ["BLOCK", "SYMMETRY_X", "SYMMETRY_Y", "TOP", "BOTTOM"]
        .iter()
        .fold(case.clone(), |text, name| {
            let quoted = format!("\"{name}\"");
            assert!(text.contains(&quoted), "{name} is not in the example");
            text.replace(&quoted, &format!("\"{}\"", name.to_lowercase()))
        });
    std::fs::write(dir.path().join("case.toml"), &lower).unwrap();
    let out = check(dir.path());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{stderr}");
    // a misspelt one still fails, with the deck's spelling suggested
    let wrong = lower.replacen("\"top\"", "\"topp\"", 1);
    std::fs::write(dir.path().join("case.toml"), wrong).unwrap();
    let stderr = String::from_utf8_lossy(&check(dir.path()).stderr).to_string();
    assert!(stderr.contains("did you mean 'TOP'?"), "{stderr}");
}

/// A missing file named by a key: the message names the key, its line and
/// the path the file was looked for at, absolute.
#[test]
fn a_missing_file_is_named_by_its_key_and_resolved_path() {
    let wall = "shape = \"plane\"\npoint = [-0.01, 0.0, 0.0]\nnormal = [1.0, 0.0, 0.0]";
    let cases = [
        (
            "mesh.file",
            "line 2",
            edited("\"cube.msh\"", "\"blok.msh\""),
            "blok.msh",
        ),
        (
            "obstacle[0].file",
            "line 26",
            edited(wall, "shape = \"stl\"\nfile = \"punch.stl\""),
            "punch.stl",
        ),
        (
            "obstacle[0].file",
            "line 26",
            edited(
                wall,
                "shape = \"gmsh\"\nfile = \"sub/tool.msh\"\nsurface = \"s\"",
            ),
            "sub/tool.msh",
        ),
    ];
    for (key, line, text, file) in cases {
        let dir = cube_case(&text);
        let out = check(dir.path());
        let stderr = String::from_utf8_lossy(&out.stderr).to_string();
        let resolved = std::fs::canonicalize(dir.path()).unwrap().join(file);
        let expected = format!("{line}: {key}: cannot read");
        assert_eq!(out.status.code(), Some(1), "{stderr}");
        assert!(stderr.contains(&expected), "no '{expected}' in: {stderr}");
        assert!(
            stderr.contains(&format!("'{}'", resolved.display())),
            "no '{}' in: {stderr}",
            resolved.display()
        );
    }
}

/// An `*INCLUDE` of a deck whose file is missing: the deck and line of the
/// `*INCLUDE`, and the included file's absolute path.
#[test]
fn a_missing_include_names_its_line_and_resolved_path() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::copy(data("inp/block.inp"), dir.path().join("block.inp")).unwrap();
    let case = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/inp-import/case.toml"),
    )
    .unwrap();
    std::fs::write(dir.path().join("case.toml"), case).unwrap();
    let stderr = String::from_utf8_lossy(&check(dir.path()).stderr).to_string();
    let resolved = std::fs::canonicalize(dir.path())
        .unwrap()
        .join("block_nodes.inp");
    assert!(stderr.contains("block.inp' at line 4"), "{stderr}");
    assert!(
        stderr.contains(&format!("'{}'", resolved.display())),
        "{stderr}"
    );
}
