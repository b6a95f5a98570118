//! The closest point on a triangle `(a, b, c)` to a point `p`.
//!
//! The plane of the triangle is split into seven Voronoi regions: three
//! vertex regions, three edge regions and the face (Ericson, *Real-Time
//! Collision Detection*, §5.1.5). With `ab = b − a`, `ac = c − a` and
//!
//! ```text
//! d1 = ab·(p − a)   d2 = ac·(p − a)
//! d3 = ab·(p − b)   d4 = ac·(p − b)
//! d5 = ab·(p − c)   d6 = ac·(p − c)
//! vc = d1 d4 − d3 d2,   vb = d5 d2 − d1 d6,   va = d3 d6 − d5 d4
//! ```
//!
//! the regions are tested in turn: vertex `a` (`d1 ≤ 0, d2 ≤ 0`), vertex `b`
//! (`d3 ≥ 0, d4 ≤ d3`), edge `ab` (`vc ≤ 0, d1 ≥ 0, d3 ≤ 0`, parameter
//! `t = d1/(d1 − d3) = d1/|ab|²`), vertex `c` (`d6 ≥ 0, d5 ≤ d6`), edge `ca`
//! (`vb ≤ 0, d2 ≥ 0, d6 ≤ 0`, `t = d2/(d2 − d6) = d2/|ac|²`), edge `bc`
//! (`va ≤ 0, d4 ≥ d3, d5 ≥ d6`, `t = (d4 − d3)/|bc|²`), else the face with
//! barycentrics `(va, vb, vc)/(va + vb + vc)`, where `va + vb + vc = |ab × ac|²`.
//!
//! Every denominator is a squared edge length or the squared doubled area.
//! A triangle whose area is zero to round-off (collinear or coincident
//! vertices) has no face region: it is treated as its three edges, so
//! nothing divides by zero.

use nalgebra::Vector3;

/// Where on the triangle the closest point lies. Vertices are numbered
/// `0, 1, 2` for `a, b, c`; edge `i` joins vertex `i` to vertex `(i + 1) % 3`
/// (`Edge(0)` = ab, `Edge(1)` = bc, `Edge(2)` = ca).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Feature {
    /// The interior of the triangle.
    Face,
    /// The interior of edge `i`.
    Edge(usize),
    /// Vertex `i`.
    Vertex(usize),
}

/// The closest point on a triangle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TriangleProjection {
    /// The closest point `x̄ = λ₀ a + λ₁ b + λ₂ c`.
    pub point: Vector3<f64>,
    /// Barycentric coordinates `(λ₀, λ₁, λ₂)`, each in `[0, 1]`, summing to 1.
    pub barycentric: [f64; 3],
    /// The Voronoi feature `point` lies on.
    pub feature: Feature,
}

