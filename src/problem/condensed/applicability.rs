//! Where the condensed path applies: the path a run takes ([`choose`]) and
//! why the condensed one does not apply ([`not_applicable`]).

use super::{friction, has_friction, Problem};
use crate::contact::interface::ContactInterface;
use crate::contact::laws::NormalEnforcement;
use crate::material::Kinematics;
use crate::solve::settings::Strategy;
use nalgebra::{Matrix6, Vector3, Vector6};

/// Which path a run takes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Path {
    Monolithic,
    Condensed,
}

impl Path {
    /// `"monolithic"` or `"condensed"` (summary.json's `strategy`).
    pub fn name(self) -> &'static str {
        match self {
            Path::Monolithic => "monolithic",
            Path::Condensed => "condensed",
        }
    }
}

/// The path a run takes and why the other one is not taken.
#[derive(Clone, Debug, PartialEq)]
pub struct Choice {
    pub path: Path,
    pub reason: String,
}

/// The path `[solver] strategy` asks for on `problem`; an error (the
/// reason) when `condensed` is asked for where it does not apply.
pub fn choose(problem: &Problem) -> std::result::Result<Choice, String> {
    let why_not = not_applicable(problem);
    let strategy = problem.settings.strategy;
    let condensed = || Choice {
        path: Path::Condensed,
        reason: if has_friction(problem) && super::has_pairs(problem) {
            "the stiffness is constant and some contact is between two bodies with Coulomb \
             friction: one factorisation per run with both contact surfaces ordered last, the \
             frictional contact problem solved on the contact nodes by a dense semismooth \
             Newton method at the current projections until they settle (monolithic Newton \
             would factorise at every iteration)"
                .into()
        } else if has_friction(problem) && super::has_moving_rows(problem) {
            "the stiffness is constant and every contact is against a rigid obstacle with \
             Coulomb friction, some curved or triangulated (a sphere, a cylinder, an STL or \
             Gmsh surface): one factorisation per run, the frictional contact problem solved on the \
             contact nodes by a dense semismooth Newton method at the current normals until \
             they settle (monolithic Newton would \
             factorise at every iteration)"
                .into()
        } else if has_friction(problem) {
            "the stiffness is constant and every contact is against a rigid plane with Coulomb \
             friction: one factorisation per run, the frictional contact problem solved on the \
             contact nodes by a dense semismooth Newton method (monolithic Newton would \
             factorise at every iteration)"
                .into()
        } else if super::has_moving_rows(problem) && !super::has_pairs(problem) {
            "the stiffness is constant and every contact is frictionless against a rigid \
             obstacle, some curved or triangulated (a sphere, a cylinder, an STL or \
             Gmsh surface): one factorisation per run with the contact surfaces ordered last, the contact problem solved on the contact nodes at \
             the current normals until they settle (monolithic Newton would factorise at every \
             iteration)"
                .into()
        } else if super::has_pairs(problem) {
            "the stiffness is constant and every contact is frictionless, some between two \
             bodies: one factorisation per run with both contact surfaces ordered last, the \
             contact problem solved on the contact nodes at the current projections until \
             they settle (monolithic Newton would factorise at every iteration)"
                .into()
        } else {
            "the stiffness is constant and every contact is frictionless against a rigid \
             plane: one factorisation per run, the contact problem solved exactly on the \
             contact nodes (monolithic Newton would factorise at every iteration)"
                .into()
        },
    };
    match (strategy, why_not) {
        (Strategy::Monolithic, _) => Ok(Choice {
            path: Path::Monolithic,
            reason: "[solver] strategy = \"monolithic\"".into(),
        }),
        (Strategy::Condensed, None) | (Strategy::Auto, None) => Ok(condensed()),
        (Strategy::Condensed, Some(why)) => Err(format!(
            "solver.strategy = \"condensed\" does not apply: {why}; use strategy = \"auto\" or \
             \"monolithic\""
        )),
        (Strategy::Auto, Some(why)) => Ok(Choice {
            path: Path::Monolithic,
            reason: format!("the condensed path does not apply: {why}"),
        }),
    }
}

