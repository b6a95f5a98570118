//! Polygons in the auxiliary plane: orientation, Sutherland–Hodgman
//! clipping of a polygon by a convex one (Sutherland & Hodgman, CACM 17,
//! 1974; the segmentation of Puso & Laursen 2004 and Popp et al. 2010),
//! and the split of the clip polygon into triangles about its centroid.

/// A polygon's vertices in plane coordinates, in order.
pub type Polygon = Vec<[f64; 2]>;

/// A triangle in plane coordinates.
pub type Triangle = [[f64; 2]; 3];

/// `(b − a) × (c − a)`, twice the signed area of the triangle `(a, b, c)`.
pub fn cross(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
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
pub fn counter_clockwise(polygon: Polygon) -> Polygon {
    counter_clockwise_order(&polygon)
        .into_iter()
        .map(|i| polygon[i])
        .collect()
}

/// The vertex order `0, 1, …` or its reverse that makes the polygon
/// counter-clockwise.
pub fn counter_clockwise_order(polygon: &[[f64; 2]]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..polygon.len()).collect();
    if signed_area(polygon) < 0.0 {
        order.reverse();
    }
    order
}

/// The intersection of the segment `(s, e)` with the line through `(a, b)`:
/// `p = s + t (e − s)`, `t = d_s / (d_s − d_e)`, `d = (b − a) × (· − a)`.
pub fn intersection(s: [f64; 2], e: [f64; 2], a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    let (ds, de) = (cross(a, b, s), cross(a, b, e));
    let t = ds / (ds - de);
    [s[0] + t * (e[0] - s[0]), s[1] + t * (e[1] - s[1])]
}

/// Where a vertex of the clipping's trace comes from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum VertexOrigin {
    /// The subject polygon's vertex `i`.
    Subject(usize),
    /// The intersection of the segment between the trace's vertices `s`
    /// and `e` with the line through the clip polygon's vertices `edge`
    /// and `edge + 1`.
    Intersection { s: usize, e: usize, edge: usize },
}

/// A Sutherland–Hodgman clipping with every vertex it made: `origins[v]`
/// and `points[v]` for each vertex `v` (earlier vertices first), and the
/// clip polygon as vertex indices. Differentiating along the trace gives
/// the clip polygon's derivative ([`super::clip_derivatives`]).
#[derive(Clone, Debug, PartialEq, Default)]
pub struct ClipTrace {
    pub origins: Vec<VertexOrigin>,
    pub points: Vec<[f64; 2]>,
    pub polygon: Vec<usize>,
}

impl ClipTrace {
    /// The clip polygon's points.
    pub fn polygon_points(&self) -> Polygon {
        self.polygon.iter().map(|&v| self.points[v]).collect()
    }

    fn push(&mut self, origin: VertexOrigin, point: [f64; 2]) -> usize {
        self.origins.push(origin);
        self.points.push(point);
        self.points.len() - 1
    }
}

/// Relative tolerance of the clipping: a vertex within `TOLERANCE · L` of
/// a clip edge's line (`L` the clip's size, its largest coordinate) is on
/// that line, vertices closer than that are merged, and an overlap of area
/// below `TOLERANCE` times the clip's is a sliver, dropped.
pub const TOLERANCE: f64 = 1e-12;

/// Sutherland–Hodgman: the part of `subject` inside the convex `clip`, both
/// counter-clockwise, robust where edges coincide or are parallel (Puso &
/// Laursen 2004; Popp, Gitterle, Gee & Wall 2010, §4.2), with
/// [`TOLERANCE`] relative to the clip's size:
/// - a vertex at signed distance `d ≥ −tol` from an edge's line is inside;
/// - an edge `(s, e)` that crosses the line gets the intersection
///   `t = d_s / (d_s − d_e)` only if its inside end is strictly inside
///   (`d > tol`): an inside end on the line (`|d| ≤ tol`) is the crossing
///   itself. So every `t` is in `(0, 1)` with `|d_s − d_e| > 2 tol`; without
///   the rule an edge running along the line within the band (`d_s = −0.9
///   tol`, `d_e = −1.1 tol`) gave `t = −4.5`, a vertex far off the faces;
/// - consecutive vertices closer than `tol` are merged, and an overlap of
///   fewer than three vertices, or of an area below `TOLERANCE` times the
///   clip's, is empty.
pub fn clip_convex(subject: &[[f64; 2]], clip: &[[f64; 2]]) -> Polygon {
    clip_convex_traced(subject, clip).polygon_points()
}

/// [`clip_convex`] with the origin of every vertex.
pub fn clip_convex_traced(subject: &[[f64; 2]], clip: &[[f64; 2]]) -> ClipTrace {
    let size = clip
        .iter()
        .flat_map(|p| p.iter())
        .fold(0.0f64, |m, c| m.max(c.abs()))
        .max(f64::MIN_POSITIVE);
    let tol = TOLERANCE * size;
    let mut trace = ClipTrace::default();
    let mut output: Vec<usize> = subject
        .iter()
        .enumerate()
        .map(|(i, p)| trace.push(VertexOrigin::Subject(i), *p))
        .collect();
    for edge in 0..clip.len() {
        let (a, b) = (clip[edge], clip[(edge + 1) % clip.len()]);
        let length = ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt();
        if length == 0.0 {
            continue; // two coincident corners: no edge to clip by
        }
        let input = std::mem::take(&mut output);
        // the signed distance from the edge's line, `(b − a) × (p − a) / L`
        let distance = |v: usize, t: &ClipTrace| cross(a, b, t.points[v]) / length;
        for k in 0..input.len() {
            let (s, e) = (input[(k + input.len() - 1) % input.len()], input[k]);
            let (ds, de) = (distance(s, &trace), distance(e, &trace));
            let (s_in, e_in) = (ds >= -tol, de >= -tol);
            if s_in != e_in && ds.max(de) > tol {
                let p = intersection(trace.points[s], trace.points[e], a, b);
                output.push(trace.push(VertexOrigin::Intersection { s, e, edge }, p));
            }
            if e_in {
                output.push(e);
            }
        }
        if output.is_empty() {
            return trace;
        }
    }
    trace.polygon = merge_close(output, &trace.points, tol);
    let points = trace.polygon_points();
    if signed_area(&points).abs() <= TOLERANCE * signed_area(clip).abs() {
        trace.polygon.clear();
    }
    trace
}

/// Drops vertices within `tol` of their predecessor (and the last if it
/// repeats the first); fewer than three left is empty.
fn merge_close(polygon: Vec<usize>, points: &[[f64; 2]], tol: f64) -> Vec<usize> {
    let close = |p: usize, q: usize| {
        let (p, q) = (points[p], points[q]);
        (p[0] - q[0]).abs() <= tol && (p[1] - q[1]).abs() <= tol
    };
    let mut out: Vec<usize> = Vec::with_capacity(polygon.len());
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
