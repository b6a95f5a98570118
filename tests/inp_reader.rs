//! The Abaqus/CalculiX `.inp` reader: a deck written by Gmsh (against the
//! same mesh read from `.msh`, and one run on both), a hand-written deck
//! with `*SURFACE` face sets, `GENERATE` and `*INCLUDE`, the Abaqus face
//! numbering of C3D4, and malformed decks whose errors name the file and
//! line.

use nalgebra::Vector3;
use signorini::mesh::inp::read_inp;
use signorini::mesh::{Mesh, SurfaceSet};
use signorini::run::{run, RunOptions};
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
}

/// Node ids of a set of node indices.
fn ids(mesh: &Mesh, nodes: &[usize]) -> BTreeSet<u64> {
    nodes.iter().map(|&n| mesh.node_ids[n]).collect()
}

/// A surface set's facets as sets of node ids, with the facets' outward
/// normals (right-hand rule, area-weighted) summed.
fn facets(mesh: &Mesh, s: &SurfaceSet) -> (BTreeSet<BTreeSet<u64>>, [f64; 3]) {
    let mut total = Vector3::zeros();
    for f in &s.facets {
        let x: Vec<Vector3<f64>> = f.nodes.iter().map(|&n| mesh.nodes[n].into()).collect();
        // (x2 − x0) × (x3 − x1) / 2 for a quadrangle, (x1 − x0) × (x2 − x0) / 2 for a triangle
        let (a, b) = if x.len() == 4 {
            (x[2] - x[0], x[3] - x[1])
        } else {
            (x[1] - x[0], x[2] - x[0])
        };
        total += 0.5 * a.cross(&b);
    }
    let sets = s.facets.iter().map(|f| ids(mesh, &f.nodes)).collect();
    (sets, total.into())
}

/// Gmsh wrote the same mesh as `bar_tet.msh` and `bar_tet.inp`: the same
/// nodes (to the 14 digits of the deck), elements (node order included), regions, surface facets with the
/// same outward orientation, and node sets (the `.msh` from its 0D/1D
/// physical groups, the `.inp` from `*NSET`).
#[test]
fn gmsh_deck_matches_gmsh_msh() {
    let msh = signorini::mesh::gmsh::read_msh(&data("bar_tet.msh")).unwrap();
    let deck = read_inp(&data("bar_tet.inp")).unwrap();
    let inp = &deck.mesh;
    assert_eq!(inp.node_ids, msh.node_ids);
    // Gmsh writes 14 significant digits to .inp, 16 to .msh
    for (a, b) in inp.nodes.iter().zip(&msh.nodes) {
        for i in 0..3 {
            assert!((a[i] - b[i]).abs() < 1e-13, "{a:?} {b:?}");
        }
    }
    assert_eq!(inp.elements, msh.elements);
    assert!(inp.elements.len() > 100, "{}", inp.elements.len());
    // Gmsh also writes an element set per geometric entity (Volume1, …)
    let bar = inp.region("bar").unwrap();
    assert_eq!(bar.elements, msh.region("bar").unwrap().elements);
    for name in ["fixed", "loaded", "bottom"] {
        let (a, b) = (inp.surface(name).unwrap(), msh.surface(name).unwrap());
        assert_eq!(a.facets, b.facets, "{name}");
    }
    let (_, normal) = facets(inp, inp.surface("loaded").unwrap());
    assert!(
        (normal[0] - 1.0).abs() < 1e-12 && normal[1].abs() < 1e-12,
        "{normal:?}"
    );
    for name in ["origin", "edge", "fixed"] {
        let a = ids(inp, &inp.node_set(name).unwrap().nodes);
        let b = match msh.node_set(name) {
            Some(s) => ids(&msh, &s.nodes),
            None => ids(&msh, &msh.surface_nodes(msh.surface(name).unwrap())),
        };
        assert_eq!(a, b, "{name}");
    }
    let origin = &inp.node_set("origin").unwrap().nodes;
    assert_eq!(origin.len(), 1);
    assert_eq!(inp.nodes[origin[0]], [0.0, 0.0, 0.0]);
    for &n in &msh.node_set("edge").unwrap().nodes {
        assert!(msh.nodes[n][0] == 0.0 && msh.nodes[n][1] == 0.0);
    }
    assert!(deck.notes.is_empty(), "{:?}", deck.notes);
}

