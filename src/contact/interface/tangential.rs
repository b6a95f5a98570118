//! An interface's tangential settings node by node: its Coulomb law
//! with the node's factor, exact stick and its tangential multipliers,
//! and the nodes' prescribed axes with exact stick's rule of
//! [`friction::HeldTangent`] there.

use super::{ContactInterface, Primary};
use crate::contact::friction::{self, Coulomb, FrictionMultiplier};
use nalgebra::Vector3;

impl ContactInterface {
    /// The friction law of secondary node `i` (its tangential penalty
    /// with the node's factor).
    pub fn friction_at(&self, i: usize) -> Option<Coulomb> {
        let f = self.tangential_scale.get(i).copied().unwrap_or(1.0);
        self.friction.map(|c| Coulomb {
            tangential_penalty: c.tangential_penalty * f,
            ..c
        })
    }

    /// Whether friction sticks exactly (the augmented Lagrangian of
    /// [`friction`], "Exact stick"): asked for, with a law that augments
    /// friction ([`NormalLaw::augments_friction`]), against a rigid
    /// obstacle or a primary surface.
    pub fn exact_stick(&self) -> bool {
        self.exact_stick_requested && self.law.augments_friction()
    }

    /// Whether exact stick's tangential multipliers are unknowns of Newton
    /// (two per node, numbered after the `n` normal multipliers of the
    /// interface: its multiplier `n + 2i + α` is node `i`'s `ℓ^α`,
    /// [`TangentialMultiplier`]): with friction, exact stick, the law's
    /// multiplier dof and [`FrictionMultiplier::Newton`].
    pub fn tangential_multipliers(&self) -> bool {
        self.has_friction()
            && self.exact_stick()
            && self.law.has_multiplier_dof()
            && self.friction_multiplier == FrictionMultiplier::Newton
    }

    /// Record which components of each secondary node are prescribed,
    /// from the mask `constrained` over all dofs (`3 × node + component`).
    pub fn set_prescribed_axes(&mut self, constrained: &[bool]) {
        self.prescribed_axes = (self.nodes.iter())
            .map(|&a| [0, 1, 2].map(|d| constrained.get(3 * a + d) == Some(&true)))
            .collect();
    }

    /// Whether exact stick's rule of [`friction::HeldTangent`] may apply
    /// at node `i`: tangential multipliers as unknowns and a prescribed
    /// component of the node's own dofs (the held directions are those of
    /// the node's normal and its prescribed components, as the condensed
    /// path's node law has them), on node-to-surface and on dual mortar
    /// alike; on dual mortar not at a node whose dofs are all prescribed
    /// ([`holds_every_component`](Self::holds_every_component)).
    pub(super) fn holds_tangent(&self, i: usize) -> bool {
        let Some(axes) = self.prescribed_axes.get(i) else {
            return false;
        };
        self.tangential_multipliers()
            && axes.iter().any(|&p| p)
            && !(matches!(self.primary, Primary::Mortar(_)) && axes.iter().all(|&p| p))
    }

    /// Whether some secondary node of a dual mortar pair has all three
    /// components prescribed. Its stick rows are then constraints on the
    /// primary nodes its lever reaches through `M_jl` (the tangential
    /// traction is determined: tests/mortar_friction.rs's patch test, whose
    /// fully prescribed edge nodes carry the exact uniform traction), so
    /// Newton keeps them whole; the condensed path has no column for the
    /// node's motion and holds its committed traction there instead
    /// ([`crate::problem::condensed::not_applicable`] leaves such pairs to
    /// Newton under `auto`).
    pub fn holds_every_component(&self) -> bool {
        matches!(self.primary, Primary::Mortar(_))
            && (self.prescribed_axes.iter()).any(|a| a.iter().all(|&p| p))
    }

    /// Node `i`'s held tangential directions at unit normal `n` under
    /// exact stick's rule ([`friction::HeldTangent`]).
    pub fn held_tangent(&self, i: usize, n: &Vector3<f64>) -> friction::HeldTangent {
        let axes = self.prescribed_axes.get(i).copied().unwrap_or_default();
        friction::HeldTangent::of(n, axes)
    }

    /// Whether friction makes the tangent nonsymmetric.
    pub fn has_friction(&self) -> bool {
        self.friction.is_some_and(|c| c.coefficient > 0.0)
    }
}
