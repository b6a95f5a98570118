//! Finite-difference twins of the segmentation's directional derivatives
//! (Popp, Gitterle, Gee & Wall 2010, §5): the auxiliary plane, the clip
//! polygon's vertices (kept corners and edge–edge intersections), the
//! Gauss points' plane and parameter coordinates on both faces, the cell
//! Jacobian, and a pair's `D_j` and `M_jl`, on warped and curved faces of
//! every shape pairing that overlap partly. Central differences with
//! `h = 1e-6` (truncation O(h²) ≈ 1e-12, round-off ≈ 1e-16/h = 1e-10); the
//! derivatives agree to 1e-6 relative.

mod mortar_common;

use mortar_common::{curved_face, increments, shifted, v, SHAPES};
use nalgebra::{Rotation3, Vector3};
use signorini::contact::mortar::auxiliary_plane::AuxiliaryPlane;
use signorini::contact::mortar::clipping::VertexOrigin;
use signorini::contact::mortar::pair_linearisation::linearise_pair;
use signorini::contact::mortar::segment::{cell_points, point_jacobians};
use signorini::contact::mortar::segment_derivatives::{
    cell_point_derivatives, integrals_derivative,
};
use signorini::contact::mortar::{integrate_pair, overlap, DualBasis, FaceShape, MortarFace};

const H: f64 = 1e-6;
const TOLERANCE: f64 = 1e-6;

/// A primary face of `shape` that partly overlaps the secondary
/// [`curved_face`]: the curved face mirrored (so its normal faces the
/// secondary one), turned 25° about the vertical, shifted by
/// `(0.5, 0.6)` and lifted by 0.1, so the clip polygon has intersection
/// vertices.
fn primary_face(shape: FaceShape) -> MortarFace {
    let turn = Rotation3::from_axis_angle(&Vector3::z_axis(), 25f64.to_radians());
    let xs = curved_face(shape)
        .coordinates
        .iter()
        .map(|x| turn * v(x.x, -x.y, -0.5 * x.z) + v(0.5, 0.6, 0.1))
        .collect();
    MortarFace::new(shape, xs).unwrap()
}

/// A secondary and a primary face with their nodes' increments.
struct Pair {
    s: MortarFace,
    p: MortarFace,
    dxs: Vec<Vector3<f64>>,
    dxm: Vec<Vector3<f64>>,
}

/// Every shape pairing.
fn pairs() -> Vec<Pair> {
    let mut out = Vec::new();
    for (i, s) in SHAPES.iter().enumerate() {
        for (k, p) in SHAPES.iter().enumerate() {
            let seed = 10.0 * i as f64 + k as f64;
            out.push(Pair {
                s: curved_face(*s),
                p: primary_face(*p),
                dxs: increments(s.node_count(), seed),
                dxm: increments(p.node_count(), seed + 0.5),
            });
        }
    }
    out
}

/// The faces moved by `h` along the increments.
fn moved(
    s: &MortarFace,
    p: &MortarFace,
    dxs: &[Vector3<f64>],
    dxm: &[Vector3<f64>],
    h: f64,
) -> (MortarFace, MortarFace) {
    (
        MortarFace::new(s.shape, shifted(&s.coordinates, dxs, h)).unwrap(),
        MortarFace::new(p.shape, shifted(&p.coordinates, dxm, h)).unwrap(),
    )
}

/// `|fd − exact| ≤ TOLERANCE · max(|exact|, 1)` over flattened values.
fn assert_close(what: &str, fd: &[f64], exact: &[f64]) {
    assert_eq!(fd.len(), exact.len(), "{what}: lengths");
    let error: f64 = fd
        .iter()
        .zip(exact)
        .map(|(a, b)| (a - b).powi(2))
        .sum::<f64>()
        .sqrt();
    let scale: f64 = exact.iter().map(|a| a * a).sum::<f64>().sqrt();
    eprintln!(
        "{what}: |fd − exact| / max(|exact|, 1) = {:.1e}",
        error / scale.max(1.0)
    );
    assert!(
        error <= TOLERANCE * scale.max(1.0),
        "{what}: |fd − exact| = {error:e} (|exact| = {scale:e})\nfd    {fd:?}\nexact {exact:?}"
    );
}

