//! The contact interfaces of a problem and their life cycle:
//!
//! 1. **install** ([`ContactSet::install`]): number the multipliers of the
//!    interfaces one after the other;
//! 2. **update pairs** ([`ContactSet::refresh_pairs`]): at the start of an
//!    increment, pair the secondary nodes of every deformable interface with
//!    the primary triangles they may touch, which fixes the sparsity
//!    couplings ([`ContactSet::couplings`]) for the increment;
//! 3. **initial states** ([`ContactSet::initial_state`]);
//! 4. per Newton iteration: **assemble** ([`ContactSet::assemble`]),
//!    **precondition** ([`ContactSet::precondition`], friction in stick,
//!    dual mortar's multiplier couplings by the force columns),
//!    **advance** ([`ContactSet::advance`], the slack law's local unknowns);
//! 5. after Newton converged: **check pairs** ([`ContactSet::pairs_hold`]),
//!    **augment** ([`ContactSet::augment`], the outer loop of a law that
//!    has one), and once the increment is accepted **commit**
//!    ([`ContactSet::commit`]).
//!
//! The set owns the interfaces (their geometry, laws and pairs); the per-node
//! history ([`ContactState`]) is the stepper's, which keeps a trial copy per
//! increment attempt and throws it away on a cut.

use super::interface::{ContactContext, ContactInterface, NodeReport, Primary};
use super::laws::NodeContactState;
use crate::assembly::pattern::SparsityPattern;

/// The per-node contact states of every interface (multipliers held fixed
/// by Uzawa, local slack unknowns): history that Newton reads and the
/// stepper commits when an increment converges.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ContactState {
    pub interfaces: Vec<Vec<NodeContactState>>,
}

impl ContactState {
    /// Whether every node's state is finite ([`NodeContactState::is_finite`]).
    pub fn is_finite(&self) -> bool {
        self.interfaces.iter().flatten().all(|n| n.is_finite())
    }
}

/// The contact interfaces of a problem, reached through narrow queries
/// (each interface by index or name, their number, an iterator) and the
/// operations of the life cycle; no slice of them is lent out, so what
/// changes the numbering of the multipliers goes through
/// [`install`](Self::install).
#[derive(Clone, Debug, Default)]
pub struct ContactSet {
    pub(super) interfaces: Vec<ContactInterface>,
    /// Which couplings [`couplings`](Self::couplings) gives the pattern.
    pattern: ContactPattern,
}

/// Which contact couplings the sparsity pattern holds
/// ([`ContactSet::couplings`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ContactPattern {
    /// Newton's: every coupling its contact tangent fills, each secondary
    /// node's groups ([`ContactInterface::coupled_groups`]) and each
    /// multiplier with the nodes its row reads
    /// ([`ContactInterface::coupled_nodes`]).
    #[default]
    Newton,
    /// The condensed path's: each multiplier with its own node alone (so
    /// that it is ordered right after it, as node-to-surface's against
    /// an obstacle), no node groups. Its factor is of the elements'
    /// stiffness and reads no contact entry; a run builds this pattern
    /// until it has chosen its path, and Newton's couplings when Newton
    /// first runs ([`crate::problem::Problem::newton_pattern`]).
    Condensed,
}

impl<'a> IntoIterator for &'a ContactSet {
    type Item = &'a ContactInterface;
    type IntoIter = std::slice::Iter<'a, ContactInterface>;
    fn into_iter(self) -> Self::IntoIter {
        self.interfaces.iter()
    }
}

/// The sparsity couplings of the contact interfaces: node groups (each
/// secondary node of a deformable interface with its candidates' nodes) and
/// the nodes each multiplier couples to, and the multipliers each
/// multiplier couples to (a node's normal and tangential multipliers).
#[derive(Default)]
pub struct Couplings {
    pub groups: Vec<Vec<usize>>,
    pub multipliers: Vec<Vec<usize>>,
    pub multiplier_groups: Vec<Vec<usize>>,
}

impl ContactSet {
    /// Install `interfaces`, numbering their multipliers one after the other.
    pub fn install(&mut self, mut interfaces: Vec<ContactInterface>) {
        let mut offset = 0;
        for c in &mut interfaces {
            c.multiplier_offset = offset;
            offset += c.num_multipliers();
        }
        self.interfaces = interfaces;
    }

    /// The number of interfaces.
    pub fn len(&self) -> usize {
        self.interfaces.len()
    }

    /// Whether there is no interface.
    pub fn is_empty(&self) -> bool {
        self.interfaces.is_empty()
    }

