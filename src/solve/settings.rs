//! What the nonlinear solve is told: Newton and stepping controls, the
//! linear solver to use, and the load steps (the `[solver]` and `[[step]]`
//! sections of the case file, once resolved).

/// One load step: pseudo-time runs from the end of the previous step to
/// `end_time` in increments chosen adaptively.
#[derive(Clone, Debug)]
pub struct Step {
    pub name: String,
    pub end_time: f64,
    pub initial_increment: f64,
    pub min_increment: f64,
    pub max_increment: f64,
}

/// Newton and stepping controls.
#[derive(Clone, Debug)]
pub struct SolverSettings {
    /// Newton iterations before an increment is cut.
    pub max_iterations: usize,
    /// Converged when `‖r‖ ≤ residual_tolerance · max(‖f_ext‖, ‖f_int‖)`…
    pub residual_tolerance: f64,
    /// …and `‖δu‖ ≤ displacement_tolerance · ‖Δu‖` (increment of the step).
    pub displacement_tolerance: f64,
    /// Backtracking line search on the residual norm.
    pub line_search: bool,
    /// Consecutive cuts of one increment before giving up.
    pub max_cuts: usize,
    /// Increment growth factor after an easy increment.
    pub growth_factor: f64,
    /// An increment that converged in at most this many iterations is easy.
    pub easy_iterations: usize,
    /// Linear solver of nonsymmetric tangents (friction, follower loads)
    /// under [`LinearMethod::Auto`].
    pub nonsymmetric: NonsymmetricSolver,
    /// The linear solver ([`crate::solve::linear_solver`]).
    pub linear: LinearMethod,
    /// The first Newton iterate of an increment (`[solver] predictor`).
    pub predictor: Predictor,
    /// Monolithic Newton or the condensed contact path (`[solver] strategy`).
    pub strategy: Strategy,
    /// PETSc options for [`LinearMethod::Petsc`] (`[solver.petsc] options`),
    /// read after the environment's `PETSC_OPTIONS`.
    pub petsc_options: String,
}

/// How a run is solved (`[solver] strategy`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum Strategy {
    /// The condensed path where it applies (it reproduces the monolithic
    /// answer there), else monolithic Newton.
    #[default]
    Auto,
    /// Newton on the whole system of displacements and multipliers, a
    /// factorisation per iteration.
    Monolithic,
    /// One factorisation of the constant stiffness per run, the contact
    /// problem solved exactly on its condensation `W = Eᵀ K⁻¹ E`
    /// (`crate::problem::condensed`); an error where it does not apply.
    Condensed,
}

/// Where Newton starts an increment (`[solver] predictor`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum Predictor {
    /// [`Predictor::Contact`] where the problem linearises its contact
    /// constraints (every interface frictionless Rockafellar against a
    /// rigid plane with a coordinate-axis normal, a serial run), else
    /// [`AUTO_FALLBACK`] ([`Predictor::chosen`]). The default: the same
    /// converged states, fewer Newton iterations (BENCHMARKS.md, "Issue 13
    /// item 4, fourth round").
    #[default]
    Auto,
    /// At the converged state of the last increment (the prescribed values'
    /// jump is linearised into the first correction).
    None,
    /// At `u + (Δt / Δt_last) Δu_last`: the last converged increment,
    /// scaled by the ratio of the increments (a secant extrapolation; the
    /// history carried along it); the first increment starts as with
    /// [`Predictor::None`]. Fewer Newton iterations on smoothly loaded
    /// paths (BENCHMARKS.md, "Issue 13 items 3 and 4"), the same converged
    /// states to the tolerances. Opt-in: on by default it changes Newton's
    /// path, and tests built on one path (the increments of press-pull,
    /// how closely an `.inp` and an `.msh` run agree) would need other
    /// set-ups; the follower-pressure test's bound is not a reason (it
    /// holds in the corrections).
    Secant,
    /// From the secant's start ([`Predictor::Secant`]), the first
    /// correction solves the contact constraints linearised at the
    /// iterate exactly (a
    /// Josephy–Newton step, [`crate::solve::josephy`]): Newton lands on the
    /// active set of the linearised problem instead of finding it one
    /// iteration at a time. Where the problem cannot linearise its contact
    /// that way (friction, other laws or obstacles than a frictionless
    /// Rockafellar contact against axis-aligned planes) or the step fails,
    /// Newton's plain step, as with [`Predictor::Secant`].
    Contact,
}

