//! The gap of a secondary node against a *deforming* primary triangle, with
//! its exact first and second derivatives with respect to all four nodes
//! (formulation note §4, the paper's eqs. 27–28): the kinematics of
//! node-to-surface contact between two deformable bodies.
//!
//! ## Geometry
//! Secondary node `x_s`, primary triangle `x1, x2, x3` (current positions),
//! unknowns ordered `q = (x_s, x1, x2, x3)` (12 components):
//! ```text
//! a1 = x2 − x1,  a2 = x3 − x1,  c = a1 × a2,  ℓ = |c|,  n = c/ℓ
//! w  = x_s − x1,  g = w·n,  w_t = w − g n = x̄ − x1,  P = I − n nᵀ
//! ```
//! `g` is the signed distance to the triangle's *plane*, positive on the
//! side `n` points to. The caller orients the primary facets so that `n`
//! points out of the primary body, toward the secondary body; then `g ≥ 0`
//! is open and `g < 0` penetration, as everywhere in [`crate::contact`].
//!
//! The projection `x̄ = x_s − g n = Σ N_i x_i` has the barycentric (linear
//! shape function) coordinates `N = (1 − ξ1 − ξ2, ξ1, ξ2)`, where `ξ`
//! solves `M ξ = b` with the metric `M_αβ = a_α·a_β` and `b_α = a_α·w`
//! (`det M = ℓ²`, Lagrange's identity).
//!
//! Every formula is that of the extended plane, valid wherever `ℓ > 0`:
//! for a projection outside the triangle (`min N_i < 0`) `g` is still the
//! distance to the plane, not to the closest point of the triangle
//! ([`super::triangle`]). Deciding which facet a node is paired with, and
//! what to do near edges, is the search's job.
//!
//! ## Derivatives
//! With the constant operators (3×12, one 3×3 block per node of `q`)
//! ```text
//! A1 = ∂a1/∂q = (0, −I, I, 0)       A2 = ∂a2/∂q = (0, −I, 0, I)
//! D  = ∂w/∂q  = (I, −I, 0, 0)       R  = D − ξ1 A1 − ξ2 A2 = (I, −N1 I, −N2 I, −N3 I)
//! C  = ∂c/∂q  = (0, [a2 − a1]×, −[a2]×, [a1]×)         ([v]× u = v × u)
//! ```
//! the first derivatives are
//! ```text
//! ∂n/∂q = P C / ℓ                                        (zero in the x_s columns)
//! ∂g/∂q = Dᵀn + Cᵀw_t/ℓ = (n, −N1 n, −N2 n, −N3 n)       (w_t = ξ1 a1 + ξ2 a2)
//! ∂ξ/∂q = M⁻¹ [ g nᵀA_α + a_αᵀ R ]_(α = 1, 2)            (rows α)
//! ```
//! and, with `W = [w_t]×` and `N' = ∂n/∂q`, the Hessian
//! ```text
//! ∂²g/∂q² = N'ᵀD + DᵀN' + (A2ᵀ W A1 − A1ᵀ W A2)/ℓ
//!         − [ (Cᵀn)(Cᵀw_t)ᵀ + (Cᵀw_t)(Cᵀn)ᵀ ] / ℓ² − g N'ᵀN'
//! ```
//! (`N'ᵀN' = CᵀPC/ℓ²` since `P² = P`). Each term is symmetric; the
//! computed matrix is averaged with its transpose so that it is exactly
//! symmetric in floating point too. The `x_s`–`x_s` block is zero: `g` is linear in `x_s`. A rigid
//! translation of all four nodes leaves `g` unchanged, so the gradient's
//! four blocks and each block row of the Hessian sum to zero.
//!
//! ## Quadrangles
//! [`split_quadrangle`] splits a quadrangle facet (a Hex8 face) into two
//! triangles with its orientation kept (formulation note §4).

use crate::mesh::{Facet, FacetKind};
use nalgebra::{Matrix2, Matrix3, SMatrix, SVector, Vector2, Vector3};

