//! The one scatter of local blocks into the global system: element
//! matrices, follower-load blocks and the contact blocks of a secondary
//! node all go through [`add_block`] (and [`add_nodal`] for their vectors);
//! the contact multipliers' column and row through [`add_multiplier_block`].
//!
//! A local block is indexed node-major over its `nodes`: local dof `3a + i`
//! is component `i` of mesh node `nodes[a]`, global dof `3 nodes[a] + i`.

use super::pattern::SparsityPattern;

/// `values[3 n_a + i] += entry(3a + i)` for every node `n_a` of `nodes`.
pub fn add_nodal(values: &mut [f64], nodes: &[usize], entry: impl Fn(usize) -> f64) {
    for (a, &na) in nodes.iter().enumerate() {
        for i in 0..3 {
            values[3 * na + i] += entry(3 * a + i);
        }
    }
}

/// Add the local block `entry(row, column)` over `nodes` into the pattern's
/// values, skipping the rows and columns of global dofs that `keep`
/// refuses. Node pairs outside the pattern are skipped.
pub fn add_block(
    pattern: &SparsityPattern,
    values: &mut [f64],
    nodes: &[usize],
    entry: impl Fn(usize, usize) -> f64,
    keep: impl Fn(usize) -> bool,
) {
    for (a, &na) in nodes.iter().enumerate() {
        for (b, &nb) in nodes.iter().enumerate() {
            let Some(columns) = pattern.block_columns(na, nb) else {
                continue;
            };
            for (j, col) in columns.iter().enumerate() {
                if !keep(3 * nb + j) {
                    continue;
                }
                for i in 0..3 {
                    if keep(3 * na + i) {
                        values[col + i] += entry(3 * a + i, 3 * b + j);
                    }
                }
            }
        }
    }
}

/// Add multiplier `m`'s column `∂r_q/∂λ = column(k)` and row
/// `∂r_λ/∂q = row(k)` over the local dofs `k` of `nodes` (entries of global
/// dofs that `keep` refuses skipped).
pub fn add_multiplier_block(
    pattern: &SparsityPattern,
    values: &mut [f64],
    m: usize,
    nodes: &[usize],
    column: impl Fn(usize) -> f64,
    row: impl Fn(usize) -> f64,
    keep: impl Fn(usize) -> bool,
) {
    for (a, &na) in nodes.iter().enumerate() {
        if let Some(e) = pattern.multiplier_entries(m, na) {
            for d in 0..3 {
                if keep(3 * na + d) {
                    values[e.node_rows[d]] += column(3 * a + d);
                    values[e.multiplier_row[d]] += row(3 * a + d);
                }
            }
        }
    }
}
