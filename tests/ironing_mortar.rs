//! `examples/ironing-mortar` (after Puso & Laursen 2004, 3D): a stiff die
//! pressed 1.4 into a soft neo-Hookean slab, then slid along it with
//! Coulomb friction (μ = 0.3) through dual mortar contact with exact
//! stick. Run on the example's coarser mesh (`coarse.msh`, from the same
//! `ironing.geo`; README there) in larger increments, to keep it short.
//!
//! References: Coulomb's law in steady sliding, the friction force μ
//! times the normal force (Puso & Laursen's check); and the smoothness
//! that mortar promises, a tangential force that stays level while the
//! slab's nodes enter and leave the contact.

use signorini::contact::friction::STICK_SHIFT;
use signorini::contact::interface::NodeReport;
use signorini::output::summary::IncrementSummary;
use signorini::problem::{ContactState, Problem};
use signorini::run::{RunOptions, Simulation};
use signorini::solve::backend::linear_solver;
use signorini::solve::josephy::Josephy;
use signorini::solve::linear_solver::SolverStatistics;
use signorini::solve::method::{Increment, IncrementMethod, Monolithic};
use signorini::solve::newton::{IterationRecord, NewtonOutcome};
use signorini::solve::stepping::resume_steps;
use std::path::{Path, PathBuf};

const MU: f64 = 0.3;

/// The example's case text on `coarse.msh`, pressed in 5 increments and
/// slid 2.0 (to t = 1.5) in increments of 0.2, writing into `out`; and
/// the example's folder (the mesh's).
fn coarse_case(out: &Path) -> (String, PathBuf) {
    let (text, folder) = example_case(out);
    if std::env::var("IRONING_FULL").is_ok() {
        // diagnostics on the example's own mesh and increments
        return (text, folder);
    }
    let edits = [
        ("file = \"ironing.msh\"", "file = \"coarse.msh\""),
        // the example's short first slide increments (its README): the
        // coarse run slides from the press's end in its own increments
        (
            "[[step]]\nname = \"slide_start\"\nend_time = 1.025\ninitial_increment = 0.00625\nmax_increment = 0.025\n\n",
            "",
        ),
        (
            "end_time = 1.0\ninitial_increment = 0.1\nmax_increment = 0.1",
            "end_time = 1.0\ninitial_increment = 0.2\nmax_increment = 0.2",
        ),
        (
            "end_time = 2.0\ninitial_increment = 0.025\nmax_increment = 0.025",
            "end_time = 1.5\ninitial_increment = 0.05\nmax_increment = 0.05",
        ),
    ];
    let mut case = text;
    for (from, to) in edits {
        assert!(case.contains(from), "case.toml no longer holds {from:?}");
        case = case.replace(from, to);
    }
    (case, folder)
}

/// The example's case text as committed, writing into `out` (no VTU
/// series but the steps' ends), and the example's folder.
fn example_case(out: &Path) -> (String, PathBuf) {
    let folder = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/ironing-mortar");
    let text = std::fs::read_to_string(folder.join("case.toml")).unwrap();
    let case = text.replace("every = 5", "every = 1000");
    let case = case.replace("[output]\n", &format!("[output]\nfolder = {out:?}\n"));
    (case, folder)
}

/// The example's case on `coarse.msh` ([`coarse_case`]), run.
fn coarse_run() -> Vec<IncrementSummary> {
    run_case(coarse_case).0
}

/// The case that `case` writes for an output folder, run there: its
/// increments and the example's folder.
fn run_case(case: fn(&Path) -> (String, PathBuf)) -> (Vec<IncrementSummary>, PathBuf) {
    let out = tempfile::tempdir().unwrap();
    let (case, folder) = case(out.path());
    let mut simulation = Simulation::from_toml(&case, &folder).unwrap();
    let outcome = simulation
        .run(
            &RunOptions::default(),
            &mut signorini::output::observer::Silent,
        )
        .expect("the ironing case runs");
    (outcome.summary.increments, folder)
}

