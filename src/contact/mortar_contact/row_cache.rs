//! The mortar producer's row cache: the rows of the last configurations,
//! so that every driver operation at one state segments and integrates
//! them once ([`super::MortarSurfaces`]).

use super::MortarRows;
use crate::contact::mortar::Derivatives;
use std::collections::VecDeque;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};

/// How many configurations the row cache keeps: Newton's iterate and the
/// line search's trial (the driver advances the states at the iterate
/// after evaluating the trial).
const CACHED_CONFIGURATIONS: usize = 2;

/// The producer's rows at the last [`CACHED_CONFIGURATIONS`]
/// configurations, keyed by the coordinates of the surfaces' nodes, each
/// with its derivatives or without ([`Derivatives`]): every driver
/// operation at one state (the residual, its tangent, the states'
/// advance, the commit, the gaps) segments and integrates it once, and
/// once more with derivatives where the first operation read values
/// alone (rows with derivatives serve a request for values). A clone
/// starts empty (it may refresh its candidates on its own); counts of rows
/// asked for and integrated with derivatives, and of the evaluations of
/// values alone (rows or gaps without derivatives),
/// [`MortarSurfaces::row_counts`].
#[derive(Default)]
pub(super) struct RowCache {
    entries: Mutex<VecDeque<CachedRows>>,
    requested: AtomicUsize,
    integrated: AtomicUsize,
    values: AtomicUsize,
}

/// One configuration's key, whether its rows carry derivatives, the rows.
type CachedRows = (Vec<f64>, Derivatives, Arc<MortarRows>);

impl Clone for RowCache {
    fn clone(&self) -> Self {
        Self::default()
    }
}

impl std::fmt::Debug for RowCache {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "RowCache({:?})", self.counts())
    }
}

/// How often the producer asked for the rows of a configuration, and how
/// often it segmented and integrated them with their derivatives (the rest
/// came from the cache, or needed values alone); how often values alone
/// were evaluated, without derivatives (rows taken
/// [`Derivatives::Without`], or the gaps of [`RowSource::gaps`](super::RowSource::gaps), where
/// the configuration's rows were not cached).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RowCounts {
    pub requested: usize,
    pub integrated: usize,
    pub values: usize,
}

impl RowCache {
    pub(super) fn counts(&self) -> RowCounts {
        RowCounts {
            requested: self.requested.load(Ordering::Relaxed),
            integrated: self.integrated.load(Ordering::Relaxed),
            values: self.values.load(Ordering::Relaxed),
        }
    }

    /// The rows at `key` with at least `derivatives`, from the cache or
    /// from `integrate` (then kept in place of rows at `key` without
    /// derivatives, the oldest configuration dropped).
    pub(super) fn rows(
        &self,
        key: Vec<f64>,
        derivatives: Derivatives,
        integrate: impl FnOnce() -> MortarRows,
    ) -> Arc<MortarRows> {
        self.requested.fetch_add(1, Ordering::Relaxed);
        let mut entries = self.entries.lock().unwrap_or_else(|e| e.into_inner());
        let found = entries.iter().position(|(k, _, _)| *k == key);
        if let Some(entry) = found.and_then(|at| entries.remove(at)) {
            if entry.1 == Derivatives::With || derivatives == Derivatives::Without {
                let rows = entry.2.clone();
                entries.push_front(entry);
                return rows;
            }
        }
        let count = match derivatives {
            Derivatives::With => &self.integrated,
            Derivatives::Without => &self.values,
        };
        count.fetch_add(1, Ordering::Relaxed);
        let rows = Arc::new(integrate());
        entries.push_front((key, derivatives, rows.clone()));
        entries.truncate(CACHED_CONFIGURATIONS);
        rows
    }

    /// The rows at `key` (with derivatives or without) if the cache holds
    /// them, leaving the cache and its counts as they are.
    pub(super) fn peek(&self, key: &[f64]) -> Option<Arc<MortarRows>> {
        let entries = self.entries.lock().unwrap_or_else(|e| e.into_inner());
        (entries.iter())
            .find(|(k, _, _)| k == key)
            .map(|(_, _, rows)| rows.clone())
    }

    pub(super) fn clear(&self) {
        self.entries
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .clear();
    }

    /// Count one evaluation of values alone outside the cache (the gaps
    /// of [`RowSource::gaps`](super::RowSource::gaps)).
    pub(super) fn count_values(&self) {
        self.values.fetch_add(1, Ordering::Relaxed);
    }
}
