//! The case file schema (TOML). Every table rejects unknown keys, so a
//! misspelled key is an error that names its path. Units are the user's,
//! consistent throughout (e.g. mm, N, MPa).

use schemars::JsonSchema;
use serde::de::Error as _;
use serde::{Deserialize, Deserializer};

/// `[x, y, z]`: exactly three numbers (serde reads the first three of a
/// longer array and ignores the rest).
fn three<'de, D: Deserializer<'de>>(d: D) -> Result<[f64; 3], D::Error> {
    let v = Vec::<f64>::deserialize(d)?;
    <[f64; 3]>::try_from(v.as_slice())
        .map_err(|_| D::Error::invalid_length(v.len(), &"an array of 3 numbers [x, y, z]"))
}

/// An optional [`three`].
fn option_three<'de, D: Deserializer<'de>>(d: D) -> Result<Option<[f64; 3]>, D::Error> {
    three(d).map(Some)
}

/// A whole case file.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CaseFile {
    /// `[mesh]`: the mesh to read.
    pub mesh: MeshSpec,
    /// `[[material]]`: one per volume region.
    #[serde(default)]
    pub material: Vec<MaterialSpec>,
    /// `[[displacement]]`: prescribed displacement components on a surface.
    #[serde(default)]
    pub displacement: Vec<DisplacementSpec>,
    /// `[[pressure]]`: pressure on a surface.
    #[serde(default)]
    pub pressure: Vec<PressureSpec>,
    /// `[[body_force]]`: force per unit reference volume.
    #[serde(default)]
    pub body_force: Vec<BodyForceSpec>,
    /// `[[nodal_force]]`: a total force spread over a node set.
    #[serde(default)]
    pub nodal_force: Vec<NodalForceSpec>,
    /// `[[obstacle]]`: rigid obstacles.
    #[serde(default)]
    pub obstacle: Vec<ObstacleSpec>,
    /// `[[contact]]`: a surface of the body against an obstacle.
    #[serde(default)]
    pub contact: Vec<ContactSpec>,
    /// `[amplitudes]`: named piecewise-linear functions of pseudo-time,
    /// `name = [[t0, v0], [t1, v1], …]` (each point two numbers, checked
    /// with the key path at validation).
    #[serde(default)]
    pub amplitudes: std::collections::BTreeMap<String, Vec<Vec<f64>>>,
    /// `[[step]]`: load steps in sequence.
    pub step: Vec<StepSpec>,
    /// `[solver]`: Newton and stepping controls.
    #[serde(default)]
    pub solver: SolverSpec,
    /// `[output]`: where and what to write.
    #[serde(default)]
    pub output: OutputSpec,
    /// `[units]`: the names of the length and force units, for the plots'
    /// labels only.
    #[serde(default)]
    pub units: UnitsSpec,
}

/// `[units]`: `length = "mm"`, `force = "N"` (each optional). Labels only:
/// the numbers of the case are the user's consistent units and nothing is
/// converted; a plot of a pressure reads `N/mm²`.
#[derive(Debug, Default, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct UnitsSpec {
    pub length: Option<String>,
    pub force: Option<String>,
}

/// `[mesh]`
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct MeshSpec {
    /// Gmsh `.msh` file (MSH 2.2 or 4.1, ASCII or binary) or, by the
    /// extension `.inp`, an Abaqus/CalculiX deck; relative to the case file.
    pub file: String,
    /// The most ids the `GENERATE` lines of an `.inp` deck (with its
    /// includes) may list together; default
    /// [`crate::input::MAX_GENERATED_IDS`] (10⁸).
    pub max_generated_ids: Option<u64>,
}

impl MeshSpec {
    /// The limits the mesh's files are read within.
    pub fn input_limits(&self) -> crate::input::Limits {
        let default = crate::input::Limits::default();
        crate::input::Limits {
            generated_ids: self.max_generated_ids.unwrap_or(default.generated_ids),
        }
    }
}

/// `[[material]]`: a region and its constitutive model. The `model` key
/// chooses the variant, and each variant rejects the keys of the others
/// (an Ogden material with `youngs_modulus` is an error naming the key).
#[derive(Debug, Deserialize, JsonSchema)]
pub struct MaterialSpec {
    /// Volume region (3D physical group) name.
    pub region: String,
    /// `model = "linear_elastic"`, `"saint_venant_kirchhoff"`,
    /// `"neo_hookean"` or `"ogden"`, with that model's constants.
    #[serde(flatten)]
    pub model: MaterialModel,
}

