//! Global assembly: element kernels evaluated in parallel (rayon) and
//! scattered into a fixed sparsity pattern.
//!
//! The elements are coloured once per mesh, at the first assembly that needs it ([`colouring`]: no two elements
//! of a colour share a node); the elements of a colour are evaluated and
//! scattered in parallel, straight into the global values, colour after
//! colour. Every global entry is therefore summed in the same order (colour
//! order) whatever the number of threads, and results are bitwise
//! independent of it. The element kernel works on the stack (no heap
//! allocation per element) and the scatter reads the positions from a map
//! built once per sparsity pattern ([`scatter_map`]). For a model whose
//! materials all have a constant tangent, `K` is assembled once and
//! `f_int = K u` ([`constant_stiffness`]).
//!
//! Newton's tangent has both triangles of `K`: the LDLᵀ reads only the
//! lower one, but the LU fallback, the nonsymmetric (frictional,
//! follower-load) tangents and the Krylov solver read both, and the
//! contact and load terms are scattered into it. Where only a
//! factorisation and products read `K` — the constant stiffness, cached
//! and condensed onto the contact nodes — its lower triangle alone is
//! assembled ([`Model::assemble_internal_lower`], [`triangle`]): the element
//! blocks `(n_a, n_b)` with `n_a ≥ n_b`, the same values as the whole
//! assembly's (summed in the same order), half the entries. The kernel
//! computes only the blocks `b ≥ a` and mirrors them.

pub mod amplitude;
pub mod colouring;
pub mod constant_stiffness;
pub mod hooke;
pub mod kernel;
pub mod loads;
pub mod pattern;
pub mod scatter;
pub mod scatter_map;
pub mod share;
pub mod sink;
pub mod triangle;

use crate::material::{Mat3, Material};
use crate::mesh::Mesh;
use colouring::{DisjointSlice, ElementColouring};
use constant_stiffness::StiffnessCache;
use kernel::{KernelFailure, PointGeometry, LINEAR_MAX_NODES, MAX_NODES};
use pattern::{NodeGraph, SparsityPattern};
use rayon::prelude::*;
use scatter_map::ScatterMap;
use share::Share;
use sink::{Tangent, TangentSink};
use std::sync::{Arc, Mutex, OnceLock, PoisonError};
use triangle::LowerTriangle;

/// A mesh with a material on every element and the precomputed reference
/// geometry of every quadrature point: everything the internal-force
/// assembly needs.
pub struct Model {
    pub mesh: Arc<Mesh>,
    pub materials: Vec<Arc<dyn Material>>,
    /// Index into `materials` of each element.
    pub element_material: Vec<usize>,
    geometry: Vec<Vec<PointGeometry>>,
    pub pattern: SparsityPattern,
    /// Made at the first assembly through it ([`Self::colouring`]): a
    /// constant stiffness in closed form is assembled without it.
    colouring: OnceLock<ElementColouring>,
    /// The scatter map of the pattern it was last built for.
    scatter_map: Mutex<Option<Arc<ScatterMap>>>,
    /// The lower triangle of the pattern it was last built for, and the
    /// scatter map into it (built at the first assembly into it).
    lower: Mutex<Option<Arc<LowerTriangle>>>,
    lower_map: Mutex<Option<Arc<ScatterMap>>>,
    /// The side pattern of the pattern it was made for
    /// ([`Model::side_pattern`]).
    side: Mutex<Option<(u64, Arc<SparsityPattern>)>>,
    /// `Some` when every element's material has a constant tangent.
    constant: Option<StiffnessCache>,
    /// In a distributed run: the elements this process assembles
    /// ([`share`]); `None`: every element.
    share: Option<Share>,
}

/// An element that could not be evaluated.
#[derive(Clone, Copy, Debug)]
pub struct ElementFailure {
    /// Index into `mesh.elements`.
    pub element: usize,
    pub failure: KernelFailure,
}

impl Model {
    /// Precompute the reference geometry and the sparsity pattern. Fails on
    /// the first element that is inverted or degenerate in the reference
    /// configuration.
    pub fn new(
        mesh: Arc<Mesh>,
        materials: Vec<Arc<dyn Material>>,
        element_material: Vec<usize>,
    ) -> Result<Self, ElementFailure> {
        Self::with_graph(mesh, materials, element_material, |_| ())
    }

    /// [`Self::new`], handing the elements' node graph to `on_graph` as
    /// soon as it exists (before the pattern's compressed columns and
    /// while the colouring runs): what reads only the graph (a
    /// fill-reducing ordering) can start there.
    pub fn with_graph(
        mesh: Arc<Mesh>,
        materials: Vec<Arc<dyn Material>>,
        element_material: Vec<usize>,
        on_graph: impl FnOnce(&NodeGraph) + Send,
    ) -> Result<Self, ElementFailure> {
        Self::with_graph_of(mesh, materials, element_material, on_graph, true)
    }