/// Why the condensed path does not apply to `problem` (`None`: it does).
pub fn not_applicable(problem: &Problem) -> Option<String> {
    if problem.contacts.is_empty() {
        return Some(
            "there is no contact (Newton solves a linear problem in one iteration)".into(),
        );
    }
    if let Some(m) = problem
        .model
        .materials
        .iter()
        .find(|m| m.kinematics() != Kinematics::SmallStrain)
    {
        return Some(format!(
            "material '{}' is finite-strain (its stiffness changes with the displacement)",
            m.name()
        ));
    }
    if let Some(p) = problem.pressures.iter().find(|p| p.follower) {
        return Some(format!(
            "the pressure on '{}' follows the deformed surface (its load stiffness changes)",
            p.surface
        ));
    }
    let strategy = problem.settings.strategy;
    if let Some((c, why)) = (problem.contacts.iter())
        .find_map(|c| contact_not_applicable(c, strategy).map(|why| (c, why)))
    {
        return Some(format!("contact '{}' {why}", c.name));
    }
    let mut held = problem.constrained_dofs();
    // between bodies no dof is shifted: the prescribed displacements must
    // hold every body
    let shifted = has_friction(problem) && !super::has_pairs(problem);
    if shifted {
        // the frictional path shifts the dofs of the nodes touching at the
        // start (`K̂ = K̃ + ρ Σ I₃`), which holds a body that friction holds
        for d in friction::initially_touching_dofs(problem) {
            held[d] = true;
        }
    }
    free_rigid_body_mode(problem, &held).map(|why| {
        if shifted {
            format!("{why}, and the nodes touching the obstacle at the start do not hold it")
        } else {
            why
        }
    })
}

/// Why the condensed path does not apply to contact `c` under `strategy`
/// (`None`: it does).
fn contact_not_applicable(c: &ContactInterface, strategy: Strategy) -> Option<String> {
    // the gap from the node driver, affine in `u`; a law whose
    // converged state is exact or a penalty (not an outer loop's)
    let why = match c.affine_gap() {
        Ok(()) => None,
        // a rigid sphere, cylinder or triangulated surface: the
        // rows at the current normals, in rounds as between bodies
        Err(_) if c.rows_move() && !c.projected_gap() => None,
        // between bodies: the rows at the current projections
        // ([`super::pairs`], [`super::friction`]). Frictionless
        // node-to-surface under `auto` too: with the facet choice of
        // `contact::primary` (committed triangle first) the rounds and
        // Newton end on the same triangles, and examples/two-spheres'
        // answers agree to 1.6e-14 of the displacements (they differed
        // by 1.9e-4 under the last iterate's triangle). With Coulomb
        // friction under `auto` too: examples/cattaneo-mindlin's
        // tractions equal Newton's at 1e-11 node by node to 5.7e-10
        // of the peak (BENCHMARKS.md, session 20). Dual mortar between
        // bodies, frictionless or with Coulomb friction, the same
        // rounds at the current segmentation (tests/mortar_condensed.rs:
        // equal to Newton; with friction under `auto` since session
        // 22, when Newton's mortar multiplier rows took the rule of
        // `friction::HeldTangent` on a symmetry plane). Not under
        // `auto` where exact stick meets a mortar secondary node whose
        // dofs are all prescribed: there the paths keep different
        // equations (`ContactInterface::holds_every_component`).
        Err(why)
            if c.projected_gap()
                && c.has_friction()
                && c.exact_stick()
                && c.holds_every_component()
                && strategy != Strategy::Condensed =>
        {
            Some(format!(
                "{why} with Coulomb friction and exact stick at a secondary node whose \
                 components are all prescribed, which is condensed only with strategy = \
                 \"condensed\" (Newton keeps that node's stick rows, which move the primary \
                 surface; the condensed path holds its committed tangential traction)"
            ))
        }
        Err(_) if c.projected_gap() => None,
        Err(why) => Some(why),
    };
    // dual mortar friction against an obstacle: the slip of `x̃_j`
    // relative to the obstacle on `D_j`, which the frictional rounds
    // (node-to-surface's law on a plane, fixed areas) do not read
    let why = why.or_else(|| {
        (c.has_friction() && !c.fixed_area() && !c.projected_gap()).then(|| {
            "uses Coulomb friction with discretisation = \"mortar\" against an obstacle, \
             which Newton's path takes"
                .into()
        })
    });
    let why = why.or_else(|| {
        c.law.has_outer_loop().then(|| {
            "uses uzawa, which meets the constraint only to its outer loop's tolerance".into()
        })
    });
    why.or_else(|| {
        (!c.fixed_area() && penalty(c)).then(|| {
            "uses penalty with discretisation = \"mortar\", whose force D_j ε ⟨−g⟩ changes \
             with the area D_j of the current surface"
                .into()
        })
    })
}

