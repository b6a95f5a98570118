//! Node-to-surface contact between deformable bodies (formulation note §4,
//! last point): a secondary node against the primary triangle it projects
//! on, both moving, assembled through the same normal laws as the rigid
//! obstacles.
//!
//! ## The gap and its derivatives
//! For secondary node `s` and its primary triangle `(x1, x2, x3)`
//! ([`primary::best_triangle`](super::primary::best_triangle) among the
//! node's candidates), [`triangle_gap`] gives the signed distance `g` to the
//! triangle's plane and its exact gradient and Hessian with respect to the
//! twelve coordinates `q = (x_s, x1, x2, x3)`; `∂g/∂x_i = −N_i(ξ) n`, so the
//! force `A_s t_N n` on the secondary node is balanced by `−A_s t_N N_i n`
//! on the triangle's nodes.
//!
//! ## One law, any geometry
//! The normal laws reach `q` by the chain rule of
//! [`kinematics`](super::kinematics) with this `∇g` and `∇²g`, which hold
//! the change of the projection point and of the normal: Newton keeps its
//! quadratic rate.
//!
//! ## Friction between bodies
//! Slip is measured against the *material point* of the primary surface the
//! node was over at the last converged increment ([`MaterialPoint`]: a
//! triangle `(y1, y2, y3)` and its weights `N̄_j`), which moves with the
//! primary body: the return mapping of [`friction`] gets
//! ```text
//! d = x_s − Σ N̄_j y_j,     n, ∂n/∂q from the current triangle,
//! ∂t_N/∂q = (∂t_N/∂g) ∇g
//! ```
//! over the 21 unknowns `q = (x_s, x1, x2, x3, y1, y2, y3)` (the anchor's
//! triangle may be the current one: its blocks then add up). The traction
//! acts on the secondary node and, opposite, on the current projection
//! point: `r = −A_s Bᵀ t_T` with `B = (I, −N1 I, −N2 I, −N3 I, 0, 0, 0)`
//! (`B = ∂(x_s − x̄)/∂q` at fixed `ξ`), so that
//! ```text
//! K_qq += −A_s Bᵀ ∂t_T/∂q + A_s Σ_i e_iᵀ t_T ⊗ ∂N_i/∂q      (e_i: block row of x_i)
//! K_qλ += −A_s Bᵀ ∂t_T/∂λ
//! ```
//! The committed traction travels with the primary surface too: it is
//! stored as its components `τ^α` on the anchor triangle's edges and
//! rebuilt as `t_T,n = τ^α a_α(y)` (derivative in the `y` columns), so that
//! a sticking pair that turns as a whole keeps its traction (objectivity;
//! a traction kept in global components would lose `cos θ` of it and leave
//! the tangent plane).
//!
//! After an increment converges the node's new material point is its
//! current projection ([`SurfaceGap::anchor`], at every commit and at the
//! start); a node beyond the
//! primary surface's edge gets the surface's point closest to it. A node
//! without one (it had no candidate triangle at the last commit, or that
//! triangle left its candidates) measures the increment's slip from its own
//! committed position `x_s,n`, as against a fixed surface:
//! `d = x_s − x_s,n`; the search margin makes this rare.

use super::friction::{
    Coulomb, FrictionHistory, MaterialPoint, SlipKinematics, TangentialResponse,
};
use super::kinematics::{current_position, GapKinematics, GapProducer, SecondaryNode, SlipFrame};
use super::laws::NodeContactState;
use super::primary::PrimarySurface;
use super::triangle_gap::TriangleGap;
use nalgebra::{Const, Matrix3, SMatrix, Vector3};

/// Unknowns of one node's contribution: `q = (x_s, x1, x2, x3, y1, y2, y3)`,
/// the secondary node, its triangle and its friction anchor's triangle.
pub const Q: usize = 21;

/// The gap producer of a deformable primary surface.
pub struct SurfaceGap<'a> {
    pub primary: &'a PrimarySurface,
}

