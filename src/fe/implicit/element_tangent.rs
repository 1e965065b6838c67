//! One ring element over one load increment: its internal forces after the nodal
//! displacement increment Δu from its committed state, and their derivative with respect to
//! Δu (the tangent Newton-Raphson needs), both from the element's own update.
//!
//! The increment is the explicit update over a pseudo-time of 1 s with v = Δu/(1 s): the
//! same objective (Hughes-Winget) midpoint kinematics, hoop term, B-bar or hourglass
//! control and return mapping as a dynamic step, so the static solver carries no second copy
//! of the kinematics or of any hardening law. The tangent is the central difference of those
//! forces, hence consistent with the discrete update to O(h²) for every element and law.

use crate::fe::elements::ring::element::Quad;
use crate::fe::elements::ring::shape::characteristic_length;
use crate::fe::elements::ring::{update, QuadFormulation, QuadOutput, QuadState};
use crate::fe::materials::J2Material;

/// The pseudo-time of one increment, s (rates in the update are Δu per increment).
pub const INCREMENT_TIME: f64 = 1.0;

/// Relative size of the central-difference step on a nodal displacement (of the element's
/// characteristic length): strains of 1e-7, small enough that few integration points
/// straddle the yield surface (a straddling difference averages the elastic and plastic
/// slopes), large against the round-off of forces that are sums of stresses of 1e8 Pa.
const STEP: f64 = 1e-7;

/// The forces (N, whole ring, (r, z) per node) of a quad whose nodes `x0` (m) at the start of
/// the increment move by `du` (m), from its committed state `st0`; returns the update's
/// output and the state it leaves (committed only when the increment converges).
pub fn increment_forces(
    form: QuadFormulation,
    mat: &J2Material,
    x0: &Quad,
    du: &Quad,
    st0: &QuadState,
) -> (QuadOutput, QuadState) {
    let x1: Quad = std::array::from_fn(|k| [x0[k][0] + du[k][0], x0[k][1] + du[k][1]]);
    let v: Quad = du.map(|d| [d[0] / INCREMENT_TIME, d[1] / INCREMENT_TIME]);
    let mut st = *st0;
    let out = update(&x1, &v, INCREMENT_TIME, mat, form, &mut st);
    (out, st)
}

/// The tangent ∂f/∂Δu of [`increment_forces`] (N/m, 8 × 8, row and column 2k + c for node k
/// and component c = r, z), by central differences of step 1e-7 of the element size, and
/// whether any of its evaluations flowed plastically (the tangent then depends on the
/// increment through the return mapping, not only through the geometry).
pub fn increment_tangent(
    form: QuadFormulation,
    mat: &J2Material,
    x0: &Quad,
    du: &Quad,
    st0: &QuadState,
) -> ([[f64; 8]; 8], bool) {
    let h = STEP * characteristic_length(x0);
    let mut k = [[0.0; 8]; 8];
    let mut flowed = false;
    for j in 0..8 {
        let (node, c) = (j / 2, j % 2);
        let mut plus = *du;
        plus[node][c] += h;
        let mut minus = *du;
        minus[node][c] -= h;
        let (fp, sp) = increment_forces(form, mat, x0, &plus, st0);
        let (fm, sm) = increment_forces(form, mat, x0, &minus, st0);
        flowed |= sp.plastic_work != st0.plastic_work || sm.plastic_work != st0.plastic_work;
        for i in 0..8 {
            k[i][j] = (fp.force[i / 2][i % 2] - fm.force[i / 2][i % 2]) / (2.0 * h);
        }
    }
    (k, flowed)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::Material;

    fn quad() -> Quad {
        [[0.01, 0.0], [0.02, 0.001], [0.021, 0.011], [0.009, 0.01]]
    }

    /// An elastic element's tangent at Δu = 0 is its stiffness: symmetric, and K Δu gives
    /// the forces of a small Δu.
    #[test]
    fn small_increment_forces_are_the_tangent_times_the_increment() {
        let m = Material::preset("copper").unwrap();
        let mat = J2Material::new(&m, true);
        for form in QuadFormulation::ALL {
            let st = QuadState::default();
            let zero = [[0.0; 2]; 4];
            let k = increment_tangent(form, &mat, &quad(), &zero, &st).0;
            let du: Quad = [[1e-9, -2e-9], [3e-9, 0.5e-9], [-1e-9, 2e-9], [0.0, 1e-9]];
            let f = increment_forces(form, &mat, &quad(), &du, &st).0.force;
            let scale = k.iter().flatten().fold(0.0f64, |a, b| a.max(b.abs()));
            for i in 0..8 {
                let kdu: f64 = (0..8).map(|j| k[i][j] * du[j / 2][j % 2]).sum();
                assert!(
                    (f[i / 2][i % 2] - kdu).abs() < 1e-6 * scale * 3e-9,
                    "{form:?} row {i}: {} vs {kdu}",
                    f[i / 2][i % 2]
                );
                for j in 0..8 {
                    assert!(
                        (k[i][j] - k[j][i]).abs() < 1e-6 * scale,
                        "{form:?} K[{i}][{j}]"
                    );
                }
            }
        }
    }
}
