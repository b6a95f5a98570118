//! The contact of a [`Problem`] as linearised unilateral constraints
//! ([`Linearisation`]), for the Josephy–Newton step of
//! [`crate::solve::josephy`]: the frictionless Rockafellar law against
//! rigid planes whose normal is a coordinate axis, where the gap of node
//! `a` is linear in its displacement, `g_a = n·(X_a + u_a − c(t))`, and
//! its force `f_a = A_a k λ_a` (at a closed node, `t̂ = kλ`).

use super::{ContactState, Problem};
use crate::contact::interface::Primary;
use crate::contact::laws::NormalLaw;
use crate::contact::obstacle::RigidObstacle;
use crate::solve::nonlinear::{Linearisation, NormalConstraint};

impl Problem {
    /// `f_int − f_ext` at `t`, `x` (no contact; zero on the multipliers),
    /// its tangent into `tangent`, and every contact node as a
    /// [`NormalConstraint`]; `None` unless every interface is a
    /// frictionless Rockafellar one against a rigid plane with a
    /// coordinate-axis normal, or in a distributed run (whose tangent is
    /// shared among processes).
    pub fn linearised_contact(
        &self,
        t: f64,
        x: &[f64],
        contact: &ContactState,
        tangent: &mut [f64],
    ) -> Result<Option<Linearisation>, crate::assembly::ElementFailure> {
        if self.contacts.is_empty() || self.model.is_shared() {
            return Ok(None);
        }
        let first_multiplier = self.model.num_dofs();
        let mut constraints = Vec::new();
        for (c, states) in self.contacts.iter().zip(&contact.interfaces) {
            let Primary::Rigid(RigidObstacle::Plane { normal, .. }) = &c.primary else {
                return Ok(None);
            };
            let Some(axis) = (0..3).find(|&d| normal[d].abs() == 1.0) else {
                return Ok(None);
            };
            if c.has_friction() {
                return Ok(None);
            }
            let gaps = c.gaps(&self.model.mesh.nodes, t, x, Some(states));
            for (i, (&node, gap)) in c.nodes.iter().zip(gaps).enumerate() {
                let NormalLaw::Rockafellar { k, .. } = c.law_at(i) else {
                    return Ok(None);
                };
                constraints.push(NormalConstraint {
                    dof: 3 * node + axis,
                    sign: normal[axis],
                    gap,
                    multiplier: first_multiplier + c.multiplier_offset + i,
                    force_per_multiplier: c.areas[i] * k,
                });
            }
        }
        tangent.iter_mut().for_each(|v| *v = 0.0);
        let mut residual = vec![0.0; self.num_unknowns()];
        self.model
            .assemble_internal(x, &mut residual, Some(&mut *tangent))?;
        let f_ext = self.external_force(t, x, Some(tangent));
        for (r, f) in residual.iter_mut().zip(&f_ext) {
            *r -= f;
        }
        Ok(Some(Linearisation {
            residual,
            constraints,
        }))
    }
}
