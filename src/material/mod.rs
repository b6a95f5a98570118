//! Constitutive laws: strain energy `W(F)` per unit reference volume, the
//! second Piola–Kirchhoff stress `S = ∂W/∂E` and the material tangent
//! `𝔻 = ∂S/∂E`, written as pure functions of the deformation gradient that
//! unit tests call directly.

use nalgebra::{Matrix3, Matrix6};

/// 3×3 tensor.
pub type Mat3 = Matrix3<f64>;
/// 6×6 matrix in Voigt notation, order (11, 22, 33, 12, 23, 13).
pub type Mat6 = Matrix6<f64>;

/// How a material wants the element to measure strain.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kinematics {
    /// Infinitesimal strain `ε = sym(F) − I`; the element uses the linear
    /// strain–displacement operator and no geometric stiffness.
    SmallStrain,
    /// Total Lagrangian finite strain.
    FiniteStrain,
}

/// A hyperelastic material.
pub trait Material: Send + Sync + std::fmt::Debug {
    /// Short name for messages, e.g. `"neo_hookean"`.
    fn name(&self) -> &'static str;

    /// Which strain measure the element must use.
    fn kinematics(&self) -> Kinematics {
        Kinematics::FiniteStrain
    }

    /// Strain energy per unit reference volume, `W(F)`.
    fn strain_energy(&self, f: &Mat3) -> f64;

    /// Second Piola–Kirchhoff stress `S = ∂W/∂E` and the material tangent
    /// `𝔻 = ∂S/∂E` (Voigt, order (11, 22, 33, 12, 23, 13), engineering shear
    /// strain, so `𝔻` is symmetric).
    ///
    /// For [`Kinematics::SmallStrain`] materials the "S" is the Cauchy stress
    /// `σ = ℂ : ε` with `ε = sym(F) − I`, and `𝔻 = ℂ`.
    fn stress_and_tangent(&self, f: &Mat3) -> (Mat3, Mat6);

    /// Second Piola–Kirchhoff stress alone.
    fn second_piola_kirchhoff(&self, f: &Mat3) -> Mat3 {
        self.stress_and_tangent(f).0
    }

    /// A representative Young's modulus (initial stiffness), used for
    /// automatic penalty and scaling parameters.
    fn reference_youngs_modulus(&self) -> f64;
}
