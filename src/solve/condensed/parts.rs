//! `K̃` factorised as its independent diagonal blocks, side by side.
//!
//! Bodies in contact with each other share no element, and the condensed
//! path's `K̃` is the elements' stiffness alone
//! ([`super::decoupled::Decoupled::within_elements`]), so that after a
//! symmetric permutation it is block diagonal, one block per body, plus
//! the 1 × 1 pivots of its decoupled unknowns:
//!
//! ```text
//! P K̃ Pᵀ = diag(K̃₁, K̃₂, …),   K̃⁻¹ = Pᵀ diag(K̃₁⁻¹, K̃₂⁻¹, …) P.
//! ```
//!
//! A supernodal factorisation (faer's) walks its supernodes one after the
//! other and parallelises only inside a dense block, so the two bodies'
//! elimination trees, which share nothing, are factorised in turn. Here
//! each block (a connected component of the structure) is a
//! [`SparseLdlt`] of its own on one thread, the blocks on the run's
//! threads at once (two bodies of equal size on two cores: half the wall
//! time of the factorisation), and so are its solves and the trailing
//! inverses ([`TrailingInverse`]). The ordering of each block is the
//! whole one restricted to it (the same relative order): the same factor
//! as the whole matrix's in exact arithmetic. One component (a body
//! against a rigid obstacle), or one holding more than
//! [`LARGEST_SHARE`] of the unknowns, keeps the whole matrix in one
//! factor on the run's threads, as before.

use super::schur::TrailingInverse;
use crate::solve::linear::{
    FactorReport, IterativeRefinement, Ordering, Precision, SolverTimings, SparseLdlt,
};
use crate::Result;
use faer::sparse::SymbolicSparseColMat;
use rayon::prelude::*;
use std::time::Instant;

/// A component holding more than this share of the unknowns of all
/// components (the decoupled 1 × 1 pivots apart) keeps the matrix whole:
/// beside it the others would leave a core idle, and inside one factor
/// the dense blocks use every thread.
const LARGEST_SHARE: f64 = 0.75;

/// One diagonal block: its unknowns (ascending), its structure on them
/// (local indices) with the index of each entry in the whole structure's
/// values, and its factor.
struct Part {
    unknowns: Vec<usize>,
    structure: SymbolicSparseColMat<usize>,
    source: Vec<usize>,
    ldlt: SparseLdlt,
}

/// The factor of a symmetric matrix as the factors of its independent
/// diagonal blocks (module docs).
pub struct PartedLdlt {
    parts: Vec<Part>,
    /// Whether the one part is the whole matrix (its indices the whole's).
    whole: bool,
    dimension: usize,
    /// Wall times and counts of the parts together (one part: its own).
    timings: SolverTimings,
}

