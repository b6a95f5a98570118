//! The case file: parsing ([`schema`]) and validation into a [`Problem`].
//! Every check of the user's input lives here, with the key path in the
//! message.

pub mod budget;
pub mod deck;
pub mod diagnosis;
pub mod limits;
mod lines;
pub mod output;
pub mod schema;
mod tagged;

use crate::assembly::pattern::NodeGraph;
use crate::assembly::Model;
use crate::contact::friction::FrictionMultiplier;
use crate::contact::interface::ContactInterface;
use crate::contact::setup::{Enforcement, Method, SetupError};
use crate::contact::{RigidObstacle, TriangulatedSurface};
use crate::material::{self, Material};
use crate::mesh::Mesh;
use crate::problem::{
    Amplitude, BodyForce, LinearMethod, NodalForce, PrescribedDisplacement, PressureLoad, Problem,
    SolverSettings, Step,
};
use crate::solve::ordering::EarlyDissection;
use crate::{Error, Result};
use nalgebra::Vector3;
use schema::{
    AmplitudeRef, CaseFile, ContactMethod, FrictionMultiplierSpec, MaterialModel, ObstacleShape,
};
use std::path::{Path, PathBuf};
use std::sync::Arc;

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

fn case_error(path: &Path, message: impl Into<String>) -> Error {
    Error::Case {
        path: path.to_path_buf(),
        message: message.into(),
    }
}

/// Parse a case file's text. Errors name the line and the key path.
pub fn parse(path: &Path, text: &str) -> Result<CaseFile> {
    let spec = deserialize(path, text)?;
    if let Some((offset, message)) = limits::check(text) {
        return Err(case_error(
            path,
            format!("line {}: {message}", line_of(text, offset)),
        ));
    }
    Ok(spec)
}

/// The 1-based line of byte `offset` in `text`.
fn line_of(text: &str, offset: usize) -> usize {
    text[..offset.min(text.len())].matches('\n').count() + 1
}

/// The schema read from the text, or an error naming the line and the key.
fn deserialize(path: &Path, text: &str) -> Result<CaseFile> {
    let de = toml::Deserializer::new(text);
    serde_path_to_error::deserialize(de).map_err(|e| {
        let key = e.path().to_string();
        let inner = e.into_inner();
        let msg = inner.message().to_string();
        let line = |offset: usize| line_of(text, offset);
        if let Some((offset, message)) = tagged::refine(text, &key, &msg) {
            return case_error(path, format!("line {}: {message}", line(offset)));
        }
        let location = inner
            .span()
            .map(|s| format!("line {}: ", line(s.start)))
            .unwrap_or_default();
        let key = if key == "." {
            String::new()
        } else {
            format!("at key '{key}': ")
        };
        case_error(path, format!("{location}{key}{msg}"))
    })
}

/// Read the case file and its mesh; an Abaqus/CalculiX deck (`.inp`) is
/// read with its physics, as the case [`deck::load`] translates it into.
pub fn load(path: &Path) -> Result<Case> {
    if path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("inp"))
    {
        return deck::load(path);
    }
    let text = crate::input::read_text(path, "read case file", crate::input::MAX_CASE_FILE)?;
    from_text(path, &text)
}

/// A case from the text of a case file; its paths (the mesh, the output
/// folder) are relative to `base_dir`.
pub fn from_toml(text: &str, base_dir: &Path) -> Result<Case> {
    from_text(&base_dir.join("case"), text)
}

/// A case from the text of a case file without its `[mesh]` table and a
/// mesh built in code ([`Mesh::from_arrays`]); the text's other paths (the
/// output folder) are relative to `base_dir`. Errors are those of a case
/// file, with the same line numbers and key paths.
pub fn from_mesh(text: &str, base_dir: &Path, mesh: Mesh) -> Result<Case> {
    let path = base_dir.join("case");
    if text
        .parse::<toml::Table>()
        .is_ok_and(|t| t.contains_key("mesh"))
    {
        return Err(case_error(
            &path,
            "[mesh]: the mesh is given as arrays; remove the [mesh] table",
        ));
    }
    // the schema's [mesh] table, after the text so that its line numbers hold
    let text = format!(
        "{text}\n[mesh]\nfile = \"{}\"\n",
        crate::mesh::arrays::ARRAYS
    );
    let spec = parse(&path, &text)?;
    Ok(Case {
        path,
        spec,
        mesh: Arc::new(mesh),
        notes: Vec::new(),
        text,
    })
}

