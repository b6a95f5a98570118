//! Why an increment did not converge. An [`IncrementFailure`] is mended,
//! if at all, by a smaller increment: the stepper cuts the increment on
//! it and stops after `max_cuts` consecutive cuts. Two end the run at once
//! instead ([`IncrementFailure::mended_by_a_cut`]): a cancelled run and a
//! linear solver that cannot be set up as asked, which the increment
//! finds first but no increment mends. Other errors that no cut can mend
//! (a failed output write, a bad ordering) are `Err` instead. `Display`
//! gives the message of the log and of the final error.

use super::chattering::Chatter;
use crate::assembly::kernel::KernelFailure;

/// What the closed contact nodes measured when a rigid-body mode went
/// through them (see [`IncrementFailure::RigidBodyMode`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum ClosedContact {
    /// No contact, or no closed node.
    #[default]
    None,
    /// Frictionless: the closed nodes hold no load along the contact
    /// surface, so a tangential direction is unsupported.
    Frictionless,
    /// With friction, every closed node slips at the Coulomb limit
    /// `|t_T| = μ t_N`: the tangential load exceeds the capacity `μN`.
    AllSlip,
    /// With friction, some closed nodes stick.
    SomeStick,
}

/// A failed increment, by cause.
#[derive(Clone, Debug, PartialEq)]
pub enum IncrementFailure {
    /// An element could not be evaluated: inverted (`det F ≤ 0`) or
    /// degenerate in the reference configuration. `element` is its mesh id.
    InvertedElement {
        element: u64,
        failure: KernelFailure,
    },
    /// The relative residual is NaN or infinite.
    NotFinite,
    /// The relative residual grew a thousandfold over that after the
    /// predictor.
    Diverging { relative: f64 },
    /// The contact statuses cycle between iterations.
    Chattering(Chatter),
    /// A correction `largest` far beyond the body's `size`: if it is a
    /// `prescribed` displacement's jump, the increment is too large for the
    /// prescribed motion; else with `contact`, a rigid-body mode that the
    /// saddle system's regularisation let through — with every contact
    /// node `open`, the body lost contact (or never reached it) and nothing
    /// else holds it; with closed nodes, [`RigidBodyMode::closed`] says
    /// why they do not hold it; without contact, the tangent is near
    /// singular (an element near inversion, a load beyond the material's
    /// range, a missing support). `direction` is the unit correction of
    /// the node that moves most (the direction of the motion).
    RigidBodyMode {
        largest: f64,
        size: f64,
        contact: bool,
        prescribed: bool,
        open: bool,
        direction: [f64; 3],
        closed: ClosedContact,
    },
    /// The linear solve failed (a singular tangent, a Krylov method that
    /// diverged, a solution that is not finite); the solver's message.
    LinearSolve(String),
    /// The linear solver could not be set up as its options ask (an option
    /// value it rejects, a factorisation package it lacks): the solver's
    /// message, with what to check. No smaller increment mends it: the
    /// stepper ends the run with it (not cut).
    LinearSolverSetUp(String),
    /// No convergence in `iterations` Newton iterations.
    MaxIterations { iterations: usize, relative: f64 },
    /// A contact node slid beyond the primary triangles it was paired with
    /// at the start of the increment.
    PairsMoved,
    /// Contact node `node` (its mesh id) of interface `interface` passed
    /// through the rigid obstacle within the increment: its path relative
    /// to the obstacle reached the signed distance `gap`, deeper than the
    /// contact element size `size` ([`crate::contact::sweep`]).
    PassedThrough {
        node: u64,
        interface: String,
        gap: f64,
        size: f64,
    },
    /// The outer (Uzawa) loop did not reach its tolerance in `updates`.
    OuterLoopLimit { updates: usize },
    /// The condensed contact solve failed (its message).
    Condensed(String),
    /// The load exceeds the friction capacity of a body that only its
    /// contact holds along the contact plane (measured from the load by
    /// the condensed path: the tangential load `|F_T| = tangential` along
    /// `direction` against `μN` = `coefficient × normal_force`), so no
    /// equilibrium exists.
    FrictionCapacity {
        tangential: f64,
        normal_force: f64,
        coefficient: f64,
        direction: [f64; 3],
    },
    /// The condensed solution leaves a relative residual above the
    /// tolerance (a floating body's ill-conditioned shift, say).
    CondensedResidual { relative: f64, tolerance: f64 },
    /// The run was cancelled (its cancel flag set) between two Newton
    /// iterations: not cut, the run ends.
    Cancelled,
}

