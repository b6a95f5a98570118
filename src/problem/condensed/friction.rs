//! The frictional condensed path: Coulomb friction against rigid planes,
//! rigid spheres or cylinders, or between bodies, on bodies of constant stiffness, three unknowns per
//! contact node, solved per increment by the dense semismooth Newton method
//! of [`crate::solve::condensed::cone`], with the friction history
//! committed per increment by the problem itself (as the monolithic path
//! does).
//!
//! ## The node's relative motion
//! The columns of `E` are the rows of each node's lever `B` (the node
//! driver's [`ConstraintRow::lever_row`]: `e_s` against a rigid obstacle,
//! `e_s − Σ N_i e_{p_i}` between bodies), one per free component of the
//! secondary node, so that `Eᵀu` is the node's relative motion `v = B u`
//! and `E A t` carries its traction to both bodies. The cone problem's
//! gap and slip are those of [`Linearisation`]: exact at rest against a
//! rigid plane; between bodies at the last answer `x̂`, the increment
//! solved again at its answer (with `W` formed anew from `(K̃⁻¹)_SS`, the
//! surfaces' dofs ordered last, [`super::pairs::surface_trailing`]) until
//! the answer is the point it was linearised at. A component prescribed
//! on the secondary node has no column, but between bodies its lever
//! reaches primary dofs that are free (a node on a symmetry plane over a
//! vertex off it): that reaction is carried as a load, at the last
//! round's tractions, until it settles too
//! ([`FrictionalCondensation::uncolumned_force`]). That fixed point is the
//! monolithic node-to-surface problem with Coulomb friction, which the
//! problem's evaluation then checks. Bodies held only by contact are not
//! condensed between bodies (no shift).
//!
//! ## A body that only contact holds
//! A body held in a tangential direction by friction alone (examples/
//! press-pull: nothing prescribes its x displacement) has a singular `K̃`.
//! The dofs of the nodes touching the obstacle at the start get a shift
//! `ρ` (the scale of `K̃`'s prescribed rows, the mean diagonal):
//! `K̂ = K̃ + ρ Σ_{a touching} I₃`, regular when those nodes with the
//! prescribed displacements hold every rigid-body motion
//! ([`super::not_applicable`] checks it). The shift is exact: it is added
//! on both sides, `K̂ u = b + E (A t + ρ P_S u_F)`, so the condensed
//! problem carries `ρ P_S u_F` ([`ConeProblem::shift`]). Where the
//! prescribed displacements hold the body no dof is shifted.
//!
//! ## Candidates
//! `Ŵ = Eᵀ K̂⁻¹ E` over the free dofs of the candidate nodes: those
//! touching or penetrating at the start, then every node that penetrates
//! at an increment's answer (the increment is solved again with it; its
//! columns are solves with the same factor, not shifted). One
//! factorisation per run.
//!
//! ## Increments
//! The next increment grows (`[solver] growth_factor`, up to the step's
//! `max_increment`) after an easy one, as Newton's do: one whose first
//! contact solve, the semismooth Newton iterations from the last answer
//! (the analogue of Newton's from the converged state; the rounds after
//! it follow the projections, the solves after it the nodes that
//! entered), took at most `[solver] easy_iterations`. Only the count, not
//! Newton's second clause ("settled and fast",
//! [`crate::solve::record`]): a semismooth solve starts from the last
//! increment's statuses and settles them within its count, and with the
//! clause examples/press-pull's pull increments (8–9 iterations, the last
//! switch at the fourth) grew where Newton's (21–26) do not, moving its
//! answer by 1.1e-5. Friction's answer depends on the increments, so the
//! condensed and the monolithic path equal each other where they take the
//! same ones: compare with `max_increment` pinned.

