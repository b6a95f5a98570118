//! Detection of a contact status that cycles between Newton iterations
//! (active-set or stick–slip chattering).
//!
//! Newton on a contact problem re-evaluates every node's status (open,
//! stick, slip) at each iterate. Near a status boundary it can fall into a
//! cycle: a set of nodes flips one way, the next iterate flips them back,
//! and so on, without the residual settling. Iterating to the limit then
//! wastes the whole iteration budget. The detector remembers the status
//! vector of every iteration of an increment; an iteration whose status
//! changed (`switched > 0`) and equals that of an earlier iteration other
//! than the previous one is a *revisit*. After [`REVISITS`] revisits the
//! increment is declared chattering, so the stepper can cut it: a smaller
//! increment moves fewer nodes across the boundary at once.

/// Revisits of an earlier status before the increment is given up.
pub const REVISITS: usize = 3;

/// A detected cycle.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Chatter {
    /// Iterations between the two visits of the last revisited status.
    pub period: usize,
    /// Nodes whose status changed in the last iteration.
    pub flipping: usize,
    /// How many times an earlier status came back.
    pub revisits: usize,
    /// What the nodes of the last iteration flipped between.
    pub flips: Flips,
}

/// The flips of one iteration by kind: between stick and slip (friction at
/// the Coulomb limit), between open and closed (the edge of the contact
/// zone), between primary triangles (a node over a facet edge).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Flips {
    pub stick_slip: usize,
    pub open_closed: usize,
    pub facet: usize,
}

impl Flips {
    /// The flips from `before` to `after` (statuses as
    /// [`ChatterDetector::observe`] takes them).
    pub fn between(before: &[u64], after: &[u64]) -> Flips {
        let mut flips = Flips::default();
        for (a, b) in before.iter().zip(after).filter(|(a, b)| a != b) {
            if a % 4 == 0 || b % 4 == 0 {
                flips.open_closed += 1;
            } else if a / 4 != b / 4 {
                flips.facet += 1;
            } else {
                flips.stick_slip += 1;
            }
        }
        flips
    }
}

impl std::fmt::Display for Chatter {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "contact status chattering: an earlier set of open/stick/slip nodes came back {} times \
             (cycle of {} iterations, {} nodes flipping)",
            self.revisits, self.period, self.flipping
        )?;
        let Flips {
            stick_slip,
            open_closed,
            facet,
        } = self.flips;
        if stick_slip >= open_closed.max(facet) && stick_slip > 0 {
            write!(
                f,
                "; they flip between stick and slip: at the Coulomb limit Newton cannot settle \
                 which side, and smaller increments rarely cure it; try method = \"penalty\", \
                 whose elastic stick (t_T/ε_T) and penalty gap smooth the transition"
            )
        } else if facet >= open_closed && facet > 0 {
            write!(
                f,
                "; they flip between primary triangles (a node over a facet edge): make the finer \
                 surface the secondary, or refine the primary surface"
            )
        } else if open_closed > 0 {
            write!(
                f,
                "; they flip between open and closed (the edge of the contact zone): take smaller \
                 increments, or try method = \"penalty\", whose gap law is smooth"
            )
        } else {
            Ok(())
        }
    }
}

/// Remembers the status vector of each iteration of one increment.
#[derive(Default)]
pub struct ChatterDetector {
    seen: Vec<Vec<u64>>,
    revisits: usize,
}

impl ChatterDetector {
    /// Record this iteration's statuses (one per secondary node: `0` open,
    /// `1` stick, `2` slip, plus 4 × (1 + the primary triangle) on a
    /// deformable interface, so that a change of triangle counts too). Returns the number of nodes that switched since
    /// the previous iteration, and the cycle once it has come back
    /// [`REVISITS`] times.
    pub fn observe(&mut self, statuses: Vec<u64>) -> (usize, Option<Chatter>) {
        let flips = self.seen.last().map_or_else(Flips::default, |previous| {
            Flips::between(previous, &statuses)
        });
        let switched = flips.stick_slip + flips.open_closed + flips.facet;
        let mut chatter = None;
        if switched > 0 {
            let earlier = self.seen.len().saturating_sub(1);
            if let Some(j) = self.seen[..earlier].iter().rposition(|s| *s == statuses) {
                self.revisits += 1;
                if self.revisits >= REVISITS {
                    chatter = Some(Chatter {
                        period: self.seen.len() - j,
                        flipping: switched,
                        revisits: self.revisits,
                        flips,
                    });
                }
            }
        }
        self.seen.push(statuses);
        (switched, chatter)
    }

