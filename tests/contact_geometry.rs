//! Verification of the contact geometry kernels (`signorini::contact`):
//! analytic obstacles against hand formulas and finite-difference
//! curvatures, the closest point on a triangle against an independent
//! reference and dense sampling, the bounding-box search against brute
//! force (and its cost), STL and Gmsh readers, and tributary areas against
//! the consistent pressure loads.

mod common;

use common::icosphere;
use nalgebra::{Matrix3, Vector3};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use signorini::assembly::loads::pressure_facet;
use signorini::contact::triangle::{closest_point_on_triangle, Feature};
use signorini::contact::tributary::facet_area;
use signorini::contact::{tributary_areas, Projection, RigidObstacle, TriangulatedSurface};
use signorini::mesh::structured::box_mesh;
use signorini::mesh::{ElementKind, Facet, FacetKind, Mesh, SurfaceSet};
use signorini::Error;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

type V3 = Vector3<f64>;

fn v(x: f64, y: f64, z: f64) -> V3 {
    V3::new(x, y, z)
}

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
}

// ---------------------------------------------------------------------------
// analytic obstacles

/// Central-difference Hessian of `g`:
/// `H_ij ≈ [g(x+he_i+he_j) − g(x+he_i−he_j) − g(x−he_i+he_j) + g(x−he_i−he_j)]/(4h²)`.
fn fd_hessian(g: impl Fn(&V3) -> f64, x: &V3, h: f64) -> Matrix3<f64> {
    let mut hess = Matrix3::zeros();
    for i in 0..3 {
        for j in 0..3 {
            let (mut ei, mut ej) = (V3::zeros(), V3::zeros());
            ei[i] = h;
            ej[j] = h;
            hess[(i, j)] = (g(&(x + ei + ej)) - g(&(x + ei - ej)) - g(&(x - ei + ej))
                + g(&(x - ei - ej)))
                / (4.0 * h * h);
        }
    }
    hess
}

/// Central-difference gradient of `g`.
fn fd_gradient(g: impl Fn(&V3) -> f64, x: &V3, h: f64) -> V3 {
    V3::from_fn(|i, _| {
        let mut e = V3::zeros();
        e[i] = h;
        (g(&(x + e)) - g(&(x - e))) / (2.0 * h)
    })
}

/// `∂g/∂x = n` and `∂²g/∂x² = curvature` by central differences; the
/// Hessian to relative 1e-6 (of max(|H|, 1): the plane's is zero).
fn check_derivatives(obstacle: &RigidObstacle, x: &V3) {
    let p = obstacle.project(x);
    let gap = |y: &V3| obstacle.project(y).gap;
    let grad = fd_gradient(gap, x, 1e-6);
    assert!(
        (grad - p.normal).norm() < 1e-8,
        "gradient {grad} vs normal {} at {x}",
        p.normal
    );
    let hess = fd_hessian(gap, x, 1e-4);
    let err = (hess - p.curvature).norm();
    assert!(
        err < 1e-6 * p.curvature.norm().max(1.0),
        "Hessian at {x}: fd {hess} analytic {} (error {err:.2e})",
        p.curvature
    );
    assert!((p.curvature - p.curvature.transpose()).norm() < 1e-15);
}

fn assert_projection(p: &Projection, point: V3, normal: V3, gap: f64) {
    assert!((p.point - point).norm() < 1e-14, "{} vs {point}", p.point);
    assert!(
        (p.normal - normal).norm() < 1e-14,
        "{} vs {normal}",
        p.normal
    );
    assert!((p.gap - gap).abs() < 1e-14, "{} vs {gap}", p.gap);
}

#[test]
fn plane_gap_point_and_curvature() {
    // the plane x + 2y + 2z = 3 (through (1, 1, 0)), normal (1, 2, 2)/3
    let plane = RigidObstacle::plane(v(1.0, 1.0, 0.0), v(1.0, 2.0, 2.0)).unwrap();
    let n = v(1.0, 2.0, 2.0) / 3.0;
    for x in [
        v(0.0, 0.0, 0.0),
        v(2.0, 3.0, 4.0),
        v(1.0, 1.0, 0.0),
        v(-5.0, 0.5, 7.0),
    ] {
        let g = (x[0] + 2.0 * x[1] + 2.0 * x[2] - 3.0) / 3.0;
        let p = plane.project(&x);
        assert_projection(&p, x - n * g, n, g);
        assert_eq!(p.curvature, Matrix3::zeros());
        check_derivatives(&plane, &x);
    }
    // x = 0: g = −1 (behind the plane)
    assert!((plane.project(&V3::zeros()).gap + 1.0).abs() < 1e-15);
}

