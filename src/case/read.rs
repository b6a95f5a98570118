//! Reading a case file: its text parsed into the schema, and the mesh it
//! names loaded, with errors that name the line and the key path.

use super::schema::CaseFile;
use super::{deck, limits, lines, tagged, Case};
use crate::error::{suggest, words};
use crate::mesh::Mesh;
use crate::{Error, Result};
use std::path::Path;
use std::sync::Arc;

pub(super) fn case_error(path: &Path, message: impl Into<String>) -> Error {
    Error::Case {
        path: path.to_path_buf(),
        message: message.into(),
    }
}

/// Parse a case file's text. Errors name the line and the key path.
pub fn parse(path: &Path, text: &str) -> Result<CaseFile> {
    let spec = deserialize(path, text)?;
    if let Some((offset, message)) = limits::check(text) {
        return Err(case_error(
            path,
            format!("line {}: {message}", line_of(text, offset)),
        ));
    }
    Ok(spec)
}

/// The 1-based line of byte `offset` in `text`.
pub(super) fn line_of(text: &str, offset: usize) -> usize {
    text[..offset.min(text.len())].matches('\n').count() + 1
}

/// The schema read from the text, or an error naming the line and the key.
fn deserialize(path: &Path, text: &str) -> Result<CaseFile> {
    let de = toml::Deserializer::new(text);
    serde_path_to_error::deserialize(de).map_err(|e| {
        let key = e.path().to_string();
        let inner = e.into_inner();
        let msg = inner.message().to_string();
        let line = |offset: usize| line_of(text, offset);
        if let Some((offset, message)) = tagged::refine(text, &key, &msg) {
            let message = words::plain(&message);
            return case_error(path, format!("line {}: {message}", line(offset)));
        }
        let location = inner
            .span()
            .map(|s| format!("line {}: ", line(s.start)))
            .unwrap_or_default();
        let key = if key == "." {
            String::new()
        } else {
            format!("at key '{key}': ")
        };
        let hint = suggest::serde_hint(&msg);
        case_error(path, format!("{location}{key}{}{hint}", words::plain(&msg)))
    })
}

/// A file error ([`Error::Io`]: missing, unreadable, too large) of the
/// file that the key `key` of the case file names, as an error of the case
/// file at that key's line: the key, then the path resolved. Other errors
/// (of the file's contents) name the file already and pass unchanged.
pub(super) fn file_error(path: &Path, text: &str, key: &str, e: Error) -> Error {
    if !matches!(e, Error::Io { .. }) {
        return e;
    }
    let line = lines::offset_of_path(text, key)
        .map(|o| format!("line {}: ", line_of(text, o)))
        .unwrap_or_default();
    case_error(path, format!("{line}{key}: {e}"))
}

impl Case {
    /// [`file_error`] of this case file.
    pub(super) fn file_error(&self, key: &str, e: Error) -> Error {
        file_error(&self.path, &self.text, key, e)
    }
}

/// Read the case file and its mesh; an Abaqus/CalculiX deck (`.inp`) is
/// read with its physics, as the case [`deck::load`] translates it into.
pub fn load(path: &Path) -> Result<Case> {
    if path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("inp"))
    {
        return deck::load(path);
    }
    let text = crate::input::read_text(path, "read case file", crate::input::MAX_CASE_FILE)?;
    from_text(path, &text)
}

/// A case from the text of a case file; its paths (the mesh, the output
/// folder) are relative to `base_dir`.
pub fn from_toml(text: &str, base_dir: &Path) -> Result<Case> {
    from_text(&base_dir.join("case"), text)
}

/// A case from the text of a case file without its `[mesh]` table and a
/// mesh built in code ([`Mesh::from_arrays`]); the text's other paths (the
/// output folder) are relative to `base_dir`. Errors are those of a case
/// file, with the same line numbers and key paths.
pub fn from_mesh(text: &str, base_dir: &Path, mesh: Mesh) -> Result<Case> {
    let path = base_dir.join("case");
    if text
        .parse::<toml::Table>()
        .is_ok_and(|t| t.contains_key("mesh"))
    {
        return Err(case_error(
            &path,
            "[mesh]: the mesh is given as arrays; remove the [mesh] table",
        ));
    }
    // the schema's [mesh] table, after the text so that its line numbers hold
    let text = format!(
        "{text}\n[mesh]\nfile = \"{}\"\n",
        crate::mesh::arrays::ARRAYS
    );
    let mut spec = parse(&path, &text)?;
    let mut notes = Vec::new();
    super::contacts::default_discretisations(&mut spec, &mesh, &mut notes);
    Ok(Case {
        path,
        spec,
        mesh: Arc::new(mesh),
        notes,
        text,
    })
}

/// A case from the text of the case file at `path` (which names it in
/// messages; its folder resolves the mesh path).
fn from_text(path: &Path, text: &str) -> Result<Case> {
    let mut spec = parse(path, text)?;
    if spec.mesh.file.trim().is_empty() {
        return Err(case_error(
            path,
            "mesh.file is empty: give the path of the .msh file, relative to the case file",
        ));
    }
    let mesh_path = path
        .parent()
        .unwrap_or(Path::new("."))
        .join(&spec.mesh.file);
    let (mesh, mut notes) = crate::mesh::read_mesh_with(&mesh_path, &spec.mesh.input_limits())
        .map_err(|e| file_error(path, text, "mesh.file", e))?;
    if mesh_path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("inp"))
    {
        super::deck_names::match_deck_case(&mut spec, &mesh);
    }
    if mesh.elements.is_empty() {
        return Err(Error::Mesh {
            path: mesh_path,
            message: "the mesh has no volume elements (Tet4 or Hex8); mesh the volume (gmsh -3) and save it".into(),
        });
    }
    super::contacts::default_discretisations(&mut spec, &mesh, &mut notes);
    Ok(Case {
        path: path.to_path_buf(),
        spec,
        mesh: Arc::new(mesh),
        notes,
        text: text.to_string(),
    })
}
