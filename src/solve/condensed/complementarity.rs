//! The linear complementarity problem of frictionless contact on a
//! condensed, dense, symmetric positive definite matrix: find `λ ∈ ℝᵐ` with
//!
//! ```text
//! g = q + W λ,   λ ≥ 0,   g ≥ 0,   λᵢ gᵢ = 0   (i = 1‥m)
//! ```
//!
//! (`λ` the contact forces, `g` the gaps, `W = Eᵀ K⁻¹ E` the flexibility of
//! the contact nodes), solved exactly by block principal pivoting
//! (Júdice & Pires 1994; Kim & Park 2011 for NNLS): a guess of the active
//! set `A` (where `g = 0`) gives `λ_A = −W_AA⁻¹ q_A` by a dense Cholesky,
//! `λ_I = 0` elsewhere; every index that violates `λ ≥ 0` in `A` or `g ≥ 0`
//! outside it changes sides at once while the number of violations falls
//! (the primal–dual active-set step, Hintermüller–Ito–Kunisch 2002), and
//! after three steps without progress only the largest violating index
//! changes (Murty's rule, finite for a positive definite `W`). The answer
//! is exact up to round-off: `g_A = 0`, `λ_I = 0`.

use crate::solve::record::IterationRecord;
use nalgebra::DMatrix;

/// Steps without a smaller number of violations before the single-index
/// (Murty) rule takes over.
const BACKUP_STEPS: usize = 3;

/// The solution of one complementarity problem.
#[derive(Clone, Debug, PartialEq)]
pub struct Complementarity {
    /// `λ ≥ 0`.
    pub lambda: Vec<f64>,
    /// `g = q + W λ` (exactly 0 on the active set).
    pub gap: Vec<f64>,
    /// The active set (`g = 0`, `λ ≥ 0`).
    pub active: Vec<bool>,
    /// Active-set steps (dense Cholesky solves).
    pub iterations: usize,
    /// Per step, as reported to the user ([`crate::solve::method`]): the
    /// largest violation in force units relative to the force scale `F`,
    /// `max(max_{i∈A} ⟨−λ_i⟩, max_{i∉A} ⟨−g_i⟩ / W_ii) / F`, with
    /// `F = max(max λ, max ⟨−q_i⟩ / W_ii)` (the force that closes the
    /// deepest penetration alone); the change `|Δλ|∞ / F` from the last
    /// step (from `λ = 0` at the first; at least ε: a solve was taken);
    /// the statuses flipped.
    pub history: Vec<IterationRecord>,
}

/// Solve `g = q + W λ ≥ 0 ⊥ λ ≥ 0` for a symmetric positive definite `W`
/// (m × m), starting from the active set `guess` (all open when empty;
/// the previous increment's is a good one). A violation is a `λᵢ` below
/// `−tolerance_lambda` or a `gᵢ` below `−tolerance_gap`. Errors when a
/// principal block of `W` is not positive definite.
pub fn solve_lcp(
    w: &DMatrix<f64>,
    q: &[f64],
    guess: &[bool],
    tolerance_gap: f64,
    tolerance_lambda: f64,
) -> Result<Complementarity, String> {
    let m = q.len();
    let mut active: Vec<bool> = if guess.len() == m {
        guess.to_vec()
    } else {
        q.iter().map(|&qi| qi < 0.0).collect()
    };
    let (mut best, mut backup) = (usize::MAX, BACKUP_STEPS);
    // Murty's rule ends in at most 2^m steps; block steps end far sooner
    let limit = 50 + 10 * m;
    let closing = |i: usize, g: f64| (-g).max(0.0) / w[(i, i)];
    let deepest = (0..m).map(|i| closing(i, q[i])).fold(0.0f64, f64::max);
    let mut history = Vec::new();
    let mut last = vec![0.0; m];
    for iteration in 1..=limit {
        let (lambda, gap) = solve_on(w, q, &active)?;
        let violations: Vec<usize> = (0..m)
            .filter(|&i| {
                if active[i] {
                    lambda[i] < -tolerance_lambda
                } else {
                    gap[i] < -tolerance_gap
                }
            })
            .collect();
        let scale = lambda
            .iter()
            .fold(deepest, |s, &l| s.max(l))
            .max(f64::MIN_POSITIVE);
        let violation = (0..m)
            .map(|i| {
                if active[i] {
                    (-lambda[i]).max(0.0)
                } else {
                    closing(i, gap[i])
                }
            })
            .fold(0.0f64, f64::max);
        let change = (0..m)
            .map(|i| (lambda[i] - last[i]).abs())
            .fold(0.0f64, f64::max);
        history.push(IterationRecord {
            residual: violation / scale,
            correction: (change / scale).max(f64::EPSILON),
            step_length: 1.0,
            switched: violations.len(),
            linear: Default::default(),
        });
        last.clone_from(&lambda);
        if violations.is_empty() {
            return Ok(Complementarity {
                lambda: lambda.iter().map(|&l| l.max(0.0)).collect(),
                gap,
                active,
                iterations: iteration,
                history,
            });
        }
        if violations.len() < best {
            best = violations.len();
            backup = BACKUP_STEPS;
            violations.iter().for_each(|&i| active[i] = !active[i]);
        } else if backup > 0 {
            backup -= 1;
            violations.iter().for_each(|&i| active[i] = !active[i]);
        } else if let Some(&i) = violations.last() {
            active[i] = !active[i];
        }
    }
    Err(format!(
        "the contact active set did not settle in {limit} steps"
    ))
}

