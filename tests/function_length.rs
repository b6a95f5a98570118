//! The guard of function length: every function of `src/` longer than
//! [`LIMIT`] lines (outside `#[cfg(test)]` modules) is listed, with the
//! reason it stays whole, in DESIGN.md's "Long functions" table, and every
//! function that table lists is still that long (issue 32: "the list of
//! functions over 100 lines in `src/`, with a reason for each").
//!
//! A function is counted from its `fn` line to the line of its closing
//! brace; braces inside string and character literals and after `//` are
//! not counted. A new long function fails this test, naming the file, the
//! line and the length: split it, or add it to the table with its reason.

mod common;
use common::rust_files;
use std::collections::BTreeSet;
use std::path::Path;

/// Functions longer than this many lines must be listed.
const LIMIT: usize = 100;

/// `line` without string and character literals and without a `//`
/// comment, so that its braces are the code's.
fn code_of(line: &str) -> String {
    let chars: Vec<char> = line.chars().collect();
    let mut out = String::new();
    let mut i = 0;
    while i < chars.len() {
        match chars[i] {
            '/' if chars.get(i + 1) == Some(&'/') => break,
            '"' => {
                i += 1;
                while i < chars.len() && chars[i] != '"' {
                    i += if chars[i] == '\\' { 2 } else { 1 };
                }
                out.push_str("\"\"");
            }
            // a character literal ('{', '\n'); a lifetime ('a) has no closing quote
            '\'' if chars.get(i + 2) == Some(&'\'') && chars.get(i + 1) != Some(&'\\') => {
                i += 2;
                out.push_str("''");
            }
            '\'' if chars.get(i + 1) == Some(&'\\') && chars.get(i + 3) == Some(&'\'') => {
                i += 3;
                out.push_str("''");
            }
            c => out.push(c),
        }
        i += 1;
    }
    out
}

/// The name of the function a line declares (`fn name`, with any of
/// `pub`, `pub(crate)`, `const`, `unsafe`, `extern "C"` before it).
fn declared(line: &str) -> Option<&str> {
    let at = line.find("fn ")?;
    let before = line[..at].trim();
    let qualifiers = before.split_whitespace().all(|w| {
        w == "pub"
            || w.starts_with("pub(")
            || ["const", "async", "unsafe", "extern", "\"C\""].contains(&w)
    });
    if !qualifiers {
        return None;
    }
    let rest = &line[at + 3..];
    let end = rest
        .find(|c: char| !(c.is_alphanumeric() || c == '_'))
        .unwrap_or(rest.len());
    (end > 0).then(|| &rest[..end])
}

/// `(file, name, first line, length)` of every function of `src/` longer
/// than [`LIMIT`] lines, outside `#[cfg(test)]` modules.
fn long_functions(root: &Path) -> Vec<(String, String, usize, usize)> {
    let mut files = Vec::new();
    rust_files(&root.join("src"), &mut files);
    let mut out = Vec::new();
    for path in files {
        let text = std::fs::read_to_string(&path).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        let end = (lines.iter())
            .position(|l| l.starts_with("#[cfg(test)]"))
            .unwrap_or(lines.len());
        let file = path.strip_prefix(root).unwrap().display().to_string();
        let mut i = 0;
        while i < end {
            let Some(name) = declared(lines[i]) else {
                i += 1;
                continue;
            };
            let (mut depth, mut opened, mut j) = (0i64, false, i);
            while j < end {
                let code = code_of(lines[j]);
                for c in code.chars() {
                    match c {
                        '{' => (depth, opened) = (depth + 1, true),
                        '}' => depth -= 1,
                        _ => {}
                    }
                }
                if (opened && depth == 0) || (!opened && code.trim_end().ends_with(';')) {
                    break;
                }
                j += 1;
            }
            let length = j + 1 - i;
            if opened && length > LIMIT {
                out.push((file.clone(), name.to_string(), i + 1, length));
                i = j + 1;
            } else {
                i += 1;
            }
        }
    }
    out
}

/// `(file, name)` of every row of DESIGN.md's "Long functions" table
/// (`| file | function | reason |`).
fn listed(root: &Path) -> BTreeSet<(String, String)> {
    let design = std::fs::read_to_string(root.join("DESIGN.md")).unwrap();
    let section = design
        .split("\n## Long functions\n")
        .nth(1)
        .expect("DESIGN.md has a section \"## Long functions\"");
    let section = section.split("\n## ").next().unwrap();
    section
        .lines()
        .filter_map(|l| {
            let cells: Vec<&str> = l.split('|').map(str::trim).collect();
            let code = |c: &str| c.trim_matches('`').to_string();
            (cells.len() >= 4 && cells[1].starts_with("`src/"))
                .then(|| (code(cells[1]), code(cells[2])))
        })
        .collect()
}

#[test]
fn every_long_function_is_listed_with_its_reason() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let long = long_functions(root);
    let found: BTreeSet<(String, String)> = (long.iter())
        .map(|(f, n, ..)| (f.clone(), n.clone()))
        .collect();
    let listed = listed(root);
    let unlisted: Vec<String> = (long.iter())
        .filter(|(f, n, ..)| !listed.contains(&(f.clone(), n.clone())))
        .map(|(f, n, line, length)| format!("{f}:{line}: `{n}` has {length} lines"))
        .collect();
    let stale: Vec<String> = (listed.difference(&found))
        .map(|(f, n)| format!("{f}: `{n}`"))
        .collect();
    assert!(
        unlisted.is_empty() && stale.is_empty(),
        "functions over {LIMIT} lines not in DESIGN.md's \"Long functions\" table (split \
         them, or list them with the reason they stay whole):\n{}\nlisted but no longer over \
         {LIMIT} lines (remove their rows):\n{}",
        unlisted.join("\n"),
        stale.join("\n")
    );
}

/// The counter itself, on a function of known length: a brace in a string
/// and in a character literal, a lifetime and a comment do not count.
#[test]
fn a_function_is_counted_from_fn_to_its_closing_brace() {
    let source = [
        "pub(crate) fn sample<'a>(x: &'a str) -> usize { // {",
        "    let open = \"{{\";",
        "    let brace = '}';",
        "    x.len() + open.len()",
        "}",
        "fn next() {}",
    ];
    let (mut depth, mut closed_at) = (0, None);
    for (i, line) in source.iter().enumerate() {
        for c in code_of(line).chars() {
            match c {
                '{' => depth += 1,
                '}' => depth -= 1,
                _ => {}
            }
        }
        if depth == 0 && closed_at.is_none() {
            closed_at = Some(i);
        }
    }
    assert_eq!(closed_at, Some(4));
    assert_eq!(declared(source[0]), Some("sample"));
    assert_eq!(declared(source[5]), Some("next"));
    assert_eq!(declared("    // a fn in prose"), None);
    assert_eq!(declared("    let f = |x| x; // fn"), None);
}
