//! The quadratic and wedge elements (Tet10, Hex20, Hex20R, Wedge6, Wedge15),
//! issue 33: patch tests with every material on distorted meshes, the
//! finite-difference tangent of every material on every new element,
//! consistent pressure loads on Tri6/Quad8 faces, convergence rates
//! against a manufactured solution, and a bending case where Tet10 does not
//! lock and Tet4 does.

use nalgebra::Vector3;
use signorini::assembly::kernel::{internal_force_and_tangent, reference_geometry};
use signorini::assembly::loads::pressure_facet;
use signorini::assembly::Model;
use signorini::fem::{quadrature, shape};
use signorini::material::{LinearElastic, Material, NeoHookean, Ogden, SaintVenantKirchhoff};
use signorini::mesh::structured::{box_mesh, perturb_interior, with_mid_side_nodes};
use signorini::mesh::{topology, ElementKind, FacetKind, Mesh};
use signorini::solve::linear::{Ordering, SparseLdlt};
use std::f64::consts::PI;
use std::sync::Arc;

const NEW_KINDS: [ElementKind; 5] = [
    ElementKind::Tet10,
    ElementKind::Hex20,
    ElementKind::Hex20R,
    ElementKind::Wedge6,
    ElementKind::Wedge15,
];

fn materials() -> Vec<Arc<dyn Material>> {
    vec![
        Arc::new(LinearElastic::new(100.0, 0.3, "m").unwrap()),
        Arc::new(SaintVenantKirchhoff::new(100.0, 0.3, "m").unwrap()),
        Arc::new(NeoHookean::new(100.0, 0.45, "m").unwrap()),
        Arc::new(Ogden::new(vec![0.4095, 0.003, 0.01], vec![1.3, 5.0, -2.0], 4.0, "m").unwrap()),
    ]
}

/// Newton on `f_int(u) = f_ext` with the dofs `fixed` held at their values
/// in `u`: the model's sparse tangent, rows and columns of the fixed dofs
/// replaced by the identity, factorised by the crate's LDLᵀ. Stops when a
/// correction is below 1e-15 of `u`'s size.
fn solve(model: &Model, fixed: &[bool], u: &mut [f64], f_ext: &[f64]) {
    let symbolic = model.pattern.symbolic();
    let mut ldlt = SparseLdlt::new(Ordering::Amd, 1);
    ldlt.analyse(symbolic).unwrap();
    let n = u.len();
    for _ in 0..25 {
        let mut f = vec![0.0; n];
        let mut k = vec![0.0; model.pattern.nnz()];
        model.assemble_internal(u, &mut f, Some(&mut k)).unwrap();
        let (cp, ri) = (symbolic.col_ptr(), symbolic.row_idx());
        for j in 0..n {
            for p in cp[j]..cp[j + 1] {
                let i = ri[p];
                if fixed[i] || fixed[j] {
                    k[p] = if i == j { 1.0 } else { 0.0 };
                }
            }
        }
        let mut du: Vec<f64> = (0..n)
            .map(|i| if fixed[i] { 0.0 } else { f_ext[i] - f[i] })
            .collect();
        ldlt.factorize(symbolic, &k, None).unwrap();
        ldlt.solve_in_place(&mut du).unwrap();
        let size = u.iter().fold(1e-300f64, |m, v| m.max(v.abs()));
        let step = du.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        u.iter_mut().zip(&du).for_each(|(x, d)| *x += d);
        if step <= 1e-15 * size {
            return;
        }
    }
}

/// The dofs of the nodes on the boundary of the box `[0, l]³`.
fn boundary_dofs(mesh: &Mesh, lengths: [f64; 3]) -> Vec<bool> {
    mesh.nodes
        .iter()
        .flat_map(|x| {
            let on = (0..3).any(|d| x[d].abs() < 1e-12 || (x[d] - lengths[d]).abs() < 1e-12);
            [on; 3]
        })
        .collect()
}

