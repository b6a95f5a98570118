//! [`Problem`] as the solver sees it: `impl NonlinearProblem`, whose
//! history is the contact state and whose reports are every interface's
//! nodes. Each method calls the problem's own.

use super::{ContactState, Problem, SolverSettings, Step};
use crate::assembly::pattern::SparsityPattern;
use crate::assembly::ElementFailure;
use crate::contact::interface::NodeReport;
use crate::solve::failure::IncrementFailure;
use crate::solve::nonlinear::{Evaluation, Linearisation, NonlinearProblem};

impl Problem {
    /// An element failure as a failed increment, with the element's mesh id.
    pub fn element_failure(&self, f: &ElementFailure) -> IncrementFailure {
        IncrementFailure::InvertedElement {
            element: self.model.mesh.elements[f.element].id,
            failure: f.failure,
        }
    }
}

/// The boundary-value problem as Newton and the stepper see it: the
/// history is the contact state, the reports are every interface's nodes.
impl NonlinearProblem for Problem {
    type State = ContactState;
    type Report = Vec<Vec<NodeReport>>;

    fn settings(&self) -> &SolverSettings {
        &self.settings
    }
    fn steps(&self) -> &[Step] {
        &self.steps
    }
    fn pattern(&self) -> &SparsityPattern {
        &self.model.pattern
    }
    fn num_dofs(&self) -> usize {
        self.model.num_dofs()
    }
    fn size(&self) -> f64 {
        self.model.size()
    }
    fn has_contact(&self) -> bool {
        !self.contacts.is_empty()
    }
    fn has_friction(&self) -> bool {
        self.contacts.has_friction()
    }
    fn has_nonsymmetric_tangent(&self) -> bool {
        Problem::has_nonsymmetric_tangent(self)
    }
    fn constrained_dofs(&self) -> Vec<bool> {
        Problem::constrained_dofs(self)
    }
    fn apply_prescribed(&self, t: f64, x: &mut [f64]) {
        Problem::apply_prescribed(self, t, x)
    }
    fn initial_state(&self, x: &[f64]) -> ContactState {
        self.initial_contact_state(x)
    }
    /// [`Problem::residual_into`]; a node's status code is its
    /// open/stick/slip code plus 4 × (1 + its primary triangle).
    fn evaluate(
        &self,
        t: f64,
        x: &[f64],
        state: &ContactState,
        tangent: Option<crate::assembly::sink::Tangent<'_>>,
    ) -> Result<Evaluation<Self::Report>, IncrementFailure> {
        let (residual, reports) = self
            .residual_into(t, x, state, tangent)
            .map_err(|f| self.element_failure(&f))?;
        let statuses = reports
            .iter()
            .flatten()
            .map(|n| n.status.code() as u64 + 4 * n.facet.map_or(0, |f| f as u64 + 1))
            .collect();
        Ok(Evaluation {
            residual: residual.r,
            internal_norm: residual.internal_norm,
            external_norm: residual.external_norm,
            statuses,
            reports,
        })
    }
    fn symmetric_neighbour(
        &self,
        t: f64,
        x: &[f64],
        state: &ContactState,
        constrained: &[bool],
        tangent: &[f64],
        values: &mut [f64],
    ) {
        self.stick_preconditioner(t, x, state, constrained, tangent, values)
    }
    fn advance_state(&self, t: f64, x: &[f64], dx: &[f64], state: &mut ContactState) {
        self.advance_contact_states(t, x, dx, state)
    }
    fn augment(&self, t: f64, x: &[f64], state: &mut ContactState) -> bool {
        self.augment_multipliers(t, x, state)
    }
    fn commit(&self, t: f64, x: &[f64], state: &mut ContactState) {
        self.commit_contact_history(t, x, state)
    }
    fn refresh_pattern(&mut self, x: &[f64], motion: f64, reached: Option<&[f64]>) -> bool {
        self.search_contact_pairs(x, motion, reached)
    }
    /// [`Problem::newton_pattern`].
    fn newton_pattern(&mut self) -> bool {
        Problem::newton_pattern(self)
    }
    fn couplings_hold(&self, x: &[f64], state: &ContactState) -> bool {
        self.contact_pairs_hold(x, state)
    }
    /// A contact node's path through a rigid obstacle
    /// ([`ContactInterface::passed_through`](crate::contact::interface::ContactInterface::passed_through)).
    fn passed_through(&self, start: (f64, &[f64]), end: (f64, &[f64])) -> Option<IncrementFailure> {
        let reference = &self.model.mesh.nodes;
        self.contacts.iter().find_map(|c| {
            let (node, gap) = c.passed_through(reference, start, end)?;
            Some(IncrementFailure::PassedThrough {
                node: self.model.mesh.node_ids[node],
                interface: c.name.clone(),
                gap,
                size: c.element_size,
            })
        })
    }
    fn moving_coupled_nodes(&self) -> Vec<usize> {
        self.deformable_contact_nodes()
    }
    /// [`Problem::contact_linearisation`].
    fn constraints_linearise(&self) -> Result<(), String> {
        self.contact_linearisation()
    }
    /// [`Problem::linearised_contact`].
    fn linearise_constraints(
        &self,
        t: f64,
        x: &[f64],
        state: &ContactState,
        tangent: &mut [f64],
    ) -> Result<Option<Linearisation>, IncrementFailure> {
        self.linearised_contact(t, x, state, tangent)
            .map_err(|f| self.element_failure(&f))
    }
    fn sum_over_processes(&self, v: &mut [f64]) {
        self.model.sum_over_processes(v)
    }
}
