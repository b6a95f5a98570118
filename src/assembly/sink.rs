//! Where an evaluation writes the tangent: faer's values array on the
//! model's pattern, or a linear solver's own matrix ([`TangentSink`]).
//!
//! A serial run, and every faer path, writes `K` by pattern position into
//! one values array (the element scatter maps, the cached constant `K`'s
//! expansion, contact's and the follower loads' [`super::scatter`]). A
//! distributed run on PETSc (`mpirun`) writes it into PETSc's matrix
//! instead, so that a process holds one copy of its part of the tangent,
//! PETSc's, and no values array on its pattern beside it: the element
//! blocks go in as dense blocks by global row and column
//! ([`TangentSink::add_element`], PETSc's `MatSetValues` with
//! `ADD_VALUES`, the usual finite-element assembly into PETSc), the cached
//! constant `K` as its lower triangle's columns, mirrored
//! ([`TangentSink::add_columns`]), and what is not an element's (contact,
//! follower loads, the multipliers) is written by position, as on every
//! other path, into a small array on the pattern of those couplings alone
//! (`Problem`'s side pattern), whose own rows then go in by columns too.

use faer::sparse::SymbolicSparseColMat;

/// Which entries of a compressed-column array a sink takes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Entries {
    /// A symmetric matrix's lower triangle (diagonal included): every
    /// stored entry `(i, j)`, and `(j, i)` for `i ≠ j`.
    LowerMirrored,
    /// The entries in the rows this process owns only (contact and loads,
    /// which every process evaluates alike and each adds in its own rows).
    OwnRows,
}

/// A matrix the assembly adds the tangent into, in place of a values
/// array: a fill is [`begin`](Self::begin), the additions (from several
/// threads: the implementation serialises them), then
/// [`finish`](Self::finish). Every method but the additions is collective
/// in a distributed run (every process calls it, in the same order).
/// Indices are the model's unknowns (displacements 3 per node, then the
/// multipliers). A failure is kept and reported by the next
/// [`finish`](Self::finish), [`multiply`](Self::multiply) or
/// [`identity_rows`](Self::identity_rows).
pub trait TangentSink: Send + Sync {
    /// Start a fill: every entry zero.
    fn begin(&self);
    /// Add an element's dense block over the unknowns `dofs`, `values`
    /// `dofs.len()²` of them (symmetric, so either orientation).
    fn add_element(&self, dofs: &[usize], values: &[f64]);
    /// Add `values` stored on `pattern`, the entries `which` says.
    fn add_columns(&self, pattern: &SymbolicSparseColMat<usize>, values: &[f64], which: Entries);
    /// End a fill: the matrix is the sum of what every process added.
    fn finish(&self) -> Result<(), String>;
    /// `y = K x` (whole vectors, the same on every process).
    fn multiply(&self, x: &[f64], y: &mut [f64]) -> Result<(), String>;
    /// Make the rows and columns of the `constrained` unknowns a scaled
    /// identity `s I`, `s` the mean `|K_dd|` over the free unknowns among
    /// the first `dofs` (1 if there is none), as Newton does on a values
    /// array; returns `s`.
    fn identity_rows(&self, constrained: &[bool], dofs: usize) -> Result<f64, String>;
}

/// Where an evaluation writes its tangent.
pub enum Tangent<'a> {
    /// By position into values on the model's pattern (both triangles).
    Values(&'a mut [f64]),
    /// Into a linear solver's matrix.
    Sink(&'a dyn TangentSink),
}

impl<'a> Tangent<'a> {
    /// A shorter borrow of the same target.
    pub fn reborrow(&mut self) -> Tangent<'_> {
        match self {
            Tangent::Values(v) => Tangent::Values(v),
            Tangent::Sink(s) => Tangent::Sink(*s),
        }
    }
}
