//! The partition of a mesh over the processes of a distributed run
//! (`mpirun -np N`): METIS' `PartMeshDual` cuts the element graph (two
//! elements adjacent when they share a face: 3 nodes in a mesh with
//! tetrahedra, 4 in an all-hexahedral one) into `parts` parts of nearly
//! equal element counts with few cut faces, and gives every node the part
//! of one of its elements. METIS is deterministic, so every process
//! computes the same partition from the same mesh (the mesh is read by
//! every process). The vendored METIS of `metis-sys` needs no system
//! library.
//!
//! A distributed run cuts the mesh in parallel where PETSc can
//! (`crate::solve::petsc::partitioning`: ParMETIS or PT-Scotch through
//! PETSc's `MatPartitioning`, each process giving the rows of its block of
//! elements of the dual graph, [`dual_graph`]), and takes the element parts
//! it returns with [`MeshPartition::from_element_parts`], after
//! [`MeshPartition::check`]; METIS here is the serial fallback.

use crate::mesh::{ElementKind, Mesh};
use crate::{Error, Result};

/// Which process owns each element and each node.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MeshPartition {
    pub parts: usize,
    /// How the elements were cut, in words for the log.
    pub method: String,
    /// The part of every element.
    pub element_part: Vec<usize>,
    /// The part of every node (one of its elements' parts; 0 for a node of
    /// no element).
    pub node_part: Vec<usize>,
}

impl MeshPartition {
    /// `mesh` cut into `parts` parts (every element in part 0 when
    /// `parts` is 1).
    pub fn new(mesh: &Mesh, parts: usize) -> Result<Self> {
        let (ne, nn) = (mesh.elements.len(), mesh.num_nodes());
        if parts <= 1 || ne == 0 {
            return Ok(MeshPartition {
                parts: parts.max(1),
                method: "one part".into(),
                element_part: vec![0; ne],
                node_part: vec![0; nn],
            });
        }
        if parts > ne {
            return Err(Error::LinearSolver(format!(
                "{parts} processes for a mesh of {ne} elements: run with at most {ne} \
                 processes (mpirun -np)"
            )));
        }
        let index = |v: usize| {
            i32::try_from(v)
                .map_err(|_| Error::LinearSolver("mesh too large for 32-bit METIS indices".into()))
        };
        let mut eptr = Vec::with_capacity(ne + 1);
        let mut eind = Vec::new();
        eptr.push(0);
        for e in &mesh.elements {
            for &n in &e.nodes {
                eind.push(index(n)?);
            }
            eptr.push(index(eind.len())?);
        }
        let mut ncommon = common_nodes(mesh) as i32;
        let (mut ne_i, mut nn_i, mut np_i) = (index(ne)?, index(nn)?, index(parts)?);
        let mut options = [-1i32; metis_sys::METIS_NOPTIONS as usize];
        let mut objval = 0i32;
        let mut epart = vec![0i32; ne];
        let mut npart = vec![0i32; nn];
        let _metis = super::ordering::metis_lock();
        // SAFETY: eptr has ne + 1 entries, eind eptr[ne], epart ne, npart
        // nn, options NOPTIONS; the null arguments are optional in METIS
        let status = unsafe {
            metis_sys::METIS_SetDefaultOptions(options.as_mut_ptr());
            metis_sys::METIS_PartMeshDual(
                &mut ne_i,
                &mut nn_i,
                eptr.as_mut_ptr(),
                eind.as_mut_ptr(),
                std::ptr::null_mut(),
                std::ptr::null_mut(),
                &mut ncommon,
                &mut np_i,
                std::ptr::null_mut(),
                options.as_mut_ptr(),
                &mut objval,
                epart.as_mut_ptr(),
                npart.as_mut_ptr(),
            )
        };
        if status != metis_sys::rstatus_et_METIS_OK {
            return Err(Error::LinearSolver(format!(
                "METIS_PartMeshDual failed with status {status}"
            )));
        }
        let element_part: Vec<usize> = epart.iter().map(|&p| p as usize).collect();
        let node_part = node_parts(mesh, &element_part, |n| Some(npart[n] as usize));
        Ok(MeshPartition {
            parts,
            method: "METIS (PartMeshDual)".into(),
            element_part,
            node_part,
        })
    }

    /// The partition whose elements are in `element_part` (every one in
    /// `0..parts`, e.g. from a parallel partitioner), cut by `method` (in
    /// words): each node in the part of the first of its elements.
    pub fn from_element_parts(
        mesh: &Mesh,
        parts: usize,
        element_part: Vec<usize>,
        method: String,
    ) -> Self {
        let node_part = node_parts(mesh, &element_part, |_| None);
        MeshPartition {
            parts,
            method,
            element_part,
            node_part,
        }
    }

