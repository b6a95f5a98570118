//! The signed distance to a sphere or a cylinder, `g = |r| − R`, without
//! the cancellation of the naive formula.
//!
//! ## Why
//! Near contact `|r| ≈ R`, and `r = x − c` is formed from coordinates of
//! the size of the obstacle: a sphere of radius 100 under a block at
//! `z ≈ 0` has `c_z = −100`, so `x_z − c_z` is rounded to `ulp(100)/2 ≈
//! 7e-15`, and `|r| − R` inherits it whatever follows. Every contact row
//! then carries an error `p A_s δg` (`p` the normal penalty): on
//! examples/press-pull pressed on a sphere of `R = 100` (221 nodes, `p ≈
//! 1e4`) Newton converged quadratically down to a relative residual of
//! about 2e-11 and then stood still there, whatever the increment (the
//! floor measured in BENCHMARKS.md, session 17).
//!
//! ## How
//! `r` is kept exactly as an unevaluated sum `r_hi + r_lo` (Knuth's
//! TwoSum, [`two_difference`]), the squares as `p + e` with `e` from a
//! fused multiply–add (Dekker's TwoProduct, [`two_product`]), and
//! ```text
//! s = |r|² − R² = Σ_i (r_hi,i² + 2 r_hi,i r_lo,i) − R²     (compensated sum)
//! g = s / (|r| + R)
//! ```
//! so `g` is correct to a few roundings of `g` itself (Ogita, Rump &
//! Oishi, *Accurate sum and dot product*, SIAM J. Sci. Comput. 26 (2005)
//! 1955–1988, for the error-free transformations). The cylinder takes
//! `r⊥ = w − a (a·w)`, `w = x − p`, in the same form; `(a·w)` itself
//! needs no care, since `|r⊥|²` is stationary under a change of `r⊥`
//! along the axis.

use nalgebra::Vector3;

/// `a − b = hi + lo` exactly (Knuth's TwoSum of `a` and `−b`).
fn two_difference(a: f64, b: f64) -> (f64, f64) {
    let hi = a - b;
    let b_virtual = hi - a;
    let lo = (a - (hi - b_virtual)) + (-b - b_virtual);
    (hi, lo)
}

/// `a b = p + e` exactly (Dekker's TwoProduct, by a fused multiply–add).
fn two_product(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    (p, a.mul_add(b, -p))
}

/// A vector as the unevaluated sum `hi + lo` of two vectors, `|lo|` below
/// an ulp of `|hi|`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ExactVector {
    pub hi: Vector3<f64>,
    pub lo: Vector3<f64>,
}

impl ExactVector {
    /// `x − c`, exactly.
    pub fn difference(x: &Vector3<f64>, c: &Vector3<f64>) -> Self {
        let mut v = Self {
            hi: Vector3::zeros(),
            lo: Vector3::zeros(),
        };
        for i in 0..3 {
            (v.hi[i], v.lo[i]) = two_difference(x[i], c[i]);
        }
        v
    }

    /// `r − a (a·r)` for a unit `a`: the part across the axis `a`, to an
    /// ulp along `a` (which does not change `|r⊥|²` to first order).
    pub fn across(&self, a: &Vector3<f64>) -> Self {
        let along = a.dot(&(self.hi + self.lo));
        let mut v = *self;
        for i in 0..3 {
            let (q, q_lo) = two_product(a[i], along);
            let (hi, lo) = two_difference(self.hi[i], q);
            v.hi[i] = hi;
            v.lo[i] = lo + self.lo[i] - q_lo;
        }
        v
    }

    /// `|r| − R` to a few roundings of the result (module docs).
    pub fn distance_minus(&self, radius: f64) -> f64 {
        let mut terms = [0.0; 11];
        for i in 0..3 {
            let (p, e) = two_product(self.hi[i], self.hi[i]);
            terms[3 * i] = p;
            terms[3 * i + 1] = e;
            terms[3 * i + 2] = 2.0 * self.hi[i] * self.lo[i];
        }
        let (p, e) = two_product(radius, radius);
        terms[9] = -p;
        terms[10] = -e;
        compensated_sum(&terms) / (self.hi.norm() + radius)
    }
}

