//! Reader for Abaqus input decks (`.inp`), the keyword format that
//! CalculiX also reads and that Gmsh, meshio, FreeCAD, PrePoMax and Salome
//! write. Only the mesh is read: the case file stays the one source of
//! physics.
//!
//! ## What it reads
//! - `*NODE` (`NSET=` adds the nodes to a node set): `id, x, y, z`.
//! - `*ELEMENT, TYPE=…` (`ELSET=` adds the elements to an element set):
//!   `id, n1, n2, …`, a line ending with a comma continued on the next.
//!   C3D4 and C3D8 (and their H, R, I variants, read as the plain
//!   fully-integrated element, with a note) are volume elements;
//!   3- and 4-node surface elements (S3, S4, CPS3, CPS4, M3D4, …, as Gmsh
//!   writes its 2D physical groups) are facets of the surface sets of
//!   their element sets; 2- and 3-node line elements (T3D2, B31, …) give
//!   their nodes to the node sets of their element sets. Quadratic
//!   elements (C3D10, C3D20, …) are recognised and rejected as not
//!   supported yet.
//! - `*ELSET, ELSET=…` and `*NSET, NSET=…`: ids and names of sets defined
//!   before, or with `GENERATE` lines `first, last[, step]` (ids in the
//!   range that no element or node has are skipped); `*NSET, ELSET=…`
//!   takes the nodes of an element set. A set defined twice is extended.
//! - `*SURFACE, NAME=…, TYPE=ELEMENT` (the default type): lines
//!   `element-or-element-set, S<k>` with Abaqus's face numbering
//!   ([`element_type`]), or without the face identifier: every free face
//!   of the elements.
//! - `*INCLUDE, INPUT=file`, relative to the including file, read where it
//!   stands.
//! - `*HEADING` and every other keyword (materials, sections, steps,
//!   boundary conditions, loads, output requests) are skipped with their
//!   data lines and listed in one note. `*PART`, `*ASSEMBLY` and
//!   `*INSTANCE` are refused (their local numbering needs the assembly's
//!   transformations): write the deck flat.
//!
//! Element sets with volume elements become regions (volume elements in
//! none: the region `"default"`), surfaces and element sets of surface
//! elements become surface sets (merged by name), node sets and element
//! sets of line elements become node sets (merged by name). Names keep the
//! spelling of their first definition; references inside the deck ignore
//! case, as Abaqus does. Facets are oriented out of the body as with Gmsh
//! meshes. Errors name the file (an included one, if there) and the line.
//!
//! ## Why hand-written
//! See `DESIGN.md` (dependencies): the Rust crates that read `.inp` map it
//! to their own mesh types, drop `*SURFACE` face sets or report errors
//! without a line.
//!
//! ## Layout
//! - `deck`: the lines of the files, includes followed, keyword lines
//!   parsed, located errors.
//! - `element_type`: the Abaqus element types and face numbering.
//! - `builder`: nodes, elements and sets into a [`Mesh`].
//! - here: the keywords and their data lines.

mod builder;
mod deck;
mod element_type;

use super::Mesh;
use crate::Result;
use builder::{kind_name, Builder, Member};
use deck::{split_fields, unquote, Deck, Keyword, Line};
use element_type::{element_type, face_count, outward_face, Shape};
use rayon::prelude::*;
use std::path::Path;

/// The most ids one `GENERATE` line may list (a guard against a typo
/// such as `1, 1000000000000`).
const MAX_GENERATED: u64 = 100_000_000;

/// A mesh read from a deck, and notes for the user (the keywords skipped,
/// element types read as another).
pub struct InpMesh {
    pub mesh: Mesh,
    pub notes: Vec<String>,
}

