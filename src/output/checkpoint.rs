//! `NAME.checkpoint`: the state of a run after its last converged
//! increment, rewritten (atomically, [`write_atomically_synced`]) after each one,
//! from which `signorini run CASE --restart DIR` goes on
//! ([`crate::run::RunOptions::restart`]) to the final state an
//! uninterrupted run reaches.
//!
//! It holds the unknowns (displacements and multipliers), the committed
//! contact history ([`ContactState`]: Uzawa multipliers, slack unknowns,
//! friction's traction, anchors, slip and status), the stepper's own state
//! ([`Stepping`]: step, time, next increment size, force scale, the
//! predictor's secant, the pair search's last motion), and what the output
//! files have so far (`summary.json`'s text, the histories' samples, the
//! profiles' tables), with what identifies the case ([`CaseKey`]).
//!
//! The format: the 8 bytes [`MAGIC`], the format version (`u32`, little
//! endian), then records, each its payload's length (`u64`), the payload
//! and its FNV-1a hash (`u64`). The first record is a whole [`Checkpoint`];
//! each later one an [`Increment`], the state after one more converged
//! increment with only what it adds to the output (its entry of
//! `summary.json`, its histories' samples, the profiles' new tables), so
//! that writing it costs the same at every increment ([`CheckpointFile`]
//! appends it and syncs it to the disk). A reader takes the longest valid
//! prefix of records: a record cut short by a `kill -9` (or its hash not
//! matching) ends the file, and the state is that of the record before.
//! When the appended records outweigh the whole one, the file is rewritten
//! whole (atomically, [`write_atomically_synced`]), so it stays within
//! about twice one whole record and the rewrites cost a bounded amount per
//! increment; a resumed run rewrites it whole first, dropping a torn
//! record. A truncated, a corrupted first record and a file of another
//! version are told apart. The payload is in
//! [postcard](https://docs.rs/postcard) (serde's compact binary format with
//! a stable wire format, 1.0; bincode, the other candidate, is
//! unmaintained): every state struct derives `Serialize`/`Deserialize`, so a
//! field added to the contact history comes along. `f64`s are stored as
//! their 8 bytes, so the resumed run starts from bitwise the same state.
//! The summary is stored as its JSON text, since it leaves out absent keys,
//! which a format without field names cannot read back.

use std::borrow::Cow;
use std::fs::File;
use std::io::Write as _;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::profile::StepProfile;
use super::summary::{IncrementSummary, Summary};
use super::write_atomically_synced;
use crate::problem::ContactState;
use crate::solve::stepping::Stepping;
use crate::{Error, Result};

/// The first 8 bytes of a checkpoint.
pub const MAGIC: &[u8; 8] = b"SIGNCKPT";
/// The version of the format this build writes and reads.
pub const FORMAT_VERSION: u32 = 3;
/// Bytes before the records: magic, version.
const HEADER: usize = 8 + 4;

/// What ties a checkpoint to its case: the sizes of the model, a hash of
/// its physics and its steps.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CaseKey {
    pub nodes: usize,
    /// Displacement dofs (3 per node) and all unknowns (with the contact
    /// multipliers).
    pub dofs: usize,
    pub unknowns: usize,
    /// FNV-1a hash of the physics: the mesh (coordinates, elements, sets)
    /// and the case's materials, loads, amplitudes, obstacles and
    /// contacts (not `[solver]`, `[output]` or the steps).
    pub physics: u64,
    /// Name and end time of every step.
    pub steps: Vec<(String, f64)>,
}

/// A history's sample: the time and the values ([`super::history::History::samples`]).
pub type Sample = (f64, Vec<f64>);

/// The content of a checkpoint (borrowed when written, owned when read).
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Checkpoint<'a> {
    pub case: Cow<'a, CaseKey>,
    /// Displacements, then contact multipliers.
    pub unknowns: Cow<'a, [f64]>,
    pub contact: Cow<'a, ContactState>,
    pub stepping: Cow<'a, Stepping>,
    /// `summary.json` as written after this increment.
    pub summary: String,
    /// The samples `(time, values)` of each history, in the case's order.
    pub histories: Vec<Cow<'a, [Sample]>>,
    /// The tables of the steps ended so far of each profile.
    pub profiles: Vec<Cow<'a, [StepProfile]>>,
}