/// Gmsh's deck of the structured Hex8 cube (quadrangle surface elements,
/// CPS4) against its MSH 4.1: the same elements in the same node order,
/// the same regions and the same outward facets.
#[test]
fn gmsh_hex_deck_matches_gmsh_msh() {
    let msh = signorini::mesh::gmsh::read_msh(&data("cube_hex_41_ascii.msh")).unwrap();
    let inp = read_inp(&data("cube_hex.inp")).unwrap().mesh;
    assert_eq!(inp.node_ids, msh.node_ids);
    for (a, b) in inp.nodes.iter().zip(&msh.nodes) {
        for i in 0..3 {
            assert!((a[i] - b[i]).abs() < 1e-13, "{a:?} {b:?}");
        }
    }
    assert_eq!(inp.elements, msh.elements);
    assert_eq!(inp.elements.len(), 27);
    assert_eq!(
        inp.region("body").unwrap().elements,
        msh.region("body").unwrap().elements
    );
    for name in ["bottom", "top", "contact"] {
        assert_eq!(
            inp.surface(name).unwrap().facets,
            msh.surface(name).unwrap().facets,
            "{name}"
        );
    }
    let (_, normal) = facets(&inp, inp.surface("top").unwrap());
    assert!((normal[2] - 1.0).abs() < 1e-12, "{normal:?}");
}

/// The hand-written deck: nodes from an `*INCLUDE`d file, an element line
/// continued after a trailing comma, `GENERATE`, set names in set lists
/// (case ignored), `*SURFACE` with face identifiers and without, and the
/// physics keywords listed as ignored.
#[test]
fn hand_written_deck_with_surfaces_generate_and_include() {
    let deck = read_inp(&data("inp/block.inp")).unwrap();
    let m = &deck.mesh;
    assert_eq!(m.nodes.len(), 12);
    assert_eq!(m.elements.len(), 2);
    assert_eq!(m.elements[0].nodes.len(), 8);
    let names: Vec<&str> = m.regions.iter().map(|r| r.name.as_str()).collect();
    assert_eq!(names, ["ALL", "Left", "right"]);
    assert_eq!(m.region("right").unwrap().elements, [1]);
    let set = |name: &str| ids(m, &m.node_set(name).unwrap().nodes);
    assert_eq!(set("xmin"), BTreeSet::from([1, 4, 7, 10]));
    assert_eq!(set("XMAX"), BTreeSet::from([3, 6, 9, 12]));
    assert_eq!(set("both_ends").len(), 8);
    assert_eq!(set("all_nodes").len(), 12);
    // top: S2 (5-8-7-6) of both elements, z = 1, outward +z, area 2
    let (top, normal) = facets(m, m.surface("top").unwrap());
    assert_eq!(
        top,
        BTreeSet::from([
            BTreeSet::from([7, 8, 11, 10]),
            BTreeSet::from([8, 9, 12, 11])
        ])
    );
    assert_eq!(normal, [0.0, 0.0, 2.0]);
    // end: S4 (2-6-7-3) of element 2 is the face x = 2
    let (end, normal) = facets(m, m.surface("end").unwrap());
    assert_eq!(end, BTreeSet::from([BTreeSet::from([3, 6, 12, 9])]));
    assert_eq!(normal, [1.0, 0.0, 0.0]);
    // outer: the five free faces of element 1; their outward areas cancel
    // but for the face it shares with element 2 (x = 1, missing): −(+x)
    let (outer, normal) = facets(m, m.surface("outer").unwrap());
    assert_eq!(outer.len(), 5);
    assert_eq!(normal, [-1.0, 0.0, 0.0]);
    assert_eq!(deck.notes.len(), 1, "{:?}", deck.notes);
    assert!(
        deck.notes[0].contains(
            "*MATERIAL, *ELASTIC, *SOLID SECTION, *STEP, *STATIC, *BOUNDARY, *CLOAD, *END STEP"
        ),
        "{}",
        deck.notes[0]
    );
}

/// C3D4 faces by the Abaqus numbering S1 = 1-2-3, S2 = 1-4-2, S3 = 2-4-3,
/// S4 = 3-4-1, each oriented out of the element.
#[test]
fn c3d4_face_numbering() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("tet.inp");
    let mut deck = String::from(
        "*NODE\n11, 0, 0, 0\n12, 1, 0, 0\n13, 0, 1, 0\n14, 0, 0, 1\n\
         *ELEMENT, TYPE=C3D4, ELSET=tet\n5, 11, 12, 13, 14\n",
    );
    for s in 1..=4 {
        deck.push_str(&format!("*SURFACE, NAME=s{s}\n5, S{s}\n"));
    }
    std::fs::write(&path, deck).unwrap();
    let m = read_inp(&path).unwrap().mesh;
    let expected = [[11, 12, 13], [11, 14, 12], [12, 14, 13], [13, 14, 11]];
    let centroid = [0.25; 3];
    for (s, nodes) in expected.iter().enumerate() {
        let surface = m.surface(&format!("s{}", s + 1)).unwrap();
        let (faces, normal) = facets(&m, surface);
        assert_eq!(
            faces,
            BTreeSet::from([BTreeSet::from(*nodes)]),
            "S{}",
            s + 1
        );
        // outward: the normal points from the element's centroid to the face
        let d = Vector3::from(m.nodes[surface.facets[0].nodes[0]]) - Vector3::from(centroid);
        assert!(d.dot(&Vector3::from(normal)) > 0.0, "S{}", s + 1);
    }
}

