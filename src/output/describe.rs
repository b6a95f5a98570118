//! The model in words: what `signorini check` prints, what a run's log
//! starts with, and what the terminal shows before the first increment.

use crate::contact::interface::{ContactInterface, Primary};
use crate::contact::laws::NormalLaw;
use crate::contact::obstacle::RigidObstacle;
use crate::mesh::ElementKind;
use crate::problem::Problem;

/// The model's description, a line each: sizes, regions and their
/// materials, sets, loads, contact interfaces (method and parameters in
/// words), steps and solver settings.
pub fn describe_model(problem: &Problem) -> Vec<String> {
    let mut lines = Vec::new();
    lines.extend(sizes(problem));
    lines.extend(regions(problem));
    lines.extend(sets(problem));
    lines.extend(loads(problem));
    lines.extend(problem.contacts.iter().map(contact));
    lines.extend(problem.steps.iter().map(|s| {
        format!(
            "step '{}': pseudo-time to {}, first increment {}, increments between {} and {}",
            s.name, s.end_time, s.initial_increment, s.min_increment, s.max_increment
        )
    }));
    let s = &problem.settings;
    lines.push(format!(
        "solver: Newton–Raphson, at most {} iterations, residual tolerance {:e}, displacement tolerance {:e}, line search {}, at most {} cuts of an increment",
        s.max_iterations,
        s.residual_tolerance,
        s.displacement_tolerance,
        if s.line_search { "on" } else { "off" },
        s.max_cuts
    ));
    lines
}

fn sizes(problem: &Problem) -> Vec<String> {
    let mesh = &problem.model.mesh;
    let count = |kind: ElementKind| mesh.elements.iter().filter(|e| e.kind == kind).count();
    let kinds: Vec<String> = [
        (ElementKind::Tet4, "Tet4"),
        (ElementKind::Hex8, "Hex8"),
        (ElementKind::Tet10, "Tet10"),
        (ElementKind::Hex20, "Hex20"),
        (ElementKind::Hex20R, "Hex20R"),
        (ElementKind::Wedge6, "Wedge6"),
        (ElementKind::Wedge15, "Wedge15"),
    ]
    .into_iter()
    .filter(|(k, _)| count(*k) > 0)
    .map(|(k, name)| format!("{} {name}", count(k)))
    .collect();
    let prescribed = problem.constrained_dofs().iter().filter(|&&c| c).count();
    let multipliers = if problem.num_unknowns() > problem.model.num_dofs() {
        format!(
            ", {} unknowns with the contact multipliers",
            problem.num_unknowns()
        )
    } else {
        String::new()
    };
    vec![format!(
        "model: {} nodes, {} elements ({}), {} dofs ({prescribed} prescribed){multipliers}",
        mesh.num_nodes(),
        mesh.elements.len(),
        kinds.join(", "),
        problem.model.num_dofs(),
    )]
}

/// `n` and `noun`, the noun in the plural unless `n` is 1: "1 increment",
/// "3 increments".
pub fn counted(n: usize, noun: &str) -> String {
    if n == 1 {
        format!("1 {noun}")
    } else {
        format!("{n} {noun}s")
    }
}

/// A material model's name in words.
fn model_in_words(name: &str) -> &str {
    match name {
        "linear_elastic" => "linear elastic (small strain)",
        "saint_venant_kirchhoff" => "Saint Venant–Kirchhoff",
        "neo_hookean" => "neo-Hookean",
        "ogden" => "Ogden",
        other => other,
    }
}

fn regions(problem: &Problem) -> Vec<String> {
    let model = &problem.model;
    model
        .mesh
        .regions
        .iter()
        .map(|r| {
            let material = r
                .elements
                .first()
                .map(|&e| &model.materials[model.element_material[e]]);
            let words = material.map_or_else(
                || "no elements".to_string(),
                |m| format!("{} ({})", model_in_words(m.name()), m.parameters()),
            );
            format!(
                "region '{}': {} elements, {words}",
                r.name,
                r.elements.len()
            )
        })
        .collect()
}

fn sets(problem: &Problem) -> Vec<String> {
    let mesh = &problem.model.mesh;
    let surfaces = mesh.surfaces.iter().map(|s| {
        format!(
            "surface set '{}': {} facets, {} nodes",
            s.name,
            s.facets.len(),
            mesh.surface_nodes(s).len()
        )
    });
    let nodes = mesh
        .node_sets
        .iter()
        .map(|s| format!("node set '{}': {} nodes", s.name, s.nodes.len()));
    surfaces.chain(nodes).collect()
}

