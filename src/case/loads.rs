//! The loads of a case: `[[displacement]]`, `[[pressure]]`,
//! `[[body_force]]` and `[[nodal_force]]`, each with its amplitude in
//! pseudo-time, resolved against the mesh.

use super::schema::AmplitudeRef;
use super::Case;
use crate::assembly::Model;
use crate::problem::{Amplitude, BodyForce, NodalForce, PrescribedDisplacement, PressureLoad};
use crate::Result;

impl Case {
    /// The amplitude `a` of key `key`: the default ramp (0 at time 0, 1
    /// at the end of the first step, then held), a named one of
    /// `[amplitudes]`, or the points given.
    pub(super) fn amplitude(&self, key: &str, a: &Option<AmplitudeRef>) -> Result<Amplitude> {
        let points = match a {
            None => {
                let t1 = self.spec.step.first().map(|s| s.end_time).unwrap_or(1.0);
                return Ok(Amplitude::new(vec![(0.0, 0.0), (t1, 1.0)]));
            }
            Some(AmplitudeRef::Named(name)) => self.spec.amplitudes.get(name).ok_or_else(|| {
                let have: Vec<&str> = self.spec.amplitudes.keys().map(|s| s.as_str()).collect();
                self.err(format!(
                    "{key}: no amplitude named '{name}' in [amplitudes]; {}",
                    crate::error::suggest::listing(name, &have, "none")
                ))
            })?,
            Some(AmplitudeRef::Points(p)) => p,
        };
        if points.is_empty() {
            return Err(self.err(format!(
                "{key}: an amplitude needs at least one [time, value] point"
            )));
        }
        if let Some((k, p)) = points.iter().enumerate().find(|(_, p)| p.len() != 2) {
            return Err(self.err(format!(
                "{key}: point {k} has {} numbers; an amplitude point is [time, value]",
                p.len()
            )));
        }
        for w in points.windows(2) {
            if !(w[1][0] > w[0][0]) {
                return Err(self.err(format!(
                    "{key}: amplitude times must increase strictly ({} then {})",
                    w[0][0], w[1][0]
                )));
            }
        }
        if points.iter().flatten().any(|v| !v.is_finite()) {
            return Err(self.err(format!("{key}: amplitude values must be finite")));
        }
        Ok(Amplitude::new(
            points.iter().map(|p| (p[0], p[1])).collect(),
        ))
    }

    /// The nodes of `[[displacement]]` `i`: its `surface` or its `nodes`.
    pub(super) fn displacement_nodes(&self, i: usize) -> Result<(String, Vec<usize>)> {
        let d = &self.spec.displacement[i];
        let key = format!("displacement[{i}]");
        match (&d.surface, &d.nodes) {
            (Some(name), None) => {
                let surface = self.surface(&format!("{key}.surface"), name)?;
                Ok((name.clone(), self.mesh.surface_nodes(surface)))
            }
            (None, Some(name)) => {
                let set = self.node_set(&format!("{key}.nodes"), name)?;
                Ok((name.clone(), set.nodes.clone()))
            }
            (s, _) => Err(self.err(format!(
                "{key}: give either `surface` (a surface set) or `nodes` (a node set), not {}",
                if s.is_some() { "both" } else { "neither" }
            ))),
        }
    }

    /// `[[displacement]]`: the prescribed components of each node set or
    /// surface (those with a `rotation`: [`Case::rotations`]).
    pub(super) fn prescribed(&self) -> Result<Vec<PrescribedDisplacement>> {
        let spec = &self.spec;
        let mut prescribed = Vec::new();
        for (i, d) in spec.displacement.iter().enumerate() {
            if super::rotations::is_rotation(d) {
                continue;
            }
            let key = format!("displacement[{i}]");
            let (set, nodes) = self.displacement_nodes(i)?;
            let components: Vec<(usize, f64)> = [d.x, d.y, d.z]
                .iter()
                .enumerate()
                .filter_map(|(c, v)| v.map(|v| (c, v)))
                .collect();
            if components.is_empty() {
                return Err(self.err(format!("{key}: give at least one of x, y, z")));
            }
            if components.iter().any(|(_, v)| !v.is_finite()) {
                return Err(self.err(format!("{key}: displacement values must be finite")));
            }
            prescribed.push(PrescribedDisplacement {
                surface: set,
                nodes,
                components,
                amplitude: self.amplitude(&format!("{key}.amplitude"), &d.amplitude)?,
            });
        }
        Ok(prescribed)
    }

    /// `[[pressure]]`: a pressure on each surface set's facets.
    pub(super) fn pressures(&self) -> Result<Vec<PressureLoad>> {
        let spec = &self.spec;
        let mut pressures = Vec::new();
        for (i, p) in spec.pressure.iter().enumerate() {
            let key = format!("pressure[{i}]");
            let surface = self.surface(&format!("{key}.surface"), &p.surface)?;
            if !p.value.is_finite() {
                return Err(self.err(format!("{key}.value must be finite")));
            }
            pressures.push(PressureLoad {
                surface: p.surface.clone(),
                facets: surface.facets.clone(),
                pressure: p.value,
                follower: p.follower,
                amplitude: self.amplitude(&format!("{key}.amplitude"), &p.amplitude)?,
            });
        }
        Ok(pressures)
    }

    /// `[[body_force]]`: a force per unit reference volume on each region
    /// (every element without one), as the nodal volumes `∫ N_a dV₀` of
    /// `model`.
    pub(super) fn body_forces(&self, model: &Model) -> Result<Vec<BodyForce>> {
        let spec = &self.spec;
        let mut body_forces = Vec::new();
        for (i, b) in spec.body_force.iter().enumerate() {
            let key = format!("body_force[{i}]");
            let elements: Vec<usize> = match &b.region {
                Some(r) => self.region(&format!("{key}.region"), r)?.elements.clone(),
                None => (0..self.mesh.elements.len()).collect(),
            };
            if b.value.iter().any(|v| !v.is_finite()) {
                return Err(self.err(format!("{key}.value must be finite")));
            }
            body_forces.push(BodyForce {
                region: b.region.clone().unwrap_or_else(|| "all".into()),
                nodal_volumes: model.nodal_volumes(&elements),
                force: b.value,
                amplitude: self.amplitude(&format!("{key}.amplitude"), &b.amplitude)?,
            });
        }
        Ok(body_forces)
    }

    /// `[[nodal_force]]`: the total force shared equally by a node set's
    /// nodes.
    pub(super) fn nodal_forces(&self) -> Result<Vec<NodalForce>> {
        let spec = &self.spec;
        let mut nodal_forces = Vec::new();
        for (i, p) in spec.nodal_force.iter().enumerate() {
            let key = format!("nodal_force[{i}]");
            let set = self.node_set(&format!("{key}.nodes"), &p.nodes)?;
            if set.nodes.is_empty() {
                return Err(self.err(format!("{key}.nodes: node set '{}' is empty", p.nodes)));
            }
            if p.value.iter().any(|v| !v.is_finite()) {
                return Err(self.err(format!("{key}.value must be finite")));
            }
            let share = 1.0 / set.nodes.len() as f64;
            nodal_forces.push(NodalForce {
                set: p.nodes.clone(),
                nodes: set.nodes.clone(),
                force: p.value.map(|v| v * share),
                amplitude: self.amplitude(&format!("{key}.amplitude"), &p.amplitude)?,
            });
        }
        Ok(nodal_forces)
    }
}