/// One converged increment after the record before it: the state, and
/// what it adds to the output files (borrowed when written, owned when
/// read).
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Increment<'a> {
    pub unknowns: Cow<'a, [f64]>,
    pub contact: Cow<'a, ContactState>,
    pub stepping: Cow<'a, Stepping>,
    /// `summary.json` without its increments ([`Summary::head`]), as JSON.
    pub summary_head: String,
    /// The entries of `summary.json`'s increments since the record
    /// before, as JSON.
    pub increments: Vec<String>,
    /// Per history, its samples since the record before.
    pub samples: Vec<Cow<'a, [Sample]>>,
    /// Per profile, its tables since the record before.
    pub profiles: Vec<Cow<'a, [StepProfile]>>,
}

/// The first byte of a record's payload: a whole [`Checkpoint`], or an
/// [`Increment`] (postcard's variant index of the enum they would make).
const WHOLE: u8 = 0;
const INCREMENT: u8 = 1;

/// The checkpoint file of the series `name` in `dir`.
pub fn path(dir: &Path, name: &str) -> PathBuf {
    dir.join(format!("{name}.checkpoint"))
}

/// Write `checkpoint` to `path` as a file of one whole record, atomically
/// and synced to the disk ([`write_atomically_synced`]); its size in
/// bytes.
pub fn write(path: &Path, checkpoint: &Checkpoint) -> Result<u64> {
    let record = record(path, WHOLE, checkpoint)?;
    write_atomically_synced(path, |w| {
        w.write_all(MAGIC)?;
        w.write_all(&FORMAT_VERSION.to_le_bytes())?;
        w.write_all(&record)
    })?;
    Ok((HEADER + record.len()) as u64)
}

/// One record: the payload's length (`u64`), the payload (`tag`, then
/// `value` in postcard) and the payload's FNV-1a hash (`u64`).
fn record<T: Serialize>(path: &Path, tag: u8, value: &T) -> Result<Vec<u8>> {
    let mut bytes = vec![0; 8];
    bytes.push(tag);
    let mut bytes = postcard::to_extend(value, bytes).map_err(|e| {
        Error::io(
            "write",
            path,
            std::io::Error::new(std::io::ErrorKind::InvalidData, e.to_string()),
        )
    })?;
    let length = (bytes.len() - 8) as u64;
    bytes[..8].copy_from_slice(&length.to_le_bytes());
    let hash = fnv1a(&bytes[8..]);
    bytes.extend_from_slice(&hash.to_le_bytes());
    Ok(bytes)
}

/// `NAME.checkpoint` as a run writes it: a whole record at the first
/// increment (and the first after a restart, which drops a torn record),
/// then one [`Increment`] record appended per increment and synced, and
/// the file rewritten whole once the appended records outweigh the whole
/// one. A whole record of `n` increments costs `W = s + n·e` (`s` the
/// state, `e` an increment's output) and comes after at least `W / (s +
/// e)` appended ones, so the rewrites add at most `s + e` per increment:
/// the cost per increment does not grow with the run, and the file stays
/// under about `2 W`.
#[derive(Debug)]
pub struct CheckpointFile {
    path: PathBuf,
    /// Open for appending after the last whole record; `None`: the next
    /// record is whole.
    file: Option<File>,
    /// The size of the file after its whole record, and of the records
    /// appended since.
    whole: u64,
    appended: u64,
}

impl CheckpointFile {
    /// The checkpoint at `path`, its first record still to write.
    pub fn new(path: PathBuf) -> Self {
        CheckpointFile {
            path,
            file: None,
            whole: 0,
            appended: 0,
        }
    }

    /// The file's path.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Whether the next record is to be whole: the first, or the appended
    /// records outweigh the whole one.
    pub fn wants_whole(&self) -> bool {
        self.file.is_none() || self.appended > self.whole
    }

