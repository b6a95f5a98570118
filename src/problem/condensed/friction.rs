//! The frictional condensed path: Coulomb friction against rigid planes on
//! a body of constant stiffness, three unknowns per contact node, solved
//! per increment by the dense semismooth Newton method of
//! [`crate::solve::condensed::cone`], with the friction history committed per
//! increment by the problem itself (as the monolithic path does).
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

use super::{constraint_rows, Condensation, ContactNode, ContactState, IncrementSolver, Problem};
use crate::contact::friction::{ContactStatus, Coulomb};
use crate::contact::interface::ConstraintRow;
use crate::solve::condensed::cone::{
    solve_cone, ConeNode, ConeProblem, ConeSolution, TangentialLaw,
};
use crate::solve::condensed::flexibility::Column;
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
    /// Its unit normal (constant: the gaps are affine).
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
    /// `Ŵ⁻¹` (a Cholesky inverse), once per `Ŵ`.
    inverse: Option<nalgebra::DMatrix<f64>>,
    /// Per column of `Ŵ`: shifted by `ρ`.
    shifted: Vec<bool>,
    /// The shift `ρ` (0 when nothing is shifted).
    shift: f64,
    /// The last answer per contact node (the next increment's start).
    traction: Vec<Vector3<f64>>,
    displacement: Vec<Option<f64>>,
    iterations: usize,
}

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

impl FrictionalCondensation {
    /// The contact nodes and their columns; `K̂` factorised once (shifted
    /// where only contact holds the body); the nodes touching at the start
    /// made candidates.
    pub(super) fn new(problem: &Problem) -> Result<Self> {
        let constrained = problem.constrained_dofs();
        let (mut owners, mut columns) = (Vec::new(), Vec::new());
        let mut column_owner = Vec::new();
        let mut contact = Vec::new();
        let mut initial = Vec::new();
        let tolerance = touching(problem);
        let zero = vec![0.0; problem.num_unknowns()];
        for (ci, rows) in constraint_rows(problem, 0.0, &zero).iter().enumerate() {
            let gaps = initial_gaps(problem, ci);
            for (i, row) in rows.iter().enumerate() {
                let Some(row) = row else { continue };
                let node = row.node;
                let mut own = Vec::new();
                for d in (0..3).filter(|&d| !constrained[3 * node + d]) {
                    own.push((d, columns.len()));
                    column_owner.push((contact.len(), d));
                    owners.push(ContactNode {
                        interface: ci,
                        index: i,
                    });
                    columns.push(Column {
                        entries: row.lever_row(d),
                        compliance: 0.0,
                    });
                }
                if gaps[i] <= tolerance {
                    initial.push(contact.len());
                }
                contact.push(FrictionNode {
                    interface: ci,
                    index: i,
                    node,
                    normal: row.normal,
                    columns: own,
                });
            }
        }
        // shift only where the prescribed displacements do not hold a body
        let floating = super::free_rigid_body_mode(problem, &constrained).is_some();
        let shifted_dofs: Vec<usize> = if floating {
            initial
                .iter()
                .flat_map(|&a| {
                    let node = contact[a].node;
                    contact[a].columns.iter().map(move |&(d, _)| 3 * node + d)
                })
                .collect()
        } else {
            Vec::new()
        };
        let base = Condensation::factorise(problem, owners, columns, &shifted_dofs, 1.0, false)?;
        let shift = if floating {
            base.flexibility.scale
        } else {
            0.0
        };
        let count = contact.len();
        let columns_count = base.flexibility.columns.len();
        let mut condensation = FrictionalCondensation {
            base,
            contact,
            column_owner,
            candidates: Vec::new(),
            batches: Vec::new(),
            is_candidate: vec![false; count],
            inverse: None,
            shifted: Vec::new(),
            shift,
            traction: vec![Vector3::zeros(); count],
            displacement: vec![None; columns_count],
            iterations: 0,
        };
        condensation.grow(&initial, floating)?;
        Ok(condensation)
    }

    /// Make the contact nodes `new` candidates: their columns of `Ŵ`.
    fn grow(&mut self, new: &[usize], shifted: bool) -> Result<()> {
        let columns: Vec<usize> = new
            .iter()
            .flat_map(|&a| self.contact[a].columns.iter().map(|&(_, col)| col))
            .collect();
        self.base.flexibility.grow(&columns)?;
        self.inverse = None;
        self.shifted.extend(columns.iter().map(|_| shifted));
        for &a in new {
            self.is_candidate[a] = true;
            self.candidates.push(a);
        }
        Ok(())
    }

    /// The condensed node of contact node `a` from its committed state and
    /// its constraint row `rest` at `u = 0` (at the increment's time).
    fn cone_node(
        &self,
        problem: &Problem,
        rest: &ConstraintRow,
        state: &ContactState,
        a: usize,
    ) -> ConeNode {
        let c = &self.contact[a];
        let interface = problem.contacts.interface(c.interface);
        let committed = &state.interfaces[c.interface][c.index];
        let coulomb = interface.friction_at(c.index).unwrap_or(Coulomb {
            coefficient: 0.0,
            tangential_penalty: 1.0,
        });
        ConeNode {
            normal: rest.normal,
            area: rest.area,
            normal_law: interface.law_at(c.index).converged(),
            tangential_law: if interface.exact_stick() {
                TangentialLaw::ExactStick
            } else {
                TangentialLaw::Regularised
            },
            coulomb,
            committed_traction: committed.friction.traction,
            gap_at_rest: rest.gap,
            offset_at_rest: rest.relative_position - committed.friction.anchor,
            committed_gap: committed.gap,
            was_open: committed.friction.status == ContactStatus::Open,
            prescribed: [0, 1, 2].map(|d| self.base.flexibility.constrained[3 * c.node + d]),
        }
    }

