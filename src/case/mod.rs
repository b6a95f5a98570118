//! The case file: parsing ([`schema`]) and validation into a [`Problem`].
//! Every check of the user's input lives here, with the key path in the
//! message.

pub mod budget;
mod contacts;
pub mod deck;
mod deck_names;
pub mod diagnosis;
pub mod limits;
mod lines;
pub mod output;
mod read;
pub mod reference;
pub mod schema;
mod tagged;

use crate::assembly::pattern::NodeGraph;
use crate::assembly::Model;
use crate::material::{self, Material};
use crate::mesh::Mesh;
use crate::problem::{
    Amplitude, BodyForce, LinearMethod, NodalForce, PrescribedDisplacement, PressureLoad, Problem,
    SolverSettings, Step,
};
use crate::solve::ordering::EarlyDissection;
use crate::{Error, Result};
use read::{case_error, line_of};
use schema::{AmplitudeRef, CaseFile, MaterialModel};
use std::path::{Path, PathBuf};
use std::sync::Arc;

pub use read::{from_mesh, from_toml, load, parse};

/// A parsed case file and the mesh it names.
pub struct Case {
    pub path: PathBuf,
    pub spec: CaseFile,
    pub mesh: Arc<Mesh>,
    /// Notes on reading the mesh for the user (e.g. the `.inp` keywords
    /// that were ignored).
    pub notes: Vec<String>,
    /// The case file's text, for the lines that errors name.
    pub text: String,
}

/// `{key} = {value} must be positive`, or, for an infinite or NaN value,
/// that it is not a finite number (not that it is not positive).
pub(crate) fn not_positive(key: &str, value: f64) -> String {
    if value.is_finite() {
        format!("{key} = {value} must be positive")
    } else {
        format!("{key} = {value} is not a finite number; give a positive value")
    }
}

/// `name` is a file stem that stays in the output folder: not empty, not
/// hidden, letters, digits, `-`, `_` and `.` only (no `/`, no `..`).
pub(crate) fn is_file_stem(name: &str) -> bool {
    !name.is_empty()
        && !name.starts_with('.')
        && name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || matches!(c, '-' | '_' | '.'))
}

/// The first name in `names` that an earlier one already has, with the
/// indices of both.
fn first_duplicate<'a>(names: impl Iterator<Item = &'a str>) -> Option<(usize, usize, &'a str)> {
    let mut seen = std::collections::HashMap::new();
    for (i, name) in names.enumerate() {
        if let Some(&j) = seen.get(name) {
            return Some((j, i, name));
        }
        seen.insert(name, i);
    }
    None
}

impl Case {
    /// The folder of the case file.
    pub fn dir(&self) -> PathBuf {
        self.path.parent().unwrap_or(Path::new(".")).to_path_buf()
    }

    /// The output folder: `override_dir` if given, else `[output].folder`
    /// relative to the case file, else `results` beside it.
    pub fn output_dir(&self, override_dir: Option<&Path>) -> PathBuf {
        match override_dir {
            Some(d) => d.to_path_buf(),
            None => self
                .dir()
                .join(self.spec.output.folder.as_deref().unwrap_or("results")),
        }
    }

    /// The nodal and cell fields the VTU files hold: `[output] fields`, or
    /// [`OutputField::default_set`](crate::output::OutputField::default_set).
    pub fn output_fields(
        &self,
    ) -> (
        Vec<crate::output::NodalField>,
        Vec<crate::output::CellField>,
    ) {
        use crate::output::OutputField;
        let chosen: Vec<OutputField> = match &self.spec.output.fields {
            Some(f) => f.clone(),
            None => OutputField::default_set().collect(),
        };
        let nodal = chosen
            .iter()
            .filter_map(|f| match f {
                OutputField::Nodal(n) => Some(*n),
                OutputField::Cell(_) => None,
            })
            .collect();
        let cells = chosen
            .iter()
            .filter_map(|f| match f {
                OutputField::Cell(c) => Some(*c),
                OutputField::Nodal(_) => None,
            })
            .collect();
        (nodal, cells)
    }

    /// `[output] every`: a VTU file every this many increments (≥ 1).
    pub fn output_every(&self) -> Result<usize> {
        match self.spec.output.every {
            None => Ok(1),
            Some(n) if n >= 1 => Ok(n as usize),
            Some(n) => Err(self.err(format!(
                "output.every = {n}: write every N ≥ 1 increments (1 writes them all; the last increment of each step is always written)"
            ))),
        }
    }

