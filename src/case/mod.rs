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
mod loads;
mod materials;
pub mod output;
mod read;
pub mod reference;
mod rotations;
pub mod schema;
mod solver;
mod steps;
mod tagged;

use crate::mesh::Mesh;
use crate::problem::{ContactPattern, Problem};
use crate::{Error, Result};
use read::{case_error, line_of};
use schema::{AmplitudeRef, CaseFile};
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

/// `{key} = {value} must be zero or positive` (`why` after it), or, for
/// an infinite or NaN value, that it is not a finite number.
pub(crate) fn not_non_negative(key: &str, value: f64, why: &str) -> String {
    if value.is_finite() {
        format!("{key} = {value} must be zero or positive{why}")
    } else {
        format!("{key} = {value} is not a finite number; give zero or a positive value{why}")
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
    /// contact[0].obstacle: …`) when the text has it. For a case read
    /// from an Abaqus/CalculiX deck the text is the case the deck converts
    /// to, not the deck, so the line is named as that case's, after the
    /// message.
    fn err(&self, message: impl Into<String>) -> Error {
        let message = message.into();
        let from_deck = self
            .path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("inp"));
        match lines::offset_of_path(&self.text, lines::leading_path(&message)) {
            Some(offset) if !message.starts_with("line ") => {
                let line = line_of(&self.text, offset);
                case_error(
                    &self.path,
                    if from_deck {
                        format!("{message} (line {line} of the case that `signorini convert` writes from this deck)")
                    } else {
                        format!("line {line}: {message}")
                    },
                )
            }
            _ => case_error(&self.path, message),
        }
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

    /// The node set `name` of the mesh, which must hold a node: an empty
    /// one (an `*NSET` with no lines) would constrain, load or report
    /// nothing without a word.
    fn node_set(&self, key: &str, name: &str) -> Result<&crate::mesh::NodeSet> {
        let set = self
            .mesh
            .node_set(name)
            .ok_or_else(|| Error::UnknownGroup {
                key: key.to_string(),
                kind: "node set (0D/1D physical group, .inp *NSET)",
                name: name.to_string(),
                available: self.mesh.node_set_names(),
            })?;
        if set.nodes.is_empty() {
            return Err(self.err(format!(
                "{key} = '{}': the node set has no nodes (an *NSET without node lines, or a \
                 physical group without entities), so it would act on nothing; give the set its \
                 nodes in the mesh, or name another set",
                crate::input::shorten(name)
            )));
        }
        Ok(set)
    }

    fn region(&self, key: &str, name: &str) -> Result<&crate::mesh::Region> {
        self.mesh.region(name).ok_or_else(|| Error::UnknownGroup {
            key: key.to_string(),
            kind: "volume region (3D physical group)",
            name: name.to_string(),
            available: self.mesh.region_names(),
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
                    "output.name = '{}': it names the output files, so use ASCII letters, digits, '-', \
                     '_' and '.', not first (no folder: set output.folder for that)",
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

    /// Validate everything and build the problem: the names, the
    /// amplitudes, the materials and the model, the loads, the steps, the
    /// solver settings, then the contacts (which read the model's
    /// materials for their automatic parameters).
    pub fn build_problem(&self) -> Result<Problem> {
        self.problem_with(true, ContactPattern::Newton)
    }

    /// [`Case::build_problem`] with the contact couplings of `pattern` in
    /// its sparsity pattern: a run builds the condensed path's until it
    /// has chosen its path (`crate::run::problem_as_run`).
    pub fn build_problem_with(&self, pattern: ContactPattern) -> Result<Problem> {
        self.problem_with(true, pattern)
    }

    /// [`Case::build_problem`] for a process of a distributed run
    /// (`mpirun`): the same problem, but its sparsity pattern holds only
    /// each node's diagonal block until the run gives the process its
    /// share of the elements and the pattern of their rows
    /// (`Problem::set_share`), so that no process builds the whole one.
    pub fn build_distributed_problem(&self) -> Result<Problem> {
        self.problem_with(false, ContactPattern::Newton)
    }

    /// [`Case::build_problem`], with the whole pattern or not, and the
    /// contact couplings of `pattern`.
    fn problem_with(&self, whole_pattern: bool, pattern: ContactPattern) -> Result<Problem> {
        self.check_names()?;
        for name in self.spec.amplitudes.keys() {
            self.amplitude(
                &format!("amplitudes.{name}"),
                &Some(AmplitudeRef::Named(name.clone())),
            )?;
        }
        let (materials, element_material) = self.element_materials()?;
        let (model, dissection) = self.model(materials, element_material, whole_pattern)?;
        let prescribed = self.prescribed()?;
        let rotations = self.rotations()?;
        let pressures = self.pressures()?;
        let body_forces = self.body_forces(&model)?;
        let nodal_forces = self.nodal_forces()?;
        let mut problem = Problem::builder(model)
            .prescribed(prescribed)
            .rotations(rotations)
            .pressures(pressures)
            .body_forces(body_forces)
            .nodal_forces(nodal_forces)
            .steps(self.steps()?)
            .settings(self.settings()?)
            .dissection(dissection)
            .build()
            .map_err(|e| self.err(e.to_string()))?;
        let contacts = self.contacts(&problem)?;
        problem.contacts.set_pattern(pattern);
        if !contacts.is_empty() {
            problem.set_contacts(contacts);
        }
        Ok(problem)
    }
}
