//! Restarting a run from its checkpoint (`--restart DIR`,
//! [`RunOptions::restart`](super::RunOptions::restart)): the checkpoint read
//! back and checked against the case (its [`CaseKey`], the same histories and
//! profiles, the same output folder), and the hash of the case's physics
//! that ties a checkpoint to it.

use super::Simulation;
use crate::case::Case;
use crate::output::checkpoint::{self, CaseKey, Fnv1a};
use crate::output::summary::Summary;
use crate::problem::ContactState;
use crate::solve::stepping::Resume;
use crate::{Error, Result};
use std::path::{Path, PathBuf};

/// What a restart resumes from: the checkpoint's state and output.
pub(super) struct Restart {
    pub(super) resume: Resume<ContactState>,
    pub(super) summary: Summary,
    pub(super) histories: Vec<Vec<(f64, Vec<f64>)>>,
    pub(super) profiles: Vec<Vec<crate::output::profile::StepProfile>>,
    /// The increments in the checkpoint, and the folder it was read from.
    pub(super) increments: usize,
    pub(super) dir: PathBuf,
}

impl Simulation {
    /// The checkpoint in `dir` (`NAME.checkpoint`), checked against this
    /// case, with the output it restores; `output` must be `dir` or none.
    pub(super) fn read_restart(&self, dir: &Path, output: Option<&Path>) -> Result<Restart> {
        if let Some(out) = output.filter(|out| !same_folder(out, dir)) {
            return Err(Error::Restart {
                path: dir.to_path_buf(),
                message: format!(
                    "a restart goes on writing into the folder it resumes from, not into '{}'; \
                     leave out --output (or give the same folder), or copy the folder first \
                     to keep the interrupted run's files",
                    out.display()
                ),
            });
        }
        let c = checkpoint::read(dir, &self.name)?;
        let path = checkpoint::path(dir, &self.name);
        c.check_case(&self.case_key, &path)?;
        let fail = |message: String| Error::Restart {
            path: path.clone(),
            message,
        };
        let (histories, profiles) = (&self.requests.histories, &self.requests.profiles);
        if c.histories.len() != histories.len() || c.profiles.len() != profiles.len() {
            return Err(fail(format!(
                "the checkpoint has {} histories and {} profiles, the case asks for {} and {}; \
                 a restart needs the same [[output.history]] and [[output.profile]] tables",
                c.histories.len(),
                c.profiles.len(),
                histories.len(),
                profiles.len()
            )));
        }
        let summary: Summary = serde_json::from_str(&c.summary)
            .map_err(|e| fail(format!("corrupted: its summary does not read back ({e})")))?;
        if let Some(what) = not_finite(&c.unknowns, &c.contact, &c.stepping) {
            return Err(fail(format!(
                "its {what} is not finite (NaN or infinite), which no converged increment \
                 leaves: the file was edited or forged; run the case from the start (without \
                 --restart)"
            )));
        }
        let missing: Vec<&str> = summary
            .increments
            .iter()
            .map(|i| i.file.as_str())
            .filter(|f| !f.is_empty() && !dir.join(f).is_file())
            .collect();
        if let Some(first) = missing.first() {
            return Err(fail(format!(
                "{} of the VTU files it wrote are gone from '{}' (the first: {first}); a restart \
                 keeps the earlier files and lists them again in the .pvd, so put them back, or \
                 run the case from the start (without --restart)",
                missing.len(),
                dir.display()
            )));
        }
        Ok(Restart {
            increments: summary.increments.len(),
            summary,
            histories: c.histories.into_iter().map(|h| h.into_owned()).collect(),
            profiles: c.profiles.into_iter().map(|p| p.into_owned()).collect(),
            resume: Resume {
                unknowns: c.unknowns.into_owned(),
                state: c.contact.into_owned(),
                stepping: c.stepping.into_owned(),
            },
            dir: dir.to_path_buf(),
        })
    }
}

/// Which part of a checkpoint's state is not finite, if any: the unknowns,
/// the contact history ([`ContactState::is_finite`]) or the stepping
/// ([`Stepping::is_finite`](crate::solve::stepping::Stepping::is_finite));
/// a converged increment leaves every value finite.
fn not_finite(
    unknowns: &[f64],
    contact: &ContactState,
    stepping: &crate::solve::stepping::Stepping,
) -> Option<&'static str> {
    if !unknowns.iter().all(|x| x.is_finite()) {
        Some("state (the unknowns)")
    } else if !contact.is_finite() {
        Some("contact history")
    } else if !stepping.is_finite() {
        Some("stepping state (time, increment)")
    } else {
        None
    }
}

/// What ties a checkpoint to `case` and its built `problem`: the sizes,
/// the steps and the hash of the physics ([`physics_hash`]).
pub(super) fn case_key(case: &Case, problem: &crate::problem::Problem) -> CaseKey {
    CaseKey {
        nodes: problem.model.mesh.num_nodes(),
        dofs: problem.model.num_dofs(),
        unknowns: problem.num_unknowns(),
        physics: physics_hash(case),
        steps: problem
            .steps
            .iter()
            .map(|s| (s.name.clone(), s.end_time))
            .collect(),
    }
}

/// Whether `a` and `b` name the same folder (compared as given when
/// either does not exist).
fn same_folder(a: &Path, b: &Path) -> bool {
    match (a.canonicalize(), b.canonicalize()) {
        (Ok(a), Ok(b)) => a == b,
        _ => a == b,
    }
}

/// The FNV-1a hash of a case's physics ([`CaseKey::physics`]): the mesh's
/// coordinates (their bits), elements and sets, and the debug form of the
/// case's materials, loads, amplitudes, obstacles and contacts.
fn physics_hash(case: &Case) -> u64 {
    use std::fmt::Write;
    use std::hash::Hasher;
    let mut h = Fnv1a::default();
    let mesh = &case.mesh;
    for x in mesh.nodes.iter().flatten() {
        h.write(&x.to_bits().to_le_bytes());
    }
    for e in &mesh.elements {
        let _ = write!(h, "{:?}", e.kind);
        for &n in &e.nodes {
            h.write(&(n as u64).to_le_bytes());
        }
    }
    let s = &case.spec;
    let _ = write!(
        h,
        "{:?}{:?}{:?}{:?}{:?}{:?}{:?}{:?}{:?}{:?}{:?}",
        mesh.regions,
        mesh.surfaces,
        mesh.node_sets,
        s.material,
        s.displacement,
        s.pressure,
        s.body_force,
        s.nodal_force,
        s.obstacle,
        s.contact,
        s.amplitudes
    );
    h.finish()
}
