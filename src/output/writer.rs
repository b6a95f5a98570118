//! The result files of a run, as an observer: one VTU per converged
//! increment, the PVD collection listing them, the histories and profiles
//! asked for, `summary.json`, the checkpoint and the convergence plot at
//! the end. The listings of every increment so far (`summary.json`, the
//! `.pvd`, the histories) are rewritten on a geometric schedule
//! ([`super::schedule`]) and at the end, and the checkpoint takes one
//! appended record per increment ([`CheckpointFile`]), so an increment's
//! files cost the same at the start of a run and after 10⁵ increments.

use std::borrow::Cow;
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::sync::{Arc, OnceLock};

use super::checkpoint::{self, CaseKey, Checkpoint, CheckpointFile, Increment};
use super::fields::{CellField, ConvergedIncrement, NodalField};
use super::history::History;
use super::manifest::Manifest;
use super::observer::StepObserver;
use super::profile::{file_part, Profile};
use super::pvtu::{data_set_file, IncrementArrays, Pieces};
use super::recovery::PatchRecovery;
use super::schedule::Rewrite;
use super::summary::Summary;
use super::{plot, pvd::PvdCollection, vtu};
use crate::mesh::Mesh;
use crate::{Error, Result};

/// A mesh's encoded VTU points and cells, made once (by whichever of the
/// background job and the first VTU file comes first).
type SharedMeshArrays = Arc<OnceLock<std::io::Result<vtu::MeshArrays>>>;

/// A mesh's VTU points and cells being encoded on the rayon pool it was
/// started from ([`MeshEncoding::start`]), for a [`ResultWriter`] made
/// later ([`ResultWriter::encoded_mesh`]): started while the problem is
/// still being built, the encoding runs on a core that the set-up leaves
/// idle instead of beside the solve's first parallel phase.
#[derive(Clone)]
pub struct MeshEncoding {
    mesh: Arc<Mesh>,
    options: vtu::VtuOptions,
    arrays: SharedMeshArrays,
}

impl MeshEncoding {
    /// Starts encoding `mesh` with `options` (`rayon::spawn`).
    pub fn start(mesh: Arc<Mesh>, options: vtu::VtuOptions) -> Self {
        let arrays = SharedMeshArrays::default();
        let (job_mesh, job_arrays) = (Arc::clone(&mesh), Arc::clone(&arrays));
        rayon::spawn(move || {
            job_arrays.get_or_init(|| vtu::MeshArrays::new(&job_mesh, options));
        });
        MeshEncoding {
            mesh,
            options,
            arrays,
        }
    }
}

/// Writes a run's results into one folder.
pub struct ResultWriter {
    dir: PathBuf,
    /// Every file of the run, claimed before it is first written.
    manifest: Manifest,
    pvd: PvdCollection,
    /// The fields each VTU holds.
    nodal: Vec<NodalField>,
    cells: Vec<CellField>,
    histories: Vec<History>,
    profiles: Vec<Profile>,
    /// zlib compression of the VTU arrays.
    vtu: vtu::VtuOptions,
    /// The series' name (`NAME.checkpoint`).
    name: String,
    /// The case the checkpoint is written for; `None`: no checkpoint.
    case_key: Option<CaseKey>,
    /// The checkpoint file once its first record is due, and how much of
    /// the output its records hold.
    checkpoint: Option<CheckpointFile>,
    recorded: Recorded,
    /// When `summary.json`, the `.pvd` and the histories are rewritten.
    listings: Rewrite,
    /// In a distributed run (rank 0): its piece of each `.pvtu`, which it
    /// writes with the `.pvtu`; `None`: whole `.vtu` files.
    pieces: Option<Pieces>,
    /// The mesh of the VTU files and its points and cells, encoded once
    /// per series ([`Self::prepare_mesh`], else at the first file).
    mesh_arrays: Option<(Arc<Mesh>, vtu::VtuOptions, SharedMeshArrays)>,
    /// The patch recovery weights of the VTU files' mesh, made at the
    /// first file with a recovered field.
    recovery: Option<(Arc<Mesh>, Arc<PatchRecovery>)>,
    /// Whether the reference state (`NAME_0000.vtu`, t = 0) is still to be
    /// written, before the first increment's file.
    reference_pending: bool,
    /// Newton's relative residual tolerance, drawn in the convergence plot.
    residual_tolerance: Option<f64>,
}

