//! Sparse LU with partial pivoting (faer's supernodal LU, COLAMD column
//! ordering) for nonsymmetric tangents: the fallback when GMRES
//! preconditioned by an LDLᵀ does not converge or an LDLᵀ breaks down, and
//! a [`LinearSolver`] of its own (`[solver] nonsymmetric = "lu"` or
//! `linear = "lu"`) for comparisons.
//!
//! faer's LU takes no custom ordering, and on 3D meshes COLAMD fills far
//! more than nested dissection: it was measured about 20 times slower and
//! with 10 times the memory of the LDLᵀ at 150 k dofs (see BENCHMARKS.md),
//! which is why it is not the default.

use super::failure::IncrementFailure;
use super::linear::{pattern_fingerprint, Ordering};
use super::linear_solver::{LinearSolver, LinearSystem, SolverStatistics};
use crate::{Error, Result};
use faer::linalg::solvers::Solve;
use faer::sparse::linalg::solvers::{Lu, SymbolicLu};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMat};
use faer::MatMut;
use std::time::{Duration, Instant};

/// A reusable sparse LU: the symbolic analysis is kept while the pattern
/// (recognised by a fingerprint of its structure) does not change.
#[derive(Default)]
pub struct SparseLu {
    /// The symbolic analysis and the fingerprint of the pattern it was made
    /// for (the structure, not only its size: a rebuilt pattern of the same
    /// size must be analysed again).
    symbolic: Option<(SymbolicLu<usize>, u64)>,
    /// Time spent in factorisations and solves so far.
    pub total: Duration,
    /// Factorisations so far.
    pub factorisations: usize,
    /// Solves asked for so far (those that failed too).
    pub solves: usize,
}

impl SparseLu {
    /// Factorise `A` (full CSC pattern and values) and solve `A x = b` in
    /// place.
    pub fn factor_and_solve(
        &mut self,
        pattern: &SymbolicSparseColMat<usize>,
        values: &[f64],
        rhs: &mut [f64],
    ) -> Result<()> {
        let start = Instant::now();
        let key = pattern_fingerprint(pattern);
        let symbolic = match &self.symbolic {
            Some((s, k)) if *k == key => s.clone(),
            _ => {
                let s = SymbolicLu::try_new(pattern.as_ref())
                    .map_err(|e| Error::LinearSolver(format!("LU symbolic analysis: {e:?}")))?;
                self.symbolic = Some((s.clone(), key));
                s
            }
        };
        let a = SparseColMatRef::new(pattern.as_ref(), values);
        let lu = Lu::try_new_with_symbolic(symbolic, a).map_err(|e| {
            Error::LinearSolver(format!(
                "LU factorisation failed ({e:?}): the tangent is singular; \
                 check that the boundary conditions remove every rigid-body motion"
            ))
        })?;
        let n = rhs.len();
        lu.solve_in_place(MatMut::from_column_major_slice_mut(rhs, n, 1));
        self.total += start.elapsed();
        self.factorisations += 1;
        if rhs.iter().any(|v| !v.is_finite()) {
            return Err(Error::LinearSolver(
                "the LU solution is not finite: the tangent is singular".into(),
            ));
        }
        Ok(())
    }

    /// Solve `K x = rhs` after another solver failed with `cause`; the
    /// error names both failures.
    pub fn solve_after(
        &mut self,
        cause: &dyn std::fmt::Display,
        system: &LinearSystem<'_>,
        rhs: &[f64],
        x: &mut [f64],
    ) -> std::result::Result<(), IncrementFailure> {
        LinearSolver::solve(self, system, rhs, x)
            .map_err(|e| IncrementFailure::LinearSolve(format!("{cause}; then {e}")))
    }
}

impl LinearSolver for SparseLu {
    /// The LU orders its columns itself (COLAMD).
    fn set_ordering(&mut self, _ordering: Ordering) {}

    fn solve(
        &mut self,
        system: &LinearSystem<'_>,
        rhs: &[f64],
        x: &mut [f64],
    ) -> std::result::Result<(), IncrementFailure> {
        x.copy_from_slice(rhs);
        self.solves += 1;
        self.factor_and_solve(system.pattern, system.matrix, x)
            .map_err(|e| IncrementFailure::LinearSolve(e.to_string()))
    }

    fn statistics(&self) -> SolverStatistics {
        SolverStatistics {
            factorisation: self.total,
            lu_solves: self.solves,
            ..Default::default()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::sparse::SparseColMat;

    #[test]
    fn solves_a_nonsymmetric_system() {
        // A = [[4, 1, 0], [2, 5, 1], [0, 3, 6]], x = (1, −2, 3)
        let triplets = [
            (0, 0, 4.0),
            (1, 0, 2.0),
            (0, 1, 1.0),
            (1, 1, 5.0),
            (2, 1, 3.0),
            (1, 2, 1.0),
            (2, 2, 6.0),
        ];
        let t: Vec<_> = triplets
            .iter()
            .map(|&(i, j, v)| faer::sparse::Triplet::new(i, j, v))
            .collect();
        let a = SparseColMat::<usize, f64>::try_new_from_triplets(3, 3, &t).unwrap();
        let x = [1.0, -2.0, 3.0];
        let mut b = vec![
            4.0 * x[0] + x[1],
            2.0 * x[0] + 5.0 * x[1] + x[2],
            3.0 * x[1] + 6.0 * x[2],
        ];
        let mut lu = SparseLu::default();
        lu.factor_and_solve(&a.symbolic().to_owned().unwrap(), a.val(), &mut b)
            .unwrap();
        for i in 0..3 {
            assert!((b[i] - x[i]).abs() < 1e-14, "{b:?}");
        }
        assert_eq!(lu.factorisations, 1);
    }
}
