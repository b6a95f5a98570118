//! Dual mortar against rigid obstacles (issue 28 item 3): the face kernel
//! against central differences, the identities on a plane, the driver's
//! terms against central differences of the producer, the contact patch
//! test of a block on a rigid plane for Tet4, Hex8, Tet10 and Hex20, Newton's
//! rate against a sphere, and the case file's `discretisation = "mortar"`
//! with an obstacle.
//!
//! Reference of the patch test: a linear elastic block (E = 100, ν = 0.3)
//! under a dead pressure P = 2 on its top, symmetry planes x = 0 and
//! y = 0, on a frictionless rigid plane z = 0: the uniaxial stress
//! `σ = −P e_z ⊗ e_z`, lateral strain `νP/E`, and the contact pressure is
//! the dead load over the current contact area, `P/(1 + νP/E)²`, at every
//! node (node-to-surface refuses the quadratic faces, whose corner nodes
//! get no share of a uniform pressure).

mod common;

use common::{assert_quadratic, fix, problem, run, solve, CaseRun};
use nalgebra::Dyn;
use nalgebra::{Matrix3, Vector3};
use signorini::assembly::amplitude::Amplitude;
use signorini::assembly::sink::Tangent;
use signorini::contact::interface::ContactInterface;
use signorini::contact::kinematics::GapKinematics;
use signorini::contact::laws::{NodeContactState, NormalLaw};
use signorini::contact::mortar::obstacle_rows::{face_obstacle_integrals, obstacle_rows};
use signorini::contact::mortar::quadratic::nodal_transformation;
use signorini::contact::mortar::{Derivatives, FaceShape, MortarFace};
use signorini::contact::obstacle::RigidObstacle;
use signorini::contact::projection::Projection;
use signorini::material::LinearElastic;
use signorini::mesh::{structured::box_mesh, ElementKind, Mesh};
use signorini::problem::{PressureLoad, Problem};
use std::sync::Arc;

const E: f64 = 100.0;
const NU: f64 = 0.3;
const P: f64 = 2.0;

/// A face of `shape` in the unit square (triangles in the unit triangle),
/// lifted to `z = 0.1 + 0.05 sin(…)` and warped in plane: a curved,
/// distorted face, its nodes counter-clockwise seen from `−z` (outward
/// normal `−z`, toward an obstacle below).
fn warped_face(shape: FaceShape) -> MortarFace {
    let coordinates = shape
        .reference_nodes()
        .iter()
        .enumerate()
        .map(|(i, r)| {
            let (u, v) = if shape.is_triangle() {
                (r[0], r[1])
            } else {
                (0.5 * (r[0] + 1.0), 0.5 * (r[1] + 1.0))
            };
            let s = (i as f64 * 1.7).sin();
            // swap u, v so that the normal points down
            Vector3::new(0.4 * v + 0.02 * s, 0.4 * u - 0.015 * s, 0.1 + 0.01 * s)
        })
        .collect();
    MortarFace::new(shape, coordinates).unwrap()
}

/// The sphere of radius 0.5 centred at `(0.2, 0.2, −0.45)` as the kernel
/// sees it.
fn sphere() -> impl Fn(&Vector3<f64>) -> Projection {
    let s = RigidObstacle::sphere(Vector3::new(0.2, 0.2, -0.45), 0.5).unwrap();
    move |x| s.project(x)
}

/// The face kernel's gradients (`∇D_j`, `∇g̃_j`, `∂L_j/∂x`) against
/// central differences (h = 1e-6) of its own values, on warped faces of the
/// four shapes against a sphere (curved: `H ≠ 0`), to 1e-6 of each
/// quantity's scale. A missing term (the dual basis's or the area
/// element's change, the curvature) is off by its own size, ≥ 1e-2 here.
/// Without derivatives the kernel gives the same values to the bit, and
/// no gradient.
#[test]
fn face_kernel_matches_finite_differences() {
    let obstacle = sphere();
    for shape in [
        FaceShape::Tri3,
        FaceShape::Quad4,
        FaceShape::Tri6,
        FaceShape::Quad8,
    ] {
        let face = warped_face(shape);
        let f0 = face_obstacle_integrals(&face, &obstacle, Derivatives::With).unwrap();
        let values = face_obstacle_integrals(&face, &obstacle, Derivatives::Without).unwrap();
        let same = (&values.d, &values.weighted_gap, &values.lever);
        assert_eq!(same, (&f0.d, &f0.weighted_gap, &f0.lever), "{shape:?}");
        assert!(values.lever_gradient.is_empty() && values.d_gradient.is_empty());
        let n = shape.node_count();
        let h = 1e-6;
        let mut worst = 0.0_f64;
        for c in 0..3 * n {
            let at = |s: f64| {
                let mut g = face.clone();
                g.coordinates[c / 3][c % 3] += s * h;
                face_obstacle_integrals(&g, &obstacle, Derivatives::With).unwrap()
            };
            let (fp, fm) = (at(1.0), at(-1.0));
            for j in 0..n {
                let checks = [
                    (
                        fp.d[j] - fm.d[j],
                        f0.d_gradient[(j, c)],
                        f0.d_gradient.amax(),
                    ),
                    (
                        fp.weighted_gap[j] - fm.weighted_gap[j],
                        f0.weighted_gap_gradient[(j, c)],
                        f0.weighted_gap_gradient.amax(),
                    ),
                ];
                for (diff, exact, scale) in checks {
                    let e = (diff / (2.0 * h) - exact).abs() / scale;
                    worst = worst.max(e);
                    assert!(e < 1e-6, "{shape:?} j {j} c {c}: {e:e}");
                }
                for r in 0..3 * n {
                    let fd = (fp.lever[(j, r)] - fm.lever[(j, r)]) / (2.0 * h);
                    let scale = f0.lever_gradient[j].amax();
                    let e = (fd - f0.lever_gradient[j][(r, c)]).abs() / scale;
                    worst = worst.max(e);
                    assert!(e < 1e-6, "{shape:?} ∂L j {j} r {r} c {c}: {e:e}");
                }
            }
        }
        println!("{shape:?}: largest relative difference {worst:.1e}");
    }
}

