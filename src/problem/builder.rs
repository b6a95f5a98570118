//! [`ProblemBuilder`]: a [`Problem`] put together by a library user (and
//! by the case file) without filling its public fields: a model, then the
//! loads, steps, solver settings and contacts, each with a default.

use super::{
    BodyForce, NodalForce, PrescribedDisplacement, PrescribedRotation, PressureLoad, Problem,
};
use crate::assembly::Model;
use crate::contact::interface::ContactInterface;
use crate::contact::setup::SetupError;
use crate::solve::ordering::EarlyDissection;
use crate::solve::settings::{SolverSettings, Step};

/// A [`Problem`] in the making (see [`Problem::builder`]). Without steps
/// it has one, `"load"`, over `t ∈ [0, 1]` in one increment; without
/// settings, [`SolverSettings::default`].
pub struct ProblemBuilder {
    problem: Problem,
    /// Contact interfaces and the initial penetration each accepts.
    contacts: Vec<(ContactInterface, f64)>,
}

impl Problem {
    /// A problem on `model` with no loads and no contact, to be built up.
    pub fn builder(model: Model) -> ProblemBuilder {
        ProblemBuilder {
            problem: Problem {
                model,
                prescribed: Vec::new(),
                rotations: Vec::new(),
                pressures: Vec::new(),
                body_forces: Vec::new(),
                nodal_forces: Vec::new(),
                contacts: Default::default(),
                steps: Vec::new(),
                settings: SolverSettings::default(),
                timings: Default::default(),
                dissection: None,
            },
            contacts: Vec::new(),
        }
    }
}

impl ProblemBuilder {
    /// Prescribes displacements.
    pub fn prescribed(mut self, d: impl IntoIterator<Item = PrescribedDisplacement>) -> Self {
        self.problem.prescribed.extend(d);
        self
    }

    /// Prescribes rigid rotations of node sets.
    pub fn rotations(mut self, r: impl IntoIterator<Item = PrescribedRotation>) -> Self {
        self.problem.rotations.extend(r);
        self
    }

    /// Adds pressure loads.
    pub fn pressures(mut self, p: impl IntoIterator<Item = PressureLoad>) -> Self {
        self.problem.pressures.extend(p);
        self
    }

    /// Adds body forces.
    pub fn body_forces(mut self, b: impl IntoIterator<Item = BodyForce>) -> Self {
        self.problem.body_forces.extend(b);
        self
    }

    /// Adds nodal forces.
    pub fn nodal_forces(mut self, f: impl IntoIterator<Item = NodalForce>) -> Self {
        self.problem.nodal_forces.extend(f);
        self
    }

    /// Appends load steps (in order of their end times).
    pub fn steps(mut self, s: impl IntoIterator<Item = Step>) -> Self {
        self.problem.steps.extend(s);
        self
    }

    /// The solver settings.
    pub fn settings(mut self, settings: SolverSettings) -> Self {
        self.problem.settings = settings;
        self
    }

    /// A nested dissection of the model's element graph started early
    /// ([`super::dissects_element_graph`]).
    pub fn dissection(mut self, d: Option<EarlyDissection>) -> Self {
        self.problem.dissection = d;
        self
    }

    /// Adds a contact interface, which [`build`](Self::build) checks in
    /// the reference configuration with the default tolerance
    /// ([`ContactInterface::default_penetration_tolerance`]).
    pub fn contact(self, interface: ContactInterface) -> Self {
        let tolerance = interface.default_penetration_tolerance();
        self.contact_within(interface, tolerance)
    }

    /// Adds a contact interface that may start up to `tolerance` (a
    /// length ≥ 0) inside its primary side.
    pub fn contact_within(mut self, interface: ContactInterface, tolerance: f64) -> Self {
        self.contacts.push((interface, tolerance));
        self
    }

    /// The problem: the contacts checked
    /// ([`ContactInterface::check_reference_gaps`]: no node starting inside
    /// the primary side, no plane with its normal pointing away) and
    /// installed, one step over `[0, 1]` if none was given.
    pub fn build(self) -> Result<Problem, SetupError> {
        let mesh = self.problem.model.mesh.clone();
        for (c, tolerance) in &self.contacts {
            c.check_reference_gaps(&mesh, *tolerance)?;
        }
        let mut problem = self.problem;
        if problem.steps.is_empty() {
            problem.steps.push(Step {
                name: "load".into(),
                end_time: 1.0,
                initial_increment: 1.0,
                min_increment: 1.0 / 1024.0,
                max_increment: 1.0,
            });
        }
        if !self.contacts.is_empty() {
            problem.set_contacts(self.contacts.into_iter().map(|(c, _)| c).collect());
        }
        Ok(problem)
    }
}
