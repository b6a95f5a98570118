//! Size limits of the case file's values, so that a huge value is an error
//! that says where it is instead of memory or a message of megabytes: a
//! string or key (a name, a path) of at most [`MAX_STRING`] characters, an
//! array (an amplitude table) of at most [`MAX_ARRAY`] items.

use toml_edit::{ImDocument, Item, Value};

/// Characters of a string value or a key (names and paths).
pub const MAX_STRING: usize = 1024;
/// Items of an array (amplitude points).
pub const MAX_ARRAY: usize = 100_000;

/// The first value over a limit: its byte offset in the text and the
/// message.
pub(super) fn check(text: &str) -> Option<(usize, String)> {
    let doc = ImDocument::parse(text).ok()?;
    table(
        doc.as_table()
            .iter()
            .map(|(k, v)| (k, Some(v), None))
            .collect(),
        "",
    )
}

type Entry<'a> = (&'a str, Option<&'a Item>, Option<&'a Value>);

fn table<'a>(entries: Vec<Entry<'a>>, path: &str) -> Option<(usize, String)> {
    for (key, item, value) in entries {
        let path = if path.is_empty() {
            key.to_string()
        } else {
            format!("{path}.{key}")
        };
        let at = item
            .and_then(Item::span)
            .or_else(|| value.and_then(Value::span));
        if key.chars().count() > MAX_STRING {
            return Some((
                at.map_or(0, |s| s.start),
                format!(
                    "a key of {} characters ('{}'); keys and names have at most {MAX_STRING}",
                    key.chars().count(),
                    crate::input::shorten(key)
                ),
            ));
        }
        let found = match (item, value) {
            (Some(Item::Table(t)), _) => {
                table(t.iter().map(|(k, v)| (k, Some(v), None)).collect(), &path)
            }
            (Some(Item::ArrayOfTables(a)), _) => a.iter().enumerate().find_map(|(i, t)| {
                table(
                    t.iter().map(|(k, v)| (k, Some(v), None)).collect(),
                    &format!("{path}[{i}]"),
                )
            }),
            (Some(Item::Value(v)), _) | (None, Some(v)) => self::value(v, &path),
            _ => None,
        };
        if found.is_some() {
            return found;
        }
    }
    None
}

fn value(v: &Value, path: &str) -> Option<(usize, String)> {
    let at = v.span().map_or(0, |s| s.start);
    match v {
        Value::String(s) if s.value().chars().count() > MAX_STRING => Some((
            at,
            format!(
                "at key '{path}': a string of {} characters ('{}'); names and paths have at most {MAX_STRING}",
                s.value().chars().count(),
                crate::input::shorten(s.value())
            ),
        )),
        Value::Array(a) if a.len() > MAX_ARRAY => Some((
            at,
            format!(
                "at key '{path}': an array of {} items; at most {MAX_ARRAY} (an amplitude \
                 table that long is better resampled)",
                a.len()
            ),
        )),
        Value::Array(a) => a
            .iter()
            .enumerate()
            .find_map(|(i, v)| value(v, &format!("{path}[{i}]"))),
        Value::InlineTable(t) => table(t.iter().map(|(k, v)| (k, None, Some(v))).collect(), path),
        _ => None,
    }
}
