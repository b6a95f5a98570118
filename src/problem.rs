//! The boundary-value problem: a [`Model`] with prescribed displacements,
//! pressures and body forces, each scaled by its own amplitude in
//! pseudo-time, and the sequence of load steps.
//!
//! Everything here is already resolved against the mesh (node and facet
//! lists); [`crate::case`] builds it from the case file.

use crate::assembly::loads::pressure_facet;
use crate::assembly::pattern::{NodeGraph, SparsityPattern};
use crate::assembly::sink::{Entries, Tangent};
use crate::assembly::{ElementFailure, Model};
use crate::contact::friction::FrictionMultiplier;
use crate::contact::interface::{ContactContext, ContactInterface, NodeReport};
use crate::contact::set::ContactSet;
use crate::mesh::Facet;
use crate::solve::ordering::{EarlyDissection, AMD_DOFS};
use crate::solve::settings::Strategy;
pub use crate::solve::settings::{LinearMethod, NonsymmetricSolver, SolverSettings, Step};
pub use builder::ProblemBuilder;

mod builder;
pub mod condensed;
mod constraints;
mod nonlinear;
mod rotation;

pub use rotation::{rotation_displacement, rotation_matrix, PrescribedRotation};

pub use crate::contact::set::{ContactPattern, ContactState};

pub use crate::assembly::amplitude::Amplitude;

/// Whether a run orders its elements' node graph by nested dissection,
/// from what is known before the problem is built (its solver settings,
/// `num_dofs` displacement unknowns, and of each contact whether it is
/// against a rigid obstacle, or between bodies where `auto` is expected
/// to condense it: the case's `condensed_pair`): then
/// [`Problem::dissection`] is started as
/// soon as that graph exists. So it is with contacts all against rigid
/// obstacles (the condensed path's trailing ordering, and a saddle system,
/// at any size) or more than [`AMD_DOFS`] unknowns; with contact between
/// bodies only when the condensed path is asked for or expected (its factor drops the
/// contact couplings and is ordered on the elements' graph,
/// [`crate::solve::ordering::element_dissection`]; Newton's pattern with
/// those couplings is another graph); not for PETSc
/// (which orders its own systems; the condensed path excepted), where the
/// ordering is made where it is used, as before. Small penalty contact
/// decided monolithic is ordered by AMD: its dissection, of fewer than
/// [`AMD_DOFS`]` / 3` nodes, goes unused on the idle core.
pub fn dissects_element_graph(
    linear: LinearMethod,
    strategy: Strategy,
    num_dofs: usize,
    mut against_rigid: impl ExactSizeIterator<Item = bool>,
) -> bool {
    let petsc = linear == LinearMethod::Petsc && strategy != Strategy::Condensed;
    let contact = against_rigid.len() > 0;
    let all_rigid = against_rigid.all(|rigid| rigid);
    !petsc && (all_rigid || strategy == Strategy::Condensed) && (contact || num_dofs > AMD_DOFS)
}

/// Prescribed displacement components on the nodes of a surface set or a
/// node set: `u_i = value_i · amplitude(t)`.
#[derive(Clone, Debug)]
pub struct PrescribedDisplacement {
    /// The set's name.
    pub surface: String,
    pub nodes: Vec<usize>,
    /// `(component 0‥2, value)`.
    pub components: Vec<(usize, f64)>,
    pub amplitude: Amplitude,
}

/// A pressure (positive into the body) on a surface set.
#[derive(Clone, Debug)]
pub struct PressureLoad {
    pub surface: String,
    pub facets: Vec<Facet>,
    pub pressure: f64,
    /// Follows the deformed surface (follower) or stays on the reference
    /// normal and area (dead).
    pub follower: bool,
    pub amplitude: Amplitude,
}

/// A body force per unit reference volume on a region.
#[derive(Clone, Debug)]
pub struct BodyForce {
    pub region: String,
    /// `∫ N_a dV₀` of every node over the region.
    pub nodal_volumes: Vec<f64>,
    pub force: [f64; 3],
    pub amplitude: Amplitude,
}

/// Point loads on the nodes of a node set: `f_a = force · amplitude(t)` on
/// each node `a` (a dead load).
#[derive(Clone, Debug)]
pub struct NodalForce {
    /// The node set's name.
    pub set: String,
    pub nodes: Vec<usize>,
    /// The force on each node (the case file's total divided by the number
    /// of nodes).
    pub force: [f64; 3],
    pub amplitude: Amplitude,
}

