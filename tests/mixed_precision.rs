//! Mixed precision (`[solver] linear = "mixed"`, and `auto` on large
//! systems): the LDLᵀ factorised in f32 and refined against the f64
//! tangent gives the f64 solution, and falls back to an f64 factorisation by
//! itself where the refinement stalls.

use signorini::run::{run, RunOptions, RunOutcome};
use std::path::Path;

/// `examples/<example>/case.toml` with its mesh replaced by `mesh` (a path
/// from the crate's root), each `(old, new)` of `edits` replaced, and
/// `[solver] linear = method` (monolithic, `predictor = "none"`), run in a
/// temporary folder.
fn run_with(
    example: &str,
    mesh: Option<(&str, &str)>,
    edits: &[(&str, &str)],
    method: &str,
) -> RunOutcome {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let folder = root.join("examples").join(example);
    let mut text = std::fs::read_to_string(folder.join("case.toml")).unwrap();
    if let Some((old, new)) = mesh {
        assert!(text.contains(old));
        text = text.replace(
            old,
            &format!("file = {:?}", root.join(new).display().to_string()),
        );
    }
    for (old, new) in edits {
        assert!(text.contains(old), "{old}");
        text = text.replace(old, new);
    }
    assert!(!text.contains("[solver]"));
    // the linear solver of every Newton correction: the monolithic path
    // from the plain start (the contact predictor's Josephy–Newton steps,
    // the default on these cases, factorise a tangent of their own)
    text.push_str(&format!(
        "\n[solver]\nlinear = \"{method}\"\nstrategy = \"monolithic\"\npredictor = \"none\"\n"
    ));
    let dir = tempfile::tempdir().unwrap();
    // the example's own mesh, by its relative path
    for entry in std::fs::read_dir(&folder).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "msh") {
            std::fs::copy(&path, dir.path().join(path.file_name().unwrap())).unwrap();
        }
    }
    let case = dir.path().join("case.toml");
    std::fs::write(&case, text).unwrap();
    run(
        &case,
        &RunOptions {
            output: Some(dir.path().join("results")),
            threads: None,
            cancel: None,
            restart: None,
        },
    )
    .unwrap_or_else(|e| panic!("{example}, linear = {method}: {e}"))
}

fn max_abs(u: &[f64]) -> f64 {
    u.iter().fold(0.0, |m, v| m.max(v.abs()))
}

/// The Hertz hemisphere (examples/hertz's case on the coarse
/// tests/data/hemisphere_coarse.msh, 2.4 k dofs): a saddle-point system
/// (the Rockafellar multipliers) factorised in f32 every Newton iteration,
/// refined in f64, gives the f64 LDLᵀ's displacements and contact force to
/// 1e-10 relative, in the same Newton iterations, with no fallback and
/// between 1 and 3 refinement steps per factorisation. Node-to-surface
/// named (the example takes dual mortar by default: on its tangent the f32
/// factor needed 67 refinement steps for 14 factorisations, beyond this
/// bound, not studied yet).
#[test]
fn mixed_precision_equals_f64_on_hertz() {
    let mesh = Some((
        "file = \"hemisphere.msh\"",
        "tests/data/hemisphere_coarse.msh",
    ));
    let nts = [(
        "method = \"rockafellar\"",
        "method = \"rockafellar\"\ndiscretisation = \"node_to_surface\"",
    )];
    let double = run_with("hertz", mesh, &nts, "ldlt");
    let mixed = run_with("hertz", mesh, &nts, "mixed");
    let scale = max_abs(&double.displacement);
    assert!(scale > 0.01, "{scale}");
    let difference = double
        .displacement
        .iter()
        .zip(&mixed.displacement)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    assert!(difference <= 1e-10 * scale, "{difference:e} of {scale:e}");
    let force = |o: &RunOutcome| o.summary.increments.last().unwrap().contact["pole"].force[2];
    let (fd, fm) = (force(&double), force(&mixed));
    assert!(
        fd.abs() > 0.0 && (fd - fm).abs() <= 1e-10 * fd.abs(),
        "{fd} vs {fm}"
    );
    let iterations = |o: &RunOutcome| -> Vec<usize> {
        o.summary.increments.iter().map(|i| i.iterations).collect()
    };
    assert_eq!(iterations(&double), iterations(&mixed));
    let (d, m) = (&double.summary, &mixed.summary);
    assert_eq!(
        (d.single_factorisations, d.mixed_precision_fallbacks),
        (0, 0)
    );
    assert_eq!(m.mixed_precision_fallbacks, 0);
    assert_eq!(m.single_factorisations, m.factorisations);
    assert_eq!(m.factorisations, d.factorisations);
    assert!(
        m.refinement_steps >= m.factorisations && m.refinement_steps <= 3 * m.factorisations,
        "{} refinement steps for {} factorisations",
        m.refinement_steps,
        m.factorisations
    );
}

