//! Element colouring for a parallel, deterministic assembly.
//!
//! The elements are split into colours such that no two elements of one
//! colour share a node (greedy colouring of the element–node–element graph,
//! in mesh order: each element takes the smallest colour none of its
//! neighbours has). The elements of a colour then add into disjoint global
//! entries and can be scattered by any number of threads at once; colour
//! after colour, every global entry receives its element contributions in
//! the same order (colour order) whatever the number of threads, so the
//! assembled values are bitwise independent of it.

/// The elements of each colour, in mesh order.
#[derive(Debug)]
pub struct ElementColouring {
    colours: Vec<Vec<usize>>,
}

impl ElementColouring {
    /// Greedy colouring of the elements whose node lists `element_nodes`
    /// yields (nodes numbered below `num_nodes`).
    pub fn new<'a>(num_nodes: usize, element_nodes: impl Iterator<Item = &'a [usize]>) -> Self {
        let elements: Vec<&[usize]> = element_nodes.collect();
        // node → elements, in CSR form
        let mut start = vec![0usize; num_nodes + 1];
        for nodes in &elements {
            for &n in *nodes {
                start[n + 1] += 1;
            }
        }
        for n in 0..num_nodes {
            start[n + 1] += start[n];
        }
        let mut fill = start.clone();
        let mut node_elements = vec![0usize; start[num_nodes]];
        for (e, nodes) in elements.iter().enumerate() {
            for &n in *nodes {
                node_elements[fill[n]] = e;
                fill[n] += 1;
            }
        }
        const NONE: usize = usize::MAX;
        let mut colour = vec![NONE; elements.len()];
        // taken[c] == e + 1: colour c is used by a neighbour of element e
        let mut taken: Vec<usize> = Vec::new();
        let mut colours: Vec<Vec<usize>> = Vec::new();
        for (e, nodes) in elements.iter().enumerate() {
            for &n in *nodes {
                for &other in &node_elements[start[n]..start[n + 1]] {
                    let c = colour[other];
                    if c != NONE {
                        taken[c] = e + 1;
                    }
                }
            }
            let c = taken
                .iter()
                .position(|&t| t != e + 1)
                .unwrap_or(taken.len());
            if c == taken.len() {
                taken.push(0);
                colours.push(Vec::new());
            }
            colour[e] = c;
            colours[c].push(e);
        }
        ElementColouring { colours }
    }

    /// The elements of each colour, in mesh order.
    pub fn colours(&self) -> &[Vec<usize>] {
        &self.colours
    }
}

/// Mutable access from several threads to a slice whose entries the
/// threads touch disjointly (the elements of one colour).
pub(crate) struct DisjointSlice<'a> {
    ptr: *mut f64,
    len: usize,
    _borrow: std::marker::PhantomData<&'a mut [f64]>,
}

// SAFETY: the only access is `add`, whose callers guarantee that no two
// threads touch the same index concurrently (see `add`).
unsafe impl Send for DisjointSlice<'_> {}
// SAFETY: as above.
unsafe impl Sync for DisjointSlice<'_> {}

impl<'a> DisjointSlice<'a> {
    /// Borrow `values` mutably for the lifetime of the wrapper.
    pub(crate) fn new(values: &'a mut [f64]) -> Self {
        DisjointSlice {
            ptr: values.as_mut_ptr(),
            len: values.len(),
            _borrow: std::marker::PhantomData,
        }
    }

    /// `values[i] += v`.
    ///
    /// # Safety
    /// No other thread reads or writes index `i` during the call: the
    /// callers add the contributions of the elements of one colour, which
    /// share no node and hence no global entry.
    #[inline]
    pub(crate) unsafe fn add(&self, i: usize, v: f64) {
        assert!(i < self.len, "index {i} out of {}", self.len);
        // SAFETY: in bounds (checked above); exclusive by the caller's contract
        unsafe { *self.ptr.add(i) += v };
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::structured::box_mesh;
    use crate::mesh::ElementKind;

    /// Every element has exactly one colour, and no two elements of a colour
    /// share a node.
    #[test]
    fn colours_partition_the_elements_and_share_no_node() {
        for kind in [ElementKind::Tet4, ElementKind::Hex8] {
            let mesh = box_mesh(kind, [4, 3, 5], [1.0, 1.0, 1.0]);
            let c = ElementColouring::new(
                mesh.num_nodes(),
                mesh.elements.iter().map(|e| e.nodes.as_slice()),
            );
            let mut seen = vec![0; mesh.elements.len()];
            for colour in c.colours() {
                let mut owner = vec![usize::MAX; mesh.num_nodes()];
                for &e in colour {
                    seen[e] += 1;
                    for &n in &mesh.elements[e].nodes {
                        assert_eq!(owner[n], usize::MAX, "{kind:?}: node {n} twice");
                        owner[n] = e;
                    }
                }
            }
            assert!(seen.iter().all(|&s| s == 1));
            // a Hex8 grid needs 8 colours (the cells around a vertex), greedy
            // in lexicographic order finds exactly that
            if kind == ElementKind::Hex8 {
                assert_eq!(c.colours().len(), 8);
            }
        }
    }
}
