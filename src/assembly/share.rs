//! One process's share of a distributed assembly (`mpirun -np N`): the
//! elements it owns, and the communicator that completes what the
//! processes assemble apart.
//!
//! Every process holds the whole mesh, the sparsity pattern and the
//! unknowns; it evaluates only its own elements. The internal force is
//! then summed over the processes, `f_int = Σ_p f_int^p`, so that every
//! process holds the same whole force (and Newton, the stepping and the
//! contact states stay identical on every process); the tangent stays
//! each process's part, `K = Σ_p K^p`, and the distributed linear solver
//! adds the parts in its matrix. Products with the tangent are completed
//! the same way: `K v = Σ_p K^p v`.

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