/// What [`Predictor::Auto`] runs where the contact predictor does not
/// apply: the plain start, which keeps those runs' Newton paths (and so
/// their increments and path-dependent frictional answers) as they were
/// (BENCHMARKS.md, "Issue 13 item 4, fourth round": the secant moves the
/// final state of ironing by 5e-3 and of cattaneo-mindlin's coarse case
/// by 3e-4, and takes the latter 96 iterations instead of 35).
pub const AUTO_FALLBACK: Predictor = Predictor::None;

impl Predictor {
    /// The predictor that runs and why: [`Predictor::Auto`] resolved by
    /// `contact`, whether the problem linearises its contact constraints
    /// (`Ok`) or why not; any other one as asked for.
    pub fn chosen(self, contact: Result<(), String>) -> (Predictor, String) {
        match (self, contact) {
            (Predictor::Auto, Ok(())) => (
                Predictor::Contact,
                "auto: frictionless Rockafellar contact against axis-aligned rigid planes".into(),
            ),
            (Predictor::Auto, Err(why)) => (AUTO_FALLBACK, format!("auto: {why}")),
            (asked, _) => (asked, "as [solver] predictor asks".into()),
        }
    }

    /// The case file's name of the predictor.
    pub fn name(self) -> &'static str {
        match self {
            Predictor::Auto => "auto",
            Predictor::None => "none",
            Predictor::Secant => "secant",
            Predictor::Contact => "contact",
        }
    }

    /// Whether the increment starts from the secant's extrapolation.
    pub fn extrapolates(self) -> bool {
        matches!(self, Predictor::Secant | Predictor::Contact)
    }
}

/// How a nonsymmetric tangent is solved.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum NonsymmetricSolver {
    /// GMRES preconditioned by the LDLᵀ of a symmetric neighbour of the
    /// tangent (its symmetric part, friction in stick), with the sparse LU
    /// as the fallback when it does not converge.
    #[default]
    Gmres,
    /// Sparse LU with partial pivoting, every time.
    Lu,
}

/// The linear solver of every Newton correction (`[solver] linear`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum LinearMethod {
    /// A symmetric tangent by the direct LDLᵀ (in mixed precision from
    /// [`crate::solve::backend::MIXED_PRECISION_DOFS`] unknowns on), a
    /// nonsymmetric one as `[solver] nonsymmetric` says (GMRES or the LU).
    #[default]
    Auto,
    /// The direct LDLᵀ of the tangent in f64 with iterative refinement; the
    /// sparse LU when it breaks down or leaves a relative residual above
    /// 1e-8.
    Ldlt,
    /// The direct LDLᵀ of the tangent in f32, refined against the f64
    /// tangent to a relative residual of 1e-13; `ldlt` when the refinement
    /// stalls (mixed precision, what `auto` does on large systems).
    Mixed,
    /// GMRES preconditioned by the LDLᵀ of the tangent's symmetric
    /// neighbour (of the tangent itself when it is symmetric); the sparse
    /// LU when it does not converge.
    Gmres,
    /// The sparse LU with partial pivoting, every time.
    Lu,
    /// PETSc's KSP and PC from its options database (cargo feature
    /// `petsc`; default: a direct LU by MUMPS).
    Petsc,
}

impl Default for SolverSettings {
    fn default() -> Self {
        SolverSettings {
            max_iterations: 20,
            residual_tolerance: 1e-8,
            displacement_tolerance: 1e-6,
            line_search: true,
            max_cuts: 8,
            growth_factor: 1.5,
            easy_iterations: 5,
            nonsymmetric: NonsymmetricSolver::Gmres,
            linear: LinearMethod::Auto,
            predictor: Predictor::Auto,
            strategy: Strategy::Auto,
            petsc_options: String::new(),
        }
    }
}
