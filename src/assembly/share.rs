//! One process's share of a distributed assembly (`mpirun -np N`): the
//! elements it owns, and the communicator that completes what the
//! processes assemble apart.
//!
//! Every process holds the whole mesh and the unknowns; it evaluates only
//! its own elements, and its sparsity pattern holds only their entries
//! ([`Model::set_share_with_local_rows`]): the rows of its own nodes and of
//! the ghost nodes its elements touch, each restricted to the columns its
//! elements couple, plus the diagonal block of every other node (9 entries
//! a node, so that a prescribed dof's row and the diagonal lookups stay
//! where they are) and whatever the caller couples besides (contact,
//! follower-load faces). The internal force is
//! then summed over the processes, `f_int = Σ_p f_int^p`, so that every
//! process holds the same whole force (and Newton, the stepping and the
//! contact states stay identical on every process); the tangent stays
//! each process's part, `K = Σ_p K^p`, and the distributed linear solver
//! adds the parts in its matrix. Products with the tangent are completed
//! the same way: `K v = Σ_p K^p v`.

use super::pattern::{NodeGraph, SparsityPattern};
use super::Model;
use std::sync::Arc;

/// The processes of a distributed run (MPI's world, through PETSc).
pub trait Communicator: Send + Sync {
    /// This process's rank, `0 ≤ rank < size`.
    fn rank(&self) -> usize;
    /// The number of processes.
    fn size(&self) -> usize;
    /// `v ← Σ_p v^p` on every process, bit for bit the same everywhere.
    fn sum(&self, v: &mut [f64]);
}

/// The elements this process assembles and its communicator.
#[derive(Clone)]
pub struct Share {
    /// `owned[e]`: element `e` is assembled here.
    pub owned: Vec<bool>,
    pub communicator: Arc<dyn Communicator>,
}

impl Share {
    /// The lead process (rank 0) adds what is not an element's: contact
    /// and load contributions to the tangent.
    pub fn is_lead(&self) -> bool {
        self.communicator.rank() == 0
    }
}

impl Model {
    /// [`Model::set_share`], and the pattern restricted to this process's
    /// rows: that of the owned elements' node graph (each node its own
    /// neighbour, the other nodes' diagonal blocks only) with every pair of
    /// nodes in one of `groups` coupled too (what the caller adds to the
    /// tangent outside the elements: the lead's follower-load faces). A
    /// later [`SparsityPattern::coupled`] keeps both. `K^p`, its cached
    /// constant part and the scatter maps live on this pattern, which
    /// holds about `1/N` of the whole one's entries on `N` processes plus
    /// the ghost layer's rows.
    pub fn set_share_with_local_rows(&mut self, share: Share, groups: &[Vec<usize>]) {
        let owned = self
            .mesh
            .elements
            .iter()
            .zip(&share.owned)
            .filter(|(_, &own)| own)
            .map(|(e, _)| e.nodes.as_slice());
        let graph = NodeGraph::of_elements(
            self.mesh.num_nodes(),
            owned.chain(groups.iter().map(Vec::as_slice)),
        );
        self.pattern = SparsityPattern::from_graph(&graph);
        self.set_share(share);
    }

    /// The node list of element `e` as the scatter maps see it: empty for
    /// an element another process assembles (its blocks may not be in
    /// this process's pattern).
    pub(super) fn assembled_nodes(&self, e: usize) -> &[usize] {
        match &self.share {
            Some(share) if !share.owned[e] => &[],
            _ => &self.mesh.elements[e].nodes,
        }
    }
}
