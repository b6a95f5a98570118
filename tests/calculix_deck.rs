//! Abaqus/CalculiX decks run as they are (issue 33):
//! - `examples/calculix-deck`: parts and instances, HARD contact with
//!   friction against a fixed meshed block, press then pull; run as a deck
//!   and through the case `signorini convert` writes, the same answer to
//!   1e-12, and the pull's reaction Coulomb's `μ p A`.
//! - A linear elastic cantilever without contact against CalculiX's `ccx`
//!   (skipped, with a message, when `ccx` is not installed): the nodal
//!   displacements agree to 1e-6 of the largest.
//! - `examples/calculix-deck/deck_c3d10.inp`: the pad of C3D10 (192
//!   quadratic tetrahedra, ν = 0) pressed on the fixed C3D8 block by
//!   `p = 100` on its top, then pulled sideways by 0.01; its
//!   `*CONTACT PAIR` has quadratic faces (Tri6), so it becomes dual mortar
//!   contact. The deck and its converted case give the same displacements
//!   to 1e-12; pressed (end of step 1) the pad's stress is uniaxial,
//!   `σ_zz = −p` (ν = 0: nothing holds it sideways), so every secondary
//!   node's multiplier is `λ_j = p` and the contact force `p A = 100`
//!   (A = 1); pulled (end of step 2) the whole pad slides, and the
//!   sideways reaction on its top is Coulomb's `μ p A = 30` with
//!   `*FRICTION` μ = 0.3 (Coulomb on mortar's weighted slip), zero without.

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
    let case = dir.path().join("case.toml");
    as_deck_and_as_case(&deck, dir.path(), "primary = \"Base-1.Top\"");
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

const P: f64 = 100.0;
const AREA: f64 = 1.0;
const MU: f64 = 0.3;
const MORTAR: &str = "discretisation = \"mortar\"";

fn c3d10_example() -> PathBuf {
    root().join("examples/calculix-deck/deck_c3d10.inp")
}

/// The deck at `deck` run as it is (into `dir/deck`) and through the
/// case that `signorini convert` writes (`dir/case.toml`): the deck's
/// outcome, after checking that the case's text holds `in_case` and that
/// the displacements agree to 1e-12 of the largest (one path by
/// construction: the deck is translated into the structure the TOML
/// parses into).
fn as_deck_and_as_case(deck: &Path, dir: &Path, in_case: &str) -> RunOutcome {
    let as_deck = run_into(deck, &dir.join("deck"));
    let case = dir.join("case.toml");
    let status = Command::new(env!("CARGO_BIN_EXE_signorini"))
        .args(["convert", deck.to_str().unwrap(), "--output"])
        .arg(&case)
        .status()
        .unwrap();
    assert!(status.success());
    let text = std::fs::read_to_string(&case).unwrap();
    assert!(text.contains(in_case), "{text}");
    let as_case = run_into(&case, &dir.join("case"));
    assert_eq!(as_deck.displacement.len(), as_case.displacement.len());
    let scale = as_deck
        .displacement
        .iter()
        .fold(0.0f64, |m, u| m.max(u.abs()));
    assert!(scale > 1e-5, "{scale}");
    for (a, b) in as_deck.displacement.iter().zip(&as_case.displacement) {
        assert!((a - b).abs() <= 1e-12 * scale, "{a} vs {b}");
    }
    as_deck
}

/// The largest `|λ_j − p|` over the pad's bottom nodes at the end of the
/// increment ending at total time `time`, and the contact force's normal
/// component and area there (`summary.json`).
fn pressure_at(deck: &Path, outcome: &RunOutcome, time: f64) -> (f64, f64, f64) {
    let increment = outcome
        .summary
        .increments
        .iter()
        .rfind(|i| (i.time - time).abs() < 1e-12)
        .unwrap_or_else(|| panic!("no increment ends at {time}"));
    let contact = increment.contact.values().next().expect("one interface");
    let file = outcome.output_dir.join(&increment.file);
    let pressure = signorini::output::vtu::read_point_field(&file, "contact_pressure").unwrap();
    let mesh = signorini::mesh::inp::read_inp(deck).unwrap().mesh;
    let bottom = mesh.surface_nodes(mesh.surface("Pad-1.Bottom").unwrap());
    assert_eq!(bottom.len(), 81);
    let worst = bottom
        .iter()
        .map(|&n| (pressure[n] - P).abs())
        .fold(0.0f64, f64::max);
    (worst, contact.force[2].abs(), contact.area)
}

/// The press of the uniform state: `λ_j = p` at every node of the pad's
/// bottom (to `tolerance` of p: 1e-10 frictionless, measured 1e-14
/// pressed, 1e-13 slid; 1e-8 with the deck's regularised friction, whose
/// tangential unknowns leave Newton's tolerance on λ, measured 1.1e-9),
/// the force `p A` and the area `A` (1e-10).
fn assert_uniform_press(worst: f64, force: f64, area: f64, tolerance: f64) {
    println!("press: max |λ_j − p| {worst:.3e}, force {force:.12}, area {area:.12}");
    assert!(worst <= tolerance * P, "max |λ_j − p| = {worst}");
    assert!((force - P * AREA).abs() <= 1e-10 * P, "force {force}");
    assert!((area - AREA).abs() <= 1e-10, "area {area}");
}

