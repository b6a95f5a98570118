//! `summary.json`: the machine-readable record of a run, rewritten
//! (atomically) on a geometric schedule of the converged increments
//! ([`super::schedule`]) and at the end of the run, so that it is valid
//! whatever happens later and its cost per increment does not grow with
//! the run.

use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::Path;

/// One converged increment.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
pub struct IncrementSummary {
    /// Step index (0-based) and name.
    pub step: usize,
    pub step_name: String,
    /// Pseudo-time at the end of the increment, and its size.
    pub time: f64,
    pub increment: f64,
    /// Newton iterations (linear solves) of the increment.
    pub iterations: usize,
    /// Relative force residual at the start of every iteration, the last
    /// one being the converged value.
    pub residuals: Vec<f64>,
    /// Relative size of each Newton correction.
    pub corrections: Vec<f64>,
    /// Cuts of the increment before it converged.
    pub cuts: usize,
    /// Wall time of the increment, seconds.
    pub wall_time: f64,
    /// Contact nodes that switched status, per Newton iteration.
    pub switched: Vec<usize>,
    /// Per contact interface: totals at the end of the increment.
    pub contact: BTreeMap<String, InterfaceSummary>,
    /// VTU file of the increment (relative to the output folder); empty
    /// when `[output] every` skipped it.
    pub file: String,
    /// `Σ (f_int − f_ext)` over the nodes of each surface set: the reaction
    /// force where displacements are prescribed.
    pub reaction_forces: BTreeMap<String, [f64; 3]>,
    /// The path that solved the increment, `monolithic` or `condensed`
    /// (its iterations are then the contact solve's active-set or
    /// semismooth Newton iterations, the last residual the evaluation's).
    #[serde(default)]
    pub method: String,
    /// When `auto`'s condensed path failed the increment and Newton's path
    /// solved it again: why the condensed solve failed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub retried: Option<String>,
}

/// Where the time went, seconds.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
pub struct PhaseTimes {
    /// Element kernels, scatter and loads (every residual evaluation,
    /// line-search trials included).
    pub assembly: f64,
    /// Contact search (projection on the obstacles) and contact assembly.
    pub contact: f64,
    /// Symbolic analyses.
    pub symbolic: f64,
    /// Numeric factorisations; with `linear = "petsc"` all of PETSc's
    /// time (the matrix's values put in, the set-up and the solve).
    pub factorisation: f64,
    /// Triangular solves (refinement and Krylov iterations included).
    pub solve: f64,
    /// With `linear = "petsc"` only: of `factorisation`, PETSc's set-up
    /// of its KSP and preconditioner (`KSPSetUp`: MUMPS's factorisation,
    /// GAMG's or fieldsplit's set-up) and its `KSPSolve` (the Krylov
    /// iterations, MUMPS's triangular solves); the rest of
    /// `factorisation` is the matrix's values and the vectors handed to
    /// PETSc. Under `mpirun`, rank 0's.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub petsc_setup: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub petsc_solve: Option<f64>,
}

/// One contact interface at the end of an increment.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
pub struct InterfaceSummary {
    /// Total normal contact force on the body, `Σ A_s t_N n`.
    pub force: [f64; 3],
    /// Total tangential (friction) force on the body, `Σ A_s t_T`.
    pub tangential_force: [f64; 3],
    /// Closed nodes that stick (every closed node without friction) and
    /// that slip.
    pub stick_nodes: usize,
    pub slip_nodes: usize,
    /// Reference area of the closed nodes, `Σ A_s`.
    pub area: f64,
    pub closed_nodes: usize,
    /// Largest penetration `max(0, −g)` over the secondary nodes.
    pub largest_penetration: f64,
    /// With a deformable primary surface: the total contact force on it,
    /// `−Σ A_s (t_N n + t_T) N_i(ξ)` over its nodes (minus `force +
    /// tangential_force`: action and reaction); absent for a rigid obstacle.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub primary_force: Option<[f64; 3]>,
    /// A note where contact could not be evaluated on part of the
    /// interface (a mortar face pair that cannot be integrated leaves every
    /// node open); the log prints it as a `warning:` line.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub warning: Option<String>,
}

