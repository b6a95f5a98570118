//! Fill-reducing orderings for the sparse LDLᵀ.
//!
//! faer brings approximate minimum degree (AMD); for 3D meshes a nested
//! dissection (METIS `NodeND`) fills far less: on a 53 k-dof Hex8 cube,
//! 44.5 M factor entries against AMD's 72.2 M, and a 2–3 times faster
//! numeric factorisation (`BENCHMARKS.md`). METIS orders
//! the node graph (three times smaller than the dof graph), and each node's
//! three dofs stay together, which also keeps the supernodes wide. The
//! `metis-sys` crate builds METIS from its vendored C sources with `cc`; no
//! system library is needed.

use super::linear::Ordering;
use crate::assembly::pattern::SparsityPattern;
use crate::{Error, Result};
use std::sync::{Mutex, MutexGuard};

/// METIS keeps its random-number state in globals (GKlib's seeded
/// generator, reseeded at the start of every call): two calls at once in
/// one process interleave it and each returns a different, still valid,
/// answer, so that two simulations run side by side (threads, the Python
/// package) ordered their matrices differently and differed in round-off
/// (4e-16 measured on press-pull). Every METIS call holds this lock.
static METIS: Mutex<()> = Mutex::new(());

/// The lock around a METIS call (see [`METIS`]); a panic while it was
/// held leaves nothing to repair, so a poisoned lock is taken as it is.
pub(crate) fn metis_lock() -> MutexGuard<'static, ()> {
    METIS
        .lock()
        .unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// Nested-dissection permutation of the nodes of a graph given in CSR form
/// (`xadj`, `adjncy`, self excluded). Returns `forward` with
/// `forward[new] = old` (node indices); expand it to dofs with
/// [`crate::assembly::pattern::SparsityPattern::dof_ordering`].
pub fn nested_dissection(xadj: &[usize], adjncy: &[usize]) -> Result<Vec<usize>> {
    let n = xadj.len().saturating_sub(1);
    if n == 0 {
        return Ok(Vec::new());
    }
    let to_idx = |v: usize| {
        i32::try_from(v)
            .map_err(|_| Error::LinearSolver("graph too large for 32-bit METIS indices".into()))
    };
    let mut x: Vec<i32> = xadj.iter().map(|&v| to_idx(v)).collect::<Result<_>>()?;
    let mut a: Vec<i32> = adjncy.iter().map(|&v| to_idx(v)).collect::<Result<_>>()?;
    let mut nv = to_idx(n)?;
    let mut perm = vec![0i32; n];
    let mut iperm = vec![0i32; n];
    let mut options = [-1i32; metis_sys::METIS_NOPTIONS as usize];
    let _metis = metis_lock();
    // SAFETY: every array has the length METIS_NodeND expects (nvtxs + 1,
    // xadj[nvtxs], nvtxs, nvtxs, NOPTIONS); METIS does not keep the pointers.
    let status = unsafe {
        metis_sys::METIS_SetDefaultOptions(options.as_mut_ptr());
        metis_sys::METIS_NodeND(
            &mut nv,
            x.as_mut_ptr(),
            a.as_mut_ptr(),
            std::ptr::null_mut(),
            options.as_mut_ptr(),
            perm.as_mut_ptr(),
            iperm.as_mut_ptr(),
        )
    };
    if status != metis_sys::rstatus_et_METIS_OK {
        return Err(Error::LinearSolver(format!(
            "METIS_NodeND failed with status {status}"
        )));
    }
    // METIS: row i of the permuted matrix is row perm[i] of the original.
    Ok(perm.iter().map(|&node| node as usize).collect())
}

/// AMD for small problems, METIS nested dissection above 10 000 dofs
/// (where it already fills less: 2.4 times fewer factor entries at 28 k
/// dofs on a Hex8 box). `num_dofs` displacement unknowns come first in
/// `pattern`, the multipliers after them.
pub fn fill_reducing_ordering(pattern: &SparsityPattern, num_dofs: usize) -> Result<Ordering> {
    // a saddle system needs each multiplier after its node: always ND then
    if num_dofs <= 10_000 && pattern.dimension() <= num_dofs {
        return Ok(Ordering::Amd);
    }
    let (xadj, adjncy) = pattern.node_graph();
    let nodes = nested_dissection(&xadj, &adjncy)?;
    Ok(Ordering::Custom(pattern.dof_ordering(&nodes)))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A path graph is ordered into a valid permutation of all dofs.
    #[test]
    fn permutation_is_valid() {
        let n = 20;
        let mut xadj = vec![0];
        let mut adj = Vec::new();
        for i in 0..n {
            if i > 0 {
                adj.push(i - 1);
            }
            if i + 1 < n {
                adj.push(i + 1);
            }
            xadj.push(adj.len());
        }
        let mut p = nested_dissection(&xadj, &adj).unwrap();
        assert_eq!(p.len(), n);
        p.sort_unstable();
        assert!(p.iter().enumerate().all(|(i, &v)| i == v));
    }
}