/// The resolved problem.
pub struct Problem {
    /// The mesh, materials and the sparsity pattern (which holds the
    /// contact multipliers, if any, after the displacements).
    pub model: Model,
    pub prescribed: Vec<PrescribedDisplacement>,
    /// Prescribed rigid rotations of node sets (all three components of
    /// their nodes), applied after `prescribed`.
    pub rotations: Vec<PrescribedRotation>,
    pub pressures: Vec<PressureLoad>,
    pub body_forces: Vec<BodyForce>,
    pub nodal_forces: Vec<NodalForce>,
    /// Contact interfaces (with rigid obstacles or between bodies).
    pub contacts: ContactSet,
    pub steps: Vec<Step>,
    pub settings: SolverSettings,
    /// Time spent in assembly and contact, for reports and benchmarks.
    pub timings: PhaseTimings,
    /// The nested dissection of the elements' node graph, started as soon
    /// as it exists, while the rest of the problem is built
    /// ([`dissects_element_graph`]); `None`: each ordering computes its own.
    pub dissection: Option<EarlyDissection>,
}

/// Time spent in the assembly phases (element kernels and scatter; contact
/// search and contact assembly), summed over every residual evaluation.
#[derive(Debug, Default)]
pub struct PhaseTimings {
    pub assembly_ns: std::sync::atomic::AtomicU64,
    pub contact_ns: std::sync::atomic::AtomicU64,
}

impl PhaseTimings {
    fn add(counter: &std::sync::atomic::AtomicU64, since: std::time::Instant) {
        counter.fetch_add(
            since.elapsed().as_nanos() as u64,
            std::sync::atomic::Ordering::Relaxed,
        );
    }
    /// Seconds in element assembly (internal forces and tangent, loads).
    pub fn assembly(&self) -> f64 {
        self.assembly_ns.load(std::sync::atomic::Ordering::Relaxed) as f64 * 1e-9
    }
    /// Seconds in contact search and contact assembly.
    pub fn contact(&self) -> f64 {
        self.contact_ns.load(std::sync::atomic::Ordering::Relaxed) as f64 * 1e-9
    }
}

/// Residual `r = f_int − f_ext − f_contact` over all unknowns (displacements,
/// then contact multipliers) with the norms used to scale it.
pub struct Residual {
    pub r: Vec<f64>,
    pub internal_norm: f64,
    pub external_norm: f64,
}

impl Problem {
    /// Which dofs are prescribed (in any step).
    pub fn constrained_dofs(&self) -> Vec<bool> {
        let mut mask = vec![false; self.num_unknowns()];
        for c in &self.prescribed {
            for &n in &c.nodes {
                for &(i, _) in &c.components {
                    mask[3 * n + i] = true;
                }
            }
        }
        for r in &self.rotations {
            for &n in &r.nodes {
                mask[3 * n..3 * n + 3].fill(true);
            }
        }
        mask
    }

    /// Write the prescribed displacements at time `t` into `u` (later
    /// conditions win where two prescribe the same component; the
    /// rotations last).
    pub fn apply_prescribed(&self, t: f64, u: &mut [f64]) {
        for c in &self.prescribed {
            let a = c.amplitude.value(t);
            for &n in &c.nodes {
                for &(i, v) in &c.components {
                    u[3 * n + i] = v * a;
                }
            }
        }
        for r in &self.rotations {
            r.apply(t, &self.model.mesh.nodes, u);
        }
    }

    /// Whether the tangent is nonsymmetric (follower pressure on a
    /// surface, Coulomb friction, dual mortar between bodies:
    /// [`ContactSet::has_nonsymmetric_tangent`]).
    pub fn has_nonsymmetric_tangent(&self) -> bool {
        self.pressures.iter().any(|p| p.follower) || self.contacts.has_nonsymmetric_tangent()
    }

    /// External force at time `t` and displacement `u`; if `tangent` is
    /// given, add the follower-load stiffness `−∂f_ext/∂u` (nonsymmetric).
    pub fn external_force(&self, t: f64, u: &[f64], tangent: Option<&mut [f64]>) -> Vec<f64> {
        self.external_force_on(t, u, tangent.map(|k| (&self.model.pattern, k)))
    }

