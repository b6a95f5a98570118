//! Reader for Abaqus input decks (`.inp`), the keyword format that
//! CalculiX also reads and that Gmsh, meshio, FreeCAD, PrePoMax and Salome
//! write. [`read_inp`] reads the mesh of a case file (the case gives the
//! physics); [`read_deck`] also reads the deck's physics ([`physics`]), to
//! run the deck as it is (`crate::case::deck` turns it into a case).
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
//! - `*PART … *END PART`, `*ASSEMBLY`, `*INSTANCE, NAME=…, PART=…` with
//!   its translation and rotation lines ([`assembly`]): ids local to a part
//!   mapped to global ones, names qualified by instance (`Part-1-1.TOP`).
//! - The physics keywords ([`keywords`], [`history`]): for a case file's
//!   mesh, skipped and listed in one note; for the deck run as it is, read
//!   or refused by name.
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
//! - `assembly`: parts, instances and their transforms.
//! - `physics`: the records of the deck's physics; `keywords` and
//!   `history` read them.
//! - here: the keywords and their data lines.

mod assembly;
mod builder;
mod deck;
mod element_type;
mod history;
mod keywords;
pub mod physics;

use super::Mesh;
use crate::Result;
use assembly::{Context, Instance, Part, Transform};
use builder::{kind_name, Builder, Member};
use deck::{split_fields, unquote, Deck, Keyword, Line};
use element_type::{element_type, face_count, outward_face, Shape};
use physics::{Physics, StepDef};
use rayon::prelude::*;
use std::ops::Range;
use std::path::Path;

/// A mesh read from a deck, and notes for the user (the keywords skipped,
/// element types read as another).
pub struct InpMesh {
    pub mesh: Mesh,
    pub notes: Vec<String>,
}

/// A whole deck: its mesh, its physics and notes for the user.
pub struct InpDeck {
    pub mesh: Mesh,
    pub physics: Physics,
    pub notes: Vec<String>,
}

/// What the deck is read for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Mode {
    /// The mesh of a case file: the physics keywords are listed as ignored
    /// (read all the same, for the implicit sets that a case converted
    /// from the deck names), their errors dropped.
    Mesh,
    /// The deck run as it is: every keyword read, or an error.
    Deck,
}

/// Reads an Abaqus/CalculiX deck (and the files it includes) into a
/// [`Mesh`] with outward-oriented surface sets; the physics keywords are
/// ignored (the case file gives the physics).
pub fn read_inp(path: &Path) -> Result<InpMesh> {
    read_inp_with(path, &crate::input::Limits::default())
}

/// [`read_inp`] within `limits` (the ids the deck's `GENERATE` lines list
/// together).
pub fn read_inp_with(path: &Path, limits: &crate::input::Limits) -> Result<InpMesh> {
    let deck = read(path, Mode::Mesh, limits)?;
    Ok(InpMesh {
        mesh: deck.mesh,
        notes: deck.notes,
    })
}

/// Reads a deck with its physics, to run it as it is: a keyword that
/// would change the answer and that is not supported is an error naming
/// it and its line.
pub fn read_deck(path: &Path) -> Result<InpDeck> {
    read(path, Mode::Deck, &crate::input::Limits::default()).map_err(|e| match e {
        crate::Error::MeshSyntax {
            path,
            line,
            message,
        } => crate::Error::Deck {
            path,
            line,
            message,
        },
        e => e,
    })
}

