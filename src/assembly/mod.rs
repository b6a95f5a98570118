//! Global assembly: element kernels evaluated in parallel (rayon) and
//! scattered into a fixed sparsity pattern.
//!
//! Elements are processed in chunks: the kernels of a chunk run in
//! parallel, then the chunk is scattered in element order by one thread.
//! Every global entry is therefore summed in the same order whatever the
//! number of threads, and results are bitwise independent of it.

pub mod amplitude;
pub mod kernel;
pub mod loads;
pub mod pattern;
pub mod scatter;

use crate::material::{Mat3, Material};
use crate::mesh::Mesh;
use kernel::{KernelFailure, PointGeometry};
use pattern::SparsityPattern;
use rayon::prelude::*;
use std::sync::Arc;

/// Elements per parallel chunk.
const CHUNK: usize = 4096;

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
        let geometry = mesh
            .elements
            .par_iter()
            .enumerate()
            .map(|(e, el)| {
                let coords: Vec<[f64; 3]> = el.nodes.iter().map(|&n| mesh.nodes[n]).collect();
                kernel::reference_geometry(el.kind, &coords).map_err(|failure| ElementFailure {
                    element: e,
                    failure,
                })
            })
            .collect::<Vec<_>>()
            .into_iter()
            .collect::<Result<Vec<_>, _>>()?; // in order: the first failing element, see `assemble_internal`
        let pattern = SparsityPattern::from_elements(
            mesh.num_nodes(),
            mesh.elements.iter().map(|e| e.nodes.as_slice()),
        );
        Ok(Model {
            mesh,
            materials,
            element_material,
            geometry,
            pattern,
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

    /// Number of unknowns (3 per node).
    pub fn num_dofs(&self) -> usize {
        3 * self.mesh.num_nodes()
    }

    fn element_displacements(&self, e: usize, u: &[f64]) -> Vec<[f64; 3]> {
        self.mesh.elements[e]
            .nodes
            .iter()
            .map(|&n| [u[3 * n], u[3 * n + 1], u[3 * n + 2]])
            .collect()
    }

    /// Assemble the internal force `f_int(u)` into `force` (overwritten) and,
    /// if `tangent` is given, `∂f_int/∂u` into it (overwritten; length
    /// `pattern.nnz()`).
    pub fn assemble_internal(
        &self,
        u: &[f64],
        force: &mut [f64],
        mut tangent: Option<&mut [f64]>,
    ) -> Result<(), ElementFailure> {
        force.iter_mut().for_each(|x| *x = 0.0);
        if let Some(k) = tangent.as_deref_mut() {
            k.iter_mut().for_each(|x| *x = 0.0);
        }
        let with_tangent = tangent.is_some();
        let n_el = self.mesh.elements.len();
        for start in (0..n_el).step_by(CHUNK) {
            let end = (start + CHUNK).min(n_el);
            let outputs = (start..end)
                .into_par_iter()
                .map(|e| {
                    kernel::internal_force_and_tangent(
                        &self.geometry[e],
                        &self.element_displacements(e, u),
                        self.materials[self.element_material[e]].as_ref(),
                        with_tangent,
                    )
                    .map_err(|failure| ElementFailure {
                        element: e,
                        failure,
                    })
                })
                .collect::<Vec<_>>()
                .into_iter()
                // in order: a parallel collect into a `Result` returns the
                // failure some thread met first, which changes from run to
                // run; the first element (in mesh order) that fails is named
                .collect::<Result<Vec<_>, _>>()?;
            for (e, out) in (start..end).zip(outputs) {
                let nodes = &self.mesh.elements[e].nodes;
                scatter::add_nodal(force, nodes, |k| out.force[k]);
                if let Some(k) = tangent.as_deref_mut() {
                    let dofs = 3 * nodes.len();
                    scatter_block_matrix(&self.pattern, nodes, &out.stiffness, dofs, k);
                }
            }
        }
        Ok(())
    }

    /// Volume-averaged Cauchy stress of every element.
    pub fn cauchy_stresses(&self, u: &[f64]) -> Vec<Mat3> {
        (0..self.mesh.elements.len())
            .into_par_iter()
            .map(|e| {
                kernel::element_cauchy_stress(
                    &self.geometry[e],
                    &self.element_displacements(e, u),
                    self.materials[self.element_material[e]].as_ref(),
                )
            })
            .collect()
    }

    /// Reference volume of every element.
    pub fn element_volumes(&self) -> Vec<f64> {
        self.geometry
            .iter()
            .map(|g| g.iter().map(|p| p.dv).sum())
            .collect()
    }

    /// `∫ N_a dV₀` for every node, over the elements in `elements`: the
    /// consistent nodal weights of a uniform body force.
    pub fn nodal_volumes(&self, elements: &[usize]) -> Vec<f64> {
        let mut w = vec![0.0; self.mesh.num_nodes()];
        for &e in elements {
            let el = &self.mesh.elements[e];
            let r = crate::fem::volume_reference(el.kind);
            for (q, p) in self.geometry[e].iter().enumerate() {
                for (a, &n) in el.nodes.iter().enumerate() {
                    w[n] += r.values[q][a] * p.dv;
                }
            }
        }
        w
    }
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
