//! The fixed sparsity pattern of the global tangent, built once per mesh
//! from node adjacency (3×3 blocks per node pair), in compressed sparse
//! column form for faer.
//!
//! Besides the 3 displacement dofs of every node, the pattern can hold
//! scalar *multiplier* unknowns (contact pressures, constraint forces),
//! numbered after the displacements (`3N + k`), each coupled to the
//! displacement dofs of a list of nodes, to itself and to the other
//! multipliers of its group (a contact node's normal and tangential
//! multipliers, [`SparsityPattern::with_multiplier_groups`]). The resulting saddle
//! system is symmetric indefinite; [`SparsityPattern::dof_ordering`] orders
//! each multiplier right after its nodes, and
//! [`SparsityPattern::pivot_signs`] gives the LDLᵀ pivot signs to
//! regularise towards (the multipliers' only).

use faer::sparse::SymbolicSparseColMat;
use rayon::prelude::*;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, OnceLock};

/// Source of [`SparsityPattern::id`]: every pattern built gets the next one.
static NEXT_PATTERN_ID: AtomicU64 = AtomicU64::new(0);

/// Node-block sparsity pattern of a 3-dof-per-node matrix, with optional
/// multiplier unknowns, plus the adjacency that locates an entry in
/// `O(log degree)`.
#[derive(Debug)]
pub struct SparsityPattern {
    /// Sorted neighbour nodes of each node (itself included).
    neighbours: Arc<Vec<Vec<usize>>>,
    /// The part of `neighbours` that the elements make (shared with the
    /// patterns [`SparsityPattern::coupled`] makes from this one).
    elements: Arc<Vec<Vec<usize>>>,
    /// Sorted multipliers coupled to each node.
    node_multipliers: Vec<Vec<usize>>,
    /// Sorted nodes coupled to each multiplier.
    multiplier_nodes: Vec<Vec<usize>>,
    /// Sorted multipliers coupled to each multiplier (itself included).
    multiplier_group: Vec<Vec<usize>>,
    /// Where each column starts in the CSC structure (both triangles;
    /// `nnz` last): what locating an entry reads, made with the pattern.
    col_ptr: Vec<usize>,
    /// The symbolic CSC structure (its row indices, as many as the
    /// entries), made at its first use ([`Self::symbolic`]): the element
    /// pattern a model is made with is replaced by [`Self::coupled`]'s
    /// when the contact is set up, before anything reads its rows.
    symbolic: OnceLock<SymbolicSparseColMat<usize>>,
    /// `mirror[k]` is the index of entry (j, i) for entry `k` = (i, j),
    /// made at its first use ([`Self::mirrors`]): the condensed path
    /// never reads it, and the pattern that the contact multipliers
    /// replace never did.
    mirror: OnceLock<Vec<usize>>,
    /// Unique among the patterns of a process ([`SparsityPattern::id`]).
    id: u64,
}

/// A pattern's node adjacency (each node its own neighbour), shared with
/// the pattern it came from: what a fill-reducing ordering of the nodes
/// reads.
#[derive(Clone, Debug)]
pub struct NodeGraph(Arc<Vec<Vec<usize>>>);