/// Reads an Abaqus/CalculiX deck (and the files it includes) into a
/// [`Mesh`] with outward-oriented surface sets.
pub fn read_inp(path: &Path) -> Result<InpMesh> {
    let deck = Deck::read(path)?;
    let mut reader = Reader {
        deck: &deck,
        builder: Builder::new(),
        ignored: Vec::new(),
        notes: Vec::new(),
    };
    let mut i = 0;
    while i < deck.lines.len() {
        let line = &deck.lines[i];
        let end = (i + 1..deck.lines.len())
            .find(|&j| deck.lines[j].is_keyword())
            .unwrap_or(deck.lines.len());
        if !line.is_keyword() {
            return Err(deck.error(
                line,
                format!(
                    "a data line before any keyword: '{}'; a deck starts with a keyword line such as *NODE",
                    line.text()
                ),
            ));
        }
        reader.keyword(line, &deck.lines[i + 1..end])?;
        i = end;
    }
    let Reader {
        builder,
        ignored,
        mut notes,
        ..
    } = reader;
    let mesh = builder.finish().map_err(|message| crate::Error::Mesh {
        path: path.to_path_buf(),
        message,
    })?;
    if !ignored.is_empty() {
        notes.push(format!(
            "{}: ignored keywords (the case file gives materials, loads, boundary conditions and steps): {}",
            path.display(),
            ignored.join(", ")
        ));
    }
    Ok(InpMesh { mesh, notes })
}

struct Reader<'a> {
    deck: &'a Deck,
    builder: Builder,
    /// Keywords skipped, `*NAME`, each once, in order of appearance.
    ignored: Vec<String>,
    notes: Vec<String>,
}

