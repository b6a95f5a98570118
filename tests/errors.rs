//! Bad input, through the command line as a user meets it: every case gets
//! a clear message naming the file, the line, the key or the entity, a
//! non-zero exit code, and no panic.

mod common;

use signorini::mesh::structured::box_mesh;
use signorini::mesh::ElementKind;
use std::path::Path;
use std::process::Command;

/// A valid case: a neo-Hookean cube compressed through `bottom`/`top`.
const CASE: &str = r#"
[mesh]
file = "cube.msh"

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

[[displacement]]
surface = "zmax"
z = -0.2

[[step]]
name = "press"
end_time = 1.0
initial_increment = 0.5
"#;

fn write_cube(dir: &Path) {
    let mesh = box_mesh(ElementKind::Hex8, [2, 2, 2], [1.0, 1.0, 1.0]);
    std::fs::write(dir.join("cube.msh"), common::msh22(&mesh)).unwrap();
}

/// Run `signorini <args>` in `dir`; return (exit code, stderr).
fn signorini(dir: &Path, args: &[&str]) -> (i32, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_signorini"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("runs");
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(!stderr.contains("panicked"), "panic: {stderr}");
    (out.status.code().unwrap_or(-1), stderr)
}

/// Write `case` (and the cube mesh) to a fresh folder, run `check` and `run`
/// and expect both to fail with every fragment in `expect`.
fn expect_failure(case: &str, expect: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    write_cube(dir.path());
    std::fs::write(dir.path().join("case.toml"), case).unwrap();
    for cmd in ["check", "run"] {
        let (code, err) = signorini(
            dir.path(),
            &[cmd, "case.toml", "--quiet"][..if cmd == "check" { 2 } else { 3 }],
        );
        assert_eq!(code, 1, "{cmd}: exit code {code}, stderr {err}");
        for e in expect {
            assert!(err.contains(e), "{cmd}: '{e}' not in: {err}");
        }
    }
}

#[test]
fn valid_case_checks_and_runs() {
    let dir = tempfile::tempdir().unwrap();
    write_cube(dir.path());
    std::fs::write(dir.path().join("case.toml"), CASE).unwrap();
    let (code, err) = signorini(dir.path(), &["check", "case.toml"]);
    assert_eq!(code, 0, "{err}");
    let (code, err) = signorini(
        dir.path(),
        &["run", "case.toml", "--quiet", "--threads", "1"],
    );
    assert_eq!(code, 0, "{err}");
    assert!(dir.path().join("results/summary.json").exists());
}

#[test]
fn missing_case_file() {
    let dir = tempfile::tempdir().unwrap();
    let (code, err) = signorini(dir.path(), &["run", "nothing.toml"]);
    assert_eq!(code, 1);
    assert!(
        err.contains("nothing.toml") && err.contains("cannot read case file"),
        "{err}"
    );
}

#[test]
fn missing_mesh_file() {
    expect_failure(&CASE.replace("cube.msh", "absent.msh"), &["absent.msh"]);
}

#[test]
fn malformed_mesh_says_where() {
    let dir = tempfile::tempdir().unwrap();
    write_cube(dir.path());
    let text = std::fs::read_to_string(dir.path().join("cube.msh")).unwrap();
    // damage the 3rd node line
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    let at = lines.iter().position(|l| l == "$Nodes").unwrap() + 4;
    lines[at] = "3 0.5 zero 0.0".into();
    std::fs::write(dir.path().join("cube.msh"), lines.join("\n")).unwrap();
    std::fs::write(dir.path().join("case.toml"), CASE).unwrap();
    let (code, err) = signorini(dir.path(), &["check", "case.toml"]);
    assert_eq!(code, 1);
    assert!(
        err.contains("cube.msh") && err.contains(&format!("line {}", at + 1)),
        "{err}"
    );
}