use super::linearisation::Linearisation;
use super::{constraint_rows, Condensation, ContactNode, ContactState, IncrementSolver, Problem};
use crate::contact::friction::Coulomb;
use crate::contact::interface::ConstraintRow;
use crate::contact::mortar::Derivatives;
use crate::solve::condensed::cone::{
    solve_cone, ConeNode, ConeProblem, ConeSolution, Flexibility, TangentialLaw,
};
use crate::solve::condensed::flexibility::Column;
use crate::solve::failure::IncrementFailure;
use crate::solve::linear_solver::SolverStatistics;
use crate::solve::method::WarmStart;
use crate::solve::newton::IterationRecord;
use crate::{Error, Result};
use nalgebra::Vector3;

/// A secondary node of an interface.
struct FrictionNode {
    interface: usize,
    index: usize,
    node: usize,
    /// Its unit normal at the last linearisation (constant against a
    /// plane).
    normal: Vector3<f64>,
    /// Its free components `d` with their columns in [`Condensation::nodes`].
    columns: Vec<(usize, usize)>,
}

/// The frictional condensed solver of a run.
pub(super) struct FrictionalCondensation {
    /// The factor of `K̂`, one column `e_d` per free dof of every contact
    /// node, `Ŵ` over the candidates' columns.
    base: Condensation,
    contact: Vec<FrictionNode>,
    /// The column's contact node and component.
    column_owner: Vec<(usize, usize)>,
    /// Candidate nodes (into `contact`), in the order of their columns.
    candidates: Vec<usize>,
    /// The nodes that joined after the first candidates, in their batches
    /// (a restart's replay).
    batches: Vec<Vec<usize>>,
    is_candidate: Vec<bool>,
    /// `Ŵ` and its Cholesky factor, once per `Ŵ`.
    factor: Option<Flexibility>,
    /// Per column of `Ŵ`: shifted by `ρ`.
    shifted: Vec<bool>,
    /// The shift `ρ` (0 when nothing is shifted).
    shift: f64,
    /// The last answer per contact node (the next increment's start).
    traction: Vec<Vector3<f64>>,
    /// Exact stick's multiplier `λ_T` per contact node at the last answer
    /// ([`ConeSolution::multiplier`]), handed to the friction history.
    multiplier: Vec<Vector3<f64>>,
    displacement: Vec<Option<f64>>,
    iterations: usize,
    /// Between bodies: the rows follow the projections (module docs).
    projected: bool,
    /// The iterations of the last increment's first contact solve (module
    /// docs, "Increments").
    first_solve: Option<usize>,
}

/// Rounds of the fixed point on the projections at most (between bodies).
const MAX_ROUNDS: usize = 30;

/// The projections are taken as settled when no normal component or
/// primary weight changes by more than this, and the linearised gaps and
/// slips are exact to this fraction of the model size.
const ROUND_TOLERANCE: f64 = 1e-12;

/// The gaps of every node of interface `c` at the reference position
/// plus the prescribed displacements at `t = 0`.
fn initial_gaps(problem: &Problem, c: usize) -> Vec<f64> {
    let mut x = vec![0.0; problem.num_unknowns()];
    problem.apply_prescribed(0.0, &mut x);
    problem
        .contacts
        .interface(c)
        .gaps(&problem.model.mesh.nodes, 0.0, &x, None)
}

/// The touching tolerance: 1e-12 of the model size.
fn touching(problem: &Problem) -> f64 {
    1e-12 * problem.model.size()
}

/// The free dofs of the secondary nodes that touch or penetrate at the
/// start: the ones the frictional path shifts.
pub(super) fn initially_touching_dofs(problem: &Problem) -> Vec<usize> {
    let constrained = problem.constrained_dofs();
    let tolerance = touching(problem);
    let mut dofs = Vec::new();
    for (ci, c) in problem.contacts.iter().enumerate() {
        for (i, g) in initial_gaps(problem, ci).iter().enumerate() {
            if *g <= tolerance {
                let node = c.nodes[i];
                dofs.extend((0..3).map(|d| 3 * node + d).filter(|&d| !constrained[d]));
            }
        }
    }
    dofs
}

