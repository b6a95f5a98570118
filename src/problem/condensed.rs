//! The condensed contact path (`[solver] strategy`, issue 13 item 1): for
//! a body whose stiffness `K` is constant (small-strain linear elasticity,
//! dead loads) against rigid planes, the contact problem of every
//! increment is solved exactly on the contact nodes alone, with one
//! factorisation of `K` per run.
//!
//! ## The equations
//! With `K̃` the stiffness whose prescribed rows and columns are a scaled
//! identity (as in Newton, [`crate::solve::newton::apply_identity_rows`];
//! the multiplier unknowns too, at zero), `E` the matrix whose column `a`
//! is the plane's normal `n` on the free dofs of contact node `a`, and
//! `λ_a = A_a t_N,a` the normal contact force of node `a`, equilibrium at
//! time `t` is
//!
//! ```text
//! K̃ u = b(t) + E λ,   b_f = f_ext(t) − K_fp ū(t),   b_p = s ū(t)
//! ```
//!
//! (`f_int = K u` exactly for a small-strain linear material). The gap of a
//! node on a plane is linear in `u`: `g = g(u₀) + Eᵀ(u − u₀)`, so with
//! `u₀ = K̃⁻¹ b(t)` and the flexibility `W = Eᵀ K̃⁻¹ E` (m × m, dense, one
//! solve with the factor per contact node, once per run)
//!
//! ```text
//! g = g(u₀) + W λ ≥ 0,   λ ≥ 0,   λ_a g_a = 0
//! ```
//!
//! a linear complementarity problem solved exactly
//! ([`crate::solve::complementarity`]); `u = K̃⁻¹ (b + E λ)` follows from one
//! more solve. The exact laws (Rockafellar, slack) converge to this very
//! solution (their `p`, `k` only condition Newton); penalty's
//! `t_N = ε⟨−g⟩` is the same problem with `W + diag(1/(A_a ε_a))`. Uzawa
//! meets `g ≥ 0` only to its outer loop's tolerance, so it is not
//! condensed. The monolithic answer is reproduced to round-off: the
//! converged state is checked by a full residual evaluation of the problem,
//! which must be within the Newton tolerance.
//!
//! ## Candidate nodes
//! `W` is built for the candidate nodes only: those that penetrate at
//! `u₀` (the answer without contact) or were candidates before. After the
//! complementarity solve every other node's gap is checked at `u`; a node
//! that penetrates joins the candidates (its column of `W` is one more
//! solve with the same factor) and the increment is solved again. The
//! factorisation is never repeated.
//!
//! ## Coulomb friction
//! With friction on some interface the run takes [`friction`]: three
//! unknowns per contact node, a dense semismooth Newton solve per
//! increment ([`crate::solve::cone`]), and a shifted `K̂` where only the
//! contact holds a body.
//!
//! ## Where it applies ([`not_applicable`])
//! Every material small-strain (`linear_elastic`: the total-Lagrangian
//! laws are geometrically nonlinear, their `K` changes with `u`), no
//! follower pressure, every contact against a rigid plane (translating or
//! not), frictionless or with Coulomb friction, with an exact or penalty
//! law, and every body held by its prescribed displacements (`K̃` regular:
//! a body held only by contact has a rigid-body mode) or, with friction,
//! by those and the nodes touching the plane at the start. `auto` takes it
//! exactly then; otherwise the run is monolithic and the log and
//! `summary.json` say why.

use super::{ContactState, Problem};
use crate::assembly::triangle::{self, LowerTriangle};
use crate::contact::interface::NodeReport;
use crate::contact::interface::Primary;
use crate::contact::laws::{NormalLaw, SlackState};
use crate::contact::obstacle::RigidObstacle;
use crate::material::Kinematics;
use crate::solve::complementarity::solve_lcp;
use crate::solve::decoupled::{decoupled_first, Decoupled};
use crate::solve::failure::IncrementFailure;
use crate::solve::linear::{scaled_identity_rows, Precision, SparseLdlt};
use crate::solve::linear_solver::SolverStatistics;
use crate::solve::method::{Increment, IncrementMethod, WarmStart};
use crate::solve::newton::{IterationRecord, NewtonOutcome};
use crate::solve::nonlinear::NonlinearProblem;
use crate::solve::schur::{grow_flexibility, trailing_ordering, Direction, TrailingInverse};
use crate::solve::settings::{LinearMethod, Strategy};
use crate::{Error, Result};
use nalgebra::{DMatrix, Matrix6, Vector3, Vector6};
use std::sync::Arc;

mod friction;

/// Which path a run takes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Path {
    Monolithic,
    Condensed,
}

impl Path {
    /// `"monolithic"` or `"condensed"` (summary.json's `strategy`).
    pub fn name(self) -> &'static str {
        match self {
            Path::Monolithic => "monolithic",
            Path::Condensed => "condensed",
        }
    }
}

/// The path a run takes and why the other one is not taken.
#[derive(Clone, Debug, PartialEq)]
pub struct Choice {
    pub path: Path,
    pub reason: String,
}