/// On a plane the integrals are exact and closed: `D_j = ∫ Ñ_j dA`,
/// `g̃_j = D_j g(x̃_j)`, `L_jk = D_j R_jk n` (biorthogonality,
/// `∫ Φ_j N_k dA = D_j R_jk`), to 1e-13 of the area, on flat faces of the
/// four shapes tilted against an oblique plane.
#[test]
fn plane_integrals_are_closed_forms() {
    let m = Vector3::new(0.2, -0.1, 1.0).normalize();
    let plane = RigidObstacle::plane(Vector3::new(0.0, 0.0, -0.3), m).unwrap();
    let project = |x: &Vector3<f64>| plane.project(x);
    for shape in [
        FaceShape::Tri3,
        FaceShape::Quad4,
        FaceShape::Tri6,
        FaceShape::Quad8,
    ] {
        let mut face = warped_face(shape);
        // flatten: z a linear function of x, y (a flat, distorted face)
        for x in &mut face.coordinates {
            x[2] = 0.1 + 0.3 * x[0] - 0.2 * x[1];
        }
        let f = face_obstacle_integrals(&face, &project, Derivatives::With).unwrap();
        let area = face.area();
        let r = nodal_transformation(shape);
        for (j, rj) in r.iter().enumerate() {
            let x_tilde: Vector3<f64> = rj.iter().map(|&(k, rk)| face.coordinates[k] * rk).sum();
            let g = plane.project(&x_tilde).gap;
            let e = (f.weighted_gap[j] - f.d[j] * g).abs() / area;
            assert!(e < 1e-13, "{shape:?} g̃_{j}: {e:e}");
            for k in 0..shape.node_count() {
                let rjk: f64 = rj.iter().filter(|p| p.0 == k).map(|p| p.1).sum();
                for d in 0..3 {
                    let e = (f.lever[(j, 3 * k + d)] - f.d[j] * rjk * m[d]).abs() / area;
                    assert!(e < 1e-13, "{shape:?} L_{j}{k}: {e:e}");
                }
            }
        }
    }
}

/// A block of `kind` (`cells` × `cells` × 2 cells, 1 × 1 × 0.5) on the
/// plane z = 0, symmetry planes x = 0 and y = 0, the dead pressure P on
/// its top, its bottom in mortar contact with the plane under `law`.
fn block_on_plane(
    kind: ElementKind,
    cells: usize,
    law: NormalLaw,
    plane: RigidObstacle,
) -> Problem {
    let mesh = box_mesh(kind, [cells, cells, 2], [1.0, 1.0, 0.5]);
    let mut pr = problem(mesh, Arc::new(LinearElastic::new(E, NU, "m").unwrap()));
    fix(&mut pr, "xmin", &[(0, 0.0)]);
    fix(&mut pr, "ymin", &[(1, 0.0)]);
    let facets = pr.model.mesh.surface("zmax").unwrap().facets.clone();
    pr.pressures.push(PressureLoad {
        surface: "zmax".into(),
        facets,
        pressure: P,
        follower: false,
        amplitude: Amplitude::ramp(),
    });
    let c = ContactInterface::mortar_rigid(&pr.model.mesh, "zmin", plane, &law.into()).unwrap();
    pr.set_contacts(vec![c]);
    pr.settings.residual_tolerance = 1e-13;
    pr
}

/// The plane z = 0, analytic.
fn floor() -> RigidObstacle {
    RigidObstacle::plane(Vector3::zeros(), Vector3::z()).unwrap()
}

/// The plane z = 0 as a triangulated square `[−1, 2]²` (four triangles
/// about its centre, normals `+z`).
fn triangulated_floor() -> RigidObstacle {
    use signorini::contact::triangulated::TriangulatedSurface;
    let v = [
        [-1.0, -1.0],
        [2.0, -1.0],
        [2.0, 2.0],
        [-1.0, 2.0],
        [0.5, 0.5],
    ]
    .map(|[x, y]| Vector3::new(x, y, 0.0))
    .to_vec();
    let t = vec![[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]];
    RigidObstacle::Triangulated(TriangulatedSurface::new(v, t).unwrap())
}

