//! Bodies in contact with each other on the condensed path, frictionless
//! (issue 32 item 3): with every body of constant stiffness, `K̃` is
//! factorised once with the dofs of every contact surface (secondary and
//! primary) ordered last, so that `(K̃⁻¹)_SS` is read off its trailing
//! block, and each increment is solved on the node driver's constraint
//! rows at the current projections:
//!
//! ```text
//! K̃ u = b + E(u) λ,   g(u) ≥ 0,   λ ≥ 0,   λ_a g_a(u) = 0,
//! ```
//!
//! column `a` of `E(u)` the gap gradient `∇g_a = Bᵀn` of secondary node `a`
//! (its own dofs and those of the primary triangle it projects on, with
//! the weights `−N_i`). A fixed point on the projections: `E` from the rows
//! at the last answer `û`, `W = Eᵀ K̃⁻¹ E` formed anew from `(K̃⁻¹)_SS` (no
//! solves while every column lies on the trailing block), the
//! complementarity problem solved once on the gaps linearised at `û`,
//! `g(û) + Eᵀ(u − û)` (one solve with the factor, and its refinement),
//! the rows read again at the answer, until the columns of the nodes that
//! carry a force change by less than [`COLUMN_TOLERANCE`] and the exact
//! gaps equal the linearised ones to the gap tolerance. On an f32 factor
//! (`[solver] linear = "auto"` from 10 000 unknowns, or `"mixed"`) the
//! block's response is that of the f32 factor's Schur complement, off by
//! its round-off: the settled rounds' forces are then solved with the
//! refined factor, the free solution shifted on the block by the
//! difference, and the rounds go on until the two agree to the gap
//! tolerance (a defect correction; one more pass on
//! examples/two-spheres). While the active
//! set holds, the next linearisation point is Anderson's mix of the last
//! rounds ([`Anderson`]) instead of the last answer. At the fixed point `K̃u = b + E(u)λ` and
//! `g(u) ⊥ λ`: the equations of the monolithic node-to-surface problem
//! (whose `∇g` at fixed projection is `Bᵀn`), whose residual the problem's
//! evaluation then checks.

use super::condensation::normal_column;
use super::{set_multipliers, zero_per_node};
use super::{Condensation, ContactNode, ContactState, IncrementSolver, Problem};
use crate::contact::interface::{ConstraintRow, Primary};
use crate::contact::mortar::Derivatives;
use crate::problem::norm;
use crate::solve::condensed::anderson::Anderson;
use crate::solve::condensed::flexibility::{take_trailing, Column, MAX_TRAILING};
use crate::solve::failure::IncrementFailure;
use crate::solve::linear_solver::SolverStatistics;
use crate::solve::method::WarmStart;
use crate::solve::newton::IterationRecord;
use crate::{Error, Result};

/// Rounds of the fixed point on the projections at most.
const MAX_ROUNDS: usize = 30;

/// Rounds kept for the Anderson mixing of the linearisation points
/// ([`Anderson`]): the plain fixed point contracts linearly (on
/// examples/two-spheres by about 0.2 a round, the change of the force
/// directions `∂E/∂u λ` that Newton's contact stiffness carries and the
/// rounds do not), 17 rounds after the active set settled.
const ANDERSON_DEPTH: usize = 3;

/// The projections are taken as settled when no entry of a column (a
/// normal component times a weight, at most 1) changes by more than this.
const COLUMN_TOLERANCE: f64 = 1e-12;

/// Passes of the defect correction of an f32 factor's block at the
/// rounds' end (module docs) at most.
const MAX_CORRECTIONS: usize = 10;

/// On an f32 factor the first correction of the block's response comes at
/// the first round whose columns change by less than this, each next one
/// once the change has fallen by [`CORRECTION_GAIN`] since.
const FIRST_CORRECTION: f64 = 1e-3;

/// See [`FIRST_CORRECTION`].
const CORRECTION_GAIN: f64 = 1e-4;

