//! The lower triangle of a symmetric matrix on a [`SparsityPattern`]:
//! what an LDLᵀ factorisation reads, stored alone.
//!
//! The pattern stores both triangles (the LU, GMRES and the nonsymmetric
//! frictional or follower-load tangents read them). A symmetric matrix
//! that only a factorisation and products read needs half: the entries
//! `(i, j)` with `i ≥ j`, in compressed sparse columns. Column `j` of the
//! triangle is the tail of the pattern's column `j` from its diagonal
//! (rows are sorted), so the triangle's entries are in the same order as
//! the pattern's and an entry's position follows from its column alone:
//!
//! ```text
//! lower(k) = c_j + (k − p_j − s_j),   k in column j of the pattern,
//! ```
//!
//! `p_j`, `c_j` the columns' starts in the pattern and the triangle,
//! `s_j` the number of rows above the diagonal in column `j`.
//!
//! The product with the whole matrix, `y = A x = L x + Lᵀ x − D x`
//! ([`multiply`]), reads each stored entry once for two products: a
//! column's dot product with `x` (`Lᵀ x`) and its scatter into `y`
//! (`L x`), the diagonal once.

use super::pattern::SparsityPattern;
use faer::sparse::SymbolicSparseColMat;

/// The structure of the lower triangle of one pattern.
#[derive(Debug)]
pub struct LowerTriangle {
    /// `pattern.id()` of the pattern it was taken from.
    pattern_id: u64,
    /// Rows `≥ j` of each column `j`, sorted (the diagonal first).
    symbolic: SymbolicSparseColMat<usize>,
    /// `s_j`: rows of the pattern's column `j` above the diagonal.
    above: Vec<usize>,
}

impl LowerTriangle {
    /// The lower triangle of `pattern` (an empty column stays empty).
    pub fn of(pattern: &SparsityPattern) -> Self {
        // the rows read from the pattern's adjacency
        // ([`SparsityPattern::column_rows`]): its whole row indices are
        // not made for this
        let cp = pattern.col_ptr();
        let n = pattern.dimension();
        let mut col_ptr = Vec::with_capacity(n + 1);
        let mut row_idx = Vec::with_capacity((pattern.nnz() + n) / 2);
        let mut above = Vec::with_capacity(n);
        col_ptr.push(0);
        for j in 0..n {
            let before = row_idx.len();
            row_idx.extend(pattern.column_rows(j).skip_while(|&i| i < j));
            above.push(cp[j + 1] - cp[j] - (row_idx.len() - before));
            col_ptr.push(row_idx.len());
        }
        // sorted tails of sorted, in-range columns
        let symbolic = SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx);
        LowerTriangle {
            pattern_id: pattern.id(),
            symbolic,
            above,
        }
    }

    /// Whether this is the triangle of `pattern`.
    pub fn is_for(&self, pattern: &SparsityPattern) -> bool {
        self.pattern_id == pattern.id()
    }

    /// The structure, for a factorisation on `Side::Lower`.
    pub fn symbolic(&self) -> &SymbolicSparseColMat<usize> {
        &self.symbolic
    }

    /// Number of stored entries.
    pub fn nnz(&self) -> usize {
        self.symbolic.row_idx().len()
    }

    /// Index of the diagonal entry of unknown `d` (the first of its
    /// column), for a `d` whose diagonal the pattern stores (all of them
    /// but on a process's pattern under `mpirun`, whose columns of the
    /// nodes it does not touch are empty:
    /// [`SparsityPattern::stored_diagonal`]).
    #[inline]
    pub fn diagonal_entry(&self, d: usize) -> usize {
        self.symbolic.col_ptr()[d]
    }

    /// Offsets from the position of entry (row `3a`, column `3b`) to
    /// those of entries (row `3a`, column `3b + j`), `j = 0, 1, 2`, for
    /// node `a ≥ b` coupled to `b`: rows `3a + i` follow contiguously
    /// (from `i = j` when `a = b`, where row `3b + i` sits at offset
    /// `i − j` in column `3b + j`). The triangle's three columns of a node
    /// hold 0, 1 and 2 rows fewer than the first.
    #[inline]
    pub fn node_column_offsets(&self, b: usize) -> [usize; 3] {
        let cp = self.symbolic.col_ptr();
        let first = cp[3 * b];
        [0, cp[3 * b + 1] - first - 1, cp[3 * b + 2] - first - 2]
    }

    /// Position of entry (row `3a`, column `3b`) for nodes `a ≥ b` that
    /// `pattern` couples (`None` otherwise): in the pattern at
    /// `p + 3 r_a` (`r_a` the rank of `a` among `b`'s neighbours), in the
    /// triangle at `c + 3 (r_a − r_b)`.
    pub fn block_start(&self, pattern: &SparsityPattern, a: usize, b: usize) -> Option<usize> {
        if a < b {
            return None;
        }
        let full = pattern.block_columns(a, b)?[0];
        Some(self.position(pattern, full, 3 * b))
    }

    /// Position in the triangle of the pattern's entry `k` of column `j`
    /// (which must be on or below the diagonal).
    #[inline]
    fn position(&self, pattern: &SparsityPattern, k: usize, j: usize) -> usize {
        self.symbolic.col_ptr()[j] + (k - pattern.col_ptr()[j] - self.above[j])
    }

    /// The lower triangle of `full` (values on `pattern`).
    pub fn values(&self, full: &[f64]) -> Vec<f64> {
        let cp = self.symbolic.col_ptr();
        let mut lower = Vec::with_capacity(self.nnz());
        let mut start = 0;
        for (j, &s) in self.above.iter().enumerate() {
            let len = cp[j + 1] - cp[j];
            lower.extend_from_slice(&full[start + s..start + s + len]);
            start += s + len;
        }
        lower
    }

    /// The whole symmetric matrix on `pattern` from its lower triangle
    /// `lower`: each column's tail copied, then each entry above the
    /// diagonal set to its mirror's.
    pub fn expand_into(&self, pattern: &SparsityPattern, lower: &[f64], full: &mut [f64]) {
        let (cp, full_cp) = (self.symbolic.col_ptr(), pattern.col_ptr());
        for (j, &s) in self.above.iter().enumerate() {
            let start = full_cp[j] + s;
            full[start..full_cp[j + 1]].copy_from_slice(&lower[cp[j]..cp[j + 1]]);
        }
        pattern.mirror_lower_into_upper(full);
    }
}