    /// Whether this is a valid partition of `mesh` balanced within
    /// `imbalance`: one part in `0..parts` for every element (so each is
    /// owned once) and every node, each node in the part of one of its
    /// elements, and no part with more than `(1 + imbalance) ne/parts + 1`
    /// elements (nor none); what is wrong otherwise.
    pub fn check(&self, mesh: &Mesh, imbalance: f64) -> std::result::Result<(), String> {
        let (ne, nn) = (mesh.elements.len(), mesh.num_nodes());
        if self.element_part.len() != ne || self.node_part.len() != nn {
            return Err(format!(
                "{} element parts for {ne} elements, {} node parts for {nn} nodes",
                self.element_part.len(),
                self.node_part.len()
            ));
        }
        if let Some(e) = self.element_part.iter().position(|&p| p >= self.parts) {
            return Err(format!(
                "element {e} in part {} of {}",
                self.element_part[e], self.parts
            ));
        }
        if let Some(n) = self.node_part.iter().position(|&p| p >= self.parts) {
            return Err(format!(
                "node {n} in part {} of {}",
                self.node_part[n], self.parts
            ));
        }
        // per node: (in an element, in one of its elements' parts)
        let mut held = vec![(false, false); nn];
        for (el, &p) in mesh.elements.iter().zip(&self.element_part) {
            for &n in &el.nodes {
                held[n] = (true, held[n].1 || self.node_part[n] == p);
            }
        }
        if let Some(n) = held.iter().position(|&(any, own)| any && !own) {
            return Err(format!(
                "node {n} in part {}, which has none of its elements",
                self.node_part[n]
            ));
        }
        let counts = self.element_counts();
        let bound = (1.0 + imbalance) * ne as f64 / self.parts as f64 + 1.0;
        if counts.iter().any(|&c| c == 0 || c as f64 > bound) {
            return Err(format!(
                "element counts {counts:?} out of balance (each at most {bound:.0}, none empty)"
            ));
        }
        Ok(())
    }

    /// What process `part` would hold of the tangent if it kept only its
    /// rows (issue 29 item 1; displacement rows, 3 per node, multipliers
    /// left out): its own nodes, the ghost layer (the other nodes of its
    /// elements), the entries of its own rows (complete: every element at
    /// an own node, `9 × Σ_own |neighbours|`) and those of the ghost rows
    /// its own elements touch. Summed over the parts, the own rows'
    /// entries are the whole pattern's.
    pub fn local_sizes(&self, mesh: &Mesh, part: usize) -> LocalSizes {
        let own = |n: usize| self.node_part[n] == part;
        // columns (nodes) of each local row, by node
        let mut rows: std::collections::BTreeMap<usize, Vec<usize>> = Default::default();
        for (el, &p) in mesh.elements.iter().zip(&self.element_part) {
            for &a in el.nodes.iter().filter(|&&a| p == part || own(a)) {
                rows.entry(a).or_default().extend(&el.nodes);
            }
        }
        let mut sizes = LocalSizes::default();
        for (a, columns) in rows.iter_mut() {
            columns.sort_unstable();
            columns.dedup();
            let entries = 9 * columns.len();
            if own(*a) {
                sizes.own_nodes += 1;
                sizes.own_entries += entries;
            } else {
                sizes.ghost_nodes += 1;
                sizes.ghost_entries += entries;
            }
        }
        sizes
    }

    /// The elements `part`'s rows read, as a mask over every element: its
    /// own, and the ghost layer of its rows (the other parts' elements at
    /// one of its nodes, which complete its rows: [`Self::local_sizes`]).
    pub fn row_elements(&self, mesh: &Mesh, part: usize) -> Vec<bool> {
        mesh.elements
            .iter()
            .zip(&self.element_part)
            .map(|(el, &p)| p == part || el.nodes.iter().any(|&n| self.node_part[n] == part))
            .collect()
    }

    /// The elements of `part`, as a mask over every element.
    pub fn owned_elements(&self, part: usize) -> Vec<bool> {
        self.element_part.iter().map(|&p| p == part).collect()
    }

    /// The elements of each part.
    pub fn element_counts(&self) -> Vec<usize> {
        counts(&self.element_part, self.parts)
    }

    /// The nodes of each part.
    pub fn node_counts(&self) -> Vec<usize> {
        counts(&self.node_part, self.parts)
    }
}

/// One process's rows of the tangent ([`MeshPartition::local_sizes`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LocalSizes {
    /// Nodes it owns (their rows are its rows of PETSc's matrix).
    pub own_nodes: usize,
    /// Nodes of its elements owned by another process: the ghost layer.
    pub ghost_nodes: usize,
    /// Entries of its own rows.
    pub own_entries: usize,
    /// Entries of the ghost rows its elements touch.
    pub ghost_entries: usize,
}

