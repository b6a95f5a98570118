//! Validation of `[[output.history]]` and `[[output.profile]]`: names,
//! points, interfaces and segments checked against the problem, and the
//! nodes they read resolved once.

use super::schema::{HistoryQuantitySpec, HistorySpec, ProfileSpec};
use super::Case;
use crate::output::history::{History, HistoryQuantity};
use crate::output::profile::{file_part, nodes_in_band, Profile, ProfileNode};
use crate::output::provenance::sha256_hex;
use crate::output::units::Units;
use crate::problem::Problem;
use crate::Result;

/// The histories and profiles a run writes.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct OutputRequests {
    pub histories: Vec<History>,
    pub profiles: Vec<Profile>,
}

/// The index of the point of `candidates` (indices into `nodes`) nearest
/// `point`, the first one on a tie.
fn nearest(
    nodes: &[[f64; 3]],
    candidates: impl Iterator<Item = usize>,
    point: [f64; 3],
) -> Option<usize> {
    let distance = |n: usize| {
        (0..3)
            .map(|i| (nodes[n][i] - point[i]).powi(2))
            .sum::<f64>()
    };
    candidates.min_by(|&a, &b| distance(a).total_cmp(&distance(b)).then(a.cmp(&b)))
}

impl Case {
    /// The interface named `name` (its index), or an error at `key` that
    /// lists the interfaces.
    fn interface_index(&self, problem: &Problem, key: &str, name: &str) -> Result<usize> {
        problem
            .contacts
            .by_name(name)
            .map(|(i, _)| i)
            .ok_or_else(|| {
                let have: Vec<&str> = problem.contacts.names().collect();
                self.err(format!(
                    "{key}: no contact interface named '{name}'; {}",
                    crate::error::suggest::listing(name, &have, "none (add a [[contact]])")
                ))
            })
    }

    /// A history or profile name: a non-empty file stem, unique among all
    /// of them and not `convergence` (the convergence plot's name).
    fn output_file_stem(&self, key: &str, name: &str, taken: &mut Vec<String>) -> Result<()> {
        if !super::is_file_stem(name) {
            return Err(self.err(format!(
                "{key}.name = '{}': use ASCII letters, digits, '-', '_' and '.', not first (it names the output files)",
                crate::input::shorten(name)
            )));
        }
        if name == "convergence" || taken.iter().any(|t| t == name) {
            return Err(self.err(format!(
                "{key}.name = '{}' is already used by another output file; choose another name",
                crate::input::shorten(name)
            )));
        }
        taken.push(name.to_string());
        Ok(())
    }

    /// A profile writes `<name>_<step>.csv` for every step (the step name
    /// with characters other than letters, digits, `-` and `_` made `_`):
    /// no two steps may give the same file, and no such file may be a
    /// history's `<name>.csv`.
    fn profile_files_collide(&self, problem: &Problem, out: &OutputRequests) -> Result<()> {
        let Some(profile) = out.profiles.first() else {
            return Ok(());
        };
        let parts: Vec<String> = problem.steps.iter().map(|s| file_part(&s.name)).collect();
        for (i, part) in parts.iter().enumerate() {
            if let Some(j) = parts[..i].iter().position(|p| p == part) {
                return Err(self.err(format!(
                    "step[{i}] ('{}') and step[{j}] ('{}') give the same file name {}_{part}.csv of profile '{}'; \
                     rename one of the steps",
                    crate::input::shorten(&problem.steps[i].name),
                    crate::input::shorten(&problem.steps[j].name),
                    profile.name,
                    profile.name
                )));
            }
        }
        for p in &out.profiles {
            for (step, part) in problem.steps.iter().zip(&parts) {
                let file = format!("{}_{part}", p.name);
                if out.histories.iter().any(|h| h.name == file) {
                    return Err(self.err(format!(
                        "output.history '{file}' writes {file}.csv, which profile '{}' also writes for step '{}'; \
                         rename the history or the profile",
                        p.name, step.name
                    )));
                }
            }
        }
        Ok(())
    }

