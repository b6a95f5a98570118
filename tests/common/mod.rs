//! Shared helpers of the integration tests: problems on structured meshes
//! built directly through the library API.
#![allow(dead_code)]

use nalgebra::Vector3;
use signorini::assembly::Model;
use signorini::contact::friction::{ContactStatus, Coulomb};
use signorini::contact::interface::ContactInterface;
use signorini::contact::interface::NodeReport;
use signorini::contact::laws::NormalLaw;
use signorini::contact::RigidObstacle;
use signorini::material::{LinearElastic, Material, NeoHookean};
use signorini::mesh::structured::box_mesh;
use signorini::mesh::ElementKind;
use signorini::mesh::Mesh;
use signorini::problem::{
    Amplitude, ContactState, PrescribedDisplacement, Problem, SolverSettings, Step,
};
use signorini::solve::backend::linear_solver;
use signorini::solve::linear::Ordering;
use signorini::solve::nonlinear::Evaluation;
use signorini::solve::stepping::{run_steps, IncrementRecord, StepObserver};
use std::collections::HashMap;
use std::path::Path;
use std::sync::Arc;

/// A problem with one material everywhere and no loads yet.
pub fn problem(mesh: Mesh, material: Arc<dyn Material>) -> Problem {
    let n = mesh.elements.len();
    let model = Model::new(Arc::new(mesh), vec![material], vec![0; n]).expect("valid mesh");
    Problem::builder(model)
        .steps([Step {
            name: "load".into(),
            end_time: 1.0,
            initial_increment: 1.0,
            min_increment: 1e-4,
            max_increment: 1.0,
        }])
        .settings(SolverSettings {
            residual_tolerance: 1e-10,
            ..SolverSettings::default()
        })
        .build()
        .expect("no contact to check")
}

/// Prescribe components `(component, value)` on every node of a surface.
pub fn fix(problem: &mut Problem, surface: &str, components: &[(usize, f64)]) {
    let mesh = &problem.model.mesh;
    let s = mesh.surface(surface).expect("surface exists");
    problem.prescribed.push(PrescribedDisplacement {
        surface: surface.into(),
        nodes: mesh.surface_nodes(s),
        components: components.to_vec(),
        amplitude: Amplitude::ramp(),
    });
}

/// A pressure `pressure` (into the body, ramped from 0 at t = 0) on
/// every facet of a surface, a follower load or a dead one.
pub fn press(problem: &mut Problem, surface: &str, pressure: f64, follower: bool) {
    let facets = problem
        .model
        .mesh
        .surface(surface)
        .expect("surface exists")
        .facets
        .clone();
    problem.pressures.push(signorini::problem::PressureLoad {
        surface: surface.into(),
        facets,
        pressure,
        follower,
        amplitude: Amplitude::ramp(),
    });
}

/// Records every converged increment.
#[derive(Default)]
pub struct Recorder {
    pub increments: Vec<IncrementRecord>,
}

impl StepObserver<Problem> for Recorder {
    fn on_converged(
        &mut self,
        _p: &Problem,
        record: &IncrementRecord,
        _u: &[f64],
        _r: &Evaluation<Vec<Vec<NodeReport>>>,
        _c: &signorini::problem::ContactState,
    ) -> signorini::Result<()> {
        self.increments.push(record.clone());
        Ok(())
    }
}

/// Solve all steps; return the displacement and the increments.
pub fn solve(problem: &mut Problem) -> (Vec<f64>, Vec<IncrementRecord>) {
    let mut solver = linear_solver(&problem.settings, Ordering::Amd, 1);
    let mut rec = Recorder::default();
    let u = run_steps(problem, &mut *solver, &mut rec, "unused".into()).expect("converges");
    (u, rec.increments)
}

/// The text of an ASCII MSH 2.2 file of `mesh` (physical groups: the
/// regions as 3D groups, the surface sets as 2D groups), for tests that go
/// through the case file and the Gmsh reader.
pub fn msh22(mesh: &Mesh) -> String {
    use std::fmt::Write;
    let mut s = String::from("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n");
    let groups = mesh.regions.len() + mesh.surfaces.len();
    writeln!(s, "{groups}").unwrap();
    for (i, r) in mesh.regions.iter().enumerate() {
        writeln!(s, "3 {} \"{}\"", i + 1, r.name).unwrap();
    }
    for (i, f) in mesh.surfaces.iter().enumerate() {
        writeln!(s, "2 {} \"{}\"", 100 + i, f.name).unwrap();
    }
    s.push_str("$EndPhysicalNames\n$Nodes\n");
    writeln!(s, "{}", mesh.nodes.len()).unwrap();
    for (n, x) in mesh.nodes.iter().enumerate() {
        writeln!(s, "{} {} {} {}", n + 1, x[0], x[1], x[2]).unwrap();
    }
    s.push_str("$EndNodes\n$Elements\n");
    let mut lines = Vec::new();
    for (i, f) in mesh.surfaces.iter().enumerate() {
        for facet in &f.facets {
            let nodes: Vec<String> = facet.nodes.iter().map(|n| (n + 1).to_string()).collect();
            lines.push(format!(
                "{} 2 {} {} {}",
                facet.kind.gmsh_type(),
                100 + i,
                100 + i,
                nodes.join(" ")
            ));
        }
    }
    for (i, r) in mesh.regions.iter().enumerate() {
        for &e in &r.elements {
            let el = &mesh.elements[e];
            let nodes: Vec<String> = el.nodes.iter().map(|n| (n + 1).to_string()).collect();
            lines.push(format!(
                "{} 2 {} {} {}",
                el.kind.gmsh_type(),
                i + 1,
                i + 1,
                nodes.join(" ")
            ));
        }
    }
    writeln!(s, "{}", lines.len()).unwrap();
    for (k, l) in lines.iter().enumerate() {
        writeln!(s, "{} {l}", k + 1).unwrap();
    }
    s.push_str("$EndElements\n");
    s
}