/// Writes `text` as `name` in `dir`.
fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

const NODES: &str = "*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n3, 0, 1, 0\n4, 0, 0, 1\n";

/// Malformed decks: each error names the file and the line, and says what
/// is wrong.
#[test]
fn malformed_decks_give_file_and_line() {
    let dir = tempfile::tempdir().unwrap();
    let element = "*ELEMENT, TYPE=C3D4, ELSET=body\n1, 1, 2, 3, 4\n";
    let cases: Vec<(&str, String, &str, usize, &str)> = vec![
        (
            "missing_node.inp",
            format!("{NODES}*ELEMENT, TYPE=C3D4\n1, 1, 2, 3, 9\n"),
            "missing_node.inp",
            7,
            "element 1 refers to node 9",
        ),
        (
            "quadratic.inp",
            format!("{NODES}*ELEMENT, TYPE=C3D27, ELSET=body\n"),
            "quadratic.inp",
            6,
            "C3D27 is not supported yet",
        ),
        (
            "c3d20.inp",
            format!("{NODES}** comment\n*Element, type=c3d8t\n"),
            "c3d20.inp",
            7,
            "C3D8T is not supported yet",
        ),
        (
            "bad_number.inp",
            "*NODE\n1, 0, 0, 0\n2, 1, zero, 0\n".into(),
            "bad_number.inp",
            3,
            "expected a number, found 'zero'",
        ),
        (
            "bad_face.inp",
            format!("{NODES}{element}*SURFACE, NAME=s\n1, S5\n"),
            "bad_face.inp",
            9,
            "element 1 is a C3D4 with faces S1…S4, not S5",
        ),
        (
            "unknown_set.inp",
            format!("{NODES}{element}*ELSET, ELSET=e\nbody, missing\n"),
            "unknown_set.inp",
            9,
            "'missing', which is neither a defined element id nor the name of an earlier element set",
        ),
        (
            "short_element.inp",
            format!("{NODES}*ELEMENT, TYPE=C3D8\n1, 1, 2, 3, 4\n"),
            "short_element.inp",
            7,
            "'id' and 8 node ids; found 5 fields",
        ),
        (
            "generate_backwards.inp",
            format!("{NODES}*NSET, NSET=n, GENERATE\n5, 1\n"),
            "generate_backwards.inp",
            7,
            "GENERATE from 5 to 1: the last id must not be smaller than the first",
        ),
        (
            "generate_empty.inp",
            format!("{NODES}*NSET, NSET=n, GENERATE\n10, 20, 2\n"),
            "generate_empty.inp",
            6,
            "*NSET 'n': the GENERATE ranges hold no defined id",
        ),
        (
            "unknown_type.inp",
            format!("{NODES}*ELEMENT, TYPE=SPRINGA\n1, 1, 2\n"),
            "unknown_type.inp",
            6,
            "element type SPRINGA is not supported",
        ),
        (
            "surface_of_shells.inp",
            format!("{NODES}{element}*ELEMENT, TYPE=S3, ELSET=skin\n2, 1, 2, 3\n*SURFACE, NAME=s\nskin, S1\n"),
            "surface_of_shells.inp",
            11,
            "*SURFACE 's': 'skin' holds no C3D4 or C3D8 element",
        ),
        // the data lines are parsed side by side: of two bad lines, the
        // first in the deck is the one reported
        (
            "two_bad_numbers.inp",
            "*NODE\n1, 0, 0, 0\n2, 1, zero, 0\n3, 1, 1, one\n".into(),
            "two_bad_numbers.inp",
            3,
            "expected a number, found 'zero'",
        ),
        (
            "two_short_elements.inp",
            format!("{NODES}*ELEMENT, TYPE=C3D4\n1, 1, 2, 3, 4\n2, 1, 2, 3\n3, 1, 2\n"),
            "two_short_elements.inp",
            8,
            "'id' and 4 node ids; found 4 fields",
        ),
        (
            "continued_then_missing.inp",
            format!("{NODES}*ELEMENT, TYPE=C3D4\n1, 1, 2,\n3, 4\n2, 1, 2, 3, 9\n3, 1, 2, 3, 8\n"),
            "continued_then_missing.inp",
            9,
            "element 2 refers to node 9",
        ),
        (
            "data_first.inp",
            "1, 0, 0, 0\n".into(),
            "data_first.inp",
            1,
            "a data line before any keyword",
        ),
        (
            "part.inp",
            "*HEADING\nmodel\n*PART, NAME=Part-1\n".into(),
            "part.inp",
            3,
            "*PART 'Part-1' has no *END PART after it",
        ),
        (
            "twice.inp",
            "*NODE\n1, 0, 0, 0\n\n1, 1, 0, 0\n".into(),
            "twice.inp",
            4,
            "node 1 is defined twice",
        ),
        (
            "includes_broken.inp",
            format!("{NODES}*INCLUDE, INPUT=broken_part.inp\n"),
            "broken_part.inp",
            2,
            "expected a node id (a positive integer), found '-3'",
        ),
        (
            "cycle.inp",
            "*HEADING\n*INCLUDE, INPUT=cycle.inp\n".into(),
            "cycle.inp",
            2,
            "includes itself",
        ),
        (
            "missing_include.inp",
            "*INCLUDE, INPUT=nowhere.inp\n".into(),
            "missing_include.inp",
            1,
            "cannot read the included file",
        ),
    ];
    write(dir.path(), "broken_part.inp", "*NODE\n-3, 0, 0, 0\n");
    for (name, text, file, line, message) in cases {
        let path = write(dir.path(), name, &text);
        let e = read_inp(&path)
            .err()
            .unwrap_or_else(|| panic!("{name} reads"));
        let e = e.to_string();
        let at = format!("{}' at line {line}: ", dir.path().join(file).display());
        assert!(e.contains(&at), "{name}: {e}");
        assert!(e.contains(message), "{name}: {e}");
    }
    // not a mesh: no volume element; a surface element on no volume element
    let path = write(dir.path(), "no_volume.inp", NODES);
    let e = read_inp(&path).err().unwrap().to_string();
    assert!(e.contains("no C3D4 or C3D8 volume elements"), "{e}");
    let path = write(
        dir.path(),
        "orphan.inp",
        &format!("{NODES}*NODE\n5, 5, 5, 5\n{element}*ELEMENT, TYPE=S3, ELSET=skin\n2, 1, 2, 5\n"),
    );
    let e = read_inp(&path).err().unwrap().to_string();
    assert!(
        e.contains("surface element 2 of element set 'skin' is not a face of any volume element"),
        "{e}"
    );
}