impl NodeGraph {
    /// The graph of the nodes that share an element (`element_nodes`
    /// yields each element's node list): each node's sorted neighbours,
    /// itself included.
    pub fn of_elements<'a>(
        num_nodes: usize,
        element_nodes: impl Iterator<Item = &'a [usize]>,
    ) -> Self {
        Self::of_elements_and(num_nodes, element_nodes, |_| true)
    }

    /// [`Self::of_elements`] where a node that no element lists is its
    /// own neighbour only if `alone(node)`, else has no neighbours at all
    /// (no rows or columns in a pattern of the graph): a process's graph
    /// of its own elements keeps its own nodes and leaves out the other
    /// processes' nodes that its elements do not touch.
    pub fn of_elements_and<'a>(
        num_nodes: usize,
        element_nodes: impl Iterator<Item = &'a [usize]>,
        alone: impl Fn(usize) -> bool + Sync,
    ) -> Self {
        // each node's elements in one flat array (counted first: no list
        // grows), then each node's neighbours gathered from its elements,
        // a mark per node keeping each once, and sorted: the lists are
        // made by chunks of nodes side by side, a mark array per chunk
        let elements: Vec<&[usize]> = element_nodes.collect();
        let (start, of_node) = lists_of_nodes(num_nodes, &elements);
        let chunk = num_nodes.div_ceil(4 * rayon::current_num_threads()).max(1);
        let neighbours: Vec<Vec<usize>> = (0..num_nodes.div_ceil(chunk))
            .into_par_iter()
            .flat_map_iter(|c| {
                let mut mark = vec![usize::MAX; num_nodes];
                let (start, of_node, elements, alone) = (&start, &of_node, &elements, &alone);
                (c * chunk..((c + 1) * chunk).min(num_nodes)).map(move |a| {
                    if start[a + 1] == start[a] && !alone(a) {
                        return Vec::new();
                    }
                    let mut list = vec![a];
                    mark[a] = a;
                    for &e in &of_node[start[a]..start[a + 1]] {
                        for &b in elements[e] {
                            if mark[b] != a {
                                mark[b] = a;
                                list.push(b);
                            }
                        }
                    }
                    list.sort_unstable();
                    list
                })
            })
            .collect();
        NodeGraph(Arc::new(neighbours))
    }

    /// The adjacency without self-loops, in CSR form `(xadj, adjncy)`.
    pub fn csr(&self) -> (Vec<usize>, Vec<usize>) {
        let mut xadj = Vec::with_capacity(self.0.len() + 1);
        let mut adjncy = Vec::new();
        xadj.push(0);
        for (n, list) in self.0.iter().enumerate() {
            adjncy.extend(list.iter().copied().filter(|&m| m != n));
            xadj.push(adjncy.len());
        }
        (xadj, adjncy)
    }

    /// Whether `other` is this very graph (the same shared adjacency, not
    /// an equal copy): then an ordering of one orders the other.
    pub fn is(&self, other: &NodeGraph) -> bool {
        Arc::ptr_eq(&self.0, &other.0)
    }
}

/// Where the entries coupling multiplier `k` and node `a` are stored.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MultiplierEntries {
    /// Entries (row `3a + i`, column `3N + k`), `i = 0, 1, 2`.
    pub node_rows: [usize; 3],
    /// Entries (row `3N + k`, column `3a + i`), `i = 0, 1, 2`.
    pub multiplier_row: [usize; 3],
}

