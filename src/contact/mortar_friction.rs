//! Coulomb friction on dual mortar (issue 28, item 4): the slip frame,
//! lever and stick stiffness that [`MortarGap`]'s
//! [`GapProducer`](super::kinematics::GapProducer) hands the node driver,
//! so that the one friction law of [`friction`](super::friction) (return
//! mapping, exact stick with tangential multipliers in Newton, the same
//! keys) runs on mortar between deformable bodies and against rigid
//! obstacles.
//!
//! ## Slip: the frame-indifferent weighted slip (Gitterle et al. 2010)
//! The driver's offset `d` of secondary node `j` is its weighted slip
//! increment per area, `d_j = w_j / D_j` with
//! `w_j = Σ_l (M_jl − M_jl,n) x_l − (D_j − D_j,n) x̃_j`
//! ([`weighted_slip`](super::mortar::weighted_slip)): `D_j,n`, `M_jl,n`
//! are the coupling at the last converged configuration, kept in
//! [`MortarSurfaces::committed`] at the start of every increment from the
//! producer's own rows there (the row cache's converged entry: one reader
//! of `D` and `M`). A node no segment reached at
//! the last commit measures `d = x_s − x_s,n` from its own committed
//! position (it is closing: the driver's first-contact rule counts its
//! slip from where it touches).
//!
//! ## Against a rigid obstacle
//! A rigid obstacle has no `M`: the slip is the node's motion relative to
//! the obstacle, as node-to-surface measures it
//! ([`friction`](super::friction), "Signs and kinematics"), at the
//! transformed point the mortar lever loads,
//! ```text
//! d_j = (x̃_j − c(t)) − (x̃_j − c)ₙ,     x̃_j = Σ_k R_jk x_k,     ∂d_j/∂x_k = R_jk I,
//! ```
//! `c(t)` the obstacle's translation (`R = I` on linear faces, where this
//! is node-to-surface's slip of the node itself). It is the weighted slip
//! of a primary that does not deform: the obstacle's material points do
//! not move in its own frame, and `D_j` is not a primary integral. The
//! force is the lever's `D_j R_jk t_T` on the secondary nodes, so the
//! tangential work is `Σ_j D_j t_T·δx̃_j`, conjugate to the slip.
//!
//! ## A node that closes in the increment
//! The node driver counts the slip of a node open at the last commit from
//! its first contact, `d' = (1 − α) d` with `α = g_n/(g_n − g)` for
//! `g < 0` and 1 for `g ≥ 0`
//! ([`friction::first_contact`](super::friction::first_contact)). With a
//! normal multiplier in Newton the mortar constraint holds exactly,
//! `g_j = 0` at every converged closed node, so the converged state sits
//! on that fraction's kink: `∂d'/∂q` jumps by `d ⊗ ∇g / g_n` across
//! `g = 0`. On the ironing's rear edge (`g_n ≈ 0.015`, `|d| ≈ 0.03`) that
//! is a tangential stiffness `ε_T |d|/g_n ≈ 90`, twenty times the normal
//! `p`, on one side of a point no status switch counts, where Newton's
//! tangent is right on either side (the FD check of
//! `tests/ironing_mortar.rs`). Such a
//! node takes the fraction's value at the solution in every iteration,
//! `α = 1` ([`friction::first_contact_at_solution`](super::friction::first_contact_at_solution)):
//! no slip and no tangential traction in the increment it closes, as
//! before at convergence, and no kink (the ironing's press at t = 0.3:
//! 8 Newton iterations before, 5 after).
//!
//! ## Force: the mortar lever
//! The tangential traction `t_T` of node `j` (a dual multiplier, like
//! `λ_j`) acts on the secondary nodes `k` as `D_j R_jk t_T` and on the
//! primary nodes `l` as `−M_jl t_T`: the driver's `r_q −= A Bᵀ t_T` with
//! `A = D_j` and the lever at fixed `D`, `M`
//! ```text
//! B = ∂(x̃_j − Σ_l (M_jl/D_j) x_l)/∂q = (R_jk I on k;  −(M_jl/D_j) I on l),
//! ```
//! so the forces balance where `Σ_l M_jl = D_j Σ_k R_jk`. Its own change
//! (with the area's) at fixed `t_T`
//! ([`lever_stiffness`](super::kinematics::GapProducer::lever_stiffness)):
//! `∂(−A Bᵀ t)/∂q = (−R_jk t ⊗ ∇D_j on k;  t ⊗ ∇M_jl on l)`.
//!
//! The committed traction of a law without tangential multipliers
//! (penalty) is kept as a global vector and projected on the current
//! tangent plane, as against a rigid obstacle: a pair that turns as a
//! whole while sticking loses `1 − cos θ` of it (the node-to-surface path
//! carries it on the primary triangle's edges; not done here).