/// The patch test of the block on the plane: every `λ_j` against
/// `P/(1 + νP/E)²` and every element's Cauchy stress against
/// `−P e_z ⊗ e_z`, the largest errors relative to P, and Newton's
/// iterations.
fn patch_test(
    kind: ElementKind,
    cells: usize,
    law: NormalLaw,
    plane: RigidObstacle,
) -> (f64, f64, usize) {
    let mut pr = block_on_plane(kind, cells, law, plane);
    let last = run(&mut pr);
    let dofs = pr.model.num_dofs();
    let x = &last.x;
    let c = pr.contacts.interface(0);
    let ctx = signorini::contact::interface::ContactContext {
        reference: &pr.model.mesh.nodes,
        t: 1.0,
        x,
        first_multiplier: dofs,
    };
    let mut residual = vec![0.0; pr.num_unknowns()];
    let reports = c.assemble(&ctx, &last.contact.interfaces[0], &mut residual, None);
    assert!(reports.iter().all(|r| r.active), "every node in contact");
    let lambda = P / (1.0 + NU * P / E).powi(2);
    let pressure = reports
        .iter()
        .map(|r| (r.pressure - lambda).abs() / P)
        .fold(0.0, f64::max);
    let mut exact = Matrix3::zeros();
    exact[(2, 2)] = -P;
    let stress = pr
        .model
        .cauchy_stresses(&x[..dofs])
        .iter()
        .map(|s| (s - exact).abs().max() / P)
        .fold(0.0, f64::max);
    let iterations = last.increments.iter().map(|i| i.iterations).sum();
    (pressure, stress, iterations)
}

/// The contact patch test on a rigid plane, Tet4, Hex8, Tet10 and Hex20
/// (Tri3, Quad4, Tri6, Quad8 faces): every multiplier is the pressure on the
/// current area and the stress is `−P` in z everywhere, to 1e-10 of P;
/// every law on Hex20 (parameter 4E); Tet10 on the plane as a
/// triangulated surface. Node-to-surface refuses the quadratic faces
/// (their corners would carry no load).
#[test]
fn patch_test_on_a_rigid_plane_is_exact() {
    let rockafellar = NormalLaw::Rockafellar {
        p: 4.0 * E,
        k: 4.0 * E,
    };
    for (kind, cells) in [
        (ElementKind::Tet4, 4),
        (ElementKind::Hex8, 4),
        (ElementKind::Tet10, 3),
        (ElementKind::Hex20, 3),
    ] {
        let (p, s, n) = patch_test(kind, cells, rockafellar, floor());
        println!("{kind:?}: pressure {p:.1e} stress {s:.1e} iterations {n}");
        assert!(p <= 1e-10, "{kind:?}: pressure error {p:e}");
        assert!(s <= 1e-10, "{kind:?}: stress error {s:e}");
    }
    for (name, law) in common::every_method(4.0 * E) {
        let (p, s, n) = patch_test(ElementKind::Hex20, 2, law, floor());
        println!("Hex20 {name}: pressure {p:.1e} stress {s:.1e} iterations {n}");
        assert!(p <= 1e-10 && s <= 1e-10, "{name}: {p:e} {s:e}");
    }
    let (p, s, _) = patch_test(ElementKind::Tet10, 3, rockafellar, triangulated_floor());
    println!("Tet10 on the triangulated plane: pressure {p:.1e} stress {s:.1e}");
    assert!(p <= 1e-10 && s <= 1e-10, "triangulated: {p:e} {s:e}");
    let mesh = box_mesh(ElementKind::Tet10, [2, 2, 1], [1.0, 1.0, 0.5]);
    let law = NormalLaw::Penalty { epsilon: E };
    let refused = ContactInterface::rigid(&mesh, "zmin", floor(), &law.into());
    assert!(refused.is_err(), "node-to-surface takes Tri6 faces");
}

/// A linear elastic block of `kind` (3 × 3 × 2 cells, 1 × 1 × 0.5) on the
/// rigid sphere of radius 2 that touches its corner at the origin, its top
/// pushed down by 0.03 in two increments, symmetry planes x = 0, y = 0.
fn block_on_sphere(kind: ElementKind) -> Problem {
    let sphere = RigidObstacle::sphere(Vector3::new(0.0, 0.0, -2.0), 2.0).unwrap();
    block_on(kind, sphere)
}

/// [`block_on_sphere`] on `obstacle`.
fn block_on(kind: ElementKind, obstacle: RigidObstacle) -> Problem {
    let mesh: Mesh = box_mesh(kind, [3, 3, 2], [1.0, 1.0, 0.5]);
    let mut pr = problem(mesh, Arc::new(LinearElastic::new(E, NU, "m").unwrap()));
    fix(&mut pr, "xmin", &[(0, 0.0)]);
    fix(&mut pr, "ymin", &[(1, 0.0)]);
    fix(&mut pr, "zmax", &[(2, -0.03)]);
    pr.steps[0].initial_increment = 0.5;
    pr.steps[0].max_increment = 0.5;
    let law = NormalLaw::Rockafellar {
        p: 10.0 * E,
        k: 10.0 * E,
    };
    let c = ContactInterface::mortar_rigid(&pr.model.mesh, "zmin", obstacle, &law.into()).unwrap();
    pr.set_contacts(vec![c]);
    pr.settings.residual_tolerance = 1e-12;
    pr
}