fn read(path: &Path, mode: Mode, limits: &crate::input::Limits) -> Result<InpDeck> {
    let deck = Deck::read(path, limits)?;
    let mut blocks = Vec::new();
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
        blocks.push((i, i + 1..end));
        i = end;
    }
    let mut reader = Reader {
        deck: &deck,
        blocks,
        mode,
        builder: Builder::new(),
        ignored: Vec::new(),
        notes: Vec::new(),
        parts: Vec::new(),
        instances: Vec::new(),
        context: Context::default(),
        max_node: 0,
        max_element: 0,
        physics: Physics::default(),
        step: None,
        material: None,
        interaction: None,
    };
    let mut b = 0;
    while b < reader.blocks.len() {
        b = reader.block(b)?;
    }
    if let Some(step) = reader.step.as_ref().filter(|_| mode == Mode::Deck) {
        return Err(step
            .at
            .error(format!("*STEP '{}' has no *END STEP", step.name)));
    }
    let Reader {
        builder,
        ignored,
        mut notes,
        physics,
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
    Ok(InpDeck {
        mesh,
        physics,
        notes,
    })
}

struct Reader<'a> {
    deck: &'a Deck,
    /// Each keyword line and the range of its data lines.
    blocks: Vec<(usize, Range<usize>)>,
    mode: Mode,
    builder: Builder,
    /// Keywords skipped, `*NAME`, each once, in order of appearance.
    ignored: Vec<String>,
    notes: Vec<String>,
    parts: Vec<Part>,
    instances: Vec<Instance>,
    /// How ids and names are read here (global, or inside an instance).
    context: Context,
    /// The largest node and element ids read so far.
    max_node: u64,
    max_element: u64,
    physics: Physics,
    /// The step being read (between `*STEP` and `*END STEP`).
    step: Option<StepDef>,
    /// The material and surface interaction the keywords that follow
    /// `*MATERIAL` and `*SURFACE INTERACTION` describe.
    material: Option<usize>,
    interaction: Option<usize>,
}

impl<'a> Reader<'a> {
    fn err(&self, line: &Line, message: String) -> crate::Error {
        self.deck.error(line, message)
    }

    /// The keyword line and data lines of block `b`.
    fn lines(&self, b: usize) -> (&'a Line, &'a [Line]) {
        let (k, data) = &self.blocks[b];
        let deck = self.deck;
        (&deck.lines[*k], &deck.lines[data.clone()])
    }

    /// Reads block `b` (and, for `*PART` and `*INSTANCE`, the blocks up to
    /// their end); the index of the next block.
    fn block(&mut self, b: usize) -> Result<usize> {
        let (line, data) = self.lines(b);
        let keyword = self.deck.keyword(line)?;
        match keyword.name.as_str() {
            "PART" => self.part(b, &keyword),
            "INSTANCE" => self.instance(b, &keyword),
            "ASSEMBLY" | "END ASSEMBLY" => Ok(b + 1),
            "END PART" | "END INSTANCE" => Err(self.err(
                line,
                format!(
                    "*{} without a *{} before it",
                    keyword.name,
                    &keyword.name[4..]
                ),
            )),
            _ => {
                self.keyword(line, data)?;
                Ok(b + 1)
            }
        }
    }

    /// The first block after `b` whose keyword is `*<end>`.
    fn find_end(&self, b: usize, end: &str) -> Result<Option<usize>> {
        for j in b + 1..self.blocks.len() {
            let (line, _) = self.lines(j);
            if self.deck.keyword(line)?.name == end {
                return Ok(Some(j));
            }
        }
        Ok(None)
    }

    /// `*PART, NAME=…`: its blocks kept until an instance places it.
    fn part(&mut self, b: usize, keyword: &Keyword) -> Result<usize> {
        let (line, _) = self.lines(b);
        let name = self.required(line, keyword, "NAME")?.to_string();
        let end = self
            .find_end(b, "END PART")?
            .ok_or_else(|| self.err(line, format!("*PART '{name}' has no *END PART after it")))?;
        if self
            .parts
            .iter()
            .any(|p| p.name.eq_ignore_ascii_case(&name))
        {
            return Err(self.err(line, format!("*PART '{name}' is defined twice")));
        }
        for j in b + 1..end {
            let (inner, _) = self.lines(j);
            let k = self.deck.keyword(inner)?;
            if matches!(k.name.as_str(), "PART" | "INSTANCE" | "ASSEMBLY" | "STEP") {
                return Err(self.err(
                    inner,
                    format!(
                        "*{} inside *PART '{name}': close the part with *END PART first",
                        k.name
                    ),
                ));
            }
        }
        self.parts.push(Part {
            name,
            blocks: b + 1..end,
        });
        Ok(end + 1)
    }

