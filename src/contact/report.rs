//! What contact reports of one converged increment, on every node of the
//! mesh and per interface, from the node driver's own visit: the
//! [`NodeReport`]s of the converged evaluation (gap, pressure, force and the
//! primary nodes of each reaction with their weights) and the committed
//! states (status, tangential traction, slip).
//!
//! - **Secondary nodes**: `A_s t_N n` and `A_s t_T` on the node, divided by
//!   its whole tributary area ([`ContactInterface::report_areas`]; a
//!   two-pass interface assembles on half of it) for the pressure and the
//!   traction; its own gap, status and slip.
//! - **Mortar totals**: `force` and `tangential_force` are the forces as
//!   assembled, `Σ D_j λ_j n_j` and `Σ D_j t_T` on the current `D_j`
//!   ([`NodeReport::area`]; the nodal fields keep the reference areas), and
//!   `primary_force` their counterpart through `M`
//!   ([`mortar_primary_force`]); the primary surface's nodal fields are
//!   not filled.
//! - **Primary nodes** (deformable interfaces): each secondary node's force
//!   `A_s (t_N n + t_T)` goes, opposite, to the primary nodes of its
//!   reaction with the weights `w_i` of [`report_weights`], divided by the
//!   primary node's tributary area ([`PrimarySurface::node_areas`]); the
//!   status is the largest of the closed secondary nodes over it, the slip
//!   minus theirs averaged with the weights `A_s w_i`, the gap the primary
//!   node's distance to the secondary surface
//!   ([`ContactInterface::secondary_surface`]; NaN beyond its edge or
//!   farther than the search margin). A node that is itself secondary in
//!   another pass keeps its own gap and slip.
//!
//! Every interface adds its share; the pressure and traction are divided by
//! the area once every interface has added its force.

use super::friction::ContactStatus;
use super::interface::{ContactInterface, NodeReport, Primary};
use super::kinematics::SecondaryNode;
use super::laws::NodeContactState;
use super::primary::PrimarySurface;
use super::set::{ContactSet, ContactState};
use nalgebra::Vector3;

/// The contact values of every mesh node (3 per node for vectors; 0 away
/// from contact surfaces, NaN for the gap).
#[derive(Clone, Debug, Default)]
pub struct NodalContact {
    /// Normal force over tributary area (`t_N` at the secondary nodes of
    /// one pass; the sum of the two passes' shares with `two_pass`).
    pub pressure: Vec<f64>,
    /// The normal force and tributary area behind `pressure`.
    pub nodal_force: Vec<f64>,
    pub nodal_area: Vec<f64>,
    /// Signed gap.
    pub gap: Vec<f64>,
    /// 0 open, 1 stick (closed, without friction), 2 slip.
    pub status: Vec<f64>,
    /// Traction on the body, `t_N n + t_T`.
    pub traction: Vec<f64>,
    /// Whether the node is a secondary node of some interface.
    pub secondary: Vec<bool>,
    /// Accumulated slip `Σ Δg_T^slip`.
    pub slip: Vec<f64>,
    /// This increment's slip, `slip_n+1 − slip_n`.
    pub slip_increment: Vec<f64>,
}

/// The totals of one interface.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct InterfaceTotals {
    /// `Σ A_s t_N n` on the body.
    pub force: [f64; 3],
    /// `Σ A_s t_T` on the body (mortar: `Σ D_j t_T`, the current `D_j`
    /// the force is assembled on, [`NodeReport::area`]).
    pub tangential_force: [f64; 3],
    /// Closed nodes that stick (every closed node without friction) and
    /// that slip.
    pub stick_nodes: usize,
    pub slip_nodes: usize,
    /// `Σ A_s` over the closed nodes.
    pub area: f64,
    pub closed_nodes: usize,
    /// `max(0, −g)` over the secondary nodes.
    pub largest_penetration: f64,
    /// The total force on a deformable primary surface,
    /// `−Σ A_s (t_N n + t_T) w_i` (mortar: [`mortar_primary_force`];
    /// `None` against a rigid obstacle).
    pub primary_force: Option<[f64; 3]>,
    /// Why contact could not be evaluated on part of the interface at
    /// this state (mortar: a face pair that cannot be integrated leaves
    /// every node open, [`MortarSurfaces::integration_failure`](super::mortar_contact::MortarSurfaces::integration_failure)).
    pub warning: Option<String>,
}

