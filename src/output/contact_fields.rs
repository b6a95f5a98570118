//! The contact fields of one converged increment, on every node of the
//! mesh: what the VTU files show (`contact_pressure`, `gap`,
//! `contact_status`, `contact_traction`, `slip` = `accumulated_slip`,
//! `slip_increment`) and the per-interface totals of `summary.json`. They
//! are what contact reports ([`ContactSet::report`](crate::contact::set::ContactSet),
//! `src/contact/report.rs`: the node driver's reports of the converged
//! evaluation and the committed states); nothing here measures geometry.

use crate::contact::interface::NodeReport;
use crate::contact::report::{ContactReport, InterfaceTotals};
use crate::output::summary::InterfaceSummary;
use crate::problem::{ContactState, Problem};

/// Nodal contact output of every interface, and its totals.
pub struct ContactFields {
    /// Contact pressure: at a node of a contact surface, the normal force
    /// that every interface puts on it (`A_s t_N` as a secondary node, the
    /// shares `w_i A_s t_N` as a primary node) over its tributary area;
    /// `t_N` at the secondary nodes of one pass, the sum of the two passes'
    /// shares with `two_pass`. 0 elsewhere.
    pub pressure: Vec<f64>,
    /// The normal force and tributary area behind `pressure`.
    pub nodal_force: Vec<f64>,
    pub nodal_area: Vec<f64>,
    /// Signed gap at the nodes of contact surfaces, NaN elsewhere.
    pub gap: Vec<f64>,
    /// 0 open, 1 stick (closed, without friction), 2 slip (0 away from
    /// contact surfaces).
    pub status: Vec<f64>,
    /// Traction on the body, `t_N n + t_T` (3 per node, 0 elsewhere).
    pub traction: Vec<f64>,
    /// Whether the node is a secondary node of some interface (its own
    /// gap and slip then win over those seen from a primary side).
    pub secondary: Vec<bool>,
    /// Accumulated slip vector `Σ Δg_T^slip` over every increment so far
    /// (3 per node, 0 elsewhere): the `slip` and `accumulated_slip` arrays.
    pub slip: Vec<f64>,
    /// This increment's slip `Δg_T^slip = slip_n+1 − slip_n` (3 per node,
    /// 0 elsewhere; 0 at a node that stuck or stayed open).
    pub slip_increment: Vec<f64>,
    pub summaries: std::collections::BTreeMap<String, InterfaceSummary>,
    /// Every secondary node of every interface.
    pub reports: Vec<Vec<NodeReport>>,
}

impl ContactFields {
    /// The fields at unknowns `x` with the committed states `contact`, the
    /// states committed at the previous increment `previous` (an empty
    /// state, e.g. [`ContactState::default`], before the first: no slip
    /// before it) and the node `reports` of the converged evaluation there
    /// (one list per interface).
    pub fn new(
        problem: &Problem,
        x: &[f64],
        contact: &ContactState,
        previous: &ContactState,
        reports: Vec<Vec<NodeReport>>,
    ) -> Self {
        let reference = &problem.model.mesh.nodes;
        let ContactReport {
            nodal,
            totals,
            nodes,
        } = problem
            .contacts
            .report(reference, x, contact, previous, reports);
        ContactFields {
            pressure: nodal.pressure,
            nodal_force: nodal.nodal_force,
            nodal_area: nodal.nodal_area,
            gap: nodal.gap,
            status: nodal.status,
            traction: nodal.traction,
            secondary: nodal.secondary,
            slip: nodal.slip,
            slip_increment: nodal.slip_increment,
            summaries: totals
                .into_iter()
                .map(|(name, t)| (name, summary(&t)))
                .collect(),
            reports: nodes,
        }
    }
}

/// An interface's totals as `summary.json` writes them.
fn summary(t: &InterfaceTotals) -> InterfaceSummary {
    InterfaceSummary {
        force: t.force,
        tangential_force: t.tangential_force,
        stick_nodes: t.stick_nodes,
        slip_nodes: t.slip_nodes,
        area: t.area,
        closed_nodes: t.closed_nodes,
        largest_penetration: t.largest_penetration,
        primary_force: t.primary_force,
    }
}