/// The path `[solver] strategy` asks for on `problem`; an error (the
/// reason) when `condensed` is asked for where it does not apply.
pub fn choose(problem: &Problem) -> std::result::Result<Choice, String> {
    let why_not = not_applicable(problem);
    let strategy = problem.settings.strategy;
    let condensed = || Choice {
        path: Path::Condensed,
        reason: if has_friction(problem) {
            "the stiffness is constant and every contact is against a rigid plane with Coulomb \
             friction: one factorisation per run, the frictional contact problem solved on the \
             contact nodes by a dense semismooth Newton method (monolithic Newton would \
             factorise at every iteration)"
                .into()
        } else {
            "the stiffness is constant and every contact is frictionless against a rigid \
             plane: one factorisation per run, the contact problem solved exactly on the \
             contact nodes (monolithic Newton would factorise at every iteration)"
                .into()
        },
    };
    match (strategy, why_not) {
        (Strategy::Monolithic, _) => Ok(Choice {
            path: Path::Monolithic,
            reason: "[solver] strategy = \"monolithic\"".into(),
        }),
        (Strategy::Condensed, None) | (Strategy::Auto, None) => Ok(condensed()),
        (Strategy::Condensed, Some(why)) => Err(format!(
            "solver.strategy = \"condensed\" does not apply: {why}; use strategy = \"auto\" or \
             \"monolithic\""
        )),
        (Strategy::Auto, Some(why)) => Ok(Choice {
            path: Path::Monolithic,
            reason: format!("the condensed path does not apply: {why}"),
        }),
    }
}

/// Why the condensed path does not apply to `problem` (`None`: it does).
pub fn not_applicable(problem: &Problem) -> Option<String> {
    if problem.contacts.is_empty() {
        return Some(
            "there is no contact (Newton solves a linear problem in one iteration)".into(),
        );
    }
    if let Some(m) = problem
        .model
        .materials
        .iter()
        .find(|m| m.kinematics() != Kinematics::SmallStrain)
    {
        return Some(format!(
            "material '{}' is finite-strain (its stiffness changes with the displacement)",
            m.name()
        ));
    }
    if let Some(p) = problem.pressures.iter().find(|p| p.follower) {
        return Some(format!(
            "the pressure on '{}' follows the deformed surface (its load stiffness changes)",
            p.surface
        ));
    }
    for c in &problem.contacts {
        let why = match (&c.primary, c.law) {
            (Primary::Surface(_), _) => Some("is between two bodies (not condensed yet)".into()),
            (Primary::Rigid(RigidObstacle::Plane { .. }), NormalLaw::Uzawa { .. }) => Some(
                "uses uzawa, which meets the constraint only to its outer loop's tolerance".into(),
            ),
            (Primary::Rigid(RigidObstacle::Plane { .. }), _) => None,
            (Primary::Rigid(o), _) => Some(format!(
                "is against a {}, whose gap is not linear in the displacement",
                match o {
                    RigidObstacle::Sphere { .. } => "sphere",
                    RigidObstacle::Cylinder { .. } => "cylinder",
                    _ => "triangulated surface",
                }
            )),
        };
        if let Some(why) = why {
            return Some(format!("contact '{}' {why}", c.name));
        }
    }
    let mut held = problem.constrained_dofs();
    if has_friction(problem) {
        // the frictional path shifts the dofs of the nodes touching at the
        // start (`K̂ = K̃ + ρ Σ I₃`), which holds a body that friction holds
        for d in friction::initially_touching_dofs(problem) {
            held[d] = true;
        }
    }
    free_rigid_body_mode(problem, &held).map(|why| {
        if has_friction(problem) {
            format!("{why}, and the nodes touching the obstacle at the start do not hold it")
        } else {
            why
        }
    })
}

/// A body (a connected set of elements) that the `constrained` dofs (its
/// prescribed displacements, and the shifted contact dofs) do not hold against every rigid-body motion (`K̃` is then singular),
/// named by one of its nodes; a node in no element that is not fully
/// prescribed. The six rigid modes of a body about its centroid `c`,
/// `t_i = e_i` and `r_i = e_i × (X − c)/L`, are held when their Gram
/// matrix over the prescribed dofs, `G = Σ_d m(d) m(d)ᵀ`, is regular
/// (smallest eigenvalue above 1e-10 of the largest).
fn free_rigid_body_mode(problem: &Problem, constrained: &[bool]) -> Option<String> {
    let mesh = &problem.model.mesh;
    let n = mesh.num_nodes();
    let mut parent: Vec<usize> = (0..n).collect();
    fn root(parent: &mut [usize], mut a: usize) -> usize {
        while parent[a] != a {
            parent[a] = parent[parent[a]];
            a = parent[a];
        }
        a
    }
    let mut in_element = vec![false; n];
    for e in &mesh.elements {
        for &a in &e.nodes {
            in_element[a] = true;
            let (ra, rb) = (root(&mut parent, a), root(&mut parent, e.nodes[0]));
            parent[ra] = rb;
        }
    }
    let mut bodies: std::collections::BTreeMap<usize, Vec<usize>> = Default::default();
    for a in 0..n {
        if !in_element[a] {
            if !(0..3).all(|d| constrained[3 * a + d]) {
                return Some(format!("node {} belongs to no element", mesh.node_ids[a]));
            }
            continue;
        }
        let r = root(&mut parent, a);
        bodies.entry(r).or_default().push(a);
    }
    for nodes in bodies.values() {
        let count = nodes.len() as f64;
        let mut c = Vector3::zeros();
        for &a in nodes {
            c += Vector3::from(mesh.nodes[a]) / count;
        }
        let size = nodes
            .iter()
            .map(|&a| (Vector3::from(mesh.nodes[a]) - c).norm())
            .fold(0.0f64, f64::max)
            .max(f64::MIN_POSITIVE);
        let mut gram = Matrix6::zeros();
        for &a in nodes {
            let y = (Vector3::from(mesh.nodes[a]) - c) / size;
            for d in 0..3 {
                if !constrained[3 * a + d] {
                    continue;
                }
                let mut m = Vector6::zeros();
                m[d] = 1.0;
                for axis in 0..3 {
                    m[3 + axis] = Vector3::ith(axis, 1.0).cross(&y)[d];
                }
                gram += m * m.transpose();
            }
        }
        let eigen = gram.symmetric_eigenvalues();
        let (lo, hi) = (eigen.min(), eigen.max());
        if !(lo > 1e-10 * hi) {
            return Some(format!(
                "the body of node {} is held only by contact (a rigid-body motion is free of \
                 prescribed displacements, so its stiffness is singular)",
                mesh.node_ids[nodes[0]]
            ));
        }
    }
    None
}