    /// `*INSTANCE, NAME=…, PART=…` with its optional translation and
    /// rotation lines: the part's keywords read in the instance's context.
    fn instance(&mut self, b: usize, keyword: &Keyword) -> Result<usize> {
        let (line, data) = self.lines(b);
        let name = self.required(line, keyword, "NAME")?.to_string();
        let part_name = keyword.param("PART").ok_or_else(|| {
            self.err(
                line,
                format!("*INSTANCE '{name}' needs PART=<name>: an instance places a *PART (an instance with its own nodes is not supported)"),
            )
        })?;
        let part = self
            .parts
            .iter()
            .find(|p| p.name.eq_ignore_ascii_case(part_name))
            .cloned()
            .ok_or_else(|| {
                let have: Vec<&str> = self.parts.iter().map(|p| p.name.as_str()).collect();
                self.err(
                    line,
                    format!(
                        "*INSTANCE '{name}': no *PART named '{part_name}' is defined before it (parts: {})",
                        if have.is_empty() { "none".into() } else { have.join(", ") }
                    ),
                )
            })?;
        if self.instance_named(&name).is_some() {
            return Err(self.err(line, format!("*INSTANCE '{name}' is defined twice")));
        }
        let transform = self.transform(data)?;
        let end = self.find_end(b, "END INSTANCE")?.ok_or_else(|| {
            self.err(
                line,
                format!("*INSTANCE '{name}' has no *END INSTANCE after it"),
            )
        })?;
        if end > b + 1 {
            let (inner, _) = self.lines(b + 1);
            return Err(self.err(
                inner,
                format!("keywords inside *INSTANCE '{name}' are not supported: define the mesh in its *PART"),
            ));
        }
        let context = Context {
            instance: Some(name.clone()),
            node_offset: self.max_node,
            element_offset: self.max_element,
            transform: Some(transform),
        };
        let (nodes, elements) = self.builder.counts();
        let outer = std::mem::replace(&mut self.context, context.clone());
        for j in part.blocks.clone() {
            let (l, d) = self.lines(j);
            self.keyword(l, d)?;
        }
        self.context = outer;
        let (nodes_after, elements_after) = self.builder.counts();
        self.builder
            .node_sets
            .entry(&name)
            .extend(nodes..nodes_after);
        self.builder
            .element_sets
            .entry(&name)
            .extend((elements..elements_after).map(Member::Volume));
        self.instances.push(Instance {
            name,
            context: Context {
                transform: None,
                ..context
            },
        });
        Ok(end + 1)
    }

    /// The instance called `name` (case ignored).
    fn instance_named(&self, name: &str) -> Option<&Instance> {
        self.instances
            .iter()
            .find(|i| i.name.eq_ignore_ascii_case(name))
    }

    /// The transform of an `*INSTANCE`'s data lines: `tx, ty, tz` and
    /// `ax, ay, az, bx, by, bz, angle`.
    fn transform(&self, data: &[Line]) -> Result<Transform> {
        if data.len() > 2 {
            return Err(self.err(
                &data[2],
                "an *INSTANCE has at most two data lines (translation, rotation)".into(),
            ));
        }
        let numbers = |l: &Line, n: usize, what: &str| -> Result<Vec<f64>> {
            let fields = data_fields(l);
            if fields.len() != n {
                return Err(self.err(
                    l,
                    format!(
                        "the {what} line of an *INSTANCE has {n} numbers; found {}",
                        fields.len()
                    ),
                ));
            }
            fields.iter().map(|f| self.number(l, f)).collect()
        };
        let translation = match data.first() {
            Some(l) => numbers(l, 3, "translation")?,
            None => vec![0.0; 3],
        };
        let rotation = match data.get(1) {
            Some(l) => Some(numbers(l, 7, "rotation (a, b, angle)")?),
            None => None,
        };
        Transform::new(
            [translation[0], translation[1], translation[2]],
            rotation.map(|r| [r[0], r[1], r[2], r[3], r[4], r[5], r[6]]),
        )
        .map_err(|m| self.err(&data[1], format!("*INSTANCE rotation: {m}")))
    }

