//! STL files (ASCII or binary, via the `stl_io` crate), read with bounded
//! memory and with errors that say what is wrong with the file: empty,
//! truncated (the binary header announces more triangles than the file
//! holds), or not STL at all.
//!
//! A binary STL is an 80-byte header, a 4-byte little-endian triangle count
//! `n` and `n` records of 50 bytes: its length is `84 + 50 n` exactly. An
//! ASCII STL starts with `solid `.

use crate::input::{read_bounded, MAX_STL_FILE};
use crate::{Error, Result};
use std::path::Path;

/// Bytes of a binary STL's header and triangle count.
const HEADER: usize = 84;
/// Bytes of a binary STL's triangle record.
const RECORD: u64 = 50;

fn invalid(path: &Path, message: String) -> Error {
    Error::ContactInput {
        what: format!("STL file '{}'", path.display()),
        message,
    }
}

/// The triangles of the STL file `path`.
pub fn read_stl(path: &Path) -> Result<stl_io::IndexedMesh> {
    parse_stl(&read_bounded(path, "read STL file", MAX_STL_FILE)?, path)
}

/// The triangles of the STL file contents `data`; `path` is used only in
/// error messages.
pub fn parse_stl(data: &[u8], path: &Path) -> Result<stl_io::IndexedMesh> {
    diagnose(data).map_err(|m| invalid(path, m))?;
    let mesh = stl_io::read_stl(&mut std::io::Cursor::new(data)).map_err(|e| {
        invalid(
            path,
            format!(
                "cannot be read as STL: {}",
                crate::error::words::plain(&e.to_string())
            ),
        )
    })?;
    for (i, v) in mesh.vertices.iter().enumerate() {
        let fault = (0..3).find_map(|a| crate::input::coordinate_fault(v[a] as f64));
        if let Some(fault) = fault {
            return Err(invalid(
                path,
                format!("vertex {i} (0-based, after merging) {fault}"),
            ));
        }
    }
    Ok(mesh)
}

/// What is wrong with `data` as an STL file that `stl_io` would report
/// unclearly (its message is "failed to fill whole buffer" for all of it).
fn diagnose(data: &[u8]) -> std::result::Result<(), String> {
    if data.is_empty() {
        return Err("the file is empty (0 bytes); export the obstacle's surface as STL".into());
    }
    let ascii = data.starts_with(b"solid ") || data.starts_with(b"solid\n");
    if ascii {
        return Ok(()); // stl_io's ASCII errors name the line's problem
    }
    let Some(count) = data.get(80..HEADER) else {
        return Err(format!(
            "not an STL file: it does not start with 'solid ' (ASCII), and at {} bytes it is \
             shorter than a binary STL's 84-byte header",
            data.len()
        ));
    };
    let mut n = [0u8; 4];
    n.copy_from_slice(count);
    let triangles = u32::from_le_bytes(n) as u64;
    let expected = HEADER as u64 + RECORD * triangles;
    let actual = data.len() as u64;
    if expected > MAX_STL_FILE {
        return Err(format!(
            "not an STL file: it does not start with 'solid ' (ASCII), and as binary STL its \
             header announces {triangles} triangles ({expected} bytes, more than the {MAX_STL_FILE} \
             bytes read at most) while the file has {actual} bytes"
        ));
    }
    if actual < expected {
        return Err(format!(
            "truncated binary STL: its header announces {triangles} triangles \
             (84 + 50 × {triangles} = {expected} bytes), the file has {actual} bytes"
        ));
    }
    if actual > expected {
        return Err(format!(
            "not an STL file: it does not start with 'solid ' (ASCII), and as binary STL its \
             header announces {triangles} triangles ({expected} bytes) while the file has {actual} bytes"
        ));
    }
    if triangles == 0 {
        return Err("the binary STL has no triangles".into());
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::diagnose;

    fn binary(triangles: u32, records: usize) -> Vec<u8> {
        let mut d = vec![0u8; 80];
        d.extend_from_slice(&triangles.to_le_bytes());
        d.extend(std::iter::repeat_n(0u8, 50 * records));
        d
    }

    #[test]
    fn each_fault_has_its_message() {
        assert!(diagnose(b"").unwrap_err().contains("empty"));
        assert!(diagnose(b"garbage").unwrap_err().contains("shorter than"));
        assert!(diagnose(&binary(u32::MAX, 1))
            .unwrap_err()
            .contains("not an STL file"));
        assert!(diagnose(&binary(2, 1)).unwrap_err().contains("truncated"));
        assert!(diagnose(&binary(1, 2))
            .unwrap_err()
            .contains("not an STL file"));
        assert!(diagnose(&binary(0, 0))
            .unwrap_err()
            .contains("no triangles"));
        assert!(diagnose(&binary(2, 2)).is_ok());
        assert!(diagnose(b"solid x\nendsolid x\n").is_ok());
    }
}
