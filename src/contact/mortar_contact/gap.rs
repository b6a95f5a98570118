//! The mortar gap producer of the node driver ([`MortarGap`]): the rows of
//! [`MortarSurfaces`] (or of a rigid obstacle's [`RowSource`]) in one
//! configuration, read as each secondary node's gap kinematics.

use super::{coordinates, MortarRows, MortarSurfaces};
use crate::contact::friction::{Coulomb, FrictionHistory, TangentialResponse};
use crate::contact::kinematics::{
    CoupledNodes, GapKinematics, GapProducer, PrimaryWeights, SecondaryNode, SlipFrame,
};
use crate::contact::laws::NodeContactState;
use crate::contact::mortar::{Derivatives, MortarRow};
use nalgebra::{DMatrix, DVector, Dyn, OMatrix, Vector3, U3};
use std::collections::{BTreeMap, BTreeSet};
use std::sync::{Arc, OnceLock};

/// The mortar gap producer in one configuration: every secondary node's
/// row of the coupling ([`mortar_rows`](crate::contact::mortar::mortar_rows): `g̃_j`, `D_j`, `M_jl`, `n_j`, the
/// lever and their complete first derivatives), integrated there (or taken
/// from [`MortarSurfaces::rows_at`]'s cache) when an operation first asks
/// for a node's kinematics; the gaps alone ([`GapProducer::gap`]) from the
/// rows' values without their derivatives where the rows are not there
/// ([`RowSource::gaps`]).
pub struct MortarGap<'a> {
    pub surfaces: &'a MortarSurfaces,
    pub(in crate::contact) source: Box<dyn RowSource + 'a>,
    /// What the operation reads of the rows: their values alone (the
    /// kinematics' gradients then zero: a residual without its tangent,
    /// frictionless) or their derivatives too.
    derivatives: Derivatives,
    rows: OnceLock<Arc<MortarRows>>,
    gaps: OnceLock<BTreeMap<usize, f64>>,
}

/// Where a [`MortarGap`] takes what it reads in its configuration: the
/// deformable primary surface ([`SurfaceRows`]) or a rigid obstacle
/// ([`MortarObstacle`](crate::contact::mortar_rigid::MortarObstacle)'s source).
pub(crate) trait RowSource {
    /// The rows with their derivatives or without, from the surfaces' row
    /// cache or integrated (then kept there).
    fn rows(&self, derivatives: Derivatives) -> Arc<MortarRows>;

    /// The normalised gap `g̃_j / D_j` of every node with a row (mesh node
    /// to gap), from the same sums as [`rows`](Self::rows)' values without
    /// their derivatives: from the cache where this configuration's rows
    /// are there (not counted), else evaluated (counted as values,
    /// [`RowCounts::values`]).
    fn gaps(&self) -> BTreeMap<usize, f64>;

    /// Against a rigid obstacle, its translation `c(t)` in this
    /// configuration; `None` between bodies.
    fn obstacle_translation(&self) -> Option<Vector3<f64>> {
        None
    }
}

/// The normalised gaps `g̃_j / D_j` of `rows` where `D_j > 0` (the nodes
/// [`MortarGap::node_row`] gives).
pub(crate) fn row_gaps(rows: &MortarRows) -> BTreeMap<usize, f64> {
    (rows.iter())
        .filter(|(_, r)| r.d > 0.0)
        .map(|(&n, r)| (n, r.weighted_gap / r.d))
        .collect()
}

/// The deformable mortar surfaces at the nodes' current coordinates.
/// With `near`, the rows of those secondary mesh nodes alone
/// ([`MortarSurfaces::rows_near`]).
struct SurfaceRows<'a> {
    surfaces: &'a MortarSurfaces,
    xs: Vec<Vector3<f64>>,
    near: Option<BTreeSet<usize>>,
}