    /// Why the set `name` (as the mesh would have it) is not found: a
    /// qualified name whose instance does not exist says so.
    fn missing_set(&self, name: &str, kind: &str) -> String {
        if let Some((instance, _)) = name.split_once('.') {
            if self.instance_named(instance).is_none() {
                let have: Vec<&str> = self.instances.iter().map(|i| i.name.as_str()).collect();
                return format!(
                    "'{name}' names the instance '{instance}', which no *INSTANCE defines before it (instances: {})",
                    if have.is_empty() { "none".into() } else { have.join(", ") }
                );
            }
        }
        format!("no {kind} '{name}' is defined before it")
    }

    /// Reads the keyword at `line` and its data lines `data`, in the
    /// context of `INSTANCE=` if it has one.
    fn keyword(&mut self, line: &Line, data: &[Line]) -> Result<()> {
        let keyword = self.deck.keyword(line)?;
        let Some(instance) = keyword.param("INSTANCE") else {
            return self.dispatch(line, &keyword, data);
        };
        let context = self
            .instance_named(instance)
            .map(|i| Context {
                instance: None,
                ..i.context.clone()
            })
            .ok_or_else(|| {
                self.err(
                    line,
                    format!("INSTANCE={instance}: no *INSTANCE of that name is defined before it"),
                )
            })?;
        let outer = std::mem::replace(&mut self.context, context);
        let result = self.dispatch(line, &keyword, data);
        self.context = outer;
        result
    }

