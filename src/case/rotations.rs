//! `[[displacement]]` with `rotation`: a prescribed rigid rotation (and
//! translation) of a node set, resolved against the mesh
//! ([`PrescribedRotation`]).

use super::schema::DisplacementSpec;
use super::Case;
use crate::problem::PrescribedRotation;
use crate::Result;

impl Case {
    /// The `[[displacement]]` entries with a `rotation`, validated: a
    /// non-zero finite axis, a finite centre and angle, finite `x`, `y`,
    /// `z`, and no node also prescribed by another `[[displacement]]` (the
    /// rotation prescribes all three components).
    pub(super) fn rotations(&self) -> Result<Vec<PrescribedRotation>> {
        let mut out = Vec::new();
        for (i, d) in self.spec.displacement.iter().enumerate() {
            let Some(r) = &d.rotation else { continue };
            let key = format!("displacement[{i}].rotation");
            let norm = r.axis.iter().map(|a| a * a).sum::<f64>().sqrt();
            if !(norm > 0.0 && norm.is_finite()) {
                return Err(self.err(format!(
                    "{key}.axis = {:?} is not a direction: give a non-zero axis, e.g. [0, 0, 1]",
                    r.axis
                )));
            }
            if !r.angle.is_finite() || r.centre.iter().any(|v| !v.is_finite()) {
                return Err(self.err(format!("{key}: angle and centre must be finite")));
            }
            let translation = [d.x, d.y, d.z].map(|v| v.unwrap_or(0.0));
            if translation.iter().any(|v| !v.is_finite()) {
                return Err(self.err(format!(
                    "displacement[{i}]: displacement values must be finite"
                )));
            }
            let (set, nodes) = self.displacement_nodes(i)?;
            self.check_rotation_alone(i, &set, &nodes)?;
            let translation_amplitude =
                self.amplitude(&format!("displacement[{i}].amplitude"), &d.amplitude)?;
            let angle_amplitude = match &r.amplitude {
                Some(_) => self.amplitude(&format!("{key}.amplitude"), &r.amplitude)?,
                None => translation_amplitude.clone(),
            };
            out.push(PrescribedRotation {
                set,
                nodes,
                axis: r.axis,
                centre: r.centre,
                angle: r.angle.to_radians(),
                angle_amplitude,
                translation,
                translation_amplitude,
            });
        }
        Ok(out)
    }

    /// An error if another `[[displacement]]` prescribes a node of the
    /// rotated set `nodes` of entry `i`: which entry, which node, and the fix.
    fn check_rotation_alone(&self, i: usize, set: &str, nodes: &[usize]) -> Result<()> {
        let mut mine = vec![false; self.mesh.num_nodes()];
        for &n in nodes {
            mine[n] = true;
        }
        for (j, other) in self.spec.displacement.iter().enumerate() {
            if j == i {
                continue;
            }
            let (other_set, other_nodes) = self.displacement_nodes(j)?;
            if let Some(&n) = other_nodes.iter().find(|&&n| mine[n]) {
                return Err(self.err(format!(
                    "displacement[{i}] rotates '{set}', which prescribes all three components of its nodes, \
                     but displacement[{j}] ('{other_set}'{}) also prescribes node {}: \
                     give the translation as x, y, z of displacement[{i}], or take the node out of one set",
                    if other.rotation.is_some() { ", also rotated" } else { "" },
                    self.mesh.node_ids[n]
                )));
            }
        }
        Ok(())
    }
}

/// Whether a `[[displacement]]` is a rotation (handled by
/// [`Case::rotations`], not as components).
pub(super) fn is_rotation(d: &DisplacementSpec) -> bool {
    d.rotation.is_some()
}