    /// The interfaces in their order (that of the multipliers and of
    /// [`ContactState::interfaces`]).
    pub fn iter(&self) -> std::slice::Iter<'_, ContactInterface> {
        self.interfaces.iter()
    }

    /// Interface `i`.
    pub fn interface(&self, i: usize) -> &ContactInterface {
        &self.interfaces[i]
    }

    /// Interface `i`, to change its parameters (motion, amplitude, law's
    /// parameters, sizes); what changes its number of multipliers (its
    /// nodes, law kind, friction) needs [`install`](Self::install) again.
    pub fn interface_mut(&mut self, i: usize) -> &mut ContactInterface {
        &mut self.interfaces[i]
    }

    /// The interface named `name` with its index.
    pub fn by_name(&self, name: &str) -> Option<(usize, &ContactInterface)> {
        self.interfaces
            .iter()
            .enumerate()
            .find(|(_, c)| c.name == name)
    }

    /// The interfaces' names, in their order.
    pub fn names(&self) -> impl Iterator<Item = &str> {
        self.interfaces.iter().map(|c| c.name.as_str())
    }

    /// Whether any interface has exact stick's tangential multipliers as
    /// unknowns ([`ContactInterface::tangential_multipliers`]).
    pub fn has_tangential_multipliers(&self) -> bool {
        self.interfaces.iter().any(|c| c.tangential_multipliers())
    }

    /// Whether any interface has friction (a nonsymmetric tangent).
    pub fn has_friction(&self) -> bool {
        self.iter().any(|c| c.has_friction())
    }

    /// Whether the interfaces' tangent is nonsymmetric: with Coulomb
    /// friction, and with dual mortar between bodies, whose force acts
    /// through the gap's gradient at fixed `D`, `M` while its constraint
    /// row keeps the whole gradient (Popp, Gee & Wall 2009; the
    /// [`kinematics`](super::kinematics) module's docs): there `K_uλ` and
    /// `K_λuᵀ` differ by a fraction of the largest entry, not round-off.
    pub fn has_nonsymmetric_tangent(&self) -> bool {
        self.has_friction() || self.iter().any(|c| matches!(c.primary, Primary::Mortar(_)))
    }

    /// Which couplings the pattern is built with.
    pub fn pattern(&self) -> ContactPattern {
        self.pattern
    }

    /// Build the pattern with `pattern`'s couplings from now on (the
    /// caller rebuilds it).
    pub fn set_pattern(&mut self, pattern: ContactPattern) {
        self.pattern = pattern;
    }

    /// The sparsity couplings of the interfaces ([`ContactPattern`]).
    pub fn couplings(&self) -> Couplings {
        let newton = self.pattern == ContactPattern::Newton;
        let mut out = Couplings::default();
        for c in self.iter() {
            let groups = (0..c.nodes.len()).map(|i| match newton {
                true => c.coupled_nodes(i),
                false => vec![c.nodes[i]],
            });
            let first = out.multipliers.len();
            out.multipliers
                .resize(first + c.num_multipliers(), Vec::new());
            out.multiplier_groups
                .resize(first + c.num_multipliers(), Vec::new());
            for (i, nodes) in groups.enumerate() {
                let own = c.node_multipliers(i);
                for &k in &own {
                    out.multipliers[first + k] = nodes.clone();
                    out.multiplier_groups[first + k] = own.iter().map(|l| first + l).collect();
                }
            }
            // a mortar node couples the nodes of its faces (with each
            // other unless its lever lies on itself against a plane)
            if newton
                && matches!(
                    c.primary,
                    Primary::Surface(_) | Primary::Mortar(_) | Primary::MortarRigid(_)
                )
            {
                out.groups
                    .extend((0..c.nodes.len()).flat_map(|i| c.coupled_groups(i)));
            }
        }
        out
    }

    /// Pair the secondary nodes of every deformable interface with the
    /// primary triangles they may touch at unknowns `x`, with search margins
    /// `2h_t + 2 motion` (`src/contact/primary.rs`, search rule), and with
    /// `reached` (the unknowns of an answer that left the last pairs) the
    /// pairs a search there with no motion finds. Returns whether a pairing
    /// changed (then the couplings did).
    pub fn refresh_pairs(
        &mut self,
        reference: &[[f64; 3]],
        x: &[f64],
        motion: f64,
        reached: Option<&[f64]>,
    ) -> bool {
        let mut changed = false;
        for c in &mut self.interfaces {
            match &mut c.primary {
                Primary::Surface(p) => {
                    changed |= p.refresh(reference, x, &c.nodes, motion, reached)
                }
                Primary::Mortar(m) => changed |= m.refresh(reference, x, motion, reached),
                Primary::Rigid(_) | Primary::MortarRigid(_) => {}
            }
        }
        changed
    }

    /// The nodes of every deformable interface (secondary and primary).
    pub fn deformable_nodes(&self) -> Vec<usize> {
        let mut nodes: Vec<usize> = self
            .iter()
            .filter_map(|c| match &c.primary {
                Primary::Surface(p) => Some(c.nodes.iter().chain(&p.nodes).copied()),
                Primary::Mortar(m) => Some(c.nodes.iter().chain(&m.primary_nodes).copied()),
                Primary::Rigid(_) | Primary::MortarRigid(_) => None,
            })
            .flatten()
            .collect();
        nodes.sort_unstable();
        nodes.dedup();
        nodes
    }

    /// Whether every secondary node of the deformable interfaces found, at
    /// unknowns `x`, the primary triangle a fresh search would give it (the
    /// same gap, or open either way, to 1e-9 of the element size).
    pub fn pairs_hold(&self, reference: &[[f64; 3]], x: &[f64], contact: &ContactState) -> bool {
        self.iter().zip(&contact.interfaces).all(|(c, states)| {
            let p = match &c.primary {
                Primary::Surface(p) => p,
                Primary::Mortar(m) => return m.pairs_hold(reference, x),
                _ => return true,
            };
            let mut fresh = p.clone();
            fresh.refresh(reference, x, &c.nodes, 0.0, None);
            let mut with_fresh = c.clone();
            with_fresh.primary = Primary::Surface(fresh);
            let (used, now) = (
                c.gaps(reference, 0.0, x, Some(states)),
                with_fresh.gaps(reference, 0.0, x, Some(states)),
            );
            let tolerance = 1e-9 * c.element_size;
            used.iter()
                .zip(&now)
                // the same gap, or open either way (no force)
                .all(|(a, b)| (a - b).abs() <= tolerance || (*a > 0.0 && *b > 0.0))
        })
    }

    /// The states before the first increment (gaps at `x`, time 0).
    pub fn initial_state(&self, reference: &[[f64; 3]], x: &[f64]) -> ContactState {
        ContactState {
            interfaces: self
                .iter()
                .map(|c| c.initial_states(reference, x))
                .collect(),
        }
    }

    /// Add every interface's residual (and tangent) at `ctx`; the reports.
    pub fn assemble(
        &self,
        ctx: &ContactContext,
        contact: &ContactState,
        residual: &mut [f64],
        mut tangent: Option<(&SparsityPattern, &mut [f64])>,
    ) -> Vec<Vec<NodeReport>> {
        self.iter()
            .zip(&contact.interfaces)
            .map(|(c, states)| {
                let tangent = tangent.as_mut().map(|(p, k)| (*p, &mut **k));
                c.assemble(ctx, states, residual, tangent)
            })
            .collect()
    }

    /// Commit the history of every interface once an increment converged.
    pub fn commit(&self, ctx: &ContactContext, contact: &mut ContactState) {
        for (c, states) in self.iter().zip(&mut contact.interfaces) {
            c.commit_history(ctx, states);
        }
    }

    /// The outer loop of every interface whose law has one; `true` when
    /// any updated its multipliers (solve again).
    pub fn augment(&self, ctx: &ContactContext, contact: &mut ContactState) -> bool {
        let mut again = false;
        for (c, states) in self.iter().zip(&mut contact.interfaces) {
            again |= c.augment(ctx, states);
        }
        again
    }

    /// The preconditioner from the symmetric part `values` of the tangent
    /// `tangent`: every interface's stick preconditioner's shift
    /// ([`ContactInterface::shift_to_stick_preconditioner`]) and dual
    /// mortar's multiplier couplings from the tangent's force columns
    /// ([`ContactInterface::couple_multipliers_by_force`]).
    pub fn precondition(
        &self,
        ctx: &ContactContext,
        contact: &ContactState,
        constrained: &[bool],
        pattern: &SparsityPattern,
        (tangent, values): (&[f64], &mut [f64]),
    ) {
        for (c, states) in self.iter().zip(&contact.interfaces) {
            c.shift_to_stick_preconditioner(ctx, states, constrained, pattern, values);
            c.couple_multipliers_by_force(ctx, pattern, tangent, values);
        }
    }

    /// Carry the states along a Newton step `dx` from `ctx.x`.
    pub fn advance(&self, ctx: &ContactContext, dx: &[f64], contact: &mut ContactState) {
        for (c, states) in self.iter().zip(&mut contact.interfaces) {
            c.advance_states(ctx, dx, states);
        }
    }
}