#[test]
fn unknown_group_lists_the_available_ones() {
    expect_failure(
        &CASE.replace("surface = \"zmax\"", "surface = \"lid\""),
        &["displacement[1].surface", "'lid'", "zmax", "xmin"],
    );
    expect_failure(
        &CASE.replace("region = \"body\"", "region = \"rubber\""),
        &["'rubber'", "body"],
    );
}

#[test]
fn misspelled_key_names_its_path() {
    expect_failure(
        &CASE.replace("poisson_ratio", "poison_ratio"),
        &["material[0]", "poison_ratio", "line 9"],
    );
    expect_failure(&CASE.replace("[[step]]", "[[steps]]"), &["steps"]);
}

#[test]
fn material_parameter_out_of_range() {
    expect_failure(
        &CASE.replace("poisson_ratio = 0.3", "poisson_ratio = 0.5"),
        &["material[0].poisson_ratio", "0.5"],
    );
    expect_failure(
        &CASE.replace("youngs_modulus = 100.0", "youngs_modulus = -1.0"),
        &["material[0].youngs_modulus"],
    );
}

#[test]
fn inverted_element_is_named() {
    let dir = tempfile::tempdir().unwrap();
    let mut mesh = box_mesh(ElementKind::Tet4, [1, 1, 1], [1.0, 1.0, 1.0]);
    mesh.elements[3].nodes.swap(1, 2);
    std::fs::write(dir.path().join("cube.msh"), common::msh22(&mesh)).unwrap();
    std::fs::write(dir.path().join("case.toml"), CASE).unwrap();
    let (code, err) = signorini(dir.path(), &["check", "case.toml"]);
    assert_eq!(code, 1);
    // msh22 numbers surface facets first, then the volume elements
    let facets: usize = mesh.surfaces.iter().map(|s| s.facets.len()).sum();
    let id = facets + 4;
    assert!(
        err.contains(&format!("element {id}")) && err.contains("inverted"),
        "{err}"
    );
}

/// Newton failing after all cuts: the converged increments of the first
/// step stay on disk, the summary says `failed`, the exit code is 1.
#[test]
fn no_convergence_keeps_converged_steps() {
    let case = CASE.replace(
        "[[step]]\nname = \"press\"\nend_time = 1.0\ninitial_increment = 0.5\n",
        "[amplitudes]\ncrush = [[0.0, 0.0], [1.0, 1.0], [2.0, 6.0]]\n\n[[step]]\nname = \"press\"\nend_time = 1.0\ninitial_increment = 0.5\n\n[[step]]\nname = \"crush\"\nend_time = 2.0\ninitial_increment = 1.0\n\n[solver]\nmax_cuts = 3\n",
    )
    .replace("z = -0.2\n", "z = -0.2\namplitude = \"crush\"\n")
    // confined compression (no lateral escape, no flipping over) past the
    // cube's height: impossible, so Newton must fail
    .replace(
        "[[step]]\nname = \"press\"",
        "[[displacement]]\nsurface = \"xmin\"\nx = 0.0\n\n[[displacement]]\nsurface = \"xmax\"\nx = 0.0\n\n\
         [[displacement]]\nsurface = \"ymin\"\ny = 0.0\n\n[[displacement]]\nsurface = \"ymax\"\ny = 0.0\n\n[[step]]\nname = \"press\"",
    );
    let dir = tempfile::tempdir().unwrap();
    write_cube(dir.path());
    std::fs::write(dir.path().join("case.toml"), case).unwrap();
    let (code, err) = signorini(dir.path(), &["run", "case.toml", "--quiet"]);
    assert_eq!(code, 1, "{err}");
    assert!(
        err.contains("step 'crush'") && err.contains("did not converge"),
        "{err}"
    );
    let summary: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(dir.path().join("results/summary.json")).unwrap(),
    )
    .unwrap();
    assert_eq!(summary["status"], "failed");
    let increments = summary["increments"].as_array().unwrap();
    assert!(increments.len() >= 2, "the press step converged");
    for inc in increments {
        let file = inc["file"].as_str().unwrap();
        assert!(dir.path().join("results").join(file).exists(), "{file}");
    }
    let pvd = std::fs::read_to_string(dir.path().join("results/case.pvd")).unwrap();
    // the increments and the reference state (t = 0)
    assert_eq!(pvd.matches("<DataSet").count(), increments.len() + 1);
}