/// The patch test: on a distorted 2×2×2 mesh of each new kind (interior
/// corners moved by up to 20 % of a cell, the mid-side nodes halfway along
/// the straight edges), the boundary held at the homogeneous deformation
/// `u = A X + b`, Newton reproduces it at every interior node to 1e-12 with
/// every material (no body force: a homogeneous deformation is in
/// equilibrium for any hyperelastic law).
#[test]
fn patch_test_every_new_element_every_material() {
    let lengths = [1.0, 1.2, 0.9];
    let a = [
        [0.02, -0.01, 0.015],
        [0.005, -0.03, 0.01],
        [-0.012, 0.008, 0.025],
    ];
    let b = [0.01, -0.02, 0.005];
    for kind in NEW_KINDS {
        let mut linear = box_mesh(topology::linear(kind), [2, 2, 2], lengths);
        perturb_interior(&mut linear, [2, 2, 2], lengths, 0.2, 7);
        let mesh = if kind.is_quadratic() {
            with_mid_side_nodes(&linear, kind)
        } else {
            linear
        };
        let exact: Vec<f64> = mesh
            .nodes
            .iter()
            .flat_map(|x| [0, 1, 2].map(|i| b[i] + (0..3).map(|j| a[i][j] * x[j]).sum::<f64>()))
            .collect();
        let fixed = boundary_dofs(&mesh, lengths);
        assert!(fixed.iter().any(|f| !f), "{kind:?}: interior nodes");
        let mesh = Arc::new(mesh);
        for material in materials() {
            let model = Model::new(
                Arc::clone(&mesh),
                vec![material.clone()],
                vec![0; mesh.elements.len()],
            )
            .unwrap();
            let mut u: Vec<f64> = (0..exact.len())
                .map(|i| if fixed[i] { exact[i] } else { 0.0 })
                .collect();
            let zero = vec![0.0; u.len()];
            solve(&model, &fixed, &mut u, &zero);
            let error = u
                .iter()
                .zip(&exact)
                .fold(0.0f64, |m, (x, e)| m.max((x - e).abs()));
            assert!(
                error < 1e-12,
                "{kind:?} {}: patch error {error:e}",
                material.name()
            );
        }
    }
}

/// The reference nodes of `kind` through a curved map, and a displacement
/// of a few percent.
fn curved_element(kind: ElementKind) -> (Vec<[f64; 3]>, Vec<[f64; 3]>) {
    let x = shape::reference_nodes(kind)
        .iter()
        .map(|x| {
            [
                x[0] + 0.1 * x[1] + 0.03 * x[2] * x[2],
                0.05 * x[0] + 0.9 * x[1] + 0.03 * x[0] * x[1],
                0.02 * x[0] + 0.1 * x[1] + 1.1 * x[2] + 0.03 * x[1] * x[1],
            ]
        })
        .collect::<Vec<_>>();
    let u = (0..x.len())
        .map(|a| {
            let s = a as f64;
            [
                0.03 * s.sin(),
                -0.02 * (0.7 * s).cos(),
                0.04 * (1.3 * s).sin(),
            ]
        })
        .collect();
    (x, u)
}

/// The element tangent `∂f/∂u` of every material on every new element
/// (curved) equals the central finite difference of the internal force,
/// `h = 1e-6`, to 1e-6 of the tangent's largest entry.
#[test]
fn element_tangents_match_finite_differences() {
    for kind in NEW_KINDS {
        let (x, u) = curved_element(kind);
        let geometry = reference_geometry(kind, &x).unwrap();
        let n = u.len();
        for material in materials() {
            let m = material.as_ref();
            let k = internal_force_and_tangent(&geometry, &u, m, true)
                .unwrap()
                .stiffness;
            let scale = k.iter().fold(0.0f64, |s, v| s.max(v.abs()));
            let h = 1e-6;
            for col in 0..3 * n {
                let (mut up, mut um) = (u.clone(), u.clone());
                up[col / 3][col % 3] += h;
                um[col / 3][col % 3] -= h;
                let fp = internal_force_and_tangent(&geometry, &up, m, false)
                    .unwrap()
                    .force;
                let fm = internal_force_and_tangent(&geometry, &um, m, false)
                    .unwrap()
                    .force;
                for row in 0..3 * n {
                    let fd = (fp[row] - fm[row]) / (2.0 * h);
                    let exact = k[row * 3 * n + col];
                    assert!(
                        (fd - exact).abs() < 1e-6 * scale,
                        "{kind:?} {} K[{row},{col}] {exact} vs FD {fd}",
                        m.name()
                    );
                }
            }
        }
    }
}