/// A case from the text of the case file at `path` (which names it in
/// messages; its folder resolves the mesh path).
fn from_text(path: &Path, text: &str) -> Result<Case> {
    let spec = parse(path, text)?;
    if spec.mesh.file.trim().is_empty() {
        return Err(case_error(
            path,
            "mesh.file is empty: give the path of the .msh file, relative to the case file",
        ));
    }
    let mesh_path = path
        .parent()
        .unwrap_or(Path::new("."))
        .join(&spec.mesh.file);
    let (mesh, notes) = crate::mesh::read_mesh_with(&mesh_path, &spec.mesh.input_limits())?;
    if mesh.elements.is_empty() {
        return Err(Error::Mesh {
            path: mesh_path,
            message: "the mesh has no volume elements (Tet4 or Hex8); mesh the volume (gmsh -3) and save it".into(),
        });
    }
    Ok(Case {
        path: path.to_path_buf(),
        spec,
        mesh: Arc::new(mesh),
        notes,
        text: text.to_string(),
    })
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
                    "{key}: no amplitude named '{name}' in [amplitudes]; it has: {}",
                    if have.is_empty() {
                        "none".to_string()
                    } else {
                        have.join(", ")
                    }
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

    /// The `[[obstacle]]` at index `i`, validated.
    fn obstacle(&self, i: usize) -> Result<RigidObstacle> {
        let o = &self.spec.obstacle[i];
        let with_key = |e: Error| self.err(format!("obstacle[{i}] ('{}'): {e}", o.name));
        let v = Vector3::from;
        Ok(match &o.shape {
            ObstacleShape::Plane { point, normal } => {
                RigidObstacle::plane(v(*point), v(*normal)).map_err(with_key)?
            }
            ObstacleShape::Sphere { center, radius } => {
                RigidObstacle::sphere(v(*center), *radius).map_err(with_key)?
            }
            ObstacleShape::Cylinder {
                point,
                axis,
                radius,
            } => RigidObstacle::cylinder(v(*point), v(*axis), *radius).map_err(with_key)?,
            ObstacleShape::Stl { file } => {
                RigidObstacle::Triangulated(TriangulatedSurface::from_stl(&self.dir().join(file))?)
            }
            ObstacleShape::Gmsh { file, surface } => {
                let mesh = crate::mesh::gmsh::read_surface_msh(&self.dir().join(file))?;
                RigidObstacle::Triangulated(TriangulatedSurface::from_surface_facets(
                    &mesh, surface,
                )?)
            }
        })
    }

    /// The `[[contact]]` interfaces, validated against the mesh and the
    /// obstacles, with automatic parameters where none are given.
    fn contacts(&self, problem: &Problem) -> Result<Vec<ContactInterface>> {
        let spec = &self.spec;
        let mesh = &self.mesh;
        // Young's modulus of the body under a surface set: of the stiffest
        // material among the elements that hold one of its nodes (of the
        // stiffest material of all without such elements)
        let youngs_of = |surface: &str| -> f64 {
            let model = &problem.model;
            let stiffest = |e: &mut dyn Iterator<Item = usize>| {
                e.map(|m| model.materials[m].reference_youngs_modulus())
                    .fold(0.0f64, f64::max)
            };
            let on_surface = mesh.surface(surface).map(|set| {
                let nodes: std::collections::HashSet<usize> = set
                    .facets
                    .iter()
                    .flat_map(|f| f.nodes.iter().copied())
                    .collect();
                stiffest(
                    &mut mesh
                        .elements
                        .iter()
                        .zip(&model.element_material)
                        .filter(|(e, _)| e.nodes.iter().any(|n| nodes.contains(n)))
                        .map(|(_, &m)| m),
                )
            });
            match on_surface {
                Some(e) if e > 0.0 => e,
                _ => stiffest(&mut (0..model.materials.len())),
            }
        };
        let mut out = Vec::new();
        for (i, c) in spec.contact.iter().enumerate() {
            let key = format!("contact[{i}]");
            self.surface(&format!("{key}.surface"), &c.surface)?;
            // what the secondary nodes touch
            enum Target<'a> {
                Obstacle(usize),
                Surface(&'a str),
            }
            let target = match (&c.obstacle, &c.primary) {
                (Some(name), None) => {
                    let index = spec
                        .obstacle
                        .iter()
                        .position(|o| &o.name == name)
                        .ok_or_else(|| {
                            let have: Vec<&str> =
                                spec.obstacle.iter().map(|o| o.name.as_str()).collect();
                            self.err(format!(
                                "{key}.obstacle: no [[obstacle]] named '{name}'; there are: {}",
                                if have.is_empty() {
                                    "none".to_string()
                                } else {
                                    have.join(", ")
                                }
                            ))
                        })?;
                    Target::Obstacle(index)
                }
                (None, Some(name)) => {
                    self.surface(&format!("{key}.primary"), name)?;
                    if name == &c.surface {
                        return Err(self.err(format!(
                            "{key}.primary = '{name}' is the secondary surface itself; name the surface of the other body"
                        )));
                    }
                    // validated as a primary surface (triangles) here, built by the constructors
                    self.primary_surface(&format!("{key}.primary"), name)?;
                    Target::Surface(name)
                }
                _ => {
                    return Err(self.err(format!(
                        "{key}: give either `obstacle` (a rigid [[obstacle]] name) or `primary` (a surface set of another body), not {}",
                        if c.obstacle.is_some() { "both" } else { "neither" }
                    )))
                }
            };
            // the passes: one, or with `two_pass` also the primary surface's
            // nodes against the secondary surface's triangles, each pass on
            // half of every node's tributary area
            if c.two_pass && !matches!(target, Target::Surface(_)) {
                return Err(self.err(format!(
                    "{key}.two_pass applies to contact between deformable bodies only (with `primary`); \
                     remove it, or name the other body's surface with `primary` instead of `obstacle`"
                )));
            }
            // two passes constrain the same motion twice (at least where
            // nodes coincide: the stacked blocks' 41 constraints have rank
            // 37), and a multiplier unknown per constraint makes the saddle
            // system singular (`tests/two_pass.rs`): only the methods
            // without multiplier unknowns
            if c.two_pass && matches!(c.method, ContactMethod::Rockafellar | ContactMethod::Slack) {
                return Err(self.err(format!(
                    "{key}.two_pass needs method = \"uzawa\" or \"penalty\" (method is \"{}\"): the two passes \
                     constrain the same motion twice, which makes the multiplier system of rockafellar and slack \
                     singular; uzawa reaches the same Lagrangian solution without multiplier unknowns",
                    if matches!(c.method, ContactMethod::Slack) {
                        "slack"
                    } else {
                        "rockafellar"
                    }
                )));
            }
            let name = c.name.clone().unwrap_or_else(|| c.surface.clone());
            let reverse = format!("{name}.reverse");
            if c.two_pass {
                if let Some(j) = spec
                    .contact
                    .iter()
                    .position(|o| o.name.as_deref().unwrap_or(&o.surface) == reverse)
                {
                    return Err(self.err(format!(
                        "{key}.two_pass names its reverse pass '{reverse}', which is the name of contact[{j}]; rename one of them"
                    )));
                }
            }
            let positive = |v: Option<f64>, name: &str| -> Result<Option<f64>> {
                match v {
                    Some(x) if !(x > 0.0 && x.is_finite()) => {
                        Err(self.err(not_positive(&format!("{key}.{name}"), x)))
                    }
                    v => Ok(v),
                }
            };
            let friction_coefficient = match (c.friction_coefficient, c.tangential_penalty) {
                (None, Some(_)) => {
                    return Err(self.err(format!(
                        "{key}.tangential_penalty is given without {key}.friction_coefficient; \
                         add the friction coefficient or remove the tangential penalty"
                    )))
                }
                (Some(mu), _) if !(mu >= 0.0 && mu.is_finite()) => {
                    return Err(self.err(format!(
                        "{key}.friction_coefficient = {mu} must be zero or positive"
                    )))
                }
                (mu, _) => mu,
            };
            let enforcement = Enforcement {
                method: match c.method {
                    ContactMethod::Penalty => Method::Penalty,
                    ContactMethod::Uzawa => Method::Uzawa,
                    ContactMethod::Rockafellar => Method::Rockafellar,
                    ContactMethod::Slack => Method::Slack,
                },
                penalty: positive(c.penalty, "penalty")?,
                scaling: positive(c.scaling, "scaling")?,
                youngs_modulus: youngs_of(&c.surface),
                primary_youngs_modulus: match &target {
                    Target::Surface(primary) => Some(youngs_of(primary)),
                    Target::Obstacle(_) => None,
                },
                friction_coefficient,
                tangential_penalty: positive(c.tangential_penalty, "tangential_penalty")?,
                exact_stick: c.exact_stick,
                friction_multiplier: match (c.friction_multiplier, c.method) {
                    (Some(FrictionMultiplierSpec::Newton), _) => FrictionMultiplier::Newton,
                    (None, ContactMethod::Rockafellar | ContactMethod::Slack) => {
                        FrictionMultiplier::Newton
                    }
                    _ => FrictionMultiplier::Outer,
                },
            };
            if let Some(spec) = c.friction_multiplier {
                let why = if !c.exact_stick {
                    Some("it applies to exact stick only: add exact_stick = true or remove it")
                } else if spec == FrictionMultiplierSpec::Newton
                    && !matches!(c.method, ContactMethod::Rockafellar | ContactMethod::Slack)
                {
                    Some("the tangential multipliers are unknowns of Newton beside the normal ones, which this method does not have: use friction_multiplier = \"outer\" or method = \"rockafellar\" or \"slack\"")
                } else {
                    None
                };
                if let Some(why) = why {
                    return Err(self.err(format!("{key}.friction_multiplier: {why}")));
                }
            }
            if c.exact_stick {
                let why = if friction_coefficient.is_none() {
                    Some("it needs friction: give friction_coefficient")
                } else if matches!(c.method, ContactMethod::Penalty) {
                    Some("the penalty method keeps the regularised law: use method = \"rockafellar\", \"slack\" or \"uzawa\"")
                } else {
                    None
                };
                if let Some(why) = why {
                    return Err(self.err(format!("{key}.exact_stick = true: {why}")));
                }
            }
            // the passes: one, or with `two_pass` also the primary surface's
            // nodes against the secondary surface's triangles, each pass on
            // half of every node's tributary area
            let reverse_pass = " (two_pass: the reverse pass)";
            let setup = |e: SetupError| {
                let (SetupError::NoArea(s)
                | SetupError::UnknownSurface(s)
                | SetupError::QuadraticSurface(s)
                | SetupError::Degenerate { surface: s, .. }) = &e;
                let pass = if *s == c.surface { "" } else { reverse_pass };
                self.err(match e {
                    SetupError::NoArea(_) => format!("{key}{pass}: surface '{s}' has no area"),
                    SetupError::Degenerate { element_size, .. } => format!(
                        "{key}{pass}: surface '{s}' has the element size {} (the square root of its \
                         mean area per node), not a positive finite length; check the mesh's coordinates",
                        crate::input::number(element_size)
                    ),
                    SetupError::UnknownSurface(_) => {
                        format!("{key}{pass}: the mesh has no surface set '{s}'")
                    }
                    SetupError::QuadraticSurface(_) => {
                        format!("{key}: {}", SetupError::quadratic_surface_message(s))
                    }
                })
            };
            // the same surface under another name (or one holding it); after
            // the checks of the keys, which name the case file's mistake first
            if let Target::Surface(name) = &target {
                let nodes_of = |surface: &str| -> std::collections::HashSet<usize> {
                    mesh.surface(surface)
                        .map(|set| {
                            set.facets
                                .iter()
                                .flat_map(|f| f.nodes.iter().copied())
                                .collect()
                        })
                        .unwrap_or_default()
                };
                let (secondary, primary) = (nodes_of(&c.surface), nodes_of(name));
                if !secondary.is_empty() && secondary.is_subset(&primary) {
                    return Err(self.err(format!(
                        "{key}: self-paired surface: every node of the secondary surface '{}' is also on the \
                         primary surface '{name}' (the same surface under another name, or one holding it), \
                         so each node would contact its own facets; name as primary the surface of the other \
                         body",
                        c.surface
                    )));
                }
            }
            let passes = match target {
                Target::Obstacle(index) => {
                    let o = &spec.obstacle[index];
                    let motion = o.motion.map(Vector3::from).unwrap_or_else(Vector3::zeros);
                    let amplitude =
                        self.amplitude(&format!("obstacle[{index}].amplitude"), &o.amplitude)?;
                    let obstacle = self.obstacle(index)?;
                    let interface =
                        ContactInterface::rigid(mesh, &c.surface, obstacle, &enforcement)
                            .map_err(setup)?;
                    vec![(
                        interface.named(&name).moving(motion, amplitude),
                        "",
                        format!("obstacle '{}'", o.name),
                    )]
                }
                Target::Surface(primary) if c.two_pass => {
                    let [forward, back] =
                        ContactInterface::two_pass(mesh, &c.surface, primary, &enforcement)
                            .map_err(setup)?;
                    vec![
                        (
                            forward.named(&name),
                            "",
                            format!("primary surface '{primary}'"),
                        ),
                        (
                            back.named(&reverse),
                            reverse_pass,
                            format!("primary surface '{}'", c.surface),
                        ),
                    ]
                }
                Target::Surface(primary) => {
                    let interface =
                        ContactInterface::between_bodies(mesh, &c.surface, primary, &enforcement)
                            .map_err(setup)?;
                    vec![(
                        interface.named(&name),
                        "",
                        format!("primary surface '{primary}'"),
                    )]
                }
            };
            for (interface, pass, against) in passes {
                // a surface that starts inside the obstacle is a set-up error
                let secondary = &interface.surface;
                let tolerance = c
                    .initial_penetration_tolerance
                    .unwrap_or(0.01 * interface.element_size);
                if !(tolerance >= 0.0 && tolerance.is_finite()) {
                    return Err(self.err(format!(
                        "{key}.initial_penetration_tolerance = {tolerance} must be zero or positive \
                         (the largest initial penetration accepted, a length)"
                    )));
                }
                let zero = vec![0.0; 3 * mesh.num_nodes()];
                let gaps = interface.gaps(&mesh.nodes, 0.0, &zero, None);
                // a plane with the whole body behind it (every node of the
                // mesh, not only the surface's: a plane raised into the body
                // leaves some in front): its normal points away
                if let Target::Obstacle(index) = &target {
                    let o = &spec.obstacle[*index];
                    if let ObstacleShape::Plane { point, normal } = &o.shape {
                        let length = Vector3::from(*normal).norm();
                        let height = |x: &[f64; 3]| {
                            (Vector3::from(*x) - Vector3::from(*point)).dot(&Vector3::from(*normal))
                                / length
                        };
                        if !gaps.is_empty()
                            && gaps.iter().all(|&g| g < -tolerance)
                            && mesh.nodes.iter().all(|x| height(x) < -tolerance)
                        {
                            let nearest = mesh
                                .nodes
                                .iter()
                                .map(height)
                                .fold(f64::NEG_INFINITY, f64::max);
                            return Err(self.err(format!(
                                "{key}: obstacle normal pointing away: the whole body is behind plane \
                                 '{}' (every node, the nearest at {nearest:.3e}), so its normal points away \
                                 from the body; flip it: normal = [{}, {}, {}]",
                                o.name,
                                -normal[0] + 0.0,
                                -normal[1] + 0.0,
                                -normal[2] + 0.0
                            )));
                        }
                    }
                }
                for (j, &g) in gaps.iter().enumerate() {
                    if g < -tolerance {
                        return Err(self.err(format!(
                            "{key}{pass}: node {} of surface '{secondary}' starts inside {against} (gap {g:.3e}, tolerance {tolerance:.3e}); \
                             move the bodies apart, or check the normal (an obstacle's must point toward the body)",
                            mesh.node_ids[interface.nodes[j]]
                        )));
                    }
                }
                out.push(interface);
            }
        }
        Ok(out)
    }
}
