//! `[[displacement]] rotation`: a prescribed finite rotation of a node set
//! (Rodrigues), checked against the rigid-body motion it must produce, and
//! its input errors.

use signorini::output::{ConvergedIncrement, StepObserver, Summary};
use signorini::problem::{rotation_displacement, rotation_matrix};
use signorini::run::{RunOptions, Simulation};
use std::path::Path;

/// The final displacement and element Cauchy stresses of a run.
#[derive(Default)]
struct Last {
    displacement: Vec<f64>,
    largest_stress: f64,
}

impl StepObserver for Last {
    fn on_increment(&mut self, inc: &ConvergedIncrement, _: &Summary) -> signorini::Result<()> {
        self.displacement = inc.displacement().to_vec();
        self.largest_stress = inc
            .element_stresses()
            .iter()
            .flat_map(|s| s.iter().copied())
            .fold(0.0, |m, v| m.max(v.abs()));
        Ok(())
    }
}

const AXIS: [f64; 3] = [0.3, -0.5, 1.0];
const CENTRE: [f64; 3] = [0.5, 0.4, 0.2];
const TRANSLATION: [f64; 3] = [0.1, 0.2, -0.3];

/// The unit cube of 3 × 3 × 3 Hex8 with `rotation` (a TOML inline table's
/// keys) on its faces `bottom` and `top`, Saint Venant–Kirchhoff.
fn cube_case(rotation: &str, extra: &str) -> String {
    let d = |surface: &str| {
        format!(
            "[[displacement]]\nsurface = \"{surface}\"\nx = {}\ny = {}\nz = {}\nrotation = {{ {rotation} }}\n",
            TRANSLATION[0], TRANSLATION[1], TRANSLATION[2]
        )
    };
    format!(
        "[mesh]\nfile = \"cube_hex_41_ascii.msh\"\n\n\
         [[material]]\nregion = \"body\"\nmodel = \"saint_venant_kirchhoff\"\n\
         youngs_modulus = 100.0\npoisson_ratio = 0.3\n\n{}{}{extra}\n\
         [[step]]\nname = \"turn\"\nend_time = 1.0\ninitial_increment = 0.25\nmax_increment = 0.25\n\n\
         [solver]\nresidual_tolerance = 1e-12\n",
        d("bottom"),
        d("top")
    )
}

fn data() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data")
}

/// A Saint Venant–Kirchhoff cube whose two opposite faces are turned by
/// 90° about a skew axis and translated, in four increments: the solution
/// is the rigid motion `u = (R − I)(X − c) + t` at every node (the faces'
/// prescribed motion extended to the body; analytic reference), to 1e-10
/// of the cube's size, and the stress vanishes to 1e-10 E (SVK is frame
/// indifferent: `E = 0` under a rotation of any size).
#[test]
fn a_rigid_quarter_turn_leaves_the_body_unstressed() {
    let rotation = format!("axis = {AXIS:?}, centre = {CENTRE:?}, angle = 90.0");
    let text = cube_case(&rotation, "");
    let mut simulation = Simulation::from_toml(&text, &data()).unwrap();
    let mut last = Last::default();
    let options = RunOptions {
        output: None,
        threads: Some(1),
        cancel: None,
        restart: None,
    };
    simulation.run(&options, &mut last).unwrap();
    let r = rotation_matrix(AXIS, std::f64::consts::FRAC_PI_2);
    let nodes = &simulation.problem().model.mesh.nodes;
    let mut worst = 0.0f64;
    for (n, &x) in nodes.iter().enumerate() {
        let exact = rotation_displacement(&r, CENTRE, x);
        for i in 0..3 {
            worst = worst.max((last.displacement[3 * n + i] - exact[i] - TRANSLATION[i]).abs());
        }
    }
    assert!(
        worst < 1e-10,
        "displacement off the rigid motion by {worst:.3e}"
    );
    assert!(
        last.largest_stress < 1e-10 * 100.0,
        "largest stress {:.3e}",
        last.largest_stress
    );
}

/// The errors: a zero axis, and a node of the rotated set prescribed again
/// by another `[[displacement]]` (the face `contact` is `top`).
#[test]
fn a_zero_axis_and_a_conflicting_component_are_errors_in_words() {
    let zero = cube_case("axis = [0, 0, 0], centre = [0, 0, 0], angle = 10", "");
    let error = Simulation::from_toml(&zero, &data())
        .err()
        .unwrap()
        .to_string();
    assert!(
        error.contains("displacement[0].rotation.axis") && error.contains("non-zero axis"),
        "{error}"
    );
    let conflict = cube_case(
        "axis = [0, 0, 1], centre = [0, 0, 0], angle = 10",
        "[[displacement]]\nsurface = \"contact\"\nz = 0.0\n",
    );
    let error = Simulation::from_toml(&conflict, &data())
        .err()
        .unwrap()
        .to_string();
    assert!(
        error.contains("displacement[0] rotates 'bottom'") || error.contains("rotates 'top'"),
        "{error}"
    );
    assert!(error.contains("displacement[2] ('contact')"), "{error}");
}
