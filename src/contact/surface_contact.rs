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
//! Every normal law is a function of the scalar gap (and of the node's
//! multiplier): evaluated on a one-dimensional geometry (`n = e₁`, `H = 0`)
//! it returns the force conjugate to the gap, `f = ∂(A_s Φ)/∂g` (its
//! `r_u[0]`), with `∂f/∂g` (`K_uu[0,0]`), `∂f/∂λ` (`K_uλ[0]`), `r_λ` and
//! `K_λλ`. The chain rule then gives the node's contribution on `(q, λ)`:
//! ```text
//! r_q  = f ∇g                     K_qq = (∂f/∂g) ∇g ∇gᵀ + f ∇²g
//! K_qλ = (∂f/∂λ) ∇g               K_λq = (∂r_λ/∂g) ∇gᵀ = (∂f/∂λ) ∇gᵀ
//! ```
//! which includes the change of the projection point and of the normal
//! (both inside `∇²g`): Newton keeps its quadratic rate.
//!
//! Friction between bodies is not implemented yet (the case file refuses
//! it with a message).

use super::friction::{ContactStatus, TangentialResponse};
use super::interface::{ContactInterface, NodeReport};
use super::laws::{GapGeometry, NodeContactState, NodeContribution, NormalLaw};
use super::primary::{best_triangle, PrimarySurface};
use super::triangle_gap::{triangle_gap, TriangleGap};
use crate::assembly::pattern::SparsityPattern;
use nalgebra::{Matrix3, Vector3};

/// One secondary node evaluated against its primary triangle.
pub struct SurfaceNode {
    /// Index of the primary triangle.
    pub triangle: usize,
    /// Mesh nodes `(s, t1, t2, t3)` of the twelve coordinates `q`.
    pub nodes: [usize; 4],
    pub gap: TriangleGap,
    /// The law on the one-dimensional geometry (see the module docs).
    pub law: NodeContribution,
}

/// How far outside its triangle (in barycentric coordinates) a node keeps
/// the triangle it was projected on before. The plane-extended gap jumps
/// where two non-coplanar triangles meet (a warped quadrangle's diagonal,
/// an element edge of a curved surface); a node sitting on such a crease
/// flipped between the two triangles at every Newton iteration and never
/// converged (the stacked-blocks patch test, nodes on the diagonals). The
/// band makes the choice hysteretic: a node changes triangle once it is 5 %
/// of the triangle beyond it. The price: the converged state depends a
/// little on the path (measured: ~5e-4 relative in the patch test's
/// pressures between Uzawa and Rockafellar).
const STICKY_BAND: f64 = 0.05;

/// The one-dimensional geometry of a scalar gap `g`.
fn scalar_geometry(g: f64) -> GapGeometry {
    GapGeometry {
        signed_gap: g,
        normal: Vector3::x(),
        hessian: Matrix3::zeros(),
    }
}

