//! What the ring elements' scalar updates share: the mid-step configuration, the update of
//! one integration point (objective rotation, return mapping, energy account) or of the four
//! Gauss points, and the output of an update.

use super::shape::{characteristic_length, velocity_gradient, Point};
use super::state::{QuadOutput, QuadState};
use crate::fe::{
    elements::objective::{hughes_winget, rotate_symmetric},
    materials::J2Material,
    tensor::{ddot, spin_vector, sym_part, Mat3},
};

/// The mid-step nodes x^{n+1/2} = x^{n+1} − Δt/2 v^{n+1/2} (m), from `x1` (m), `v` (m/s) and
/// `dt` (s).
#[inline]
pub(super) fn mid_step(x1: &[[f64; 2]; 4], v: &[[f64; 2]; 4], dt: f64) -> [[f64; 2]; 4] {
    let half = 0.5 * dt;
    std::array::from_fn(|i| [x1[i][0] - half * v[i][0], x1[i][1] - half * v[i][1]])
}

/// Rotates, updates and accounts point `k` of `st`: velocity gradient `l` (1/s), the
/// element's mean volumetric rate `vol_bar` (1/s) replacing the point's own when given, step
/// `dt` (s), ring volume `volume` (m³); the internal and plastic energy increments (J) are
/// added to the element's.
#[inline]
pub(super) fn advance_point(
    st: &mut QuadState,
    k: usize,
    l: &Mat3,
    vol_bar: Option<f64>,
    dt: f64,
    volume: f64,
    mat: &J2Material,
) {
    let p = &mut st.points[k];
    let mut d = sym_part(l);
    if let Some(vb) = vol_bar {
        let shift = (vb - (d[0] + d[1] + d[2])) / 3.0;
        for c in d.iter_mut().take(3) {
            *c += shift;
        }
    }
    let d = d.map(|e| e * dt);
    let w = spin_vector(l).map(|e| e * dt);
    p.stress = rotate_symmetric(&hughes_winget(w), &p.stress);
    let before = p.stress;
    let dwp = mat.update(&mut p.stress, &mut p.eps_p, &d, dt);
    st.internal_energy += 0.5 * volume * (ddot(&before, &d) + ddot(&p.stress, &d));
    st.plastic_work += dwp * volume;
}

/// Advances the four Gauss points `pm` (on the mid-step configuration) of `st` with the
/// nodal velocities `v` (m/s) over `dt` (s): each on its own strain rate, its volumetric
/// part replaced by `vol_bar` (1/s) when given.
#[inline]
pub(super) fn advance_gauss_points(
    st: &mut QuadState,
    pm: &[Point; 4],
    v: &[[f64; 2]; 4],
    vol_bar: Option<f64>,
    dt: f64,
    mat: &J2Material,
) {
    for (k, p) in pm.iter().enumerate() {
        let l = velocity_gradient(v, &p.grad);
        advance_point(st, k, &l, vol_bar, dt, p.grad.volume, mat);
    }
}

/// The output of an update: nodal forces `force` (N) on the quad `x1` (m) of ring volume
/// `volume` (m³) and smallest Jacobian `min_jacobian` (m²), with its Courant step.
#[inline]
pub(super) fn output(
    x1: &[[f64; 2]; 4],
    force: [[f64; 2]; 4],
    volume: f64,
    min_jacobian: f64,
    mat: &J2Material,
) -> QuadOutput {
    QuadOutput {
        force,
        volume,
        min_jacobian,
        dt_crit: characteristic_length(x1) / mat.wave_speed,
    }
}
