//! A whole run, reading like a table of contents: load the case → read the
//! mesh → build the problem → for each step: Newton increments → write each
//! converged increment → summary and plot.

use crate::case::{self, Case};
use crate::contact::friction::ContactStatus;
use crate::contact::interface::{ContactInterface, NodeReport, Primary};
use crate::contact::laws::NodeContactState;
use crate::contact::primary::PrimarySurface;
use crate::output::summary::{IncrementSummary, Summary};
use crate::output::summary::{InterfaceSummary, PhaseTimes};
use crate::output::{plot, pvd::PvdCollection, vtu};
use crate::problem::{ContactState, Problem};
use crate::solve::linear::SparseLdlt;
use crate::solve::stepping::{run_steps, IncrementRecord, StepObserver};
use crate::{Error, Result};
use indicatif::{ProgressBar, ProgressStyle};
use nalgebra::Vector3;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Command-line choices of a run.
#[derive(Clone, Debug, Default)]
pub struct RunOptions {
    /// Output folder (overrides the case file's).
    pub output: Option<PathBuf>,
    /// No progress bar, no log lines.
    pub quiet: bool,
}

/// What a finished run leaves.
#[derive(Debug)]
pub struct RunOutcome {
    pub output_dir: PathBuf,
    pub summary: Summary,
    /// Final displacement of every dof.
    pub displacement: Vec<f64>,
    /// Contact history committed with the last converged increment
    /// (Uzawa multipliers, slack unknowns, friction's tangential traction
    /// and slip).
    pub contact: ContactState,
}

/// Run a case file end to end. On failure the converged increments, the
/// `.pvd` and a `summary.json` with `status = "failed"` stay in the output
/// folder.
pub fn run(case_path: &Path, options: &RunOptions) -> Result<RunOutcome> {
    let start = Instant::now();
    let case = case::load(case_path)?;
    let mut problem = case.build_problem()?;
    let output_dir = case.output_dir(options.output.as_deref());
    let mut writer = Writer::new(&case, &problem, &output_dir, options.quiet, start)?;
    writer.log_requests(&problem);
    let mut solver = SparseLdlt::new(fill_reducing_ordering(&problem)?, 0);
    let result = run_steps(&mut problem, &mut solver, &mut writer, output_dir.clone());
    writer.progress.finish_and_clear();
    writer.summary.symbolic_analyses = solver.timings.analyses;
    writer.summary.phase_times = PhaseTimes {
        assembly: problem.timings.assembly(),
        contact: problem.timings.contact(),
        symbolic: solver.timings.symbolic_total.as_secs_f64(),
        factorisation: (solver.timings.numeric_total + solver.lu.total).as_secs_f64(),
        solve: solver.timings.solve_total.as_secs_f64(),
    };
    writer.summary.factor_nnz = solver.factor_nnz();
    writer.summary.krylov_solves = solver.timings.krylov_solves;
    writer.summary.krylov_iterations = solver.timings.krylov_iterations;
    writer.summary.lu_solves = solver.timings.lu_solves;
    writer.summary.wall_time = start.elapsed().as_secs_f64();
    match result {
        Ok(displacement) => {
            writer.summary.status = "completed".into();
            writer.finish()?;
            Ok(RunOutcome {
                output_dir,
                summary: writer.summary,
                displacement,
                contact: writer.contact,
            })
        }
        Err(e) => {
            writer.summary.status = "failed".into();
            writer.summary.error = Some(e.to_string());
            // keep what converged; the original error matters more than a
            // failure to write the failure report
            let _ = writer.finish();
            Err(e)
        }
    }
}

/// Writes every converged increment (VTU, PVD, summary) and reports progress.
struct Writer {
    dir: PathBuf,
    name: String,
    pvd: PvdCollection,
    summary: Summary,
    progress: ProgressBar,
    quiet: bool,
    last: Instant,
    start: Instant,
    contact: ContactState,
    /// `[[output.history]]` and `[[output.profile]]`.
    requests: crate::case::output::OutputRequests,
}

