//! The direct solver: the LDLᵀ of `K` (faer's supernodal factorisation
//! without pivoting, [`SparseLdlt`]) with iterative refinement, and the
//! sparse LU with partial pivoting where the LDLᵀ breaks down; above a
//! size, the LDLᵀ in f32 refined against the f64 matrix (mixed precision).

use super::failure::IncrementFailure;
use super::linear::{Ordering, SparseLdlt};
use super::linear_solver::{LinearSolver, LinearSystem, SolverStatistics};
use super::lu::SparseLu;

/// Refinement steps after the LDLᵀ solve.
const REFINEMENTS: usize = 3;

/// Largest relative residual `‖b − K x‖ / ‖b‖` the refined LDLᵀ solve may
/// leave before the LU solves again (digits lost beyond what refinement
/// recovers).
const LDLT_RESIDUAL: f64 = 1e-8;

/// Refinement steps at most on an f32 factor.
const MIXED_REFINEMENTS: usize = 10;

/// Largest relative residual the refined f32 solve may leave (a stalled
/// refinement above it factorises again in f64): within a few units of
/// the f64 solve's own floor, so the Newton iterates agree with the f64
/// path to round-off.
const MIXED_RESIDUAL: f64 = 1e-12;

/// When the LDLᵀ factorises in f32 and refines in f64.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MixedPrecision {
    /// Always in f64.
    Never,
    /// Always in f32 first.
    Always,
    /// In f32 first for systems of at least this many unknowns.
    FromDofs(usize),
}

impl MixedPrecision {
    /// Whether a system of `dofs` unknowns is factorised in f32 first.
    pub fn applies(self, dofs: usize) -> bool {
        match self {
            MixedPrecision::Never => false,
            MixedPrecision::Always => true,
            MixedPrecision::FromDofs(n) => dofs >= n,
        }
    }
}

/// `K = L D Lᵀ`, refined; the LU when the factorisation fails or leaves a
/// relative residual above 1e-8. An indefinite tangent that the LDLᵀ
/// without pivoting cannot factorise (the curvature term `f ∇²g` of
/// deformable contact after a large first step, examples/two-spheres) is
/// solved by the LU with partial pivoting, which also tells a singular one.
///
/// With mixed precision, `K` is first factorised in f32 and the solve
/// refined against the f64 `K` (`x += (L̃D̃L̃ᵀ)⁻¹ (b − K x)`, residuals in
/// f64) until `‖b − K x‖ / ‖b‖ < 1e-13`; when a step stops halving the
/// residual above 1e-12 (an indefinite or ill-conditioned tangent, where the
/// f32 factor's error `κ ε₃₂` is not small), the same `K` is factorised
/// again in f64 (a fallback, counted) and solved as above.
pub struct DirectLdlt {
    ldlt: SparseLdlt,
    lu: SparseLu,
    mixed: MixedPrecision,
    mixed_fallbacks: usize,
}

impl DirectLdlt {
    /// With `ordering` and `threads` threads (0 = rayon's pool).
    pub fn new(ordering: Ordering, threads: usize) -> Self {
        DirectLdlt {
            ldlt: SparseLdlt::new(ordering, threads),
            lu: SparseLu::default(),
            mixed: MixedPrecision::Never,
            mixed_fallbacks: 0,
        }
    }

    /// Factorise in f32 first as `mixed` says.
    pub fn with_mixed_precision(mut self, mixed: MixedPrecision) -> Self {
        self.mixed = mixed;
        self
    }

    /// Solve `K x = rhs` with the f32 LDLᵀ of `K` refined in f64; `false`
    /// (and `x` undefined) when the factorisation failed or the refinement
    /// stalled above [`MIXED_RESIDUAL`].
    fn solve_mixed(&mut self, system: &LinearSystem<'_>, rhs: &[f64], x: &mut [f64]) -> bool {
        let (pattern, k) = (system.pattern, system.matrix);
        x.copy_from_slice(rhs);
        self.ldlt
            .factorize_single(pattern, k, system.pivot_signs)
            .and_then(|()| self.ldlt.refine(pattern, k, x, MIXED_REFINEMENTS, true))
            .is_ok_and(|relative| relative <= MIXED_RESIDUAL)
    }
}

impl LinearSolver for DirectLdlt {
    fn set_ordering(&mut self, ordering: Ordering) {
        self.ldlt.set_ordering(ordering);
    }

    fn solve(
        &mut self,
        system: &LinearSystem<'_>,
        rhs: &[f64],
        x: &mut [f64],
    ) -> Result<(), IncrementFailure> {
        if self.mixed.applies(rhs.len()) {
            if self.solve_mixed(system, rhs, x) {
                return Ok(());
            }
            self.mixed_fallbacks += 1;
        }
        let (pattern, k) = (system.pattern, system.matrix);
        x.copy_from_slice(rhs);
        let direct = self
            .ldlt
            .factorize(pattern, k, system.pivot_signs)
            .and_then(|()| self.ldlt.solve_refined(pattern, k, x, REFINEMENTS))
            .and_then(|relative| {
                (relative <= LDLT_RESIDUAL).then_some(()).ok_or_else(|| {
                    crate::Error::LinearSolver(format!(
                        "the LDLᵀ solve left a relative residual of {relative:.1e}"
                    ))
                })
            });
        match direct {
            Ok(()) => Ok(()),
            Err(e) => self.lu.solve_after(&e, system, rhs, x),
        }
    }