/// The deck without `*FRICTION`: mortar, deck = converted case to 1e-12;
/// press uniform (`λ_j = p`, force `p A`); the frictionless pull slides
/// the pad by 0.01 over the non-matching block with no sideways reaction
/// (1e-8 of `μ p A`) and the same uniform pressure.
#[test]
fn c3d10_deck_without_friction_presses_uniformly() {
    let text = std::fs::read_to_string(c3d10_example()).unwrap();
    let frictionless = text.replace("*Friction\n 0.3, 1e7\n", "");
    assert_ne!(text, frictionless, "the example has its *Friction");
    let dir = tempfile::tempdir().unwrap();
    let deck = dir.path().join("deck_c3d10.inp");
    std::fs::write(&deck, frictionless).unwrap();
    let notes = signorini::case::deck::translate_file(&deck, "deck_c3d10.inp")
        .unwrap()
        .notes;
    assert!(
        notes
            .iter()
            .any(|n| n.contains("dual mortar contact") && n.contains("quadratic faces")),
        "{notes:?}"
    );
    let as_deck = as_deck_and_as_case(&deck, dir.path(), MORTAR);
    let (worst, force, area) = pressure_at(&deck, &as_deck, 1.0);
    assert_uniform_press(worst, force, area, 1e-10);
    let (worst, force, area) = pressure_at(&deck, &as_deck, 2.0);
    assert_uniform_press(worst, force, area, 1e-10);
    let rf = last_row(&dir.path().join("deck/Pad-1.Top_RF.csv"));
    println!("pull without friction: reaction {rf:?}");
    assert_eq!(rf[0], 2.0);
    assert!(rf[1].abs() <= 1e-8 * MU * P * AREA, "{rf:?}");
    assert!(rf[2].abs() <= 1e-8 * MU * P * AREA, "{rf:?}");
}

/// The committed deck, with `*FRICTION` μ = 0.3: deck = converted case to
/// 1e-12; press uniform as without friction (ν = 0: nothing slips while
/// pressed); at the end of the pull the whole pad slides and the
/// sideways reaction on its top is Coulomb's `μ p A = 30` (1e-6: Newton's
/// tolerance), its y component zero to 1e-5 of it (measured 1.2e-6: the
/// pad's Kuhn split into tetrahedra is not mirror-symmetric in y, so the
/// slip turns by that much).
#[test]
fn c3d10_deck_press_then_pull_with_friction() {
    let dir = tempfile::tempdir().unwrap();
    let as_deck = as_deck_and_as_case(&c3d10_example(), dir.path(), MORTAR);
    let (worst, force, area) = pressure_at(&c3d10_example(), &as_deck, 1.0);
    assert_uniform_press(worst, force, area, 1e-8);
    let rf = last_row(&dir.path().join("deck/Pad-1.Top_RF.csv"));
    println!("pull with friction: reaction {rf:?}");
    assert_eq!(rf[0], 2.0);
    let coulomb = MU * P * AREA;
    assert!((rf[1].abs() - coulomb).abs() < 1e-6 * coulomb, "{rf:?}");
    assert!(rf[2].abs() < 1e-5 * coulomb, "{rf:?}");
}

/// CalculiX's `TYPE=` on the C3D8 example's pair (linear faces, without
/// its `*FRICTION`): `MORTAR` and its variants become mortar (the
/// variants with a note that they are read as `MORTAR`), `NODE TO
/// SURFACE`, `SURFACE TO SURFACE` and no `TYPE=` node-to-surface; the
/// converted case says `discretisation = "mortar"` for the first and
/// `"node_to_surface"` for the others (written: the case file's default is
/// mortar).
#[test]
fn calculix_pair_types_map_to_the_discretisation() {
    use signorini::case::schema::DiscretisationSpec::{Mortar, NodeToSurface};
    let deck = root().join("examples/calculix-deck/deck.inp");
    let text = std::fs::read_to_string(deck)
        .unwrap()
        .replace("*Friction\n 0.3, 1e7\n", "");
    let dir = tempfile::tempdir().unwrap();
    for (given, expected, variant) in [
        (", type=MORTAR", Mortar, false),
        (", type=pglinmortar", Mortar, true),
        (", type=LinMortar", Mortar, true),
        (", type=PGMORTAR", Mortar, true),
        (", type=NODE TO SURFACE", NodeToSurface, false),
        (", type=node  to surface", NodeToSurface, false),
        (", type=SURFACE TO SURFACE", NodeToSurface, false),
        ("", NodeToSurface, false),
    ] {
        let path = dir.path().join("pair.inp");
        std::fs::write(&path, text.replace(", type=SURFACE TO SURFACE", given)).unwrap();
        let translated = signorini::case::deck::translate_file(&path, "pair.inp").unwrap();
        assert_eq!(
            translated.spec.contact[0].discretisation,
            Some(expected),
            "{given}"
        );
        let toml = signorini::case::deck::to_toml(&translated.spec);
        assert_eq!(
            toml.contains("discretisation = \"mortar\""),
            expected == Mortar
        );
        assert_eq!(
            toml.contains("discretisation = \"node_to_surface\""),
            expected == NodeToSurface
        );
        let note = translated
            .notes
            .iter()
            .any(|n| n.contains("read as MORTAR"));
        assert_eq!(note, variant, "{given}: {:?}", translated.notes);
    }
}
