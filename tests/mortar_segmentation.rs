//! Segmentation of a secondary–primary face pair in the secondary face's
//! auxiliary plane (Puso & Laursen 2004; Popp, Gitterle, Gee & Wall 2010):
//! overlap areas known in closed form, a primary tiling of a secondary face
//! whose clip areas sum to the face's projected area, and the Newton
//! projection of points back onto curved faces.

mod mortar_common;

use mortar_common::{grid, hash_unit, linspace};
use nalgebra::Vector3;
use signorini::contact::mortar::clipping;
use signorini::contact::mortar::projection::project_along;
use signorini::contact::mortar::{integrate_pair, overlap, DualBasis, FaceShape, MortarFace};

fn v(x: f64, y: f64, z: f64) -> Vector3<f64> {
    Vector3::new(x, y, z)
}

fn face(shape: FaceShape, xs: &[[f64; 3]]) -> MortarFace {
    MortarFace::new(shape, xs.iter().map(|p| v(p[0], p[1], p[2])).collect()).unwrap()
}

#[test]
fn overlap_of_two_offset_squares() {
    // [0,1]² against [0.5,1.5]×[0.25,1.25] (facing down, 0.2 above): 0.375.
    let s = face(
        FaceShape::Quad4,
        &[
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ],
    );
    let p = face(
        FaceShape::Quad4,
        &[
            [0.5, 0.25, 0.2],
            [0.5, 1.25, 0.2],
            [1.5, 1.25, 0.2],
            [1.5, 0.25, 0.2],
        ],
    );
    let o = overlap(&s, &p);
    assert!((o.area() - 0.375).abs() < 1e-15, "{}", o.area());
    let seg = integrate_pair(&s, &DualBasis::of_face(&s).unwrap(), &p)
        .unwrap()
        .unwrap();
    assert!((seg.area - 0.375).abs() < 1e-14, "{}", seg.area);
}

#[test]
fn overlap_of_a_triangle_and_a_square() {
    // [0,2]² against the triangle (1,0.5), (2.5,0.5), (1,2): the part with
    // x ≤ 2 has area ∫₁² (2.5 − x) dx = 1.
    let s = face(
        FaceShape::Quad4,
        &[
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [2.0, 2.0, 0.0],
            [0.0, 2.0, 0.0],
        ],
    );
    let p = face(
        FaceShape::Tri3,
        &[[1.0, 0.5, -0.1], [1.0, 2.0, -0.1], [2.5, 0.5, -0.1]],
    );
    assert!((overlap(&s, &p).area() - 1.0).abs() < 1e-15);
    // on a tilted pair (both faces rotated and the primary lifted along n₀)
    let rotate = |x: [f64; 3]| [0.8 * x[0] - 0.6 * x[2], x[1], 0.6 * x[0] + 0.8 * x[2]];
    let tilt = |f: &MortarFace| {
        let xs: Vec<[f64; 3]> = f
            .coordinates
            .iter()
            .map(|x| rotate([x.x, x.y, x.z]))
            .collect();
        face(f.shape, &xs)
    };
    assert!((overlap(&tilt(&s), &tilt(&p)).area() - 1.0).abs() < 1e-14);
}