/// Constitutive models, tagged by the case file's `model` key.
#[derive(Clone, Debug, Deserialize, PartialEq, JsonSchema)]
#[serde(tag = "model", rename_all = "snake_case")]
pub enum MaterialModel {
    LinearElastic(ElasticConstants),
    SaintVenantKirchhoff(ElasticConstants),
    NeoHookean(ElasticConstants),
    Ogden(OgdenConstants),
}

/// Constants of the models given by Young's modulus and Poisson's ratio.
#[derive(Clone, Copy, Debug, Deserialize, PartialEq, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ElasticConstants {
    /// Young's modulus `E > 0`.
    pub youngs_modulus: f64,
    /// Poisson's ratio `−1 < ν < 0.5`.
    pub poisson_ratio: f64,
}

/// Constants of the Ogden model.
#[derive(Clone, Debug, Deserialize, PartialEq, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct OgdenConstants {
    /// Shear moduli `μ_p` (initial shear modulus `Σ μ_p`).
    pub mu: Vec<f64>,
    /// Exponents `α_p` (`μ_p α_p > 0`).
    pub alpha: Vec<f64>,
    /// Bulk modulus `κ > 0`.
    pub bulk_modulus: f64,
}

impl MaterialModel {
    /// The model's name as the case file writes it (`neo_hookean`,
    /// `ogden`, …), as messages print it.
    pub fn name(&self) -> &'static str {
        match self {
            Self::LinearElastic(_) => "linear_elastic",
            Self::SaintVenantKirchhoff(_) => "saint_venant_kirchhoff",
            Self::NeoHookean(_) => "neo_hookean",
            Self::Ogden(_) => "ogden",
        }
    }
}

/// An amplitude: the name of one in `[amplitudes]`, or inline points.
#[derive(Debug, Deserialize, Clone, JsonSchema)]
#[serde(
    untagged,
    expecting = "expected the name of an amplitude of [amplitudes] or its points [[t0, v0], [t1, v1], …]"
)]
pub enum AmplitudeRef {
    Named(String),
    /// `[[t0, v0], [t1, v1], …]` (each point two numbers, checked at
    /// validation: serde would ignore a third).
    Points(Vec<Vec<f64>>),
}

/// `[[displacement]]`: any of `x`, `y`, `z` given are prescribed, the others
/// are free, on the nodes of `surface` or of `nodes` (one of the two).
/// With `rotation`, the set moves rigidly: all three components are
/// prescribed, `u = (R(θ) − I)(X − c) + (x, y, z)` (a missing `x`, `y`,
/// `z` is 0), and no other `[[displacement]]` may prescribe its nodes.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct DisplacementSpec {
    /// Surface set (2D physical group, `.inp` surface) name.
    pub surface: Option<String>,
    /// Node set (0D/1D physical group, `.inp` `*NSET`) name.
    pub nodes: Option<String>,
    pub x: Option<f64>,
    pub y: Option<f64>,
    pub z: Option<f64>,
    /// Scales the values; default: ramp 0 → 1 over the first step.
    pub amplitude: Option<AmplitudeRef>,
    /// A finite rotation of the set about an axis (exact at any angle).
    pub rotation: Option<RotationSpec>,
}

/// `rotation = { axis = [0, 0, 1], centre = [x, y, z], angle = 90 }`: the
/// rotation `R(θ)` by `θ = angle · amplitude(t)` degrees, right-handed
/// about `axis` through `centre` (Rodrigues' formula).
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RotationSpec {
    /// Axis direction (non-zero; its length does not matter).
    #[serde(deserialize_with = "three")]
    pub axis: [f64; 3],
    /// A point of the axis, reference configuration (length unit).
    #[serde(deserialize_with = "three")]
    pub centre: [f64; 3],
    /// Angle in degrees, right-handed about `axis`.
    pub angle: f64,
    /// Scales the angle; default: the `[[displacement]]`'s `amplitude`
    /// (whose default is the ramp 0 → 1 over the first step).
    pub amplitude: Option<AmplitudeRef>,
}

/// `[[pressure]]`
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct PressureSpec {
    /// Surface set name.
    pub surface: String,
    /// Pressure, positive pushing into the body.
    pub value: f64,
    /// `true`: follows the deformed surface; `false` (default): dead load on
    /// the reference normal and area.
    #[serde(default)]
    pub follower: bool,
    pub amplitude: Option<AmplitudeRef>,
}

