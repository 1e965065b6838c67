//! The trilinear 8-node hexahedron: shape functions N_I(ξ, η, ζ) on [-1, 1]³, their
//! derivatives, the Jacobian ∂x/∂ξ and the spatial gradients ∂N_I/∂x.
//!
//! Local node order is gmsh/VTK (see [`crate::mesh`]); node I sits at the natural
//! coordinates [`NODE_XI`]`[I]`.

use crate::fe::tensor::{inverse, Mat3};

/// Natural coordinates (ξ, η, ζ) of the eight nodes.
pub const NODE_XI: [[f64; 3]; 8] = crate::mesh::HEX_NODE_XI;

/// The nodes at mid-step t^{n+1/2}, x^{n+1} − (Δt/2) v^{n+1/2} (m), from the positions `x1`
/// (m) and velocities `v` (m/s) of a step of `dt` (s).
#[inline(always)]
pub fn mid_step(x1: &[[f64; 3]; 8], v: &[[f64; 3]; 8], dt: f64) -> [[f64; 3]; 8] {
    let half = 0.5 * dt;
    std::array::from_fn(|i| {
        [
            x1[i][0] - half * v[i][0],
            x1[i][1] - half * v[i][1],
            x1[i][2] - half * v[i][2],
        ]
    })
}

/// Gauss abscissa of the 2-point rule, 1/√3 (weights 1).
pub const GAUSS2: f64 = 0.577_350_269_189_625_8;

/// The 2x2x2 Gauss points (weights all 1), ordered like the nodes.
pub fn gauss_points_2x2x2() -> [[f64; 3]; 8] {
    NODE_XI.map(|p| p.map(|c| c * GAUSS2))
}

/// Shape function values N_I(ξ) = (1 + ξ ξ_I)(1 + η η_I)(1 + ζ ζ_I)/8; they sum to 1.
pub fn shape_functions(xi: [f64; 3]) -> [f64; 8] {
    NODE_XI.map(|n| 0.125 * (1.0 + xi[0] * n[0]) * (1.0 + xi[1] * n[1]) * (1.0 + xi[2] * n[2]))
}

/// Natural derivatives ∂N_I/∂ξ_j at `xi`, shape [node][ξ, η, ζ].
pub fn natural_derivatives(xi: [f64; 3]) -> [[f64; 3]; 8] {
    NODE_XI.map(|n| {
        let a = 1.0 + xi[0] * n[0];
        let b = 1.0 + xi[1] * n[1];
        let c = 1.0 + xi[2] * n[2];
        [
            0.125 * n[0] * b * c,
            0.125 * a * n[1] * c,
            0.125 * a * b * n[2],
        ]
    })
}

/// Jacobian J_ij = ∂x_i/∂ξ_j = Σ_I x_Ii ∂N_I/∂ξ_j for nodal coordinates `x` (m).
#[inline]
pub fn jacobian(x: &[[f64; 3]; 8], dn: &[[f64; 3]; 8]) -> Mat3 {
    let mut j = [[0.0; 3]; 3];
    for (xi, di) in x.iter().zip(dn) {
        for r in 0..3 {
            for c in 0..3 {
                j[r][c] += xi[r] * di[c];
            }
        }
    }
    j
}

/// Spatial gradients ∂N_I/∂x (1/m, shape [node][x, y, z]) and det J (m³ per unit natural
/// volume) from natural derivatives `dn` and nodal coordinates `x`.
///
/// A non-positive determinant means the element is inverted at this point; the gradients
/// are then meaningless and the caller must stop.
#[inline]
pub fn spatial_gradients(x: &[[f64; 3]; 8], dn: &[[f64; 3]; 8]) -> ([[f64; 3]; 8], f64) {
    let j = jacobian(x, dn);
    let (ji, det) = inverse(&j);
    // ∂N/∂x_k = Σ_j ∂N/∂ξ_j (J⁻¹)_jk.
    let g = dn.map(|d| {
        [
            d[0] * ji[0][0] + d[1] * ji[1][0] + d[2] * ji[2][0],
            d[0] * ji[0][1] + d[1] * ji[1][1] + d[2] * ji[2][1],
            d[0] * ji[0][2] + d[1] * ji[1][2] + d[2] * ji[2][2],
        ]
    });
    (g, det)
}

/// The volume (m³) and the volume integral ∫ ∂N_I/∂x dV (m², shape [node][x, y, z]) of the
/// hexahedron `x` by 2x2x2 Gauss quadrature (exact for a trilinear hexahedron).
#[cfg(test)]
pub(crate) fn gauss_volume_gradient(x: &[[f64; 3]; 8]) -> (f64, [[f64; 3]; 8]) {
    let mut volume = 0.0;
    let mut integral = [[0.0; 3]; 8];
    for p in gauss_points_2x2x2() {
        let (g, j) = spatial_gradients(x, &natural_derivatives(p));
        volume += j;
        for i in 0..8 {
            for k in 0..3 {
                integral[i][k] += g[i][k] * j;
            }
        }
    }
    (volume, integral)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shape_functions_interpolate_nodes_and_sum_to_one() {
        for (i, p) in NODE_XI.iter().enumerate() {
            let n = shape_functions(*p);
            for (j, v) in n.iter().enumerate() {
                assert_eq!(*v, if i == j { 1.0 } else { 0.0 });
            }
        }
        let n = shape_functions([0.3, -0.2, 0.7]);
        assert!((n.iter().sum::<f64>() - 1.0).abs() < 1e-15);
    }

    #[test]
    fn derivatives_match_finite_differences() {
        let p = [0.3, -0.2, 0.7];
        let d = natural_derivatives(p);
        let h = 1e-6;
        for k in 0..3 {
            let mut a = p;
            let mut b = p;
            a[k] += h;
            b[k] -= h;
            let (na, nb) = (shape_functions(a), shape_functions(b));
            for i in 0..8 {
                assert!(((na[i] - nb[i]) / (2.0 * h) - d[i][k]).abs() < 1e-9);
            }
        }
    }
}