    /// The displacements (all unknowns, multipliers zero) and the traction
    /// of every contact node at time `t`: the condensed problem over the
    /// candidates solved, then solved again with the nodes that penetrate
    /// at its answer, until none does.
    fn solve_increment(
        &mut self,
        problem: &Problem,
        t: f64,
        state: &ContactState,
        history: &mut Vec<IterationRecord>,
    ) -> Result<(Vec<f64>, Vec<Vector3<f64>>)> {
        let b = self.base.load(problem, t);
        let mut u0 = b.clone();
        self.base.flexibility.solve(&mut u0)?;
        let mut prescribed = vec![0.0; b.len()];
        problem.apply_prescribed(t, &mut prescribed);
        let rest = constraint_rows(problem, t, &vec![0.0; b.len()]);
        loop {
            let nodes = self.cone_nodes(problem, &rest, state)?;
            let columns = self.cone_columns();
            let flexibility = &self.base.flexibility;
            let free: Vec<f64> = (flexibility.candidates.iter())
                .map(|&c| flexibility.column_dot(c, &u0))
                .collect();
            let guess_u: Vec<f64> = (flexibility.candidates.iter().zip(&free))
                .map(|(&c, &f)| self.displacement[c].unwrap_or(f))
                .collect();
            let guess_t: Vec<Vector3<f64>> =
                self.candidates.iter().map(|&a| self.traction[a]).collect();
            let inverse = self.inverse_flexibility()?;
            let at_nodes = |a: &usize| {
                let n = self.contact[*a].node;
                Vector3::new(
                    prescribed[3 * n],
                    prescribed[3 * n + 1],
                    prescribed[3 * n + 2],
                )
            };
            let cone = ConeProblem {
                inverse_flexibility: &inverse,
                columns: &columns,
                shifted: &self.shifted,
                shift: self.shift,
                free_displacement: &free,
                prescribed: &self.candidates.iter().map(at_nodes).collect::<Vec<_>>(),
                nodes: &nodes,
            };
            let mut solution = solve_cone(&cone, guess_u, guess_t).map_err(|e| {
                Error::LinearSolver(format!(
                    "{e} at time {t}; run with [solver] strategy = \"monolithic\""
                ))
            })?;
            self.iterations += solution.iterations;
            history.append(&mut solution.history);
            self.inverse = Some(inverse);
            let u = self.displacements(&b, &columns, &nodes, &solution)?;
            let entering = self.entering(problem, t, &u);
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

    /// The condensed node of every candidate from its constraint row at
    /// rest (`rest`, per interface) and its committed state.
    fn cone_nodes(
        &self,
        problem: &Problem,
        rest: &[Vec<Option<ConstraintRow>>],
        state: &ContactState,
    ) -> Result<Vec<ConeNode>> {
        (self.candidates.iter())
            .map(|&a| {
                let c = &self.contact[a];
                let row = rest[c.interface][c.index].as_ref().ok_or_else(|| {
                    Error::LinearSolver(format!(
                        "contact node {} of '{}' has no obstacle within reach",
                        problem.model.mesh.node_ids[c.node],
                        problem.contacts.interface(c.interface).name
                    ))
                })?;
                Ok(self.cone_node(problem, row, state, a))
            })
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

    /// `Ŵ⁻¹`: the one kept since `Ŵ` last changed, else its Cholesky
    /// inverse.
    fn inverse_flexibility(&mut self) -> Result<nalgebra::DMatrix<f64>> {
        if let Some(inverse) = self.inverse.take() {
            return Ok(inverse);
        }
        let cholesky = self.base.flexibility.w.clone().cholesky().ok_or_else(|| {
            Error::LinearSolver("the condensed contact flexibility is not positive definite".into())
        })?;
        Ok(cholesky.inverse())
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
        }
        self.base.flexibility.solve(&mut u)?;
        Ok(u)
    }

    /// The contact nodes outside the candidates that penetrate at `u`.
    fn entering(&self, problem: &Problem, t: f64, u: &[f64]) -> Vec<usize> {
        let reference = &problem.model.mesh.nodes;
        let gaps: Vec<Vec<f64>> = (problem.contacts.iter())
            .map(|c| c.gaps(reference, t, u, None))
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

impl IncrementSolver for FrictionalCondensation {
    /// The condensed answer as the monolithic unknowns: the multipliers
    /// from the pressures; with exact stick each node's tangential
    /// multiplier `λ_T` set to its traction (the augmented Lagrangian's
    /// fixed point, which the problem's evaluation and commit then read).
    fn increment(
        &mut self,
        problem: &Problem,
        t: f64,
        state: &ContactState,
        x: &mut [f64],
        trial: &mut ContactState,
        history: &mut Vec<IterationRecord>,
    ) -> Result<()> {
        let (u, traction) = self.solve_increment(problem, t, state, history)?;
        let mut pressures = super::zero_per_node(problem);
        for (a, c) in self.contact.iter().enumerate() {
            let interface = problem.contacts.interface(c.interface);
            let normal = &c.normal;
            let tn = normal.dot(&traction[a]);
            pressures[c.interface][c.index] = tn;
            if interface.exact_stick() {
                trial.interfaces[c.interface][c.index].friction.traction =
                    traction[a] - normal * tn;
            }
        }
        super::set_multipliers(problem, &pressures, &u, t, x, trial);
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
