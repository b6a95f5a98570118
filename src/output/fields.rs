//! The result fields of a converged increment, by name: what the VTU files
//! hold and what an observer of a run reads in memory.
//!
//! A new field is one arm of [`NodalField`] or [`CellField`] (its name,
//! components and whether it needs contact) and one arm of
//! [`ConvergedIncrement::nodal`] or [`ConvergedIncrement::cells`].

use rayon::prelude::*;
use std::borrow::Cow;

use super::contact_fields::ContactFields;
use super::recovery::PatchRecovery;
use super::tensors::{green_lagrange_strain, logarithmic_strain, principal_values};
use super::vtu::ArrayKind;
use crate::material::Mat3;
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
    /// Cauchy stress at the nodes (9 per node, row-major), recovered from
    /// the element averages by superconvergent patch recovery
    /// ([`super::recovery`]).
    RecoveredCauchyStress,
    /// The principal values `σ₁ ≥ σ₂ ≥ σ₃` of the recovered nodal Cauchy
    /// stress (3 per node).
    RecoveredPrincipalStress,
    /// Von Mises stress of the recovered nodal Cauchy stress.
    RecoveredVonMises,
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
    /// The principal values `σ₁ ≥ σ₂ ≥ σ₃` of the element's averaged Cauchy
    /// stress (3 per element).
    PrincipalStress,
    /// Green–Lagrange strain `E = ½(FᵀF − I)`, averaged over the element's
    /// quadrature points (9 per element, row-major).
    GreenLagrangeStrain,
    /// Logarithmic (Hencky) strain `ln V = ½ ln(F Fᵀ)` (spatial), averaged
    /// over the element's quadrature points (9 per element, row-major).
    LogarithmicStrain,
}

impl NodalField {
    /// Every nodal field read from the state, in the order the VTU files
    /// list them (new fields go at the end, so the files keep their order;
    /// the Python relay takes them by name).
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

    /// The nodal fields recovered from the element stresses, after
    /// [`Self::ALL`] in the VTU files.
    pub const RECOVERED: [NodalField; 3] = [
        NodalField::RecoveredCauchyStress,
        NodalField::RecoveredPrincipalStress,
        NodalField::RecoveredVonMises,
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
            NodalField::RecoveredCauchyStress => "recovered_cauchy_stress",
            NodalField::RecoveredPrincipalStress => "recovered_principal_stress",
            NodalField::RecoveredVonMises => "recovered_von_mises",
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
            | NodalField::AccumulatedSlip
            | NodalField::RecoveredPrincipalStress => 3,
            NodalField::RecoveredCauchyStress => 9,
            NodalField::ContactPressure
            | NodalField::Gap
            | NodalField::ContactStatus
            | NodalField::NodeId
            | NodalField::RecoveredVonMises => 1,
        }
    }

    /// Whether the field exists only in a problem with contact.
    pub fn needs_contact(self) -> bool {
        !matches!(self, NodalField::Displacement | NodalField::NodeId) && !self.is_recovered()
    }

    /// Whether the field is recovered from the element stresses.
    pub fn is_recovered(self) -> bool {
        NodalField::RECOVERED.contains(&self)
    }
}

impl CellField {
    /// Every cell field, in the order the VTU files list them.
    pub const ALL: [CellField; 6] = [
        CellField::CauchyStress,
        CellField::VonMises,
        CellField::Region,
        CellField::PrincipalStress,
        CellField::GreenLagrangeStrain,
        CellField::LogarithmicStrain,
    ];

