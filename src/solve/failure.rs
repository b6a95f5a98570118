//! Why an increment did not converge. Every [`IncrementFailure`] is mended,
//! if at all, by a smaller increment: the stepper cuts the increment on
//! any of them and stops after `max_cuts` consecutive cuts. Errors that no
//! cut can mend (a failed output write, a bad ordering) are `Err` instead.
//! `Display` gives the message of the log and of the final error.

use super::chattering::Chatter;
use crate::assembly::kernel::KernelFailure;

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
    /// else holds it; without contact, the tangent is near singular (an
    /// element near inversion, a load beyond the material's range, a
    /// missing support).
    RigidBodyMode {
        largest: f64,
        size: f64,
        contact: bool,
        prescribed: bool,
        open: bool,
    },
    /// The linear solve failed (a singular tangent); the solver's message.
    LinearSolve(String),
    /// No convergence in `iterations` Newton iterations.
    MaxIterations { iterations: usize, relative: f64 },
    /// A contact node slid beyond the primary triangles it was paired with
    /// at the start of the increment.
    PairsMoved,
    /// The outer (Uzawa) loop did not reach its tolerance in `updates`.
    OuterLoopLimit { updates: usize },
    /// The condensed contact solve failed (its message).
    Condensed(String),
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
                ..
            } => write!(
                f,
                "a correction of {largest:.3e} against a body of size {size:.3e}: a rigid-body mode \
                 although some contact nodes are closed (every contact node slips so that friction \
                 cannot hold a load beyond its capacity, or a support is missing); add a support or \
                 reduce the tangential load"
            ),
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
            IncrementFailure::OuterLoopLimit { updates } => write!(
                f,
                "the Uzawa multipliers did not reach the penetration tolerance in {updates} updates"
            ),
            IncrementFailure::Condensed(message) => {
                write!(f, "the condensed contact solve failed: {message}")
            }
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

#[cfg(test)]
mod tests {
    use super::IncrementFailure;

    /// A correction far beyond the body names the cause the problem can
    /// have: a prescribed jump, a lost contact, or (without contact) a
    /// near-singular body.
    #[test]
    fn rigid_body_mode_message_follows_the_cause() {
        let message = |contact, prescribed, open| {
            IncrementFailure::RigidBodyMode {
                largest: 50.0,
                size: 1.0,
                contact,
                prescribed,
                open,
            }
            .to_string()
        };
        let free = message(false, false, false);
        assert!(free.contains("far larger than the body"), "{free}");
        assert!(free.contains("element near inversion"), "{free}");
        assert!(!free.contains("contact"), "{free}");
        let lost = message(true, false, true);
        assert!(lost.contains("loss of contact"), "{lost}");
        assert!(lost.contains("every contact node is open"), "{lost}");
        let held = message(true, false, false);
        assert!(held.contains("some contact nodes are closed"), "{held}");
        assert!(!held.contains("loss of contact"), "{held}");
        for contact in [false, true] {
            let jump = message(contact, true, contact);
            assert!(
                jump.contains("a prescribed displacement of 5.000e1"),
                "{jump}"
            );
        }
    }
}
