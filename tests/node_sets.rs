//! Node sets in the case file: prescribed displacements on `nodes = "set"`
//! and `[[nodal_force]]` (a total force split equally over a set's nodes),
//! against the closed-form bar `u = F L / (E A)`, on meshes read from
//! `.inp` decks written here.

use signorini::mesh::structured::box_mesh;
use signorini::mesh::{ElementKind, Mesh};
use signorini::run::{run, RunOptions};
use std::fmt::Write;
use std::path::Path;

/// An `.inp` deck of `mesh` with one element set `bar` and the node sets
/// `(name, nodes)`.
fn deck(mesh: &Mesh, sets: &[(&str, Vec<usize>)]) -> String {
    let mut s = String::from("*HEADING\n bar\n*NODE\n");
    for (id, x) in mesh.node_ids.iter().zip(&mesh.nodes) {
        writeln!(s, "{id}, {:.17e}, {:.17e}, {:.17e}", x[0], x[1], x[2]).unwrap();
    }
    let kind = match mesh.elements[0].kind {
        ElementKind::Tet4 => "C3D4",
        ElementKind::Hex8 => "C3D8",
        other => panic!("{other:?}: this helper writes linear decks only"),
    };
    writeln!(s, "*ELEMENT, TYPE={kind}, ELSET=bar").unwrap();
    for e in &mesh.elements {
        let nodes: Vec<String> = e
            .nodes
            .iter()
            .map(|&n| mesh.node_ids[n].to_string())
            .collect();
        writeln!(s, "{}, {}", e.id, nodes.join(", ")).unwrap();
    }
    for (name, nodes) in sets {
        writeln!(s, "*NSET, NSET={name}").unwrap();
        for chunk in nodes.chunks(8) {
            let ids: Vec<String> = chunk
                .iter()
                .map(|&n| mesh.node_ids[n].to_string())
                .collect();
            writeln!(s, "{},", ids.join(", ")).unwrap();
        }
    }
    s
}

/// Nodes of `mesh` where `keep(x)`.
fn nodes_where(mesh: &Mesh, keep: impl Fn([f64; 3]) -> bool) -> Vec<usize> {
    (0..mesh.nodes.len())
        .filter(|&n| keep(mesh.nodes[n]))
        .collect()
}

const E: f64 = 1000.0;
const F: f64 = 2.0;
const L: f64 = 10.0;

/// A linear elastic bar `[0, L] × [0, 1]²` on rollers at `x = 0` (`u_x = 0`
/// on the end, `u_y = 0` on its edge `y = 0`, `u_z = 0` on its edge `z = 0`:
/// no constraint on the Poisson contraction), pulled by the total force `F`
/// along x spread equally over the nodes of the end `x = L`. Returns the
/// mesh, the final displacements and the reaction on the support `clamp`.
fn pulled_bar(mesh: Mesh) -> (Mesh, Vec<f64>, [f64; 3]) {
    let dir = tempfile::tempdir().unwrap();
    let sets = [
        ("clamp", nodes_where(&mesh, |x| x[0] == 0.0)),
        (
            "clamp_y",
            nodes_where(&mesh, |x| x[0] == 0.0 && x[1] == 0.0),
        ),
        (
            "clamp_z",
            nodes_where(&mesh, |x| x[0] == 0.0 && x[2] == 0.0),
        ),
        ("tip", nodes_where(&mesh, |x| x[0] == L)),
    ];
    std::fs::write(dir.path().join("bar.inp"), deck(&mesh, &sets)).unwrap();
    let case = format!(
        r#"
[mesh]
file = "bar.inp"
[[material]]
region = "bar"
model = "linear_elastic"
youngs_modulus = {E}
poisson_ratio = 0.3
[[displacement]]
nodes = "clamp"
x = 0.0
[[displacement]]
nodes = "clamp_y"
y = 0.0
[[displacement]]
nodes = "clamp_z"
z = 0.0
[[nodal_force]]
nodes = "tip"
value = [{F}, 0.0, 0.0]
[[step]]
name = "pull"
end_time = 1.0
[solver]
residual_tolerance = 1e-12
[[output.history]]
name = "support_x"
quantity = "reaction_force_x"
nodes = "clamp"
[[output.history]]
name = "support"
quantity = "reaction_force"
nodes = "clamp"
"#
    );
    std::fs::write(dir.path().join("case.toml"), case).unwrap();
    let outcome = run(
        &dir.path().join("case.toml"),
        &RunOptions {
            output: Some(dir.path().join("results")),
            threads: None,
            cancel: None,
            restart: None,
        },
    )
    .expect("the bar runs");
    let reaction = outcome.summary.increments.last().unwrap().reaction_forces["clamp"];
    // the histories on the node set read the same reaction: `−F` along x
    let last_row = |file: &str| -> Vec<f64> {
        let text = std::fs::read_to_string(dir.path().join("results").join(file)).unwrap();
        let row = text.lines().last().unwrap();
        row.split(',').map(|v| v.parse().unwrap()).collect()
    };
    let (x, all) = (last_row("support_x.csv"), last_row("support.csv"));
    assert_eq!((x.len(), all.len(), x[0], all[0]), (2, 4, 1.0, 1.0));
    assert!((x[1] + F).abs() < 1e-10 * F, "{x:?}");
    for (a, b) in all[1..].iter().zip(reaction) {
        assert!((a - b).abs() < 1e-12 * F, "{all:?} vs {reaction:?}");
    }
    (mesh, outcome.displacement, reaction)
}