/// The frictionless condensation of bodies in contact with each other.
pub(super) struct PairCondensation {
    base: Condensation,
    /// Whether every free dof of the contact surfaces is on the trailing
    /// block: then a round needs no solve with the factor
    /// ([`crate::solve::condensed::flexibility::Flexibility::solve_on_block`]), one per increment at its end.
    on_block: bool,
    /// Rounds of the fixed point, over the run.
    rounds: usize,
    /// Per interface the gap of a node without a row
    /// ([`crate::contact::interface::ContactInterface::open_gap`]).
    open: Vec<f64>,
    /// Whether the last increment's first round left the contact pairs
    /// searched at its start ([`IncrementSolver::diagnose`]).
    left_pairs: bool,
}

/// A node of dual mortar between bodies is read again in a round only
/// where its gap at the last full reading is at most this many times the
/// largest displacement of a contact surface's node since
/// ([`FullReading::near`]).
const NEAR_GAP_PER_MOTION: f64 = 4.0;

/// The rows of every node at the point `at` of the last full reading:
/// dual mortar's segments are most of a round's cost, and a node whose
/// gap there is large against how far the surfaces moved since stays open
/// with no force; its row is taken from here, the others' read again
/// ([`rows_at`]).
struct FullReading {
    at: Vec<f64>,
    rows: Vec<Vec<Option<ConstraintRow>>>,
}

impl FullReading {
    /// Per interface of dual mortar between bodies, which nodes to read at
    /// `u`: those with no row at `at` or a gap there at most
    /// [`NEAR_GAP_PER_MOTION`] times the contact surfaces' largest
    /// displacement from `at` to `u` (every node of the other kinds);
    /// `None` where every node is to be read.
    fn near(&self, problem: &Problem, u: &[f64]) -> Option<Vec<Vec<bool>>> {
        let motion = (problem.contacts.deformable_nodes().iter())
            .flat_map(|&n| 3 * n..3 * n + 3)
            .map(|d| (u[d] - self.at[d]).abs())
            .fold(0.0, f64::max);
        let reach = NEAR_GAP_PER_MOTION * motion;
        let near: Vec<Vec<bool>> = (problem.contacts.iter().zip(&self.rows))
            .map(|(c, rows)| {
                let mortar = matches!(c.primary, Primary::Mortar(_));
                (rows.iter())
                    .map(|row| !mortar || row.as_ref().is_none_or(|r| r.gap <= reach))
                    .collect()
            })
            .collect();
        near.iter().flatten().any(|n| !n).then_some(near)
    }
}

/// The constraint rows of every interface at unknowns `u`, time `t`, on
/// the primary triangles kept in `kept`, each node's triangle then kept
/// (as Newton keeps it: a node over the kink between two triangles does
/// not flip from one round to the next). With a last full reading
/// `full`, dual mortar reads only the nodes near contact
/// ([`FullReading::near`]) and takes the others' rows from it; a reading
/// of every node becomes the full one.
fn rows_at(
    problem: &Problem,
    t: f64,
    u: &[f64],
    kept: &mut ContactState,
    full: &mut Option<FullReading>,
) -> Vec<Vec<Option<ConstraintRow>>> {
    let reference = &problem.model.mesh.nodes;
    let near = full.as_ref().and_then(|f| f.near(problem, u));
    let rows: Vec<_> = (problem.contacts.iter().enumerate())
        .map(|(ci, c)| {
            let states = &mut kept.interfaces[ci];
            let flags = near.as_ref().map(|n| n[ci].as_slice());
            let without = Derivatives::Without;
            let mut rows = c.constraint_rows_with(reference, t, u, Some(states), without, flags);
            for (state, row) in states.iter_mut().zip(&rows) {
                if let Some(row) = row {
                    state.move_to_facet(row.facet);
                }
            }
            if let (Some(flags), Some(full)) = (flags, full.as_ref()) {
                for (i, _) in flags.iter().enumerate().filter(|(_, &f)| !f) {
                    rows[i] = full.rows[ci][i].clone();
                }
            }
            rows
        })
        .collect();
    if near.is_none() {
        *full = Some(FullReading {
            at: u.to_vec(),
            rows: rows.clone(),
        });
    }
    rows
}

