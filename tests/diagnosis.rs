//! Diagnosis of non-convergence from its cause (issue 14 item 3): each
//! cause gets its own message with the fix — `signorini check` warns of
//! implausible material and load scales and of incompressibility locking
//! (and a run prints the warnings at its start and names them as the
//! likely cause when it fails); an obstacle whose normal points away from
//! the body and a surface paired with itself are input errors at `check`;
//! a body that loses every contact is told so. Each case runs the binary
//! on the 27-element cube of `tests/bad_inputs.rs` and asserts the exit
//! code and the key words.

mod common;

use signorini::mesh::structured::box_mesh;
use signorini::mesh::ElementKind;
use std::path::Path;
use std::process::Command;

/// The valid cube case of the bad-input catalogue.
const BASE: &str = include_str!("data/cube_case.toml");

/// What the binary said: exit code, stdout, stderr.
struct Said {
    code: i32,
    out: String,
    err: String,
}

/// Run `signorini ARGS` in `dir`.
fn signorini(dir: &Path, args: &[&str]) -> Said {
    let out = Command::new(env!("CARGO_BIN_EXE_signorini"))
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap();
    let said = Said {
        code: out.status.code().unwrap_or(-1),
        out: String::from_utf8_lossy(&out.stdout).into_owned(),
        err: String::from_utf8_lossy(&out.stderr).into_owned(),
    };
    assert!(!said.err.contains("panicked"), "{}", said.err);
    said
}

/// A folder with the cube mesh and `case.toml` = `BASE` with `from`
/// replaced by `to`.
fn cube_case(from: &str, to: &str) -> tempfile::TempDir {
    assert!(BASE.contains(from), "'{from}' is not in the base case");
    let dir = tempfile::tempdir().unwrap();
    let mesh = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/cube_hex_41_ascii.msh");
    std::fs::copy(mesh, dir.path().join("cube.msh")).unwrap();
    std::fs::write(dir.path().join("case.toml"), BASE.replacen(from, to, 1)).unwrap();
    dir
}

#[track_caller]
fn assert_has(text: &str, words: &[&str]) {
    for w in words {
        assert!(text.contains(w), "'{w}' missing in:\n{text}");
    }
}

/// A warning of `check` (exit 0, the case is valid) that a run repeats at
/// its start and, as it fails (exit 1), names as the likely cause.
#[track_caller]
fn assert_warned_and_blamed(from: &str, to: &str, words: &[&str]) {
    let dir = cube_case(from, to);
    let check = signorini(dir.path(), &["check", "case.toml"]);
    assert_eq!(check.code, 0, "{}", check.err);
    assert_has(&check.out, words);
    let run = signorini(dir.path(), &["run", "case.toml", "--output", "out"]);
    assert_eq!(run.code, 1, "{}\n{}", run.out, run.err);
    // told at the start of the run (the log holds what the terminal shows)
    let log = std::fs::read_to_string(dir.path().join("out/cube.log")).unwrap();
    let first_iteration = log.find("  step 'load' t = ").unwrap_or(log.len());
    let warnings: String = log[..first_iteration]
        .lines()
        .filter(|l| l.contains("warning: "))
        .collect();
    assert_has(&warnings, words);
    assert_has(&run.err, &["did not converge", "likely cause: "]);
    assert_has(&run.err, words);
}

/// The base case is plausible: `check` warns of nothing.
#[test]
fn a_plausible_case_has_no_warning() {
    let dir = cube_case("", "");
    let check = signorini(dir.path(), &["check", "case.toml"]);
    assert_eq!(check.code, 0, "{}", check.err);
    assert!(!check.out.contains("warning"), "{}", check.out);
}

/// Every example is plausible too (no false alarm on a real model).
#[test]
fn no_example_is_warned_about() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    for entry in std::fs::read_dir(&root).unwrap() {
        let case = entry.unwrap().path().join("case.toml");
        if !case.exists() {
            continue;
        }
        let check = signorini(&root, &["check", case.to_str().unwrap()]);
        assert_eq!(check.code, 0, "{}: {}", case.display(), check.err);
        assert!(
            !check.out.contains("warning"),
            "{}: {}",
            case.display(),
            check.out
        );
    }
}

/// E = 1e300: forces and stiffnesses overflow; the run ends on a
/// non-finite residual, blamed on the material's scale, with the fix
/// (other units).
#[test]
fn a_huge_youngs_modulus_is_an_implausible_material_scale() {
    assert_warned_and_blamed(
        "youngs_modulus = 100.0",
        "youngs_modulus = 1e300",
        &["implausible material scale", "1.000e300", "units"],
    );
}

