//! The case file's reference cannot drift (issue 30, item 3): the JSON
//! Schema generated from the schema types and the key reference generated
//! from it equal the committed `docs/case-file.schema.json` and
//! `docs/case-file.md`.

use std::path::Path;

/// The command that rewrites both files.
const REGENERATE: &str = "SIGNORINI_WRITE_DOCS=1 cargo test --release --test case_reference";

/// `expected` equals the committed file `docs/<name>`, or (with
/// `SIGNORINI_WRITE_DOCS=1`) is written there.
fn compare(name: &str, expected: &str) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("docs")
        .join(name);
    if std::env::var_os("SIGNORINI_WRITE_DOCS").is_some() {
        std::fs::write(&path, expected).unwrap();
        return;
    }
    let committed = std::fs::read_to_string(&path).unwrap_or_default();
    if committed != expected {
        let line = committed
            .lines()
            .zip(expected.lines())
            .position(|(a, b)| a != b)
            .unwrap_or(committed.lines().count().min(expected.lines().count()));
        panic!(
            "docs/{name} differs from the one generated from src/case/schema.rs \
             (first at line {}); regenerate it with\n    {REGENERATE}",
            line + 1
        );
    }
}

#[test]
fn the_committed_schema_and_key_reference_are_generated() {
    let schema = signorini::case::reference::json_schema();
    let json = serde_json::to_string_pretty(&schema).unwrap() + "\n";
    compare("case-file.schema.json", &json);
    compare(
        "case-file.md",
        &signorini::case::reference::key_reference(&schema),
    );
}
