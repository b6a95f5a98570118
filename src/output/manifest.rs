//! `NAME.manifest`: the files a run of the case `NAME` wrote into its
//! output folder, one name a line, so that the next run of the same case
//! can remove them before it writes its own.
//!
//! A file is added to the manifest *before* it is first written, so the
//! manifest on disk always lists at least every file of the run, whenever
//! the run is killed. A new name is appended as one line (a run of 10⁵
//! VTU files does not rewrite a list of 10⁵ names each time); the list is
//! written whole, atomically, once at the start of a run. A line cut short
//! by a kill names no file of the run (every name ends in its extension),
//! so it removes nothing. At the start of a run
//! ([`Manifest::take_over`]) the earlier run's files are removed in an
//! order that never leaves a listing of a missing file: first
//! `summary.json` and `NAME.pvd` (which name the VTU files), then the VTU
//! files, histories, profiles, plots and log, then the leftover temporary
//! files `.FILE.PID-N.tmp` of [`write_atomically`](super::write_atomically)
//! whose `FILE` is one of the case's. The run holds the folder's lock
//! ([`super::lock`]) meanwhile, so no other run is writing them.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use super::write_atomically;
use crate::{Error, Result};

/// Largest manifest read: 64 MiB (a million file names).
const MAX_MANIFEST: u64 = 64 << 20;

/// The manifest of the current run.
pub struct Manifest {
    path: PathBuf,
    files: BTreeSet<String>,
}

impl Manifest {
    /// Take over `dir` for the case `name`: remove what an earlier run of
    /// it wrote (its manifest's files, and for folders written before
    /// manifests existed `summary.json`, `NAME.pvd` and `NAME_NNNN.vtu`) and
    /// the leftover temporary files of those files (not another case's),
    /// then start a new manifest listing itself.
    pub fn take_over(dir: &Path, name: &str) -> Result<Self> {
        let path = dir.join(format!("{name}.manifest"));
        let mut old = read_list(&path)?;
        let pvd = format!("{name}.pvd");
        let listings = ["summary.json".to_string(), pvd];
        // the listings go first, so no file on disk names a removed file
        for file in &listings {
            remove(&dir.join(file))?;
            old.remove(file);
        }
        let entries =
            std::fs::read_dir(dir).map_err(|e| Error::io("list output folder", dir, e))?;
        let mut temporaries = Vec::new();
        let own = |target: &str| old.contains(target) || is_own_file(target, name);
        let mut series = Vec::new();
        for entry in entries.flatten() {
            let file = entry.file_name().to_string_lossy().into_owned();
            if is_series_file(&file, name) {
                series.push(file);
            } else if temporary_target(&file).is_some_and(own) {
                // only the temporaries of this case's files: the folder is
                // locked (super::lock), so their writer was killed
                temporaries.push(file);
            }
        }
        old.extend(series);
        old.remove(&format!("{name}.manifest"));
        // the lock this run holds is never removed, whatever a manifest says
        old.remove(super::lock::LOCK_FILE);
        for file in old.iter().chain(&temporaries) {
            remove(&dir.join(file))?;
        }
        let manifest = Manifest {
            path,
            files: BTreeSet::from([format!("{name}.manifest")]),
        };
        manifest.rewrite()?;
        Ok(manifest)
    }

    /// Go on with the manifest of `dir` for the case `name` (a restart,
    /// which continues the series in its folder): the files it lists stay
    /// listed and on disk, except the VTU files of the series that `keep`
    /// does not name (those of increments after the checkpoint's, which the
    /// resumed run writes again), which are removed, as are leftover
    /// temporary files.
    pub fn resume(dir: &Path, name: &str, keep: &BTreeSet<String>) -> Result<Self> {
        let path = dir.join(format!("{name}.manifest"));
        let mut files = read_list(&path)?;
        let entries =
            std::fs::read_dir(dir).map_err(|e| Error::io("list output folder", dir, e))?;
        for entry in entries.flatten() {
            let file = entry.file_name().to_string_lossy().into_owned();
            let own_temporary = temporary_target(&file)
                .is_some_and(|target| files.contains(target) || is_own_file(target, name));
            if (is_series_file(&file, name) && !keep.contains(&file)) || own_temporary {
                remove(&dir.join(&file))?;
                files.remove(&file);
            }
        }
        files.insert(format!("{name}.manifest"));
        let manifest = Manifest { path, files };
        manifest.rewrite()?;
        Ok(manifest)
    }

    /// Add `file` (a name in the output folder) to the manifest before it
    /// is written; a new name is appended to the file as one line.
    pub fn claim(&mut self, file: &str) -> Result<()> {
        if self.files.insert(file.to_string()) {
            let line = format!("{file}\n");
            std::fs::OpenOptions::new()
                .append(true)
                .create(true)
                .open(&self.path)
                .and_then(|mut f| std::io::Write::write_all(&mut f, line.as_bytes()))
                .map_err(|e| Error::io("write", &self.path, e))?;
        }
        Ok(())
    }

    /// The whole list, written atomically.
    fn rewrite(&self) -> Result<()> {
        write_atomically(&self.path, |w| {
            for f in &self.files {
                writeln!(w, "{f}")?;
            }
            Ok(())
        })
    }
}

