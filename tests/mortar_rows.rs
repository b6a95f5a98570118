//! The assembled mortar rows (`mortar_rows`): values equal to the
//! reference path `mortar_coupling` and, bit for bit, to the values-only
//! path `mortar_row_values`, gradients of `D_j`, `M_jl`, `n_j`,
//! `g̃_j` and the lever `b_j` against central differences (`h = 1e-6`, to
//! 1e-6 relative) on curved non-matching surfaces of every shape pairing,
//! and the identities a wrong linearisation breaks (Popp, Gitterle, Gee &
//! Wall 2010, §5): `∇(Σ_l M_jl − D_j) = 0`; `Σ_nodes b_j = 0`; a rigid
//! translation leaves `D`, `M`, `n`, `g̃` unchanged; a rigid rotation
//! `δx = ω × x` leaves `D`, `M`, `g̃` unchanged and turns `n_j` by
//! `ω × n_j`; on a flat, fully covered patch `D_j = ∫ Ñ_j dA` does not
//! see in-plane moves of the primary nodes, and follows those of the
//! secondary ones as `δ∫ Ñ_j dA` does.

mod mortar_common;

use mortar_common::{
    graded_secondary, grid, in_plane_moves, increments, linspace, nodal_integrals, shifted, v,
    SHAPES,
};
use nalgebra::{DVector, Vector3};
use signorini::contact::mortar::quadratic::{mid_side_edges, mortar_values};
use signorini::contact::mortar::{
    all_pairs, mortar_coupling, mortar_row_values, mortar_rows, Derivatives, FaceShape, MortarRow,
    SurfaceFace,
};

const H: f64 = 1e-6;

/// Two surfaces: a secondary one on `[0, 1] × [0, 0.8]` (normal +z) on a
/// graded grid, and a finer primary one 0.05 above (normal −z) that
/// overhangs it on every side (`covered`) or covers only its middle, with
/// no grid line in common. `curved` warps both out of plane; triangle
/// meshes get their interior corners moved.
struct Surfaces {
    secondary: Vec<SurfaceFace>,
    primary: Vec<SurfaceFace>,
    coords: Vec<Vector3<f64>>,
}

fn surfaces(secondary: FaceShape, primary: FaceShape, curved: bool, covered: bool) -> Surfaces {
    let mut coords = Vec::new();
    let s = graded_secondary(secondary, &mut coords);
    let first_primary = coords.len();
    let p = grid(
        &if covered {
            linspace(-0.1, 1.12, 5)
        } else {
            linspace(0.17, 0.71, 3)
        },
        &if covered {
            linspace(-0.13, 0.93, 4)
        } else {
            linspace(0.11, 0.62, 2)
        },
        0.05,
        primary,
        true,
        &in_plane_moves(primary),
        &mut coords,
    );
    if curved {
        for (i, x) in coords.iter_mut().enumerate() {
            let lift = if i < first_primary {
                0.0
            } else {
                0.02 * (3.0 * x.y).cos() * x.x
            };
            x.z += 0.08 * (2.0 * x.x).sin() * (1.0 + x.y) + lift;
        }
    }
    Surfaces {
        secondary: s,
        primary: p,
        coords,
    }
}

fn rows(s: &Surfaces, coords: &[Vector3<f64>]) -> Vec<MortarRow> {
    let pairs = all_pairs(s.secondary.len(), s.primary.len());
    mortar_rows(&s.secondary, &s.primary, &pairs, coords, Derivatives::With).unwrap()
}

/// The increments of a row's nodes, node-major.
fn local(row: &MortarRow, dx: &[Vector3<f64>]) -> DVector<f64> {
    DVector::from_iterator(
        3 * row.nodes.len(),
        row.nodes
            .iter()
            .flat_map(|&n| dx[n].iter().copied().collect::<Vec<_>>()),
    )
}

/// Taken without derivatives: no gradient; the lever `b_j` on its nodes
/// (those of `R_jk` and `M_jl`) is `row`'s there, bit for bit, and `row`'s
/// is zero elsewhere; `D_j`, `g̃_j`, `n_j` are `row`'s (through
/// [`mortar_row_values`], the same rows' values).
fn assert_same_lever(what: &str, row: &MortarRow, without: &MortarRow) {
    assert!(
        row.has_derivatives() && !without.has_derivatives(),
        "{what}"
    );
    assert_eq!(without.node, row.node, "{what}");
    for (a, n) in row.nodes.iter().enumerate() {
        let b = (without.nodes.iter().position(|m| m == n)).map_or(Vector3::zeros(), |w| {
            without.lever.fixed_rows::<3>(3 * w).into()
        });
        assert_eq!(row.lever.fixed_rows::<3>(3 * a), b, "{what}: b on {n}");
    }
}