    /// [`Self::with_graph`]; without `elements`, the pattern (and the
    /// graph handed on) holds each node's diagonal block only: a process
    /// of a distributed run, whose pattern is made when the partition is
    /// known ([`Model::set_share_with_local_rows`]), so that no process
    /// ever holds the whole one.
    pub fn with_graph_of(
        mesh: Arc<Mesh>,
        materials: Vec<Arc<dyn Material>>,
        element_material: Vec<usize>,
        on_graph: impl FnOnce(&NodeGraph) + Send,
        elements: bool,
    ) -> Result<Self, ElementFailure> {
        // the elements' graph first (the ordering waits for it), beside
        // the geometry
        let (pattern, geometry) = rayon::join(
            || {
                let graph = NodeGraph::of_elements(
                    mesh.num_nodes(),
                    mesh.elements
                        .iter()
                        .filter(|_| elements)
                        .map(|e| e.nodes.as_slice()),
                );
                on_graph(&graph);
                SparsityPattern::from_graph(&graph)
            },
            || {
                mesh.elements
                    .par_iter()
                    .enumerate()
                    .map(|(e, el)| {
                        let coords: Vec<[f64; 3]> =
                            el.nodes.iter().map(|&n| mesh.nodes[n]).collect();
                        kernel::reference_geometry(el.kind, &coords).map_err(|failure| {
                            ElementFailure {
                                element: e,
                                failure,
                            }
                        })
                    })
                    .collect::<Vec<_>>()
            },
        );
        // in order: the first failing element, see `assemble_internal`
        let geometry = geometry.into_iter().collect::<Result<Vec<_>, _>>()?;
        let constant = element_material
            .iter()
            .all(|&m| materials[m].constant_tangent())
            .then(StiffnessCache::default);
        Ok(Model {
            mesh,
            materials,
            element_material,
            geometry,
            pattern,
            colouring: OnceLock::new(),
            scatter_map: Mutex::new(None),
            lower: Mutex::new(None),
            lower_map: Mutex::new(None),
            side: Mutex::new(None),
            constant,
            share: None,
        })
    }

    /// The elements in colours, no two elements of a colour sharing a node
    /// ([`ElementColouring`]), made at the first call.
    fn colouring(&self) -> &ElementColouring {
        self.colouring.get_or_init(|| {
            ElementColouring::new(
                self.mesh.num_nodes(),
                self.mesh.elements.iter().map(|e| e.nodes.as_slice()),
            )
        })
    }

    /// The diagonal of the reference bounding box: a length scale of the body.
    pub fn size(&self) -> f64 {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for x in &self.mesh.nodes {
            for d in 0..3 {
                lo[d] = lo[d].min(x[d]);
                hi[d] = hi[d].max(x[d]);
            }
        }
        (0..3).map(|d| (hi[d] - lo[d]).powi(2)).sum::<f64>().sqrt()
    }

    /// Assemble only the elements `share` owns from now on (a distributed
    /// run, [`share`]): the internal force is summed over the processes,
    /// the tangent is this process's part. A cached constant stiffness is
    /// dropped (it held every element).
    pub fn set_share(&mut self, share: Share) {
        if self.constant.is_some() {
            self.constant = Some(StiffnessCache::default());
        }
        self.share = Some(share);
    }

    /// This process's share of a distributed assembly, if any.
    pub fn share(&self) -> Option<&Share> {
        self.share.as_ref()
    }

    /// Whether this process is the lead (rank 0, which writes the run's
    /// files): always without a share.
    pub fn is_lead(&self) -> bool {
        self.share.as_ref().is_none_or(Share::is_lead)
    }

    /// Whether the elements are shared among processes (a distributed
    /// run: this process assembles its part `K^p` of the tangent only).
    pub fn is_shared(&self) -> bool {
        self.share.is_some()
    }

    /// Complete a product with this process's part of the tangent,
    /// `v ← Σ_p K^p w` (nothing to do without a share).
    pub fn sum_over_processes(&self, v: &mut [f64]) {
        if let Some(share) = &self.share {
            share.communicator.sum(v);
        }
    }

    /// Number of unknowns (3 per node).
    pub fn num_dofs(&self) -> usize {
        3 * self.mesh.num_nodes()
    }

    /// The displacements of element `e`'s nodes (the first
    /// `nodes.len()` entries), on the stack, in a buffer of `M ≥ n` nodes.
    fn element_displacements<const M: usize>(&self, e: usize, u: &[f64]) -> [[f64; 3]; M] {
        let mut d = [[0.0; 3]; M];
        for (da, &n) in d.iter_mut().zip(&self.mesh.elements[e].nodes) {
            *da = [u[3 * n], u[3 * n + 1], u[3 * n + 2]];
        }
        d
    }

    /// `f` of the displacements of element `e`'s nodes, held on the stack
    /// in a buffer sized for a linear element where it is one.
    fn with_element_displacements<R>(
        &self,
        e: usize,
        u: &[f64],
        f: impl FnOnce(&[[f64; 3]]) -> R,
    ) -> R {
        let n = self.mesh.elements[e].nodes.len();
        if n <= LINEAR_MAX_NODES {
            f(&self.element_displacements::<LINEAR_MAX_NODES>(e, u)[..n])
        } else {
            f(&self.element_displacements::<MAX_NODES>(e, u)[..n])
        }
    }

    /// Assemble the internal force `f_int(u)` into `force` (overwritten) and,
    /// if `tangent` is given, `∂f_int/∂u` into it (overwritten; length
    /// `pattern.nnz()`, both triangles). With a constant stiffness (every
    /// material linear, small strain), `f_int = K u` with the cached `K`
    /// ([`Model::constant_stiffness`]).
    ///
    /// With a [`Share`], only the owned elements are evaluated; `force` is
    /// then summed over the processes and the first failing element (in
    /// mesh order, over every process) is reported on every process.
    pub fn assemble_internal(
        &self,
        u: &[f64],
        force: &mut [f64],
        tangent: Option<&mut [f64]>,
    ) -> Result<(), ElementFailure> {
        self.assemble_internal_in(u, force, tangent.map(|t| Out::Values(t, Storage::Full)))
    }