/// `signorini check` on `case` (with the cube mesh): success and stdout.
fn check_stdout(case: &str) -> (bool, String) {
    let dir = tempfile::tempdir().unwrap();
    write_cube(dir.path());
    std::fs::write(dir.path().join("case.toml"), case).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_signorini"))
        .args(["check", "case.toml"])
        .current_dir(dir.path())
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    (out.status.success(), stdout)
}

#[test]
fn check_prints_what_was_read() {
    let (success, stdout) = check_stdout(CASE);
    assert!(success, "{stdout}");
    // 2×2×2 Hex8 cube: 27 nodes, 8 elements, 81 dofs
    for expected in [
        "nodes     27",
        "elements  8",
        "dofs      81",
        "body",
        "zmax",
        "press",
    ] {
        assert!(stdout.contains(expected), "'{expected}' not in:\n{stdout}");
    }
}

#[test]
fn region_without_material() {
    let dir = tempfile::tempdir().unwrap();
    let mut mesh = box_mesh(ElementKind::Hex8, [2, 2, 2], [1.0, 1.0, 1.0]);
    // split "body" into "lower" and "upper" halves
    let (lower, upper): (Vec<usize>, Vec<usize>) = (0..mesh.elements.len()).partition(|&e| {
        mesh.elements[e]
            .nodes
            .iter()
            .map(|&n| mesh.nodes[n][2])
            .sum::<f64>()
            < 4.0
    });
    mesh.regions = vec![
        signorini::mesh::Region {
            name: "lower".into(),
            elements: lower,
        },
        signorini::mesh::Region {
            name: "upper".into(),
            elements: upper,
        },
    ];
    std::fs::write(dir.path().join("cube.msh"), common::msh22(&mesh)).unwrap();
    std::fs::write(
        dir.path().join("case.toml"),
        CASE.replace("region = \"body\"", "region = \"lower\""),
    )
    .unwrap();
    let (code, err) = signorini(dir.path(), &["check", "case.toml"]);
    assert_eq!(code, 1);
    assert!(
        err.contains("(region upper) has no material") && err.contains("region = \"upper\""),
        "{err}"
    );
}

#[test]
fn other_case_errors_name_their_key() {
    // two materials on one region
    expect_failure(
        &CASE.replace(
            "[[displacement]]\nsurface = \"zmin\"",
            "[[material]]\nregion = \"body\"\nmodel = \"saint_venant_kirchhoff\"\nyoungs_modulus = 1.0\npoisson_ratio = 0.2\n\n[[displacement]]\nsurface = \"zmin\"",
        ),
        &["material[1].region", "already has the material of material[0]"],
    );
    expect_failure(
        &CASE.replace("z = -0.2\n", "z = -0.2\namplitude = \"slow\"\n"),
        &["displacement[1].amplitude", "no amplitude named 'slow'"],
    );
    expect_failure(
        &CASE.replace("model = \"neo_hookean\"", "model = \"ogden\""),
        &["material[0].youngs_modulus does not apply to model 'ogden'"],
    );
    expect_failure(
        &CASE.replace("end_time = 1.0", "end_time = -1.0"),
        &["step[0].end_time"],
    );
}

/// The cube of `CASE` resting on a plane at z = 0, with `obstacle` replaced
/// by the given table body.
fn contact_case(obstacle: &str, contact_surface: &str) -> String {
    format!(
        "{CASE}\n[[obstacle]]\nname = \"floor\"\n{obstacle}\n\n[[contact]]\nsurface = \"{contact_surface}\"\nobstacle = \"floor\"\n"
    )
    .replace("[[displacement]]\nsurface = \"zmin\"\nx = 0.0\ny = 0.0\nz = 0.0\n", "[[displacement]]\nsurface = \"xmin\"\nx = 0.0\n")
}

