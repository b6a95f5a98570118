//! The cursor over a MSH file: ASCII tokens with line numbers, binary
//! values with byte offsets, and the errors that say where the file is wrong.

use crate::{Error, Result};
use std::path::Path;

/// A position in the file. ASCII is read as whitespace-separated tokens and
/// errors give the 1-based line (computed from the offset only when an error
/// is reported); binary payloads are read as fixed-size values and errors
/// give the byte offset.
pub(super) struct Cursor<'a> {
    data: &'a [u8],
    pub(super) pos: usize,
    path: &'a Path,
    /// The file is binary (`$MeshFormat` file type 1).
    pub(super) binary_file: bool,
    /// The cursor is inside a binary payload.
    pub(super) binary: bool,
    pub(super) big_endian: bool,
    /// Bytes in a `size_t` (4.1 binary).
    pub(super) size_t: usize,
    /// The section whose binary payload is being read, and where it starts.
    section: &'static str,
    section_start: usize,
}

impl<'a> Cursor<'a> {
    pub(super) fn new(data: &'a [u8], path: &'a Path) -> Self {
        Cursor {
            data,
            pos: 0,
            path,
            binary_file: false,
            binary: false,
            big_endian: false,
            size_t: 8,
            section: "",
            section_start: 0,
        }
    }

    pub(super) fn binary_file(&self) -> bool {
        self.binary_file
    }

    // -- errors -----------------------------------------------------------

    fn line_of(&self, at: usize) -> usize {
        let end = at.min(self.data.len());
        1 + self.data[..end].iter().filter(|&&c| c == b'\n').count()
    }

    /// Where offset `at` is, for messages.
    pub(super) fn location(&self, at: usize) -> String {
        if self.binary {
            format!("byte offset {at} (binary {} data)", self.section)
        } else {
            format!("line {}", self.line_of(at))
        }
    }

    /// A syntax error at offset `at`: its line for ASCII, its byte offset
    /// (and the line of the section header) for binary data.
    pub(super) fn syntax(&self, at: usize, message: String) -> Error {
        let (line, message) = if self.binary {
            (
                self.line_of(self.section_start),
                format!(
                    "in the binary {} data, at byte offset {at}: {message}",
                    self.section
                ),
            )
        } else if self.binary_file {
            (self.line_of(at), format!("{message} (byte offset {at})"))
        } else {
            (self.line_of(at), message)
        };
        Error::MeshSyntax {
            path: self.path.to_path_buf(),
            line,
            message,
        }
    }

    pub(super) fn invalid(&self, message: String) -> Error {
        Error::Mesh {
            path: self.path.to_path_buf(),
            message,
        }
    }

    fn end_of_file(&self, what: &str) -> Error {
        self.syntax(
            self.data.len(),
            format!("unexpected end of file (truncated?): expected {what}"),
        )
    }

    // -- ASCII --------------------------------------------------------------

    fn skip_whitespace(&mut self) {
        while let Some(c) = self.data.get(self.pos) {
            if !c.is_ascii_whitespace() {
                break;
            }
            self.pos += 1;
        }
    }

    /// The next whitespace-separated token and its offset.
    pub(super) fn token(&mut self, what: &str) -> Result<(&'a [u8], usize)> {
        self.skip_whitespace();
        let start = self.pos;
        if start >= self.data.len() {
            return Err(self.end_of_file(what));
        }
        let len = self.data[start..]
            .iter()
            .position(|c| c.is_ascii_whitespace())
            .unwrap_or(self.data.len() - start);
        self.pos = start + len;
        Ok((&self.data[start..start + len], start))
    }

    /// An integer token.
    pub(super) fn ascii_int(&mut self, what: &str) -> Result<(i64, usize)> {
        let (tok, at) = self.token(what)?;
        match parse_int(tok) {
            Some(v) => Ok((v, at)),
            None => Err(self.syntax(at, format!("expected {what}, found '{}'", show(tok)))),
        }
    }

    /// The keyword `keyword` as the next token.
    pub(super) fn expect(&mut self, keyword: &str) -> Result<()> {
        let (tok, at) = self.token(keyword)?;
        if tok == keyword.as_bytes() {
            Ok(())
        } else {
            Err(self.syntax(at, format!("expected {keyword}, found '{}'", show(tok))))
        }
    }