/// The reference state's VTU file of the series `name`: `NAME_0000.vtu`
/// (the increments' files count from 1).
pub fn reference_file(name: &str) -> String {
    format!("{name}_0000.vtu")
}

/// What a restart restores of the result files: the increments so far
/// (`summary.json`'s, whose VTU files the `.pvd` lists again), the
/// histories' samples and the profiles' tables.
pub struct Restored<'a> {
    pub summary: &'a Summary,
    pub histories: Vec<Vec<(f64, Vec<f64>)>>,
    pub profiles: Vec<Vec<super::profile::StepProfile>>,
}

/// What a series holds: the VTU files' nodal and cell fields, the
/// histories and the profiles.
pub struct SeriesContent {
    pub nodal: Vec<NodalField>,
    pub cells: Vec<CellField>,
    pub histories: Vec<History>,
    pub profiles: Vec<Profile>,
}

impl ResultWriter {
    /// A writer into `dir` (created if needed) for the series `name`: the
    /// files of an earlier run with that name (its `NAME.manifest`) and
    /// leftover temporary files are removed, `summary.json` and the `.pvd`
    /// first, so the folder never lists files that are gone
    /// ([`Manifest::take_over`]); then an empty `.pvd` is written. The
    /// manifest also claims `NAME.log`, which [`LogWriter`](super::LogWriter)
    /// writes. `content.nodal` and `content.cells` choose the fields of the
    /// VTU files (contact fields are left out of a problem without contact).
    pub fn new(dir: &Path, name: &str, content: SeriesContent) -> Result<Self> {
        std::fs::create_dir_all(dir).map_err(|e| Error::io("create output folder", dir, e))?;
        let manifest = Manifest::take_over(dir, name)?;
        let mut writer = Self::open(dir, name, manifest, content, Vec::new())?;
        writer.reference_pending = true;
        Ok(writer)
    }

    /// A writer that goes on with the series `name` in `dir` after a
    /// restart ([`Manifest::resume`]): the earlier files stay, the `.pvd`
    /// lists the VTU files of `restored.summary` again, and the histories
    /// and profiles start from their restored samples and tables (matched
    /// to `histories` and `profiles` by position; the caller checks the
    /// counts).
    pub fn resume(
        dir: &Path,
        name: &str,
        mut content: SeriesContent,
        restored: Restored,
    ) -> Result<Self> {
        // the reference state's frame, if the first run wrote one, first
        let reference = reference_file(name);
        let files: Vec<(f64, String)> = dir
            .join(&reference)
            .is_file()
            .then_some((0.0, reference))
            .into_iter()
            .chain(
                restored
                    .summary
                    .increments
                    .iter()
                    .filter(|i| !i.file.is_empty())
                    .map(|i| (i.time, i.file.clone())),
            )
            .collect();
        // before any file is touched: the samples fit the histories
        for (h, samples) in content.histories.iter().zip(&restored.histories) {
            h.check_restored(samples)
                .map_err(|message| Error::Restart {
                    path: checkpoint::path(dir, name),
                    message,
                })?;
        }
        let keep: BTreeSet<String> = files.iter().map(|(_, f)| f.clone()).collect();
        let manifest = Manifest::resume(dir, name, &keep)?;
        for (h, samples) in content.histories.iter_mut().zip(restored.histories) {
            h.samples = samples;
        }
        for (p, steps) in content.profiles.iter_mut().zip(restored.profiles) {
            p.steps = steps;
        }
        Self::open(dir, name, manifest, content, files)
    }

