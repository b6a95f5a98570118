//! Bad decks run as they are (`signorini check deck.inp`), issue 33:
//! each is refused with exit code 1 and a message that names the file, the
//! line and what to change. Beside `tests/bad_inputs.rs` (the case files').

use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// `examples/calculix-deck/deck.inp` with `from` replaced by `to`.
fn edited(from: &str, to: &str) -> String {
    let text = std::fs::read_to_string(root().join("examples/calculix-deck/deck.inp")).unwrap();
    assert!(text.contains(from), "the example has no '{from}'");
    text.replacen(from, to, 1)
}

/// The 1-based line of the first line of `text` that contains `needle`.
fn line_of(text: &str, needle: &str) -> usize {
    text.lines()
        .position(|l| l.contains(needle))
        .expect("the line")
        + 1
}

/// Checks `text` as a deck: exit code 1, the message names `file:line`
/// and holds `message`.
fn refused(dir: &Path, name: &str, text: &str, line: usize, message: &str) {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_signorini"))
        .args(["check", path.to_str().unwrap()])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{name}: {err}");
    assert!(
        err.contains(&format!("{name}' at line {line}:")),
        "{name}: line {line}? {err}"
    );
    assert!(err.contains(message), "{name}: '{message}'? {err}");
    assert!(!err.contains("panicked"), "{name}: {err}");
}

#[test]
fn bad_decks_are_refused_by_name_and_line() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // a keyword with physics that is not read
    let t = edited(
        "*Elastic\n 210000., 0.3\n",
        "*Elastic\n 210000., 0.3\n*Plastic\n 250., 0.\n",
    );
    refused(
        d,
        "plastic.inp",
        &t,
        line_of(&t, "*Plastic"),
        "*PLASTIC is not supported: it changes the model",
    );
    let t = edited("*Friction\n", "*Friction, rough\n");
    refused(
        d,
        "rough.inp",
        &t,
        line_of(&t, "*Friction"),
        "*FRICTION, ROUGH is not supported",
    );
    // an instance of a missing part
    let t = edited("part=Base\n", "part=Plate\n");
    refused(
        d,
        "no_part.inp",
        &t,
        line_of(&t, "part=Plate"),
        "no *PART named 'Plate'",
    );
    // a set that names a missing instance
    let t = edited("Base-1.BaseNodes, 1, 3", "Base-2.BaseNodes, 1, 3");
    refused(
        d,
        "no_instance.inp",
        &t,
        line_of(&t, "Base-2.BaseNodes"),
        "'Base-2.BaseNodes' names the instance 'Base-2', which no *INSTANCE defines",
    );
    // a rotation with a zero axis
    let t = edited(
        " 0.5, 0.5, 0., 0.5, 0.5, 1., 90.",
        " 0.5, 0.5, 0., 0.5, 0.5, 0., 90.",
    );
    refused(
        d,
        "zero_axis.inp",
        &t,
        line_of(&t, "0.5, 0.5, 0., 90."),
        "zero length",
    );
    // a *BOUNDARY on an unknown set
    let t = edited("Pad-1.Top, 1, 2", "Pad-1.Tip, 1, 2");
    refused(
        d,
        "unknown_set.inp",
        &t,
        line_of(&t, "Pad-1.Tip"),
        "no node set (*NSET) 'Pad-1.Tip'",
    );
    // a surface interaction that does not exist
    let t = edited("interaction=Rough,", "interaction=Smooth,");
    refused(
        d,
        "no_interaction.inp",
        &t,
        line_of(&t, "Pad-1.Bottom, Base-1.Top"),
        "no *SURFACE INTERACTION named 'Smooth'",
    );
    // a section's material that does not exist (the first part placed: Base)
    let t = edited("*Material, name=Steel", "*Material, name=Iron");
    refused(
        d,
        "no_material.inp",
        &t,
        line_of(&t, "*Solid Section, elset=BaseAll"),
        "no *MATERIAL named 'Steel'",
    );
    // OP=NEW would release the block's fixed dofs
    let t = edited(
        "*Boundary\nPad-1.Top, 1, 1, 0.01",
        "*Boundary, op=NEW\nPad-1.Top, 1, 1, 0.01",
    );
    refused(
        d,
        "release.inp",
        &t,
        line_of(&t, "*Step, name=Pull"),
        "releasing a prescribed dof is not supported",
    );
    // NLGEOM in one step only
    let t = edited("*Step, name=Pull", "*Step, name=Pull, nlgeom");
    refused(
        d,
        "nlgeom.inp",
        &t,
        line_of(&t, "*Step, name=Pull"),
        "give every step the same NLGEOM",
    );
    // an incompressible neo-Hookean material
    let t = edited(
        "*Elastic\n 210000., 0.3\n",
        "*Hyperelastic, neo hooke\n 80000., 0.\n",
    );
    refused(
        d,
        "incompressible.inp",
        &t,
        line_of(&t, "*Material"),
        "D1 = 0",
    );
    // a rotation dof on a solid node
    let t = edited("Pad-1.Top, 1, 2", "Pad-1.Top, 5, 5");
    refused(
        d,
        "rotation_dof.inp",
        &t,
        line_of(&t, "Pad-1.Top, 5, 5"),
        "degree of freedom 5 is not a translation",
    );
    // a step left open
    let t = edited("*End Step\n*Step, name=Pull", "*Step, name=Pull");
    refused(
        d,
        "open_step.inp",
        &t,
        line_of(&t, "*Step, name=Pull"),
        "*STEP inside *STEP 'Press'",
    );
    // no step: nothing to run (the deck is still a mesh for a case file)
    let text = std::fs::read_to_string(root().join("examples/calculix-deck/deck.inp")).unwrap();
    let t = &text[..text.find("*Step").unwrap()];
    let path = d.join("no_step.inp");
    std::fs::write(&path, t).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_signorini"))
        .args(["check", path.to_str().unwrap()])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.contains("no_step.inp") && err.contains("the deck has no *STEP"),
        "{err}"
    );
}