/// A triangle is degenerate when `ℓ = |a1 × a2| ≤ DEGENERACY · (longest edge)²`.
pub const DEGENERACY: f64 = 1e-14;

/// The gap of a secondary node against a primary triangle and its
/// derivatives with respect to `q = (x_s, x1, x2, x3)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TriangleGap {
    /// Signed gap `g = (x_s − x1)·n`: distance to the triangle's plane,
    /// positive on the side `n` points to.
    pub gap: f64,
    /// Unit normal `n = (a1 × a2)/|a1 × a2|`.
    pub normal: Vector3<f64>,
    /// Local coordinates `ξ = (ξ1, ξ2)` of the projection `x̄ = x_s − g n`
    /// (outside `ξ1, ξ2 ≥ 0, ξ1 + ξ2 ≤ 1` the projection is off the triangle).
    pub xi: [f64; 2],
    /// Shape functions at `ξ`: `N = (1 − ξ1 − ξ2, ξ1, ξ2)`, `x̄ = Σ N_i x_i`.
    pub shape: [f64; 3],
    /// `∂g/∂q = (n, −N1 n, −N2 n, −N3 n)`.
    pub gradient: SVector<f64, 12>,
    /// `∂²g/∂q²`, exact and symmetric (see the module documentation).
    pub hessian: SMatrix<f64, 12, 12>,
    /// `∂n/∂q = P C/ℓ` (zero in the `x_s` columns).
    pub normal_gradient: SMatrix<f64, 3, 12>,
    /// `∂ξ/∂q = M⁻¹ [g nᵀA_α + a_αᵀ R]`.
    pub xi_gradient: SMatrix<f64, 2, 12>,
}

/// The 3×12 operator with 3×3 blocks `blocks` for `(x_s, x1, x2, x3)`.
fn block_row(blocks: [Matrix3<f64>; 4]) -> SMatrix<f64, 3, 12> {
    let mut m = SMatrix::<f64, 3, 12>::zeros();
    for (k, b) in blocks.iter().enumerate() {
        m.fixed_view_mut::<3, 3>(0, 3 * k).copy_from(b);
    }
    m
}

/// Whether the triangle `x` is degenerate for [`triangle_gap`]:
/// `|a1 × a2| ≤` [`DEGENERACY`] `· (longest edge)²`, or not finite.
pub fn is_degenerate(x: [&Vector3<f64>; 3]) -> bool {
    let [x1, x2, x3] = x;
    let (a1, a2) = (x2 - x1, x3 - x1);
    let longest2 = a1
        .norm_squared()
        .max(a2.norm_squared())
        .max((x3 - x2).norm_squared());
    // written so that NaN counts as degenerate
    !(a1.cross(&a2).norm() > DEGENERACY * longest2)
}

