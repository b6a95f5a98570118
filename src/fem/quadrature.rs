//! Gauss quadrature rules on the reference cells: points and weights whose
//! sum is the reference measure (tetrahedron 1/6, hexahedron 8, triangle
//! 1/2, quadrilateral 4).

/// Gauss–Legendre points and weights on [−1, 1] with `n` points (1‥3).
pub fn gauss_legendre(n: usize) -> (Vec<f64>, Vec<f64>) {
    match n {
        1 => (vec![0.0], vec![2.0]),
        2 => {
            let a = 1.0 / 3f64.sqrt();
            (vec![-a, a], vec![1.0, 1.0])
        }
        3 => {
            let a = (3.0f64 / 5.0).sqrt();
            (vec![-a, 0.0, a], vec![5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0])
        }
        #[allow(clippy::panic)] // the rules are chosen in code (per element kind), not by input
        _ => panic!("gauss_legendre: {n} points not tabulated (1‥3)"),
    }
}

/// Tensor-product Gauss rule with `n` points per direction on [−1, 1]³.
pub fn hexahedron(n: usize) -> (Vec<[f64; 3]>, Vec<f64>) {
    let (x, w) = gauss_legendre(n);
    let mut points = Vec::new();
    let mut weights = Vec::new();
    for k in 0..n {
        for j in 0..n {
            for i in 0..n {
                points.push([x[i], x[j], x[k]]);
                weights.push(w[i] * w[j] * w[k]);
            }
        }
    }
    (points, weights)
}

/// Tensor-product Gauss rule with `n` points per direction on [−1, 1]².
pub fn quadrilateral(n: usize) -> (Vec<[f64; 2]>, Vec<f64>) {
    square(gauss_legendre(n))
}

/// The tensor product on [−1, 1]² of a rule `(x, w)` on [−1, 1]: points
/// `(x_i, x_j)`, `i` fastest, weights `w_i w_j`.
fn square((x, w): (Vec<f64>, Vec<f64>)) -> (Vec<[f64; 2]>, Vec<f64>) {
    let mut points = Vec::with_capacity(x.len() * x.len());
    let mut weights = Vec::with_capacity(x.len() * x.len());
    for (xj, wj) in x.iter().zip(&w) {
        for (xi, wi) in x.iter().zip(&w) {
            points.push([*xi, *xj]);
            weights.push(wi * wj);
        }
    }
    (points, weights)
}

/// Symmetric rules on the unit tetrahedron: 1 point (degree 1) or 4 points
/// (degree 2).
pub fn tetrahedron(n: usize) -> (Vec<[f64; 3]>, Vec<f64>) {
    match n {
        1 => (vec![[0.25; 3]], vec![1.0 / 6.0]),
        4 => {
            let a = 0.585_410_196_624_968_5;
            let b = 0.138_196_601_125_010_5;
            (
                vec![[b, b, b], [a, b, b], [b, a, b], [b, b, a]],
                vec![1.0 / 24.0; 4],
            )
        }
        #[allow(clippy::panic)] // the rules are chosen in code (per element kind), not by input
        _ => panic!("tetrahedron rule with {n} points not tabulated (1, 4)"),
    }
}

/// Symmetric rules on the unit triangle: 1 point (degree 1), 3 points
/// (degree 2) or 6 points (degree 4, Dunavant 1985, table 4).
pub fn triangle(n: usize) -> (Vec<[f64; 2]>, Vec<f64>) {
    match n {
        1 => (vec![[1.0 / 3.0; 2]], vec![0.5]),
        3 => (
            vec![
                [1.0 / 6.0, 1.0 / 6.0],
                [2.0 / 3.0, 1.0 / 6.0],
                [1.0 / 6.0, 2.0 / 3.0],
            ],
            vec![1.0 / 6.0; 3],
        ),
        6 => {
            let (a, wa) = (0.445_948_490_915_965, 0.223_381_589_678_011);
            let (b, wb) = (0.091_576_213_509_771, 0.109_951_743_655_322);
            let mut points = Vec::new();
            let mut weights = Vec::new();
            for (c, w) in [(a, wa), (b, wb)] {
                let d = 1.0 - 2.0 * c;
                points.extend([[c, c], [d, c], [c, d]]);
                weights.extend([0.5 * w; 3]);
            }
            (points, weights)
        }
        #[allow(clippy::panic)] // the rules are chosen in code (per element kind), not by input
        _ => panic!("triangle rule with {n} points not tabulated (1, 3, 6)"),
    }
}

