//! The contact fields of one converged increment, on every node of the
//! mesh: what the VTU files show (`contact_pressure`, `gap`,
//! `contact_status`, `contact_traction`, `slip` = `accumulated_slip`,
//! `slip_increment`) and the per-interface totals of `summary.json`, built
//! from the committed contact states (this increment's and the previous
//! one's) and the node reports of the converged evaluation.

use crate::contact::friction::ContactStatus;
use crate::contact::interface::{ContactInterface, NodeReport, Primary};
use crate::contact::kinematics::SecondaryNode;
use crate::contact::laws::NodeContactState;
use crate::contact::primary::PrimarySurface;
use crate::output::summary::InterfaceSummary;
use crate::problem::{ContactState, Problem};
use nalgebra::Vector3;

/// Nodal contact output of every interface, and its totals.
pub struct ContactFields {
    /// Contact pressure: at a node of a contact surface, the normal force
    /// that every interface puts on it (`A_s t_N` as a secondary node, the
    /// shares `N_i(ξ) A_s t_N` as a primary node) over its tributary area;
    /// `t_N` at the secondary nodes of one pass, the sum of the two passes'
    /// shares with `two_pass`. 0 elsewhere.
    pub pressure: Vec<f64>,
    /// The normal force and tributary area behind `pressure`.
    pub nodal_force: Vec<f64>,
    pub nodal_area: Vec<f64>,
    /// Signed gap at secondary nodes, NaN elsewhere.
    pub gap: Vec<f64>,
    /// 0 open, 1 stick (closed, without friction), 2 slip (0 away from
    /// contact surfaces).
    pub status: Vec<f64>,
    /// Traction on the body, `t_N n + t_T` (3 per node, 0 elsewhere):
    /// the nodal contact force of every pass until divided by `nodal_area`.
    pub traction: Vec<f64>,
    /// Whether the node is a secondary node of some interface (its own
    /// gap and slip then win over those seen from a primary side).
    pub secondary: Vec<bool>,
    /// Accumulated slip vector `Σ Δg_T^slip` over every increment so far
    /// (3 per node, 0 elsewhere): the `slip` and `accumulated_slip` arrays.
    pub slip: Vec<f64>,
    /// This increment's slip `Δg_T^slip = slip_n+1 − slip_n`, the
    /// accumulated slip committed now minus the one committed at the
    /// previous increment (3 per node, 0 elsewhere; 0 at a node that stuck
    /// or stayed open during the increment).
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
        mut reports: Vec<Vec<NodeReport>>,
    ) -> Self {
        let n = problem.model.mesh.num_nodes();
        let mut fields = ContactFields {
            pressure: vec![0.0; n],
            nodal_force: vec![0.0; n],
            nodal_area: vec![0.0; n],
            gap: vec![f64::NAN; n],
            status: vec![0.0; n],
            traction: vec![0.0; 3 * n],
            secondary: vec![false; n],
            slip: vec![0.0; 3 * n],
            slip_increment: vec![0.0; 3 * n],
            summaries: Default::default(),
            reports: Vec::new(),
        };
        if problem.contacts.is_empty() {
            return fields;
        }
        for (i, ((c, nodes), states)) in problem
            .contacts
            .iter()
            .zip(&mut reports)
            .zip(&contact.interfaces)
            .enumerate()
        {
            let before = previous.interfaces.get(i).map(Vec::as_slice);
            let increments: Vec<Vector3<f64>> = states
                .iter()
                .enumerate()
                .map(|(k, state)| {
                    let old = before
                        .and_then(|b| b.get(k))
                        .map_or_else(Vector3::zeros, |b| b.friction.slip);
                    state.friction.slip - old
                })
                .collect();
            let mut summary = InterfaceSummary::default();
            let mesh = &problem.model.mesh;
            #[allow(clippy::expect_used)]
            // an interface is built from this surface set of this mesh
            let set = mesh.surface(&c.surface).expect("validated");
            let (_, whole) = crate::contact::tributary_areas(mesh, set);
            for (((((&s, &area), r), state), &whole), increment) in c
                .nodes
                .iter()
                .zip(&c.areas)
                .zip(nodes.iter_mut())
                .zip(states)
                .zip(&whole)
                .zip(&increments)
            {
                // status and tangential traction as committed for this
                // increment (re-evaluated from the committed history, a
                // slipping node would sit exactly on the Coulomb cone and
                // may read as stick), for every consumer of the reports
                let history = &state.friction;
                r.status = history.status;
                r.tangential_traction = history.traction.into();
                fields.nodal_force[s] += area * r.pressure;
                fields.nodal_area[s] = whole;
                fields.gap[s] = r.gap;
                fields.secondary[s] = true;
                fields.status[s] = fields.status[s].max(history.status.code() as f64);
                for d in 0..3 {
                    summary.force[d] += r.force[d];
                    summary.tangential_force[d] += area * history.traction[d];
                    // a force here, a traction once every pass has added its share
                    fields.traction[3 * s + d] += r.force[d] + area * history.traction[d];
                    fields.slip[3 * s + d] = history.slip[d];
                    fields.slip_increment[3 * s + d] = increment[d];
                }
                match history.status {
                    ContactStatus::Open => {}
                    ContactStatus::Stick => summary.stick_nodes += 1,
                    ContactStatus::Slip => summary.slip_nodes += 1,
                }
                if r.active {
                    summary.closed_nodes += 1;
                    summary.area += area;
                }
                summary.largest_penetration = summary.largest_penetration.max(-r.gap);
            }
            if let Primary::Surface(p) = &c.primary {
                let secondary = SecondarySide {
                    states,
                    increments: &increments,
                    reports: nodes,
                };
                summary.primary_force = Some(fields.add_primary_side(problem, c, p, x, &secondary));
            }
            fields.summaries.insert(c.name.clone(), summary);
        }
        for (((p, f), t), a) in fields
            .pressure
            .iter_mut()
            .zip(&fields.nodal_force)
            .zip(fields.traction.chunks_exact_mut(3))
            .zip(&fields.nodal_area)
        {
            if *a > 0.0 {
                *p = f / a;
                t.iter_mut().for_each(|t| *t /= a);
            }
        }
        fields.reports = reports;
        fields
    }
}

