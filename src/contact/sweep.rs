//! A secondary node's path through a rigid obstacle over an increment.
//!
//! Node-to-surface contact sees the nodes' end positions only. When an
//! obstacle moves farther in one increment than the surface can follow (a
//! ball driven through a block's top in one step), a node it should have
//! pushed ahead can come out on its far side: with the node past the
//! sphere's centre, its closest point and normal are those of the far
//! side, the contact pushes it out there, and the increment converges with
//! the obstacle inside the body and no node inside the obstacle. The
//! signed distance at the end cannot tell; the node's path can.
//!
//! In the obstacle's frame (it only translates) node `a` goes from
//! `p₀ = x_a(t₀) − c(t₀)` to `p₁ = x_a(t₁) − c(t₁)`. Taking the path as the
//! segment `p(s) = p₀ + s (p₁ − p₀)`, `s ∈ [0, 1]` (the increment's
//! linear interpolation), the node passed through the obstacle when the
//! segment goes deeper than `δ` inside: `g(p(s)) < −δ` for some `s`.
//! A node that stays on the surface while it slides by `L` follows a chord
//! of the surface, `L²/(8R)` deep on a sphere of radius `R`; `δ` is the
//! contact element size, so that only a path through the obstacle, or a
//! slide too long for the increment to follow, is caught, and a smaller
//! increment mends both.
//!
//! The segment is searched by sphere tracing (Hart, *The Visual Computer*
//! 12, 1996): the signed distance `g` of a plane, sphere or cylinder is
//! 1-Lipschitz, so from `p(s)` every point within `g(p(s)) + δ` has
//! `g ≥ −δ`, and the march steps by that much (at least `δ/100`).

use super::interface::{ContactInterface, Primary};
use super::obstacle::RigidObstacle;
use nalgebra::Vector3;

/// The first `s` at which the segment `from → to` is deeper than `depth`
/// inside `obstacle` (module docs), with the signed distance there;
/// `None` when it never is, or for a triangulated obstacle (whose signed
/// distance is not 1-Lipschitz behind an open sheet's edges).
pub fn path_inside(
    obstacle: &RigidObstacle,
    from: &Vector3<f64>,
    to: &Vector3<f64>,
    depth: f64,
) -> Option<(f64, f64)> {
    if matches!(obstacle, RigidObstacle::Triangulated(_)) || !(depth > 0.0) {
        return None;
    }
    let length = (to - from).norm();
    let mut s = 0.0;
    loop {
        let gap = obstacle.project(&(from + (to - from) * s)).gap;
        if gap < -depth {
            return Some((s, gap));
        }
        if s >= 1.0 || length == 0.0 || !gap.is_finite() {
            return None;
        }
        s = (s + (gap + depth).max(0.01 * depth) / length).min(1.0);
    }
}

impl ContactInterface {
    /// A secondary node of a rigid interface whose path over the increment
    /// from `(t0, x0)` to `(t1, x1)` passes deeper than the contact element
    /// size inside the obstacle ([`path_inside`]): its mesh index and the
    /// signed distance reached.
    pub fn passed_through(
        &self,
        reference: &[[f64; 3]],
        (t0, x0): (f64, &[f64]),
        (t1, x1): (f64, &[f64]),
    ) -> Option<(usize, f64)> {
        let Primary::Rigid(obstacle) = &self.primary else {
            return None;
        };
        let (c0, c1) = (self.translation_at(t0), self.translation_at(t1));
        (0..self.nodes.len()).find_map(|i| {
            let from = self.relative_position(reference, &c0, x0, i);
            let to = self.relative_position(reference, &c1, x1, i);
            path_inside(obstacle, &from, &to, self.element_size).map(|(_, g)| (self.nodes[i], g))
        })
    }
}

#[cfg(test)]
mod tests {
    use super::path_inside;
    use crate::contact::obstacle::RigidObstacle;
    use nalgebra::Vector3;

    /// A sphere of radius 0.5 at the origin: a path through it is caught
    /// at the depth the tracing reaches (the chord through the centre goes
    /// 0.5 deep); a path beside it, a chord 0.01 deep (shallower than δ =
    /// 0.05) and a path that ends inside by less than δ are not.
    #[test]
    fn a_path_through_a_sphere_is_caught() {
        let ball = RigidObstacle::sphere(Vector3::zeros(), 0.5).unwrap();
        let (above, below) = (Vector3::new(0.0, 0.0, 0.6), Vector3::new(0.0, 0.0, -0.6));
        let (s, g) = path_inside(&ball, &above, &below, 0.05).expect("through the centre");
        assert!((-0.5..-0.05).contains(&g), "{g}");
        // the first point 0.05 deep is at z = 0.45, s = 0.15/1.2, passed
        // by at most the smallest step δ/100 over the length 1.2
        let first = 0.15 / 1.2;
        assert!((first..=first + 5e-4 / 1.2 + 1e-12).contains(&s), "{s}");
        let beside = Vector3::new(0.6, 0.0, 0.0);
        assert!(path_inside(&ball, &(above + beside), &(below + beside), 0.05).is_none());
        // a chord between two surface points at ±θ: sagitta R(1 − cos θ)
        let theta = 0.2f64;
        let on = |a: f64| Vector3::new(0.5 * a.sin(), 0.0, 0.5 * a.cos());
        let sagitta = 0.5 * (1.0 - theta.cos());
        assert!(sagitta < 0.05);
        assert!(path_inside(&ball, &on(-theta), &on(theta), 0.05).is_none());
        assert!(path_inside(&ball, &on(-theta), &on(theta), 0.5 * sagitta).is_some());
        let shallow = Vector3::new(0.0, 0.0, 0.49);
        assert!(path_inside(&ball, &above, &shallow, 0.05).is_none());
    }

    /// A half-space cannot be passed through: a path from in front of a
    /// plane to behind it is caught only once it is deeper than δ.
    #[test]
    fn a_plane_is_caught_only_behind_it() {
        let plane = RigidObstacle::plane(Vector3::zeros(), Vector3::z()).unwrap();
        let from = Vector3::new(0.0, 0.0, 1.0);
        assert!(path_inside(&plane, &from, &Vector3::new(5.0, 0.0, -0.04), 0.05).is_none());
        let (s, g) = path_inside(&plane, &from, &Vector3::new(0.0, 0.0, -1.0), 0.05).unwrap();
        assert!(g < -0.05 && s > 0.5 && s < 0.53, "{s} {g}");
    }
}
