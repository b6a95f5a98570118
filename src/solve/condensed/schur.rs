//! The block of `K⁻¹` on a few unknowns read off the LDLᵀ factor, and the
//! flexibility `W = Eᵀ K⁻¹ E` of a set of sparse directions built from it.
//!
//! ## The trailing block
//! Order the unknowns `T` (`c` of them, e.g. the normal displacement of
//! the contact nodes) last: `P K Pᵀ = L D Lᵀ` with
//!
//! ```text
//! P K Pᵀ = [ A   B ]     L = [ L_AA    0   ]
//!          [ Bᵀ  C ],        [ L_TA  L_TT ].
//! ```
//!
//! `L⁻¹` is lower triangular, so `(L⁻¹)_{kT} = 0` for `k` before `T` and
//!
//! ```text
//! (K⁻¹)_TT = (L⁻ᵀ D⁻¹ L⁻¹)_TT = L_TT⁻ᵀ D_T⁻¹ L_TT⁻¹ = S⁻¹,
//! ```
//!
//! `S = C − Bᵀ A⁻¹ B = L_TT D_T L_TTᵀ` the Schur complement, which the
//! supernodal factorisation has already computed in its trailing
//! supernodes (George and Liu, *Computer Solution of Large Sparse Positive
//! Definite Systems*, 1981, §2.1; the "Schur complement feature" of
//! MUMPS and PARDISO). Reading it costs a dense `c × c` triangular
//! inverse and product (`≈ 2c³/3` flops) instead of `c` solves with the
//! whole factor (`4 nnz(L)` flops each): on examples/hertz (15 M factor
//! entries, 925 contact nodes) about 1 GFLOP instead of 26.
//!
//! ## The flexibility
//! `W_ij = e_iᵀ K⁻¹ e_j` for directions `e_i` (sparse vectors over the
//! unknowns). When both lie on `T` it is `e_iᵀ (K⁻¹)_TT e_j`; a direction
//! that leaves `T` gets its column by a block solve with the factor, as
//! before.

use crate::assembly::pattern::SparsityPattern;
use crate::solve::linear::FactorValues;
use crate::solve::linear::{Ordering, SparseLdlt};
use crate::solve::ordering::{element_dissection, EarlyDissection};
use crate::{Error, Result};
use faer::linalg::matmul::triangular::BlockStructure;
use faer::sparse::linalg::cholesky::{SymbolicCholesky, SymbolicCholeskyRaw};
use faer::{Mat, Par};
use nalgebra::DMatrix;

/// From this many trailing unknowns the Schur complement of
/// [`trailing_schur`] is made on the run's threads, below on one.
/// `(K⁻¹)_TT` ([`TrailingInverse::of`]) instead runs on the factor's own
/// threads ([`SparseLdlt::parallelism`]), so that one constant decides
/// for both on the condensed path: at `c` = 737 (the small race; `L_TT⁻¹`
/// and the product, about `2.3 c³` = 0.9 GFLOP) one thread made the whole
/// run 3 % faster beside builders (8 pairs, load 7.6).
const PARALLEL_TRAILING: usize = 1500;

/// A direction `e`: `(unknown, component)` pairs.
pub type Direction = Vec<(usize, f64)>;

/// Right-hand sides solved together for the directions outside `T`.
const BLOCK: usize = 64;

/// The nested-dissection ordering of `pattern`'s elements' node graph
/// (without its contact couplings: the factor drops them,
/// [`super::decoupled::Decoupled::within_elements`]; each node's dofs
/// together, each multiplier after its node), with the unknowns
/// marked in `trailing` moved to the end in the same relative order
/// (the dissection `early`'s when it is of that graph), grouped by the
/// body (connected set of elements) they belong to: bodies in contact
/// share no element, so `K` couples no unknown of one with one of
/// another, their trailing unknowns contiguous make `L_TT` block
/// diagonal, one dense block per body ([`TrailingInverse`]).
pub fn trailing_ordering(
    pattern: &SparsityPattern,
    trailing: &[bool],
    early: Option<&EarlyDissection>,
) -> Result<Ordering> {
    let nodes = element_dissection(pattern, early)?;
    let forward = pattern.dof_ordering(&nodes);
    let (mut front, mut back): (Vec<usize>, Vec<usize>) =
        forward.into_iter().partition(|&i| !trailing[i]);
    let body = element_components(pattern);
    // stable: within a body the dissection's order
    back.sort_by_key(|&i| body.get(i / 3).copied().unwrap_or(usize::MAX));
    front.extend(back);
    Ok(Ordering::Custom(front))
}

