//! The outer loops of the laws that have one, run by the stepper after a
//! converged Newton solve: exact stick's augmentation of the tangential
//! multipliers (`λ_T ← t_T`, [`friction::augment`]) and Uzawa's of the
//! normal ones (`λ ← λ + ε ⟨−g⟩`, [`NormalLaw::augmented_multiplier`]),
//! each until its residual is within 1e-9 of the element size. They use
//! the node driver ([`ContactInterface::for_each_node`]) like every other
//! operation of the interface.

use super::{ContactContext, ContactInterface, MortarGap, Primary, RigidGap, SurfaceGap};
use crate::contact::kinematics::GapProducer;
use crate::contact::laws::{uzawa, NodeContactState};
#[cfg(doc)]
use crate::contact::{friction, laws::NormalLaw};

impl ContactInterface {
    /// The outer loops of the laws that have one, after a converged Newton
    /// solve at `ctx`: exact stick's ([`exact_stick`](Self::exact_stick)),
    /// where the largest `|t_T − T λ_T|/ε_T` exceeds the tolerance (1e-9
    /// of the element size), updates every tangential multiplier
    /// ([`friction::augment`]); Uzawa's, where the largest penetration
    /// exceeds the same tolerance, every normal multiplier
    /// ([`NormalLaw::augmented_multiplier`]). Returns `true` when either
    /// updated (solve again), `false` otherwise.
    pub fn augment(&self, ctx: &ContactContext, states: &mut [NodeContactState]) -> bool {
        let tangential = self.augment_friction(ctx, states);
        tangential | self.augment_normal(ctx, states)
    }

    /// Exact stick's outer loop (see [`augment`](Self::augment)): every
    /// node's tangential multiplier augmented at `ctx` (`λ_T ← t_T`,
    /// [`GapProducer::augment`]) unless the largest multiplier residual
    /// `|t_T − T λ_T|/ε_T` is within the tolerance.
    fn augment_friction(&self, ctx: &ContactContext, states: &mut [NodeContactState]) -> bool {
        if !(self.has_friction() && self.exact_stick()) || self.tangential_multipliers() {
            return false;
        }
        let mut worst = 0.0_f64;
        let mut augmented = Vec::with_capacity(self.nodes.len());
        with_producer!(self, ctx, p => {
            let state_of = |i| self.node_state(ctx, states, i);
            self.for_each_node(p, ctx, state_of, |node, state, k| {
                let e = k.map(|k| self.evaluate(p, node, k, &state, None));
                let response = e
                    .as_ref()
                    .and_then(|e| e.tangential.as_ref().map(|t| (t, &e.kinematics.normal)));
                if let Some((r, _)) = response {
                    worst = worst.max(r.multiplier_residual.norm());
                }
                augmented.push(p.augment(node, &state.friction, response));
            });
        });
        if worst <= 1e-9 * self.element_size {
            return false;
        }
        for (state, history) in states.iter_mut().zip(augmented) {
            state.friction = history;
        }
        true
    }

    /// Uzawa's outer loop (see [`augment`](Self::augment)).
    fn augment_normal(&self, ctx: &ContactContext, states: &mut [NodeContactState]) -> bool {
        if !self.law.has_outer_loop() {
            return false;
        }
        let gaps = self.gaps(ctx.reference, ctx.t, ctx.x, Some(states));
        if uzawa::penetration_converged(gaps.iter().copied(), 1e-9 * self.element_size) {
            return false;
        }
        for (i, (state, g)) in states.iter_mut().zip(&gaps).enumerate() {
            state.lambda = self.law_at(i).augmented_multiplier(state.lambda, *g);
        }
        true
    }
}