    /// [`Model::assemble_internal`] with the tangent written into
    /// `tangent`: values on the pattern, or a linear solver's matrix
    /// ([`sink`]; the element part only, added to what the sink holds).
    pub fn assemble_internal_into(
        &self,
        u: &[f64],
        force: &mut [f64],
        tangent: Option<Tangent<'_>>,
    ) -> Result<(), ElementFailure> {
        let out = tangent.map(|t| match t {
            Tangent::Values(v) => Out::Values(v, Storage::Full),
            Tangent::Sink(s) => Out::Sink(s),
        });
        self.assemble_internal_in(u, force, out)
    }

    /// [`Model::assemble_internal`] with the tangent's lower triangle alone
    /// in `tangent` (length `lower_triangle().nnz()`): for a symmetric
    /// tangent that only a factorisation and products
    /// ([`triangle::multiply`]) read. The same values as the whole
    /// tangent's entries on and below the diagonal, bitwise.
    pub fn assemble_internal_lower(
        &self,
        u: &[f64],
        force: &mut [f64],
        tangent: &mut [f64],
    ) -> Result<(), ElementFailure> {
        self.assemble_internal_in(u, force, Some(Out::Values(tangent, Storage::Lower)))
    }

    /// [`Model::assemble_internal`] into a tangent stored as `Storage` says.
    fn assemble_internal_in(
        &self,
        u: &[f64],
        force: &mut [f64],
        tangent: Option<Out<'_>>,
    ) -> Result<(), ElementFailure> {
        let local = if let Some(k) = self.constant_stiffness() {
            let lower = self.lower_triangle();
            triangle::multiply(lower.symbolic(), &k, u, force);
            match tangent {
                Some(Out::Values(t, Storage::Full)) => lower.expand_into(&self.pattern, &k, t),
                Some(Out::Values(t, Storage::Lower)) => t.copy_from_slice(&k),
                Some(Out::Sink(sink)) => {
                    sink.add_columns(lower.symbolic(), &k, sink::Entries::LowerMirrored)
                }
                None => {}
            }
            Ok(())
        } else {
            self.assemble_elements(u, force, tangent)
        };
        let Some(share) = &self.share else {
            return local;
        };
        share.communicator.sum(force);
        agree_on_failure(share, local.err()).map_or(Ok(()), Err)
    }

    /// The lower triangle of the element stiffness `K = ∫ Bᵀ ℂ B dV` on
    /// the current pattern's [`Model::lower_triangle`] when every
    /// element's material has a constant tangent (`None` otherwise):
    /// assembled at the first call for a pattern and shared after that.
    /// Holds the element part only (no contact, no loads). With Hooke's
    /// law on every element, in closed form
    /// ([`constant_stiffness::assemble_hooke_lower`]).
    pub fn constant_stiffness(&self) -> Option<Arc<Vec<f64>>> {
        let k = self.constant.as_ref()?.get_or_build(&self.pattern, || {
            let hooke: Option<Vec<(f64, f64)>> =
                self.materials.iter().map(|m| m.hooke_lame()).collect();
            if let Some(lame) = hooke {
                let (lower, map) = self.lower_triangle_and_map();
                let closed_form = constant_stiffness::assemble_hooke_lower(
                    &self.mesh.elements,
                    |e| self.geometry_of(e),
                    |e| lame[self.element_material[e]],
                    |e| self.share.as_ref().is_none_or(|s| s.owned[e]),
                    &lower,
                    &map,
                );
                // Tet4 and Hex8 only: the other kinds by the general kernel
                if closed_form.is_some() {
                    return closed_form;
                }
            }
            let zero = vec![0.0; self.pattern.dimension()];
            let mut force = vec![0.0; self.pattern.dimension()];
            let mut k = vec![0.0; self.lower_triangle().nnz()];
            self.assemble_elements(&zero, &mut force, Some(Out::Values(&mut k, Storage::Lower)))
                .ok()?;
            Some(k)
        });
        // the scatter map into the lower triangle served only to build `K`
        // (every later assembly multiplies the cached `K`): a position per
        // pair of each element's nodes, a third of the cached `K`'s memory,
        // given back (made again if a new pattern asks for a new `K`)
        if k.is_some() {
            *self
                .lower_map
                .lock()
                .unwrap_or_else(PoisonError::into_inner) = None;
        }
        k
    }

    /// The lower triangle of the current pattern (built at the first call
    /// for it).
    pub fn lower_triangle(&self) -> Arc<LowerTriangle> {
        let mut slot = self.lower.lock().unwrap_or_else(PoisonError::into_inner);
        match slot.as_ref() {
            Some(lower) if lower.is_for(&self.pattern) => Arc::clone(lower),
            _ => {
                let lower = Arc::new(LowerTriangle::of(&self.pattern));
                *slot = Some(Arc::clone(&lower));
                lower
            }
        }
    }

    /// The lower triangle of the current pattern and the element scatter
    /// map into it (each built at the first call for the pattern).
    fn lower_triangle_and_map(&self) -> (Arc<LowerTriangle>, Arc<ScatterMap>) {
        let lower = self.lower_triangle();
        let mut slot = self
            .lower_map
            .lock()
            .unwrap_or_else(PoisonError::into_inner);
        match slot.as_ref() {
            Some(map) if map.is_for(&self.pattern) => (lower, Arc::clone(map)),
            _ => {
                let map = Arc::new(ScatterMap::lower(
                    &self.pattern,
                    &lower,
                    (0..self.mesh.elements.len()).map(|e| self.assembled_nodes(e)),
                ));
                *slot = Some(Arc::clone(&map));
                (lower, map)
            }
        }
    }

