//! Restarted GMRES with right preconditioning (Saad, *Iterative Methods for
//! Sparse Linear Systems*, 2nd ed., Algorithm 9.5), for the nonsymmetric
//! tangents of follower loads and friction: the preconditioner is an LDLᵀ
//! close to the tangent (of its symmetric part for follower loads; with
//! friction, of the stick preconditioner of
//! `ContactInterface::shift_to_stick_preconditioner`), so the Krylov method
//! only has to resolve a small remainder and converges in a few iterations.

/// Outcome of a GMRES solve.
#[derive(Clone, Copy, Debug)]
pub struct GmresReport {
    /// `‖b − A x‖ / ‖b‖` at the end (recomputed, not estimated).
    pub relative_residual: f64,
    /// Matrix–vector products used.
    pub iterations: usize,
}

/// Solve `A x = b` starting from `x`, with `A` given by `apply` (`y = A v`)
/// and the preconditioner `M⁻¹` by `precondition` (in place). Restarts every
/// `restart` iterations; stops at `tolerance` relative residual or after
/// `max_iterations` products.
pub fn gmres<E>(
    mut apply: impl FnMut(&[f64], &mut [f64]),
    mut precondition: impl FnMut(&mut [f64]) -> Result<(), E>,
    b: &[f64],
    x: &mut [f64],
    tolerance: f64,
    restart: usize,
    max_iterations: usize,
) -> Result<GmresReport, E> {
    let n = b.len();
    let b_norm = norm(b).max(f64::MIN_POSITIVE);
    let mut r = vec![0.0; n];
    let mut w = vec![0.0; n];
    let mut iterations = 0;
    loop {
        // r = b − A x
        apply(x, &mut w);
        for i in 0..n {
            r[i] = b[i] - w[i];
        }
        let beta = norm(&r);
        if beta / b_norm <= tolerance || iterations >= max_iterations {
            return Ok(GmresReport {
                relative_residual: beta / b_norm,
                iterations,
            });
        }
        let m = restart.min(max_iterations - iterations).max(1);
        let mut v: Vec<Vec<f64>> = vec![r.iter().map(|ri| ri / beta).collect()];
        let mut h = vec![vec![0.0; m]; m + 1];
        let (mut cs, mut sn) = (vec![0.0; m], vec![0.0; m]);
        let mut g = vec![0.0; m + 1];
        g[0] = beta;
        let mut k = 0;
        for j in 0..m {
            // w = A M⁻¹ v_j
            let mut z = v[j].clone();
            precondition(&mut z)?;
            apply(&z, &mut w);
            iterations += 1;
            // modified Gram–Schmidt
            for (i, vi) in v.iter().enumerate() {
                let hij = dot(&w, vi);
                h[i][j] = hij;
                for (wl, vl) in w.iter_mut().zip(vi) {
                    *wl -= hij * vl;
                }
            }
            let h_next = norm(&w);
            h[j + 1][j] = h_next;
            // previous Givens rotations on the new column, then a new one
            for i in 0..j {
                let (a, c) = (h[i][j], h[i + 1][j]);
                h[i][j] = cs[i] * a + sn[i] * c;
                h[i + 1][j] = -sn[i] * a + cs[i] * c;
            }
            let rho = h[j][j].hypot(h[j + 1][j]);
            if rho == 0.0 {
                k = j;
                break;
            }
            cs[j] = h[j][j] / rho;
            sn[j] = h[j + 1][j] / rho;
            h[j][j] = rho;
            h[j + 1][j] = 0.0;
            g[j + 1] = -sn[j] * g[j];
            g[j] *= cs[j];
            k = j + 1;
            if g[j + 1].abs() / b_norm <= tolerance || h_next == 0.0 {
                break;
            }
            v.push(w.iter().map(|wl| wl / h_next).collect());
        }
        // y = H⁻¹ g (upper triangular), x += M⁻¹ (V y)
        let mut y = vec![0.0; k];
        for i in (0..k).rev() {
            let s: f64 = (i + 1..k).map(|l| h[i][l] * y[l]).sum();
            y[i] = (g[i] - s) / h[i][i];
        }
        let mut update = vec![0.0; n];
        for (yi, vi) in y.iter().zip(&v) {
            for (ul, vl) in update.iter_mut().zip(vi) {
                *ul += yi * vl;
            }
        }
        precondition(&mut update)?;
        for (xi, ui) in x.iter_mut().zip(&update) {
            *xi += ui;
        }
        if k == 0 {
            // breakdown with no progress: report the residual as it is
            apply(x, &mut w);
            let res: f64 = b
                .iter()
                .zip(&w)
                .map(|(bi, wi)| (bi - wi).powi(2))
                .sum::<f64>()
                .sqrt();
            return Ok(GmresReport {
                relative_residual: res / b_norm,
                iterations,
            });
        }
    }
}

/// `a · b`.
pub fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// `‖a‖₂`.
pub fn norm(a: &[f64]) -> f64 {
    dot(a, a).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A nonsymmetric tridiagonal system, preconditioned by the inverse of
    /// its symmetric part's diagonal, is solved to the tolerance; without
    /// restarts it takes at most n iterations (exact arithmetic bound).
    #[test]
    fn solves_a_nonsymmetric_system() {
        let n = 40;
        let apply = |v: &[f64], y: &mut [f64]| {
            for i in 0..n {
                let mut s = 4.0 * v[i];
                if i > 0 {
                    s += -1.5 * v[i - 1];
                }
                if i + 1 < n {
                    s += -0.5 * v[i + 1];
                }
                y[i] = s;
            }
        };
        let x_true: Vec<f64> = (0..n).map(|i| (i as f64 * 0.3).cos()).collect();
        let mut b = vec![0.0; n];
        apply(&x_true, &mut b);
        for restart in [n, 7] {
            let mut x = vec![0.0; n];
            let report = gmres(
                apply,
                |z: &mut [f64]| -> Result<(), ()> {
                    z.iter_mut().for_each(|v| *v /= 4.0);
                    Ok(())
                },
                &b,
                &mut x,
                1e-12,
                restart,
                400,
            )
            .unwrap();
            assert!(report.relative_residual <= 1e-12, "{report:?}");
            for i in 0..n {
                assert!((x[i] - x_true[i]).abs() < 1e-10);
            }
        }
    }
}
