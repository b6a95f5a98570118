//! The watchdog of Newton's line search (Chamberlain, Powell, Lemaréchal
//! & Pedersen, "The watchdog technique for forcing convergence in
//! algorithms for constrained optimization", Math. Programming Study 16,
//! 1982, pp. 1–17).
//!
//! A monotone line search keeps a step only where `‖r‖` falls (or, in
//! [`super::newton`], where Crisfield's energy test passes). On a
//! residual that is only piecewise smooth — a contact node that changes
//! its primary triangle, or turns from slip to stick — the full Newton
//! step can cross a kink and raise `‖r‖` although the next full step
//! from there converges, while every shorter step stays on the near side
//! of the kink, where `‖r‖` cannot fall: the search *stalls*, its steps
//! shrink to `α ≈ 10⁻²…10⁻⁴`, and the residual stays put for as many
//! iterations as it takes a fallback to take the full step
//! (node-to-surface ironing, t = 1.28: 3.5e-5 for 7 iterations;
//! press-pull on a triangulated cap, t = 1.75: 8.1e-4 for 11;
//! BENCHMARKS.md, "Session 21").
//!
//! The watchdog relaxes the monotone test there, and only there: where
//! the search stalls (its step shorter than [`STALL`]) near the answer
//! (relative residual below [`NEAR`]) and the full step from the iterate
//! `u_k` switches a contact status (open/stick/slip or a primary facet:
//! it crosses a kink), that full step is taken anyway and `u_k` is kept
//! as a *checkpoint* with its correction. The relaxed steps succeed as
//! soon as an iterate's residual is below `(1 − σ) ‖r_k‖` (`σ` =
//! [`DECREASE`], Armijo's constant at `α = 1`); until then up to
//! [`EXTRA_STEPS`] more full steps are taken. If none succeeds, Newton
//! goes back to `u_k` and takes the monotone search's step along `u_k`'s
//! correction, as it would have without the watchdog, forgets the
//! watched iterates (the chattering detector judges Newton's path, not
//! the steps it went back from), and takes no relaxed step for the rest
//! of the increment (a failed watch costs at most `EXTRA_STEPS + 1`
//! iterations once per increment).
//!
//! Why not wherever the full step switches a status (session 20's rule):
//! far from the answer that is where the monotone search does its work.
//! Press-pull on a triangulated cap (its first increment, the block
//! pressed from a touch) took the first full step, 220 nodes switching,
//! instead of `α = 0.003`: Newton converged in 7 iterations instead of
//! 12, to another converged facet choice (the nodes that flipped back
//! keep their last triangle, `contact::facet_walk`), 6e-4 of the contact
//! force's y component away from the condensed path's; and after each
//! augmentation of the Simo–Laursen outer loop (press-pull, exact stick,
//! `friction_multiplier = "outer"`) the relaxed steps cycled three nodes
//! between stick and slip until the chattering detector cut the
//! increment. Chamberlain et al.'s watchdog is a device for the local
//! rate (the Maratos effect); [`NEAR`] keeps it local.

/// A line search stalls where its step is shorter than this: the kink
/// is that close along the correction, and `‖r‖` falls by about the step.
pub const STALL: f64 = 0.1;

/// The relative residual below which the watchdog may act: the iterate
/// is near the answer (`‖r‖` at 1 % of the forces). The first iterates of
/// an increment, which carry its load jump, keep the monotone search.
pub const NEAR: f64 = 1e-2;

/// Full steps taken after the relaxed one before the watch is judged to
/// have failed (Chamberlain et al.'s `t`, "one or two").
pub const EXTRA_STEPS: usize = 1;

/// The sufficient decrease a relaxed step must reach: `‖r‖ ≤ (1 − σ)
/// ‖r_k‖` against the checkpoint's residual.
pub const DECREASE: f64 = 1e-4;

