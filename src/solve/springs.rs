//! Uncoupled springs on the three dofs of one node: a [`NonlinearProblem`]
//! that is not the finite-element `Problem`, with no history, for the
//! unit tests of Newton (`solve::newton`) and of the stepper
//! (`solve::stepping`).

use super::failure::IncrementFailure;
use super::gmres::norm;
use super::nonlinear::{Evaluation, NonlinearProblem};
use super::settings::{SolverSettings, Step};
use crate::assembly::pattern::SparsityPattern;

/// One spring at its displacement `x` and the load time `t`: its force,
/// the load on it, its stiffness `∂f/∂x`, and a contact status where it
/// plays a contact node.
pub struct Spring {
    pub internal: f64,
    pub external: f64,
    pub stiffness: f64,
    pub status: Option<u64>,
}

/// The law of spring `i`: `(t, i, x) ↦` [`Spring`].
pub type Law = Box<dyn Fn(f64, usize, f64) -> Spring>;

/// Three uncoupled springs, `r_i = f_int(x_i) − f_ext,i(t)`.
pub struct Springs {
    pub settings: SolverSettings,
    pub steps: Vec<Step>,
    pub pattern: SparsityPattern,
    pub law: Law,
}

impl Springs {
    /// The springs of `law` under `settings`, loaded through `steps`.
    pub fn new(settings: SolverSettings, steps: Vec<Step>, law: Law) -> Self {
        let nodes = [0usize];
        Springs {
            settings,
            steps,
            pattern: SparsityPattern::from_elements(1, std::iter::once(&nodes[..])),
            law,
        }
    }
}

impl NonlinearProblem for Springs {
    type State = ();
    type Report = ();
    fn settings(&self) -> &SolverSettings {
        &self.settings
    }
    fn steps(&self) -> &[Step] {
        &self.steps
    }
    fn pattern(&self) -> &SparsityPattern {
        &self.pattern
    }
    fn num_dofs(&self) -> usize {
        3
    }
    fn size(&self) -> f64 {
        1.0
    }
    fn has_nonsymmetric_tangent(&self) -> bool {
        false
    }
    fn constrained_dofs(&self) -> Vec<bool> {
        vec![false; 3]
    }
    fn apply_prescribed(&self, _t: f64, _x: &mut [f64]) {}
    fn initial_state(&self, _x: &[f64]) {}
    fn evaluate(
        &self,
        t: f64,
        x: &[f64],
        _state: &(),
        tangent: Option<crate::assembly::sink::Tangent<'_>>,
    ) -> Result<Evaluation<()>, IncrementFailure> {
        let springs: Vec<Spring> = x
            .iter()
            .enumerate()
            .map(|(i, &xi)| (self.law)(t, i, xi))
            .collect();
        if let Some(crate::assembly::sink::Tangent::Values(values)) = tangent {
            values.iter_mut().for_each(|v| *v = 0.0);
            for (i, s) in springs.iter().enumerate() {
                values[self.pattern.diagonal_entry(i)] = s.stiffness;
            }
        }
        let internal: Vec<f64> = springs.iter().map(|s| s.internal).collect();
        let external: Vec<f64> = springs.iter().map(|s| s.external).collect();
        Ok(Evaluation {
            residual: internal.iter().zip(&external).map(|(a, b)| a - b).collect(),
            internal_norm: norm(&internal),
            external_norm: norm(&external),
            statuses: springs.iter().filter_map(|s| s.status).collect(),
            reports: (),
        })
    }
    fn symmetric_neighbour(&self, _: f64, _: &[f64], _: &(), _: &[bool], _: &[f64], _: &mut [f64]) {
    }
    fn advance_state(&self, _: f64, _: &[f64], _: &[f64], _: &mut ()) {}
    fn augment(&self, _: f64, _: &[f64], _: &mut ()) -> bool {
        false
    }
    fn commit(&self, _: f64, _: &[f64], _: &mut ()) {}
    fn refresh_pattern(&mut self, _: &[f64], _: f64, _: Option<&[f64]>) -> bool {
        false
    }
    fn couplings_hold(&self, _: &[f64], _: &()) -> bool {
        true
    }
    fn moving_coupled_nodes(&self) -> Vec<usize> {
        Vec::new()
    }
}
