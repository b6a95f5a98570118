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
//! current projection (`ContactInterface::commit_surface_history`; at the
//! start, `ContactInterface::initial_surface_states`); a node beyond the
//! primary surface's edge gets the surface's point closest to it. A node
//! without one (it had no candidate triangle at the last commit, or that
//! triangle left its candidates) measures the increment's slip from its own
//! committed position `x_s,n`, as against a fixed surface:
//! `d = x_s − x_s,n`; the search margin makes this rare.

use super::friction::{
    self, ContactStatus, FrictionHistory, MaterialPoint, NormalPressure, SlipKinematics,
    TangentialResponse,
};
use super::interface::{ContactInterface, NodeReport};
use super::laws::{GapGeometry, NodeContactState, NodeContribution, NormalLaw};
use super::primary::PrimarySurface;
use super::triangle_gap::{triangle_gap, TriangleGap};
use crate::assembly::pattern::SparsityPattern;
use nalgebra::{Matrix3, SMatrix, SVector, Vector3};

/// Unknowns of one node's contribution: `q = (x_s, x1, x2, x3, y1, y2, y3)`,
/// the secondary node, its triangle and its friction anchor's triangle.
const Q: usize = 21;

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
pub(crate) const STICKY_BAND: f64 = 0.05;

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
        // the last triangle while the node stays over it (within the
        // band), else the nearest candidate
        let kept = state.facet.and_then(|t| {
            primary.candidates.get(i)?.contains(&t).then_some(())?;
            let corners = primary.corners(reference, x, t);
            let gap = triangle_gap(&x_s, [&corners[0], &corners[1], &corners[2]])?;
            gap.shape
                .iter()
                .all(|&n| n >= -STICKY_BAND)
                .then_some((t, gap))
        });
        let (t, gap) = match kept {
            Some(k) => k,
            // the nearest usable candidate; a node whose projection misses
            // even that triangle is beyond the primary surface's edge: open
            // (its extended plane would otherwise push it, with negative
            // weights on the primary nodes)
            None => primary.nearest_gap(reference, x, i, &x_s)?,
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
                let node = self.surface_node(primary, reference, x, i, &blank);
                let g = node.as_ref().map_or(primary.margin, |n| n.gap.gap);
                let mut state = NodeContactState::initial(&law, g);
                state.friction =
                    FrictionHistory::at(PrimarySurface::position(reference, x, self.nodes[i]));
                state.friction.material_point =
                    self.anchor_at(primary, reference, x, i, node.as_ref(), &Vector3::zeros());
                state
            })
            .collect()
    }

    /// The material point node `i` anchors its friction to after an
    /// increment converged at `x` (or at the start), `node` its evaluation
    /// there: where the node is over the primary surface; beyond its edge,
    /// the surface's point closest to it.
    fn anchor_at(
        &self,
        primary: &PrimarySurface,
        reference: &[[f64; 3]],
        x: &[f64],
        i: usize,
        node: Option<&SurfaceNode>,
        traction: &Vector3<f64>,
    ) -> Option<MaterialPoint> {
        let point = match node {
            Some(n) => MaterialPoint {
                triangle: n.triangle,
                shape: n.gap.shape,
                traction: [0.0; 2],
            },
            None => {
                let x_s = PrimarySurface::position(reference, x, self.nodes[i]);
                primary.closest_material_point(reference, x, i, &x_s)?
            }
        };
        let y = primary.corners(reference, x, point.triangle);
        Some(MaterialPoint {
            traction: edge_components(&(y[1] - y[0]), &(y[2] - y[0]), traction),
            ..point
        })
    }

    /// The primary material point node `i` measures its slip from: the one
    /// stored in `state` while its triangle is among the node's candidates
    /// (`None` otherwise, see the module docs).
    fn material_point(
        &self,
        primary: &PrimarySurface,
        i: usize,
        state: &NodeContactState,
    ) -> Option<MaterialPoint> {
        state.friction.material_point.filter(|m| {
            primary
                .candidates
                .get(i)
                .is_some_and(|c| c.contains(&m.triangle))
        })
    }

    /// The tangential response of closed node `i` (`None` when open; zero
    /// traction in stick without friction) over the unknowns `q` of
    /// [`Q`], with the nodes of the anchor's triangle (the current
    /// triangle's when the node has no material point).
    fn surface_tangential(
        &self,
        primary: &PrimarySurface,
        reference: &[[f64; 3]],
        x: &[f64],
        i: usize,
        node: &SurfaceNode,
        state: &NodeContactState,
    ) -> Option<(TangentialResponse<Q>, [usize; 3])> {
        if !node.law.active {
            return None;
        }
        let point = self.material_point(primary, i, state);
        let anchor_nodes = point.map_or_else(
            || [node.nodes[1], node.nodes[2], node.nodes[3]],
            |m| primary.triangles[m.triangle],
        );
        let Some(coulomb) = self.friction_at(i) else {
            let stick = TangentialResponse {
                status: ContactStatus::Stick,
                ..TangentialResponse::none()
            };
            return Some((stick, anchor_nodes));
        };
        let mut offset = PrimarySurface::position(reference, x, node.nodes[0]);
        let mut offset_gradient = SMatrix::<f64, 3, Q>::zeros();
        offset_gradient
            .fixed_view_mut::<3, 3>(0, 0)
            .copy_from(&Matrix3::identity());
        let mut traction = state.friction.traction;
        let mut traction_gradient = SMatrix::<f64, 3, Q>::zeros();
        match point {
            Some(m) => {
                for (j, (&y, &weight)) in anchor_nodes.iter().zip(&m.shape).enumerate() {
                    offset -= weight * PrimarySurface::position(reference, x, y);
                    offset_gradient
                        .fixed_view_mut::<3, 3>(0, 12 + 3 * j)
                        .copy_from(&(-weight * Matrix3::identity()));
                }
                // t_T,n = τ¹ (y2 − y1) + τ² (y3 − y1), carried by the surface
                let [t1, t2] = m.traction;
                let y = anchor_nodes.map(|n| PrimarySurface::position(reference, x, n));
                traction = t1 * (y[1] - y[0]) + t2 * (y[2] - y[0]);
                for (j, w) in [-(t1 + t2), t1, t2].into_iter().enumerate() {
                    traction_gradient
                        .fixed_view_mut::<3, 3>(0, 12 + 3 * j)
                        .copy_from(&(w * Matrix3::identity()));
                }
            }
            // no material point: slip from the node's own committed
            // position, the committed traction as it was
            None => offset -= state.friction.anchor,
        }
        let mut normal_gradient = SMatrix::<f64, 3, Q>::zeros();
        normal_gradient
            .fixed_view_mut::<3, 12>(0, 0)
            .copy_from(&node.gap.normal_gradient);
        // the law on the scalar geometry: ∂t_N/∂g is its gradient's first entry
        let mut pressure_gradient = SVector::<f64, Q>::zeros();
        pressure_gradient
            .fixed_rows_mut::<12>(0)
            .copy_from(&(node.law.pressure_gradient[0] * node.gap.gradient));
        let kinematics = SlipKinematics {
            traction,
            traction_gradient,
            offset,
            offset_gradient,
            normal: node.gap.normal,
            normal_gradient,
        };
        let pressure = NormalPressure {
            value: node.law.pressure,
            gradient: pressure_gradient,
            multiplier_derivative: node.law.pressure_multiplier_derivative,
        };
        let response = friction::return_map_on(&coulomb, &kinematics, &pressure);
        Some((response, anchor_nodes))
    }

    /// Everything node `i` adds to the residual and tangent (see the module
    /// docs); `None` when the node has no usable primary triangle.
    fn surface_contribution(
        &self,
        primary: &PrimarySurface,
        reference: &[[f64; 3]],
        x: &[f64],
        i: usize,
        state: &NodeContactState,
    ) -> Option<SurfaceContribution> {
        let node = self.surface_node(primary, reference, x, i, state)?;
        let tangential = self.surface_tangential(primary, reference, x, i, &node, state);
        let c = &node.law;
        let (f, df_dg, df_dlambda) = (c.r_u[0], c.k_uu[(0, 0)], c.k_ulambda[0]);
        let grad = node.gap.gradient;
        let mut residual = SVector::<f64, Q>::zeros();
        let mut stiffness = SMatrix::<f64, Q, Q>::zeros();
        let mut constraint_gradient = SVector::<f64, Q>::zeros();
        residual.fixed_rows_mut::<12>(0).copy_from(&(f * grad));
        stiffness
            .fixed_view_mut::<12, 12>(0, 0)
            .copy_from(&(df_dg * grad * grad.transpose() + f * node.gap.hessian));
        constraint_gradient
            .fixed_rows_mut::<12>(0)
            .copy_from(&(df_dlambda * grad));
        let mut multiplier_column = constraint_gradient;
        let mut nodes = [node.nodes[0]; 7];
        nodes[..4].copy_from_slice(&node.nodes);
        let mut used = 4;
        let mut friction_lever = None;
        if let Some((t, anchor_nodes)) = &tangential {
            if self.friction.is_some() {
                nodes[4..].copy_from_slice(anchor_nodes);
                used = 7;
                let area = self.areas[i];
                let lever = contact_point_lever(&node.gap);
                residual -= area * lever.transpose() * t.traction;
                stiffness -= area * lever.transpose() * t.traction_gradient;
                // the weights N_i(ξ) of the reaction move with ξ
                let xi = &node.gap.xi_gradient;
                let shape_gradients = [
                    -(xi.row(0) + xi.row(1)),
                    xi.row(0).into_owned(),
                    xi.row(1).into_owned(),
                ];
                for (k, dn) in shape_gradients.iter().enumerate() {
                    let mut rows = stiffness.fixed_view_mut::<3, 12>(3 + 3 * k, 0);
                    rows += area * t.traction * dn;
                }
                multiplier_column -= area * lever.transpose() * t.traction_multiplier_derivative;
                friction_lever = Some(lever);
            }
        }
        Some(SurfaceContribution {
            nodes,
            used,
            residual,
            stiffness,
            multiplier_column,
            multiplier_row: constraint_gradient,
            node,
            tangential: tangential.map(|(t, _)| t),
            friction_lever,
        })
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
            let Some(contribution) = self.surface_contribution(primary, reference, x, i, &state)
            else {
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
            let SurfaceContribution {
                nodes,
                used,
                node,
                tangential,
                ..
            } = &contribution;
            let nodes = &nodes[..*used];
            for (a, &n) in nodes.iter().enumerate() {
                for d in 0..3 {
                    residual[3 * n + d] += contribution.residual[3 * a + d];
                }
            }
            if let Some(m) = multiplier {
                residual[m] += node.law.r_lambda;
            }
            if let Some((pattern, k)) = tangent.as_mut() {
                add_node_block(pattern, k, nodes, &contribution.stiffness, |_| true);
                if multiplier.is_some() {
                    let m = self.multiplier_offset + i;
                    add_multiplier_block(
                        pattern,
                        k,
                        m,
                        nodes,
                        &contribution.multiplier_column,
                        &contribution.multiplier_row,
                        |_| true,
                    );
                    k[pattern.multiplier_diagonal(m)] += node.law.k_lambdalambda;
                }
            }
            let force = node.gap.normal * (self.areas[i] * node.law.pressure);
            let t = tangential.unwrap_or_else(TangentialResponse::none);
            reports.push(NodeReport {
                gap: node.gap.gap,
                pressure: node.law.pressure,
                active: node.law.active,
                status: t.status,
                force: force.into(),
                tangential_traction: t.traction.into(),
                facet: Some(node.triangle),
            });
        }
        reports
    }

    /// The stick preconditioner's shift of the deformable interface (see
    /// [`ContactInterface::shift_to_stick_preconditioner`]): at every
    /// closed node, the symmetrised friction block `−A_s Bᵀ ∂t_T/∂q`
    /// replaced by the stick stiffness at the current projection,
    /// `A_s ε_T Bᵀ T B`, and the symmetrised `−A_s Bᵀ ∂t_T/∂λ` removed;
    /// entries of `constrained` dofs skipped.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn shift_surface_to_stick(
        &self,
        primary: &PrimarySurface,
        reference: &[[f64; 3]],
        x: &[f64],
        states: &[NodeContactState],
        first_multiplier: usize,
        constrained: &[bool],
        pattern: &SparsityPattern,
        values: &mut [f64],
    ) {
        let keep = |dof: usize| !constrained[dof];
        for i in 0..self.nodes.len() {
            let state = self.node_state(states, x, first_multiplier, i);
            let Some(c) = self.surface_contribution(primary, reference, x, i, &state) else {
                continue;
            };
            let (Some(t), Some(lever)) = (c.tangential, c.friction_lever) else {
                continue;
            };
            let area = self.areas[i];
            // the stick stiffness at the current projection, `A_s ε_T Bᵀ T B`
            // (positive semi-definite; the trial derivative `J*` is not
            // when the anchor lies on another triangle), for the tangent's
            // `−A_s Bᵀ ∂t_T/∂q`
            let n = c.node.gap.normal;
            let projector = Matrix3::identity() - n * n.transpose();
            let eps = self.friction_at(i).map_or(0.0, |f| f.tangential_penalty);
            let stick = area * eps * lever.transpose() * projector * lever;
            let shift = stick + area * lever.transpose() * t.traction_gradient;
            let shift = 0.5 * (shift + shift.transpose());
            let nodes = &c.nodes[..c.used];
            add_node_block(pattern, values, nodes, &shift, keep);
            if self.law.has_multiplier_dof() {
                // sym added ½(−A_s Bᵀ ∂t_T/∂λ) to both entries: remove it
                let half = -0.5 * area * lever.transpose() * t.traction_multiplier_derivative;
                let m = self.multiplier_offset + i;
                add_multiplier_block(pattern, values, m, nodes, &-half, &-half, keep);
            }
        }
    }

    /// The status and friction history of every node after an increment
    /// converged (frictionless: stick = closed), and its new material point.
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
            let response = node.as_ref().and_then(|n| {
                self.surface_tangential(primary, reference, x, i, n, &state)
                    .map(|(t, _)| t)
            });
            states[i].friction = friction::commit(
                &state.friction,
                response.as_ref(),
                PrimarySurface::position(reference, x, self.nodes[i]),
            );
            let traction = states[i].friction.traction;
            states[i].friction.material_point =
                self.anchor_at(primary, reference, x, i, node.as_ref(), &traction);
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

