//! An Abaqus/CalculiX deck run as it is: its physics
//! ([`crate::mesh::inp::physics`]) translated into the case structure
//! that a case file is parsed into ([`CaseFile`]), written as TOML
//! ([`write::to_toml`]) and parsed back, so that `signorini run deck.inp`
//! and `signorini run` on the case `signorini convert deck.inp` writes go
//! through one path and agree by construction.
//!
//! ## The mapping
//! - `*SOLID SECTION, ELSET=r, MATERIAL=m` → `[[material]] region = "r"`:
//!   `*ELASTIC` `E, ν` → `linear_elastic` without `NLGEOM` (small strain),
//!   `saint_venant_kirchhoff` with it (Abaqus integrates a hypoelastic
//!   law instead: the same at small strain); `*HYPERELASTIC, NEO HOOKE`
//!   `C10, D1` → `ogden` with `μ = [2 C10]`, `α = [2]`, `κ = 2/D1`, which
//!   is Abaqus's energy `C10 (Ī₁ − 3) + (J − 1)²/D1` exactly;
//!   `*HYPERELASTIC, OGDEN, N=n` `μ_i, α_i, D_i` → `ogden` with the same
//!   `μ_i, α_i` (Abaqus's `2μ_i/α_i²` convention is ours) and `κ = 2/D1`
//!   (`D2 = D3 = 0` only). Hyperelastic materials are finite-strain with
//!   or without `NLGEOM` (CalculiX switches it on for them).
//! - Steps: `*STATIC` `initial, period, min, max` → `[[step]]` with
//!   `end_time` the total time, the increments as given (`DIRECT`: fixed);
//!   `TIME POINTS=` splits the step at the points inside it, and when
//!   every step has them the VTU files are written at those times only.
//! - `*DLOAD` `elset, GRAV, g, n` → `[[body_force]]` `ρ g n/‖n‖` on each
//!   section's region under the set, `ρ` its material's `*DENSITY`
//!   ([`gravity`]).
//! - `*BOUNDARY`, `*CLOAD` (per node: the case's total `value` is the
//!   node count times it), `*DLOAD` `P<k>` and `*DSLOAD` `P` (follower
//!   with `NLGEOM`, dead without) → `[[displacement]]`, `[[nodal_force]]`,
//!   `[[pressure]]`, each with the amplitude of its [`timeline`].
//! - `*CONTACT PAIR` `secondary, primary` → `[[contact]]` `surface`,
//!   `primary`, node-to-surface, or dual mortar for quadratic faces and
//!   `TYPE=MORTAR`; `HARD`, `LINEAR`, `*FRICTION` → the law and friction
//!   ([`contact`]).
//! - Output: `*NODE FILE` `U` → `displacement`; `*EL FILE` `S` →
//!   `cauchy_stress`, `von_mises`; `*CONTACT FILE` `CDIS` → `gap`, `slip`,
//!   `CSTR` → `contact_pressure`, `contact_traction`, `PCON` →
//!   `contact_status`; `*NODE PRINT, NSET=s` `U` → histories of the
//!   displacement of the set's first node, `RF` → the set's reaction force.

mod contact;
mod gravity;
mod timeline;
mod write;

use super::schema::*;
use super::Case;
use crate::mesh::inp::physics::{Hyperelastic, OutputKind, Physics};
use crate::mesh::inp::{read_deck, InpDeck};
use crate::mesh::Mesh;
use crate::Result;
use std::collections::BTreeMap;
use std::path::Path;
use std::sync::Arc;
use timeline::{scaled, timeline, InStep};
pub use write::to_toml;

/// A deck read and translated: the case structure and the notes.
pub struct Translated {
    pub spec: CaseFile,
    pub notes: Vec<String>,
    pub mesh: Mesh,
}

