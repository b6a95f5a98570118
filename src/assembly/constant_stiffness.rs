//! The stiffness of a geometrically and materially linear model, cached.
//!
//! When every element's material has a constant tangent
//! ([`Material::constant_tangent`](crate::material::Material::constant_tangent):
//! `linear_elastic`, small strain, `K = ∫ Bᵀ ℂ B dV` with the linear `B`),
//! the internal force is linear in the displacement, `f_int(u) = K u`, and
//! `K` is the same at every `u`. It is assembled once per sparsity pattern
//! (a new pattern — contact pairs that changed — assembles it again) and
//! every later residual costs one sparse product instead of an element
//! loop. The finite-strain materials (total Lagrangian: `B` depends on `F`,
//! and the geometric stiffness on `S`) never use the cache.
//!
//! Other parts of the solver may read the cached `K` through
//! [`Model::constant_stiffness`](super::Model::constant_stiffness): the
//! element part only (no contact, no follower load), its lower triangle
//! ([`super::triangle`]: half the entries of the whole pattern; zero in the
//! multiplier rows), from which `f = K u` is one symmetric product
//! ([`super::triangle::multiply`]) and a whole tangent a copy through each
//! entry's mirror.
//!
//! When every material is Hooke's ([`Material::hooke_lame`]: small-strain
//! isotropic), `K` is assembled with the element stiffness in closed form
//! ([`assemble_hooke_lower`], [`super::hooke`]) instead of the general
//! kernel at `u = 0`: the same `K` to round-off, a fraction of the work.
//!
//! [`Material::hooke_lame`]: crate::material::Material::hooke_lame

use super::hooke::hooke_stiffness;
use super::kernel::PointGeometry;
use super::pattern::SparsityPattern;
use super::scatter_map::ScatterMap;
use super::triangle::LowerTriangle;
use crate::mesh::{Element, ElementKind};
use std::borrow::Cow;
use std::sync::{Arc, Mutex, PoisonError};

/// `K` on the pattern it was assembled for.
#[derive(Debug, Default)]
pub struct StiffnessCache {
    slot: Mutex<Option<(u64, Arc<Vec<f64>>)>>,
}

impl StiffnessCache {
    /// The cached `K` if it belongs to `pattern`, else `build()` (cached
    /// unless it is `None`).
    pub fn get_or_build(
        &self,
        pattern: &SparsityPattern,
        build: impl FnOnce() -> Option<Vec<f64>>,
    ) -> Option<Arc<Vec<f64>>> {
        let mut slot = self.slot.lock().unwrap_or_else(PoisonError::into_inner);
        if let Some((id, k)) = slot.as_ref() {
            if *id == pattern.id() {
                return Some(Arc::clone(k));
            }
        }
        let k = Arc::new(build()?);
        *slot = Some((pattern.id(), Arc::clone(&k)));
        Some(k)
    }
}

/// The lower triangle `lower` of Hooke's `K = Σ_e K_e`, `K_e` in closed
/// form ([`hooke_stiffness`]) from each element's reference geometry
/// `geometry(e)` (kept, or made again: [`super::Model::geometry_of`]) and
/// Lamé parameters `lame(e)`, over the elements `owned` admits, added
/// through the scatter map `map` into `lower` ([`ScatterMap::lower`]).
/// `None` if an element is not a Tet4 or a Hex8 (the other kinds go
/// through the general kernel).
///
/// One thread, in mesh order: neighbouring elements share nodes, so the
/// entries they add to are still in cache (three times faster on the race
/// mesh than the general loop's colour order, each colour of which sweeps
/// the whole mesh); every entry is summed in mesh order, the same on any
/// number of threads. Its caller runs it beside the fill-reducing
/// ordering, on the other thread.
pub fn assemble_hooke_lower<'g>(
    elements: &[Element],
    geometry: impl Fn(usize) -> Cow<'g, [PointGeometry]>,
    lame: impl Fn(usize) -> (f64, f64),
    owned: impl Fn(usize) -> bool,
    lower: &LowerTriangle,
    map: &ScatterMap,
) -> Option<Vec<f64>> {
    let closed_form = |kind| matches!(kind, ElementKind::Tet4 | ElementKind::Hex8);
    if !elements.iter().all(|e| closed_form(e.kind)) {
        return None;
    }
    let mut k = vec![0.0; lower.nnz()];
    for (e, element) in elements.iter().enumerate() {
        if !owned(e) {
            continue;
        }
        let g = &*geometry(e);
        let (lambda, mu) = lame(e);
        let mut add = |blocks: &[[f64; 9]]| {
            add_upper_blocks(&mut k, lower, map.element(e), &element.nodes, blocks)
        };
        match element.kind {
            ElementKind::Tet4 => add(&hooke_stiffness::<4, 10>(g, lambda, mu)),
            ElementKind::Hex8 => add(&hooke_stiffness::<8, 36>(g, lambda, mu)),
            _ => return None,
        }
    }
    Some(k)
}

/// Add an element's blocks `K_ab`, `a ≤ b` (in the order of
/// [`hooke_stiffness`], `K_ba = K_abᵀ`), into the lower triangle `values`
/// of `lower` at the block starts `starts` ([`ScatterMap::element`]):
/// block `(a, b)` holds the entries (row `3 n_a + i`, column `3 n_b + k`)
/// `= K_ab[i][k]` if `n_a ≥ n_b`, else (row `3 n_b + k`, column
/// `3 n_a + i`); a diagonal block from its diagonal down.
fn add_upper_blocks(
    values: &mut [f64],
    lower: &LowerTriangle,
    starts: &[usize],
    nodes: &[usize],
    blocks: &[[f64; 9]],
) {
    let n = nodes.len();
    let mut blocks = blocks.iter();
    for (a, &na) in nodes.iter().enumerate() {
        for (b, &nb) in nodes.iter().enumerate().skip(a) {
            let Some(k_ab) = blocks.next() else {
                return;
            };
            // the stored block: rows of the larger node, columns of the other
            let (start, column_node, transposed) = if na >= nb {
                (starts[a * n + b], nb, false)
            } else {
                (starts[b * n + a], na, true)
            };
            for (j, offset) in lower.node_column_offsets(column_node).iter().enumerate() {
                let first = if a == b { j } else { 0 };
                for i in first..3 {
                    values[start + offset + i] += if transposed {
                        k_ab[3 * j + i]
                    } else {
                        k_ab[3 * i + j]
                    };
                }
            }
        }
    }
}