/// The connected components of a symmetric structure (an entry `(i, j)`
/// joins `i` and `j`): the component of each unknown, numbered from 0 in
/// the order of their smallest unknown.
fn components(structure: &SymbolicSparseColMat<usize>) -> Vec<usize> {
    let n = structure.ncols();
    let mut parent: Vec<usize> = (0..n).collect();
    fn root(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    let (cp, ri) = (structure.col_ptr(), structure.row_idx());
    for j in 0..n {
        for &i in &ri[cp[j]..cp[j + 1]] {
            let (a, b) = (root(&mut parent, i), root(&mut parent, j));
            if a != b {
                parent[a.max(b)] = a.min(b);
            }
        }
    }
    let mut number = vec![usize::MAX; n];
    let mut next = 0;
    (0..n)
        .map(|i| {
            let r = root(&mut parent, i);
            if number[r] == usize::MAX {
                number[r] = next;
                next += 1;
            }
            number[r]
        })
        .collect()
}

/// The unknowns of each part: every component of more than one unknown a
/// part, the single unknowns (decoupled pivots) with the first; one part
/// of every unknown when fewer than two such components or one holds more
/// than [`LARGEST_SHARE`] of them.
fn part_unknowns(structure: &SymbolicSparseColMat<usize>) -> Vec<Vec<usize>> {
    let n = structure.ncols();
    let component = components(structure);
    let count = component.iter().copied().max().map_or(0, |m| m + 1);
    let mut size = vec![0usize; count];
    component.iter().for_each(|&c| size[c] += 1);
    let large: Vec<usize> = (0..count).filter(|&c| size[c] > 1).collect();
    let total: usize = large.iter().map(|&c| size[c]).sum();
    let largest = large.iter().map(|&c| size[c]).max().unwrap_or(0);
    if large.len() < 2 || largest as f64 > LARGEST_SHARE * total as f64 {
        return vec![(0..n).collect()];
    }
    let mut part_of = vec![0usize; count];
    large.iter().enumerate().for_each(|(p, &c)| part_of[c] = p);
    let mut parts = vec![Vec::new(); large.len()];
    for (i, &c) in component.iter().enumerate() {
        parts[part_of[c]].push(i);
    }
    parts
}

impl Part {
    /// The block of `structure` on `unknowns` (ascending), ordered by
    /// `forward` restricted to them, analysed.
    fn analysed(
        structure: &SymbolicSparseColMat<usize>,
        forward: &[usize],
        unknowns: Vec<usize>,
    ) -> Result<Self> {
        let mut local = vec![usize::MAX; structure.ncols()];
        unknowns.iter().enumerate().for_each(|(l, &g)| local[g] = l);
        let (cp, ri) = (structure.col_ptr(), structure.row_idx());
        let (mut col_ptr, mut row_idx, mut source) = (vec![0], Vec::new(), Vec::new());
        for &g in &unknowns {
            for (k, &i) in ri.iter().enumerate().take(cp[g + 1]).skip(cp[g]) {
                if local[i] != usize::MAX {
                    row_idx.push(local[i]);
                    source.push(k);
                }
            }
            col_ptr.push(row_idx.len());
        }
        let m = unknowns.len();
        let block = SymbolicSparseColMat::new_checked(m, m, col_ptr, None, row_idx);
        let order: Vec<usize> = (forward.iter())
            .filter(|&&g| local[g] != usize::MAX)
            .map(|&g| local[g])
            .collect();
        let mut ldlt = SparseLdlt::new(Ordering::Custom(order), 1).threads_as_given();
        ldlt.analyse(&block)?;
        Ok(Part {
            unknowns,
            structure: block,
            source,
            ldlt,
        })
    }

    /// `x` on this part's unknowns, from `v` on every unknown (`columns`
    /// columns of `n` each).
    fn gather(&self, v: &[f64], n: usize, columns: usize) -> Vec<f64> {
        (0..columns)
            .flat_map(|c| self.unknowns.iter().map(move |&g| v[c * n + g]))
            .collect()
    }
}

impl PartedLdlt {
    /// The symbolic analysis of `structure` (a symmetric matrix's lower
    /// triangle, or both) under `ordering`: per independent block when it
    /// has two or more of comparable size (module docs), else whole on
    /// `threads` threads (0: the run's pool, 1: one).
    pub fn analyse(
        structure: &SymbolicSparseColMat<usize>,
        ordering: Ordering,
        threads: usize,
    ) -> Result<Self> {
        let start = Instant::now();
        let dimension = structure.ncols();
        let unknowns = match &ordering {
            Ordering::Custom(_) => part_unknowns(structure),
            Ordering::Amd => vec![(0..dimension).collect()],
        };
        let (parts, whole) = match (&ordering, unknowns.len()) {
            (Ordering::Custom(forward), p) if p > 1 => {
                let parts: Result<Vec<Part>> = (unknowns.into_par_iter())
                    .map(|u| Part::analysed(structure, forward, u))
                    .collect();
                (parts?, false)
            }
            _ => {
                let mut ldlt = SparseLdlt::new(ordering, threads).threads_as_given();
                ldlt.analyse(structure)?;
                let part = Part {
                    unknowns: (0..dimension).collect(),
                    structure: structure.clone(),
                    source: Vec::new(),
                    ldlt,
                };
                (vec![part], true)
            }
        };
        let mut timings = SolverTimings::default();
        timings.symbolic = start.elapsed();
        timings.symbolic_total = timings.symbolic;
        timings.analyses = 1;
        Ok(PartedLdlt {
            parts,
            whole,
            dimension,
            timings,
        })
    }

    /// Number of independent blocks factorised apart.
    pub fn parts(&self) -> usize {
        self.parts.len()
    }

    /// Size (touch the pages of) every factor's storage in `precision`.
    pub fn reserve(&mut self, precision: Precision) {
        (self.parts.par_iter_mut()).for_each(|p| p.ldlt.reserve(precision));
    }

    /// Factorise the matrix of `values` (on the analysed structure) in
    /// `precision`, the blocks at once.
    pub fn factorize(&mut self, values: &[f64], precision: Precision) -> Result<()> {
        let start = Instant::now();
        let whole = self.whole;
        (self.parts.par_iter_mut()).try_for_each(|p| {
            let local: Vec<f64>;
            let v = if whole {
                values
            } else {
                local = p.source.iter().map(|&k| values[k]).collect();
                &local
            };
            match precision {
                Precision::Double => p.ldlt.factorize(&p.structure, v, None),
                Precision::Single => p.ldlt.factorize_single(&p.structure, v, None),
            }
        })?;
        let t = &mut self.timings;
        t.numeric = start.elapsed();
        t.numeric_total += t.numeric;
        match precision {
            Precision::Double => t.factorisations += 1,
            Precision::Single => t.single_factorisations += 1,
        }
        Ok(())
    }

    /// The arithmetic of the last factorisation.
    pub fn precision(&self) -> Precision {
        self.parts[0].ldlt.precision()
    }

    /// Solve `A X = B` in place for `B` of `columns` columns (column-major)
    /// with the last factorisation, the blocks at once.
    pub fn solve_columns_in_place(&mut self, rhs: &mut [f64], columns: usize) -> Result<()> {
        let start = Instant::now();
        if self.whole {
            self.parts[0].ldlt.solve_columns_in_place(rhs, columns)?;
        } else {
            let n = self.dimension;
            let solved: Result<Vec<Vec<f64>>> = (self.parts.par_iter_mut())
                .map(|p| {
                    let mut x = p.gather(rhs, n, columns);
                    p.ldlt.solve_columns_in_place(&mut x, columns)?;
                    Ok(x)
                })
                .collect();
            for (p, x) in self.parts.iter().zip(solved?) {
                let m = p.unknowns.len();
                for c in 0..columns {
                    for (l, &g) in p.unknowns.iter().enumerate() {
                        rhs[c * n + g] = x[c * m + l];
                    }
                }
            }
        }
        self.timings.solve = start.elapsed();
        self.timings.solve_total += self.timings.solve;
        Ok(())
    }

    /// Solve `A x = b` in place with the last factorisation.
    pub fn solve_in_place(&mut self, rhs: &mut [f64]) -> Result<()> {
        self.solve_columns_in_place(rhs, 1)
    }

    /// `(A⁻¹)_TT` on the unknowns `trailing` (each block's ordered last in
    /// it): per block ([`TrailingInverse::of`]) at once, joined.
    pub fn trailing_inverse(&self, trailing: &[usize]) -> Result<TrailingInverse> {
        if self.whole {
            return TrailingInverse::of(&self.parts[0].ldlt, trailing);
        }
        let mut local = vec![usize::MAX; self.dimension];
        for p in &self.parts {
            p.unknowns
                .iter()
                .enumerate()
                .for_each(|(l, &g)| local[g] = l);
        }
        let pieces: Result<Vec<(TrailingInverse, &[usize])>> = (self.parts.par_iter())
            .map(|p| {
                let mut mine = vec![false; self.dimension];
                p.unknowns.iter().for_each(|&g| mine[g] = true);
                let t: Vec<usize> = (trailing.iter())
                    .filter(|&&g| mine[g])
                    .map(|&g| local[g])
                    .collect();
                Ok((TrailingInverse::of(&p.ldlt, &t)?, &p.unknowns[..]))
            })
            .collect();
        Ok(TrailingInverse::joined(self.dimension, pieces?))
    }
}

impl FactorReport for PartedLdlt {
    fn timings(&self) -> SolverTimings {
        if self.whole {
            let mut t = self.parts[0].ldlt.timings;
            t.refinement_steps += self.timings.refinement_steps;
            return t;
        }
        self.timings
    }

    fn factor_nnz(&self) -> usize {
        self.parts.iter().map(|p| p.ldlt.factor_nnz()).sum()
    }
}

impl IterativeRefinement for PartedLdlt {
    fn solve_with_factor(&mut self, rhs: &mut [f64]) -> Result<()> {
        self.solve_in_place(rhs)
    }

    fn timings_mut(&mut self) -> &mut SolverTimings {
        &mut self.timings
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solve::linear::multiply;

    /// Two chains of `n` unknowns (a 1-D Laplacian each, unknowns of the
    /// two interleaved) and two single unknowns: the full structure and
    /// values.
    fn two_chains(n: usize) -> (SymbolicSparseColMat<usize>, Vec<f64>) {
        let dim = 2 * n + 2;
        // chain a: even unknowns 0, 2, …; chain b: odd 1, 3, …; the last
        // two alone
        let neighbours = |j: usize| -> Vec<usize> {
            if j >= 2 * n {
                return vec![j];
            }
            let mut v = vec![j];
            if j >= 2 {
                v.push(j - 2);
            }
            if j + 2 < 2 * n {
                v.push(j + 2);
            }
            v.sort_unstable();
            v
        };
        let (mut col_ptr, mut row_idx, mut values) = (vec![0], Vec::new(), Vec::new());
        for j in 0..dim {
            for i in neighbours(j) {
                row_idx.push(i);
                values.push(if i == j { 2.5 + (j % 3) as f64 } else { -1.0 });
            }
            col_ptr.push(row_idx.len());
        }
        let s = SymbolicSparseColMat::new_checked(dim, dim, col_ptr, None, row_idx);
        (s, values)
    }

    /// The two chains make two parts (the single unknowns with the
    /// first); the solve of both together meets `A x = b` to 1e-13, and
    /// the trailing inverse on unknowns of both equals the columns of
    /// `A⁻¹` solved one by one to 1e-13 (zero across the chains).
    #[test]
    fn independent_blocks_are_factorised_apart() {
        let n = 40;
        let (structure, values) = two_chains(n);
        let dim = structure.ncols();
        let trailing = [2 * n - 4, 2 * n - 2, 2 * n - 3, 2 * n - 1];
        let mut forward: Vec<usize> = (0..dim).filter(|i| !trailing.contains(i)).collect();
        forward.extend(trailing);
        let mut ldlt = PartedLdlt::analyse(&structure, Ordering::Custom(forward), 0).unwrap();
        assert_eq!(ldlt.parts(), 2);
        ldlt.factorize(&values, Precision::Double).unwrap();
        let b: Vec<f64> = (0..dim).map(|i| 1.0 + (i % 7) as f64).collect();
        let mut x = b.clone();
        ldlt.solve_in_place(&mut x).unwrap();
        let mut ax = vec![0.0; dim];
        multiply(&structure, &values, &x, &mut ax);
        for (a, bi) in ax.iter().zip(&b) {
            assert!((a - bi).abs() < 1e-13, "{a} against {bi}");
        }
        let inverse = ldlt.trailing_inverse(&trailing).unwrap();
        assert_eq!(inverse.blocks(), 2);
        for &j in &trailing {
            let mut column = vec![0.0; dim];
            column[j] = 1.0;
            ldlt.solve_in_place(&mut column).unwrap();
            let mut response = vec![0.0; dim];
            inverse.add_response(&vec![(j, 1.0)], &mut response);
            for &i in &trailing {
                assert!((response[i] - column[i]).abs() < 1e-13, "({i}, {j})");
            }
            assert!(column[j].abs() > 0.1);
        }
    }

    /// One chain and its single unknowns stay one factor on the whole
    /// matrix.
    #[test]
    fn one_block_stays_whole() {
        let (structure, values) = two_chains(10);
        let dim = structure.ncols();
        // join the chains: a structure whose only component is large
        let (cp, ri) = (structure.col_ptr(), structure.row_idx());
        // each column's rows, and the entries (0, 1), (1, 0)
        let mut columns: Vec<Vec<usize>> =
            (0..dim).map(|j| ri[cp[j]..cp[j + 1]].to_vec()).collect();
        columns[0].push(1);
        columns[1].push(0);
        let (mut col_ptr, mut row_idx) = (vec![0], Vec::new());
        for mut rows in columns {
            rows.sort_unstable();
            row_idx.extend(rows);
            col_ptr.push(row_idx.len());
        }
        let joined = SymbolicSparseColMat::new_checked(dim, dim, col_ptr, None, row_idx);
        let forward: Vec<usize> = (0..dim).collect();
        let ldlt = PartedLdlt::analyse(&joined, Ordering::Custom(forward), 1).unwrap();
        assert_eq!(ldlt.parts(), 1);
        assert!(values.len() < joined.row_idx().len());
    }
}