/// The closest point on triangle `(a, b, c)` to `p` (see the module
/// documentation for the region classification). Never divides by zero,
/// whatever the triangle.
pub fn closest_point_on_triangle(
    p: &Vector3<f64>,
    a: &Vector3<f64>,
    b: &Vector3<f64>,
    c: &Vector3<f64>,
) -> TriangleProjection {
    let ab = b - a;
    let ac = c - a;
    let bc = c - b;
    let scale = ab
        .norm_squared()
        .max(ac.norm_squared())
        .max(bc.norm_squared());
    let area2 = ab.cross(&ac).norm_squared();
    // |ab × ac|² relative to the longest edge to the fourth: zero-area
    // triangles (to round-off) have no face region.
    if !(area2 > 1e-24 * scale * scale) {
        return closest_point_on_degenerate_triangle(p, [a, b, c]);
    }

    let vertex = |i: usize, x: &Vector3<f64>| {
        let mut barycentric = [0.0; 3];
        barycentric[i] = 1.0;
        TriangleProjection {
            point: *x,
            barycentric,
            feature: Feature::Vertex(i),
        }
    };
    // the point at parameter t on edge i from vertex i to vertex i + 1
    let edge = |i: usize, t: f64, from: &Vector3<f64>, to: &Vector3<f64>| {
        let mut barycentric = [0.0; 3];
        barycentric[i] = 1.0 - t;
        barycentric[(i + 1) % 3] = t;
        TriangleProjection {
            point: from + (to - from) * t,
            barycentric,
            feature: Feature::Edge(i),
        }
    };

    let ap = p - a;
    let d1 = ab.dot(&ap);
    let d2 = ac.dot(&ap);
    if d1 <= 0.0 && d2 <= 0.0 {
        return vertex(0, a);
    }
    let bp = p - b;
    let d3 = ab.dot(&bp);
    let d4 = ac.dot(&bp);
    if d3 >= 0.0 && d4 <= d3 {
        return vertex(1, b);
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        // d1 − d3 = |ab|² > 0
        return edge(0, d1 / (d1 - d3), a, b);
    }
    let cp = p - c;
    let d5 = ab.dot(&cp);
    let d6 = ac.dot(&cp);
    if d6 >= 0.0 && d5 <= d6 {
        return vertex(2, c);
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        // edge ca, parameter from c: 1 − d2/|ac|²; d2 − d6 = |ac|² > 0
        let t = d2 / (d2 - d6);
        return edge(2, 1.0 - t, c, a);
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 {
        // (d4 − d3) + (d5 − d6) = |bc|² > 0
        return edge(1, (d4 - d3) / ((d4 - d3) + (d5 - d6)), b, c);
    }
    let denom = va + vb + vc; // = |ab × ac|² > 0 up to round-off
    let (v, w) = (vb / denom, vc / denom);
    TriangleProjection {
        point: a + ab * v + ac * w,
        barycentric: [1.0 - v - w, v, w],
        feature: Feature::Face,
    }
}

/// The closest point on a zero-area triangle: the best of its three edges
/// (each edge may itself have zero length).
fn closest_point_on_degenerate_triangle(
    p: &Vector3<f64>,
    v: [&Vector3<f64>; 3],
) -> TriangleProjection {
    let mut best: Option<(f64, TriangleProjection)> = None;
    for i in 0..3 {
        let (from, to) = (v[i], v[(i + 1) % 3]);
        let d = to - from;
        let len2 = d.norm_squared();
        let t = if len2 > 0.0 {
            ((p - from).dot(&d) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let mut barycentric = [0.0; 3];
        barycentric[i] = 1.0 - t;
        barycentric[(i + 1) % 3] = t;
        let (point, feature) = if t <= 0.0 {
            (*from, Feature::Vertex(i))
        } else if t >= 1.0 {
            (*to, Feature::Vertex((i + 1) % 3))
        } else {
            (from + d * t, Feature::Edge(i))
        };
        let dist2 = (p - point).norm_squared();
        if best.as_ref().is_none_or(|(b, _)| dist2 < *b) {
            best = Some((
                dist2,
                TriangleProjection {
                    point,
                    barycentric,
                    feature,
                },
            ));
        }
    }
    #[allow(clippy::expect_used)] // the loop above visits the three edges, so `best` is set
    best.expect("a triangle has three edges").1
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn degenerate_triangles_give_finite_results() {
        let p = Vector3::new(0.3, 0.7, -0.2);
        let a = Vector3::new(0.0, 0.0, 0.0);
        let b = Vector3::new(1.0, 0.0, 0.0);
        // a point triangle
        let r = closest_point_on_triangle(&p, &a, &a, &a);
        assert_eq!(r.point, a);
        assert_eq!(r.feature, Feature::Vertex(0));
        // a segment with a repeated vertex
        let r = closest_point_on_triangle(&p, &a, &a, &b);
        assert!((r.point - Vector3::new(0.3, 0.0, 0.0)).norm() < 1e-15);
        assert!(matches!(r.feature, Feature::Edge(_)));
        assert!((r.barycentric.iter().sum::<f64>() - 1.0).abs() < 1e-15);
        // collinear vertices, closest to the middle one
        let m = Vector3::new(2.0, 0.0, 0.0);
        let r = closest_point_on_triangle(&Vector3::new(1.0, 1.0, 0.0), &a, &m, &b);
        assert!((r.point - b).norm() < 1e-15);
    }
}