#[test]
fn disjoint_and_edge_touching_faces_do_not_overlap() {
    let s = face(
        FaceShape::Tri3,
        &[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
    );
    let far = face(
        FaceShape::Tri3,
        &[[2.0, 2.0, 0.1], [2.0, 3.0, 0.1], [3.0, 2.0, 0.1]],
    );
    let touching = face(
        FaceShape::Tri3,
        &[[1.0, 0.0, 0.1], [0.0, 1.0, 0.1], [1.0, 1.0, 0.1]],
    );
    let dual = DualBasis::of_face(&s).unwrap();
    for p in [far, touching] {
        assert!(overlap(&s, &p).polygon.is_empty());
        assert!(integrate_pair(&s, &dual, &p).unwrap().is_none());
    }
}

#[test]
fn a_primary_tiling_covers_the_secondary_face_exactly() {
    // A warped secondary Quad4 under a perturbed Tri3 tiling of a larger
    // square: the clip areas sum to the secondary face's projected area
    // (the signed area of its projected corners) to round-off.
    let s = face(
        FaceShape::Quad4,
        &[
            [0.1, 0.05, 0.0],
            [0.93, 0.12, 0.04],
            [0.88, 0.81, -0.03],
            [0.07, 0.95, 0.02],
        ],
    );
    let mut coords = Vec::new();
    let perturb = |x: f64, y: f64| [0.03 * hash_unit(x + 3.0 * y), 0.03 * hash_unit(2.0 * x - y)];
    let tiles = grid(
        &linspace(-0.2, 1.2, 7),
        &linspace(-0.1, 1.1, 6),
        0.3,
        FaceShape::Tri3,
        true,
        &perturb,
        &mut coords,
    );
    let projected = {
        let o = overlap(&s, &s);
        clipping::signed_area(&o.polygon)
    };
    let total: f64 = tiles
        .iter()
        .map(|t| overlap(&s, &t.with_coordinates(&coords).unwrap()).area())
        .sum();
    assert!((total - projected).abs() < 1e-14, "{total} vs {projected}");
    assert!(projected > 0.6, "{projected}");
}

#[test]
fn gauss_points_project_onto_curved_faces() {
    // A Quad8 face with bulging mid-side nodes: the projection along a
    // direction lands on x(ξ) = X + α d to 1e-13.
    let mut xs = vec![
        [0.0, 0.0, 0.0],
        [2.0, 0.0, 0.1],
        [2.0, 2.0, 0.0],
        [0.0, 2.0, -0.1],
    ];
    xs.extend([
        [1.0, -0.1, 0.3],
        [2.1, 1.0, 0.2],
        [1.0, 2.1, 0.25],
        [-0.1, 1.0, 0.15],
    ]);
    let f = face(FaceShape::Quad8, &xs);
    let d = v(0.1, -0.05, 1.0).normalize();
    for x in [v(0.5, 0.5, -1.0), v(1.7, 0.3, 2.0), v(1.0, 1.9, 0.0)] {
        let hit = project_along(&f, &x, &d).unwrap();
        let error = (f.point(hit.xi) - x - d * hit.distance).norm();
        assert!(error < 1e-13, "{x:?}: {error}");
        assert!(FaceShape::Quad8.contains(hit.xi, 1e-12), "{:?}", hit.xi);
    }
    // a direction in the plane of a flat face has no projection
    let flat = face(
        FaceShape::Tri3,
        &[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
    );
    assert!(project_along(&flat, &v(0.2, 0.2, 0.0), &v(1.0, 0.0, 0.0)).is_err());
}

/// Whether `p` is inside the counter-clockwise convex `polygon` to `tol`.
fn inside_polygon(p: [f64; 2], polygon: &[[f64; 2]], tol: f64) -> bool {
    let n = polygon.len();
    (0..n).all(|i| clipping::cross(polygon[i], polygon[(i + 1) % n], p) >= -tol)
}

/// Coincident and parallel edges (matching meshes: every primary vertex
/// over a secondary one, the edges on each other's lines up to round-off
/// or a small offset). An edge running along a clip edge inside the
/// tolerance band (distances −0.9e-12 and −1.1e-12 from its line) once
/// made an intersection at `t = −4.5`, a vertex 2.7 off the faces, which
/// the next edge cut back to the clip's corner (0, 0), 0.2 off the
/// subject: the area stayed right (the spike along the line has none), but
/// a cell's integration points left the primary face. The subject is
/// inside the clip to 1e-12: the overlap is the subject, its area to 1e-11
/// and every vertex in it to 1e-10. Then
/// triangles and squares whose corners are the clip's moved by `ε ×`
/// (hash in [−1, 1]) for ε from 0 to 1e-6: every overlap vertex lies in
/// both polygons to 1e-10 and the area is at most the smaller one's (plus
/// the tolerance band along the perimeter, `2e-12 ×` its length) and
/// at least the larger one's minus the area swept by the moves (`4 ε` ×
/// the perimeter), so no sliver or wild vertex enters.
#[test]
fn coincident_and_parallel_edges_clip_robustly() {
    let clip = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
    let subject = [[0.2, -0.9e-12], [0.8, -1.1e-12], [0.5, 0.4]];
    let overlap = clipping::clip_convex(&subject, &clip);
    let area = clipping::signed_area(&overlap);
    assert!((area - 0.12).abs() < 1e-11, "overlap {area}");
    for p in &overlap {
        assert!(inside_polygon(*p, &subject, 1e-10), "{overlap:?}");
    }
    let shapes: [&[[f64; 2]]; 2] = [
        &[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]],
        &[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
    ];
    let mut seed = 0.0;
    for clip in shapes {
        let perimeter: f64 = (0..clip.len())
            .map(|i| {
                let (a, b) = (clip[i], clip[(i + 1) % clip.len()]);
                ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt()
            })
            .sum();
        for eps in [0.0, 1e-16, 1e-14, 5e-13, 1e-12, 2e-12, 1e-10, 1e-8, 1e-6] {
            for _ in 0..50 {
                let subject: Vec<[f64; 2]> = clip
                    .iter()
                    .map(|p| {
                        seed += 1.0;
                        [
                            p[0] + eps * hash_unit(seed),
                            p[1] + eps * hash_unit(seed + 0.5),
                        ]
                    })
                    .collect();
                let overlap = clipping::clip_convex(&subject, clip);
                let area = clipping::signed_area(&overlap);
                let (a_s, a_c) = (clipping::signed_area(&subject), clipping::signed_area(clip));
                let label = format!("ε = {eps:e}, subject {subject:?}: overlap {overlap:?}");
                // a vertex within the tolerance band counts as inside
                let band = 2.0 * clipping::TOLERANCE * perimeter;
                assert!(area <= a_s.min(a_c) + band, "{label}");
                assert!(
                    area >= a_s.max(a_c) - 4.0 * eps * perimeter - 1e-12,
                    "{label}"
                );
                for p in &overlap {
                    assert!(inside_polygon(*p, clip, 1e-10), "{label}");
                    assert!(inside_polygon(*p, &subject, 1e-10), "{label}");
                }
            }
        }
    }
}