/// Everything one secondary node adds, on its nodes
/// `(s, x1, x2, x3, y1, y2, y3)` (the unknowns `q`).
struct SurfaceContribution {
    /// Mesh nodes of `q`.
    nodes: [usize; 7],
    /// How many of `nodes` carry terms: 4 without friction, 7 with.
    used: usize,
    /// `r_q`.
    residual: SVector<f64, Q>,
    /// `∂r_q/∂q` (nonsymmetric with friction).
    stiffness: SMatrix<f64, Q, Q>,
    /// `∂r_q/∂λ`.
    multiplier_column: SVector<f64, Q>,
    /// `∂r_λ/∂q`.
    multiplier_row: SVector<f64, Q>,
    node: SurfaceNode,
    /// `None` when the node is open.
    tangential: Option<TangentialResponse<Q>>,
    /// `B` where the interface has friction.
    friction_lever: Option<SMatrix<f64, 3, Q>>,
}

/// `B = ∂(x_s − x̄)/∂q` at fixed `ξ`: `(I, −N1 I, −N2 I, −N3 I, 0, 0, 0)`,
/// which carries the tangential traction to the secondary node and,
/// opposite, to the current projection point.
fn contact_point_lever(gap: &TriangleGap) -> SMatrix<f64, 3, Q> {
    let mut lever = SMatrix::<f64, 3, Q>::zeros();
    lever
        .fixed_view_mut::<3, 3>(0, 0)
        .copy_from(&Matrix3::identity());
    for (k, &n) in gap.shape.iter().enumerate() {
        lever
            .fixed_view_mut::<3, 3>(0, 3 + 3 * k)
            .copy_from(&(-n * Matrix3::identity()));
    }
    lever
}