/// `λ_A = −W_AA⁻¹ q_A`, `λ_I = 0`, and `g = q + W λ` with `g_A = 0` exactly.
/// `W_AA` is factorised by faer's blocked dense Cholesky (on the large race
/// mesh `|A|` ≈ 850 at every step of every defect pass: nalgebra's
/// unblocked one took 6 % of the run).
fn solve_on(w: &DMatrix<f64>, q: &[f64], active: &[bool]) -> Result<(Vec<f64>, Vec<f64>), String> {
    use faer::linalg::solvers::Solve;
    let m = q.len();
    let index: Vec<usize> = (0..m).filter(|&i| active[i]).collect();
    let mut lambda = vec![0.0; m];
    if !index.is_empty() {
        let n = index.len();
        let a = faer::Mat::<f64>::from_fn(n, n, |r, c| w[(index[r], index[c])]);
        let cholesky = a.llt(faer::Side::Lower).map_err(|_| {
            "the condensed contact flexibility W is not positive definite".to_string()
        })?;
        let mut x = faer::Mat::<f64>::from_fn(n, 1, |r, _| -q[index[r]]);
        cholesky.solve_in_place(x.as_mut());
        for (k, &i) in index.iter().enumerate() {
            lambda[i] = x[(k, 0)];
        }
    }
    // g = q + Σ_{j ∈ A} W e_j λ_j, column by column (contiguous in memory)
    let mut gap = q.to_vec();
    for &j in &index {
        let column = w.column(j);
        for (g, wij) in gap.iter_mut().zip(column.iter()) {
            *g += wij * lambda[j];
        }
    }
    index.iter().for_each(|&i| gap[i] = 0.0);
    Ok((lambda, gap))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 3-node LCP with a known answer: `W = [[2, 1, 0], [1, 2, 1], [0, 1,
    /// 2]]`, `q = (−1, 1, −1)`. With nodes 0 and 2 active,
    /// `λ₀ = λ₂ = 1/2` and `g₁ = 1 + ½ + ½ = 2 > 0`: the solution, found from
    /// every starting set, with `g = q + W λ` checked entry by entry.
    #[test]
    fn the_active_set_of_a_small_lcp_is_found_from_any_guess() {
        let w = DMatrix::from_row_slice(3, 3, &[2.0, 1.0, 0.0, 1.0, 2.0, 1.0, 0.0, 1.0, 2.0]);
        let q = [-1.0, 1.0, -1.0];
        for bits in 0..8u32 {
            let guess: Vec<bool> = (0..3).map(|i| bits & (1 << i) != 0).collect();
            let s = solve_lcp(&w, &q, &guess, 1e-14, 1e-14).unwrap();
            assert_eq!(s.active, [true, false, true], "from {guess:?}");
            for (l, e) in s.lambda.iter().zip([0.5, 0.0, 0.5]) {
                assert!((l - e).abs() < 1e-15, "{:?}", s.lambda);
            }
            for i in 0..3 {
                let g = q[i] + (0..3).map(|j| w[(i, j)] * s.lambda[j]).sum::<f64>();
                assert!((g - s.gap[i]).abs() < 1e-15);
            }
            assert!((s.gap[1] - 2.0).abs() < 1e-15);
        }
    }

    /// Random SPD problems (`W = BᵀB + I/10`, 40 nodes): the answer meets
    /// `λ ≥ 0`, `g ≥ 0`, `λᵢ gᵢ = 0` to round-off, and it minimises
    /// `½ λᵀWλ + qᵀλ` over `λ ≥ 0` (no feasible coordinate step lowers it).
    #[test]
    fn random_problems_satisfy_the_complementarity_conditions() {
        let mut seed = 12345u64;
        let mut next = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((seed >> 11) as f64 / (1u64 << 53) as f64) - 0.5
        };
        for _ in 0..20 {
            let m = 40;
            let b = DMatrix::from_fn(m, m, |_, _| next());
            let w = b.transpose() * &b + DMatrix::identity(m, m) * 0.1;
            let q: Vec<f64> = (0..m).map(|_| next()).collect();
            let s = solve_lcp(&w, &q, &[], 1e-13, 1e-13).unwrap();
            for i in 0..m {
                let g = q[i] + (0..m).map(|j| w[(i, j)] * s.lambda[j]).sum::<f64>();
                assert!(
                    s.lambda[i] >= 0.0 && g >= -1e-12,
                    "{i}: {} {g}",
                    s.lambda[i]
                );
                assert!((s.lambda[i] * g).abs() < 1e-12, "{i}");
                // a coordinate step that stays feasible cannot lower the energy
                // (its gradient is g): g_i ≥ 0 and g_i = 0 where λ_i > 0
                if s.lambda[i] > 1e-12 {
                    assert!(g.abs() < 1e-12);
                }
            }
        }
    }
}
