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
use crate::assembly::pattern::{NodeGraph, SparsityPattern};
use crate::{Error, Result};
use std::sync::{Arc, Mutex, MutexGuard, OnceLock};

/// Up to this many displacement unknowns a system without multipliers is
/// ordered by AMD, above it by nested dissection
/// ([`fill_reducing_ordering`]).
pub const AMD_DOFS: usize = 10_000;

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
    metis_node_nd(xadj, adjncy).map_err(Error::LinearSolver)
}

/// [`nested_dissection`], its error a message (what
/// [`EarlyDissection`] keeps for whoever asks).
fn metis_node_nd(xadj: &[usize], adjncy: &[usize]) -> std::result::Result<Vec<usize>, String> {
    let n = xadj.len().saturating_sub(1);
    if n == 0 {
        return Ok(Vec::new());
    }
    let to_idx = |v: usize| {
        i32::try_from(v).map_err(|_| "graph too large for 32-bit METIS indices".to_string())
    };
    let mut x: Vec<i32> = xadj.iter().map(|&v| to_idx(v)).collect::<Result<_, _>>()?;
    let mut a: Vec<i32> = adjncy
        .iter()
        .map(|&v| to_idx(v))
        .collect::<Result<_, _>>()?;
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
        return Err(format!("METIS_NodeND failed with status {status}"));
    }
    // METIS: row i of the permuted matrix is row perm[i] of the original.
    Ok(perm.iter().map(|&node| node as usize).collect())
}

/// The nested dissection of a pattern's node graph, started on a thread
/// of its own as soon as the graph exists
/// ([`EarlyDissection::start`], from [`crate::assembly::Model::with_graph`]):
/// it reads only the graph, which the mesh gives, while the factorisation that needs it comes after the contacts,
/// the output set-up and the assembly, so it runs on a core those leave
/// idle. Whoever asks first computes it — the task, or
/// [`node_dissection`] when the task has not started yet (the task then
/// finds it done) — by the same METIS call on the same graph as without
/// it: the same ordering, bit for bit, and the same error.
#[derive(Clone, Debug)]
pub struct EarlyDissection {
    graph: NodeGraph,
    nodes: Arc<OnceLock<std::result::Result<Vec<usize>, String>>>,
}

impl EarlyDissection {
    /// Start the dissection of `graph` on a thread of its own (not a
    /// pool's: a pool thread waiting in a `join` would run a task queued
    /// on it before returning). Once every holder of the returned handle
    /// is gone, a task not yet started does nothing; a thread that cannot
    /// be started leaves the work to the first who asks.
    pub fn start(graph: &NodeGraph) -> Self {
        let early = EarlyDissection {
            graph: graph.clone(),
            nodes: Arc::default(),
        };
        let graph = early.graph.clone();
        let nodes = Arc::downgrade(&early.nodes);
        let task = move || {
            if let Some(nodes) = nodes.upgrade() {
                nodes.get_or_init(|| dissect(&graph));
            }
        };
        let _ = std::thread::Builder::new()
            .name("dissection".into())
            .spawn(task);
        early
    }

    /// Whether `pattern`'s node graph is the one it dissects.
    pub fn fits(&self, pattern: &SparsityPattern) -> bool {
        self.graph.is(&pattern.graph())
    }

    /// Whether `pattern`'s elements' graph (without its contact
    /// couplings) is the one it dissects: the graph that the condensed
    /// path's factor is ordered on ([`element_dissection`]).
    pub fn fits_elements(&self, pattern: &SparsityPattern) -> bool {
        self.graph.is(&pattern.element_graph())
    }

    /// The node ordering, when `pattern`'s node graph is the one it
    /// dissects (waiting for the task if it is running, computing it if
    /// the task has not started).
    fn nodes_for(&self, pattern: &SparsityPattern) -> Option<Result<Vec<usize>>> {
        self.fits(pattern).then(|| {
            self.nodes
                .get_or_init(|| dissect(&self.graph))
                .clone()
                .map_err(Error::LinearSolver)
        })
    }
}

/// The nested dissection of `graph`, each connected component (a body)
/// dissected on its own and the components one after the other (METIS's
/// `CCORDER`, by hand): METIS bisects a graph of two bodies as if they
/// were one, and on examples/two-spheres' elements that ordering filled
/// 14 % more than one dissection per body. One component: the one call,
/// as before.
fn dissect(graph: &NodeGraph) -> std::result::Result<Vec<usize>, String> {
    let (xadj, adjncy) = graph.csr();
    let component = graph_components(&xadj, &adjncy);
    let count = component.iter().copied().max().map_or(0, |m| m + 1);
    if count <= 1 {
        return metis_node_nd(&xadj, &adjncy);
    }
    let mut nodes = vec![Vec::new(); count];
    component
        .iter()
        .enumerate()
        .for_each(|(a, &c)| nodes[c].push(a));
    let mut local = vec![0usize; component.len()];
    let mut forward = Vec::with_capacity(component.len());
    for members in &nodes {
        members.iter().enumerate().for_each(|(l, &a)| local[a] = l);
        let (mut sub_x, mut sub_adj) = (vec![0], Vec::new());
        for &a in members {
            sub_adj.extend(adjncy[xadj[a]..xadj[a + 1]].iter().map(|&b| local[b]));
            sub_x.push(sub_adj.len());
        }
        let order = metis_node_nd(&sub_x, &sub_adj)?;
        forward.extend(order.into_iter().map(|l| members[l]));
    }
    Ok(forward)
}

