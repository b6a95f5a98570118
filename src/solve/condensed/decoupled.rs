//! A symmetric matrix stored without the couplings of its decoupled
//! unknowns, for the factorisation.
//!
//! The condensed path factorises `K̃`, whose prescribed rows and columns
//! (and those of the unused contact multipliers) are a scaled identity:
//! their off-diagonal entries are zero, but the problem's pattern still
//! stores them, and a symbolic analysis of that pattern makes fill for
//! them as if they were coupled. Dropping them from the structure,
//!
//! ```text
//! keep (i, j)  ⇔  i = j  or  (i and j both coupled),
//! ```
//!
//! leaves the same matrix and the same factor values with less fill: each
//! decoupled unknown is a 1 × 1 pivot of its own. They go first in the
//! ordering ([`decoupled_first`]): interleaved with the coupled unknowns
//! they would split the supernodes (on the small race mesh the f32
//! factorisation took 3× longer that way). On the small race mesh (19 100
//! unknowns, 1 379 prescribed, 737 multipliers) the factor shrinks from
//! 11.4 M to 8.6 M entries.

use crate::solve::linear::Ordering;
use faer::sparse::SymbolicSparseColMat;

/// `ordering` with the `decoupled` unknowns moved to the front (in their
/// order there), the others after them in theirs.
pub fn decoupled_first(ordering: Ordering, decoupled: &[bool]) -> Ordering {
    match ordering {
        Ordering::Amd => Ordering::Amd,
        Ordering::Custom(forward) => {
            let (mut first, rest): (Vec<usize>, Vec<usize>) =
                forward.into_iter().partition(|&i| decoupled[i]);
            first.extend(rest);
            Ordering::Custom(first)
        }
    }
}

/// The structure of a symmetric matrix without the off-diagonal entries
/// of its decoupled rows and columns, and where each kept entry is in the
/// full matrix's values.
#[derive(Debug)]
pub struct Decoupled {
    symbolic: SymbolicSparseColMat<usize>,
    /// `source[k]`: the full values' index of kept entry `k`.
    source: Vec<usize>,
    /// The full values' index of each entry between coupled unknowns
    /// dropped as sharing no element ([`Self::within_elements`]).
    uncoupled: Vec<usize>,
}

impl Decoupled {
    /// From the full (both triangles, sorted rows) `pattern` and the
    /// unknowns whose couplings are dropped (`decoupled[i]`).
    pub fn new(pattern: &SymbolicSparseColMat<usize>, decoupled: &[bool]) -> Self {
        Self::keeping(pattern, decoupled, |_, _| true)
    }

    /// [`Self::new`], and dropped too every entry between two nodes' dofs
    /// (3 per node, numbered first) that share no element in `elements`
    /// (each node's sorted neighbours through the elements): a stiffness
    /// assembled from the elements is zero there (the pattern's contact
    /// couplings), and bodies in contact with each other stay apart in
    /// the factor ([`super::schur::TrailingInverse`]).
    /// [`Self::couples_across`] checks that the values are zero there.
    pub fn within_elements(
        pattern: &SymbolicSparseColMat<usize>,
        decoupled: &[bool],
        elements: &[Vec<usize>],
    ) -> Self {
        let displacements = 3 * elements.len();
        Self::keeping(pattern, decoupled, |i, j| {
            i >= displacements
                || j >= displacements
                || elements[i / 3].binary_search(&(j / 3)).is_ok()
        })
    }

    /// The entries `(i, j)` kept: the diagonal, and those of two coupled
    /// unknowns for which `coupled(i, j)`; the others that `coupled`
    /// drops remembered in `uncoupled`.
    fn keeping(
        pattern: &SymbolicSparseColMat<usize>,
        decoupled: &[bool],
        coupled: impl Fn(usize, usize) -> bool,
    ) -> Self {
        let n = pattern.ncols();
        let (cp, ri) = (pattern.col_ptr(), pattern.row_idx());
        let mut col_ptr = Vec::with_capacity(n + 1);
        let mut row_idx = Vec::with_capacity(ri.len());
        let mut source = Vec::with_capacity(ri.len());
        let mut uncoupled = Vec::new();
        col_ptr.push(0);
        for j in 0..n {
            for (k, &i) in ri.iter().enumerate().take(cp[j + 1]).skip(cp[j]) {
                if i == j || !(decoupled[i] || decoupled[j]) && coupled(i, j) {
                    row_idx.push(i);
                    source.push(k);
                } else if !(decoupled[i] || decoupled[j]) {
                    uncoupled.push(k);
                }
            }
            col_ptr.push(row_idx.len());
        }
        // a subset of the sorted, in-range rows of each column
        let symbolic = SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx);
        Decoupled {
            symbolic,
            source,
            uncoupled,
        }
    }

    /// Whether `full` (values on the full pattern) has a nonzero entry
    /// between two coupled unknowns that [`Self::within_elements`] dropped.
    pub fn couples_across(&self, full: &[f64]) -> bool {
        self.uncoupled.iter().any(|&k| full[k] != 0.0)
    }

    /// The structure the factorisation analyses.
    pub fn symbolic(&self) -> &SymbolicSparseColMat<usize> {
        &self.symbolic
    }

    /// The kept entries of `full` (values on the full pattern).
    pub fn values(&self, full: &[f64]) -> Vec<f64> {
        self.source.iter().map(|&k| full[k]).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solve::linear::{multiply, Ordering, SparseLdlt};

    /// A 1-D Laplacian on 6 unknowns with unknowns 1 and 4 made a scaled
    /// identity: the decoupled factor solves the full system exactly and
    /// its structure holds only their diagonals.
    #[test]
    fn decoupled_factor_solves_the_full_matrix() {
        let n: usize = 6;
        let mut col_ptr = vec![0];
        let mut row_idx = Vec::new();
        for j in 0..n {
            row_idx.extend(j.saturating_sub(1)..(j + 2).min(n));
            col_ptr.push(row_idx.len());
        }
        let pattern = SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx);
        let fixed = [false, true, false, false, true, false];
        let (cp, ri) = (pattern.col_ptr(), pattern.row_idx());
        let mut values = vec![0.0; ri.len()];
        for j in 0..n {
            for k in cp[j]..cp[j + 1] {
                let i = ri[k];
                values[k] = match (i == j, fixed[i] || fixed[j]) {
                    (true, true) => 3.0,
                    (true, false) => 2.0,
                    (false, true) => 0.0,
                    (false, false) => -1.0,
                };
            }
        }
        let reduced = Decoupled::new(&pattern, &fixed);
        let (rcp, rri) = (reduced.symbolic().col_ptr(), reduced.symbolic().row_idx());
        assert_eq!(&rri[rcp[1]..rcp[2]], &[1]);
        assert_eq!(&rri[rcp[4]..rcp[5]], &[4]);
        assert_eq!(&rri[rcp[2]..rcp[3]], &[2, 3]);
        let b: Vec<f64> = (0..n).map(|i| 1.0 + i as f64).collect();
        let mut x = b.clone();
        let mut ldlt = SparseLdlt::new(Ordering::Amd, 1);
        ldlt.factorize(reduced.symbolic(), &reduced.values(&values), None)
            .unwrap();
        ldlt.solve_in_place(&mut x).unwrap();
        let mut ax = vec![0.0; n];
        multiply(&pattern, &values, &x, &mut ax);
        for (a, bi) in ax.iter().zip(&b) {
            assert!((a - bi).abs() < 1e-13, "{a} against {bi}");
        }
    }
}