    /// A pattern beside the current one, made by `build` at the first call
    /// for the current pattern and kept until it changes: the pattern of
    /// what is not an element's, into which the problem writes contact and
    /// loads when the elements go into a linear solver's matrix
    /// ([`sink`]).
    pub fn side_pattern(&self, build: impl FnOnce() -> SparsityPattern) -> Arc<SparsityPattern> {
        let mut slot = self.side.lock().unwrap_or_else(PoisonError::into_inner);
        match slot.as_ref() {
            Some((id, side)) if *id == self.pattern.id() => Arc::clone(side),
            _ => {
                let side = Arc::new(build());
                *slot = Some((self.pattern.id(), Arc::clone(&side)));
                side
            }
        }
    }

    /// The scatter map of the current pattern (built at the first call for it).
    fn scatter_map(&self) -> Arc<ScatterMap> {
        let mut slot = self
            .scatter_map
            .lock()
            .unwrap_or_else(PoisonError::into_inner);
        match slot.as_ref() {
            Some(map) if map.is_for(&self.pattern) => Arc::clone(map),
            _ => {
                let map = Arc::new(ScatterMap::new(
                    &self.pattern,
                    (0..self.mesh.elements.len()).map(|e| self.assembled_nodes(e)),
                ));
                *slot = Some(Arc::clone(&map));
                map
            }
        }
    }

    /// The element loop of [`Model::assemble_internal`]: colour after
    /// colour, the elements of a colour in parallel, each evaluated on the
    /// stack and added straight into `force` and `tangent`. On failure, the
    /// first failing element in mesh order is named (whatever the threads).
    fn assemble_elements(
        &self,
        u: &[f64],
        force: &mut [f64],
        tangent: Option<Out<'_>>,
    ) -> Result<(), ElementFailure> {
        force.iter_mut().for_each(|x| *x = 0.0);
        let (tangent, storage, sink) = match tangent {
            Some(Out::Values(k, storage)) => (Some(k), Some(storage), None),
            Some(Out::Sink(sink)) => (None, None, Some(sink)),
            None => (None, None, None),
        };
        let tangent = tangent.map(|k| {
            // the whole tangent (megabytes) zeroed on the threads too
            k.par_chunks_mut(ZERO_CHUNK).for_each(|c| c.fill(0.0));
            DisjointSlice::new(k)
        });
        let (lower, map) = match storage {
            None => (None, None),
            Some(Storage::Full) => (None, Some(self.scatter_map())),
            Some(Storage::Lower) => {
                let (lower, map) = self.lower_triangle_and_map();
                (Some(lower), Some(map))
            }
        };
        let force = DisjointSlice::new(force);
        let target = tangent
            .as_ref()
            .zip(map.as_deref())
            .map(|(values, map)| Target::Values {
                values,
                map,
                lower: lower.as_deref(),
            })
            .or(sink.map(Target::Sink));
        let mut first_failure: Option<ElementFailure> = None;
        for colour in self.colouring().colours() {
            let owned = |e: &&usize| self.share.as_ref().is_none_or(|s| s.owned[**e]);
            let failure = colour
                .par_iter()
                .with_min_len(16)
                .filter(owned)
                .filter_map(|&e| self.add_element(e, u, &force, target.as_ref()).err())
                .min_by_key(|f| f.element);
            first_failure = match (first_failure, failure) {
                (Some(a), Some(b)) => Some(if b.element < a.element { b } else { a }),
                (a, b) => a.or(b),
            };
        }
        first_failure.map_or(Ok(()), Err)
    }

    /// Evaluate element `e` at `u` and add its force into `force` and, if
    /// given, its stiffness into the tangent through the scatter map.
    /// Only called for the elements of one colour at a time, which share no
    /// node: the entries each call adds to are touched by no other thread.
    fn add_element(
        &self,
        e: usize,
        u: &[f64],
        force: &DisjointSlice<'_>,
        tangent: Option<&Target<'_>>,
    ) -> Result<(), ElementFailure> {
        if self.mesh.elements[e].nodes.len() <= LINEAR_MAX_NODES {
            self.add_element_sized::<LINEAR_MAX_NODES>(e, u, force, tangent)
        } else {
            self.add_quadratic_element(e, u, force, tangent)
        }
    }

    /// [`Self::add_element_sized`] for an element of more than
    /// [`LINEAR_MAX_NODES`] nodes, in a frame of its own.
    #[inline(never)]
    fn add_quadratic_element(
        &self,
        e: usize,
        u: &[f64],
        force: &DisjointSlice<'_>,
        tangent: Option<&Target<'_>>,
    ) -> Result<(), ElementFailure> {
        self.add_element_sized::<MAX_NODES>(e, u, force, tangent)
    }