/// The connected component of each node of a CSR graph, numbered from 0
/// in the order of their first node.
fn graph_components(xadj: &[usize], adjncy: &[usize]) -> Vec<usize> {
    let n = xadj.len().saturating_sub(1);
    let mut component = vec![usize::MAX; n];
    let mut next = 0;
    let mut stack = Vec::new();
    for start in 0..n {
        if component[start] != usize::MAX {
            continue;
        }
        component[start] = next;
        stack.push(start);
        while let Some(a) = stack.pop() {
            for &b in &adjncy[xadj[a]..xadj[a + 1]] {
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

/// The nested dissection of `pattern`'s node graph (`forward[new] = old`,
/// nodes): `early`'s when it dissects that graph, else computed here.
pub fn node_dissection(
    pattern: &SparsityPattern,
    early: Option<&EarlyDissection>,
) -> Result<Vec<usize>> {
    if let Some(nodes) = early.and_then(|e| e.nodes_for(pattern)) {
        return nodes;
    }
    let (xadj, adjncy) = pattern.node_graph();
    nested_dissection(&xadj, &adjncy)
}

/// The nested dissection of the graph of `pattern`'s elements alone
/// (`forward[new] = old`, nodes), without its contact couplings: the
/// ordering of a matrix assembled from the elements only (the condensed
/// path's `K̃`, whose factor drops those couplings); `early`'s when it
/// dissects that graph (it was started on it), else computed here.
pub fn element_dissection(
    pattern: &SparsityPattern,
    early: Option<&EarlyDissection>,
) -> Result<Vec<usize>> {
    if let Some(early) = early.filter(|e| e.fits_elements(pattern)) {
        return early
            .nodes
            .get_or_init(|| dissect(&early.graph))
            .clone()
            .map_err(Error::LinearSolver);
    }
    dissect(&pattern.element_graph()).map_err(Error::LinearSolver)
}

/// AMD for small problems, METIS nested dissection above [`AMD_DOFS`]
/// (where it already fills less: 2.4 times fewer factor entries at 28 k
/// dofs on a Hex8 box; `early`'s when it dissects the pattern's graph).
/// `num_dofs` displacement unknowns come first in `pattern`, the
/// multipliers after them.
pub fn fill_reducing_ordering(
    pattern: &SparsityPattern,
    num_dofs: usize,
    early: Option<&EarlyDissection>,
) -> Result<Ordering> {
    // a saddle system needs each multiplier after its node: always ND then
    if num_dofs <= AMD_DOFS && pattern.dimension() <= num_dofs {
        return Ok(Ordering::Amd);
    }
    let nodes = node_dissection(pattern, early)?;
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

    /// A graph of two components (two chains of tetrahedra-like elements)
    /// is dissected one component after the other: a permutation whose
    /// first half is the first chain's nodes.
    #[test]
    fn components_are_dissected_one_after_the_other() {
        let chain = |first: usize| -> Vec<Vec<usize>> {
            (0..30)
                .map(|e| (first + e..first + e + 4).collect())
                .collect()
        };
        let mut elements = chain(0);
        elements.extend(chain(33));
        let pattern = SparsityPattern::from_elements(66, elements.iter().map(Vec::as_slice));
        let forward = dissect(&pattern.graph()).unwrap();
        let mut sorted = forward.clone();
        sorted.sort_unstable();
        assert!(sorted.iter().enumerate().all(|(i, &v)| i == v));
        assert!(forward[..33].iter().all(|&a| a < 33));
    }

    /// The early dissection is the dissection of the graph it was started
    /// on, for the pattern itself and for a pattern coupled without node
    /// groups (the same graph); a pattern with node groups (another
    /// graph) gets its own graph's dissection.
    #[test]
    fn early_dissection_is_the_dissection_of_its_graph() {
        // a chain of 40 tetrahedra-like elements of 4 nodes each, overlapping
        let elements: Vec<Vec<usize>> = (0..40).map(|e| (e..e + 4).collect()).collect();
        let pattern = SparsityPattern::from_elements(43, elements.iter().map(Vec::as_slice));
        let early = EarlyDissection::start(&pattern.graph());
        let dissect_here = |p: &SparsityPattern| {
            let (xadj, adjncy) = p.node_graph();
            nested_dissection(&xadj, &adjncy).unwrap()
        };
        let own = dissect_here(&pattern);
        assert_eq!(node_dissection(&pattern, Some(&early)).unwrap(), own);
        let with_multipliers = pattern.coupled(&[], &[vec![3], vec![7]], &[]);
        assert!(early.fits(&with_multipliers));
        assert_eq!(
            node_dissection(&with_multipliers, Some(&early)).unwrap(),
            own
        );
        let grouped = pattern.coupled(&[vec![0, 42], vec![10, 30]], &[], &[]);
        assert!(!early.fits(&grouped));
        assert_eq!(
            node_dissection(&grouped, Some(&early)).unwrap(),
            dissect_here(&grouped)
        );
    }
}
