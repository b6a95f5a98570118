//! The partition of a mesh over the processes of a distributed run
//! (`mpirun -np N`): METIS' `PartMeshDual` cuts the element graph (two
//! elements adjacent when they share a face: 3 nodes in a mesh with
//! tetrahedra, 4 in an all-hexahedral one) into `parts` parts of nearly
//! equal element counts with few cut faces, and gives every node the part
//! of one of its elements. METIS is deterministic, so every process
//! computes the same partition from the same mesh (the mesh is read by
//! every process). The vendored METIS of `metis-sys` needs no system
//! library.

use crate::mesh::{ElementKind, Mesh};
use crate::{Error, Result};

/// Which process owns each element and each node.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MeshPartition {
    pub parts: usize,
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
        let all_hex = mesh.elements.iter().all(|e| e.kind == ElementKind::Hex8);
        let mut ncommon: i32 = if all_hex { 4 } else { 3 };
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
        // a node belongs to the part of one of its elements (METIS' node
        // parts need not be), so that each process owns rows it assembles
        let mut node_part = vec![usize::MAX; nn];
        for (e, el) in mesh.elements.iter().enumerate() {
            for &n in &el.nodes {
                let p = element_part[e];
                if node_part[n] == usize::MAX || npart[n] as usize == p {
                    node_part[n] = p;
                }
            }
        }
        node_part.iter_mut().for_each(|p| {
            if *p == usize::MAX {
                *p = 0
            }
        });
        Ok(MeshPartition {
            parts,
            element_part,
            node_part,
        })
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

fn counts(owner: &[usize], parts: usize) -> Vec<usize> {
    let mut c = vec![0; parts];
    for &p in owner {
        c[p] += 1;
    }
    c
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
    }
}
