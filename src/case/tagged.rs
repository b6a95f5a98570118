//! Error messages of the tagged tables, `[[material]]` (tag `model`) and
//! `[[obstacle]]` (tag `shape`).
//!
//! serde reads a tagged table through a buffer, so an error inside it knows
//! neither the key it is about nor its line: only `material[0]`. This module
//! finds the key again in the text and rewrites the message:
//! - an unknown key is one that does not apply to the chosen model or shape
//!   (`material[0].alpha does not apply to model 'neo_hookean'`), with the
//!   nearest key of that model if one is near ("did you mean");
//! - a missing key is required by it;
//! - any other error (a string for a number) is the one a single key gives
//!   alone with the tag, found by deserializing each key so.

use super::schema::{MaterialModel, ObstacleShape};
use crate::error::suggest;
use serde::de::DeserializeOwned;
use std::ops::Range;
use toml_edit::{ImDocument, Item};

/// The tagged tables: (array name, tag key, what the tag chooses).
const TAGGED: [(&str, &str, &str); 2] = [
    ("material", "model", "model"),
    ("obstacle", "shape", "shape"),
];

/// A key of one table in the text: its name, the span of the key and the
/// raw text of its value.
struct KeyText<'a> {
    name: &'a str,
    key: Range<usize>,
    value: &'a str,
}

/// `name[index]` → (name, index).
fn split_path(path: &str) -> Option<(&str, usize)> {
    let (name, rest) = path.split_once('[')?;
    let index = rest.strip_suffix(']')?.parse().ok()?;
    Some((name, index))
}

/// The keys of table `index` of the array of tables `array`, with the
/// span of the table's header.
fn table_keys<'a>(
    doc: &ImDocument<&'a str>,
    text: &'a str,
    array: &str,
    index: usize,
) -> Option<(Option<Range<usize>>, Vec<KeyText<'a>>)> {
    let table = match doc.get(array)? {
        Item::ArrayOfTables(tables) => tables.get(index)?,
        _ => return None,
    };
    let keys = table
        .iter()
        .filter_map(|(name, item)| {
            let key = table.key(name)?.span()?;
            let value = text.get(item.span()?)?;
            let name = text.get(key.clone())?;
            Some(KeyText { name, key, value })
        })
        .collect();
    Some((table.span(), keys))
}

/// The error message of `snippet` deserialized as `T`, if any.
fn message_of<T: DeserializeOwned>(snippet: &str) -> Option<String> {
    toml::from_str::<T>(snippet)
        .err()
        .map(|e| e.message().to_string())
}

/// A better message (and the byte offset it is about) for the serde error
/// `message` at key path `path`, if `path` is a tagged table.
pub(super) fn refine(text: &str, path: &str, message: &str) -> Option<(usize, String)> {
    let (array, index) = split_path(path)?;
    let &(_, tag, what) = TAGGED.iter().find(|(a, _, _)| *a == array)?;
    let doc = ImDocument::parse(text).ok()?;
    let (header, keys) = table_keys(&doc, text, array, index)?;
    let header = header.map(|h| h.start).unwrap_or(0);
    let tag_value = keys
        .iter()
        .find(|k| k.name == tag)
        .map(|k| k.value.trim_matches(|c| c == '"' || c == '\''));
    // the model or shape as the case file writes it
    let chosen = |v: &str| format!("'{v}'");
    let quoted = |m: &str, prefix: &str| {
        m.strip_prefix(prefix)
            .and_then(|r| r.split('`').next())
            .map(str::to_string)
    };
    if let Some(key) = quoted(message, "unknown field `") {
        let at = keys.iter().find(|k| k.name == key).map(|k| k.key.start);
        let chosen = chosen(tag_value.unwrap_or("?"));
        let takes = message
            .split_once("expected ")
            .map(|(_, e)| format!(" ({what} {chosen} takes {e})"))
            .unwrap_or_default();
        return Some((
            at.unwrap_or(header),
            format!(
                "{path}.{key} does not apply to {what} {chosen}; remove it, or check its spelling{}{takes}",
                suggest::hint(&key, &suggest::expected_words(message)),
            ),
        ));
    }
    let tag_line = keys.iter().find(|k| k.name == tag);
    // the error of the tag's variant alone, with `extra` (a key and value)
    let variant_error = |extra: &str| {
        let snippet = format!("{tag} = {}\n{extra}", tag_line.map_or("\"\"", |t| t.value));
        if array == "material" {
            message_of::<MaterialModel>(&snippet)
        } else {
            message_of::<ObstacleShape>(&snippet)
        }
    };
    if let Some(key) = quoted(message, "missing field `") {
        // the variant's keys: those it expects instead of an unknown one
        let of_variant =
            variant_error("__unknown__ = 0\n").is_some_and(|m| m.contains(&format!("`{key}`")));
        let text = match tag_value {
            Some(v) if of_variant => format!("{path}.{key} is required for {what} {}", chosen(v)),
            _ if key == tag => format!("{path}.{key} is required: it chooses the {what}"),
            _ => format!("{path}.{key} is required"),
        };
        return Some((header, text));
    }
    // another error: the tag's own (an unknown model), or the one a key
    // gives alone with the tag
    let tag_line = tag_line?;
    if variant_error("").as_deref() == Some(message) {
        return Some((
            tag_line.key.start,
            format!(
                "at key '{path}.{tag}': {message}{}",
                suggest::serde_hint(message)
            ),
        ));
    }
    keys.iter()
        .filter(|k| k.name != tag)
        .find(|k| variant_error(&format!("{} = {}\n", k.name, k.value)).as_deref() == Some(message))
        .map(|k| {
            (
                k.key.start,
                format!("at key '{path}.{}': {message}", k.name),
            )
        })
}