/// The contact nodes of a run and their columns of `E`.
#[derive(Default)]
struct ContactColumns {
    owners: Vec<ContactNode>,
    columns: Vec<Column>,
    column_owner: Vec<(usize, usize)>,
    contact: Vec<FrictionNode>,
    /// The nodes touching or penetrating at the start (into `contact`).
    initial: Vec<usize>,
}

impl ContactColumns {
    /// One node per secondary node of every interface, one column per free
    /// component `d` of the node, row `d` of its lever `B` at `u = 0`
    /// (`rows`; a node with no primary in reach gets `e_s`: its column
    /// follows its projection once it has one).
    fn of(problem: &Problem, rows: &[Vec<Option<ConstraintRow>>]) -> Self {
        let constrained = problem.constrained_dofs();
        let tolerance = touching(problem);
        let mut all = ContactColumns::default();
        for (ci, rows) in rows.iter().enumerate() {
            let gaps = initial_gaps(problem, ci);
            let c = problem.contacts.interface(ci);
            for (i, row) in rows.iter().enumerate() {
                let node = row.as_ref().map_or(c.nodes[i], |r| r.node);
                let mut own = Vec::new();
                for d in (0..3).filter(|&d| !constrained[3 * node + d]) {
                    own.push((d, all.columns.len()));
                    all.column_owner.push((all.contact.len(), d));
                    all.owners.push(ContactNode {
                        interface: ci,
                        index: i,
                    });
                    let entries = row
                        .as_ref()
                        .map_or_else(|| vec![(3 * node + d, 1.0)], |r| r.lever_row(d));
                    all.columns.push(Column {
                        entries,
                        compliance: 0.0,
                    });
                }
                if gaps[i] <= tolerance {
                    all.initial.push(all.contact.len());
                }
                all.contact.push(FrictionNode {
                    interface: ci,
                    index: i,
                    node,
                    normal: row.as_ref().map_or(Vector3::z(), |r| r.normal),
                    columns: own,
                });
            }
        }
        all
    }
}

impl FrictionalCondensation {
    /// The contact nodes and their columns; `K̂` factorised once (against
    /// rigid planes shifted where only contact holds the body; between
    /// bodies with the surfaces' dofs last); the nodes touching at the
    /// start made candidates.
    pub(super) fn new(problem: &Problem) -> Result<Self> {
        // rounds at the current rows between bodies and against a curved
        // rigid obstacle; the surfaces' dofs last (no shift) between bodies
        let projected = super::has_moving_rows(problem);
        let between = super::has_pairs(problem);
        let constrained = problem.constrained_dofs();
        let zero = vec![0.0; problem.num_unknowns()];
        let rows = if projected {
            let reference = &problem.model.mesh.nodes;
            let mut kept = problem.contacts.initial_state(reference, &zero);
            Linearisation::at(problem, 0.0, &zero, &mut kept).rows
        } else {
            constraint_rows(problem, 0.0, &zero, Derivatives::With)
        };
        let all = ContactColumns::of(problem, &rows);
        // shift only where the prescribed displacements do not hold a body
        let floating = !between && super::free_rigid_body_mode(problem, &constrained).is_some();
        let shifted_dofs: Vec<usize> = if floating {
            (all.initial.iter())
                .flat_map(|&a| {
                    let node = all.contact[a].node;
                    all.contact[a]
                        .columns
                        .iter()
                        .map(move |&(d, _)| 3 * node + d)
                })
                .collect()
        } else {
            Vec::new()
        };
        let (owners, columns) = (all.owners, all.columns);
        let base = if between {
            let trailing = super::pairs::surface_trailing(problem);
            Condensation::factorise_on(problem, owners, columns, &[], trailing, false)?
        } else {
            Condensation::factorise(problem, owners, columns, &shifted_dofs, 1.0, false)?
        };
        let shift = if floating {
            base.flexibility.scale
        } else {
            0.0
        };
        let count = all.contact.len();
        let columns_count = base.flexibility.columns.len();
        let mut condensation = FrictionalCondensation {
            base,
            contact: all.contact,
            column_owner: all.column_owner,
            candidates: Vec::new(),
            batches: Vec::new(),
            is_candidate: vec![false; count],
            factor: None,
            shifted: Vec::new(),
            shift,
            traction: vec![Vector3::zeros(); count],
            multiplier: vec![Vector3::zeros(); count],
            displacement: vec![None; columns_count],
            iterations: 0,
            projected,
            first_solve: None,
        };
        condensation.grow(&all.initial, floating)?;
        Ok(condensation)
    }

