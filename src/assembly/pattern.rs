//! The fixed sparsity pattern of the global tangent, built once per mesh
//! from node adjacency (3×3 blocks per node pair), in compressed sparse
//! column form for faer.

use faer::sparse::SymbolicSparseColMat;

/// Node-block sparsity pattern of a 3-dof-per-node matrix, plus the node
/// adjacency that locates a block in `O(log degree)`.
#[derive(Debug)]
pub struct SparsityPattern {
    /// Sorted neighbour nodes of each node (itself included).
    neighbours: Vec<Vec<usize>>,
    /// Symbolic CSC structure, all entries (both triangles).
    symbolic: SymbolicSparseColMat<usize>,
    /// `mirror[k]` is the index of entry (j, i) for entry `k` = (i, j).
    mirror: Vec<usize>,
}

impl SparsityPattern {
    /// Pattern of the matrix coupling every pair of nodes that share an
    /// element (`element_nodes` yields each element's node list).
    pub fn from_elements<'a>(
        num_nodes: usize,
        element_nodes: impl Iterator<Item = &'a [usize]>,
    ) -> Self {
        let mut neighbours: Vec<Vec<usize>> = (0..num_nodes).map(|n| vec![n]).collect();
        for nodes in element_nodes {
            for &a in nodes {
                neighbours[a].extend_from_slice(nodes);
            }
        }
        for list in &mut neighbours {
            list.sort_unstable();
            list.dedup();
        }
        let n = 3 * num_nodes;
        let mut col_ptr = Vec::with_capacity(n + 1);
        let nnz: usize = neighbours.iter().map(|l| 9 * l.len()).sum();
        let mut row_idx = Vec::with_capacity(nnz);
        col_ptr.push(0);
        for list in &neighbours {
            for _j in 0..3 {
                for &a in list {
                    row_idx.extend([3 * a, 3 * a + 1, 3 * a + 2]);
                }
                col_ptr.push(row_idx.len());
            }
        }
        let symbolic = SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx);
        let mut pattern = SparsityPattern {
            neighbours,
            symbolic,
            mirror: Vec::new(),
        };
        let cp = pattern.symbolic.col_ptr();
        let ri = pattern.symbolic.row_idx();
        let mirror = (0..n)
            .flat_map(|j| (cp[j]..cp[j + 1]).map(move |k| (ri[k], j)))
            .map(|(i, j)| {
                pattern
                    .block_entry(j / 3, j % 3, i / 3, i % 3)
                    .expect("the node-block pattern is structurally symmetric")
            })
            .collect();
        pattern.mirror = mirror;
        pattern
    }

    /// Number of rows (= columns).
    pub fn dimension(&self) -> usize {
        self.symbolic.nrows()
    }

    /// Number of stored entries.
    pub fn nnz(&self) -> usize {
        self.symbolic.row_idx().len()
    }

    /// The faer symbolic structure.
    pub fn symbolic(&self) -> &SymbolicSparseColMat<usize> {
        &self.symbolic
    }

    /// Index into the value array of entry (row `3a + i`, column `3b + j`),
    /// or `None` if nodes `a` and `b` are not coupled.
    #[inline]
    pub fn block_entry(&self, a: usize, i: usize, b: usize, j: usize) -> Option<usize> {
        let pos = self.neighbours[b].binary_search(&a).ok()?;
        Some(self.symbolic.col_ptr()[3 * b + j] + 3 * pos + i)
    }

    /// Indices of entries (row `3a`, column `3b + j`) for `j = 0, 1, 2`;
    /// rows `3a + i` follow contiguously. `None` if `a`, `b` are not coupled.
    #[inline]
    pub fn block_columns(&self, a: usize, b: usize) -> Option<[usize; 3]> {
        let pos = self.neighbours[b].binary_search(&a).ok()?;
        let cp = self.symbolic.col_ptr();
        Some([0, 1, 2].map(|j| cp[3 * b + j] + 3 * pos))
    }

    /// The node adjacency without self-loops, in CSR form `(xadj, adjncy)`,
    /// for graph orderings.
    pub fn node_graph(&self) -> (Vec<usize>, Vec<usize>) {
        let mut xadj = Vec::with_capacity(self.neighbours.len() + 1);
        let mut adjncy = Vec::new();
        xadj.push(0);
        for (n, list) in self.neighbours.iter().enumerate() {
            adjncy.extend(list.iter().copied().filter(|&m| m != n));
            xadj.push(adjncy.len());
        }
        (xadj, adjncy)
    }

    /// The symmetric part `½ (A + Aᵀ)` of values on this pattern.
    pub fn symmetric_part(&self, values: &[f64]) -> Vec<f64> {
        self.mirror
            .iter()
            .enumerate()
            .map(|(k, &m)| 0.5 * (values[k] + values[m]))
            .collect()
    }

    /// Index of the diagonal entry of dof `d`.
    #[inline]
    pub fn diagonal_entry(&self, d: usize) -> usize {
        self.block_entry(d / 3, d % 3, d / 3, d % 3)
            .expect("every node is its own neighbour")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn block_lookup_matches_row_indices() {
        let elements: Vec<Vec<usize>> = vec![vec![0, 1, 2], vec![1, 2, 3]];
        let p = SparsityPattern::from_elements(4, elements.iter().map(|e| e.as_slice()));
        assert_eq!(p.dimension(), 12);
        // node 0 couples with 0,1,2 → 9 rows per column, 3 columns
        assert_eq!(p.symbolic().col_ptr()[3], 27);
        for (a, b) in [(0, 2), (3, 1), (2, 2)] {
            for i in 0..3 {
                for j in 0..3 {
                    let k = p.block_entry(a, i, b, j).unwrap();
                    assert_eq!(p.symbolic().row_idx()[k], 3 * a + i);
                    assert!(
                        k >= p.symbolic().col_ptr()[3 * b + j]
                            && k < p.symbolic().col_ptr()[3 * b + j + 1]
                    );
                }
            }
        }
        assert!(p.block_entry(0, 0, 3, 0).is_none());
        // symmetric part of a matrix with A[i][j] = i − j + 2ij is 2ij
        let (cp, ri) = (p.symbolic().col_ptr(), p.symbolic().row_idx());
        let mut values = vec![0.0; p.nnz()];
        for j in 0..12 {
            for k in cp[j]..cp[j + 1] {
                let i = ri[k] as f64;
                values[k] = i - j as f64 + 2.0 * i * j as f64;
            }
        }
        let sym = p.symmetric_part(&values);
        for j in 0..12 {
            for k in cp[j]..cp[j + 1] {
                assert_eq!(sym[k], 2.0 * ri[k] as f64 * j as f64);
            }
        }
    }
}