/// One secondary node of a rigid-plane interface.
struct ContactNode {
    interface: usize,
    /// Index among the interface's nodes, and the mesh node.
    index: usize,
    node: usize,
    normal: Vector3<f64>,
    /// `1/(A ε)` of a penalty law (0 for the exact laws): the diagonal
    /// added to `W`.
    compliance: f64,
}

/// The condensed solver of a run: the factor of `K̃`, the contact nodes,
/// the candidates and their flexibility `W`.
struct Condensation {
    ldlt: SparseLdlt,
    /// `(K̃⁻¹)_TT` on the normal dofs of the contact nodes nearest to their
    /// planes, ordered last in the factorisation: `W` of those nodes
    /// without solves ([`crate::solve::schur`]).
    trailing: TrailingInverse,
    trailing_dofs: Vec<usize>,
    /// The lower triangle of the pattern, and on it `K` as assembled and
    /// `K̃` (prescribed rows, columns and multipliers a scaled identity
    /// `s`): what the factorisation and the products read.
    lower: Arc<LowerTriangle>,
    k: Arc<Vec<f64>>,
    k_tilde: Vec<f64>,
    /// `K̃` without the couplings of its identity rows, as factorised.
    decoupled: Decoupled,
    scale: f64,
    constrained: Vec<bool>,
    nodes: Vec<ContactNode>,
    /// Candidate nodes (indices into `nodes`), `W` over them, and the
    /// last active set.
    candidates: Vec<usize>,
    /// The candidates in the batches they joined in (a restart's replay).
    batches: Vec<Vec<usize>>,
    is_candidate: Vec<bool>,
    w: DMatrix<f64>,
    active: Vec<bool>,
    active_set_iterations: usize,
    /// f32 factorisations refactorised in f64 when a refined solve stalled.
    fallbacks: usize,
}

/// The largest relative residual the condensed solution may leave when a
/// tighter `residual_tolerance` is asked for: the round-off of the solves
/// and of the residual's assembly (2e-12 measured on Hertz).
const RESIDUAL_FLOOR: f64 = 1e-10;

/// The nodes that join the candidates in one round penetrate by at least
/// this fraction of the deepest penetration ([`Condensation::entering`]).
/// On examples/hertz (335 closed nodes at the end) 0 gives 621 candidates,
/// 0.3 gives 530, 0.5 gives 431 and 0.8 the 335 closed nodes exactly but in
/// 68 active-set steps instead of 13 and more rounds of small solves:
/// 0.5 was the fastest.
const ENTERING_FRACTION: f64 = 0.5;

/// At most this many unknowns ordered last for `(K̃⁻¹)_TT` (a dense
/// block: `2c³/3` flops to read, `c²` entries): the normal dofs of the
/// contact nodes with the smallest gaps at `u = 0`; a node beyond them
/// gets its column of `W` by a solve.
const MAX_TRAILING: usize = 4000;

/// On the frictionless path the normal dofs of the nearest half of the
/// contact nodes are ordered last: each node there costs fill and its share
/// of the `c³` of `(K̃⁻¹)_TT`, a node outside it a column of `W` by a solve
/// once it becomes a candidate, and on Hertz about 36 % of the nodes close
/// (266 of 737 on the small race mesh, 848 of 2 436 on the large one, 335
/// of 925 on examples/hertz). Half instead of all: factor entries 10.2 →
/// 9.0 M (small), 137 → 121 M (large), 16.9 → 14.8 M (examples/hertz), the
/// same answers to 1e-10 and no longer solve phase. The frictional path
/// keeps every node (its nodes touch from the start).
const TRAILING_FRACTION: f64 = 0.5;

/// From this many unknowns `[solver] linear = "auto"` factorises `K̃` in
/// f32 on the condensed path (refined in f64; the contact forces corrected
/// against the f64 gaps, [`Condensation::solve_increment`]): the one
/// factorisation is most of the run there.
const MIXED_PRECISION_UNKNOWNS: usize = 10_000;