/// Totals of one load step over its converged increments.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct StepSummary {
    pub name: String,
    /// Pseudo-time reached in the step.
    pub time: f64,
    pub increments: usize,
    /// Newton iterations of the step's converged increments.
    pub iterations: usize,
    /// Cuts of the increment within the step (after a failed increment,
    /// its cuts too: the count of the run's error message).
    pub cuts: usize,
    /// Wall time of the step's converged increments, seconds.
    pub wall_time: f64,
}

/// The whole run.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
pub struct Summary {
    /// The case file.
    pub case: String,
    /// `running`, `completed` or `failed`.
    pub status: String,
    /// The error, if the run failed.
    pub error: Option<String>,
    pub nodes: usize,
    pub elements: usize,
    pub dofs: usize,
    /// Prescribed (constrained) dofs.
    pub constrained_dofs: usize,
    pub threads: usize,
    /// Wall time since the start of the run, seconds.
    pub wall_time: f64,
    /// Symbolic analyses of the tangent's pattern (1 on a fixed mesh).
    pub symbolic_analyses: usize,
    /// Stored entries of the tangent (at the last converged increment: new
    /// deformable contact pairs change the pattern; on the condensed path
    /// without the contact couplings only Newton's tangent fills, until
    /// Newton first solves) and of its LDLᵀ factor.
    /// Under `mpirun` each process keeps only its own rows' pattern, and
    /// `matrix_nnz` is rank 0's (the log's `rows:` lines give every
    /// process's).
    pub matrix_nnz: usize,
    pub factor_nnz: usize,
    /// Wall time split by phase, seconds (totals of the run so far,
    /// updated after every increment; after a restart, the interrupted
    /// run's included, as in the other totals).
    pub phase_times: PhaseTimes,
    /// Nonsymmetric linear solves: by GMRES (with their Krylov iterations
    /// in total) and by the sparse LU (chosen, or the fallback).
    pub krylov_solves: usize,
    pub krylov_iterations: usize,
    pub lu_solves: usize,
    /// Numeric LDLᵀ factorisations (f64 and f32), of them in f32 (mixed
    /// precision), the iterative refinement steps after their solves, and
    /// the f32 factorisations whose refinement stalled and that were
    /// replaced by an f64 one.
    pub factorisations: usize,
    pub single_factorisations: usize,
    pub refinement_steps: usize,
    pub mixed_precision_fallbacks: usize,
    /// Which path solved the run, `monolithic` (Newton on the whole
    /// system) or `condensed` (one factorisation, the contact problem
    /// solved on the contact nodes: `crate::problem::condensed`), and why
    /// the other one was not taken.
    pub strategy: String,
    pub strategy_reason: String,
    /// Where Newton started each increment on the monolithic path
    /// (`[solver] predictor` resolved: `none`, `secant` or `contact`), and
    /// why (`auto`'s choice, or as asked); empty on the condensed path,
    /// which has no Newton iterations.
    #[serde(default)]
    pub predictor: String,
    #[serde(default)]
    pub predictor_reason: String,
    /// Condensed path: active-set steps (dense Cholesky solves of the
    /// contact problem; with friction, semismooth Newton iterations) of
    /// its converged increments, the sum of their `iterations`; 0 on the
    /// monolithic path.
    pub active_set_iterations: usize,
    /// Increments that `auto`'s condensed path failed and Newton's path
    /// solved again (`increments[i].retried` says why).
    #[serde(default)]
    pub fallback_increments: usize,
    /// Per load step, totals over its increments.
    pub steps: Vec<StepSummary>,
    pub increments: Vec<IncrementSummary>,
}

impl Summary {
    /// Recompute the per-step totals from the increments.
    pub fn update_step_totals(&mut self) {
        let mut steps = Vec::new();
        for inc in &self.increments {
            add_to_steps(&mut steps, inc);
        }
        self.steps = steps;
    }

