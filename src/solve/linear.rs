//! Sparse direct solve with faer's supernodal LDLᵀ.
//!
//! The symbolic analysis (fill-reducing ordering, elimination tree,
//! supernodes) is computed once per sparsity pattern and reused for every
//! numeric factorisation: a Newton loop on a fixed mesh pays for it once.
//! faer is used because it is a maintained, pure-Rust sparse direct solver
//! with separate symbolic and numeric phases and a supernodal LDLᵀ that also
//! handles the symmetric indefinite systems of contact multipliers.

use crate::{Error, Result};
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::ldlt::factor::{LdltParams, LdltRegularization};
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, supernodal, CholeskySymbolicParams, LdltRef, SymbolicCholesky,
    SymbolicCholeskyRaw, SymmetricOrdering,
};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMat};
use faer::{MatMut, Par, Side, Spec};
use std::time::{Duration, Instant};

/// Below this many factor entries a numeric factorisation and its solves
/// run on one thread (faer's `Par::Seq`) whatever the solver's thread
/// count: the supernodes are too small for the threads' synchronisation to
/// pay, and beside other processes a waiting thread costs more than it
/// saves. Measured: examples/ogden-plate (6 448 unknowns, 1.6 M entries,
/// 18 factorisations, machine load 8–10) 0.93–0.98 s on one thread, 1.7–2.7
/// s on two; the condensed path's small race mesh (11.4 M entries) 0.13 s
/// on one thread at any load, 0.11 s on two idle and 0.24–0.32 s on two
/// beside two builds (`src/problem/condensed.rs`, which decides by the
/// number of unknowns for its one factorisation).
pub const PARALLEL_FACTOR_ENTRIES: usize = 12_000_000;

/// Fill-reducing ordering for the symbolic analysis.
#[derive(Clone, Debug, Default)]
pub enum Ordering {
    /// faer's approximate minimum degree.
    #[default]
    Amd,
    /// A permutation computed elsewhere (e.g. nested dissection):
    /// `forward[new] = old`.
    Custom(Vec<usize>),
}

/// Timings of the last calls, for reports and benchmarks.
#[derive(Clone, Copy, Debug, Default)]
pub struct SolverTimings {
    /// The last symbolic analysis, numeric factorisation and solve.
    pub symbolic: Duration,
    pub numeric: Duration,
    pub solve: Duration,
    /// Number of symbolic analyses done so far.
    pub analyses: usize,
    /// Numeric factorisations so far, in f64 and in f32.
    pub factorisations: usize,
    pub single_factorisations: usize,
    /// Iterative refinement steps (one residual and one triangular solve
    /// each) so far.
    pub refinement_steps: usize,
    /// Totals since the solver was made.
    pub symbolic_total: Duration,
    pub numeric_total: Duration,
    pub solve_total: Duration,
}

/// A reusable sparse LDLᵀ solver for symmetric matrices given by their
/// full (both triangles) CSC pattern; only the lower triangle is read.
pub struct SparseLdlt {
    ordering: Ordering,
    symbolic: Option<SymbolicCholesky<usize>>,
    /// Fingerprint of the pattern the symbolic analysis was made for.
    analysed: Option<u64>,
    factor: Vec<f64>,
    /// The f32 factor of [`Self::factorize_single`].
    factor_single: Vec<f32>,
    /// Which factor the last factorisation made (the one solves use).
    precision: Precision,
    par: Par,
    /// One thread below [`PARALLEL_FACTOR_ENTRIES`] whatever `par` says
    /// (off: [`Self::threads_as_given`]).
    small_on_one_thread: bool,
    pub timings: SolverTimings,
}

/// The values of a factor, in its arithmetic.
#[derive(Clone, Copy, Debug)]
pub enum FactorValues<'a> {
    Double(&'a [f64]),
    Single(&'a [f32]),
}

impl FactorValues<'_> {
    /// Entry `k`, in f64.
    pub fn get(&self, k: usize) -> f64 {
        match self {
            FactorValues::Double(v) => v[k],
            FactorValues::Single(v) => v[k] as f64,
        }
    }
}

/// The arithmetic of a numeric factorisation.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Precision {
    #[default]
    Double,
    Single,
}

impl SparseLdlt {
    /// Use `ordering` from the next factorisation on (a new symbolic
    /// analysis): after the sparsity pattern changed, e.g. new contact pairs.
    pub fn set_ordering(&mut self, ordering: Ordering) {
        self.ordering = ordering;
        self.symbolic = None;
        self.analysed = None;
    }

    /// A solver using `ordering` and `threads` threads (0 = rayon's pool).
    pub fn new(ordering: Ordering, threads: usize) -> Self {
        let par = match threads {
            1 => Par::Seq,
            0 => Par::rayon(rayon::current_num_threads()),
            t => Par::rayon(t),
        };
        SparseLdlt {
            ordering,
            symbolic: None,
            analysed: None,
            factor: Vec::new(),
            factor_single: Vec::new(),
            precision: Precision::Double,
            par,
            small_on_one_thread: true,
            timings: SolverTimings::default(),
        }
    }