    /// The writer of [`new`](Self::new) and [`resume`](Self::resume): it
    /// claims the log and the `.pvd`, and writes the `.pvd` listing `files`
    /// (time, VTU file).
    fn open(
        dir: &Path,
        name: &str,
        mut manifest: Manifest,
        content: SeriesContent,
        files: Vec<(f64, String)>,
    ) -> Result<Self> {
        let SeriesContent {
            nodal,
            cells,
            histories,
            profiles,
        } = content;
        manifest.claim(&format!("{name}.log"))?;
        let pvd_file = format!("{name}.pvd");
        manifest.claim(&pvd_file)?;
        let mut pvd = PvdCollection::new(dir.join(pvd_file));
        for (time, file) in files {
            pvd.push(time, file);
        }
        pvd.write()?;
        Ok(ResultWriter {
            dir: dir.to_path_buf(),
            manifest,
            pvd,
            nodal,
            cells,
            histories,
            profiles,
            vtu: vtu::VtuOptions { compress: true },
            name: name.to_string(),
            case_key: None,
            checkpoint: None,
            recorded: Recorded::default(),
            listings: Rewrite::default(),
            pieces: None,
            mesh_arrays: None,
            recovery: None,
            reference_pending: false,
            residual_tolerance: None,
        })
    }

    /// Encode `mesh`'s VTU points and cells now, on the run's threads
    /// (`rayon::spawn`), while the problem is solved: the first VTU file
    /// then only writes them (or waits for them). Call it after
    /// [`Self::compress`].
    pub fn prepare_mesh(self, mesh: Arc<Mesh>) -> Self {
        let encoding = MeshEncoding::start(mesh, self.vtu);
        self.encoded_mesh(encoding)
    }

    /// The VTU files' mesh and its points and cells as `encoding` makes
    /// them (started earlier, [`MeshEncoding::start`]); the first file
    /// encodes them afresh if the writer's options are not the
    /// encoding's. Call it after [`Self::compress`].
    pub fn encoded_mesh(mut self, encoding: MeshEncoding) -> Self {
        self.mesh_arrays = Some((encoding.mesh, encoding.options, encoding.arrays));
        self
    }

    /// The shared encoded points and cells of `mesh` in this writer's
    /// form, made empty when new.
    fn arrays_of(&mut self, mesh: &Arc<Mesh>) -> SharedMeshArrays {
        let options = self.vtu;
        match &self.mesh_arrays {
            Some((m, o, arrays)) if Arc::ptr_eq(m, mesh) && *o == options => Arc::clone(arrays),
            _ => {
                let arrays = SharedMeshArrays::default();
                self.mesh_arrays = Some((Arc::clone(mesh), options, Arc::clone(&arrays)));
                arrays
            }
        }
    }

    /// The patch recovery of `mesh`, made once per mesh; `None` when no
    /// VTU field is recovered.
    fn recovery_of(&mut self, mesh: &Arc<Mesh>) -> Option<Arc<PatchRecovery>> {
        if !self.nodal.iter().any(|f| f.is_recovered()) {
            return None;
        }
        match &self.recovery {
            Some((m, r)) if Arc::ptr_eq(m, mesh) => Some(Arc::clone(r)),
            _ => {
                let r = Arc::new(PatchRecovery::new(mesh));
                self.recovery = Some((Arc::clone(mesh), Arc::clone(&r)));
                Some(r)
            }
        }
    }

    /// Write `NAME.checkpoint` after every increment, for the case `key`
    /// (a restart resumes from it).
    pub fn checkpoint(mut self, key: CaseKey) -> Self {
        self.case_key = Some(key);
        self
    }

    /// Write each data set as a `.pvtu` over one piece per process, this
    /// process (rank 0) writing its own piece (a distributed run; the
    /// summary names `.pvtu` files then).
    pub fn pieces(mut self, pieces: Pieces) -> Self {
        self.pieces = Some(pieces);
        self
    }

    /// Draw Newton's relative residual `tolerance` (`[solver]
    /// residual_tolerance`) in the convergence plot.
    pub fn residual_tolerance(mut self, tolerance: f64) -> Self {
        self.residual_tolerance = Some(tolerance);
        self
    }

    /// Write the VTU arrays compressed (the default) or not.
    pub fn compress(mut self, compress: bool) -> Self {
        self.vtu.compress = compress;
        self
    }

