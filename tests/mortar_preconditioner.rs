//! The preconditioner of Newton's nonsymmetric solve with dual mortar
//! between bodies (`ContactInterface::couple_multipliers_by_force`): its
//! multiplier couplings are the tangent's force columns on both sides,
//! where the symmetric part averages them with the constraint rows, which
//! differ from them by the derivatives of `D_j`, `M_jl` and `n_j` acting on
//! the gap. On two-spheres with mortar on Newton's path that average left
//! GMRES at 8e-8 after its 200 iterations, and the sparse LU solved
//! (BENCHMARKS.md, "Session 27: mortar Newton's preconditioner").

mod common;

use common::{mortar_blocks, two_bodies};
use signorini::contact::laws::NormalLaw;
use signorini::mesh::{structured::box_mesh, ElementKind};
use signorini::problem::Problem;
use signorini::solve::krylov::PreconditionedGmres;
use signorini::solve::linear::Ordering;
use signorini::solve::linear_solver::{LinearSolver, LinearSystem, SolverStatistics};
use signorini::solve::lu::SparseLu;
use signorini::solve::newton::apply_identity_rows;
use signorini::solve::nonlinear::NonlinearProblem;

const E: f64 = 100.0;
/// The upper block's lowest point below the lower block's top.
const PENETRATION: f64 = 0.15;
/// The upper block's bottom face `z = z₀ + CURVATURE (x² + y²)`.
const CURVATURE: f64 = 0.3;

/// Two linear elastic blocks 1 × 1 × 0.5 (lower 15 × 15 × 3 cells of
/// Tet4, upper 12 × 12 × 3), the upper one bent into a dome (each node raised by
/// `CURVATURE (x² + y²)`) whose pole is `PENETRATION` into the lower one,
/// as Newton's first iterate leaves bodies that start apart and carry no
/// force yet; symmetry planes x = 0 and y = 0, the lower bottom and the
/// upper top held in z; dual mortar, the upper bottom secondary, every
/// multiplier 0 (penetrated nodes active: `t̂ = −p g > 0`).
fn penetrating_dome() -> Problem {
    let lower = box_mesh(ElementKind::Tet4, [15, 15, 3], [1.0, 1.0, 0.5]);
    let upper = box_mesh(ElementKind::Tet4, [12, 12, 3], [1.0, 1.0, 0.5]);
    let first_upper = lower.nodes.len();
    let mut mesh = two_bodies(
        lower,
        "lower",
        upper,
        "upper",
        [0.0, 0.0, 0.5 - PENETRATION],
    );
    for x in &mut mesh.nodes[first_upper..] {
        x[2] += CURVATURE * (x[0] * x[0] + x[1] * x[1]);
    }
    let mut pr = mortar_blocks(mesh, E, 0.0, NormalLaw::Rockafellar { p: E, k: E });
    pr.newton_pattern();
    pr
}

/// GMRES on `k` preconditioned by the LDLᵀ of `neighbour`: the answer and
/// the solver's counts.
fn solve(
    pr: &Problem,
    k: &[f64],
    neighbour: &[f64],
    signs: &[i8],
    rhs: &[f64],
) -> (Vec<f64>, SolverStatistics) {
    let pattern = pr.model.pattern.symbolic();
    let node_order: Vec<usize> = (0..pr.model.pattern.num_nodes()).collect();
    let ordering = Ordering::Custom(pr.model.pattern.dof_ordering(&node_order));
    let mut gmres = PreconditionedGmres::new(ordering, 1);
    let system = LinearSystem {
        pattern,
        matrix: k,
        symmetric_neighbour: Some(neighbour),
        pivot_signs: Some(signs),
    };
    let mut x = vec![0.0; rhs.len()];
    gmres.solve(&system, rhs, &mut x).expect("solves");
    (x, gmres.statistics())
}

/// At the dome's first tangent the constraint rows differ from the force
/// columns by more than a tenth of the columns' norm; the preconditioner
/// takes the columns on both sides, exactly; and GMRES on it takes at
/// most 4/5 of the iterations it takes on the symmetric part (26 against
/// 40 when written), with no LU solve, both answers the sparse LU's to
/// 1e-8.
#[test]
fn mortar_preconditioner_couples_by_the_force_columns() {
    let pr = penetrating_dome();
    let n = pr.num_unknowns();
    let dofs = pr.model.num_dofs();
    let x = vec![0.0; n];
    let state = pr.initial_contact_state(&x);
    let mut k = vec![0.0; pr.model.pattern.nnz()];
    let (residual, _) = pr.residual_in(1.0, &x, &state, Some(&mut k)).unwrap();
    let constrained = pr.constrained_dofs();
    let symmetric = pr.model.pattern.symmetric_part(&k);
    let mut by_force = symmetric.clone();
    NonlinearProblem::symmetric_neighbour(&pr, 1.0, &x, &state, &constrained, &k, &mut by_force);
    // the couplings: each multiplier's row against its column
    let (mut difference, mut column_norm, mut active) = (0.0f64, 0.0f64, 0);
    for m in 0..n - dofs {
        let mut coupled = false;
        for a in 0..pr.model.pattern.num_nodes() {
            let Some(e) = pr.model.pattern.multiplier_entries(m, a) else {
                continue;
            };
            for (&c, &r) in e.node_rows.iter().zip(&e.multiplier_row) {
                difference += (k[c] - k[r]).powi(2);
                column_norm += k[c].powi(2);
                coupled |= k[c] != 0.0;
                assert_eq!((by_force[c], by_force[r]), (k[c], k[c]), "multiplier {m}");
            }
        }
        active += coupled as usize;
    }
    let (difference, column_norm) = (difference.sqrt(), column_norm.sqrt());
    assert!(active >= 4, "{active} active multipliers");
    assert!(
        difference > 0.1 * column_norm,
        "rows − columns {difference:.3e} against columns {column_norm:.3e}"
    );
    // the systems Newton solves: prescribed rows a scaled identity
    let mut k_free = k.clone();
    let mut symmetric = symmetric;
    for values in [&mut k_free, &mut symmetric, &mut by_force] {
        apply_identity_rows(&pr, &constrained, values);
    }
    let rhs: Vec<f64> = (0..n)
        .map(|i| if constrained[i] { 0.0 } else { -residual.r[i] })
        .collect();
    let signs = pr.model.pattern.pivot_signs();
    let mut reference = vec![0.0; n];
    let mut lu = SparseLu::default();
    let system = LinearSystem {
        pattern: pr.model.pattern.symbolic(),
        matrix: &k_free,
        symmetric_neighbour: None,
        pivot_signs: None,
    };
    lu.solve(&system, &rhs, &mut reference).unwrap();
    let (x_sym, on_symmetric) = solve(&pr, &k_free, &symmetric, &signs, &rhs);
    let (x_force, on_force) = solve(&pr, &k_free, &by_force, &signs, &rhs);
    let scale = reference.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    for (name, x) in [("symmetric part", &x_sym), ("force columns", &x_force)] {
        let error = x
            .iter()
            .zip(&reference)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        assert!(error < 1e-8 * scale, "{name}: {error:.3e} of {scale:.3e}");
    }
    assert_eq!(on_force.lu_solves, 0, "{on_force:?}");
    assert!(
        5 * on_force.krylov_iterations <= 4 * on_symmetric.krylov_iterations,
        "GMRES iterations: {} on the force columns, {} on the symmetric part (LU solves {})",
        on_force.krylov_iterations,
        on_symmetric.krylov_iterations,
        on_symmetric.lu_solves
    );
}
