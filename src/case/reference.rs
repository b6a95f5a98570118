//! The case file's reference, generated from the schema types of
//! [`super::schema`] (their serde attributes and doc comments, read by
//! `schemars`): a JSON Schema (draft 7, which editors read: taplo, Even
//! Better TOML) shipped as `docs/case-file.schema.json`, and the key
//! reference `docs/case-file.md` written from that schema. The test
//! `tests/case_reference.rs` regenerates both and fails when they differ
//! from the committed files, so the reference cannot drift from the code.

use super::schema::CaseFile;
use schemars::generate::SchemaSettings;
use serde_json::Value;

/// The case file's JSON Schema (draft 7): every table and key, with the
/// keys' descriptions (their doc comments), types, allowed values and
/// defaults; an optional key is one not `required`.
pub fn json_schema() -> Value {
    let settings = SchemaSettings::draft07().with(|s| s.inline_subschemas = true);
    let mut schema = settings
        .into_generator()
        .into_root_schema_for::<CaseFile>()
        .to_value();
    schema["title"] = "signorini case file".into();
    plain_descriptions(&mut schema);
    without_null(&mut schema);
    for (path, value) in code_defaults() {
        if let Some(key) = key_schema(&mut schema, path) {
            key["default"] = value;
        }
    }
    schema
}

/// The defaults of optional keys that the code applies (`None` → a value),
/// read from the code's own defaults where it has them as values
/// ([`crate::solve::settings::SolverSettings::default`], the budgets'
/// limits), so that the schema states what a run does.
fn code_defaults() -> Vec<(&'static str, Value)> {
    let solver = crate::solve::settings::SolverSettings::default();
    // the enums' names as the case file writes them (`rename_all = "lowercase"`)
    let name = |debug: String| Value::from(debug.to_lowercase());
    vec![
        (
            "mesh.max_generated_ids",
            crate::input::MAX_GENERATED_IDS.into(),
        ),
        (
            "contact.method",
            name(format!("{:?}", super::schema::ContactMethod::default())),
        ),
        ("contact.friction_coefficient", 0.0.into()),
        ("step.max_increments", super::budget::MAX_INCREMENTS.into()),
        ("solver.max_iterations", solver.max_iterations.into()),
        (
            "solver.residual_tolerance",
            solver.residual_tolerance.into(),
        ),
        (
            "solver.displacement_tolerance",
            solver.displacement_tolerance.into(),
        ),
        ("solver.line_search", solver.line_search.into()),
        ("solver.max_cuts", solver.max_cuts.into()),
        ("solver.growth_factor", solver.growth_factor.into()),
        ("solver.easy_iterations", solver.easy_iterations.into()),
        (
            "solver.nonsymmetric",
            name(format!("{:?}", solver.nonsymmetric)),
        ),
        ("solver.linear", name(format!("{:?}", solver.linear))),
        ("solver.predictor", name(format!("{:?}", solver.predictor))),
        ("solver.strategy", name(format!("{:?}", solver.strategy))),
        ("output.folder", "results".into()),
        ("output.every", 1.into()),
        ("output.max_bytes", super::budget::MAX_OUTPUT_BYTES.into()),
        ("output.compress", true.into()),
    ]
}

/// The schema of the key at `path` (`solver.max_iterations`,
/// `contact.method`: through arrays of tables to their items).
fn key_schema<'a>(schema: &'a mut Value, path: &str) -> Option<&'a mut Value> {
    path.split('.').try_fold(schema, |table, key| {
        let table = match table.get("items") {
            Some(_) => table.get_mut("items")?,
            None => table,
        };
        table.get_mut("properties")?.get_mut(key)
    })
}

/// Every `description` (and `title`) of `value` without Rust's intra-doc
/// links: `` [`super::budget::MAX_INCREMENTS`] `` → `` `MAX_INCREMENTS` ``,
/// its lines joined.
fn plain_descriptions(value: &mut Value) {
    match value {
        Value::Object(map) => {
            for (key, v) in map.iter_mut() {
                match v {
                    Value::String(text) if key == "description" || key == "title" => {
                        *text = plain_doc(text)
                    }
                    _ => plain_descriptions(v),
                }
            }
        }
        Value::Array(items) => items.iter_mut().for_each(plain_descriptions),
        _ => {}
    }
}