fn counts(owner: &[usize], parts: usize) -> Vec<usize> {
    let mut c = vec![0; parts];
    for &p in owner {
        c[p] += 1;
    }
    c
}

/// The nodes two elements share when they share a face: 4 in an
/// all-hexahedral mesh, else 3 (a triangle of a tetrahedron or a wedge).
pub fn common_nodes(mesh: &Mesh) -> usize {
    let all_hex = mesh.elements.iter().all(|e| e.kind == ElementKind::Hex8);
    if all_hex {
        4
    } else {
        3
    }
}

/// Each node's part: among its elements' parts, `preferred(node)` when one
/// of them is that, else the first element's (mesh order); 0 for a node of
/// no element.
fn node_parts(
    mesh: &Mesh,
    element_part: &[usize],
    preferred: impl Fn(usize) -> Option<usize>,
) -> Vec<usize> {
    let mut node_part = vec![usize::MAX; mesh.num_nodes()];
    for (e, el) in mesh.elements.iter().enumerate() {
        let p = element_part[e];
        for &n in &el.nodes {
            if node_part[n] == usize::MAX || preferred(n) == Some(p) {
                node_part[n] = p;
            }
        }
    }
    node_part
        .into_iter()
        .map(|p| if p == usize::MAX { 0 } else { p })
        .collect()
}