/// The gaps without derivatives ([`MortarObstacle::gap_values`], what the
/// condensed path's contact solve reads) against the rows' own
/// `g̃_j / D_j` at a warped, pressed state, on a fresh interface each
/// (no row cache): to the bit on a sphere and a cylinder (the same sums),
/// to 1e-15 of the block's size on an oblique plane (the closed form
/// `g(x̃_j)`), for Tet4, Tet10 and Hex20 faces; some nodes open, some
/// penetrating.
#[test]
fn gaps_without_derivatives_are_the_rows_gaps() {
    let plane = RigidObstacle::plane(Vector3::zeros(), Vector3::new(0.03, 0.02, 1.0)).unwrap();
    let sphere = RigidObstacle::sphere(Vector3::new(0.0, 0.0, -2.0), 2.0).unwrap();
    let cylinder =
        RigidObstacle::cylinder(Vector3::new(0.0, 0.0, -2.0), Vector3::y(), 2.0).unwrap();
    for kind in [ElementKind::Tet4, ElementKind::Tet10, ElementKind::Hex20] {
        for (o, obstacle) in [plane.clone(), sphere.clone(), cylinder.clone()]
            .iter()
            .enumerate()
        {
            let fresh = || block_on(kind, obstacle.clone());
            let pr = fresh();
            let n = pr.num_unknowns();
            let mut x: Vec<f64> = (0..n).map(|i| 0.004 * ((i as f64) * 0.77).sin()).collect();
            for (i, xi) in x.iter_mut().enumerate().take(pr.model.num_dofs()) {
                if i % 3 == 2 {
                    *xi -= 0.02;
                }
            }
            let reference = &pr.model.mesh.nodes;
            let c = pr.contacts.interface(0);
            let gaps = c.gaps(reference, 1.0, &x, None);
            let (counts, open) = match &c.primary {
                signorini::contact::interface::Primary::MortarRigid(m) => {
                    (m.row_counts(), m.surfaces.margin)
                }
                _ => unreachable!("a mortar interface"),
            };
            assert_eq!((counts.integrated, counts.values), (0, 1), "{counts:?}");
            let rows = fresh()
                .contacts
                .interface(0)
                .constraint_rows(reference, 1.0, &x, None);
            let (mut closed, mut far) = (0, 0);
            for (i, (g, row)) in gaps.iter().zip(&rows).enumerate() {
                let Some(row) = row else {
                    assert_eq!(*g, open, "{kind:?} obstacle {o} node {i}");
                    far += 1;
                    continue;
                };
                closed += usize::from(row.gap < 0.0);
                if o == 0 {
                    assert!(
                        (g - row.gap).abs() <= 1e-15,
                        "{kind:?} node {i}: {g} {}",
                        row.gap
                    );
                } else {
                    assert_eq!(*g, row.gap, "{kind:?} obstacle {o} node {i}");
                }
            }
            println!("{kind:?} obstacle {o}: {closed} penetrating, {far} open at the margin");
            assert!(closed >= 1, "{kind:?} obstacle {o}: none penetrating");
        }
    }
}

/// A warped, pressed state of `pr`'s unknowns (some bottom nodes through
/// the obstacle, some open; the multipliers nonzero).
fn pressed_state(pr: &Problem) -> Vec<f64> {
    let mut x: Vec<f64> = (0..pr.num_unknowns())
        .map(|i| 0.004 * ((i as f64) * 0.77).sin())
        .collect();
    for (i, xi) in x.iter_mut().enumerate().take(pr.model.num_dofs()) {
        if i % 3 == 2 {
            *xi -= 0.02;
        }
    }
    x
}

/// The mortar obstacle of `pr`'s one interface.
fn mortar_obstacle(pr: &Problem) -> &signorini::contact::mortar_rigid::MortarObstacle {
    match &pr.contacts.interface(0).primary {
        signorini::contact::interface::Primary::MortarRigid(m) => m,
        _ => unreachable!("a mortar interface"),
    }
}