    /// Where the path stands now, to [`ChatterDetector::rewind`] to.
    pub fn mark(&self) -> ChatterMark {
        ChatterMark {
            seen: self.seen.len(),
            revisits: self.revisits,
        }
    }

    /// Forget the iterations observed since `mark`: iterates Newton left
    /// (the watchdog's steps it went back from) are no part of its path.
    pub fn rewind(&mut self, mark: ChatterMark) {
        self.seen.truncate(mark.seen);
        self.revisits = mark.revisits;
    }
}

/// The length of a [`ChatterDetector`]'s path and its revisits so far.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ChatterMark {
    seen: usize,
    revisits: usize,
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rewound to a mark, the detector forgets the iterates since: the
    /// cycle those made is not counted, and later revisits count anew.
    #[test]
    fn a_rewound_path_forgets_its_revisits() {
        let mut d = ChatterDetector::default();
        let (a, b) = (vec![1, 2, 0], vec![1, 1, 1]);
        d.observe(a.clone());
        let mark = d.mark();
        d.observe(b.clone());
        d.observe(a.clone()); // revisit 1
        d.observe(b.clone()); // revisit 2
        d.rewind(mark);
        assert_eq!(d.mark(), mark);
        assert_eq!(d.observe(b.clone()), (2, None));
        assert_eq!(d.observe(a.clone()), (2, None)); // revisit 1 again
        assert_eq!(d.observe(b).0, 2); // revisit 2
        assert!(d.observe(a).1.is_some()); // revisit 3: chattering
    }

    #[test]
    fn a_period_two_flip_is_caught_on_its_third_return() {
        let mut d = ChatterDetector::default();
        let (a, b) = (vec![1, 2, 0], vec![1, 1, 1]);
        assert_eq!(d.observe(a.clone()), (0, None));
        assert_eq!(d.observe(b.clone()), (2, None));
        assert_eq!(d.observe(a.clone()), (2, None)); // revisit 1
        assert_eq!(d.observe(b.clone()), (2, None)); // revisit 2
        let (switched, chatter) = d.observe(a);
        assert_eq!(switched, 2);
        assert_eq!(
            chatter,
            Some(Chatter {
                period: 2,
                flipping: 2,
                revisits: 3,
                flips: Flips {
                    stick_slip: 1,
                    open_closed: 1,
                    facet: 0
                }
            })
        );
    }

    /// The message names what the nodes flip between, and what to change.
    #[test]
    fn the_message_names_the_kind_of_flip() {
        let message = |before: &[u64], after: &[u64]| {
            Chatter {
                period: 2,
                flipping: 1,
                revisits: 3,
                flips: Flips::between(before, after),
            }
            .to_string()
        };
        let friction = message(&[1, 2, 9], &[2, 2, 9]);
        assert!(friction.contains("between stick and slip"), "{friction}");
        assert!(friction.contains("method = \"penalty\""), "{friction}");
        // 4 × (1 + triangle) + status: triangle 1 then 2, both closed
        let facet = message(&[9, 0], &[13, 0]);
        assert!(facet.contains("between primary triangles"), "{facet}");
        let edge = message(&[0, 1], &[1, 1]);
        assert!(edge.contains("between open and closed"), "{edge}");
    }

    #[test]
    fn settling_statuses_are_not_chattering() {
        let mut d = ChatterDetector::default();
        // a monotone progression, then a fixed status: no revisit
        for s in [vec![0, 0, 0], vec![1, 0, 0], vec![1, 1, 0], vec![1, 1, 2]] {
            assert!(d.observe(s).1.is_none());
        }
        for _ in 0..10 {
            assert_eq!(d.observe(vec![1, 1, 2]), (0, None));
        }
    }
}