#[test]
fn contact_input_errors() {
    let plane = "shape = \"plane\"\npoint = [0.0, 0.0, 0.0]\nnormal = [0.0, 0.0, 1.0]";
    // the valid case checks
    let dir = tempfile::tempdir().unwrap();
    write_cube(dir.path());
    std::fs::write(dir.path().join("case.toml"), contact_case(plane, "zmin")).unwrap();
    let (code, err) = signorini(dir.path(), &["check", "case.toml"]);
    assert_eq!(code, 0, "{err}");
    // a contact surface the mesh lacks
    expect_failure(
        &contact_case(plane, "sole"),
        &["contact[0].surface", "'sole'", "zmin"],
    );
    // a zero normal, a non-positive radius
    expect_failure(
        &contact_case(&plane.replace("[0.0, 0.0, 1.0]", "[0.0, 0.0, 0.0]"), "zmin"),
        &["obstacle[0]", "normal"],
    );
    expect_failure(
        &contact_case(
            "shape = \"sphere\"\ncenter = [0.5, 0.5, -2.0]\nradius = -1.0",
            "zmin",
        ),
        &["obstacle[0]", "radius"],
    );
    // an STL that cannot be read
    expect_failure(
        &contact_case("shape = \"stl\"\nfile = \"punch.stl\"", "zmin"),
        &["punch.stl"],
    );
    // the surface starts inside the obstacle (the plane raised into the cube)
    expect_failure(
        &contact_case(
            &plane.replace("point = [0.0, 0.0, 0.0]", "point = [0.0, 0.0, 0.2]"),
            "zmin",
        ),
        &["contact[0]", "starts inside obstacle 'floor'", "gap"],
    );
    // an obstacle name that does not exist
    expect_failure(
        &contact_case(plane, "zmin").replace("obstacle = \"floor\"\n", "obstacle = \"ground\"\n"),
        &["contact[0].obstacle", "'ground'", "floor"],
    );
}

#[test]
fn friction_input_errors() {
    let plane = "shape = \"plane\"\npoint = [0.0, 0.0, 0.0]\nnormal = [0.0, 0.0, 1.0]";
    let with = |keys: &str| format!("{}{keys}\n", contact_case(plane, "zmin"));
    // a valid frictional interface checks
    let dir = tempfile::tempdir().unwrap();
    write_cube(dir.path());
    std::fs::write(
        dir.path().join("case.toml"),
        with("friction_coefficient = 0.3\ntangential_penalty = 1e3"),
    )
    .unwrap();
    let (code, err) = signorini(dir.path(), &["check", "case.toml"]);
    assert_eq!(code, 0, "{err}");
    // a negative coefficient
    expect_failure(
        &with("friction_coefficient = -0.1"),
        &[
            "contact[0].friction_coefficient",
            "-0.1",
            "zero or positive",
        ],
    );
    // a tangential penalty without friction, or not positive
    expect_failure(
        &with("tangential_penalty = 1e3"),
        &[
            "contact[0].tangential_penalty",
            "without",
            "friction_coefficient",
        ],
    );
    expect_failure(
        &with("friction_coefficient = 0.3\ntangential_penalty = 0.0"),
        &["contact[0].tangential_penalty", "must be positive"],
    );
    // an unknown nonsymmetric solver
    expect_failure(
        &format!(
            "{}\n[solver]\nnonsymmetric = \"bicgstab\"\n",
            with("friction_coefficient = 0.3")
        ),
        &["solver.nonsymmetric", "bicgstab"],
    );
}

/// `contact_case` on `zmin` with `output` appended (history and profile
/// tables).
fn output_case(output: &str) -> String {
    let plane = "shape = \"plane\"\npoint = [0.0, 0.0, 0.0]\nnormal = [0.0, 0.0, 1.0]";
    format!("{}\n{output}\n", contact_case(plane, "zmin"))
}