    /// Make the contact nodes `new` candidates: their columns of `Ŵ`.
    fn grow(&mut self, new: &[usize], shifted: bool) -> Result<()> {
        let columns: Vec<usize> = new
            .iter()
            .flat_map(|&a| self.contact[a].columns.iter().map(|&(_, col)| col))
            .collect();
        self.base.flexibility.grow(&columns)?;
        self.factor = None;
        self.shifted.extend(columns.iter().map(|_| shifted));
        for &a in new {
            self.is_candidate[a] = true;
            self.candidates.push(a);
        }
        Ok(())
    }

    /// The condensed node of contact node `a` from its committed state and
    /// the contact linearised at `lin` (at the increment's time).
    fn cone_node(
        &self,
        problem: &Problem,
        lin: &Linearisation,
        state: &ContactState,
        a: usize,
    ) -> Result<ConeNode> {
        let c = &self.contact[a];
        let interface = problem.contacts.interface(c.interface);
        let found = lin.rows[c.interface][c.index]
            .as_ref()
            .zip((lin.slips[c.interface][c.index].as_ref()).zip(lin.at_zero(c.interface, c.index)));
        let Some((row, (slip, (gap_at_rest, offset_at_rest)))) = found else {
            return Err(Error::LinearSolver(format!(
                "contact node {} of '{}' has no obstacle within reach",
                problem.model.mesh.node_ids[c.node], interface.name
            )));
        };
        let committed = &state.interfaces[c.interface][c.index];
        let coulomb = interface.friction_at(c.index).unwrap_or(Coulomb {
            coefficient: 0.0,
            tangential_penalty: 1.0,
        });
        Ok(ConeNode {
            normal: row.normal,
            area: row.area,
            normal_law: interface.law_at(c.index).converged(),
            tangential_law: if interface.exact_stick() {
                TangentialLaw::ExactStick
            } else {
                TangentialLaw::Regularised
            },
            coulomb,
            committed_traction: slip.committed_traction,
            gap_at_rest,
            offset_at_rest,
            committed_gap: committed.gap,
            was_open: interface.first_contact_pending(committed),
            prescribed: self.prescribed_axes(c),
        })
    }

    /// The node's components without a column (its prescribed ones).
    fn prescribed_axes(&self, c: &FrictionNode) -> [bool; 3] {
        [0, 1, 2].map(|d| self.base.flexibility.constrained[3 * c.node + d])
    }

    /// The displacements (all unknowns, multipliers zero) and the traction
    /// of every contact node at time `t`, each node's primary triangle kept
    /// in `kept`: against rigid planes the problem linearised at rest,
    /// between bodies the rounds on the projections from `start` (module
    /// docs).
    fn solve_increment(
        &mut self,
        problem: &Problem,
        t: f64,
        state: &ContactState,
        kept: &mut ContactState,
        start: &[f64],
        history: &mut Vec<IterationRecord>,
    ) -> Result<(Vec<f64>, Vec<Vector3<f64>>)> {
        let load = Load::at(problem, t, &mut self.base)?;
        if !self.projected {
            let lin = Linearisation::at_rest(problem, t, state);
            return self.solve_linearised(problem, &load, state, kept, &lin, history);
        }
        let mut lin = Linearisation::at(problem, t, start, kept);
        let length = ROUND_TOLERANCE * problem.model.size();
        // the reaction no column carries, at the last answer's tractions
        let mut lagged = self.uncolumned_force(&lin);
        for _ in 0..MAX_ROUNDS {
            self.replace_columns(&lin)?;
            let with_lagged;
            let round_load = match &lagged {
                Some(force) => {
                    with_lagged = load.plus(force, &mut self.base)?;
                    &with_lagged
                }
                None => &load,
            };
            let (u, traction) =
                self.solve_linearised(problem, round_load, state, kept, &lin, history)?;
            let next = Linearisation::at(problem, t, &u, kept);
            let nodes = (self.candidates.iter()).map(|&a| {
                let c = &self.contact[a];
                (c.interface, c.index, traction[a] != Vector3::zeros())
            });
            let defect = lin.defect(&next, &u, nodes);
            let now = self.uncolumned_force(&next);
            let lag = self.force_change(lagged.as_deref(), now.as_deref(), &next);
            if defect.is_some_and(|(geometry, l)| geometry <= ROUND_TOLERANCE && l <= length)
                && lag <= ROUND_TOLERANCE
            {
                self.take_normals(&next);
                return Ok((u, traction));
            }
            lin = next;
            lagged = now;
        }
        Err(Error::LinearSolver(format!(
            "the projections between the bodies did not settle in {MAX_ROUNDS} condensed \
             frictional solves at time {t}; run with [solver] strategy = \"monolithic\""
        )))
    }

