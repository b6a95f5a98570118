//! The choice of linear solver (`[solver] linear`): one arm per
//! [`LinearMethod`], and `auto`, today's default, which solves a symmetric
//! tangent directly and a nonsymmetric one as `[solver] nonsymmetric` says.
//! A new backend is one file implementing [`LinearSolver`] and one arm here.

use super::direct::{DirectLdlt, MixedPrecision};
use super::failure::IncrementFailure;
use super::krylov::PreconditionedGmres;
use super::linear::Ordering;
use super::linear_solver::{LinearSolver, LinearSystem, SolverStatistics};
use super::lu::SparseLu;
use super::settings::{LinearMethod, NonsymmetricSolver, SolverSettings};
use crate::Result;

/// The size from which `auto` factorises a symmetric tangent in f32 and
/// refines in f64: below it the factorisation is not the larger part of a
/// Newton iteration and the refinement steps cost what the f32 factor
/// saves (measured in BENCHMARKS.md, "Mixed precision").
pub const MIXED_PRECISION_DOFS: usize = 20_000;

/// When `[solver] linear = method` factorises a symmetric tangent in f32:
/// `mixed` always, `auto` from [`MIXED_PRECISION_DOFS`] unknowns, the
/// others never (also the rule of Newton's Josephy–Newton factor).
pub fn mixed_precision(method: LinearMethod) -> MixedPrecision {
    match method {
        LinearMethod::Auto => MixedPrecision::FromDofs(MIXED_PRECISION_DOFS),
        LinearMethod::Mixed => MixedPrecision::Always,
        _ => MixedPrecision::Never,
    }
}

/// The linear solver `settings` ask for, with fill-reducing `ordering` and
/// `threads` threads (0 = rayon's pool). A backend that cannot start
/// (PETSc) gives a solver whose every solve fails with the reason; a run
/// uses [`try_linear_solver`] to stop at once instead.
pub fn linear_solver(
    settings: &SolverSettings,
    ordering: Ordering,
    threads: usize,
) -> Box<dyn LinearSolver> {
    try_linear_solver(settings, ordering, threads, None)
        .unwrap_or_else(|e| Box::new(Unavailable(e.to_string())))
}

/// [`linear_solver`], or why its backend cannot start. `coordinates`
/// (reference, 3 per node) give an algebraic multigrid its rigid-body
/// modes (PETSc's GAMG).
pub fn try_linear_solver(
    settings: &SolverSettings,
    ordering: Ordering,
    threads: usize,
    coordinates: Option<Vec<f64>>,
) -> Result<Box<dyn LinearSolver>> {
    Ok(match settings.linear {
        LinearMethod::Auto => Box::new(Auto {
            nonsymmetric: settings.nonsymmetric,
            direct: DirectLdlt::new(ordering.clone(), threads)
                .with_mixed_precision(mixed_precision(LinearMethod::Auto)),
            gmres: PreconditionedGmres::new(ordering, threads),
            lu: SparseLu::default(),
        }),
        LinearMethod::Ldlt => Box::new(DirectLdlt::new(ordering, threads)),
        LinearMethod::Mixed => Box::new(
            DirectLdlt::new(ordering, threads)
                .with_mixed_precision(mixed_precision(LinearMethod::Mixed)),
        ),
        LinearMethod::Gmres => Box::new(PreconditionedGmres::new(ordering, threads)),
        LinearMethod::Lu => Box::new(SparseLu::default()),
        LinearMethod::Petsc => petsc_solver(settings, coordinates)?,
    })
}

#[cfg(feature = "petsc")]
fn petsc_solver(
    settings: &SolverSettings,
    coordinates: Option<Vec<f64>>,
) -> Result<Box<dyn LinearSolver>> {
    Ok(Box::new(super::petsc::PetscSolver::new(
        &settings.petsc_options,
        coordinates,
    )?))
}

#[cfg(not(feature = "petsc"))]
fn petsc_solver(_: &SolverSettings, _: Option<Vec<f64>>) -> Result<Box<dyn LinearSolver>> {
    Err(crate::Error::LinearSolver(PETSC_MISSING.into()))
}

/// A backend that could not start: every solve fails with `.0`, a
/// failure no cut mends (the run ends).
struct Unavailable(String);

impl LinearSolver for Unavailable {
    fn set_ordering(&mut self, _: Ordering) {}
    fn solve(
        &mut self,
        _: &LinearSystem<'_>,
        _: &[f64],
        _: &mut [f64],
    ) -> std::result::Result<(), IncrementFailure> {
        Err(IncrementFailure::LinearSolverSetUp(self.0.clone()))
    }
    fn statistics(&self) -> SolverStatistics {
        SolverStatistics::default()
    }
}