#[test]
fn sphere_gap_point_and_curvature() {
    let c = v(1.0, -2.0, 0.5);
    let sphere = RigidObstacle::sphere(c, 2.0).unwrap();
    // outside, on the surface, inside
    for (offset, gap) in [
        (v(3.0, 4.0, 0.0), 3.0),    // |r| = 5
        (v(0.0, 0.0, -2.0), 0.0),   // on the surface
        (v(1.0, 2.0, 2.0), 1.0),    // |r| = 3
        (v(0.0, 0.6, 0.8), -1.0),   // |r| = 1, inside
        (v(-0.3, 0.0, -0.4), -1.5), // |r| = 0.5
    ] {
        let x = c + offset;
        let n = offset.normalize();
        let p = sphere.project(&x);
        assert_projection(&p, c + n * 2.0, n, gap);
        let d = offset.norm();
        let expected = (Matrix3::identity() - n * n.transpose()) / d;
        assert!((p.curvature - expected).norm() < 1e-14);
        check_derivatives(&sphere, &x);
    }
}

#[test]
fn cylinder_gap_point_and_curvature() {
    // axis through (1, 0, 0) along (0, 0, 1) given unnormalised, radius 1
    let cyl = RigidObstacle::cylinder(v(1.0, 0.0, 0.0), v(0.0, 0.0, 3.0), 1.0).unwrap();
    for (x, foot, n, gap) in [
        (
            v(4.0, 4.0, 7.0),
            v(1.6, 0.8, 7.0),
            v(0.6, 0.8, 0.0),
            4.0, // |r⊥| = 5
        ),
        (
            v(1.0, -0.5, -2.0),
            v(1.0, -1.0, -2.0),
            v(0.0, -1.0, 0.0),
            -0.5,
        ),
        (v(2.0, 0.0, 0.3), v(2.0, 0.0, 0.3), v(1.0, 0.0, 0.0), 0.0),
    ] {
        let p = cyl.project(&x);
        assert_projection(&p, foot, n, gap);
        check_derivatives(&cyl, &x);
    }
    // an oblique axis: the derivatives still match
    let oblique = RigidObstacle::cylinder(v(0.2, -0.1, 0.3), v(1.0, 2.0, -0.5), 0.7).unwrap();
    for x in [v(1.0, 0.0, 1.0), v(-0.4, 0.9, 0.1), v(0.56, -0.28, 0.3)] {
        let p = oblique.project(&x);
        // hand formula: distance to the axis minus the radius
        let a = v(1.0, 2.0, -0.5).normalize();
        let r = x - v(0.2, -0.1, 0.3);
        let d = (r - a * a.dot(&r)).norm();
        assert!((p.gap - (d - 0.7)).abs() < 1e-14);
        let foot = p.point - v(0.2, -0.1, 0.3);
        assert!(((foot - a * a.dot(&foot)).norm() - 0.7).abs() < 1e-14);
        check_derivatives(&oblique, &x);
    }
}

#[test]
fn translated_obstacles_move_rigidly() {
    let d = v(0.3, -1.2, 2.5);
    let x = v(1.1, 0.4, 3.0);
    let surface = unit_square_sheet();
    for obstacle in [
        RigidObstacle::plane(v(0.0, 0.0, 1.0), v(0.0, 1.0, 1.0)).unwrap(),
        RigidObstacle::sphere(v(0.0, 1.0, 0.0), 0.5).unwrap(),
        RigidObstacle::cylinder(v(0.0, 1.0, 0.0), v(1.0, 1.0, 0.0), 0.5).unwrap(),
        RigidObstacle::Triangulated(surface),
    ] {
        let before = obstacle.project(&x);
        let after = obstacle.translated(&d).project(&(x + d));
        assert!((after.point - before.point - d).norm() < 1e-14);
        assert!((after.normal - before.normal).norm() < 1e-14);
        assert!((after.gap - before.gap).abs() < 1e-14);
    }
}