/// Steady sliding, from a slide of 1.6 on (t ≥ 1.4: the die's tangential
/// reaction levels off there on both meshes, the slab's shear having
/// built up). The die's reaction `F = (F_x, F_z)` balances the contact
/// force on it: the normal pressures' resultant `N` (summary.json's
/// `force`, `Σ D_j λ_j n_j`) and the friction. The friction along x over
/// the normal load, `(F_x − N_x)/F_z`, is Coulomb's μ to 5 % (the slab's
/// surface slips partly sideways as it is squeezed out under the die, so
/// the x share falls a little short of μ: 0.298–0.301 on the example's
/// mesh); `F_x/F_z` itself is ≈ 0.35, above μ by the ploughing `N_x` of
/// the deep indentation (printed, not asserted). The die's tangential
/// reaction `F_x` stays within 1 % of its mean (the ripple bound).
#[test]
fn ironing_mortar_slides_smoothly_at_mu() {
    let increments = coarse_run();
    let steady: Vec<&IncrementSummary> =
        increments.iter().filter(|i| i.time >= 1.4 - 1e-9).collect();
    assert!(steady.len() >= 3, "{} steady increments", steady.len());
    for i in &steady {
        let [fx, _, fz] = i.reaction_forces["die_top"];
        let normal = i.contact["ironing"].force;
        let friction = (fx - normal[0]) / -fz;
        println!(
            "t = {:.3}: F_x {fx:.5} F_z {:.5} F_x/F_z {:.4} N_x {:.5} (F_x − N_x)/F_z {friction:.4} iterations {}",
            i.time,
            -fz,
            fx / -fz,
            normal[0],
            i.iterations
        );
        assert!(
            (friction - MU).abs() < 0.05 * MU,
            "t = {}: (F_x − N_x)/F_z = {friction}",
            i.time
        );
    }
    assert_forces_balance_the_die(&increments);
    assert_newton_iterations(&increments);
    let fx: Vec<f64> = steady
        .iter()
        .map(|i| i.reaction_forces["die_top"][0])
        .collect();
    let mean = fx.iter().sum::<f64>() / fx.len() as f64;
    let ripple = fx.iter().map(|f| (f - mean).abs()).fold(0.0, f64::max) / mean.abs();
    println!(
        "F_x mean {mean:.5}, largest deviation {:.3} %",
        100.0 * ripple
    );
    assert!(ripple < 0.01, "F_x ripple {ripple}");
}

/// After every increment, `summary.json`'s contact forces are the forces
/// assembled on the nodes: the die's reaction (`Σ (f_int − f_ext)` over
/// its loaded face, the die itself in equilibrium) equals the slab's
/// normal and tangential contact force, `force + tangential_force`
/// (`Σ D_j λ_j n_j + Σ D_j t_T`), and minus the force on the die's arc,
/// `primary_force`, to 1e-8 of the reaction (the residual tolerance).
fn assert_forces_balance_the_die(increments: &[IncrementSummary]) {
    for i in increments.iter().filter(|i| i.time > 0.4) {
        let reaction = i.reaction_forces["die_top"];
        let c = &i.contact["ironing"];
        let primary = c.primary_force.expect("mortar reports the die's force");
        let size = reaction[0].hypot(reaction[2]);
        for d in 0..3 {
            let secondary = c.force[d] + c.tangential_force[d];
            println!(
                "t = {:.3} {d}: reaction {:.10} secondary {secondary:.10} primary {:.10}",
                i.time, reaction[d], primary[d]
            );
            assert!(
                (reaction[d] - secondary).abs() < 1e-8 * size,
                "t = {}: reaction {reaction:?}, force + tangential_force {secondary}",
                i.time
            );
            assert!(
                (reaction[d] + primary[d]).abs() < 1e-8 * size,
                "t = {}: reaction {reaction:?}, primary_force {primary:?}",
                i.time
            );
        }
    }
}

/// The example itself (`case.toml` on `ironing.msh`, 52 increments): no
/// cut and at most 6 Newton iterations in every increment, the issue's
/// bound (measured 2026-11-28: 3–6; the first slide increment took 7 in
/// one increment of 0.025, 5, 4 and 4 in the short increments the case now
/// starts the slide with, README "Newton at the stick–slip turn"); and the
/// die's reaction after every increment equal to the committed
/// `figures/die_reaction.csv` to 1e-8 of its largest force (the residual
/// tolerance). About 20 minutes on a loaded 2-core machine:
/// `cargo test --release --test ironing_mortar -- --ignored ironing_mortar_example_within_six_iterations`
#[test]
#[ignore = "about 20 min; run with --ignored (the example's whole run)"]
fn ironing_mortar_example_within_six_iterations() {
    let (increments, folder) = run_case(example_case);
    assert_newton_iterations(&increments);
    let csv = std::fs::read_to_string(folder.join("figures/die_reaction.csv")).unwrap();
    let rows: Vec<Vec<f64>> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), increments.len(), "one row per increment");
    let largest = rows
        .iter()
        .flat_map(|r| &r[1..])
        .fold(0.0, |m: f64, v| m.max(v.abs()));
    for (row, i) in rows.iter().zip(&increments) {
        let reaction = i.reaction_forces["die_top"];
        assert!(
            (row[0] - i.time).abs() < 1e-9,
            "t = {} against {}",
            i.time,
            row[0]
        );
        for d in 0..3 {
            assert!(
                (reaction[d] - row[d + 1]).abs() < 1e-8 * largest,
                "t = {}: reaction {reaction:?}, committed {row:?}",
                i.time
            );
        }
    }
}

