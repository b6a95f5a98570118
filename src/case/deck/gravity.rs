//! `*DLOAD … GRAV` → `[[body_force]]`: the body force per unit reference
//! volume `b = ρ g n` (Abaqus and CalculiX: `g` the magnitude, `n` the
//! direction, `ρ` the `*DENSITY` of each element's material), one
//! `[[body_force]]` per section under the gravity's element set, on the
//! section's region (or on the set itself when it lies inside one
//! section). Its time history follows the deck's step rules
//! ([`super::timeline`]), `OP=NEW` on a `*DLOAD` removing it with the
//! pressures.

use super::super::schema::{BodyForceSpec, CaseFile};
use super::timeline::InStep;
use super::{bits, give, points_ref, remove_held, Bits, Channels, Points, StepTimes};
use crate::mesh::inp::physics::{Located, Physics};
use crate::mesh::Mesh;
use crate::Result;
use std::collections::{BTreeMap, HashSet};

/// `[[body_force]]` of the deck's gravity loads.
pub(super) fn gravities(times: &StepTimes, mesh: &Mesh, spec: &mut CaseFile) -> Result<()> {
    let physics = times.physics;
    let n = times.count();
    let mut channels: Channels<(String, usize)> = BTreeMap::new();
    let mut first: BTreeMap<String, &Located> = BTreeMap::new();
    for (k, s) in physics.steps.iter().enumerate() {
        for g in &s.gravities {
            for (c, &a) in g.acceleration.iter().enumerate() {
                let given = InStep::Given(a, g.amplitude.as_deref(), &g.at);
                give(&mut channels, (g.elements.clone(), c), k, n, given);
            }
            first.entry(g.elements.clone()).or_insert(&g.at);
        }
        if s.new_pressures {
            remove_held(&mut channels, k);
        }
    }
    let mut grouped: BTreeMap<(String, Bits), ([f64; 3], Points)> = BTreeMap::new();
    for ((set, c), steps) in &channels {
        let (scale, amplitude) = times.scaled(0.0, steps)?;
        if scale == 0.0 {
            continue;
        }
        let entry = grouped
            .entry((set.clone(), bits(&amplitude)))
            .or_insert(([0.0; 3], amplitude));
        entry.0[*c] = scale;
    }
    for ((set, _), (acceleration, amplitude)) in grouped {
        for (region, density) in densities(physics, mesh, &set, first[&set])? {
            spec.body_force.push(BodyForceSpec {
                region: Some(region),
                value: acceleration.map(|a| density * a),
                amplitude: points_ref(&amplitude),
            });
        }
    }
    Ok(())
}

/// The regions and densities `ρ` of the sections under element set `set`:
/// a section's region when the set holds all of it, the set itself when
/// it lies inside one section.
fn densities(
    physics: &Physics,
    mesh: &Mesh,
    set: &str,
    at: &Located,
) -> Result<Vec<(String, f64)>> {
    let elements: HashSet<usize> = mesh
        .region(set)
        .ok_or_else(|| {
            at.error(format!(
                "*DLOAD, GRAV on '{set}': the element set holds no volume element (C3D…)"
            ))
        })?
        .elements
        .iter()
        .copied()
        .collect();
    let mut out = Vec::new();
    for section in &physics.sections {
        let Some(region) = mesh.region(&section.region) else {
            continue;
        };
        let inside = region
            .elements
            .iter()
            .filter(|e| elements.contains(e))
            .count();
        // a section without its material is refused where materials are read
        let Some(m) = physics.material_of(section).filter(|_| inside > 0) else {
            continue;
        };
        let density = m
            .density
            .filter(|&d| d >= 0.0 && d.is_finite())
            .ok_or_else(|| {
                at.error(format!(
                "*DLOAD, GRAV on '{set}': *MATERIAL '{}' (of *SOLID SECTION, ELSET={}) has {}; \
                 add *DENSITY with its mass per unit volume",
                m.name,
                section.region,
                match m.density {
                    None => "no *DENSITY".to_string(),
                    Some(d) => format!("*DENSITY {d}, not a mass density ≥ 0"),
                }
            ))
            })?;
        let name = if inside == region.elements.len() {
            section.region.clone()
        } else if inside == elements.len() {
            set.to_string()
        } else {
            return Err(at.error(format!(
                "*DLOAD, GRAV on '{set}' covers part of *SOLID SECTION, ELSET={} and elements of \
                 other sections: give one GRAV line per section's element set",
                section.region
            )));
        };
        out.push((name, density));
    }
    Ok(out)
}
