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

use super::pattern::SparsityPattern;
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