impl std::fmt::Display for IncrementFailure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            IncrementFailure::InvertedElement {
                element: id,
                failure:
                    KernelFailure::Inverted {
                        quadrature_point,
                        det_f,
                    },
            } => write!(
                f,
                "element {id} inverted (det F = {det_f:.3e} at quadrature point {quadrature_point})"
            ),
            IncrementFailure::InvertedElement {
                element: id,
                failure:
                    KernelFailure::ReferenceInverted {
                        quadrature_point,
                        det_j,
                    },
            } => write!(
                f,
                "element {id} degenerate in the reference configuration (det J = {det_j:.3e} at quadrature point {quadrature_point})"
            ),
            IncrementFailure::NotFinite => write!(f, "the residual is not finite"),
            IncrementFailure::Diverging { relative } => {
                write!(f, "diverging (relative residual {relative:.3e})")
            }
            IncrementFailure::Chattering(chatter) => chatter.fmt(f),
            IncrementFailure::RigidBodyMode {
                largest,
                size,
                prescribed: true,
                ..
            } => write!(
                f,
                "a prescribed displacement of {largest:.3e} in one increment, far larger than the \
                 body (size {size:.3e}): take smaller increments (initial_increment, max_increment)"
            ),
            IncrementFailure::RigidBodyMode {
                largest,
                size,
                contact: true,
                open: true,
                ..
            } => write!(
                f,
                "loss of contact: every contact node is open and nothing else holds the body, so it \
                 moves as a rigid body (a correction of {largest:.3e} against a body of size \
                 {size:.3e}); hold the body with a [[displacement]] until the contact closes, or \
                 start it touching the obstacle (check the obstacle's position and that its normal \
                 points toward the body), or load it toward the contact"
            ),
            IncrementFailure::RigidBodyMode {
                largest,
                size,
                contact: true,
                direction,
                closed,
                ..
            } => closed_rigid_body_mode(f, *largest, *size, direction, *closed),
            IncrementFailure::RigidBodyMode {
                largest,
                size,
                contact: false,
                ..
            } => write!(
                f,
                "a correction of {largest:.3e}, far larger than the body (size {size:.3e}): \
                 an element near inversion, a load far beyond the material's range, \
                 or a missing support"
            ),
            IncrementFailure::LinearSolve(message) => f.write_str(message),
            IncrementFailure::LinearSolverSetUp(message) => f.write_str(message),
            IncrementFailure::MaxIterations {
                iterations,
                relative,
            } => write!(
                f,
                "no convergence in {iterations} iterations (relative residual {relative:.3e})"
            ),
            IncrementFailure::PairsMoved => write!(
                f,
                "a contact node slid beyond the primary triangles it was paired with at the \
                 start of the increment"
            ),
            IncrementFailure::PassedThrough {
                node,
                interface,
                gap,
                size,
            } => write!(
                f,
                "contact node {node} of '{interface}' passed through the obstacle within the \
                 increment: its path relative to the obstacle went {:.3e} deep inside, more \
                 than the contact element size {size:.3e}; the obstacle moves farther in one \
                 increment than the surface can follow, so take smaller increments \
                 (initial_increment, max_increment) or a smaller motion",
                -gap
            ),
            IncrementFailure::OuterLoopLimit { updates } => write!(
                f,
                "the Uzawa multipliers did not reach the penetration tolerance in {updates} updates"
            ),
            IncrementFailure::Condensed(message) => {
                write!(f, "the condensed contact solve failed: {message}")
            }
            IncrementFailure::FrictionCapacity {
                tangential,
                normal_force,
                coefficient,
                direction,
            } => write!(
                f,
                "the tangential load exceeds the friction capacity μN: the external load along \
                 the contact plane is {tangential:.4e} along {} against μN = {coefficient} × \
                 {normal_force:.4e} = {:.4e}, and only friction holds the body in that \
                 direction, so no increment size can reach equilibrium; reduce the load along \
                 that direction below μ times the normal force, raise friction_coefficient, or \
                 hold the body with a [[displacement]]",
                along(direction),
                coefficient * normal_force
            ),
            IncrementFailure::CondensedResidual {
                relative,
                tolerance,
            } => write!(
                f,
                "the condensed solution leaves a relative residual of {relative:.1e} \
                 (tolerance {tolerance:.1e})"
            ),
            IncrementFailure::Cancelled => write!(f, "cancelled between two Newton iterations"),
        }
    }
}

impl IncrementFailure {
    /// Whether a smaller increment may mend it: false for a cancelled run
    /// and a linear solver that cannot be set up, which end the run at once.
    pub fn mended_by_a_cut(&self) -> bool {
        !matches!(
            self,
            IncrementFailure::Cancelled | IncrementFailure::LinearSolverSetUp(_)
        )
    }
}

/// What the closed contact nodes say of a rigid-body mode, from the
/// statuses of an evaluation (`status % 4`: 0 open, 1 stick or closed
/// frictionless, 2 slip; [`super::nonlinear::Evaluation::statuses`]).
pub(crate) fn closed_contact(statuses: &[u64], friction: bool) -> ClosedContact {
    let closed = || statuses.iter().map(|s| s % 4).filter(|&s| s != 0);
    match (closed().next(), friction) {
        (None, _) => ClosedContact::None,
        (Some(_), false) => ClosedContact::Frictionless,
        (Some(_), true) if closed().all(|s| s == 2) => ClosedContact::AllSlip,
        (Some(_), true) => ClosedContact::SomeStick,
    }
}

