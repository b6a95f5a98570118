//! Node-to-surface contact on quadratic faces is refused at set-up:
//! it gives the corners of a Tri6 face no share of a uniform pressure.
//! The error names the surface, says why and what to do. Without a
//! `discretisation` key quadratic faces take dual mortar (issue 28), and
//! the case builds.

use signorini::mesh::structured::box_mesh;
use signorini::mesh::ElementKind;

const CASE: &str = r#"
[[material]]
region = "body"
model = "linear_elastic"
youngs_modulus = 100.0
poisson_ratio = 0.3

[[displacement]]
surface = "zmin"
x = 0.0
y = 0.0
z = 0.0

[[obstacle]]
name = "wall"
shape = "plane"
point = [0.0, 0.0, 1.1]
normal = [0.0, 0.0, -1.0]

[[step]]
name = "load"
end_time = 1.0
"#;

fn build_error(kind: ElementKind, contact: &str) -> String {
    let dir = tempfile::tempdir().unwrap();
    let mesh = box_mesh(kind, [1, 1, 1], [1.0, 1.0, 1.0]);
    let text = format!("{CASE}\n[[contact]]\n{contact}\n");
    let case = signorini::case::from_mesh(&text, dir.path(), mesh).unwrap();
    match case.build_problem() {
        Ok(_) => String::new(),
        Err(e) => e.to_string(),
    }
}

/// A Tet10 body's Tri6 face against a rigid plane, and a Hex20 body's
/// Quad8 faces paired as secondary and primary surfaces, both with
/// `discretisation = "node_to_surface"`: refused with the surface's name,
/// the reason (mortar) and the way out (a linear mesh); the same case on
/// Tet4 builds, and so does the Tet10 case without the key (mortar by
/// default).
#[test]
fn quadratic_contact_surfaces_are_refused_with_the_way_out() {
    let nodal = "\ndiscretisation = \"node_to_surface\"";
    let obstacle = "surface = \"zmax\"\nobstacle = \"wall\"";
    let message = build_error(ElementKind::Tet10, &format!("{obstacle}{nodal}"));
    for words in [
        "contact[0]",
        "'zmax'",
        "quadratic faces",
        "mortar",
        "linear elements",
    ] {
        assert!(message.contains(words), "missing '{words}' in: {message}");
    }
    let between = "surface = \"zmax\"\nprimary = \"xmin\"";
    let message = build_error(ElementKind::Hex20, &format!("{between}{nodal}"));
    // the primary surface is checked first
    assert!(
        message.contains("'xmin'") && message.contains("mortar"),
        "{message}"
    );
    assert_eq!(
        build_error(ElementKind::Tet4, &format!("{obstacle}{nodal}")),
        ""
    );
    assert_eq!(build_error(ElementKind::Tet10, obstacle), "");
}