/// `value` without the `null` that schemars allows for an `Option`: TOML
/// has no null, an optional key is one left out (`"type": ["number",
/// "null"]` → `"type": "number"`; an `anyOf` with `{"type": "null"}` →
/// its other alternative).
fn without_null(value: &mut Value) {
    match value {
        Value::Object(map) => {
            if map.get("default") == Some(&Value::Null) {
                map.remove("default");
            }
            if let Some(Value::Array(values)) = map.get_mut("enum") {
                values.retain(|v| !v.is_null());
            }
            if let Some(Value::Array(types)) = map.get_mut("type") {
                types.retain(|t| t != "null");
                if types.len() == 1 {
                    let only = types.remove(0);
                    map.insert("type".into(), only);
                }
            }
            if let Some(Value::Array(options)) = map.get_mut("anyOf") {
                options.retain(|o| o.get("type").is_none_or(|t| t != "null"));
                if let [Value::Object(only)] = options.as_slice() {
                    let only = only.clone();
                    map.remove("anyOf");
                    for (k, v) in only {
                        map.entry(k).or_insert(v);
                    }
                }
            }
            map.values_mut().for_each(without_null);
        }
        Value::Array(items) => items.iter_mut().for_each(without_null),
        _ => {}
    }
}

/// A doc comment as one line of plain text (see [`plain_descriptions`]).
fn plain_doc(text: &str) -> String {
    let mut out = String::new();
    let mut rest = text;
    while let Some(start) = rest.find("[`") {
        let Some(end) = rest[start..].find("`]") else {
            break;
        };
        out.push_str(&rest[..start]);
        let path = &rest[start + 2..start + end];
        out.push('`');
        out.push_str(path.rsplit("::").next().unwrap_or(path));
        out.push('`');
        rest = &rest[start + end + 2..];
    }
    out.push_str(rest);
    out.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// The key reference (`docs/case-file.md`) of the JSON Schema `schema`
/// ([`json_schema`]): a section per table (`[mesh]`, `[[material]]`, …,
/// one per model or shape of a tagged table), a row per key with its
/// allowed values, its default and its meaning.
pub fn key_reference(schema: &Value) -> String {
    let mut out = String::from(HEADER);
    let mut sections = Vec::new();
    table(schema, "", &mut sections);
    for section in sections {
        out.push_str(&section);
    }
    out
}

const HEADER: &str = "# Case file keys\n\n\
Every key of a case file: its values, its default and its meaning. \
Generated, with the JSON Schema `docs/case-file.schema.json`, from the \
schema types of `src/case/schema.rs` (their doc comments and serde \
attributes) and the code's defaults; do not edit by hand: \
`SIGNORINI_WRITE_DOCS=1 cargo test --release --test case_reference` \
rewrites both, and that test fails while they differ from the code. \
A key is required where its default says so; an optional key without a \
default in the column has the one its meaning states, or none. \
Tables are in alphabetical order, as are their keys. Units are the \
user's, consistent throughout (e.g. mm, N, MPa).\n";

/// The sections of the table `schema` at `path` (`""` the whole file,
/// `solver`, `output.history`) and of its sub-tables, in `out`.
fn table(schema: &Value, path: &str, out: &mut Vec<String>) {
    let (header, item) = match schema.get("items") {
        Some(items) => (format!("[[{path}]]"), items),
        None if path.is_empty() => ("top level".to_string(), schema),
        None => (format!("[{path}]"), schema),
    };
    let mut text = if path.is_empty() {
        format!("\n## The {header}\n\n")
    } else {
        format!("\n## `{header}`\n\n")
    };
    if let Some(d) = schema.get("description").and_then(Value::as_str) {
        text.push_str(&format!("{d}\n\n"));
    }
    let mut subtables = Vec::new();
    text.push_str(&rows(item, path, &mut subtables));
    // a tagged table: the keys of each model or shape
    for variant in item
        .get("oneOf")
        .and_then(Value::as_array)
        .into_iter()
        .flatten()
    {
        let tag = variant["properties"]
            .as_object()
            .and_then(|p| p.iter().find_map(|(k, v)| Some((k, v.get("const")?))));
        if let Some((key, value)) = tag {
            text.push_str(&format!("\n### `{header}` with `{key} = {value}`\n\n"));
            if let Some(d) = variant.get("description").and_then(Value::as_str) {
                text.push_str(&format!("{d}\n\n"));
            }
            text.push_str(&rows(variant, path, &mut subtables));
        }
    }
    out.push(text);
    for (key, sub) in subtables {
        table(sub, &key, out);
    }
}

/// The rows of the keys of the object `schema` (those that are tables of
/// their own go to `subtables`, with their path).
fn rows<'a>(schema: &'a Value, path: &str, subtables: &mut Vec<(String, &'a Value)>) -> String {
    let required: Vec<&str> = schema["required"]
        .as_array()
        .map(|r| r.iter().filter_map(Value::as_str).collect())
        .unwrap_or_default();
    let mut text = String::from("| key | value | default | meaning |\n|---|---|---|---|\n");
    for (key, sub) in schema["properties"].as_object().into_iter().flatten() {
        let full = if path.is_empty() {
            key.clone()
        } else {
            format!("{path}.{key}")
        };
        let is_table =
            |s: &Value| s.get("properties").is_some() && s.get("type") == Some(&"object".into());
        if is_table(sub) || sub.get("items").is_some_and(is_table) {
            subtables.push((full, sub));
            continue;
        }
        let default = match (sub.get("default"), required.contains(&key.as_str())) {
            (Some(d), _) => format!("`{}`", toml_value(d)),
            (None, true) => "required".into(),
            (None, false) => String::new(),
        };
        let meaning = sub.get("description").and_then(Value::as_str).unwrap_or("");
        text.push_str(&format!(
            "| `{key}` | {} | {default} | {} |\n",
            allowed(sub),
            meaning.replace('|', "\\|")
        ));
    }
    text
}

/// A JSON value as TOML writes it.
fn toml_value(v: &Value) -> String {
    match v {
        Value::Array(items) => {
            let items: Vec<String> = items.iter().map(toml_value).collect();
            format!("[{}]", items.join(", "))
        }
        other => other.to_string(),
    }
}

/// The values a key takes, in words: `number`, `whole number ≥ 0`,
/// `"a"`, `"b"` or `"c"`, `[x, y, z]`, ….
fn allowed(s: &Value) -> String {
    if let Some(values) = s.get("enum").and_then(Value::as_array) {
        let values: Vec<String> = values.iter().map(|v| format!("`{v}`")).collect();
        return values.join(", ");
    }
    if let Some(c) = s.get("const") {
        return format!("`{c}`");
    }
    for alternatives in ["oneOf", "anyOf"] {
        if let Some(options) = s.get(alternatives).and_then(Value::as_array) {
            let options: Vec<String> = options.iter().map(allowed).collect();
            // the values of an enum, some with descriptions: one list
            let joint = if options.iter().all(|o| o.starts_with('`')) {
                ", "
            } else {
                " or "
            };
            return options.join(joint);
        }
    }
    let at_least = |s: &Value| match s.get("minimum").and_then(Value::as_f64) {
        Some(m) => format!(" ≥ {m}"),
        None => String::new(),
    };
    match s.get("type").and_then(Value::as_str) {
        Some("number") => "number".into(),
        Some("integer") => format!("whole number{}", at_least(s)),
        Some("string") => "string".into(),
        Some("boolean") => "`true` or `false`".into(),
        Some("array") => {
            let items = &s["items"];
            let n = s.get("minItems").filter(|n| s.get("maxItems") == Some(n));
            match n.and_then(Value::as_u64) {
                Some(3) if items["type"] == "number" => "`[x, y, z]`".into(),
                Some(n) => format!("array of {n} × {}", allowed(items)),
                None => format!("array of {}", allowed(items)),
            }
        }
        Some("object") => match s.get("additionalProperties") {
            Some(v) if v.is_object() => format!("table of `name = {}`", allowed(v)),
            _ => "table".into(),
        },
        _ => "any".into(),
    }
}