/// `Σ terms`, compensated (Neumaier's variant of Kahan's sum): the error
/// is a few roundings of the result plus `O(n u²) Σ|terms|`.
fn compensated_sum(terms: &[f64]) -> f64 {
    let (mut sum, mut correction) = (0.0_f64, 0.0_f64);
    for &t in terms {
        let s = sum + t;
        correction += if sum.abs() >= t.abs() {
            (sum - s) + t
        } else {
            (t - s) + sum
        };
        sum = s;
    }
    sum + correction
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_difference_is_exact() {
        for (a, b) in [(100.0, -1e-3), (0.1, 0.3), (1e16, -1.0), (3.0, 3.0)] {
            let (hi, lo) = two_difference(a, b);
            assert_eq!(hi, a - b);
            // hi + lo = a − b in exact arithmetic: checked on a pair whose
            // difference is known, below; here the classic identity
            assert!(lo.abs() <= f64::EPSILON * hi.abs());
        }
        // 100 − (−1e-3 − 2⁻⁶⁰): hi rounds, lo keeps what it lost
        let (hi, lo) = two_difference(1e-3, -100.0);
        let exact_tail = 1e-3 - (hi - 100.0);
        assert_eq!(lo, exact_tail);
    }

    /// On a sphere of radius 100 whose centre is 100 below the origin, a
    /// point a hair above its top: the exact gap is the point's `z`, which
    /// the naive `|x − c| − R` misses by up to an ulp of 100 (7e-15), and
    /// the compensated one meets to a few roundings of `z`.
    #[test]
    fn gap_above_a_large_sphere_is_exact() {
        let c = Vector3::new(2.0, 0.0, -100.0);
        let mut naive_worst = 0.0_f64;
        for k in 1..200 {
            let z = 1.234_567e-9 * k as f64 - 1e-7;
            let x = Vector3::new(2.0, 0.0, z);
            let g = ExactVector::difference(&x, &c).distance_minus(100.0);
            assert!((g - z).abs() <= 4.0 * f64::EPSILON * z.abs(), "{g} vs {z}");
            naive_worst = naive_worst.max(((x - c).norm() - 100.0 - z).abs());
        }
        assert!(naive_worst > 1e-15, "naive error {naive_worst:e}");
    }

    /// Off the pole, a point `(60 + e₁, 80 + e₂, e₃)` about a sphere of
    /// radius 100 at the origin (the triple 60, 80, 100), the `e` dyadic so
    /// that `s = 120 e₁ + 160 e₂ + e₁² + e₂² + e₃²` is exact: the gap
    /// `s/(|r| + R)` to 4 roundings; the naive one is off by 1e-15.
    #[test]
    fn gap_off_the_pole_is_exact() {
        let c = Vector3::new(0.0, 0.0, 0.0);
        let (e1, e2, e3) = (2f64.powi(-33), -(2f64.powi(-35)), 2f64.powi(-30));
        let x = Vector3::new(60.0 + e1, 80.0 + e2, e3);
        let s = (120.0 * e1 + 160.0 * e2) + (e1 * e1 + e2 * e2 + e3 * e3);
        let expected = s / (x.norm() + 100.0);
        let g = ExactVector::difference(&x, &c).distance_minus(100.0);
        assert!((g - expected).abs() <= 4.0 * f64::EPSILON * expected.abs());
        // the same point and centre moved by −1000 along z (exactly:
        // the e are multiples of ulp(1000)): the same gap
        let shift = Vector3::new(0.0, 0.0, -1000.0);
        let moved = ExactVector::difference(&(x + shift), &(c + shift)).distance_minus(100.0);
        assert!((moved - expected).abs() <= 4.0 * f64::EPSILON * expected.abs());
        let naive = ((x + shift) - (c + shift)).norm() - 100.0;
        assert!(
            (naive - expected).abs() > 1e-15,
            "naive {naive:e} vs {expected:e}"
        );
    }

    /// A cylinder of radius 100 along `a = (1, 1, 0)/√2` through
    /// `(0, 0, −100)`: a point above its top line at height `z` has gap
    /// `z`, wherever it lies along the axis.
    #[test]
    fn gap_above_a_large_cylinder_is_exact() {
        let a = Vector3::new(1.0, 1.0, 0.0).normalize();
        let p = Vector3::new(0.0, 0.0, -100.0);
        for (along, z) in [(0.3, 3.3e-9), (-7.0, -2.2e-8), (40.0, 1e-12)] {
            let x = a * along + Vector3::new(0.0, 0.0, z);
            let r = ExactVector::difference(&x, &p).across(&a);
            let g = r.distance_minus(100.0);
            assert!(
                (g - z).abs() <= 8.0 * f64::EPSILON * z.abs() + 1e-25,
                "{g} vs {z}"
            );
        }
    }
}