/// Per secondary node of every interface its owner and its column of `E`
/// from its row: `∇g = Bᵀn` and a penalty law's compliance `1/(A ε)` (an
/// empty column where the node has no primary in reach: it is open at the
/// search margin).
fn columns_of(
    problem: &Problem,
    rows: &[Vec<Option<ConstraintRow>>],
) -> (Vec<ContactNode>, Vec<Column>) {
    let (mut nodes, mut columns) = (Vec::new(), Vec::new());
    for (ci, (c, rows)) in problem.contacts.iter().zip(rows).enumerate() {
        for (i, row) in rows.iter().enumerate() {
            nodes.push(ContactNode {
                interface: ci,
                index: i,
            });
            columns.push(match row {
                Some(row) => normal_column(c.law_at(i).converged(), row),
                None => Column {
                    entries: Vec::new(),
                    compliance: 0.0,
                },
            });
        }
    }
    (nodes, columns)
}

/// The columns of `E` and the exact gaps of every secondary node at
/// unknowns `u`, from one reading of the rows ([`rows_at`], the triangles
/// kept): a row's gap is the one [`Condensation::gaps`] gives on the same
/// triangle (both the node driver's kinematics), `open[ci]` that of a
/// node of interface `ci` without a row (beyond the search margin).
fn columns_and_gaps_at(
    problem: &Problem,
    t: f64,
    u: &[f64],
    kept: &mut ContactState,
    open: &[f64],
    full: &mut Option<FullReading>,
) -> (Vec<Column>, Vec<f64>) {
    let rows = rows_at(problem, t, u, kept, full);
    let gaps = (rows.iter().zip(open))
        .flat_map(|(rows, &open)| rows.iter().map(move |r| r.as_ref().map_or(open, |r| r.gap)))
        .collect();
    (columns_of(problem, &rows).1, gaps)
}

/// The largest change of an entry between two sets of columns of the
/// nodes that carry a force (an open node's column acts on nothing, and
/// its gap is the driver's exact one), each taken as a sparse vector on
/// the unknowns (so that a node over a shared edge, whose weight on the
/// off-edge vertex is zero, has the same column on either triangle).
fn column_change(old: &[Column], new: &[Column], forces: &[f64]) -> f64 {
    use std::collections::BTreeMap;
    let sparse = |c: &Column| {
        let mut v: BTreeMap<usize, f64> = BTreeMap::new();
        for &(i, x) in &c.entries {
            *v.entry(i).or_default() += x;
        }
        v
    };
    (old.iter().zip(new).zip(forces))
        .filter(|(_, &force)| force != 0.0)
        .map(|((a, b), _)| {
            let (a_sparse, mut b_sparse) = (sparse(a), sparse(b));
            let mut change = (a.compliance - b.compliance).abs();
            for (i, x) in a_sparse {
                change = change.max((x - b_sparse.remove(&i).unwrap_or(0.0)).abs());
            }
            b_sparse.values().fold(change, |m, x| m.max(x.abs()))
        })
        .fold(0.0, f64::max)
}

/// The record of a round whose answer `u` solved the equations
/// linearised at `û` (`at`), from the increment's `start`: as its
/// residual the force residual of the monolithic equations at `u`,
/// `r = K̃u − b − E(u)λ = (E(û) − E(u))λ` (the round solved
/// `K̃u = b + E(û)λ`; an f32 factor's round-off aside, which the defect
/// correction takes up), relative to the contact force `‖E(u)λ‖`, both
/// on the free unknowns (`constrained` false); as its correction
/// `‖u − û‖ / ‖u − start‖`. The old columns `E(û)`, the new `E(u)`.
fn round_record(
    old: &[Column],
    new: &[Column],
    forces: &[f64],
    constrained: &[bool],
    (at, u, start): (&[f64], &[f64], &[f64]),
) -> IterationRecord {
    let (mut residual, mut force) = (vec![0.0; u.len()], vec![0.0; u.len()]);
    for ((a, b), &lambda) in old.iter().zip(new).zip(forces) {
        let free = |&&(i, _): &&(usize, f64)| !constrained[i];
        for &(i, e) in a.entries.iter().filter(free) {
            residual[i] += lambda * e;
        }
        for &(i, e) in b.entries.iter().filter(free) {
            residual[i] -= lambda * e;
            force[i] += lambda * e;
        }
    }
    let from = |v: &[f64]| -> Vec<f64> { u.iter().zip(v).map(|(x, y)| x - y).collect() };
    IterationRecord {
        residual: norm(&residual) / norm(&force).max(f64::MIN_POSITIVE),
        correction: norm(&from(at)) / norm(&from(start)).max(f64::MIN_POSITIVE),
        step_length: 1.0,
        switched: 0,
        linear: Default::default(),
    }
}