    /// [`Problem::external_force`] with the follower-load stiffness added
    /// into values on the pattern given with them.
    fn external_force_on(
        &self,
        t: f64,
        u: &[f64],
        mut tangent: Option<(&SparsityPattern, &mut [f64])>,
    ) -> Vec<f64> {
        let mesh = &self.model.mesh;
        let mut f = vec![0.0; self.model.num_dofs()];
        for b in &self.body_forces {
            let a = b.amplitude.value(t);
            for (n, w) in b.nodal_volumes.iter().enumerate() {
                for i in 0..3 {
                    f[3 * n + i] += w * b.force[i] * a;
                }
            }
        }
        for p in &self.nodal_forces {
            let a = p.amplitude.value(t);
            for &n in &p.nodes {
                for i in 0..3 {
                    f[3 * n + i] += p.force[i] * a;
                }
            }
        }
        for p in &self.pressures {
            let value = p.pressure * p.amplitude.value(t);
            if value == 0.0 {
                continue;
            }
            for facet in &p.facets {
                let coords: Vec<[f64; 3]> = facet
                    .nodes
                    .iter()
                    .map(|&n| {
                        let x = mesh.nodes[n];
                        if p.follower {
                            [x[0] + u[3 * n], x[1] + u[3 * n + 1], x[2] + u[3 * n + 2]]
                        } else {
                            x
                        }
                    })
                    .collect();
                let with_tangent = p.follower && tangent.is_some();
                let (fe, ke) = pressure_facet(facet.kind, &coords, value, with_tangent);
                crate::assembly::scatter::add_nodal(&mut f, &facet.nodes, |k| fe[k]);
                if let (true, Some((pattern, k))) = (with_tangent, tangent.as_mut()) {
                    crate::assembly::scatter_block_matrix(
                        pattern,
                        &facet.nodes,
                        &ke,
                        3 * facet.nodes.len(),
                        k,
                    );
                }
            }
        }
        f
    }

    /// Install contact interfaces ([`ContactSet::install`]), pair them at the
    /// reference configuration and rebuild the sparsity pattern (every
    /// secondary node keeps its multiplier, active or not: the number of
    /// unknowns is fixed for the run).
    pub fn set_contacts(&mut self, mut contacts: Vec<ContactInterface>) {
        let constrained = self.constrained_dofs();
        for c in &mut contacts {
            c.set_prescribed_axes(&constrained);
        }
        self.contacts.install(contacts);
        let zero = vec![0.0; self.model.num_dofs()];
        self.refresh_contact_pairs(&zero, 0.0);
        self.rebuild_pattern();
    }

    /// Exact stick's tangential multipliers kept in the friction history
    /// (Simo–Laursen's form, [`FrictionMultiplier::Outer`]) rather than as
    /// unknowns of Newton: the condensed path solves the frictional
    /// problem itself and hands its fixed point to the history, which the
    /// problem's evaluation then reads. Renumbers the multipliers and
    /// rebuilds the pattern where that changes them.
    pub fn keep_friction_multipliers_in_history(&mut self) {
        if !self.contacts.has_tangential_multipliers() {
            return;
        }
        let mut contacts: Vec<ContactInterface> = self.contacts.iter().cloned().collect();
        for c in &mut contacts {
            c.friction_multiplier = FrictionMultiplier::Outer;
        }
        self.contacts.install(contacts);
        self.rebuild_pattern();
    }

    /// Newton's pattern ([`ContactPattern::Newton`], the default) where
    /// the problem has the condensed path's (a run builds that one until
    /// it has chosen its path, `crate::run::problem_as_run`: mortar's
    /// multipliers with their faces' nodes are 3 % of the entries on the
    /// race's one-increment case, and the condensed factor reads none):
    /// called before Newton's path first solves (the run going on
    /// Newton's path, the fallback of `auto`). Returns whether the
    /// pattern changed (a linear solver ordered on the old one orders
    /// again).
    pub fn newton_pattern(&mut self) -> bool {
        let changed = self.contacts.pattern() != ContactPattern::Newton;
        if changed {
            self.contacts.set_pattern(ContactPattern::Newton);
            self.rebuild_pattern();
        }
        changed
    }

