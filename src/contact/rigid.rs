//! The gap producer of a rigid obstacle translated by `c(t)`: `q = x_s`
//! (`Q = 3`), `g` the obstacle's signed gap at `x_s − c(t)`, `∇g = n`,
//! `∇²g = H` (its curvature), and friction measured relative to the
//! obstacle, `d = (x_s − c(t)) − (x_s − c)ₙ` with the lever `B = I`.
//!
//! The point is moved back by the translation and projected on the stored
//! obstacle (no copy of a triangulated surface and its tree); gap, normal
//! and curvature are unchanged by it.

use super::friction::{Coulomb, FrictionHistory, SlipKinematics, TangentialResponse};
use super::kinematics::{GapKinematics, GapProducer, PrimaryWeights, SecondaryNode, SlipFrame};
use super::laws::NodeContactState;
use super::obstacle::RigidObstacle;
use nalgebra::{Matrix3, Vector3, U3};

/// A rigid obstacle at translation `c(t)`.
pub struct RigidGap<'a> {
    pub obstacle: &'a RigidObstacle,
    pub translation: Vector3<f64>,
}

impl GapProducer<U3> for RigidGap<'_> {
    type Point = ();

    fn kinematics(
        &self,
        node: &SecondaryNode,
        state: &NodeContactState,
    ) -> Option<GapKinematics<U3>> {
        // a triangulated obstacle's facet choice: the triangle the node's
        // walk keeps ([`crate::contact::facet_walk`]) while it is over it
        let kept = state.facet_walk.kept(state.facet);
        let (facet, p) = (self.obstacle).project_keeping(&self.relative_position(node), kept);
        Some(GapKinematics {
            nodes: smallvec::smallvec![node.mesh_node],
            gap: p.gap,
            gradient: p.normal,
            lever: None,
            hessian: p.curvature,
            area: None,
            area_gradient: None,
            normal: p.normal,
            normal_gradient: p.curvature,
            facet,
            primary: PrimaryWeights::new(),
            point: (),
        })
    }

    fn open_gap(&self) -> f64 {
        f64::INFINITY
    }

    fn relative_position(&self, node: &SecondaryNode) -> Vector3<f64> {
        node.position() - self.translation
    }

    fn slip(
        &self,
        node: &SecondaryNode,
        kinematics: &mut GapKinematics<U3>,
        history: &FrictionHistory,
    ) -> SlipFrame<U3> {
        SlipFrame {
            kinematics: SlipKinematics::rigid(
                history,
                &self.relative_position(node),
                &kinematics.normal,
                &kinematics.hessian,
            ),
            lever: Matrix3::identity(),
        }
    }

    /// `−A_s β J*`, the trial derivative scaled by the slip ratio `β`
    /// (`A_s β ε_T T` on a plane).
    fn stick_stiffness(
        &self,
        _: &GapKinematics<U3>,
        _: &SlipFrame<U3>,
        response: &TangentialResponse<U3>,
        _: &Coulomb,
        area: f64,
    ) -> Matrix3<f64> {
        -area * response.stick_scale * response.trial_gradient
    }
}
