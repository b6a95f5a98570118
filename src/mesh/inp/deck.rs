//! The lines of a deck: every file read, `*INCLUDE` followed where it
//! stands, comments (`**`) and blank lines dropped, a keyword line
//! continued by a trailing comma joined with its continuation; each line
//! keeps its file and 1-based line number for the errors.
//!
//! Every file, the deck and each include, goes through the input guard
//! ([`crate::input::read_text_bytes`]: a regular file, within the mesh
//! file's size, text); the files of one deck hold at most that size
//! together, and their `GENERATE` ranges and the sets named in sets list
//! at most [`Limits::generated_ids`] ids together ([`Deck::generated`]).

use crate::input::{read_text_bytes, Budget, Limits, MAX_MESH_FILE};
use crate::{Error, Result};
use std::ops::Range;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// How deep `*INCLUDE`s may nest (a guard against runaway recursion; a
/// cycle is reported as such before this is reached).
const MAX_INCLUDE_DEPTH: usize = 32;

/// One significant line of the deck: a range of its file's text (no
/// allocation per line), or the joined text of a continued keyword line.
pub(super) struct Line {
    /// Index into [`Deck::files`].
    file: usize,
    /// 1-based line number in that file.
    pub(super) number: usize,
    /// The file's text and the line's (trimmed) byte range in it.
    source: Arc<str>,
    range: Range<usize>,
    /// A keyword line joined with its continuation lines.
    joined: Option<String>,
}

impl Line {
    /// The line, trimmed.
    pub(super) fn text(&self) -> &str {
        match &self.joined {
            Some(text) => text,
            None => &self.source[self.range.clone()],
        }
    }
    pub(super) fn is_keyword(&self) -> bool {
        self.text().starts_with('*')
    }
}

/// A keyword line: `*NAME, KEY=VALUE, FLAG, …`, the name and keys upper
/// case with single spaces (`*SOLID SECTION`), values as written without
/// quotes.
pub(super) struct Keyword {
    pub(super) name: String,
    params: Vec<(String, Option<String>)>,
}

impl Keyword {
    /// The value of `KEY=value`.
    pub(super) fn param(&self, key: &str) -> Option<&str> {
        self.params
            .iter()
            .find(|(k, _)| k == key)
            .and_then(|(_, v)| v.as_deref())
    }
    /// Whether the parameter `key` is present (with or without a value).
    pub(super) fn has(&self, key: &str) -> bool {
        self.params.iter().any(|(k, _)| k == key)
    }
}

/// All the lines of a deck and its included files.
pub(super) struct Deck {
    files: Vec<PathBuf>,
    pub(super) lines: Vec<Line>,
    /// Bytes of all the files read, against [`MAX_MESH_FILE`].
    bytes: Budget,
    /// Ids listed by `GENERATE` lines so far, against [`Limits::generated_ids`].
    generated: Budget,
}

impl Deck {
    /// Reads `path` and, recursively, the files it includes (`*INCLUDE,
    /// INPUT=file`, relative to the including file's folder).
    pub(super) fn read(path: &Path, limits: &Limits) -> Result<Deck> {
        let mut deck = Deck {
            files: Vec::new(),
            lines: Vec::new(),
            bytes: Budget::new(MAX_MESH_FILE),
            generated: Budget::new(limits.generated_ids),
        };
        let text = read_text_bytes(path, "read", MAX_MESH_FILE)?;
        deck.read_file(path, &text, &mut Vec::new())?;
        Ok(deck)
    }

    /// Counts the `count` ids a `GENERATE` range, or a set named in a set,
    /// at `line` lists; refused when the deck's sets together would list
    /// more than the limit (a set named 1 000 times in a set named 1 000
    /// times … grows as 1 000ⁿ).
    pub(super) fn generated(&self, line: &Line, count: u64) -> Result<()> {
        self.generated.spend(count).map_err(|(total, limit)| {
            self.error(
                line,
                format!(
                    "the sets of this mesh would list {total} ids with this one's {count} (GENERATE \
                     ranges and the sets named in other sets count together), more than the {limit} \
                     allowed: check the ranges (a typo such as '1, 1000000000000') and the set names, \
                     or raise the limit with [mesh] max_generated_ids in the case file"
                ),
            )
        })
    }

    fn read_file(&mut self, path: &Path, bytes: &[u8], stack: &mut Vec<PathBuf>) -> Result<()> {
        self.bytes.spend(bytes.len() as u64).map_err(|(total, limit)| {
            Error::io(
                "read",
                path,
                std::io::Error::new(
                    std::io::ErrorKind::InvalidInput,
                    format!("the deck and its includes hold {total} bytes together, more than the limit of {limit} bytes of a mesh"),
                ),
            )
        })?;
        let file = self.files.len();
        self.files.push(path.to_path_buf());
        stack.push(path.canonicalize().unwrap_or_else(|_| path.to_path_buf()));
        let source: Arc<str> = Arc::from(String::from_utf8_lossy(bytes));
        let base = source.as_ptr() as usize;
        let mut raw = source
            .lines()
            .enumerate()
            .map(|(i, l)| (i + 1, l.trim()))
            .filter(|(_, l)| !l.is_empty() && !l.starts_with("**"))
            .peekable();
        while let Some((number, first)) = raw.next() {
            // a keyword line ending with a comma continues on the next line
            let mut joined: Option<String> = None;
            while first.starts_with('*') && joined.as_deref().unwrap_or(first).ends_with(',') {
                match raw.peek() {
                    Some((_, next)) if !next.starts_with('*') => {
                        joined
                            .get_or_insert_with(|| first.to_string())
                            .push_str(next);
                        raw.next();
                    }
                    _ => break,
                }
            }
            // `first` is a slice of `source`: its offset is where it starts
            let start = first.as_ptr() as usize - base;
            let line = Line {
                file,
                number,
                source: Arc::clone(&source),
                range: start..start + first.len(),
                joined,
            };
            if line.is_keyword() && self.keyword(&line)?.name == "INCLUDE" {
                self.include(&line, stack)?;
            } else {
                self.lines.push(line);
            }
        }
        stack.pop();
        Ok(())
    }

