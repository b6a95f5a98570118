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
//! element part only (no contact, no follower load), on the whole pattern
//! (both triangles, zero in the multiplier rows and columns).

use super::pattern::SparsityPattern;
use rayon::prelude::*;
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

/// `f = K u` over the first `displacement_dofs` unknowns (the rest of `f`
/// set to zero): `f_j = Σ_i K_ji u_i`, column `j` of the CSC values read
/// as row `j`, which holds because `K` is symmetric (bitwise: the element
/// blocks are mirrored and both triangles summed in the same order). One
/// task per entry of `f`, so the result does not depend on the threads.
pub fn multiply_symmetric(
    pattern: &SparsityPattern,
    k: &[f64],
    displacement_dofs: usize,
    u: &[f64],
    f: &mut [f64],
) {
    let symbolic = pattern.symbolic();
    let (cp, ri) = (symbolic.col_ptr(), symbolic.row_idx());
    let (head, tail) = f.split_at_mut(displacement_dofs);
    tail.iter_mut().for_each(|v| *v = 0.0);
    head.par_iter_mut()
        .with_min_len(256)
        .enumerate()
        .for_each(|(j, fj)| {
            let mut sum = 0.0;
            // rows are sorted: the multiplier rows come last
            for p in cp[j]..cp[j + 1] {
                let i = ri[p];
                if i >= displacement_dofs {
                    break;
                }
                sum += k[p] * u[i];
            }
            *fj = sum;
        });
}