    fn statistics(&self) -> SolverStatistics {
        SolverStatistics {
            mixed_precision_fallbacks: self.mixed_fallbacks,
            ..SolverStatistics::of_ldlt(&self.ldlt)
        } + self.lu.statistics()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::assembly::pattern::SparsityPattern;
    use crate::solve::linear::multiply;

    /// `[[1, 1], [1, 1 − ε]]`, ε = 1e-9: indefinite (pivots 1 and −ε).
    /// Rounded to f32, `1 − ε` is 1: the f32 LDLᵀ breaks down on a zero second
    /// pivot, and the
    /// solver factorises again in f64 (pivot −ε to 7 digits), which solves
    /// to a relative residual below 1e-13 after refinement. A
    /// well-conditioned SPD one refines on its f32 factor without a
    /// fallback.
    #[test]
    fn an_f32_factor_that_cannot_be_refined_falls_back_to_f64() {
        let nodes = [0usize];
        let blocks = SparsityPattern::from_elements(1, std::iter::once(&nodes[..]));
        // 3 × 3: the 2 × 2 above and an uncoupled 1 (column-major)
        let eps = 1e-9;
        let indefinite = [1.0, 1.0, 0.0, 1.0, 1.0 - eps, 0.0, 0.0, 0.0, 1.0];
        let spd = [4.0, 1.0, 0.0, 1.0, 3.0, 0.0, 0.0, 0.0, 2.0];
        let mut solver =
            DirectLdlt::new(Ordering::Amd, 1).with_mixed_precision(MixedPrecision::Always);
        let rhs = [1.0, 2.0, 3.0];
        for (k, fallbacks) in [(&spd, 0), (&indefinite, 1)] {
            let system = LinearSystem {
                pattern: blocks.symbolic(),
                matrix: k,
                symmetric_neighbour: None,
                pivot_signs: None,
            };
            let mut x = [0.0; 3];
            solver.solve(&system, &rhs, &mut x).unwrap();
            let mut kx = [0.0; 3];
            multiply(blocks.symbolic(), k, &x, &mut kx);
            let residual = kx
                .iter()
                .zip(&rhs)
                .map(|(a, b)| (a - b).powi(2))
                .sum::<f64>()
                .sqrt();
            assert!(residual < 1e-12 * 3.0f64.sqrt(), "{residual:e}");
            let s = solver.statistics();
            assert_eq!(s.mixed_precision_fallbacks, fallbacks);
            // the f32 factorisation of the indefinite one breaks down (zero
            // pivot) and is not counted
            assert_eq!(s.single_factorisations, 1);
            assert_eq!((s.factorisations, s.lu_solves), (fallbacks, 0));
        }
    }

    /// One node with the 3 × 3 block `k_uu` and one multiplier on its `z`
    /// dof (`K_uλ = e_z`, `K_λλ = 0`: an active contact node), with the
    /// pattern's pivot signs.
    fn saddle(k_uu: [[f64; 3]; 3]) -> (SparsityPattern, Vec<f64>) {
        let nodes = [0usize];
        let pattern = SparsityPattern::with_multipliers(1, std::iter::once(&nodes[..]), &[vec![0]]);
        let mut k = vec![0.0; pattern.nnz()];
        for (i, row) in k_uu.iter().enumerate() {
            for (j, &v) in row.iter().enumerate() {
                k[pattern.block_entry(0, i, 0, j).unwrap()] = v;
            }
        }
        let e = pattern.multiplier_entries(0, 0).unwrap();
        k[e.node_rows[2]] = 1.0;
        k[e.multiplier_row[2]] = 1.0;
        (pattern, k)
    }

    /// Solve the saddle system of `k_uu` for `x = (1, −2, 3, 4)` with
    /// `signs` and assert the solution to 1e-14; the solver's statistics.
    fn solve_saddle(k_uu: [[f64; 3]; 3], signs: Option<&[i8]>) -> SolverStatistics {
        let (pattern, k) = saddle(k_uu);
        let x_true = [1.0, -2.0, 3.0, 4.0];
        let mut rhs = [0.0; 4];
        multiply(pattern.symbolic(), &k, &x_true, &mut rhs);
        let own_signs = pattern.pivot_signs();
        let system = LinearSystem {
            pattern: pattern.symbolic(),
            matrix: &k,
            symmetric_neighbour: None,
            pivot_signs: Some(signs.unwrap_or(&own_signs)),
        };
        let mut solver = DirectLdlt::new(Ordering::Amd, 1);
        let mut x = [0.0; 4];
        solver.solve(&system, &rhs, &mut x).unwrap();
        for (a, b) in x.iter().zip(&x_true) {
            assert!((a - b).abs() < 1e-14, "{x:?}");
        }
        solver.statistics()
    }

    /// An indefinite displacement block (pivot −2, as in the tangent of a
    /// large-deformation trial state) in a saddle system: the pattern's
    /// signs regularise the multiplier's pivot only, so the LDLᵀ factorises
    /// the matrix as it is and solves it, without the LU. Regularised
    /// towards +1, the pivot −2 would become `+δ` and the factor another
    /// matrix's: only the LU would solve it.
    #[test]
    fn an_indefinite_displacement_block_needs_no_lu() {
        let k_uu = [[1.0, 0.0, 0.0], [0.0, -2.0, 0.0], [0.0, 0.0, 3.0]];
        let s = solve_saddle(k_uu, None);
        assert_eq!((s.factorisations, s.lu_solves), (1, 0));
        let s = solve_saddle(k_uu, Some(&[1, 1, 1, -1]));
        assert_eq!(s.lu_solves, 1);
    }

    /// A true breakdown: the displacement block `[[0, 1], [1, 0]]` has a
    /// zero pivot in any symmetric order. The LDLᵀ without pivoting cannot
    /// factorise it and the LU with partial pivoting, kept as the last
    /// resort, solves it.
    #[test]
    fn a_zero_pivot_is_solved_by_the_lu() {
        let k_uu = [[0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 3.0]];
        let s = solve_saddle(k_uu, None);
        assert_eq!(s.lu_solves, 1);
    }
}