// ---------------------------------------------------------------------------
// closest point on a triangle

/// Independent reference: the interior projection if it is inside,
/// otherwise the nearest of the three clamped segment projections.
fn reference_closest(p: &V3, t: [V3; 3]) -> V3 {
    let [a, b, c] = t;
    let n = (b - a).cross(&(c - a));
    let q = p - n * ((p - a).dot(&n) / n.norm_squared());
    let area = |x: &V3, y: &V3, z: &V3| (y - x).cross(&(z - x)).dot(&n);
    let total = area(&a, &b, &c);
    let bary = [
        area(&q, &b, &c) / total,
        area(&a, &q, &c) / total,
        area(&a, &b, &q) / total,
    ];
    if bary.iter().all(|&l| l >= 0.0) {
        return q;
    }
    let mut best = a;
    for (x, y) in [(a, b), (b, c), (c, a)] {
        let s = ((p - x).dot(&(y - x)) / (y - x).norm_squared()).clamp(0.0, 1.0);
        let candidate = x + (y - x) * s;
        if (p - candidate).norm() < (p - best).norm() {
            best = candidate;
        }
    }
    best
}

/// Smallest distance from `p` to `m(m+1)/2` points sampled uniformly on the
/// triangle (barycentric grid of spacing `1/m`).
fn sampled_distance(p: &V3, t: [V3; 3], m: usize) -> f64 {
    let mut best = f64::INFINITY;
    for i in 0..=m {
        for j in 0..=m - i {
            let (u, w) = (i as f64 / m as f64, j as f64 / m as f64);
            let x = t[0] * (1.0 - u - w) + t[1] * u + t[2] * w;
            best = best.min((p - x).norm());
        }
    }
    best
}

#[test]
fn closest_point_in_each_voronoi_region() {
    // a general triangle in space (not axis aligned, acute)
    let (a, b, c) = (v(0.2, -0.1, 0.4), v(2.1, 0.3, -0.2), v(0.7, 1.9, 0.5));
    let tri = [a, b, c];
    let n = (b - a).cross(&(c - a)).normalize();
    // in-plane outward normals of the edges
    let out = |x: V3, y: V3, opposite: V3| {
        let e = (y - x).normalize();
        let m = n.cross(&e);
        if m.dot(&(opposite - x)) > 0.0 {
            -m
        } else {
            m
        }
    };
    let unit = |x: V3| x.normalize();
    let cases: Vec<(V3, V3, Feature, [f64; 3])> = vec![
        // face
        (
            a * 0.2 + b * 0.3 + c * 0.5 + n * 0.7,
            a * 0.2 + b * 0.3 + c * 0.5,
            Feature::Face,
            [0.2, 0.3, 0.5],
        ),
        // vertices
        (
            a - (unit(b - a) + unit(c - a)) * 0.8 - n * 0.3,
            a,
            Feature::Vertex(0),
            [1.0, 0.0, 0.0],
        ),
        (
            b - (unit(a - b) + unit(c - b)) * 0.5 + n * 1.1,
            b,
            Feature::Vertex(1),
            [0.0, 1.0, 0.0],
        ),
        (
            c - (unit(a - c) + unit(b - c)) * 0.4,
            c,
            Feature::Vertex(2),
            [0.0, 0.0, 1.0],
        ),
        // edges: ab, bc, ca
        (
            a + (b - a) * 0.35 + out(a, b, c) * 0.6 + n * 0.2,
            a + (b - a) * 0.35,
            Feature::Edge(0),
            [0.65, 0.35, 0.0],
        ),
        (
            b + (c - b) * 0.8 + out(b, c, a) * 0.3 - n * 0.9,
            b + (c - b) * 0.8,
            Feature::Edge(1),
            [0.0, 0.2, 0.8],
        ),
        (
            c + (a - c) * 0.1 + out(c, a, b) * 1.5,
            c + (a - c) * 0.1,
            Feature::Edge(2),
            [0.1, 0.0, 0.9],
        ),
    ];
    for (p, expected, feature, bary) in cases {
        let r = closest_point_on_triangle(&p, &a, &b, &c);
        assert_eq!(r.feature, feature, "query {p}");
        assert!(
            (r.point - expected).norm() < 1e-12,
            "{} vs {expected}",
            r.point
        );
        for (got, want) in r.barycentric.iter().zip(&bary) {
            assert!((got - want).abs() < 1e-12, "{:?}", r.barycentric);
        }
        assert!((r.barycentric.iter().sum::<f64>() - 1.0).abs() < 1e-15);
        assert!((reference_closest(&p, tri) - r.point).norm() < 1e-12);
        // dense sampling: nothing sampled is closer, and the sample gets
        // within its grid spacing
        let m = 300;
        let sampled = sampled_distance(&p, tri, m);
        let d = (p - r.point).norm();
        assert!(d <= sampled + 1e-15, "{d} > sampled {sampled}");
        assert!(sampled - d < 3.0 / m as f64);
    }
}