    /// The solver on the threads it was made with whatever the factor's
    /// size, for a caller that decides itself (the condensed path, by its
    /// number of unknowns: `PARALLEL_FACTOR_UNKNOWNS` in
    /// `src/problem/condensed.rs`).
    pub fn threads_as_given(mut self) -> Self {
        self.small_on_one_thread = false;
        self
    }

    /// The symbolic analysis, done again only when the pattern changes
    /// (recognised by a fingerprint of its structure, so that no copy of the
    /// pattern is kept); the next factorisation does it when it was not
    /// done before.
    pub fn analyse(&mut self, pattern: &SymbolicSparseColMat<usize>) -> Result<()> {
        let fingerprint = pattern_fingerprint(pattern);
        if self.symbolic.is_some() && self.analysed == Some(fingerprint) {
            return Ok(());
        }
        let start = Instant::now();
        // faer's convention: the factorised matrix is P A Pᵀ with
        // forward[new] = old (METIS NodeND's `perm` has the same meaning)
        let perm = match &self.ordering {
            Ordering::Amd => None,
            Ordering::Custom(fwd) => {
                if fwd.len() != pattern.nrows() {
                    return Err(Error::LinearSolver(format!(
                        "the ordering has {} entries for a matrix of dimension {}",
                        fwd.len(),
                        pattern.nrows()
                    )));
                }
                let mut inv = vec![usize::MAX; fwd.len()];
                for (new, &old) in fwd.iter().enumerate() {
                    if old >= inv.len() || inv[old] != usize::MAX {
                        return Err(Error::LinearSolver(
                            "the ordering is not a permutation".into(),
                        ));
                    }
                    inv[old] = new;
                }
                Some(faer::perm::Perm::new_checked(
                    fwd.clone().into_boxed_slice(),
                    inv.into_boxed_slice(),
                    fwd.len(),
                ))
            }
        };
        let ordering = match &perm {
            None => SymmetricOrdering::Amd,
            Some(p) => SymmetricOrdering::Custom(p.as_ref()),
        };
        let symbolic = factorize_symbolic_cholesky(
            pattern.as_ref(),
            Side::Lower,
            ordering,
            CholeskySymbolicParams::default(),
        )
        .map_err(|e| Error::LinearSolver(format!("symbolic analysis: {e:?}")))?;
        // sized at the first factorisation in its precision (beside the
        // values' permutation, [`NumericInput::factorize`])
        self.factor = Vec::new();
        self.factor_single = Vec::new();
        self.symbolic = Some(symbolic);
        self.analysed = Some(fingerprint);
        self.timings.symbolic = start.elapsed();
        self.timings.symbolic_total += self.timings.symbolic;
        self.timings.analyses += 1;
        Ok(())
    }

    /// The last factorisation: its symbolic structure and values (`L`
    /// below the diagonal, `D` on it), in the precision it was made in;
    /// `None` before one.
    pub fn factor_parts(&self) -> Option<(&SymbolicCholesky<usize>, FactorValues<'_>)> {
        let s = self.symbolic.as_ref()?;
        match self.precision {
            Precision::Double if self.factor.len() == s.len_val() => {
                Some((s, FactorValues::Double(&self.factor)))
            }
            Precision::Single if self.factor_single.len() == s.len_val() => {
                Some((s, FactorValues::Single(&self.factor_single)))
            }
            _ => None,
        }
    }

    /// The arithmetic of the last factorisation.
    pub fn precision(&self) -> Precision {
        self.precision
    }

    /// The parallelism of factorisations and solves: the solver's, or one
    /// thread below [`PARALLEL_FACTOR_ENTRIES`] factor entries (unless
    /// [`Self::threads_as_given`]).
    pub fn parallelism(&self) -> Par {
        match &self.symbolic {
            Some(s) if self.small_on_one_thread && s.len_val() < PARALLEL_FACTOR_ENTRIES => {
                Par::Seq
            }
            _ => self.par,
        }
    }

    /// Number of stored entries of the factor `L` (after analysis).
    pub fn factor_nnz(&self) -> usize {
        self.symbolic.as_ref().map_or(0, |s| s.len_val())
    }

    /// Factorise `A = L D Lᵀ`. `signs`, if given, asks for dynamic
    /// regularisation: pivot `k` is expected to have sign `signs[k]` (+1 for
    /// displacement unknowns, −1 for multipliers) and is pushed away from
    /// zero if it has not.
    pub fn factorize(
        &mut self,
        pattern: &SymbolicSparseColMat<usize>,
        values: &[f64],
        signs: Option<&[i8]>,
    ) -> Result<()> {
        self.factorize_in(Precision::Double, pattern, values, signs)
    }