    /// Each history's `x`: another history of one column, which it is
    /// plotted against ([`History::against`]); `histories` in the case's
    /// order.
    fn history_axes(&self, histories: &mut [History]) -> Result<()> {
        for (i, h) in self.spec.output.history.iter().enumerate() {
            let Some(x) = &h.x else { continue };
            let key = format!("output.history[{i}].x");
            let j = match histories.iter().position(|g| &g.name == x) {
                Some(j) if j == i => {
                    return Err(self.err(format!(
                        "{key} = '{x}' is this history itself; name another [[output.history]] (e.g. a displacement) as its x axis"
                    )))
                }
                Some(j) => j,
                None => {
                    let names: Vec<&str> = histories.iter().map(|g| g.name.as_str()).collect();
                    return Err(self.err(format!(
                        "{key} = '{}': no [[output.history]] has that name; the histories are: {}",
                        crate::input::shorten(x),
                        names.join(", ")
                    )));
                }
            };
            if matches!(histories[j].quantity, HistoryQuantity::ReactionForce { .. }) {
                return Err(self.err(format!(
                    "{key} = '{x}' records reaction_force, three components; an x axis is one column: \
                     record reaction_force_x, _y or _z in '{x}'"
                )));
            }
            if matches!(
                histories[j].quantity,
                HistoryQuantity::ReactionMoment {
                    component: None,
                    ..
                }
            ) {
                return Err(self.err(format!(
                    "{key} = '{x}' records reaction_moment, three components; an x axis is one column: \
                     record reaction_moment_x, _y or _z in '{x}'"
                )));
            }
            let axis = histories[j].clone();
            histories[i] = histories[i].clone().against(&axis);
        }
        Ok(())
    }

