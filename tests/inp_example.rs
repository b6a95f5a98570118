//! `examples/inp-import`, run end to end as the CLI runs it, against the
//! closed form stated in its README.

use signorini::run::{run, RunOptions};
use std::path::Path;

mod common;

/// A block from an Abaqus deck (`*SURFACE` face sets, `*NSET` symmetry
/// planes) pressed by `p` on a frictionless rigid plane: uniaxial uniform
/// stress `σ_zz = −p`, which Hex8 elements represent exactly, so
/// `u = (ν p x / E, ν p y / E, −p z / E)` at every node, the contact force
/// is `p A` and the symmetry reactions vanish.
#[test]
fn inp_import_block_matches_uniaxial_compression() {
    let out = tempfile::tempdir().unwrap();
    let case = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/inp-import/case.toml");
    let outcome = run(
        &case,
        &RunOptions {
            output: Some(out.path().to_path_buf()),
            threads: None,
            cancel: None,
            restart: None,
        },
    )
    .expect("the example runs");
    assert!(common::assert_contact_pressure_nonnegative(&outcome) > 0.0);
    let (p, e, nu, area) = (10.0, 1000.0, 0.3, 4.0);
    let loaded = signorini::case::load(&case).unwrap();
    assert!(
        loaded.notes[0].contains("ignored keywords"),
        "{:?}",
        loaded.notes
    );
    let mesh = &loaded.mesh;
    assert_eq!(mesh.elements.len(), 32);
    let u = &outcome.displacement;
    for (n, x) in mesh.nodes.iter().enumerate() {
        let exact = [nu * p * x[0] / e, nu * p * x[1] / e, -p * x[2] / e];
        for i in 0..3 {
            assert!(
                (u[3 * n + i] - exact[i]).abs() < 1e-10 * p / e,
                "node {} at {x:?}: u = {:?}, exact {exact:?}",
                mesh.node_ids[n],
                &u[3 * n..3 * n + 3]
            );
        }
    }
    let last = outcome.summary.increments.last().unwrap();
    let contact = &last.contact["BOTTOM"];
    assert!(
        (contact.force[2] - p * area).abs() < 1e-10 * p * area,
        "{:?}",
        contact.force
    );
    assert!(contact.force[0].abs() < 1e-10 && contact.force[1].abs() < 1e-10);
    assert_eq!(contact.closed_nodes, 25);
    assert!((contact.area - area).abs() < 1e-12);
    for set in ["SYMMETRY_X", "SYMMETRY_Y"] {
        let r = last.reaction_forces[set];
        assert!(r.iter().all(|v| v.abs() < 1e-9 * p * area), "{set}: {r:?}");
    }
}

/// `signorini check` on the example prints the ignored keywords of the deck
/// in one note line, and the node sets it read.
#[test]
fn check_lists_ignored_keywords_and_node_sets() {
    let case = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/inp-import/case.toml");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_signorini"))
        .arg("check")
        .arg(&case)
        .output()
        .unwrap();
    assert!(out.status.success());
    let stdout = String::from_utf8_lossy(&out.stdout);
    let notes: Vec<&str> = stdout.lines().filter(|l| l.starts_with("note: ")).collect();
    assert_eq!(notes.len(), 1, "{stdout}");
    assert!(
        notes[0].ends_with(
            "block.inp: ignored keywords (the case file gives materials, loads, boundary conditions \
             and steps): *MATERIAL, *ELASTIC, *SOLID SECTION, *STEP, *STATIC, *BOUNDARY, *DSLOAD, \
             *END STEP"
        ),
        "{}",
        notes[0]
    );
    assert!(
        stdout.contains("node set 'SYMMETRY_X': 15 nodes"),
        "{stdout}"
    );
}