/// The connected component of each node in `pattern`'s element graph
/// (the elements' adjacency, without contact couplings), numbered from 0.
fn element_components(pattern: &SparsityPattern) -> Vec<usize> {
    let neighbours = pattern.element_neighbours();
    let mut component = vec![usize::MAX; neighbours.len()];
    let mut stack = Vec::new();
    let mut next = 0;
    for start in 0..neighbours.len() {
        if component[start] != usize::MAX {
            continue;
        }
        component[start] = next;
        stack.push(start);
        while let Some(a) = stack.pop() {
            for &b in &neighbours[a] {
                if component[b] == usize::MAX {
                    component[b] = next;
                    stack.push(b);
                }
            }
        }
        next += 1;
    }
    component
}

/// The factor of `ldlt` and where the unknowns `trailing` are in its last
/// `trailing.len()` columns: the first of those columns, and each
/// unknown's position among them (`usize::MAX`: not in `T`); an error if
/// one of them is not there.
fn trailing_positions<'a>(
    ldlt: &'a SparseLdlt,
    trailing: &[usize],
) -> Result<(
    &'a SymbolicCholesky<usize>,
    FactorValues<'a>,
    usize,
    Vec<usize>,
)> {
    let (symbolic, values) = ldlt
        .factor_parts()
        .ok_or_else(|| Error::LinearSolver("the trailing block needs a factorisation".into()))?;
    let n = symbolic.nrows();
    let first = n - trailing.len();
    let inverse: Vec<usize> = match symbolic.perm() {
        Some(p) => p.arrays().1.to_vec(),
        None => (0..n).collect(),
    };
    let mut position = vec![usize::MAX; n];
    for &i in trailing {
        let at = inverse[i];
        if at < first {
            return Err(Error::LinearSolver(format!(
                "unknown {i} is not in the factor's trailing block"
            )));
        }
        position[i] = at - first;
    }
    Ok((symbolic, values, first, position))
}

/// Every stored entry of the factor's columns from `first` on, as
/// `visit(row, column, value)` with positions counted from `first`
/// (`row ≥ column`; on the diagonal `D`, below it `L`).
fn trailing_entries(
    symbolic: &SymbolicCholesky<usize>,
    values: &FactorValues<'_>,
    first: usize,
    mut visit: impl FnMut(usize, usize, f64),
) {
    match symbolic.raw() {
        SymbolicCholeskyRaw::Supernodal(s) => {
            let (begin, end) = (s.supernode_begin(), s.supernode_end());
            let (ptr_row, ptr_val, rows) =
                (s.col_ptr_for_row_idx(), s.col_ptr_for_val(), s.row_idx());
            for k in 0..s.n_supernodes() {
                if end[k] <= first {
                    continue;
                }
                let width = end[k] - begin[k];
                let pattern = &rows[ptr_row[k]..ptr_row[k + 1]];
                let height = width + pattern.len();
                for jj in 0..width {
                    let j = begin[k] + jj;
                    if j < first {
                        continue;
                    }
                    let column = ptr_val[k] + jj * height;
                    for ii in jj..width {
                        visit(begin[k] + ii - first, j - first, values.get(column + ii));
                    }
                    for (p, &row) in pattern.iter().enumerate() {
                        visit(row - first, j - first, values.get(column + width + p));
                    }
                }
            }
        }
        SymbolicCholeskyRaw::Simplicial(s) => {
            let factor = s.factor();
            let (cp, ri) = (factor.col_ptr(), factor.row_idx());
            for j in first..symbolic.nrows() {
                for (k, &row) in ri.iter().enumerate().take(cp[j + 1]).skip(cp[j]) {
                    visit(row - first, j - first, values.get(k));
                }
            }
        }
    }
}