/// `[[body_force]]`
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct BodyForceSpec {
    /// Volume region; all elements if omitted.
    pub region: Option<String>,
    /// Force per unit reference volume (e.g. `ρ g`).
    #[serde(deserialize_with = "three")]
    pub value: [f64; 3],
    pub amplitude: Option<AmplitudeRef>,
}

/// `[[nodal_force]]`: the total force `value` split equally over the nodes
/// of a node set (`value / n` on each of its `n` nodes).
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct NodalForceSpec {
    /// Node set (0D/1D physical group, `.inp` `*NSET`) name.
    pub nodes: String,
    /// Total force on the set (force unit), fixed in direction.
    pub value: [f64; 3],
    pub amplitude: Option<AmplitudeRef>,
}

/// `[[obstacle]]`: a rigid obstacle. Its outward normal points toward the
/// body (for an STL surface: the triangles' right-hand normals). The
/// `shape` key chooses the geometry, and each shape rejects the keys of the
/// others (a plane with a `radius` is an error naming the key).
#[derive(Debug, Deserialize, JsonSchema)]
pub struct ObstacleSpec {
    /// Name that `[[contact]]` refers to.
    pub name: String,
    /// `shape = "plane"`, `"sphere"`, `"cylinder"`, `"stl"` or `"gmsh"`,
    /// with that shape's keys.
    #[serde(flatten)]
    pub shape: ObstacleShape,
    /// Rigid translation, scaled by `amplitude` (default none).
    #[serde(default, deserialize_with = "option_three")]
    pub motion: Option<[f64; 3]>,
    pub amplitude: Option<AmplitudeRef>,
}

/// Obstacle shapes, tagged by the case file's `shape` key.
#[derive(Clone, Debug, Deserialize, PartialEq, JsonSchema)]
#[serde(tag = "shape", rename_all = "snake_case", deny_unknown_fields)]
pub enum ObstacleShape {
    Plane {
        /// A point on the plane.
        #[serde(deserialize_with = "three")]
        point: [f64; 3],
        /// The outward normal (toward the body); need not be unit.
        #[serde(deserialize_with = "three")]
        normal: [f64; 3],
    },
    Sphere {
        #[serde(deserialize_with = "three")]
        center: [f64; 3],
        /// Radius > 0.
        radius: f64,
    },
    Cylinder {
        /// A point on the axis.
        #[serde(deserialize_with = "three")]
        point: [f64; 3],
        /// Axis direction; need not be unit.
        #[serde(deserialize_with = "three")]
        axis: [f64; 3],
        /// Radius > 0.
        radius: f64,
    },
    /// A triangulated surface read from an STL file, relative to the case
    /// file.
    Stl { file: String },
    /// A triangulated surface: the surface set (2D physical group)
    /// `surface` of a Gmsh mesh `file` (quadrangles split in two).
    Gmsh { file: String, surface: String },
}

impl ObstacleShape {
    /// The shape's name as the case file writes it.
    pub fn name(&self) -> &'static str {
        match self {
            Self::Plane { .. } => "plane",
            Self::Sphere { .. } => "sphere",
            Self::Cylinder { .. } => "cylinder",
            Self::Stl { .. } => "stl",
            Self::Gmsh { .. } => "gmsh",
        }
    }
}

/// Enforcement methods of the normal contact constraint.
#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq, Default, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum ContactMethod {
    Penalty,
    Uzawa,
    /// Monolithic Rockafellar augmented Lagrangian (the default).
    #[default]
    Rockafellar,
    /// The paper's slack-variable augmented Lagrangian.
    Slack,
}

/// `[[contact]] friction_multiplier`.
#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum FrictionMultiplierSpec {
    Newton,
    Outer,
}

/// `[[contact]] discretisation`.
#[derive(Clone, Copy, Debug, Default, Deserialize, PartialEq, Eq, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum DiscretisationSpec {
    /// Each secondary node against the primary triangle it projects on.
    NodeToSurface,
    /// Dual mortar (segment-to-segment): weighted gaps and one multiplier
    /// per secondary node (between two bodies, with Coulomb friction on the
    /// frame-indifferent weighted slip, or against a rigid obstacle, with
    /// or without friction; one pass): the default where it takes the
    /// pairing and keeps the run's path (`ContactSpec::discretisation`).
    #[default]
    Mortar,
}