    /// Factorise `Ã = L D Lᵀ` in f32, `Ã` the matrix `values` rounded to
    /// f32, on the same symbolic analysis as [`Self::factorize`]: half the
    /// memory traffic and twice the SIMD width of the f64 factorisation.
    /// Solves then use this factor until the next factorisation; pair them
    /// with iterative refinement against the f64 matrix
    /// ([`Self::solve_refined`]), which converges while
    /// `κ(A) · ε₃₂ · growth < 1` (ε₃₂ = 6e-8).
    pub fn factorize_single(
        &mut self,
        pattern: &SymbolicSparseColMat<usize>,
        values: &[f64],
        signs: Option<&[i8]>,
    ) -> Result<()> {
        self.factorize_in(Precision::Single, pattern, values, signs)
    }

    /// The numeric LDLᵀ in `precision`, on the pattern's symbolic analysis.
    fn factorize_in(
        &mut self,
        precision: Precision,
        pattern: &SymbolicSparseColMat<usize>,
        values: &[f64],
        signs: Option<&[i8]>,
    ) -> Result<()> {
        self.analyse(pattern)?;
        let start = Instant::now();
        let par = self.parallelism();
        let symbolic = self
            .symbolic
            .as_ref()
            .ok_or_else(|| Error::LinearSolver("factorisation before analysis".into()))?;
        let scale = max_abs_diagonal(pattern, values);
        let (delta, epsilon) = (1e-10 * scale, 1e-13 * scale);
        let input = NumericInput {
            symbolic,
            pattern,
            values,
            signs,
            par,
        };
        match precision {
            Precision::Double => {
                input.factorize(&mut self.factor, |v| v, (delta, epsilon))?;
                self.timings.factorisations += 1;
            }
            Precision::Single => {
                let regularization = (delta as f32, epsilon as f32);
                input.factorize(&mut self.factor_single, |v| v as f32, regularization)?;
                self.timings.single_factorisations += 1;
            }
        }
        self.precision = precision;
        self.timings.numeric = start.elapsed();
        self.timings.numeric_total += self.timings.numeric;
        Ok(())
    }

    /// Size the storage of a factor in `precision` for the analysed
    /// pattern, its pages touched (zeroed), unless it has that size: what
    /// the next factorisation in `precision` would do first, for a caller
    /// that has it done on another thread beside its own preparation of
    /// the values (36 MB of f32 on the small race mesh, about 9 000 page
    /// faults). Without an analysis, nothing.
    pub fn reserve(&mut self, precision: Precision) {
        let Some(len) = self.symbolic.as_ref().map(|s| s.len_val()) else {
            return;
        };
        match precision {
            Precision::Double => sized(&mut self.factor, len),
            Precision::Single => sized(&mut self.factor_single, len),
        }
    }

    /// Solve `A x = b` in place with the last factorisation.
    pub fn solve_in_place(&mut self, rhs: &mut [f64]) -> Result<()> {
        let start = Instant::now();
        let par = self.parallelism();
        let symbolic = self
            .symbolic
            .as_ref()
            .ok_or_else(|| Error::LinearSolver("solve before factorisation".into()))?;
        let n = rhs.len();
        match self.precision {
            Precision::Double => {
                let ldlt = LdltRef::<'_, usize, f64>::new(symbolic, &self.factor);
                let mut mem = MemBuffer::new(symbolic.solve_in_place_scratch::<f64>(1, par));
                let x = MatMut::from_column_major_slice_mut(rhs, n, 1);
                ldlt.solve_in_place_with_conj(faer::Conj::No, x, par, MemStack::new(&mut mem));
            }
            Precision::Single => {
                let ldlt = LdltRef::<'_, usize, f32>::new(symbolic, &self.factor_single);
                let mut mem = MemBuffer::new(symbolic.solve_in_place_scratch::<f32>(1, par));
                let mut single: Vec<f32> = rhs.iter().map(|&v| v as f32).collect();
                let x = MatMut::from_column_major_slice_mut(&mut single, n, 1);
                ldlt.solve_in_place_with_conj(faer::Conj::No, x, par, MemStack::new(&mut mem));
                rhs.iter_mut()
                    .zip(&single)
                    .for_each(|(r, &s)| *r = s as f64);
            }
        }
        self.timings.solve = start.elapsed();
        self.timings.solve_total += self.timings.solve;
        if rhs.iter().any(|v| !v.is_finite()) {
            return Err(Error::LinearSolver(
                "the solution is not finite: the tangent is singular or badly conditioned".into(),
            ));
        }
        Ok(())
    }
}

