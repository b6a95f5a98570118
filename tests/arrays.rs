//! A case around a mesh given as arrays (`Mesh::from_arrays`,
//! `case::from_mesh`), as the Python package builds one, against the same
//! mesh read from its `.msh` file; and an observer that stops a run.

use signorini::case;
use signorini::mesh::gmsh::read_msh;
use signorini::mesh::Mesh;
use signorini::output::{ConvergedIncrement, StepObserver, Summary};
use signorini::run::{RunOptions, Simulation};
use signorini::Error;
use std::path::{Path, PathBuf};

fn data() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data")
}

/// A unit cube of 3 × 3 × 3 hexahedra, its bottom held, pressed on top,
/// in two increments (without its `[mesh]` table).
const CUBE: &str = r#"
[[material]]
region = "body"
model = "neo_hookean"
youngs_modulus = 100.0
poisson_ratio = 0.3

[[displacement]]
surface = "bottom"
x = 0.0
y = 0.0
z = 0.0

[[pressure]]
surface = "top"
value = 5.0

[[step]]
name = "load"
end_time = 1.0
initial_increment = 0.5
max_increment = 0.5
"#;

/// The arrays of the cube's `.msh`, its facets given inside out (from the
/// same first node, so that orienting them restores the file's order).
fn cube_from_arrays() -> Mesh {
    let mesh = read_msh(&data().join("cube_hex_41_ascii.msh")).unwrap();
    Mesh::from_arrays(
        mesh.nodes.clone(),
        mesh.elements
            .iter()
            .map(|e| (e.kind, e.nodes.clone()))
            .collect(),
        mesh.regions
            .iter()
            .map(|r| (r.name.clone(), r.elements.clone()))
            .collect(),
        mesh.surfaces
            .iter()
            .map(|s| {
                let facets = s.facets.iter().map(|f| {
                    let mut nodes = f.nodes.clone();
                    nodes[1..].reverse();
                    nodes
                });
                (s.name.clone(), facets.collect())
            })
            .collect(),
    )
    .unwrap()
}

fn run(case: &case::Case, observer: &mut (dyn StepObserver + Send)) -> signorini::Result<Vec<f64>> {
    let mut simulation = Simulation::from_case(case)?;
    let options = RunOptions {
        output: None,
        threads: Some(1),
        cancel: None,
        restart: None,
    };
    Ok(simulation.run(&options, observer)?.displacement)
}

/// The same cube from arrays and from its file gives bitwise the same
/// displacements (the same mesh, numbering and facets after orientation).
#[test]
fn a_case_around_arrays_runs_as_the_case_file() {
    let from_file = case::from_toml(
        &format!("[mesh]\nfile = \"cube_hex_41_ascii.msh\"\n{CUBE}"),
        &data(),
    )
    .unwrap();
    let from_arrays = case::from_mesh(CUBE, &data(), cube_from_arrays()).unwrap();
    let silent = &mut signorini::output::observer::Silent;
    let a = run(&from_file, silent).unwrap();
    let b = run(&from_arrays, silent).unwrap();
    assert_eq!(a, b);
    // compressed: the top moves down
    let uz_min = a.chunks(3).map(|u| u[2]).fold(0.0, f64::min);
    assert!(uz_min < -0.01, "{uz_min}");
}

/// Errors of the text keep its line numbers and key paths; a `[mesh]`
/// table is refused (the arrays are the mesh).
#[test]
fn a_case_around_arrays_reports_the_case_file_errors() {
    let bad = CUBE.replace("youngs_modulus = 100.0", "youngs_modulus = \"x\"");
    let message = case::from_mesh(&bad, &data(), cube_from_arrays())
        .err()
        .unwrap()
        .to_string();
    assert!(
        message.contains("line 5: at key 'material[0].youngs_modulus'"),
        "{message}"
    );
    let with_mesh = format!("[mesh]\nfile = \"x.msh\"\n{CUBE}");
    let message = case::from_mesh(&with_mesh, &data(), cube_from_arrays())
        .err()
        .unwrap()
        .to_string();
    assert!(message.contains("remove the [mesh] table"), "{message}");
    // an inverted element: the first hexahedron's top and bottom swapped
    let mut mesh = cube_from_arrays();
    let e = &mut mesh.elements[0].nodes;
    e.rotate_left(4);
    let mesh = Mesh::from_arrays(
        mesh.nodes.clone(),
        mesh.elements
            .iter()
            .map(|e| (e.kind, e.nodes.clone()))
            .collect(),
        vec![("body".into(), (0..27).collect())],
        vec![],
    )
    .unwrap();
    let case = case::from_mesh(CUBE, &data(), mesh).unwrap();
    let message = case.build_problem().err().unwrap().to_string();
    assert!(
        message.starts_with("element 0 (mesh id) is inverted"),
        "{message}"
    );
}

/// Stops the run after `limit` increments.
struct StopAfter {
    limit: usize,
    seen: usize,
    status: String,
}

impl StepObserver for StopAfter {
    fn on_increment(&mut self, _: &ConvergedIncrement, _: &Summary) -> signorini::Result<()> {
        self.seen += 1;
        if self.seen == self.limit {
            return Err(Error::Interrupted {
                reason: format!("after {} increments", self.seen),
            });
        }
        Ok(())
    }
    fn on_finish(&mut self, summary: &Summary) -> signorini::Result<()> {
        self.status = summary.status.clone();
        assert_eq!(summary.increments.len(), self.seen);
        Ok(())
    }
}

/// An observer's `Interrupted` ends the run after that increment with the
/// status "interrupted".
#[test]
fn an_observer_stops_a_run() {
    let text = CUBE.replace(
        "initial_increment = 0.5\nmax_increment = 0.5",
        "initial_increment = 0.25\nmax_increment = 0.25",
    );
    let case = case::from_mesh(&text, &data(), cube_from_arrays()).unwrap();
    let mut stop = StopAfter {
        limit: 2,
        seen: 0,
        status: String::new(),
    };
    let error = run(&case, &mut stop).err().unwrap();
    assert!(matches!(error, Error::Interrupted { .. }), "{error}");
    assert_eq!(stop.seen, 2);
    assert_eq!(stop.status, "interrupted");
}