/// Reads the deck at `path` and translates it; `mesh_file` is what the
/// case's `[mesh] file` says (the deck, relative to the case file).
pub fn translate_file(path: &Path, mesh_file: &str) -> Result<Translated> {
    let InpDeck {
        mesh,
        physics,
        mut notes,
    } = read_deck(path)?;
    let stem = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "deck".into());
    if physics.steps.is_empty() {
        return Err(crate::Error::Case {
            path: path.to_path_buf(),
            message: "the deck has no *STEP, so nothing to run: add a *STEP with *STATIC and the \
                      loads, or name the deck as the [mesh] of a case file"
                .into(),
        });
    }
    let spec = translate(&physics, &mesh, mesh_file, &stem, &mut notes)?;
    if !physics.without_effect.is_empty() {
        notes.push(format!(
            "{}: read, without effect on the answer: {}",
            path.display(),
            physics.without_effect.join(", ")
        ));
    }
    Ok(Translated { spec, notes, mesh })
}

/// The deck at `deck` as a case file at `case` names it: its file name
/// when both are in one folder, else its absolute path.
pub fn mesh_path(deck: &Path, case: &Path) -> String {
    let folder = |p: &Path| {
        let parent = p
            .parent()
            .filter(|d| !d.as_os_str().is_empty())
            .unwrap_or(Path::new("."));
        parent
            .canonicalize()
            .unwrap_or_else(|_| parent.to_path_buf())
    };
    if folder(deck) == folder(case) {
        if let Some(name) = deck.file_name() {
            return name.to_string_lossy().into_owned();
        }
    }
    deck.canonicalize()
        .unwrap_or_else(|_| deck.to_path_buf())
        .to_string_lossy()
        .into_owned()
}

/// The case of the deck at `path`, through its TOML text (the text
/// `signorini convert` writes beside the deck).
pub fn load(path: &Path) -> Result<Case> {
    let file = path
        .file_name()
        .map(|f| f.to_string_lossy().into_owned())
        .unwrap_or_default();
    let Translated { spec, notes, mesh } = translate_file(path, &file)?;
    let text = to_toml(&spec);
    let spec = super::parse(path, &text)?;
    Ok(Case {
        path: path.to_path_buf(),
        spec,
        mesh: Arc::new(mesh),
        notes,
        text,
    })
}

/// The case structure of the deck's `physics` on its `mesh`.
fn translate(
    physics: &Physics,
    mesh: &Mesh,
    mesh_file: &str,
    stem: &str,
    notes: &mut Vec<String>,
) -> Result<CaseFile> {
    let first = physics.steps.first().ok_or_else(|| crate::Error::Case {
        path: mesh_file.into(),
        message: "the deck has no *STEP".into(),
    })?;
    if let Some(s) = physics.steps.iter().find(|s| s.nlgeom != first.nlgeom) {
        return Err(s.at.error(format!(
            "*STEP '{}' has NLGEOM {} but the first step has it {}: give every step the same NLGEOM",
            s.name,
            if s.nlgeom { "on" } else { "off" },
            if first.nlgeom { "on" } else { "off" }
        )));
    }
    let nlgeom = first.nlgeom;
    notes.push(if nlgeom {
        "NLGEOM: finite strain; *ELASTIC is read as Saint Venant–Kirchhoff, pressures follow the deformed surface".into()
    } else {
        "no NLGEOM: *ELASTIC is read as small-strain linear elasticity, pressures as dead loads".into()
    });
    let (steps, spans) = steps(physics)?;
    let first_end = spans[0].1;
    let mut spec = CaseFile {
        mesh: MeshSpec {
            file: mesh_file.to_string(),
            max_generated_ids: None,
        },
        material: materials(physics, nlgeom)?,
        displacement: Vec::new(),
        pressure: Vec::new(),
        body_force: Vec::new(),
        nodal_force: Vec::new(),
        obstacle: Vec::new(),
        contact: contact::contacts(physics, mesh, notes)?,
        amplitudes: BTreeMap::new(),
        step: steps,
        solver: SolverSpec::default(),
        output: OutputSpec {
            name: Some(stem.to_string()),
            ..OutputSpec::default()
        },
        units: UnitsSpec::default(),
    };
    let times = StepTimes {
        physics,
        spans,
        first_end,
    };
    boundaries(&times, &mut spec)?;
    loads(&times, mesh, nlgeom, &mut spec)?;
    gravity::gravities(&times, mesh, &mut spec)?;
    outputs(physics, mesh, &mut spec, notes);
    at_time_points(physics, &mut spec, notes);
    Ok(spec)
}

