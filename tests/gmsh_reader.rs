//! Tests of the Gmsh MSH reader on the meshes in `tests/data` (made by the
//! `.geo` scripts there; Gmsh is not needed to run the tests).

use signorini::mesh::gmsh::read_msh;
use signorini::mesh::{ElementKind, Mesh};
use signorini::Error;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
}

fn read(name: &str) -> Mesh {
    read_msh(&data(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

const FLAVOURS: [&str; 4] = ["41_ascii", "41_bin", "22_ascii", "22_bin"];

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Volume of a linear tet or trilinear hex (2×2×2 Gauss rule, exact for the
/// trilinear Jacobian determinant).
fn element_volume(mesh: &Mesh, e: usize) -> f64 {
    let el = &mesh.elements[e];
    let x: Vec<[f64; 3]> = el.nodes.iter().map(|&n| mesh.nodes[n]).collect();
    match el.kind {
        ElementKind::Tet4 => dot(sub(x[1], x[0]), cross(sub(x[2], x[0]), sub(x[3], x[0]))) / 6.0,
        ElementKind::Hex8 => {
            let corners = [
                [-1., -1., -1.],
                [1., -1., -1.],
                [1., 1., -1.],
                [-1., 1., -1.],
                [-1., -1., 1.],
                [1., -1., 1.],
                [1., 1., 1.],
                [-1., 1., 1.],
            ];
            let g = 1.0 / 3f64.sqrt();
            let mut v = 0.0;
            for p in [
                [-g, -g, -g],
                [g, -g, -g],
                [g, g, -g],
                [-g, g, -g],
                [-g, -g, g],
                [g, -g, g],
                [g, g, g],
                [-g, g, g],
            ] {
                let mut j = [[0.0; 3]; 3]; // j[i][k] = dx_i / dxi_k
                for (a, c) in corners.iter().enumerate() {
                    let f = |k: usize| 1.0 + c[k] * p[k];
                    let dn = [
                        c[0] * f(1) * f(2) / 8.0,
                        f(0) * c[1] * f(2) / 8.0,
                        f(0) * f(1) * c[2] / 8.0,
                    ];
                    for i in 0..3 {
                        for k in 0..3 {
                            j[i][k] += x[a][i] * dn[k];
                        }
                    }
                }
                v += dot(j[0], cross(j[1], j[2])); // det J, weights 1
            }
            v
        }
        // the other kinds by the library's own rule (tests/quadratic_elements.rs)
        kind => signorini::assembly::kernel::reference_geometry(kind, &x)
            .expect("a valid element")
            .iter()
            .map(|p| p.dv)
            .sum(),
    }
}

fn total_volume(mesh: &Mesh, elements: &[usize]) -> f64 {
    elements.iter().map(|&e| element_volume(mesh, e)).sum()
}

fn all(mesh: &Mesh) -> Vec<usize> {
    (0..mesh.elements.len()).collect()
}

/// Element node lists as sorted lists of node ids, sorted.
fn elements_by_id(mesh: &Mesh) -> Vec<Vec<u64>> {
    let mut v: Vec<Vec<u64>> = mesh
        .elements
        .iter()
        .map(|e| e.nodes.iter().map(|&n| mesh.node_ids[n]).collect())
        .collect();
    v.sort();
    v
}

/// Node count, element count, (name, size) of every region and surface set.
type Summary = (usize, usize, Vec<(String, usize)>, Vec<(String, usize)>);

fn summary(mesh: &Mesh) -> Summary {
    (
        mesh.nodes.len(),
        mesh.elements.len(),
        mesh.regions
            .iter()
            .map(|r| (r.name.clone(), r.elements.len()))
            .collect(),
        mesh.surfaces
            .iter()
            .map(|s| (s.name.clone(), s.facets.len()))
            .collect(),
    )
}

fn check_flavours_agree(stem: &str, kind: ElementKind) {
    let meshes: Vec<Mesh> = FLAVOURS
        .iter()
        .map(|f| read(&format!("{stem}_{f}.msh")))
        .collect();
    let reference = &meshes[0];
    assert!(reference.elements.iter().all(|e| e.kind == kind));
    assert_eq!(reference.region_names(), ["body"]);
    assert_eq!(reference.surface_names(), ["bottom", "top", "contact"]);
    let coords: HashMap<u64, [f64; 3]> = reference
        .node_ids
        .iter()
        .copied()
        .zip(reference.nodes.iter().copied())
        .collect();
    for (mesh, flavour) in meshes.iter().zip(FLAVOURS) {
        assert_eq!(summary(mesh), summary(reference), "{stem} {flavour}");
        for (id, x) in mesh.node_ids.iter().zip(&mesh.nodes) {
            let y = coords[id];
            for k in 0..3 {
                assert!((x[k] - y[k]).abs() <= 1e-15, "{stem} {flavour}: node {id}");
            }
        }
        assert_eq!(
            elements_by_id(mesh),
            elements_by_id(reference),
            "{stem} {flavour}"
        );
        let volume = total_volume(mesh, &all(mesh));
        assert!(
            (volume - 1.0).abs() < 1e-12,
            "{stem} {flavour}: volume {volume}"
        );
        assert!(all(mesh).iter().all(|&e| element_volume(mesh, e) > 0.0));
    }
}

#[test]
fn tet_mesh_reads_the_same_in_all_four_flavours() {
    check_flavours_agree("cube_tet", ElementKind::Tet4);
}

#[test]
fn hex_mesh_reads_the_same_in_all_four_flavours() {
    check_flavours_agree("cube_hex", ElementKind::Hex8);
    assert_eq!(read("cube_hex_41_ascii.msh").elements.len(), 27);
}

fn facet_normal(mesh: &Mesh, nodes: &[usize]) -> [f64; 3] {
    let x = |i: usize| mesh.nodes[nodes[i]];
    cross(sub(x(1), x(0)), sub(x(2), x(0)))
}

#[test]
fn surface_facets_point_outward() {
    for stem in ["cube_tet", "cube_hex"] {
        for flavour in FLAVOURS {
            let mesh = read(&format!("{stem}_{flavour}.msh"));
            for (name, sign) in [("top", 1.0), ("bottom", -1.0), ("contact", 1.0)] {
                let surface = mesh.surface(name).unwrap();
                assert!(!surface.facets.is_empty());
                for f in &surface.facets {
                    let n = facet_normal(&mesh, &f.nodes);
                    assert!(sign * n[2] > 0.0, "{stem} {flavour} {name} facet {}", f.id);
                    assert!(n[0].abs() < 1e-12 && n[1].abs() < 1e-12);
                }
            }
            // "contact" is the same geometric surface as "top"
            let sorted = |name: &str| {
                let mut v: Vec<Vec<usize>> = mesh
                    .surface(name)
                    .unwrap()
                    .facets
                    .iter()
                    .map(|f| f.nodes.clone())
                    .collect();
                v.sort();
                v
            };
            assert_eq!(sorted("top"), sorted("contact"));
        }
    }
}

#[test]
fn two_physical_volumes_give_two_regions() {
    let a = read("two_blocks_41_param.msh");
    let b = read("two_blocks_22_bin.msh");
    assert_eq!(summary(&a), summary(&b));
    assert_eq!(elements_by_id(&a), elements_by_id(&b));
    for mesh in [&a, &b] {
        // the unnamed physical volume 7 is called "7"
        assert_eq!(mesh.region_names(), ["lower", "7"]);
        assert_eq!(mesh.surface_names(), ["bottom", "interface"]);
        for region in &mesh.regions {
            let v = total_volume(mesh, &region.elements);
            assert!((v - 1.0).abs() < 1e-12, "{}: {v}", region.name);
        }
        let lower = mesh.region("lower").unwrap();
        assert!(lower.elements.iter().all(|&e| mesh.elements[e]
            .nodes
            .iter()
            .all(|&n| mesh.nodes[n][2] <= 1.0)));
    }
    // parametric coordinates in the 4.1 file are skipped, not read as nodes
    let coords: HashMap<u64, [f64; 3]> = b
        .node_ids
        .iter()
        .copied()
        .zip(b.nodes.iter().copied())
        .collect();
    for (id, x) in a.node_ids.iter().zip(&a.nodes) {
        let y = coords[id];
        assert!((0..3).all(|k| (x[k] - y[k]).abs() <= 1e-15), "node {id}");
    }
}

const SPARSE_41: &str = r#"$MeshFormat
4.1 0 8
$EndMeshFormat
$Comments
free text, even a $Nodes word
$EndComments
$Entities
0 0 0 1
1 0 0 0 1 1 1 0 0
$EndEntities
$Nodes
1 5 10 500000
3 1 0 5
10
200
3000
40000
500000
0 0 0
1 0 0
0 1 0
0 0 1
1 1 1
$EndNodes
$Elements
1 2 5 9
3 1 4 2
5 10 200 3000 40000
9 200 3000 40000 500000
$EndElements
$NodeData
1
"u"
1
0.0
3
0
1
5
10 0
200 0
3000 0
40000 0
500000 0
$EndNodeData
"#;

fn write_temp(dir: &tempfile::TempDir, name: &str, contents: &[u8]) -> PathBuf {
    let path = dir.path().join(name);
    std::fs::write(&path, contents).unwrap();
    path
}

#[test]
fn sparse_tags_unknown_sections_and_default_region() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = read_msh(&write_temp(&dir, "sparse.msh", SPARSE_41.as_bytes())).unwrap();
    assert_eq!(mesh.node_ids, [10, 200, 3000, 40000, 500000]);
    assert_eq!(mesh.elements.len(), 2);
    assert_eq!(mesh.elements[1].nodes, [1, 2, 3, 4]);
    assert_eq!(mesh.elements[1].id, 9);
    assert_eq!(mesh.region_names(), ["default"]);
    assert!(mesh.surfaces.is_empty());
    assert!((total_volume(&mesh, &all(&mesh)) - 0.5).abs() < 1e-15);
}

/// A 2.2 mesh: one tet (physical volume 1 "body"), one triangle in physical
/// surface 2 "top", and the triangle lines given.
fn small_22(element_lines: &str) -> String {
    format!(
        "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n2\n2 2 \"top\"\n3 1 \"body\"\n\
         $EndPhysicalNames\n$Nodes\n5\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n5 1 1 1\n$EndNodes\n\
         $Elements\n{}\n{element_lines}$EndElements\n",
        element_lines.lines().count()
    )
}

fn read_err(contents: &[u8]) -> Error {
    let dir = tempfile::tempdir().unwrap();
    let path = write_temp(&dir, "bad.msh", contents);
    match read_msh(&path) {
        Ok(_) => panic!("expected an error"),
        Err(e) => e,
    }
}

fn assert_contains(e: &Error, parts: &[&str]) {
    let text = e.to_string();
    for p in parts {
        assert!(text.contains(p), "'{text}' does not contain '{p}'");
    }
}

#[test]
fn small_22_mesh_orients_its_facet() {
    let dir = tempfile::tempdir().unwrap();
    let text = small_22("1 4 2 1 1 1 2 3 4\n2 2 2 2 5 2 3 4\n");
    let mesh = read_msh(&write_temp(&dir, "ok.msh", text.as_bytes())).unwrap();
    assert_eq!(mesh.region_names(), ["body"]);
    let facet = &mesh.surface("top").unwrap().facets[0];
    assert_eq!(facet.id, 2);
    let n = facet_normal(&mesh, &facet.nodes);
    assert!(n.iter().all(|&c| c > 0.0), "outward is (1,1,1): {n:?}");
}

#[test]
fn missing_file_is_an_io_error() {
    let e = read_msh(&data("no_such_mesh.msh")).unwrap_err();
    assert!(matches!(e, Error::Io { .. }), "{e}");
    assert_contains(&e, &["no_such_mesh.msh"]);
}

#[test]
fn truncated_ascii_file() {
    let text = std::fs::read_to_string(data("cube_tet_41_ascii.msh")).unwrap();
    let cut: String = text.lines().take(1500).map(|l| format!("{l}\n")).collect();
    let e = read_err(cut.as_bytes());
    assert!(matches!(e, Error::MeshSyntax { line: 1501, .. }), "{e}");
    assert_contains(&e, &["line 1501", "end of file"]);
}

#[test]
fn truncated_binary_files() {
    for name in ["cube_tet_41_bin.msh", "cube_tet_22_bin.msh"] {
        let bytes = std::fs::read(data(name)).unwrap();
        let e = read_err(&bytes[..bytes.len() * 3 / 5]);
        assert!(matches!(e, Error::MeshSyntax { .. }), "{e}");
        assert_contains(&e, &["byte offset", "end of file", "binary $Elements"]);
    }
}

#[test]
fn wrong_version() {
    let text = std::fs::read_to_string(data("cube_hex_41_ascii.msh")).unwrap();
    for v in ["3.0", "4.0", "1.0"] {
        let e = read_err(text.replacen("4.1 0 8", &format!("{v} 0 8"), 1).as_bytes());
        assert_contains(&e, &["line 2", v, "4.1", "2.2", "not supported"]);
    }
    let e = read_err(b"$NOD\n1\n1 0 0 0\n$ENDNOD\n");
    assert_contains(&e, &["line 1", "expected $MeshFormat", "$NOD"]);
}

#[test]
fn missing_sections() {
    let text = std::fs::read_to_string(data("cube_hex_22_ascii.msh")).unwrap();
    let no_elements = &text[..text.find("$Elements").unwrap()];
    assert_contains(&read_err(no_elements.as_bytes()), &["no $Elements section"]);
    let start = text.find("$Nodes").unwrap();
    let end = text.find("$Elements").unwrap();
    let no_nodes = format!("{}{}", &text[..start], &text[end..]);
    assert_contains(
        &read_err(no_nodes.as_bytes()),
        &["$Elements comes before $Nodes"],
    );
    let e = read_err(b"$MeshFormat\n2.2 0 8\n$EndMeshFormat\n");
    assert_contains(&e, &["no $Nodes section"]);
    let e = read_err(small_22("1 2 2 2 5 2 3 4\n").as_bytes());
    assert_contains(&e, &["no volume elements (Tet4, Tet10, Hex8"]);
}

#[test]
fn element_with_a_missing_node_tag() {
    // line 19 of the small mesh is the tet
    let e = read_err(small_22("1 4 2 1 1 1 2 3 99999\n").as_bytes());
    assert!(matches!(e, Error::MeshSyntax { line: 19, .. }), "{e}");
    assert_contains(&e, &["line 19", "element 1", "node tag 99999"]);
    // and in a Gmsh-written 4.1 file
    let text = std::fs::read_to_string(data("cube_hex_41_ascii.msh")).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let last = lines.iter().rposition(|l| l.starts_with("45 ")).unwrap();
    let mut changed: Vec<String> = lines.iter().map(|l| l.to_string()).collect();
    changed[last] = "45 1 2 3 4 5 6 7 77777".into();
    let e = read_err(changed.join("\n").as_bytes());
    assert_contains(
        &e,
        &[
            &format!("line {}", last + 1),
            "element 45",
            "node tag 77777",
        ],
    );
}

#[test]
fn element_with_too_few_nodes() {
    let e = read_err(small_22("1 4 2 1 1 1 2 3\n").as_bytes());
    assert_contains(
        &e,
        &[
            "line 19",
            "expected 4 node tags for element 1 of type 4, found 3",
        ],
    );
    let text = std::fs::read_to_string(data("cube_hex_41_ascii.msh")).unwrap();
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    let i = lines.iter().rposition(|l| l.starts_with("45 ")).unwrap();
    lines[i] = "45 1 2 3 4 5 6 7".into();
    let e = read_err(lines.join("\n").as_bytes());
    assert_contains(
        &e,
        &[
            &format!("line {}", i + 1),
            "expected 8 node tags for element 45 of type 5, found 7",
        ],
    );
}

#[test]
fn element_with_a_repeated_node() {
    let e = read_err(small_22("1 4 2 1 1 1 2 3 2\n").as_bytes());
    assert_contains(&e, &["line 19", "element 1", "node 2 more than once"]);
}

#[test]
fn unsupported_volume_element_type() {
    // a 10-node tetrahedron is read now (tests/quadratic_elements.rs)
    let mesh = read_msh(&data("cube_tet10_41.msh")).unwrap();
    assert!(mesh.elements.iter().all(|e| e.kind == ElementKind::Tet10));
    // a 5-node pyramid is not
    let e = read_err(small_22("1 7 2 1 1 1 2 3 4 5\n").as_bytes());
    assert!(matches!(e, Error::Mesh { .. }), "{e}");
    assert_contains(
        &e,
        &["element 1 ", "5-node pyramid", "type 7", "Tet4", "Wedge15"],
    );
}

#[test]
fn unsupported_facet_type_in_a_surface_group() {
    // a 9-node quadrangle (Tri6 and Quad8 are read: tests/quadratic_elements.rs)
    let e = read_err(small_22("1 4 2 1 1 1 2 3 4\n2 10 2 2 5 2 3 4 1 1 1 1 1 1\n").as_bytes());
    assert_contains(&e, &["element 2", "9-node", "type 10", "Tri3", "Quad8"]);
    // ... but ignored when it is in no physical group
    let dir = tempfile::tempdir().unwrap();
    let text = small_22("1 4 2 1 1 1 2 3 4\n2 10 2 0 5 2 3 4 1 2 3 1 2 3\n3 1 2 0 3 1 2\n");
    assert!(read_msh(&write_temp(&dir, "ok.msh", text.as_bytes())).is_ok());
}

#[test]
fn facet_on_no_volume_element() {
    let e = read_err(small_22("1 4 2 1 1 1 2 3 4\n12 2 2 2 5 2 3 5\n").as_bytes());
    assert!(matches!(e, Error::Mesh { .. }), "{e}");
    assert_contains(
        &e,
        &["facet 12 of surface 'top' is not a face of any volume element"],
    );
}

#[test]
fn binary_error_gives_the_byte_offset() {
    // Corrupt the first element-block header of a 2.2 binary file: an
    // unknown element type.
    let mut bytes = std::fs::read(data("cube_hex_22_bin.msh")).unwrap();
    let header = bytes.windows(10).position(|w| w == b"$Elements\n").unwrap();
    let start = header
        + 10
        + bytes[header + 10..]
            .iter()
            .position(|&c| c == b'\n')
            .unwrap()
        + 1;
    bytes[start..start + 4].copy_from_slice(&1234i32.to_le_bytes());
    let e = read_err(&bytes);
    assert_contains(
        &e,
        &[
            &format!("byte offset {start}"),
            "unknown Gmsh element type 1234",
        ],
    );
}

/// Every truncation and many random byte changes of the small meshes give
/// an error or a mesh, never a panic.
#[test]
fn never_panics_on_damaged_files() {
    use rand::{Rng, SeedableRng};
    let mut rng = rand::rngs::StdRng::seed_from_u64(7);
    for flavour in FLAVOURS {
        let bytes = std::fs::read(data(&format!("cube_hex_{flavour}.msh"))).unwrap();
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("damaged.msh");
        for cut in (0..bytes.len()).step_by(7) {
            std::fs::write(&path, &bytes[..cut]).unwrap();
            assert!(read_msh(&path).is_err(), "{flavour} cut at {cut}");
        }
        for _ in 0..300 {
            let mut damaged = bytes.clone();
            for _ in 0..rng.gen_range(1..4) {
                let i = rng.gen_range(0..damaged.len());
                damaged[i] = rng.gen();
            }
            std::fs::write(&path, &damaged).unwrap();
            let _ = read_msh(&path);
        }
    }
}

#[test]
fn msh22_element_in_two_volume_groups_is_one_element() {
    // Gmsh 2.2 writes a volume element once per physical group, with a new
    // element tag each time.
    let dir = tempfile::tempdir().unwrap();
    let text = small_22("1 4 2 1 1 1 2 3 4\n2 4 2 3 1 1 2 3 4\n3 2 2 2 5 2 3 4\n")
        .replace("2\n2 2 \"top\"", "3\n3 3 \"hard\"\n2 2 \"top\"");
    let mesh = read_msh(&write_temp(&dir, "two.msh", text.as_bytes())).unwrap();
    assert_eq!(mesh.elements.len(), 1);
    assert_eq!(mesh.region_names(), ["body", "hard"]);
    assert!(mesh.regions.iter().all(|r| r.elements == [0]));
}