/// A uniform pressure `p` on a flat Tri6 of area `A` gives the corners no
/// force and each mid-side node `p A / 3`; on a flat Quad8 the corners
/// `−p A / 12` and the mid-side nodes `p A / 3` (the nodal integrals of
/// the quadratic shape functions), all along `−n`.
#[test]
fn consistent_pressure_on_quadratic_faces() {
    let p = 2.5;
    // a Tri6 in the plane z = 1 with corners (0,0), (3,0), (0,2): A = 3
    let tri = [
        [0.0, 0.0, 1.0],
        [3.0, 0.0, 1.0],
        [0.0, 2.0, 1.0],
        [1.5, 0.0, 1.0],
        [1.5, 1.0, 1.0],
        [0.0, 1.0, 1.0],
    ];
    let (f, _) = pressure_facet(FacetKind::Tri6, &tri, p, false);
    for a in 0..6 {
        let expected = if a < 3 { 0.0 } else { -p * 3.0 / 3.0 };
        assert!(
            (f[3 * a + 2] - expected).abs() < 1e-13,
            "Tri6 node {a}: {}",
            f[3 * a + 2]
        );
        assert!(f[3 * a].abs() < 1e-13 && f[3 * a + 1].abs() < 1e-13);
    }
    // a Quad8: the rectangle 2 × 1 in z = 0, A = 2
    let quad = [
        [0.0, 0.0, 0.0],
        [2.0, 0.0, 0.0],
        [2.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
        [1.0, 0.0, 0.0],
        [2.0, 0.5, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 0.5, 0.0],
    ];
    let (f, _) = pressure_facet(FacetKind::Quad8, &quad, p, false);
    for a in 0..8 {
        let expected = if a < 4 {
            p * 2.0 / 12.0
        } else {
            -p * 2.0 / 3.0
        };
        assert!(
            (f[3 * a + 2] - expected).abs() < 1e-13,
            "Quad8 node {a}: {}",
            f[3 * a + 2]
        );
    }
}

/// A quadrature rule finer than the elements' own, to measure errors:
/// 3 Gauss points a direction on the hexahedron; on the tetrahedron the
/// same rule on the cube collapsed onto it (Duffy: `ξ = s`,
/// `η = t (1 − s)`, `ζ = r (1 − s)(1 − t)`, weight `(1 − s)² (1 − t)`).
fn error_rule(kind: ElementKind) -> (Vec<[f64; 3]>, Vec<f64>) {
    let (points, weights) = quadrature::hexahedron(3);
    if topology::linear(kind) == ElementKind::Hex8 {
        return (points, weights);
    }
    let unit = |x: f64| 0.5 * (x + 1.0);
    points
        .iter()
        .zip(&weights)
        .map(|(p, w)| {
            let (s, t, r) = (unit(p[0]), unit(p[1]), unit(p[2]));
            (
                [s, t * (1.0 - s), r * (1.0 - s) * (1.0 - t)],
                w / 8.0 * (1.0 - s).powi(2) * (1.0 - t),
            )
        })
        .unzip()
}

/// The manufactured solution `u_i = φ = sin πx sin πy sin πz` (every
/// component; zero on the unit cube's boundary), its gradient, and the
/// body force `b = −div σ = −(λ + μ) ∇(div u) − μ Δu` of Hooke's law.
struct Manufactured {
    lambda: f64,
    mu: f64,
}

impl Manufactured {
    fn u(&self, x: &[f64; 3]) -> f64 {
        x.iter().map(|v| (PI * v).sin()).product()
    }
    /// `∂φ/∂x_d`
    fn gradient(&self, x: &[f64; 3]) -> [f64; 3] {
        let (s, c) = (x.map(|v| (PI * v).sin()), x.map(|v| (PI * v).cos()));
        [
            PI * c[0] * s[1] * s[2],
            PI * s[0] * c[1] * s[2],
            PI * s[0] * s[1] * c[2],
        ]
    }
    fn body_force(&self, x: &[f64; 3]) -> [f64; 3] {
        let (s, c) = (x.map(|v| (PI * v).sin()), x.map(|v| (PI * v).cos()));
        // ∂²φ/∂x_i∂x_j
        let hessian = |i: usize, j: usize| -> f64 {
            if i == j {
                -PI * PI * s[0] * s[1] * s[2]
            } else {
                let k = 3 - i - j;
                PI * PI * c[i] * c[j] * s[k]
            }
        };
        let laplacian = -3.0 * PI * PI * s[0] * s[1] * s[2];
        std::array::from_fn(|i| {
            let grad_div: f64 = (0..3).map(|j| hessian(i, j)).sum();
            -(self.lambda + self.mu) * grad_div - self.mu * laplacian
        })
    }
}

/// The L2 and H1-seminorm errors of the finite-element solution on a mesh
/// of `cells³` elements of `kind` of the unit cube (linear elastic, `E = 1`,
/// `ν = 0.3`, the boundary fixed, the manufactured body force).
fn manufactured_errors(kind: ElementKind, cells: usize) -> (f64, f64) {
    let (e, nu) = (1.0, 0.3);
    let exact = Manufactured {
        lambda: e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)),
        mu: e / (2.0 * (1.0 + nu)),
    };
    let mesh = Arc::new(box_mesh(kind, [cells; 3], [1.0; 3]));
    let material: Arc<dyn Material> = Arc::new(LinearElastic::new(e, nu, "m").unwrap());
    let model = Model::new(
        Arc::clone(&mesh),
        vec![material],
        vec![0; mesh.elements.len()],
    )
    .unwrap();
    let n = 3 * mesh.num_nodes();
    let mut f_ext = vec![0.0; n];
    for el in &mesh.elements {
        let x: Vec<[f64; 3]> = el.nodes.iter().map(|&a| mesh.nodes[a]).collect();
        let r = signorini::fem::volume_reference(el.kind);
        let geometry = reference_geometry(el.kind, &x).unwrap();
        for (q, p) in geometry.iter().enumerate() {
            let xq = point(&r.values[q], &x);
            let b = exact.body_force(&xq);
            for (a, &node) in el.nodes.iter().enumerate() {
                for i in 0..3 {
                    f_ext[3 * node + i] += r.values[q][a] * b[i] * p.dv;
                }
            }
        }
    }
    let fixed = boundary_dofs(&mesh, [1.0; 3]);
    let mut u = vec![0.0; n];
    solve(&model, &fixed, &mut u, &f_ext);
    let (points, weights) = error_rule(kind);
    let (mut l2, mut h1) = (0.0, 0.0);
    for el in &mesh.elements {
        let x: Vec<[f64; 3]> = el.nodes.iter().map(|&a| mesh.nodes[a]).collect();
        for (xi, w) in points.iter().zip(&weights) {
            let (values, gradients) = shape::evaluate(el.kind, xi);
            let mut j = nalgebra::Matrix3::zeros();
            for (xa, g) in x.iter().zip(&gradients) {
                j += Vector3::from(*xa) * Vector3::from(*g).transpose();
            }
            let (det, inv_t) = (j.determinant(), j.try_inverse().unwrap().transpose());
            let xq = point(&values, &x);
            let (ue, ge) = (exact.u(&xq), Vector3::from(exact.gradient(&xq)));
            for i in 0..3 {
                let mut uh = 0.0;
                let mut gh = Vector3::zeros();
                for (a, &node) in el.nodes.iter().enumerate() {
                    uh += values[a] * u[3 * node + i];
                    gh += inv_t * Vector3::from(gradients[a]) * u[3 * node + i];
                }
                l2 += (uh - ue).powi(2) * det * w;
                h1 += (gh - ge).norm_squared() * det * w;
            }
        }
    }
    (l2.sqrt(), h1.sqrt())
}

