//! The state a ring element keeps between steps (stress and plastic strain at its
//! integration points, hourglass force, energies) and what one update returns.

use crate::fe::tensor::Sym;

/// Stress and plastic strain of one integration point.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PointState {
    /// Cauchy stress [rr, zz, θθ, rz, 0, 0], Pa.
    pub stress: Sym,
    /// Equivalent plastic strain.
    pub eps_p: f64,
}

/// The history of one element.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct QuadState {
    /// Integration points (only the first is used by the one-point form).
    pub points: [PointState; 4],
    /// Hourglass generalised force (r, z), N.
    pub hourglass: [f64; 2],
    /// Stress power integrated in time ∫ V σ:D dt, J.
    pub internal_energy: f64,
    /// Plastic work, J.
    pub plastic_work: f64,
    /// Hourglass energy, J.
    pub hourglass_energy: f64,
}

/// What one element update returns.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct QuadOutput {
    /// Internal nodal forces (r, z) of the whole ring at t^{n+1}, N.
    pub force: [[f64; 2]; 4],
    /// Ring volume at t^{n+1}, m³.
    pub volume: f64,
    /// Smallest Gauss-point Jacobian, m² (≤ 0: inverted).
    pub min_jacobian: f64,
    /// Courant step L_e / c, s.
    pub dt_crit: f64,
}
