//! The physics of a deck as the deck states it: materials, sections,
//! amplitudes, surface interactions, contact pairs and steps with their
//! boundary conditions, loads and output requests. Set and surface names
//! are those of the [`Mesh`](crate::mesh::Mesh) read from the same deck
//! (qualified by instance, node ids given as implicit node sets); what the
//! records mean in the case's terms is decided in `crate::case::deck`.

use std::path::PathBuf;

/// Where a record stands in the deck: the file (an included one, if
/// there) and the 1-based line of its keyword or data line.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Located {
    pub path: PathBuf,
    pub line: usize,
}

impl Located {
    /// An error at this place.
    pub fn error(&self, message: impl Into<String>) -> crate::Error {
        crate::Error::Deck {
            path: self.path.clone(),
            line: self.line,
            message: message.into(),
        }
    }
}

/// `*HYPERELASTIC` models, with Abaqus's constants.
#[derive(Clone, Debug, PartialEq)]
pub enum Hyperelastic {
    /// `NEO HOOKE`: `C10, D1`; `W = C10 (Ī₁ − 3) + (J − 1)²/D1`.
    NeoHooke { c10: f64, d1: f64 },
    /// `OGDEN, N=n`: `μ_i, α_i` then `D_i`;
    /// `W = Σ 2μ_i/α_i² (λ̄₁^α_i + λ̄₂^α_i + λ̄₃^α_i − 3) + Σ (J − 1)^(2i)/D_i`.
    Ogden {
        mu: Vec<f64>,
        alpha: Vec<f64>,
        d: Vec<f64>,
    },
}

/// `*MATERIAL, NAME=…` and its `*ELASTIC` or `*HYPERELASTIC`.
#[derive(Clone, Debug)]
pub struct MaterialDef {
    pub name: String,
    /// `*ELASTIC` (isotropic): `E, ν`.
    pub elastic: Option<(f64, f64)>,
    pub hyperelastic: Option<Hyperelastic>,
    /// `*DENSITY`: mass per unit reference volume `ρ` (read for `GRAV`).
    pub density: Option<f64>,
    pub at: Located,
}

/// `*SOLID SECTION, ELSET=…, MATERIAL=…` (the element set's region name).
#[derive(Clone, Debug)]
pub struct SectionDef {
    pub region: String,
    pub material: String,
    pub at: Located,
}

/// `*AMPLITUDE, NAME=…`: `(time, value)` pairs; `total_time` for
/// `TIME=TOTAL TIME` (default: step time).
#[derive(Clone, Debug)]
pub struct AmplitudeDef {
    pub name: String,
    pub points: Vec<(f64, f64)>,
    pub total_time: bool,
    pub at: Located,
}

/// `*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=…`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Overclosure {
    /// `HARD` (the default): no penetration.
    Hard,
    /// `LINEAR`: pressure = slope × overclosure.
    Linear { slope: f64 },
}

/// `*FRICTION`: `μ[, stick slope]` (CalculiX's second field), `LAGRANGE`
/// or `EXACT` for exact stick, `SLIP TOLERANCE=`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrictionDef {
    pub mu: f64,
    pub stick_slope: Option<f64>,
    pub exact: bool,
    pub slip_tolerance: Option<f64>,
}

/// `*SURFACE INTERACTION, NAME=…` and its behaviour and friction.
#[derive(Clone, Debug)]
pub struct InteractionDef {
    pub name: String,
    pub overclosure: Overclosure,
    pub friction: Option<FrictionDef>,
    pub at: Located,
}

/// `*CONTACT PAIR, TYPE=…`: the discretisation the deck asks for
/// (CalculiX's keyword; Abaqus writes `TYPE=SURFACE TO SURFACE` too).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum PairType {
    /// No `TYPE=` (CalculiX's default is `NODE TO SURFACE`).
    Unspecified,
    /// `TYPE=NODE TO SURFACE`.
    NodeToSurface,
    /// `TYPE=SURFACE TO SURFACE` (CalculiX's face-to-face penalty contact).
    SurfaceToSurface,
    /// `TYPE=MORTAR`, `LINMORTAR`, `PGMORTAR` or `PGLINMORTAR` (the name,
    /// upper case): CalculiX's mortar variants.
    Mortar(String),
}

impl PairType {
    /// The type of `TYPE=value` (any case, any spacing), or the message
    /// naming the types there are.
    pub fn parse(value: &str) -> Result<Self, String> {
        let words: Vec<String> = value
            .split_whitespace()
            .map(str::to_ascii_uppercase)
            .collect();
        match words.join(" ").as_str() {
            "NODE TO SURFACE" => Ok(Self::NodeToSurface),
            "SURFACE TO SURFACE" => Ok(Self::SurfaceToSurface),
            m @ ("MORTAR" | "LINMORTAR" | "PGMORTAR" | "PGLINMORTAR") => {
                Ok(Self::Mortar(m.to_string()))
            }
            _ => Err(format!(
                "*CONTACT PAIR, TYPE={value} is not known: give NODE TO SURFACE, SURFACE TO \
                 SURFACE, MORTAR, LINMORTAR, PGMORTAR or PGLINMORTAR"
            )),
        }
    }
}

/// `*CONTACT PAIR, INTERACTION=…[, TYPE=…]`: `secondary, primary` surfaces.
#[derive(Clone, Debug)]
pub struct ContactPairDef {
    pub interaction: String,
    pub pair_type: PairType,
    pub secondary: String,
    pub primary: String,
    pub at: Located,
}

