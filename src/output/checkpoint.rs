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
//! endian), the payload's length (`u64`), the payload, and its FNV-1a hash
//! (`u64`), so a truncated or corrupted file is told apart from a file of
//! another version. The payload is the [`Checkpoint`] in
//! [postcard](https://docs.rs/postcard) (serde's compact binary format with
//! a stable wire format, 1.0; bincode, the other candidate, is
//! unmaintained): every state struct derives `Serialize`/`Deserialize`, so a
//! field added to the contact history comes along. `f64`s are stored as
//! their 8 bytes, so the resumed run starts from bitwise the same state.
//! The summary is stored as its JSON text, since it leaves out absent keys,
//! which a format without field names cannot read back.

use std::borrow::Cow;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::profile::StepProfile;
use super::write_atomically_synced;
use crate::problem::ContactState;
use crate::solve::stepping::Stepping;
use crate::{Error, Result};

/// The first 8 bytes of a checkpoint.
pub const MAGIC: &[u8; 8] = b"SIGNCKPT";
/// The version of the format this build writes and reads.
pub const FORMAT_VERSION: u32 = 2;
/// Bytes before the payload: magic, version, payload length.
const HEADER: usize = 8 + 4 + 8;

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

/// The checkpoint file of the series `name` in `dir`.
pub fn path(dir: &Path, name: &str) -> PathBuf {
    dir.join(format!("{name}.checkpoint"))
}

/// Write `checkpoint` to `path`, atomically and synced to the disk
/// ([`write_atomically_synced`]).
pub fn write(path: &Path, checkpoint: &Checkpoint) -> Result<()> {
    let payload = postcard::to_stdvec(checkpoint).map_err(|e| {
        Error::io(
            "write",
            path,
            std::io::Error::new(std::io::ErrorKind::InvalidData, e.to_string()),
        )
    })?;
    write_atomically_synced(path, |w| {
        w.write_all(MAGIC)?;
        w.write_all(&FORMAT_VERSION.to_le_bytes())?;
        w.write_all(&(payload.len() as u64).to_le_bytes())?;
        w.write_all(&payload)?;
        w.write_all(&fnv1a(&payload).to_le_bytes())
    })
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

/// The checkpoint in `bytes`, or why they are not one.
fn decode(bytes: &[u8]) -> std::result::Result<Checkpoint<'static>, String> {
    if bytes.len() < 8 || &bytes[..8] != MAGIC {
        return Err(
            "not a signorini checkpoint (it does not start with the checkpoint \
                    marker); give the output folder of the run to resume"
                .into(),
        );
    }
    let truncated = |what: &str| {
        format!(
            "truncated ({} bytes, {what}): the file was cut short after signorini wrote it \
             (an interrupted copy, a full disk); restore it, or run the case from the start",
            bytes.len()
        )
    };
    if bytes.len() < HEADER {
        return Err(truncated("shorter than its header"));
    }
    let version = u32::from_le_bytes(bytes[8..12].try_into().map_err(|_| truncated("header"))?);
    if version != FORMAT_VERSION {
        return Err(format!(
            "format version {version}, but this build reads version {FORMAT_VERSION}: resume \
             with the signorini that wrote it, or run the case from the start"
        ));
    }
    let length = u64::from_le_bytes(bytes[12..20].try_into().map_err(|_| truncated("header"))?);
    let expected = (HEADER as u64).saturating_add(length).saturating_add(8);
    if (bytes.len() as u64) < expected {
        return Err(truncated(&format!("{expected} expected")));
    }
    if (bytes.len() as u64) > expected {
        return Err(format!(
            "corrupted: {} bytes where its header announces {expected}; run the case from the start",
            bytes.len()
        ));
    }
    let payload = &bytes[HEADER..HEADER + length as usize];
    let stored = u64::from_le_bytes(
        bytes[HEADER + length as usize..]
            .try_into()
            .map_err(|_| truncated("checksum"))?,
    );
    if fnv1a(payload) != stored {
        return Err("corrupted: its checksum does not match its content; \
                    run the case from the start"
            .into());
    }
    postcard::from_bytes(payload)
        .map_err(|e| format!("corrupted ({e}); run the case from the start"))
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
        flipped[HEADER + 5] ^= 0x40;
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