/// The rows without derivatives against a plane, in closed form
/// (`MortarObstacle::rows` through `plane_rows`: `g̃_j = D_j g(x̃_j)`,
/// `L_jk = D_j R_jk n`), against the integrated rows of the same faces
/// (`obstacle_rows`) at a warped, pressed state on an oblique plane, for
/// Tet4, Tet10 and Hex20 faces: the same nodes, coupled nodes and
/// transformations; `D_j`, `g̃_j`, the lever and the normal within 1e-14
/// of `D_j` (of 1 for the normal; the block's size is 1). A wrong `D_j`
/// (a missed face) or a lever off `R_j` is off by its own size.
#[test]
fn plane_rows_are_the_integrated_rows() {
    let plane = RigidObstacle::plane(Vector3::zeros(), Vector3::new(0.03, 0.02, 1.0)).unwrap();
    let project = |x: &Vector3<f64>| plane.project(x);
    for kind in [ElementKind::Tet4, ElementKind::Tet10, ElementKind::Hex20] {
        let pr = block_on(kind, plane.clone());
        let x = pressed_state(&pr);
        let reference = &pr.model.mesh.nodes;
        let xs: Vec<Vector3<f64>> = (reference.iter().enumerate())
            .map(|(n, r)| Vector3::new(r[0] + x[3 * n], r[1] + x[3 * n + 1], r[2] + x[3 * n + 2]))
            .collect();
        let m = mortar_obstacle(&pr);
        let closed = m.rows(&Vector3::zeros(), &xs, Derivatives::Without);
        let faces = &m.surfaces.secondary_faces;
        let all: Vec<usize> = (0..faces.len()).collect();
        let integrated = obstacle_rows(faces, &all, &xs, &project, Derivatives::Without).unwrap();
        assert!(closed.len() >= 4, "{kind:?}: {} rows", closed.len());
        for (node, c) in closed.iter() {
            let i = &integrated[node];
            assert_eq!((&c.nodes, &c.transformation), (&i.nodes, &i.transformation));
            let close = |a: f64, b: f64, what: &str| {
                let e = (a - b).abs() / i.d;
                assert!(
                    e <= 1e-14,
                    "{kind:?} node {node} {what}: {a} {b} ({e:e} of D)"
                );
            };
            close(c.d, i.d, "D");
            close(c.weighted_gap, i.weighted_gap, "g̃");
            for (a, b) in c.lever.iter().zip(i.lever.iter()) {
                close(*a, *b, "lever");
            }
            let e = (c.normal - i.normal).norm();
            assert!(e <= 1e-14, "{kind:?} node {node} normal: {e:e}");
        }
    }
}

/// Against a plane a mortar node whose `x̃_j = x_j` couples in the
/// sparsity pattern only with the nodes of its faces (the pairs of
/// `MortarObstacle::coupled_groups`), not those nodes with each other:
/// the tangent assembled on the problem's pattern equals, entry by entry,
/// the one assembled on the pattern with every node's faces' nodes
/// coupled to each other (to the bit where both have the entry), and the
/// entries only the latter has are round-off (below 1e-13 of the largest),
/// at a warped, pressed state on an oblique plane: Tet4 faces (every node
/// paired), Tet10 faces (the corners paired, the mid-side nodes with
/// `x̃_j = Σ_k R_jk x_k` coupled as before). A dropped term of the tangent
/// (a lever on another node) would be of the contact stiffness's size.
#[test]
fn plane_pattern_drops_only_round_off() {
    let plane = RigidObstacle::plane(Vector3::zeros(), Vector3::new(0.03, 0.02, 1.0)).unwrap();
    for kind in [ElementKind::Tet4, ElementKind::Tet10] {
        let mut pr = block_on(kind, plane.clone());
        let x = pressed_state(&pr);
        let state = pr.initial_contact_state(&x);
        let tangent = |pr: &Problem| {
            let mut values = vec![0.0; pr.model.pattern.nnz()];
            pr.residual_into(1.0, &x, &state, Some(Tangent::Values(&mut values)))
                .unwrap();
            values
        };
        let k_paired = tangent(&pr);
        let couplings = pr.contacts.couplings();
        let c = pr.contacts.interface(0);
        let cliques: Vec<Vec<usize>> = (0..c.nodes.len()).map(|i| c.coupled_nodes(i)).collect();
        let with_cliques = pr.model.pattern.coupled(
            &cliques,
            &couplings.multipliers,
            &couplings.multiplier_groups,
        );
        let paired = std::mem::replace(&mut pr.model.pattern, with_cliques);
        let k_cliques = tangent(&pr);
        let largest = k_cliques.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        let (mut dropped, mut largest_dropped) = (0, 0.0_f64);
        let n = paired.num_nodes();
        for (a, b) in (0..n).flat_map(|a| (0..n).map(move |b| (a, b))) {
            let Some(full) = pr.model.pattern.block_columns(a, b) else {
                continue;
            };
            let kept = paired.block_columns(a, b);
            for (j, i) in (0..3).flat_map(|j| (0..3).map(move |i| (j, i))) {
                let v = k_cliques[full[j] + i];
                match kept {
                    Some(kept) => assert_eq!(k_paired[kept[j] + i], v, "{kind:?} ({a}, {b})"),
                    None => {
                        dropped += 1;
                        largest_dropped = largest_dropped.max(v.abs());
                    }
                }
            }
        }
        println!("{kind:?}: {dropped} entries dropped, largest {largest_dropped:e} of {largest:e}");
        assert!(dropped > 0, "{kind:?}: no entry dropped");
        assert!(
            largest_dropped <= 1e-13 * largest,
            "{kind:?}: {largest_dropped:e}"
        );
    }
}