#[test]
fn closest_point_on_random_triangles_matches_reference() {
    let mut rng = StdRng::seed_from_u64(7);
    let mut features = HashMap::new();
    for _ in 0..20_000 {
        let mut r = || {
            v(
                rng.gen_range(-1.0..1.0),
                rng.gen_range(-1.0..1.0),
                rng.gen_range(-1.0..1.0),
            )
        };
        let t = [r(), r(), r()];
        let p = r() * 2.0;
        let q = closest_point_on_triangle(&p, &t[0], &t[1], &t[2]);
        let reference = reference_closest(&p, t);
        // both are projections onto a convex set, so they must agree
        assert!(
            ((p - q.point).norm() - (p - reference).norm()).abs() < 1e-12,
            "distance mismatch for {p} on {t:?}"
        );
        assert!((q.point - reference).norm() < 1e-9);
        let from_bary = t[0] * q.barycentric[0] + t[1] * q.barycentric[1] + t[2] * q.barycentric[2];
        assert!((from_bary - q.point).norm() < 1e-12);
        assert!((q.barycentric.iter().sum::<f64>() - 1.0).abs() < 1e-14);
        assert!(q.barycentric.iter().all(|&l| (0.0..=1.0).contains(&l)));
        *features.entry(q.feature).or_insert(0) += 1;
    }
    // every one of the seven regions was visited
    assert_eq!(features.len(), 7, "{features:?}");
}

// ---------------------------------------------------------------------------
// triangulated surfaces and the search tree

/// A random point at a distance in `[lo, hi)·r` from the origin, uniform in
/// direction.
fn random_point(rng: &mut StdRng, r: f64, lo: f64, hi: f64) -> V3 {
    let dir = loop {
        let d = v(
            rng.gen_range(-1.0..1.0),
            rng.gen_range(-1.0..1.0),
            rng.gen_range(-1.0..1.0),
        );
        if d.norm() > 0.1 && d.norm() <= 1.0 {
            break d.normalize();
        }
    };
    dir * (r * rng.gen_range(lo..hi))
}