/// The free dofs of every contact surface's nodes (secondary and
/// primary), ordered last in the factorisation so that `(K̃⁻¹)_SS` is read
/// off its trailing block: the secondary nodes nearest to contact first
/// (by their gap at rest), each with the primary nodes it projects on,
/// then the other surface nodes, all three dofs of a node together, at
/// most [`MAX_TRAILING`] of them (a column beyond them gets its column of
/// `W` by a solve).
pub(super) fn surface_trailing(problem: &Problem) -> Vec<usize> {
    let zero = vec![0.0; problem.num_unknowns()];
    let reference = &problem.model.mesh.nodes;
    let kept = problem.contacts.initial_state(reference, &zero);
    let rows: Vec<_> = (problem.contacts.iter().enumerate())
        .map(|(ci, c)| {
            c.constraint_rows_with(
                reference,
                0.0,
                &zero,
                Some(&kept.interfaces[ci]),
                Derivatives::Without,
                None,
            )
        })
        .collect();
    trailing_of_rows(problem, &rows)
}

/// [`surface_trailing`] from the rows at rest (on the initial state).
fn trailing_of_rows(problem: &Problem, rows: &[Vec<Option<ConstraintRow>>]) -> Vec<usize> {
    let mut near: Vec<(f64, Vec<usize>)> = Vec::new();
    for (c, rows) in problem.contacts.iter().zip(rows) {
        for (i, row) in rows.iter().enumerate() {
            let Some(row) = row else {
                near.push((f64::INFINITY, vec![c.nodes[i]]));
                continue;
            };
            let nodes = std::iter::once(row.node).chain(row.primary.iter().map(|&(p, _)| p));
            near.push((row.gap, nodes.collect()));
        }
    }
    near.sort_by(|a, b| a.0.total_cmp(&b.0));
    let rest = problem.contacts.deformable_nodes();
    let ordered = near.into_iter().flat_map(|(_, nodes)| nodes).chain(rest);
    let groups = ordered.map(|n| 3 * n..3 * n + 3);
    take_trailing(groups, &problem.constrained_dofs(), MAX_TRAILING)
}

impl PairCondensation {
    /// The columns at `u = 0`, and `K̃` factorised once (in f32 where
    /// [`Condensation::factorise_on`] takes it) with every free dof of the
    /// contact surfaces' nodes ordered last.
    pub(super) fn new(problem: &Problem) -> Result<Self> {
        let zero = vec![0.0; problem.num_unknowns()];
        let mut initial = problem
            .contacts
            .initial_state(&problem.model.mesh.nodes, &zero);
        // the rows at rest once: the columns and the trailing unknowns
        let rows = rows_at(problem, 0.0, &zero, &mut initial, &mut None);
        let (nodes, columns) = columns_of(problem, &rows);
        let trailing = trailing_of_rows(problem, &rows);
        let constrained = problem.constrained_dofs();
        let surface_dofs = (problem.contacts.deformable_nodes().iter())
            .flat_map(|&n| 3 * n..3 * n + 3)
            .filter(|&d| !constrained[d])
            .count();
        let on_block = trailing.len() == surface_dofs;
        let base = Condensation::factorise_on(problem, nodes, columns, &[], trailing, true)?;
        let reference = &problem.model.mesh.nodes;
        let open = (problem.contacts.iter())
            .map(|c| c.open_gap(reference, &zero))
            .collect();
        Ok(PairCondensation {
            base,
            on_block,
            rounds: 0,
            open,
            left_pairs: false,
        })
    }