/// Where a relaxed step was taken from: the iterate `u_k` and its local
/// contact unknowns, its Newton correction `δu_k`, its out-of-balance
/// force `r_k` with its relative size.
pub struct Checkpoint<S> {
    pub u: Vec<f64>,
    pub state: S,
    pub du: Vec<f64>,
    pub out_of_balance: Vec<f64>,
    pub relative: f64,
    /// The chattering detector's path up to `u_k`.
    pub chatter: super::chattering::ChatterMark,
}

/// What the watchdog asks of the iteration that judges an iterate.
pub enum Judgement<S> {
    /// A line search; `relax`: it may take a full step that fails the
    /// monotone test (a watch then starts, or goes on).
    Search { relax: bool },
    /// The relaxed steps did not lower `‖r‖`: go back to the checkpoint
    /// and search along its correction.
    Revert(Checkpoint<S>),
}

/// The watch over one increment's relaxed steps.
pub struct Watchdog<S> {
    watch: Option<Watch<S>>,
    failed: bool,
}

struct Watch<S> {
    checkpoint: Checkpoint<S>,
    /// `‖r_k‖` at the checkpoint.
    residual: f64,
    /// Full steps still allowed before the watch fails.
    left: usize,
}

impl<S> Default for Watchdog<S> {
    fn default() -> Self {
        Watchdog {
            watch: None,
            failed: false,
        }
    }
}

impl<S> Watchdog<S> {
    /// Judge the iterate of out-of-balance norm `residual`: the watch
    /// succeeds where it is below `(1 − σ) ‖r_k‖` (and ends), goes on
    /// while steps are left, and fails otherwise (once per increment).
    pub fn judge(&mut self, residual: f64) -> Judgement<S> {
        let Some(mut watch) = self.watch.take() else {
            return Judgement::Search {
                relax: !self.failed,
            };
        };
        if residual <= (1.0 - DECREASE) * watch.residual {
            return Judgement::Search { relax: true };
        }
        if watch.left > 0 {
            watch.left -= 1;
            self.watch = Some(watch);
            return Judgement::Search { relax: true };
        }
        self.failed = true;
        Judgement::Revert(watch.checkpoint)
    }

    /// Start a watch from `checkpoint`, whose full step was taken though
    /// it failed the monotone test (none is started while one runs, nor
    /// after one failed in this increment).
    pub fn start(&mut self, checkpoint: Checkpoint<S>) {
        if self.watch.is_none() && !self.failed {
            let residual = super::gmres::norm(&checkpoint.out_of_balance);
            self.watch = Some(Watch {
                checkpoint,
                residual,
                left: EXTRA_STEPS,
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn checkpoint(residual: f64) -> Checkpoint<()> {
        Checkpoint {
            u: vec![0.0],
            state: (),
            du: vec![1.0],
            out_of_balance: vec![residual],
            relative: residual,
            chatter: crate::solve::chattering::ChatterDetector::default().mark(),
        }
    }

    /// A watch succeeds on a sufficient decrease within its steps, fails
    /// (back to the checkpoint, once) without one, and no relaxed step is
    /// allowed after a failure.
    #[test]
    fn a_watch_succeeds_on_decrease_and_fails_once() {
        let mut dog = Watchdog::default();
        assert!(matches!(dog.judge(1.0), Judgement::Search { relax: true }));
        dog.start(checkpoint(1.0));
        assert!(matches!(dog.judge(2.0), Judgement::Search { relax: true }));
        assert!(matches!(dog.judge(0.5), Judgement::Search { relax: true }));
        dog.start(checkpoint(0.5));
        assert!(matches!(dog.judge(0.5), Judgement::Search { relax: true }));
        match dog.judge(0.49999) {
            Judgement::Revert(back) => assert_eq!(back.out_of_balance, [0.5]),
            _ => panic!("the watch should fail: 0.49999 > (1 − 1e-4) · 0.5"),
        }
        assert!(matches!(dog.judge(0.1), Judgement::Search { relax: false }));
        dog.start(checkpoint(0.1));
        assert!(matches!(dog.judge(1.0), Judgement::Search { relax: false }));
    }
}