impl Writer {
    fn new(
        case: &Case,
        problem: &Problem,
        dir: &Path,
        quiet: bool,
        start: Instant,
    ) -> Result<Self> {
        std::fs::create_dir_all(dir).map_err(|e| Error::io("create output folder", dir, e))?;
        let name = case.output_name();
        let requests = case.output_requests(problem)?;
        remove_old_series(dir, &name)?;
        // an empty series at once: a .pvd of an earlier run must not list
        // files that are gone
        let pvd = PvdCollection::new(dir.join(format!("{name}.pvd")));
        pvd.write()?;
        let mesh = &problem.model.mesh;
        let progress = if quiet {
            ProgressBar::hidden()
        } else {
            let bar = ProgressBar::new(1000);
            bar.set_style(
                ProgressStyle::with_template("{spinner} [{elapsed_precise}] {bar:40} t = {msg}")
                    .expect("valid template"),
            );
            bar
        };
        let summary = Summary {
            case: case.path.display().to_string(),
            status: "running".into(),
            error: None,
            nodes: mesh.num_nodes(),
            elements: mesh.elements.len(),
            dofs: problem.model.num_dofs(),
            constrained_dofs: problem.constrained_dofs().iter().filter(|&&c| c).count(),
            threads: rayon::current_num_threads(),
            wall_time: 0.0,
            symbolic_analyses: 0,
            matrix_nnz: problem.model.pattern.nnz(),
            factor_nnz: 0,
            phase_times: Default::default(),
            krylov_solves: 0,
            krylov_iterations: 0,
            lu_solves: 0,
            steps: Vec::new(),
            increments: Vec::new(),
        };
        Ok(Writer {
            pvd,
            dir: dir.to_path_buf(),
            name,
            summary,
            progress,
            quiet,
            last: Instant::now(),
            start,
            contact: ContactState::default(),
            requests,
        })
    }

    /// Log which node each history reads.
    fn log_requests(&self, problem: &Problem) {
        for h in &self.requests.histories {
            self.log(format!(
                "history '{}': {} {}",
                h.name,
                h.label,
                h.location(&problem.model.mesh.nodes)
            ));
        }
        for p in &self.requests.profiles {
            self.log(format!(
                "profile '{}': {} nodes of interface '{}'",
                p.name,
                p.nodes.len(),
                p.interface_name
            ));
        }
    }

    /// Histories after every increment; profiles at the end of a step.
    fn write_requests(
        &mut self,
        problem: &Problem,
        record: &IncrementRecord,
        u: &[f64],
        residual: &[f64],
        reports: &[Vec<NodeReport>],
    ) -> Result<()> {
        for h in &mut self.requests.histories {
            h.record(record.time, u, residual, reports);
            h.write(&self.dir)?;
        }
        if record.time == problem.steps[record.step].end_time {
            for p in &mut self.requests.profiles {
                p.record(&record.step_name, record.time, &reports[p.interface]);
                p.write(&self.dir)?;
            }
        }
        Ok(())
    }

    fn log(&self, line: String) {
        if self.quiet {
            return;
        }
        if self.progress.is_hidden() {
            eprintln!("{line}");
        } else {
            self.progress.println(line);
        }
    }

    /// Final summary and convergence plot.
    fn finish(&mut self) -> Result<()> {
        self.summary.wall_time = self.start.elapsed().as_secs_f64();
        self.summary.write(&self.dir.join("summary.json"))?;
        let steps: Vec<plot::StepResiduals> = self
            .summary
            .increments
            .iter()
            .map(|i| plot::StepResiduals {
                label: format!("{} t={:.4}", i.step_name, i.time),
                residuals: i.residuals.clone(),
            })
            .collect();
        plot::write_convergence_plot(&self.dir.join("convergence.svg"), &steps)
    }
}