impl SparseLdlt {
    /// Solve `A X = B` in place for `B` of `columns` columns (column-major,
    /// `rhs.len() = n · columns`) with the last factorisation (in its
    /// arithmetic: unrefined after an f32 one): one pass over the factor
    /// for all of them (supernodal blocks against a block of right-hand
    /// sides).
    pub fn solve_columns_in_place(&mut self, rhs: &mut [f64], columns: usize) -> Result<()> {
        let start = Instant::now();
        let par = self.parallelism();
        let symbolic = self
            .symbolic
            .as_ref()
            .ok_or_else(|| Error::LinearSolver("solve before factorisation".into()))?;
        if columns == 0 || !rhs.len().is_multiple_of(columns) {
            return Err(Error::LinearSolver(
                "a block solve needs whole columns".into(),
            ));
        }
        let n = rhs.len() / columns;
        match self.precision {
            Precision::Double => {
                let ldlt = LdltRef::<'_, usize, f64>::new(symbolic, &self.factor);
                let mut mem = MemBuffer::new(symbolic.solve_in_place_scratch::<f64>(columns, par));
                let x = MatMut::from_column_major_slice_mut(rhs, n, columns);
                ldlt.solve_in_place_with_conj(faer::Conj::No, x, par, MemStack::new(&mut mem));
            }
            Precision::Single => {
                let ldlt = LdltRef::<'_, usize, f32>::new(symbolic, &self.factor_single);
                let mut mem = MemBuffer::new(symbolic.solve_in_place_scratch::<f32>(columns, par));
                let mut single: Vec<f32> = rhs.iter().map(|&v| v as f32).collect();
                let x = MatMut::from_column_major_slice_mut(&mut single, n, columns);
                ldlt.solve_in_place_with_conj(faer::Conj::No, x, par, MemStack::new(&mut mem));
                rhs.iter_mut()
                    .zip(&single)
                    .for_each(|(r, &s)| *r = s as f64);
            }
        }
        self.timings.solve = start.elapsed();
        self.timings.solve_total += self.timings.solve;
        if rhs.iter().any(|v| !v.is_finite()) {
            return Err(Error::LinearSolver(
                "the solution is not finite: the matrix is singular".into(),
            ));
        }
        Ok(())
    }
}

impl SparseLdlt {
    /// Solve `A x = b` in place with the last factorisation of `A`, then
    /// improve `x` by iterative refinement (`x += A⁻¹ (b − A x)`) while the
    /// relative residual of the linear system exceeds 1e-13, at most
    /// `max_refinements` times. An LDLᵀ without pivoting of an indefinite or
    /// ill-conditioned tangent can lose digits; refinement recovers them
    /// and keeps Newton's quadratic rate. Returns the final relative
    /// residual `‖b − A x‖ / ‖b‖`.
    pub fn solve_refined(
        &mut self,
        pattern: &SymbolicSparseColMat<usize>,
        values: &[f64],
        rhs: &mut [f64],
        max_refinements: usize,
    ) -> Result<f64> {
        self.refine(pattern, values, rhs, max_refinements, false)
    }

    /// [`Self::solve_refined`] that also stops when a step does not halve
    /// the residual (`stop_on_stall`): refinement on an f32 factor that
    /// stalls will not reach f64 accuracy, and the caller factorises again
    /// in f64.
    pub fn refine(
        &mut self,
        pattern: &SymbolicSparseColMat<usize>,
        values: &[f64],
        rhs: &mut [f64],
        max_refinements: usize,
        stop_on_stall: bool,
    ) -> Result<f64> {
        let b = rhs.to_vec();
        self.solve_in_place(rhs)?;
        self.refine_from(pattern, values, &b, rhs, max_refinements, stop_on_stall)
    }

    /// Iterative refinement of `x`, an approximate solution of `A x = b`
    /// (`x += A⁻¹ (b − A x)` with the last factorisation) until the
    /// relative residual `‖b − A x‖ / ‖b‖` is below 1e-13, after at most
    /// `max_refinements` steps, or (`stop_on_stall`) when a step does not
    /// halve it. From a good start (the solution for a nearby `b`) it
    /// needs fewer steps than a fresh solve, or none. Returns the final
    /// relative residual.
    pub fn refine_from(
        &mut self,
        pattern: &SymbolicSparseColMat<usize>,
        values: &[f64],
        b: &[f64],
        x: &mut [f64],
        max_refinements: usize,
        stop_on_stall: bool,
    ) -> Result<f64> {
        let product = |v: &[f64], y: &mut [f64]| multiply(pattern, values, v, y);
        self.refine_with(product, b, x, max_refinements, stop_on_stall)
    }
}

/// A factor that refines a solution iteratively with its own solves,
/// counting the steps in its timings: [`Self::refine_with`] with the
/// product `y = A x` given, for a matrix stored otherwise than on its
/// whole pattern (a symmetric one's lower triangle,
/// [`crate::assembly::triangle::multiply`]).
pub trait IterativeRefinement {
    /// `r ← A⁻¹ r` with the factor.
    fn solve_with_factor(&mut self, rhs: &mut [f64]) -> Result<()>;