    /// The SHA-256 of the case file's bytes ([`sha256_hex`]): those of the
    /// deck for an Abaqus/CalculiX deck (`.inp`, read again), of the text
    /// read otherwise (for a case given as text, that text).
    pub fn source_sha256(&self) -> String {
        let deck = self
            .path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("inp"));
        match deck.then(|| std::fs::read(&self.path)) {
            Some(Ok(bytes)) => sha256_hex(&bytes),
            Some(Err(e)) => format!("unknown (cannot read the deck again: {e})"),
            None => sha256_hex(self.text.as_bytes()),
        }
    }

    /// `[units]`, each name non-empty and on one line.
    fn units(&self) -> Result<Units> {
        let spec = &self.spec.units;
        for (key, value) in [("length", &spec.length), ("force", &spec.force)] {
            if let Some(v) = value {
                if v.trim().is_empty() || v.chars().any(char::is_control) {
                    return Err(self.err(format!(
                        "units.{key} = {v:?} is not a unit name: give one such as \"{}\", or remove the key",
                        if key == "length" { "mm" } else { "N" }
                    )));
                }
            }
        }
        Ok(Units {
            length: spec.length.clone(),
            force: spec.force.clone(),
        })
    }

    /// Validate `[[output.history]]` and `[[output.profile]]` against the
    /// problem and resolve their nodes.
    pub fn output_requests(&self, problem: &Problem) -> Result<OutputRequests> {
        let mut taken = Vec::new();
        let mut out = OutputRequests::default();
        let units = self.units()?;
        for (i, h) in self.spec.output.history.iter().enumerate() {
            let key = format!("output.history[{i}]");
            self.output_file_stem(&key, &h.name, &mut taken)?;
            let history = match reaction_of(h.quantity) {
                Some((moment, component)) => {
                    self.reaction_history(&key, h, moment, component, problem, &units)?
                }
                None => self.point_history(&key, h, problem, &units)?,
            };
            out.histories.push(history);
        }
        self.history_axes(&mut out.histories)?;
        for (i, p) in self.spec.output.profile.iter().enumerate() {
            let key = format!("output.profile[{i}]");
            self.output_file_stem(&key, &p.name, &mut taken)?;
            out.profiles.push(self.profile(&key, p, problem, &units)?);
        }
        self.profile_files_collide(problem, &out)?;
        self.output_files_fit(problem, &out)?;
        Ok(out)
    }

    /// The reaction history `[[output.history]]` `key` asks (`moment`: a
    /// moment about `point`; `component`: one axis, or the vector): the
    /// sum over the nodes of `surface` or of the node set `nodes`.
    fn reaction_history(
        &self,
        key: &str,
        h: &HistorySpec,
        moment: bool,
        component: Option<usize>,
        problem: &Problem,
        units: &Units,
    ) -> Result<History> {
        let mesh = &problem.model.mesh;
        let quantity = h.quantity.name();
        let (name, nodes) = match (&h.surface, &h.nodes) {
            (Some(name), None) => {
                let surface = self.surface(&format!("{key}.surface"), name)?;
                (name, mesh.surface_nodes(surface))
            }
            (None, Some(name)) => {
                let set = self.node_set(&format!("{key}.nodes"), name)?;
                (name, set.nodes.clone())
            }
            (None, None) => {
                return Err(self.err(format!(
                    "{key}.surface is required for quantity {quantity}: give a surface set name (or `nodes`, a node set)"
                )))
            }
            (Some(_), Some(_)) => {
                return Err(self.err(format!(
                    "{key}: give either `surface` (a surface set) or `nodes` (a node set), not both"
                )))
            }
        };
        for (given, what) in [
            (h.point.is_some() && !moment, "point"),
            (h.interface.is_some(), "interface"),
        ] {
            if given {
                return Err(self.err(format!(
                    "{key}.{what} does not apply to reaction_force (the sum over `surface`); remove it"
                )));
            }
        }
        let &first = nodes.first().ok_or_else(|| {
            self.err(format!(
                "{key}.surface = '{name}' has no nodes; name a surface set with facets"
            ))
        })?;
        let (set, quantity) = (name.clone(), quantity.to_string());
        if h.point.is_some_and(|p| p.iter().any(|v| !v.is_finite())) {
            return Err(self.err(format!("{key}.point must be finite")));
        }
        let history = match (moment, component) {
            (true, component) => HistoryQuantity::ReactionMoment {
                set,
                reference: nodes.iter().map(|&n| mesh.nodes[n]).collect(),
                nodes,
                centre: h.point,
                component,
            },
            (false, None) => HistoryQuantity::ReactionForce {
                surface: set,
                nodes,
            },
            (false, Some(component)) => HistoryQuantity::ReactionComponent {
                set,
                nodes,
                component,
            },
        };
        Ok(History::new(
            h.name.clone(),
            first,
            mesh.node_ids[first],
            history,
            quantity,
        )
        .with_units(units.clone()))
    }

    /// The history `[[output.history]]` `key` asks at the node nearest
    /// `point`: a displacement component, or an interface's gap or
    /// contact pressure.
    fn point_history(
        &self,
        key: &str,
        h: &HistorySpec,
        problem: &Problem,
        units: &Units,
    ) -> Result<History> {
        let mesh = &problem.model.mesh;
        for (given, what) in [
            (h.surface.is_some(), "surface"),
            (h.nodes.is_some(), "nodes"),
        ] {
            if given {
                return Err(self.err(format!(
                    "{key}.{what} applies to reaction_force only (and its components reaction_force_x, _y, _z, and reaction_moment and its components); remove it"
                )));
            }
        }
        let point = h.point.ok_or_else(|| {
            self.err(format!(
                "{key}.point is required for quantity \"{}\": the node nearest it is recorded",
                h.quantity.name()
            ))
        })?;
        if point.iter().any(|v| !v.is_finite()) {
            return Err(self.err(format!("{key}.point must be finite")));
        }
        let component = match h.quantity {
            HistoryQuantitySpec::DisplacementX => Some(0),
            HistoryQuantitySpec::DisplacementY => Some(1),
            HistoryQuantitySpec::DisplacementZ => Some(2),
            HistoryQuantitySpec::Gap | HistoryQuantitySpec::ContactPressure => None,
            HistoryQuantitySpec::ReactionForce
            | HistoryQuantitySpec::ReactionForceX
            | HistoryQuantitySpec::ReactionForceY
            | HistoryQuantitySpec::ReactionForceZ
            | HistoryQuantitySpec::ReactionMoment
            | HistoryQuantitySpec::ReactionMomentX
            | HistoryQuantitySpec::ReactionMomentY
            | HistoryQuantitySpec::ReactionMomentZ => unreachable!("handled above"),
        };
        let (node, quantity, label) = match (component, &h.interface) {
            (Some(c), None) => {
                let node = nearest(&mesh.nodes, 0..mesh.num_nodes(), point)
                    .ok_or_else(|| self.err(format!("{key}: the mesh has no node")))?;
                let label = ["displacement_x", "displacement_y", "displacement_z"][c];
                (node, HistoryQuantity::Displacement(c), label)
            }
            (Some(_), Some(_)) => {
                return Err(self.err(format!(
                    "{key}.interface applies to gap and contact_pressure only; remove it"
                )))
            }
            (None, None) => {
                return Err(self.err(format!(
                    "{key}.interface is required for quantity {:?}: give a [[contact]] name",
                    h.quantity
                )))
            }
            (None, Some(name)) => {
                let interface = self.interface_index(problem, &format!("{key}.interface"), name)?;
                let nodes = &problem.contacts.interface(interface).nodes;
                let index = nearest(
                    &nodes.iter().map(|&n| mesh.nodes[n]).collect::<Vec<_>>(),
                    0..nodes.len(),
                    point,
                )
                .ok_or_else(|| self.err(format!("{key}: interface '{name}' has no node")))?;
                let (quantity, label) = if h.quantity == HistoryQuantitySpec::Gap {
                    (HistoryQuantity::Gap { interface, index }, "gap")
                } else {
                    (
                        HistoryQuantity::ContactPressure { interface, index },
                        "contact_pressure",
                    )
                };
                (nodes[index], quantity, label)
            }
        };
        Ok(History::new(
            h.name.clone(),
            node,
            mesh.node_ids[node],
            quantity,
            label.to_string(),
        )
        .with_units(units.clone()))
    }

    /// The profile `[[output.profile]]` `key` asks: the secondary nodes of
    /// its interface within `width` of the segment `from → to`, with their
    /// abscissae along it.
    fn profile(
        &self,
        key: &str,
        p: &ProfileSpec,
        problem: &Problem,
        units: &Units,
    ) -> Result<Profile> {
        let mesh = &problem.model.mesh;
        let interface = self.interface_index(problem, &format!("{key}.interface"), &p.interface)?;
        if p.from.iter().chain(&p.to).any(|v| !v.is_finite()) {
            return Err(self.err(format!("{key}.from and .to must be finite")));
        }
        let length = (0..3)
            .map(|d| (p.to[d] - p.from[d]).powi(2))
            .sum::<f64>()
            .sqrt();
        if !(length > 0.0) {
            return Err(self.err(format!(
                "{key}: from and to are the same point ({:?}); give a segment of positive length",
                p.from
            )));
        }
        if !(p.width > 0.0) || !p.width.is_finite() {
            return Err(self.err(super::not_positive(&format!("{key}.width"), p.width)));
        }
        let contact = problem.contacts.interface(interface);
        let positions: Vec<[f64; 3]> = contact.nodes.iter().map(|&n| mesh.nodes[n]).collect();
        let nodes: Vec<ProfileNode> = nodes_in_band(&positions, p.from, p.to, p.width)
            .into_iter()
            .map(|(index, abscissa)| ProfileNode {
                index,
                node_id: mesh.node_ids[contact.nodes[index]],
                abscissa,
            })
            .collect();
        if nodes.is_empty() {
            return Err(self.err(format!(
                "{key}: no secondary node of interface '{}' lies within width = {} of the segment {:?} → {:?}; widen the band or move the segment onto the surface '{}'",
                p.interface, p.width, p.from, p.to, contact.surface
            )));
        }
        Ok(Profile {
            name: p.name.clone(),
            interface,
            interface_name: p.interface.clone(),
            direction: {
                let d: Vec<f64> = (0..3).map(|i| p.to[i] - p.from[i]).collect();
                let l = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
                [d[0] / l, d[1] / l, d[2] / l]
            },
            friction_coefficient: contact.friction.map(|f| f.coefficient),
            nodes,
            steps: Vec::new(),
            units: units.clone(),
        })
    }

    /// What the run would otherwise find only when it writes (issue 31
    /// item 4): no field named twice in `[output] fields`, no contact field
    /// named without a `[[contact]]` (the files would lack it), and every file
    /// name it writes, with its temporary copy, within the 255 bytes a
    /// file name may have ([`MAX_FILE_STEM`] for the stem).
    fn output_files_fit(&self, problem: &Problem, out: &OutputRequests) -> Result<()> {
        if let Some(fields) = &self.spec.output.fields {
            let names = fields.iter().map(|f| f.name());
            if let Some((_, _, name)) = super::first_duplicate(names) {
                return Err(self.err(format!(
                    "output.fields names '{name}' twice; name each field once"
                )));
            }
            let contact_only = fields
                .iter()
                .find(|f| matches!(f, crate::output::OutputField::Nodal(n) if n.needs_contact()));
            if let (Some(field), true) = (contact_only, problem.contacts.is_empty()) {
                return Err(self.err(format!(
                    "output.fields names '{}', a contact field, and the case has no [[contact]], \
                     so the VTU files would not hold it; remove it from output.fields, or add the \
                     [[contact]] it should report",
                    field.name()
                )));
            }
        }
        let steps = problem.steps.iter().map(|s| file_part(&s.name));
        let profiles = out.profiles.iter().flat_map(|p| {
            steps.clone().map(move |step| {
                (
                    format!("output.profile '{}'", p.name),
                    format!("{}_{step}", p.name),
                )
            })
        });
        let stems = std::iter::once(("output.name".to_string(), self.output_name()))
            .chain(
                out.histories
                    .iter()
                    .map(|h| (format!("output.history '{}'", h.name), h.name.clone())),
            )
            .chain(profiles);
        for (key, stem) in stems {
            if stem.len() > MAX_FILE_STEM {
                return Err(self.err(format!(
                    "{key}: the file name '{}…' is {} bytes long, and the run's files with their \
                     temporary copies (.NAME_0001.vtu.PID-N.tmp) must fit in the 255 bytes a file \
                     name may have; use a name of at most {MAX_FILE_STEM} bytes",
                    stem.chars().take(24).collect::<String>(),
                    stem.len()
                )));
            }
        }
        Ok(())
    }
}

/// The longest file stem of an output file (`[output] name`, a history's
/// name, a profile's `NAME_STEP`): a file name has at most 255 bytes, and
/// the longest one a run writes is the temporary copy of a VTU file,
/// `.STEM_NNNNNNN.vtu.PID-N.tmp`, 46 bytes more than its stem with a
/// 10-digit process id and a 20-digit counter.
pub const MAX_FILE_STEM: usize = 200;

/// Whether history `quantity` is a reaction, and which: `(moment,
/// component)` (`component`: one axis, or `None` for the vector); `None`
/// for the point quantities.
fn reaction_of(quantity: HistoryQuantitySpec) -> Option<(bool, Option<usize>)> {
    use HistoryQuantitySpec as Q;
    match quantity {
        Q::ReactionForce => Some((false, None)),
        Q::ReactionForceX => Some((false, Some(0))),
        Q::ReactionForceY => Some((false, Some(1))),
        Q::ReactionForceZ => Some((false, Some(2))),
        Q::ReactionMoment => Some((true, None)),
        Q::ReactionMomentX => Some((true, Some(0))),
        Q::ReactionMomentY => Some((true, Some(1))),
        Q::ReactionMomentZ => Some((true, Some(2))),
        _ => None,
    }
}