/// The gap of the secondary node `x_s` against the primary triangle
/// `x = [x1, x2, x3]` (current positions), with the derivatives listed in
/// [`TriangleGap`]. `None` if the triangle is degenerate
/// (`|a1 × a2| ≤` [`DEGENERACY`] `· (longest edge)²`) or a coordinate is
/// not finite.
pub fn triangle_gap(x_s: &Vector3<f64>, x: [&Vector3<f64>; 3]) -> Option<TriangleGap> {
    let [x1, x2, x3] = x;
    if is_degenerate(x) || !x_s.iter().all(|v| v.is_finite()) {
        return None;
    }
    let a1 = x2 - x1;
    let a2 = x3 - x1;
    let c = a1.cross(&a2);
    let l = c.norm();
    let n = c / l;
    let w = x_s - x1;
    let g = w.dot(&n);
    let w_t = w - g * n;

    // ξ from M ξ = b, M⁻¹ = adj(M)/ℓ²
    let (m11, m12, m22) = (a1.dot(&a1), a1.dot(&a2), a2.dot(&a2));
    let m_inv = Matrix2::new(m22, -m12, -m12, m11) / (l * l);
    let xi = m_inv * Vector2::new(a1.dot(&w), a2.dot(&w));
    let shape = [1.0 - xi[0] - xi[1], xi[0], xi[1]];

    let id = Matrix3::identity();
    let zero = Matrix3::zeros();
    let op_a1 = block_row([zero, -id, id, zero]);
    let op_a2 = block_row([zero, -id, zero, id]);
    let op_d = block_row([id, -id, zero, zero]);
    let op_r = block_row([id, -shape[0] * id, -shape[1] * id, -shape[2] * id]);
    let op_c = block_row([
        zero,
        (a2 - a1).cross_matrix(),
        -a2.cross_matrix(),
        a1.cross_matrix(),
    ]);

    let projector = id - n * n.transpose();
    let normal_gradient = projector * op_c / l;

    let mut gradient = SVector::<f64, 12>::zeros();
    gradient.fixed_rows_mut::<3>(0).copy_from(&n);
    for (i, n_i) in shape.iter().enumerate() {
        gradient
            .fixed_rows_mut::<3>(3 * (i + 1))
            .copy_from(&(-n_i * n));
    }

    let mut rows = SMatrix::<f64, 2, 12>::zeros();
    for (alpha, (a, op_a)) in [(a1, op_a1), (a2, op_a2)].iter().enumerate() {
        let row = g * n.transpose() * op_a + a.transpose() * op_r;
        rows.row_mut(alpha).copy_from(&row);
    }
    let xi_gradient = m_inv * rows;

    let ct_n = op_c.transpose() * n;
    let ct_wt = op_c.transpose() * w_t;
    let w_x = w_t.cross_matrix();
    let nd = normal_gradient.transpose() * op_d;
    let hessian = nd
        + nd.transpose()
        + (op_a2.transpose() * w_x * op_a1 - op_a1.transpose() * w_x * op_a2) / l
        - (ct_n * ct_wt.transpose() + ct_wt * ct_n.transpose()) / (l * l)
        - g * normal_gradient.transpose() * normal_gradient;
    // each term is symmetric; averaging removes the round-off of the products
    let hessian = (hessian + hessian.transpose()) / 2.0;

    Some(TriangleGap {
        gap: g,
        normal: n,
        xi: [xi[0], xi[1]],
        shape,
        gradient,
        hessian,
        normal_gradient,
        xi_gradient,
    })
}

/// The two triangles `(q0, q1, q2)` and `(q0, q2, q3)` of the quadrangle
/// `q = (q0, q1, q2, q3)`, split along the diagonal `q0–q2`. Both keep the
/// quadrangle's orientation (its directed edges, hence the side its normal
/// points to); on a warped quadrangle the split is one of two choices.
pub fn split_quadrangle(q: [usize; 4]) -> [[usize; 3]; 2] {
    [[q[0], q[1], q[2]], [q[0], q[2], q[3]]]
}