impl StepObserver for Writer {
    fn on_converged(
        &mut self,
        problem: &Problem,
        record: &IncrementRecord,
        u: &[f64],
        residual: &[f64],
        contact: &ContactState,
    ) -> Result<()> {
        self.contact.clone_from(contact);
        // deformable contact may have rebuilt the pattern with new pairs
        self.summary.matrix_nnz = problem.model.pattern.nnz();
        let index = self.summary.increments.len() + 1;
        let file = format!("{}_{index:04}.vtu", self.name);
        let stresses = problem.model.cauchy_stresses(u);
        let cauchy: Vec<f64> = stresses
            .iter()
            .flat_map(|s| s.transpose().iter().copied().collect::<Vec<_>>())
            .collect();
        let von_mises: Vec<f64> = stresses.iter().map(crate::material::von_mises).collect();
        let displacement = &u[..problem.model.num_dofs()];
        let contact_fields = ContactFields::new(problem, record.time, u, contact)?;
        let mut point_data = vec![vtu::Field {
            name: "displacement",
            components: 3,
            values: displacement,
        }];
        if !problem.contacts.is_empty() {
            point_data.extend([
                vtu::Field {
                    name: "contact_pressure",
                    components: 1,
                    values: &contact_fields.pressure,
                },
                vtu::Field {
                    name: "gap",
                    components: 1,
                    values: &contact_fields.gap,
                },
                vtu::Field {
                    name: "contact_status",
                    components: 1,
                    values: &contact_fields.status,
                },
                vtu::Field {
                    name: "contact_traction",
                    components: 3,
                    values: &contact_fields.traction,
                },
                vtu::Field {
                    name: "slip",
                    components: 3,
                    values: &contact_fields.slip,
                },
            ]);
        }
        vtu::write_vtu(
            &self.dir.join(&file),
            &problem.model.mesh,
            &point_data,
            &[
                vtu::Field {
                    name: "cauchy_stress",
                    components: 9,
                    values: &cauchy,
                },
                vtu::Field {
                    name: "von_mises",
                    components: 1,
                    values: &von_mises,
                },
            ],
        )?;
        self.pvd.add(record.time, &file)?;
        self.write_requests(problem, record, u, residual, &contact_fields.reports)?;
        let reaction_forces = problem.surface_forces(residual).into_iter().collect();
        let now = Instant::now();
        let final_residual = record.newton.last().map(|r| r.residual).unwrap_or(0.0);
        self.summary.increments.push(IncrementSummary {
            step: record.step,
            step_name: record.step_name.clone(),
            time: record.time,
            increment: record.increment,
            iterations: record.iterations,
            residuals: record.newton.iter().map(|r| r.residual).collect(),
            corrections: record.newton.iter().map(|r| r.correction).collect(),
            cuts: record.cuts,
            wall_time: (now - self.last).as_secs_f64(),
            switched: record.newton.iter().map(|r| r.switched).collect(),
            contact: contact_fields.summaries,
            file,
            reaction_forces,
        });
        self.last = now;
        self.summary.wall_time = self.start.elapsed().as_secs_f64();
        self.summary.write(&self.dir.join("summary.json"))?;
        let end = problem.steps.last().map(|s| s.end_time).unwrap_or(1.0);
        self.progress
            .set_position((1000.0 * record.time / end) as u64);
        self.progress
            .set_message(format!("{:.4} ({})", record.time, record.step_name));
        self.log(format!(
            "step '{}'  t = {:.6}  Δt = {:.3e}  iterations {:2}  residual {:.2e}",
            record.step_name, record.time, record.increment, record.iterations, final_residual
        ));
        Ok(())
    }

    fn on_cut(&mut self, step: &str, time: f64, increment: f64, reason: &str) {
        self.log(format!(
            "step '{step}'  t = {time:.6}  Δt = {increment:.3e}  not converged ({reason}): cutting the increment"
        ));
    }
}

/// Nodal contact output of every interface, and its totals.
struct ContactFields {
    /// Contact pressure: at a node of a contact surface, the normal force
    /// that every interface puts on it (`A_s t_N` as a secondary node, the
    /// shares `N_i(ξ) A_s t_N` as a primary node) over its tributary area;
    /// `t_N` at the secondary nodes of one pass, the sum of the two passes'
    /// shares with `two_pass`. 0 elsewhere.
    pressure: Vec<f64>,
    /// The normal force and tributary area behind `pressure`.
    nodal_force: Vec<f64>,
    nodal_area: Vec<f64>,
    /// Signed gap at secondary nodes, NaN elsewhere.
    gap: Vec<f64>,
    /// 0 open, 1 stick (closed, without friction), 2 slip (0 away from
    /// contact surfaces).
    status: Vec<f64>,
    /// Traction on the body, `t_N n + t_T` (3 per node, 0 elsewhere):
    /// the nodal contact force of every pass until divided by `nodal_area`.
    traction: Vec<f64>,
    /// Whether the node is a secondary node of some interface (its own
    /// gap and slip then win over those seen from a primary side).
    secondary: Vec<bool>,
    /// Accumulated slip vector (3 per node, 0 elsewhere).
    slip: Vec<f64>,
    summaries: std::collections::BTreeMap<String, InterfaceSummary>,
    /// Every secondary node of every interface.
    reports: Vec<Vec<NodeReport>>,
}