    /// The timings the refinement steps are counted in.
    fn timings_mut(&mut self) -> &mut SolverTimings;

    /// [`refinement`] of `x` for `A x = b` with the factor's solves: the
    /// final relative residual; the steps are added to the timings.
    fn refine_with(
        &mut self,
        product: impl Fn(&[f64], &mut [f64]),
        b: &[f64],
        x: &mut [f64],
        max_refinements: usize,
        stop_on_stall: bool,
    ) -> Result<f64> {
        let solve = |r: &mut [f64]| self.solve_with_factor(r);
        let (relative, steps) = refinement(product, solve, b, x, max_refinements, stop_on_stall)?;
        self.timings_mut().refinement_steps += steps;
        Ok(relative)
    }
}

impl IterativeRefinement for SparseLdlt {
    fn solve_with_factor(&mut self, rhs: &mut [f64]) -> Result<()> {
        self.solve_in_place(rhs)
    }

    fn timings_mut(&mut self) -> &mut SolverTimings {
        &mut self.timings
    }
}

/// Iterative refinement of `x` for `A x = b`, `x += A⁻¹ (b − A x)` with
/// `product` (`y = A x`) and `solve` (`r ← A⁻¹ r`, a factor's), until the
/// relative residual `‖b − A x‖ / ‖b‖` is below 1e-13, after at most
/// `max_refinements` steps, or (`stop_on_stall`) when a step does not
/// halve it: the final relative residual and the steps taken.
pub fn refinement(
    product: impl Fn(&[f64], &mut [f64]),
    mut solve: impl FnMut(&mut [f64]) -> Result<()>,
    b: &[f64],
    x: &mut [f64],
    max_refinements: usize,
    stop_on_stall: bool,
) -> Result<(f64, usize)> {
    let b_norm = b
        .iter()
        .map(|v| v * v)
        .sum::<f64>()
        .sqrt()
        .max(f64::MIN_POSITIVE);
    let mut ax = vec![0.0; b.len()];
    let mut relative = f64::INFINITY;
    let mut steps = 0;
    for k in 0..=max_refinements {
        product(x, &mut ax);
        let mut r: Vec<f64> = b.iter().zip(&ax).map(|(bi, ai)| bi - ai).collect();
        let previous = relative;
        relative = r.iter().map(|v| v * v).sum::<f64>().sqrt() / b_norm;
        let stalled = stop_on_stall && !(relative < 0.5 * previous);
        if relative < 1e-13 || k == max_refinements || stalled {
            break;
        }
        steps += 1;
        solve(&mut r)?;
        for (xi, d) in x.iter_mut().zip(&r) {
            *xi += d;
        }
    }
    Ok((relative, steps))
}

/// What a report reads of a factorisation: its timings and the entries of
/// its factor ([`crate::solve::linear_solver::SolverStatistics::of_ldlt`]).
pub trait FactorReport {
    fn timings(&self) -> SolverTimings;
    fn factor_nnz(&self) -> usize;
}

impl FactorReport for SparseLdlt {
    fn timings(&self) -> SolverTimings {
        self.timings
    }

    fn factor_nnz(&self) -> usize {
        SparseLdlt::factor_nnz(self)
    }
}

/// `v` with `len` entries, each zero, unless it has `len` already (its
/// values are then left as they are: a factorisation overwrites them).
/// A new one is zeroed by the allocator (fresh pages, for a large one)
/// and written once per 4 KiB page, so that its page faults are taken
/// here without a memset of the whole: in chunks of 1 MiB on the rayon
/// pool's threads (the faults of the small race's 36 MB f32 factor took
/// 20 ms on one thread while the other, done with its own part, waited).
fn sized<T: Copy + Default + Send>(v: &mut Vec<T>, len: usize) {
    use rayon::prelude::*;
    if v.len() != len {
        *v = vec![T::default(); len];
        // opaque: the writes below are not known to store what is there
        let fresh = std::hint::black_box(&mut v[..]);
        let page = (4096 / std::mem::size_of::<T>().max(1)).max(1);
        fresh.par_chunks_mut(256 * page).for_each(|chunk| {
            for i in (0..chunk.len()).step_by(page) {
                chunk[i] = T::default();
            }
        });
    }
}

/// `a` and then `b`, or both at once on the rayon pool when `par` is.
fn beside(par: Par, a: impl FnOnce() + Send, b: impl FnOnce() + Send) {
    match par {
        Par::Seq => {
            a();
            b();
        }
        Par::Rayon(_) => {
            rayon::join(a, b);
        }
    }
}