/// Below this many unknowns the one factorisation of `K̃`, its solves and
/// `(K̃⁻¹)_TT` run on one thread (faer's `Par::Seq`) whatever the run's
/// thread count, from it on the run's threads: the one constant of that
/// choice ([`SparseLdlt::threads_as_given`]; the dense `(K̃⁻¹)_TT` follows
/// the factor's threads). On the small race mesh (19 100 unknowns, 9.0 M
/// factor entries) the f32 factorisation took 0.13–0.14 s on one thread at
/// any load, on two 0.11 s on an idle machine but 0.24–0.32 s beside two
/// compiling processes (1-minute load 4), the supernodes being too small
/// for the threads' synchronisation to pay; at 108 k unknowns (121 M
/// entries) two threads do pay. On an idle machine (1-minute load 1.7,
/// 2026-11-25 23:50, 10 + 10 alternating whole runs of the small race)
/// two threads took 0.92–0.96× the wall time of one and 1.13–1.16× its
/// CPU; issue 13 measures wall time, so from 10 000 unknowns the run's
/// threads are used (BENCHMARKS.md, "Session 9").
const PARALLEL_FACTOR_UNKNOWNS: usize = 10_000;

/// Refinement steps at most on an f32 factor before the f64 fallback.
const MIXED_REFINEMENTS: usize = 10;

impl Condensation {
    /// The frictionless condensation: one column per secondary node of
    /// every rigid-plane interface, its normal; `K̃` unshifted.
    fn new(problem: &Problem) -> Result<Self> {
        let mut nodes = Vec::new();
        for (ci, c) in problem.contacts.iter().enumerate() {
            let Primary::Rigid(RigidObstacle::Plane { normal, .. }) = &c.primary else {
                continue;
            };
            for (i, &node) in c.nodes.iter().enumerate() {
                let compliance = match c.law_at(i) {
                    NormalLaw::Penalty { epsilon } => 1.0 / (c.areas[i] * epsilon),
                    _ => 0.0,
                };
                nodes.push(ContactNode {
                    interface: ci,
                    index: i,
                    node,
                    normal: *normal,
                    compliance,
                });
            }
        }
        Self::factorise(problem, nodes, &[], TRAILING_FRACTION, true)
    }

    /// Assemble `K` at `u = 0` (its lower triangle), make `K̃` (prescribed rows and columns a
    /// scaled identity `s`, plus `ρ = s` on the diagonal of the `shifted`
    /// dofs) and factorise it once; `nodes` are the columns of `E`, the
    /// nearest `fraction` of them ordered last. The assembly and the
    /// ordering with its symbolic analysis (which read only the pattern)
    /// run side by side on the run's threads, the ordering's nested
    /// dissection mostly done before ([`Problem::dissection`]). In f32
    /// (from [`MIXED_PRECISION_UNKNOWNS`], or `linear = "mixed"`) only where
    /// `single_allowed`: the frictionless solve corrects the contact
    /// forces for the f32 `W̃` ([`Self::solve_increment`]); the frictional
    /// one has no such correction and factorises in f64 (on a 10 k-dof
    /// floating block the f32 `Ŵ` left a residual of 5.7e-7).
    fn factorise(
        problem: &Problem,
        nodes: Vec<ContactNode>,
        shifted: &[usize],
        fraction: f64,
        single_allowed: bool,
    ) -> Result<Self> {
        let pattern = &problem.model.pattern;
        let dimension = pattern.dimension();
        let mut constrained = problem.constrained_dofs();
        let dofs = problem.model.num_dofs();
        constrained[dofs..].iter_mut().for_each(|c| *c = true);
        let lower = problem.model.lower_triangle();
        let (k, analysed) = rayon::join(
            || match problem.model.constant_stiffness() {
                Some(k) => Ok(k),
                None => {
                    let mut k = vec![0.0; lower.nnz()];
                    let mut force = vec![0.0; dimension];
                    problem
                        .model
                        .assemble_internal_lower(&vec![0.0; dimension], &mut force, &mut k)
                        .map_err(|f| Error::LinearSolver(problem.describe_failure(&f)))
                        .map(|()| Arc::new(k))
                }
            },
            || Self::analyse(problem, &lower, &nodes, &constrained, fraction),
        );
        let (k, (trailing, decoupled, mut ldlt)) = (k?, analysed?);
        let count = nodes.len();
        let single = single_allowed
            && match problem.settings.linear {
                LinearMethod::Mixed => true,
                LinearMethod::Auto => dimension >= MIXED_PRECISION_UNKNOWNS,
                _ => false,
            };
        let precision = if single {
            Precision::Single
        } else {
            Precision::Double
        };
        // the factor's storage sized (its pages touched) on one thread
        // while the other makes `K̃` and its values
        let (_, (k_tilde, scale, values)) = rayon::join(
            || ldlt.reserve(precision),
            || {
                let mut k_tilde = k.to_vec();
                let diagonal = |d: usize| lower.diagonal_entry(d);
                let scale = scaled_identity_rows(
                    lower.symbolic(),
                    diagonal,
                    dofs,
                    &constrained,
                    &mut k_tilde,
                );
                for &d in shifted {
                    k_tilde[lower.diagonal_entry(d)] += scale;
                }
                let values = decoupled.values(&k_tilde);
                (k_tilde, scale, values)
            },
        );
        if single {
            ldlt.factorize_single(decoupled.symbolic(), &values, None)?;
        } else {
            ldlt.factorize(decoupled.symbolic(), &values, None)?;
        }
        let trailing_dofs = trailing;
        let trailing = TrailingInverse::of(&ldlt, &trailing_dofs)?;
        Ok(Condensation {
            ldlt,
            trailing,
            trailing_dofs,
            lower,
            k,
            k_tilde,
            decoupled,
            scale,
            constrained,
            nodes,
            candidates: Vec::new(),
            batches: Vec::new(),
            is_candidate: vec![false; count],
            w: DMatrix::zeros(0, 0),
            active: Vec::new(),
            active_set_iterations: 0,
            fallbacks: 0,
        })
    }

