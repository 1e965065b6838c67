//! What the ring elements' scalar updates share: the mid-step configuration and the
//! update of one integration point (objective rotation, return mapping, energy account).

use super::state::PointState;
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

/// Rotates, updates and accounts one point: velocity gradient `l` (1/s), the element's mean
/// volumetric rate `vol_bar` (1/s) replacing the point's own when given, step `dt` (s), ring
/// volume `volume` (m³). Returns the (internal, plastic) energy increments, J.
#[inline]
pub(super) fn advance_point(
    p: &mut PointState,
    l: &Mat3,
    vol_bar: Option<f64>,
    dt: f64,
    volume: f64,
    mat: &J2Material,
) -> (f64, f64) {
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
    (
        0.5 * volume * (ddot(&before, &d) + ddot(&p.stress, &d)),
        dwp * volume,
    )
}
