//! The README and docs/ stay true to the repository: the README's case
//! file is `examples/hertz/case.toml` (comments aside), and every relative
//! link of README.md and docs/*.md names a file that exists and, with a
//! `#fragment`, a heading of that file. (The README's Rust snippet is a
//! doc-test: `cargo test --doc ReadmeDoctests`.)

use std::path::{Path, PathBuf};

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// A TOML text's lines without comments (from a `#` outside a string) and
/// without blank lines, each trimmed.
fn without_comments(text: &str) -> Vec<String> {
    text.lines()
        .map(|line| {
            let mut quoted = false;
            let end = line
                .char_indices()
                .find(|&(_, c)| {
                    quoted ^= c == '"';
                    c == '#' && !quoted
                })
                .map_or(line.len(), |(i, _)| i);
            line[..end].trim().to_string()
        })
        .filter(|line| !line.is_empty())
        .collect()
}

/// The fenced blocks of a Markdown text in `language`, in order.
fn fenced_blocks(text: &str, language: &str) -> Vec<String> {
    let mut blocks = Vec::new();
    let mut current: Option<String> = None;
    for line in text.lines() {
        match current.as_mut() {
            None if line.trim_end() == format!("```{language}") => current = Some(String::new()),
            None => {}
            Some(_) if line.starts_with("```") => blocks.extend(current.take()),
            Some(block) => {
                block.push_str(line);
                block.push('\n');
            }
        }
    }
    blocks
}

#[test]
fn the_readme_case_is_the_hertz_example() {
    let readme = read(&repo().join("README.md"));
    let blocks = fenced_blocks(&readme, "toml");
    assert_eq!(blocks.len(), 1, "README.md: one TOML block, the Hertz case");
    let case = read(&repo().join("examples/hertz/case.toml"));
    assert_eq!(without_comments(&blocks[0]), without_comments(&case));
}

/// GitHub's anchor of a heading: lower case, letters, digits, `-` and `_`
/// kept, spaces to `-`, everything else dropped.
fn anchor(heading: &str) -> String {
    heading
        .trim()
        .to_lowercase()
        .chars()
        .filter_map(|c| match c {
            ' ' => Some('-'),
            c if c.is_alphanumeric() || c == '-' || c == '_' => Some(c),
            _ => None,
        })
        .collect()
}

/// The targets of the inline links `[text](target)` of a Markdown text,
/// outside fenced code blocks.
fn link_targets(text: &str) -> Vec<String> {
    let mut targets = Vec::new();
    let mut fenced = false;
    for line in text.lines() {
        if line.starts_with("```") {
            fenced = !fenced;
            continue;
        }
        if fenced {
            continue;
        }
        let mut rest = line;
        while let Some(i) = rest.find("](") {
            let after = &rest[i + 2..];
            let Some(end) = after.find(')') else { break };
            targets.push(after[..end].to_string());
            rest = &after[end..];
        }
    }
    targets
}

#[test]
fn relative_links_of_the_readme_and_docs_resolve() {
    let mut files = vec![repo().join("README.md")];
    for entry in std::fs::read_dir(repo().join("docs")).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "md") {
            files.push(path);
        }
    }
    let mut checked = 0;
    for file in &files {
        for target in link_targets(&read(file)) {
            if target.contains("://") || target.starts_with("mailto:") {
                continue;
            }
            let (path, fragment) = target.split_once('#').unwrap_or((&target, ""));
            let resolved = if path.is_empty() {
                file.clone()
            } else {
                file.parent().unwrap().join(path)
            };
            assert!(
                resolved.exists(),
                "{}: link to {target}: no such file",
                file.display()
            );
            if !fragment.is_empty() {
                let headings: Vec<String> = read(&resolved)
                    .lines()
                    .filter(|l| l.starts_with('#') && l.contains("# "))
                    .map(|l| anchor(l.trim_start_matches('#')))
                    .collect();
                assert!(
                    headings.iter().any(|h| h == fragment),
                    "{}: link to {target}: no heading #{fragment} in {}",
                    file.display(),
                    resolved.display()
                );
            }
            checked += 1;
        }
    }
    // the README alone links to docs/guide.md, case-file.md, results.md, …
    assert!(checked >= 20, "only {checked} links found");
}

#[test]
fn anchors_follow_github() {
    assert_eq!(anchor(" The case file"), "the-case-file");
    assert_eq!(
        anchor(" Distributed runs (`mpirun`)"),
        "distributed-runs-mpirun"
    );
}