/// Whether `c`'s law converges to a penalty (`t_N = ε ⟨−g⟩`) rather than
/// to the exact contact conditions.
fn penalty(c: &ContactInterface) -> bool {
    matches!(c.law.converged(), NormalEnforcement::Penalty { .. })
}

/// A body (a connected set of elements) that the `constrained` dofs (its
/// prescribed displacements, and the shifted contact dofs) do not hold against every rigid-body motion (`K̃` is then singular),
/// named by one of its nodes; a node in no element that is not fully
/// prescribed. The six rigid modes of a body about its centroid `c`,
/// `t_i = e_i` and `r_i = e_i × (X − c)/L`, are held when their Gram
/// matrix over the prescribed dofs, `G = Σ_d m(d) m(d)ᵀ`, is regular
/// (smallest eigenvalue above 1e-10 of the largest).
pub(super) fn free_rigid_body_mode(problem: &Problem, constrained: &[bool]) -> Option<String> {
    let mesh = &problem.model.mesh;
    let n = mesh.num_nodes();
    let mut parent: Vec<usize> = (0..n).collect();
    fn root(parent: &mut [usize], mut a: usize) -> usize {
        while parent[a] != a {
            parent[a] = parent[parent[a]];
            a = parent[a];
        }
        a
    }
    let mut in_element = vec![false; n];
    for e in &mesh.elements {
        for &a in &e.nodes {
            in_element[a] = true;
            let (ra, rb) = (root(&mut parent, a), root(&mut parent, e.nodes[0]));
            parent[ra] = rb;
        }
    }
    let mut bodies: std::collections::BTreeMap<usize, Vec<usize>> = Default::default();
    for a in 0..n {
        if !in_element[a] {
            if !(0..3).all(|d| constrained[3 * a + d]) {
                return Some(format!("node {} belongs to no element", mesh.node_ids[a]));
            }
            continue;
        }
        let r = root(&mut parent, a);
        bodies.entry(r).or_default().push(a);
    }
    for nodes in bodies.values() {
        let count = nodes.len() as f64;
        let mut c = Vector3::zeros();
        for &a in nodes {
            c += Vector3::from(mesh.nodes[a]) / count;
        }
        let size = nodes
            .iter()
            .map(|&a| (Vector3::from(mesh.nodes[a]) - c).norm())
            .fold(0.0f64, f64::max)
            .max(f64::MIN_POSITIVE);
        let mut gram = Matrix6::zeros();
        for &a in nodes {
            let y = (Vector3::from(mesh.nodes[a]) - c) / size;
            for d in 0..3 {
                if !constrained[3 * a + d] {
                    continue;
                }
                let mut m = Vector6::zeros();
                m[d] = 1.0;
                for axis in 0..3 {
                    m[3 + axis] = Vector3::ith(axis, 1.0).cross(&y)[d];
                }
                gram += m * m.transpose();
            }
        }
        let eigen = gram.symmetric_eigenvalues();
        let (lo, hi) = (eigen.min(), eigen.max());
        if !(lo > 1e-10 * hi) {
            return Some(format!(
                "the body of node {} is held only by contact (a rigid-body motion is free of \
                 prescribed displacements, so its stiffness is singular)",
                mesh.node_ids[nodes[0]]
            ));
        }
    }
    None
}
