//! Polygons in the auxiliary plane: orientation, Sutherland–Hodgman
//! clipping of a polygon by a convex one (Sutherland & Hodgman, CACM 17,
//! 1974; the segmentation of Puso & Laursen 2004 and Popp et al. 2010),
//! and the split of the clip polygon into triangles about its centroid.

/// A polygon's vertices in plane coordinates, in order.
pub type Polygon = Vec<[f64; 2]>;

/// A triangle in plane coordinates.
pub type Triangle = [[f64; 2]; 3];

/// `(b − a) × (c − a)`, twice the signed area of the triangle `(a, b, c)`.
fn cross(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

/// The signed area `½ Σ_i (p_i × p_{i+1})` (positive counter-clockwise).
pub fn signed_area(polygon: &[[f64; 2]]) -> f64 {
    let n = polygon.len();
    (0..n)
        .map(|i| {
            let (a, b) = (polygon[i], polygon[(i + 1) % n]);
            a[0] * b[1] - a[1] * b[0]
        })
        .sum::<f64>()
        * 0.5
}

/// The polygon with its vertices counter-clockwise.
pub fn counter_clockwise(mut polygon: Polygon) -> Polygon {
    if signed_area(&polygon) < 0.0 {
        polygon.reverse();
    }
    polygon
}

/// The intersection of the segment `(s, e)` with the line through `(a, b)`.
fn intersection(s: [f64; 2], e: [f64; 2], a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    let (ds, de) = (cross(a, b, s), cross(a, b, e));
    let t = ds / (ds - de);
    [s[0] + t * (e[0] - s[0]), s[1] + t * (e[1] - s[1])]
}

/// Sutherland–Hodgman: the part of `subject` inside the convex `clip`, both
/// counter-clockwise. A vertex on an edge counts as inside. Consecutive
/// vertices closer than `1e-12` of the clip's size are merged; an overlap
/// of fewer than three vertices is empty.
pub fn clip_convex(subject: &[[f64; 2]], clip: &[[f64; 2]]) -> Polygon {
    let size = clip
        .iter()
        .flat_map(|p| p.iter())
        .fold(0.0f64, |m, c| m.max(c.abs()))
        .max(f64::MIN_POSITIVE);
    let tol = 1e-12 * size;
    let mut output: Polygon = subject.to_vec();
    for i in 0..clip.len() {
        let (a, b) = (clip[i], clip[(i + 1) % clip.len()]);
        let edge = ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt();
        let inside = |p: [f64; 2]| cross(a, b, p) >= -tol * edge;
        let input = std::mem::take(&mut output);
        for k in 0..input.len() {
            let (s, e) = (input[(k + input.len() - 1) % input.len()], input[k]);
            match (inside(s), inside(e)) {
                (true, true) => output.push(e),
                (true, false) => output.push(intersection(s, e, a, b)),
                (false, true) => {
                    output.push(intersection(s, e, a, b));
                    output.push(e);
                }
                (false, false) => {}
            }
        }
        if output.is_empty() {
            return output;
        }
    }
    merge_close(output, tol)
}

/// Drops vertices within `tol` of their predecessor (and the last if it
/// repeats the first); fewer than three left is empty.
fn merge_close(polygon: Polygon, tol: f64) -> Polygon {
    let close = |p: [f64; 2], q: [f64; 2]| (p[0] - q[0]).abs() <= tol && (p[1] - q[1]).abs() <= tol;
    let mut out: Polygon = Vec::with_capacity(polygon.len());
    for p in polygon {
        if out.last().is_none_or(|q| !close(p, *q)) {
            out.push(p);
        }
    }
    while out.len() > 1 && close(out[0], out[out.len() - 1]) {
        out.pop();
    }
    if out.len() < 3 {
        out.clear();
    }
    out
}

/// The vertex centroid `c = (1/n) Σ_i p_i`.
pub fn centroid(polygon: &[[f64; 2]]) -> [f64; 2] {
    let n = polygon.len() as f64;
    let s = polygon
        .iter()
        .fold([0.0; 2], |s, p| [s[0] + p[0], s[1] + p[1]]);
    [s[0] / n, s[1] / n]
}

/// The triangles `(c, p_i, p_{i+1})` about the vertex centroid `c` of a
/// convex polygon (Popp et al. 2010: the integration cells).
pub fn centroid_triangles(polygon: &[[f64; 2]]) -> Vec<Triangle> {
    let c = centroid(polygon);
    let n = polygon.len();
    (0..n)
        .map(|i| [c, polygon[i], polygon[(i + 1) % n]])
        .collect()
}
