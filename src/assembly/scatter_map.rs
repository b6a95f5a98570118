//! The element → CSC position map of one sparsity pattern, built once per
//! pattern so that the element loop scatters without a search.
//!
//! For element `e` with nodes `n_0 … n_{m−1}`, entry `a m + b` of its slice
//! is the position in the value array of global entry (row `3 n_a`,
//! column `3 n_b`). The rows `3 n_a + i` follow contiguously, and the three
//! columns of a node hold the same rows, so entry (row `3 n_a + i`, column
//! `3 n_b + j`) is at `start + j · L(n_b) + i` with `L(n_b)`
//! [`SparsityPattern::node_column_length`].
//!
//! A map into the pattern's lower triangle ([`ScatterMap::lower`]) holds
//! the start of the blocks with `n_a ≥ n_b` in the triangle's values
//! ([`LowerTriangle::block_start`]) and [`ScatterMap::ABOVE`] for the
//! others, which the triangle does not store.

use super::pattern::SparsityPattern;
use super::triangle::LowerTriangle;

/// Positions of every element's node blocks in one pattern's values.
#[derive(Debug)]
pub struct ScatterMap {
    /// `pattern.id()` of the pattern the positions point into.
    pattern_id: u64,
    /// `first[e] .. first[e + 1]`: element `e`'s `m × m` block starts.
    first: Vec<usize>,
    starts: Vec<usize>,
}

impl ScatterMap {
    /// The map of the elements `element_nodes` yields into `pattern`
    /// (which must couple every pair of nodes of an element).
    pub fn new<'a>(
        pattern: &SparsityPattern,
        element_nodes: impl Iterator<Item = &'a [usize]>,
    ) -> Self {
        // the pattern is built from the elements: every pair is coupled
        Self::of_blocks(pattern, element_nodes, |na, nb| {
            pattern.block_columns(na, nb).map_or(usize::MAX, |c| c[0])
        })
    }

    /// The map whose block `(n_a, n_b)` starts at `start(n_a, n_b)`.
    fn of_blocks<'a>(
        pattern: &SparsityPattern,
        element_nodes: impl Iterator<Item = &'a [usize]>,
        start: impl Fn(usize, usize) -> usize,
    ) -> Self {
        let mut first = vec![0];
        let mut starts = Vec::new();
        for nodes in element_nodes {
            for &na in nodes {
                starts.extend(nodes.iter().map(|&nb| start(na, nb)));
            }
            first.push(starts.len());
        }
        ScatterMap {
            pattern_id: pattern.id(),
            first,
            starts,
        }
    }

    /// The start of a block above the diagonal in a map into the lower
    /// triangle: not stored.
    pub const ABOVE: usize = usize::MAX;

    /// The map of the elements `element_nodes` yields into the lower
    /// triangle `lower` of `pattern`.
    pub fn lower<'a>(
        pattern: &SparsityPattern,
        lower: &LowerTriangle,
        element_nodes: impl Iterator<Item = &'a [usize]>,
    ) -> Self {
        Self::of_blocks(pattern, element_nodes, |na, nb| {
            lower.block_start(pattern, na, nb).unwrap_or(Self::ABOVE)
        })
    }

    /// Whether the map points into `pattern`.
    pub fn is_for(&self, pattern: &SparsityPattern) -> bool {
        self.pattern_id == pattern.id()
    }

    /// Element `e`'s block starts, `a m + b` for nodes `a`, `b`.
    #[inline]
    pub fn element(&self, e: usize) -> &[usize] {
        &self.starts[self.first[e]..self.first[e + 1]]
    }
}