/// What contact reports of a converged increment.
#[derive(Clone, Debug, Default)]
pub struct ContactReport {
    pub nodal: NodalContact,
    /// Per interface, in the set's order: its name and totals.
    pub totals: Vec<(String, InterfaceTotals)>,
    /// Every secondary node of every interface, with the status and
    /// tangential traction as committed.
    pub nodes: Vec<Vec<NodeReport>>,
}

impl ContactSet {
    /// The report at unknowns `x` (reference coordinates `reference`) with
    /// the committed states `contact`, those committed at the previous
    /// increment `previous` (empty before the first: no slip before it) and
    /// the node `reports` of the converged evaluation (one list per
    /// interface). See the module docs.
    pub fn report(
        &self,
        reference: &[[f64; 3]],
        x: &[f64],
        contact: &ContactState,
        previous: &ContactState,
        mut reports: Vec<Vec<NodeReport>>,
    ) -> ContactReport {
        let mut nodal = NodalContact::new(reference.len());
        let mut totals = Vec::new();
        for (i, ((c, nodes), states)) in self
            .interfaces
            .iter()
            .zip(&mut reports)
            .zip(&contact.interfaces)
            .enumerate()
        {
            let before = previous.interfaces.get(i).map(Vec::as_slice);
            let increments = slip_increments(states, before);
            let mut sum = nodal.add_secondary_side(c, nodes, states, &increments);
            match &c.primary {
                Primary::Surface(p) => {
                    let side = SecondarySide {
                        states,
                        increments: &increments,
                        reports: nodes,
                    };
                    sum.primary_force = Some(nodal.add_primary_side(reference, x, c, p, &side));
                }
                Primary::Mortar(m) => {
                    sum.primary_force = Some(mortar_primary_force(c, nodes, states));
                    sum.warning = m
                        .integration_failure(reference, x)
                        .map(|why| format!("contact '{}': {why}", c.name));
                }
                Primary::Rigid(_) | Primary::MortarRigid(_) => {}
            }
            totals.push((c.name.clone(), sum));
        }
        nodal.divide_by_areas();
        ContactReport {
            nodal,
            totals,
            nodes: reports,
        }
    }
}

/// The total force on a mortar interface's primary surface: each
/// secondary node `j`'s forces as assembled on the primary nodes `l`,
/// `−(M_jl/D_j) (D_j λ_j n_j + D_j t_T,j)` (the weights `M_jl/D_j` of its
/// report, unclamped; the committed traction as on the secondary side),
/// summed. It is minus the secondary side's `force + tangential_force`
/// where every closed node is fully covered, `Σ_l M_jl = D_j` (Newton's
/// third law through `M`; a node only partly over the primary surface
/// has `Σ_l M_jl < D_j`).
fn mortar_primary_force(
    c: &ContactInterface,
    reports: &[NodeReport],
    states: &[NodeContactState],
) -> [f64; 3] {
    let mut total = Vector3::zeros();
    for (k, (r, state)) in reports.iter().zip(states).enumerate() {
        let weight: f64 = r.primary.iter().map(|(_, w)| w).sum();
        let area = r.area.unwrap_or(c.areas[k]);
        total -= (Vector3::from(r.force) + area * state.friction.traction) * weight;
    }
    total.into()
}

/// Each node's slip of this increment, the accumulated slip in `states`
/// minus the one in `before` (zero where there is none).
fn slip_increments(
    states: &[NodeContactState],
    before: Option<&[NodeContactState]>,
) -> Vec<Vector3<f64>> {
    states
        .iter()
        .enumerate()
        .map(|(k, state)| {
            let old = before
                .and_then(|b| b.get(k))
                .map_or_else(Vector3::zeros, |b| b.friction.slip);
            state.friction.slip - old
        })
        .collect()
}

/// What the primary side reads of an interface's secondary nodes: their
/// committed states, slip increments and reports.
struct SecondarySide<'a> {
    states: &'a [NodeContactState],
    increments: &'a [Vector3<f64>],
    reports: &'a [NodeReport],
}

