//! The parallel partition of a distributed run (issue 29 item 4): the
//! mesh's dual graph (elements joined where they share a face,
//! [`dual_graph`]) cut by PETSc's `MatPartitioning` with ParMETIS, or
//! PT-Scotch where PETSc was built with that instead (Debian's PETSc 3.18
//! has PT-Scotch, not ParMETIS), each process giving the rows of its own
//! block of elements (`⌊ne·r/N⌋ … ⌊ne·(r+1)/N⌋`), so that no process
//! builds or cuts the whole graph. The element parts are gathered on every
//! process (the mesh is still replicated) and checked
//! ([`MeshPartition::check`]: every element owned once, no part over
//! [`IMBALANCE`]). Where PETSc has neither partitioner, or its partition
//! fails the check, every process cuts the whole mesh with serial METIS
//! ([`MeshPartition::new`], deterministic, so all agree) and the
//! partition's `method` says so, for the log.

use super::{message, MESSAGE, PETSC};
use crate::mesh::Mesh;
use crate::solve::partition::{common_nodes, dual_graph, MeshPartition};
use crate::{Error, Result};
use std::ffi::{c_char, c_int};

mod ffi {
    use std::ffi::{c_char, c_int};
    extern "C" {
        pub fn sg_petsc_partitioner(name: *mut c_char, name_len: usize);
        pub fn sg_petsc_mpi_partition(
            local: c_int,
            global: c_int,
            offsets: *const c_int,
            neighbours: *const c_int,
            parts: c_int,
            part: *mut c_int,
            err: *mut c_char,
            err_len: usize,
        ) -> c_int;
    }
}

/// The largest excess of a part's elements over the mean that a parallel
/// partition may have (beyond one element): ParMETIS' default tolerance
/// is 5 %, PT-Scotch's (PETSc's default) 1 %.
pub const IMBALANCE: f64 = 0.05;

/// PETSc's parallel partitioner (`"parmetis"`, `"ptscotch"`), or `None`
/// when it was built with neither. PETSc initialised first.
pub fn parallel_partitioner() -> Option<String> {
    let mut name = [0 as c_char; 64];
    // SAFETY: a buffer of the length given
    unsafe { ffi::sg_petsc_partitioner(name.as_mut_ptr(), name.len()) };
    Some(message(&name)).filter(|n| !n.is_empty())
}

/// This process's block of the `ne` elements among `size` processes.
fn block(ne: usize, rank: usize, size: usize) -> std::ops::Range<usize> {
    ne * rank / size..ne * (rank + 1) / size
}

/// `mesh` cut into `size` parts, one per process of MPI's world, by
/// PETSc's parallel partitioner, or by serial METIS where it has none or
/// its partition does not check (the partition's `method` says which, and
/// why). Collective: every process calls it with the same mesh.
pub fn partition(mesh: &Mesh, rank: usize, size: usize) -> Result<MeshPartition> {
    if size <= 1 || mesh.elements.is_empty() {
        return MeshPartition::new(mesh, size);
    }
    let Some(partitioner) = parallel_partitioner() else {
        return serial(mesh, size, "this PETSc has neither ParMETIS nor PT-Scotch");
    };
    let element_part = cut(mesh, rank, size, size)?;
    let method = format!("{partitioner} through PETSc's MatPartitioning, in parallel");
    let cut = MeshPartition::from_element_parts(mesh, size, element_part, method);
    match cut.check(mesh, IMBALANCE) {
        Ok(()) => Ok(cut),
        Err(why) => serial(mesh, size, &format!("{partitioner}'s partition: {why}")),
    }
}

/// The serial fallback: METIS on every process, `why` in its `method`.
fn serial(mesh: &Mesh, size: usize, why: &str) -> Result<MeshPartition> {
    let mut partition = MeshPartition::new(mesh, size)?;
    partition.method = format!("{}, serial on every process ({why})", partition.method);
    Ok(partition)
}