    /// The columns of `E` at the projections of `lin` (a node without a
    /// primary in reach keeps its last), `Ŵ` formed anew.
    fn replace_columns(&mut self, lin: &Linearisation) -> Result<()> {
        let flexibility = &self.base.flexibility;
        let columns: Vec<Column> = (self.column_owner.iter().enumerate())
            .map(|(col, &(a, d))| {
                let c = &self.contact[a];
                match &lin.rows[c.interface][c.index] {
                    Some(row) => Column {
                        entries: row.lever_row(d),
                        compliance: 0.0,
                    },
                    None => flexibility.columns[col].clone(),
                }
            })
            .collect();
        self.base.flexibility.replace_columns(columns)?;
        self.factor = None;
        Ok(())
    }

    /// The force `Σ_d A t_d B_dᵀ` of the candidates' components without a
    /// column (prescribed on the secondary node) on the free dofs of their
    /// lever, at the rows of `lin` and the last answer's tractions; `None`
    /// where it is zero. Between bodies a secondary node on a symmetry
    /// plane projects on a triangle with a vertex off the plane: its
    /// reaction along the plane's normal acts on that vertex (weighted by
    /// `−w_i`, as the monolithic residual has it), and no column of `E`
    /// carries it, so the rounds carry it as a load, lagged by one round
    /// until it settles ([`Self::force_change`]).
    fn uncolumned_force(&self, lin: &Linearisation) -> Option<Vec<f64>> {
        let constrained = &self.base.flexibility.constrained;
        let mut force: Option<Vec<f64>> = None;
        for &a in &self.candidates {
            let c = &self.contact[a];
            let Some(row) = &lin.rows[c.interface][c.index] else {
                continue;
            };
            for d in (0..3).filter(|&d| constrained[3 * c.node + d]) {
                let nodal = row.area * self.traction[a][d];
                for (i, w) in row.lever_row(d) {
                    if !constrained[i] && w * nodal != 0.0 {
                        let f = force.get_or_insert_with(|| vec![0.0; constrained.len()]);
                        f[i] += w * nodal;
                    }
                }
            }
        }
        force
    }

    /// How far the force `now` ([`Self::uncolumned_force`] at the rows of
    /// `next` and the tractions just solved, the next round's load) is
    /// from the `lagged` one the round was solved with: the largest change
    /// of an entry, relative to the largest nodal contact force `A |t|∞`
    /// of the candidates.
    fn force_change(
        &self,
        lagged: Option<&[f64]>,
        now: Option<&[f64]>,
        next: &Linearisation,
    ) -> f64 {
        let change = match (lagged, now) {
            (None, None) => return 0.0,
            (Some(f), None) | (None, Some(f)) => f.iter().fold(0.0f64, |m, v| m.max(v.abs())),
            (Some(a), Some(b)) => (a.iter().zip(b)).fold(0.0f64, |m, (x, y)| m.max((x - y).abs())),
        };
        let scale = (self.candidates.iter())
            .filter_map(|&a| {
                let c = &self.contact[a];
                let row = next.rows[c.interface][c.index].as_ref()?;
                Some(row.area * self.traction[a].amax())
            })
            .fold(f64::MIN_POSITIVE, f64::max);
        change / scale
    }