    /// A distributed run: assemble only `share`'s elements, on a pattern
    /// of this process's rows ([`Model::set_share_with_local_rows`]) with
    /// the contact couplings and the faces of the follower pressures (on
    /// every process: each adds their tangent in the rows it owns).
    pub fn set_share(&mut self, share: crate::assembly::share::Share) {
        let faces = self.follower_faces();
        self.model.set_share_with_local_rows(share, &faces);
        self.rebuild_pattern();
    }

    /// The node lists of the follower-pressure faces (their tangent
    /// couples every pair of a face's nodes).
    fn follower_faces(&self) -> Vec<Vec<usize>> {
        let followers = self.pressures.iter().filter(|p| p.follower);
        followers
            .flat_map(|p| p.facets.iter().map(|f| f.nodes.clone()))
            .collect()
    }

    /// The sparsity pattern of the elements, of each secondary node with the
    /// primary nodes it may touch, and of the multipliers (the contact
    /// couplings of [`ContactSet::pattern`]).
    fn rebuild_pattern(&mut self) {
        let couplings = self.contacts.couplings();
        self.model.pattern = self.model.pattern.coupled(
            &couplings.groups,
            &couplings.multipliers,
            &couplings.multiplier_groups,
        );
    }

    /// The side pattern: that of every node contact or a follower load
    /// writes to, and nothing else (each contact node's groups of coupled
    /// nodes, as in the model's pattern, itself alone against a rigid
    /// obstacle; every pair of nodes
    /// of a follower face; the multipliers), where contact and loads write
    /// their tangent when the elements' goes into a linear solver's matrix
    /// ([`Tangent::Sink`]); made at the first call for the model's pattern
    /// ([`Model::side_pattern`]).
    fn side_pattern(&self) -> std::sync::Arc<SparsityPattern> {
        self.model.side_pattern(|| {
            let mut groups = self.follower_faces();
            // the main pattern's groups (pairs, not a clique, for a node
            // against a plane whose lever lies on itself): an entry here
            // outside the pattern is one the linear solver's matrix has
            // no room for
            for c in &self.contacts {
                groups.extend((0..c.nodes.len()).flat_map(|i| c.coupled_groups(i)));
            }
            let graph = NodeGraph::of_elements_and(
                self.model.mesh.num_nodes(),
                groups.iter().map(Vec::as_slice),
                |_| false,
            );
            let couplings = self.contacts.couplings();
            SparsityPattern::from_graph(&graph).coupled(
                &[],
                &couplings.multipliers,
                &couplings.multiplier_groups,
            )
        })
    }

    /// Pair the secondary nodes with the primary triangles they may touch
    /// at `x` ([`ContactSet::refresh_pairs`]; `motion` the largest nodal
    /// displacement expected in the coming increment) and rebuild the
    /// sparsity pattern if a pairing changed. Returns whether it did.
    pub fn refresh_contact_pairs(&mut self, x: &[f64], motion: f64) -> bool {
        self.search_contact_pairs(x, motion, None)
    }

    /// [`refresh_contact_pairs`](Self::refresh_contact_pairs), and with
    /// `reached` the pairs a search at those unknowns (an answer that left
    /// the last pairs) finds too.
    pub fn search_contact_pairs(
        &mut self,
        x: &[f64],
        motion: f64,
        reached: Option<&[f64]>,
    ) -> bool {
        let changed = self
            .contacts
            .refresh_pairs(&self.model.mesh.nodes, x, motion, reached);
        if changed {
            self.rebuild_pattern();
        }
        changed
    }

    /// The nodes of every deformable interface (secondary and primary), whose
    /// motion sets the search margin.
    pub fn deformable_contact_nodes(&self) -> Vec<usize> {
        self.contacts.deformable_nodes()
    }

    /// Whether no secondary node slid, by `x`, out of the candidates it was
    /// paired with at the increment's start ([`ContactSet::pairs_hold`];
    /// otherwise the increment is cut, which shrinks the motion per increment).
    pub fn contact_pairs_hold(&self, x: &[f64], contact: &ContactState) -> bool {
        self.contacts.pairs_hold(&self.model.mesh.nodes, x, contact)
    }

    /// Number of unknowns: 3 displacements per node, then the contact
    /// multipliers.
    pub fn num_unknowns(&self) -> usize {
        self.model.pattern.dimension()
    }