/// The driver's terms of mortar nodes on a sphere (Hex8, Tet10 faces) and
/// a cylinder (Hex20 faces) against central differences (h = 1e-6) of the producer itself,
/// whose dual basis, area elements and obstacle normals follow the nodes:
/// `∇g` of the normalised gap, `∂(A b)/∂q = A ∂b/∂q` of the lever at the
/// area `A = D_j`, and the normal law's `K_qq`, to 1e-6 of their size.
#[test]
fn driver_terms_match_finite_differences() {
    let cylinder =
        RigidObstacle::cylinder(Vector3::new(0.0, 0.0, -2.0), Vector3::y(), 2.0).unwrap();
    let sphere = RigidObstacle::sphere(Vector3::new(0.0, 0.0, -2.0), 2.0).unwrap();
    for (kind, obstacle) in [
        (ElementKind::Hex8, sphere.clone()),
        (ElementKind::Tet10, sphere),
        (ElementKind::Hex20, cylinder),
    ] {
        let pr = block_on(kind, obstacle);
        let c = pr.contacts.interface(0);
        let signorini::contact::interface::Primary::MortarRigid(m) = &c.primary else {
            panic!("a mortar interface");
        };
        let mesh = &pr.model.mesh;
        let mut x = vec![0.0; 3 * mesh.num_nodes()];
        for (i, v) in x.iter_mut().enumerate() {
            *v = 0.004 * ((i as f64) * 0.77).sin();
        }
        m.nodes.iter().for_each(|&n| x[3 * n + 2] -= 0.06);
        // the four nodes nearest the point of first contact
        let mut nearest = m.nodes.clone();
        let radius = |n: &usize| mesh.nodes[*n][0].hypot(mesh.nodes[*n][1]);
        nearest.sort_by(|a, b| radius(a).total_cmp(&radius(b)));
        let law = NormalLaw::Penalty { epsilon: 300.0 };
        let st = NodeContactState::initial(&law, -1.0);
        let translation = Vector3::zeros();
        let p0 = m.producer(&translation, &mesh.nodes, &x, Derivatives::With);
        let mut checked = 0;
        for &j in nearest.iter().take(4) {
            let row = p0.node_row(j).expect("the corner nodes touch");
            let k0 = p0.row_kinematics(j, row);
            let r0 = k0.normal_response(&law, k0.area.unwrap(), &st);
            assert!(r0.active, "{kind:?} node {j} open");
            let h = 1e-6;
            for (a, &node) in k0.nodes.iter().enumerate() {
                for d in 0..3 {
                    let at = |s: f64| {
                        let mut y = x.clone();
                        y[3 * node + d] += s * h;
                        let p = m.producer(&translation, &mesh.nodes, &y, Derivatives::With);
                        let k = p.row_kinematics(j, p.node_row(j).unwrap());
                        let r = k.normal_response(&law, k.area.unwrap(), &st);
                        (k, r)
                    };
                    let ((kp, rp), (km, rm)) = (at(1.0), at(-1.0));
                    let c = 3 * a + d;
                    let close = |fd: f64, exact: f64, scale: f64, what: &str| {
                        assert!(
                            (fd - exact).abs() <= 1e-6 * scale,
                            "{kind:?} node {j}, q{c} {what}: fd {fd:e} exact {exact:e}"
                        );
                    };
                    let scale = k0.gradient.amax();
                    close((kp.gap - km.gap) / (2.0 * h), k0.gradient[c], scale, "∇g");
                    let lever = k0.lever.as_ref().unwrap();
                    for r in 0..k0.gradient.len() {
                        let area_lever =
                            |k: &GapKinematics<Dyn>| k.area.unwrap() * k.lever.as_ref().unwrap()[r];
                        let fd = (area_lever(&kp) - area_lever(&km)) / (2.0 * h);
                        let a0 = k0.area.unwrap();
                        close(fd / a0, k0.hessian[(r, c)], lever.amax(), "∂b/∂q");
                        let fd = (rp.residual[r] - rm.residual[r]) / (2.0 * h);
                        close(fd, r0.stiffness[(r, c)], r0.stiffness.amax(), "K_qq");
                    }
                }
            }
            checked += 1;
        }
        assert_eq!(checked, 4, "{kind:?}");
    }
}

/// Newton's rate against a sphere: the blocks of
/// [`block_on_sphere`] (Hex8, Tet10) pressed by 0.03 in two increments
/// converge to 1e-12 with the quadratic rate (`r_{k+1} ≤ 100 r_k²` once
/// below 1e-4, pairs where the contact set changed skipped), and the
/// contact force balances the top's reaction. The row cache integrates
/// the rows once per configuration Newton visits (at most once per
/// iteration and increment start), where the driver asks for them at
/// least twice as often.
#[test]
fn newton_converges_quadratically_on_a_sphere() {
    for kind in [ElementKind::Hex8, ElementKind::Tet10] {
        let mut pr = block_on_sphere(kind);
        let (_, increments) = solve(&mut pr);
        let iterations: Vec<usize> = increments.iter().map(|i| i.iterations).collect();
        let residuals: Vec<String> = increments
            .iter()
            .flat_map(|i| &i.newton)
            .map(|r| format!("{:.1e}", r.residual))
            .collect();
        println!(
            "{kind:?}: iterations {iterations:?}, residuals {}",
            residuals.join(" ")
        );
        let pairs = assert_quadratic(&increments);
        assert!(pairs >= 1);
        let signorini::contact::interface::Primary::MortarRigid(m) =
            &pr.contacts.interface(0).primary
        else {
            panic!("a mortar interface");
        };
        let counts = m.row_counts();
        let (newton, steps) = (iterations.iter().sum::<usize>(), increments.len());
        println!("{kind:?}: rows {counts:?}");
        assert!(counts.integrated <= newton + steps + 1, "{counts:?}");
        assert!(counts.requested >= 2 * counts.integrated, "{counts:?}");
    }
}