/// The diagonal blocks of the factor's trailing `c` columns from `first`
/// on, from its structure: the start of each (ascending, from 0), a
/// block ending where no stored entry of a column before it lies in a row
/// after it. Unknowns that `K` does not couple (two bodies) make two.
fn trailing_blocks(symbolic: &SymbolicCholesky<usize>, first: usize, c: usize) -> Vec<usize> {
    // the last stored row of each trailing column
    let mut reach: Vec<usize> = (0..c).collect();
    match symbolic.raw() {
        SymbolicCholeskyRaw::Supernodal(s) => {
            let (begin, end) = (s.supernode_begin(), s.supernode_end());
            let (ptr_row, rows) = (s.col_ptr_for_row_idx(), s.row_idx());
            for k in 0..s.n_supernodes() {
                if end[k] <= first {
                    continue;
                }
                let pattern = &rows[ptr_row[k]..ptr_row[k + 1]];
                let last = pattern.iter().copied().fold(end[k] - 1, usize::max);
                for j in begin[k].max(first)..end[k] {
                    reach[j - first] = last - first;
                }
            }
        }
        SymbolicCholeskyRaw::Simplicial(s) => {
            let factor = s.factor();
            let (cp, ri) = (factor.col_ptr(), factor.row_idx());
            for j in first..symbolic.nrows() {
                let rows = &ri[cp[j]..cp[j + 1]];
                reach[j - first] = rows.iter().copied().fold(j, usize::max) - first;
            }
        }
    }
    let mut starts = vec![0];
    let mut furthest = 0;
    for (p, &r) in reach.iter().enumerate() {
        furthest = furthest.max(r);
        if furthest == p && p + 1 < c {
            starts.push(p + 1);
        }
    }
    starts
}

/// The trailing block of an LDLᵀ factor: `L_TT` (unit lower, dense) and
/// `D_T`, whose product `L_TT D_T L_TTᵀ` is the Schur complement `S`.
struct TrailingFactor {
    /// Index of each unknown in the block (`usize::MAX`: not in `T`).
    position: Vec<usize>,
    l: Mat<f64>,
    d: Vec<f64>,
}

impl TrailingFactor {
    /// `L_TT` and `D_T` from the last factorisation of `ldlt` (in f64
    /// arithmetic from an f32 factor's values), for the unknowns `trailing`
    /// (all of them in the last `trailing.len()` positions of its ordering,
    /// else an error; a zero pivot among them is an error too).
    fn of(ldlt: &SparseLdlt, trailing: &[usize]) -> Result<Self> {
        let (symbolic, values, first, position) = trailing_positions(ldlt, trailing)?;
        let c = trailing.len();
        let mut l = Mat::<f64>::zeros(c, c);
        let mut d = vec![0.0; c];
        trailing_entries(symbolic, &values, first, |row, col, v| {
            if row == col {
                d[col] = v;
            } else {
                l[(row, col)] = v;
            }
        });
        check_pivots(&d)?;
        Ok(TrailingFactor { position, l, d })
    }
}

/// An error for a zero (or not finite) pivot of the trailing block.
fn check_pivots(d: &[f64]) -> Result<()> {
    if d.iter().any(|v| *v == 0.0 || !v.is_finite()) {
        return Err(Error::LinearSolver(
            "a zero pivot in the trailing block".into(),
        ));
    }
    Ok(())
}

/// `(L D Lᵀ)⁻¹ = L⁻ᵀ D⁻¹ L⁻¹` for a unit lower `L` (its strict lower
/// triangle in `l`) and the diagonal `d`, in two `c × c` matrices (each
/// costs its page faults, about 4 ms for `c` = 1 100): `M = L⁻¹` in the
/// strict lower triangle of a new one and `L⁻ᵀ D⁻¹` (`M`'s transpose, its
/// columns over `d`) in its upper triangle with the diagonal, then their
/// product, an upper triangle times a unit lower one, its lower triangle
/// only (`c³/6` multiply-adds instead of the dense product's `c³`), into
/// `l`'s storage (no longer read), mirrored; on `par` (as faer's own
/// dense `ldlt::inverse`).
fn ldl_inverse(l: Mat<f64>, d: &[f64], par: Par) -> Mat<f64> {
    let c = d.len();
    let mut m = Mat::<f64>::zeros(c, c);
    faer::linalg::triangular_inverse::invert_unit_lower_triangular(m.as_mut(), l.as_ref(), par);
    for j in 0..c {
        m[(j, j)] = 1.0 / d[j];
    }
    transpose_lower(m.as_mut(), |i, v| v / d[i]);
    let mut inverse = l;
    faer::linalg::matmul::triangular::matmul(
        inverse.as_mut(),
        BlockStructure::TriangularLower,
        faer::Accum::Replace,
        m.as_ref(),
        BlockStructure::TriangularUpper,
        m.as_ref(),
        BlockStructure::UnitTriangularLower,
        1.0,
        par,
    );
    transpose_lower(inverse.as_mut(), |_, v| v);
    inverse
}

