//! The result fields of a converged increment, by name: what the VTU files
//! hold and what an observer of a run reads in memory.
//!
//! A new field is one arm of [`NodalField`] or [`CellField`] (its name,
//! components and whether it needs contact) and one arm of
//! [`ConvergedIncrement::nodal`] or [`ConvergedIncrement::cells`].

use rayon::prelude::*;
use std::borrow::Cow;

use super::contact_fields::ContactFields;
use super::vtu::ArrayKind;
use crate::problem::{ContactState, Problem};
use crate::solve::stepping::IncrementRecord;

/// A field with values at the nodes (VTU point data).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Deserialize, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum NodalField {
    /// Displacement `u` (3 per node).
    Displacement,
    /// Contact pressure `t_N ≥ 0` (compressive), 0 off the contact surfaces.
    ContactPressure,
    /// Signed gap `g` (open > 0), NaN off the contact surfaces.
    Gap,
    /// 0 open, 1 stick (closed, frictionless included), 2 slip.
    ContactStatus,
    /// Contact traction on the body, `t_N n + t_T` (3 per node).
    ContactTraction,
    /// Accumulated slip vector (3 per node).
    Slip,
    /// The mesh file's id (tag) of the node, to find the nodes that
    /// messages, histories and profiles name.
    NodeId,
    /// This increment's slip `Δg_T^slip` (3 per node): the accumulated
    /// slip now minus at the previous increment.
    SlipIncrement,
    /// The accumulated slip `Σ Δg_T^slip` (3 per node): the same values as
    /// `slip`, under the name that says which of the two it is.
    AccumulatedSlip,
}

/// A field with values per element (VTU cell data).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Deserialize, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum CellField {
    /// Cauchy stress `σ = J⁻¹ F S Fᵀ`, averaged over the element's
    /// quadrature points (9 per element, row-major).
    CauchyStress,
    /// Von Mises stress of that average.
    VonMises,
    /// The index of the element's region, in the order `signorini check`
    /// lists the regions (0-based).
    Region,
}

impl NodalField {
    /// Every nodal field, in the order the VTU files list them (new fields
    /// go at the end, so the files keep their order; the Python relay takes
    /// them by name).
    pub const ALL: [NodalField; 9] = [
        NodalField::Displacement,
        NodalField::ContactPressure,
        NodalField::Gap,
        NodalField::ContactStatus,
        NodalField::ContactTraction,
        NodalField::Slip,
        NodalField::NodeId,
        NodalField::SlipIncrement,
        NodalField::AccumulatedSlip,
    ];

    /// The array name in the VTU files (a contract with users' scripts).
    pub fn name(self) -> &'static str {
        match self {
            NodalField::Displacement => "displacement",
            NodalField::ContactPressure => "contact_pressure",
            NodalField::Gap => "gap",
            NodalField::ContactStatus => "contact_status",
            NodalField::ContactTraction => "contact_traction",
            NodalField::Slip => "slip",
            NodalField::NodeId => "node_id",
            NodalField::SlipIncrement => "slip_increment",
            NodalField::AccumulatedSlip => "accumulated_slip",
        }
    }

    /// The number type of its array.
    pub fn kind(self) -> ArrayKind {
        match self {
            NodalField::ContactStatus | NodalField::NodeId => ArrayKind::Int64,
            _ => ArrayKind::Float64,
        }
    }

    /// Numbers per node.
    pub fn components(self) -> usize {
        match self {
            NodalField::Displacement
            | NodalField::ContactTraction
            | NodalField::Slip
            | NodalField::SlipIncrement
            | NodalField::AccumulatedSlip => 3,
            NodalField::ContactPressure
            | NodalField::Gap
            | NodalField::ContactStatus
            | NodalField::NodeId => 1,
        }
    }

    /// Whether the field exists only in a problem with contact.
    pub fn needs_contact(self) -> bool {
        !matches!(self, NodalField::Displacement | NodalField::NodeId)
    }
}