/// The lower triangle of `P A Pᵀ` from `A`'s `values` on `pattern` (whole
/// or its lower triangle), each rounded by `convert`: entry `(i, j)`,
/// `i ≥ j`, of `A` is entry `(max(pᵢ, pⱼ), min(pᵢ, pⱼ))` of `P A Pᵀ` (`p`
/// the inverse permutation, `p[old] = new`, none: the identity), rows
/// unsorted within a column, as faer's supernodal factorisation reads it
/// (each entry added once into a zeroed block: the order of a column's
/// rows does not change the factor). The values go straight into the
/// factor's order and arithmetic beside the sizing of the factor's storage
/// (faer would copy, then permute them after it, on the same thread).
fn permuted_lower<T: Copy + Default>(
    pattern: &SymbolicSparseColMat<usize>,
    inverse: Option<&[usize]>,
    values: &[f64],
    convert: impl Fn(f64) -> T,
) -> (SymbolicSparseColMat<usize>, Vec<T>) {
    let n = pattern.ncols();
    let (cp, ri) = (pattern.col_ptr(), pattern.row_idx());
    let at = |i: usize| inverse.map_or(i, |p| p[i]);
    // (entry, column, row) in P A Pᵀ of every lower entry of A
    let lower = |j: usize| {
        (cp[j]..cp[j + 1])
            .filter(move |&k| ri[k] >= j)
            .map(move |k| {
                let (a, b) = (at(ri[k]), at(j));
                (k, a.min(b), a.max(b))
            })
    };
    let mut col_ptr = vec![0usize; n + 1];
    (0..n)
        .flat_map(lower)
        .for_each(|(_, c, _)| col_ptr[c + 1] += 1);
    for c in 0..n {
        col_ptr[c + 1] += col_ptr[c];
    }
    let nnz = col_ptr[n];
    let mut next = col_ptr[..n].to_vec();
    let (mut row_idx, mut permuted) = (vec![0usize; nnz], vec![T::default(); nnz]);
    for (k, c, r) in (0..n).flat_map(lower) {
        row_idx[next[c]] = r;
        permuted[next[c]] = convert(values[k]);
        next[c] += 1;
    }
    let symbolic = SymbolicSparseColMat::new_unsorted_checked(n, n, col_ptr, None, row_idx);
    (symbolic, permuted)
}

/// What a numeric factorisation reads: the analysis, the matrix's values
/// on `pattern` and the solver's threads.
struct NumericInput<'a> {
    symbolic: &'a SymbolicCholesky<usize>,
    pattern: &'a SymbolicSparseColMat<usize>,
    values: &'a [f64],
    signs: Option<&'a [i8]>,
    par: Par,
}

impl NumericInput<'_> {
    /// The numeric LDLᵀ in `T` arithmetic (`convert` rounding each value)
    /// into `factor`, with dynamic
    /// regularisation `(δ, ε)` towards the signs when given. On a
    /// supernodal analysis the factor's storage is sized (its pages
    /// touched) on one thread while the other writes the values in the
    /// factor's order ([`permuted_lower`]); a simplicial (small) one
    /// lets faer permute them.
    fn factorize<T>(
        self,
        factor: &mut Vec<T>,
        convert: impl Fn(f64) -> T + Send,
        (delta, epsilon): (T, T),
    ) -> Result<()>
    where
        T: faer::traits::RealField + faer::traits::ComplexField<Real = T> + Copy + Default,
    {
        let NumericInput {
            symbolic,
            pattern,
            values,
            signs,
            par,
        } = self;
        let len = symbolic.len_val();
        let params: Spec<LdltParams, T> = Default::default();
        let SymbolicCholeskyRaw::Supernodal(supernodal) = symbolic.raw() else {
            sized(factor, len);
            let input: Vec<T> = values.iter().map(|&v| convert(v)).collect();
            let a = SparseColMatRef::new(pattern.as_ref(), &input[..]);
            let mut mem = MemBuffer::new(symbolic.factorize_numeric_ldlt_scratch::<T>(par, params));
            let regularization = regularization(signs, delta, epsilon);
            return symbolic
                .factorize_numeric_ldlt(
                    factor,
                    a,
                    Side::Lower,
                    regularization,
                    par,
                    MemStack::new(&mut mem),
                    params,
                )
                .map(|_| ())
                .map_err(factorisation_failed);
        };
        let perm = symbolic.perm().map(|p| p.arrays());
        let mut permuted = None;
        beside(
            par,
            || sized(factor, len),
            || {
                let inverse = perm.map(|(_, inverse)| inverse);
                permuted = Some(permuted_lower(pattern, inverse, values, convert));
            },
        );
        let (structure, input) = permuted
            .ok_or_else(|| Error::LinearSolver("the permuted input was not made".into()))?;
        let a = SparseColMatRef::new(structure.as_ref(), &input[..]);
        // the signs in the factor's order, as faer's own permutation
        let signs: Option<Vec<i8>> = signs.map(|s| match perm {
            Some((forward, _)) => forward.iter().map(|&old| s[old]).collect(),
            None => s.to_vec(),
        });
        let regularization = regularization(signs.as_deref(), delta, epsilon);
        let mut mem = MemBuffer::new(supernodal::factorize_supernodal_numeric_ldlt_scratch::<
            usize,
            T,
        >(supernodal, par, params));
        supernodal::factorize_supernodal_numeric_ldlt(
            factor,
            a,
            regularization,
            supernodal,
            par,
            MemStack::new(&mut mem),
            params,
        )
        .map(|_| ())
        .map_err(factorisation_failed)
    }
}