    /// Whether the system has multiplier unknowns (a saddle point).
    pub fn has_multipliers(&self) -> bool {
        self.num_unknowns() > self.model.num_dofs()
    }

    /// Where the contact operations are evaluated: time `t`, unknowns `x`.
    pub fn contact_context<'a>(&'a self, t: f64, x: &'a [f64]) -> ContactContext<'a> {
        ContactContext {
            reference: &self.model.mesh.nodes,
            t,
            x,
            first_multiplier: self.model.num_dofs(),
        }
    }

    /// The contact states before the first increment (gaps at `x`, time 0).
    pub fn initial_contact_state(&self, x: &[f64]) -> ContactState {
        self.contacts.initial_state(&self.model.mesh.nodes, x)
    }

    /// Commit the contact history once an increment has converged at `t`,
    /// `x` ([`ContactSet::commit`]).
    pub fn commit_contact_history(&self, t: f64, x: &[f64], contact: &mut ContactState) {
        self.contacts.commit(&self.contact_context(t, x), contact);
    }

    /// After a converged Newton solve, the outer loop of the laws that have
    /// one ([`ContactSet::augment`]); `true`: solve again.
    pub fn augment_multipliers(&self, t: f64, x: &[f64], contact: &mut ContactState) -> bool {
        self.contacts.augment(&self.contact_context(t, x), contact)
    }

    /// The preconditioner of a nonsymmetric solve from the symmetric part
    /// `values` of the tangent `tangent` ([`ContactSet::precondition`]).
    pub fn stick_preconditioner(
        &self,
        t: f64,
        x: &[f64],
        contact: &ContactState,
        constrained: &[bool],
        tangent: &[f64],
        values: &mut [f64],
    ) {
        let ctx = self.contact_context(t, x);
        let pattern = &self.model.pattern;
        let matrices = (tangent, values);
        self.contacts
            .precondition(&ctx, contact, constrained, pattern, matrices);
    }

    /// Carry the contact states along a Newton step `dx` from `x`.
    pub fn advance_contact_states(
        &self,
        t: f64,
        x: &[f64],
        dx: &[f64],
        contact: &mut ContactState,
    ) {
        self.contacts
            .advance(&self.contact_context(t, x), dx, contact);
    }

    /// Residual at time `t` and unknowns `x` for a problem without contact
    /// history (or at its initial state), and the tangent if asked.
    pub fn residual(
        &self,
        t: f64,
        x: &[f64],
        tangent: Option<&mut [f64]>,
    ) -> Result<Residual, ElementFailure> {
        self.residual_in(t, x, &self.initial_contact_state(x), tangent)
            .map(|(r, _)| r)
    }

    /// Residual at time `t`, unknowns `x` and contact states `contact`, the
    /// tangent if asked, and the contact report of every interface node.
    pub fn residual_in(
        &self,
        t: f64,
        x: &[f64],
        contact: &ContactState,
        tangent: Option<&mut [f64]>,
    ) -> Result<(Residual, Vec<Vec<NodeReport>>), ElementFailure> {
        self.residual_into(t, x, contact, tangent.map(Tangent::Values))
    }

