//! The contact fields of one converged increment, on every node of the
//! mesh: what the VTU files show (`contact_pressure`, `gap`,
//! `contact_status`, `contact_traction`, `slip` = `accumulated_slip`,
//! `slip_increment`) and the per-interface totals of `summary.json`. They
//! are what contact reports ([`ContactSet::report`](crate::contact::set::ContactSet),
//! `src/contact/report.rs`: the node driver's reports of the converged
//! evaluation and the committed states); nothing here measures geometry.

use crate::contact::interface::NodeReport;
use crate::contact::report::{ContactReport, InterfaceTotals, NodalContact};
use crate::output::summary::InterfaceSummary;
use crate::problem::{ContactState, Problem};

/// Nodal contact output of every interface, and its totals.
pub struct ContactFields {
    /// The nodal values as contact reports them: pressure (at a node of a
    /// contact surface, the normal force every interface puts on it over
    /// its tributary area; the sum of the two passes' shares with
    /// `two_pass`), gap (NaN away from contact surfaces), status, traction,
    /// accumulated slip and this increment's slip (3 per node for vectors,
    /// 0 away from contact surfaces).
    pub nodal: NodalContact,
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
            nodal,
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
        warning: t.warning.clone(),
    }
}