/// Entry `(j, i)` of the square `a` set to `weigh(i, a[(i, j)])` for
/// every `i > j`: its strict lower triangle copied into the upper one, in
/// tiles (a column of one is a row of the other: entry by entry every
/// write would touch a new cache line).
fn transpose_lower(mut a: faer::MatMut<'_, f64>, weigh: impl Fn(usize, f64) -> f64) {
    const TILE: usize = 64;
    let c = a.nrows();
    for jb in (0..c).step_by(TILE) {
        for ib in (jb..c).step_by(TILE) {
            for j in jb..(jb + TILE).min(c) {
                for i in ib.max(j + 1)..(ib + TILE).min(c) {
                    a[(j, i)] = weigh(i, a[(i, j)]);
                }
            }
        }
    }
}

/// `(K⁻¹)_TT`, read from the factor of `K` whose ordering put the
/// unknowns `T` last ([`trailing_ordering`]), as its diagonal blocks:
/// where `K` couples no unknown of one set of `T` with one of another
/// (bodies in contact with each other), `L_TT`, `S` and `S⁻¹` are block
/// diagonal, and each block costs `(2/3) b³` flops to invert instead of
/// the whole block's `(2/3) c³` (two bodies of equal share: a quarter).
#[derive(Clone, Debug)]
pub struct TrailingInverse {
    /// Index of each unknown in `T` (`usize::MAX`: not in `T`).
    position: Vec<usize>,
    /// The first position of each diagonal block, ascending, and its
    /// inverse.
    blocks: Vec<(usize, Mat<f64>)>,
    /// The block of each position in `T`.
    block_of: Vec<usize>,
}

impl TrailingInverse {
    /// No block: every direction is solved with the factor.
    pub fn empty(dimension: usize) -> Self {
        TrailingInverse {
            position: vec![usize::MAX; dimension],
            blocks: Vec::new(),
            block_of: Vec::new(),
        }
    }

    /// `(K⁻¹)_TT = L_TT⁻ᵀ D_T⁻¹ L_TT⁻¹` from the last factorisation of
    /// `ldlt` (in f64 arithmetic from an f32 factor's values: then the
    /// inverse of the f32 factor's Schur complement), for the unknowns
    /// `trailing` (all of them in the last `trailing.len()` positions of
    /// its ordering, else an error), block by diagonal block of the
    /// factor's structure ([`ldl_inverse`] each, on the factor's threads).
    pub fn of(ldlt: &SparseLdlt, trailing: &[usize]) -> Result<Self> {
        let (symbolic, values, first, position) = trailing_positions(ldlt, trailing)?;
        let c = trailing.len();
        let starts = trailing_blocks(symbolic, first, c);
        let mut block_of = vec![0; c];
        for (k, &s) in starts.iter().enumerate() {
            block_of[s..].iter_mut().for_each(|b| *b = k);
        }
        let size = |k: usize| starts.get(k + 1).copied().unwrap_or(c) - starts[k];
        let mut l: Vec<Mat<f64>> = (0..starts.len())
            .map(|k| Mat::zeros(size(k), size(k)))
            .collect();
        let mut d = vec![0.0; c];
        // a stored row lies in its column's block (`trailing_blocks`)
        trailing_entries(symbolic, &values, first, |row, col, v| {
            let (k, s) = (block_of[col], starts[block_of[col]]);
            if row == col {
                d[col] = v;
            } else {
                l[k][(row - s, col - s)] = v;
            }
        });
        check_pivots(&d)?;
        let par = ldlt.parallelism();
        let blocks = (l.into_iter().enumerate())
            .map(|(k, l)| {
                (
                    starts[k],
                    ldl_inverse(l, &d[starts[k]..starts[k] + size(k)], par),
                )
            })
            .collect();
        Ok(TrailingInverse {
            position,
            blocks,
            block_of,
        })
    }

    /// The inverse of a block diagonal matrix's trailing block from each
    /// diagonal block's own ([`Self::of`] on its factor), each `piece` on
    /// its own unknowns (`unknowns[local]` the index among `dimension`):
    /// their blocks side by side.
    pub fn joined(dimension: usize, pieces: Vec<(TrailingInverse, &[usize])>) -> Self {
        let mut position = vec![usize::MAX; dimension];
        let (mut blocks, mut block_of) = (Vec::new(), Vec::new());
        for (piece, unknowns) in pieces.into_iter().filter(|(p, _)| !p.is_empty()) {
            let (offset, first_block) = (block_of.len(), blocks.len());
            for (l, &p) in piece.position.iter().enumerate() {
                if p != usize::MAX {
                    position[unknowns[l]] = offset + p;
                }
            }
            block_of.extend(piece.block_of.iter().map(|b| first_block + b));
            blocks.extend(piece.blocks.into_iter().map(|(s, m)| (offset + s, m)));
        }
        TrailingInverse {
            position,
            blocks,
            block_of,
        }
    }

