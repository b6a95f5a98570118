//! The guard of the crate's layout: imports point one way.
//!
//! The modules of `src/` form layers, in the order the method runs
//! (DESIGN.md, "Layers"):
//!
//! ```text
//! error → input → mesh, material → fem → assembly → contact → solve → problem → output → case → run → main
//! ```
//!
//! A file may use items of its own module and of modules to its left, never
//! of a module to its right nor of a peer in the same layer (`mesh` and
//! `material` know nothing of each other). Within a module, the files must
//! not import each other in a cycle. This test reads every `crate::…` and
//! `super::…` path of `src/` (in `use` lines and inline, doc comments
//! excepted; `#[cfg(test)]` modules included) and fails on any import
//! against that order, naming the file, the line and the path.
//!
//! Shown once, by hand: adding `use crate::run::RunOptions;` at the end of
//! `src/mesh/mod.rs` (its line 212) makes it fail with
//!
//! ```text
//! src/mesh/mod.rs:212: `crate::run::RunOptions`: mesh (layer 2) must not import run (layer 10)
//! import cycle among files: src/assembly/kernel.rs → src/fem/mod.rs → src/mesh/mod.rs → src/run.rs → src/case/mod.rs → src/assembly/kernel.rs
//! ```
//!
//! (the backward import also closes a cycle among files, reported as such).

mod common;
use common::rust_files;
use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The layers, left to right. Files directly in `src/` are modules of
/// their own (`problem.rs`, `run.rs`, …); `lib.rs` re-exports and may name
/// anything.
const LAYERS: &[&[&str]] = &[
    &["error"],
    &["input"],
    &["mesh", "material"],
    &["fem"],
    &["assembly"],
    &["contact"],
    &["solve"],
    &["problem"],
    &["output"],
    &["case"],
    &["run", "simulation"],
    &["main"],
];

fn layer_of(module: &str) -> Option<usize> {
    LAYERS.iter().position(|l| l.contains(&module))
}

/// The module path of a file: `src/contact/laws/mod.rs` → `[contact, laws]`.
fn module_path(src: &Path, file: &Path) -> Vec<String> {
    let rel = file.strip_prefix(src).unwrap();
    let mut parts: Vec<String> = rel
        .iter()
        .map(|p| p.to_string_lossy().trim_end_matches(".rs").to_string())
        .collect();
    if parts.last().is_some_and(|p| p == "mod" || p == "lib") {
        parts.pop();
    }
    parts
}

/// The code of a line without its comment (`//` outside a string is rare
/// enough in paths to ignore strings).
fn code_of(line: &str) -> &str {
    match line.find("//") {
        Some(i) => &line[..i],
        None => line,
    }
}

/// Expand a `use` tree `a::{b, c::{d, e}}` into its paths.
fn expand(tree: &str) -> Vec<String> {
    let tree = tree.trim();
    let Some(open) = tree.find('{') else {
        return vec![tree.split(" as ").next().unwrap().trim().to_string()];
    };
    let prefix = &tree[..open];
    let inner = &tree[open + 1..tree.rfind('}').unwrap()];
    let (mut depth, mut start, mut items) = (0, 0, Vec::new());
    for (i, c) in inner.char_indices() {
        match c {
            '{' => depth += 1,
            '}' => depth -= 1,
            ',' if depth == 0 => {
                items.push(&inner[start..i]);
                start = i + 1;
            }
            _ => {}
        }
    }
    items.push(&inner[start..]);
    items
        .into_iter()
        .filter(|s| !s.trim().is_empty())
        .flat_map(|s| expand(s).into_iter().map(move |p| format!("{prefix}{p}")))
        .collect()
}