/// The rows' values are the coupling's ([`mortar_coupling`]) to 1e-14, on
/// curved non-matching surfaces of every pairing of the four shapes, and
/// the rows without derivatives ([`Derivatives::Without`],
/// [`mortar_row_values`]) are the rows' values to the bit.
#[test]
fn values_equal_the_coupling() {
    const NO: Derivatives = Derivatives::Without;
    for s_shape in SHAPES {
        for p_shape in SHAPES {
            let s = surfaces(s_shape, p_shape, true, true);
            let pairs = all_pairs(s.secondary.len(), s.primary.len());
            let coupling = mortar_coupling(&s.secondary, &s.primary, &pairs, &s.coords).unwrap();
            let gaps = coupling.weighted_gaps(&s.coords);
            let rows = rows(&s, &s.coords);
            assert_eq!(rows.len(), coupling.d.len());
            let values = mortar_row_values(&s.secondary, &s.primary, &pairs, &s.coords).unwrap();
            assert_eq!(values.len(), rows.len());
            let without = (mortar_rows(&s.secondary, &s.primary, &pairs, &s.coords, NO)).unwrap();
            assert_eq!(without.len(), rows.len());
            for ((row, values), without) in rows.iter().zip(&values).zip(&without) {
                let what = format!("{s_shape:?}–{p_shape:?} node {}", row.node);
                assert_same_lever(&what, row, without);
                // the values-only path: the same numbers, bit for bit
                assert_eq!(values.node, row.node, "{what}");
                assert_eq!(values.d, row.d, "{what}: D (values only)");
                assert_eq!(values.m, row.m, "{what}: M (values only)");
                assert_eq!(values.normal, row.normal, "{what}: n (values only)");
                assert_eq!(
                    values.weighted_gap, row.weighted_gap,
                    "{what}: g̃ (values only)"
                );
                assert!((row.d - coupling.d[&row.node]).abs() < 1e-14, "{what}: D");
                assert!(
                    (row.normal - coupling.normals[&row.node]).norm() < 1e-14,
                    "{what}: n"
                );
                assert!(
                    (row.weighted_gap - gaps[&row.node]).abs() < 1e-14,
                    "{what}: g̃"
                );
                for (l, m) in &row.m {
                    assert!(
                        (m - coupling.m[&(row.node, *l)]).abs() < 1e-14,
                        "{what}: M_{l}"
                    );
                }
                assert!(
                    row.nodes.windows(2).all(|w| w[0] < w[1]),
                    "{what}: sorted nodes"
                );
            }
        }
    }
}

/// Every row's gradients against central differences along `dx`, to 1e-6
/// of the directional derivative's scale `|∇q| |δx|` (at least 1e-3 of
/// `|∇D_j| |δx|`); returns the worst ratio of error to scale.
fn check_row_gradients(what: &str, s: &Surfaces, dx: &[Vector3<f64>]) -> f64 {
    let rows0 = rows(s, &s.coords);
    let plus = rows(s, &shifted(&s.coords, dx, H));
    let minus = rows(s, &shifted(&s.coords, dx, -H));
    assert_eq!(
        (plus.len(), minus.len()),
        (rows0.len(), rows0.len()),
        "{what}: the same rows under ±h"
    );
    let mut worst: f64 = 0.0;
    let mut check = |name: String,
                     fd: &DVector<f64>,
                     exact: &DVector<f64>,
                     gradient_norm: f64,
                     dx_norm: f64,
                     floor: f64| {
        assert!(
            gradient_norm * dx_norm > 1e-8,
            "{name}: a non-trivial gradient"
        );
        let scale = (gradient_norm * dx_norm).max(floor);
        let error = (fd - exact).norm();
        assert!(
            error <= 1e-6 * scale,
            "{name}: |fd − exact| = {error:e}, scale {scale:e}\nfd {fd}\nexact {exact}"
        );
        worst = worst.max(error / scale);
    };
    let one = |x: f64| DVector::from_element(1, x);
    for ((row, p), m) in rows0.iter().zip(&plus).zip(&minus) {
        let at = format!("{what} node {}", row.node);
        assert_eq!(
            (p.node, m.node, p.m.len()),
            (row.node, row.node, row.m.len()),
            "{at}: same row under ±h"
        );
        let dxl = local(row, dx);
        let dxn = dxl.norm();
        // entries 1e3 below the row's D scale (slivers of overlap) are
        // held to 1e-6 of that floor: their differences are round-off
        let floor = 1e-3 * row.d_gradient.norm() * dxn;
        let fd = |a: f64, b: f64| one((a - b) / (2.0 * H));
        check(
            format!("{at} D"),
            &fd(p.d, m.d),
            &one(row.d_gradient.dot(&dxl)),
            row.d_gradient.norm(),
            dxn,
            floor,
        );
        for (a, (l, _)) in row.m.iter().enumerate() {
            let g = &row.m_gradients[a];
            check(
                format!("{at} M_{l}"),
                &fd(p.m[a].1, m.m[a].1),
                &one(g.dot(&dxl)),
                g.norm(),
                dxn,
                floor,
            );
        }
        let g = &row.weighted_gap_gradient;
        check(
            format!("{at} g̃"),
            &fd(p.weighted_gap, m.weighted_gap),
            &one(g.dot(&dxl)),
            g.norm(),
            dxn,
            floor,
        );
        let fd_n = DVector::from_iterator(3, ((p.normal - m.normal) / (2.0 * H)).iter().copied());
        check(
            format!("{at} n"),
            &fd_n,
            &(&row.normal_gradient * &dxl),
            row.normal_gradient.norm(),
            dxn,
            floor,
        );
        let fd_b = (&p.lever - &m.lever) / (2.0 * H);
        check(
            format!("{at} b"),
            &fd_b,
            &(&row.lever_gradient * &dxl),
            row.lever_gradient.norm(),
            dxn,
            floor,
        );
    }
    worst
}