impl CellField {
    /// Every cell field, in the order the VTU files list them.
    pub const ALL: [CellField; 3] = [
        CellField::CauchyStress,
        CellField::VonMises,
        CellField::Region,
    ];

    /// The array name in the VTU files.
    pub fn name(self) -> &'static str {
        match self {
            CellField::CauchyStress => "cauchy_stress",
            CellField::VonMises => "von_mises",
            CellField::Region => "region",
        }
    }

    /// The number type of its array.
    pub fn kind(self) -> ArrayKind {
        match self {
            CellField::Region => ArrayKind::Int64,
            _ => ArrayKind::Float64,
        }
    }

    /// Numbers per element.
    pub fn components(self) -> usize {
        match self {
            CellField::CauchyStress => 9,
            CellField::VonMises | CellField::Region => 1,
        }
    }
}

/// A field of either kind, as the case file names it
/// (`[output] fields = ["displacement", "von_mises"]`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum OutputField {
    Nodal(NodalField),
    Cell(CellField),
}

impl OutputField {
    /// Every field, nodal ones first.
    pub fn all() -> impl Iterator<Item = OutputField> {
        NodalField::ALL
            .into_iter()
            .map(OutputField::Nodal)
            .chain(CellField::ALL.into_iter().map(OutputField::Cell))
    }

    /// The array name in the VTU files.
    pub fn name(self) -> &'static str {
        match self {
            OutputField::Nodal(f) => f.name(),
            OutputField::Cell(f) => f.name(),
        }
    }
}

impl std::str::FromStr for OutputField {
    type Err = String;
    /// By its VTU name; the error lists the names.
    fn from_str(name: &str) -> Result<Self, String> {
        OutputField::all()
            .find(|f| f.name() == name)
            .ok_or_else(|| {
                let names: Vec<&str> = OutputField::all().map(OutputField::name).collect();
                format!(
                    "unknown output field '{}'; the fields are: {}",
                    name.chars().take(60).collect::<String>(),
                    names.join(", ")
                )
            })
    }
}

impl<'de> serde::Deserialize<'de> for OutputField {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let name = String::deserialize(d)?;
        name.parse().map_err(serde::de::Error::custom)
    }
}

/// One converged increment, in memory: what every observer of a run
/// receives.
pub struct ConvergedIncrement<'a> {
    pub problem: &'a Problem,
    /// Step, time, increment size, Newton iterations and residuals.
    pub record: &'a IncrementRecord,
    /// The unknowns: displacements (3 per node), then contact multipliers.
    pub unknowns: &'a [f64],
    /// `r = f_int − f_ext − f_contact` over every dof: the reactions where
    /// displacements are prescribed.
    pub residual: &'a [f64],
    /// The contact history committed with this increment.
    pub contact: &'a ContactState,
    /// The stepper's state after it (with `unknowns` and `contact`, what a
    /// restart resumes from).
    pub stepping: &'a crate::solve::stepping::Stepping,
    /// The contact fields and per-interface totals.
    pub contact_fields: ContactFields,
}