    /// [`Self::add_element`] with the element's force and stiffness on the
    /// stack in buffers of `M ≥ n` nodes.
    #[inline(always)]
    fn add_element_sized<const M: usize>(
        &self,
        e: usize,
        u: &[f64],
        force: &DisjointSlice<'_>,
        tangent: Option<&Target<'_>>,
    ) -> Result<(), ElementFailure> {
        let nodes = &self.mesh.elements[e].nodes;
        let n = nodes.len();
        let dofs = 3 * n;
        let displacements = self.element_displacements::<M>(e, u);
        let mut fe = [[0.0; 3]; M];
        let fe = fe.as_flattened_mut();
        let mut ke = [[[[0.0; 3]; M]; 3]; M];
        let ke = ke.as_flattened_mut().as_flattened_mut().as_flattened_mut();
        kernel::internal_force_and_tangent_into(
            &self.geometry_of(e),
            &displacements[..n],
            self.materials[self.element_material[e]].as_ref(),
            &mut fe[..dofs],
            tangent.is_some().then_some(&mut ke[..dofs * dofs]),
        )
        .map_err(|failure| ElementFailure {
            element: e,
            failure,
        })?;
        for (a, &na) in nodes.iter().enumerate() {
            for i in 0..3 {
                // SAFETY: the elements of a colour share no node, so no
                // other thread adds to dof 3 na + i now
                unsafe { force.add(3 * na + i, fe[3 * a + i]) };
            }
        }
        let Some(target) = tangent else {
            return Ok(());
        };
        let (values, map, lower) = match target {
            Target::Values { values, map, lower } => (values, map, lower),
            Target::Sink(sink) => {
                let mut dofs_of = [0; 3 * MAX_NODES];
                for (a, &na) in nodes.iter().enumerate() {
                    dofs_of[3 * a..3 * a + 3].copy_from_slice(&[3 * na, 3 * na + 1, 3 * na + 2]);
                }
                sink.add_element(&dofs_of[..dofs], &ke[..dofs * dofs]);
                return Ok(());
            }
        };
        // K_e is exactly symmetric: entry (3a + i, 3b + j) is read as
        // (3b + j, 3a + i), contiguous in i like the global column
        let starts = map.element(e);
        if let Some(lower) = lower {
            for (a, &na) in nodes.iter().enumerate() {
                for (b, &nb) in nodes.iter().enumerate() {
                    let start = starts[a * n + b];
                    if start == ScatterMap::ABOVE {
                        continue;
                    }
                    let offsets = lower.node_column_offsets(nb);
                    for (j, offset) in offsets.iter().enumerate() {
                        // a diagonal block: its rows from the diagonal on
                        let first = if na == nb { j } else { 0 };
                        for i in first..3 {
                            // SAFETY: as below, one entry of the nodes na, nb
                            unsafe {
                                values.add(start + offset + i, ke[(3 * b + j) * dofs + 3 * a + i])
                            };
                        }
                    }
                }
            }
            return Ok(());
        }
        for a in 0..n {
            for (b, &nb) in nodes.iter().enumerate() {
                let start = starts[a * n + b];
                let stride = self.pattern.node_column_length(nb);
                for j in 0..3 {
                    for i in 0..3 {
                        // SAFETY: entry (3 na + i, 3 nb + j) couples two nodes
                        // of this element; no other element of the colour has
                        // either node
                        unsafe {
                            values.add(start + j * stride + i, ke[(3 * b + j) * dofs + 3 * a + i])
                        };
                    }
                }
            }
        }
        Ok(())
    }

    /// Volume-averaged Cauchy stress of every element (zero for an
    /// element whose connectivity this process does not hold,
    /// [`Model::hold_elements`]).
    pub fn cauchy_stresses(&self, u: &[f64]) -> Vec<Mat3> {
        (0..self.mesh.elements.len())
            .into_par_iter()
            .map(|e| {
                if !self.mesh.holds_element(e) {
                    return Mat3::zeros();
                }
                self.with_element_displacements(e, u, |d| {
                    kernel::element_cauchy_stress(
                        &self.geometry_of(e),
                        d,
                        self.materials[self.element_material[e]].as_ref(),
                    )
                })
            })
            .collect()
    }

    /// The volume average over every element of a tensor function `g` of
    /// the deformation gradient `F = I + ∂u/∂X` at its quadrature points,
    /// `Σ_q g(F_q) dV_q / Σ_q dV_q` (for output: strains; zero for an
    /// element whose connectivity this process does not hold).
    pub fn element_averages(&self, u: &[f64], g: impl Fn(&Mat3) -> Mat3 + Sync) -> Vec<Mat3> {
        (0..self.mesh.elements.len())
            .into_par_iter()
            .map(|e| {
                if !self.mesh.holds_element(e) {
                    return Mat3::zeros();
                }
                self.with_element_displacements(e, u, |displacements| {
                    let (mut sum, mut volume) = (Mat3::zeros(), 0.0);
                    for p in self.geometry_of(e).iter() {
                        let f = kernel::deformation_gradient(&p.gradients, displacements);
                        sum += g(&f) * p.dv;
                        volume += p.dv;
                    }
                    sum / volume
                })
            })
            .collect()
    }

    /// Reference volume of every element.
    pub fn element_volumes(&self) -> Vec<f64> {
        (0..self.geometry.len())
            .map(|e| self.geometry_of(e).iter().map(|p| p.dv).sum())
            .collect()
    }

    /// `∫ N_a dV₀` for every node, over the elements in `elements`: the
    /// consistent nodal weights of a uniform body force.
    pub fn nodal_volumes(&self, elements: &[usize]) -> Vec<f64> {
        let mut w = vec![0.0; self.mesh.num_nodes()];
        for &e in elements {
            let el = &self.mesh.elements[e];
            let r = crate::fem::volume_reference(el.kind);
            for (q, p) in self.geometry_of(e).iter().enumerate() {
                for (a, &n) in el.nodes.iter().enumerate() {
                    w[n] += r.values[q][a] * p.dv;
                }
            }
        }
        w
    }
}

/// Entries of the tangent one thread zeroes at a time before an assembly.
const ZERO_CHUNK: usize = 1 << 15;

/// How an assembled tangent is stored: on the whole pattern, or its lower
/// triangle alone ([`LowerTriangle`]).
#[derive(Clone, Copy, Debug)]
enum Storage {
    Full,
    Lower,
}