/// Add the `3 nodes.len()` leading rows and columns of `block` over
/// `nodes` into the pattern's values, skipping rows and columns whose dof
/// `keep` refuses. Blocks outside the pattern are skipped.
fn add_node_block(
    pattern: &SparsityPattern,
    values: &mut [f64],
    nodes: &[usize],
    block: &SMatrix<f64, Q, Q>,
    keep: impl Fn(usize) -> bool,
) {
    for (a, &na) in nodes.iter().enumerate() {
        for (b, &nb) in nodes.iter().enumerate() {
            let Some(columns) = pattern.block_columns(na, nb) else {
                continue;
            };
            for (j, col) in columns.iter().enumerate() {
                if !keep(3 * nb + j) {
                    continue;
                }
                for r in 0..3 {
                    if keep(3 * na + r) {
                        values[col + r] += block[(3 * a + r, 3 * b + j)];
                    }
                }
            }
        }
    }
}

/// Add multiplier `m`'s column `∂r_q/∂λ` and row `∂r_λ/∂q` over `nodes`
/// (entries of dofs `keep` refuses skipped).
fn add_multiplier_block(
    pattern: &SparsityPattern,
    values: &mut [f64],
    m: usize,
    nodes: &[usize],
    column: &SVector<f64, Q>,
    row: &SVector<f64, Q>,
    keep: impl Fn(usize) -> bool,
) {
    for (a, &na) in nodes.iter().enumerate() {
        if let Some(e) = pattern.multiplier_entries(m, na) {
            for d in 0..3 {
                if keep(3 * na + d) {
                    values[e.node_rows[d]] += column[3 * a + d];
                    values[e.multiplier_row[d]] += row[3 * a + d];
                }
            }
        }
    }
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