impl RowSource for SurfaceRows<'_> {
    fn rows(&self, derivatives: Derivatives) -> Arc<MortarRows> {
        match &self.near {
            Some(near) => Arc::new(self.surfaces.rows_near(&self.xs, near, derivatives)),
            None => self.surfaces.rows_at_coordinates(&self.xs, derivatives),
        }
    }

    /// [`MortarSurfaces::covered_gaps`] over the candidate pairs: the
    /// covered rows' values ([`mortar_row_values`], the rows' sums to the
    /// bit), none where a face cannot be integrated (as the rows).
    fn gaps(&self) -> BTreeMap<usize, f64> {
        if self.near.is_some() {
            return row_gaps(&self.rows(Derivatives::Without));
        }
        if let Some(rows) = self.surfaces.cached(&self.xs, &[]) {
            return row_gaps(&rows);
        }
        self.surfaces.count_values();
        let pairs = self.surfaces.pairs();
        (self.surfaces.covered_gaps(&pairs, &self.xs)).unwrap_or_default()
    }
}

impl<'a> MortarGap<'a> {
    /// The producer at unknowns `x`, reading the rows with `derivatives`
    /// or without. A face the kernels cannot integrate (degenerate, or a
    /// projection that fails) leaves every node open in this evaluation;
    /// the element assembly reports such a face's element.
    pub fn at(
        surfaces: &'a MortarSurfaces,
        reference: &[[f64; 3]],
        x: &[f64],
        derivatives: Derivatives,
    ) -> Self {
        Self::near(surfaces, reference, x, derivatives, None)
    }

    /// [`at`](Self::at), with `near` the rows of those secondary mesh
    /// nodes alone (the others have none, as nodes beyond the surface).
    pub fn near(
        surfaces: &'a MortarSurfaces,
        reference: &[[f64; 3]],
        x: &[f64],
        derivatives: Derivatives,
        near: Option<BTreeSet<usize>>,
    ) -> Self {
        let xs = coordinates(reference, x);
        let source = Box::new(SurfaceRows { surfaces, xs, near });
        Self::from_source(surfaces, source, derivatives)
    }

    /// The producer over `surfaces` reading `source`, with `derivatives`
    /// or without.
    pub(crate) fn from_source(
        surfaces: &'a MortarSurfaces,
        source: Box<dyn RowSource + 'a>,
        derivatives: Derivatives,
    ) -> Self {
        Self {
            surfaces,
            source,
            derivatives,
            rows: OnceLock::new(),
            gaps: OnceLock::new(),
        }
    }

    /// The rows of this configuration (taken at the first call).
    pub fn rows(&self) -> &MortarRows {
        self.rows.get_or_init(|| self.source.rows(self.derivatives))
    }

    /// Mesh node `j`'s row: the one place that gathers it; `None` where
    /// `D_j ≤ 0` or where less than half of `∫ Ñ_j dA` over its faces is
    /// covered by the primary surface (see the module docs, "Search").
    pub fn node_row(&self, j: usize) -> Option<&MortarRow> {
        self.rows().get(&j).filter(|row| row.d > 0.0)
    }

    /// The node's kinematics from its `row` (see the module docs): `q`
    /// over the node first, then the other coupled nodes in `row`'s order;
    /// every gradient zero where the row has no derivatives
    /// ([`MortarRow::has_derivatives`]).
    pub fn row_kinematics(&self, j: usize, row: &MortarRow) -> GapKinematics<Dyn> {
        let me = row.nodes.iter().position(|&n| n == j).unwrap_or(0);
        // q's order: j first, then row.nodes without j
        let order: Vec<usize> = std::iter::once(me)
            .chain((0..row.nodes.len()).filter(|&a| a != me))
            .collect();
        let dofs: Vec<usize> = order
            .iter()
            .flat_map(|&a| (0..3).map(move |c| 3 * a + c))
            .collect();
        let nodes: CoupledNodes = order.iter().map(|&a| row.nodes[a]).collect();
        let d = row.d;
        let gap = row.weighted_gap / d;
        let lever = -row.lever.select_rows(&dofs) / d;
        let q = dofs.len();
        let (gradient, hessian, area_gradient, normal_gradient) = if row.has_derivatives() {
            // ∇g = (∇g̃ − g ∇D)/D, ∂lever at constant area −∂b/D
            let full = (&row.weighted_gap_gradient - gap * &row.d_gradient) / d;
            (
                full.select_rows(&dofs),
                -row.lever_gradient.select_rows(&dofs).select_columns(&dofs) / d,
                row.d_gradient.select_rows(&dofs),
                -row.normal_gradient.select_columns(&dofs),
            )
        } else {
            let zero = DVector::zeros(q);
            (
                zero.clone(),
                DMatrix::zeros(q, q),
                zero,
                DMatrix::zeros(3, q),
            )
        };
        GapKinematics {
            primary: row
                .m
                .iter()
                .map(|(l, m)| (*l, m / d))
                .collect::<PrimaryWeights>(),
            nodes,
            gap,
            gradient,
            lever: Some(lever),
            hessian,
            area: Some(d),
            area_gradient: Some(area_gradient),
            normal: -row.normal,
            normal_gradient: OMatrix::<f64, U3, Dyn>::from_iterator_generic(
                U3,
                Dyn(dofs.len()),
                normal_gradient.iter().copied(),
            ),
            facet: None,
            point: (),
        }
    }
}