/// Newton per increment on the coarse run: no cut, and at most 6
/// iterations in every increment (the bound). Measured
/// 2026-11-27: 4–6; the press's first contact (0.01 apart, then pressed
/// 0.28) 6 with 20, 7 and 2 status switches, the slide at t = 1.3 6 with
/// 14 and 6 (7 each before a closing node's first-contact fraction was
/// taken at its solution value, mortar_friction.rs). On the example's own
/// mesh the first slide increment took 18, then 7, and the example now
/// starts its slide in short increments (its README, "Newton at the
/// stick–slip turn"; [`ironing_mortar_example_within_six_iterations`]).
/// Each increment's residuals and status switches are printed.
fn assert_newton_iterations(increments: &[IncrementSummary]) {
    for i in increments {
        let residuals: Vec<String> = i.residuals.iter().map(|r| format!("{r:.1e}")).collect();
        println!(
            "{} t = {:.3}: {} iterations, residuals {}, switched {:?}",
            i.step_name,
            i.time,
            i.iterations,
            residuals.join(" "),
            i.switched
        );
    }
    for i in increments {
        assert!(
            i.cuts == 0 && i.iterations <= 6,
            "{} t = {}: {} iterations, {} cuts",
            i.step_name,
            i.time,
            i.iterations,
            i.cuts
        );
    }
}

/// Newton's iterates as the run takes them ([`Monolithic`]), stopped in
/// the slide (from `from`) at the first iteration whose line search
/// shortens the step (or, if none does, at iteration `fallback` of the
/// slide's first increment; with `IRONING_STOP_AT=k`, at its iteration
/// `k` whatever the step): the iterate `x` there, its trial history and
/// the increment's time. Each slide iteration's relative residual, step,
/// status switches and correction `‖α δu‖/‖Δu‖` are printed.
struct StopInSlide<'a> {
    newton: Monolithic<'a>,
    from: f64,
    fallback: usize,
    captured: Option<(Vec<f64>, ContactState, f64)>,
}

impl IncrementMethod<Problem> for StopInSlide<'_> {
    fn name(&self) -> &'static str {
        "monolithic"
    }

    fn pattern_changed(&mut self, problem: &Problem) -> signorini::Result<()> {
        self.newton.pattern_changed(problem)
    }

    fn solve(
        &mut self,
        problem: &Problem,
        increment: &Increment<'_>,
        u: &[f64],
        state: &mut ContactState,
        x: &mut Vec<f64>,
        on_iteration: &mut dyn FnMut(&IterationRecord) -> bool,
    ) -> NewtonOutcome<Vec<Vec<NodeReport>>> {
        if increment.time <= self.from {
            return self
                .newton
                .solve(problem, increment, u, state, x, on_iteration);
        }
        let first = (increment.start - self.from).abs() < 1e-9;
        let (fallback, mut count, mut stopped) = (self.fallback, 0, false);
        let mut stop = |r: &IterationRecord| {
            count += 1;
            println!(
                "t = {:.3} iteration {count}: residual {:.2e} step {:.3} switched {} correction {:.2e}",
                increment.time, r.residual, r.step_length, r.switched, r.correction
            );
            stopped = if let Ok(at) = std::env::var("IRONING_STOP_AT") {
                first && count == at.parse::<usize>().unwrap()
            } else {
                r.step_length < 1.0 || (first && count == fallback)
            };
            on_iteration(r) && !stopped
        };
        let outcome = self
            .newton
            .solve(problem, increment, u, state, x, &mut stop);
        if stopped {
            self.captured = Some((x.clone(), state.clone(), increment.time));
        }
        outcome
    }

    fn statistics(&self) -> SolverStatistics {
        IncrementMethod::<Problem>::statistics(&self.newton)
    }
}

