//! The contact of a [`Problem`] as linearised unilateral constraints
//! ([`Linearisation`]), for the Josephy–Newton step of
//! [`crate::solve::josephy`], read from the node driver's
//! [`ConstraintRow`]s: a frictionless Rockafellar law on interfaces whose
//! gap is affine in the displacement with a gradient along one unknown,
//! `g_a = g_a(x) + sign · δ[dof]` (a rigid plane whose normal is a
//! coordinate axis), and its force `f_a = A_a k λ_a` (at a closed node,
//! `t̂ = kλ`).

use super::{ContactState, Problem};
use crate::contact::interface::{ConstraintRow, ContactInterface};
use crate::solve::nonlinear::{Linearisation, NormalConstraint};

/// `(dof, sign)` of a row whose gradient is `sign · e_dof` with
/// `|sign| = 1`, if it is one.
fn single_unknown(row: &ConstraintRow) -> Option<(usize, f64)> {
    match row.gradient().as_slice() {
        &[(dof, sign)] if sign.abs() == 1.0 => Some((dof, sign)),
        _ => None,
    }
}

/// Whether `c`'s constraints are linearised for the Josephy step, or why
/// not (after `contact '{name}'`).
fn linearises(c: &ContactInterface, reference: &[[f64; 3]], zero: &[f64]) -> Result<(), String> {
    c.affine_gap()?;
    if !c.fixed_area() {
        return Err("uses discretisation = \"mortar\" (its force D_j k λ follows the area D_j of the current surface)".into());
    }
    let rows = c.constraint_rows(reference, 0.0, zero, None);
    if !rows.iter().flatten().all(|r| single_unknown(r).is_some()) {
        return Err("has a gap gradient that is not a coordinate axis".into());
    }
    if c.has_friction() {
        return Err("has friction".into());
    }
    // a multiplier `λ` with `t_N = kλ` and no local unknowns: Rockafellar's
    if c.law.pressure_per_multiplier().is_none() || c.law.has_local_unknowns() {
        return Err("is not a monolithic Rockafellar one".into());
    }
    Ok(())
}

impl Problem {
    /// Whether [`Problem::linearised_contact`] writes the contact as
    /// linearised constraints (`Ok`), or why not: no contact, a
    /// distributed run (whose tangent is shared among processes), or an
    /// interface that is not a frictionless Rockafellar one with an
    /// affine gap along one unknown (named in the reason).
    pub fn contact_linearisation(&self) -> Result<(), String> {
        if self.contacts.is_empty() {
            return Err("no contact interface".into());
        }
        if self.model.is_shared() {
            return Err("a distributed run".into());
        }
        let zero = vec![0.0; self.num_unknowns()];
        for c in &self.contacts {
            linearises(c, &self.model.mesh.nodes, &zero)
                .map_err(|why| format!("contact '{}' {why}", c.name))?;
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
            let rows = c.constraint_rows(&self.model.mesh.nodes, t, x, Some(states));
            for (i, row) in rows.iter().enumerate() {
                let (Some(row), Some(k)) = (row, c.law_at(i).pressure_per_multiplier()) else {
                    return Ok(None);
                };
                let Some((dof, sign)) = single_unknown(row) else {
                    return Ok(None);
                };
                constraints.push(NormalConstraint {
                    dof,
                    sign,
                    gap: row.gap,
                    multiplier: first_multiplier + c.multiplier_offset + i,
                    force_per_multiplier: row.area * k,
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