impl NodalContact {
    /// No contact on any of `n` nodes.
    fn new(n: usize) -> Self {
        NodalContact {
            pressure: vec![0.0; n],
            nodal_force: vec![0.0; n],
            nodal_area: vec![0.0; n],
            gap: vec![f64::NAN; n],
            status: vec![0.0; n],
            traction: vec![0.0; 3 * n],
            secondary: vec![false; n],
            slip: vec![0.0; 3 * n],
            slip_increment: vec![0.0; 3 * n],
        }
    }

    /// Add the secondary nodes of interface `c` (their `reports`, committed
    /// `states` and slip `increments`); the interface's totals. The
    /// reports take the committed status and tangential traction
    /// (re-evaluated from the committed history, a slipping node would sit
    /// exactly on the Coulomb cone and may read as stick).
    fn add_secondary_side(
        &mut self,
        c: &ContactInterface,
        reports: &mut [NodeReport],
        states: &[NodeContactState],
        increments: &[Vector3<f64>],
    ) -> InterfaceTotals {
        let mut sum = InterfaceTotals::default();
        for (k, (r, state)) in reports.iter_mut().zip(states).enumerate() {
            let (s, area, increment) = (c.nodes[k], c.areas[k], increments[k]);
            // the area the assembled tangential force acts on (mortar: D_j)
            let applied = r.area.unwrap_or(area);
            let history = &state.friction;
            r.status = history.status;
            r.tangential_traction = history.traction.into();
            self.nodal_force[s] += area * r.pressure;
            self.nodal_area[s] = c.report_areas[k];
            self.gap[s] = r.gap;
            self.secondary[s] = true;
            self.status[s] = self.status[s].max(history.status.code() as f64);
            for d in 0..3 {
                sum.force[d] += r.force[d];
                sum.tangential_force[d] += applied * history.traction[d];
                // a force here, a traction once every pass has added its share
                self.traction[3 * s + d] += r.force[d] + area * history.traction[d];
                self.slip[3 * s + d] = history.slip[d];
                self.slip_increment[3 * s + d] = increment[d];
            }
            match history.status {
                ContactStatus::Open => {}
                ContactStatus::Stick => sum.stick_nodes += 1,
                ContactStatus::Slip => sum.slip_nodes += 1,
            }
            if r.active {
                sum.closed_nodes += 1;
                sum.area += area;
            }
            sum.largest_penetration = sum.largest_penetration.max(-r.gap);
        }
        sum
    }

    /// Add the nodes of interface `c`'s primary surface `primary` (see the
    /// module docs); the total force on it.
    fn add_primary_side(
        &mut self,
        reference: &[[f64; 3]],
        x: &[f64],
        c: &ContactInterface,
        primary: &PrimarySurface,
        secondary: &SecondarySide,
    ) -> [f64; 3] {
        let n_nodes = reference.len();
        let mut normal = vec![0.0; n_nodes];
        let mut forces = vec![Vector3::zeros(); n_nodes];
        // (Σ w slip, Σ w slip increment, Σ w) over the closed nodes
        let mut slip = vec![(Vector3::zeros(), Vector3::zeros(), 0.0); n_nodes];
        let mut status = vec![0u8; n_nodes];
        let mut total = Vector3::zeros();
        let sides = secondary.reports.iter().zip(secondary.states);
        for (k, (r, state)) in sides.enumerate() {
            if r.primary.is_empty() {
                continue;
            }
            let area = c.areas[k];
            // the committed tangential traction, as on the secondary side
            let history = &state.friction;
            let force = -(Vector3::from(r.force) + area * history.traction);
            for (n, weight) in report_weights(&r.primary) {
                normal[n] += area * r.pressure * weight;
                forces[n] += force * weight;
                // the closed nodes over the primary node, by their weights
                if r.active && weight > 0.0 {
                    slip[n].0 -= history.slip * (area * weight);
                    slip[n].1 -= secondary.increments[k] * (area * weight);
                    slip[n].2 += area * weight;
                    status[n] = status[n].max(history.status.code());
                }
            }
            total += force;
        }
        let gaps = c.primary_gaps(reference, x);
        for (k, (&n, &a)) in primary.nodes.iter().zip(&primary.node_areas).enumerate() {
            self.nodal_force[n] += normal[n];
            self.nodal_area[n] = a;
            let (slip_sum, increment_sum, weight) = slip[n];
            for (d, force) in forces[n].iter().enumerate() {
                self.traction[3 * n + d] += force;
                if weight > 0.0 && !self.secondary[n] {
                    self.slip[3 * n + d] = slip_sum[d] / weight;
                    self.slip_increment[3 * n + d] = increment_sum[d] / weight;
                }
            }
            self.status[n] = self.status[n].max(status[n] as f64);
            if !self.secondary[n] {
                if let Some(g) = gaps[k] {
                    self.gap[n] = g;
                }
            }
        }
        total.into()
    }

