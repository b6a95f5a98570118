//! A secondary node's walk over the primary triangles within one
//! increment: the memory of the facet choice
//! ([`PrimarySurface::projection`](super::primary::PrimarySurface::projection),
//! module docs of [`primary`](super::primary), "Facet choice").
//!
//! The choice must be the same for Newton's iterates and the condensed
//! rounds, which reach the answer along different iterates, and must have a
//! fixed point for a node sliding over a crease. The walk holds what the
//! choice reads besides the current position:
//! - `committed`: the triangle at the last converged increment (at the
//!   start, the nearest at the initial configuration), tried first while
//!   the node is over it within the sticky band;
//! - `left`: the last triangle the node moved off within the increment;
//! - `returned`: whether the node came back onto a triangle it had left (its
//!   committed one after any excursion, or the one it last moved off: a
//!   flip back, `A → B → A`). From then on, within the increment, the node
//!   keeps its last iterate's triangle while it stays over it within the
//!   band: the hysteresis that gives a node on a crease a fixed point.
//!
//! A node whose iterates never flip back thus ends on a function of the
//! committed state and the current position alone (the committed triangle
//! while within its band, else the nearest), whichever iterates led there.

/// The memory of a node's facet choice within an increment (module docs).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct FacetWalk {
    /// The triangle at the last converged increment (`None`: the node had
    /// none, it was beyond the surface's edge or without candidates).
    pub committed: Option<usize>,
    /// The triangle of the node's last iterate that had one…
    pub on: Option<usize>,
    /// …and the last triangle the node moved off within the increment.
    pub left: Option<usize>,
    /// Whether the node has come back onto a triangle it had left.
    pub returned: bool,
}

impl FacetWalk {
    /// The walk at the start of an increment: on `facet`, committed there.
    pub fn committed_on(facet: Option<usize>) -> Self {
        Self {
            committed: facet,
            on: facet,
            left: None,
            returned: false,
        }
    }

    /// An iterate projects the node on triangle `to`. An open iterate
    /// (`to = None`) changes nothing, so that a path that records it and
    /// one that does not walk alike.
    pub fn step(&mut self, to: Option<usize>) {
        let Some(to) = to else { return };
        if self.on == Some(to) {
            return;
        }
        let back_home = self.left.is_some() && self.committed == Some(to);
        if back_home || self.left == Some(to) {
            self.returned = true;
        }
        self.left = self.on;
        self.on = Some(to);
    }

    /// The triangle the choice tries first, given the last iterate's
    /// `iterate`: the committed one until the node has flipped back, the
    /// last iterate's after.
    pub fn kept(&self, iterate: Option<usize>) -> Option<usize> {
        if self.returned {
            iterate
        } else {
            self.committed
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_committed_triangle_is_kept_until_a_flip_back() {
        // an excursion that does not come back: still the committed first
        let mut w = FacetWalk::committed_on(Some(3));
        w.step(Some(3));
        w.step(Some(7));
        w.step(Some(9));
        assert_eq!((w.kept(Some(9)), w.returned), (Some(3), false));
        // back onto the committed triangle after it: the iterate's from then
        w.step(Some(3));
        assert!(w.returned);
        assert_eq!(w.kept(Some(3)), Some(3));
        w.step(Some(7));
        assert_eq!(w.kept(Some(7)), Some(7));
    }

    #[test]
    fn a_flip_back_between_other_triangles_counts_and_open_iterates_do_not() {
        let mut w = FacetWalk::committed_on(None);
        w.step(Some(4));
        w.step(Some(5));
        assert!(!w.returned);
        assert_eq!(w.kept(Some(5)), None);
        // open in between (Newton records it, the rounds do not)
        let mut rounds = w;
        w.step(None);
        w.step(Some(4));
        assert!(w.returned);
        rounds.step(Some(4));
        assert_eq!(rounds, w);
    }
}