use super::friction::{Coulomb, FrictionHistory, SlipKinematics, TangentialResponse};
use super::kinematics::{current_position, GapKinematics, SecondaryNode, SlipFrame};
use super::mortar::obstacle_rows::transformed_position;
use super::mortar::weighted_slip::{committed_row, weighted_slip};
use super::mortar::Derivatives;
use super::mortar::{MortarCoupling, MortarRow};
use super::mortar_contact::{MortarGap, MortarRows, MortarSurfaces};
use nalgebra::{DMatrix, Dyn, Matrix3, OMatrix, Vector3, U3};

impl MortarSurfaces {
    /// Keep the coupling of every converged increment from now on
    /// (friction needs it), starting with the one at `reference`.
    pub fn track_slip(&mut self, reference: &[[f64; 3]]) {
        self.committed = Some(MortarCoupling::default());
        let xs: Vec<Vector3<f64>> = reference.iter().map(|x| Vector3::from(*x)).collect();
        self.commit_coupling(&xs);
    }

    /// Keep `D`, `M` at the converged coordinates `xs` where slip is
    /// tracked ([`track_slip`](Self::track_slip)): the covered rows there
    /// ([`rows_at_coordinates`](Self::rows_at_coordinates), their values:
    /// the coupling reads no derivative), from the row cache's converged
    /// entry while the candidate pairs hold (integrated once more, values
    /// alone, where they changed). A node without a covered row (a face the
    /// kernels cannot integrate; less than half covered, whose `D_j,n`,
    /// `M_jl,n` are as unreliable as its gap) slips from its own committed
    /// position.
    pub fn commit_coupling(&mut self, xs: &[Vector3<f64>]) {
        if self.committed.is_some() {
            let rows = self.rows_at_coordinates(xs, Derivatives::Without);
            self.committed = Some(committed_coupling(&rows));
        }
    }
}

/// The coupling `D_j`, `M_jl`, `n_j`, `R_jk` of the producer's `rows`:
/// what the weighted slip reads as the committed state.
fn committed_coupling(rows: &MortarRows) -> MortarCoupling {
    let mut out = MortarCoupling::default();
    for (&j, row) in rows {
        out.d.insert(j, row.d);
        out.m.extend(row.m.iter().map(|&(l, v)| ((j, l), v)));
        out.normals.insert(j, row.normal);
        out.transformation.insert(j, row.transformation.clone());
    }
    out
}

/// Position of every mesh node of `nodes` in `among` (the kinematics'
/// `q` order), node-major offsets `3a`.
fn offsets(among: &[usize], nodes: &[usize]) -> Vec<usize> {
    nodes
        .iter()
        .map(|n| 3 * among.iter().position(|m| m == n).unwrap_or(0))
        .collect()
}

/// Adds the 3-row block `block` (columns node-major over `nodes`) to
/// `target` (columns over `q`, `offsets` of `nodes` there).
fn add_columns(target: &mut OMatrix<f64, U3, Dyn>, block: &DMatrix<f64>, offsets: &[usize]) {
    for (a, &c) in offsets.iter().enumerate() {
        for i in 0..3 {
            for k in 0..3 {
                target[(i, c + k)] += block[(i, 3 * a + k)];
            }
        }
    }
}