#[test]
fn tree_search_equals_brute_force_and_gap_is_within_facetting_error() {
    let r = 1.5;
    let (vertices, triangles) = icosphere(r, 4);
    assert_eq!(triangles.len(), 5120);
    let surface = TriangulatedSurface::new(vertices.clone(), triangles.clone()).unwrap();
    for (t, tri) in triangles.iter().enumerate() {
        let centroid = (vertices[tri[0]] + vertices[tri[1]] + vertices[tri[2]]) / 3.0;
        assert!(
            surface.face_normal(t).dot(&centroid) > 0.0,
            "outward normals"
        );
    }
    // facetting: the facetted sphere lies between the balls of radius
    // r_in = min distance from the centre to a facet plane, and r; so
    // |g_facets − g_sphere| ≤ r − r_in ≈ ρ²/(2r), ρ the facet circumradius
    // (h²/(6r) for an equilateral facet of edge h; h²/(8r) at an edge
    // midpoint)
    let mut r_in = f64::INFINITY;
    let mut h = 0.0f64;
    for (t, tri) in triangles.iter().enumerate() {
        r_in = r_in.min(surface.face_normal(t).dot(&vertices[tri[0]]));
        for i in 0..3 {
            h = h.max((vertices[tri[i]] - vertices[tri[(i + 1) % 3]]).norm());
        }
    }
    let bound = r - r_in;
    assert!(
        bound <= h * h / (6.0 * r) * 1.01,
        "{bound} vs {}",
        h * h / (6.0 * r)
    );

    let mut rng = StdRng::seed_from_u64(2024);
    let mut max_error = 0.0f64;
    let mut max_angle = 0.0f64;
    for q in 0..2000 {
        let x = random_point(&mut rng, r, 0.5, 1.5);
        let (t, p) = surface.closest_point(&x).unwrap();
        let brute = triangles
            .iter()
            .map(|tri| {
                let [a, b, c] = tri.map(|i| vertices[i]);
                (x - closest_point_on_triangle(&x, &a, &b, &c).point).norm()
            })
            .fold(f64::INFINITY, f64::min);
        let d = (x - p.point).norm();
        assert!(
            (d - brute).abs() < 1e-14,
            "query {q}: tree search {d} vs brute force {brute}"
        );
        let tri = triangles[t];
        let direct =
            closest_point_on_triangle(&x, &vertices[tri[0]], &vertices[tri[1]], &vertices[tri[2]]);
        assert_eq!(direct.point, p.point);

        let proj = surface.project(&x);
        let exact = x.norm() - r;
        assert!(proj.gap.signum() == exact.signum() || proj.gap.abs() < bound);
        max_error = max_error.max((proj.gap - exact).abs());
        assert!((proj.gap - (x - proj.point).dot(&proj.normal)).abs() < 1e-14);
        assert!((proj.normal.norm() - 1.0).abs() < 1e-14);
        if (x.norm() - r).abs() > 0.1 * r {
            max_angle = max_angle.max(proj.normal.angle(&x.normalize()));
        }
    }
    assert!(max_error <= bound * (1.0 + 1e-12), "{max_error} > {bound}");
    println!(
        "icosphere r = {r}, 5120 triangles, longest edge h = {h:.5}: \
         max |g − g_sphere| = {max_error:.3e}, bound r − r_in = {bound:.3e}, \
         h²/(8r) = {:.3e}, h²/(6r) = {:.3e}; max normal angle {max_angle:.3e} rad",
        h * h / (8.0 * r),
        h * h / (6.0 * r)
    );
    // the normal is the facet's or the pseudo-normal's: within a facet's
    // angular size (h/r) of the radial direction
    assert!(max_angle < h / r);
}

/// The unit square `[0, 1]² × {0}` as two triangles, normal +z.
fn unit_square_sheet() -> TriangulatedSurface {
    TriangulatedSurface::new(
        vec![
            v(0.0, 0.0, 0.0),
            v(1.0, 0.0, 0.0),
            v(1.0, 1.0, 0.0),
            v(0.0, 1.0, 0.0),
        ],
        vec![[0, 1, 2], [0, 2, 3]],
    )
    .unwrap()
}

#[test]
fn triangulated_curvature_matches_finite_differences_off_faces() {
    let obstacle = RigidObstacle::Triangulated(unit_square_sheet());
    // beyond an edge (above and below the sheet), beyond a vertex, over the face
    for x in [
        v(1.3, 0.5, 0.4),
        v(0.4, -0.3, -0.2),
        v(-0.5, -0.4, 0.3),
        v(1.2, 1.5, -0.7),
        v(0.3, 0.6, 0.2),
    ] {
        check_derivatives(&obstacle, &x);
    }
    // the normal turns continuously around the edge x = 1: above the face
    // it is +z, beyond the edge it tilts toward +x
    let n_face = obstacle.project(&v(0.999, 0.5, 0.1)).normal;
    let n_edge = obstacle.project(&v(1.001, 0.5, 0.1)).normal;
    assert!((n_face - n_edge).norm() < 0.011);
}