impl ContactFields {
    fn new(problem: &Problem, t: f64, x: &[f64], contact: &ContactState) -> Result<Self> {
        let n = problem.model.mesh.num_nodes();
        let mut fields = ContactFields {
            pressure: vec![0.0; n],
            nodal_force: vec![0.0; n],
            nodal_area: vec![0.0; n],
            gap: vec![f64::NAN; n],
            status: vec![0.0; n],
            traction: vec![0.0; 3 * n],
            secondary: vec![false; n],
            slip: vec![0.0; 3 * n],
            summaries: Default::default(),
            reports: Vec::new(),
        };
        if problem.contacts.is_empty() {
            return Ok(fields);
        }
        let (_, mut reports) =
            problem
                .residual_in(t, x, contact, None)
                .map_err(|f| Error::Case {
                    path: PathBuf::new(),
                    message: problem.describe_failure(&f),
                })?;
        for ((c, nodes), states) in problem
            .contacts
            .iter()
            .zip(&mut reports)
            .zip(&contact.interfaces)
        {
            let mut summary = InterfaceSummary::default();
            let mesh = &problem.model.mesh;
            let set = mesh.surface(&c.surface).expect("validated");
            let (_, whole) = crate::contact::tributary_areas(mesh, set);
            for ((((&s, &area), r), state), &whole) in c
                .nodes
                .iter()
                .zip(&c.areas)
                .zip(nodes.iter_mut())
                .zip(states)
                .zip(&whole)
            {
                // status and tangential traction as committed for this
                // increment (re-evaluated from the committed history, a
                // slipping node would sit exactly on the Coulomb cone and
                // may read as stick), for every consumer of the reports
                let history = &state.friction;
                r.status = history.status;
                r.tangential_traction = history.traction.into();
                fields.nodal_force[s] += area * r.pressure;
                fields.nodal_area[s] = whole;
                fields.gap[s] = r.gap;
                fields.secondary[s] = true;
                fields.status[s] = fields.status[s].max(history.status.code() as f64);
                for d in 0..3 {
                    summary.force[d] += r.force[d];
                    summary.tangential_force[d] += area * history.traction[d];
                    // a force here, a traction once every pass has added its share
                    fields.traction[3 * s + d] += r.force[d] + area * history.traction[d];
                    fields.slip[3 * s + d] = history.slip[d];
                }
                match history.status {
                    ContactStatus::Open => {}
                    ContactStatus::Stick => summary.stick_nodes += 1,
                    ContactStatus::Slip => summary.slip_nodes += 1,
                }
                if r.active {
                    summary.closed_nodes += 1;
                    summary.area += area;
                }
                summary.largest_penetration = summary.largest_penetration.max(-r.gap);
            }
            if let Primary::Surface(p) = &c.primary {
                summary.primary_force =
                    Some(fields.add_primary_side(problem, c, p, x, states, nodes));
            }
            fields.summaries.insert(c.name.clone(), summary);
        }
        for (((p, f), t), a) in fields
            .pressure
            .iter_mut()
            .zip(&fields.nodal_force)
            .zip(fields.traction.chunks_exact_mut(3))
            .zip(&fields.nodal_area)
        {
            if *a > 0.0 {
                *p = f / a;
                t.iter_mut().for_each(|t| *t /= a);
            }
        }
        fields.reports = reports;
        Ok(fields)
    }
}