/// The weights of `B = Σ_k w_k e_k ⊗ I` of `row`: `R_jk` on the secondary
/// nodes `k`, `−M_jl/D_j` on the primary nodes `l`.
fn lever_weights(row: &MortarRow) -> impl Iterator<Item = (usize, f64)> + '_ {
    (row.transformation.iter().copied()).chain(row.m.iter().map(|(l, m)| (*l, -m / row.d)))
}

/// `B = (R_jk I on k; −(M_jl/D_j) I on l)` of `row` over `q`'s `nodes`.
fn lever(nodes: &[usize], row: &MortarRow) -> OMatrix<f64, U3, Dyn> {
    let mut lever = OMatrix::<f64, U3, Dyn>::zeros_generic(U3, Dyn(3 * nodes.len()));
    for (n, w) in lever_weights(row) {
        let c = offsets(nodes, &[n])[0];
        for i in 0..3 {
            lever[(i, c + i)] += w;
        }
    }
    lever
}

impl MortarGap<'_> {
    /// The node's committed `(D_j,n, M_jl,n)`, where slip is tracked and a
    /// segment reached it at the last commit.
    fn committed_of(&self, j: usize) -> Option<(f64, Vec<(usize, f64)>)> {
        committed_row(self.surfaces.committed.as_ref()?, j)
    }

    /// `kinematics` of mesh node `j` with the committed primary nodes it
    /// no longer couples to appended to `q` (zero entries), so that the
    /// weighted slip's `−M_jl,n x_l` reaches them.
    pub(super) fn with_committed_nodes(
        &self,
        j: usize,
        mut kinematics: GapKinematics<Dyn>,
    ) -> GapKinematics<Dyn> {
        let Some((_, m_n)) = self.committed_of(j) else {
            return kinematics;
        };
        let extra: Vec<usize> = m_n
            .iter()
            .map(|(l, _)| *l)
            .filter(|l| !kinematics.nodes.contains(l))
            .collect();
        if extra.is_empty() {
            return kinematics;
        }
        kinematics.nodes.extend_from_slice(&extra);
        let q = 3 * kinematics.nodes.len();
        let k = kinematics;
        GapKinematics {
            gradient: k.gradient.resize_vertically(q, 0.0),
            lever: k.lever.map(|b| b.resize_vertically(q, 0.0)),
            area_gradient: k.area_gradient.map(|a| a.resize_vertically(q, 0.0)),
            hessian: k.hessian.resize(q, q, 0.0),
            normal_gradient: k.normal_gradient.resize_horizontally(q, 0.0),
            ..k
        }
    }

    /// The slip frame of a closed node (see the module docs): `d_j = w_j /
    /// D_j` (or `x_s − x_s,n` without a committed row), the committed
    /// traction, and the mortar lever `B`.
    pub(super) fn frictional_slip(
        &self,
        node: &SecondaryNode,
        kinematics: &GapKinematics<Dyn>,
        history: &FrictionHistory,
    ) -> SlipFrame<Dyn> {
        let (j, q) = (node.mesh_node, kinematics.gradient.len());
        let zero = || OMatrix::<f64, U3, Dyn>::zeros_generic(U3, Dyn(q));
        // a closed node has a row; without one (never asked for) no
        // lever: no tangential force reaches the nodes
        let row = self.node_row(j);
        let mut offset_gradient = zero();
        let offset = match (row, self.committed_of(j)) {
            (Some(row), _) if self.source.obstacle_translation().is_some() => {
                // x̃_j − c − (x̃_j − c)ₙ: ∂/∂x_k = R_jk I, the lever's weights
                offset_gradient = lever(&kinematics.nodes, row);
                self.frictional_relative_position(node) - history.anchor
            }
            (Some(row), Some((d_n, m_n))) => {
                let position = |n| current_position(node.reference, node.x, n);
                let slip = weighted_slip(row, (d_n, &m_n), position);
                let (d, gradient) = slip.per_area(row);
                add_columns(
                    &mut offset_gradient,
                    &gradient,
                    &offsets(&kinematics.nodes, &slip.nodes),
                );
                d
            }
            _ => {
                offset_gradient
                    .fixed_view_mut::<3, 3>(0, 0)
                    .fill_diagonal(1.0);
                node.position() - history.anchor
            }
        };
        SlipFrame {
            kinematics: SlipKinematics {
                traction: history.traction,
                traction_gradient: zero(),
                offset,
                offset_gradient,
                normal: kinematics.normal,
                normal_gradient: kinematics.normal_gradient.clone(),
            },
            lever: row.map_or_else(zero, |row| lever(&kinematics.nodes, row)),
        }
    }

    /// The position the node's slip is measured from (see the module
    /// docs): `x_s` between bodies; against a rigid obstacle translated by
    /// `c(t)`, `x̃_j − c(t)` with `x̃_j = Σ_k R_jk x_k` over a face that
    /// holds the node.
    pub(super) fn frictional_relative_position(&self, node: &SecondaryNode) -> Vector3<f64> {
        let Some(c) = self.source.obstacle_translation() else {
            return node.position();
        };
        let faces = self.surfaces.node_faces.get(node.index);
        let Some(&e) = faces.and_then(|f| f.first()) else {
            return node.position() - c;
        };
        let face = &self.surfaces.secondary_faces[e];
        let position = |k| current_position(node.reference, node.x, k);
        transformed_position(face, node.mesh_node, position) - c
    }

    /// The weights of the node's lever `B` (see the module docs, "Force"):
    /// `R_jk` on the secondary nodes, `−M_jl/D_j` on the primary ones.
    pub(super) fn frictional_lever_weights(
        &self,
        kinematics: &GapKinematics<Dyn>,
    ) -> Option<Vec<(usize, f64)>> {
        let row = self.node_row(kinematics.nodes[0])?;
        Some(lever_weights(row).collect())
    }

    /// `∂(−A Bᵀ t)/∂q` at fixed `t = traction / A`, `A = D_j` (see the
    /// module docs); `None` where the row was taken without its
    /// derivatives (a residual alone, which reads no stiffness).
    pub(super) fn frictional_lever_stiffness(
        &self,
        kinematics: &GapKinematics<Dyn>,
        traction: &Vector3<f64>,
    ) -> Option<DMatrix<f64>> {
        let j = kinematics.nodes[0];
        let row = self.node_row(j).filter(|row| row.has_derivatives())?;
        let t = traction / row.d;
        let q = kinematics.gradient.len();
        let columns = offsets(&kinematics.nodes, &row.nodes);
        let mut stiffness = DMatrix::zeros(q, q);
        let mut add = |n: usize, gradient: &nalgebra::DVector<f64>, scale: f64| {
            let at = offsets(&kinematics.nodes, &[n])[0];
            for (a, &c) in columns.iter().enumerate() {
                for i in 0..3 {
                    for k in 0..3 {
                        stiffness[(at + i, c + k)] += scale * t[i] * gradient[3 * a + k];
                    }
                }
            }
        };
        for (k, r) in &row.transformation {
            add(*k, &row.d_gradient, -r);
        }
        for ((l, _), g) in row.m.iter().zip(&row.m_gradients) {
            add(*l, g, 1.0);
        }
        Some(stiffness)
    }

    /// The stick stiffness at the current coupling scaled by the slip
    /// ratio `β`, `A β ε_T Bᵀ T B` (positive semi-definite), for the
    /// preconditioner of the frictional solve.
    pub(super) fn frictional_stick_stiffness(
        kinematics: &GapKinematics<Dyn>,
        frame: &SlipFrame<Dyn>,
        response: &TangentialResponse<Dyn>,
        law: &Coulomb,
        area: f64,
    ) -> DMatrix<f64> {
        let n = kinematics.normal;
        let projector = Matrix3::identity() - n * n.transpose();
        let lever = &frame.lever;
        let stiffness = area * response.stick_scale * law.tangential_penalty;
        stiffness * lever.transpose() * projector * lever
    }
}
