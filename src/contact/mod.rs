//! Contact with obstacles and between bodies: gap kinematics and normal-contact laws.
pub mod laws;