    /// Each contact node's normal from the rows of `lin` (where it has one).
    fn take_normals(&mut self, lin: &Linearisation) {
        for c in &mut self.contact {
            if let Some(row) = &lin.rows[c.interface][c.index] {
                c.normal = row.normal;
            }
        }
    }

    /// The condensed problem over the candidates with the contact
    /// linearised at `lin`, solved, then solved again with the nodes that
    /// penetrate at its answer, until none does.
    fn solve_linearised(
        &mut self,
        problem: &Problem,
        load: &Load,
        state: &ContactState,
        kept: &ContactState,
        lin: &Linearisation,
        history: &mut Vec<IterationRecord>,
    ) -> Result<(Vec<f64>, Vec<Vector3<f64>>)> {
        let t = load.time;
        loop {
            let nodes = self.cone_nodes(problem, lin, state)?;
            let columns = self.cone_columns();
            let flexibility = &self.base.flexibility;
            let free: Vec<f64> = (flexibility.candidates.iter())
                .map(|&c| flexibility.column_dot(c, &load.free))
                .collect();
            let guess_u: Vec<f64> = (flexibility.candidates.iter().zip(&free))
                .map(|(&c, &f)| self.displacement[c].unwrap_or(f))
                .collect();
            let guess_t: Vec<Vector3<f64>> =
                self.candidates.iter().map(|&a| self.traction[a]).collect();
            let fixed: Vec<Vector3<f64>> = (self.candidates.iter())
                .map(|&a| {
                    let c = &self.contact[a];
                    let columned = self.prescribed_axes(c).map(|p| !p);
                    let constrained = &self.base.flexibility.constrained;
                    lin.fixed_motion(
                        c.interface,
                        c.index,
                        columned,
                        constrained,
                        &load.prescribed,
                    )
                })
                .collect();
            let factor = self.flexibility_factor()?;
            let cone = ConeProblem {
                flexibility: &factor,
                columns: &columns,
                shifted: &self.shifted,
                shift: self.shift,
                free_displacement: &free,
                prescribed: &fixed,
                nodes: &nodes,
            };
            let mut solution = solve_cone(&cone, guess_u, guess_t).map_err(|e| {
                Error::LinearSolver(format!(
                    "{e} at time {t}; run with [solver] strategy = \"monolithic\""
                ))
            })?;
            self.iterations += solution.iterations;
            self.first_solve.get_or_insert(solution.iterations);
            history.append(&mut solution.history);
            self.factor = Some(factor);
            let u = self.displacements(&load.b, &columns, &nodes, &solution)?;
            let entering = self.entering(problem, t, &u, kept);
            if entering.is_empty() {
                let mut traction = vec![Vector3::zeros(); self.contact.len()];
                for &a in &self.candidates {
                    traction[a] = self.traction[a];
                }
                return Ok((u, traction));
            }
            self.batches.push(entering.clone());
            self.grow(&entering, false)?;
        }
    }

    /// The condensed node of every candidate from the contact linearised at
    /// `lin` and its committed state.
    fn cone_nodes(
        &self,
        problem: &Problem,
        lin: &Linearisation,
        state: &ContactState,
    ) -> Result<Vec<ConeNode>> {
        (self.candidates.iter())
            .map(|&a| self.cone_node(problem, lin, state, a))
            .collect()
    }

    /// Per column of `Ŵ`: its candidate's slot and the component.
    fn cone_columns(&self) -> Vec<(usize, usize)> {
        let slot: std::collections::HashMap<usize, usize> = (self.candidates.iter().enumerate())
            .map(|(s, &a)| (a, s))
            .collect();
        (self.base.flexibility.candidates.iter())
            .map(|&col| {
                let (a, d) = self.column_owner[col];
                (slot[&a], d)
            })
            .collect()
    }