/// The rows `elements` of the mesh's dual graph in compressed form: the
/// neighbours of each element (those sharing at least `common` nodes with
/// it: a face), sorted, itself left out; `(offsets, neighbours)` with
/// `offsets.len() == elements.len() + 1`. A parallel partitioner takes
/// each process's block of rows.
pub fn dual_graph(
    mesh: &Mesh,
    elements: std::ops::Range<usize>,
    common: usize,
) -> (Vec<usize>, Vec<usize>) {
    let nn = mesh.num_nodes();
    let mut start = vec![0usize; nn + 1];
    for el in &mesh.elements {
        for &n in &el.nodes {
            start[n + 1] += 1;
        }
    }
    for n in 0..nn {
        start[n + 1] += start[n];
    }
    let mut next = start.clone();
    let mut of_node = vec![0usize; start[nn]];
    for (e, el) in mesh.elements.iter().enumerate() {
        for &n in &el.nodes {
            of_node[next[n]] = e;
            next[n] += 1;
        }
    }
    let mut offsets = vec![0];
    let mut neighbours = Vec::new();
    let mut shared: std::collections::BTreeMap<usize, usize> = Default::default();
    for e in elements {
        shared.clear();
        for &n in &mesh.elements[e].nodes {
            for &f in &of_node[start[n]..start[n + 1]] {
                *shared.entry(f).or_default() += 1;
            }
        }
        neighbours.extend(
            shared
                .iter()
                .filter(|&(&f, &c)| f != e && c >= common)
                .map(|(&f, _)| f),
        );
        offsets.push(neighbours.len());
    }
    (offsets, neighbours)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::structured::box_mesh;

    #[test]
    fn two_parts_balance_the_elements_and_own_nodes_of_their_elements() {
        let mesh = box_mesh(ElementKind::Hex8, [6, 4, 2], [3.0, 2.0, 1.0]);
        let p = MeshPartition::new(&mesh, 2).unwrap();
        let counts = p.element_counts();
        assert_eq!(counts.iter().sum::<usize>(), 48);
        // METIS' default imbalance is 3 %: 24 ± 1
        assert!(counts.iter().all(|&c| (23..=25).contains(&c)), "{counts:?}");
        for (n, &part) in p.node_part.iter().enumerate() {
            assert!(
                mesh.elements
                    .iter()
                    .enumerate()
                    .any(|(e, el)| el.nodes.contains(&n) && p.element_part[e] == part),
                "node {n} owned by a part none of whose elements has it"
            );
        }
        // deterministic: the same partition again
        assert_eq!(MeshPartition::new(&mesh, 2).unwrap(), p);
        assert_eq!(p.check(&mesh, 0.05), Ok(()));
    }

    /// A 3 × 2 × 1 block of Hex8 (elements x fastest): an inner element
    /// has the face neighbours ±1 in x and ±3 in y, not the edge ones.
    #[test]
    fn the_dual_graph_joins_elements_that_share_a_face() {
        let mesh = box_mesh(ElementKind::Hex8, [3, 2, 1], [3.0, 2.0, 1.0]);
        let (offsets, neighbours) = dual_graph(&mesh, 0..6, common_nodes(&mesh));
        let of = |e: usize| &neighbours[offsets[e]..offsets[e + 1]];
        let centre = |e: usize| {
            let el = &mesh.elements[e];
            let sum = el
                .nodes
                .iter()
                .map(|&n| nalgebra::Vector3::from(mesh.nodes[n]))
                .sum::<nalgebra::Vector3<f64>>();
            sum / el.nodes.len() as f64
        };
        for e in 0..6 {
            // face neighbours are exactly the elements one unit away
            let expected: Vec<usize> = (0..6)
                .filter(|&f| ((centre(f) - centre(e)).norm() - 1.0).abs() < 1e-12)
                .collect();
            assert_eq!(of(e), expected.as_slice(), "element {e}");
        }
        // a block of rows gives the same rows
        let (o, n) = dual_graph(&mesh, 2..4, 4);
        assert_eq!(&n[o[0]..o[2]], &neighbours[offsets[2]..offsets[4]]);
    }

    /// Four Hex8 in a row, two per part: part 0 owns the 12 nodes at
    /// x = 0, 1, 2 (the shared ones go with the first element), part 1 the
    /// 8 at x = 3, 4 and has those at x = 2 as ghosts. A node's row has 8
    /// neighbours at an end plane, 12 inside, times 9 entries.
    #[test]
    fn local_sizes_count_own_rows_and_the_ghost_layer() {
        let mesh = box_mesh(ElementKind::Hex8, [4, 1, 1], [4.0, 1.0, 1.0]);
        let p = MeshPartition::from_element_parts(&mesh, 2, vec![0, 0, 1, 1], "test".into());
        let zero = p.local_sizes(&mesh, 0);
        let one = p.local_sizes(&mesh, 1);
        let row = |neighbours: usize| 4 * 9 * neighbours;
        assert_eq!(
            zero,
            LocalSizes {
                own_nodes: 12,
                ghost_nodes: 0,
                own_entries: row(8) + row(12) + row(12),
                ghost_entries: 0,
            }
        );
        assert_eq!(
            one,
            LocalSizes {
                own_nodes: 8,
                ghost_nodes: 4,
                own_entries: row(12) + row(8),
                ghost_entries: row(8),
            }
        );
        // the own rows make the whole pattern once
        assert_eq!(
            zero.own_entries + one.own_entries,
            row(8 + 12 + 12 + 12 + 8)
        );
        // the elements each part's rows read: its own, and element 2 for
        // part 0 (at its nodes x = 2); a mesh holding only those gives
        // the same sizes
        let rows = [p.row_elements(&mesh, 0), p.row_elements(&mesh, 1)];
        assert_eq!(rows[0], [true, true, true, false]);
        assert_eq!(rows[1], [false, false, true, true]);
        for (part, sizes) in [(0, zero), (1, one)] {
            let mut held = mesh.clone();
            held.release_elements(&rows[part]);
            assert_eq!(held.held_elements(), if part == 0 { 3 } else { 2 });
            assert!(held.holds_element(2) && !held.holds_element(3 * (1 - part)));
            assert_eq!(p.local_sizes(&held, part), sizes, "part {part}");
        }
    }

    #[test]
    fn a_partition_that_owns_an_element_twice_or_leans_is_refused() {
        let mesh = box_mesh(ElementKind::Hex8, [4, 1, 1], [4.0, 1.0, 1.0]);
        let good = MeshPartition::from_element_parts(&mesh, 2, vec![0, 0, 1, 1], "test".into());
        assert_eq!(good.check(&mesh, 0.0), Ok(()));
        // the nodes between elements 1 and 2 take element 1's part
        assert_eq!(good.node_counts(), vec![12, 8]);
        let out_of_range = MeshPartition {
            element_part: vec![0, 0, 1, 2],
            ..good.clone()
        };
        assert!(out_of_range.check(&mesh, 0.0).is_err());
        // 6 of 8 elements in one part: over (1 + 0.05) 4 + 1, within (1 + 0.5) 4 + 1
        let long = box_mesh(ElementKind::Hex8, [8, 1, 1], [8.0, 1.0, 1.0]);
        let parts = vec![0, 0, 0, 0, 0, 0, 1, 1];
        let leaning = MeshPartition::from_element_parts(&long, 2, parts, "test".into());
        assert!(leaning.check(&long, 0.05).unwrap_err().contains("balance"));
        assert_eq!(leaning.check(&long, 0.5), Ok(()));
        let stray_node = MeshPartition {
            node_part: {
                let mut n = good.node_part.clone();
                n[0] = 1;
                n
            },
            ..good.clone()
        };
        assert!(stray_node.check(&mesh, 0.0).unwrap_err().contains("node 0"));
    }
}