#[test]
fn row_gradients_match_central_differences() {
    for (i, s_shape) in SHAPES.iter().enumerate() {
        for (k, p_shape) in SHAPES.iter().enumerate() {
            let s = surfaces(*s_shape, *p_shape, true, true);
            let dx = increments(s.coords.len(), 0.7 + i as f64 + 0.25 * k as f64);
            let worst = check_row_gradients(&format!("{s_shape:?}–{p_shape:?}"), &s, &dx);
            eprintln!("{s_shape:?}–{p_shape:?}: worst |fd − exact| / (|∇q| |δx|) = {worst:.1e}");
        }
    }
}

#[test]
fn row_gradients_on_a_partly_covered_surface() {
    for (i, s_shape) in SHAPES.iter().enumerate() {
        let p_shape = SHAPES[(i + 1) % 4];
        let s = surfaces(*s_shape, p_shape, true, false);
        let dx = increments(s.coords.len(), 2.9 + i as f64);
        let worst =
            check_row_gradients(&format!("{s_shape:?}–{p_shape:?} partly covered"), &s, &dx);
        eprintln!("{s_shape:?}–{p_shape:?} partly covered: worst {worst:.1e}");
    }
}

/// `δx = a + ω × x` for every node.
fn rigid(coords: &[Vector3<f64>], a: Vector3<f64>, omega: Vector3<f64>) -> Vec<Vector3<f64>> {
    coords.iter().map(|x| a + omega.cross(x)).collect()
}

#[test]
fn identities_of_the_gradients() {
    for s_shape in SHAPES {
        for p_shape in SHAPES {
            for curved in [false, true] {
                let s = surfaces(s_shape, p_shape, curved, true);
                let translation = rigid(&s.coords, v(0.3, -0.7, 0.4), Vector3::zeros());
                let rotation = rigid(&s.coords, Vector3::zeros(), v(0.2, 0.5, -0.4));
                for row in rows(&s, &s.coords) {
                    let what = format!("{s_shape:?}–{p_shape:?} curved {curved} node {}", row.node);
                    let sum_m: DVector<f64> = row.m_gradients.iter().sum();
                    assert!(
                        (&sum_m - &row.d_gradient).norm() < 1e-12,
                        "{what}: ∇(Σ M − D)"
                    );
                    let (b, db) = (&row.lever, &row.lever_gradient);
                    let block_sum =
                        |k: usize| (0..row.nodes.len()).map(|a| b[3 * a + k]).sum::<f64>();
                    assert!(
                        [0, 1, 2].iter().all(|&k| block_sum(k).abs() < 1e-13),
                        "{what}: Σ b = 0"
                    );
                    let db_sum = (0..row.nodes.len())
                        .fold(nalgebra::DMatrix::zeros(3, db.ncols()), |acc, a| {
                            acc + db.rows(3 * a, 3)
                        });
                    assert!(db_sum.norm() < 1e-12, "{what}: Σ ∂b = 0");
                    for (name, motion) in [("translation", &translation), ("rotation", &rotation)] {
                        let dxl = local(&row, motion);
                        assert!(
                            row.d_gradient.dot(&dxl).abs() < 1e-12,
                            "{what}: {name} moves D"
                        );
                        for g in &row.m_gradients {
                            assert!(g.dot(&dxl).abs() < 1e-12, "{what}: {name} moves M");
                        }
                        assert!(
                            row.weighted_gap_gradient.dot(&dxl).abs() < 1e-12,
                            "{what}: {name} moves g̃"
                        );
                        let expected = if name == "rotation" {
                            v(0.2, 0.5, -0.4).cross(&row.normal)
                        } else {
                            Vector3::zeros()
                        };
                        let dn = &row.normal_gradient * &dxl;
                        assert!(
                            (Vector3::new(dn[0], dn[1], dn[2]) - expected).norm() < 1e-12,
                            "{what}: {name} of n"
                        );
                    }
                }
            }
        }
    }
}