impl SparsityPattern {
    /// Pattern of the matrix coupling every pair of nodes that share an
    /// element (`element_nodes` yields each element's node list).
    pub fn from_elements<'a>(
        num_nodes: usize,
        element_nodes: impl Iterator<Item = &'a [usize]>,
    ) -> Self {
        Self::with_multipliers(num_nodes, element_nodes, &[])
    }

    /// Pattern of the node-block matrix plus one multiplier unknown per
    /// entry of `multiplier_nodes`, coupled to the displacement dofs of the
    /// nodes listed there (and to itself: the diagonal is always stored).
    pub fn with_multipliers<'a>(
        num_nodes: usize,
        element_nodes: impl Iterator<Item = &'a [usize]>,
        multiplier_nodes: &[Vec<usize>],
    ) -> Self {
        Self::with_multiplier_groups(num_nodes, element_nodes, multiplier_nodes, &[])
    }

    /// [`with_multipliers`](Self::with_multipliers) where multiplier `k`
    /// is also coupled to the multipliers `groups[k]` (a dense block
    /// among the multipliers of one contact node; the relation is made
    /// symmetric, and a missing entry of `groups` means none).
    pub fn with_multiplier_groups<'a>(
        num_nodes: usize,
        element_nodes: impl Iterator<Item = &'a [usize]>,
        multiplier_nodes: &[Vec<usize>],
        groups: &[Vec<usize>],
    ) -> Self {
        let graph = NodeGraph::of_elements(num_nodes, element_nodes);
        Self::from_neighbours(Arc::clone(&graph.0), graph.0, multiplier_nodes, groups)
    }

    /// [`Self::from_elements`] from the elements' graph
    /// ([`NodeGraph::of_elements`]), which it shares
    /// ([`Self::graph`]`.is(graph)`).
    pub fn from_graph(graph: &NodeGraph) -> Self {
        Self::from_neighbours(Arc::clone(&graph.0), Arc::clone(&graph.0), &[], &[])
    }

    /// This pattern's element couplings (those it was first built from,
    /// not the groups of an earlier [`Self::coupled`]) plus every pair of
    /// nodes in one of `groups`, and the multipliers `multiplier_nodes`
    /// coupled within `multiplier_groups`
    /// ([`Self::with_multiplier_groups`] without walking the elements again).
    pub fn coupled(
        &self,
        groups: &[Vec<usize>],
        multiplier_nodes: &[Vec<usize>],
        multiplier_groups: &[Vec<usize>],
    ) -> Self {
        if groups.is_empty() {
            let elements = Arc::clone(&self.elements);
            return Self::from_neighbours(
                Arc::clone(&elements),
                elements,
                multiplier_nodes,
                multiplier_groups,
            );
        }
        // each node's groups (counted first), then each touched node's
        // element neighbours joined by its groups' members, a mark per
        // node keeping each once, and sorted
        let num_nodes = self.elements.len();
        let (start, of_node) = lists_of_nodes(num_nodes, groups);
        let mut neighbours: Vec<Vec<usize>> = (*self.elements).clone();
        let mut mark = vec![usize::MAX; num_nodes];
        for (a, list) in neighbours.iter_mut().enumerate() {
            if start[a + 1] == start[a] {
                continue;
            }
            for &b in list.iter() {
                mark[b] = a;
            }
            for &g in &of_node[start[a]..start[a + 1]] {
                for &b in &groups[g] {
                    if mark[b] != a {
                        mark[b] = a;
                        list.push(b);
                    }
                }
            }
            list.sort_unstable();
        }
        Self::from_neighbours(
            Arc::new(neighbours),
            Arc::clone(&self.elements),
            multiplier_nodes,
            multiplier_groups,
        )
    }

    /// The pattern of the sorted node adjacency `neighbours` (each node
    /// its own neighbour) and the multipliers, multiplier `k` coupled to
    /// the multipliers `groups[k]`; `elements` the element part of the
    /// adjacency, kept for [`Self::coupled`].
    fn from_neighbours(
        neighbours: Arc<Vec<Vec<usize>>>,
        elements: Arc<Vec<Vec<usize>>>,
        multiplier_nodes: &[Vec<usize>],
        groups: &[Vec<usize>],
    ) -> Self {
        let num_nodes = neighbours.len();
        let multiplier_nodes: Vec<Vec<usize>> = multiplier_nodes
            .iter()
            .map(|l| {
                let mut l = l.clone();
                l.sort_unstable();
                l.dedup();
                l
            })
            .collect();
        let mut node_multipliers: Vec<Vec<usize>> = vec![Vec::new(); num_nodes];
        for (k, nodes) in multiplier_nodes.iter().enumerate() {
            for &a in nodes {
                node_multipliers[a].push(k);
            }
        }
        let mut multiplier_group: Vec<Vec<usize>> =
            (0..multiplier_nodes.len()).map(|k| vec![k]).collect();
        for (k, group) in groups.iter().enumerate() {
            for &l in group {
                multiplier_group[k].push(l);
                multiplier_group[l].push(k);
            }
        }
        for list in &mut multiplier_group {
            list.sort_unstable();
            list.dedup();
        }
        let n = 3 * num_nodes + multiplier_nodes.len();
        let mut col_ptr = Vec::with_capacity(n + 1);
        col_ptr.push(0);
        let mut entries = 0;
        for (list, multipliers) in neighbours.iter().zip(&node_multipliers) {
            for _j in 0..3 {
                entries += 3 * list.len() + multipliers.len();
                col_ptr.push(entries);
            }
        }
        for (nodes, group) in multiplier_nodes.iter().zip(&multiplier_group) {
            entries += 3 * nodes.len() + group.len();
            col_ptr.push(entries);
        }
        SparsityPattern {
            neighbours,
            elements,
            node_multipliers,
            multiplier_nodes,
            multiplier_group,
            col_ptr,
            symbolic: OnceLock::new(),
            mirror: OnceLock::new(),
            id: NEXT_PATTERN_ID.fetch_add(1, Ordering::Relaxed),
        }
    }

    /// An identifier no other pattern built in this process has: what is
    /// derived from a pattern (the element scatter map, a cached constant
    /// stiffness) is valid while the pattern it was built for has this id.
    pub fn id(&self) -> u64 {
        self.id
    }

    /// Number of stored rows of the three columns of node `b` (they hold
    /// the same rows): the stride between the entries (row `3a + i`,
    /// column `3b + j`) and (row `3a + i`, column `3b + j + 1`).
    #[inline]
    pub fn node_column_length(&self, b: usize) -> usize {
        let cp = &self.col_ptr;
        cp[3 * b + 1] - cp[3 * b]
    }

    /// Number of nodes (each with 3 displacement dofs, numbered first).
    pub fn num_nodes(&self) -> usize {
        self.neighbours.len()
    }

    /// Sorted neighbour nodes of each node through the elements alone
    /// (itself included): the adjacency without contact couplings, that
    /// of a stiffness assembled from the elements.
    pub fn element_neighbours(&self) -> &[Vec<usize>] {
        &self.elements
    }

    /// Number of multiplier unknowns (numbered after the displacements).
    pub fn num_multipliers(&self) -> usize {
        self.multiplier_nodes.len()
    }

    /// Entries coupling multiplier `k` and node `a`, or `None` if they are
    /// not coupled.
    pub fn multiplier_entries(&self, k: usize, a: usize) -> Option<MultiplierEntries> {
        let cp = &self.col_ptr;
        let in_column = self.node_multipliers[a].binary_search(&k).ok()?;
        let in_row = self.multiplier_nodes[k].binary_search(&a).ok()?;
        let node_count = 3 * self.neighbours[a].len();
        let column = 3 * self.num_nodes() + k;
        Some(MultiplierEntries {
            node_rows: [0, 1, 2].map(|i| cp[column] + 3 * in_row + i),
            multiplier_row: [0, 1, 2].map(|i| cp[3 * a + i] + node_count + in_column),
        })
    }

    /// Index of the diagonal entry of multiplier `k`.
    pub fn multiplier_diagonal(&self, k: usize) -> usize {
        self.multiplier_pair(k, k).unwrap_or(0)
    }

    /// Index of the entry (row `3N + l`, column `3N + k`) coupling
    /// multipliers `l` and `k` of one group, or `None` if they are not.
    pub fn multiplier_pair(&self, l: usize, k: usize) -> Option<usize> {
        let group = &self.multiplier_group[k];
        let position = group.binary_search(&l).ok()?;
        let column = 3 * self.num_nodes() + k;
        Some(self.col_ptr[column + 1] - group.len() + position)
    }

    /// Expected signs of the LDLᵀ pivots, for faer's dynamic
    /// regularisation (a pivot `d` of the wrong sign or `|d| ≤ ε` becomes
    /// `±δ` of the expected sign): −1 for multipliers, 0 (none expected)
    /// for displacement dofs.
    ///
    /// A multiplier's diagonal is 0 on an active node (`K_λλ = 0`); when the
    /// ordering eliminates it before its node (AMD may;
    /// [`Self::dof_ordering`] does not), or when its coupling is gone (its
    /// node's dofs prescribed: their rows and columns become the identity),
    /// its pivot is 0 and only the regularisation `−δ` lets the
    /// factorisation go on (the refinement then removes the perturbation). A displacement pivot has
    /// no sign to expect: the tangent of a large-deformation or deformable
    /// contact state is indefinite (examples/ogden-plate's first
    /// iterations), and pushing its negative pivots to `+δ` factorises
    /// another matrix, which no refinement recovers. With 0 they are kept;
    /// faer's supernodal kernel still moves a pivot with `|d| ≤ ε` to `±δ`
    /// of its own sign.
    pub fn pivot_signs(&self) -> Vec<i8> {
        let mut signs = vec![0i8; 3 * self.num_nodes()];
        signs.resize(self.dimension(), -1);
        signs
    }

    /// A dof ordering from a node ordering (`node_order[new] = old`): each
    /// node's three dofs stay together, and each multiplier follows the last
    /// of its nodes, so that it is eliminated after them (ordering the
    /// multipliers all at the end fills far more). Returns
    /// `forward[new] = old` over all dofs.
    pub fn dof_ordering(&self, node_order: &[usize]) -> Vec<usize> {
        let mut position = vec![0usize; self.num_nodes()];
        for (new, &old) in node_order.iter().enumerate() {
            position[old] = new;
        }
        // multipliers attached to the node (in the new order) they follow
        let mut after: Vec<Vec<usize>> = vec![Vec::new(); self.num_nodes()];
        for (k, nodes) in self.multiplier_nodes.iter().enumerate() {
            let last = nodes.iter().copied().max_by_key(|&a| position[a]);
            match last {
                Some(a) => after[a].push(k),
                None => after[node_order.last().copied().unwrap_or(0)].push(k),
            }
        }
        let first_multiplier = 3 * self.num_nodes();
        let mut forward = Vec::with_capacity(self.dimension());
        for &node in node_order {
            forward.extend([3 * node, 3 * node + 1, 3 * node + 2]);
            forward.extend(after[node].iter().map(|k| first_multiplier + k));
        }
        if node_order.is_empty() {
            forward.extend(first_multiplier..self.dimension());
        }
        forward
    }

    /// Number of rows (= columns).
    pub fn dimension(&self) -> usize {
        self.col_ptr.len() - 1
    }

    /// Number of stored entries.
    pub fn nnz(&self) -> usize {
        self.col_ptr[self.col_ptr.len() - 1]
    }

    /// Where each column starts in [`Self::symbolic`]'s row indices (the
    /// number of entries last), without making them.
    #[inline]
    pub fn col_ptr(&self) -> &[usize] {
        &self.col_ptr
    }

    /// The faer symbolic structure (made at the first call).
    pub fn symbolic(&self) -> &SymbolicSparseColMat<usize> {
        self.symbolic.get_or_init(|| {
            let n = self.dimension();
            let row_idx = self.row_indices();
            SymbolicSparseColMat::new_checked(n, n, self.col_ptr.clone(), None, row_idx)
        })
    }

    /// The rows of column `j`, increasing: a node's three columns each
    /// hold the three dofs of its neighbours, then its multipliers; a
    /// multiplier's, the dofs of its nodes, then its group. What
    /// [`Self::symbolic`]'s row indices hold, without making them.
    pub fn column_rows(&self, j: usize) -> impl Iterator<Item = usize> + '_ {
        let first_multiplier = 3 * self.num_nodes();
        let (nodes, multipliers) = match j.checked_sub(first_multiplier) {
            None => (&self.neighbours[j / 3], &self.node_multipliers[j / 3]),
            Some(k) => (&self.multiplier_nodes[k], &self.multiplier_group[k]),
        };
        (nodes.iter())
            .flat_map(|&b| [3 * b, 3 * b + 1, 3 * b + 2])
            .chain(multipliers.iter().map(move |k| first_multiplier + k))
    }

    /// The row indices of every column ([`Self::column_rows`]), in the
    /// order of [`Self::col_ptr`]: filled node by node in parallel (the
    /// columns' slices are known from `col_ptr`).
    fn row_indices(&self) -> Vec<usize> {
        let mut row_idx = vec![0; self.nnz()];
        let mut slices: Vec<&mut [usize]> = Vec::with_capacity(self.col_ptr.len() / 3 + 1);
        let mut rest = row_idx.as_mut_slice();
        for a in 0..self.num_nodes() {
            let (node, after) = rest.split_at_mut(self.col_ptr[3 * a + 3] - self.col_ptr[3 * a]);
            slices.push(node);
            rest = after;
        }
        slices.par_iter_mut().enumerate().for_each(|(a, out)| {
            let length = out.len() / 3;
            for (j, column) in out.chunks_mut(length.max(1)).enumerate() {
                for (slot, row) in column.iter_mut().zip(self.column_rows(3 * a + j)) {
                    *slot = row;
                }
            }
        });
        let first_multiplier = 3 * self.num_nodes();
        let multipliers = first_multiplier..self.dimension();
        let rows = multipliers.flat_map(|j| self.column_rows(j));
        for (slot, row) in rest.iter_mut().zip(rows) {
            *slot = row;
        }
        row_idx
    }

    /// Index into the value array of entry (row `3a + i`, column `3b + j`),
    /// or `None` if nodes `a` and `b` are not coupled.
    #[inline]
    pub fn block_entry(&self, a: usize, i: usize, b: usize, j: usize) -> Option<usize> {
        let pos = self.neighbours[b].binary_search(&a).ok()?;
        Some(self.col_ptr[3 * b + j] + 3 * pos + i)
    }

    /// Indices of entries (row `3a`, column `3b + j`) for `j = 0, 1, 2`;
    /// rows `3a + i` follow contiguously. `None` if `a`, `b` are not coupled.
    #[inline]
    pub fn block_columns(&self, a: usize, b: usize) -> Option<[usize; 3]> {
        let pos = self.neighbours[b].binary_search(&a).ok()?;
        let cp = &self.col_ptr;
        Some([0, 1, 2].map(|j| cp[3 * b + j] + 3 * pos))
    }

    /// The node adjacency without self-loops, in CSR form `(xadj, adjncy)`,
    /// for graph orderings.
    pub fn node_graph(&self) -> (Vec<usize>, Vec<usize>) {
        self.graph().csr()
    }

    /// The elements' node adjacency alone (without the contact couplings of
    /// [`Self::coupled`]'s groups) as a shared graph: the graph handed to
    /// `on_graph` when the model was made, so that an ordering started
    /// from it fits ([`NodeGraph::is`]).
    pub fn element_graph(&self) -> NodeGraph {
        NodeGraph(Arc::clone(&self.elements))
    }

    /// The node adjacency (elements and contact couplings) as a shared
    /// graph: the patterns [`Self::coupled`] makes without node groups
    /// (rigid obstacles only) share their elements' graph, so an ordering
    /// of it started from the first pattern fits them
    /// ([`NodeGraph::is`]).
    pub fn graph(&self) -> NodeGraph {
        NodeGraph(Arc::clone(&self.neighbours))
    }

    /// Index of entry `(j, i)` for entry `k = (i, j)`.
    #[inline]
    pub fn mirror(&self, k: usize) -> usize {
        self.mirrors()[k]
    }

    /// [`Self::mirror`] of every entry (made at the first call).
    fn mirrors(&self) -> &[usize] {
        self.mirror
            .get_or_init(|| transpose_positions(self.symbolic()))
    }

    /// Set each entry above the diagonal of `values` to its mirror's
    /// (`A_ij = A_ji` for `i < j`): the whole symmetric matrix from its
    /// lower triangle. The mirrors are found as [`transpose_positions`]
    /// finds them, a cursor per column (one index per unknown), not read
    /// from [`Self::mirror`]'s stored ones (one index per entry, as large
    /// as the values): the cached constant `K` of a large run expands
    /// without them.
    pub fn mirror_lower_into_upper(&self, values: &mut [f64]) {
        let (cp, ri) = (&self.col_ptr, self.symbolic().row_idx());
        let mut cursor: Vec<usize> = cp[..self.dimension()].to_vec();
        for j in 0..self.dimension() {
            for k in cp[j]..cp[j + 1] {
                let i = ri[k];
                // entry (j, i), in column i, where the cursor stands
                let mirror = cursor[i];
                cursor[i] += 1;
                if i < j {
                    values[k] = values[mirror];
                }
            }
        }
    }

    /// Set the couplings of multiplier `k` in `values` to its column of
    /// `tangent` on both sides: entries `(3a + i, 3N + k)` and
    /// `(3N + k, 3a + i)` of every node `a` it couples take `tangent`'s
    /// entry `(3a + i, 3N + k)`, `∂r_u/∂λ_k` (a symmetric matrix whose
    /// coupling is the tangent's column where the tangent's row differs
    /// from it: `ContactInterface::couple_multipliers_by_force`).
    pub fn couple_multiplier_by_column(&self, k: usize, tangent: &[f64], values: &mut [f64]) {
        for &a in &self.multiplier_nodes[k] {
            if let Some(e) = self.multiplier_entries(k, a) {
                for (&column, &row) in e.node_rows.iter().zip(&e.multiplier_row) {
                    values[column] = tangent[column];
                    values[row] = tangent[column];
                }
            }
        }
    }

    /// The symmetric part `½ (A + Aᵀ)` of values on this pattern.
    pub fn symmetric_part(&self, values: &[f64]) -> Vec<f64> {
        self.mirrors()
            .iter()
            .enumerate()
            .map(|(k, &m)| 0.5 * (values[k] + values[m]))
            .collect()
    }

    /// Index of the diagonal entry of dof `d`, of a pattern that stores
    /// every node's diagonal block (all but a process's own,
    /// [`crate::assembly::Model::set_share_with_local_rows`]: there
    /// [`Self::stored_diagonal`]).
    #[inline]
    pub fn diagonal_entry(&self, d: usize) -> usize {
        #[allow(clippy::expect_used)] // the pattern is built with every node its own neighbour
        let entry = self
            .stored_diagonal(d)
            .expect("every node is its own neighbour");
        entry
    }

    /// Index of the diagonal entry of dof `d`, or `None` for the dof of a
    /// node this pattern holds no rows of (another process's node that
    /// this process's elements do not touch).
    #[inline]
    pub fn stored_diagonal(&self, d: usize) -> Option<usize> {
        let first_multiplier = 3 * self.num_nodes();
        if d >= first_multiplier {
            return Some(self.multiplier_diagonal(d - first_multiplier));
        }
        self.block_entry(d / 3, d % 3, d / 3, d % 3)
    }
}