/// The steps, split at their time points, and each deck step's span in
/// total time.
fn steps(physics: &Physics) -> Result<(Vec<StepSpec>, Spans)> {
    let mut out = Vec::new();
    let mut spans = Vec::new();
    let mut start = 0.0;
    for s in &physics.steps {
        let [initial, period, min, max] = s.increments;
        let period = period.unwrap_or(1.0);
        if !(period > 0.0) {
            return Err(s.at.error(format!(
                "*STATIC: the time period {period} must be positive"
            )));
        }
        let end = start + period;
        let mut ends = Vec::new();
        if let Some(name) = &s.time_points {
            let (_, times) = physics
                .time_points
                .iter()
                .find(|(n, _)| n.eq_ignore_ascii_case(name))
                .ok_or_else(|| {
                    s.at.error(format!("TIME POINTS={name}: no *TIME POINTS of that name"))
                })?;
            ends.extend(
                times
                    .iter()
                    .filter(|&&t| t > 0.0 && t < period)
                    .map(|t| start + t),
            );
        }
        ends.push(end);
        let fixed = s.direct.then_some(initial.unwrap_or(period));
        let mut from = start;
        for (k, &to) in ends.iter().enumerate() {
            let length = to - from;
            let name = if k + 1 == ends.len() {
                s.name.clone()
            } else {
                format!("{}@{}", s.name, to - start)
            };
            out.push(StepSpec {
                name,
                end_time: to,
                initial_increment: initial.or(fixed).map(|i| i.min(length)),
                min_increment: fixed.or(min).map(|i| i.min(length)),
                max_increment: fixed.or(max).map(|i| i.min(length)),
                max_increments: None,
            });
            from = to;
        }
        spans.push((start, end));
        start = end;
    }
    Ok((out, spans))
}

/// A material model from a deck material.
fn materials(physics: &Physics, nlgeom: bool) -> Result<Vec<MaterialSpec>> {
    let mut out = Vec::new();
    for section in &physics.sections {
        let m = physics.material_of(section).ok_or_else(|| {
            section.at.error(format!(
                "*SOLID SECTION: no *MATERIAL named '{}'",
                section.material
            ))
        })?;
        let bulk = |d: f64, what: &str| -> Result<f64> {
            if d > 0.0 {
                Ok(2.0 / d)
            } else {
                Err(m.at.error(format!(
                    "*MATERIAL '{}': {what} D1 = {d}: an incompressible material (D1 = 0) is not supported; give D1 > 0 (bulk modulus 2/D1)",
                    m.name
                )))
            }
        };
        let model = match (&m.hyperelastic, m.elastic) {
            (Some(Hyperelastic::NeoHooke { c10, d1 }), _) => MaterialModel::Ogden(OgdenConstants {
                mu: vec![2.0 * c10],
                alpha: vec![2.0],
                bulk_modulus: bulk(*d1, "NEO HOOKE")?,
            }),
            (Some(Hyperelastic::Ogden { mu, alpha, d }), _) => {
                if d[1..].iter().any(|&x| x != 0.0) {
                    return Err(m.at.error(format!(
                        "*MATERIAL '{}': OGDEN with D2 or D3 ≠ 0 is not supported: the volumetric energy is (J − 1)²/D1",
                        m.name
                    )));
                }
                MaterialModel::Ogden(OgdenConstants {
                    mu: mu.clone(),
                    alpha: alpha.clone(),
                    bulk_modulus: bulk(d[0], "OGDEN")?,
                })
            }
            (None, Some((e, nu))) => {
                let c = ElasticConstants {
                    youngs_modulus: e,
                    poisson_ratio: nu,
                };
                if nlgeom {
                    MaterialModel::SaintVenantKirchhoff(c)
                } else {
                    MaterialModel::LinearElastic(c)
                }
            }
            (None, None) => {
                return Err(m.at.error(format!(
                    "*MATERIAL '{}' has neither *ELASTIC nor *HYPERELASTIC",
                    m.name
                )))
            }
        };
        out.push(MaterialSpec {
            region: section.region.clone(),
            model,
        });
    }
    Ok(out)
}

