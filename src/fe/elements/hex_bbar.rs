//! The fully integrated 2x2x2 hexahedron with B-bar (Hughes 1980, mean-dilatation) volumetric
//! strain: at every Gauss point the volumetric part of the velocity gradient is replaced by its
//! element volume average, so an element in isochoric (plastic, nearly incompressible) flow
//! has one volumetric constraint instead of eight and does not lock. This is the ANSYS
//! SOLID185 default the paper used. There is no plain 2x2x2 option on purpose.

use crate::fe::{
    elements::batch::ElementStateMut,
    elements::hex_one_point::ElementOutput,
    elements::objective::{hughes_winget, rotate_symmetric},
    elements::shape::{gauss_points_2x2x2, natural_derivatives, spatial_gradients},
    materials::J2Material,
    solver::timestep::characteristic_length,
    tensor::{ddot, deviator, spin_vector, sym_part, sym_vec, trace},
};
use std::sync::OnceLock;

/// Natural derivatives at the eight Gauss points, computed once.
pub fn gauss_derivatives() -> &'static [[[f64; 3]; 8]; 8] {
    static D: OnceLock<[[[f64; 3]; 8]; 8]> = OnceLock::new();
    D.get_or_init(|| gauss_points_2x2x2().map(natural_derivatives))
}

/// Spatial gradients and Jacobian determinants (Gauss weights are 1) at the 8 Gauss points.
#[inline]
pub fn gauss_gradients(x: &[[f64; 3]; 8]) -> ([[[f64; 3]; 8]; 8], [f64; 8]) {
    let dn = gauss_derivatives();
    let mut g = [[[0.0; 3]; 8]; 8];
    let mut j = [0.0; 8];
    for p in 0..8 {
        (g[p], j[p]) = spatial_gradients(x, &dn[p]);
    }
    (g, j)
}

/// Updates one B-bar element from t^n to t^{n+1} (arguments as
/// [`crate::fe::elements::hex_one_point::update`]; `st.points` has 8 entries, one per Gauss point).
///
/// At each Gauss point g: L̄_g = L_g + (div_mean − tr L_g)/3 I with
/// div_mean = Σ_g J_g tr L_g / Σ_g J_g, all on the mid-step configuration; the stress is rotated
/// by the point's Hughes-Winget increment and updated with D̄_g Δt. Forces on x^{n+1}:
/// f_I = Σ_g J_g s_g ∇N_I(g) + (Σ_g J_g p_g) B̄_I, with B̄_I the element mean gradient.
#[inline]
pub fn update(
    x1: &[[f64; 3]; 8],
    v: &[[f64; 3]; 8],
    dt: f64,
    mat: &J2Material,
    st: ElementStateMut<'_>,
) -> ElementOutput {
    let ElementStateMut {
        points,
        plastic_work,
        internal_energy,
        ..
    } = st;
    let xm = super::shape::mid_step(x1, v, dt);
    let (gm, jm) = gauss_gradients(&xm);
    let mut ls = [[[0.0; 3]; 3]; 8];
    let mut div_sum = 0.0;
    let mut vol_m = 0.0;
    for p in 0..8 {
        let l = &mut ls[p];
        for (vi, gi) in v.iter().zip(&gm[p]) {
            for r in 0..3 {
                for c in 0..3 {
                    l[r][c] += vi[r] * gi[c];
                }
            }
        }
        div_sum += jm[p] * (l[0][0] + l[1][1] + l[2][2]);
        vol_m += jm[p];
    }
    let div_mean = div_sum / vol_m;
    for (p, ip) in points.iter_mut().enumerate() {
        let l = &ls[p];
        let mut d = sym_part(l);
        let shift = (div_mean - (l[0][0] + l[1][1] + l[2][2])) / 3.0;
        d[0] += shift;
        d[1] += shift;
        d[2] += shift;
        let d = d.map(|e| e * dt);
        let rot = hughes_winget(spin_vector(l).map(|e| e * dt));
        ip.stress = rotate_symmetric(&rot, &ip.stress);
        let before = ip.stress;
        let dwp = mat.update(&mut ip.stress, &mut ip.eps_p, &d, dt);
        *plastic_work += dwp * jm[p];
        *internal_energy += 0.5 * jm[p] * (ddot(&before, &d) + ddot(&ip.stress, &d));
    }

    let (g1, j1) = gauss_gradients(x1);
    let mut vol = 0.0;
    let mut pj = 0.0;
    let mut bbar = [[0.0; 3]; 8];
    let mut force = [[0.0; 3]; 8];
    let mut jmin = f64::INFINITY;
    for (p, ip) in points.iter_mut().enumerate() {
        let j = j1[p];
        jmin = jmin.min(j);
        ip.volume = j;
        vol += j;
        pj += j * trace(&ip.stress) / 3.0;
        let s = deviator(&ip.stress);
        for i in 0..8 {
            let gi = g1[p][i];
            let f = sym_vec(&s, gi);
            for c in 0..3 {
                force[i][c] += j * f[c];
                bbar[i][c] += j * gi[c];
            }
        }
    }
    // Pressure part with the mean gradient B̄_I = Σ_g J_g ∇N_I(g) / V: Σ_g J_g p_g B̄_I.
    let scale = pj / vol;
    for (f, b) in force.iter_mut().zip(&bbar) {
        for c in 0..3 {
            f[c] += scale * b[c];
        }
    }
    let dt_crit = characteristic_length(x1, vol) / mat.wave_speed;
    ElementOutput {
        force,
        volume: vol,
        min_jacobian: jmin,
        dt_crit,
    }
}