/// The coarse ironing run as the example runs it, stopped at a slide
/// iterate ([`StopInSlide`]): the problem (its pattern that of the
/// increment), the iterate, its trial history and its time.
fn slide_iterate() -> (Problem, Vec<f64>, ContactState, f64) {
    let out = tempfile::tempdir().unwrap();
    let (text, folder) = coarse_case(out.path());
    let case = signorini::case::from_toml(&text, &folder).unwrap();
    let (mut problem, _) = signorini::run::problem_as_run(&case).unwrap();
    let ordering = signorini::run::fill_reducing_ordering(&problem).unwrap();
    let mut solver = linear_solver(&problem.settings, ordering, 0);
    let mut josephy = Josephy::default();
    let newton = Monolithic::new(&problem, &mut *solver, &mut josephy);
    let mut method = StopInSlide {
        newton,
        from: 1.0,
        fallback: if std::env::var("IRONING_FULL").is_ok() {
            usize::MAX
        } else {
            2
        },
        captured: None,
    };
    let mut quiet = Quiet;
    let result = resume_steps(
        &mut problem,
        &mut method,
        None,
        &mut quiet,
        out.path().into(),
        None,
    );
    let (x, state, t) = method.captured.take().expect("stopped in the slide");
    assert!(result.is_err(), "the run stops where it was stopped");
    (problem, x, state, t)
}

/// The stepper's observer that keeps nothing.
struct Quiet;

impl signorini::solve::stepping::StepObserver<Problem> for Quiet {
    fn on_converged(
        &mut self,
        _: &Problem,
        _: &signorini::solve::stepping::IncrementRecord,
        _: &[f64],
        _: &signorini::solve::nonlinear::Evaluation<Vec<Vec<NodeReport>>>,
        _: &ContactState,
    ) -> signorini::Result<()> {
        Ok(())
    }
}

/// The unknowns' kinds: displacement, normal multiplier, tangential
/// multiplier.
const KINDS: [&str; 3] = ["u", "λ_N", "λ_T"];

/// The largest `|K_ij − FD_ij|` and `|K_ij|` of each block (rows × columns
/// by kind, [`KINDS`]) of the assembled tangent at `(t, x, state)` against
/// central differences of the assembled residual (step `h`), over the
/// columns of the contact nodes' displacements and every multiplier.
/// The tangential rows' diagonal is compared after taking out the
/// Jacobian's shift `−STICK_SHIFT A_s ε_T` (friction.rs), which the
/// residual does not hold.
fn tangent_block_errors(
    pr: &Problem,
    t: f64,
    x: &[f64],
    state: &ContactState,
    h: f64,
) -> [[(f64, f64); 3]; 3] {
    let (n, dofs) = (pr.num_unknowns(), pr.model.num_dofs());
    let interface = pr.contacts.interface(0);
    let normal = interface.nodes.len();
    let kind = |i: usize| match i {
        i if i < dofs => 0,
        i if i < dofs + normal => 1,
        _ => 2,
    };
    let mut k = vec![0.0; pr.model.pattern.nnz()];
    pr.residual_in(t, x, state, Some(&mut k)).unwrap();
    let pattern = pr.model.pattern.symbolic();
    let mut columns: Vec<usize> = pr
        .deformable_contact_nodes()
        .iter()
        .flat_map(|&a| 3 * a..3 * a + 3)
        .collect();
    columns.extend(dofs..n);
    let eps_t = interface.friction.expect("friction").tangential_penalty;
    let rows_of = |j: usize| &pattern.row_idx()[pattern.col_ptr()[j]..pattern.col_ptr()[j + 1]];
    let mut blocks = [[(0.0f64, 0.0f64); 3]; 3];
    for group in structurally_orthogonal(&columns, n, rows_of) {
        let (mut xp, mut xm) = (x.to_vec(), x.to_vec());
        for &j in &group {
            xp[j] += h;
            xm[j] -= h;
        }
        let rp = pr.residual_in(t, &xp, state, None).unwrap().0.r;
        let rm = pr.residual_in(t, &xm, state, None).unwrap().0.r;
        // the rows of the group's columns are disjoint: each row's
        // difference is one column's (a row outside them, which the
        // pattern says no column reaches, must not change)
        let mut owner: Vec<Option<usize>> = vec![None; n];
        for &j in &group {
            rows_of(j).iter().for_each(|&i| owner[i] = Some(j));
        }
        for i in 0..n {
            let fd = (rp[i] - rm[i]) / (2.0 * h);
            let Some(j) = owner[i] else {
                let block = &mut blocks[kind(i)][kind(group[0])];
                block.0 = block.0.max(fd.abs());
                continue;
            };
            let idx = pattern.col_ptr()[j] + rows_of(j).iter().position(|&r| r == i).unwrap();
            let exact = k[idx];
            let mut err = (fd - exact).abs();
            if i == j && kind(i) == 2 {
                // a closed node's Jacobian shift (none where open)
                let node = (i - dofs - normal) / 2;
                let shift = STICK_SHIFT * interface.areas[node] * eps_t;
                err = err.min((fd - exact - shift).abs());
            }
            let block = &mut blocks[kind(i)][kind(j)];
            block.0 = block.0.max(err);
            block.1 = block.1.max(exact.abs());
        }
    }
    blocks
}

