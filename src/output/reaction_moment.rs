//! The reaction moment of a node set about a point, in the current
//! configuration: `M = Σ_a (x_a − c) × r_a`, with `x_a = X_a + u_a` the
//! node's current position and `r_a` its reaction force (the residual
//! `f_int − f_ext` at a prescribed node).

/// `Σ_a (x_a − c) × r_a` over the nodes `nodes` whose reference positions
/// are `reference` (same order), displacements `u` and residual `residual`
/// (three entries a node); `c = centre`, or the nodes' current centroid
/// `x̄ = Σ x_a / n` when `None`.
pub fn reaction_moment(
    nodes: &[usize],
    reference: &[[f64; 3]],
    centre: Option<[f64; 3]>,
    u: &[f64],
    residual: &[f64],
) -> [f64; 3] {
    let current: Vec<[f64; 3]> = nodes
        .iter()
        .zip(reference)
        .map(|(&n, x)| std::array::from_fn(|i| x[i] + u[3 * n + i]))
        .collect();
    let c = centre.unwrap_or_else(|| centroid(&current));
    let mut m = [0.0; 3];
    for (&n, x) in nodes.iter().zip(&current) {
        let d = [x[0] - c[0], x[1] - c[1], x[2] - c[2]];
        let r = &residual[3 * n..3 * n + 3];
        m[0] += d[1] * r[2] - d[2] * r[1];
        m[1] += d[2] * r[0] - d[0] * r[2];
        m[2] += d[0] * r[1] - d[1] * r[0];
    }
    m
}

/// The mean of `points` (the origin for none).
fn centroid(points: &[[f64; 3]]) -> [f64; 3] {
    let n = points.len().max(1) as f64;
    std::array::from_fn(|i| points.iter().map(|p| p[i]).sum::<f64>() / n)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A couple: ±F ŷ at x = ±a about the centroid gives M_z = 2 a F,
    /// at the current positions (the displacement shifts both nodes, and a
    /// stretch along x lengthens the arm); a net force adds (c' − c) × F
    /// when the centre moves.
    #[test]
    fn a_couple_and_a_moved_centre() {
        let reference = [[-1.0, 0.0, 0.0], [1.0, 0.0, 0.0]];
        let u = [0.5, 2.0, 0.0, 1.5, 2.0, 0.0];
        let r = [0.0, -3.0, 0.0, 0.0, 3.0, 0.0];
        let m = reaction_moment(&[0, 1], &reference, None, &u, &r);
        assert_eq!(m, [0.0, 0.0, 2.0 * 1.5 * 3.0]);
        // a net force F = (0, 0, 2) at x = (2.5, 2, 0) about the origin:
        // M = x × F = (4, −5, 0)
        let r = [0.0, 0.0, 0.0, 0.0, 0.0, 2.0];
        let m = reaction_moment(&[0, 1], &reference, Some([0.0; 3]), &u, &r);
        assert_eq!(m, [4.0, -5.0, 0.0]);
    }
}