/// Every element's part among `parts` by `sg_petsc_mpi_partition`, this
/// process (`rank` of `size`) giving its block of the dual graph's rows.
fn cut(mesh: &Mesh, rank: usize, size: usize, parts: usize) -> Result<Vec<usize>> {
    let ne = mesh.elements.len();
    let index = |v: usize| {
        c_int::try_from(v).map_err(|_| {
            Error::LinearSolver(format!(
                "{ne} elements: the dual graph exceeds PETSc's 32-bit indices"
            ))
        })
    };
    let mine = block(ne, rank, size);
    let local = mine.len();
    let (offsets, neighbours) = dual_graph(mesh, mine, common_nodes(mesh));
    let offsets = offsets.into_iter().map(index).collect::<Result<Vec<_>>>()?;
    let neighbours = neighbours
        .into_iter()
        .map(index)
        .collect::<Result<Vec<_>>>()?;
    let mut part = vec![0 as c_int; ne];
    let mut err = [0 as c_char; MESSAGE];
    let _lock = PETSC.lock().unwrap_or_else(|e| e.into_inner());
    // SAFETY: offsets has local + 1 entries, neighbours offsets[local],
    // part ne; the buffer its length
    let code = unsafe {
        ffi::sg_petsc_mpi_partition(
            index(local)?,
            index(ne)?,
            offsets.as_ptr(),
            neighbours.as_ptr(),
            index(parts)?,
            part.as_mut_ptr(),
            err.as_mut_ptr(),
            err.len(),
        )
    };
    if code != 0 {
        return Err(Error::LinearSolver(message(&err)));
    }
    Ok(part.into_iter().map(|p| p as usize).collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::structured::box_mesh;
    use crate::mesh::ElementKind;

    /// PETSc's partitioner (PT-Scotch on Debian) on one process cuts a
    /// 12 × 6 × 4 Hex8 block into 4 parts: every element in one part, each
    /// node in a part of its elements, no part over 5 % above the mean.
    #[test]
    fn petsc_cuts_a_block_into_balanced_parts() {
        super::super::initialise().unwrap();
        let Some(partitioner) = parallel_partitioner() else {
            panic!("this PETSc has no parallel partitioner (the CI's Debian PETSc has PT-Scotch)");
        };
        let mesh = box_mesh(ElementKind::Hex8, [12, 6, 4], [3.0, 1.5, 1.0]);
        let parts = cut(&mesh, 0, 1, 4).unwrap();
        let p = MeshPartition::from_element_parts(&mesh, 4, parts, partitioner);
        println!(
            "element counts {:?}, node counts {:?}",
            p.element_counts(),
            p.node_counts()
        );
        assert_eq!(p.check(&mesh, IMBALANCE), Ok(()));
        assert_eq!(p.element_counts().iter().sum::<usize>(), 288);
    }

    #[test]
    fn the_serial_fallback_says_so() {
        let mesh = box_mesh(ElementKind::Hex8, [4, 2, 2], [2.0, 1.0, 1.0]);
        let p = serial(&mesh, 2, "no ParMETIS").unwrap();
        assert_eq!(
            p,
            MeshPartition {
                method: p.method.clone(),
                ..MeshPartition::new(&mesh, 2).unwrap()
            }
        );
        assert!(
            p.method.starts_with("METIS (PartMeshDual), serial"),
            "{}",
            p.method
        );
        assert!(p.method.contains("no ParMETIS"), "{}", p.method);
    }

    #[test]
    fn the_blocks_cover_the_elements_once() {
        for (ne, size) in [(10, 3), (7, 7), (100, 2)] {
            let mut next = 0;
            for rank in 0..size {
                let b = block(ne, rank, size);
                assert_eq!(b.start, next);
                assert!(b.len() >= ne / size && b.len() <= ne / size + 1);
                next = b.end;
            }
            assert_eq!(next, ne);
        }
    }
}