/// Each deck step's `[start, end]` in total time.
type Spans = Vec<(f64, f64)>;

/// Points of an amplitude (`None`: the default ramp), and their bits.
type Points = Option<Vec<(f64, f64)>>;
type Bits = Vec<[u64; 2]>;

/// The deck's quantities over the steps, keyed by what they act on.
type Channels<'a, K> = BTreeMap<K, Vec<InStep<'a>>>;

/// Puts `(key, given)` of step `k` (of `n`) into `channels`.
fn give<'a, K: Ord>(channels: &mut Channels<'a, K>, key: K, k: usize, n: usize, given: InStep<'a>) {
    channels.entry(key).or_insert_with(|| vec![InStep::Held; n])[k] = given;
}

/// `OP=NEW` in step `k`: every quantity of `channels` not given again
/// there is removed (ramps down to zero over the step).
fn remove_held<K>(channels: &mut Channels<'_, K>, k: usize) {
    for steps in channels.values_mut() {
        if matches!(steps[k], InStep::Held) {
            steps[k] = InStep::Removed;
        }
    }
}

/// The deck's steps in total time: what turns a quantity's values over
/// the steps into a case's value and amplitude.
struct StepTimes<'a> {
    physics: &'a Physics,
    /// Each deck step's `[start, end]` in total time.
    spans: Spans,
    /// The end of the first step, where a case's amplitude is 1.
    first_end: f64,
}

impl StepTimes<'_> {
    /// The number of deck steps.
    fn count(&self) -> usize {
        self.physics.steps.len()
    }

    /// `(value, amplitude)` of a quantity that is `start` at time 0 and
    /// does `steps[k]` in step `k`: its [`timeline`] `f(t)` as
    /// `value × a(t)`, `value = f(first_end)` ([`scaled`]).
    fn scaled(&self, start: f64, steps: &[InStep]) -> Result<(f64, Points)> {
        let points = timeline(start, steps, &self.spans, &self.physics.amplitudes)?;
        Ok(scaled(&points, self.first_end))
    }
}

/// `[[displacement]]` of the `*BOUNDARY`s: per node set, the dofs with the
/// same amplitude together.
fn boundaries(times: &StepTimes, spec: &mut CaseFile) -> Result<()> {
    let physics = times.physics;
    let n = times.count();
    let mut channels: Channels<(String, usize)> = BTreeMap::new();
    let mut initial: BTreeMap<(String, usize), f64> = BTreeMap::new();
    for b in &physics.initial_boundaries {
        initial.insert((b.nodes.clone(), b.dof), b.value);
        channels
            .entry((b.nodes.clone(), b.dof))
            .or_insert_with(|| vec![InStep::Held; n]);
    }
    for (k, s) in physics.steps.iter().enumerate() {
        for b in &s.boundaries {
            give(
                &mut channels,
                (b.nodes.clone(), b.dof),
                k,
                n,
                InStep::Given(b.value, b.amplitude.as_deref(), &b.at),
            );
        }
    }
    for (k, s) in physics
        .steps
        .iter()
        .enumerate()
        .filter(|(_, s)| s.new_boundaries)
    {
        if let Some(((set, dof), _)) = channels.iter().find(|(_, v)| matches!(v[k], InStep::Held)) {
            return Err(s.at.error(format!(
                "*BOUNDARY, OP=NEW in step '{}' would release dof {} of '{set}': releasing a prescribed dof is not supported; keep it (OP=MOD)",
                s.name,
                dof + 1
            )));
        }
    }
    let mut grouped: BTreeMap<(String, Bits), [Option<f64>; 3]> = BTreeMap::new();
    let mut amplitudes = BTreeMap::new();
    for ((set, dof), steps) in &channels {
        let start = initial.get(&(set.clone(), *dof)).copied().unwrap_or(0.0);
        let (scale, amplitude) = times.scaled(start, steps)?;
        let key = bits(&amplitude);
        amplitudes.insert(key.clone(), amplitude);
        grouped.entry((set.clone(), key)).or_default()[*dof] = Some(scale);
    }
    for ((set, key), [x, y, z]) in grouped {
        spec.displacement.push(DisplacementSpec {
            surface: None,
            nodes: Some(set),
            x,
            y,
            z,
            amplitude: points_ref(&amplitudes[&key]),
            rotation: None,
        });
    }
    Ok(())
}