fn flat3(xs: &[Vector3<f64>]) -> Vec<f64> {
    xs.iter().flat_map(|x| x.iter().copied()).collect()
}

fn flat2(xs: &[[f64; 2]]) -> Vec<f64> {
    xs.iter().flat_map(|x| x.iter().copied()).collect()
}

#[test]
fn auxiliary_plane_derivative_matches_central_differences() {
    for shape in SHAPES {
        let face = curved_face(shape);
        let dx = increments(shape.node_count(), 2.5);
        let plane = AuxiliaryPlane::of_face(&face);
        let d = plane.derivative(&face, &dx);
        let at = |h: f64| {
            AuxiliaryPlane::of_face(
                &MortarFace::new(shape, shifted(&face.coordinates, &dx, h)).unwrap(),
            )
        };
        let (p, m) = (at(H), at(-H));
        let fd = |a: Vector3<f64>, b: Vector3<f64>| (a - b) / (2.0 * H);
        let fd_all = [
            fd(p.centre, m.centre),
            fd(p.normal, m.normal),
            fd(p.frame[0], m.frame[0]),
            fd(p.frame[1], m.frame[1]),
        ];
        let exact = [d.centre, d.normal, d.frame[0], d.frame[1]];
        assert_close(&format!("{shape:?} plane"), &flat3(&fd_all), &flat3(&exact));
        assert!(d.normal.norm() > 1e-2, "{shape:?}: a non-trivial δn₀");
        // a point moving with the plane's derivative: its local coordinates
        let x = v(0.4, 0.7, 0.3);
        let dxp = v(0.2, -0.1, 0.3);
        let exact = plane.local_point_derivative(&d, &x, &dxp);
        let (lp, lm) = (p.local_point(&(x + dxp * H)), m.local_point(&(x - dxp * H)));
        let fd = [0, 1].map(|i| (lp[i] - lm[i]) / (2.0 * H));
        assert_close(&format!("{shape:?} local point"), &fd, &exact);
    }
}

#[test]
fn clip_polygon_derivative_matches_central_differences() {
    for Pair { s, p, dxs, dxm } in pairs() {
        let o = overlap(&s, &p);
        let what = format!("{:?}–{:?}", s.shape, p.shape);
        let intersections = o
            .trace
            .polygon
            .iter()
            .filter(|&&i| matches!(o.trace.origins[i], VertexOrigin::Intersection { .. }))
            .count();
        assert!(
            intersections >= 2,
            "{what}: a partial overlap ({intersections} intersections)"
        );
        let secondary_area =
            signorini::contact::mortar::clipping::signed_area(&o.secondary_polygon);
        assert!(
            o.area() > 0.05 && o.area() < 0.9 * secondary_area,
            "{what}: a partial overlap (area {} of {secondary_area})",
            o.area()
        );
        let d = o.derivative(&s, &p, &dxs, &dxm);
        let (sp, pp) = moved(&s, &p, &dxs, &dxm, H);
        let (sm, pm) = moved(&s, &p, &dxs, &dxm, -H);
        let (plus, minus) = (overlap(&sp, &pp).polygon, overlap(&sm, &pm).polygon);
        assert_eq!(
            plus.len(),
            o.polygon.len(),
            "{what}: the same polygon under ±h"
        );
        let fd: Vec<[f64; 2]> = plus
            .iter()
            .zip(&minus)
            .map(|(a, b)| [0, 1].map(|i| (a[i] - b[i]) / (2.0 * H)))
            .collect();
        assert_close(&format!("{what} polygon"), &flat2(&fd), &flat2(&d.polygon));
    }
}