/// Dynamic regularisation `(δ, ε)` towards `signs`, none without them.
fn regularization<T: faer::traits::RealField>(
    signs: Option<&[i8]>,
    delta: T,
    epsilon: T,
) -> LdltRegularization<'_, T> {
    match signs {
        Some(s) => LdltRegularization {
            dynamic_regularization_signs: Some(s),
            dynamic_regularization_delta: delta,
            dynamic_regularization_epsilon: epsilon,
        },
        None => LdltRegularization::default(),
    }
}

fn factorisation_failed(e: faer::linalg::cholesky::ldlt::factor::LdltError) -> Error {
    Error::LinearSolver(format!(
        "LDLᵀ factorisation failed ({e:?}): the tangent is singular; \
         check that the boundary conditions remove every rigid-body motion"
    ))
}

/// A hash of a pattern's structure (FNV-1a over its dimensions, column
/// pointers and row indices).
pub fn pattern_fingerprint(pattern: &SymbolicSparseColMat<usize>) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    let mut eat = |v: usize| {
        h ^= v as u64;
        h = h.wrapping_mul(0x0100_0000_01b3);
    };
    eat(pattern.nrows());
    pattern.col_ptr().iter().for_each(|&v| eat(v));
    pattern.row_idx().iter().for_each(|&v| eat(v));
    h
}

fn max_abs_diagonal(pattern: &SymbolicSparseColMat<usize>, values: &[f64]) -> f64 {
    let (cp, ri) = (pattern.col_ptr(), pattern.row_idx());
    (0..pattern.ncols())
        .flat_map(|j| (cp[j]..cp[j + 1]).filter(move |&k| ri[k] == j))
        .map(|k| values[k].abs())
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE)
}

/// Make the rows and columns of the `constrained` unknowns of `values`
/// (a symmetric matrix stored on `pattern`, whole or its lower triangle;
/// `diagonal(d)` the index of entry `(d, d)`, `None` where the pattern
/// holds no such entry) a scaled identity `s I`: their diagonal `s`, their
/// other entries 0. `s` is the mean `|K_dd|` over the free unknowns among
/// the first `dofs` (the displacements: a multiplier's diagonal may be 0),
/// an entry not stored counting as 0 (a process's pattern leaves out the
/// nodes its elements do not touch, whose part of `K_dd` is 0: the mean
/// is the one the whole diagonal blocks gave), 1 if there is none;
/// returned.
pub fn scaled_identity_rows(
    pattern: &SymbolicSparseColMat<usize>,
    diagonal: impl Fn(usize) -> Option<usize>,
    dofs: usize,
    constrained: &[bool],
    values: &mut [f64],
) -> f64 {
    let (cp, ri) = (pattern.col_ptr(), pattern.row_idx());
    let (mut sum, mut count) = (0.0, 0usize);
    for (d, &c) in constrained.iter().enumerate().take(dofs) {
        if !c {
            sum += diagonal(d).map_or(0.0, |k| values[k].abs());
            count += 1;
        }
    }
    let scale = if count > 0 && sum > 0.0 {
        sum / count as f64
    } else {
        1.0
    };
    for j in 0..pattern.ncols() {
        for idx in cp[j]..cp[j + 1] {
            let i = ri[idx];
            if constrained[i] || constrained[j] {
                values[idx] = if i == j { scale } else { 0.0 };
            }
        }
    }
    scale
}