/// Runs a case file `text` written in a fresh folder.
fn run_case(text: &str) -> (tempfile::TempDir, signorini::run::RunOutcome) {
    let dir = tempfile::tempdir().unwrap();
    let case = write(dir.path(), "case.toml", text);
    let outcome = run(
        &case,
        &RunOptions {
            output: Some(dir.path().join("results")),
            threads: None,
            cancel: None,
            restart: None,
        },
    )
    .expect("the case runs");
    (dir, outcome)
}

/// The same neo-Hookean bar, clamped on `fixed`, held by node sets at the
/// corner and edge, under pressure on `loaded`, solved from the `.msh` and
/// from the `.inp` Gmsh wrote: the displacements agree to round-off
/// (1e-12 of the largest; measured 2.6e-15 of 0.21, the deck's coordinates
/// having 14 digits).
#[test]
fn same_result_from_inp_and_msh() {
    let case = |mesh: &str| {
        format!(
            r#"
[mesh]
file = "{}"
[[material]]
region = "bar"
model = "neo_hookean"
youngs_modulus = 100.0
poisson_ratio = 0.3
[[displacement]]
surface = "fixed"
x = 0.0
[[displacement]]
nodes = "origin"
y = 0.0
z = 0.0
[[displacement]]
nodes = "edge"
z = 0.0
[[pressure]]
surface = "loaded"
value = -5.0
[[step]]
name = "pull"
end_time = 1.0
initial_increment = 0.5
"#,
            data(mesh).display()
        )
    };
    let (_a, msh) = run_case(&case("bar_tet.msh"));
    let (_b, inp) = run_case(&case("bar_tet.inp"));
    let scale = msh.displacement.iter().fold(0.0f64, |m, u| m.max(u.abs()));
    assert!(scale > 0.1, "{scale}"); // a stretch of several per cent
    let worst = msh
        .displacement
        .iter()
        .zip(&inp.displacement)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    assert!(
        worst <= 1e-12 * scale,
        "largest difference {worst:e} of {scale}"
    );
    // the reaction on the clamped end balances the pull, also by node sets
    let last = inp.summary.increments.last().unwrap();
    let pull = 5.0 * 1.0 * 1.0;
    assert!((last.reaction_forces["fixed"][0] + pull).abs() < 1e-8 * pull);
    assert!(last.reaction_forces.contains_key("origin"));
}
