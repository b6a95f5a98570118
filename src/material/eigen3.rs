//! Eigen-decomposition of a symmetric 3×3 matrix by cyclic Jacobi rotations,
//! on the stack: what the Ogden material needs at every quadrature point
//! (`C = FᵀF = Σ_i c_i N_i⊗N_i`), several times cheaper than a general
//! Householder–QR solver.
//!
//! Each rotation `J_pq(θ)` zeroes `a_pq` of `A ← Jᵀ A J` with
//! `τ = (a_qq − a_pp)/(2 a_pq)`, `t = sign(τ)/(|τ| + √(1 + τ²))`,
//! `c = 1/√(1 + t²)`, `s = t c` (Golub & Van Loan §8.5, the form that keeps
//! `|θ| ≤ π/4`), which changes `a_pp ← a_pp − t a_pq`, `a_qq ← a_qq + t a_pq`
//! and, `r` the third index, `a_rp ← c a_rp − s a_rq`,
//! `a_rq ← s a_rp + c a_rq` (Rutishauser's updates: the diagonal moves by
//! `t a_pq` alone); the eigenvectors accumulate as `V ← V J`. Sweeps over the
//! three pairs repeat until every off-diagonal entry is negligible beside
//! its diagonal ones (`|a_pq| ≤ ε (|a_pp| + |a_qq|) / 4`, Jacobi's
//! high relative accuracy) or is exactly zero; Jacobi converges
//! quadratically, in 3–5 sweeps in double precision.
//!
//! Why by hand and not nalgebra's `SymmetricEigen` (the library's general
//! solver, used before): with it the Ogden plate's Newton iterations
//! stalled at residuals of 2e-9..3e-8 and its answer moved by 2.3e-9 with
//! the thread count; with Jacobi's high relative accuracy they reach 1e-14
//! and agree to 1.2e-15 (BENCHMARKS.md, issue 13 items 3 and 4, second
//! round), and the stack-only kernel is cheaper.

use nalgebra::{Matrix3, Vector3};

/// Most sweeps: far beyond the quadratic convergence's need.
const MAX_SWEEPS: usize = 32;

/// Above this `|τ|` a rotation is `t = 1/(2τ)`, `c = 1`: then
/// `√(1 + τ²) = |τ| (1 + 1/(2τ²) + …)` and `1/√(1 + t²)` differ from `|τ|`
/// and 1 by less than `1/(2τ²) < ε/2`, so the general formula would give
/// the same numbers to rounding. The last sweeps of Jacobi's quadratic
/// convergence are such tiny rotations.
const SMALL_ANGLE_TAU: f64 = 1e8;

/// Eigenvalues (unsorted) and orthonormal eigenvectors (the columns, in
/// the same order) of the symmetric `a` (its upper triangle is read).
pub fn symmetric_eigen(a: &Matrix3<f64>) -> (Vector3<f64>, Matrix3<f64>) {
    let mut m = [
        [a[(0, 0)], a[(0, 1)], a[(0, 2)]],
        [a[(0, 1)], a[(1, 1)], a[(1, 2)]],
        [a[(0, 2)], a[(1, 2)], a[(2, 2)]],
    ];
    let mut v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    for _ in 0..MAX_SWEEPS {
        let mut rotated = false;
        for (p, q) in [(0, 1), (0, 2), (1, 2)] {
            let apq = m[p][q];
            if apq == 0.0 || apq.abs() <= 0.25 * f64::EPSILON * (m[p][p].abs() + m[q][q].abs()) {
                continue;
            }
            rotated = true;
            let tau = (m[q][q] - m[p][p]) / (2.0 * apq);
            let (t, c) = if tau.abs() > SMALL_ANGLE_TAU {
                // t = 1/(2τ) and c = 1 to rounding: no square roots
                (0.5 / tau, 1.0)
            } else {
                let t = tau.signum() / (tau.abs() + (1.0 + tau * tau).sqrt());
                (t, 1.0 / (1.0 + t * t).sqrt())
            };
            let s = t * c;
            // A ← Jᵀ A J: of rows and columns p, q only the diagonal (by
            // the rotation's defining `a_pq' = 0`) and the third index r's
            // entries change
            let r = 3 - p - q;
            let (arp, arq) = (m[r][p], m[r][q]);
            m[p][p] -= t * apq;
            m[q][q] += t * apq;
            m[p][q] = 0.0;
            m[q][p] = 0.0;
            m[r][p] = c * arp - s * arq;
            m[p][r] = m[r][p];
            m[r][q] = s * arp + c * arq;
            m[q][r] = m[r][q];
            // V ← V J
            for row in &mut v {
                let (vp, vq) = (row[p], row[q]);
                row[p] = c * vp - s * vq;
                row[q] = s * vp + c * vq;
            }
        }
        if !rotated {
            break;
        }
    }
    (
        Vector3::new(m[0][0], m[1][1], m[2][2]),
        Matrix3::new(
            v[0][0], v[0][1], v[0][2], v[1][0], v[1][1], v[1][2], v[2][0], v[2][1], v[2][2],
        ),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::check;

    /// `V diag(c) Vᵀ = A` and `VᵀV = I` to a few ulps, and the eigenvalues
    /// those of nalgebra's solver (sorted) to 1e-14 of the largest, for the
    /// right Cauchy–Green tensors of the material checks' deformations
    /// (identity, equal and nearly equal stretches, rotations, shear) and
    /// a matrix with a large spread.
    #[test]
    fn decomposes_the_right_cauchy_green_tensors() {
        let mut matrices: Vec<Matrix3<f64>> = check::deformations()
            .into_iter()
            .map(|(_, f)| f.transpose() * f)
            .collect();
        matrices.push(Matrix3::new(1e6, 1.0, 2.0, 1.0, 3.0, 1e-3, 2.0, 1e-3, 1e-4));
        for a in matrices {
            let (c, v) = symmetric_eigen(&a);
            let scale = a.amax();
            let back = v * Matrix3::from_diagonal(&c) * v.transpose();
            assert!((back - a).amax() <= 1e-14 * scale, "{a}: {back}");
            assert!((v.transpose() * v - Matrix3::identity()).amax() <= 1e-14);
            let mut ours: Vec<f64> = c.iter().copied().collect();
            let mut theirs: Vec<f64> = a.symmetric_eigenvalues().iter().copied().collect();
            ours.sort_by(f64::total_cmp);
            theirs.sort_by(f64::total_cmp);
            for (x, y) in ours.iter().zip(&theirs) {
                assert!((x - y).abs() <= 1e-14 * scale, "{ours:?} vs {theirs:?}");
            }
        }
    }

    /// A diagonal matrix is its own decomposition (no rotation at all).
    #[test]
    fn a_diagonal_matrix_is_returned_as_it_is() {
        let a = Matrix3::from_diagonal(&Vector3::new(1.2, 1.2, 0.9));
        let (c, v) = symmetric_eigen(&a);
        assert_eq!(c, Vector3::new(1.2, 1.2, 0.9));
        assert_eq!(v, Matrix3::identity());
    }
}