    /// The array name in the VTU files.
    pub fn name(self) -> &'static str {
        match self {
            CellField::CauchyStress => "cauchy_stress",
            CellField::VonMises => "von_mises",
            CellField::Region => "region",
            CellField::PrincipalStress => "principal_stress",
            CellField::GreenLagrangeStrain => "green_lagrange_strain",
            CellField::LogarithmicStrain => "logarithmic_strain",
        }
    }

    /// The number type of its array.
    pub fn kind(self) -> ArrayKind {
        match self {
            CellField::Region => ArrayKind::Int64,
            _ => ArrayKind::Float64,
        }
    }

    /// Whether the field is computed from the element stresses.
    pub fn needs_stress(self) -> bool {
        matches!(
            self,
            CellField::CauchyStress | CellField::VonMises | CellField::PrincipalStress
        )
    }

    /// Numbers per element.
    pub fn components(self) -> usize {
        match self {
            CellField::CauchyStress
            | CellField::GreenLagrangeStrain
            | CellField::LogarithmicStrain => 9,
            CellField::PrincipalStress => 3,
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
            .chain(NodalField::RECOVERED)
            .map(OutputField::Nodal)
            .chain(CellField::ALL.into_iter().map(OutputField::Cell))
    }

    /// The fields a run writes when `[output] fields` names none: every
    /// nodal field read from the state, and the element `cauchy_stress`,
    /// `von_mises` and `region`. The recovered nodal stresses, the
    /// principal stresses and the strains are written when named: on the
    /// Hertz example they nearly triple each VTU file (4.7 → 13.1 MB) and
    /// add 0.18 s to a 0.65 s run (paired timing, 10 pairs), which the race
    /// against CalculiX would pay for arrays it does not read.
    pub fn default_set() -> impl Iterator<Item = OutputField> {
        NodalField::ALL.into_iter().map(OutputField::Nodal).chain(
            [
                CellField::CauchyStress,
                CellField::VonMises,
                CellField::Region,
            ]
            .into_iter()
            .map(OutputField::Cell),
        )
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
                    "unknown output field '{}'; the fields are: {}{}",
                    name.chars().take(60).collect::<String>(),
                    names.join(", "),
                    crate::error::suggest::hint(name, &names)
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
        let c = &self.contact_fields.nodal;
        if field == NodalField::NodeId {
            let ids = &self.problem.model.mesh.node_ids;
            return Cow::Owned(ids.iter().map(|&id| id as f64).collect());
        }
        if field.is_recovered() {
            let recovery = PatchRecovery::new(&self.problem.model.mesh);
            let stresses = self.element_stresses();
            return Cow::Owned(self.recovered(&[field], &stresses, &recovery).remove(0));
        }
        Cow::Borrowed(match field {
            NodalField::Displacement => self.displacement(),
            NodalField::ContactPressure => &c.pressure,
            NodalField::Gap => &c.gap,
            NodalField::ContactStatus => &c.status,
            NodalField::ContactTraction => &c.traction,
            NodalField::Slip | NodalField::AccumulatedSlip => &c.slip,
            NodalField::SlipIncrement => &c.slip_increment,
            NodalField::NodeId
            | NodalField::RecoveredCauchyStress
            | NodalField::RecoveredPrincipalStress
            | NodalField::RecoveredVonMises => &[],
        })
    }

    /// The Cauchy stress of every element, averaged over its quadrature
    /// points.
    pub fn element_stresses(&self) -> Vec<Mat3> {
        self.problem.model.cauchy_stresses(self.unknowns)
    }

    /// The values of each recovered nodal field of `fields` (others give
    /// an empty list), `components()` per node, from the element stresses
    /// `stresses` by the mesh's patch recovery `recovery`.
    pub fn recovered(
        &self,
        fields: &[NodalField],
        stresses: &[Mat3],
        recovery: &PatchRecovery,
    ) -> Vec<Vec<f64>> {
        if !fields.iter().any(|f| f.is_recovered()) {
            return vec![Vec::new(); fields.len()];
        }
        let nodal = recovery.recover(stresses);
        fields
            .iter()
            .map(|field| match field {
                NodalField::RecoveredCauchyStress => nodal.iter().flat_map(row_major).collect(),
                NodalField::RecoveredPrincipalStress => {
                    nodal.iter().flat_map(principal_values).collect()
                }
                NodalField::RecoveredVonMises => {
                    nodal.iter().map(crate::material::von_mises).collect()
                }
                _ => Vec::new(),
            })
            .collect()
    }

    /// The values of each cell field of `fields`, `components()` per
    /// element (the stresses computed once for all of them).
    pub fn cells(&self, fields: &[CellField]) -> Vec<Vec<f64>> {
        let stresses = if fields.iter().any(|f| f.needs_stress()) {
            self.element_stresses()
        } else {
            Vec::new()
        };
        self.cells_from(fields, &stresses)
    }

    /// [`Self::cells`] with the element stresses given (empty if no field
    /// needs them).
    pub fn cells_from(&self, fields: &[CellField], stresses: &[Mat3]) -> Vec<Vec<f64>> {
        let model = &self.problem.model;
        let mesh = &model.mesh;
        fields
            .par_iter()
            .map(|field| match field {
                CellField::Region => region_indices(mesh),
                CellField::CauchyStress => stresses.iter().flat_map(row_major).collect(),
                CellField::VonMises => stresses.iter().map(crate::material::von_mises).collect(),
                CellField::PrincipalStress => stresses.iter().flat_map(principal_values).collect(),
                CellField::GreenLagrangeStrain => model
                    .element_averages(self.displacement(), green_lagrange_strain)
                    .iter()
                    .flat_map(row_major)
                    .collect(),
                CellField::LogarithmicStrain => model
                    .element_averages(self.displacement(), logarithmic_strain)
                    .iter()
                    .flat_map(row_major)
                    .collect(),
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

/// The index of each element's region, in the order of `mesh.regions`.
pub fn region_indices(mesh: &crate::mesh::Mesh) -> Vec<f64> {
    let mut region = vec![0.0; mesh.elements.len()];
    for (r, set) in mesh.regions.iter().enumerate() {
        for &e in &set.elements {
            region[e] = r as f64;
        }
    }
    region
}

/// The entries of `m` row by row (the VTU files' order of a tensor).
fn row_major(m: &Mat3) -> [f64; 9] {
    let t = m.transpose(); // column-major storage of the transpose
    std::array::from_fn(|i| t[i])
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