/// Largest nodal difference between two runs' final displacements,
/// relative to the first's largest displacement.
fn relative_difference(a: &RunOutcome, b: &RunOutcome) -> f64 {
    let difference = a
        .displacement
        .iter()
        .zip(&b.displacement)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
    difference / max_abs(&a.displacement)
}

/// Newton iterations per increment.
fn iterations(o: &RunOutcome) -> Vec<usize> {
    o.summary.increments.iter().map(|i| i.iterations).collect()
}

/// examples/ogden-plate (large deformation): the tangents of its first
/// Newton iterations are indefinite (negative pivots among the
/// displacements, which the LDLᵀ keeps: only the multipliers' pivots are
/// regularised, `SparsityPattern::pivot_signs`). Their f32 factors refine
/// to the f64 solution like the others: no fallback, no LU, one f32
/// factorisation per iteration, and the run ends where the f64 LDLᵀ's and
/// the sparse LU's (partial pivoting, every iteration) end, to 1e-10 of
/// the largest displacement, in the same Newton iterations.
#[test]
fn mixed_precision_refines_the_indefinite_ogden_tangent() {
    let lu = run_with("ogden-plate", None, &[], "lu");
    let double = run_with("ogden-plate", None, &[], "ldlt");
    let mixed = run_with("ogden-plate", None, &[], "mixed");
    let (l, d, m) = (&lu.summary, &double.summary, &mixed.summary);
    let newton: usize = iterations(&lu).iter().sum();
    assert_eq!(l.lu_solves, newton);
    assert_eq!((d.lu_solves, d.mixed_precision_fallbacks), (0, 0));
    assert_eq!((m.lu_solves, m.mixed_precision_fallbacks), (0, 0));
    assert_eq!(m.single_factorisations, m.factorisations);
    assert_eq!(m.factorisations, d.factorisations);
    for run in [&double, &mixed] {
        assert_eq!(iterations(run), iterations(&lu));
        let difference = relative_difference(&lu, run);
        assert!(difference <= 1e-10, "{difference:e}");
    }
}

/// The coarse Ogden plate made nearly incompressible (`κ = 1000`,
/// `κ/μ ≈ 2400`): the tangent's condition number times f32's 6e-8 is no
/// longer small, refinement on the f32 factor stalls above 1e-12 on some
/// iterations, and the solver factorises those again in f64 by itself
/// (counted). The run equals the f64 LDLᵀ's to 1e-10, in the same Newton
/// iterations and cuts.
#[test]
fn mixed_precision_falls_back_on_a_nearly_incompressible_ogden_tangent() {
    let mesh = Some((
        "file = \"plate.msh\"",
        "examples/ogden-plate/plate-coarse.msh",
    ));
    let stiff = [("bulk_modulus = 4.0 ", "bulk_modulus = 1000.0 ")];
    let double = run_with("ogden-plate", mesh, &stiff, "ldlt");
    let mixed = run_with("ogden-plate", mesh, &stiff, "mixed");
    let (d, m) = (&double.summary, &mixed.summary);
    assert!(m.mixed_precision_fallbacks >= 1, "no fallback");
    assert!(
        m.mixed_precision_fallbacks < m.single_factorisations,
        "{} fallbacks of {} f32 factorisations",
        m.mixed_precision_fallbacks,
        m.single_factorisations
    );
    assert_eq!(d.mixed_precision_fallbacks, 0);
    // every fallback is one more f64 factorisation of the same tangent
    assert_eq!(
        m.factorisations,
        m.single_factorisations + m.mixed_precision_fallbacks
    );
    assert_eq!(m.single_factorisations, d.factorisations);
    assert_eq!(iterations(&double), iterations(&mixed));
    let difference = relative_difference(&double, &mixed);
    assert!(difference <= 1e-10, "{difference:e}");
}