fn point(values: &[f64], x: &[[f64; 3]]) -> [f64; 3] {
    std::array::from_fn(|d| values.iter().zip(x).map(|(n, xa)| n * xa[d]).sum())
}

/// Convergence against the manufactured solution, mesh size halved (cells
/// 2 → 4 for the quadratic elements, 4 → 8 for the linear ones): the
/// observed orders `log₂(e_h / e_{h/2})` are 3 in L2 and 2 in the energy
/// (H1-seminorm) for Tet10 and Hex20, 2 and 1 for Tet4 and Hex8, each
/// within 0.3.
#[test]
fn convergence_rates_against_a_manufactured_solution() {
    let cases = [
        (ElementKind::Tet10, 3, 3.0, 2.0),
        (ElementKind::Hex20, 3, 3.0, 2.0),
        (ElementKind::Tet4, 4, 2.0, 1.0),
        (ElementKind::Hex8, 4, 2.0, 1.0),
    ];
    for (kind, coarse, l2_order, h1_order) in cases {
        let (l2_h, h1_h) = manufactured_errors(kind, coarse);
        let (l2_half, h1_half) = manufactured_errors(kind, 2 * coarse);
        let (l2_rate, h1_rate) = ((l2_h / l2_half).log2(), (h1_h / h1_half).log2());
        println!("{kind:?}: L2 {l2_h:.3e} → {l2_half:.3e} (order {l2_rate:.2}), H1 {h1_h:.3e} → {h1_half:.3e} (order {h1_rate:.2})");
        assert!(
            (l2_rate - l2_order).abs() < 0.3,
            "{kind:?} L2 order {l2_rate}"
        );
        assert!(
            (h1_rate - h1_order).abs() < 0.3,
            "{kind:?} H1 order {h1_rate}"
        );
    }
}