impl SurfaceGap<'_> {
    /// The primary material point node `i` measures its slip from: the one
    /// in `history` while its triangle is among the node's candidates
    /// (`None` otherwise, see the module docs).
    fn material_point(&self, i: usize, history: &FrictionHistory) -> Option<MaterialPoint> {
        history.material_point.filter(|m| {
            self.primary
                .candidates
                .get(i)
                .is_some_and(|c| c.contains(&m.triangle))
        })
    }
}

impl GapProducer<Const<Q>> for SurfaceGap<'_> {
    type Point = TriangleGap;

    /// Against the triangle the facet choice keeps (`state.facet_walk`: the
    /// committed one, or after a flip back the last iterate's) while the
    /// node stays over it, else its nearest candidate
    /// ([`PrimarySurface::projection`]);
    /// `None` without a usable candidate or beyond the surface's edge.
    fn kinematics(
        &self,
        node: &SecondaryNode,
        state: &NodeContactState,
    ) -> Option<GapKinematics<Const<Q>, TriangleGap>> {
        let (t, gap) = self
            .primary
            .projection(node, state.facet_walk.kept(state.facet))?;
        let [a, b, c] = self.primary.triangles[t];
        Some(GapKinematics {
            nodes: smallvec::smallvec![node.mesh_node, a, b, c],
            gap: gap.gap,
            gradient: padded(&gap.gradient),
            lever: None,
            hessian: padded(&gap.hessian),
            area: None,
            area_gradient: None,
            normal: gap.normal,
            normal_gradient: padded(&gap.normal_gradient),
            facet: Some(t),
            primary: [a, b, c].into_iter().zip(gap.shape).collect(),
            point: gap,
        })
    }

    fn open_gap(&self) -> f64 {
        self.primary.margin
    }

    fn relative_position(&self, node: &SecondaryNode) -> Vector3<f64> {
        node.position()
    }

    /// `d = x_s − Σ N̄_j y_j` against the material point (or `x_s − x_s,n`
    /// without one), the committed traction rebuilt on the anchor's edges,
    /// and `B = (I, −N1 I, −N2 I, −N3 I, 0, 0, 0)`; the anchor's triangle
    /// (the current one without a material point) fills `y1, y2, y3`.
    fn slip(
        &self,
        node: &SecondaryNode,
        kinematics: &mut GapKinematics<Const<Q>, TriangleGap>,
        history: &FrictionHistory,
    ) -> SlipFrame<Const<Q>> {
        let position = |n| current_position(node.reference, node.x, n);
        let point = self.material_point(node.index, history);
        let current = [1, 2, 3].map(|a| kinematics.nodes[a]);
        let anchor_nodes = point.map_or(current, |m| self.primary.triangles[m.triangle]);
        kinematics.nodes.truncate(4);
        kinematics.nodes.extend_from_slice(&anchor_nodes);
        let mut offset = node.position();
        let mut offset_gradient = SMatrix::<f64, 3, Q>::zeros();
        offset_gradient
            .fixed_view_mut::<3, 3>(0, 0)
            .fill_diagonal(1.0);
        let mut traction = history.traction;
        let mut traction_gradient = SMatrix::<f64, 3, Q>::zeros();
        match point {
            Some(m) => {
                for (j, (&y, &weight)) in anchor_nodes.iter().zip(&m.shape).enumerate() {
                    offset -= weight * position(y);
                    offset_gradient
                        .fixed_view_mut::<3, 3>(0, 12 + 3 * j)
                        .fill_diagonal(-weight);
                }
                // t_T,n = τ¹ (y2 − y1) + τ² (y3 − y1), carried by the surface
                let [t1, t2] = m.traction;
                let y = anchor_nodes.map(position);
                traction = t1 * (y[1] - y[0]) + t2 * (y[2] - y[0]);
                for (j, w) in [-(t1 + t2), t1, t2].into_iter().enumerate() {
                    traction_gradient
                        .fixed_view_mut::<3, 3>(0, 12 + 3 * j)
                        .fill_diagonal(w);
                }
            }
            // no material point: slip from the node's own committed
            // position, the committed traction as it was
            None => offset -= history.anchor,
        }
        SlipFrame {
            kinematics: SlipKinematics {
                traction,
                traction_gradient,
                offset,
                offset_gradient,
                normal: kinematics.normal,
                normal_gradient: kinematics.normal_gradient,
            },
            lever: contact_point_lever(&kinematics.point),
        }
    }

    /// The weights `N_i(ξ)` of the reaction `−N_i t` on the triangle's
    /// nodes move with `ξ`: rows `x_i` get `t ⊗ ∂N_i/∂q`.
    fn lever_stiffness(
        &self,
        kinematics: &GapKinematics<Const<Q>, TriangleGap>,
        traction: &Vector3<f64>,
    ) -> Option<SMatrix<f64, Q, Q>> {
        let xi = &kinematics.point.xi_gradient;
        let shape_gradients = [
            -(xi.row(0) + xi.row(1)),
            xi.row(0).into_owned(),
            xi.row(1).into_owned(),
        ];
        let mut stiffness = SMatrix::<f64, Q, Q>::zeros();
        for (k, dn) in shape_gradients.iter().enumerate() {
            let mut rows = stiffness.fixed_view_mut::<3, 12>(3 + 3 * k, 0);
            rows += traction * dn;
        }
        Some(stiffness)
    }

    /// The stick stiffness at the current projection scaled by the slip
    /// ratio `β`, `A_s β ε_T Bᵀ T B` (positive semi-definite; the trial
    /// derivative `J*` is not when the anchor lies on another triangle).
    fn stick_stiffness(
        &self,
        kinematics: &GapKinematics<Const<Q>, TriangleGap>,
        frame: &SlipFrame<Const<Q>>,
        response: &TangentialResponse<Const<Q>>,
        law: &Coulomb,
        area: f64,
    ) -> SMatrix<f64, Q, Q> {
        let n = kinematics.normal;
        let projector = Matrix3::identity() - n * n.transpose();
        let lever = &frame.lever;
        let stiffness = area * response.stick_scale * law.tangential_penalty;
        stiffness * lever.transpose() * projector * lever
    }

    /// `λ_T ← t_T` on the material point: its components `τ^α` on the
    /// anchor triangle's edges projected on the current tangent plane,
    /// `M τ = ((T a_α)·t_T)`, `M_αβ = (T a_α)·(T a_β)`, so that
    /// [`slip`](GapProducer::slip)'s `T (τ^α a_α) = t_T` exactly also when
    /// the anchor lies on another triangle than the projection (its plain
    /// edge components, [`anchor`](GapProducer::anchor)'s, would leave
    /// `O(θ²) |t_T|` between the two planes at angle `θ`: the outer loop
    /// would stall there). Without a material point, the global vector.
    fn augment(
        &self,
        node: &SecondaryNode,
        history: &FrictionHistory,
        response: Option<(&TangentialResponse<Const<Q>>, &Vector3<f64>)>,
    ) -> FrictionHistory {
        let traction = response.map_or_else(Vector3::zeros, |(r, _)| r.traction);
        let material_point = match self.material_point(node.index, history) {
            Some(m) => {
                // open (no response): t_T = 0, and so are its components
                let n = response.map_or_else(Vector3::zeros, |(_, n)| *n);
                let y = self.primary.corners(node.reference, node.x, m.triangle);
                let projector = Matrix3::identity() - n * n.transpose();
                let (a1, a2) = (projector * (y[1] - y[0]), projector * (y[2] - y[0]));
                Some(MaterialPoint {
                    traction: edge_components(&a1, &a2, &traction),
                    ..m
                })
            }
            None => history.material_point,
        };
        FrictionHistory {
            traction,
            material_point,
            ..*history
        }
    }

    /// Where the node is over the primary surface; beyond its edge, the
    /// surface's point closest to it; the traction as its components on
    /// the point's triangle's edges.
    fn anchor(
        &self,
        node: &SecondaryNode,
        kinematics: Option<&GapKinematics<Const<Q>, TriangleGap>>,
        traction: &Vector3<f64>,
    ) -> Option<MaterialPoint> {
        let point = match kinematics {
            Some(k) => MaterialPoint {
                triangle: k.facet?,
                shape: k.point.shape,
                traction: [0.0; 2],
            },
            None => self.primary.closest_material_point(node)?,
        };
        let y = self.primary.corners(node.reference, node.x, point.triangle);
        Some(MaterialPoint {
            traction: edge_components(&(y[1] - y[0]), &(y[2] - y[0]), traction),
            ..point
        })
    }
}

