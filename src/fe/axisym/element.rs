//! The axisymmetric quadrilateral's update from t^n to t^{n+1}, in two formulations like the
//! hexahedron's:
//!
//! - [`QuadFormulation::OnePoint`]: one stress state per element on the volume-averaged
//!   operator B̄ ([`quad::mean_gradient`]) with Flanagan-Belytschko stiffness hourglass
//!   control (Q̇ = k q per direction, k = ε_hg (λ + 2G) V Σ_I |B̄_I|² / 2);
//! - [`QuadFormulation::SelectiveReduced`]: four 2x2 Gauss points for the deviatoric strain
//!   rate and the element's mean dilatation for the volumetric one (B-bar, Hughes 1980), so
//!   the isochoric plastic flow does not lock; no hourglass modes, no hourglass control.
//!
//! The strain rate and spin are evaluated on the mid-step configuration x^{n+1/2}, the stress
//! is rotated by the Hughes-Winget increment of the in-plane spin (the 3D code's objective
//! update: the rotation is about the hoop direction and leaves σ_θθ alone), advanced by
//! [`J2Material::update`] (every hardening law of the material seam), and the nodal forces
//! are V B̄ᵀσ on x^{n+1}. Forces are those of the whole ring (2π r weighting).

use super::quad::{
    add_stress_forces, characteristic_length, gauss_points, hourglass_gamma, mean_gradient,
    mean_of, velocity_gradient, Gradient,
};
use crate::fe::{
    elements::objective::{hughes_winget, rotate_symmetric},
    materials::J2Material,
    tensor::{ddot, spin_vector, sym_part, Sym},
};

/// Default hourglass coefficient ε_hg of the one-point quad (as the hexahedron's).
pub const DEFAULT_HOURGLASS: f64 = 0.05;

/// How the quad is integrated.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum QuadFormulation {
    /// One stress point with stiffness hourglass control of coefficient ε_hg ≥ 0.
    OnePoint {
        /// Hourglass coefficient ε_hg (dimensionless, 0.03-0.1 usual).
        hourglass: f64,
    },
    /// 2x2 Gauss points for the deviator, mean dilatation for the volume (B-bar).
    SelectiveReduced,
}

impl Default for QuadFormulation {
    fn default() -> Self {
        QuadFormulation::OnePoint {
            hourglass: DEFAULT_HOURGLASS,
        }
    }
}

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

/// Updates one element: nodal coordinates `x1` = x^{n+1} (m), velocities `v` = v^{n+1/2}
/// (m/s), step `dt` (s; 0 evaluates the forces of the current state without advancing it).
#[inline]
pub fn update(
    x1: &[[f64; 2]; 4],
    v: &[[f64; 2]; 4],
    dt: f64,
    mat: &J2Material,
    form: QuadFormulation,
    st: &mut QuadState,
) -> QuadOutput {
    let half = 0.5 * dt;
    let xm: [[f64; 2]; 4] =
        std::array::from_fn(|i| [x1[i][0] - half * v[i][0], x1[i][1] - half * v[i][1]]);
    let mut force = [[0.0; 2]; 4];
    let min_j;
    let g1;
    match form {
        QuadFormulation::OnePoint { hourglass } => {
            let (gm, _) = mean_gradient(&xm);
            (g1, min_j) = mean_gradient(x1);
            let l = velocity_gradient(v, &gm);
            let (wi, wp) = advance_point(&mut st.points[0], &l, None, dt, gm.volume, mat);
            st.internal_energy += wi;
            st.plastic_work += wp;
            add_stress_forces(&mut force, &st.points[0].stress, &g1);
            if hourglass > 0.0 {
                let k = hourglass_stiffness(hourglass, mat.p_modulus(), &g1);
                let rot = in_plane_rotation(&l, dt);
                let gam = hourglass_gamma(x1, &g1);
                let e = hourglass_update(&mut st.hourglass, &gam, v, k, rot, dt, &mut force);
                st.hourglass_energy += e;
            }
        }
        QuadFormulation::SelectiveReduced => {
            let pm = gauss_points(&xm);
            let (gm, _) = mean_of(&pm);
            let p1 = gauss_points(x1);
            (g1, min_j) = mean_of(&p1);
            let lbar = velocity_gradient(v, &gm);
            let vol_bar = lbar[0][0] + lbar[1][1] + lbar[2][2];
            for (k, p) in pm.iter().enumerate() {
                let l = velocity_gradient(v, &p.grad);
                let (wi, wp) =
                    advance_point(&mut st.points[k], &l, Some(vol_bar), dt, p.grad.volume, mat);
                st.internal_energy += wi;
                st.plastic_work += wp;
            }
            for (k, p) in p1.iter().enumerate() {
                bbar_forces(&mut force, &st.points[k].stress, &p.grad, &g1);
            }
        }
    }
    QuadOutput {
        force,
        volume: g1.volume,
        min_jacobian: min_j,
        dt_crit: characteristic_length(x1) / mat.wave_speed,
    }
}