#[test]
fn closed_box_surface_gives_the_signed_distance() {
    // all six sides of a Tet4 box mesh as one closed surface set
    let (l, c) = ([2.0, 1.0, 1.5], [2, 2, 3]);
    let mut mesh = box_mesh(ElementKind::Tet4, c, l);
    let all: Vec<Facet> = mesh
        .surfaces
        .iter()
        .flat_map(|s| s.facets.clone())
        .collect();
    mesh.surfaces.push(SurfaceSet {
        name: "all".into(),
        facets: all,
    });
    let surface = TriangulatedSurface::from_surface_facets(&mesh, "all").unwrap();
    let obstacle = RigidObstacle::Triangulated(surface);
    let half = V3::from(l) / 2.0;
    let mut rng = StdRng::seed_from_u64(5);
    for _ in 0..500 {
        let x = v(
            rng.gen_range(-1.0..3.0),
            rng.gen_range(-1.0..2.0),
            rng.gen_range(-1.0..2.5),
        );
        // signed distance to the box [0, l]
        let q = (x - half).abs() - half;
        let exact = if q.max() > 0.0 {
            q.sup(&V3::zeros()).norm()
        } else {
            q.max()
        };
        let p = obstacle.project(&x);
        assert!((p.gap - exact).abs() < 1e-13, "{x}: {} vs {exact}", p.gap);
    }
}

// ---------------------------------------------------------------------------
// readers

#[test]
fn stl_ascii_and_binary_give_the_same_tetrahedron() {
    let ascii = TriangulatedSurface::from_stl(&data("tetrahedron_ascii.stl")).unwrap();
    let binary = TriangulatedSurface::from_stl(&data("tetrahedron_binary.stl")).unwrap();
    let corners = |s: &TriangulatedSurface| -> Vec<[V3; 3]> {
        s.triangles()
            .iter()
            .map(|t| t.map(|i| s.vertices()[i]))
            .collect()
    };
    assert_eq!(ascii.triangles().len(), 4);
    assert_eq!(ascii.vertices().len(), 4);
    assert_eq!(corners(&ascii), corners(&binary));
    // gaps against the unit right tetrahedron: outside beyond the slanted
    // face, inside (nearest faces x = y = z = 0 at 0.1), below a vertex
    for s in [&ascii, &binary] {
        let g = |x: V3| s.project(&x).gap;
        assert!((g(v(1.0, 1.0, 1.0)) - 2.0 / 3f64.sqrt()).abs() < 1e-14);
        assert!((g(v(0.1, 0.1, 0.1)) + 0.1).abs() < 1e-14);
        assert!((g(v(0.2, 0.3, -0.4)) - 0.4).abs() < 1e-14);
        assert!((g(v(-1.0, -2.0, -2.0)) - 3.0).abs() < 1e-14);
    }
}

#[test]
fn corrupt_or_missing_stl_errors_name_the_file() {
    let dir = tempfile::tempdir().unwrap();
    // a binary STL cut short: the header promises 4 triangles
    let bytes = std::fs::read(data("tetrahedron_binary.stl")).unwrap();
    let truncated = dir.path().join("truncated.stl");
    std::fs::write(&truncated, &bytes[..84 + 60]).unwrap();
    // ASCII that breaks off in the middle of a facet
    let broken = dir.path().join("broken_ascii.stl");
    std::fs::write(
        &broken,
        "solid x\n facet normal 0 0 1\n outer loop\n vertex 0 0 0\n vertex 1 zero 0\n",
    )
    .unwrap();
    for path in [&truncated, &broken] {
        let e = TriangulatedSurface::from_stl(path).unwrap_err();
        assert!(matches!(e, Error::ContactInput { .. }), "{e:?}");
        assert!(e.to_string().contains(&path.display().to_string()), "{e}");
    }
    let missing = dir.path().join("missing.stl");
    let e = TriangulatedSurface::from_stl(&missing).unwrap_err();
    assert!(e.to_string().contains("missing.stl"), "{e}");
}

#[test]
fn gmsh_surface_sets_as_obstacles() {
    // the top (z = 1) of the unit cube, Tri3 and Quad4 facets
    for name in ["cube_tet_41_ascii.msh", "cube_hex_41_bin.msh"] {
        let mesh = signorini::mesh::gmsh::read_msh(&data(name)).unwrap();
        let top = TriangulatedSurface::from_surface_facets(&mesh, "top").unwrap();
        let p = top.project(&v(0.3, 0.4, 1.2));
        assert_projection(&p, v(0.3, 0.4, 1.0), V3::z(), 0.2);
        let p = top.project(&v(0.7, 0.1, 0.9));
        assert!((p.gap + 0.1).abs() < 1e-14);
        let area: f64 = top
            .triangles()
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| top.vertices()[i]);
                (b - a).cross(&(c - a)).norm() / 2.0
            })
            .sum();
        assert!((area - 1.0).abs() < 1e-12, "{name}: area {area}");
        let e = TriangulatedSurface::from_surface_facets(&mesh, "lid").unwrap_err();
        assert!(matches!(e, Error::UnknownGroup { .. }));
        assert!(e.to_string().contains("top"), "{e}");
    }
}