    /// The displacements and the contact force of every node at time `t`
    /// from the unknowns `start` (the last answer): the fixed point on the
    /// projections (module docs), the primary triangles kept in `kept`.
    /// Each round solves the complementarity problem once on the gaps
    /// linearised at the last answer `û`, `g(u) ≈ g(û) + E(û)ᵀ(u − û)`
    /// (affine: [`crate::solve::condensed::flexibility::Flexibility::solve_increment`] settles in one or two
    /// passes), until the columns have settled and the exact gaps equal
    /// the linearised ones to the gap tolerance.
    fn solve_increment(
        &mut self,
        problem: &Problem,
        t: f64,
        start: &[f64],
        kept: &mut ContactState,
        history: &mut Vec<IterationRecord>,
    ) -> Result<(Vec<f64>, Vec<f64>)> {
        let tolerance = 1e-12 * problem.model.size();
        let b = self.base.load(problem, t);
        let constrained = problem.constrained_dofs();
        let mut free = if self.on_block {
            let mut u_b = b.clone();
            self.base.flexibility.solve(&mut u_b)?;
            Some(u_b)
        } else {
            None
        };
        let mut full = None;
        let (mut columns, mut gaps_at) =
            columns_and_gaps_at(problem, t, start, kept, &self.open, &mut full);
        let mut at = start.to_vec();
        let mut anderson = Anderson::new(ANDERSON_DEPTH);
        let mut support: Vec<bool> = Vec::new();
        let mut corrections = Corrections {
            passes: 0,
            below: FIRST_CORRECTION,
            tolerance,
        };
        // the corrections' passes at the end take a round each
        let single = self.on_block && self.base.flexibility.is_single();
        let limit = MAX_ROUNDS + if single { MAX_CORRECTIONS } else { 0 };
        for round in 0..limit {
            self.rounds += 1;
            // anew at an increment's first round (as a restart makes it),
            // then only where the columns changed
            let flexibility = &mut self.base.flexibility;
            if round == 0 {
                flexibility.replace_columns(columns.clone())?;
            } else {
                flexibility.update_columns(columns.clone())?;
            }
            let linear = |u: &[f64]| linearised_gaps(&columns, &gaps_at, &at, u);
            let (u, forces, steps) =
                self.solve_round(free.as_deref(), &b, &linear, tolerance, history)?;
            // the first round's answer is the increment's to the rounds'
            // change of the projections: where it leaves the pairs, the
            // rounds would end on an answer the stepper cuts
            if round == 0 && !problem.contact_pairs_hold(&u, kept) {
                self.left_pairs = true;
                history.extend(steps);
                return Ok((u, forces));
            }
            let (next, exact) = columns_and_gaps_at(problem, t, &u, kept, &self.open, &mut full);
            let change = column_change(&columns, &next, &forces);
            let record = round_record(&columns, &next, &forces, &constrained, (&at, &u, start));
            tell_round(history, steps, record);
            let settled =
                change <= COLUMN_TOLERANCE && consistent(&exact, &linear(&u), &forces, tolerance);
            if settled && free.is_none() {
                return Ok((u, forces));
            }
            if let Some(u_b) = free.as_mut() {
                let round = (forces.as_slice(), u.as_slice());
                match self.round_end(&b, round, u_b, (settled, change), &mut corrections)? {
                    RoundEnd::Answer(solved) => return Ok((solved, forces)),
                    RoundEnd::Corrected(solved) => {
                        anderson.reset();
                        (columns, gaps_at) =
                            columns_and_gaps_at(problem, t, &solved, kept, &self.open, &mut full);
                        at = solved;
                        continue;
                    }
                    RoundEnd::Shifted => anderson.reset(),
                    RoundEnd::Next => {}
                }
            }
            // the next linearisation point: Anderson's mix of the rounds
            // since the active set last changed (the map is smooth there)
            let now: Vec<bool> = forces.iter().map(|f| *f != 0.0).collect();
            if now != support {
                anderson.reset();
                support = now;
            }
            let mixed = anderson.next(&at, &u);
            if mixed == u {
                (at, gaps_at, columns) = (u, exact, next);
            } else {
                (columns, gaps_at) =
                    columns_and_gaps_at(problem, t, &mixed, kept, &self.open, &mut full);
                at = mixed;
            }
        }
        Err(Error::LinearSolver(format!(
            "the projections between the bodies did not settle in {limit} condensed solves at \
             time {t}; run with [solver] strategy = \"monolithic\""
        )))
    }
}

