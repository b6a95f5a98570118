//! A law's converged state read without Newton: what a solve that meets
//! the contact conditions directly (the condensed path, the
//! Josephy–Newton step) needs of the law. The exact laws (Rockafellar,
//! slack; Uzawa to its outer loop's tolerance) converge to `g ≥ 0 ⊥
//! t_N ≥ 0`, their parameters only conditioning Newton; the penalty law
//! converges to `t_N = ε⟨−g⟩`.

use super::{NodeContactState, NormalLaw, SlackState};

/// How a law's converged state constrains a node's normal contact.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum NormalEnforcement {
    /// `g ≥ 0 ⊥ t_N ≥ 0` exactly, written with the parameter `r > 0`
    /// (traction per length; it only conditions a solve of it).
    Exact { r: f64 },
    /// `t_N = ε⟨−g⟩`.
    Penalty { epsilon: f64 },
}

impl NormalLaw {
    /// The law's converged state: the penalty law's `t_N = ε⟨−g⟩`; for
    /// the others `g ≥ 0 ⊥ t_N ≥ 0` (Uzawa's to its outer loop's
    /// tolerance), written with the law's own `p` (Rockafellar, slack) or
    /// `ε` (Uzawa).
    pub fn converged(&self) -> NormalEnforcement {
        match *self {
            Self::Penalty { epsilon } => NormalEnforcement::Penalty { epsilon },
            Self::Uzawa { epsilon } => NormalEnforcement::Exact { r: epsilon },
            Self::Rockafellar { p, .. } | Self::Slack { p, .. } => {
                NormalEnforcement::Exact { r: p }
            }
        }
    }

    /// `k` of the multiplier laws, `t_N = kλ` at a converged closed node
    /// (the module docs of [`super`]); `None` without a multiplier dof.
    pub fn pressure_per_multiplier(&self) -> Option<f64> {
        match *self {
            Self::Rockafellar { k, .. } | Self::Slack { k, .. } => Some(k),
            _ => None,
        }
    }

    /// Write into `state` the multiplier `λ = t_N/k` of a node that carries
    /// `pressure` at gap `g` and, for the slack law, its local unknowns
    /// consistent with them ([`SlackState::consistent`]); `None` (the
    /// state untouched) for a law without a multiplier dof, else `λ`.
    pub fn set_converged_pressure(
        &self,
        pressure: f64,
        signed_gap: f64,
        state: &mut NodeContactState,
    ) -> Option<f64> {
        let k = self.pressure_per_multiplier()?;
        state.lambda = pressure / k;
        if let Self::Slack { p, k } = *self {
            state.slack = SlackState::consistent(signed_gap, state.lambda, p, k);
        }
        Some(state.lambda)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::gap::GapGeometry;
    use crate::contact::laws::Support;

    /// The state written for a pressure is the law's own converged state:
    /// its contribution at that gap reports the pressure back and leaves
    /// the multiplier's equation satisfied (closed at `g = 0`, open at
    /// `g > 0` with zero pressure).
    #[test]
    fn converged_pressure_is_the_laws_fixed_point() {
        let laws = [
            NormalLaw::Rockafellar { p: 3.0, k: 2.0 },
            NormalLaw::Slack { p: 3.0, k: 2.0 },
        ];
        for law in laws {
            for (pressure, gap) in [(5.0, 0.0), (0.0, 0.25)] {
                let mut state = NodeContactState::initial(&law, gap);
                let lambda = law.set_converged_pressure(pressure, gap, &mut state);
                assert_eq!(lambda, Some(pressure / 2.0));
                let c =
                    law.contribution(Support::Supported, 0.5, &GapGeometry::scalar(gap), &state);
                assert!(
                    (c.pressure - pressure).abs() < 1e-12,
                    "{law:?}: {}",
                    c.pressure
                );
                assert!(c.r_lambda.abs() < 1e-12, "{law:?}: r_λ = {}", c.r_lambda);
            }
        }
        let penalty = NormalLaw::Penalty { epsilon: 7.0 };
        let mut state = NodeContactState::initial(&penalty, 0.0);
        assert_eq!(penalty.set_converged_pressure(1.0, 0.0, &mut state), None);
        assert_eq!(
            penalty.converged(),
            NormalEnforcement::Penalty { epsilon: 7.0 }
        );
    }
}
