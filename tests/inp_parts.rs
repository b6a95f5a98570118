//! Parts, instances and the assembly of an Abaqus/CAE deck: a part of one
//! C3D8 cube placed twice (the second translated, then turned a quarter
//! about a vertical axis), ids local to the part mapped to global ones,
//! sets and surfaces qualified by instance, assembly sets with
//! `INSTANCE=`, names compared without case.

use signorini::mesh::inp::read_inp;
use std::path::PathBuf;

const PART: &str = "\
*Heading
** two instances of one part
*Part, name=Cube
*Node
      1,           0.,           0.,           0.
      2,           1.,           0.,           0.
      3,           1.,           1.,           0.
      4,           0.,           1.,           0.
      5,           0.,           0.,           1.
      6,           1.,           0.,           1.
      7,           1.,           1.,           1.
      8,           0.,           1.,           1.
*Element, type=C3D8R
1, 1, 2, 3, 4, 5, 6, 7, 8
*Nset, nset=Bottom
 1, 2, 3, 4
*Elset, elset=All
 1,
*Surface, type=ELEMENT, name=Top
All, S2
*Solid Section, elset=All, material=Steel
,
*End Part
*Assembly, name=Assembly
*Instance, name=Cube-1, part=CUBE
*End Instance
*Instance, name=Cube-2, part=Cube
 0., 0., 2.
 1., 0., 0., 1., 0., 5., 90.
*End Instance
*Nset, nset=Corner, instance=Cube-2
 7,
*Elset, elset=Both
 cube-1.all, Cube-2.All
*End Assembly
";

fn write(name: &str, text: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("signorini-inp-parts-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// The second instance's node 7 (1, 1, 1) is translated to (1, 1, 3), then
/// turned 90° about the vertical axis through (1, 0): (x − 1, y) = (0, 1)
/// turns to (−1, 0), so the node lands at (0, 0, 3).
#[test]
fn two_instances_of_one_part() {
    let deck = read_inp(&write("parts.inp", PART)).unwrap();
    let m = &deck.mesh;
    assert_eq!(m.nodes.len(), 16);
    assert_eq!(m.elements.len(), 2);
    // the first instance keeps its ids, the second follows the largest
    assert_eq!(m.node_ids[..8], [1, 2, 3, 4, 5, 6, 7, 8]);
    assert_eq!(m.node_ids[8..], [9, 10, 11, 12, 13, 14, 15, 16]);
    assert_eq!(m.elements[1].id, 2);
    let corner = &m.node_set("Corner").unwrap().nodes;
    assert_eq!(corner.len(), 1);
    let x = m.nodes[corner[0]];
    for (a, b) in x.iter().zip([0.0, 0.0, 3.0]) {
        assert!((a - b).abs() < 1e-14, "{x:?}");
    }
    // every node of the second cube: translated then turned (x−1, y) → (−y, x−1)
    for k in 0..8 {
        let [x0, y0, z0] = m.nodes[k];
        let [x, y, z] = m.nodes[8 + k];
        let want = [1.0 - y0, x0 - 1.0, z0 + 2.0];
        for (a, b) in [x, y, z].iter().zip(want) {
            assert!(
                (a - b).abs() < 1e-14,
                "node {k}: {:?} vs {want:?}",
                [x, y, z]
            );
        }
    }
    // qualified sets and surfaces, one per instance, and the instances' own
    for name in ["Cube-1.Bottom", "Cube-2.Bottom", "Cube-1", "Cube-2"] {
        assert_eq!(
            m.node_set(name).map(|s| s.nodes.len()),
            Some(if name.contains('.') { 4 } else { 8 }),
            "{name}"
        );
    }
    assert_eq!(m.region("Both").unwrap().elements, [0, 1]);
    assert_eq!(m.region("Cube-2.All").unwrap().elements, [1]);
    let top = m.surface("Cube-2.Top").unwrap();
    assert_eq!(top.facets.len(), 1);
    // the top face of the turned cube is still at z = 3
    assert!(top.facets[0]
        .nodes
        .iter()
        .all(|&n| (m.nodes[n][2] - 3.0).abs() < 1e-14));
}

/// The errors of parts and instances name the line and what to fix.
#[test]
fn bad_parts_and_instances() {
    let cases = [
        (
            PART.replace("part=CUBE", "part=Sphere"),
            25,
            "no *PART named 'Sphere'",
        ),
        (
            PART.replace(" cube-1.all", " Cube-3.all"),
            34,
            "'Cube-3.all' names the instance 'Cube-3', which no *INSTANCE defines",
        ),
        (
            PART.replace("1., 0., 5., 90.", "1., 0., 0., 90."),
            29,
            "zero length",
        ),
        (
            PART.replace("*End Part\n", ""),
            3,
            "*PART 'Cube' has no *END PART",
        ),
        (
            PART.replace("instance=Cube-2", "instance=Cube-9"),
            31,
            "INSTANCE=Cube-9: no *INSTANCE of that name",
        ),
    ];
    for (k, (text, line, message)) in cases.iter().enumerate() {
        let e = read_inp(&write(&format!("bad{k}.inp"), text))
            .err()
            .unwrap_or_else(|| panic!("case {k}: no error"))
            .to_string();
        assert!(
            e.contains(&format!("bad{k}.inp' at line {line}:")),
            "{k}: {e}"
        );
        assert!(e.contains(message), "{k}: {e}");
    }
}