/// An amplitude's points as bits (a map key that compares exactly).
fn bits(amplitude: &Option<Vec<(f64, f64)>>) -> Vec<[u64; 2]> {
    amplitude
        .iter()
        .flatten()
        .map(|&(t, v)| [t.to_bits(), v.to_bits()])
        .collect()
}

fn points_ref(amplitude: &Option<Vec<(f64, f64)>>) -> Option<AmplitudeRef> {
    amplitude
        .as_ref()
        .map(|p| AmplitudeRef::Points(p.iter().map(|&(t, v)| vec![t, v]).collect()))
}

/// `[[nodal_force]]` of the `*CLOAD`s and `[[pressure]]` of the
/// `*DLOAD`/`*DSLOAD`s.
fn loads(times: &StepTimes, mesh: &Mesh, nlgeom: bool, spec: &mut CaseFile) -> Result<()> {
    let physics = times.physics;
    let n = times.count();
    let mut forces: Channels<(String, usize)> = BTreeMap::new();
    let mut pressures: Channels<String> = BTreeMap::new();
    for (k, s) in physics.steps.iter().enumerate() {
        for c in &s.cloads {
            give(
                &mut forces,
                (c.nodes.clone(), c.dof),
                k,
                n,
                InStep::Given(c.value, c.amplitude.as_deref(), &c.at),
            );
        }
        for p in &s.pressures {
            give(
                &mut pressures,
                p.surface.clone(),
                k,
                n,
                InStep::Given(p.value, p.amplitude.as_deref(), &p.at),
            );
        }
    }
    for (k, s) in physics.steps.iter().enumerate() {
        if s.new_cloads {
            remove_held(&mut forces, k);
        }
        if s.new_pressures {
            remove_held(&mut pressures, k);
        }
    }
    let mut grouped: BTreeMap<(String, Bits), ([f64; 3], Points)> = BTreeMap::new();
    for ((set, dof), steps) in &forces {
        let (scale, amplitude) = times.scaled(0.0, steps)?;
        let count = mesh.node_set(set).map_or(1, |s| s.nodes.len()) as f64;
        let entry = grouped
            .entry((set.clone(), bits(&amplitude)))
            .or_insert(([0.0; 3], amplitude));
        entry.0[*dof] = count * scale;
    }
    for ((set, _), (value, amplitude)) in grouped {
        spec.nodal_force.push(NodalForceSpec {
            nodes: set,
            value,
            amplitude: points_ref(&amplitude),
        });
    }
    for (surface, steps) in &pressures {
        let (scale, amplitude) = times.scaled(0.0, steps)?;
        spec.pressure.push(PressureSpec {
            surface: surface.clone(),
            value: scale,
            follower: nlgeom,
            amplitude: points_ref(&amplitude),
        });
    }
    Ok(())
}

/// `*TIME POINTS` as CalculiX writes them: the field output at the time
/// points only. The steps end at the points ([`steps`]) and a step's last
/// increment is always written, so `[output] every` of the most
/// increments a step may take writes those alone, when every step has
/// time points (`every` is one for the whole run); the histories keep
/// every increment.
fn at_time_points(physics: &Physics, spec: &mut CaseFile, notes: &mut Vec<String>) {
    let with = physics.steps.iter().filter(|s| s.time_points.is_some());
    match with.count() {
        0 => {}
        n if n == physics.steps.len() => {
            spec.output.every = Some(super::budget::MAX_INCREMENTS as i64);
            notes.push(
                "*TIME POINTS: the steps end at the time points, and the VTU files are written there only ([output] every)"
                    .into(),
            );
        }
        _ => notes.push(
            "*TIME POINTS: the steps end at the time points, and the VTU files are written at every increment (some steps have no time points)"
                .into(),
        ),
    }
}