impl GapProducer<Dyn> for MortarGap<'_> {
    type Point = ();

    /// The node's row at fixed `D`, `M`, carried to its unknowns; `None`
    /// without a segment (`D_j ≤ 0`).
    fn kinematics(
        &self,
        node: &SecondaryNode,
        _state: &NodeContactState,
    ) -> Option<GapKinematics<Dyn>> {
        let row = self.node_row(node.mesh_node)?;
        let kinematics = self.row_kinematics(node.mesh_node, row);
        Some(self.with_committed_nodes(node.mesh_node, kinematics))
    }

    /// `g̃_j / D_j` of the node's row without the row's derivatives:
    /// from the rows where an operation took them in this configuration,
    /// else from [`RowSource::gaps`] (evaluated once per producer).
    fn gap(&self, node: &SecondaryNode, _state: &NodeContactState) -> Option<f64> {
        if self.rows.get().is_some() {
            return (self.node_row(node.mesh_node)).map(|r| r.weighted_gap / r.d);
        }
        let gaps = self.gaps.get_or_init(|| self.source.gaps());
        gaps.get(&node.mesh_node).copied()
    }

    fn open_gap(&self) -> f64 {
        self.surfaces.margin
    }

    /// `x_s` between bodies, `x̃_j − c(t)` against a rigid obstacle
    /// ([`mortar_friction`](crate::contact::mortar_friction), "Against a rigid
    /// obstacle").
    fn relative_position(&self, node: &SecondaryNode) -> Vector3<f64> {
        self.frictional_relative_position(node)
    }

    /// The weighted slip, the committed traction and the mortar lever
    /// ([`mortar_friction`](crate::contact::mortar_friction)).
    fn slip(
        &self,
        node: &SecondaryNode,
        kinematics: &mut GapKinematics<Dyn>,
        history: &FrictionHistory,
    ) -> SlipFrame<Dyn> {
        self.frictional_slip(node, kinematics, history)
    }

    fn lever_stiffness(
        &self,
        kinematics: &GapKinematics<Dyn>,
        traction: &Vector3<f64>,
    ) -> Option<DMatrix<f64>> {
        self.frictional_lever_stiffness(kinematics, traction)
    }

    /// `R_jk` on the secondary nodes, `−M_jl/D_j` on the primary ones
    /// ([`mortar_friction`](crate::contact::mortar_friction), "Force").
    fn lever_weights(&self, kinematics: &GapKinematics<Dyn>) -> Option<Vec<(usize, f64)>> {
        self.frictional_lever_weights(kinematics)
    }

    fn stick_stiffness(
        &self,
        kinematics: &GapKinematics<Dyn>,
        frame: &SlipFrame<Dyn>,
        response: &TangentialResponse<Dyn>,
        law: &Coulomb,
        area: f64,
    ) -> DMatrix<f64> {
        Self::frictional_stick_stiffness(kinematics, frame, response, law, area)
    }
}