/// `[[contact]]`: frictionless node-to-surface contact of a surface set
/// of the body (its nodes are the secondary nodes) with an obstacle.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ContactSpec {
    /// Name in reports; default: the surface's name.
    pub name: Option<String>,
    /// Secondary surface set of the body.
    pub surface: String,
    /// An `[[obstacle]]` name (contact with a rigid obstacle) …
    pub obstacle: Option<String>,
    /// … or a surface set of another body of the mesh (contact between
    /// deformable bodies: the secondary nodes against its triangles).
    pub primary: Option<String>,
    /// `penalty`, `uzawa`, `rockafellar` (default) or `slack`.
    #[serde(default)]
    pub method: ContactMethod,
    /// ε (penalty, Uzawa) or p (Rockafellar, slack); default `E/h_s` at each
    /// secondary node (100 `E/h_s` for Uzawa, see
    /// `contact::laws::uzawa::AUTOMATIC_FACTOR`), `E` the Young's modulus
    /// of the secondary surface's body, `h_s` the square root of the node's
    /// tributary area; between two bodies the harmonic mean of that and
    /// the primary side's `E_p/h_p` (`contact::setup::pair_stiffness`).
    pub penalty: Option<f64>,
    /// k (Rockafellar, slack); default `E/h_s` per node.
    pub scaling: Option<f64>,
    /// Coulomb friction coefficient `μ ≥ 0`; default 0 (frictionless).
    pub friction_coefficient: Option<f64>,
    /// Tangential penalty `ε_T` of the friction law (traction per unit
    /// elastic slip); default: the normal penalty (`E/h_s` per node).
    pub tangential_penalty: Option<f64>,
    /// Exact stick: the tangential augmented Lagrangian of Simo and
    /// Laursen, so that sticking nodes do not move at convergence and the
    /// answer does not depend on `tangential_penalty`; with method
    /// rockafellar, slack or uzawa, against an obstacle or a primary
    /// surface. Default: true with friction and one of those methods
    /// (rockafellar and slack solve for the tangential multipliers in
    /// Newton, uzawa in its outer loop), false with penalty or without
    /// friction; `false`: the regularised Coulomb law (elastic slip
    /// `t_T/ε_T` while sticking).
    pub exact_stick: Option<bool>,
    /// How exact stick finds its tangential multiplier: `"newton"` (the
    /// default with rockafellar and slack: two unknowns of Newton per node,
    /// Alart–Curnier's form, one Newton solve per increment) or `"outer"`
    /// (Simo–Laursen's loop of Newton solves, the tangential multiplier
    /// updated after each; uzawa's only one). Only with exact stick.
    pub friction_multiplier: Option<FrictionMultiplierSpec>,
    /// Largest initial penetration accepted; default 1 % of the contact
    /// element size.
    pub initial_penetration_tolerance: Option<f64>,
    /// Symmetric (two-pass) node-to-surface contact, with `primary` only:
    /// a second interface `<name>.reverse` checks the primary surface's
    /// nodes against the secondary's triangles, and both interfaces use
    /// half of each node's tributary area (default false: one pass).
    #[serde(default)]
    pub two_pass: bool,
    /// `"node_to_surface"` or `"mortar"`: dual mortar between two bodies
    /// (with `primary`, with or without friction) or against a rigid
    /// obstacle (with `obstacle`, with or without friction: the slip
    /// relative to the obstacle, Newton's path), one pass; linear and
    /// quadratic faces; `contact_pressure` is then the multiplier `λ_j`,
    /// the force over the node's current area (`contact_traction`: per
    /// reference area). Default: `"mortar"` wherever mortar takes the
    /// pairing and keeps the run on the path node-to-surface would take;
    /// `"node_to_surface"` with `two_pass` (mortar has one pass), and on
    /// linear faces against a curved or triangulated obstacle, with Coulomb
    /// friction against an obstacle or with `method = "penalty"`, which
    /// `strategy = "auto"` condenses with node-to-surface (one
    /// factorisation per run) but leaves to Newton with mortar (the log
    /// says so in a note), and against a plane where the run is on Newton's
    /// path anyway (a finite-strain material or `strategy = "monolithic"`:
    /// there mortar's conditions on linear faces are node-to-surface's, at
    /// about twice the cost). Quadratic faces (Tri6/Quad8,
    /// whose corner nodes node-to-surface gives no share of a uniform
    /// pressure) take mortar wherever mortar takes the pairing.
    pub discretisation: Option<DiscretisationSpec>,
}