/// The lists (elements, contact groups) each node is in: node `a`'s are
/// `of_node[start[a]..start[a + 1]]`, in increasing list index (counted
/// first: no list grows).
fn lists_of_nodes<L: AsRef<[usize]>>(num_nodes: usize, lists: &[L]) -> (Vec<usize>, Vec<usize>) {
    let mut start = vec![0usize; num_nodes + 1];
    for nodes in lists {
        for &a in nodes.as_ref() {
            start[a + 1] += 1;
        }
    }
    for a in 0..num_nodes {
        start[a + 1] += start[a];
    }
    let mut of_node = vec![0usize; start[num_nodes]];
    let mut next = start[..num_nodes].to_vec();
    for (l, nodes) in lists.iter().enumerate() {
        for &a in nodes.as_ref() {
            of_node[next[a]] = l;
            next[a] += 1;
        }
    }
    (start, of_node)
}

/// `mirror[k]`: the position of entry `(j, i)` for entry `k = (i, j)` of a
/// structurally symmetric pattern with sorted rows: walking the columns in
/// order meets the entries `(i, j)` of row `i` with `j` increasing, which
/// is the order of column `i`'s rows, so a cursor per column places them
/// (a transpose by counting, `O(nnz)`).
fn transpose_positions(symbolic: &SymbolicSparseColMat<usize>) -> Vec<usize> {
    let (cp, ri) = (symbolic.col_ptr(), symbolic.row_idx());
    let mut cursor: Vec<usize> = cp[..symbolic.ncols()].to_vec();
    let mut mirror = vec![0; ri.len()];
    for j in 0..symbolic.ncols() {
        for (k, &i) in ri.iter().enumerate().take(cp[j + 1]).skip(cp[j]) {
            mirror[k] = cursor[i];
            cursor[i] += 1;
        }
    }
    mirror
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Multipliers of one group (a contact node's normal and tangential
    /// ones) couple to each other: every pair's entry is where the
    /// symbolic structure has it, the diagonal too, and the pattern stays
    /// structurally symmetric.
    #[test]
    fn multiplier_groups_couple_their_members() {
        let elements: Vec<Vec<usize>> = vec![vec![0, 1, 2], vec![1, 2, 3]];
        let nodes = vec![vec![1], vec![2], vec![1], vec![1], vec![2], vec![2]];
        // as the contact set lists them: every member its whole group
        let (a, b) = (vec![0, 2, 3], vec![1, 4, 5]);
        let groups = vec![a.clone(), b.clone(), a.clone(), a, b.clone(), b];
        let p = SparsityPattern::with_multiplier_groups(
            4,
            elements.iter().map(|e| e.as_slice()),
            &nodes,
            &groups,
        );
        let (cp, ri) = (p.symbolic().col_ptr(), p.symbolic().row_idx());
        let first = 12;
        for (k, group) in [
            [0, 2, 3],
            [1, 4, 5],
            [0, 2, 3],
            [0, 2, 3],
            [1, 4, 5],
            [1, 4, 5],
        ]
        .iter()
        .enumerate()
        {
            for l in 0..6 {
                let entry = p.multiplier_pair(l, k);
                assert_eq!(entry.is_some(), group.contains(&l), "({l}, {k})");
                if let Some(e) = entry {
                    assert_eq!(ri[e], first + l);
                    assert!(e >= cp[first + k] && e < cp[first + k + 1]);
                }
            }
            assert_eq!(ri[p.multiplier_diagonal(k)], first + k);
            assert_eq!(p.diagonal_entry(first + k), p.multiplier_diagonal(k));
        }
        // the mirror of every entry exists: the pattern is symmetric
        let values: Vec<f64> = (0..p.nnz()).map(|k| k as f64).collect();
        let sym = p.symmetric_part(&values);
        assert_eq!(sym.len(), p.nnz());
    }

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

    /// Each node's neighbours are the nodes of its elements, itself
    /// included, sorted and each once (against a set per node), also with
    /// more nodes than one chunk of the parallel gathering holds.
    #[test]
    fn element_graph_lists_each_neighbour_once() {
        let n = 200;
        let elements: Vec<Vec<usize>> = (0..300)
            .map(|e| (0..4).map(|i| (e * 7 + i * 13 + e * e % 11) % n).collect())
            .collect();
        let graph = NodeGraph::of_elements(n, elements.iter().map(|e| e.as_slice()));
        let mut expected = vec![std::collections::BTreeSet::new(); n];
        for (a, set) in expected.iter_mut().enumerate() {
            set.insert(a);
        }
        for e in &elements {
            for &a in e {
                expected[a].extend(e.iter().copied());
            }
        }
        for (a, set) in expected.iter().enumerate() {
            assert_eq!(
                graph.0[a],
                set.iter().copied().collect::<Vec<_>>(),
                "node {a}"
            );
        }
    }

    /// A process's graph ([`NodeGraph::of_elements_and`]): a node no
    /// element lists keeps its diagonal block only if asked (an own node),
    /// another has empty columns and no diagonal entry, and the entries
    /// of the nodes the elements touch are the whole pattern's.
    #[test]
    fn lone_nodes_are_kept_or_left_out() {
        let elements: Vec<Vec<usize>> = vec![vec![0, 1, 2], vec![1, 2, 3]];
        let graph =
            NodeGraph::of_elements_and(6, elements.iter().map(|e| e.as_slice()), |a| a == 4);
        let part = SparsityPattern::from_graph(&graph);
        let whole = SparsityPattern::from_elements(6, elements.iter().map(|e| e.as_slice()));
        assert_eq!(part.dimension(), 18);
        assert_eq!(part.nnz() + 9, whole.nnz());
        assert_eq!(part.node_column_length(5), 0);
        for d in 0..15 {
            let k = part.stored_diagonal(d).unwrap();
            assert_eq!(part.symbolic().row_idx()[k], d);
            assert_eq!(k, whole.diagonal_entry(d), "dof {d}");
        }
        assert!((15..18).all(|d| part.stored_diagonal(d).is_none()));
        assert!(part.block_entry(5, 0, 3, 0).is_none());
    }

    /// A pattern coupled from an element pattern equals the one built from
    /// the elements and the groups at once, and each entry's mirror is the
    /// transposed entry.
    #[test]
    fn coupled_pattern_equals_the_one_built_at_once() {
        let elements: Vec<Vec<usize>> = vec![vec![0, 1, 2], vec![1, 2, 3], vec![3, 4]];
        let groups: Vec<Vec<usize>> = vec![vec![0, 4], vec![2, 5]];
        let multipliers: Vec<Vec<usize>> = vec![vec![4, 0], vec![5]];
        let base = SparsityPattern::from_elements(6, elements.iter().map(|e| e.as_slice()));
        let all = elements.iter().chain(&groups).map(|e| e.as_slice());
        let at_once = SparsityPattern::with_multipliers(6, all, &multipliers);
        let coupled = base.coupled(&groups, &multipliers, &[]);
        let again = coupled.coupled(&[], &multipliers, &[]);
        assert_eq!(coupled.symbolic().col_ptr(), at_once.symbolic().col_ptr());
        assert_eq!(coupled.symbolic().row_idx(), at_once.symbolic().row_idx());
        assert!(
            again.block_entry(0, 0, 4, 0).is_none(),
            "the groups are not kept"
        );
        assert_eq!(again.dimension(), 20);
        for p in [&coupled, &again, &base] {
            let (cp, ri) = (p.symbolic().col_ptr(), p.symbolic().row_idx());
            for j in 0..p.dimension() {
                for k in cp[j]..cp[j + 1] {
                    let m = p.mirror(k);
                    assert_eq!(ri[m], j);
                    assert!(m >= cp[ri[k]] && m < cp[ri[k] + 1]);
                }
            }
        }
    }
}