/// An icosphere of radius `r`: the icosahedron with each triangle split in
/// four `levels` times, new vertices pushed onto the sphere. Right-hand
/// normals point outward. `20·4^levels` triangles.
pub fn icosphere(r: f64, levels: usize) -> (Vec<Vector3<f64>>, Vec<[usize; 3]>) {
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    let mut vertices: Vec<Vector3<f64>> = [
        (-1.0, t, 0.0),
        (1.0, t, 0.0),
        (-1.0, -t, 0.0),
        (1.0, -t, 0.0),
        (0.0, -1.0, t),
        (0.0, 1.0, t),
        (0.0, -1.0, -t),
        (0.0, 1.0, -t),
        (t, 0.0, -1.0),
        (t, 0.0, 1.0),
        (-t, 0.0, -1.0),
        (-t, 0.0, 1.0),
    ]
    .iter()
    .map(|&(x, y, z)| Vector3::new(x, y, z).normalize() * r)
    .collect();
    let mut triangles: Vec<[usize; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    for _ in 0..levels {
        let mut midpoint: HashMap<(usize, usize), usize> = HashMap::new();
        let mut mid = |i: usize, j: usize, vertices: &mut Vec<Vector3<f64>>| {
            *midpoint.entry((i.min(j), i.max(j))).or_insert_with(|| {
                vertices.push(((vertices[i] + vertices[j]) / 2.0).normalize() * r);
                vertices.len() - 1
            })
        };
        let mut finer = Vec::with_capacity(4 * triangles.len());
        for [a, b, c] in triangles {
            let ab = mid(a, b, &mut vertices);
            let bc = mid(b, c, &mut vertices);
            let ca = mid(c, a, &mut vertices);
            finer.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
        }
        triangles = finer;
    }
    (vertices, triangles)
}

/// A contact interface on surface `surface` of `p` against `obstacle`,
/// frictionless, fixed obstacle, no per-node parameter factors.
pub fn interface(
    p: &Problem,
    element_size: f64,
    surface: &str,
    obstacle: RigidObstacle,
    law: NormalLaw,
) -> ContactInterface {
    let c = ContactInterface::rigid(&p.model.mesh, surface, obstacle, &law.into()).unwrap();
    ContactInterface { element_size, ..c }
}

/// One converged increment: its record, unknowns, residual (reactions on
/// prescribed dofs) and committed contact state.
#[derive(Clone)]
pub struct Snapshot {
    pub record: IncrementRecord,
    pub x: Vec<f64>,
    pub residual: Vec<f64>,
    pub contact: ContactState,
}

/// The final state of a run (unknowns, contact state) and every increment.
#[derive(Default)]
pub struct Last {
    pub x: Vec<f64>,
    pub contact: ContactState,
    pub increments: Vec<IncrementRecord>,
    pub snapshots: Vec<Snapshot>,
}

/// How the end of run `b` differs from that of run `a` of the same
/// problem (`dofs` displacement unknowns): for the tests that change only
/// the tangential penalty.
pub struct EndChange {
    /// The largest displacement of `a`.
    pub size: f64,
    /// The largest displacement difference.
    pub displacement: f64,
    /// The largest difference of a node's committed tangential traction
    /// on interface 0.
    pub traction: f64,
    /// Whether interface 0 of `a` ends with sticking and slipping nodes.
    pub partial_slip: bool,
}

impl Last {
    /// See [`EndChange`].
    pub fn change_to(&self, b: &Last, dofs: usize) -> EndChange {
        use signorini::contact::friction::ContactStatus;
        let (a, b) = (self, b);
        let size = a.x[..dofs].iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        let displacement = a.x[..dofs]
            .iter()
            .zip(&b.x[..dofs])
            .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
        let traction = a.contact.interfaces[0]
            .iter()
            .zip(&b.contact.interfaces[0])
            .map(|(a, b)| (a.friction.traction - b.friction.traction).norm())
            .fold(0.0, f64::max);
        let has = |s| {
            a.contact.interfaces[0]
                .iter()
                .any(|n| n.friction.status == s)
        };
        EndChange {
            size,
            displacement,
            traction,
            partial_slip: has(ContactStatus::Stick) && has(ContactStatus::Slip),
        }
    }
}

impl StepObserver<Problem> for Last {
    fn on_converged(
        &mut self,
        _p: &Problem,
        record: &IncrementRecord,
        u: &[f64],
        evaluation: &Evaluation<Vec<Vec<NodeReport>>>,
        c: &ContactState,
    ) -> signorini::Result<()> {
        let r = &evaluation.residual;
        self.x = u.to_vec();
        self.contact = c.clone();
        self.increments.push(record.clone());
        self.snapshots.push(Snapshot {
            record: record.clone(),
            x: u.to_vec(),
            residual: r.to_vec(),
            contact: c.clone(),
        });
        Ok(())
    }
}

/// Run every step with the run's fill-reducing ordering; panics if the
/// run fails.
pub fn run(p: &mut Problem) -> Last {
    let ordering = signorini::run::fill_reducing_ordering(p).unwrap();
    let mut solver = linear_solver(&p.settings, ordering, 1);
    let mut last = Last::default();
    run_steps(p, &mut *solver, &mut last, "unused".into()).expect("converges");
    last
}

/// Asserts Newton's quadratic rate in the last iterations of each
/// increment (after the predictor): once the relative residual is below 1e-4,
/// `r_{k+1} ≤ 100 r_k²` (or at the round-off floor of contact systems, 1e-11). A linear rate of even 0.1
/// fails this (1e-4 → 1e-5 against the bound 1e-6). Pairs across which a
/// contact node changed status (or primary triangle) are skipped. A rise from a
/// converged residual (≤ 1e-10) starts a new Newton solve (an Uzawa
/// multiplier update within the increment) and is not a pair. Returns the
/// number of iteration pairs checked (at least one).
pub fn assert_quadratic(incs: &[IncrementRecord]) -> usize {
    let mut checked = 0;
    for inc in incs {
        let r: Vec<f64> = inc.newton.iter().map(|i| i.residual).collect();
        // skip the residual before the predictor (≈ 0 when only prescribed
        // displacements change)
        let switched: Vec<usize> = inc.newton.iter().map(|i| i.switched).collect();
        for (k, w) in r.windows(2).enumerate().skip(1) {
            let new_solve = w[0] <= 1e-10 && w[1] > w[0];
            // a contact node changed status or primary triangle: another
            // system, not a Newton step on the same one
            let changed = switched[k + 1] > 0;
            if w[0] <= 1e-4 && w[0] > 1e-11 && !new_solve && !changed {
                assert!(
                    w[1] <= (100.0 * w[0] * w[0]).max(1e-11),
                    "residuals {r:?}: {} → {}",
                    w[0],
                    w[1]
                );
                checked += 1;
            }
        }
    }
    assert!(checked > 0, "no iteration pair in the quadratic range");
    checked
}

/// The assembled tangent at `(t, x)` with contact states `state` is the
/// central-difference derivative of the assembled residual, column by
/// column over every unknown, to `1e-5 (1 + |K_ij|)`.
#[track_caller]
pub fn assert_tangent_matches_fd(
    pr: &Problem,
    t: f64,
    x: &[f64],
    state: &ContactState,
    label: &str,
) {
    assert_corrected_tangent_matches_fd(pr, t, x, state, label, |_| {});
}

/// [`assert_tangent_matches_fd`] after `correct` changed the assembled
/// values (to take out what the tangent holds on purpose and the
/// residual does not, such as a diagonal shift).
pub fn assert_corrected_tangent_matches_fd(
    pr: &Problem,
    t: f64,
    x: &[f64],
    state: &ContactState,
    label: &str,
    correct: impl Fn(&mut [f64]),
) {
    assert_tangent_rows_match_fd(pr, t, x, state, label, correct, |_| true, |_, _| 0.0);
}

/// The one finite-difference driver of the assembled tangent: every
/// column `j` of `K` at `(t, x)` (after `correct` changed its values)
/// against the central difference `(r(x + h e_j) − r(x − h e_j))/(2h)`,
/// `h = 1e-7`, on the rows `rows` keeps, to `1e-5 (1 + |K_ij|) + slack(i, j)`
/// (`slack`: what the tangent holds on purpose beyond the residual's
/// derivative, such as a Jacobian's diagonal shift).
#[allow(clippy::too_many_arguments)]
pub fn assert_tangent_rows_match_fd(
    pr: &Problem,
    t: f64,
    x: &[f64],
    state: &ContactState,
    label: &str,
    correct: impl Fn(&mut [f64]),
    rows: impl Fn(usize) -> bool,
    slack: impl Fn(usize, usize) -> f64,
) {
    let n = pr.num_unknowns();
    let mut k = vec![0.0; pr.model.pattern.nnz()];
    pr.residual_in(t, x, state, Some(&mut k)).unwrap();
    correct(&mut k);
    let pattern = pr.model.pattern.symbolic();
    let h = 1e-7;
    for j in 0..n {
        let (mut xp, mut xm) = (x.to_vec(), x.to_vec());
        xp[j] += h;
        xm[j] -= h;
        let rp = pr.residual_in(t, &xp, state, None).unwrap().0.r;
        let rm = pr.residual_in(t, &xm, state, None).unwrap().0.r;
        let mut column = vec![0.0; n];
        for idx in pattern.col_ptr()[j]..pattern.col_ptr()[j + 1] {
            column[pattern.row_idx()[idx]] = k[idx];
        }
        for i in (0..n).filter(|&i| rows(i)) {
            let fd = (rp[i] - rm[i]) / (2.0 * h);
            assert!(
                (fd - column[i]).abs() < 1e-5 * (1.0 + column[i].abs()) + slack(i, j),
                "{label}: K[{i},{j}] = {} vs fd {fd}",
                column[i]
            );
        }
    }
}

/// The node reports hold open, sticking and slipping nodes (a state that
/// exercises every branch of the frictional tangent).
#[track_caller]
pub fn assert_open_stick_and_slip(
    reports: &[signorini::contact::interface::NodeReport],
    label: &str,
) {
    use signorini::contact::friction::ContactStatus;
    let count = |s: ContactStatus| reports.iter().filter(|r| r.status == s).count();
    assert!(
        count(ContactStatus::Open) > 0
            && count(ContactStatus::Stick) > 0
            && count(ContactStatus::Slip) > 0,
        "{label}: want open, stick and slip nodes: {:?}",
        reports.iter().map(|r| r.status).collect::<Vec<_>>()
    );
}

/// Two bodies in one mesh: `b` translated by `offset`, its node and element
/// numbering after `a`'s; regions renamed `a_name` and `b_name`, surface
/// sets prefixed `"{a_name}."` and `"{b_name}."` (e.g. `upper.zmin`).
pub fn two_bodies(a: Mesh, a_name: &str, b: Mesh, b_name: &str, offset: [f64; 3]) -> Mesh {
    let (na, ea) = (a.nodes.len(), a.elements.len());
    let mut m = Mesh {
        nodes: a.nodes.clone(),
        node_ids: (1..=na as u64).collect(),
        elements: a.elements.clone(),
        regions: vec![signorini::mesh::Region {
            name: a_name.into(),
            elements: (0..ea).collect(),
        }],
        surfaces: a
            .surfaces
            .iter()
            .map(|s| signorini::mesh::SurfaceSet {
                name: format!("{a_name}.{}", s.name),
                facets: s.facets.clone(),
            })
            .collect(),
        node_sets: Vec::new(),
    };
    m.nodes.extend(
        b.nodes
            .iter()
            .map(|x| [x[0] + offset[0], x[1] + offset[1], x[2] + offset[2]]),
    );
    m.node_ids = (1..=m.nodes.len() as u64).collect();
    for (k, e) in b.elements.iter().enumerate() {
        let mut e = e.clone();
        e.nodes.iter_mut().for_each(|n| *n += na);
        e.id = (ea + k + 1) as u64;
        m.elements.push(e);
    }
    m.regions.push(signorini::mesh::Region {
        name: b_name.into(),
        elements: (ea..ea + b.elements.len()).collect(),
    });
    for s in &b.surfaces {
        let mut facets = s.facets.clone();
        for f in &mut facets {
            f.nodes.iter_mut().for_each(|n| *n += na);
        }
        m.surfaces.push(signorini::mesh::SurfaceSet {
            name: format!("{b_name}.{}", s.name),
            facets,
        });
    }
    m
}

/// Two bodies of [`two_bodies`] named `lower` and `upper` (box meshes),
/// linear elastic (`e`, ν = 0.3), symmetry planes x = 0 and y = 0 on
/// both, the lower bottom held in z and the upper top moved by `top` in
/// z; dual mortar under `law`, the upper bottom secondary, installed.
pub fn mortar_blocks(mesh: Mesh, e: f64, top: f64, law: NormalLaw) -> Problem {
    let mut pr = problem(mesh, Arc::new(LinearElastic::new(e, 0.3, "m").unwrap()));
    fix(&mut pr, "lower.zmin", &[(2, 0.0)]);
    fix(&mut pr, "upper.zmax", &[(2, top)]);
    for body in ["lower", "upper"] {
        fix(&mut pr, &format!("{body}.xmin"), &[(0, 0.0)]);
        fix(&mut pr, &format!("{body}.ymin"), &[(1, 0.0)]);
    }
    let mesh = &pr.model.mesh;
    let c = ContactInterface::mortar(mesh, "upper.zmin", "lower.zmax", &law.into()).unwrap();
    pr.set_contacts(vec![c]);
    pr
}

/// A deformable interface: the nodes of surface `secondary` against the
/// triangles of surface `primary`, frictionless.
pub fn surface_interface(
    p: &Problem,
    secondary: &str,
    primary: &str,
    law: NormalLaw,
) -> ContactInterface {
    ContactInterface::between_bodies(&p.model.mesh, secondary, primary, &law.into()).unwrap()
}

/// The two passes of a symmetric deformable interface, as the case file's
/// `two_pass = true` builds them: the nodes of `secondary` against the
/// triangles of `primary` (named `secondary`), and the nodes of `primary`
/// against the triangles of `secondary` (named `"{secondary}.reverse"`),
/// each node with half its tributary area.
pub fn two_pass_interfaces(
    p: &Problem,
    secondary: &str,
    primary: &str,
    law: NormalLaw,
) -> Vec<ContactInterface> {
    ContactInterface::two_pass(&p.model.mesh, secondary, primary, &law.into())
        .unwrap()
        .to_vec()
}

/// The stacked blocks: lower 4 × 4 × 2 Hex8, upper 3 × 3 × 2 Hex8, both
/// 1 × 1 × 0.5, non-matching at z = 0.5.
pub fn stacked_blocks_mesh() -> Mesh {
    use signorini::mesh::{structured::box_mesh, ElementKind};
    let lower = box_mesh(ElementKind::Hex8, [4, 4, 2], [1.0, 1.0, 0.5]);
    let upper = box_mesh(ElementKind::Hex8, [3, 3, 2], [1.0, 1.0, 0.5]);
    two_bodies(lower, "lower", upper, "upper", [0.0, 0.0, 0.5])
}

/// The stacked blocks' tables after `[mesh]`: materials (`lower` and
/// `upper`: each a `model` and its parameters), symmetry planes x = 0 and
/// y = 0, the lower bottom held in z, `pressure` on the upper top, the
/// `[[contact]]` of the upper bottom on the lower top with the keys
/// `contact` after `name`, `surface` and `primary`, and one step.
pub fn stacked_blocks_tables(lower: &str, upper: &str, pressure: f64, contact: &str) -> String {
    format!(
        r#"
[[material]]
region = "lower"
{lower}

[[material]]
region = "upper"
{upper}

[[displacement]]
surface = "lower.zmin"
z = 0.0

[[displacement]]
surface = "lower.xmin"
x = 0.0

[[displacement]]
surface = "lower.ymin"
y = 0.0

[[displacement]]
surface = "upper.xmin"
x = 0.0

[[displacement]]
surface = "upper.ymin"
y = 0.0

[[pressure]]
surface = "upper.zmax"
value = {pressure:?}

[[contact]]
name = "interface"
surface = "upper.zmin"
primary = "lower.zmax"
{contact}

[[step]]
name = "press"
end_time = 1.0
"#
    )
}

/// The stacked blocks as a case file (the lower block linear elastic,
/// E = 100, ν = 0.3; the upper one `upper_material` (its `model` and
/// parameters); symmetry planes x = 0 and y = 0, the lower bottom held in
/// z, pressure 2 on the upper top; one increment, residual tolerance
/// 1e-10); `contact` is the `[[contact]]` table's keys after `name`,
/// `surface` and `primary`.
pub fn stacked_blocks_case(upper_material: &str, contact: &str) -> String {
    let lower = "model = \"linear_elastic\"\nyoungs_modulus = 100.0\npoisson_ratio = 0.3";
    format!(
        "\n[mesh]\nfile = \"blocks.msh\"\n{}\n[solver]\nresidual_tolerance = 1e-10\n",
        stacked_blocks_tables(lower, upper_material, 2.0, contact)
    )
}

/// Write the stacked blocks' mesh and case into `dir`; the case's path.
pub fn write_stacked_blocks_case(
    dir: &Path,
    upper_material: &str,
    contact: &str,
) -> std::path::PathBuf {
    std::fs::write(dir.join("blocks.msh"), msh22(&stacked_blocks_mesh())).unwrap();
    let path = dir.join("case.toml");
    std::fs::write(&path, stacked_blocks_case(upper_material, contact)).unwrap();
    path
}

/// Move the mesh nodes `nodes` of the unknowns `x` by `amount(node)` in x
/// and y (a tangential slide, for a frictional history).
pub fn slide_nodes(
    x: &mut [f64],
    nodes: impl IntoIterator<Item = usize>,
    amount: impl Fn(usize) -> [f64; 2],
) {
    for n in nodes {
        let [a, b] = amount(n);
        x[3 * n] += a;
        x[3 * n + 1] += b;
    }
}

/// An uneven slide of node `n`, `0.004 (cos(0.9 n) (n mod 3), sin(0.9 n))`:
/// neighbouring nodes move by different amounts, so that some stick and
/// some slip.
pub fn uneven_slide(n: usize) -> [f64; 2] {
    let k = n as f64;
    [0.004 * (0.9 * k).cos() * (k % 3.0), 0.004 * (0.9 * k).sin()]
}

/// A state for finite-difference checks of a contact tangent: every
/// unknown `amplitude · sin(0.77 i)`, except the multipliers of the slack
/// law (`slack = true`), which start at 0 so that its local unknowns can be
/// solved consistently for the gap.
pub fn perturbed_state(pr: &Problem, amplitude: f64, slack: bool) -> Vec<f64> {
    let dofs = pr.model.num_dofs();
    (0..pr.num_unknowns())
        .map(|i| {
            if slack && i >= dofs {
                0.0
            } else {
                amplitude * ((i as f64) * 0.77).sin()
            }
        })
        .collect()
}

/// Supports and load of two stacked blocks in one mesh: symmetry planes
/// x = 0 and y = 0 for both (`lower.xmin`, …, `upper.ymin`), the lower
/// block's bottom held in z, a dead pressure `pressure` on the upper top.
pub fn support_stacked_blocks(pr: &mut Problem, pressure: f64) {
    fix(pr, "lower.zmin", &[(2, 0.0)]);
    for body in ["lower", "upper"] {
        fix(pr, &format!("{body}.xmin"), &[(0, 0.0)]);
        fix(pr, &format!("{body}.ymin"), &[(1, 0.0)]);
    }
    let facets = pr.model.mesh.surface("upper.zmax").unwrap().facets.clone();
    pr.pressures.push(signorini::problem::PressureLoad {
        surface: "upper.zmax".into(),
        facets,
        pressure,
        follower: false,
        amplitude: Amplitude::ramp(),
    });
}

/// Every normal-contact method, all with the same parameter `e`
/// (`ε`, or `p = k`), named as in the case file.
pub fn every_method(e: f64) -> Vec<(&'static str, NormalLaw)> {
    vec![
        ("penalty", NormalLaw::Penalty { epsilon: e }),
        ("uzawa", NormalLaw::Uzawa { epsilon: e }),
        ("rockafellar", NormalLaw::Rockafellar { p: e, k: e }),
        ("slack", NormalLaw::Slack { p: e, k: e }),
    ]
}

/// A case run through the CLI's `run`, with the problem it built (for its
/// mesh) and its output folder.
pub struct CaseRun {
    pub outcome: signorini::run::RunOutcome,
    pub problem: Problem,
}

impl CaseRun {
    /// Run the case file `path`, writing into `output`.
    pub fn new(path: &Path, output: &Path) -> Self {
        let outcome = signorini::run::run(
            path,
            &signorini::run::RunOptions {
                output: Some(output.to_path_buf()),
                threads: None,
                cancel: None,
                restart: None,
            },
        )
        .expect("the case runs");
        let problem = signorini::case::load(path)
            .unwrap()
            .build_problem()
            .unwrap();
        Self { outcome, problem }
    }

    /// The stacked blocks as a case file in `dir` (see
    /// [`stacked_blocks_case`]), run.
    pub fn stacked_blocks(dir: &Path, upper_material: &str, contact: &str) -> Self {
        let path = write_stacked_blocks_case(dir, upper_material, contact);
        Self::new(&path, &dir.join("out"))
    }

    /// Point field `name` of the last converged increment's VTU.
    pub fn last_field(&self, name: &str) -> Vec<f64> {
        let file = &self.outcome.summary.increments.last().unwrap().file;
        signorini::output::vtu::read_point_field(&self.outcome.output_dir.join(file), name).unwrap()
    }
}

/// Two neo-Hookean blocks (`lower` 1 × 1 × 0.5 of 2 × 2 × 1 Hex8, `upper`
/// 0.8 × 0.8 × 0.5 of `upper_cells` × `upper_cells` × 1, shifted by
/// `offset`) with Coulomb friction (μ = 0.3, ε_T = 3E) between the upper
/// bottom and the lower top under `law`, at a perturbed state
/// ([`perturbed_state`], amplitude 0.02; multipliers `0.02 cos(1.3 i)`
/// except the slack law's). Returns the problem, the upper block's node
/// range and the state.
pub fn frictional_blocks(
    e: f64,
    name: &str,
    law: NormalLaw,
    upper_cells: usize,
    offset: [f64; 3],
) -> (Problem, std::ops::Range<usize>, Vec<f64>) {
    let mesh_lower = box_mesh(ElementKind::Hex8, [2, 2, 1], [1.0, 1.0, 0.5]);
    let mesh_upper = box_mesh(
        ElementKind::Hex8,
        [upper_cells, upper_cells, 1],
        [0.8, 0.8, 0.5],
    );
    let lower_nodes = mesh_lower.nodes.len();
    let mesh = two_bodies(mesh_lower, "lower", mesh_upper, "upper", offset);
    let mut pr = problem(mesh, Arc::new(NeoHookean::new(e, 0.3, "m").unwrap()));
    let mut c = surface_interface(&pr, "upper.zmin", "lower.zmax", law);
    c.friction = Some(Coulomb {
        coefficient: 0.3,
        tangential_penalty: 3.0 * e,
    });
    pr.set_contacts(vec![c]);
    let dofs = pr.model.num_dofs();
    let slack = name == "slack";
    let mut x = perturbed_state(&pr, 0.02, slack);
    if !slack {
        for (m, v) in x.iter_mut().enumerate().skip(dofs) {
            *v = 0.02 * ((m as f64) * 1.3).cos();
        }
    }
    (pr, lower_nodes..dofs / 3, x)
}

/// Write the case `text` to `dir/bad.toml`, load and build it, and assert
/// that it fails with a message containing every string of `expect`.
#[track_caller]
pub fn assert_case_error(dir: &Path, text: &str, expect: &[&str]) {
    std::fs::write(dir.join("bad.toml"), text).unwrap();
    let err = signorini::case::load(&dir.join("bad.toml"))
        .and_then(|c| c.build_problem().map(|_| ()))
        .expect_err("a bad case");
    let message = err.to_string();
    for e in expect {
        assert!(message.contains(e), "{message}\nlacks: {e}");
    }
}

/// Signorini's `t_N ≥ 0` on the output: at every node of every written
/// increment of `outcome`, `contact_pressure ≥ −1e-10 p_max`, with `p_max`
/// that increment's largest pressure (on both sides of every interface:
/// a primary node's pressure is the sum of the shares of the secondary
/// nodes' forces). Returns the largest pressure of the run, so that a
/// caller can check that contact happened.
pub fn assert_contact_pressure_nonnegative(outcome: &signorini::run::RunOutcome) -> f64 {
    let mut largest = 0.0_f64;
    let mut written = 0;
    for inc in outcome
        .summary
        .increments
        .iter()
        .filter(|i| !i.file.is_empty())
    {
        let path = outcome.output_dir.join(&inc.file);
        let p = signorini::output::vtu::read_point_field(&path, "contact_pressure").unwrap();
        let p_max = p.iter().copied().fold(0.0, f64::max);
        let (node, lowest) = p
            .iter()
            .copied()
            .enumerate()
            .fold(
                (0, f64::INFINITY),
                |a, (i, v)| if v < a.1 { (i, v) } else { a },
            );
        assert!(
            lowest >= -1e-10 * p_max,
            "{}: contact_pressure {lowest} at node index {node} (largest {p_max})",
            inc.file
        );
        largest = largest.max(p_max);
        written += 1;
    }
    assert!(written > 0, "no increment written");
    largest
}

/// `max |a − b| / max |b|`.
pub fn relative_difference(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    let scale = b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
        / scale
}

/// The start of a case file for a linear elastic block (`block.msh`, its
/// region `body`, E = 100, ν = 0.3) held on its symmetry planes x = 0 and
/// y = 0 (surface sets `xmin`, `ymin`): the tests add its load, obstacle
/// and contact.
pub const SYMMETRIC_BLOCK: &str = r#"
[mesh]
file = "block.msh"

[[material]]
region = "body"
model = "linear_elastic"
youngs_modulus = 100.0
poisson_ratio = 0.3

[[displacement]]
surface = "xmin"
x = 0.0

[[displacement]]
surface = "ymin"
y = 0.0
"#;

/// A fresh folder holding the tests' cube mesh (`cube.msh`, from
/// `tests/data/cube_hex_41_ascii.msh`) and `case.toml` with `case`: the
/// folder (removed when dropped) and the case file's path.
pub fn cube_folder(case: &str) -> (tempfile::TempDir, std::path::PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data");
    std::fs::copy(
        data.join("cube_hex_41_ascii.msh"),
        dir.path().join("cube.msh"),
    )
    .unwrap();
    let path = dir.path().join("case.toml");
    std::fs::write(&path, case).unwrap();
    (dir, path)
}

/// The tests' cube case (`tests/data/cube_case.toml`: a history, a
/// profile, a wall), its text.
pub fn cube_case() -> String {
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data");
    std::fs::read_to_string(data.join("cube_case.toml")).unwrap()
}

/// Every `.rs` file under `dir` (the guards of the source layout read
/// `src/` with it).
pub fn rust_files(dir: &std::path::Path, out: &mut Vec<std::path::PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// Every node of `reports` slips on Coulomb's cone, `|t_T| = μ t_N` to
/// 1e-10 of `t_N`, its traction opposing the body's `slide` relative to
/// the primary (`t_T · slide < 0`); the largest `||t_T|/t_N − μ|`.
#[track_caller]
pub fn assert_slip_on_the_cone(
    reports: &[signorini::contact::interface::NodeReport],
    mu: f64,
    slide: &Vector3<f64>,
    label: &str,
) -> f64 {
    use signorini::contact::friction::ContactStatus;
    let mut worst = 0.0_f64;
    for (i, r) in reports.iter().enumerate() {
        assert_eq!(r.status, ContactStatus::Slip, "{label} node {i}");
        let t = Vector3::from(r.tangential_traction);
        let error = (t.norm() - mu * r.pressure).abs() / r.pressure;
        worst = worst.max(error);
        assert!(
            error <= 1e-10,
            "{label} node {i}: |t_T| {} against μ t_N {}",
            t.norm(),
            mu * r.pressure
        );
        assert!(
            t.dot(slide) < 0.0,
            "{label} node {i}: t_T {t:?} does not oppose the slide"
        );
    }
    worst
}

/// A case file: the linear elastic block of [`SYMMETRIC_BLOCK`] under a
/// dead pressure 2 on its top, its bottom `zmin` in dual mortar contact
/// with the plane z = 0 (`[[contact]]` `bottom`, with the further keys
/// `contact`), one step, and the `[solver]` keys `solver`.
pub fn mortar_block_on_floor_case(contact: &str, solver: &str) -> String {
    format!(
        r#"{SYMMETRIC_BLOCK}
[[pressure]]
surface = "zmax"
value = 2.0

[[obstacle]]
name = "floor"
shape = "plane"
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]

[[contact]]
name = "bottom"
surface = "zmin"
obstacle = "floor"
discretisation = "mortar"
{contact}

[[step]]
name = "press"
end_time = 1.0

[solver]
{solver}
"#
    )
}

/// A frictional history for finite-difference checks of a tangent: the
/// contact state committed at `x`, then again after a slide of `nodes`
/// by (0.002, 0.001), then `nodes` moved tangentially by `amount` in `x`
/// (e.g. [`uneven_slide`]). Returns the committed state (time 0.5).
pub fn slid_history(
    pr: &mut Problem,
    x: &mut [f64],
    nodes: &[usize],
    amount: impl Fn(usize) -> [f64; 2],
) -> signorini::problem::ContactState {
    let mut state = pr.initial_contact_state(x);
    pr.refresh_contact_pairs(x, 0.0);
    pr.commit_contact_history(0.5, x, &mut state);
    slide_nodes(x, nodes.iter().copied(), |_| [0.002, 0.001]);
    pr.refresh_contact_pairs(x, 0.0);
    pr.commit_contact_history(0.5, x, &mut state);
    slide_nodes(x, nodes.iter().copied(), amount);
    state
}

/// Two steps, `press` (t ∈ [0, 1]) and `shear` (t ∈ [1, 2]), one
/// increment each, cut down to 1e-3 at most.
pub fn press_then_shear_steps() -> Vec<signorini::solve::settings::Step> {
    ["press", "shear"]
        .iter()
        .enumerate()
        .map(|(s, name)| signorini::solve::settings::Step {
            name: name.to_string(),
            end_time: s as f64 + 1.0,
            initial_increment: 1.0,
            min_increment: 1e-3,
            max_increment: 1.0,
        })
        .collect()
}

/// The node reports of the first interface of `pr` at the end of run
/// `last`, evaluated at time `t`.
pub fn interface_reports(pr: &Problem, last: &Last, t: f64) -> Vec<NodeReport> {
    let ctx = signorini::contact::interface::ContactContext {
        reference: &pr.model.mesh.nodes,
        t,
        x: &last.x,
        first_multiplier: pr.model.num_dofs(),
    };
    let mut residual = vec![0.0; pr.num_unknowns()];
    let c = pr.contacts.interface(0);
    c.assemble(&ctx, &last.contact.interfaces[0], &mut residual, None)
}

/// Every node of `reports` (its index, its report) closed in `status`
/// with pressure `t_n` to 1e-10 of `t_n` and tangential traction `t_t` to
/// 1e-9 of `t_n` (observed on tests/mortar_friction.rs's Hex8 blocks 1e-11
/// and 4.5e-10 (9.4e-10 on 2026-11-27) with ε_T = 5E, 6e-10 with ε_T = E:
/// the tangential multipliers come out of the converged Newton solve less
/// exactly than the normal ones); returns the largest error.
pub fn assert_uniform<'a>(
    reports: impl IntoIterator<Item = (usize, &'a NodeReport)>,
    status: ContactStatus,
    (t_n, t_t): (f64, Vector3<f64>),
    label: &str,
) -> f64 {
    let mut worst = 0.0_f64;
    for (i, r) in reports {
        assert_eq!(r.status, status, "{label}: node {i}");
        let e_n = (r.pressure - t_n).abs() / t_n;
        let e_t = (Vector3::from(r.tangential_traction) - t_t).norm() / t_n;
        worst = worst.max(e_n).max(e_t);
        assert!(
            e_n <= 1e-10 && e_t <= 1e-9,
            "{label}: node {i}: t_N {} t_T {:?} (exact {t_n}, {t_t:?})",
            r.pressure,
            r.tangential_traction
        );
    }
    worst
}
