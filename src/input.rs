//! The one guard every file the program reads goes through (the case
//! file, the mesh and every file a deck includes, STL obstacles, the
//! checkpoint), and long values shortened before a message echoes them.
//!
//! - Only regular files are read (`/dev/zero` or a FIFO would otherwise be
//!   read until memory runs out, or wait forever), and only up to a limit
//!   per kind of file, checked against the length the file system
//!   announces before anything is allocated ([`read_bounded`]).
//! - A text format's file that holds binary data is refused
//!   ([`read_text_bytes`], [`binary_fault`]).
//! - What one file makes the reader produce is counted per mesh, not per
//!   line ([`Limits::generated_ids`]), so that a small deck cannot ask for
//!   10¹¹ ids a line at a time.
//! - Coordinates are finite and within ±[`MAX_COORDINATE`]
//!   ([`coordinate_fault`]), whatever the reader.

use crate::{Error, Result};
use std::io::Read;
use std::path::Path;
use std::sync::atomic::{AtomicU64, Ordering};

/// Largest case file read: 4 MiB (an amplitude table of 100 000 points is
/// about 3 MB of TOML; parsing costs some 50 bytes of memory per byte).
pub const MAX_CASE_FILE: u64 = 4 << 20;
/// Largest mesh file read: 16 GiB.
pub const MAX_MESH_FILE: u64 = 16 << 30;
/// Largest STL file read: 4 GiB (80 million triangles).
pub const MAX_STL_FILE: u64 = 4 << 30;
/// Largest checkpoint read: 16 GiB (the state of some 10⁹ unknowns).
pub const MAX_CHECKPOINT_FILE: u64 = 16 << 30;

/// The largest coordinate magnitude read from a mesh: areas (length²),
/// volumes (length³) and stiffnesses `E/h` stay finite below it.
pub const MAX_COORDINATE: f64 = 1e100;

/// Why `value` cannot be a node coordinate (not finite, or beyond
/// ±[`MAX_COORDINATE`]), as the end of a sentence about it ("the x
/// coordinate of node 7 is inf, not a finite number"); `None`: it can.
pub fn coordinate_fault(value: f64) -> Option<String> {
    if !value.is_finite() {
        Some(format!("is {value}, not a finite number"))
    } else if value.abs() > MAX_COORDINATE {
        Some(format!(
            "is {}, beyond ±{}: areas and volumes would overflow; check the mesh's length unit",
            number(value),
            number(MAX_COORDINATE)
        ))
    } else {
        None
    }
}

/// The most ids the `GENERATE` lines of one mesh (a deck with all the
/// files it includes) may list together, unless the case file raises it
/// (`[mesh] max_generated_ids`).
pub const MAX_GENERATED_IDS: u64 = 100_000_000;

/// The limits on what the files of one mesh make the reader produce,
/// counted over the whole mesh rather than per line.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Limits {
    /// Ids listed by the `GENERATE` lines of a deck and its includes, and
    /// by the sets named in its sets, together (ranges as written: ids no
    /// node or element has count too).
    pub generated_ids: u64,
}

impl Default for Limits {
    fn default() -> Self {
        Limits {
            generated_ids: MAX_GENERATED_IDS,
        }
    }
}

/// A running count checked against a limit, e.g. the ids of a deck's
/// `GENERATE` lines against [`Limits::generated_ids`].
#[derive(Debug)]
pub struct Budget {
    used: AtomicU64,
    limit: u64,
}

impl Budget {
    pub fn new(limit: u64) -> Self {
        Budget {
            used: AtomicU64::new(0),
            limit,
        }
    }
    /// Spends `count`; `Err((total, limit))` (nothing spent) if the total
    /// would exceed the limit.
    pub fn spend(&self, count: u64) -> std::result::Result<(), (u64, u64)> {
        self.used
            .fetch_update(Ordering::Relaxed, Ordering::Relaxed, |used| {
                Some(used.saturating_add(count)).filter(|&t| t <= self.limit)
            })
            .map(|_| ())
            .map_err(|used| (used.saturating_add(count), self.limit))
    }
}

/// Bytes of a text file looked at for binary data.
const BINARY_PROBE: usize = 64 << 10;

/// Why `bytes`, the content of a file of a text format, look like binary
/// data (a NUL byte, or more than 1 % control characters other than tab,
/// line and page breaks in their first 64 KiB); `None`: they look like text.
pub fn binary_fault(bytes: &[u8]) -> Option<String> {
    let probe = &bytes[..bytes.len().min(BINARY_PROBE)];
    if let Some(at) = probe.iter().position(|&b| b == 0) {
        return Some(format!("binary data, not text (a NUL byte at offset {at})"));
    }
    let control = probe
        .iter()
        .filter(|&&b| (b < 0x20 && !matches!(b, b'\t' | b'\n' | b'\r' | 0x0c)) || b == 0x7f)
        .count();
    (100 * control > probe.len()).then(|| {
        format!(
            "binary data, not text ({control} control characters in its first {} bytes)",
            probe.len()
        )
    })
}

/// [`read_bounded`], refused if the bytes are binary data
/// ([`binary_fault`]): the file of a text format (a deck, an include).
pub fn read_text_bytes(path: &Path, action: &'static str, limit: u64) -> Result<Vec<u8>> {
    let bytes = read_bounded(path, action, limit)?;
    match binary_fault(&bytes) {
        Some(fault) => Err(refuse(action, path, format!("{fault}; give a text file"))),
        None => Ok(bytes),
    }
}

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
        #[cfg(unix)]
        {
            let e = read_bounded(Path::new("/dev/zero"), "read", 4).unwrap_err();
            assert!(e.to_string().contains("not a regular file"), "{e}");
        }
    }

    #[test]
    fn binary_data_is_told_from_text() {
        assert_eq!(binary_fault(b"*NODE\r\n1, 0.0, 0.0, 0.0\t\x0c\n"), None);
        assert_eq!(binary_fault("** é, ü\n".as_bytes()), None);
        let e = binary_fault(b"*NODE\n\x00\x01").unwrap();
        assert!(e.contains("NUL byte at offset 6"), "{e}");
        // 1 control character in 100 bytes is 1 %: text; 2 are more
        let mut text = vec![b'a'; 99];
        text.push(0x01);
        assert_eq!(binary_fault(&text), None);
        text[0] = 0x02;
        assert!(binary_fault(&text)
            .unwrap()
            .contains("2 control characters"));
    }

    #[test]
    fn coordinates_are_finite_and_bounded() {
        assert_eq!(coordinate_fault(-1e100), None);
        assert_eq!(coordinate_fault(0.0), None);
        let e = coordinate_fault(-1e200).unwrap();
        assert!(e.starts_with("is -1e200, beyond ±1e100"), "{e}");
        assert!(coordinate_fault(f64::NAN).unwrap().contains("not a finite"));
        assert!(coordinate_fault(f64::INFINITY).is_some());
    }

    #[test]
    fn a_budget_refuses_the_count_that_would_exceed_it() {
        let b = Budget::new(10);
        assert_eq!(b.spend(6), Ok(()));
        assert_eq!(b.spend(5), Err((11, 10)));
        // nothing was spent by the refused count
        assert_eq!(b.spend(4), Ok(()));
        assert_eq!(b.spend(u64::MAX), Err((u64::MAX, 10)));
    }
}