/// A C3D10 body's face in a `*CONTACT PAIR` (`tests/data/deck/tet_on_block.inp`:
/// a quadratic tetrahedron's S1 on a C3D8 block's top). Asked for
/// `TYPE=NODE TO SURFACE`, it is refused at the pair's line, naming the
/// surface and the way out (node-to-surface gives a Tri6's corners no
/// share of a uniform pressure), with the quadratic surface either the
/// secondary or the primary one. Without `TYPE=` the pair takes dual
/// mortar contact (`check` passes, the note says so), with `*FRICTION`
/// too (Coulomb on mortar's weighted slip).
#[test]
fn quadratic_contact_surface_takes_mortar_or_is_refused_at_the_pair() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(root().join("tests/data/deck/tet_on_block.inp")).unwrap();
    let line = line_of(&text, "TetBottom, BlockTop");
    for message in [
        "*CONTACT PAIR, TYPE=NODE TO SURFACE: surface 'TetBottom' has quadratic faces",
        "TYPE=MORTAR",
        "linear elements",
    ] {
        refused(dir.path(), "tet_on_block.inp", &text, line, message);
    }
    let swapped = text.replace("TetBottom, BlockTop", "BlockTop, TetBottom");
    let line = line_of(&swapped, "BlockTop, TetBottom");
    refused(
        dir.path(),
        "block_on_tet.inp",
        &swapped,
        line,
        "*CONTACT PAIR, TYPE=NODE TO SURFACE: surface 'TetBottom' has quadratic faces",
    );
    // without TYPE=: mortar
    let mortar = text.replace(", TYPE=NODE TO SURFACE", "");
    let path = dir.path().join("tet_mortar.inp");
    std::fs::write(&path, &mortar).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_signorini"))
        .args(["check", path.to_str().unwrap()])
        .output()
        .unwrap();
    let all = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(out.status.code(), Some(0), "{all}");
    assert!(all.contains("dual mortar contact"), "{all}");
    // with friction: mortar takes it
    let rough = mortar.replace(
        "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=HARD\n",
        "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=HARD\n*FRICTION\n0.2\n",
    );
    assert!(rough.contains("*FRICTION"));
    let path = dir.path().join("tet_rough.inp");
    std::fs::write(&path, &rough).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_signorini"))
        .args(["check", path.to_str().unwrap()])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0), "{out:?}");
    let t = edited("type=SURFACE TO SURFACE", "type=SEGMENT");
    refused(
        dir.path(),
        "segment.inp",
        &t,
        line_of(&t, "*Contact Pair"),
        "*CONTACT PAIR, TYPE=SEGMENT is not known",
    );
}
