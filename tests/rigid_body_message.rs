//! The diagnosis of a Newton correction far larger than the body names the
//! cause that the problem can have: without contact there is no contact to
//! lose, the tangent is near singular.

use signorini::run::{run, RunOptions};
use std::path::Path;

/// A contact-free Ogden cube (the rubber-tension example's mesh and
/// material) whose face `xmax` is pulled to `x = 100` (100 × its size) in
/// one increment with no cut allowed: the first correction is the
/// prescribed jump itself, far beyond the body, and the error says so
/// (smaller increments) without blaming a lost contact.
#[test]
fn huge_pull_without_contact_is_not_called_a_lost_contact() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/rubber-tension/cube.msh");
    let case = dir.path().join("case.toml");
    std::fs::write(
        &case,
        format!(
            r#"[mesh]
file = {mesh:?}

[[material]]
region = "rubber"
model = "ogden"
mu = [0.4095, 0.003, 0.01]
alpha = [1.3, 5.0, -2.0]
bulk_modulus = 20.0

[[displacement]]
surface = "xmin"
x = 0.0

[[displacement]]
surface = "ymin"
y = 0.0

[[displacement]]
surface = "zmin"
z = 0.0

[[displacement]]
surface = "xmax"
x = 100.0

[solver]
max_cuts = 0

[[step]]
name = "pull"
end_time = 1.0
initial_increment = 1.0
max_increment = 1.0

[output]
name = "cube"
"#,
            mesh = mesh.display().to_string()
        ),
    )
    .unwrap();
    let options = RunOptions {
        output: Some(dir.path().join("out")),
        threads: None,
        cancel: None,
        restart: None,
    };
    let Err(error) = run(&case, &options) else {
        panic!("the run succeeded although no increment cut is allowed");
    };
    let message = error.to_string();
    assert!(
        message.contains("a prescribed displacement of 1.000e2"),
        "{message}"
    );
    assert!(message.contains("far larger than the"), "{message}");
    assert!(message.contains("take smaller increments"), "{message}");
    assert!(!message.contains("lost contact"), "{message}");
    assert!(!message.contains("rigid-body mode"), "{message}");
}