    /// The factorisation's ordering and symbolic analysis: the normal dofs
    /// of the nearest contact nodes last ([`Self::nearest_normal_dofs`]),
    /// the decoupled identity rows of `constrained` first and without
    /// their couplings ([`Decoupled`]). Returns those trailing dofs, the
    /// decoupled structure and the analysed solver.
    fn analyse(
        problem: &Problem,
        lower: &LowerTriangle,
        nodes: &[ContactNode],
        constrained: &[bool],
        fraction: f64,
    ) -> Result<(Vec<usize>, Decoupled, SparseLdlt)> {
        let pattern = &problem.model.pattern;
        let dimension = pattern.dimension();
        let trailing = Self::nearest_normal_dofs(problem, nodes, constrained, fraction);
        let mut marked = vec![false; dimension];
        trailing.iter().for_each(|&i| marked[i] = true);
        // 1: one thread (`Par::Seq`), 0: the run's pool
        let threads = usize::from(dimension < PARALLEL_FACTOR_UNKNOWNS);
        // the structure first: the dissection may still be running
        // ([`crate::problem::dissects_element_graph`])
        let decoupled = Decoupled::new(lower.symbolic(), constrained);
        let ordering = trailing_ordering(pattern, &marked, problem.dissection.as_ref())?;
        let ordering = decoupled_first(ordering, constrained);
        let mut ldlt = SparseLdlt::new(ordering, threads).threads_as_given();
        ldlt.analyse(decoupled.symbolic())?;
        Ok((trailing, decoupled, ldlt))
    }

    /// The free dofs on which the normals of the contact nodes nearest to
    /// their planes (gap at `u = 0`, the smallest over the steps' ends)
    /// have a component, of the nearest `fraction` of the nodes, at most
    /// [`MAX_TRAILING`].
    fn nearest_normal_dofs(
        problem: &Problem,
        nodes: &[ContactNode],
        constrained: &[bool],
        fraction: f64,
    ) -> Vec<usize> {
        let dimension = constrained.len();
        let limit = MAX_TRAILING.min((fraction * nodes.len() as f64).ceil() as usize);
        let zero = vec![0.0; dimension];
        let reference = &problem.model.mesh.nodes;
        let mut gap = vec![f64::INFINITY; nodes.len()];
        let times = std::iter::once(0.0).chain(problem.steps.iter().map(|s| s.end_time));
        for t in times {
            let per_interface: Vec<Vec<f64>> = problem
                .contacts
                .iter()
                .map(|c| match c.primary {
                    Primary::Rigid(RigidObstacle::Plane { .. }) => {
                        c.gaps(reference, t, &zero, None)
                    }
                    _ => Vec::new(),
                })
                .collect();
            for (g, c) in gap.iter_mut().zip(nodes) {
                *g = g.min(per_interface[c.interface][c.index]);
            }
        }
        let mut order: Vec<usize> = (0..nodes.len()).collect();
        order.sort_by(|&a, &b| gap[a].total_cmp(&gap[b]));
        let mut dofs = Vec::new();
        let mut taken = vec![false; dimension];
        for a in order {
            let c = &nodes[a];
            let free: Vec<usize> = (0..3)
                .map(|d| 3 * c.node + d)
                .filter(|&i| !constrained[i] && c.normal[i % 3] != 0.0 && !taken[i])
                .collect();
            if dofs.len() + free.len() > limit {
                break;
            }
            free.iter().for_each(|&i| taken[i] = true);
            dofs.extend(free);
        }
        dofs
    }

    /// `E e_a`: the normal of node `a` on its free dofs, as a direction.
    fn direction(&self, a: usize) -> Direction {
        let c = &self.nodes[a];
        (0..3)
            .map(|d| (3 * c.node + d, c.normal[d]))
            .filter(|&(i, n)| !self.constrained[i] && n != 0.0)
            .collect()
    }

    /// `E e_a`: the normal of node `a` on its free dofs.
    fn add_column(&self, a: usize, factor: f64, v: &mut [f64]) {
        let c = &self.nodes[a];
        for d in 0..3 {
            if !self.constrained[3 * c.node + d] {
                v[3 * c.node + d] += factor * c.normal[d];
            }
        }
    }

    /// Add the nodes `new` to the candidates: their columns of `W` from
    /// `(K̃⁻¹)_TT` or by block solves with the factor
    /// ([`grow_flexibility`]).
    fn grow(&mut self, new: &[usize]) -> Result<()> {
        if !new.is_empty() {
            self.batches.push(new.to_vec());
        }
        self.candidates.extend_from_slice(new);
        new.iter().for_each(|&a| self.is_candidate[a] = true);
        let directions: Vec<Direction> =
            self.candidates.iter().map(|&a| self.direction(a)).collect();
        let n = self.constrained.len();
        self.w = grow_flexibility(&mut self.ldlt, &self.trailing, &self.w, &directions, n)?;
        self.active.resize(self.candidates.len(), false);
        Ok(())
    }