    /// The output folder.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// The VTU file of an increment, with the chosen fields (or, in a
    /// distributed run, the `.pvtu` and this process's piece).
    fn write_vtu(&mut self, increment: &ConvergedIncrement, file: &str) -> Result<()> {
        // a piece's recovery was made on the whole mesh, which this
        // process may no longer hold
        let recovery = match &self.pieces {
            Some(pieces) => pieces.recovery.clone(),
            None => self.recovery_of(&increment.problem.model.mesh),
        };
        let arrays = IncrementArrays::new(increment, &self.nodal, &self.cells, recovery.as_deref());
        let (point_data, cell_data) = (arrays.points(), arrays.cells());
        self.manifest.claim(file)?;
        let mesh = &increment.problem.model.mesh;
        let Some(pieces) = &self.pieces else {
            return self.write_whole(mesh, file, &point_data, &cell_data);
        };
        for rank in 0..pieces.parts {
            self.manifest.claim(&Pieces::piece_file(file, rank))?;
        }
        pieces.write_piece(&self.dir, file, mesh, &point_data, &cell_data, self.vtu)?;
        pieces.write_pvtu(&self.dir, file, &point_data, &cell_data)
    }

    /// The reference state's VTU file (`NAME_0000.vtu`, t = 0: the mesh
    /// before any load, [`IncrementArrays::reference`]), listed first in
    /// the `.pvd`.
    fn write_reference(&mut self, increment: &ConvergedIncrement) -> Result<()> {
        let file = reference_file(&self.name);
        self.manifest.claim(&file)?;
        let problem = increment.problem;
        let mesh = &problem.model.mesh;
        let arrays = IncrementArrays::reference(
            mesh,
            !problem.contacts.is_empty(),
            &self.nodal,
            &self.cells,
        );
        self.write_whole(mesh, &file, &arrays.points(), &arrays.cells())?;
        self.pvd.add(0.0, &file)
    }

    /// A whole `.vtu` file of `mesh` (its points and cells encoded once
    /// per series) with the arrays given.
    fn write_whole(
        &mut self,
        mesh: &Arc<Mesh>,
        file: &str,
        point_data: &[vtu::Field],
        cell_data: &[vtu::Field],
    ) -> Result<()> {
        let path = self.dir.join(file);
        let options = self.vtu;
        let shared = self.arrays_of(mesh);
        let arrays = shared
            .get_or_init(|| vtu::MeshArrays::new(mesh, options))
            .as_ref()
            .map_err(|e| Error::io("write", &path, std::io::Error::new(e.kind(), e.to_string())))?;
        vtu::write_vtu_on(&path, arrays, point_data, cell_data)
    }

    /// Histories' samples after every increment (their files written with
    /// the other listings, [`Self::write_listings`]); profiles at the end
    /// of a step.
    fn write_requests(&mut self, increment: &ConvergedIncrement) -> Result<()> {
        let record = increment.record;
        let reports = &increment.contact_fields.reports;
        for h in &mut self.histories {
            h.record(record.time, increment.unknowns, increment.residual, reports);
        }
        if record.time == increment.problem.steps[record.step].end_time {
            for p in &mut self.profiles {
                let csv = format!("{}_{}.csv", p.name, file_part(&record.step_name));
                self.manifest.claim(&csv)?;
                self.manifest.claim(&format!("{}.svg", p.name))?;
                p.record(&record.step_name, record.time, &reports[p.interface]);
                p.write(&self.dir)?;
            }
        }
        Ok(())
    }

    /// The files that list every increment so far: the histories (once
    /// they have a sample), the `.pvd` and `summary.json` (last: the files
    /// it names are there).
    fn write_listings(&mut self, summary: &Summary) -> Result<()> {
        for h in self.histories.iter().filter(|h| !h.samples.is_empty()) {
            self.manifest.claim(&format!("{}.csv", h.name))?;
            self.manifest.claim(&format!("{}.svg", h.name))?;
            h.write(&self.dir)?;
        }
        self.pvd.write()?;
        summary.write(&self.dir.join("summary.json"))?;
        self.listings.wrote(summary.increments.len());
        Ok(())
    }
}

impl StepObserver for ResultWriter {
    fn on_start(&mut self, summary: &Summary) -> Result<()> {
        self.manifest.claim("summary.json")?;
        summary.write(&self.dir.join("summary.json"))
    }

