//! Directional derivatives of the clip polygon's vertices (Popp, Gitterle,
//! Gee & Wall 2010, §5: the segmentation's vertices move with the nodes).
//! A vertex is either a projected corner of the subject polygon, whose
//! derivative is given, or the intersection of a segment `(s, e)` with the
//! line through the clip polygon's edge `(a, b)`:
//!
//! ```text
//! p = s + t (e − s),   t = d_s / (d_s − d_e),   d_c = (b − a) × (c − a),
//! δd_c = (δb − δa) × (c − a) + (b − a) × (δc − δa),
//! δt = (d_s δd_e − d_e δd_s) / (d_s − d_e)²,
//! δp = δs + δt (e − s) + t (δe − δs).
//! ```
//!
//! Differentiating along the [`ClipTrace`] (earlier vertices first) covers
//! every case: a kept corner, an edge–edge intersection, and a clip
//! polygon corner reached as the intersection of two intersections. The
//! centroid and the centroid triangles of [`super::clipping`] are linear
//! in the vertices, so applied to the vertices' derivatives they give
//! their own derivatives.

use super::clipping::{cross, ClipTrace, VertexOrigin};

/// `δ[(b − a) × (c − a)]`.
pub fn cross_derivative(p: [[f64; 2]; 3], dp: [[f64; 2]; 3]) -> f64 {
    let [a, b, c] = p;
    let [da, db, dc] = dp;
    let (ba, ca) = ([b[0] - a[0], b[1] - a[1]], [c[0] - a[0], c[1] - a[1]]);
    let (dba, dca) = (
        [db[0] - da[0], db[1] - da[1]],
        [dc[0] - da[0], dc[1] - da[1]],
    );
    dba[0] * ca[1] + ba[0] * dca[1] - dba[1] * ca[0] - ba[1] * dca[0]
}

/// The derivative of [`super::clipping::intersection`] for the segment
/// `(s, e)` and the line `(a, b)` moving by `(δs, δe, δa, δb)`.
pub fn intersection_derivative(p: [[f64; 2]; 4], dp: [[f64; 2]; 4]) -> [f64; 2] {
    let [s, e, a, b] = p;
    let [d_s, d_e, d_a, d_b] = dp;
    let (cs, ce) = (cross(a, b, s), cross(a, b, e));
    let (dcs, dce) = (
        cross_derivative([a, b, s], [d_a, d_b, d_s]),
        cross_derivative([a, b, e], [d_a, d_b, d_e]),
    );
    let t = cs / (cs - ce);
    let dt = (cs * dce - ce * dcs) / (cs - ce).powi(2);
    [0, 1].map(|i| d_s[i] + dt * (e[i] - s[i]) + t * (d_e[i] - d_s[i]))
}

impl ClipTrace {
    /// The derivatives of every vertex of the trace, given those of the
    /// subject polygon's vertices and of the clip polygon (`clip` its
    /// points, both in the order the clipping used).
    pub fn vertex_derivatives(
        &self,
        d_subject: &[[f64; 2]],
        clip: &[[f64; 2]],
        d_clip: &[[f64; 2]],
    ) -> Vec<[f64; 2]> {
        let mut d: Vec<[f64; 2]> = Vec::with_capacity(self.origins.len());
        for origin in &self.origins {
            let dv = match *origin {
                VertexOrigin::Subject(i) => d_subject[i],
                VertexOrigin::Intersection { s, e, edge } => {
                    let next = (edge + 1) % clip.len();
                    intersection_derivative(
                        [self.points[s], self.points[e], clip[edge], clip[next]],
                        [d[s], d[e], d_clip[edge], d_clip[next]],
                    )
                }
            };
            d.push(dv);
        }
        d
    }

    /// The derivatives of the clip polygon's vertices, in polygon order.
    pub fn polygon_derivatives(
        &self,
        d_subject: &[[f64; 2]],
        clip: &[[f64; 2]],
        d_clip: &[[f64; 2]],
    ) -> Vec<[f64; 2]> {
        let d = self.vertex_derivatives(d_subject, clip, d_clip);
        self.polygon.iter().map(|&v| d[v]).collect()
    }
}