/// The `crate::`/`super::` paths a file names, with their line numbers,
/// resolved to absolute module paths (`["contact", "laws", "GapGeometry"]`).
fn imports(module: &[String], text: &str) -> Vec<(usize, String, Vec<String>)> {
    let mut out = Vec::new();
    let lines: Vec<&str> = text.lines().collect();
    // inline `mod name {` blocks open at this line (their brace depth):
    // `super` inside one of them is the file's own module
    let (mut depth, mut inline_mods) = (0usize, Vec::<usize>::new());
    let mut i = 0;
    while i < lines.len() {
        let line = code_of(lines[i]);
        let trimmed = line.trim_start();
        let opens_mod = trimmed
            .trim_start_matches("pub ")
            .strip_prefix("mod ")
            .is_some_and(|rest| rest.trim_end().ends_with('{'));
        if opens_mod {
            inline_mods.push(depth);
        }
        depth += line.matches('{').count();
        depth = depth.saturating_sub(line.matches('}').count());
        while inline_mods.last().is_some_and(|&d| depth <= d) {
            inline_mods.pop();
        }
        let inner: Vec<String> = module
            .iter()
            .cloned()
            .chain((0..inline_mods.len()).map(|_| "{inline}".to_string()))
            .collect();
        let module = &inner[..];
        let number = i + 1;
        let statement = if (trimmed.starts_with("use ")
            || trimmed.starts_with("pub use ")
            || trimmed.starts_with("pub(crate) use "))
            && (trimmed.contains("crate::") || trimmed.contains("super::"))
        {
            // the whole statement, up to its `;`
            let mut s = String::from(line);
            while !s.contains(';') && i + 1 < lines.len() {
                i += 1;
                s.push_str(code_of(lines[i]));
            }
            let body = s.trim_start();
            let body = body[body.find("use ").unwrap() + 4..]
                .trim_end()
                .trim_end_matches(';');
            expand(body)
        } else {
            // inline paths
            inline_paths(line)
        };
        for path in statement {
            if let Some(resolved) = resolve(module, &path) {
                out.push((number, path, resolved));
            }
        }
        i += 1;
    }
    out
}

/// `crate::a::b` and `super::x` paths inside a line of code.
fn inline_paths(line: &str) -> Vec<String> {
    let mut paths = Vec::new();
    for start in ["crate::", "super::"] {
        let mut from = 0;
        while let Some(i) = line[from..].find(start) {
            let at = from + i;
            // not part of a longer identifier (`$crate::`, `my_super::`)
            let before = line[..at].chars().next_back();
            if before.is_some_and(|c| c.is_alphanumeric() || c == '_' || c == '$' || c == ':') {
                from = at + start.len();
                continue;
            }
            let end = line[at..]
                .find(|c: char| !(c.is_alphanumeric() || c == '_' || c == ':'))
                .map_or(line.len(), |e| at + e);
            paths.push(line[at..end].trim_end_matches(':').to_string());
            from = end;
        }
    }
    paths
}

/// An absolute module path for `path` seen from `module`.
fn resolve(module: &[String], path: &str) -> Option<Vec<String>> {
    let mut parts: Vec<&str> = path.split("::").filter(|p| !p.is_empty()).collect();
    let mut base: Vec<String> = match *parts.first()? {
        "crate" => {
            parts.remove(0);
            Vec::new()
        }
        "super" => {
            // `super` of `a/b.rs` (module a::b) is a; of `a/b/mod.rs` (a::b) is a too
            let mut base = module.to_vec();
            while parts.first() == Some(&"super") {
                parts.remove(0);
                base.pop()?;
            }
            if base.iter().any(|p| p == "{inline}") {
                base.retain(|p| p != "{inline}");
            }
            base
        }
        _ => return None,
    };
    base.extend(parts.into_iter().map(String::from));
    Some(base)
}

/// The file that defines the longest prefix of `path` that is a file.
fn file_of(src: &Path, path: &[String]) -> Option<PathBuf> {
    for len in (1..=path.len()).rev() {
        let dir: PathBuf = path[..len].iter().collect();
        for candidate in [
            src.join(&dir).with_extension("rs"),
            src.join(&dir).join("mod.rs"),
        ] {
            if candidate.is_file() {
                return Some(candidate);
            }
        }
    }
    None
}

/// The top-level module a resolved path lands in (`crate::Error` and
/// `crate::Result` are `error`'s re-exports).
fn top_module(path: &[String]) -> Option<String> {
    let first = path.first()?;
    Some(match first.as_str() {
        "Error" | "Result" => "error".to_string(),
        other => other.to_string(),
    })
}