/// The file names a manifest at `path` lists (none when there is none).
fn read_list(path: &Path) -> Result<BTreeSet<String>> {
    match crate::input::read_text(path, "read", MAX_MANIFEST) {
        Ok(text) => Ok(text
            .lines()
            .map(str::trim)
            .filter(|l| is_plain_name(l))
            .map(str::to_string)
            .collect()),
        Err(Error::Io { source, .. }) if source.kind() == std::io::ErrorKind::NotFound => {
            Ok(BTreeSet::new())
        }
        Err(e) => Err(e),
    }
}

/// Remove `path`; a file already gone is fine.
fn remove(path: &Path) -> Result<()> {
    match std::fs::remove_file(path) {
        Ok(()) => Ok(()),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(()),
        Err(e) => Err(Error::io("remove old result", path, e)),
    }
}

/// A name of a file directly in the folder (a manifest line that would
/// reach outside it, or is empty, is ignored).
fn is_plain_name(line: &str) -> bool {
    !line.is_empty()
        && line != "."
        && line != ".."
        && !line.contains(['/', '\\'])
        && !Path::new(line).is_absolute()
}

/// `NAME_NNNN.vtu`, a VTU file of the series `name`.
fn is_series_file(file: &str, name: &str) -> bool {
    file.strip_prefix(&format!("{name}_"))
        .and_then(|rest| rest.strip_suffix(".vtu"))
        .is_some_and(|n| !n.is_empty() && n.chars().all(|c| c.is_ascii_digit()))
}

/// A file of the case `name` whether its manifest lists it or not:
/// `summary.json`, `NAME.pvd`, `NAME.manifest`, `NAME.checkpoint`,
/// `NAME.log` and its VTU files.
fn is_own_file(file: &str, name: &str) -> bool {
    file == "summary.json"
        || is_series_file(file, name)
        || [".pvd", ".manifest", ".checkpoint", ".log"]
            .iter()
            .any(|ext| file.strip_prefix(name) == Some(ext))
}

/// `FILE` of `.FILE.PID-N.tmp`, a temporary file of [`write_atomically`]
/// left by a run that was killed while writing.
fn temporary_target(file: &str) -> Option<&str> {
    let rest = file.strip_prefix('.')?.strip_suffix(".tmp")?;
    let (target, tag) = rest.rsplit_once('.')?;
    let digits = |s: &str| !s.is_empty() && s.chars().all(|c| c.is_ascii_digit());
    let tagged = tag
        .split_once('-')
        .is_some_and(|(pid, n)| digits(pid) && digits(n));
    (!target.is_empty() && tagged).then_some(target)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn recognises_temporary_and_series_files() {
        assert_eq!(
            temporary_target(".case_0003.vtu.1234-7.tmp"),
            Some("case_0003.vtu")
        );
        assert_eq!(
            temporary_target(".summary.json.1-0.tmp"),
            Some("summary.json")
        );
        assert_eq!(temporary_target("case.tmp"), None);
        assert_eq!(temporary_target(".case.vtu.12a-7.tmp"), None);
        assert!(is_own_file("summary.json", "case") && is_own_file("case.checkpoint", "case"));
        assert!(!is_own_file("other.pvd", "case") && !is_own_file("casex.pvd", "case"));
        assert!(is_series_file("case_0012.vtu", "case"));
        assert!(!is_series_file("case_x.vtu", "case"));
        assert!(!is_series_file("other_0012.vtu", "case"));
        assert!(!is_plain_name("../x"));
        assert!(!is_plain_name("/etc/passwd"));
        assert!(is_plain_name("tip.csv"));
    }

    /// A restart keeps the earlier run's files and list, but not the VTU
    /// files after its checkpoint nor temporary files.
    #[test]
    fn a_resumed_manifest_keeps_the_earlier_files() {
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path();
        for f in [
            "case_0001.vtu",
            "case_0002.vtu",
            "tip.csv",
            ".case_0003.vtu.99-3.tmp",
        ] {
            std::fs::write(d.join(f), "x").unwrap();
        }
        std::fs::write(
            d.join("case.manifest"),
            "case.manifest\ncase_0001.vtu\ncase_0002.vtu\ntip.csv\n",
        )
        .unwrap();
        let keep = BTreeSet::from(["case_0001.vtu".to_string()]);
        let mut m = Manifest::resume(d, "case", &keep).unwrap();
        m.claim("case.checkpoint").unwrap();
        let mut left: Vec<String> = std::fs::read_dir(d)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        left.sort();
        assert_eq!(left, ["case.manifest", "case_0001.vtu", "tip.csv"]);
        // the list written whole at the start, then the new name appended
        let text = std::fs::read_to_string(d.join("case.manifest")).unwrap();
        assert_eq!(
            text,
            "case.manifest\ncase_0001.vtu\ntip.csv\ncase.checkpoint\n"
        );
    }

    #[test]
    fn removes_the_files_of_the_earlier_run() {
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path();
        for f in [
            "case.pvd",
            "summary.json",
            "case_0001.vtu",
            "old_history.csv",
            ".case_0002.vtu.99-3.tmp",
            "keep.txt",
        ] {
            std::fs::write(d.join(f), "x").unwrap();
        }
        std::fs::write(d.join("case.manifest"), "old_history.csv\n../keep.txt\n").unwrap();
        let mut m = Manifest::take_over(d, "case").unwrap();
        m.claim("case_0001.vtu").unwrap();
        let mut left: Vec<String> = std::fs::read_dir(d)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        left.sort();
        assert_eq!(left, ["case.manifest", "keep.txt"]);
        let text = std::fs::read_to_string(d.join("case.manifest")).unwrap();
        assert_eq!(text, "case.manifest\ncase_0001.vtu\n");
    }
}