/// What the primary side's fields read of an interface's secondary nodes:
/// their committed states, slip increments and reports.
struct SecondarySide<'a> {
    states: &'a [NodeContactState],
    increments: &'a [Vector3<f64>],
    reports: &'a [NodeReport],
}

impl ContactFields {
    /// The output fields on the nodes of a deformable primary surface:
    /// each secondary node's force `A_s (t_N n + t_T)` goes, opposite, to
    /// its triangle's nodes with the weights `w_i` of [`output_weights`]
    /// (`N_i(ξ)` clamped to `≥ 0` and renormalised; divided by the
    /// primary node's tributary area for `contact_pressure` and
    /// `contact_traction`); `contact_status` is the largest status of the
    /// closed secondary nodes over a primary node, `slip` and
    /// `slip_increment` minus theirs averaged with the weights `A_s N_i`
    /// and `gap` the primary node's
    /// distance to the secondary surface (projected on its triangles; NaN
    /// beyond its edge or farther than the search margin); a node that is itself secondary in another pass
    /// keeps its own gap and slip. Returns the total force on the primary
    /// surface.
    fn add_primary_side(
        &mut self,
        problem: &Problem,
        c: &ContactInterface,
        primary: &PrimarySurface,
        x: &[f64],
        secondary: &SecondarySide,
    ) -> [f64; 3] {
        let (states, increments, reports) =
            (secondary.states, secondary.increments, secondary.reports);
        let mesh = &problem.model.mesh;
        let reference = &mesh.nodes;
        let n_nodes = mesh.num_nodes();
        let mut normal = vec![0.0; n_nodes];
        let mut forces = vec![Vector3::zeros(); n_nodes];
        // (Σ w slip, Σ w slip increment, Σ w) over the closed nodes
        let mut slip = vec![(Vector3::zeros(), Vector3::zeros(), 0.0); n_nodes];
        let mut status = vec![0u8; n_nodes];
        let mut total = Vector3::zeros();
        for (((r, &area), state), increment) in
            reports.iter().zip(&c.areas).zip(states).zip(increments)
        {
            let Some(facet) = r.facet else {
                continue;
            };
            // the committed tangential traction, as on the secondary side
            let history = &state.friction;
            let force = -(Vector3::from(r.force) + area * history.traction);
            for (&n, &weight) in primary.triangles[facet]
                .iter()
                .zip(&output_weights(r.weights))
            {
                normal[n] += area * r.pressure * weight;
                forces[n] += force * weight;
                // the closed nodes over the primary node, by their weights
                if r.active && weight > 0.0 {
                    slip[n].0 -= history.slip * (area * weight);
                    slip[n].1 -= increment * (area * weight);
                    slip[n].2 += area * weight;
                    status[n] = status[n].max(history.status.code());
                }
            }
            total += force;
        }
        #[allow(clippy::expect_used)]
        // a primary surface is built from this surface set of this mesh
        let set = mesh.surface(&primary.surface).expect("validated");
        let (nodes, areas) = crate::contact::tributary_areas(mesh, set);
        // the other way round, for the gap: the primary nodes against the
        // secondary surface's triangles
        #[allow(clippy::expect_used)] // the secondary surface set exists (as above)
        let mut reverse = PrimarySurface::from_mesh(mesh, &c.surface).expect("validated");
        reverse.refresh(reference, x, &nodes, 0.0);
        for (k, (&n, &a)) in nodes.iter().zip(&areas).enumerate() {
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
                let here = SecondaryNode {
                    reference,
                    x,
                    index: k,
                    mesh_node: n,
                };
                if let Some((_, g)) = reverse.nearest_gap(&here) {
                    self.gap[n] = g.gap;
                }
            }
        }
        total.into()
    }
}

/// The weights with which the output spreads a secondary node's force onto
/// its primary triangle's nodes:
/// `w_i = max(N_i(ξ), 0) / Σ_j max(N_j(ξ), 0)`.
///
/// A secondary node just outside its triangle (kept there by the sticky
/// band of [`PrimarySurface`], up to 5 % beyond an edge) has a weight
/// `N_i(ξ) < 0` on the far node, and its share `N_i A_s t_N` of a force
/// pushing the bodies apart would read as a pull (a negative
/// `contact_pressure`, measured down to −0.125 against a peak of 78.7 on
/// nine edge nodes of `examples/two-spheres`). Clamped and renormalised,
/// every share has the sign of `t_N ≥ 0` and the shares still sum to the
/// node's force (`Σ_i w_i = 1`), so the primary side's total stays exactly
/// minus the secondary side's. The output only: the assembly keeps the
/// exact `N_i(ξ)` (the tangent is consistent with them), so the solution
/// does not change. `Σ_j max(N_j, 0) ≥ Σ_j N_j = 1` never vanishes.
fn output_weights(n: [f64; 3]) -> [f64; 3] {
    let clamped = n.map(|w| w.max(0.0));
    let sum: f64 = clamped.iter().sum();
    clamped.map(|w| w / sum)
}
