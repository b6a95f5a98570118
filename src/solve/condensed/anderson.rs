//! Anderson acceleration of a fixed point `x = F(x)` (Anderson 1965;
//! Walker and Ni, "Anderson acceleration for fixed-point iterations",
//! SIAM J. Numer. Anal. 49, 2011, type II): from the last iterate `x_k`,
//! its residual `f_k = F(x_k) − x_k` and the differences of the last `m`
//! iterates and residuals (`ΔX`, `ΔF`),
//!
//! ```text
//! γ = argmin ‖f_k − ΔF γ‖₂,    x_{k+1} = x_k + f_k − (ΔX + ΔF) γ.
//! ```
//!
//! On a linear contraction `F(x) = A x + b` of dimension `d ≤ m` it reaches
//! the fixed point in at most `d + 1` steps (a Krylov method, GMRES on
//! `(I − A) x = b`); plain iteration gains `−log₁₀ ρ(A)` digits a step.

use nalgebra::{DMatrix, DVector};

/// The last iterates and residuals of a fixed-point iteration, at most
/// `depth` differences of them.
pub struct Anderson {
    depth: usize,
    /// `(x_i, f_i)`, oldest first, at most `depth + 1`.
    history: Vec<(Vec<f64>, Vec<f64>)>,
}

impl Anderson {
    pub fn new(depth: usize) -> Self {
        Anderson {
            depth,
            history: Vec::new(),
        }
    }

    /// Forget the iterates (the map changed: a new active set).
    pub fn reset(&mut self) {
        self.history.clear();
    }

    /// The next iterate from `x` and its image `fx = F(x)`: the plain
    /// step `F(x)` while no difference is kept, else the mixed one (the
    /// plain step, and the history forgotten, where the least-squares
    /// problem is singular).
    pub fn next(&mut self, x: &[f64], fx: &[f64]) -> Vec<f64> {
        let f: Vec<f64> = fx.iter().zip(x).map(|(a, b)| a - b).collect();
        self.history.push((x.to_vec(), f));
        if self.history.len() > self.depth + 1 {
            self.history.remove(0);
        }
        let m = self.history.len() - 1;
        if m == 0 {
            return fx.to_vec();
        }
        let (xk, fk) = &self.history[m];
        let n = xk.len();
        let dx = DMatrix::from_fn(n, m, |r, c| self.history[c + 1].0[r] - self.history[c].0[r]);
        let df = DMatrix::from_fn(n, m, |r, c| self.history[c + 1].1[r] - self.history[c].1[r]);
        let gram = df.transpose() * &df;
        let rhs = df.transpose() * DVector::from_column_slice(fk);
        let Some(gamma) = gram.cholesky().map(|c| c.solve(&rhs)) else {
            self.history.drain(..m);
            return fx.to_vec();
        };
        let correction = (dx + df) * gamma;
        (0..n).map(|r| xk[r] + fk[r] - correction[r]).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `F(x) = A x + b` on 3 unknowns, `A` a contraction of spectral
    /// radius ≈ 0.8 (plain iteration: about 120 steps to 1e-12): with
    /// depth 3 the iterates reach the fixed point `x* = (I − A)⁻¹ b` to
    /// 1e-12 in at most 5 steps.
    #[test]
    fn a_linear_contraction_is_solved_in_dimension_plus_one_steps() {
        let a = [[0.5, 0.2, 0.1], [0.1, 0.6, 0.1], [0.05, 0.1, 0.5]];
        let b = [1.0, -2.0, 0.5];
        let map = |x: &[f64]| -> Vec<f64> {
            (0..3)
                .map(|i| (0..3).map(|j| a[i][j] * x[j]).sum::<f64>() + b[i])
                .collect()
        };
        let i_minus_a = nalgebra::Matrix3::from_fn(|i, j| f64::from(u8::from(i == j)) - a[i][j]);
        let fixed = i_minus_a.lu().solve(&nalgebra::Vector3::from(b)).unwrap();
        let mut anderson = Anderson::new(3);
        let mut x = vec![0.0; 3];
        let mut steps = 0;
        while (0..3).map(|i| (x[i] - fixed[i]).abs()).fold(0.0, f64::max) > 1e-12 {
            let fx = map(&x);
            x = anderson.next(&x, &fx);
            steps += 1;
            assert!(steps <= 5, "{steps} steps: {x:?} against {fixed:?}");
        }
        // plain iteration is far slower
        let mut y = vec![0.0; 3];
        for _ in 0..5 {
            y = map(&y);
        }
        assert!((y[0] - fixed[0]).abs() > 1e-3);
    }
}
