//! A prescribed finite rotation of a node set about an axis, with an
//! optional translation: the rigid motion
//!
//! `u(X, t) = (R(θ(t)) − I)(X − c) + a_u(t) t₀`,
//!
//! where `R(θ)` is the rotation by `θ` about the unit axis `n` (Rodrigues,
//! `R = I + sin θ [n]ₓ + (1 − cos θ) [n]ₓ²`, exact at any angle),
//! `θ(t) = θ₀ a_θ(t)`, `c` the centre (a point of the axis) and `t₀` the
//! translation. Every displacement component of the set's nodes is
//! prescribed.

use crate::assembly::amplitude::Amplitude;
use nalgebra::{Rotation3, Unit, Vector3};

/// A rigid rotation (and translation) prescribed on the nodes of a set.
#[derive(Clone, Debug)]
pub struct PrescribedRotation {
    /// The set's name.
    pub set: String,
    pub nodes: Vec<usize>,
    /// The rotation axis (any length but zero; normalised when used).
    pub axis: [f64; 3],
    /// A point of the axis `c` (reference configuration).
    pub centre: [f64; 3],
    /// The angle `θ₀` in radians (right hand about `axis`), scaled by
    /// `angle_amplitude`.
    pub angle: f64,
    pub angle_amplitude: Amplitude,
    /// The translation `t₀`, scaled by `translation_amplitude`.
    pub translation: [f64; 3],
    pub translation_amplitude: Amplitude,
}

/// The rotation matrix by `angle` (radians) about `axis` (non-zero), row
/// major: Rodrigues' formula (nalgebra's `Rotation3::from_axis_angle`).
pub fn rotation_matrix(axis: [f64; 3], angle: f64) -> [[f64; 3]; 3] {
    let n = Unit::new_normalize(Vector3::from(axis));
    let r = Rotation3::from_axis_angle(&n, angle).into_inner();
    std::array::from_fn(|i| std::array::from_fn(|j| r[(i, j)]))
}

/// `(R − I)(X − c)`: the displacement of the material point `x` rotated
/// by `r` about the centre `c`.
pub fn rotation_displacement(r: &[[f64; 3]; 3], centre: [f64; 3], x: [f64; 3]) -> [f64; 3] {
    let d = [x[0] - centre[0], x[1] - centre[1], x[2] - centre[2]];
    std::array::from_fn(|i| (0..3).map(|j| r[i][j] * d[j]).sum::<f64>() - d[i])
}

impl PrescribedRotation {
    /// The angle `θ(t)` in radians.
    pub fn angle_at(&self, t: f64) -> f64 {
        self.angle * self.angle_amplitude.value(t)
    }

    /// Write `u(X_a, t)` of every node `a` of the set into `u` (three dofs
    /// a node), `reference` the mesh's reference coordinates.
    pub fn apply(&self, t: f64, reference: &[[f64; 3]], u: &mut [f64]) {
        let r = rotation_matrix(self.axis, self.angle_at(t));
        let a = self.translation_amplitude.value(t);
        for &n in &self.nodes {
            let d = rotation_displacement(&r, self.centre, reference[n]);
            for i in 0..3 {
                u[3 * n + i] = d[i] + a * self.translation[i];
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A quarter turn about z maps (1, 0, 0) to (0, 1, 0): displacement
    /// (−1, 1, 0); about a shifted centre the lever arm is `X − c`.
    #[test]
    fn quarter_turn_about_z() {
        let r = rotation_matrix([0.0, 0.0, 2.0], std::f64::consts::FRAC_PI_2);
        let u = rotation_displacement(&r, [0.0; 3], [1.0, 0.0, 0.5]);
        for (a, b) in u.iter().zip([-1.0, 1.0, 0.0]) {
            assert!((a - b).abs() < 1e-15, "{u:?}");
        }
        let u = rotation_displacement(&r, [1.0, 1.0, 0.0], [2.0, 1.0, 0.0]);
        for (a, b) in u.iter().zip([-1.0, 1.0, 0.0]) {
            assert!((a - b).abs() < 1e-15, "{u:?}");
        }
    }

    /// Rodrigues' matrix is orthogonal and leaves the axis fixed, at a large angle about a skew axis.
    #[test]
    fn rotation_is_proper_and_fixes_the_axis() {
        let axis = [1.0, -2.0, 0.5];
        let r = rotation_matrix(axis, 2.3);
        for i in 0..3 {
            for j in 0..3 {
                let rrt: f64 = (0..3).map(|k| r[i][k] * r[j][k]).sum();
                assert!((rrt - f64::from(u8::from(i == j))).abs() < 1e-14);
            }
        }
        let u = rotation_displacement(&r, [0.0; 3], axis);
        assert!(u.iter().all(|v| v.abs() < 1e-14), "{u:?}");
    }
}