/// `[[step]]`
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct StepSpec {
    pub name: String,
    /// Pseudo-time at the end of the step (> the previous step's).
    pub end_time: f64,
    /// First increment; default: the step's length.
    pub initial_increment: Option<f64>,
    /// Smallest increment allowed by cut-back; default: initial / 2¹⁰.
    pub min_increment: Option<f64>,
    /// Largest increment allowed by growth; default: the step's length.
    pub max_increment: Option<f64>,
    /// The most increments the step may take at least (`⌈length /
    /// max_increment⌉`); default [`super::budget::MAX_INCREMENTS`] (10⁵).
    pub max_increments: Option<u64>,
}

/// `[solver]`
#[derive(Debug, Deserialize, Default, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SolverSpec {
    /// Newton iterations before the increment is cut (default 20).
    pub max_iterations: Option<usize>,
    /// Relative force residual tolerance (default 1e-8).
    pub residual_tolerance: Option<f64>,
    /// Relative displacement correction tolerance (default 1e-6).
    pub displacement_tolerance: Option<f64>,
    /// Backtracking line search (default true).
    pub line_search: Option<bool>,
    /// Consecutive cuts before giving up (default 8).
    pub max_cuts: Option<usize>,
    /// Increment growth after an easy increment (default 1.5).
    pub growth_factor: Option<f64>,
    /// An increment converged in at most this many Newton iterations, without
    /// a cut, is easy: the next one grows (default 5).
    pub easy_iterations: Option<usize>,
    /// Solver of nonsymmetric tangents (friction, follower pressure):
    /// `gmres` (default; preconditioned by an LDLᵀ, falls back to `lu`) or
    /// `lu`.
    pub nonsymmetric: Option<crate::problem::NonsymmetricSolver>,
    /// The linear solver: `auto` (default: LDLᵀ for a symmetric tangent,
    /// `nonsymmetric` for the others), `ldlt`, `mixed`, `gmres` or `lu`.
    pub linear: Option<crate::problem::LinearMethod>,
    /// Where Newton starts an increment: `auto` (default: `contact` where
    /// it applies, else `none`), `none` (the converged state), `secant`
    /// (extrapolated from the last increment) or `contact` (the secant's
    /// start, the first correction solving the linearised contact
    /// exactly).
    pub predictor: Option<crate::solve::settings::Predictor>,
    /// `auto` (default: the condensed contact path where it applies),
    /// `monolithic` or `condensed`.
    pub strategy: Option<crate::solve::settings::Strategy>,
    /// `[solver.petsc]`: options of the PETSc backend (`linear = "petsc"`).
    pub petsc: Option<PetscSpec>,
}

/// `[solver.petsc]`
#[derive(Debug, Deserialize, Default, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct PetscSpec {
    /// A PETSc options string, e.g. `"-ksp_type cg -pc_type gamg"`, read
    /// after the environment's `PETSC_OPTIONS` (default: none, a direct LU
    /// by MUMPS).
    pub options: Option<String>,
}

/// `[output]`
#[derive(Debug, Deserialize, Default, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct OutputSpec {
    /// Output folder relative to the case file (default `results`); the
    /// command line's `--output` overrides it.
    pub folder: Option<String>,
    /// File-name stem of the VTU series (default: the case file's stem).
    pub name: Option<String>,
    /// The fields of the VTU files, by name (default: all of them).
    #[serde(default)]
    #[schemars(schema_with = "output_fields")]
    pub fields: Option<Vec<crate::output::OutputField>>,
    /// Write a VTU file every this many converged increments (≥ 1,
    /// default 1), and always at the end of each step.
    pub every: Option<i64>,
    /// The most bytes of VTU files the run may keep on disk, estimated
    /// before it starts; default [`super::budget::MAX_OUTPUT_BYTES`] (100 GiB).
    pub max_bytes: Option<u64>,
    /// zlib compression of the VTU arrays (default true).
    pub compress: Option<bool>,
    /// `[[output.history]]`: a nodal quantity after every increment.
    #[serde(default)]
    pub history: Vec<HistorySpec>,
    /// `[[output.profile]]`: contact quantities along a line of an
    /// interface at the end of every load step.
    #[serde(default)]
    pub profile: Vec<ProfileSpec>,
}

/// The JSON Schema of `[output] fields` (which the VTU field names
/// deserialize by hand): an array of those names.
fn output_fields(_: &mut schemars::SchemaGenerator) -> schemars::Schema {
    let names: Vec<&str> = crate::output::OutputField::all()
        .map(crate::output::OutputField::name)
        .collect();
    schemars::json_schema!({
        "type": "array",
        "items": { "type": "string", "enum": names },
    })
}

