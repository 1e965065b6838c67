//! Lumped (row-sum) nodal masses: M_I = Σ_J ∫ ρ N_I N_J dV = ∫ ρ N_I dV, integrated with
//! 2x2x2 Gauss points (exact for the trilinear hex). Row-summing conserves total mass and
//! linear momentum and makes M⁻¹ trivial, which is what makes central differences explicit.

use crate::error::{Error, Result};
use crate::fe::elements::shape::{
    gauss_points_2x2x2, natural_derivatives, shape_functions, spatial_gradients,
};

/// Row-sum lumped masses (kg) of one element with coordinates `x` (m) and density `rho`
/// (kg/m³). Fails with [`Error::Numerical`] if the element is inverted at a Gauss point.
pub fn element_lumped_mass(x: &[[f64; 3]; 8], rho: f64) -> Result<[f64; 8]> {
    let mut m = [0.0; 8];
    for p in gauss_points_2x2x2() {
        let (_, det) = spatial_gradients(x, &natural_derivatives(p));
        if det.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
            return Err(Error::Numerical(format!(
                "element has a non-positive Jacobian ({det:e}) at a Gauss point: inverted or degenerate mesh"
            )));
        }
        let n = shape_functions(p);
        for (mi, ni) in m.iter_mut().zip(n) {
            *mi += rho * ni * det;
        }
    }
    Ok(m)
}