/// `y = A x` for the symmetric `A` whose lower triangle (CSC, rows `≥ j`
/// in column `j`, the diagonal first) is `values` on `lower`:
/// `y = L x + Lᵀ x − D x`. `yᵢ` is the sum, in the order of the columns
/// `j < i`, of the scatters `aᵢⱼ xⱼ` (`L x` without the diagonal), plus
/// column `i`'s dot product `Σ_{k ≥ i} aₖᵢ xₖ` (`Lᵀ x`) last: on the
/// rayon pool's threads the scatters and the dot products are two passes
/// over the columns side by side ([`scatter_below`], [`column_dots`]),
/// on one thread one pass; the same sums in the same order, so `y` does
/// not depend on the threads (bitwise). A shorter `x` multiplies the
/// leading block of its size (the displacements of a matrix with
/// multipliers after them) and `y` is zero below it.
pub fn multiply(lower: &SymbolicSparseColMat<usize>, values: &[f64], x: &[f64], y: &mut [f64]) {
    y.iter_mut().for_each(|v| *v = 0.0);
    let m = x.len().min(lower.ncols());
    if rayon::current_num_threads() > 1 {
        let mut dots = vec![0.0; m];
        rayon::join(
            || scatter_below(lower, values, x, y),
            || column_dots(lower, values, x, &mut dots),
        );
        y.iter_mut().zip(&dots).for_each(|(yj, d)| *yj += d);
        return;
    }
    let (cp, ri) = (lower.col_ptr(), lower.row_idx());
    for j in 0..m {
        let xj = x[j];
        let mut dot = 0.0;
        for k in cp[j]..cp[j + 1] {
            let i = ri[k];
            if i >= m {
                break; // sorted: the rest is below the block
            }
            let a = values[k];
            dot += a * x[i];
            if i != j {
                y[i] += a * xj;
            }
        }
        y[j] += dot;
    }
}

/// `yᵢ += aᵢⱼ xⱼ` for every entry below the diagonal of the leading block
/// of `x`'s size, column by column.
fn scatter_below(lower: &SymbolicSparseColMat<usize>, values: &[f64], x: &[f64], y: &mut [f64]) {
    let (cp, ri) = (lower.col_ptr(), lower.row_idx());
    let m = x.len().min(lower.ncols());
    for (j, &xj) in x.iter().enumerate().take(m) {
        for k in cp[j]..cp[j + 1] {
            let i = ri[k];
            if i >= m {
                break;
            }
            if i != j {
                y[i] += values[k] * xj;
            }
        }
    }
}