fn loads(problem: &Problem) -> Vec<String> {
    const AXES: [&str; 3] = ["x", "y", "z"];
    let prescribed = problem.prescribed.iter().map(|p| {
        let values: Vec<String> = p
            .components
            .iter()
            .map(|&(i, v)| format!("u_{} = {v}", AXES[i]))
            .collect();
        format!(
            "prescribed displacement on '{}' ({} nodes): {}, times its amplitude",
            p.surface,
            p.nodes.len(),
            values.join(", ")
        )
    });
    let pressures = problem.pressures.iter().map(|p| {
        format!(
            "pressure {} on '{}' ({} facets), {}, times its amplitude",
            p.pressure,
            p.surface,
            p.facets.len(),
            if p.follower {
                "following the deformed surface"
            } else {
                "dead (reference normal and area)"
            }
        )
    });
    let body = problem.body_forces.iter().map(|b| {
        format!(
            "body force {:?} per unit volume on region '{}', times its amplitude",
            b.force, b.region
        )
    });
    let nodal = problem.nodal_forces.iter().map(|f| {
        format!(
            "nodal force {:?} on each of the {} nodes of '{}', times its amplitude",
            f.force,
            f.nodes.len(),
            f.set
        )
    });
    let rotations = problem.rotations.iter().map(|r| {
        format!(
            "rotation by {}° about axis {:?} through {:?} on '{}' ({} nodes, all components), \
             times its amplitude, plus the translation {:?} times its amplitude",
            r.angle.to_degrees(),
            r.axis,
            r.centre,
            r.set,
            r.nodes.len(),
            r.translation
        )
    });
    prescribed
        .chain(rotations)
        .chain(pressures)
        .chain(body)
        .chain(nodal)
        .collect()
}

/// An enforcement method and its parameters in words.
fn law_in_words(law: &NormalLaw) -> String {
    match *law {
        NormalLaw::Penalty { epsilon } => format!("penalty, ε = {epsilon:.4e}"),
        NormalLaw::Uzawa { epsilon } => {
            format!("augmented Lagrangian with Uzawa updates, ε = {epsilon:.4e}")
        }
        NormalLaw::Rockafellar { p, k } => {
            format!("monolithic Rockafellar augmented Lagrangian, p = {p:.4e}, k = {k:.4e}")
        }
        NormalLaw::Slack { p, k } => {
            format!("slack-variable Rockafellar Lagrangian (the paper's), p = {p:.4e}, k = {k:.4e}")
        }
    }
}

/// A rigid obstacle in words ("a rigid sphere of radius 2").
fn obstacle(o: &RigidObstacle) -> String {
    match o {
        RigidObstacle::Plane { .. } => "a rigid plane".to_string(),
        RigidObstacle::Sphere { radius, .. } => {
            format!("a rigid sphere of radius {radius}")
        }
        RigidObstacle::Cylinder { radius, .. } => {
            format!("a rigid cylinder of radius {radius}")
        }
        RigidObstacle::Triangulated(t) => {
            format!(
                "a rigid triangulated surface of {} triangles",
                t.triangles().len()
            )
        }
    }
}

fn contact(c: &ContactInterface) -> String {
    let primary = match &c.primary {
        Primary::Rigid(o) => obstacle(o),
        Primary::Surface(p) => format!("the primary surface '{}' (deformable)", p.surface),
        Primary::MortarRigid(m) => format!("{} (dual mortar)", obstacle(&m.obstacle)),
        Primary::Mortar(m) => format!(
            "the primary surface '{}' (deformable, dual mortar)",
            m.primary_surface
        ),
    };
    let scaled = if c.node_scale.is_empty() {
        ""
    } else {
        " (scaled per node by E/h_s with the node's own size)"
    };
    let stick = match (c.exact_stick(), c.tangential_multipliers()) {
        (false, _) => "",
        (true, true) => ", exact stick (tangential multipliers solved by Newton)",
        (true, false) => ", exact stick",
    };
    let friction = match c.friction {
        Some(f) if f.coefficient > 0.0 => format!(
            "; Coulomb friction μ = {}, tangential penalty ε_T = {:.4e}{stick}",
            f.coefficient, f.tangential_penalty
        ),
        _ => "; frictionless".to_string(),
    };
    format!(
        "contact '{}': {} secondary nodes of '{}' against {primary}; {}{scaled}; contact element size {:.3e}{friction}",
        c.name,
        c.nodes.len(),
        c.surface,
        law_in_words(&c.law),
        c.element_size
    )
}