/// Rotates, updates and accounts one point: velocity gradient `l` (1/s), the element's mean
/// volumetric rate `vol_bar` (1/s) replacing the point's own when given, step `dt` (s), ring
/// volume `volume` (m³). Returns the (internal, plastic) energy increments, J.
#[inline]
fn advance_point(
    p: &mut PointState,
    l: &crate::fe::tensor::Mat3,
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

/// Adds the B-bar forces of one Gauss point: W_g (B_gᵀσ + p (B̄_vol − B_g,vol)), with p the
/// point's mean stress and B_vol the divergence operator (∂N/∂r + N/r, ∂N/∂z).
#[inline]
fn bbar_forces(f: &mut [[f64; 2]; 4], s: &Sym, g: &Gradient, mean: &Gradient) {
    add_stress_forces(f, s, g);
    let p = (s[0] + s[1] + s[2]) / 3.0;
    for i in 0..4 {
        let dr = (mean.b[i][0] + mean.hoop[i]) - (g.b[i][0] + g.hoop[i]);
        let dz = mean.b[i][1] - g.b[i][1];
        f[i][0] += g.volume * p * dr;
        f[i][1] += g.volume * p * dz;
    }
}

/// Hourglass stiffness k = ε_hg (λ + 2G) V Σ_I |B̄_I|² / 2, N/m.
#[inline]
pub fn hourglass_stiffness(coeff: f64, p_modulus: f64, g: &Gradient) -> f64 {
    let bb: f64 = g.b.iter().map(|b| b[0] * b[0] + b[1] * b[1]).sum();
    coeff * p_modulus * g.volume * bb / 2.0
}

/// The in-plane Hughes-Winget rotation (cos, sin) of the spin of `l` over `dt`.
#[inline]
fn in_plane_rotation(l: &crate::fe::tensor::Mat3, dt: f64) -> [f64; 2] {
    let r = hughes_winget(spin_vector(l).map(|e| e * dt));
    [r[0][0], r[1][0]]
}

/// Advances the hourglass force `q` (N; rotated by `rot` = (cos, sin), then Q̇ = k Σ γ_I v_I),
/// adds Q γ_I to `force` and returns the hourglass work of the step, J.
#[inline]
fn hourglass_update(
    q: &mut [f64; 2],
    gam: &[f64; 4],
    v: &[[f64; 2]; 4],
    k: f64,
    rot: [f64; 2],
    dt: f64,
    force: &mut [[f64; 2]; 4],
) -> f64 {
    let [c, s] = rot;
    *q = [c * q[0] - s * q[1], s * q[0] + c * q[1]];
    let mut rate = [0.0; 2];
    for (g, vi) in gam.iter().zip(v) {
        rate[0] += g * vi[0];
        rate[1] += g * vi[1];
    }
    let mut e = 0.0;
    for a in 0..2 {
        let old = q[a];
        q[a] += k * dt * rate[a];
        e += 0.5 * (old + q[a]) * rate[a] * dt;
    }
    for (f, g) in force.iter_mut().zip(gam) {
        f[0] += g * q[0];
        f[1] += g * q[1];
    }
    e
}