    /// `Ŵ` with its Cholesky factor: the one kept since `Ŵ` last changed,
    /// else factorised anew.
    fn flexibility_factor(&mut self) -> Result<Flexibility> {
        if let Some(factor) = self.factor.take() {
            return Ok(factor);
        }
        Flexibility::new(&self.base.flexibility.w).map_err(Error::LinearSolver)
    }

    /// `u = K̂⁻¹ (b + E (A t + ρ P_S u_F))` from the condensed `solution`,
    /// which becomes the next start.
    fn displacements(
        &mut self,
        b: &[f64],
        columns: &[(usize, usize)],
        nodes: &[ConeNode],
        solution: &ConeSolution,
    ) -> Result<Vec<f64>> {
        let mut u = b.to_vec();
        let flexibility = &self.base.flexibility;
        for (k, &col) in flexibility.candidates.iter().enumerate() {
            let (s, d) = columns[k];
            let shift = if self.shifted[k] {
                self.shift * solution.displacement[k]
            } else {
                0.0
            };
            let force = nodes[s].area * solution.traction[s][d] + shift;
            flexibility.add_column(col, force, &mut u);
            self.displacement[col] = Some(solution.displacement[k]);
        }
        for (s, &a) in self.candidates.iter().enumerate() {
            self.traction[a] = solution.traction[s];
            self.multiplier[a] = solution.multiplier[s];
        }
        self.base.flexibility.solve(&mut u)?;
        Ok(u)
    }

    /// The contact nodes outside the candidates that penetrate at `u` (on
    /// the primary triangles kept in `kept`).
    fn entering(&self, problem: &Problem, t: f64, u: &[f64], kept: &ContactState) -> Vec<usize> {
        let reference = &problem.model.mesh.nodes;
        let gaps: Vec<Vec<f64>> = (problem.contacts.iter().enumerate())
            .map(|(ci, c)| c.gaps(reference, t, u, Some(&kept.interfaces[ci])))
            .collect();
        let tolerance = touching(problem);
        (0..self.contact.len())
            .filter(|&a| {
                let c = &self.contact[a];
                !self.is_candidate[a] && gaps[c.interface][c.index] < -tolerance
            })
            .collect()
    }
}

/// The load of an increment: `b(t)`, the answer without contact
/// `K̂⁻¹ b` and the prescribed displacements `ū(t)` (zero elsewhere).
struct Load {
    time: f64,
    b: Vec<f64>,
    free: Vec<f64>,
    prescribed: Vec<f64>,
}

impl Load {
    /// This load with `force` added to `b`, its answer without contact
    /// solved anew.
    fn plus(&self, force: &[f64], base: &mut Condensation) -> Result<Self> {
        let b: Vec<f64> = self.b.iter().zip(force).map(|(b, f)| b + f).collect();
        let mut free = b.clone();
        base.flexibility.solve(&mut free)?;
        Ok(Load {
            time: self.time,
            b,
            free,
            prescribed: self.prescribed.clone(),
        })
    }

    fn at(problem: &Problem, t: f64, base: &mut Condensation) -> Result<Self> {
        let b = base.load(problem, t);
        let mut free = b.clone();
        base.flexibility.solve(&mut free)?;
        let mut prescribed = vec![0.0; b.len()];
        problem.apply_prescribed(t, &mut prescribed);
        Ok(Load {
            time: t,
            b,
            free,
            prescribed,
        })
    }
}