/// A cantilever `L × h × h` (`L = 10`, `h = 1`, `E = 1000`, `ν = 0`),
/// clamped at `x = 0`, under its own weight `q = ρ g h²` along `−z`: the
/// tip deflection of Timoshenko's beam is
/// `w = q L⁴ / (8 E I) + q L² / (2 κ G A)` (`I = h⁴/12`, `κ = 5/6`).
/// Tet10 on 10×2×2 cells is within 3 % of it; Tet4 on the same cells
/// locks (below 60 % of it).
#[test]
fn bending_tet10_does_not_lock_and_tet4_does() {
    let (l, h, e): (f64, f64, f64) = (10.0, 1.0, 1000.0);
    let weight = 0.01; // ρ g
    let q = weight * h * h;
    let (i, area, g) = (h.powi(4) / 12.0, h * h, e / 2.0);
    let beam = q * l.powi(4) / (8.0 * e * i) + q * l * l / (2.0 * 5.0 / 6.0 * g * area);
    let tip = |kind: ElementKind| -> f64 {
        let mesh = Arc::new(box_mesh(kind, [10, 2, 2], [l, h, h]));
        let material: Arc<dyn Material> = Arc::new(LinearElastic::new(e, 0.0, "m").unwrap());
        let all: Vec<usize> = (0..mesh.elements.len()).collect();
        let model = Model::new(Arc::clone(&mesh), vec![material], vec![0; all.len()]).unwrap();
        let volumes = model.nodal_volumes(&all);
        let f_ext: Vec<f64> = volumes
            .iter()
            .flat_map(|v| [0.0, 0.0, -weight * v])
            .collect();
        let fixed: Vec<bool> = mesh
            .nodes
            .iter()
            .flat_map(|x| [x[0].abs() < 1e-12; 3])
            .collect();
        let mut u = vec![0.0; f_ext.len()];
        solve(&model, &fixed, &mut u, &f_ext);
        let tip: Vec<usize> = (0..mesh.num_nodes())
            .filter(|&a| (mesh.nodes[a][0] - l).abs() < 1e-12)
            .collect();
        -tip.iter().map(|&a| u[3 * a + 2]).sum::<f64>() / tip.len() as f64
    };
    let (w10, w4) = (tip(ElementKind::Tet10), tip(ElementKind::Tet4));
    println!(
        "beam {beam:.5e}, Tet10 {w10:.5e} ({:.3}), Tet4 {w4:.5e} ({:.3})",
        w10 / beam,
        w4 / beam
    );
    assert!(
        (w10 / beam - 1.0).abs() < 0.03,
        "Tet10 tip {w10} against {beam}"
    );
    assert!(w4 / beam < 0.6, "Tet4 tip {w4} against {beam}: no locking?");
}

