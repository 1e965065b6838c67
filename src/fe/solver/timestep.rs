//! The explicit stable time step: Courant condition Δt ≤ L_e / c per element, with the
//! characteristic length L_e = V / (largest face area) (the LS-DYNA choice for solids) and the
//! dilatational wave speed c = sqrt((λ + 2G)/ρ). Re-evaluated every step as elements deform.

use crate::mesh::topology::HEX_FACES;

/// Area of the (possibly warped) quadrilateral p0-p1-p2-p3: half the norm of the cross product
/// of its diagonals (exact for a planar quad), m².
#[inline]
pub fn quad_area(p0: [f64; 3], p1: [f64; 3], p2: [f64; 3], p3: [f64; 3]) -> f64 {
    let d1 = [p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]];
    let d2 = [p3[0] - p1[0], p3[1] - p1[1], p3[2] - p1[2]];
    let c = crate::fe::tensor::cross(d1, d2);
    0.5 * (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt()
}

/// Characteristic length V / max face area (m) of a hexahedron with coordinates `x` (m) and
/// volume `volume` (m³). For a cube of side h it is h.
#[inline]
pub fn characteristic_length(x: &[[f64; 3]; 8], volume: f64) -> f64 {
    let mut amax: f64 = 0.0;
    for f in HEX_FACES {
        amax = amax.max(quad_area(x[f[0]], x[f[1]], x[f[2]], x[f[3]]));
    }
    volume / amax
}

/// The step limit of the whole model at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StableStep {
    /// Stable step after the safety factor, s.
    pub dt: f64,
    /// The element (global index) whose Courant limit controls, if an element controls.
    pub element: Option<usize>,
    /// Name of the interaction that controls instead, if one does.
    pub interaction: Option<usize>,
}