    /// The nodes that join the candidates at gaps `g`: those outside them
    /// that penetrate by more than `tolerance` and by at least
    /// [`ENTERING_FRACTION`] of the deepest such penetration (the deepest
    /// first: a node that penetrates only a little without contact is
    /// often lifted off by its neighbours' forces, and every candidate
    /// costs a solve).
    fn entering(&self, g: &[f64], tolerance: f64) -> Vec<usize> {
        let outside = |a: &usize| !self.is_candidate[*a] && g[*a] < -tolerance;
        let deepest = (0..self.nodes.len())
            .filter(outside)
            .map(|a| g[a])
            .fold(0.0f64, f64::min);
        // a node on the trailing block costs no solve: every one that
        // penetrates enters
        (0..self.nodes.len())
            .filter(|a| {
                outside(a)
                    && (g[*a] <= ENTERING_FRACTION * deepest
                        || self.trailing.covers(&self.direction(*a)))
            })
            .collect()
    }

    /// `K̃ u = rhs`, refined ([`Self::solve_from`] the factor's solution).
    fn solve(&mut self, rhs: &mut [f64]) -> Result<()> {
        let b = rhs.to_vec();
        self.ldlt.solve_in_place(rhs)?;
        self.solve_from(&b, rhs)
    }

    /// `K̃ x = b` refined from the approximate solution `x` (from the
    /// solution for a nearby `b` it takes fewer refinement steps than a
    /// fresh solve); on an f32 factor whose refinement stalls above 1e-12,
    /// `K̃` factorised again in f64 (and `W` made again from it) and
    /// solved with that.
    fn solve_from(&mut self, b: &[f64], x: &mut [f64]) -> Result<()> {
        let single = self.ldlt.precision() == Precision::Single;
        let refinements = if single { MIXED_REFINEMENTS } else { 3 };
        let (lower, k_tilde) = (&self.lower, &self.k_tilde);
        let product =
            |v: &[f64], y: &mut [f64]| triangle::multiply(lower.symbolic(), k_tilde, v, y);
        let mut relative = self.ldlt.refine_with(product, b, x, refinements, single)?;
        if single && relative > 1e-12 {
            self.fallbacks += 1;
            let values = self.decoupled.values(&self.k_tilde);
            self.ldlt
                .factorize(self.decoupled.symbolic(), &values, None)?;
            self.trailing = TrailingInverse::of(&self.ldlt, &self.trailing_dofs)?;
            let directions: Vec<Direction> =
                self.candidates.iter().map(|&a| self.direction(a)).collect();
            let n = self.constrained.len();
            let none = DMatrix::zeros(0, 0);
            self.w = grow_flexibility(&mut self.ldlt, &self.trailing, &none, &directions, n)?;
            x.copy_from_slice(b);
            self.ldlt.solve_in_place(x)?;
            relative = self.ldlt.refine_with(product, b, x, 3, false)?;
        }
        if relative > 1e-10 {
            return Err(Error::LinearSolver(format!(
                "the condensed stiffness solve left a relative residual of {relative:.1e}"
            )));
        }
        Ok(())
    }

    /// `b(t)`: `f_ext(t) − K_fp ū(t)` on the free dofs, `s ū(t)` on the
    /// prescribed ones, 0 on the multipliers.
    fn load(&self, problem: &Problem, t: f64) -> Vec<f64> {
        let dimension = self.constrained.len();
        let mut prescribed = vec![0.0; dimension];
        problem.apply_prescribed(t, &mut prescribed);
        let dofs = problem.model.num_dofs();
        let mut k_prescribed = vec![0.0; dimension];
        triangle::multiply(
            self.lower.symbolic(),
            &self.k,
            &prescribed,
            &mut k_prescribed,
        );
        let f = problem.external_force(t, &prescribed[..dofs], None);
        (0..dimension)
            .map(|i| {
                if i >= dofs {
                    0.0
                } else if self.constrained[i] {
                    self.scale * prescribed[i]
                } else {
                    f[i] - k_prescribed[i]
                }
            })
            .collect()
    }

    /// The gaps of every contact node at unknowns `x`, time `t`.
    fn gaps(&self, problem: &Problem, t: f64, x: &[f64]) -> Vec<f64> {
        let reference = &problem.model.mesh.nodes;
        let per_interface: Vec<Vec<f64>> = problem
            .contacts
            .iter()
            .map(|c| match c.primary {
                Primary::Rigid(RigidObstacle::Plane { .. }) => c.gaps(reference, t, x, None),
                _ => Vec::new(),
            })
            .collect();
        self.nodes
            .iter()
            .map(|c| per_interface[c.interface][c.index])
            .collect()
    }