/// `[output] fields` and `[[output.history]]` of the output requests.
fn outputs(physics: &Physics, mesh: &Mesh, spec: &mut CaseFile, notes: &mut Vec<String>) {
    let mut fields: Vec<&str> = Vec::new();
    let mut requested = false;
    let mut unmapped: Vec<String> = Vec::new();
    for out in physics.steps.iter().flat_map(|s| &s.outputs) {
        for v in &out.variables {
            let names: &[&str] = match (&out.kind, v.as_str()) {
                (OutputKind::NodeFile, "U") => &["displacement"],
                (OutputKind::ElementFile, "S") => &["cauchy_stress", "von_mises"],
                (OutputKind::ContactFile, "CDIS") => &["gap", "slip"],
                (OutputKind::ContactFile, "CSTR") => &["contact_pressure", "contact_traction"],
                (OutputKind::ContactFile, "PCON") => &["contact_status"],
                (OutputKind::NodePrint(set), "U") => {
                    histories_of_displacement(set, mesh, spec);
                    &[]
                }
                (OutputKind::NodePrint(set), "RF") => {
                    push_history(
                        spec,
                        set,
                        "RF",
                        None,
                        HistoryQuantitySpec::ReactionForce,
                        Some(set),
                    );
                    &[]
                }
                _ => {
                    let name = format!("{v} ({})", out.at.line);
                    unmapped.push(name);
                    &[]
                }
            };
            if !matches!(out.kind, OutputKind::NodePrint(_)) {
                requested = true;
            }
            fields.extend(names);
        }
    }
    if requested {
        fields.push("node_id");
        let mut chosen: Vec<crate::output::OutputField> = Vec::new();
        for field in fields.iter().filter_map(|f| f.parse().ok()) {
            if !chosen.contains(&field) {
                chosen.push(field);
            }
        }
        spec.output.fields = Some(chosen);
    }
    if !unmapped.is_empty() {
        notes.push(format!(
            "output variables not written (no such field; at the deck's lines): {}",
            unmapped.join(", ")
        ));
    }
}

/// `U` of `*NODE PRINT`: three histories at the set's first node.
fn histories_of_displacement(set: &str, mesh: &Mesh, spec: &mut CaseFile) {
    let Some(node) = mesh.node_set(set).and_then(|s| s.nodes.first()) else {
        return;
    };
    let point = mesh.nodes[*node];
    for (c, q) in [
        HistoryQuantitySpec::DisplacementX,
        HistoryQuantitySpec::DisplacementY,
        HistoryQuantitySpec::DisplacementZ,
    ]
    .into_iter()
    .enumerate()
    {
        push_history(spec, set, &format!("U{}", c + 1), Some(point), q, None);
    }
}

/// A history named `<set>_<what>` (made a file stem, unique).
fn push_history(
    spec: &mut CaseFile,
    set: &str,
    what: &str,
    point: Option<[f64; 3]>,
    quantity: HistoryQuantitySpec,
    nodes: Option<&str>,
) {
    let same =
        |h: &HistorySpec| h.quantity == quantity && h.point == point && h.nodes.as_deref() == nodes;
    if spec.output.history.iter().any(same) {
        return; // asked again in a later step: a history covers every step
    }
    let stem: String = format!("{set}_{what}")
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || matches!(c, '-' | '_' | '.') {
                c
            } else {
                '_'
            }
        })
        .collect();
    let stem = stem.trim_start_matches('.').to_string();
    let taken = |n: &str| spec.output.history.iter().any(|h| h.name == n);
    let mut name = stem.clone();
    let mut k = 2;
    while taken(&name) {
        name = format!("{stem}_{k}");
        k += 1;
    }
    spec.output.history.push(HistorySpec {
        name,
        point,
        quantity,
        interface: None,
        surface: None,
        nodes: nodes.map(str::to_string),
        x: None,
    });
}