impl ContactInterface {
    /// Secondary node `i` against its best candidate triangle of `primary`
    /// at unknowns `x`, in state `state`; `None` when the node has no
    /// candidate (far from the primary surface: open) or its triangle is
    /// degenerate.
    pub fn surface_node(
        &self,
        primary: &PrimarySurface,
        reference: &[[f64; 3]],
        x: &[f64],
        i: usize,
        state: &NodeContactState,
    ) -> Option<SurfaceNode> {
        let s = self.nodes[i];
        let x_s = PrimarySurface::position(reference, x, s);
        let candidates: Vec<(usize, [Vector3<f64>; 3])> = primary
            .candidates
            .get(i)?
            .iter()
            .map(|&t| (t, primary.corners(reference, x, t)))
            .collect();
        // the last triangle while the node stays over it (within the
        // band), else the nearest candidate
        let kept = state.facet.and_then(|t| {
            let corners = candidates.iter().find(|c| c.0 == t)?.1;
            let gap = triangle_gap(&x_s, [&corners[0], &corners[1], &corners[2]])?;
            gap.shape
                .iter()
                .all(|&n| n >= -STICKY_BAND)
                .then_some((t, gap))
        });
        let (t, gap) = match kept {
            Some(k) => k,
            None => {
                // the nearest candidate that is not degenerate
                let usable: Vec<(usize, [Vector3<f64>; 3])> = candidates
                    .iter()
                    .filter(|(_, c)| triangle_gap(&x_s, [&c[0], &c[1], &c[2]]).is_some())
                    .cloned()
                    .collect();
                let t = best_triangle(&x_s, &usable)?;
                let corners = usable.iter().find(|c| c.0 == t)?.1;
                let gap = triangle_gap(&x_s, [&corners[0], &corners[1], &corners[2]])?;
                // a node whose projection misses even its nearest triangle
                // is beyond the primary surface's edge: open (its extended
                // plane would otherwise push it, with negative weights on
                // the primary nodes)
                if gap.shape.iter().any(|&n| n < -STICKY_BAND) {
                    return None;
                }
                (t, gap)
            }
        };
        let law = self
            .law_at(i)
            .contribution(self.areas[i], &scalar_geometry(gap.gap), state);
        let [a, b, c] = primary.triangles[t];
        Some(SurfaceNode {
            triangle: t,
            nodes: [s, a, b, c],
            gap,
            law,
        })
    }

    /// The states of the nodes when the interface is set up at `x`: the
    /// normal law's initial state at the node's gap (open where the node
    /// has no candidate).
    pub(crate) fn initial_surface_states(
        &self,
        primary: &PrimarySurface,
        reference: &[[f64; 3]],
        x: &[f64],
    ) -> Vec<NodeContactState> {
        (0..self.nodes.len())
            .map(|i| {
                let law = self.law_at(i);
                let blank = NodeContactState::initial(&law, primary.margin);
                let g = self
                    .surface_node(primary, reference, x, i, &blank)
                    .map_or(primary.margin, |n| n.gap.gap);
                NodeContactState::initial(&law, g)
            })
            .collect()
    }