impl Reader<'_> {
    fn err(&self, line: &Line, message: String) -> crate::Error {
        self.deck.error(line, message)
    }

    /// Reads the keyword at `line` and its data lines `data`.
    fn keyword(&mut self, line: &Line, data: &[Line]) -> Result<()> {
        let keyword = self.deck.keyword(line)?;
        match keyword.name.as_str() {
            "NODE" => self.nodes(line, &keyword, data),
            "ELEMENT" => self.elements(line, &keyword, data),
            "ELSET" => self.element_set(line, &keyword, data),
            "NSET" => self.node_set(line, &keyword, data),
            "SURFACE" => self.surface(line, &keyword, data),
            "HEADING" => Ok(()),
            "PART" | "ASSEMBLY" | "INSTANCE" => Err(self.err(
                line,
                format!(
                    "*{} is not supported: parts and instances number nodes locally; write the \
                     deck flat (Abaqus/CAE: Model > Edit Attributes > check 'Do not use parts \
                     and assemblies in input files')",
                    keyword.name
                ),
            )),
            name => {
                let name = format!("*{name}");
                if !self.ignored.contains(&name) {
                    self.ignored.push(name);
                }
                Ok(())
            }
        }
    }

    /// A parameter that must be given, e.g. `NSET=name`.
    fn required<'k>(&self, line: &Line, keyword: &'k Keyword, key: &str) -> Result<&'k str> {
        keyword
            .param(key)
            .filter(|v| !v.is_empty())
            .ok_or_else(|| self.err(line, format!("*{} needs {key}=<name>", keyword.name)))
    }

    /// `INPUT=` on a data keyword: not supported.
    fn no_input(&self, line: &Line, keyword: &Keyword) -> Result<()> {
        if keyword.has("INPUT") {
            return Err(self.err(
                line,
                format!(
                    "INPUT= on *{} is not supported; put the data lines in the deck, or in a file read with *INCLUDE",
                    keyword.name
                ),
            ));
        }
        Ok(())
    }

    /// `*NODE`: `id, x[, y[, z]]` (missing coordinates are 0).
    fn nodes(&mut self, line: &Line, keyword: &Keyword, data: &[Line]) -> Result<()> {
        self.no_input(line, keyword)?;
        if let Some(system) = keyword.param("SYSTEM") {
            if !system.eq_ignore_ascii_case("R") {
                return Err(self.err(
                    line,
                    format!("*NODE, SYSTEM={system} is not supported: give Cartesian coordinates (SYSTEM=R)"),
                ));
            }
        }
        let nset = keyword.param("NSET").map(str::to_string);
        // the lines parsed side by side, then added in order (the first
        // error in the deck's order is the one reported)
        let parsed: Vec<Result<(u64, [f64; 3])>> =
            data.par_iter().map(|l| self.node_line(l)).collect();
        let mut added = Vec::with_capacity(data.len());
        for (l, p) in data.iter().zip(parsed) {
            let (id, x) = p?;
            added.push(self.builder.add_node(id, x).map_err(|m| self.err(l, m))?);
        }
        if let Some(name) = nset {
            self.builder.node_sets.entry(&name).extend(added);
        }
        Ok(())
    }

    /// A `*NODE` data line: `id, x, y, z` (missing coordinates are 0).
    fn node_line(&self, l: &Line) -> Result<(u64, [f64; 3])> {
        let fields = data_fields(l);
        if fields.len() < 2 || fields.len() > 4 {
            return Err(self.err(
                l,
                format!(
                    "a *NODE line is 'id, x, y, z'; found {} fields in '{}'",
                    fields.len(),
                    l.text()
                ),
            ));
        }
        let id = self.id(l, fields[0], "node id")?;
        let mut x = [0.0; 3];
        for (c, f) in x.iter_mut().zip(&fields[1..]) {
            *c = self.number(l, f)?;
        }
        Ok((id, x))
    }

    /// `*ELEMENT, TYPE=…`: `id, n1, …, nk`, continued on the next line after
    /// a trailing comma.
    fn elements(&mut self, line: &Line, keyword: &Keyword, data: &[Line]) -> Result<()> {
        self.no_input(line, keyword)?;
        let type_name = self.required(line, keyword, "TYPE")?.to_ascii_uppercase();
        let element = element_type(&type_name).map_err(|m| self.err(line, m))?;
        if let Shape::Volume(kind) = element.shape {
            if let Some(note) = element_type::variant_note(&type_name, kind_name(kind)) {
                if !self.notes.contains(&note) {
                    self.notes.push(note);
                }
            }
        }
        let elset = keyword.param("ELSET").map(str::to_string);
        // an element per line, parsed side by side; a line ending with a
        // comma continues on the next one (then the lines are joined in
        // order first)
        let mut records: Vec<(&Line, Vec<&str>)> = Vec::new();
        let continued = data.iter().any(|l| l.text().trim_end().ends_with(','));
        let parsed: Vec<Result<(u64, Vec<u64>)>> = if continued {
            let mut i = 0;
            while i < data.len() {
                let first = &data[i];
                let mut fields = data_fields(first);
                while fields.len() < element.nodes + 1
                    && data[i].text().trim_end().ends_with(',')
                    && i + 1 < data.len()
                {
                    i += 1;
                    fields.extend(data_fields(&data[i]));
                }
                i += 1;
                records.push((first, fields));
            }
            records
                .par_iter()
                .map(|(first, fields)| self.element_line(first, fields, &type_name, element.nodes))
                .collect()
        } else {
            data.par_iter()
                .map(|l| self.element_line(l, &data_fields(l), &type_name, element.nodes))
                .collect()
        };
        let firsts: Vec<&Line> = if continued {
            records.iter().map(|(first, _)| *first).collect()
        } else {
            data.iter().collect()
        };
        let mut added = Vec::with_capacity(parsed.len());
        for (first, p) in firsts.into_iter().zip(parsed) {
            let (id, nodes) = p?;
            let member = self
                .builder
                .add_element(id, element.shape, &nodes)
                .map_err(|m| self.err(first, m))?;
            added.push(member);
        }
        if let Some(name) = elset {
            self.builder.element_sets.entry(&name).extend(added);
        }
        Ok(())
    }

    /// An element's fields (`id` and its `nodes` node ids) read from the
    /// line `first` (where it starts).
    fn element_line(
        &self,
        first: &Line,
        fields: &[&str],
        type_name: &str,
        nodes: usize,
    ) -> Result<(u64, Vec<u64>)> {
        if fields.len() != nodes + 1 {
            return Err(self.err(
                first,
                format!(
                    "a {type_name} element line is 'id' and {nodes} node ids; found {} fields",
                    fields.len()
                ),
            ));
        }
        let id = self.id(first, fields[0], "element id")?;
        let ids = fields[1..]
            .iter()
            .map(|f| self.id(first, f, "node id"))
            .collect::<Result<Vec<u64>>>()?;
        Ok((id, ids))
    }

    /// The members a set's data lines list: ids (`by_id`) and names of sets
    /// of the same kind defined before (`by_name`), or with `GENERATE` the
    /// ranges `first, last[, step]` (ids that nothing has are skipped, but a
    /// range must hold one). `what` is the keyword and the kind of item,
    /// e.g. `("*NSET", "node")`.
    fn set_members<'b, T: Clone + 'b>(
        &self,
        set: SetBlock,
        by_id: impl Fn(u64) -> Option<T>,
        by_name: impl Fn(&str) -> Option<&'b [T]>,
    ) -> Result<Vec<T>> {
        let SetBlock {
            line,
            keyword,
            data,
            name,
            what,
            item,
        } = set;
        let generate = keyword.has("GENERATE");
        let mut members = Vec::new();
        for l in data {
            let fields = data_fields(l);
            if generate {
                if fields.len() < 2 || fields.len() > 3 {
                    return Err(self.err(
                        l,
                        format!(
                            "a GENERATE line is 'first, last[, step]'; found {} fields",
                            fields.len()
                        ),
                    ));
                }
                let first = self.id(l, fields[0], "first id")?;
                let last = self.id(l, fields[1], "last id")?;
                let step = match fields.get(2) {
                    Some(f) => self.id(l, f, "step")?,
                    None => 1,
                };
                if last < first {
                    return Err(self.err(
                        l,
                        format!("GENERATE from {first} to {last}: the last id must not be smaller than the first"),
                    ));
                }
                if (last - first) / step > MAX_GENERATED {
                    return Err(self.err(
                        l,
                        format!("GENERATE from {first} to {last} by {step} lists more than {MAX_GENERATED} ids"),
                    ));
                }
                members.extend((first..=last).step_by(step as usize).filter_map(&by_id));
                continue;
            }
            for f in fields.iter().filter(|f| !f.is_empty()) {
                match f.parse::<u64>() {
                    Ok(id) => members.push(by_id(id).ok_or_else(|| {
                        self.err(
                            l,
                            format!("{what} '{name}' lists {item} {id}, which no *{} defines (before it)", item.to_ascii_uppercase()),
                        )
                    })?),
                    Err(_) => {
                        let set = unquote(f);
                        members.extend_from_slice(by_name(set).ok_or_else(|| {
                            self.err(
                                l,
                                format!("{what} '{name}' lists '{set}', which is neither a defined {item} id nor the name of an earlier {item} set"),
                            )
                        })?)
                    }
                }
            }
        }
        if generate && members.is_empty() {
            return Err(self.err(
                line,
                format!("{what} '{name}': the GENERATE ranges hold no defined id"),
            ));
        }
        Ok(members)
    }

    /// `*ELSET, ELSET=name[, GENERATE]`.
    fn element_set(&mut self, line: &Line, keyword: &Keyword, data: &[Line]) -> Result<()> {
        let name = self.required(line, keyword, "ELSET")?.to_string();
        let b = &self.builder;
        let members = self.set_members(
            SetBlock {
                line,
                keyword,
                data,
                name: &name,
                what: "*ELSET",
                item: "element",
            },
            |id| b.element(id),
            |set| b.element_sets.get(set).map(Vec::as_slice),
        )?;
        self.builder.element_sets.entry(&name).extend(members);
        Ok(())
    }

    /// `*NSET, NSET=name[, GENERATE]` or `*NSET, NSET=name, ELSET=set`.
    fn node_set(&mut self, line: &Line, keyword: &Keyword, data: &[Line]) -> Result<()> {
        let name = self.required(line, keyword, "NSET")?.to_string();
        let b = &self.builder;
        let mut nodes = Vec::new();
        if let Some(elset) = keyword.param("ELSET") {
            let members = b.element_sets.get(elset).ok_or_else(|| {
                self.err(
                    line,
                    format!("*NSET '{name}': no element set '{elset}' is defined before"),
                )
            })?;
            nodes = b.member_nodes(members);
        }
        nodes.extend(self.set_members(
            SetBlock {
                line,
                keyword,
                data,
                name: &name,
                what: "*NSET",
                item: "node",
            },
            |id| b.node(id),
            |set| b.node_sets.get(set).map(Vec::as_slice),
        )?);
        self.builder.node_sets.entry(&name).extend(nodes);
        Ok(())
    }

    /// `*SURFACE, NAME=name[, TYPE=ELEMENT]`: `element-or-set[, S<k>]`.
    fn surface(&mut self, line: &Line, keyword: &Keyword, data: &[Line]) -> Result<()> {
        let name = self.required(line, keyword, "NAME")?.to_string();
        if let Some(t) = keyword.param("TYPE") {
            if !t.eq_ignore_ascii_case("ELEMENT") {
                return Err(self.err(
                    line,
                    format!(
                        "*SURFACE, TYPE={t} is not supported: give element faces (TYPE=ELEMENT, \
                         lines 'element or element set, S1…S6'); for a set of nodes use *NSET"
                    ),
                ));
            }
        }
        if data.is_empty() {
            return Err(self.err(line, format!("*SURFACE '{name}' has no data lines")));
        }
        for l in data {
            let fields = data_fields(l);
            if fields.is_empty() || fields.len() > 2 || fields[0].is_empty() {
                return Err(self.err(
                    l,
                    format!(
                        "a *SURFACE line is 'element or element set, face' (e.g. '12, S3'); found '{}'",
                        l.text()
                    ),
                ));
            }
            let members: Vec<Member> = match fields[0].parse::<u64>() {
                Ok(id) => vec![self.builder.element(id).ok_or_else(|| {
                    self.err(
                        l,
                        format!("*SURFACE '{name}': no element {id} is defined before"),
                    )
                })?],
                Err(_) => {
                    let set = unquote(fields[0]);
                    self.builder
                        .element_sets
                        .get(set)
                        .ok_or_else(|| {
                            self.err(
                                l,
                                format!("*SURFACE '{name}': '{set}' is neither an element id nor an element set defined before"),
                            )
                        })?
                        .clone()
                }
            };
            let face = match fields.get(1) {
                None => None,
                Some(f) => Some(self.face_number(l, f)?),
            };
            if !members.iter().any(|m| matches!(m, Member::Volume(_))) {
                return Err(self.err(
                    l,
                    format!(
                        "*SURFACE '{name}': '{}' holds no C3D4 or C3D8 element, so no face to take",
                        fields[0]
                    ),
                ));
            }
            for m in members {
                let Member::Volume(e) = m else {
                    continue; // surface or line elements have no solid faces
                };
                match face {
                    None => self.builder.add_free_faces(&name, e),
                    Some(s) => {
                        let el = self.builder.volume(e);
                        let local = outward_face(el.kind, s).ok_or_else(|| {
                            self.err(
                                l,
                                format!(
                                    "*SURFACE '{name}': element {} is a {} with faces S1…S{}, not S{s}",
                                    el.id,
                                    kind_name(el.kind),
                                    face_count(el.kind)
                                ),
                            )
                        })?;
                        self.builder.add_face(&name, e, local);
                    }
                }
            }
        }
        Ok(())
    }

    /// `S<k>` → `k`.
    fn face_number(&self, line: &Line, field: &str) -> Result<usize> {
        field
            .strip_prefix(['S', 's'])
            .and_then(|k| k.parse::<usize>().ok())
            .filter(|&k| k >= 1)
            .ok_or_else(|| {
                self.err(
                    line,
                    format!("'{field}' is not a face identifier of a solid element (S1, S2, …)"),
                )
            })
    }

    /// A positive integer id.
    fn id(&self, line: &Line, field: &str, what: &str) -> Result<u64> {
        field.parse::<u64>().ok().filter(|&v| v > 0).ok_or_else(|| {
            self.err(
                line,
                format!("expected a {what} (a positive integer), found '{field}'"),
            )
        })
    }

    /// A real number (Fortran `D` exponents accepted; an empty field is 0).
    fn number(&self, line: &Line, field: &str) -> Result<f64> {
        if field.is_empty() {
            return Ok(0.0);
        }
        let parsed = if field.contains(['d', 'D']) {
            field.replace(['d', 'D'], "e").parse::<f64>()
        } else {
            field.parse::<f64>()
        };
        parsed
            .ok()
            .filter(|v| v.is_finite())
            .ok_or_else(|| self.err(line, format!("expected a number, found '{field}'")))
    }
}

/// The comma-separated fields of a data line, without the empty field a
/// trailing comma leaves.
fn data_fields(line: &Line) -> Vec<&str> {
    let mut fields = split_fields(line.text());
    while fields.last().is_some_and(|f| f.is_empty()) {
        fields.pop();
    }
    fields
}

/// The lines of a `*ELSET` or `*NSET` block and what it defines.
struct SetBlock<'a> {
    /// The keyword line and its parsed keyword.
    line: &'a Line,
    keyword: &'a Keyword,
    /// The data lines after it.
    data: &'a [Line],
    /// The set's name.
    name: &'a str,
    /// The keyword and the kind of item, e.g. `"*NSET"` and `"node"`.
    what: &'a str,
    item: &'a str,
}