fn data(name: &str) -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
}

/// The second-order Gmsh meshes of `tests/data` (their `.geo` beside
/// them): a 4 × 1 × 1 bar of Tet10, of Wedge15 and of Hex20, its end
/// `x = 4` ("loaded") of Tri6 or Quad8 facets. Each is read with its kinds
/// and volume 4, and under a tension `σ` on "loaded" (a consistent
/// pressure `−σ` on its quadratic facets) and the symmetry planes held
/// normal, Newton gives the uniaxial field `u = σ/E (x, −ν y, −ν z)` to
/// 1e-10 of its size (an exact field of the quadratic elements).
#[test]
fn gmsh_second_order_bars_in_tension() {
    use signorini::mesh::gmsh::read_msh;
    let cases = [
        ("bar_tet10.msh", ElementKind::Tet10, FacetKind::Tri6),
        ("bar_wedge15.msh", ElementKind::Wedge15, FacetKind::Tri6),
        ("bar_hex20.msh", ElementKind::Hex20, FacetKind::Quad8),
    ];
    let (e, nu, sigma) = (200.0, 0.3, 2.0);
    for (file, kind, facet) in cases {
        let mesh = Arc::new(read_msh(&data(file)).unwrap());
        assert!(mesh.elements.iter().all(|el| el.kind == kind), "{file}");
        let loaded = mesh.surface("loaded").unwrap();
        assert!(loaded.facets.iter().all(|f| f.kind == facet), "{file}");
        let volume: f64 = mesh
            .elements
            .iter()
            .map(|el| {
                let x: Vec<[f64; 3]> = el.nodes.iter().map(|&a| mesh.nodes[a]).collect();
                reference_geometry(el.kind, &x)
                    .unwrap()
                    .iter()
                    .map(|p| p.dv)
                    .sum::<f64>()
            })
            .sum();
        assert!((volume - 4.0).abs() < 1e-12, "{file}: volume {volume}");
        let mut f_ext = vec![0.0; 3 * mesh.num_nodes()];
        for f in &loaded.facets {
            let x: Vec<[f64; 3]> = f.nodes.iter().map(|&a| mesh.nodes[a]).collect();
            let (force, _) = pressure_facet(f.kind, &x, -sigma, false);
            for (a, &node) in f.nodes.iter().enumerate() {
                for i in 0..3 {
                    f_ext[3 * node + i] += force[3 * a + i];
                }
            }
        }
        let fixed: Vec<bool> = mesh
            .nodes
            .iter()
            .flat_map(|x| [0, 1, 2].map(|d| x[d].abs() < 1e-12))
            .collect();
        let material: Arc<dyn Material> = Arc::new(LinearElastic::new(e, nu, "m").unwrap());
        let model = Model::new(
            Arc::clone(&mesh),
            vec![material],
            vec![0; mesh.elements.len()],
        )
        .unwrap();
        let mut u = vec![0.0; f_ext.len()];
        solve(&model, &fixed, &mut u, &f_ext);
        let strain = sigma / e;
        let error = mesh.nodes.iter().enumerate().fold(0.0f64, |m, (a, x)| {
            let exact = [strain * x[0], -nu * strain * x[1], -nu * strain * x[2]];
            (0..3).fold(m, |m, i| m.max((u[3 * a + i] - exact[i]).abs()))
        });
        assert!(error < 1e-10 * 4.0 * strain, "{file}: error {error:e}");
    }
}