#[test]
fn imports_point_one_way_and_files_form_no_cycle() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    files.sort();
    let mut violations = Vec::new();
    let mut graph: BTreeMap<PathBuf, BTreeSet<PathBuf>> = BTreeMap::new();
    for file in &files {
        let module = module_path(&src, file);
        let name = file
            .strip_prefix(src.parent().unwrap())
            .unwrap()
            .display()
            .to_string();
        let Some(own) = module.first().cloned() else {
            continue; // lib.rs: the crate root re-exports
        };
        let Some(own_layer) = layer_of(&own) else {
            violations.push(format!(
                "{name}: module `{own}` has no layer in tests/layering.rs"
            ));
            continue;
        };
        let text = std::fs::read_to_string(file).unwrap();
        for (line, path, resolved) in imports(&module, &text) {
            let Some(target) = top_module(&resolved) else {
                continue;
            };
            if target != own {
                match layer_of(&target) {
                    Some(layer) if layer < own_layer => {}
                    Some(layer) => violations.push(format!(
                        "{name}:{line}: `{path}`: {own} (layer {own_layer}) must not import {target} (layer {layer})"
                    )),
                    None => violations.push(format!(
                        "{name}:{line}: `{path}`: {target} has no layer in tests/layering.rs"
                    )),
                }
            }
            if let Some(dependency) = file_of(&src, &resolved) {
                if &dependency != file && !dependency.ends_with("lib.rs") {
                    graph.entry(file.clone()).or_default().insert(dependency);
                }
            }
        }
    }
    for cycle in cycles(&graph) {
        let names: Vec<String> = cycle
            .iter()
            .map(|p| {
                p.strip_prefix(src.parent().unwrap())
                    .unwrap()
                    .display()
                    .to_string()
            })
            .collect();
        violations.push(format!("import cycle among files: {}", names.join(" → ")));
    }
    assert!(
        violations.is_empty(),
        "imports against the layer order (DESIGN.md, \"Layers\"):\n{}",
        violations.join("\n")
    );
}

/// One cycle per strongly connected component of more than one file
/// (Tarjan), each as a closed path through the graph.
fn cycles(graph: &BTreeMap<PathBuf, BTreeSet<PathBuf>>) -> Vec<Vec<PathBuf>> {
    struct Tarjan<'a> {
        graph: &'a BTreeMap<PathBuf, BTreeSet<PathBuf>>,
        index: BTreeMap<&'a PathBuf, usize>,
        low: BTreeMap<&'a PathBuf, usize>,
        stack: Vec<&'a PathBuf>,
        on_stack: BTreeSet<&'a PathBuf>,
        components: Vec<Vec<&'a PathBuf>>,
    }
    impl<'a> Tarjan<'a> {
        fn visit(&mut self, v: &'a PathBuf) {
            let i = self.index.len();
            self.index.insert(v, i);
            self.low.insert(v, i);
            self.stack.push(v);
            self.on_stack.insert(v);
            for w in self.graph.get(v).into_iter().flatten() {
                if !self.index.contains_key(w) {
                    self.visit(w);
                    let low = self.low[v].min(self.low[w]);
                    self.low.insert(v, low);
                } else if self.on_stack.contains(w) {
                    let low = self.low[v].min(self.index[w]);
                    self.low.insert(v, low);
                }
            }
            if self.low[v] == self.index[v] {
                let mut component = Vec::new();
                while let Some(w) = self.stack.pop() {
                    self.on_stack.remove(w);
                    component.push(w);
                    if w == v {
                        break;
                    }
                }
                if component.len() > 1 {
                    self.components.push(component);
                }
            }
        }
    }
    let mut t = Tarjan {
        graph,
        index: BTreeMap::new(),
        low: BTreeMap::new(),
        stack: Vec::new(),
        on_stack: BTreeSet::new(),
        components: Vec::new(),
    };
    for v in graph.keys() {
        if !t.index.contains_key(v) {
            t.visit(v);
        }
    }
    t.components
        .into_iter()
        .map(|c| {
            // a closed path from the first file through the component
            let members: BTreeSet<&PathBuf> = c.iter().copied().collect();
            let start = *members.iter().next().unwrap();
            let mut path = vec![start.clone()];
            let mut seen = BTreeSet::from([start]);
            let mut here = start;
            loop {
                let next = graph[here]
                    .iter()
                    .find(|w| members.contains(w) && (*w == start || !seen.contains(w)));
                match next {
                    Some(w) if w == start => {
                        path.push(w.clone());
                        break;
                    }
                    Some(w) => {
                        path.push(w.clone());
                        seen.insert(w);
                        here = w;
                    }
                    None => {
                        // a dead end inside the component: list its members
                        path = c.iter().map(|p| (*p).clone()).collect();
                        break;
                    }
                }
            }
            path
        })
        .collect()
}

#[test]
fn use_trees_expand() {
    assert_eq!(
        expand("crate::contact::{friction::{A, B as C}, laws::D}"),
        vec![
            "crate::contact::friction::A",
            "crate::contact::friction::B",
            "crate::contact::laws::D"
        ]
    );
    let here: Vec<String> = vec!["solve".into(), "newton".into()];
    assert_eq!(
        resolve(&here, "super::linear::SparseLdlt").unwrap(),
        vec!["solve", "linear", "SparseLdlt"]
    );
    assert_eq!(
        inline_paths("let x = crate::assembly::scatter(a, $crate::no, super::lu::Lu::new());"),
        vec!["crate::assembly::scatter", "super::lu::Lu::new"]
    );
}
