//! Lumped nodal masses of the meridian section: the row sums of the consistent mass matrix,
//! m_I = ρ ∫ N_I 2π r dA (whole ring), integrated exactly by 2x2 Gauss.
//!
//! Why row sums and not ρ V/4 per node or ρ A/4 · 2π r_I: the nodal-radius form gives the
//! nodes on the axis zero mass (an infinite acceleration), and equal quarters of V misplace
//! the ring's mass radially. The row sum keeps the total mass and the first radial moment of
//! every element exact and gives the axis nodes the mass of the material next to them
//! (Hughes 1987, §7.3; Belytschko, Liu & Moran 2000, §4.5).

use super::shape::{shape, GAUSS_2X2};

/// Lumped masses (kg) of the quad `x` (m) of density `rho` (kg/m³), in node order.
pub fn element_masses(x: &[[f64; 2]; 4], rho: f64) -> [f64; 4] {
    let mut m = [0.0; 4];
    for xi in GAUSS_2X2 {
        let p = super::shape::point(x, xi, 1.0);
        let (n, _) = shape(xi);
        for i in 0..4 {
            m[i] += rho * n[i] * p.grad.volume;
        }
    }
    m
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn masses_sum_to_the_ring_and_axis_nodes_get_mass() {
        // Annular ring section r ∈ [0, 2], z ∈ [0, 1]: a disc of volume π r² h = 4π.
        let x = [[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [0.0, 1.0]];
        let m = element_masses(&x, 3.0);
        assert!((m.iter().sum::<f64>() - 3.0 * 4.0 * PI).abs() < 1e-12);
        // ρ ∫ N_I 2π r dA = ρ 2π ∫ N_I(r) r dr ∫ N_I(z) dz: the axis nodes 2π (2/3)(1/2),
        // the outer ones 2π (4/3)(1/2).
        assert!((m[0] - 3.0 * 2.0 * PI * (2.0 / 3.0) * 0.5).abs() < 1e-12);
        assert!((m[1] - 3.0 * 2.0 * PI * (4.0 / 3.0) * 0.5).abs() < 1e-12);
        // First radial moment exact: Σ m_I r_I = ρ ∫ r 2π r dA = ρ 2π r³/3 h.
        let mr: f64 = (0..4).map(|i| m[i] * x[i][0]).sum();
        assert!((mr - 3.0 * 2.0 * PI * 8.0 / 3.0).abs() < 1e-12);
    }
}