    fn dispatch(&mut self, line: &Line, keyword: &Keyword, data: &[Line]) -> Result<()> {
        match keyword.name.as_str() {
            "NODE" => self.nodes(line, keyword, data),
            "ELEMENT" => self.elements(line, keyword, data),
            "ELSET" => self.element_set(line, keyword, data),
            "NSET" => self.node_set(line, keyword, data),
            "SURFACE" => self.surface(line, keyword, data),
            "HEADING" => Ok(()),
            _ => self.physics_keyword(line, keyword, data),
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
        let nset = keyword.param("NSET").map(|n| self.context.name(n));
        // the lines parsed side by side, then added in order (the first
        // error in the deck's order is the one reported)
        let parsed: Vec<Result<(u64, [f64; 3])>> =
            data.par_iter().map(|l| self.node_line(l)).collect();
        let mut added = Vec::with_capacity(data.len());
        for (l, p) in data.iter().zip(parsed) {
            let (id, x) = p?;
            let id = self.context.node(id);
            let x = match &self.context.transform {
                Some(t) => t.apply(x),
                None => x,
            };
            self.max_node = self.max_node.max(id);
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
        for ((c, f), axis) in x.iter_mut().zip(&fields[1..]).zip(["x", "y", "z"]) {
            *c = self.number(l, f)?;
            if let Some(fault) = crate::input::coordinate_fault(*c) {
                return Err(self.err(l, format!("the {axis} coordinate of node {id} {fault}")));
            }
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
        let elset = keyword.param("ELSET").map(|n| self.context.name(n));
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
            let id = self.context.element(id);
            let nodes: Vec<u64> = nodes.iter().map(|&n| self.context.node(n)).collect();
            self.max_element = self.max_element.max(id);
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
                // counted over the whole deck before any id is listed
                self.deck.generated(l, (last - first) / step + 1)?;
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
                        let set = self.context.name(unquote(f));
                        let named = by_name(&set).ok_or_else(|| {
                            let why = if set.contains('.') {
                                format!(": {}", self.missing_set(&set, &format!("{item} set")))
                            } else {
                                String::new()
                            };
                            self.err(
                                l,
                                format!("{what} '{name}' lists '{set}', which is neither a defined {item} id nor the name of an earlier {item} set{why}"),
                            )
                        })?;
                        // a set named n times copies it n times: counted with GENERATE's
                        self.deck.generated(l, named.len() as u64)?;
                        members.extend_from_slice(named)
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
        let name = self.context.name(self.required(line, keyword, "ELSET")?);
        let b = &self.builder;
        let c = &self.context;
        let members = self.set_members(
            SetBlock {
                line,
                keyword,
                data,
                name: &name,
                what: "*ELSET",
                item: "element",
            },
            |id| b.element(c.element(id)),
            |set| b.element_sets.get(set).map(Vec::as_slice),
        )?;
        self.builder.element_sets.entry(&name).extend(members);
        Ok(())
    }

    /// `*NSET, NSET=name[, GENERATE]` or `*NSET, NSET=name, ELSET=set`.
    fn node_set(&mut self, line: &Line, keyword: &Keyword, data: &[Line]) -> Result<()> {
        let name = self.context.name(self.required(line, keyword, "NSET")?);
        let b = &self.builder;
        let c = &self.context;
        let mut nodes = Vec::new();
        if let Some(elset) = keyword.param("ELSET") {
            let elset = &c.name(elset);
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
            |id| b.node(c.node(id)),
            |set| b.node_sets.get(set).map(Vec::as_slice),
        )?);
        self.builder.node_sets.entry(&name).extend(nodes);
        Ok(())
    }

    /// `*SURFACE, NAME=name[, TYPE=ELEMENT]`: `element-or-set[, S<k>]`.
    fn surface(&mut self, line: &Line, keyword: &Keyword, data: &[Line]) -> Result<()> {
        let name = self.context.name(self.required(line, keyword, "NAME")?);
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
                Ok(id) => {
                    vec![self
                        .builder
                        .element(self.context.element(id))
                        .ok_or_else(|| {
                            self.err(
                                l,
                                format!("*SURFACE '{name}': no element {id} is defined before"),
                            )
                        })?]
                }
                Err(_) => {
                    let set = self.context.name(unquote(fields[0]));
                    self.builder
                        .element_sets
                        .get(&set)
                        .ok_or_else(|| {
                            self.err(
                                l,
                                format!("*SURFACE '{name}': '{set}' is neither an element id nor an element set defined before ({})", self.missing_set(&set, "element set")),
                            )
                        })?
                        .clone()
                }
            };
            let face = match fields.get(1) {
                None => None,
                Some(f) => Some(self.face_number(l, f)?),
            };
            let label = format!("*SURFACE '{name}'");
            self.add_faces(&name, &label, &members, face, l, fields[0])?;
        }
        Ok(())
    }

    /// Adds face `face` (every free face if `None`) of the volume elements
    /// among `members` to the surface `name`; `label` names the keyword and
    /// `what` the members in the messages of line `l`.
    fn add_faces(
        &mut self,
        name: &str,
        label: &str,
        members: &[Member],
        face: Option<usize>,
        l: &Line,
        what: &str,
    ) -> Result<()> {
        if !members.iter().any(|m| matches!(m, Member::Volume(_))) {
            return Err(self.err(
                l,
                format!("{label}: '{what}' holds no C3D4 or C3D8 element, so no face to take"),
            ));
        }
        for &m in members {
            let Member::Volume(e) = m else {
                continue; // surface or line elements have no solid faces
            };
            match face {
                None => self.builder.add_free_faces(name, e),
                Some(s) => {
                    let el = self.builder.volume(e);
                    let local = outward_face(el.kind, s).ok_or_else(|| {
                        self.err(
                            l,
                            format!(
                                "{label}: element {} is a {} with faces S1…S{}, not S{s}",
                                el.id,
                                kind_name(el.kind),
                                face_count(el.kind)
                            ),
                        )
                    })?;
                    self.builder.add_face(name, e, local);
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