    /// Follows `*INCLUDE, INPUT=file` at `line`.
    fn include(&mut self, line: &Line, stack: &mut Vec<PathBuf>) -> Result<()> {
        let keyword = self.keyword(line)?;
        let input = keyword
            .param("INPUT")
            .ok_or_else(|| self.error(line, "*INCLUDE needs INPUT=<file>".into()))?;
        let dir = self.files[line.file]
            .parent()
            .unwrap_or(Path::new("."))
            .to_path_buf();
        let path = dir.join(input);
        let canonical = path.canonicalize().unwrap_or_else(|_| path.clone());
        if stack.contains(&canonical) {
            return Err(self.error(
                line,
                format!("'{}' includes itself (through *INCLUDE)", path.display()),
            ));
        }
        if stack.len() >= MAX_INCLUDE_DEPTH {
            return Err(self.error(
                line,
                format!("*INCLUDE nested more than {MAX_INCLUDE_DEPTH} deep"),
            ));
        }
        // after the cycle check: a file that includes itself is not read again
        let bytes = read_text_bytes(&path, "read", MAX_MESH_FILE).map_err(|e| {
            let cause = match &e {
                Error::Io { source, .. } => source.to_string(),
                other => other.to_string(),
            };
            self.error(
                line,
                format!(
                    "cannot read the included file '{}': {cause}",
                    crate::error::resolved(&path).display()
                ),
            )
        })?;
        self.read_file(&path, &bytes, stack)
    }

    /// An error at `line`, naming its file and line number.
    pub(super) fn error(&self, line: &Line, message: String) -> Error {
        Error::MeshSyntax {
            path: self.files[line.file].clone(),
            line: line.number,
            message,
        }
    }

    /// Where `line` stands: its file and line number.
    pub(super) fn locate(&self, line: &Line) -> super::physics::Located {
        super::physics::Located {
            path: self.files[line.file].clone(),
            line: line.number,
        }
    }

    /// Parses the keyword line `line`.
    pub(super) fn keyword(&self, line: &Line) -> Result<Keyword> {
        let mut fields = split_fields(&line.text()[1..]).into_iter();
        let name = fields
            .next()
            .unwrap_or_default()
            .split_whitespace()
            .collect::<Vec<_>>()
            .join(" ")
            .to_ascii_uppercase();
        if name.is_empty() {
            return Err(self.error(line, "a '*' with no keyword after it".into()));
        }
        let mut params = Vec::new();
        for field in fields.filter(|f| !f.is_empty()) {
            let (key, value) = match field.split_once('=') {
                Some((k, v)) => (k.trim(), Some(unquote(v.trim()).to_string())),
                None => (field, None),
            };
            params.push((key.to_ascii_uppercase(), value));
        }
        Ok(Keyword { name, params })
    }
}

/// Splits a line at commas outside double quotes; fields trimmed (quotes
/// kept), borrowed from `text`.
pub(super) fn split_fields(text: &str) -> Vec<&str> {
    let mut fields = Vec::new();
    let mut start = 0;
    let mut quoted = false;
    // '"' and ',' are ASCII: their bytes never occur inside a UTF-8 sequence
    for (i, b) in text.bytes().enumerate() {
        match b {
            b'"' => quoted = !quoted,
            b',' if !quoted => {
                fields.push(text[start..i].trim());
                start = i + 1;
            }
            _ => {}
        }
    }
    fields.push(text[start..].trim());
    fields
}

/// A name without its surrounding double quotes, if any.
pub(super) fn unquote(s: &str) -> &str {
    s.strip_prefix('"')
        .and_then(|s| s.strip_suffix('"'))
        .unwrap_or(s)
}

#[cfg(test)]
mod tests {
    use super::split_fields;

    #[test]
    fn fields_split_at_commas_outside_quotes() {
        assert_eq!(
            split_fields(r#" *NSET , NSET="a, b" ,GENERATE,"#),
            [" *NSET", r#"NSET="a, b""#, "GENERATE", ""].map(str::trim)
        );
        assert_eq!(split_fields("1, 0.5, -2e-3"), ["1", "0.5", "-2e-3"]);
        assert_eq!(split_fields("é,ü"), ["é", "ü"]);
        assert_eq!(split_fields(""), [""]);
    }
}
