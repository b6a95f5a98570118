//! Time per element of the element kernel (issue 13 item 3): the
//! allocating [`internal_force_and_tangent`] (two output vectors per
//! element, what the assembly loop calls) against
//! [`internal_force_and_tangent_into`] with buffers reused across
//! elements (no heap allocation), force and tangent, for Tet4 and Hex8
//! with a small-strain and a finite-strain material. Prints one line per
//! case: microseconds per element, the median of 5 repetitions. Then the
//! tangent of `linear_elastic` in closed form ([`hooke_stiffness`], what
//! the constant stiffness of a Hooke model is assembled with) against the
//! kernel's tangent alone at `u = 0`.
//!
//! `cargo bench --bench element_kernel`

use signorini::assembly::hooke::hooke_stiffness;
use signorini::assembly::kernel::{
    internal_force_and_tangent, internal_force_and_tangent_into, reference_geometry,
};
use signorini::material::{LinearElastic, Material, NeoHookean};
use signorini::mesh::ElementKind;
use std::hint::black_box;
use std::time::Instant;

/// Elements evaluated per repetition.
const ELEMENTS: usize = 100_000;

fn median_micros(mut run: impl FnMut()) -> f64 {
    let mut times: Vec<f64> = (0..5)
        .map(|_| {
            let start = Instant::now();
            run();
            start.elapsed().as_secs_f64() * 1e6 / ELEMENTS as f64
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times[2]
}

/// The unit reference element of `kind`.
fn corners(kind: ElementKind) -> Vec<[f64; 3]> {
    match kind {
        ElementKind::Tet4 => vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        ElementKind::Hex8 => (0..8)
            .map(|a| {
                [
                    ((a & 1) ^ (a >> 1 & 1)) as f64,
                    (a >> 1 & 1) as f64,
                    (a >> 2) as f64,
                ]
            })
            .collect(),
        kind => signorini::fem::shape::reference_nodes(kind),
    }
}

fn main() {
    let materials: [(&str, Box<dyn Material>); 2] = [
        (
            "linear_elastic",
            Box::new(LinearElastic::new(1000.0, 0.3, "m").unwrap()),
        ),
        (
            "neo_hookean",
            Box::new(NeoHookean::new(100.0, 0.45, "m").unwrap()),
        ),
    ];
    println!("kind  material        allocating µs  into µs  ratio");
    for kind in [ElementKind::Tet4, ElementKind::Hex8] {
        let corners = corners(kind);
        let geometry = reference_geometry(kind, &corners).unwrap();
        let u: Vec<[f64; 3]> = (0..corners.len())
            .map(|a| [0.01 * a as f64, -0.02, 0.005 * a as f64])
            .collect();
        let dofs = 3 * u.len();
        for (name, material) in &materials {
            let allocating = median_micros(|| {
                for _ in 0..ELEMENTS {
                    black_box(
                        internal_force_and_tangent(
                            &geometry,
                            black_box(&u),
                            material.as_ref(),
                            true,
                        )
                        .unwrap(),
                    );
                }
            });
            let (mut force, mut k) = (vec![0.0; dofs], vec![0.0; dofs * dofs]);
            let into = median_micros(|| {
                for _ in 0..ELEMENTS {
                    internal_force_and_tangent_into(
                        &geometry,
                        black_box(&u),
                        material.as_ref(),
                        &mut force,
                        Some(&mut k),
                    )
                    .unwrap();
                    black_box((&force, &k));
                }
            });
            println!(
                "{kind:?}  {name:<14}  {allocating:>13.3}  {into:>7.3}  {:>5.2}",
                into / allocating
            );
        }
    }
    let hooke = LinearElastic::new(1000.0, 0.3, "m").unwrap();
    let (lambda, mu) = hooke.lame();
    println!("kind  linear_elastic tangent at u = 0: kernel µs  closed form µs  ratio");
    for kind in [ElementKind::Tet4, ElementKind::Hex8] {
        let geometry = reference_geometry(kind, &corners(kind)).unwrap();
        let n = geometry[0].gradients.len();
        let u = vec![[0.0; 3]; n];
        let (mut force, mut k) = (vec![0.0; 3 * n], vec![0.0; 9 * n * n]);
        let kernel = median_micros(|| {
            for _ in 0..ELEMENTS {
                internal_force_and_tangent_into(
                    black_box(&geometry),
                    &u,
                    &hooke,
                    &mut force,
                    Some(&mut k),
                )
                .unwrap();
                black_box((&force, &k));
            }
        });
        let closed = median_micros(|| {
            for _ in 0..ELEMENTS {
                match kind {
                    ElementKind::Tet4 => {
                        black_box(hooke_stiffness::<4, 10>(black_box(&geometry), lambda, mu));
                    }
                    ElementKind::Hex8 => {
                        black_box(hooke_stiffness::<8, 36>(black_box(&geometry), lambda, mu));
                    }
                    // no closed form for the other kinds
                    _ => {}
                }
            }
        });
        println!(
            "{kind:?}  {kernel:>42.3}  {closed:>14.3}  {:>5.2}",
            closed / kernel
        );
    }
}