impl IncrementSolver for FrictionalCondensation {
    /// The condensed answer as the monolithic unknowns: the multipliers
    /// from the pressures; with exact stick each node's tangential
    /// multiplier `λ_T` set to the solve's (its traction, but along the
    /// held directions of [`HeldTangent`](crate::contact::friction::HeldTangent),
    /// where the trial's old traction is the committed one: the augmented
    /// Lagrangian's fixed point, which the problem's evaluation and commit
    /// then read and return the solved traction from).
    fn increment(
        &mut self,
        problem: &Problem,
        t: f64,
        state: &ContactState,
        x: &mut [f64],
        trial: &mut ContactState,
        history: &mut Vec<IterationRecord>,
    ) -> Result<()> {
        let start = x.to_vec();
        self.first_solve = None;
        let (u, traction) = self.solve_increment(problem, t, state, trial, &start, history)?;
        let mut pressures = super::zero_per_node(problem);
        let mut tangential: Vec<Vec<(Vector3<f64>, Vector3<f64>)>> = (problem.contacts.iter())
            .map(|c| vec![(Vector3::zeros(), Vector3::z()); c.nodes.len()])
            .collect();
        for (a, c) in self.contact.iter().enumerate() {
            let normal = &c.normal;
            let tn = normal.dot(&traction[a]);
            pressures[c.interface][c.index] = tn;
            let multiplier = if self.is_candidate[a] {
                self.multiplier[a]
            } else {
                traction[a] - normal * tn
            };
            tangential[c.interface][c.index] = (multiplier, *normal);
        }
        super::set_multipliers(problem, &pressures, &u, t, x, trial);
        let reference = &problem.model.mesh.nodes;
        for (ci, interface) in problem.contacts.iter().enumerate() {
            if interface.exact_stick() {
                let states = &mut trial.interfaces[ci];
                interface.set_friction_multipliers(reference, t, x, states, &tangential[ci]);
            }
        }
        Ok(())
    }

    fn statistics(&self) -> (SolverStatistics, usize) {
        (
            SolverStatistics::of_ldlt(&self.base.flexibility.ldlt),
            self.iterations,
        )
    }

    /// The batches after the first candidates, and per contact node its
    /// last traction (3 values) then per column its last displacement.
    fn warm_start(&self) -> WarmStart {
        let mut values: Vec<f64> = self
            .traction
            .iter()
            .flat_map(|t| t.iter().copied())
            .collect();
        let mut set = vec![true; values.len()];
        for d in &self.displacement {
            values.push(d.unwrap_or(0.0));
            set.push(d.is_some());
        }
        WarmStart {
            batches: self.batches.clone(),
            active: Vec::new(),
            values,
            set,
        }
    }

    /// A body that only contact holds, loaded along rigid planes beyond
    /// their friction capacity ([`super::capacity::overload_failure`]).
    fn diagnose(&self, problem: &Problem, t: f64) -> Option<IncrementFailure> {
        if self.projected {
            return None;
        }
        let nodes = self.contact.iter().map(|c| {
            let interface = problem.contacts.interface(c.interface);
            let mu = interface
                .friction_at(c.index)
                .map_or(0.0, |f| f.coefficient);
            (c.normal, mu)
        });
        super::capacity::overload_failure(problem, t, nodes)
    }

    /// After an increment whose first contact solve took at most `easy`
    /// iterations (module docs, "Increments").
    fn grows(&self, easy: usize) -> bool {
        self.first_solve
            .is_some_and(|iterations| iterations <= easy)
    }

    fn resume(&mut self, warm: &WarmStart) -> Result<()> {
        let (count, columns) = (self.traction.len(), self.displacement.len());
        if warm.values.len() != 3 * count + columns || warm.set.len() != warm.values.len() {
            return Err(Error::LinearSolver(
                "the checkpoint's condensed warm start does not match the case's contact nodes"
                    .into(),
            ));
        }
        for batch in &warm.batches {
            self.batches.push(batch.clone());
            self.grow(batch, false)?;
        }
        for (a, t) in self.traction.iter_mut().enumerate() {
            *t = Vector3::new(
                warm.values[3 * a],
                warm.values[3 * a + 1],
                warm.values[3 * a + 2],
            );
        }
        for (c, d) in self.displacement.iter_mut().enumerate() {
            let i = 3 * count + c;
            *d = warm.set[i].then_some(warm.values[i]);
        }
        Ok(())
    }
}