    /// Number of unknowns in `T`.
    pub fn len(&self) -> usize {
        self.block_of.len()
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Number of diagonal blocks of `(K⁻¹)_TT`.
    pub fn blocks(&self) -> usize {
        self.blocks.len()
    }

    /// Whether every component of `e` lies on `T`.
    pub fn covers(&self, e: &Direction) -> bool {
        e.iter()
            .all(|&(i, _)| self.position.get(i).is_some_and(|&p| p != usize::MAX))
    }

    /// `(K⁻¹)_TT b` on `T` (in the block's order) for a direction `b` on
    /// `T`: a sum of the blocks' columns (contiguous), as many
    /// multiply-adds per entry of `b` as its block has rows.
    fn apply(&self, b: &Direction) -> Vec<f64> {
        let mut z = vec![0.0; self.len()];
        for &(j, bj) in b {
            let p = self.position[j];
            let (s, block) = &self.blocks[self.block_of[p]];
            let column = block.col_as_slice(p - s);
            z[*s..*s + column.len()]
                .iter_mut()
                .zip(column)
                .for_each(|(zi, kij)| *zi += bj * kij);
        }
        z
    }
    /// `v_T += (K⁻¹)_TT e` for a direction `e` on `T`: the displacement of
    /// the unknowns `T` under the load `e` (`v` on every unknown, the
    /// others untouched).
    /// The entries of `e` on one unknown are summed first (a load of many
    /// nodes' columns repeats the primary nodes they share): one column of
    /// the block per unknown.
    pub fn add_response(&self, e: &Direction, v: &mut [f64]) {
        let mut merged = vec![0.0; self.len()];
        let mut unknown = vec![usize::MAX; self.len()];
        for &(i, ei) in e {
            let p = self.position[i];
            merged[p] += ei;
            unknown[p] = i;
        }
        let once: Direction = (unknown.iter().zip(&merged))
            .filter(|(&i, _)| i != usize::MAX)
            .map(|(&i, &m)| (i, m))
            .collect();
        let z = self.apply(&once);
        for (i, &p) in self.position.iter().enumerate() {
            if p != usize::MAX {
                v[i] += z[p];
            }
        }
    }

    /// `aᵀ z` for a direction `a` on `T` and `z` on `T` in the block's
    /// order ([`Self::apply`]).
    fn dot(&self, a: &Direction, z: &[f64]) -> f64 {
        a.iter().map(|&(i, ai)| ai * z[self.position[i]]).sum()
    }
}

/// The Schur complement `S = C − Bᵀ A⁻¹ B = L_TT D_T L_TTᵀ` of the
/// unknowns `trailing`, read from the last factorisation of `ldlt` whose
/// ordering put them last ([`trailing_ordering`]), in the order of
/// `trailing`: the stiffness of `K` condensed onto `T` (`c³/3` flops, no
/// inverse).
pub fn trailing_schur(ldlt: &SparseLdlt, trailing: &[usize]) -> Result<DMatrix<f64>> {
    let TrailingFactor { position, l, d } = TrailingFactor::of(ldlt, trailing)?;
    let c = trailing.len();
    let par = trailing_par(c);
    let mut unit = l;
    for i in 0..c {
        unit[(i, i)] = 1.0;
    }
    let schur = weighted_gram(unit.transpose(), |i, v| v * d[i], par);
    Ok(DMatrix::from_fn(c, c, |a, b| {
        schur[(position[trailing[a]], position[trailing[b]])]
    }))
}

/// The threads of the Schur complement on `c` trailing unknowns
/// ([`PARALLEL_TRAILING`]).
fn trailing_par(c: usize) -> Par {
    if c < PARALLEL_TRAILING {
        Par::Seq
    } else {
        Par::rayon(rayon::current_num_threads())
    }
}

/// `Aᵀ W A` for a square `A` and a diagonal `W`, whose product with row
/// `i`'s entry `v` of `A` is `weigh(i, v)`.
fn weighted_gram(
    a: faer::MatRef<'_, f64>,
    weigh: impl Fn(usize, f64) -> f64,
    par: Par,
) -> Mat<f64> {
    let c = a.nrows();
    let scaled = Mat::<f64>::from_fn(c, a.ncols(), |i, j| weigh(i, a[(i, j)]));
    let mut product = Mat::<f64>::zeros(a.ncols(), a.ncols());
    faer::linalg::matmul::matmul(
        product.as_mut(),
        faer::Accum::Replace,
        a.transpose(),
        scaled.as_ref(),
        1.0,
        par,
    );
    product
}

/// `eᵀ v`.
fn component(e: &Direction, v: &[f64]) -> f64 {
    e.iter().map(|&(i, ei)| ei * v[i]).sum()
}

/// The flexibility `W_ij = e_iᵀ K⁻¹ e_j` over `directions`, of which the
/// first `w.nrows()` have theirs in `w` already: the new columns from
/// `inverse` where both directions lie on its unknowns, by block solves
/// with the factor of `K` otherwise (`solve(z, k)`: `Z ← K⁻¹ Z` for `k`
/// columns of `dimension` each); symmetric (the mean of the two triangles
/// where both were computed).
pub fn grow_flexibility(
    mut solve: impl FnMut(&mut [f64], usize) -> Result<()>,
    inverse: &TrailingInverse,
    w: &DMatrix<f64>,
    directions: &[Direction],
    dimension: usize,
) -> Result<DMatrix<f64>> {
    let old = w.nrows();
    let total = directions.len();
    let mut grown = DMatrix::zeros(total, total);
    grown.view_mut((0, 0), (old, old)).copy_from(w);
    let on_block: Vec<bool> = directions.iter().map(|e| inverse.covers(e)).collect();
    // a new column is read off the block when every old direction is on
    // it too (an old one off it was solved before and not kept)
    let old_on_block = on_block[..old].iter().all(|&b| b);
    let (read, solved): (Vec<usize>, Vec<usize>) =
        (old..total).partition(|&j| on_block[j] && old_on_block);
    let mut is_solved = vec![false; total];
    solved.iter().for_each(|&j| is_solved[j] = true);
    // column j of W as `e_iᵀ z_j`, `z_j = (K⁻¹)_TT e_j`: streaming the
    // block's columns instead of reading it entry by entry for every pair
    for &j in &read {
        let z = inverse.apply(&directions[j]);
        for i in 0..total {
            if on_block[i] {
                let value = inverse.dot(&directions[i], &z);
                grown[(i, j)] = value;
                grown[(j, i)] = value;
            }
        }
    }
    for chunk in solved.chunks(BLOCK) {
        let n = dimension;
        let mut z = vec![0.0; n * chunk.len()];
        for (k, &j) in chunk.iter().enumerate() {
            for &(i, v) in &directions[j] {
                z[k * n + i] += v;
            }
        }
        solve(&mut z, chunk.len())?;
        for (k, &j) in chunk.iter().enumerate() {
            let zj = &z[k * n..(k + 1) * n];
            for i in 0..total {
                let value = component(&directions[i], zj);
                grown[(i, j)] = value;
                // old and read columns take the value by symmetry; two
                // solved columns are averaged below
                if !is_solved[i] {
                    grown[(j, i)] = value;
                }
            }
        }
    }
    // the new solved columns against each other: the mean of both triangles
    for (a, &i) in solved.iter().enumerate() {
        for &j in &solved[..a] {
            let mean = 0.5 * (grown[(i, j)] + grown[(j, i)]);
            grown[(i, j)] = mean;
            grown[(j, i)] = mean;
        }
    }
    Ok(grown)
}

/// `W_ij = e_iᵀ (K⁻¹)_TT e_j` formed anew in the rows and columns
/// `changed` of `w` (the others kept), every direction on `inverse`'s
/// unknowns: one response `z_j = (K⁻¹)_TT e_j` per changed `j`, then
/// `W_ij = W_ji = e_iᵀ z_j` for every `i`.
/// The columns on the run's threads, written in the order of `changed`
/// (the same `W` whatever the threads).
pub fn refresh_flexibility(
    inverse: &TrailingInverse,
    w: &mut DMatrix<f64>,
    directions: &[Direction],
    changed: &[usize],
) {
    use rayon::prelude::*;
    let columns: Vec<Vec<f64>> = (changed.par_iter())
        .map(|&j| {
            let z = inverse.apply(&directions[j]);
            directions.iter().map(|e| inverse.dot(e, &z)).collect()
        })
        .collect();
    for (&j, column) in changed.iter().zip(columns) {
        for (i, value) in column.into_iter().enumerate() {
            w[(i, j)] = value;
            w[(j, i)] = value;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solve::linear::multiply;

    /// A 3D grid Laplacian-like SPD matrix on `n³` nodes, 3 dofs per node
    /// (the pattern of `SparsityPattern::from_elements` over 2-node edges).
    fn grid(n: usize) -> (SparsityPattern, Vec<f64>) {
        grids(n, 1)
    }

    /// [`grid`] `copies` times, the copies sharing no edge (bodies apart).
    fn grids(n: usize, copies: usize) -> (SparsityPattern, Vec<f64>) {
        let id = |i: usize, j: usize, k: usize| i + n * (j + n * k);
        let mut edges = Vec::new();
        for k in 0..n * copies {
            let k_in = k % n;
            for j in 0..n {
                for i in 0..n {
                    if i + 1 < n {
                        edges.push([id(i, j, k), id(i + 1, j, k)]);
                    }
                    if j + 1 < n {
                        edges.push([id(i, j, k), id(i, j + 1, k)]);
                    }
                    if k_in + 1 < n {
                        edges.push([id(i, j, k), id(i, j, k + 1)]);
                    }
                }
            }
        }
        let nodes = n * n * n * copies;
        let pattern = SparsityPattern::from_elements(nodes, edges.iter().map(|e| &e[..]));
        let s = pattern.symbolic();
        let (cp, ri) = (s.col_ptr(), s.row_idx());
        let mut values = vec![0.0; pattern.nnz()];
        for j in 0..s.ncols() {
            for p in cp[j]..cp[j + 1] {
                let i = ri[p];
                values[p] = if i == j {
                    7.0 + (j % 5) as f64
                } else if i / 3 != j / 3 && i % 3 == j % 3 {
                    -1.0
                } else if i / 3 == j / 3 {
                    0.3
                } else {
                    0.1
                };
            }
        }
        (pattern, values)
    }

    /// `K` factorised with the unknowns `trailing` ordered last, and
    /// `(K⁻¹)_TT` read off the factor.
    fn factor_with_trailing(
        pattern: &SparsityPattern,
        k: &[f64],
        trailing: &[usize],
    ) -> (SparseLdlt, TrailingInverse) {
        let mut marked = vec![false; pattern.dimension()];
        trailing.iter().for_each(|&i| marked[i] = true);
        let ordering = trailing_ordering(pattern, &marked, None).unwrap();
        let mut ldlt = SparseLdlt::new(ordering, 1);
        ldlt.factorize(pattern.symbolic(), k, None).unwrap();
        let inverse = TrailingInverse::of(&ldlt, trailing).unwrap();
        (ldlt, inverse)
    }

    /// `W` equals `Eᵀ K⁻¹ E` solved column by column with the factor (each
    /// solve checked against `K`) to 1e-13; the largest entry returned.
    fn assert_solved_flexibility(
        ldlt: &mut SparseLdlt,
        pattern: &SparsityPattern,
        k: &[f64],
        w: &DMatrix<f64>,
        directions: &[Direction],
    ) -> f64 {
        let dim = pattern.dimension();
        let mut largest = 0.0f64;
        for (j, ej) in directions.iter().enumerate() {
            let mut z = vec![0.0; dim];
            ej.iter().for_each(|&(i, v)| z[i] += v);
            let b = z.clone();
            ldlt.solve_in_place(&mut z).unwrap();
            let mut kz = vec![0.0; dim];
            multiply(pattern.symbolic(), k, &z, &mut kz);
            assert!(kz.iter().zip(&b).all(|(a, b)| (a - b).abs() < 1e-12));
            for (i, ei) in directions.iter().enumerate() {
                let exact = component(ei, &z);
                largest = largest.max(exact.abs());
                assert!(
                    (w[(i, j)] - exact).abs() < 1e-13,
                    "W[{i},{j}] = {} against {exact}",
                    w[(i, j)]
                );
            }
        }
        largest
    }

    /// `(K⁻¹)_TT` read from the factor equals `K⁻¹`'s columns solved one by
    /// one, to round-off, for a simplicial (small) and a supernodal
    /// (larger) factor; the flexibility of mixed directions (some on `T`,
    /// some not) equals `Eᵀ K⁻¹ E` column by column.
    #[test]
    fn trailing_block_is_the_inverse_block() {
        let mut kinds = Vec::new();
        for n in [3usize, 9] {
            let (pattern, k) = grid(n);
            let dim = pattern.dimension();
            let trailing: Vec<usize> = (0..dim).filter(|i| i % 3 == 2 && i % 7 < 3).collect();
            let (mut ldlt, inverse) = factor_with_trailing(&pattern, &k, &trailing);
            let (symbolic, _) = ldlt.factor_parts().unwrap();
            kinds.push(matches!(symbolic.raw(), SymbolicCholeskyRaw::Supernodal(_)));
            assert_eq!(inverse.len(), trailing.len());
            // directions: two on T, one off T (an x dof), one mixed
            let directions: Vec<Direction> = vec![
                vec![(trailing[0], 1.0)],
                vec![(trailing[1], -0.5), (trailing[2], 2.0)],
                vec![(0, 1.0)],
                vec![(trailing[3], 1.0), (3, 0.5)],
            ];
            let solve = |z: &mut [f64], k| ldlt.solve_columns_in_place(z, k);
            let w =
                grow_flexibility(solve, &inverse, &DMatrix::zeros(0, 0), &directions, dim).unwrap();
            let largest = assert_solved_flexibility(&mut ldlt, &pattern, &k, &w, &directions);
            assert!(largest > 1e-2, "n = {n}");
            // the Schur complement is the inverse of the trailing block
            let schur = trailing_schur(&ldlt, &trailing).unwrap();
            let c = trailing.len();
            for i in 0..c {
                for j in 0..c {
                    let z = inverse.apply(&vec![(trailing[j], 1.0)]);
                    let product: f64 = (0..c)
                        .map(|k| schur[(i, k)] * inverse.dot(&vec![(trailing[k], 1.0)], &z))
                        .sum();
                    let identity = f64::from(u8::from(i == j));
                    assert!(
                        (product - identity).abs() < 1e-12,
                        "n = {n}: (S W)[{i},{j}]"
                    );
                }
            }
        }
        // one simplicial and one supernodal factor were read
        assert_eq!(kinds, [false, true]);
    }

    /// `W` refreshed in the rows and columns of the directions that
    /// changed equals `W` formed anew over the new directions to 1e-15 of
    /// its largest entry.
    #[test]
    fn refreshed_flexibility_equals_the_one_formed_anew() {
        let (pattern, k) = grid(5);
        let dim = pattern.dimension();
        let trailing: Vec<usize> = (0..dim).filter(|i| i % 3 == 2).collect();
        let (mut ldlt, inverse) = factor_with_trailing(&pattern, &k, &trailing);
        let mut directions: Vec<Direction> = (0..6)
            .map(|a| vec![(trailing[3 * a], 1.0), (trailing[3 * a + 1], -0.3)])
            .collect();
        let none = DMatrix::zeros(0, 0);
        let solve = |z: &mut [f64], c| ldlt.solve_columns_in_place(z, c);
        let mut w = grow_flexibility(solve, &inverse, &none, &directions, dim).unwrap();
        directions[2] = vec![(trailing[20], 0.8), (trailing[6], 0.6)];
        directions[4][1].1 = 0.25;
        refresh_flexibility(&inverse, &mut w, &directions, &[2, 4]);
        let solve = |z: &mut [f64], c| ldlt.solve_columns_in_place(z, c);
        let anew = grow_flexibility(solve, &inverse, &none, &directions, dim).unwrap();
        let largest = anew.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        assert!(largest > 1e-2);
        assert!((&w - &anew).iter().all(|d| d.abs() <= 1e-15 * largest));
    }

    /// Two bodies apart (two grids that share no edge), a trailing set on
    /// both: `(K⁻¹)_TT` comes in two diagonal blocks, and the flexibility
    /// of directions on one body, on the other and across both equals
    /// `Eᵀ K⁻¹ E` solved column by column to round-off (zero across).
    #[test]
    fn two_bodies_give_two_trailing_blocks() {
        let n = 5;
        let (pattern, k) = grids(n, 2);
        let dim = pattern.dimension();
        let half = dim / 2;
        // every 4th dof of both bodies, interleaved in the unknowns' order
        let trailing: Vec<usize> = (0..dim).filter(|i| i % 4 == 1).collect();
        let (mut ldlt, inverse) = factor_with_trailing(&pattern, &k, &trailing);
        assert_eq!(inverse.blocks(), 2);
        let (a, b) = (
            trailing[2],
            *trailing.iter().find(|&&i| i > half + 7).unwrap(),
        );
        let directions: Vec<Direction> = vec![
            vec![(a, 1.0)],
            vec![(b, -0.5), (b + 4, 2.0)],
            vec![(a, 0.7), (b, 0.3)],
        ];
        assert!(directions.iter().all(|e| inverse.covers(e)));
        let solve = |z: &mut [f64], k| ldlt.solve_columns_in_place(z, k);
        let w = grow_flexibility(solve, &inverse, &DMatrix::zeros(0, 0), &directions, dim).unwrap();
        let largest = assert_solved_flexibility(&mut ldlt, &pattern, &k, &w, &directions);
        assert!(largest > 1e-2);
        assert!(
            w[(0, 1)].abs() < 1e-15 && w[(1, 0)].abs() < 1e-15,
            "no coupling across"
        );
    }
}