    /// The integers of the next non-blank line into `out`; returns the
    /// line's offset.
    pub(super) fn int_line(&mut self, out: &mut Vec<i64>, what: &str) -> Result<usize> {
        self.skip_whitespace();
        let start = self.pos;
        if start >= self.data.len() {
            return Err(self.end_of_file(what));
        }
        out.clear();
        loop {
            while matches!(self.data.get(self.pos), Some(b' ' | b'\t' | b'\r')) {
                self.pos += 1;
            }
            match self.data.get(self.pos) {
                None => break,
                Some(b'\n') => {
                    self.pos += 1;
                    break;
                }
                Some(_) => {}
            }
            let at = self.pos;
            let len = self.data[at..]
                .iter()
                .position(|c| c.is_ascii_whitespace())
                .unwrap_or(self.data.len() - at);
            let tok = &self.data[at..at + len];
            self.pos = at + len;
            match parse_int(tok) {
                Some(v) => out.push(v),
                None => {
                    return Err(self.syntax(at, format!("expected {what}, found '{}'", show(tok))))
                }
            }
        }
        Ok(start)
    }

    /// A physical group name: `"..."` (or a bare word) up to the end of the
    /// line.
    pub(super) fn quoted_name(&mut self) -> Result<String> {
        while matches!(self.data.get(self.pos), Some(b' ' | b'\t')) {
            self.pos += 1;
        }
        if self.data.get(self.pos) != Some(&b'"') {
            let (tok, _) = self.token("a physical group name")?;
            return Ok(String::from_utf8_lossy(tok).into_owned());
        }
        let start = self.pos + 1;
        let rest = self.data.get(start..).unwrap_or(&[]);
        match rest.iter().position(|&c| c == b'"' || c == b'\n') {
            Some(len) if rest[len] == b'"' => {
                self.pos = start + len + 1;
                Ok(String::from_utf8_lossy(&rest[..len]).into_owned())
            }
            _ => Err(self.syntax(
                self.pos,
                "expected a physical group name in double quotes, found no closing quote on the line"
                    .into(),
            )),
        }
    }

    /// The next section header (`$Name`) and its offset, or `None` at the end
    /// of the file.
    pub(super) fn section_header(&mut self) -> Result<Option<(&'a [u8], usize)>> {
        self.skip_whitespace();
        if self.pos >= self.data.len() {
            return Ok(None);
        }
        let (tok, at) = self.token("a section header")?;
        if tok.first() != Some(&b'$') {
            return Err(self.syntax(
                at,
                format!(
                    "expected a section header such as $Nodes or $Elements, found '{}'",
                    show(tok)
                ),
            ));
        }
        Ok(Some((tok, at)))
    }

    /// Skips an unknown section `name` (header at `at`) up to its `$End` line.
    pub(super) fn skip_section(&mut self, name: &[u8], at: usize) -> Result<()> {
        let mut end = b"$End".to_vec();
        end.extend_from_slice(name.get(1..).unwrap_or(&[]));
        let rest = self.data.get(self.pos..).unwrap_or(&[]);
        match rest.windows(end.len()).position(|w| w == end.as_slice()) {
            Some(i) => {
                self.pos += i + end.len();
                Ok(())
            }
            None => Err(self.syntax(
                at,
                format!(
                    "section {} has no {} line (truncated file?)",
                    show(name),
                    show(&end)
                ),
            )),
        }
    }

    // -- binary ---------------------------------------------------------------

    /// In a binary file, consumes the end of the header line and switches to
    /// binary values for `section`; in an ASCII file does nothing.
    pub(super) fn begin_binary(&mut self, section: &'static str) -> Result<()> {
        if !self.binary_file {
            return Ok(());
        }
        while matches!(self.data.get(self.pos), Some(b' ' | b'\t' | b'\r')) {
            self.pos += 1;
        }
        match self.data.get(self.pos) {
            Some(b'\n') => self.pos += 1,
            Some(_) => {
                return Err(self.syntax(
                    self.pos,
                    format!("expected the end of the line before the binary {section} data"),
                ))
            }
            None => return Err(self.end_of_file(&format!("the binary {section} data"))),
        }
        self.binary = true;
        self.section = section;
        self.section_start = self.pos;
        Ok(())
    }

    pub(super) fn end_binary(&mut self) {
        self.binary = false;
    }