impl ContactFields {
    /// The output fields on the nodes of a deformable primary surface:
    /// each secondary node's force `A_s (t_N n + t_T)` goes, opposite, to
    /// its triangle's nodes with the weights `N_i(ξ)` (divided by the
    /// primary node's tributary area for `contact_pressure` and
    /// `contact_traction`); `contact_status` is the largest status of the
    /// closed secondary nodes over a primary node, `slip` minus their slip
    /// averaged with the weights `A_s N_i`, and `gap` the primary node's
    /// distance to the secondary surface (projected on its triangles; NaN
    /// beyond its edge or farther than the search margin); a node that is itself secondary in another pass
    /// keeps its own gap and slip. Returns the total force on the primary
    /// surface.
    fn add_primary_side(
        &mut self,
        problem: &Problem,
        c: &ContactInterface,
        primary: &PrimarySurface,
        x: &[f64],
        states: &[NodeContactState],
        reports: &[NodeReport],
    ) -> [f64; 3] {
        let mesh = &problem.model.mesh;
        let reference = &mesh.nodes;
        let n_nodes = mesh.num_nodes();
        let mut normal = vec![0.0; n_nodes];
        let mut forces = vec![Vector3::zeros(); n_nodes];
        let mut slip = vec![(Vector3::zeros(), 0.0); n_nodes];
        let mut status = vec![0u8; n_nodes];
        let mut total = Vector3::zeros();
        for ((r, &area), state) in reports.iter().zip(&c.areas).zip(states) {
            let Some(facet) = r.facet else {
                continue;
            };
            // the committed tangential traction, as on the secondary side
            let history = &state.friction;
            let force = -(Vector3::from(r.force) + area * history.traction);
            for (&n, &weight) in primary.triangles[facet].iter().zip(&r.weights) {
                normal[n] += area * r.pressure * weight;
                forces[n] += force * weight;
                // the closed nodes over the primary node, by their weights
                // (clamped: a node just off its triangle has one below 0)
                if r.active && weight > 0.0 {
                    slip[n].0 -= history.slip * (area * weight);
                    slip[n].1 += area * weight;
                    status[n] = status[n].max(history.status.code());
                }
            }
            total += force;
        }
        let set = mesh.surface(&primary.surface).expect("validated");
        let (nodes, areas) = crate::contact::tributary_areas(mesh, set);
        // the other way round, for the gap: the primary nodes against the
        // secondary surface's triangles
        let mut reverse = PrimarySurface::from_mesh(mesh, &c.surface).expect("validated");
        reverse.refresh(reference, x, &nodes, 0.0);
        for (k, (&n, &a)) in nodes.iter().zip(&areas).enumerate() {
            self.nodal_force[n] += normal[n];
            self.nodal_area[n] = a;
            let (slip_sum, weight) = slip[n];
            for (d, force) in forces[n].iter().enumerate() {
                self.traction[3 * n + d] += force;
                if weight > 0.0 && !self.secondary[n] {
                    self.slip[3 * n + d] = slip_sum[d] / weight;
                }
            }
            self.status[n] = self.status[n].max(status[n] as f64);
            if !self.secondary[n] {
                let here = PrimarySurface::position(reference, x, n);
                if let Some((_, g)) = reverse.nearest_gap(reference, x, k, &here) {
                    self.gap[n] = g.gap;
                }
            }
        }
        total.into()
    }
}

pub use crate::solve::ordering::fill_reducing_ordering;

/// Remove VTU files of an earlier run with the same name, so the folder
/// holds one consistent series.
fn remove_old_series(dir: &Path, name: &str) -> Result<()> {
    let entries = std::fs::read_dir(dir).map_err(|e| Error::io("list output folder", dir, e))?;
    for entry in entries.flatten() {
        let file = entry.file_name().to_string_lossy().into_owned();
        let ours = file
            .strip_prefix(&format!("{name}_"))
            .and_then(|rest| rest.strip_suffix(".vtu"))
            .is_some_and(|n| n.chars().all(|c| c.is_ascii_digit()));
        if ours {
            std::fs::remove_file(entry.path())
                .map_err(|e| Error::io("remove old result", entry.path(), e))?;
        }
    }
    Ok(())
}