#[test]
fn history_and_profile_input_errors() {
    let profile = "[[output.profile]]\nname = \"line\"\ninterface = \"zmin\"\nfrom = [0.0, 0.5, 0.0]\nto = [1.0, 0.5, 0.0]\nwidth = 0.01";
    let history = "[[output.history]]\nname = \"lift\"\npoint = [0.5, 0.5, 0.0]\nquantity = \"gap\"\ninterface = \"zmin\"";
    // the valid ones check, and name their nodes
    let (success, stdout) = check_stdout(&output_case(&format!("{history}\n\n{profile}")));
    assert!(success, "{stdout}");
    // the centre of the cube's bottom, and the 3 bottom nodes on y = 0.5
    assert!(
        stdout.contains("history   lift: gap at node") && stdout.contains("(0.5, 0.5, 0)"),
        "{stdout}"
    );
    assert!(
        stdout.contains("profile   line: 3 nodes of interface 'zmin'"),
        "{stdout}"
    );
    // unknown interface
    expect_failure(
        &output_case(&profile.replace("interface = \"zmin\"", "interface = \"sole\"")),
        &["output.profile[0].interface", "'sole'", "zmin"],
    );
    expect_failure(
        &output_case(&history.replace("interface = \"zmin\"", "interface = \"sole\"")),
        &["output.history[0].interface", "'sole'"],
    );
    // zero-length segment
    expect_failure(
        &output_case(&profile.replace("to = [1.0, 0.5, 0.0]", "to = [0.0, 0.5, 0.0]")),
        &["output.profile[0]", "same point", "positive length"],
    );
    // non-positive width
    for width in ["0.0", "-1.0"] {
        expect_failure(
            &output_case(&profile.replace("width = 0.01", &format!("width = {width}"))),
            &["output.profile[0].width", "must be positive"],
        );
    }
    // a band with no node in it
    expect_failure(
        &output_case(
            &profile
                .replace("[0.0, 0.5, 0.0]", "[0.0, 0.5, 0.7]")
                .replace("[1.0, 0.5, 0.0]", "[1.0, 0.5, 0.7]"),
        ),
        &["output.profile[0]", "no secondary node", "widen the band"],
    );
    // unknown quantity: serde names the key and the choices
    expect_failure(
        &output_case(&history.replace("quantity = \"gap\"", "quantity = \"lift\"")),
        &[
            "output.history[0].quantity",
            "unknown variant",
            "displacement_z",
        ],
    );
    // gap without an interface; a displacement with one
    expect_failure(
        &output_case(&history.replace("\ninterface = \"zmin\"", "")),
        &["output.history[0].interface is required"],
    );
    expect_failure(
        &output_case(&history.replace("quantity = \"gap\"", "quantity = \"displacement_z\"")),
        &["output.history[0].interface applies to gap"],
    );
    // a reaction force needs a surface set, and takes no point
    let reaction =
        "[[output.history]]\nname = \"push\"\nquantity = \"reaction_force\"\nsurface = \"zmin\"";
    let (success, stdout) = check_stdout(&output_case(reaction));
    assert!(success, "{stdout}");
    assert!(
        stdout.contains("history   push: reaction_force on surface 'zmin'"),
        "{stdout}"
    );
    expect_failure(
        &output_case(&reaction.replace("surface = \"zmin\"", "")),
        &["output.history[0].surface is required"],
    );
    expect_failure(
        &output_case(&format!("{reaction}\npoint = [0.0, 0.0, 0.0]")),
        &["output.history[0].point does not apply to reaction_force"],
    );
    expect_failure(
        &output_case(&history.replace("\ninterface", "\nsurface = \"zmin\"\ninterface")),
        &["output.history[0].surface applies to reaction_force only"],
    );
    // two outputs with one name
    expect_failure(
        &output_case(&format!(
            "{history}\n\n{}",
            profile.replace("\"line\"", "\"lift\"")
        )),
        &["output.profile[0].name = 'lift' is already used"],
    );
}

