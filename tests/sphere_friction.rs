//! Coulomb friction against a rigid sphere of radius 100 (examples/press-pull
//! with its plane replaced by the sphere, its left face held in x): the
//! assembled frictional tangent at a pressed-and-sheared state is the
//! derivative of the residual, and Newton converges on it to 1e-12.

use signorini::contact::friction::{ContactStatus, STICK_SHIFT};
use signorini::contact::set::ContactState;
use signorini::output::{ConvergedIncrement, StepObserver, Summary};
use signorini::problem::Problem;
use signorini::run::{RunOptions, Simulation};
use std::path::Path;

/// Every converged increment's time, unknowns and committed contact state.
#[derive(Default)]
struct States(Vec<(f64, Vec<f64>, ContactState)>);

impl StepObserver for States {
    fn on_increment(&mut self, inc: &ConvergedIncrement, _: &Summary) -> signorini::Result<()> {
        let t = inc.record.time;
        self.0.push((t, inc.unknowns.to_vec(), inc.contact.clone()));
        Ok(())
    }
}

/// examples/press-pull on a rigid sphere (centre [2, 0, −99.999999999],
/// R = 100: its top 1e-9 into the block's bottom at x = 2), the left face
/// held in x, ε_T = 100, exact stick by Newton's tangential multipliers,
/// increments pinned (0.5 pressing, 0.25 pulling), monolithic Newton to a
/// relative residual of 1e-12.
fn sphere_case() -> (Simulation, States) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let folder = root.join("examples/press-pull");
    let mut text = std::fs::read_to_string(folder.join("case.toml")).unwrap();
    for (old, new) in [
        (
            "shape = \"plane\"\npoint = [0.0, 0.0, 0.0]\nnormal = [0.0, 0.0, 1.0]",
            "shape = \"sphere\"\ncenter = [2.0, 0.0, -99.999999999]\nradius = 100.0",
        ),
        (
            "initial_increment = 0.5",
            "initial_increment = 0.5\nmax_increment = 0.5",
        ),
        (
            "initial_increment = 0.25",
            "initial_increment = 0.25\nmax_increment = 0.25",
        ),
        (
            "exact_stick = true",
            "exact_stick = true\ntangential_penalty = 100.0",
        ),
        (
            "# plane strain\n",
            "[[displacement]]\nsurface = \"left\"\nx = 0.0\n\n# plane strain\n",
        ),
    ] {
        assert!(text.contains(old), "{old}");
        text = text.replace(old, new);
    }
    text.push_str("\n[solver]\nstrategy = \"monolithic\"\nresidual_tolerance = 1e-12\n");
    let mut simulation = Simulation::from_toml(&text, &folder).unwrap();
    let options = RunOptions {
        threads: Some(2),
        output: None,
        cancel: None,
        restart: None,
    };
    let mut states = States::default();
    let outcome = simulation.run(&options, &mut states).unwrap();
    // Newton to 1e-12 at every increment (it stood at ~2e-11 before the
    // sphere's gap was computed without cancellation)
    for inc in &outcome.summary.increments {
        let last = *inc.residuals.last().unwrap();
        assert!(last <= 1e-12, "t = {}: residual {last:e}", inc.time);
    }
    (simulation, states)
}

/// The contact statuses at `(t, x)` with the history `state`.
fn statuses(pr: &Problem, t: f64, x: &[f64], state: &ContactState) -> Vec<ContactStatus> {
    let (_, reports) = pr.residual_in(t, x, state, None).unwrap();
    reports[0].iter().map(|r| r.status).collect()
}

/// The assembled tangent (elasticity, Rockafellar's normal law, friction
/// and the tangential multipliers' rows) of press-pull on the sphere at
/// its last increment's answer with the history of the increment before
/// (the block pressed and pulled to 0.8 μN: partial slip), against central
/// differences of the assembled residual, `h = 1e-7`, over every column
/// of the contact nodes' displacements and of their multipliers: relative
/// error `|fd − K e_j|∞ / |K e_j|∞ ≤ 1e-6` per column. The Jacobian's
/// shift `−δ` of the tangential multipliers' diagonal (`STICK_SHIFT`, in
/// the tangent only) is taken out first. A column whose perturbation
/// switches a node between stick and slip (on the cone's edge within `h`)
/// has no derivative there and is skipped; at most 1 % are.
#[test]
fn frictional_tangent_on_a_large_sphere_matches_finite_differences() {
    let (simulation, states) = sphere_case();
    let pr = simulation.problem();
    let n = states.0.len();
    let (t, x, _) = &states.0[n - 1];
    let (_, _, history) = &states.0[n - 2];
    let c = pr.contacts.interface(0);
    let here = statuses(pr, *t, x, history);
    let count = |s| here.iter().filter(|&&h| h == s).count();
    assert!(count(ContactStatus::Stick) > 10 && count(ContactStatus::Slip) > 10);
    let mut k = vec![0.0; pr.model.pattern.nnz()];
    pr.residual_in(*t, x, history, Some(&mut k)).unwrap();
    let dofs = pr.model.num_dofs();
    let nodes = c.nodes.len();
    let first = dofs + c.multiplier_offset;
    for (i, s) in here.iter().enumerate() {
        if *s != ContactStatus::Open {
            let eps_t = c.friction_at(i).unwrap().tangential_penalty;
            for m in [first + nodes + 2 * i, first + nodes + 2 * i + 1] {
                k[pr.model.pattern.diagonal_entry(m)] += STICK_SHIFT * c.areas[i] * eps_t;
            }
        }
    }
    let columns: Vec<usize> = (c.nodes.iter().flat_map(|&s| 3 * s..3 * s + 3))
        .chain(first..first + 3 * nodes)
        .collect();
    let pattern = pr.model.pattern.symbolic();
    let h = 1e-7;
    let (mut worst, mut skipped) = (0.0_f64, 0);
    for &j in &columns {
        let (mut xp, mut xm) = (x.clone(), x.clone());
        xp[j] += h;
        xm[j] -= h;
        if statuses(pr, *t, &xp, history) != here || statuses(pr, *t, &xm, history) != here {
            skipped += 1;
            continue;
        }
        let rp = pr.residual_in(*t, &xp, history, None).unwrap().0.r;
        let rm = pr.residual_in(*t, &xm, history, None).unwrap().0.r;
        let mut column = vec![0.0; x.len()];
        for idx in pattern.col_ptr()[j]..pattern.col_ptr()[j + 1] {
            column[pattern.row_idx()[idx]] = k[idx];
        }
        let size = column.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        let error = (0..x.len())
            .map(|i| ((rp[i] - rm[i]) / (2.0 * h) - column[i]).abs())
            .fold(0.0_f64, f64::max);
        worst = worst.max(error / size);
        assert!(error <= 1e-6 * size, "column {j}: {error:e} of {size:e}");
    }
    eprintln!(
        "sphere R = 100, {} stick / {} slip: {} columns, largest relative error {worst:.1e}, \
         {skipped} skipped on the cone's edge",
        count(ContactStatus::Stick),
        count(ContactStatus::Slip),
        columns.len()
    );
    assert!(100 * skipped <= columns.len(), "{skipped} skipped");
}