/// Quantities a history can record.
#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum HistoryQuantitySpec {
    DisplacementX,
    DisplacementY,
    DisplacementZ,
    /// Signed gap of a secondary node (needs `interface`).
    Gap,
    /// Contact pressure `t_N` of a secondary node (needs `interface`).
    ContactPressure,
    /// The reaction force on a surface set, its x, y, z components (needs
    /// `surface`, no `point`).
    ReactionForce,
    /// One component of it (a scalar column `reaction_force_x`, …).
    ReactionForceX,
    ReactionForceY,
    ReactionForceZ,
    /// The reaction moment `Σ (x_a − c) × r_a` of a surface or node set
    /// about `point` (default: the set's current centroid), at the current
    /// positions `x_a`: its x, y, z components.
    ReactionMoment,
    /// One component of it (a scalar column `reaction_moment_x`, …).
    ReactionMomentX,
    ReactionMomentY,
    ReactionMomentZ,
}

impl HistoryQuantitySpec {
    /// The name as written in the case file.
    pub fn name(self) -> &'static str {
        match self {
            Self::DisplacementX => "displacement_x",
            Self::DisplacementY => "displacement_y",
            Self::DisplacementZ => "displacement_z",
            Self::Gap => "gap",
            Self::ContactPressure => "contact_pressure",
            Self::ReactionForce => "reaction_force",
            Self::ReactionForceX => "reaction_force_x",
            Self::ReactionForceY => "reaction_force_y",
            Self::ReactionForceZ => "reaction_force_z",
            Self::ReactionMoment => "reaction_moment",
            Self::ReactionMomentX => "reaction_moment_x",
            Self::ReactionMomentY => "reaction_moment_y",
            Self::ReactionMomentZ => "reaction_moment_z",
        }
    }
}

/// `[[output.history]]`: `quantity` at the mesh node nearest `point`
/// (for `gap` and `contact_pressure`: the nearest secondary node of
/// `interface`; for `reaction_force`: `Σ (f_int − f_ext)` over the nodes of
/// `surface`), written as `<name>.csv` and `<name>.svg` after every
/// converged increment.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct HistorySpec {
    /// File stem: letters, digits, `-`, `_`, `.`.
    pub name: String,
    /// Reference-configuration point; the nearest node is used (every
    /// quantity but `reaction_force` and `reaction_moment`). For
    /// `reaction_moment`: the fixed point `c` the moment is taken about
    /// (default: the set's current centroid, the mean of its nodes'
    /// current positions).
    #[serde(default, deserialize_with = "option_three")]
    pub point: Option<[f64; 3]>,
    /// `displacement_x`, `displacement_y`, `displacement_z`, `gap`,
    /// `contact_pressure`, `reaction_force` or `reaction_moment` (and
    /// their components `reaction_force_x`, …, `reaction_moment_z`).
    pub quantity: HistoryQuantitySpec,
    /// A `[[contact]]` name (required for `gap` and `contact_pressure`).
    pub interface: Option<String>,
    /// A surface set (for `reaction_force`, `reaction_moment` and their
    /// components, and only there; or `nodes`).
    pub surface: Option<String>,
    /// A node set, instead of `surface`, for `reaction_force` and its
    /// components.
    pub nodes: Option<String>,
    /// The `name` of another `[[output.history]]` of one column (not
    /// `reaction_force`, whose three components are three) whose value is
    /// the plot's x axis instead of the pseudo-time, and the CSV's column
    /// after `time`: e.g. a reaction force against a displacement, a
    /// force–displacement curve.
    pub x: Option<String>,
}

/// `[[output.profile]]`: the secondary nodes of `interface` within `width`
/// of the reference segment `from → to`, ordered along it; written at the
/// end of every load step as `<name>_<step>.csv` and plotted in
/// `<name>.svg`.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ProfileSpec {
    /// File stem: letters, digits, `-`, `_`, `.`.
    pub name: String,
    /// A `[[contact]]` name.
    pub interface: String,
    /// Segment ends in the reference configuration (distinct).
    #[serde(deserialize_with = "three")]
    pub from: [f64; 3],
    #[serde(deserialize_with = "three")]
    pub to: [f64; 3],
    /// Half-width of the band around the segment, > 0 (length unit).
    pub width: f64,
}