    /// Replace the file by `checkpoint` alone ([`write`]) and go on
    /// appending to it.
    pub fn write_whole(&mut self, checkpoint: &Checkpoint) -> Result<()> {
        self.file = None;
        self.whole = write(&self.path, checkpoint)?;
        self.appended = 0;
        let file = std::fs::OpenOptions::new()
            .append(true)
            .open(&self.path)
            .map_err(|e| Error::io("open", &self.path, e))?;
        self.file = Some(file);
        Ok(())
    }

    /// Append `increment` as one record, synced to the disk (a kill during
    /// the write leaves a torn last record, which a reader drops).
    pub fn append(&mut self, increment: &Increment) -> Result<()> {
        let record = record(&self.path, INCREMENT, increment)?;
        let path = &self.path;
        let Some(file) = self.file.as_mut() else {
            return Err(Error::io(
                "append to",
                path,
                std::io::Error::other("no whole record written before"),
            ));
        };
        let written = file.write_all(&record).and_then(|()| file.sync_data());
        if let Err(e) = written {
            // what follows the whole record is unknown: rewrite it next
            self.file = None;
            return Err(Error::io("write", path, e));
        }
        self.appended += record.len() as u64;
        Ok(())
    }
}

/// Read the checkpoint of the series `name` from the folder `dir`, with an
/// [`Error::Restart`] that says what is wrong: no folder, no checkpoint in
/// it, not a checkpoint, another format version, a truncated or corrupted
/// file.
pub fn read(dir: &Path, name: &str) -> Result<Checkpoint<'static>> {
    let fail = |message: String| Error::Restart {
        path: dir.to_path_buf(),
        message,
    };
    if !dir.is_dir() {
        return Err(fail(if dir.exists() {
            "it is not a folder; give the output folder of the run to resume".into()
        } else {
            "no such folder; give the output folder of the run to resume (the one \
             with its summary.json and NAME.checkpoint)"
                .into()
        }));
    }
    let file = path(dir, name);
    let bytes = match crate::input::read_bounded(&file, "read", crate::input::MAX_CHECKPOINT_FILE) {
        Ok(bytes) => bytes,
        Err(Error::Io { source, .. }) if source.kind() == std::io::ErrorKind::NotFound => {
            return Err(fail(missing_checkpoint(dir, name)))
        }
        Err(e) => return Err(e),
    };
    let fail = |message: String| Error::Restart {
        path: file.clone(),
        message,
    };
    decode(&bytes).map_err(fail)
}

/// Why there is no `NAME.checkpoint` in `dir`, with the checkpoints there are.
fn missing_checkpoint(dir: &Path, name: &str) -> String {
    let mut others: Vec<String> = std::fs::read_dir(dir)
        .into_iter()
        .flatten()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|f| f.ends_with(".checkpoint"))
        .collect();
    others.sort();
    let found = if others.is_empty() {
        "there is no checkpoint in it: the run stopped before its first converged \
         increment, or it is not a run's output folder; run the case from the start"
            .to_string()
    } else {
        format!(
            "it holds {} instead: the checkpoint of another case, or of this one \
             under another [output] name",
            others.join(", ")
        )
    };
    format!("no {name}.checkpoint in it ({found})")
}

/// The checkpoint in `bytes` (its whole first record with the increments
/// of the longest valid prefix of the records after it applied), or why
/// they are not one.
fn decode(bytes: &[u8]) -> std::result::Result<Checkpoint<'static>, String> {
    check_header(bytes)?;
    let (payload, mut at) = next_record(bytes, HEADER)?;
    let mut checkpoint: Checkpoint<'static> = parse(payload, WHOLE)?;
    let mut summary = None;
    // a record cut short or not matching its hash ends the valid prefix
    while let Ok((payload, next)) = next_record(bytes, at) {
        apply(&mut checkpoint, &mut summary, parse(payload, INCREMENT)?)?;
        at = next;
    }
    if let Some(summary) = summary {
        checkpoint.summary = serde_json::to_string(&summary).map_err(|e| corrupted(&e))?;
    }
    Ok(checkpoint)
}

