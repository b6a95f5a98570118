//! Abaqus/CalculiX decks run as they are (issue 33):
//! - `examples/calculix-deck`: parts and instances, HARD contact with
//!   friction against a fixed meshed block, press then pull; run as a deck
//!   and through the case `signorini convert` writes, the same answer to
//!   1e-12, and the pull's reaction Coulomb's `μ p A`.
//! - A linear elastic cantilever without contact against CalculiX's `ccx`
//!   (skipped, with a message, when `ccx` is not installed): the nodal
//!   displacements agree to 1e-6 of the largest.

mod ccx;

use signorini::run::{run, RunOptions, RunOutcome};
use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn run_into(case: &Path, out: &Path) -> RunOutcome {
    run(
        case,
        &RunOptions {
            output: Some(out.to_path_buf()),
            threads: None,
            cancel: None,
            restart: None,
        },
    )
    .unwrap_or_else(|e| panic!("{}: {e}", case.display()))
}

/// The last row of a history's CSV: time and the columns after it.
fn last_row(csv: &Path) -> Vec<f64> {
    let text = std::fs::read_to_string(csv).unwrap();
    let line = text.lines().last().unwrap();
    line.split(',').map(|f| f.trim().parse().unwrap()).collect()
}

/// The example run as a deck and as its converted case: the same
/// displacements (to 1e-12, the same path by construction); the pull's
/// reaction on the pad's top is the Coulomb force `μ p A = 0.3 × 100 × 1`
/// of a pad sliding on the block (to 1e-6: the Newton tolerance), the
/// press's sideways reaction zero by symmetry.
#[test]
fn example_deck_runs_as_deck_and_as_converted_case() {
    let deck = root().join("examples/calculix-deck/deck.inp");
    let dir = tempfile::tempdir().unwrap();
    let as_deck = run_into(&deck, &dir.path().join("deck"));
    let case = dir.path().join("case.toml");
    let status = Command::new(env!("CARGO_BIN_EXE_signorini"))
        .args([
            "convert",
            deck.to_str().unwrap(),
            "--output",
            case.to_str().unwrap(),
        ])
        .status()
        .unwrap();
    assert!(status.success());
    let text = std::fs::read_to_string(&case).unwrap();
    assert!(text.contains("primary = \"Base-1.Top\""), "{text}");
    let as_case = run_into(&case, &dir.path().join("case"));
    assert_eq!(as_deck.displacement.len(), as_case.displacement.len());
    let scale = as_deck
        .displacement
        .iter()
        .fold(0.0f64, |m, u| m.max(u.abs()));
    for (a, b) in as_deck.displacement.iter().zip(&as_case.displacement) {
        assert!((a - b).abs() <= 1e-12 * scale, "{a} vs {b}");
    }
    let rf = last_row(&dir.path().join("deck/Pad-1.Top_RF.csv"));
    assert_eq!(rf[0], 2.0);
    let coulomb = 0.3 * 100.0 * 1.0;
    assert!((rf[1].abs() - coulomb).abs() < 1e-6 * coulomb, "{rf:?}");
    assert!(rf[2].abs() < 1e-6 * coulomb, "{rf:?}");
    // a second convert refuses to overwrite the case without --force
    let again = Command::new(env!("CARGO_BIN_EXE_signorini"))
        .args([
            "convert",
            deck.to_str().unwrap(),
            "--output",
            case.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert!(!again.status.success());
    assert!(String::from_utf8_lossy(&again.stderr).contains("--force"));
}

/// Runs `deck_text` (beside the cantilever's mesh) with ccx and with
/// signorini; the largest difference of a nodal displacement and the
/// largest displacement. `None` (and a message) without ccx.
fn against_ccx(deck_text: &str) -> Option<(f64, f64)> {
    if !ccx::installed() {
        return None;
    }
    let dir = tempfile::tempdir().unwrap();
    let mesh = "cantilever_mesh.inp";
    std::fs::copy(
        root().join("tests/data/deck").join(mesh),
        dir.path().join(mesh),
    )
    .unwrap();
    std::fs::write(dir.path().join("cantilever.inp"), deck_text).unwrap();
    let reference = ccx::run(dir.path(), "cantilever");
    assert_eq!(reference.len(), 9 * 3 * 3);
    let deck = dir.path().join("cantilever.inp");
    let ours = run_into(&deck, &dir.path().join("ours"));
    let mesh = signorini::mesh::inp::read_inp(&deck).unwrap().mesh;
    let largest = reference
        .iter()
        .flat_map(|(_, u)| u.iter())
        .fold(0.0f64, |m, v| m.max(v.abs()));
    let mut worst = 0.0f64;
    for (id, u) in &reference {
        let n = mesh.node_ids.iter().position(|i| i == id).unwrap();
        for (c, reference) in u.iter().enumerate() {
            worst = worst.max((ours.displacement[3 * n + c] - reference).abs());
        }
    }
    println!("largest |u| {largest:.6e}, largest difference from ccx {worst:.3e}");
    Some((worst, largest))
}

fn cantilever() -> String {
    std::fs::read_to_string(root().join("tests/data/deck/cantilever.inp")).unwrap()
}

/// The cantilever (C3D8, a tip `*CLOAD` and a `*DLOAD` pressure, no
/// NLGEOM): signorini's small-strain run of the deck and ccx's linear
/// solve agree to 1e-6 of the largest displacement at every node (ccx
/// prints 7 significant digits; the elements are the same fully
/// integrated trilinear hexahedra). Measured: 5.0e-8 of 0.54.
#[test]
fn linear_deck_agrees_with_calculix() {
    let Some((worst, largest)) = against_ccx(&cantilever()) else {
        return;
    };
    assert!(largest > 0.1, "{largest}");
    assert!(worst <= 1e-6 * largest, "{worst} vs {largest}");
}

/// The same cantilever of `*HYPERELASTIC, NEO HOOKE` (`C10 = E/(4(1+ν))`,
/// `D1 = 2/κ` of E = 210000, ν = 0.3) with NLGEOM and a tenth of the
/// loads: read as Ogden `μ = 2 C10`, `α = 2`, `κ = 2/D1` and follower
/// pressure, against ccx's finite-strain solve. To 1e-4 of the largest
/// displacement: ccx stops Newton at its default residual criterion
/// (5e-3 of the mean force), looser than ours. Measured: 1.5e-5.
#[test]
fn neo_hooke_deck_agrees_with_calculix() {
    let text = cantilever()
        .replace(
            "*ELASTIC\n210000., 0.3",
            "*HYPERELASTIC, NEO HOOKE\n40384.615384615, 1.142857142857e-5",
        )
        .replace("*STEP\n", "*STEP, NLGEOM\n")
        .replace("TIP, 3, -50.", "TIP, 3, -5.")
        .replace("TIP, 2, 20.", "TIP, 2, 2.")
        .replace("P2, 30.", "P2, 3.");
    assert!(text.contains("NEO HOOKE") && text.contains("NLGEOM") && text.contains("P2, 3."));
    let Some((worst, largest)) = against_ccx(&text) else {
        return;
    };
    assert!(largest > 0.01, "{largest}");
    assert!(worst <= 1e-4 * largest, "{worst} vs {largest}");
}