    /// File-name stem for the VTU series.
    pub fn output_name(&self) -> String {
        self.spec.output.name.clone().unwrap_or_else(|| {
            self.path
                .file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_else(|| "result".into())
        })
    }

    /// An error in the case file, with the line of the key path the
    /// message starts with (`contact[0].obstacle: …` → `line 31:
    /// contact[0].obstacle: …`) when the text has it.
    fn err(&self, message: impl Into<String>) -> Error {
        let message = message.into();
        match lines::offset_of_path(&self.text, lines::leading_path(&message)) {
            Some(offset) if !message.starts_with("line ") => case_error(
                &self.path,
                format!("line {}: {message}", line_of(&self.text, offset)),
            ),
            _ => case_error(&self.path, message),
        }
    }

    fn amplitude(&self, key: &str, a: &Option<AmplitudeRef>) -> Result<Amplitude> {
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

    fn surface(&self, key: &str, name: &str) -> Result<&crate::mesh::SurfaceSet> {
        self.mesh.surface(name).ok_or_else(|| Error::UnknownGroup {
            key: key.to_string(),
            kind: "surface set (2D physical group)",
            name: name.to_string(),
            available: self.mesh.surface_names(),
        })
    }

    /// The surface set `name` as a primary surface (its triangles).
    fn primary_surface(
        &self,
        key: &str,
        name: &str,
    ) -> Result<crate::contact::primary::PrimarySurface> {
        crate::contact::primary::PrimarySurface::from_mesh(&self.mesh, name).ok_or_else(|| {
            Error::UnknownGroup {
                key: key.to_string(),
                kind: "surface set (2D physical group)",
                name: name.to_string(),
                available: self.mesh.surface_names(),
            }
        })
    }

    fn node_set(&self, key: &str, name: &str) -> Result<&crate::mesh::NodeSet> {
        self.mesh.node_set(name).ok_or_else(|| Error::UnknownGroup {
            key: key.to_string(),
            kind: "node set (0D/1D physical group, .inp *NSET)",
            name: name.to_string(),
            available: self.mesh.node_set_names(),
        })
    }

    /// The nodes of `[[displacement]]` `i`: its `surface` or its `nodes`.
    fn displacement_nodes(&self, i: usize) -> Result<(String, Vec<usize>)> {
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

    fn region(&self, key: &str, name: &str) -> Result<&crate::mesh::Region> {
        self.mesh.region(name).ok_or_else(|| Error::UnknownGroup {
            key: key.to_string(),
            kind: "volume region (3D physical group)",
            name: name.to_string(),
            available: self.mesh.region_names(),
        })
    }

    fn material(&self, i: usize) -> Result<Arc<dyn Material>> {
        let key = format!("material[{i}]");
        Ok(match &self.spec.material[i].model {
            MaterialModel::Ogden(c) => Arc::new(material::Ogden::new(
                c.mu.clone(),
                c.alpha.clone(),
                c.bulk_modulus,
                &key,
            )?),
            MaterialModel::LinearElastic(c) => Arc::new(material::LinearElastic::new(
                c.youngs_modulus,
                c.poisson_ratio,
                &key,
            )?),
            MaterialModel::SaintVenantKirchhoff(c) => Arc::new(
                material::SaintVenantKirchhoff::new(c.youngs_modulus, c.poisson_ratio, &key)?,
            ),
            MaterialModel::NeoHookean(c) => Arc::new(material::NeoHookean::new(
                c.youngs_modulus,
                c.poisson_ratio,
                &key,
            )?),
        })
    }

    /// The names that become file names or that others refer to: the output
    /// name is a file stem, and steps, obstacles and contacts have distinct
    /// names.
    fn check_names(&self) -> Result<()> {
        let spec = &self.spec;
        if let Some(name) = &spec.output.name {
            if !is_file_stem(name) {
                return Err(self.err(format!(
                    "output.name = '{}': it names the output files, so use letters, digits, '-', '_' \
                     and '.', not first (no folder: set output.folder for that)",
                    crate::input::shorten(name)
                )));
            }
        }
        let duplicate = |table: &str, names: Vec<&str>| match first_duplicate(names.into_iter()) {
            Some((j, i, name)) => Err(self.err(format!(
                "{table}[{i}] has the name '{}' of {table}[{j}]; give each a name of its own",
                crate::input::shorten(name)
            ))),
            None => Ok(()),
        };
        duplicate("step", spec.step.iter().map(|s| s.name.as_str()).collect())?;
        duplicate(
            "obstacle",
            spec.obstacle.iter().map(|o| o.name.as_str()).collect(),
        )?;
        duplicate(
            "contact",
            spec.contact
                .iter()
                .map(|c| c.name.as_deref().unwrap_or(&c.surface))
                .collect(),
        )
    }

    /// Validate everything and build the problem.
    pub fn build_problem(&self) -> Result<Problem> {
        let spec = &self.spec;
        let mesh = &self.mesh;
        self.check_names()?;
        for name in spec.amplitudes.keys() {
            self.amplitude(
                &format!("amplitudes.{name}"),
                &Some(AmplitudeRef::Named(name.clone())),
            )?;
        }
        // materials: exactly one per element
        let mut materials: Vec<Arc<dyn Material>> = Vec::new();
        let mut element_material: Vec<Option<usize>> = vec![None; mesh.elements.len()];
        for (i, m) in spec.material.iter().enumerate() {
            let key = format!("material[{i}].region");
            let region = self.region(&key, &m.region)?;
            materials.push(self.material(i)?);
            for &e in &region.elements {
                if let Some(j) = element_material[e] {
                    return Err(self.err(format!(
                        "{key}: element {} of region '{}' already has the material of material[{j}] (region '{}'); give each element one material",
                        mesh.elements[e].id, m.region, spec.material[j].region
                    )));
                }
                element_material[e] = Some(i);
            }
        }
        let element_material = element_material
            .iter()
            .enumerate()
            .map(|(e, m)| {
                m.ok_or_else(|| {
                    let regions: Vec<&str> = mesh
                        .regions
                        .iter()
                        .filter(|r| r.elements.contains(&e))
                        .map(|r| r.name.as_str())
                        .collect();
                    self.err(format!(
                        "element {} (region {}) has no material: add a [[material]] with region = \"{}\"",
                        mesh.elements[e].id,
                        regions.join(", "),
                        regions.first().copied().unwrap_or("default")
                    ))
                })
            })
            .collect::<Result<Vec<_>>>()?;

        // the nested dissection of the elements' graph, on the idle core
        // as soon as that graph exists, if the run will order it so
        let defaults = SolverSettings::default();
        let dissect = crate::problem::dissects_element_graph(
            spec.solver.linear.unwrap_or(defaults.linear),
            spec.solver.strategy.unwrap_or(defaults.strategy),
            3 * mesh.num_nodes(),
            spec.contact.iter().map(|c| c.obstacle.is_some()),
        );
        let mut dissection = None;
        let on_graph = |graph: &NodeGraph| {
            if dissect {
                dissection = Some(EarlyDissection::start(graph));
            }
        };
        let model = Model::with_graph(mesh.clone(), materials, element_material, on_graph);
        let model = model.map_err(|f| {
            let (quadrature_point, det_j) = match f.failure {
                crate::assembly::kernel::KernelFailure::ReferenceInverted {
                    quadrature_point,
                    det_j,
                } => (quadrature_point, det_j),
                crate::assembly::kernel::KernelFailure::Inverted {
                    quadrature_point,
                    det_f,
                } => (quadrature_point, det_f),
            };
            Error::InvertedElement {
                element: mesh.elements[f.element].id,
                quadrature_point,
                det_j,
                in_reference: true,
                what: if det_j == 0.0 {
                    "degenerate"
                } else {
                    "inverted"
                },
            }
        })?;

        let mut prescribed = Vec::new();
        for (i, d) in spec.displacement.iter().enumerate() {
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
        let mut body_forces = Vec::new();
        for (i, b) in spec.body_force.iter().enumerate() {
            let key = format!("body_force[{i}]");
            let elements: Vec<usize> = match &b.region {
                Some(r) => self.region(&format!("{key}.region"), r)?.elements.clone(),
                None => (0..mesh.elements.len()).collect(),
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
        if spec.step.is_empty() {
            return Err(self.err("no [[step]]: add at least one step with name and end_time"));
        }
        let mut steps = Vec::new();
        let mut t0 = 0.0;
        let mut output = budget::Output::new(spec, mesh);
        for (i, s) in spec.step.iter().enumerate() {
            let key = format!("step[{i}]");
            let length = s.end_time - t0;
            if !s.end_time.is_finite() {
                return Err(self.err(not_positive(&format!("{key}.end_time"), s.end_time)));
            }
            if !(length > 0.0) {
                return Err(self.err(format!(
                    "{key}.end_time = {} must be greater than the previous step's end ({t0})",
                    s.end_time
                )));
            }
            let initial = s.initial_increment.unwrap_or(length);
            let max = s.max_increment.unwrap_or(length);
            let min = s.min_increment.unwrap_or(initial / 1024.0);
            for (name, v) in [
                ("initial_increment", initial),
                ("max_increment", max),
                ("min_increment", min),
            ] {
                if !(v > 0.0) || !v.is_finite() {
                    return Err(self.err(not_positive(&format!("{key}.{name}"), v)));
                }
            }
            if max < min {
                return Err(self.err(format!(
                    "{key}.max_increment = {max} is smaller than min_increment = {min}; \
                     give max_increment ≥ min_increment"
                )));
            }
            if min > initial {
                return Err(self.err(format!(
                    "{key}.min_increment = {min} exceeds initial_increment = {initial}"
                )));
            }
            let limit = s.max_increments.unwrap_or(budget::MAX_INCREMENTS);
            if let Some(fault) = budget::increments_fault(length, max, limit) {
                let max = crate::input::number(max);
                return Err(self.err(format!("{key}.max_increment = {max}: {fault}")));
            }
            if let Some(fault) = output.add_step(length, max) {
                return Err(self.err(format!("{key}: {fault}")));
            }
            steps.push(Step {
                name: s.name.clone(),
                end_time: s.end_time,
                initial_increment: initial.min(max),
                min_increment: min,
                max_increment: max,
            });
            t0 = s.end_time;
        }
        let d = SolverSettings::default();
        let sv = &spec.solver;
        let settings = SolverSettings {
            max_iterations: sv.max_iterations.unwrap_or(d.max_iterations),
            residual_tolerance: sv.residual_tolerance.unwrap_or(d.residual_tolerance),
            displacement_tolerance: sv
                .displacement_tolerance
                .unwrap_or(d.displacement_tolerance),
            line_search: sv.line_search.unwrap_or(d.line_search),
            max_cuts: sv.max_cuts.unwrap_or(d.max_cuts),
            growth_factor: sv.growth_factor.unwrap_or(d.growth_factor),
            easy_iterations: sv.easy_iterations.unwrap_or(d.easy_iterations),
            nonsymmetric: sv.nonsymmetric.unwrap_or(d.nonsymmetric),
            linear: sv.linear.unwrap_or(d.linear),
            predictor: sv.predictor.unwrap_or(d.predictor),
            strategy: sv.strategy.unwrap_or(d.strategy),
            petsc_options: sv
                .petsc
                .as_ref()
                .and_then(|p| p.options.clone())
                .unwrap_or_default(),
        };
        if sv.petsc.is_some() && settings.linear != LinearMethod::Petsc {
            return Err(self.err(
                "[solver.petsc] is set but solver.linear is not \"petsc\": \
                 add linear = \"petsc\" or remove [solver.petsc]"
                    .to_string(),
            ));
        }
        if settings.linear == LinearMethod::Petsc && !cfg!(feature = "petsc") {
            return Err(self.err(crate::solve::backend::PETSC_MISSING.to_string()));
        }
        for (name, v) in [
            ("residual_tolerance", settings.residual_tolerance),
            ("displacement_tolerance", settings.displacement_tolerance),
        ] {
            if !(v > 0.0 && v < 1.0) {
                return Err(self.err(format!("solver.{name} = {v} must be in (0, 1)")));
            }
        }
        if !settings.growth_factor.is_finite() {
            return Err(self.err(format!(
                "solver.growth_factor = {} is not a finite number; give a value ≥ 1 (default 1.5)",
                settings.growth_factor
            )));
        }
        if !(settings.growth_factor >= 1.0) {
            return Err(self.err(format!(
                "solver.growth_factor = {} must be ≥ 1",
                settings.growth_factor
            )));
        }
        if settings.max_iterations == 0 {
            return Err(self.err("solver.max_iterations must be at least 1"));
        }
        let mut problem = Problem {
            model,
            prescribed,
            pressures,
            body_forces,
            nodal_forces,
            contacts: Default::default(),
            steps,
            settings,
            timings: Default::default(),
            dissection,
        };
        let contacts = self.contacts(&problem)?;
        if !contacts.is_empty() {
            problem.set_contacts(contacts);
        }
        Ok(problem)
    }
}