/// Why `bytes` do not start as a checkpoint of this format version does.
fn check_header(bytes: &[u8]) -> std::result::Result<(), String> {
    if bytes.len() < 8 || &bytes[..8] != MAGIC {
        return Err(
            "not a signorini checkpoint (it does not start with the checkpoint \
                    marker); give the output folder of the run to resume"
                .into(),
        );
    }
    let Some(version) = bytes.get(8..HEADER) else {
        return Err(truncated(bytes, "shorter than its header"));
    };
    let version = u32::from_le_bytes([version[0], version[1], version[2], version[3]]);
    if version != FORMAT_VERSION {
        return Err(format!(
            "format version {version}, but this build reads version {FORMAT_VERSION}: resume \
             with the signorini that wrote it, or run the case from the start"
        ));
    }
    Ok(())
}

/// The payload of the record at `at` in `bytes` and where the next record
/// starts, or why it is not whole (cut short, or its hash not matching).
fn next_record(bytes: &[u8], at: usize) -> std::result::Result<(&[u8], usize), String> {
    let Some(length) = bytes.get(at..at + 8) else {
        return Err(truncated(bytes, "shorter than a record's header"));
    };
    let mut word = [0; 8];
    word.copy_from_slice(length);
    let length = u64::from_le_bytes(word);
    let end = (at as u64 + 8).saturating_add(length).saturating_add(8);
    if (bytes.len() as u64) < end {
        return Err(truncated(bytes, &format!("{end} expected")));
    }
    let (start, end) = (at + 8, end as usize - 8);
    word.copy_from_slice(&bytes[end..end + 8]);
    if fnv1a(&bytes[start..end]) != u64::from_le_bytes(word) {
        return Err("corrupted: its checksum does not match its content; \
                    run the case from the start"
            .into());
    }
    Ok((&bytes[start..end], end + 8))
}

/// The message of a checkpoint cut short.
fn truncated(bytes: &[u8], what: &str) -> String {
    format!(
        "truncated ({} bytes, {what}): the file was cut short after signorini wrote it \
         (an interrupted copy, a full disk); restore it, or run the case from the start",
        bytes.len()
    )
}

/// The message of a checkpoint whose content does not read back.
fn corrupted(e: &dyn std::fmt::Display) -> String {
    format!("corrupted ({e}); run the case from the start")
}

/// The record `payload` as a `T`, when its tag is `tag`.
fn parse<T: serde::de::DeserializeOwned>(
    payload: &[u8],
    tag: u8,
) -> std::result::Result<T, String> {
    match payload.split_first() {
        Some((&t, value)) if t == tag => postcard::from_bytes(value).map_err(|e| corrupted(&e)),
        _ => Err(corrupted(&format!("a record of kind {tag} expected"))),
    }
}

/// `checkpoint` after the increment record `increment`: its state, the
/// summary (`summary`, read from the checkpoint's at the first increment)
/// with the new entries, the histories' and profiles' new rows.
fn apply(
    checkpoint: &mut Checkpoint<'static>,
    summary: &mut Option<Summary>,
    increment: Increment<'static>,
) -> std::result::Result<(), String> {
    if increment.samples.len() != checkpoint.histories.len()
        || increment.profiles.len() != checkpoint.profiles.len()
    {
        return Err(corrupted(
            &"an increment's histories or profiles are not the case's",
        ));
    }
    let mut head: Summary =
        serde_json::from_str(&increment.summary_head).map_err(|e| corrupted(&e))?;
    head.increments = match summary.take() {
        Some(earlier) => earlier.increments,
        None => {
            let earlier: Summary =
                serde_json::from_str(&checkpoint.summary).map_err(|e| corrupted(&e))?;
            earlier.increments
        }
    };
    for entry in &increment.increments {
        let entry: IncrementSummary = serde_json::from_str(entry).map_err(|e| corrupted(&e))?;
        head.increments.push(entry);
    }
    *summary = Some(head);
    checkpoint.unknowns = increment.unknowns;
    checkpoint.contact = increment.contact;
    checkpoint.stepping = increment.stepping;
    for (history, new) in checkpoint.histories.iter_mut().zip(increment.samples) {
        history.to_mut().extend(new.into_owned());
    }
    for (profile, new) in checkpoint.profiles.iter_mut().zip(increment.profiles) {
        profile.to_mut().extend(new.into_owned());
    }
    Ok(())
}