// ---------------------------------------------------------------------------
// tributary areas

#[test]
fn tributary_areas_sum_to_the_surface_area() {
    let l = [2.0, 3.0, 1.5];
    for kind in [ElementKind::Tet4, ElementKind::Hex8] {
        let mesh = box_mesh(kind, [3, 4, 2], l);
        for (name, area) in [
            ("xmin", l[1] * l[2]),
            ("xmax", l[1] * l[2]),
            ("ymin", l[0] * l[2]),
            ("zmax", l[0] * l[1]),
        ] {
            let set = mesh.surface(name).unwrap();
            let (nodes, areas) = tributary_areas(&mesh, set);
            assert_eq!(nodes, mesh.surface_nodes(set));
            let sum: f64 = areas.iter().sum();
            assert!((sum - area).abs() < 1e-13 * area, "{kind:?} {name}: {sum}");
            assert!(areas.iter().all(|&a| a > 0.0));
        }
    }
}

/// Consistent nodal loads of a uniform pressure, assembled over a surface
/// set, as `node → force`.
fn consistent_loads(mesh: &Mesh, set: &SurfaceSet, p: f64) -> HashMap<usize, V3> {
    let mut loads: HashMap<usize, V3> = HashMap::new();
    for f in &set.facets {
        let coords: Vec<[f64; 3]> = f.nodes.iter().map(|&n| mesh.nodes[n]).collect();
        let (force, _) = pressure_facet(f.kind, &coords, p, false);
        for (a, &n) in f.nodes.iter().enumerate() {
            *loads.entry(n).or_insert_with(V3::zeros) +=
                v(force[3 * a], force[3 * a + 1], force[3 * a + 2]);
        }
    }
    loads
}

#[test]
fn uniform_pressure_times_tributary_areas_equals_consistent_loads() {
    let p = 2.5;
    for kind in [ElementKind::Tet4, ElementKind::Hex8] {
        let mesh = box_mesh(kind, [3, 4, 2], [2.0, 3.0, 1.5]);
        let set = mesh.surface("zmax").unwrap();
        let (nodes, areas) = tributary_areas(&mesh, set);
        let loads = consistent_loads(&mesh, set, p);
        for (n, a) in nodes.iter().zip(&areas) {
            // pressure pushes into the body: −p A_s n with n = +z
            let expected = v(0.0, 0.0, -p * a);
            assert!((loads[n] - expected).norm() < 1e-13, "{kind:?} node {n}");
        }
    }
}

#[test]
fn quarter_rule_on_a_trapezoid_keeps_the_total_but_not_the_nodal_split() {
    // a flat trapezoid, parallel sides 4 (bottom) and 2 (top), height 2
    let coords = [
        [0.0, 0.0, 0.0],
        [4.0, 0.0, 0.0],
        [3.0, 2.0, 0.0],
        [1.0, 2.0, 0.0],
    ];
    let mesh = Mesh {
        nodes: coords.to_vec(),
        node_ids: vec![1, 2, 3, 4],
        surfaces: vec![SurfaceSet {
            name: "s".into(),
            facets: vec![Facet {
                kind: FacetKind::Quad4,
                nodes: vec![0, 1, 2, 3],
                id: 1,
            }],
        }],
        ..Mesh::default()
    };
    let set = &mesh.surfaces[0];
    let (_, areas) = tributary_areas(&mesh, set);
    assert_eq!(facet_area(FacetKind::Quad4, &coords), 6.0);
    assert!(areas.iter().all(|&a| (a - 1.5).abs() < 1e-14));
    let loads = consistent_loads(&mesh, set, 1.0);
    let total: f64 = loads.values().map(|f| f[2]).sum();
    assert!((total + 6.0).abs() < 1e-13);
    // the bilinear element loads the long side more: ∫N_a dA = 5/3, 4/3
    assert!((loads[&0][2] + 5.0 / 3.0).abs() < 1e-13);
    assert!((loads[&3][2] + 4.0 / 3.0).abs() < 1e-13);
}