impl ConvergedIncrement<'_> {
    /// The displacement of every node (3 per node).
    pub fn displacement(&self) -> &[f64] {
        &self.unknowns[..self.problem.model.num_dofs()]
    }

    /// The values of a nodal field, `field.components()` per node.
    pub fn nodal(&self, field: NodalField) -> Cow<'_, [f64]> {
        let c = &self.contact_fields;
        if field == NodalField::NodeId {
            let ids = &self.problem.model.mesh.node_ids;
            return Cow::Owned(ids.iter().map(|&id| id as f64).collect());
        }
        Cow::Borrowed(match field {
            NodalField::Displacement => self.displacement(),
            NodalField::ContactPressure => &c.pressure,
            NodalField::Gap => &c.gap,
            NodalField::ContactStatus => &c.status,
            NodalField::ContactTraction => &c.traction,
            NodalField::Slip | NodalField::AccumulatedSlip => &c.slip,
            NodalField::SlipIncrement => &c.slip_increment,
            NodalField::NodeId => &[],
        })
    }

    /// The values of each cell field of `fields`, `components()` per
    /// element (the stresses computed once for all of them).
    pub fn cells(&self, fields: &[CellField]) -> Vec<Vec<f64>> {
        if fields.is_empty() {
            return Vec::new();
        }
        let mesh = &self.problem.model.mesh;
        let needs_stress = fields.iter().any(|f| f != &CellField::Region);
        let stresses = if needs_stress {
            self.problem.model.cauchy_stresses(self.unknowns)
        } else {
            Vec::new()
        };
        fields
            .par_iter()
            .map(|field| match field {
                CellField::Region => {
                    let mut region = vec![0.0; mesh.elements.len()];
                    for (r, set) in mesh.regions.iter().enumerate() {
                        for &e in &set.elements {
                            region[e] = r as f64;
                        }
                    }
                    region
                }
                CellField::CauchyStress => stresses
                    .iter()
                    .flat_map(|s| {
                        // row-major: the transpose's columns
                        let t = s.transpose();
                        (0..9).map(move |i| t[i])
                    })
                    .collect(),
                CellField::VonMises => stresses.iter().map(crate::material::von_mises).collect(),
            })
            .collect()
    }

    /// The increment's linear solves by the sparse LU that were a fallback
    /// ([`lu_fallbacks`]).
    pub fn lu_fallbacks(&self) -> usize {
        lu_fallbacks(&self.problem.settings, self.record.lu_solves)
    }

    /// The total of `r` over the nodes of each surface set: the reaction
    /// force where displacements are prescribed.
    pub fn reaction_forces(&self) -> Vec<(String, [f64; 3])> {
        self.problem.surface_forces(self.residual)
    }
}

/// Of `lu_solves` solves by the sparse LU, those that were a fallback
/// (GMRES that did not converge, an LDLᵀ that broke down): all of them
/// unless `settings` chose the LU (`linear = "lu"`, or `nonsymmetric = "lu"`
/// under `linear = "auto"`), then none.
pub fn lu_fallbacks(settings: &crate::solve::settings::SolverSettings, lu_solves: usize) -> usize {
    use crate::solve::settings::{LinearMethod, NonsymmetricSolver};
    let chosen = match settings.linear {
        LinearMethod::Lu => true,
        LinearMethod::Auto => settings.nonsymmetric == NonsymmetricSolver::Lu,
        LinearMethod::Ldlt | LinearMethod::Mixed | LinearMethod::Gmres | LinearMethod::Petsc => {
            false
        }
    };
    if chosen {
        0
    } else {
        lu_solves
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solve::settings::{LinearMethod, NonsymmetricSolver, SolverSettings};

    /// LU solves are a fallback unless the settings chose the LU.
    #[test]
    fn lu_solves_are_fallbacks_unless_chosen() {
        let with = |linear, nonsymmetric| SolverSettings {
            linear,
            nonsymmetric,
            ..Default::default()
        };
        let default = SolverSettings::default();
        assert_eq!(lu_fallbacks(&default, 3), 3);
        assert_eq!(lu_fallbacks(&default, 0), 0);
        assert_eq!(
            lu_fallbacks(&with(LinearMethod::Auto, NonsymmetricSolver::Lu), 3),
            0
        );
        assert_eq!(
            lu_fallbacks(&with(LinearMethod::Lu, NonsymmetricSolver::Gmres), 3),
            0
        );
        for linear in [LinearMethod::Ldlt, LinearMethod::Mixed, LinearMethod::Gmres] {
            assert_eq!(lu_fallbacks(&with(linear, NonsymmetricSolver::Lu), 2), 2);
        }
    }
}