/// One prescribed degree of freedom of a `*BOUNDARY` line: the node set
/// (an implicit `node:<id>` set for a node id), the dof (0, 1, 2 for x, y,
/// z) and the value.
#[derive(Clone, Debug)]
pub struct BoundaryDef {
    pub nodes: String,
    pub dof: usize,
    pub value: f64,
    pub amplitude: Option<String>,
    pub at: Located,
}

/// One `*CLOAD` component: the force on every node of `nodes`.
#[derive(Clone, Debug)]
pub struct CloadDef {
    pub nodes: String,
    pub dof: usize,
    pub value: f64,
    pub amplitude: Option<String>,
    pub at: Located,
}

/// A `*DLOAD` (`elset, P<k>, p`: an implicit surface `<elset>:S<k>`) or
/// `*DSLOAD` (`surface, P, p`) pressure.
#[derive(Clone, Debug)]
pub struct PressureDef {
    pub surface: String,
    pub value: f64,
    pub amplitude: Option<String>,
    pub at: Located,
}

/// A `*DLOAD` gravity line `elset, GRAV, g, n₁, n₂, n₃`: the body force
/// per unit reference volume `ρ g n` on the element set (`n` the unit
/// direction, normalised from the deck's; `ρ` each element's `*DENSITY`).
#[derive(Clone, Debug)]
pub struct GravityDef {
    /// The element set (its canonical name).
    pub elements: String,
    /// The acceleration `g n`.
    pub acceleration: [f64; 3],
    pub amplitude: Option<String>,
    pub at: Located,
}

/// Which output request.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum OutputKind {
    /// `*NODE FILE` / `*NODE OUTPUT`.
    NodeFile,
    /// `*EL FILE` / `*ELEMENT OUTPUT`.
    ElementFile,
    /// `*CONTACT FILE` / `*CONTACT OUTPUT`.
    ContactFile,
    /// `*NODE PRINT, NSET=…` (the node set).
    NodePrint(String),
}

/// An output request and its variables (`U`, `RF`, `S`, `CDIS`, …).
#[derive(Clone, Debug)]
pub struct OutputDef {
    pub kind: OutputKind,
    pub variables: Vec<String>,
    pub at: Located,
}

/// `*STEP … *END STEP`.
#[derive(Clone, Debug)]
pub struct StepDef {
    pub name: String,
    /// `NLGEOM` (`NLGEOM=NO` is `false`; absent: `false`).
    pub nlgeom: bool,
    /// `*STATIC` data: initial increment, period, min, max (as given).
    pub increments: [Option<f64>; 4],
    /// `*STATIC, DIRECT`: fixed increments.
    pub direct: bool,
    /// `TIME POINTS=` of `*STATIC` (the name of a `*TIME POINTS`).
    pub time_points: Option<String>,
    /// `OP=NEW` on a `*BOUNDARY`, `*CLOAD`, `*DLOAD`/`*DSLOAD` of the step:
    /// the earlier ones of that kind are removed.
    pub new_boundaries: bool,
    pub new_cloads: bool,
    pub new_pressures: bool,
    pub boundaries: Vec<BoundaryDef>,
    pub cloads: Vec<CloadDef>,
    pub pressures: Vec<PressureDef>,
    /// `*DLOAD` `GRAV` lines (`OP=NEW` removes them with the pressures).
    pub gravities: Vec<GravityDef>,
    pub outputs: Vec<OutputDef>,
    pub at: Located,
}

/// Everything the deck says besides the mesh.
#[derive(Clone, Debug, Default)]
pub struct Physics {
    pub materials: Vec<MaterialDef>,
    pub sections: Vec<SectionDef>,
    pub amplitudes: Vec<AmplitudeDef>,
    /// `*TIME POINTS, NAME=…`: the times.
    pub time_points: Vec<(String, Vec<f64>)>,
    pub interactions: Vec<InteractionDef>,
    pub contact_pairs: Vec<ContactPairDef>,
    /// `*BOUNDARY` before the first step: held from time 0.
    pub initial_boundaries: Vec<BoundaryDef>,
    pub steps: Vec<StepDef>,
    /// Keywords read that do not change the answer, `*NAME`, each once.
    pub without_effect: Vec<String>,
}

impl Physics {
    /// The `*MATERIAL` that `section` names (names compare without case).
    pub fn material_of(&self, section: &SectionDef) -> Option<&MaterialDef> {
        self.materials
            .iter()
            .find(|m| m.name.eq_ignore_ascii_case(&section.material))
    }
}

#[cfg(test)]
mod tests {
    use super::PairType;

    /// `TYPE=` in any case and spacing; an unknown one names the known.
    #[test]
    fn pair_types_parse_as_calculix_writes_them() {
        assert_eq!(
            PairType::parse("node  To surface"),
            Ok(PairType::NodeToSurface)
        );
        assert_eq!(
            PairType::parse("SURFACE TO SURFACE"),
            Ok(PairType::SurfaceToSurface)
        );
        assert_eq!(
            PairType::parse("PgLinMortar"),
            Ok(PairType::Mortar("PGLINMORTAR".into()))
        );
        let e = PairType::parse("SEGMENT").unwrap_err();
        assert!(e.contains("TYPE=SEGMENT") && e.contains("MORTAR"), "{e}");
    }
}