impl Checkpoint<'_> {
    /// Whether this checkpoint was written for the case `key` (the problem
    /// about to resume): the same sizes, the same physics, and the same
    /// steps up to the one in progress (later steps may differ: a
    /// restarted run may add or change the steps still to come).
    pub fn check_case(&self, key: &CaseKey, path: &Path) -> Result<()> {
        let fail = |message: String| {
            Error::Restart {
            path: path.to_path_buf(),
            message: format!("{message}; a restart needs the case the checkpoint was written for (run this one from the start)"),
        }
        };
        let old = &*self.case;
        for (what, here, there) in [
            ("nodes", key.nodes, old.nodes),
            ("displacement dofs", key.dofs, old.dofs),
            (
                "unknowns (dofs and contact multipliers)",
                key.unknowns,
                old.unknowns,
            ),
        ] {
            if here != there {
                return Err(fail(format!(
                    "the checkpoint is of another model: {there} {what} in it, {here} in this case"
                )));
            }
        }
        if self.unknowns.len() != key.unknowns {
            return Err(fail(format!(
                "the checkpoint holds {} unknowns for a model of {}",
                self.unknowns.len(),
                key.unknowns
            )));
        }
        if key.physics != old.physics {
            return Err(fail(
                "the case's physics (the mesh, materials, loads, amplitudes, obstacles or \
                 contacts) changed since the checkpoint was written"
                    .into(),
            ));
        }
        let done = self.stepping.step;
        for (i, (name, end)) in old.steps.iter().enumerate().take(done + 1) {
            match key.steps.get(i) {
                Some((n, e)) if n == name && e == end => {}
                Some((n, e)) => {
                    return Err(fail(format!(
                        "step {} is '{n}' ending at t = {e} here, '{name}' ending at t = {end} \
                         in the checkpoint (the steps up to the one in progress, '{}', must stay)",
                        i + 1,
                        old.steps[done].0
                    )))
                }
                None => {
                    return Err(fail(format!(
                        "the case has {} steps, the checkpoint is in step {} ('{}')",
                        key.steps.len(),
                        done + 1,
                        old.steps[done].0
                    )))
                }
            }
        }
        Ok(())
    }
}

/// The 64-bit FNV-1a hash (Fowler–Noll–Vo): `h ← (h ⊕ byte) · 0x100000001b3`
/// from `h = 0xcbf29ce484222325`, byte by byte; stable across builds and
/// platforms (unlike `std`'s `DefaultHasher`).
#[derive(Clone, Copy, Debug)]
pub struct Fnv1a(pub u64);

impl Default for Fnv1a {
    fn default() -> Self {
        Fnv1a(0xcbf2_9ce4_8422_2325)
    }
}

impl std::hash::Hasher for Fnv1a {
    fn finish(&self) -> u64 {
        self.0
    }
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 = (self.0 ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3);
        }
    }
}

/// Text written into the hash (`write!(hasher, "{:?}", x)` hashes a value's
/// debug form without building the string).
impl std::fmt::Write for Fnv1a {
    fn write_str(&mut self, s: &str) -> std::fmt::Result {
        std::hash::Hasher::write(self, s.as_bytes());
        Ok(())
    }
}

