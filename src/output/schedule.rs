//! When a listing that holds every increment so far (`summary.json`, the
//! `.pvd`, a history's `.csv` and `.svg`) is rewritten: on a geometric
//! schedule, so that its cost per increment does not grow with the run
//! (issue 31 item 3).
//!
//! A listing of `n` increments costs `c·n` to write. Rewritten after every
//! increment, a run of `N` increments pays `c·N²/2`. Rewritten when the
//! increments not yet in the file number at least a fraction `1/q` of
//! those that are (`n ≥ w + max(1, ⌊w/q⌋)`, `w` the count last written),
//! the writes fall at `w_{k+1} ≈ w_k (1 + 1/q)`, and the run pays
//! `c·Σ w_k ≈ c·(q+1)·N`: at most `(q+1)·c` per increment, whatever `N`.
//! The file lags the run by at most a fraction `1/(q+1)` of its
//! increments, and it is written whole (atomically) at the end of a run,
//! whichever way the run ends.

/// The fraction `1/q` of the increments in a listing that may be missing
/// from it before it is rewritten: `q = 8`, so a listing lags by at most
/// 11 % of the run and costs at most 9 entries' writing per increment.
pub const LAG: usize = 8;

/// The geometric rewrite schedule of one listing.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Rewrite {
    /// The number of increments in the file as last written.
    written: usize,
}

impl Rewrite {
    /// Whether a listing of `count` increments is to be written now:
    /// `count ≥ w + max(1, ⌊w/q⌋)`.
    pub fn due(&self, count: usize) -> bool {
        count >= self.written + (self.written / LAG).max(1)
    }

    /// Record that the listing was written with `count` increments.
    pub fn wrote(&mut self, count: usize) {
        self.written = count;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Over 20 000 increments the schedule writes entries in total at most
    /// `(q + 1)` times the number of increments (the amortised bound), the
    /// first 8 increments every time, and never lets more than `w/q`
    /// increments pile up.
    #[test]
    fn costs_a_bounded_number_of_entries_per_increment() {
        let mut schedule = Rewrite::default();
        let (mut entries, mut writes, mut written) = (0usize, 0usize, 0usize);
        for n in 1..=20_000 {
            if schedule.due(n) {
                schedule.wrote(n);
                entries += n;
                writes += 1;
                written = n;
            }
            assert!(
                n - written <= written / LAG,
                "{n} increments, {written} written"
            );
            if n <= LAG {
                assert_eq!(written, n);
            }
        }
        assert!(entries <= (LAG + 1) * 20_000, "{entries} entries written");
        // about log(N)/log(1 + 1/q) writes: 65 for N = 20 000 beyond the first 8
        assert!(writes < 100, "{writes} writes");
    }
}