    /// Add the last increment to the per-step totals that
    /// [`update_step_totals`](Self::update_step_totals) made of the others:
    /// the same totals, in time independent of the run's length.
    pub fn add_last_to_step_totals(&mut self) {
        if let Some(inc) = self.increments.last() {
            add_to_steps(&mut self.steps, inc);
        }
    }

    /// The summary without its increments (every other key as it is):
    /// what the checkpoint stores after each increment beside the new
    /// increment alone, in time independent of the run's length. Every
    /// field is named (no `..`), so a field added to `Summary` must be
    /// added here.
    pub fn head(&self) -> Summary {
        let Summary {
            case,
            status,
            error,
            nodes,
            elements,
            dofs,
            constrained_dofs,
            threads,
            wall_time,
            symbolic_analyses,
            matrix_nnz,
            factor_nnz,
            phase_times,
            krylov_solves,
            krylov_iterations,
            lu_solves,
            factorisations,
            single_factorisations,
            refinement_steps,
            mixed_precision_fallbacks,
            strategy,
            strategy_reason,
            predictor,
            predictor_reason,
            active_set_iterations,
            fallback_increments,
            steps,
            increments: _,
        } = self;
        Summary {
            case: case.clone(),
            status: status.clone(),
            error: error.clone(),
            nodes: *nodes,
            elements: *elements,
            dofs: *dofs,
            constrained_dofs: *constrained_dofs,
            threads: *threads,
            wall_time: *wall_time,
            symbolic_analyses: *symbolic_analyses,
            matrix_nnz: *matrix_nnz,
            factor_nnz: *factor_nnz,
            phase_times: phase_times.clone(),
            krylov_solves: *krylov_solves,
            krylov_iterations: *krylov_iterations,
            lu_solves: *lu_solves,
            factorisations: *factorisations,
            single_factorisations: *single_factorisations,
            refinement_steps: *refinement_steps,
            mixed_precision_fallbacks: *mixed_precision_fallbacks,
            strategy: strategy.clone(),
            strategy_reason: strategy_reason.clone(),
            predictor: predictor.clone(),
            predictor_reason: predictor_reason.clone(),
            active_set_iterations: *active_set_iterations,
            fallback_increments: *fallback_increments,
            steps: steps.clone(),
            increments: Vec::new(),
        }
    }

    /// A summary of a run that starts: the model's sizes, no increment yet.
    pub fn start(case: &str, problem: &crate::problem::Problem) -> Self {
        let mesh = &problem.model.mesh;
        Summary {
            case: case.to_string(),
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
            factorisations: 0,
            single_factorisations: 0,
            refinement_steps: 0,
            mixed_precision_fallbacks: 0,
            strategy: String::new(),
            strategy_reason: String::new(),
            predictor: String::new(),
            predictor_reason: String::new(),
            active_set_iterations: 0,
            fallback_increments: 0,
            steps: Vec::new(),
            increments: Vec::new(),
        }
    }

    /// Write as pretty JSON, atomically (temporary file + rename).
    pub fn write(&self, path: &Path) -> crate::Result<()> {
        let text = serde_json::to_string_pretty(self)
            .map_err(|e| crate::Error::io("write", path, e.into()))?;
        super::write_atomically(path, |w| std::io::Write::write_all(w, text.as_bytes()))
    }
}

/// Add `inc` to the totals of its step, the last of `steps` (or a new one
/// when it starts another step).
fn add_to_steps(steps: &mut Vec<StepSummary>, inc: &IncrementSummary) {
    if steps.last().is_none_or(|s| s.name != inc.step_name) {
        steps.push(StepSummary {
            name: inc.step_name.clone(),
            time: inc.time,
            increments: 0,
            iterations: 0,
            cuts: 0,
            wall_time: 0.0,
        });
    }
    if let Some(s) = steps.last_mut() {
        s.time = inc.time;
        s.increments += 1;
        s.iterations += inc.iterations;
        s.cuts += inc.cuts;
        s.wall_time += inc.wall_time;
    }
}