/// The surface facets `facets` as triangles (a quadrangle as the two of
/// [`split_quadrangle`]), their nodes numbered by `node`.
pub fn facet_triangles(facets: &[Facet], node: impl Fn(usize) -> usize) -> Vec<[usize; 3]> {
    let mut triangles = Vec::new();
    for f in facets {
        let n: Vec<usize> = f.nodes.iter().map(|&n| node(n)).collect();
        match f.kind {
            FacetKind::Tri3 => triangles.push([n[0], n[1], n[2]]),
            FacetKind::Quad4 => triangles.extend(split_quadrangle([n[0], n[1], n[2], n[3]])),
            // a quadratic facet by its corners (contact refuses them at set-up)
            FacetKind::Tri6 => triangles.push([n[0], n[1], n[2]]),
            FacetKind::Quad8 => triangles.extend(split_quadrangle([n[0], n[1], n[2], n[3]])),
        }
    }
    triangles
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{DMatrix, Rotation3};
    use rand::rngs::StdRng;
    use rand::{Rng, SeedableRng};

    type Q = SVector<f64, 12>;

    fn point(q: &Q, k: usize) -> Vector3<f64> {
        q.fixed_rows::<3>(3 * k).into_owned()
    }

    fn gap_at(q: &Q) -> TriangleGap {
        let (s, x1, x2, x3) = (point(q, 0), point(q, 1), point(q, 2), point(q, 3));
        triangle_gap(&s, [&x1, &x2, &x3]).expect("non-degenerate")
    }

    fn stack(s: Vector3<f64>, x: [Vector3<f64>; 3]) -> Q {
        let mut q = Q::zeros();
        for (k, p) in [s, x[0], x[1], x[2]].iter().enumerate() {
            q.fixed_rows_mut::<3>(3 * k).copy_from(p);
        }
        q
    }

    /// Random well-shaped triangles (`ℓ ≥ 0.3 · longest edge²`) with the
    /// secondary node placed at the requested `ξ` and gap, so that every
    /// configuration is known to be inside/outside, open/penetrating.
    fn configurations() -> Vec<(Q, [f64; 2], f64)> {
        let mut rng = StdRng::seed_from_u64(11);
        let targets = [
            ([0.2, 0.3], 0.3),    // inside, open
            ([0.25, 0.5], -0.2),  // inside, penetrating
            ([0.4, 0.1], 0.0),    // on the plane
            ([1.3, -0.6], 0.4),   // outside beyond x2
            ([-0.5, -0.4], -0.3), // outside behind x1
            ([0.6, 0.7], -0.05),  // outside beyond edge x2–x3
            ([-0.2, 1.6], 1.2),   // far outside, far away
        ];
        let mut out = Vec::new();
        for (xi, g) in targets {
            for _ in 0..3 {
                let x = loop {
                    let mut r = || Vector3::from_fn(|_, _| rng.gen_range(-1.0..1.0));
                    let x: [Vector3<f64>; 3] = [r(), r(), r()];
                    let (a1, a2) = (x[1] - x[0], x[2] - x[0]);
                    let longest2 = a1
                        .norm_squared()
                        .max(a2.norm_squared())
                        .max((x[2] - x[1]).norm_squared());
                    if a1.cross(&a2).norm() > 0.3 * longest2 {
                        break x;
                    }
                };
                let n = (x[1] - x[0]).cross(&(x[2] - x[0])).normalize();
                let s = x[0] + xi[0] * (x[1] - x[0]) + xi[1] * (x[2] - x[0]) + g * n;
                out.push((stack(s, x), xi, g));
            }
        }
        out
    }

    /// Central-difference Jacobian of `f` at `q`, step `h`.
    fn jacobian<const M: usize>(
        f: &dyn Fn(&Q) -> SVector<f64, M>,
        q: &Q,
        h: f64,
    ) -> SMatrix<f64, M, 12> {
        let mut jac = SMatrix::<f64, M, 12>::zeros();
        for j in 0..12 {
            let mut qp = *q;
            let mut qm = *q;
            qp[j] += h;
            qm[j] -= h;
            jac.set_column(j, &((f(&qp) - f(&qm)) / (2.0 * h)));
        }
        jac
    }

    /// Column by column: `|a_j − b_j| ≤ rel · max(|b_j|, 10⁻² |b|)` (the
    /// floor only for columns that vanish, such as the `x_s` columns of
    /// `∂n/∂q`).
    #[track_caller]
    fn assert_columns<const M: usize>(
        a: &SMatrix<f64, M, 12>,
        b: &SMatrix<f64, M, 12>,
        rel: f64,
        what: &str,
    ) {
        let floor = 1e-2 * b.norm();
        for j in 0..12 {
            let err = (a.column(j) - b.column(j)).norm();
            let scale = b.column(j).norm().max(floor);
            assert!(
                err <= rel * scale,
                "{what}, column {j}: error {err:.3e} vs scale {scale:.3e}\n analytic {a}\n FD {b}"
            );
        }
    }

    #[test]
    fn unit_triangle_numbers() {
        let x = [
            Vector3::new(0.0, 0.0, 0.0),
            Vector3::new(1.0, 0.0, 0.0),
            Vector3::new(0.0, 1.0, 0.0),
        ];
        let s = Vector3::new(0.2, 0.3, 0.5);
        let t = triangle_gap(&s, [&x[0], &x[1], &x[2]]).unwrap();
        assert!((t.gap - 0.5).abs() < 1e-15);
        assert!((t.normal - Vector3::z()).norm() < 1e-15);
        assert!((t.xi[0] - 0.2).abs() < 1e-15 && (t.xi[1] - 0.3).abs() < 1e-15);
        let expected = [0.5, 0.2, 0.3];
        for (n, e) in t.shape.iter().zip(expected) {
            assert!((n - e).abs() < 1e-15);
        }
        // lifting x3 by δ moves the plane up by N3 δ at x̄: ∂g/∂z3 = −0.3
        assert!((t.gradient[11] + 0.3).abs() < 1e-15);
        // reversing the orientation flips n and g, not ξ's point
        let r = triangle_gap(&s, [&x[0], &x[2], &x[1]]).unwrap();
        assert!((r.gap + 0.5).abs() < 1e-15);
        assert!((r.normal + Vector3::z()).norm() < 1e-15);
        assert!((r.xi[0] - 0.3).abs() < 1e-15 && (r.xi[1] - 0.2).abs() < 1e-15);
    }

    #[test]
    fn gap_and_xi_are_those_the_node_was_placed_at() {
        for (q, xi, g) in configurations() {
            let t = gap_at(&q);
            assert!((t.gap - g).abs() < 1e-13, "g {} vs {g}", t.gap);
            assert!((t.xi[0] - xi[0]).abs() < 1e-12 && (t.xi[1] - xi[1]).abs() < 1e-12);
            // x̄ = Σ N_i x_i = x_s − g n
            let bar: Vector3<f64> = (0..3).map(|i| t.shape[i] * point(&q, i + 1)).sum();
            assert!((bar - (point(&q, 0) - t.gap * t.normal)).norm() < 1e-13);
        }
    }

    #[test]
    fn derivatives_match_central_differences() {
        let h = 1e-6;
        for (q, xi, g) in configurations() {
            let t = gap_at(&q);
            let what = |name: &str| format!("{name} at ξ = {xi:?}, g = {g}");

            let fd = jacobian(&|q| SVector::<f64, 1>::new(gap_at(q).gap), &q, h);
            assert_columns(&t.gradient.transpose(), &fd, 1e-6, &what("∂g/∂q"));

            let fd = jacobian(&|q| gap_at(q).gradient, &q, h);
            assert_columns(&t.hessian, &fd, 1e-6, &what("∂²g/∂q²"));

            let fd = jacobian(&|q| gap_at(q).normal, &q, h);
            assert_columns(&t.normal_gradient, &fd, 1e-6, &what("∂n/∂q"));

            let fd = jacobian(&|q| Vector2::from(gap_at(q).xi), &q, h);
            assert_columns(&t.xi_gradient, &fd, 1e-6, &what("∂ξ/∂q"));
        }
    }

    /// A check of the Hessian that does not rely on differences: second
    /// differences of `g` itself, at a coarser step and tolerance.
    #[test]
    fn hessian_matches_second_differences_of_the_gap() {
        let h = 1e-4;
        for (q, _, _) in configurations().into_iter().step_by(4) {
            let t = gap_at(&q);
            let g = |q: &Q| gap_at(q).gap;
            let mut fd = DMatrix::<f64>::zeros(12, 12);
            for i in 0..12 {
                for j in 0..12 {
                    let e = |k: usize, s: f64| Q::from_fn(|r, _| if r == k { s * h } else { 0.0 });
                    fd[(i, j)] = (g(&(q + e(i, 1.0) + e(j, 1.0)))
                        - g(&(q + e(i, 1.0) - e(j, 1.0)))
                        - g(&(q - e(i, 1.0) + e(j, 1.0)))
                        + g(&(q - e(i, 1.0) - e(j, 1.0))))
                        / (4.0 * h * h);
                }
            }
            let exact = DMatrix::from_column_slice(12, 12, t.hessian.as_slice());
            let err = (&exact - &fd).norm() / exact.norm();
            assert!(err < 1e-5, "relative error {err:.3e}");
        }
    }

    #[test]
    fn gradient_is_the_shape_functions_times_the_normal() {
        for (q, _, _) in configurations() {
            let t = gap_at(&q);
            // the chain-rule form Dᵀn + Cᵀw_t/ℓ, assembled independently
            let (s, x1, x2, x3) = (point(&q, 0), point(&q, 1), point(&q, 2), point(&q, 3));
            let (a1, a2) = (x2 - x1, x3 - x1);
            let l = a1.cross(&a2).norm();
            let w_t = s - x1 - t.gap * t.normal;
            let chain = [
                t.normal,
                -t.normal + (a2 - a1).cross_matrix().transpose() * w_t / l,
                -a2.cross_matrix().transpose() * w_t / l,
                a1.cross_matrix().transpose() * w_t / l,
            ];
            assert!((t.gradient.fixed_rows::<3>(0) - t.normal).norm() == 0.0);
            for i in 0..3 {
                let block = t.gradient.fixed_rows::<3>(3 * (i + 1)).into_owned();
                assert!((block + t.shape[i] * t.normal).norm() < 1e-14);
                assert!((chain[i + 1] - block).norm() < 1e-14, "block {i}");
            }
        }
    }

    #[test]
    fn rigid_translation_does_not_change_the_gap() {
        for (q, _, _) in configurations() {
            let t = gap_at(&q);
            let sum: Vector3<f64> = (0..4).map(|k| point(&t.gradient, k)).sum();
            assert!(sum.norm() < 1e-15, "gradient blocks sum to {sum:?}");
            let scale = t.hessian.norm();
            for k in 0..4 {
                let row: Matrix3<f64> = (0..4)
                    .map(|j| t.hessian.fixed_view::<3, 3>(3 * k, 3 * j).into_owned())
                    .sum();
                assert!(row.norm() < 1e-14 * scale, "block row {k}: {row}");
            }
            // the same, as a finite motion
            let d = Vector3::new(0.3, -1.7, 2.2);
            let moved = stack(
                point(&q, 0) + d,
                [point(&q, 1) + d, point(&q, 2) + d, point(&q, 3) + d],
            );
            let m = gap_at(&moved);
            assert!((m.gap - t.gap).abs() < 1e-13);
            assert!((m.xi[0] - t.xi[0]).abs() < 1e-12 && (m.xi[1] - t.xi[1]).abs() < 1e-12);
        }
    }

    #[test]
    fn rigid_rotation_does_not_change_the_gap() {
        let rotation = Rotation3::from_axis_angle(
            &nalgebra::Unit::new_normalize(Vector3::new(0.3, -1.0, 0.6)),
            2.1,
        );
        for (q, _, _) in configurations() {
            let t = gap_at(&q);
            let p: [Vector3<f64>; 4] = std::array::from_fn(|k| point(&q, k));
            let r = gap_at(&stack(
                rotation * p[0],
                [rotation * p[1], rotation * p[2], rotation * p[3]],
            ));
            assert!((r.gap - t.gap).abs() < 1e-13);
            assert!((r.normal - rotation * t.normal).norm() < 1e-13);
            assert!((r.xi[0] - t.xi[0]).abs() < 1e-12 && (r.xi[1] - t.xi[1]).abs() < 1e-12);

            // infinitesimally, about the origin with angular velocity ω:
            // v = ω × q, a = ω × (ω × q); d/dθ g = ∇g·v = 0 and
            // d²/dθ² g = vᵀ H v + ∇g·a = 0 (a check of H without differences)
            let omega = Vector3::new(0.7, 0.2, -0.5);
            let v = stack(
                omega.cross(&p[0]),
                [omega.cross(&p[1]), omega.cross(&p[2]), omega.cross(&p[3])],
            );
            let a = stack(
                omega.cross(&omega.cross(&p[0])),
                [
                    omega.cross(&omega.cross(&p[1])),
                    omega.cross(&omega.cross(&p[2])),
                    omega.cross(&omega.cross(&p[3])),
                ],
            );
            let scale = t.gradient.norm() * a.norm() + t.hessian.norm() * v.norm_squared();
            assert!(t.gradient.dot(&v).abs() < 1e-14 * scale);
            let second = v.dot(&(t.hessian * v)) + t.gradient.dot(&a);
            assert!(
                second.abs() < 1e-13 * scale,
                "second derivative {second:.3e}"
            );
        }
    }

    #[test]
    fn hessian_is_symmetric_and_linear_in_the_secondary_node() {
        for (q, _, _) in configurations() {
            let t = gap_at(&q);
            assert_eq!(t.hessian, t.hessian.transpose());
            assert_eq!(t.hessian.fixed_view::<3, 3>(0, 0), Matrix3::zeros());
            assert_eq!(t.normal_gradient.fixed_view::<3, 3>(0, 0), Matrix3::zeros());
        }
    }

    #[test]
    fn degenerate_triangles_have_no_gap() {
        let s = Vector3::new(0.1, 0.2, 0.3);
        let x1 = Vector3::new(0.0, 0.0, 0.0);
        let x2 = Vector3::new(1.0, 0.5, 0.0);
        let collinear = Vector3::new(3.0, 1.5, 0.0);
        assert!(triangle_gap(&s, [&x1, &x2, &collinear]).is_none());
        assert!(triangle_gap(&s, [&x1, &x1, &x2]).is_none());
        assert!(triangle_gap(&s, [&x1, &x1, &x1]).is_none());
        let nan = Vector3::new(f64::NAN, 0.0, 0.0);
        assert!(triangle_gap(&s, [&x1, &x2, &nan]).is_none());
        assert!(triangle_gap(&nan, [&x1, &x2, &Vector3::y()]).is_none());
        // the criterion is relative: a tiny well-shaped triangle is fine
        let tiny = 1e-9;
        let t = triangle_gap(
            &(s * tiny),
            [&(x1 * tiny), &(x2 * tiny), &(Vector3::y() * tiny)],
        )
        .unwrap();
        assert!((t.gap - 0.3 * tiny).abs() < 1e-15 * tiny);
        // a sliver just above the threshold is kept, just below is not
        let sliver = |h: f64| Vector3::new(0.5, h, 0.0);
        let (a, b) = (Vector3::zeros(), Vector3::x());
        assert!(triangle_gap(&s, [&a, &b, &sliver(2.0 * DEGENERACY)]).is_some());
        assert!(triangle_gap(&s, [&a, &b, &sliver(0.5 * DEGENERACY)]).is_none());
    }

    #[test]
    fn split_quadrangle_keeps_the_orientation() {
        assert_eq!(split_quadrangle([4, 7, 9, 2]), [[4, 7, 9], [4, 9, 2]]);
        // the directed edges of the two triangles are the quadrangle's four
        // plus the diagonal once in each direction
        let q = [4, 7, 9, 2];
        let mut edges: Vec<(usize, usize)> = split_quadrangle(q)
            .iter()
            .flat_map(|t| (0..3).map(move |i| (t[i], t[(i + 1) % 3])))
            .collect();
        edges.sort();
        let mut expected: Vec<_> = (0..4).map(|i| (q[i], q[(i + 1) % 4])).collect();
        expected.extend([(q[0], q[2]), (q[2], q[0])]);
        expected.sort();
        assert_eq!(edges, expected);
        // a planar quadrangle: both triangles have its normal, their areas
        // add up to its area ½|(x2 − x0) × (x3 − x1)|
        let x = [
            Vector3::new(0.0, 0.0, 0.0),
            Vector3::new(2.0, 0.1, 0.0),
            Vector3::new(2.2, 1.0, 0.0),
            Vector3::new(-0.1, 1.3, 0.0),
        ];
        let quad: Vector3<f64> = (x[2] - x[0]).cross(&(x[3] - x[1])) / 2.0;
        let mut area = 0.0_f64;
        for [i, j, k] in split_quadrangle([0, 1, 2, 3]) {
            let c: Vector3<f64> = (x[j] - x[i]).cross(&(x[k] - x[i])) / 2.0;
            assert!((c.normalize() - quad.normalize()).norm() < 1e-15);
            area += c.norm();
        }
        assert!((area - quad.norm()).abs() < 1e-15);
    }
}