/// A tangent the model's assembly writes: values stored as `Storage`
/// says, or a linear solver's matrix.
enum Out<'a> {
    Values(&'a mut [f64], Storage),
    Sink(&'a dyn TangentSink),
}

/// Where the element loop adds the element stiffnesses: `values` through
/// `map`, which points into the lower triangle `lower` if given; or a
/// sink, by global rows and columns.
enum Target<'a> {
    Values {
        values: &'a DisjointSlice<'a>,
        map: &'a ScatterMap,
        lower: Option<&'a LowerTriangle>,
    },
    Sink(&'a dyn TangentSink),
}

/// Add a dense element matrix (row-major, `dofs × dofs`, node-major dofs)
/// into the global values ([`scatter::add_block`]).
pub fn scatter_block_matrix(
    pattern: &SparsityPattern,
    nodes: &[usize],
    matrix: &[f64],
    dofs: usize,
    values: &mut [f64],
) {
    scatter::add_block(
        pattern,
        values,
        nodes,
        |i, j| matrix[i * dofs + j],
        |_| true,
    );
}

/// The first element failure (in mesh order) over every process of
/// `share`, given this process's `local` one: each process puts its
/// failure (element + 1, kind, quadrature point, determinant) in its own
/// slot of a vector summed over the processes.
fn agree_on_failure(share: &Share, local: Option<ElementFailure>) -> Option<ElementFailure> {
    let (rank, size) = (share.communicator.rank(), share.communicator.size());
    let mut slots = vec![0.0; 4 * size];
    if let Some(f) = local {
        let (kind, point, det) = match f.failure {
            KernelFailure::ReferenceInverted {
                quadrature_point,
                det_j,
            } => (1.0, quadrature_point, det_j),
            KernelFailure::Inverted {
                quadrature_point,
                det_f,
            } => (2.0, quadrature_point, det_f),
        };
        slots[4 * rank..4 * rank + 4].copy_from_slice(&[
            (f.element + 1) as f64,
            kind,
            point as f64,
            det,
        ]);
    }
    share.communicator.sum(&mut slots);
    slots
        .chunks_exact(4)
        .filter(|s| s[0] > 0.0)
        .min_by(|a, b| a[0].total_cmp(&b[0]))
        .map(|s| ElementFailure {
            element: s[0] as usize - 1,
            failure: if s[1] == 1.0 {
                KernelFailure::ReferenceInverted {
                    quadrature_point: s[2] as usize,
                    det_j: s[3],
                }
            } else {
                KernelFailure::Inverted {
                    quadrature_point: s[2] as usize,
                    det_f: s[3],
                }
            },
        })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::{LinearElastic, NeoHookean, Ogden, SaintVenantKirchhoff};
    use crate::mesh::structured::{box_mesh, perturb_interior};
    use crate::mesh::ElementKind;

    /// The assembly before the colouring and the scatter map, kept as the
    /// reference: a serial loop in mesh order over the allocating kernel,
    /// scattered by searching the pattern ([`scatter_block_matrix`]).
    fn reference_assembly(model: &Model, u: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let mut force = vec![0.0; model.pattern.dimension()];
        let mut k = vec![0.0; model.pattern.nnz()];
        for (e, el) in model.mesh.elements.iter().enumerate() {
            let n = el.nodes.len();
            let out = kernel::internal_force_and_tangent(
                &model.geometry[e],
                &model.element_displacements::<MAX_NODES>(e, u)[..n],
                model.materials[model.element_material[e]].as_ref(),
                true,
            )
            .unwrap();
            scatter::add_nodal(&mut force, &el.nodes, |k| out.force[k]);
            scatter_block_matrix(&model.pattern, &el.nodes, &out.stiffness, 3 * n, &mut k);
        }
        (force, k)
    }

    /// A perturbed box of `kind`, with `material`, and a smooth displacement
    /// of a few percent.
    fn model_and_u(kind: ElementKind, material: Arc<dyn Material>) -> (Model, Vec<f64>) {
        let cells = [4, 3, 3];
        let lengths = [1.0, 0.8, 0.7];
        let mut mesh = box_mesh(kind, cells, lengths);
        perturb_interior(&mut mesh, cells, lengths, 0.2, 7);
        let u: Vec<f64> = mesh
            .nodes
            .iter()
            .flat_map(|x| {
                [
                    0.03 * (3.0 * x[1]).sin() + 0.01 * x[0],
                    -0.02 * (2.0 * x[2]).cos() * x[0],
                    -0.04 * x[2] + 0.01 * (x[0] * x[1]),
                ]
            })
            .collect();
        let n_el = mesh.elements.len();
        let model = Model::new(Arc::new(mesh), vec![material], vec![0; n_el]).unwrap();
        (model, u)
    }

    fn assemble_with_threads(model: &Model, u: &[f64], threads: usize) -> (Vec<f64>, Vec<f64>) {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let mut force = vec![1.0; model.pattern.dimension()];
        let mut k = vec![1.0; model.pattern.nnz()];
        pool.install(|| model.assemble_internal(u, &mut force, Some(&mut k)))
            .unwrap();
        (force, k)
    }

    fn assert_close(a: &[f64], b: &[f64], what: &str) {
        let scale = b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        assert!(scale > 0.0, "{what}: all zero");
        let worst = a
            .iter()
            .zip(b)
            .map(|(x, y)| (x - y).abs())
            .fold(0.0f64, f64::max);
        assert!(worst <= 1e-13 * scale, "{what}: {worst:e} of {scale:e}");
    }

    /// The coloured, parallel, map-scattered assembly (and, for the linear
    /// material, the cached `K` with `f = K u`) equals the reference serial
    /// assembly to 1e-13 relative, for Tet4 and Hex8, finite and small
    /// strain; 1 and 2 threads give bitwise the same values.
    #[test]
    fn coloured_assembly_equals_the_serial_reference() {
        let materials: [Arc<dyn Material>; 2] = [
            Arc::new(NeoHookean::new(100.0, 0.45, "m").unwrap()),
            Arc::new(LinearElastic::new(1000.0, 0.3, "m").unwrap()),
        ];
        for kind in [ElementKind::Tet4, ElementKind::Hex8] {
            for material in &materials {
                let (model, u) = model_and_u(kind, Arc::clone(material));
                let linear = material.constant_tangent();
                assert_eq!(model.constant_stiffness().is_some(), linear);
                let (f_ref, k_ref) = reference_assembly(&model, &u);
                let (f1, k1) = assemble_with_threads(&model, &u, 1);
                let (f2, k2) = assemble_with_threads(&model, &u, 2);
                let what = format!("{kind:?} {}", material.name());
                assert_close(&f1, &f_ref, &format!("{what} force"));
                assert_close(&k1, &k_ref, &format!("{what} tangent"));
                assert!(f1 == f2 && k1 == k2, "{what}: 1 and 2 threads differ");
                // the element loop itself (the cache bypassed) matches too
                let mut f = vec![0.0; f_ref.len()];
                let mut k = vec![0.0; k_ref.len()];
                model
                    .assemble_elements(&u, &mut f, Some(Out::Values(&mut k, Storage::Full)))
                    .unwrap();
                assert_close(&f, &f_ref, &format!("{what} element force"));
                assert_close(&k, &k_ref, &format!("{what} element tangent"));
                // without the tangent, the same force
                let mut f_only = vec![1.0; f_ref.len()];
                model.assemble_internal(&u, &mut f_only, None).unwrap();
                assert_eq!(f_only, f1, "{what}: force alone");
            }
        }
    }

    /// The triangle-only assembly equals the lower triangle of the whole
    /// assembly (bitwise; asserted to 1e-13 relative) for the four
    /// materials on Tet4 and Hex8, with contact multipliers in the
    /// pattern; its symmetric product equals the whole tangent's to 1e-13;
    /// the force is the same; and for the linear material the whole
    /// tangent expanded from the cached triangle equals the element loop's.
    #[test]
    fn the_lower_triangle_is_the_whole_assemblys() {
        let materials: [Arc<dyn Material>; 4] = [
            Arc::new(LinearElastic::new(1000.0, 0.3, "m").unwrap()),
            Arc::new(NeoHookean::new(100.0, 0.45, "m").unwrap()),
            Arc::new(SaintVenantKirchhoff::new(100.0, 0.3, "m").unwrap()),
            Arc::new(
                Ogden::new(vec![0.4095, 0.003, 0.01], vec![1.3, 5.0, -2.0], 4.0, "m").unwrap(),
            ),
        ];
        for kind in [ElementKind::Tet4, ElementKind::Hex8] {
            for material in &materials {
                let (mut model, u) = model_and_u(kind, Arc::clone(material));
                let what = format!("{kind:?} {}", material.name());
                model.pattern = SparsityPattern::with_multipliers(
                    model.mesh.num_nodes(),
                    model.mesh.elements.iter().map(|e| e.nodes.as_slice()),
                    &[vec![0, 1], vec![5]],
                );
                let (f_full, k_full) = assemble_with_threads(&model, &u, 2);
                let lower = model.lower_triangle();
                assert!(lower.is_for(&model.pattern));
                for threads in [1, 2] {
                    let pool = rayon::ThreadPoolBuilder::new()
                        .num_threads(threads)
                        .build()
                        .unwrap();
                    let mut f = vec![1.0; f_full.len()];
                    let mut k = vec![1.0; lower.nnz()];
                    pool.install(|| model.assemble_internal_lower(&u, &mut f, &mut k))
                        .unwrap();
                    let expected = lower.values(&k_full);
                    assert_close(&k, &expected, &format!("{what} lower triangle"));
                    assert_close(&f, &f_full, &format!("{what} force"));
                    if !material.constant_tangent() {
                        assert_eq!(k, expected, "{what}: not bitwise");
                    }
                    let x: Vec<f64> = (0..f.len()).map(|i| (0.37 * i as f64).cos()).collect();
                    let mut y_full = vec![0.0; x.len()];
                    let mut y = vec![0.0; x.len()];
                    // the whole matrix's product, column by column
                    let full = model.pattern.symbolic();
                    let (cp, ri) = (full.col_ptr(), full.row_idx());
                    for j in 0..full.ncols() {
                        for e in cp[j]..cp[j + 1] {
                            y_full[ri[e]] += k_full[e] * x[j];
                        }
                    }
                    triangle::multiply(lower.symbolic(), &k, &x, &mut y);
                    assert_close(&y, &y_full, &format!("{what} product"));
                }
                // the element loop, the cache bypassed, for the linear material too
                let mut f = vec![0.0; f_full.len()];
                let mut k = vec![0.0; k_full.len()];
                model
                    .assemble_elements(&u, &mut f, Some(Out::Values(&mut k, Storage::Full)))
                    .unwrap();
                assert_close(&k, &k_full, &format!("{what} element tangent"));
                let mut k_lower = vec![0.0; lower.nnz()];
                model
                    .assemble_elements(&u, &mut f, Some(Out::Values(&mut k_lower, Storage::Lower)))
                    .unwrap();
                assert_eq!(
                    k_lower,
                    lower.values(&k),
                    "{what}: element loop, not bitwise"
                );
            }
        }
    }

    /// The cached `K` is assembled once per pattern: shared while the
    /// pattern stays, assembled again (with the new length) after the
    /// pattern is replaced, e.g. by one with contact multipliers.
    #[test]
    fn the_constant_stiffness_is_cached_per_pattern() {
        let linear: Arc<dyn Material> = Arc::new(LinearElastic::new(1000.0, 0.3, "m").unwrap());
        let (mut model, u) = model_and_u(ElementKind::Tet4, linear);
        let k0 = model.constant_stiffness().unwrap();
        assert!(Arc::ptr_eq(&k0, &model.constant_stiffness().unwrap()));
        let nodes = model.mesh.num_nodes();
        model.pattern = SparsityPattern::with_multipliers(
            nodes,
            model.mesh.elements.iter().map(|e| e.nodes.as_slice()),
            &[vec![0, 1], vec![2]],
        );
        let k1 = model.constant_stiffness().unwrap();
        assert!(!Arc::ptr_eq(&k0, &k1));
        assert_eq!(k1.len(), model.lower_triangle().nnz());
        let (f_ref, k_ref) = reference_assembly(&model, &u);
        let (f, k) = assemble_with_threads(&model, &u, 2);
        assert_close(&f, &f_ref, "force with multipliers");
        assert_close(&k, &k_ref, "tangent with multipliers");
        assert!(f[3 * nodes..].iter().all(|&v| v == 0.0));
    }

    /// A second process in this one: `sum` adds what "the other process"
    /// assembled (its elements, computed beforehand).
    struct OtherProcess {
        rank: usize,
        other: Mutex<Vec<Vec<f64>>>,
    }

    impl share::Communicator for OtherProcess {
        fn rank(&self) -> usize {
            self.rank
        }
        fn size(&self) -> usize {
            2
        }
        fn sum(&self, v: &mut [f64]) {
            let mut queue = self.other.lock().unwrap();
            let other = queue.remove(0);
            v.iter_mut().zip(other).for_each(|(a, b)| *a += b);
        }
    }

    /// Two shares of the elements (even and odd indices): each part's
    /// tangent plus the other's is the whole tangent, each process's force
    /// after the sum is the whole force, for a finite-strain and a linear
    /// (cached constant stiffness) material; an element failure of the
    /// other process is reported here too.
    #[test]
    fn two_shares_add_up_to_the_whole_assembly() {
        let materials: [Arc<dyn Material>; 2] = [
            Arc::new(NeoHookean::new(100.0, 0.45, "m").unwrap()),
            Arc::new(LinearElastic::new(1000.0, 0.3, "m").unwrap()),
        ];
        for material in materials {
            let (whole, u) = model_and_u(ElementKind::Hex8, material.clone());
            let (force, k) = assemble_with_threads(&whole, &u, 1);
            let ne = whole.mesh.elements.len();
            let part = |rank: usize, other: Vec<Vec<f64>>| {
                let (mut m, _) = model_and_u(ElementKind::Hex8, material.clone());
                let communicator = Arc::new(OtherProcess {
                    rank,
                    other: Mutex::new(other),
                });
                let nn = m.mesh.num_nodes();
                m.set_share(Share {
                    owned: (0..ne).map(|e| e % 2 == rank).collect(),
                    own_nodes: (0..nn).map(|n| n % 2 == rank).collect(),
                    communicator,
                });
                m
            };
            // the odd elements alone (a share whose sums add nothing)
            let zeros = vec![vec![0.0; force.len()], vec![0.0; 8]];
            let odd = part(1, zeros);
            let (odd_force, odd_k) = assemble_with_threads(&odd, &u, 1);
            // the even elements, completed by the odd ones
            let even = part(0, vec![odd_force, vec![0.0; 8]]);
            let (even_force, even_k) = assemble_with_threads(&even, &u, 2);
            assert_close(&even_force, &force, "summed force");
            let sum: Vec<f64> = even_k.iter().zip(&odd_k).map(|(a, b)| a + b).collect();
            assert_close(&sum, &k, "two parts of K");
            assert!(even_k
                .iter()
                .zip(&k)
                .any(|(a, b)| (a - b).abs() > 1e-6 * b.abs().max(1.0)));
        }
        // process 1 reports element 5 inverted: process 0 fails with it
        let (whole, u) = model_and_u(
            ElementKind::Hex8,
            Arc::new(LinearElastic::new(1.0, 0.3, "m").unwrap()),
        );
        let ne = whole.mesh.elements.len();
        let mut failure = vec![0.0; 8];
        failure[4..8].copy_from_slice(&[6.0, 2.0, 3.0, -0.5]);
        let (mut m, _) = model_and_u(
            ElementKind::Hex8,
            Arc::new(LinearElastic::new(1.0, 0.3, "m").unwrap()),
        );
        m.set_share(Share {
            owned: (0..ne).map(|e| e % 2 == 0).collect(),
            own_nodes: vec![true; m.mesh.num_nodes()],
            communicator: Arc::new(OtherProcess {
                rank: 0,
                other: Mutex::new(vec![vec![0.0; 3 * m.mesh.num_nodes()], failure]),
            }),
        });
        let mut force = vec![0.0; m.pattern.dimension()];
        let f = m.assemble_internal(&u, &mut force, None).unwrap_err();
        assert_eq!(f.element, 5);
        assert!(matches!(
            f.failure,
            KernelFailure::Inverted { quadrature_point: 3, det_f } if det_f == -0.5
        ));
    }
}