#[test]
fn gauss_point_derivatives_match_central_differences() {
    for Pair { s, p, dxs, dxm } in pairs() {
        let what = format!("{:?}–{:?}", s.shape, p.shape);
        let o = overlap(&s, &p);
        let points = cell_points(&o, &s, &p).unwrap();
        let jacobians = point_jacobians(&o, &points, &s, &p).unwrap();
        let d_overlap = o.derivative(&s, &p, &dxs, &dxm);
        let linearised = (points.as_slice(), jacobians.as_slice());
        let d = cell_point_derivatives(&o, &d_overlap, linearised, (&s, &p), (&dxs, &dxm)).unwrap();
        let at = |h: f64| {
            let (sh, ph) = moved(&s, &p, &dxs, &dxm, h);
            cell_points(&overlap(&sh, &ph), &sh, &ph).unwrap()
        };
        let (plus, minus) = (at(H), at(-H));
        assert_eq!(plus.len(), points.len(), "{what}: the same cells under ±h");
        let fd =
            |f: &dyn Fn(&signorini::contact::mortar::segment::CellPoint) -> Vec<f64>| -> Vec<f64> {
                plus.iter()
                    .zip(&minus)
                    .flat_map(|(a, b)| {
                        f(a).into_iter()
                            .zip(f(b))
                            .map(|(x, y)| (x - y) / (2.0 * H))
                            .collect::<Vec<_>>()
                    })
                    .collect()
            };
        let exact = |f: &dyn Fn(
            &signorini::contact::mortar::segment_derivatives::CellPointDerivative,
        ) -> Vec<f64>|
         -> Vec<f64> { d.iter().flat_map(f).collect() };
        assert_close(
            &format!("{what} plane point"),
            &fd(&|q| q.plane_point.to_vec()),
            &exact(&|q| q.plane_point.to_vec()),
        );
        assert_close(
            &format!("{what} ξ_s"),
            &fd(&|q| q.secondary.xi.to_vec()),
            &exact(&|q| q.secondary_xi.to_vec()),
        );
        assert_close(
            &format!("{what} ξ_m"),
            &fd(&|q| q.primary.xi.to_vec()),
            &exact(&|q| q.primary_xi.to_vec()),
        );
        assert_close(
            &format!("{what} J"),
            &fd(&|q| vec![q.jacobian]),
            &exact(&|q| vec![q.jacobian]),
        );
    }
}

#[test]
fn mortar_integral_derivatives_match_central_differences() {
    for Pair { s, p, dxs, dxm } in pairs() {
        let what = format!("{:?}–{:?}", s.shape, p.shape);
        let dual = DualBasis::of_face(&s).unwrap();
        let o = overlap(&s, &p);
        let points = cell_points(&o, &s, &p).unwrap();
        let jacobians = point_jacobians(&o, &points, &s, &p).unwrap();
        let linearised = (points.as_slice(), jacobians.as_slice());
        let (dd, dm) = integrals_derivative(&o, linearised, (&s, &dual, &p), (&dxs, &dxm)).unwrap();
        let at = |h: f64| {
            let (sh, ph) = moved(&s, &p, &dxs, &dxm, h);
            integrate_pair(&sh, &DualBasis::of_face(&sh).unwrap(), &ph)
                .unwrap()
                .unwrap()
        };
        let (plus, minus) = (at(H), at(-H));
        let fd_d: Vec<f64> = plus
            .d
            .iter()
            .zip(&minus.d)
            .map(|(a, b)| (a - b) / (2.0 * H))
            .collect();
        let fd_m = (&plus.m - &minus.m) / (2.0 * H);
        assert_close(&format!("{what} D"), &fd_d, &dd);
        assert_close(&format!("{what} M"), fd_m.as_slice(), dm.as_slice());
        // the assembled gradient applied to the increments is the same
        let lin = linearise_pair(&s, &dual, &p).unwrap().unwrap();
        let direction = nalgebra::DVector::from_vec(flat3(&[dxs.clone(), dxm.clone()].concat()));
        let by_gradient = &lin.d_gradient * &direction;
        assert_close(&format!("{what} ∇D·δx"), by_gradient.as_slice(), &dd);
        let by_gradient = &lin.m_gradient * &direction;
        let dm_rows: Vec<f64> = (0..dm.nrows())
            .flat_map(|j| (0..dm.ncols()).map(move |l| (j, l)))
            .map(|(j, l)| dm[(j, l)])
            .collect();
        assert_close(&format!("{what} ∇M·δx"), by_gradient.as_slice(), &dm_rows);
        assert!(dm.norm() > 1e-3, "{what}: a non-trivial δM");
    }
}