/// One Hex8 across the section: the four tip nodes carry `F/4` each, the
/// consistent load of a uniform traction, so the uniform stress `F/A` is
/// the exact discrete solution: `u_x = F x / (E A)` at every node (to
/// 1e-10), and the reaction is `−F` to 1e-10.
#[test]
fn point_load_on_a_bar_is_exact_for_the_linear_patch() {
    let (mesh, u, reaction) = pulled_bar(box_mesh(ElementKind::Hex8, [8, 1, 1], [L, 1.0, 1.0]));
    let strain = F / (E * 1.0);
    for (n, x) in mesh.nodes.iter().enumerate() {
        assert!(
            (u[3 * n] - strain * x[0]).abs() < 1e-10 * strain * L,
            "node {n} at {x:?}: u_x = {}",
            u[3 * n]
        );
    }
    assert!((reaction[0] + F).abs() < 1e-10 * F, "{reaction:?}");
    assert!(reaction[1].abs() < 1e-10 * F && reaction[2].abs() < 1e-10 * F);
}

/// 2 × 2 Tet4 cells across the section: nine tip nodes with `F/9` each is
/// not the consistent load of a uniform traction (corners would take
/// `F/16`), so the stress is uniform only away from the tip (Saint-Venant):
/// the mean tip displacement is `F L/(E A)` within 2 % (measured +1.04 %),
/// the mean at mid-length `F L/(2 E A)` within 1e-5 (measured 2.7e-7), and
/// the reaction is `−F` to 1e-10 whatever the mesh.
#[test]
fn point_load_on_a_bar_within_discretisation_error() {
    let (mesh, u, reaction) = pulled_bar(box_mesh(ElementKind::Tet4, [20, 2, 2], [L, 1.0, 1.0]));
    let tip = nodes_where(&mesh, |x| x[0] == L);
    assert_eq!(tip.len(), 9);
    let mean = tip.iter().map(|&n| u[3 * n]).sum::<f64>() / tip.len() as f64;
    let exact = F * L / (E * 1.0);
    let mid = nodes_where(&mesh, |x| x[0] == 0.5 * L);
    let mid_mean = mid.iter().map(|&n| u[3 * n]).sum::<f64>() / mid.len() as f64;
    let tip_error = (mean - exact) / exact;
    let mid_error = (mid_mean - 0.5 * exact) / (0.5 * exact);
    assert!(tip_error.abs() < 0.02, "tip: {mean} against {exact}");
    assert!(
        mid_error.abs() < 1e-5,
        "mid-length: {mid_mean} against {}",
        0.5 * exact
    );
    assert!((reaction[0] + F).abs() < 1e-10 * F, "{reaction:?}");
}

/// Case-file errors about node sets name the key and list what the mesh has.
#[test]
fn node_set_errors_name_the_key() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = box_mesh(ElementKind::Hex8, [1, 1, 1], [1.0, 1.0, 1.0]);
    let sets = [("end", nodes_where(&mesh, |x| x[0] == 0.0))];
    std::fs::write(dir.path().join("m.inp"), deck(&mesh, &sets)).unwrap();
    let check = |body: &str, expected: &str| {
        let text = format!(
            "[mesh]\nfile = \"m.inp\"\n[[material]]\nregion = \"bar\"\nmodel = \"linear_elastic\"\n\
             youngs_modulus = 1.0\npoisson_ratio = 0.3\n[[step]]\nname = \"s\"\nend_time = 1.0\n{body}"
        );
        let path = dir.path().join("case.toml");
        std::fs::write(&path, text).unwrap();
        let e = match signorini::case::load(Path::new(&path)).and_then(|c| c.build_problem()) {
            Ok(_) => panic!("accepted: {body}"),
            Err(e) => e.to_string(),
        };
        assert!(e.contains(expected), "{e}");
    };
    check(
        "[[displacement]]\nnodes = \"tip\"\nx = 0.0\n",
        "displacement[0].nodes: the mesh has no node set (0D/1D physical group, .inp *NSET) named 'tip'; it has: end",
    );
    check(
        "[[displacement]]\nnodes = \"end\"\nsurface = \"end\"\nx = 0.0\n",
        "displacement[0]: give either `surface` (a surface set) or `nodes` (a node set), not both",
    );
    check(
        "[[displacement]]\nx = 0.0\n",
        "displacement[0]: give either `surface` (a surface set) or `nodes` (a node set), not neither",
    );
    check(
        "[[nodal_force]]\nnodes = \"tip\"\nvalue = [1.0, 0.0, 0.0]\n",
        "nodal_force[0].nodes: the mesh has no node set",
    );
    check(
        "[[nodal_force]]\nnodes = \"end\"\nvalue = [1.0, 0.0]\n",
        "nodal_force[0].value",
    );
}
