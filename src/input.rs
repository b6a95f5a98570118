//! The user's files read with bounded memory, and long values shortened
//! before a message echoes them.
//!
//! A path to an endless file (`/dev/zero`, a FIFO) or a huge file would
//! otherwise be read until memory runs out: only regular files are read,
//! and only up to a limit per kind of file, checked against the length the
//! file system announces before anything is allocated.

use crate::{Error, Result};
use std::io::Read;
use std::path::Path;

/// Largest case file read: 4 MiB (an amplitude table of 100 000 points is
/// about 3 MB of TOML; parsing costs some 50 bytes of memory per byte).
pub const MAX_CASE_FILE: u64 = 4 << 20;
/// Largest mesh file read: 16 GiB.
pub const MAX_MESH_FILE: u64 = 16 << 30;
/// Largest STL file read: 4 GiB (80 million triangles).
pub const MAX_STL_FILE: u64 = 4 << 30;

fn refuse(action: &'static str, path: &Path, message: String) -> Error {
    Error::io(
        action,
        path,
        std::io::Error::new(std::io::ErrorKind::InvalidInput, message),
    )
}

/// The bytes of the regular file `path`, at most `limit` of them; `action`
/// (`"read mesh"`) is what the error messages say could not be done.
pub fn read_bounded(path: &Path, action: &'static str, limit: u64) -> Result<Vec<u8>> {
    // the metadata first: opening a FIFO would wait for a writer
    let meta = std::fs::metadata(path).map_err(|e| Error::io(action, path, e))?;
    if !meta.is_file() {
        return Err(refuse(
            action,
            path,
            "not a regular file (a folder, a device or a pipe); give the path of a file".into(),
        ));
    }
    let too_big = |len: u64| {
        refuse(
            action,
            path,
            format!("the file has {len} bytes, more than the limit of {limit} bytes"),
        )
    };
    if meta.len() > limit {
        return Err(too_big(meta.len()));
    }
    let file = std::fs::File::open(path).map_err(|e| Error::io(action, path, e))?;
    let mut data = Vec::with_capacity(meta.len() as usize);
    // `take` stops a file that grows while it is read
    file.take(limit + 1)
        .read_to_end(&mut data)
        .map_err(|e| Error::io(action, path, e))?;
    if data.len() as u64 > limit {
        return Err(too_big(data.len() as u64));
    }
    Ok(data)
}

/// [`read_bounded`] as UTF-8 text.
pub fn read_text(path: &Path, action: &'static str, limit: u64) -> Result<String> {
    String::from_utf8(read_bounded(path, action, limit)?).map_err(|e| {
        refuse(
            action,
            path,
            format!(
                "not UTF-8 text (invalid byte at offset {})",
                e.utf8_error().valid_up_to()
            ),
        )
    })
}

/// Characters of a value a message echoes in full.
pub const ECHO_CHARACTERS: usize = 60;

/// `value` as a message echoes it: in full up to [`ECHO_CHARACTERS`],
/// else its start and its length.
pub fn shorten(value: &str) -> String {
    match value.char_indices().nth(ECHO_CHARACTERS) {
        Some((i, _)) => format!("{}… ({} characters)", &value[..i], value.chars().count()),
        None => value.to_string(),
    }
}

/// `x` as a message echoes it: the shortest text that reads back to the
/// same `f64`, plainly for magnitudes from 1e-4 to 1e15 (`1000`, `0.3`)
/// and in exponent form beyond (`1e300`, `2.5e-9`), so that no value
/// prints as hundreds of digits.
pub fn number(x: f64) -> String {
    if x == 0.0 || !x.is_finite() || (1e-4..1e15).contains(&x.abs()) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_read_back_and_stay_short() {
        assert_eq!(number(1000.0), "1000");
        assert_eq!(number(0.3), "0.3");
        assert_eq!(number(1e300), "1e300");
        assert_eq!(number(-2.5e-9), "-2.5e-9");
        for x in [1e300, 1.234567890123e-200, 0.1 + 0.2, 123456.789, -7e20] {
            let text = number(x);
            assert_eq!(text.parse::<f64>().unwrap(), x, "{text}");
            assert!(text.len() < 25, "{text}");
        }
    }

    #[test]
    fn long_values_are_shortened() {
        assert_eq!(shorten("floor"), "floor");
        let long = "x".repeat(1000);
        let s = shorten(&long);
        assert!(s.starts_with(&"x".repeat(ECHO_CHARACTERS)) && s.ends_with("(1000 characters)"));
        assert!(s.chars().count() < ECHO_CHARACTERS + 30);
    }

    #[test]
    fn only_regular_files_within_the_limit_are_read() {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("f");
        std::fs::write(&file, b"12345").unwrap();
        assert_eq!(read_bounded(&file, "read", 5).unwrap(), b"12345");
        let e = read_bounded(&file, "read", 4).unwrap_err().to_string();
        assert!(e.contains("5 bytes") && e.contains("limit of 4"), "{e}");
        let e = read_bounded(dir.path(), "read", 4).unwrap_err().to_string();
        assert!(e.contains("not a regular file"), "{e}");
    }
}