    fn on_increment(&mut self, increment: &ConvergedIncrement, summary: &Summary) -> Result<()> {
        if std::mem::take(&mut self.reference_pending) && self.pieces.is_none() {
            self.write_reference(increment)?;
        }
        let file = data_set_file(summary);
        // `[output] every` leaves some increments without a file
        if !file.is_empty() {
            self.write_vtu(increment, &file)?;
            self.pvd.push(increment.record.time, file);
        }
        self.write_requests(increment)?;
        if self.listings.due(summary.increments.len()) {
            self.write_listings(summary)?;
        }
        self.write_checkpoint(increment, summary)
    }

    fn on_finish(&mut self, summary: &Summary) -> Result<()> {
        self.write_listings(summary)?;
        let steps: Vec<plot::StepResiduals> = summary
            .increments
            .iter()
            .map(|i| plot::StepResiduals {
                label: format!("{} t={:.4}", i.step_name, i.time),
                time: i.time,
                residuals: i.residuals.clone(),
            })
            .collect();
        self.manifest.claim("convergence.svg")?;
        plot::write_convergence_plot_with_tolerance(
            &self.dir.join("convergence.svg"),
            &steps,
            self.residual_tolerance,
        )
    }
}

/// How much of the output the checkpoint's records hold: the increments
/// of the summary, the samples of each history, the tables of each profile.
#[derive(Debug, Default)]
struct Recorded {
    increments: usize,
    samples: Vec<usize>,
    tables: Vec<usize>,
}

impl ResultWriter {
    /// `NAME.checkpoint` after the increment's other files: the state to
    /// resume from, a whole record when [`CheckpointFile`] wants one, else
    /// this increment's record appended.
    fn write_checkpoint(
        &mut self,
        increment: &ConvergedIncrement,
        summary: &Summary,
    ) -> Result<()> {
        let Some(key) = &self.case_key else {
            return Ok(());
        };
        if self.checkpoint.is_none() {
            let file = format!("{}.checkpoint", self.name);
            self.manifest.claim(&file)?;
            self.checkpoint = Some(CheckpointFile::new(self.dir.join(file)));
        }
        let Some(file) = self.checkpoint.as_mut() else {
            return Ok(());
        };
        let path = file.path().to_path_buf();
        if file.wants_whole() {
            let content = Checkpoint {
                case: Cow::Borrowed(key),
                unknowns: Cow::Borrowed(increment.unknowns),
                contact: Cow::Borrowed(increment.contact),
                stepping: Cow::Borrowed(increment.stepping),
                summary: to_json(summary, &path)?,
                histories: self
                    .histories
                    .iter()
                    .map(|h| Cow::Borrowed(&h.samples[..]))
                    .collect(),
                profiles: self
                    .profiles
                    .iter()
                    .map(|p| Cow::Borrowed(&p.steps[..]))
                    .collect(),
            };
            file.write_whole(&content)?;
        } else {
            let recorded = &self.recorded;
            let content = Increment {
                unknowns: Cow::Borrowed(increment.unknowns),
                contact: Cow::Borrowed(increment.contact),
                stepping: Cow::Borrowed(increment.stepping),
                summary_head: to_json(&summary.head(), &path)?,
                increments: summary.increments[recorded.increments..]
                    .iter()
                    .map(|i| to_json(i, &path))
                    .collect::<Result<_>>()?,
                samples: (self.histories.iter().zip(&recorded.samples))
                    .map(|(h, &n)| Cow::Borrowed(&h.samples[n..]))
                    .collect(),
                profiles: (self.profiles.iter().zip(&recorded.tables))
                    .map(|(p, &n)| Cow::Borrowed(&p.steps[n..]))
                    .collect(),
            };
            file.append(&content)?;
        }
        self.recorded = Recorded {
            increments: summary.increments.len(),
            samples: self.histories.iter().map(|h| h.samples.len()).collect(),
            tables: self.profiles.iter().map(|p| p.steps.len()).collect(),
        };
        Ok(())
    }
}

/// `value` as JSON text (an error about writing `path` if it has none).
fn to_json<T: serde::Serialize>(value: &T, path: &Path) -> Result<String> {
    serde_json::to_string(value).map_err(|e| Error::io("write", path, e.into()))
}