/// The FNV-1a hash of `bytes`.
pub fn fnv1a(bytes: &[u8]) -> u64 {
    let mut h = Fnv1a::default();
    std::hash::Hasher::write(&mut h, bytes);
    std::hash::Hasher::finish(&h)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The reference values of FNV-1a 64 (the empty string, "a", "foobar").
    #[test]
    fn fnv1a_matches_the_reference_values() {
        assert_eq!(fnv1a(b""), 0xcbf2_9ce4_8422_2325);
        assert_eq!(fnv1a(b"a"), 0xaf63_dc4c_8601_ec8c);
        assert_eq!(fnv1a(b"foobar"), 0x8594_4171_f739_67e8);
    }

    fn sample() -> Checkpoint<'static> {
        Checkpoint {
            case: Cow::Owned(CaseKey {
                nodes: 2,
                dofs: 6,
                unknowns: 7,
                physics: 42,
                steps: vec![("press".into(), 1.0), ("pull".into(), 2.0)],
            }),
            unknowns: Cow::Owned(vec![0.1, -0.2, 1e-300, f64::MIN_POSITIVE, 3.0, 4.0, 5.5]),
            contact: Cow::Owned(ContactState::default()),
            stepping: Cow::Owned(Stepping {
                step: 1,
                time: 1.25,
                increment: 0.25,
                force_scale: 20.0,
                secant: Some((vec![1.0; 7], 0.25)),
                last_motion: None,
                warm: Some(crate::solve::method::WarmStart {
                    batches: vec![vec![3, 1], vec![0]],
                    active: vec![true, false, true],
                    values: vec![0.5, -1e-300],
                    set: vec![true, false],
                }),
            }),
            summary: "{}".into(),
            histories: vec![Cow::Owned(vec![(0.5, vec![1.0, 2.0])])],
            profiles: vec![],
        }
    }

    /// Written and read back bit for bit; a truncated, a corrupted, a
    /// foreign and a future-version file are each told apart.
    #[test]
    fn round_trips_and_rejects_damaged_files() {
        let dir = tempfile::tempdir().unwrap();
        let c = sample();
        write(&path(dir.path(), "case"), &c).unwrap();
        let back = read(dir.path(), "case").unwrap();
        assert_eq!(back.case, c.case);
        assert_eq!(
            back.unknowns
                .iter()
                .map(|x| x.to_bits())
                .collect::<Vec<_>>(),
            c.unknowns.iter().map(|x| x.to_bits()).collect::<Vec<_>>()
        );
        assert_eq!(back.stepping, c.stepping);
        assert_eq!(back.histories, c.histories);
        let bytes = std::fs::read(path(dir.path(), "case")).unwrap();
        let message = |b: &[u8]| decode(b).err().unwrap();
        assert!(message(&bytes[..bytes.len() - 3]).contains("truncated"));
        assert!(message(&bytes[..10]).contains("truncated"));
        let mut flipped = bytes.clone();
        flipped[HEADER + 8 + 5] ^= 0x40;
        assert!(message(&flipped).contains("checksum"));
        assert!(message(b"<?xml version").contains("not a signorini checkpoint"));
        let mut future = bytes.clone();
        future[8] = 9;
        assert!(message(&future).contains("format version 9"));
        let err = read(dir.path(), "other").err().unwrap().to_string();
        assert!(
            err.contains("no other.checkpoint") && err.contains("case.checkpoint"),
            "{err}"
        );
        let err = read(&dir.path().join("nope"), "case")
            .err()
            .unwrap()
            .to_string();
        assert!(err.contains("no such folder"), "{err}");
    }

    /// A summary of `n` increments, its wall time `n`, as JSON (and its
    /// head), and the increment `n`'s entry.
    fn summary(n: usize) -> (String, String, String) {
        let entry = |k: usize| IncrementSummary {
            step_name: "press".into(),
            time: k as f64,
            residuals: vec![1.0, 1e-3 / k as f64],
            ..Default::default()
        };
        let mut s = Summary {
            wall_time: n as f64,
            increments: (1..=n).map(entry).collect(),
            ..Default::default()
        };
        s.update_step_totals();
        (
            serde_json::to_string(&s).unwrap(),
            serde_json::to_string(&s.head()).unwrap(),
            serde_json::to_string(&entry(n)).unwrap(),
        )
    }

    /// The increment record `k` after [`sample`]: unknowns all `k`, time
    /// `k`, one more history sample.
    fn increment(k: usize) -> Increment<'static> {
        let (_, head, entry) = summary(k);
        let mut stepping = sample().stepping.into_owned();
        stepping.time = k as f64;
        Increment {
            unknowns: Cow::Owned(vec![k as f64; 7]),
            contact: Cow::Owned(ContactState::default()),
            stepping: Cow::Owned(stepping),
            summary_head: head,
            increments: vec![entry],
            samples: vec![Cow::Owned(vec![(k as f64, vec![k as f64, 0.0])])],
            profiles: vec![],
        }
    }

    /// A whole record then three increments appended: the file cut at any
    /// byte after the whole record reads back as its longest whole prefix
    /// (the state, the summary with every increment and its totals, the
    /// histories' samples of the last whole record); a corrupted last
    /// record reads as the one before.
    #[test]
    fn appended_increments_read_back_to_the_longest_whole_prefix() {
        let dir = tempfile::tempdir().unwrap();
        let mut file = CheckpointFile::new(path(dir.path(), "case"));
        let mut whole = sample();
        whole.summary = summary(1).0;
        whole.unknowns = Cow::Owned(vec![1.0; 7]);
        file.write_whole(&whole).unwrap();
        let at = file.path().to_path_buf();
        let size = || std::fs::metadata(&at).unwrap().len() as usize;
        let mut ends = vec![size()];
        for k in 2..=4 {
            file.append(&increment(k)).unwrap();
            ends.push(size());
        }
        let bytes = std::fs::read(file.path()).unwrap();
        for cut in ends[0]..=bytes.len() {
            let k = ends.iter().filter(|&&end| end <= cut).count();
            let c = decode(&bytes[..cut]).unwrap();
            assert!(c.unknowns.iter().all(|&u| u == k as f64), "cut at {cut}");
            let s: Summary = serde_json::from_str(&c.summary).unwrap();
            assert_eq!(s.increments.len(), k);
            assert_eq!(s.wall_time, k as f64);
            assert_eq!(s.steps[0].increments, k);
            assert_eq!(s.increments[k - 1].residuals[1], 1e-3 / k as f64);
            assert_eq!(c.histories[0].len(), k);
            if k > 1 {
                assert_eq!(c.stepping.time, k as f64);
            }
        }
        let mut flipped = bytes.clone();
        flipped[ends[2] + 12] ^= 0x01;
        let c = decode(&flipped).unwrap();
        assert_eq!(c.unknowns[0], 3.0);
    }

    /// Appended records of about a whole one's size: a whole record is
    /// wanted again once they outweigh it, so the file stays under twice a
    /// whole record and one more.
    #[test]
    fn rewrites_whole_once_the_appended_records_outweigh_it() {
        let dir = tempfile::tempdir().unwrap();
        let mut file = CheckpointFile::new(path(dir.path(), "case"));
        assert!(file.wants_whole());
        let mut whole = sample();
        whole.summary = summary(1).0;
        file.write_whole(&whole).unwrap();
        let first = std::fs::metadata(file.path()).unwrap().len();
        let mut appended = 0;
        while !file.wants_whole() {
            file.append(&increment(2 + appended)).unwrap();
            appended += 1;
            assert!(appended < 1000);
        }
        let last = std::fs::metadata(file.path()).unwrap().len();
        let record = (last - first) / appended as u64;
        assert!(
            last > 2 * first && last <= 2 * first + 2 * record,
            "{first} {last} {record}"
        );
        assert_eq!(
            decode(&std::fs::read(file.path()).unwrap())
                .unwrap()
                .unknowns[0],
            (1 + appended) as f64
        );
    }

    /// Another model, other physics and another step in progress are
    /// refused; later steps may change.
    #[test]
    fn checks_the_case() {
        let c = sample();
        let key = c.case.clone().into_owned();
        let p = Path::new("x.checkpoint");
        c.check_case(&key, p).unwrap();
        let with = |f: &dyn Fn(&mut CaseKey)| {
            let mut k = key.clone();
            f(&mut k);
            c.check_case(&k, p).err().map(|e| e.to_string())
        };
        assert!(with(&|k| k.nodes = 3).unwrap().contains("3 in this case"));
        assert!(with(&|k| k.physics = 1).unwrap().contains("physics"));
        assert!(with(&|k| k.steps[1].1 = 3.0)
            .unwrap()
            .contains("'pull' ending at t = 3"));
        assert!(with(&|k| k.steps.push(("more".into(), 4.0))).is_none());
        assert!(with(&|k| {
            k.steps.pop();
        })
        .unwrap()
        .contains("1 steps"));
    }
}