    /// The displacements and contact forces (per node, `λ_a = A_a t_N`) at
    /// time `t`.
    ///
    /// `W` may be inexact (from an f32 factor): the complementarity problem
    /// is solved on `W̃` with the gaps shifted by the defect
    /// `d = g(u(λ)) − (g₀ + W̃λ) = (W − W̃)λ + (g(K̃⁻¹b) − g₀)` of the last
    /// solution, `g(u)` the gaps of the refined (f64) displacements and `g₀`
    /// those of the factor's unrefined `u₀` (its error, constant, is taken
    /// up by the first defect; refining `u₀` took two of the small race's
    /// eight solves with the factor), until `d` changes by
    /// less than a thousandth of the gap tolerance: then `g(u) = g₀ + Wλ` and the solution
    /// is the one of the exact `W` (a splitting iteration, contracting
    /// while `‖W̃⁻¹(W − W̃)‖ < 1`). With an f64 `W` the first `d` is
    /// round-off and one pass is enough.
    fn solve_increment(
        &mut self,
        problem: &Problem,
        t: f64,
        history: &mut Vec<IterationRecord>,
    ) -> Result<(Vec<f64>, Vec<f64>)> {
        let b = self.load(problem, t);
        // the factor's solution, unrefined: `g₀` enters the complementarity
        // problem only in `q = g₀ + d`, and the defect `d` of the refined
        // `u` takes up its error exactly, as it does `W̃`'s
        let mut u0 = b.clone();
        self.ldlt.solve_in_place(&mut u0)?;
        let g0 = self.gaps(problem, t, &u0);
        let tolerance = 1e-12 * problem.model.size();
        let entering = self.entering(&g0, tolerance);
        self.grow(&entering)?;
        let mut defect = vec![0.0; self.nodes.len()];
        // defect corrections before the splitting is taken as diverging
        const MAX_CORRECTIONS: usize = 50;
        let mut previous_change = f64::INFINITY;
        let mut previous = u0;
        for _ in 0..MAX_CORRECTIONS {
            let q: Vec<f64> = self.candidates.iter().map(|&a| g0[a] + defect[a]).collect();
            let mut w = self.w.clone();
            for (i, &a) in self.candidates.iter().enumerate() {
                w[(i, i)] += self.nodes[a].compliance;
            }
            let lambda_scale = (0..q.len()).map(|i| w[(i, i)]).fold(0.0f64, f64::max);
            let solution = solve_lcp(
                &w,
                &q,
                &self.active,
                tolerance,
                1e-14 * tolerance / lambda_scale.max(f64::MIN_POSITIVE),
            )
            .map_err(Error::LinearSolver)?;
            self.active_set_iterations += solution.iterations;
            self.active = solution.active;
            history.extend(solution.history);
            let mut rhs = b.clone();
            let mut forces = vec![0.0; self.nodes.len()];
            for (i, &a) in self.candidates.iter().enumerate() {
                forces[a] = solution.lambda[i];
                self.add_column(a, solution.lambda[i], &mut rhs);
            }
            // from the last pass's displacements: its forces differ by
            // the defect's correction only
            let mut u = previous;
            self.solve_from(&rhs, &mut u)?;
            previous = u.clone();
            let g = self.gaps(problem, t, &u);
            let mut change = 0.0f64;
            for (i, &a) in self.candidates.iter().enumerate() {
                let predicted = g0[a]
                    + (0..self.candidates.len())
                        .map(|j| self.w[(i, j)] * solution.lambda[j])
                        .sum::<f64>();
                let d = g[a] - predicted;
                change = change.max((d - defect[a]).abs());
                defect[a] = d;
            }
            let entering = self.entering(&g, tolerance);
            // settled: far below the gap tolerance (a gap error `δ` is a
            // force residual `k δ` in the augmented laws), or within it and
            // no longer contracting (round-off)
            let settled = change <= 1e-3 * tolerance
                || change <= tolerance && change >= 0.5 * previous_change;
            previous_change = change;
            if entering.is_empty() && settled {
                return Ok((u, forces));
            }
            self.grow(&entering)?;
        }
        Err(Error::LinearSolver(format!(
            "the condensed contact forces did not settle in {MAX_CORRECTIONS} corrections of \
             the flexibility; run with [solver] linear = \"ldlt\""
        )))
    }
}

/// One increment of a condensed path: the unknowns `x` (displacements and
/// the multipliers of the laws that have them) and the trial contact state
/// at time `t` from the committed `state`, so that the problem's own
/// evaluation reports (and checks) the answer; the contact solve's
/// iterations pushed to `history`.
trait IncrementSolver: Send {
    fn increment(
        &mut self,
        problem: &Problem,
        t: f64,
        state: &ContactState,
        x: &mut [f64],
        trial: &mut ContactState,
        history: &mut Vec<IterationRecord>,
    ) -> Result<()>;

    /// The factorisation's statistics and the iterations of the contact
    /// solves (active-set steps, semismooth Newton iterations).
    fn statistics(&self) -> (SolverStatistics, usize);

    /// The candidates in the order they joined, the active set and the
    /// last answer: what the next increment starts from.
    fn warm_start(&self) -> WarmStart;

    /// Take up a checkpointed warm start: the candidates added again in
    /// the same batches (so `W` is the same to the bit), the rest copied.
    fn resume(&mut self, warm: &WarmStart) -> Result<()>;
}

impl IncrementSolver for Condensation {
    fn increment(
        &mut self,
        problem: &Problem,
        t: f64,
        _: &ContactState,
        x: &mut [f64],
        trial: &mut ContactState,
        history: &mut Vec<IterationRecord>,
    ) -> Result<()> {
        let (u, forces) = self.solve_increment(problem, t, history)?;
        let mut pressures = zero_per_node(problem);
        for (a, c) in self.nodes.iter().enumerate() {
            pressures[c.interface][c.index] =
                forces[a] / problem.contacts.interface(c.interface).areas[c.index];
        }
        set_multipliers(problem, &pressures, &u, t, x, trial);
        Ok(())
    }

    fn statistics(&self) -> (SolverStatistics, usize) {
        let statistics = SolverStatistics {
            mixed_precision_fallbacks: self.fallbacks,
            ..SolverStatistics::of_ldlt(&self.ldlt)
        };
        (statistics, self.active_set_iterations)
    }

    fn warm_start(&self) -> WarmStart {
        WarmStart {
            batches: self.batches.clone(),
            active: self.active.clone(),
            ..WarmStart::default()
        }
    }