/// A round's active-set `steps` told in `history`, the last (the
/// complementarity problem solved: no violation) replaced by the round's
/// own `record` ([`round_record`]).
fn tell_round(
    history: &mut Vec<IterationRecord>,
    mut steps: Vec<IterationRecord>,
    record: IterationRecord,
) {
    steps.pop();
    history.extend(steps);
    history.push(record);
}

/// The defect corrections of an f32 factor's block in an increment: the
/// passes at the rounds' end so far, the column change below which the
/// next early one comes, and the gap tolerance the block's displacements
/// must meet.
struct Corrections {
    passes: usize,
    below: f64,
    tolerance: f64,
}

/// What the end of a round on the block gives
/// ([`PairCondensation::round_end`]).
enum RoundEnd {
    /// The increment's displacements.
    Answer(Vec<f64>),
    /// The corrected displacements, where the rounds go on from.
    Corrected(Vec<f64>),
    /// The block's response corrected: the rounds go on from the round's
    /// answer on the shifted free solution.
    Shifted,
    /// Nothing done.
    Next,
}

impl PairCondensation {
    /// One round's complementarity problem on the gaps `linear`: on the
    /// block from the free solution `free`, else with the factor from the
    /// load `b`; its displacements, forces and active-set steps (on an
    /// error the steps so far told in `history` first).
    fn solve_round(
        &mut self,
        free: Option<&[f64]>,
        b: &[f64],
        linear: &dyn Fn(&[f64]) -> Vec<f64>,
        tolerance: f64,
        history: &mut Vec<IterationRecord>,
    ) -> Result<(Vec<f64>, Vec<f64>, Vec<IterationRecord>)> {
        let flexibility = &mut self.base.flexibility;
        let mut steps = Vec::new();
        let solved = match free {
            Some(u_b) => flexibility.solve_on_block(u_b, linear, tolerance, &mut steps),
            None => flexibility.solve_increment(b, linear, tolerance, &mut steps),
        };
        match solved {
            Ok((u, forces)) => Ok((u, forces, steps)),
            Err(e) => {
                history.extend(steps);
                Err(e)
            }
        }
    }

    /// The end of a round on the block, its `(forces, u)` in `round`,
    /// `(settled, change)` its test: where the rounds settled, the
    /// displacements off the surfaces (one solve, [`Self::corrected`]),
    /// the increment's answer on an f64 factor or where they agree with
    /// the block's to the gap tolerance, else the corrected ones to go on
    /// from (an error after [`MAX_CORRECTIONS`] such passes); on an f32
    /// factor the block's response also corrected once the column change
    /// has fallen below `corrections.below`, which then falls by
    /// [`CORRECTION_GAIN`].
    fn round_end(
        &mut self,
        b: &[f64],
        (forces, u): (&[f64], &[f64]),
        u_b: &mut [f64],
        (settled, change): (bool, f64),
        corrections: &mut Corrections,
    ) -> Result<RoundEnd> {
        let single = self.base.flexibility.is_single();
        if !(settled || single && change < corrections.below) {
            return Ok(RoundEnd::Next);
        }
        let (solved, defect) = self.corrected(b, forces, u, u_b)?;
        if settled && (!single || defect <= corrections.tolerance) {
            return Ok(RoundEnd::Answer(solved));
        }
        corrections.below = change * CORRECTION_GAIN;
        if !settled {
            return Ok(RoundEnd::Shifted);
        }
        corrections.passes += 1;
        if corrections.passes >= MAX_CORRECTIONS {
            return Err(Error::LinearSolver(format!(
                "the condensed displacements between the bodies did not meet the f32 factor's \
                 in {MAX_CORRECTIONS} corrections (largest difference {defect:.1e}); run with \
                 [solver] linear = \"ldlt\""
            )));
        }
        Ok(RoundEnd::Corrected(solved))
    }