/// Gmsh's Abaqus deck of the Tet10 bar (C3D10, Abaqus's node order) and
/// its MSH file (Gmsh's order) give the same elements node for node once
/// read (by node tag, element by element id): the C3D10 order is mapped.
#[test]
fn c3d10_deck_and_msh_agree_node_for_node() {
    use signorini::mesh::gmsh::read_msh;
    use signorini::mesh::inp::read_inp;
    let msh = read_msh(&data("bar_tet10.msh")).unwrap();
    let inp = read_inp(&data("bar_tet10.inp")).unwrap().mesh;
    assert_eq!(msh.elements.len(), inp.elements.len());
    let by_id: std::collections::HashMap<u64, &signorini::mesh::Element> =
        inp.elements.iter().map(|el| (el.id, el)).collect();
    let mut matched = 0;
    // the node tags of an element (the deck and the MSH file share them)
    let tags = |m: &Mesh, el: &signorini::mesh::Element| -> Vec<u64> {
        el.nodes.iter().map(|&a| m.node_ids[a]).collect()
    };
    for el in &msh.elements {
        let other = by_id[&el.id];
        assert_eq!(tags(&inp, other), tags(&msh, el), "element {}", el.id);
        matched += 1;
    }
    assert_eq!(matched, msh.elements.len());
}

/// The whole run on the second-order bars through a case file: clamped at
/// "fixed", a tension `σ = 2` (pressure −2) on "loaded", linear elastic
/// with `ν = 0` (no lateral contraction: the clamp holds nothing back), so
/// `u_x = σ x / E` exactly; the run writes its VTU with the quadratic
/// cells (types 24, 26, 25). The Tet10 bar also as Gmsh's C3D10 deck.
#[test]
fn second_order_bars_run_through_a_case_file() {
    use signorini::run::{RunOptions, Simulation};
    for (file, vtk_type) in [
        ("bar_tet10.msh", 24u8),
        ("bar_wedge15.msh", 26),
        ("bar_hex20.msh", 25),
        // Gmsh's C3D10 deck: its CPS6 element sets "fixed" and "loaded"
        // are the surface sets
        ("bar_tet10.inp", 24),
    ] {
        let text = format!(
            r#"
[mesh]
file = "{file}"

[[material]]
region = "bar"
model = "linear_elastic"
youngs_modulus = 200.0
poisson_ratio = 0.0

[[displacement]]
surface = "fixed"
x = 0.0
y = 0.0
z = 0.0

[[pressure]]
surface = "loaded"
value = -2.0

[[step]]
name = "load"
end_time = 1.0

[output]
name = "bar"
"#
        );
        let out = tempfile::tempdir().unwrap();
        let mut simulation = Simulation::from_toml(&text, &data("")).unwrap();
        let options = RunOptions {
            output: Some(out.path().to_path_buf()),
            threads: Some(1),
            cancel: None,
            restart: None,
        };
        let silent = &mut signorini::output::observer::Silent;
        let outcome = simulation.run(&options, silent).unwrap();
        let mesh = &simulation.problem().model.mesh;
        let error = mesh.nodes.iter().enumerate().fold(0.0f64, |m, (a, x)| {
            let exact = [2.0 / 200.0 * x[0], 0.0, 0.0];
            (0..3).fold(m, |m, i| {
                m.max((outcome.displacement[3 * a + i] - exact[i]).abs())
            })
        });
        assert!(error < 1e-10, "{file}: error {error:e}");
        let vtu = std::fs::read_dir(&outcome.output_dir)
            .unwrap()
            .filter_map(|e| e.ok())
            .find(|e| e.path().extension().is_some_and(|x| x == "vtu"))
            .map(|e| e.path());
        assert!(vtu.is_some(), "{file}: no VTU written");
        assert!(mesh.elements.iter().all(|e| e.kind.vtk_type() == vtk_type));
    }
}