    fn resume(&mut self, warm: &WarmStart) -> Result<()> {
        for batch in &warm.batches {
            self.grow(batch)?;
        }
        self.active.clone_from(&warm.active);
        Ok(())
    }
}

/// The condensed contact path as a method of the stepper
/// ([`crate::solve::stepping::resume_steps`]): each increment solved
/// exactly (frictional contact by [`friction`], frictionless by the
/// complementarity problem) with the one factorisation of the run,
/// evaluated once by the problem for its residual (within the Newton
/// tolerance, else the increment fails: `auto` then retries it on Newton's
/// path) and reports. Its iterations are the contact solve's (active-set
/// steps, semismooth Newton iterations), the last record the evaluation.
/// Frictionless increments grow after every increment (each is solved
/// exactly); frictional ones stay the case's (friction is path dependent,
/// and they are the ones Newton takes where it needs no cut).
pub struct Condensed {
    solver: Box<dyn IncrementSolver>,
    path_dependent: bool,
}

impl Condensed {
    /// The condensation of `problem` (the caller checked
    /// [`not_applicable`]): `K̃` assembled and factorised once.
    pub fn new(problem: &Problem) -> Result<Self> {
        let path_dependent = has_friction(problem);
        let solver: Box<dyn IncrementSolver> = if path_dependent {
            Box::new(friction::FrictionalCondensation::new(problem)?)
        } else {
            Box::new(Condensation::new(problem)?)
        };
        Ok(Condensed {
            solver,
            path_dependent,
        })
    }
}

impl IncrementMethod<Problem> for Condensed {
    fn name(&self) -> &'static str {
        Path::Condensed.name()
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
        let t = increment.time;
        let committed = state.clone();
        x.clear();
        x.extend_from_slice(u);
        let mut history = Vec::new();
        let solved = self
            .solver
            .increment(problem, t, &committed, x, state, &mut history);
        for record in &history {
            if !on_iteration(record) {
                return (Err(IncrementFailure::Cancelled), history);
            }
        }
        if let Err(e) = solved {
            return (Err(IncrementFailure::Condensed(e.to_string())), history);
        }
        let evaluation = match problem.evaluate(t, x, state, None) {
            Ok(e) => e,
            Err(f) => return (Err(f), history),
        };
        let constrained = problem.constrained_dofs();
        let free: f64 = (evaluation.residual.iter().zip(&constrained))
            .filter(|(_, &c)| !c)
            .map(|(r, _)| r * r)
            .sum();
        let scale = evaluation
            .force_scale()
            .max(increment.force_scale)
            .max(f64::MIN_POSITIVE);
        let relative = free.sqrt() / scale;
        // the solution is exact: only round-off (≈ 1e-12 on Hertz) remains
        let tolerance = problem.settings.residual_tolerance.max(RESIDUAL_FLOOR);
        let record = IterationRecord {
            residual: relative,
            correction: 0.0,
            step_length: 1.0,
            switched: 0,
            linear: Default::default(),
        };
        // the converged evaluation, as Newton's, is not an iteration told
        history.push(record);
        if !(relative <= tolerance) {
            let failure = IncrementFailure::CondensedResidual {
                relative,
                tolerance,
            };
            return (Err(failure), history);
        }
        (Ok(evaluation), history)
    }

    fn grows(&self, _: &[IterationRecord], _: usize) -> bool {
        !self.path_dependent
    }

    fn statistics(&self) -> SolverStatistics {
        self.solver.statistics().0
    }

    fn warm_start(&self) -> Option<WarmStart> {
        Some(self.solver.warm_start())
    }

    fn resume(&mut self, _: &Problem, warm: &WarmStart) -> Result<()> {
        self.solver.resume(warm)
    }
}

/// Whether any interface has Coulomb friction (`μ > 0`).
fn has_friction(problem: &Problem) -> bool {
    problem.contacts.iter().any(|c| c.has_friction())
}

/// A zero per secondary node of every interface.
fn zero_per_node(problem: &Problem) -> Vec<Vec<f64>> {
    problem
        .contacts
        .iter()
        .map(|c| vec![0.0; c.nodes.len()])
        .collect()
}

/// The unknowns `x` of the monolithic system at the condensed solution:
/// the displacements `u` and, for the multiplier laws, `λ = t_N / k` with
/// `t_N = pressures[interface][node]` (the slack law's local unknowns
/// consistent with them), so that the problem's own evaluation reports the
/// state.
fn set_multipliers(
    problem: &Problem,
    pressures: &[Vec<f64>],
    u: &[f64],
    t: f64,
    x: &mut [f64],
    state: &mut ContactState,
) {
    let dofs = problem.model.num_dofs();
    x[..dofs].copy_from_slice(&u[..dofs]);
    let reference = &problem.model.mesh.nodes;
    for (ci, interface) in problem.contacts.iter().enumerate() {
        let gaps = interface.gaps(reference, t, u, None);
        for (i, &pressure) in pressures[ci].iter().enumerate() {
            let node = &mut state.interfaces[ci][i];
            match interface.law_at(i) {
                NormalLaw::Rockafellar { k, .. } => node.lambda = pressure / k,
                NormalLaw::Slack { p, k } => {
                    node.lambda = pressure / k;
                    node.slack = SlackState::consistent(gaps[i], node.lambda, p, k);
                }
                _ => continue,
            }
            x[dofs + interface.multiplier_offset + i] = node.lambda;
        }
    }
}