/// `columns` in groups whose rows (`rows_of`, of `n`) do not meet, so that
/// one central difference per group gives each of its columns
/// (Curtis, Powell & Reid 1974; greedy, in the given order).
fn structurally_orthogonal<'a>(
    columns: &[usize],
    n: usize,
    rows_of: impl Fn(usize) -> &'a [usize],
) -> Vec<Vec<usize>> {
    let mut groups: Vec<(Vec<usize>, Vec<bool>)> = Vec::new();
    for &j in columns {
        let fits = |used: &Vec<bool>| rows_of(j).iter().all(|&i| !used[i]);
        let at = match groups.iter().position(|(_, used)| fits(used)) {
            Some(at) => at,
            None => {
                groups.push((Vec::new(), vec![false; n]));
                groups.len() - 1
            }
        };
        let (group, used) = &mut groups[at];
        group.push(j);
        rows_of(j).iter().for_each(|&i| used[i] = true);
    }
    groups.into_iter().map(|(group, _)| group).collect()
}

/// The assembled tangent of the frictional mortar ironing (every row: the
/// structure's with the contact forces, the normal and the tangential
/// multipliers' equations) against central differences of the assembled
/// residual, at a real slide state of the coarse run: Newton's iterate
/// where the line search first shortens a step in the slide
/// ([`slide_iterate`]), with the trial history Newton holds there
/// (statuses as the residual decides them at that state; a node at a kink
/// would show as a mismatch). Columns: the contact nodes' displacements
/// and every multiplier. The largest error of each block relative to the
/// block's largest entry is at most 1e-6 (central differences with
/// `h = 1e-7` on coordinates of order 1: truncation `O(h²)` ≈ 1e-14 of the
/// third derivative, round-off ≈ 1e-16 ‖r‖/h ≈ 1e-9 ‖r‖; a missing
/// term is off by its own size).
///
/// Not in the default run: it takes about two minutes on a quiet machine
/// (the FD columns of a whole slide state), which `.ci/run`'s 20-minute
/// budget cannot carry. Run it with
/// `cargo test --release --test ironing_mortar -- --ignored frictional_mortar_tangent`.
#[test]
#[ignore = "about 2 min; run with --ignored (the FD check of the frictional mortar tangent)"]
fn frictional_mortar_tangent_matches_fd_at_a_slide_iterate() {
    let (pr, x, state, t) = slide_iterate();
    let blocks = tangent_block_errors(&pr, t, &x, &state, 1e-7);
    for (r, row) in blocks.iter().enumerate() {
        for (c, &(err, size)) in row.iter().enumerate() {
            let relative = if size > 0.0 { err / size } else { err };
            println!(
                "∂r_{}/∂{}: largest |K − FD| {err:.2e}, largest |K| {size:.2e}, relative {relative:.2e}",
                KINDS[r], KINDS[c]
            );
            assert!(
                relative <= 1e-6,
                "∂r_{}/∂{}: relative error {relative:e} at t = {t}",
                KINDS[r],
                KINDS[c]
            );
        }
    }
}

/// Diagnostics (not a check): the run stopped where the slide's line
/// search first shortens a step ([`slide_iterate`]; `IRONING_FULL=1` for
/// the example's own mesh and increments), and every closed node there:
/// status, committed status and gap, gap, pressure, `|t_T|` against
/// `μ t_N`.
#[test]
#[ignore]
fn ironing_mortar_slide_iterate_nodes() {
    let (pr, x, state, t) = slide_iterate();
    let (_, reports) = pr.residual_in(t, &x, &state, None).unwrap();
    let interface = pr.contacts.interface(0);
    for (i, (r, s)) in reports[0].iter().zip(&state.interfaces[0]).enumerate() {
        if !r.active && s.friction.status == signorini::contact::friction::ContactStatus::Open {
            continue;
        }
        let node = interface.nodes[i];
        let position: Vec<f64> = (0..3)
            .map(|d| pr.model.mesh.nodes[node][d] + x[3 * node + d])
            .collect();
        let t_t = nalgebra::Vector3::from(r.tangential_traction).norm();
        println!(
            "node {node} at ({:.3}, {:.3}, {:.3}): {:?} (committed {:?}, gap {:.3e}) gap {:.3e} t_N {:.4e} |t_T| {:.4e} μ t_N {:.4e} D {:?}",
            position[0], position[1], position[2], r.status, s.friction.status, s.gap, r.gap, r.pressure, t_t, MU * r.pressure, r.area
        );
    }
}