/// `B = ∂(x_s − x̄)/∂q` at fixed `ξ`: `(I, −N1 I, −N2 I, −N3 I, 0, 0, 0)`,
/// which carries the tangential traction to the secondary node and,
/// opposite, to the current projection point.
fn contact_point_lever(gap: &TriangleGap) -> SMatrix<f64, 3, Q> {
    let mut lever = SMatrix::<f64, 3, Q>::zeros();
    lever.fixed_view_mut::<3, 3>(0, 0).fill_diagonal(1.0);
    for (k, &n) in gap.shape.iter().enumerate() {
        lever.fixed_view_mut::<3, 3>(0, 3 + 3 * k).fill_diagonal(-n);
    }
    lever
}

/// `m` in the top-left corner of a zero matrix: the triangle's 12 unknowns
/// `(x_s, x1, x2, x3)` among the 21 of `q`.
fn padded<const R: usize, const C: usize, const R2: usize, const C2: usize>(
    m: &SMatrix<f64, R, C>,
) -> SMatrix<f64, R2, C2> {
    SMatrix::from_fn(|i, j| if i < R && j < C { m[(i, j)] } else { 0.0 })
}

/// The components `τ = (τ¹, τ²)` of the vector `t` on the edges `a1`, `a2`
/// (of its projection on their plane: `M τ = (a1·t, a2·t)`, `M_αβ = a_α·a_β`);
/// zero on a degenerate triangle.
fn edge_components(a1: &Vector3<f64>, a2: &Vector3<f64>, t: &Vector3<f64>) -> [f64; 2] {
    let (m11, m12, m22) = (a1.dot(a1), a1.dot(a2), a2.dot(a2));
    let det = m11 * m22 - m12 * m12;
    if !(det > 1e-14 * m11.max(m22).powi(2)) {
        return [0.0; 2];
    }
    let (b1, b2) = (a1.dot(t), a2.dot(t));
    [(m22 * b1 - m12 * b2) / det, (m11 * b2 - m12 * b1) / det]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The multiplier kept on an anchor triangle tilted against the current
    /// tangent plane: components on the projected edges rebuild `t_T`
    /// exactly under `T`; the plain edge components miss it by `O(θ²)`.
    #[test]
    fn projected_edge_components_rebuild_the_traction_exactly() {
        let n = Vector3::new(0.0, 0.0, 1.0);
        let projector = Matrix3::identity() - n * n.transpose();
        let t = Vector3::new(0.7, -0.4, 0.0);
        // the anchor's edges tilted by θ = 0.1 about y, and sheared
        let (a1, a2) = (Vector3::new(1.0, 0.0, 0.1), Vector3::new(0.3, 0.8, 0.02));
        let rebuilt = |[t1, t2]: [f64; 2]| projector * (t1 * a1 + t2 * a2);
        let exact = rebuilt(edge_components(&(projector * a1), &(projector * a2), &t));
        assert!((exact - t).norm() < 1e-15, "{exact} vs {t}");
        let plain = rebuilt(edge_components(&a1, &a2, &t));
        assert!((plain - t).norm() > 1e-3 * t.norm(), "{plain} vs {t}");
    }
}