/// `dⱼ = Σ_{i ≥ j} aᵢⱼ xᵢ` (in the order of the rows) for the columns `j`
/// of the leading block of `d`'s size.
fn column_dots(lower: &SymbolicSparseColMat<usize>, values: &[f64], x: &[f64], d: &mut [f64]) {
    let (cp, ri) = (lower.col_ptr(), lower.row_idx());
    let m = d.len();
    for (j, dj) in d.iter_mut().enumerate() {
        let mut dot = 0.0;
        for k in cp[j]..cp[j + 1] {
            let i = ri[k];
            if i >= m {
                break;
            }
            dot += values[k] * x[i];
        }
        *dj = dot;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A pattern with two multipliers in a group, values `A_ij = f(i, j)`
    /// symmetric.
    fn pattern_and_values() -> (SparsityPattern, Vec<f64>) {
        let elements: Vec<Vec<usize>> = vec![vec![0, 1, 2, 4], vec![1, 2, 3], vec![3, 4]];
        let p = SparsityPattern::with_multiplier_groups(
            5,
            elements.iter().map(|e| e.as_slice()),
            &[vec![1, 3], vec![3]],
            &[vec![1], vec![0]],
        );
        let (cp, ri) = (p.symbolic().col_ptr(), p.symbolic().row_idx());
        let mut values = vec![0.0; p.nnz()];
        for j in 0..p.dimension() {
            for k in cp[j]..cp[j + 1] {
                let (i, j) = (ri[k] as f64, j as f64);
                values[k] = (i + j + 1.0).sqrt() + (i * j).cos();
            }
        }
        (p, values)
    }

    /// The triangle holds the pattern's entries on and below the diagonal,
    /// expands back to the whole matrix bitwise, finds every node block
    /// and the diagonal, and its product is the whole matrix's.
    #[test]
    fn the_triangle_holds_the_lower_entries_and_multiplies_as_the_whole() {
        let (p, full) = pattern_and_values();
        let t = LowerTriangle::of(&p);
        assert!(t.is_for(&p));
        let n = p.dimension();
        assert_eq!(t.nnz(), (p.nnz() + n) / 2);
        let lower = t.values(&full);
        let (cp, ri) = (t.symbolic().col_ptr(), t.symbolic().row_idx());
        for j in 0..n {
            assert_eq!(ri[t.diagonal_entry(j)], j);
            for k in cp[j]..cp[j + 1] {
                assert!(ri[k] >= j);
                if ri[k] < 3 * p.num_nodes() {
                    let e = p.block_entry(ri[k] / 3, ri[k] % 3, j / 3, j % 3);
                    assert_eq!(lower[k], full[e.unwrap()]);
                }
            }
        }
        let mut back = vec![0.0; p.nnz()];
        t.expand_into(&p, &lower, &mut back);
        assert_eq!(back, full);
        for b in 0..p.num_nodes() {
            for a in 0..p.num_nodes() {
                let Some(start) = t.block_start(&p, a, b) else {
                    assert!(a < b || p.block_entry(a, 0, b, 0).is_none());
                    continue;
                };
                let offsets = t.node_column_offsets(b);
                for (j, offset) in offsets.iter().enumerate() {
                    let first = if a == b { j } else { 0 };
                    for i in first..3 {
                        let full_k = p.block_entry(a, i, b, j).unwrap();
                        assert_eq!(lower[start + offset + i], full[full_k]);
                    }
                }
            }
        }
        let x: Vec<f64> = (0..n).map(|i| (0.7 * i as f64).sin() - 0.2).collect();
        let (mut y_full, mut y) = (vec![0.0; n], vec![1.0; n]);
        let (fcp, fri) = (p.symbolic().col_ptr(), p.symbolic().row_idx());
        for j in 0..n {
            for k in fcp[j]..fcp[j + 1] {
                y_full[fri[k]] += full[k] * x[j];
            }
        }
        multiply(t.symbolic(), &lower, &x, &mut y);
        let scale = y_full.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for (a, b) in y.iter().zip(&y_full) {
            assert!((a - b).abs() <= 1e-14 * scale, "{a} against {b}");
        }
    }

    /// The product on two threads (scatters and dot products side by
    /// side) is the one-thread product bitwise, for the whole `x` and for
    /// a leading block.
    #[test]
    fn the_product_does_not_depend_on_the_threads() {
        let (p, full) = pattern_and_values();
        let t = LowerTriangle::of(&p);
        let lower = t.values(&full);
        let n = p.dimension();
        for m in [n, n - 2, 7] {
            let x: Vec<f64> = (0..m).map(|i| (1.3 * i as f64).cos() / 3.0).collect();
            let product = |threads: usize| {
                let pool = rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .build()
                    .unwrap();
                let mut y = vec![f64::NAN; n];
                pool.install(|| multiply(t.symbolic(), &lower, &x, &mut y));
                y
            };
            let (one, two) = (product(1), product(2));
            assert!(one
                .iter()
                .zip(&two)
                .all(|(a, b)| a.to_bits() == b.to_bits()));
            assert!(one[m..].iter().all(|v| *v == 0.0));
        }
    }
}