/// Why `linear = "petsc"` is refused by a build without the feature.
pub const PETSC_MISSING: &str = "solver.linear = \"petsc\" needs signorini built with PETSc: \
     `cargo build --release --features petsc` (PETSc from `apt-get install petsc-dev`)";

/// A symmetric system by the [`DirectLdlt`], a nonsymmetric one by the
/// [`PreconditionedGmres`] or the [`SparseLu`] (`nonsymmetric`).
struct Auto {
    nonsymmetric: NonsymmetricSolver,
    direct: DirectLdlt,
    gmres: PreconditionedGmres,
    lu: SparseLu,
}

impl LinearSolver for Auto {
    fn set_ordering(&mut self, ordering: Ordering) {
        self.direct.set_ordering(ordering.clone());
        self.gmres.set_ordering(ordering);
    }

    fn solve(
        &mut self,
        system: &LinearSystem<'_>,
        rhs: &[f64],
        x: &mut [f64],
    ) -> Result<(), IncrementFailure> {
        match (system.symmetric_neighbour, self.nonsymmetric) {
            (None, _) => self.direct.solve(system, rhs, x),
            (Some(_), NonsymmetricSolver::Gmres) => self.gmres.solve(system, rhs, x),
            (Some(_), NonsymmetricSolver::Lu) => self.lu.solve(system, rhs, x),
        }
    }

    fn statistics(&self) -> SolverStatistics {
        self.direct.statistics() + self.gmres.statistics() + self.lu.statistics()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::assembly::pattern::SparsityPattern;
    use crate::solve::linear::SparseLdlt;

    /// Solve `K du = rhs` for one node (a dense 3 × 3 block, column-major,
    /// full pattern) with `preconditioner` as Newton does under the default
    /// settings, and assert `du = expected` (1e-14) reached through one LU
    /// solve.
    fn assert_solved_by_the_lu(
        k: &[f64; 9],
        preconditioner: Option<&[f64]>,
        rhs: [f64; 3],
        expected: [f64; 3],
    ) {
        let nodes = [0usize];
        let blocks = SparsityPattern::from_elements(1, std::iter::once(&nodes[..]));
        assert_eq!(blocks.nnz(), 9);
        let mut solver = linear_solver(&SolverSettings::default(), Ordering::Amd, 1);
        let mut du = rhs;
        let system = LinearSystem {
            pattern: blocks.symbolic(),
            matrix: k,
            symmetric_neighbour: preconditioner,
            pivot_signs: None,
        };
        solver.solve(&system, &rhs, &mut du).unwrap();
        for (d, e) in du.iter().zip(expected) {
            assert!((d - e).abs() < 1e-14, "{du:?}");
        }
        assert_eq!(solver.statistics().lu_solves, 1);
    }

    /// `[[0, 1, 0], [1, 0, 0], [0, 0, 1]]`: regular, symmetric, but its
    /// first pivot is 0, which the LDLᵀ without pivoting cannot take.
    const ZERO_FIRST_PIVOT: [f64; 9] = [0.0, 1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0];

    /// A nonsymmetric tangent whose symmetric preconditioner the LDLᵀ
    /// without pivoting cannot factorise (zero pivots) is solved by the LU.
    #[test]
    fn a_preconditioner_the_ldlt_cannot_factorise_falls_back_to_the_lu() {
        let nodes = [0usize];
        let blocks = SparsityPattern::from_elements(1, std::iter::once(&nodes[..]));
        let mut solver = SparseLdlt::new(Ordering::Amd, 1);
        assert!(solver
            .factorize(blocks.symbolic(), &ZERO_FIRST_PIVOT, None)
            .is_err());
        // K du = rhs: du₁ = 1, 2 du₀ = 4, du₂ = 3
        let k = [0.0, 2.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0];
        assert_solved_by_the_lu(
            &k,
            Some(&ZERO_FIRST_PIVOT),
            [1.0, 4.0, 3.0],
            [2.0, 1.0, 3.0],
        );
    }

    /// A symmetric tangent the LDLᵀ without pivoting cannot factorise (an
    /// indefinite one with a zero leading pivot) is solved by the LU.
    #[test]
    fn a_symmetric_tangent_the_ldlt_cannot_factorise_falls_back_to_the_lu() {
        assert_solved_by_the_lu(&ZERO_FIRST_PIVOT, None, [1.0, 4.0, 3.0], [4.0, 1.0, 3.0]);
    }
}
