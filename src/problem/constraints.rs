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
    /// Whether [`Problem::linearised_contact`] writes the contact as
    /// linearised constraints (`Ok`), or why not: no contact, a
    /// distributed run (whose tangent is shared among processes), or an
    /// interface that is not a frictionless Rockafellar one against a
    /// rigid plane with a coordinate-axis normal (named in the reason).
    pub fn contact_linearisation(&self) -> Result<(), String> {
        if self.contacts.is_empty() {
            return Err("no contact interface".into());
        }
        if self.model.is_shared() {
            return Err("a distributed run".into());
        }
        for c in &self.contacts {
            let name = &c.name;
            let Primary::Rigid(RigidObstacle::Plane { normal, .. }) = &c.primary else {
                return Err(format!("contact '{name}' is not against a rigid plane"));
            };
            if plane_axis(normal).is_none() {
                return Err(format!(
                    "contact '{name}': the plane's normal is not a coordinate axis"
                ));
            }
            if c.has_friction() {
                return Err(format!("contact '{name}' has friction"));
            }
            if !matches!(c.law, NormalLaw::Rockafellar { .. }) {
                return Err(format!(
                    "contact '{name}' is not a monolithic Rockafellar one"
                ));
            }
        }
        Ok(())
    }

    /// `f_int − f_ext` at `t`, `x` (no contact; zero on the multipliers),
    /// its tangent into `tangent`, and every contact node as a
    /// [`NormalConstraint`]; `None` where
    /// [`Problem::contact_linearisation`] says it cannot.
    pub fn linearised_contact(
        &self,
        t: f64,
        x: &[f64],
        contact: &ContactState,
        tangent: &mut [f64],
    ) -> Result<Option<Linearisation>, crate::assembly::ElementFailure> {
        if self.contact_linearisation().is_err() {
            return Ok(None);
        }
        let first_multiplier = self.model.num_dofs();
        let mut constraints = Vec::new();
        for (c, states) in self.contacts.iter().zip(&contact.interfaces) {
            let Primary::Rigid(RigidObstacle::Plane { normal, .. }) = &c.primary else {
                return Ok(None);
            };
            let Some(axis) = plane_axis(normal) else {
                return Ok(None);
            };
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

/// The coordinate axis `d` of a plane's unit normal (`n = ±e_d`), if it
/// is one.
fn plane_axis(normal: &nalgebra::Vector3<f64>) -> Option<usize> {
    (0..3).find(|&d| normal[d].abs() == 1.0)
}