/// `y = A x` for a full-pattern CSC matrix.
pub fn multiply(pattern: &SymbolicSparseColMat<usize>, values: &[f64], x: &[f64], y: &mut [f64]) {
    y.iter_mut().for_each(|v| *v = 0.0);
    let (cp, ri) = (pattern.col_ptr(), pattern.row_idx());
    for j in 0..pattern.ncols() {
        let xj = x[j];
        for k in cp[j]..cp[j + 1] {
            y[ri[k]] += values[k] * xj;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 1D Laplacian (SPD) solved to round-off, twice with one analysis.
    #[test]
    fn laplacian_solve_reuses_analysis() {
        let n: usize = 50;
        let mut cp = vec![0];
        let mut ri = Vec::new();
        let mut v = Vec::new();
        for j in 0..n {
            for i in j.saturating_sub(1)..(j + 2).min(n) {
                ri.push(i);
                v.push(if i == j { 2.0 } else { -1.0 });
            }
            cp.push(ri.len());
        }
        let pattern = SymbolicSparseColMat::new_checked(n, n, cp, None, ri);
        let mut solver = SparseLdlt::new(Ordering::Amd, 1);
        for scale in [1.0, 3.0] {
            let vals: Vec<f64> = v.iter().map(|x| x * scale).collect();
            solver.factorize(&pattern, &vals, None).unwrap();
            let x_true: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).sin()).collect();
            let mut b = vec![0.0; n];
            multiply(&pattern, &vals, &x_true, &mut b);
            solver.solve_in_place(&mut b).unwrap();
            for i in 0..n {
                assert!((b[i] - x_true[i]).abs() < 1e-12);
            }
        }
        assert_eq!(solver.timings.analyses, 1);
    }

    /// The factor through [`permuted_lower`] (supernodal) equals faer's own
    /// permute-then-factorise bitwise, in f64 and f32, with and without
    /// regularisation signs.
    #[test]
    fn permuted_input_gives_faers_factor_bitwise() {
        let m: usize = 11;
        let n = m * m * m;
        let id = |i: usize, j: usize, k: usize| i + m * (j + m * k);
        let (mut cp, mut ri, mut v) = (vec![0], Vec::new(), Vec::new());
        for c in 0..n {
            let (i, j, k) = (c % m, (c / m) % m, c / (m * m));
            let mut rows = vec![(c, 6.5 + (c % 7) as f64 * 0.1)];
            for (di, dj, dk) in [(1, 0, 0), (0, 1, 0), (0, 0, 1)] {
                if i >= di && j >= dj && k >= dk {
                    rows.push((id(i - di, j - dj, k - dk), -1.0 - 0.01 * (c % 3) as f64));
                }
                if i + di < m && j + dj < m && k + dk < m {
                    rows.push((id(i + di, j + dj, k + dk), -1.0));
                }
            }
            rows.sort_by_key(|r| r.0);
            for (r, _) in &rows {
                ri.push(*r);
            }
            // symmetric values: the lower entry of each pair decides
            for &(r, _) in &rows {
                let (a, b) = (r.max(c), r.min(c));
                v.push(if a == b {
                    6.5 + (a % 7) as f64 * 0.1
                } else {
                    -1.0 - 0.01 * (a % 3) as f64
                });
            }
            cp.push(ri.len());
        }
        let pattern = SymbolicSparseColMat::new_checked(n, n, cp, None, ri);
        let signs = vec![1i8; n];
        for sign in [None, Some(&signs[..])] {
            let mut solver = SparseLdlt::new(Ordering::Amd, 1);
            solver.factorize(&pattern, &v, sign).unwrap();
            let mut single = SparseLdlt::new(Ordering::Amd, 1);
            single.factorize_single(&pattern, &v, sign).unwrap();
            let symbolic = solver.symbolic.as_ref().unwrap();
            assert!(matches!(symbolic.raw(), SymbolicCholeskyRaw::Supernodal(_)));
            let scale = max_abs_diagonal(&pattern, &v);
            let params: Spec<LdltParams, f64> = Default::default();
            let mut mem =
                MemBuffer::new(symbolic.factorize_numeric_ldlt_scratch::<f64>(Par::Seq, params));
            let mut factor = vec![0.0; symbolic.len_val()];
            let a = SparseColMatRef::new(pattern.as_ref(), &v[..]);
            symbolic
                .factorize_numeric_ldlt(
                    &mut factor,
                    a,
                    Side::Lower,
                    regularization(sign, 1e-10 * scale, 1e-13 * scale),
                    Par::Seq,
                    MemStack::new(&mut mem),
                    params,
                )
                .unwrap();
            assert_eq!(factor, solver.factor);
            let v32: Vec<f32> = v.iter().map(|&x| x as f32).collect();
            let params: Spec<LdltParams, f32> = Default::default();
            let mut mem =
                MemBuffer::new(symbolic.factorize_numeric_ldlt_scratch::<f32>(Par::Seq, params));
            let mut factor = vec![0.0f32; symbolic.len_val()];
            let a = SparseColMatRef::new(pattern.as_ref(), &v32[..]);
            let (d, e) = ((1e-10 * scale) as f32, (1e-13 * scale) as f32);
            symbolic
                .factorize_numeric_ldlt(
                    &mut factor,
                    a,
                    Side::Lower,
                    regularization(sign, d, e),
                    Par::Seq,
                    MemStack::new(&mut mem),
                    params,
                )
                .unwrap();
            assert_eq!(factor, single.factor_single);
        }
    }
}