    /// Pressure and traction: the summed forces over the nodes' areas.
    fn divide_by_areas(&mut self) {
        for (((p, f), t), a) in self
            .pressure
            .iter_mut()
            .zip(&self.nodal_force)
            .zip(self.traction.chunks_exact_mut(3))
            .zip(&self.nodal_area)
        {
            if *a > 0.0 {
                *p = f / a;
                t.iter_mut().for_each(|t| *t /= a);
            }
        }
    }
}

impl ContactInterface {
    /// The gap of each node of the primary surface (in the order of its
    /// `nodes`) against the secondary surface at unknowns `x`: the reverse
    /// projection, `None` beyond the secondary surface's edge or farther
    /// than its search margin, and for a rigid obstacle (no nodes).
    pub fn primary_gaps(&self, reference: &[[f64; 3]], x: &[f64]) -> Vec<Option<f64>> {
        let (Primary::Surface(primary), Some(surface)) = (&self.primary, &self.secondary_surface)
        else {
            return Vec::new();
        };
        let mut reverse = surface.clone();
        reverse.refresh(reference, x, &primary.nodes, 0.0, None);
        let gap = |(k, &n)| {
            let here = SecondaryNode {
                reference,
                x,
                index: k,
                mesh_node: n,
            };
            reverse.nearest_gap(&here).map(|(_, g)| g.gap)
        };
        primary.nodes.iter().enumerate().map(gap).collect()
    }
}

/// The weights with which the report spreads a secondary node's force onto
/// the primary nodes of its reaction:
/// `w_i = max(N_i, 0) / Σ_j max(N_j, 0)`.
///
/// A secondary node just outside its triangle (kept there by the sticky
/// band of [`PrimarySurface`], up to 5 % beyond an edge) has a weight
/// `N_i(ξ) < 0` on the far node, and its share `N_i A_s t_N` of a force
/// pushing the bodies apart would read as a pull (a negative
/// `contact_pressure`, measured down to −0.125 against a peak of 78.7 on
/// nine edge nodes of `examples/two-spheres`). Clamped and renormalised,
/// every share has the sign of `t_N ≥ 0` and the shares still sum to the
/// node's force (`Σ_i w_i = 1`), so the primary side's total stays exactly
/// minus the secondary side's. The report only: the assembly keeps the
/// exact weights (the tangent is consistent with them), so the solution
/// does not change. With weights that sum to 1, `Σ_j max(N_j, 0) ≥ 1`
/// never vanishes.
pub fn report_weights(n: &[(usize, f64)]) -> impl Iterator<Item = (usize, f64)> + '_ {
    let sum: f64 = n.iter().map(|(_, w)| w.max(0.0)).sum();
    n.iter().map(move |&(i, w)| (i, w.max(0.0) / sum))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Clamped and renormalised: no negative share, the shares sum to 1.
    #[test]
    fn report_weights_clamp_and_sum_to_one() {
        let w: Vec<(usize, f64)> = report_weights(&[(4, 1.03), (7, -0.05), (9, 0.02)]).collect();
        assert_eq!(w.iter().map(|p| p.0).collect::<Vec<_>>(), [4, 7, 9]);
        assert!((w[0].1 - 1.03 / 1.05).abs() < 1e-15 && w[1].1 == 0.0);
        assert!((w.iter().map(|p| p.1).sum::<f64>() - 1.0).abs() < 1e-15);
    }
}