    /// [`Problem::residual_in`] with the tangent written into `tangent`:
    /// values on the model's pattern, or a linear solver's matrix
    /// ([`Tangent::Sink`], a distributed run), into which the elements go
    /// straight and contact and loads through values on the side pattern
    /// ([`Problem::side_pattern`]), their own rows only.
    pub fn residual_into(
        &self,
        t: f64,
        x: &[f64],
        contact: &ContactState,
        mut tangent: Option<Tangent<'_>>,
    ) -> Result<(Residual, Vec<Vec<NodeReport>>), ElementFailure> {
        let start = std::time::Instant::now();
        let mut r = vec![0.0; self.num_unknowns()];
        self.model
            .assemble_internal_into(x, &mut r, tangent.as_mut().map(Tangent::reborrow))?;
        PhaseTimings::add(&self.timings.assembly_ns, start);
        let start = std::time::Instant::now();
        // contact and loads write by position: into the tangent's values,
        // or beside a sink into values on the side pattern
        let sink = match &tangent {
            Some(Tangent::Sink(sink)) => Some(*sink),
            _ => None,
        };
        let side_pattern = sink.map(|_| self.side_pattern());
        let side_pattern = side_pattern.as_deref();
        let mut side = side_pattern.map_or_else(Vec::new, |p| vec![0.0; p.nnz()]);
        let (pattern, mut values) = match (tangent, side_pattern) {
            (_, Some(side_pattern)) => (side_pattern, Some(&mut side[..])),
            (Some(Tangent::Values(k)), None) => (&self.model.pattern, Some(k)),
            _ => (&self.model.pattern, None),
        };
        // distributed (`mpirun`): every process holds the whole internal
        // force and computes contact and loads alike, and adds their
        // tangent to its part of K in the rows it owns only
        let foreign = match (&values, sink) {
            (Some(k), None) => Some(self.model.foreign_entries(k)),
            _ => None,
        };
        let reports = self.contacts.assemble(
            &self.contact_context(t, x),
            contact,
            &mut r,
            values.as_deref_mut().map(|k| (pattern, k)),
        );
        PhaseTimings::add(&self.timings.contact_ns, start);
        let start = std::time::Instant::now();
        let internal_norm = norm(&r);
        let f_ext = self.external_force_on(t, x, values.as_deref_mut().map(|k| (pattern, k)));
        match (values, foreign, sink) {
            (Some(k), Some(foreign), _) => self.model.restore_entries(k, &foreign),
            (Some(k), _, Some(sink)) => sink.add_columns(pattern.symbolic(), k, Entries::OwnRows),
            _ => {}
        }
        PhaseTimings::add(&self.timings.assembly_ns, start);
        for (ri, fi) in r.iter_mut().zip(&f_ext) {
            *ri -= fi;
        }
        Ok((
            Residual {
                r,
                internal_norm,
                external_norm: norm(&f_ext),
            },
            reports,
        ))
    }

    /// Total of `r = f_int − f_ext` over the nodes of each surface set, then
    /// of each node set whose name no surface set has: the reaction force
    /// where displacements are prescribed (zero, to the tolerance, on a free
    /// surface).
    pub fn surface_forces(&self, r: &[f64]) -> Vec<(String, [f64; 3])> {
        let mesh = &self.model.mesh;
        let total = |nodes: &[usize]| {
            let mut total = [0.0; 3];
            for &n in nodes {
                for i in 0..3 {
                    total[i] += r[3 * n + i];
                }
            }
            total
        };
        let surfaces = mesh
            .surfaces
            .iter()
            .map(|s| (s.name.clone(), total(&mesh.surface_nodes(s))));
        let node_sets = mesh
            .node_sets
            .iter()
            .filter(|s| mesh.surface(&s.name).is_none())
            .map(|s| (s.name.clone(), total(&s.nodes)));
        surfaces.chain(node_sets).collect()
    }

    /// A message for an element failure, with the element's mesh id.
    pub fn describe_failure(&self, f: &ElementFailure) -> String {
        self.element_failure(f).to_string()
    }
}

/// Euclidean norm.
pub fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The dissection starts for contact against rigid obstacles at any
    /// size and for large problems; not for small ones without contact
    /// (AMD), contact between bodies unless condensed is asked for, or PETSc
    /// unless condensed is asked for.
    #[test]
    fn the_dissection_starts_where_the_run_orders_the_element_graph() {
        use LinearMethod::{Auto, Lu, Petsc};
        use Strategy::{Auto as Either, Condensed, Monolithic};
        let starts = |linear, strategy, dofs, rigid: &[bool]| {
            dissects_element_graph(linear, strategy, dofs, rigid.iter().copied())
        };
        assert!(starts(Auto, Either, 900, &[true]));
        assert!(starts(Lu, Monolithic, 900, &[true, true]));
        assert!(starts(Auto, Either, AMD_DOFS + 3, &[]));
        assert!(starts(Petsc, Condensed, 900, &[true]));
        assert!(!starts(Auto, Either, AMD_DOFS, &[]));
        assert!(!starts(Auto, Either, 3 * AMD_DOFS, &[true, false]));
        assert!(!starts(Auto, Monolithic, 3 * AMD_DOFS, &[false]));
        assert!(starts(Auto, Condensed, 900, &[true, false]));
        assert!(!starts(Petsc, Either, 3 * AMD_DOFS, &[true]));
    }
}