/// The unit direction of the largest nodal correction in `du` (three
/// components per node); zero when `du` is.
pub(crate) fn largest_motion(du: &[f64]) -> [f64; 3] {
    let norm = |c: &[f64]| c.iter().map(|x| x * x).sum::<f64>().sqrt();
    let node = du
        .chunks_exact(3)
        .max_by(|a, b| norm(a).total_cmp(&norm(b)));
    match node {
        Some(c) if norm(c) > 0.0 => {
            let n = norm(c);
            [c[0] / n, c[1] / n, c[2] / n]
        }
        _ => [0.0; 3],
    }
}

/// A unit direction as `(x, y, z)` to two decimals (no "-0.00").
fn along(d: &[f64; 3]) -> String {
    let c = |x: f64| if x.abs() < 5e-3 { 0.0 } else { x };
    format!("({:.2}, {:.2}, {:.2})", c(d[0]), c(d[1]), c(d[2]))
}

/// The message of a rigid-body mode through closed contact nodes, by
/// what they measured ([`ClosedContact`]): an unsupported direction
/// (frictionless), a tangential load beyond the friction capacity `μN`
/// (every closed node slipping), or a missing support.
fn closed_rigid_body_mode(
    f: &mut std::fmt::Formatter<'_>,
    largest: f64,
    size: f64,
    d: &[f64; 3],
    closed: ClosedContact,
) -> std::fmt::Result {
    let motion = format!(
        "the body moves as a whole along {} (a correction of {largest:.3e} against a body of \
         size {size:.3e})",
        along(d)
    );
    match closed {
        ClosedContact::Frictionless => write!(
            f,
            "an unsupported direction: {motion}; the closed contact nodes are frictionless, so \
             they hold no load along the contact surface, and no [[displacement]] holds that \
             direction; hold it with a [[displacement]] (a symmetry plane or a support), or give \
             the contact a friction_coefficient"
        ),
        ClosedContact::AllSlip => write!(
            f,
            "the tangential load exceeds the friction capacity μN: every closed contact node \
             slips at the Coulomb limit |t_T| = μ t_N and {motion}; reduce the load along that \
             direction below μ times the normal force, raise friction_coefficient, or hold the \
             body with a [[displacement]]"
        ),
        ClosedContact::SomeStick | ClosedContact::None => write!(
            f,
            "a rigid-body mode although some contact nodes are closed and sticking: {motion}; \
             a support is missing in that direction (add a [[displacement]] holding it)"
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::{ClosedContact, IncrementFailure};

    /// A correction far beyond the body names the cause the problem can
    /// have: a prescribed jump, a lost contact, through closed nodes an
    /// unsupported direction (frictionless), a load beyond μN (every node
    /// slipping) or a missing support, or (without contact) a
    /// near-singular body.
    #[test]
    fn rigid_body_mode_message_follows_the_cause() {
        let with = |contact, prescribed, open, closed| {
            IncrementFailure::RigidBodyMode {
                largest: 50.0,
                size: 1.0,
                contact,
                prescribed,
                open,
                direction: [1.0, 0.0, 0.0],
                closed,
            }
            .to_string()
        };
        let message =
            |contact, prescribed, open| with(contact, prescribed, open, ClosedContact::None);
        let free = message(false, false, false);
        assert!(free.contains("far larger than the body"), "{free}");
        assert!(free.contains("element near inversion"), "{free}");
        assert!(!free.contains("contact"), "{free}");
        let lost = message(true, false, true);
        assert!(lost.contains("loss of contact"), "{lost}");
        assert!(lost.contains("every contact node is open"), "{lost}");
        let held = with(true, false, false, ClosedContact::SomeStick);
        assert!(held.contains("some contact nodes are closed"), "{held}");
        assert!(held.contains("along (1.00, 0.00, 0.00)"), "{held}");
        assert!(!held.contains("loss of contact"), "{held}");
        let frictionless = with(true, false, false, ClosedContact::Frictionless);
        assert!(
            frictionless.contains("an unsupported direction"),
            "{frictionless}"
        );
        assert!(!frictionless.contains("tangential load"), "{frictionless}");
        let beyond = with(true, false, false, ClosedContact::AllSlip);
        assert!(
            beyond.contains("exceeds the friction capacity μN"),
            "{beyond}"
        );
        assert!(
            beyond.contains("every closed contact node slips"),
            "{beyond}"
        );
        for contact in [false, true] {
            let jump = message(contact, true, contact);
            assert!(
                jump.contains("a prescribed displacement of 5.000e1"),
                "{jump}"
            );
        }
    }
}