/// `discretisation = "mortar"` against an obstacle through the CLI's
/// `run`: a Hex20 block (3 × 3 × 2) on the plane z = 0 under P = 2, the
/// symmetry planes x = 0, y = 0: `summary.json`'s force is P × its
/// (reference) area (1e-10), the area the whole bottom (1, to 1e-12),
/// `contact_pressure` is `P/(1 + νP/E)²` at every bottom node (1e-10 of
/// P: the force over the current area). With friction:
/// `tests/mortar_obstacle_friction.rs`.
#[test]
fn mortar_obstacle_through_the_case_file() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = box_mesh(ElementKind::Hex20, [3, 3, 2], [1.0, 1.0, 0.5]);
    std::fs::write(dir.path().join("block.msh"), common::msh22(&mesh)).unwrap();
    let path = dir.path().join("case.toml");
    std::fs::write(
        &path,
        common::mortar_block_on_floor_case("", "residual_tolerance = 1e-13"),
    )
    .unwrap();
    let run = CaseRun::new(&path, &dir.path().join("out"));
    let contact = &run.outcome.summary.increments.last().unwrap().contact["bottom"];
    let stretch = (1.0 + NU * P / E).powi(2);
    let lambda = P / stretch;
    assert!((contact.area - 1.0).abs() < 1e-12, "area {}", contact.area);
    let force = contact.force[2];
    assert!((force - P).abs() < 1e-10 * P, "force {force}");
    let pressure = run.last_field("contact_pressure");
    let mesh = &run.problem.model.mesh;
    for n in mesh.surface_nodes(mesh.surface("zmin").unwrap()) {
        assert!(
            (pressure[n] - lambda).abs() < 1e-10 * P,
            "node {n}: {}",
            pressure[n]
        );
    }
}

/// What a quarter-model Hertz run gives against Hertz (`R = 1`,
/// `E* = E/(1 − ν²)`, `E = 1000`, `ν = 0.3`, with the run's total force).
#[derive(Debug)]
struct HertzNumbers {
    /// Unknown displacements of the mesh, `3 × nodes`.
    dofs: usize,
    /// Total contact force `F` (4 × the quarter's).
    force: f64,
    /// Peak nominal nodal pressure (the node's force over its reference
    /// area: node-to-surface's `contact_pressure`; the mortar multiplier
    /// `λ_j` is the force over the current area `D_j`, higher where the
    /// surface is compressed) and Hertz's `p₀`.
    peak: f64,
    p0: f64,
    /// Contact radius fitted to `p² = p₀²(1 − r²/a²)` (nodes above 0.2 p₀)
    /// and Hertz's `a`.
    radius: f64,
    a: f64,
    /// The largest penetration (`summary.json`).
    penetration: f64,
}

impl HertzNumbers {
    fn errors(&self) -> (f64, f64) {
        (self.peak / self.p0 - 1.0, self.radius / self.a - 1.0)
    }
}

/// Run the case `case` (text, read in `folder`) and measure it
/// ([`HertzNumbers`]; `fitted_contact_radius` and `radial_pressures` of
/// `contact::hertz`, as `tests/cases.rs` reads `examples/hertz`).
fn hertz_numbers(case: &str, folder: &std::path::Path) -> HertzNumbers {
    use signorini::contact::hertz::{fitted_contact_radius, radial_pressures, Hertz};
    let mut simulation = signorini::run::Simulation::from_toml(case, folder).unwrap();
    let out = tempfile::tempdir().unwrap();
    let options = signorini::run::RunOptions {
        output: Some(out.path().to_path_buf()),
        ..Default::default()
    };
    let outcome = simulation
        .run(&options, &mut signorini::output::observer::Silent)
        .expect("the case runs");
    let problem = simulation.problem();
    let x = &outcome.displacement;
    let (_, reports) = problem
        .residual_in(1.0, x, &problem.initial_contact_state(x), None)
        .unwrap();
    let interface = problem.contacts.interface(0);
    let last = outcome.summary.increments.last().unwrap();
    let contact = &last.contact["pole"];
    let force = 4.0 * contact.force[2].abs();
    let hertz = Hertz::new(force, 1.0, 1000.0 / (1.0 - 0.09));
    let mesh = &problem.model.mesh;
    // the nominal pressure: the node's force over its reference area
    let nominal = reports[0]
        .iter()
        .zip(&interface.areas)
        .map(|(r, a)| r.force[2].abs() / a);
    let nodes = radial_pressures(&interface.nodes, &mesh.nodes, x, nominal);
    HertzNumbers {
        dofs: problem.model.num_dofs(),
        force,
        peak: nodes.iter().map(|n| n.1).fold(0.0, f64::max),
        p0: hertz.peak_pressure,
        radius: fitted_contact_radius(&nodes, 0.2 * hertz.peak_pressure),
        a: hertz.radius,
        penetration: contact.largest_penetration,
    }
}