#[test]
fn keys_of_another_shape_or_model_are_errors() {
    let plane = "shape = \"plane\"\npoint = [0.0, 0.0, 0.0]\nnormal = [0.0, 0.0, 1.0]";
    // a plane with a radius: the line of the key, the key path and the fix
    let case = contact_case(&format!("{plane}\nradius = 1.0"), "zmin");
    let line = case.lines().position(|l| l.starts_with("radius")).unwrap() + 1;
    expect_failure(
        &case,
        &[
            &format!("line {line}:"),
            "obstacle[0].radius does not apply to shape 'plane'",
            "remove it",
        ],
    );
    // a sphere without its radius
    expect_failure(
        &contact_case("shape = \"sphere\"\ncenter = [0.5, 0.5, -2.0]", "zmin"),
        &["obstacle[0].radius is required for shape 'sphere'"],
    );
    // a neo-Hookean material with an Ogden exponent
    let case = CASE.replace("poisson_ratio = 0.3", "poisson_ratio = 0.3\nalpha = [2.0]");
    let line = case.lines().position(|l| l.starts_with("alpha")).unwrap() + 1;
    expect_failure(
        &case,
        &[
            &format!("line {line}:"),
            "material[0].alpha does not apply to model 'neo_hookean'",
        ],
    );
    // a wrong type inside a tagged table still names its key and line
    let case = CASE.replace("poisson_ratio = 0.3", "poisson_ratio = \"0.3\"");
    let line = case.lines().position(|l| l.starts_with("poisson")).unwrap() + 1;
    expect_failure(
        &case,
        &[
            &format!("line {line}:"),
            "material[0].poisson_ratio",
            "expected a number",
        ],
    );
    // an unknown model names the model key
    expect_failure(
        &CASE.replace("\"neo_hookean\"", "\"mooney_rivlin\""),
        &[
            "material[0].model",
            "unknown variant `mooney_rivlin`",
            "ogden",
        ],
    );
}

/// Errors found after parsing (a name that refers to nothing, a value out
/// of range) name the case file's line of their key path, as parse errors
/// do (issue 15 item 7): the line of `obstacle = "nowhere"`, and of a
/// step's `max_increment`.
#[test]
fn errors_after_parsing_name_the_line_of_their_key() {
    let dir = tempfile::tempdir().unwrap();
    let base = common::stacked_blocks_case(
        "model = \"linear_elastic\"\nyoungs_modulus = 50.0\npoisson_ratio = 0.3",
        "",
    );
    std::fs::write(
        dir.path().join("blocks.msh"),
        common::msh22(&common::stacked_blocks_mesh()),
    )
    .unwrap();
    let line_of =
        |text: &str, needle: &str| text.lines().position(|l| l.starts_with(needle)).unwrap() + 1;
    let text = base.replace("primary = \"lower.zmax\"", "obstacle = \"nowhere\"");
    let line = line_of(&text, "obstacle = \"nowhere\"");
    common::assert_case_error(
        dir.path(),
        &text,
        &[&format!(
            "line {line}: contact[0].obstacle: no [[obstacle]] named 'nowhere'"
        )],
    );
    let text = base.replace(
        "end_time = 1.0\n",
        "end_time = 1.0\ninitial_increment = 0.5\nmin_increment = 0.25\nmax_increment = 0.1\n",
    );
    let line = line_of(&text, "max_increment = 0.1");
    common::assert_case_error(
        dir.path(),
        &text,
        &[&format!(
            "line {line}: step[0].max_increment = 0.1 is smaller"
        )],
    );
}

/// `signorini check` refuses what the run refuses when choosing its path:
/// `strategy = "condensed"` on a case it does not apply to (finite-strain
/// material, no contact) fails both with the reason and the fix.
#[test]
fn check_refuses_a_condensed_strategy_that_does_not_apply() {
    expect_failure(
        &format!("{CASE}\n[solver]\nstrategy = \"condensed\"\n"),
        &[
            "solver.strategy = \"condensed\" does not apply",
            "there is no contact",
            "use strategy = \"auto\"",
        ],
    );
}