/// `*SURFACE, TYPE=ELEMENT` with Abaqus face numbers on C3D10, C3D20 and
/// C3D15 decks (written with Abaqus's node order): the face `S3` of a
/// C3D10 (`2-4-3`), `S2` of a C3D20 (`5-8-7-6`) and `S4` of a C3D15
/// (`2-5-6-3`) become quadratic facets with the corners and the mid-side
/// nodes of those faces, oriented outward (corners in the order of
/// `ElementKind::faces`, up to a rotation).
#[test]
fn abaqus_surfaces_on_quadratic_elements() {
    use signorini::mesh::inp::read_inp;
    use std::fmt::Write;
    let cases = [
        (
            ElementKind::Tet10,
            "C3D10",
            3,
            [1, 2, 3, 5, 8, 9].as_slice(),
        ),
        (
            ElementKind::Hex20,
            "C3D20",
            2,
            &[4, 5, 6, 7, 16, 18, 19, 17],
        ),
        (
            ElementKind::Wedge15,
            "C3D15",
            4,
            &[1, 2, 5, 4, 9, 11, 14, 10],
        ),
    ];
    for (kind, name, face, local) in cases {
        let mesh = box_mesh(kind, [1, 1, 1], [1.0, 1.0, 1.0]);
        let mut deck = String::from("*NODE\n");
        for (a, x) in mesh.nodes.iter().enumerate() {
            writeln!(deck, "{}, {}, {}, {}", a + 1, x[0], x[1], x[2]).unwrap();
        }
        writeln!(deck, "*ELEMENT, TYPE={name}, ELSET=body").unwrap();
        for (e, el) in mesh.elements.iter().enumerate() {
            let abaqus: Vec<String> = kind
                .vtk_order()
                .iter()
                .map(|&a| (el.nodes[a] + 1).to_string())
                .collect();
            writeln!(deck, "{}, {}", e + 1, abaqus.join(", ")).unwrap();
        }
        writeln!(deck, "*SURFACE, NAME=side, TYPE=ELEMENT\n1, S{face}").unwrap();
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("deck.inp");
        std::fs::write(&path, deck).unwrap();
        let read = read_inp(&path).unwrap().mesh;
        let el = &read.elements[0];
        assert_eq!(
            el.nodes, mesh.elements[0].nodes,
            "{name}: the element's order"
        );
        let facets = &read.surface("side").unwrap().facets;
        assert_eq!(facets.len(), 1, "{name}");
        let facet = &facets[0];
        let expected: Vec<usize> = local.iter().map(|&a| el.nodes[a]).collect();
        let c = facet.kind.num_corners();
        assert_eq!(facet.kind.num_nodes(), local.len(), "{name}");
        // the same cycle of corners and of mid-side nodes, up to a rotation
        let start = expected[..c]
            .iter()
            .position(|&n| n == facet.nodes[0])
            .unwrap();
        let rotated: Vec<usize> = (0..c)
            .map(|i| expected[(start + i) % c])
            .chain((0..c).map(|i| expected[c + (start + i) % c]))
            .collect();
        assert_eq!(facet.nodes, rotated, "{name} S{face}");
    }
}