/// The folder of `examples/hertz`.
fn hertz_folder() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/hertz")
}

/// `examples/hertz/tet10.toml`: the hemisphere in Tet10 (13 239 nodes,
/// 39 717 dofs; `hemisphere_tet10.geo`, h = 0.012 at the pole) in dual
/// mortar contact with the rigid plane. Reference: Hertz with the run's
/// force (Johnson 1985, §4.2). The peak nominal pressure within 0.5 % of
/// `p₀` (observed −0.37 %; Tet4 node-to-surface is at +1.75 % with 161 184
/// dofs). The fitted contact radius within 2 % of `a` (observed −1.42 %):
/// it converges to about 1.4 % below Hertz with either element
/// (Tet10 −1.18, −1.33, −1.42 % at h = 0.03, 0.02, 0.012; Tet4 −0.98,
/// −1.19, −1.25 % at h = 0.006, 0.004, 0.003), the finite hemisphere's
/// departure from Hertz's half-space at `a/R ≈ 0.11`, not the
/// discretisation's (the example's README).
#[test]
fn hertz_tet10_mortar_against_hertz() {
    let folder = hertz_folder();
    let case = std::fs::read_to_string(folder.join("tet10.toml")).unwrap();
    let h = hertz_numbers(&case, &folder);
    let (dp, da) = h.errors();
    println!(
        "Tet10 mortar: {h:?}; peak {:+.2} %, radius {:+.2} %",
        100.0 * dp,
        100.0 * da
    );
    assert_eq!(h.dofs, 39_717, "the committed mesh");
    assert!(dp.abs() < 5e-3, "peak {} vs p0 {}", h.peak, h.p0);
    assert!(da.abs() < 2e-2, "radius {} vs a {}", h.radius, h.a);
    assert!(
        h.penetration < 1e-8 * 0.012,
        "penetration {}",
        h.penetration
    );
}

/// Mortar against node-to-surface on `examples/hertz` (its Tet4 mesh, the
/// rigid plane): the numbers of BENCHMARKS.md, printed; run by hand
/// (`cargo test --release --test mortar_rigid -- --ignored hertz_meshes`).
/// Or, instead, the meshes of `hemisphere.geo` listed in
/// `SIGNORINI_HERTZ_MESHES` (comma-separated `order:size`, the order 1
/// (Tet4) or 2 (Tet10) and the pole's element size, e.g.
/// `1:0.004,2:0.012`; gmsh on the PATH), Tet4 by node-to-surface (equal to
/// mortar on a plane), Tet10 by mortar: the refinement that finds the Tet4
/// mesh matching the Tet10 run's error.
#[test]
#[ignore]
fn hertz_meshes_mortar_against_node_to_surface() {
    let folder = hertz_folder();
    // the example takes mortar, the default; node-to-surface named
    let mortar = std::fs::read_to_string(folder.join("case.toml")).unwrap();
    let case = mortar.replace(
        "method = \"rockafellar\"",
        "method = \"rockafellar\"\ndiscretisation = \"node_to_surface\"",
    );
    let report = |label: &str, case: &str, folder: &std::path::Path| {
        let h = hertz_numbers(case, folder);
        let (dp, da) = h.errors();
        println!(
            "{label}: dofs {}, F {:.5}, peak {:.3} vs p0 {:.3} ({:+.2} %), radius {:.5} vs a {:.5} ({:+.2} %), penetration {:.1e}",
            h.dofs, h.force, h.peak, h.p0, 100.0 * dp, h.radius, h.a, 100.0 * da, h.penetration
        );
    };
    let meshes = std::env::var("SIGNORINI_HERTZ_MESHES").unwrap_or_default();
    if meshes.is_empty() {
        report("Tet4 h 0.006 node-to-surface", &case, &folder);
        report("Tet4 h 0.006 mortar", &mortar, &folder);
    }
    for mesh in meshes.split(',').filter(|s| !s.is_empty()) {
        let (order, hmin) = mesh.split_once(':').expect("order:size");
        let dir = tempfile::tempdir().unwrap();
        let geo = std::fs::read_to_string(folder.join("hemisphere.geo"))
            .unwrap()
            .replace("SizeMin = 0.006", &format!("SizeMin = {hmin}"));
        std::fs::write(dir.path().join("h.geo"), geo).unwrap();
        let status = std::process::Command::new("gmsh")
            .args(["-3", "-order", order, "h.geo", "-format", "msh41"])
            .args(["-o", "hemisphere.msh"])
            .current_dir(dir.path())
            .stdout(std::process::Stdio::null())
            .status()
            .expect("gmsh on the PATH");
        assert!(status.success());
        // on the plane, Tet4's mortar equals node-to-surface (module docs)
        if order == "1" {
            report(&format!("Tet4 h {hmin} node-to-surface"), &case, dir.path());
        } else {
            report(&format!("Tet10 h {hmin} mortar"), &mortar, dir.path());
        }
    }
}