    /// The next `n` bytes of binary data.
    pub(super) fn bytes(&mut self, n: usize, what: &str) -> Result<&'a [u8]> {
        let at = self.pos;
        match at.checked_add(n).and_then(|end| self.data.get(at..end)) {
            Some(bytes) => {
                self.pos = at + n;
                Ok(bytes)
            }
            None => Err(self.syntax(
                at,
                format!(
                    "unexpected end of file (truncated?): expected {what} ({n} bytes), {} bytes left",
                    self.data.len().saturating_sub(at)
                ),
            )),
        }
    }

    fn array<const N: usize>(&mut self, what: &str) -> Result<[u8; N]> {
        let b = self.bytes(N, what)?;
        let mut a = [0u8; N];
        a.copy_from_slice(b);
        if self.big_endian {
            a.reverse();
        }
        Ok(a) // little-endian from here on
    }

    // -- values: binary or ASCII -----------------------------------------------

    /// An `int` (binary: 4 bytes).
    pub(super) fn int(&mut self, what: &str) -> Result<i64> {
        if self.binary {
            Ok(i32::from_le_bytes(self.array(what)?) as i64)
        } else {
            Ok(self.ascii_int(what)?.0)
        }
    }

    /// A `size_t` (binary: the `$MeshFormat` data size) or a non-negative
    /// integer.
    pub(super) fn size(&mut self, what: &str) -> Result<u64> {
        if self.binary {
            if self.size_t == 4 {
                Ok(u32::from_le_bytes(self.array(what)?) as u64)
            } else {
                Ok(u64::from_le_bytes(self.array(what)?))
            }
        } else {
            let (v, at) = self.ascii_int(what)?;
            u64::try_from(v).map_err(|_| {
                self.syntax(
                    at,
                    format!("expected {what} (a non-negative integer), found {v}"),
                )
            })
        }
    }

    /// A `double`.
    pub(super) fn float(&mut self, what: &str) -> Result<f64> {
        if self.binary {
            Ok(f64::from_le_bytes(self.array(what)?))
        } else {
            let (tok, at) = self.token(what)?;
            parse_float(tok)
                .ok_or_else(|| self.syntax(at, format!("expected {what}, found '{}'", show(tok))))
        }
    }

    /// A finite coordinate of node `tag` (the message is built only on error).
    pub(super) fn coordinate(&mut self, axis: &str, tag: u64) -> Result<f64> {
        let what = "a node coordinate";
        // where the value starts (ASCII: the token, not the whitespace before)
        let (value, at) = if self.binary {
            let at = self.pos;
            (f64::from_le_bytes(self.array(what)?), at)
        } else {
            let (tok, at) = self.token(what)?;
            match parse_float(tok) {
                Some(v) => (v, at),
                None => {
                    return Err(self.syntax(
                        at,
                        format!(
                            "expected the {axis} coordinate of node {tag}, found '{}'",
                            show(tok)
                        ),
                    ))
                }
            }
        };
        match crate::input::coordinate_fault(value) {
            Some(fault) => {
                Err(self.syntax(at, format!("the {axis} coordinate of node {tag} {fault}")))
            }
            None => Ok(value),
        }
    }

    /// A capacity to reserve for `count` items announced by the file, bounded
    /// by the file size so that a corrupt count cannot exhaust memory.
    pub(super) fn capacity(&self, count: u64) -> usize {
        usize::try_from(count)
            .unwrap_or(usize::MAX)
            .min(self.data.len() / 8)
    }
}

fn parse_int(tok: &[u8]) -> Option<i64> {
    let (negative, digits) = match tok.split_first()? {
        (b'-', rest) => (true, rest),
        (b'+', rest) => (false, rest),
        _ => (false, tok),
    };
    if digits.is_empty() {
        return None;
    }
    let mut v: i64 = 0;
    for &c in digits {
        if !c.is_ascii_digit() {
            return None;
        }
        v = v.checked_mul(10)?.checked_add((c - b'0') as i64)?;
    }
    Some(if negative { -v } else { v })
}

fn parse_float(tok: &[u8]) -> Option<f64> {
    std::str::from_utf8(tok).ok()?.parse().ok()
}

/// A token for an error message: lossy UTF-8, at most 40 characters.
pub(super) fn show(tok: &[u8]) -> String {
    let s = String::from_utf8_lossy(tok);
    match s.char_indices().nth(40) {
        Some((i, _)) => format!("{}...", &s[..i]),
        None => s.into_owned(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn integers() {
        assert_eq!(parse_int(b"-12"), Some(-12));
        assert_eq!(parse_int(b"+7"), Some(7));
        for bad in [&b""[..], b"-", b"1.0", b"1e3", b"99999999999999999999"] {
            assert_eq!(parse_int(bad), None);
        }
    }
}
