//! Where a key path (`contact[0].primary`, `output.name`, `step[1]`) is
//! written in a case file, so that an error found after parsing (a name
//! that refers to nothing, a value out of range) names its line as a
//! parse error does.

use toml_edit::{ImDocument, TableLike};

/// The key path a message starts with (`contact[0].obstacle` of
/// `contact[0].obstacle: no [[obstacle]] named …`), possibly empty.
pub(super) fn leading_path(message: &str) -> &str {
    let end = message
        .find(|c: char| !(c.is_ascii_alphanumeric() || matches!(c, '_' | '.' | '[' | ']' | '-')))
        .unwrap_or(message.len());
    message[..end].trim_end_matches('.')
}

/// The byte offset in `text` where `path` is written: the last key of the
/// path that the text has (a key absent from the text, such as a missing
/// optional one, gives the line of its table), `None` when not even the
/// first key is there.
pub(super) fn offset_of_path(text: &str, path: &str) -> Option<usize> {
    let document = ImDocument::parse(text).ok()?;
    let mut table: &dyn TableLike = document.as_table();
    let mut offset = None;
    for segment in path.split('.') {
        let (name, index) = match segment.split_once('[') {
            Some((name, rest)) => (name, rest.strip_suffix(']')?.parse::<usize>().ok()),
            None => (segment, None),
        };
        let Some((key, item)) = table.get_key_value(name) else {
            break;
        };
        offset = key.span().map(|s| s.start).or(offset);
        match (index, item) {
            (Some(i), toml_edit::Item::ArrayOfTables(tables)) => {
                let Some(t) = tables.get(i) else { break };
                offset = t.span().map(|s| s.start).or(offset);
                table = t;
            }
            (None, item) => match item.as_table_like() {
                Some(t) => table = t,
                None => break,
            },
            _ => break,
        }
    }
    offset
}

#[cfg(test)]
mod tests {
    use super::*;

    const TEXT: &str = "[mesh]\nfile = \"a.msh\"\n\n[[contact]]\nname = \"a\"\n\n[[contact]]\nname = \"b\"\nobstacle = \"x\"\n\n[output]\nname = \"n\"\n";

    fn line(path: &str) -> Option<usize> {
        offset_of_path(TEXT, path).map(|o| TEXT[..o].matches('\n').count() + 1)
    }

    #[test]
    fn key_paths_find_their_lines() {
        assert_eq!(
            leading_path("contact[1].obstacle: no [[obstacle]] named 'x'"),
            "contact[1].obstacle"
        );
        assert_eq!(leading_path("output.name = 'n': it names"), "output.name");
        assert_eq!(
            leading_path("step[0].end_time = 2 must"),
            "step[0].end_time"
        );
        assert_eq!(line("contact[1].obstacle"), Some(9));
        assert_eq!(line("contact[1]"), Some(7));
        // a key the table lacks: the table's header
        assert_eq!(line("contact[0].obstacle"), Some(4));
        assert_eq!(line("output.name"), Some(12));
        assert_eq!(line("mesh.file"), Some(2));
        assert_eq!(line("solver.linear"), None);
        assert_eq!(line(""), None);
    }
}
