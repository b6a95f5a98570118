//! ParaView data collections (`.pvd`): the list of a run's `.vtu` files with
//! their times, so that ParaView opens them as one time series.

use std::path::{Path, PathBuf};

use super::{invalid_input, write_atomically, xml_escape};

/// A `.pvd` collection that is rewritten, atomically, after every
/// [`add`](PvdCollection::add): if the run stops, the file on disk lists
/// every step written so far.
#[derive(Clone, Debug, PartialEq)]
pub struct PvdCollection {
    path: PathBuf,
    entries: Vec<(f64, String)>,
}

impl PvdCollection {
    /// An empty collection that will be written to `path` (nothing is
    /// written until the first [`add`](PvdCollection::add)).
    pub fn new(path: impl Into<PathBuf>) -> Self {
        PvdCollection {
            path: path.into(),
            entries: Vec::new(),
        }
    }

    /// The `.pvd` file's path.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The (time, file) entries so far, in the order they were added.
    pub fn entries(&self) -> &[(f64, String)] {
        &self.entries
    }

    /// Appends the data set `file` at `time` and rewrites the `.pvd` file.
    ///
    /// `file` is the data file's name relative to the `.pvd` file's folder
    /// (e.g. `"step_0003.vtu"`); use `/` as separator. `time` must be
    /// finite. If writing fails the entry is not kept.
    pub fn add(&mut self, time: f64, file: impl Into<String>) -> crate::Result<()> {
        let file = file.into();
        if !time.is_finite() {
            let message = format!("the time {time} of data set '{file}' is not finite");
            return Err(crate::Error::io(
                "write",
                &self.path,
                invalid_input(message),
            ));
        }
        self.entries.push((time, file));
        let result = self.write();
        if result.is_err() {
            self.entries.pop();
        }
        result
    }

    /// Appends the data set `file` at `time` without writing (a restart
    /// lists the earlier files again, then [`write`](Self::write)s once).
    pub fn push(&mut self, time: f64, file: impl Into<String>) {
        self.entries.push((time, file.into()));
    }

    /// Writes the collection with all entries so far.
    pub fn write(&self) -> crate::Result<()> {
        write_atomically(&self.path, |w| {
            writeln!(w, r#"<?xml version="1.0"?>"#)?;
            writeln!(
                w,
                r#"<VTKFile type="Collection" version="1.0" byte_order="LittleEndian" header_type="UInt64">"#
            )?;
            writeln!(w, "  <Collection>")?;
            for (time, file) in &self.entries {
                // `{:?}` prints the shortest representation that reads back
                // to the same f64 (exponent form for very small/large times).
                writeln!(
                    w,
                    r#"    <DataSet timestep="{time:?}" group="" part="0" file="{}"/>"#,
                    xml_escape(file)
                )?;
            }
            writeln!(w, "  </Collection>")?;
            writeln!(w, "</VTKFile>")?;
            Ok(())
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn attribute<'a>(tag: &'a str, name: &str) -> &'a str {
        let key = format!(" {name}=\"");
        let start = tag.find(&key).unwrap() + key.len();
        let len = tag[start..].find('"').unwrap();
        &tag[start..start + len]
    }

    #[test]
    fn lists_every_data_set_with_its_time() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("result.pvd");
        let mut pvd = PvdCollection::new(&path);
        let steps = [
            (0.25, "step_0001.vtu"),
            (0.5, "step_0002.vtu"),
            (1e-9 + 1.0, "a&b.vtu"),
        ];
        for (i, (time, file)) in steps.iter().enumerate() {
            pvd.add(*time, *file).unwrap();
            let text = std::fs::read_to_string(&path).unwrap();
            assert_eq!(text.matches("<DataSet ").count(), i + 1);
        }
        let text = std::fs::read_to_string(&path).unwrap();
        assert!(text.contains(r#"<VTKFile type="Collection""#));
        let data_sets: Vec<String> = text
            .split("<DataSet ")
            .skip(1)
            .map(|s| format!(" {}", &s[..s.find("/>").unwrap()]))
            .collect();
        assert_eq!(data_sets.len(), 3);
        for (tag, (time, file)) in data_sets.iter().zip(steps) {
            assert_eq!(attribute(tag, "timestep").parse::<f64>().unwrap(), time);
            assert_eq!(attribute(tag, "file"), file.replace('&', "&amp;"));
        }
        assert_eq!(pvd.entries().len(), 3);
        // Only the .pvd file is left in the folder (no temporary files).
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    }

    #[test]
    fn rejects_non_finite_time() {
        let dir = tempfile::tempdir().unwrap();
        let mut pvd = PvdCollection::new(dir.path().join("r.pvd"));
        let err = pvd.add(f64::NAN, "x.vtu").unwrap_err();
        assert!(err.to_string().contains("x.vtu"), "{err}");
        assert!(pvd.entries().is_empty());
    }
}
