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
//! - `parts`: `*PART` and `*INSTANCE` blocks.
//! - `nodes`: `*NODE` and `*ELEMENT` blocks.
//! - `sets`: `*ELSET` and `*NSET`; `surface`: `*SURFACE`.
//! - here: the reader loop, the keyword dispatch and the field parsers.

mod assembly;
mod builder;
mod deck;
mod element_type;
mod history;
mod keywords;
mod nodes;
mod parts;
pub mod physics;
mod sets;
mod surface;

use super::Mesh;
use crate::Result;
use assembly::{Context, Instance, Part};
use builder::{Builder, Member};
use deck::{split_fields, Deck, Keyword, Line};
use physics::{Physics, StepDef};
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