    /// Residual and tangent of every secondary node against `primary` (see
    /// the module docs), and the node reports.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn assemble_on_surface(
        &self,
        primary: &PrimarySurface,
        reference: &[[f64; 3]],
        x: &[f64],
        states: &[NodeContactState],
        first_multiplier: usize,
        residual: &mut [f64],
        mut tangent: Option<(&SparsityPattern, &mut [f64])>,
    ) -> Vec<NodeReport> {
        let mut reports = Vec::with_capacity(self.nodes.len());
        for i in 0..self.nodes.len() {
            let state = self.node_state(states, x, first_multiplier, i);
            let multiplier = self
                .law
                .has_multiplier_dof()
                .then_some(first_multiplier + self.multiplier_offset + i);
            let Some(node) = self.surface_node(primary, reference, x, i, &state) else {
                // no primary triangle within the search margin: open, at a
                // gap of the margin (an inactive multiplier row)
                let open = self.law_at(i).contribution(
                    self.areas[i],
                    &scalar_geometry(primary.margin),
                    &state,
                );
                if let Some(m) = multiplier {
                    residual[m] += open.r_lambda;
                    if let Some((pattern, k)) = tangent.as_mut() {
                        k[pattern.multiplier_diagonal(m - first_multiplier)] += open.k_lambdalambda;
                    }
                }
                reports.push(NodeReport {
                    gap: primary.margin,
                    ..Default::default()
                });
                continue;
            };
            let c = &node.law;
            let (f, df_dg, df_dlambda) = (c.r_u[0], c.k_uu[(0, 0)], c.k_ulambda[0]);
            let grad = &node.gap.gradient;
            for (a, &n) in node.nodes.iter().enumerate() {
                for d in 0..3 {
                    residual[3 * n + d] += f * grad[3 * a + d];
                }
            }
            if let Some(m) = multiplier {
                residual[m] += c.r_lambda;
            }
            if let Some((pattern, k)) = tangent.as_mut() {
                let k_qq = df_dg * grad * grad.transpose() + f * node.gap.hessian;
                for (a, &na) in node.nodes.iter().enumerate() {
                    for (b, &nb) in node.nodes.iter().enumerate() {
                        let Some(columns) = pattern.block_columns(na, nb) else {
                            continue;
                        };
                        for (j, col) in columns.iter().enumerate() {
                            for r in 0..3 {
                                k[col + r] += k_qq[(3 * a + r, 3 * b + j)];
                            }
                        }
                    }
                }
                if multiplier.is_some() {
                    let m = self.multiplier_offset + i;
                    for (a, &na) in node.nodes.iter().enumerate() {
                        if let Some(e) = pattern.multiplier_entries(m, na) {
                            for d in 0..3 {
                                k[e.node_rows[d]] += df_dlambda * grad[3 * a + d];
                                k[e.multiplier_row[d]] += df_dlambda * grad[3 * a + d];
                            }
                        }
                    }
                    k[pattern.multiplier_diagonal(m)] += c.k_lambdalambda;
                }
            }
            let force = node.gap.normal * (self.areas[i] * c.pressure);
            reports.push(NodeReport {
                gap: node.gap.gap,
                pressure: c.pressure,
                active: c.active,
                status: if c.active {
                    ContactStatus::Stick
                } else {
                    ContactStatus::Open
                },
                force: force.into(),
                tangential_traction: [0.0; 3],
                facet: Some(node.triangle),
            });
        }
        reports
    }

    /// The status of every node after an increment converged (frictionless:
    /// stick = closed), for output.
    pub(crate) fn commit_surface_history(
        &self,
        primary: &PrimarySurface,
        reference: &[[f64; 3]],
        x: &[f64],
        first_multiplier: usize,
        states: &mut [NodeContactState],
    ) {
        for i in 0..self.nodes.len() {
            let state = self.node_state(states, x, first_multiplier, i);
            let node = self.surface_node(primary, reference, x, i, &state);
            states[i].facet = node.as_ref().map(|n| n.triangle);
            let closed = node.is_some_and(|n| n.law.active);
            let response = closed.then(|| TangentialResponse {
                status: ContactStatus::Stick,
                ..TangentialResponse::none()
            });
            states[i].friction = super::friction::commit(
                &state.friction,
                response.as_ref(),
                PrimarySurface::position(reference, x, self.nodes[i]),
            );
        }
    }

    /// Record each node's triangle at `x` and carry the slack law's local
    /// unknowns along a Newton step `dx` from `x` (the law's
    /// one-dimensional increment is `Δg = ∇g · Δq`).
    pub(crate) fn advance_surface_states(
        &self,
        primary: &PrimarySurface,
        reference: &[[f64; 3]],
        x: &[f64],
        dx: &[f64],
        first_multiplier: usize,
        states: &mut [NodeContactState],
    ) {
        for i in 0..self.nodes.len() {
            let mut state = self.node_state(states, x, first_multiplier, i);
            let node = self.surface_node(primary, reference, x, i, &state);
            states[i].facet = node.as_ref().map(|n| n.triangle);
            if !matches!(self.law, NormalLaw::Slack { .. }) {
                continue;
            }
            state.facet = states[i].facet;
            let dlambda = dx[first_multiplier + self.multiplier_offset + i];
            let (g, dg) = match node {
                Some(node) => {
                    let dg: f64 = node
                        .nodes
                        .iter()
                        .enumerate()
                        .map(|(a, &n)| {
                            (0..3)
                                .map(|d| node.gap.gradient[3 * a + d] * dx[3 * n + d])
                                .sum::<f64>()
                        })
                        .sum();
                    (node.gap.gap, dg)
                }
                None => (primary.margin, 0.0),
            };
            self.law_at(i).apply_increment(
                self.areas[i],
                &scalar_geometry(g),
                &mut state,
                &Vector3::new(dg, 0.0, 0.0),
                dlambda,
            );
            states[i] = state;
        }
    }
}