/// Moves each mid-side node with the mean of its edge's corners, so the
/// edges stay straight (the clip polygon is the corners' polygon; curved
/// edges are approximated, DESIGN.md "Limits today").
fn straight_edged(faces: &[SurfaceFace], dx: &mut [Vector3<f64>]) {
    for f in faces {
        let first_mid = f.shape.corner_count();
        for (m, [a, b]) in mid_side_edges(f.shape).iter().enumerate() {
            dx[f.nodes[first_mid + m]] = (dx[f.nodes[*a]] + dx[f.nodes[*b]]) * 0.5;
        }
    }
}

#[test]
fn on_a_flat_covered_patch_d_sees_only_the_secondary_surface() {
    for s_shape in SHAPES {
        for p_shape in SHAPES {
            let s = surfaces(s_shape, p_shape, false, true);
            let secondary_nodes: Vec<usize> = {
                let mut n: Vec<usize> = s.secondary.iter().flat_map(|f| f.nodes.clone()).collect();
                n.sort_unstable();
                n.dedup();
                n
            };
            // in-plane increments: interior and boundary nodes alike, both surfaces
            let mut dx: Vec<Vector3<f64>> = increments(s.coords.len(), 5.5)
                .iter()
                .map(|d| v(0.1 * d.x, 0.1 * d.y, 0.0))
                .collect();
            straight_edged(&s.secondary, &mut dx);
            straight_edged(&s.primary, &mut dx);
            let primary_only: Vec<Vector3<f64>> = dx
                .iter()
                .enumerate()
                .map(|(i, d)| {
                    if secondary_nodes.binary_search(&i).is_ok() {
                        Vector3::zeros()
                    } else {
                        *d
                    }
                })
                .collect();
            let integral = |coords: &[Vector3<f64>]| {
                nodal_integrals(&s.secondary, coords, &|shape, xi| mortar_values(shape, xi))
            };
            let (plus, minus) = (
                integral(&shifted(&s.coords, &dx, H)),
                integral(&shifted(&s.coords, &dx, -H)),
            );
            let rows = rows(&s, &s.coords);
            assert_eq!(
                rows.len(),
                secondary_nodes.len(),
                "every secondary node is covered"
            );
            for row in rows {
                let what = format!("{s_shape:?}–{p_shape:?} node {}", row.node);
                assert!(
                    row.d_gradient.dot(&local(&row, &primary_only)).abs() < 1e-12,
                    "{what}: ∇D · δx_primary"
                );
                let fd = (plus[&row.node] - minus[&row.node]) / (2.0 * H);
                let exact = row.d_gradient.dot(&local(&row, &dx));
                assert!(
                    (fd - exact).abs() < 1e-8,
                    "{what}: δ∫Ñ_j {fd:e} vs ∇D·δx {exact:e}"
                );
            }
        }
    }
}

/// The pairs are integrated side by side on the run's threads and added
/// in the pairs' order: the rows, with their gradients and without, are
/// the same bit for bit on 1 and 3 threads (curved non-matching surfaces,
/// every pairing of the four shapes).
#[test]
fn rows_are_the_same_on_any_number_of_threads() {
    for s_shape in SHAPES {
        for p_shape in SHAPES {
            let s = surfaces(s_shape, p_shape, true, true);
            let pairs = all_pairs(s.secondary.len(), s.primary.len());
            let on = |threads: usize, derivatives: Derivatives| {
                rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .build()
                    .unwrap()
                    .install(|| {
                        mortar_rows(&s.secondary, &s.primary, &pairs, &s.coords, derivatives)
                    })
                    .unwrap()
            };
            for derivatives in [Derivatives::With, Derivatives::Without] {
                let one = on(1, derivatives);
                assert!(!one.is_empty());
                assert_eq!(one, on(3, derivatives), "{s_shape:?}–{p_shape:?}");
            }
        }
    }
}