    /// The displacements `K̃⁻¹(b + Σ_a λ_a e_a)` at the contact forces
    /// `forces` (one solve with the refined factor) and their largest
    /// difference from the block's `u` on its trailing unknowns (every
    /// free surface dof, [`Self::on_block`]), `u_b` (the free solution)
    /// shifted there by that difference: the defect of an f32 factor's
    /// block (module docs).
    fn corrected(
        &mut self,
        b: &[f64],
        forces: &[f64],
        u: &[f64],
        u_b: &mut [f64],
    ) -> Result<(Vec<f64>, f64)> {
        let flexibility = &mut self.base.flexibility;
        let mut solved = b.to_vec();
        for (a, &force) in forces.iter().enumerate() {
            flexibility.add_column(a, force, &mut solved);
        }
        flexibility.solve(&mut solved)?;
        let mut defect = 0.0f64;
        for &d in &flexibility.trailing_dofs {
            defect = defect.max((solved[d] - u[d]).abs());
            u_b[d] += solved[d] - u[d];
        }
        Ok((solved, defect))
    }
}

/// Whether the exact gaps at a round's answer are its linearised ones to
/// `tolerance` where a node carries a force, and at least `−tolerance`
/// where it does not.
fn consistent(exact: &[f64], linear: &[f64], forces: &[f64], tolerance: f64) -> bool {
    (exact.iter().zip(linear).zip(forces)).all(|((g, l), f)| {
        if *f != 0.0 {
            (g - l).abs() <= tolerance
        } else {
            *g >= -tolerance
        }
    })
}

/// The gaps linearised at `û`: `g_a(u) = g_a(û) + e_aᵀ(u − û)` for every
/// column `e_a` of `E(û)` (on every unknown, the prescribed ones too: `û`
/// may be the last increment's answer), `gaps` the exact gaps at `û`.
fn linearised_gaps(columns: &[Column], gaps: &[f64], at: &[f64], u: &[f64]) -> Vec<f64> {
    (columns.iter().zip(gaps))
        .map(|(c, g)| {
            g + c
                .entries
                .iter()
                .map(|&(i, e)| e * (u[i] - at[i]))
                .sum::<f64>()
        })
        .collect()
}

impl IncrementSolver for PairCondensation {
    fn increment(
        &mut self,
        problem: &Problem,
        t: f64,
        _: &ContactState,
        x: &mut [f64],
        trial: &mut ContactState,
        history: &mut Vec<IterationRecord>,
    ) -> Result<()> {
        let start = x.to_vec();
        self.left_pairs = false;
        let (u, forces) = self.solve_increment(problem, t, &start, trial, history)?;
        let mut pressures = zero_per_node(problem);
        if self.left_pairs {
            // the first round's displacements, for the stepper's search;
            // the failure's kind from `diagnose`
            set_multipliers(problem, &pressures, &u, t, x, trial);
            return Err(Error::LinearSolver(
                "the first round's answer left the contact pairs searched at the increment's \
                 start"
                    .into(),
            ));
        }
        let reference = &problem.model.mesh.nodes;
        let rows: Vec<_> = (problem.contacts.iter().enumerate())
            .map(|(ci, c)| {
                c.constraint_rows_with(
                    reference,
                    t,
                    &u,
                    Some(&trial.interfaces[ci]),
                    Derivatives::Without,
                    None,
                )
            })
            .collect();
        for (a, c) in self.base.nodes.iter().enumerate() {
            if let Some(row) = &rows[c.interface][c.index] {
                pressures[c.interface][c.index] = forces[a] / row.area;
            }
        }
        set_multipliers(problem, &pressures, &u, t, x, trial);
        Ok(())
    }

    /// [`IncrementFailure::PairsMoved`] where the first round's answer
    /// left the contact pairs searched at the increment's start: its
    /// unknowns are that round's, and the stepper searches again where
    /// they reach.
    fn diagnose(&self, _problem: &Problem, _t: f64) -> Option<IncrementFailure> {
        self.left_pairs.then_some(IncrementFailure::PairsMoved)
    }

    fn statistics(&self) -> (SolverStatistics, usize) {
        let (statistics, iterations) = self.base.statistics();
        (statistics, iterations + self.rounds)
    }

    fn warm_start(&self) -> WarmStart {
        self.base.warm_start()
    }

    /// The candidates replayed in their batches (their columns at the
    /// start's projections), the active set copied: the next increment's
    /// first round forms `W` anew at the checkpoint's projections, as the
    /// uninterrupted run does at every increment's start, so the resumed
    /// run is the same bit for bit.
    fn resume(&mut self, warm: &WarmStart) -> Result<()> {
        self.base.resume(warm)
    }
}