/// The product of the triangle rule of `triangle_points` points and the
/// Gauss–Legendre rule of `line_points` on the wedge
/// `{ξ, η ≥ 0, ξ + η ≤ 1} × [−1, 1]` (measure 1).
pub fn wedge(triangle_points: usize, line_points: usize) -> (Vec<[f64; 3]>, Vec<f64>) {
    let (tp, tw) = triangle(triangle_points);
    let (lp, lw) = gauss_legendre(line_points);
    let mut points = Vec::new();
    let mut weights = Vec::new();
    for (z, wz) in lp.iter().zip(&lw) {
        for (p, w) in tp.iter().zip(&tw) {
            points.push([p[0], p[1], *z]);
            weights.push(w * wz);
        }
    }
    (points, weights)
}

/// Gauss–Legendre points and weights on [−1, 1] for any `n ≥ 1`, exact for
/// polynomials of degree `2n − 1`: the roots `x_i` of the Legendre
/// polynomial `P_n` by Newton's method from `cos(π (i + ¾)/(n + ½))`, and
/// `w_i = 2 / ((1 − x_i²) P_n′(x_i)²)`.
pub fn gauss_legendre_any(n: usize) -> (Vec<f64>, Vec<f64>) {
    let n = n.max(1);
    let mut points = vec![0.0; n];
    let mut weights = vec![0.0; n];
    for i in 0..n {
        let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut derivative = 1.0;
        for _ in 0..100 {
            let (p, dp) = legendre_with_derivative(n, x);
            derivative = dp;
            let step = p / dp;
            x -= step;
            if step.abs() < 1e-16 {
                derivative = legendre_with_derivative(n, x).1;
                break;
            }
        }
        points[n - 1 - i] = x;
        weights[n - 1 - i] = 2.0 / ((1.0 - x * x) * derivative * derivative);
    }
    (points, weights)
}

/// `P_n(x)` and `P_n′(x)` by the three-term recurrence
/// `k P_k = (2k − 1) x P_{k−1} − (k − 1) P_{k−2}`,
/// `P_n′ = n (x P_n − P_{n−1}) / (x² − 1)`.
fn legendre_with_derivative(n: usize, x: f64) -> (f64, f64) {
    let (mut p_prev, mut p) = (1.0, x);
    for k in 2..=n {
        let k = k as f64;
        let next = ((2.0 * k - 1.0) * x * p - (k - 1.0) * p_prev) / k;
        p_prev = p;
        p = next;
    }
    (p, n as f64 * (x * p - p_prev) / (x * x - 1.0))
}

/// Collapsed (Duffy/Stroud conical-product) rule on the unit triangle with
/// `n × n` points: `ξ = u`, `η = (1 − u) v` with `u, v` Gauss–Legendre on
/// [0, 1] and weight `w_u w_v (1 − u)`; exact for total degree `2n − 2`.
/// The weights sum to ½.
pub fn triangle_collapsed(n: usize) -> (Vec<[f64; 2]>, Vec<f64>) {
    let (x, w) = gauss_legendre_any(n);
    let mut points = Vec::with_capacity(x.len() * x.len());
    let mut weights = Vec::with_capacity(x.len() * x.len());
    for (xu, wu) in x.iter().zip(&w) {
        let u = 0.5 * (1.0 + xu);
        for (xv, wv) in x.iter().zip(&w) {
            let v = 0.5 * (1.0 + xv);
            points.push([u, (1.0 - u) * v]);
            weights.push(0.25 * wu * wv * (1.0 - u));
        }
    }
    (points, weights)
}

/// Tensor-product Gauss–Legendre rule with `n` points per direction on
/// [−1, 1]² for any `n ≥ 1` (exact to degree `2n − 1` per direction).
pub fn quadrilateral_any(n: usize) -> (Vec<[f64; 2]>, Vec<f64>) {
    square(gauss_legendre_any(n))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `∫ ξ^i η^j dA = i! j! / (i + j + 2)!` on the unit triangle, for
    /// every `i + j ≤ 4` by the 6-point rule.
    #[test]
    fn six_point_triangle_rule_is_of_degree_four() {
        let fact = |n: u32| (1..=n).product::<u32>() as f64;
        let (p, w) = triangle(6);
        for i in 0..=4u32 {
            for j in 0..=(4 - i) {
                let q: f64 = p
                    .iter()
                    .zip(&w)
                    .map(|(x, w)| w * x[0].powi(i as i32) * x[1].powi(j as i32))
                    .sum();
                let exact = fact(i) * fact(j) / fact(i + j + 2);
                assert!((q - exact).abs() < 1e-14, "ξ^{i} η^{j}: {q} vs {exact}");
            }
        }
    }
}