/// E = 1e-300: the pressure of 1 strains the body by ~1e300.
#[test]
fn a_tiny_youngs_modulus_is_an_implausible_load_scale() {
    assert_warned_and_blamed(
        "youngs_modulus = 100.0",
        "youngs_modulus = 1e-300",
        &[
            "implausible material scale",
            "implausible load scale",
            "check the units of the load",
        ],
    );
}

/// A pressure of 1e300 on E = 100: a strain of ~1e298.
#[test]
fn a_huge_pressure_is_an_implausible_load_scale() {
    assert_warned_and_blamed(
        "value = 1.0",
        "value = 1e300",
        &[
            "implausible load scale",
            "the pressure 1.000e300 on surface 'top'",
            "E·L² = 3.000e2",
        ],
    );
}

/// ν = 0.4999999999 on Hex8: volumetric locking, and the fix (ν ≤ 0.49).
#[test]
fn nearly_incompressible_linear_elements_lock() {
    assert_warned_and_blamed(
        "poisson_ratio = 0.3",
        "poisson_ratio = 0.4999999999",
        &[
            "incompressibility locking",
            "ν = 0.4999999999",
            "use ν ≤ 0.49",
        ],
    );
}

/// A prescribed displacement of 6 on a body of size √3, half of it in the
/// first increment: a strain of ~1.7 at once; `check` says to take a smaller first
/// increment (the run itself may still manage).
#[test]
fn a_first_increment_straining_the_body_beyond_one_is_warned() {
    let dir = cube_case(
        "[[pressure]]",
        "[[displacement]]\nsurface = \"top\"\nz = -6.0\n\n[[pressure]]",
    );
    let check = signorini(dir.path(), &["check", "case.toml"]);
    assert_eq!(check.code, 0, "{}", check.err);
    assert_has(
        &check.out,
        &[
            "first increment too large",
            "prescribed displacement 6.000e0 on 'top'",
            "initial_increment",
        ],
    );
}

/// A plane obstacle whose normal points away from the body: the whole body
/// is behind it; an input error naming the flipped normal (a plane raised
/// into the body, with part of it in front, keeps the message of a node
/// starting inside: `tests/errors.rs`).
#[test]
fn an_obstacle_normal_pointing_away_is_an_input_error() {
    let dir = cube_case("normal = [1.0, 0.0, 0.0]", "normal = [-1.0, 0.0, 0.0]");
    let check = signorini(dir.path(), &["check", "case.toml"]);
    assert_eq!(check.code, 1, "{}", check.out);
    assert_has(
        &check.err,
        &[
            "contact[0]",
            "obstacle normal pointing away",
            "the whole body is behind plane 'wall'",
            "flip it: normal = [1, 0, 0]",
        ],
    );
}

/// A contact whose primary surface is the secondary one under another
/// name (two physical groups of the same facets): an input error.
#[test]
fn a_self_paired_surface_is_an_input_error() {
    let mut mesh = box_mesh(ElementKind::Hex8, [2, 2, 2], [1.0, 1.0, 1.0]);
    let mut again = mesh.surface("zmax").unwrap().clone();
    again.name = "top_again".into();
    mesh.surfaces.push(again);
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("box.msh"), common::msh22(&mesh)).unwrap();
    std::fs::write(
        dir.path().join("case.toml"),
        r#"[mesh]
file = "box.msh"

[[material]]
region = "body"
model = "neo_hookean"
youngs_modulus = 100.0
poisson_ratio = 0.3

[[displacement]]
surface = "zmin"
x = 0.0
y = 0.0
z = 0.0

[[contact]]
surface = "zmax"
primary = "top_again"

[[step]]
name = "load"
end_time = 1.0
"#,
    )
    .unwrap();
    let check = signorini(dir.path(), &["check", "case.toml"]);
    assert_eq!(check.code, 1, "{}", check.out);
    assert_has(
        &check.err,
        &[
            "contact[0]",
            "self-paired surface",
            "'zmax' is also on the primary surface 'top_again'",
            "the surface of the other body",
        ],
    );
}

/// The cube without its support, pushed by a pressure away from the wall
/// it does not touch: every contact node open, nothing holds it. The run
/// fails with "loss of contact" and the fixes (a support, start touching),
/// not with a generic rigid-body text; no warning applies.
#[test]
fn a_body_held_by_nothing_but_an_open_contact_is_a_loss_of_contact() {
    let dir = cube_case(
        "[[displacement]]\nsurface = \"bottom\"\nx = 0.0\ny = 0.0\nz = 0.0\n",
        "",
    );
    let run = signorini(dir.path(), &["run", "case.toml", "--output", "out"]);
    assert_eq!(run.code, 1, "{}", run.err);
    assert_has(
        &run.err,
        &[
            "loss of contact",
            "every contact node is open",
            "hold the body with a [[displacement]]",
        ],
    );
    assert!(!run.err.contains("likely cause"), "{}", run.err);
}
