//! One process's share of a distributed assembly (`mpirun -np N`): the
//! elements it owns, and the communicator that completes what the
//! processes assemble apart.
//!
//! Every process holds the whole unknowns and the mesh's nodes, but the
//! connectivity only of the elements it reads ([`Model::hold_elements`]:
//! its own, the ghost layer of its rows, its output's recovery patches);
//! it evaluates only
//! its own elements, keeps the reference geometry of those only, and none
//! when the stiffness is constant (a cached `K`, built once per pattern)
//! ([`Model::geometry_of`] makes the others' again where output asks),
//! and its sparsity pattern holds only their entries
//! ([`Model::set_share_with_local_rows`]): the rows of its own nodes and of
//! the ghost nodes its elements touch, each restricted to the columns its
//! elements couple (and the diagonal block of an own node no own element
//! touches), plus whatever the caller couples besides (contact,
//! follower-load faces); the other processes' nodes that none of these
//! touch have no rows or columns in it (empty columns: their prescribed
//! dofs' identity rows are their owners', and their diagonal lookups
//! answer `None`, [`SparsityPattern::stored_diagonal`]). The internal force is
//! then summed over the processes, `f_int = Σ_p f_int^p`, so that every
//! process holds the same whole force (and Newton, the stepping and the
//! contact states stay identical on every process); the tangent stays
//! each process's part, `K = Σ_p K^p`, and the distributed linear solver
//! adds the parts in its matrix. Products with the tangent are completed
//! the same way: `K v = Σ_p K^p v`.
//!
//! What is not an element's (contact, follower loads) every process
//! evaluates alike, but adds to its part of the tangent only in the rows
//! it owns ([`Share::owns_row`]: the rows of its nodes, and the
//! multipliers' on the last process, as the distributed solver numbers
//! them): `K = Σ_p (K_e^p + P_p K_c)` with `P_p` the projection on process
//! `p`'s rows, `Σ_p P_p = I`. So each contact row is added once, by its
//! owner, and no process gives the solver rows it neither owns nor
//! touches ([`Model::foreign_entries`], [`Model::restore_entries`]).

use super::kernel::{self, PointGeometry};
use super::pattern::{NodeGraph, SparsityPattern};
use super::Model;
use std::borrow::Cow;
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

/// The elements this process assembles, the nodes whose rows it owns and
/// its communicator.
#[derive(Clone)]
pub struct Share {
    /// `owned[e]`: element `e` is assembled here.
    pub owned: Vec<bool>,
    /// `own_nodes[n]`: the rows of node `n` are this process's (the
    /// distributed solver's numbering, one part per process).
    pub own_nodes: Vec<bool>,
    pub communicator: Arc<dyn Communicator>,
}

impl Share {
    /// The lead process (rank 0) writes the run's files and log.
    pub fn is_lead(&self) -> bool {
        self.communicator.rank() == 0
    }

    /// Whether row `i` (of `dofs` displacement rows, then the
    /// multipliers) is this process's: a displacement row of one of its
    /// nodes, or a multiplier's on the last process.
    pub fn owns_row(&self, i: usize, dofs: usize) -> bool {
        if i < dofs {
            self.own_nodes[i / 3]
        } else {
            self.communicator.rank() + 1 == self.communicator.size()
        }
    }
}

impl Model {
    /// [`Model::set_share`], and the pattern restricted to this process's
    /// rows: that of the owned elements' node graph (each node they touch
    /// and each own node its own neighbour; the other nodes without rows or
    /// columns) with every pair of nodes in one of `groups` coupled too (what the caller adds to the
    /// tangent outside the elements: the follower-load faces). A
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
        // the other processes' nodes that no element or group here
        // touches hold no rows here (their owners set a prescribed dof's
        // identity row, and this process adds nothing to them)
        let graph = NodeGraph::of_elements_and(
            self.mesh.num_nodes(),
            owned.chain(groups.iter().map(Vec::as_slice)),
            |a| share.own_nodes[a],
        );
        self.pattern = SparsityPattern::from_graph(&graph);
        // the other processes' elements keep no reference geometry (the
        // shape-function gradients of every quadrature point, ~2 kB a
        // Hex8): made again where asked for ([`Model::geometry_of`]); nor
        // do this process's when the stiffness is constant, read only to
        // build the cached `K` once per pattern
        let constant = self.constant.is_some();
        for (g, &own) in self.geometry.iter_mut().zip(&share.owned) {
            if !own || constant {
                *g = Vec::new();
            }
        }
        self.set_share(share);
    }

    /// Let go of the connectivity of every element not in `keep` (a mask
    /// over the elements: this process's own, the ghost layer of its rows
    /// and what its output reads; [`Mesh::release_elements`]): the mesh is
    /// no longer whole on this process. The colouring is made first, on
    /// the whole mesh, so that this process's elements keep the colours,
    /// and so the order of summation, that they have in a whole mesh
    /// (bit for bit the same sums). Where something else holds the mesh
    /// too (a `Case` kept by a library caller) it stays whole: a thinned
    /// copy beside it would only add memory.
    ///
    /// [`Mesh::release_elements`]: crate::mesh::Mesh::release_elements
    pub fn hold_elements(&mut self, keep: &[bool]) {
        self.colouring();
        if let Some(mesh) = Arc::get_mut(&mut self.mesh) {
            mesh.release_elements(keep);
        }
    }

    /// The reference geometry of element `e` (its quadrature points'
    /// `∂N_a/∂X` and `dV₀ = det J₀ w_q`): the one kept, or for an element
    /// of another process ([`Model::set_share_with_local_rows`]) the same
    /// [`kernel::reference_geometry`] made again from the mesh (it
    /// succeeded when the model was made; bit for bit the kept one).
    pub fn geometry_of(&self, e: usize) -> Cow<'_, [PointGeometry]> {
        let kept = &self.geometry[e];
        if !kept.is_empty() {
            return Cow::Borrowed(kept);
        }
        // an element let go of ([`Model::hold_elements`]) has no nodes:
        // its geometry would be empty, a zero volume
        debug_assert!(self.mesh.holds_element(e), "element {e} is not held");
        let element = &self.mesh.elements[e];
        let coordinates: Vec<[f64; 3]> =
            element.nodes.iter().map(|&n| self.mesh.nodes[n]).collect();
        Cow::Owned(kernel::reference_geometry(element.kind, &coordinates).unwrap_or_default())
    }

    /// The entries of `tangent` (on this process's pattern) in the rows
    /// this process does not own, as (position, value): what
    /// [`Model::restore_entries`] puts back after the contact and load
    /// contributions, which each process adds in its own rows only. Empty
    /// without a share (a serial run adds everything). One pass over the
    /// pattern; the entries kept are the ghost rows, a few per cent of
    /// the part.
    pub fn foreign_entries(&self, tangent: &[f64]) -> Vec<(usize, f64)> {
        let Some(share) = &self.share else {
            return Vec::new();
        };
        let symbolic = self.pattern.symbolic();
        let (cp, ri) = (symbolic.col_ptr(), symbolic.row_idx());
        let dofs = self.num_dofs();
        let mut kept = Vec::new();
        for j in 0..symbolic.ncols() {
            for k in cp[j]..cp[j + 1] {
                if !share.owns_row(ri[k], dofs) {
                    kept.push((k, tangent[k]));
                }
            }
        }
        kept
    }

    /// Put back the entries [`Model::foreign_entries`] took.
    pub fn restore_entries(&self, tangent: &mut [f64], kept: &[(usize, f64)]) {
        for &(k, v) in kept {
            tangent[k] = v;
        }
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
