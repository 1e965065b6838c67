//! The one-point hexahedron of Flanagan & Belytschko (1981): uniform (mean) strain operator
//! B_I = (1/V) ∂V/∂x_I, exact volume, and stiffness-type hourglass control with the FB
//! γ vectors (the LS-DYNA ELFORM 1 / IHQ 4-5 family, Abaqus C3D8R "stiffness" hourglass).
//!
//! Hourglass control: the four hourglass "strain rates" q_α = Σ_I v_I γ_αI (m/s) drive
//! resisting generalised forces Q_α (N) through Q̇_α = k q_α with
//! k = ε_hg (λ + 2G) V Σ_I |B_I|² / 3 (N/m); nodal forces are Q_α γ_αI. The default
//! coefficient ε_hg = 0.05 (the LS-DYNA recommendation for its stiffness forms is 0.03-0.10).
//! The γ vectors are orthogonal to every linear velocity field, so rigid motion and uniform
//! strain never excite hourglass forces (patch test passes with hourglass control on).

use crate::fe::{
    elements::batch::ElementStateMut,
    elements::objective::{hughes_winget, rotate_symmetric},
    elements::shape::NODE_XI,
    materials::J2Material,
    solver::timestep::characteristic_length,
    tensor::{ddot, mat_vec, spin_vector, sym_part, sym_vec},
};

/// The hourglass base vectors h_α: ηζ, ζξ, ξη, ξηζ evaluated at the nodes.
pub const HOURGLASS_BASE: [[f64; 8]; 4] = {
    let mut h = [[0.0; 8]; 4];
    let mut i = 0;
    while i < 8 {
        let p = NODE_XI[i];
        h[0][i] = p[1] * p[2];
        h[1][i] = p[2] * p[0];
        h[2][i] = p[0] * p[1];
        h[3][i] = p[0] * p[1] * p[2];
        i += 1;
    }
    h
};

/// Node permutations of Flanagan & Belytschko's volume-derivative formula: row I lists the
/// nodes in the roles 1..8 of the formula for node I (0-based).
const FB_PERM: [[usize; 8]; 8] = [
    [0, 1, 2, 3, 4, 5, 6, 7],
    [1, 2, 3, 0, 5, 6, 7, 4],
    [2, 3, 0, 1, 6, 7, 4, 5],
    [3, 0, 1, 2, 7, 4, 5, 6],
    [4, 7, 6, 5, 0, 3, 2, 1],
    [5, 4, 7, 6, 1, 0, 3, 2],
    [6, 5, 4, 7, 2, 1, 0, 3],
    [7, 6, 5, 4, 3, 2, 1, 0],
];

/// ∂V/∂x_I for the x-component given coordinates (y, z) in the cyclic role; FB eq. (formula
/// for b_1, one line per node role).
#[inline]
fn fb_term(y: &[f64; 8], z: &[f64; 8], p: &[usize; 8]) -> f64 {
    let (y2, y3, y4, y5, y6, y8) = (y[p[1]], y[p[2]], y[p[3]], y[p[4]], y[p[5]], y[p[7]]);
    let (z2, z3, z4, z5, z6, z8) = (z[p[1]], z[p[2]], z[p[3]], z[p[4]], z[p[5]], z[p[7]]);
    (y2 * ((z6 - z3) - (z4 - z5))
        + y3 * (z2 - z4)
        + y4 * ((z3 - z8) - (z5 - z2))
        + y5 * ((z8 - z6) - (z2 - z4))
        + y6 * (z5 - z2)
        + y8 * (z4 - z5))
        / 12.0
}

/// Volume V (m³) and mean strain operator B_I = (1/V) ∂V/∂x_I (1/m, shape [node][x, y, z]) of
/// a hexahedron with nodal coordinates `x` (m). Exact for the trilinear element; Σ_I B_I = 0 and
/// Σ_I x_I ⊗ B_I = I. A non-positive V means an inverted element (B is then meaningless).
#[inline]
pub fn mean_gradient(x: &[[f64; 3]; 8]) -> (f64, [[f64; 3]; 8]) {
    let xs: [f64; 8] = std::array::from_fn(|i| x[i][0]);
    let ys: [f64; 8] = std::array::from_fn(|i| x[i][1]);
    let zs: [f64; 8] = std::array::from_fn(|i| x[i][2]);
    let mut b = [[0.0; 3]; 8];
    for (i, p) in FB_PERM.iter().enumerate() {
        b[i] = [
            fb_term(&ys, &zs, p),
            fb_term(&zs, &xs, p),
            fb_term(&xs, &ys, p),
        ];
    }
    let v: f64 = (0..8).map(|i| xs[i] * b[i][0]).sum();
    let r = 1.0 / v;
    for bi in &mut b {
        for c in bi.iter_mut() {
            *c *= r;
        }
    }
    (v, b)
}

/// FB hourglass shape vectors γ_αI = (h_αI − (Σ_J h_αJ x_J) · B_I)/8 (dimensionless).
#[inline]
pub fn hourglass_gammas(x: &[[f64; 3]; 8], b: &[[f64; 3]; 8]) -> [[f64; 8]; 4] {
    let mut g = [[0.0; 8]; 4];
    for (ga, h) in g.iter_mut().zip(&HOURGLASS_BASE) {
        let mut hx = [0.0; 3];
        for (hi, xi) in h.iter().zip(x) {
            for k in 0..3 {
                hx[k] += hi * xi[k];
            }
        }
        for i in 0..8 {
            ga[i] = 0.125 * (h[i] - (hx[0] * b[i][0] + hx[1] * b[i][1] + hx[2] * b[i][2]));
        }
    }
    g
}

/// Hourglass stiffness k = ε_hg (λ + 2G) V Σ_I |B_I|²/3, N/m.
#[inline]
pub fn hourglass_stiffness(coeff: f64, p_modulus: f64, volume: f64, b: &[[f64; 3]; 8]) -> f64 {
    let bb: f64 = b
        .iter()
        .map(|v| v[0] * v[0] + v[1] * v[1] + v[2] * v[2])
        .sum();
    coeff * p_modulus * volume * bb / 3.0
}

/// What one element update returns.
#[derive(Debug, Clone, Copy)]
pub struct ElementOutput {
    /// Internal nodal forces f_int at t^{n+1}, N.
    pub force: [[f64; 3]; 8],
    /// Volume at t^{n+1}, m³.
    pub volume: f64,
    /// Smallest Jacobian determinant (or the volume for the one-point hex); ≤ 0 means the
    /// element is inverted.
    pub min_jacobian: f64,
    /// Critical time step of the element L_e / c, s.
    pub dt_crit: f64,
}

/// Updates one element from t^n to t^{n+1}: nodal coordinates `x1` = x^{n+1} (m), velocities
/// `v` = v^{n+1/2} (m/s), step `dt` (s). The velocity gradient is evaluated on the mid-step
/// configuration x^{n+1/2} = x^{n+1} − Δt/2 v (so rigid rotations give zero strain exactly), the
/// stress and hourglass forces are rotated by the Hughes-Winget increment, the material is
/// updated, and the internal forces (element + hourglass) are computed on x^{n+1}.
/// `dt = 0` evaluates the forces of the current state without advancing it.
#[inline]
pub fn update(
    x1: &[[f64; 3]; 8],
    v: &[[f64; 3]; 8],
    dt: f64,
    mat: &J2Material,
    hg_coeff: f64,
    st: ElementStateMut<'_>,
) -> ElementOutput {
    let ElementStateMut {
        points,
        plastic_work,
        internal_energy,
        hourglass,
        hourglass_energy,
    } = st;
    let ip = &mut points[0];
    let xm = super::shape::mid_step(x1, v, dt);
    let (vm, bm) = mean_gradient(&xm);
    // Velocity gradient L_ij = Σ_I v_Ii B_Ij on the mid-step configuration.
    let mut l = [[0.0; 3]; 3];
    for (vi, bi) in v.iter().zip(&bm) {
        for r in 0..3 {
            for c in 0..3 {
                l[r][c] += vi[r] * bi[c];
            }
        }
    }
    let d = sym_part(&l).map(|e| e * dt);
    let w = spin_vector(&l).map(|e| e * dt);
    let rot = hughes_winget(w);
    ip.stress = rotate_symmetric(&rot, &ip.stress);
    for q in hourglass.iter_mut() {
        *q = mat_vec(&rot, *q);
    }
    let before = ip.stress;
    let dwp = mat.update(&mut ip.stress, &mut ip.eps_p, &d, dt);
    *plastic_work += dwp * vm;
    // Stress power with the mid-step stress (trapezoid): V (σⁿ + σⁿ⁺¹)/2 : Δε.
    *internal_energy += 0.5 * vm * (ddot(&before, &d) + ddot(&ip.stress, &d));

    let (v1, b1) = mean_gradient(x1);
    ip.volume = v1;
    let mut force = [[0.0; 3]; 8];
    for (f, b) in force.iter_mut().zip(&b1) {
        *f = sym_vec(&ip.stress, *b).map(|c| c * v1);
    }
    if hg_coeff > 0.0 {
        let gam = hourglass_gammas(x1, &b1);
        let k = hourglass_stiffness(hg_coeff, mat.p_modulus(), v1, &b1);
        let mut e = 0.0;
        for (q, ga) in hourglass.iter_mut().zip(&gam) {
            let mut rate = [0.0; 3];
            for (vi, g) in v.iter().zip(ga) {
                rate[0] += g * vi[0];
                rate[1] += g * vi[1];
                rate[2] += g * vi[2];
            }
            let old = *q;
            for c in 0..3 {
                q[c] += k * dt * rate[c];
                // Trapezoidal work of the hourglass spring = change of its stored energy.
                e += 0.5 * (old[c] + q[c]) * rate[c] * dt;
            }
            for (f, g) in force.iter_mut().zip(ga) {
                f[0] += g * q[0];
                f[1] += g * q[1];
                f[2] += g * q[2];
            }
        }
        *hourglass_energy += e;
    }
    let dt_crit = characteristic_length(x1, v1) / mat.wave_speed;
    ElementOutput {
        force,
        volume: v1,
        min_jacobian: v1,
        dt_crit,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fe::elements::shape::gauss_volume_gradient;

    fn distorted() -> [[f64; 3]; 8] {
        let mut x = NODE_XI.map(|p| p.map(|c| 0.5 * (c + 1.0)));
        let bumps = [
            [0.05, -0.02, 0.03],
            [0.1, 0.04, -0.05],
            [-0.03, 0.12, 0.02],
            [0.02, -0.06, 0.08],
        ];
        for (i, b) in bumps.iter().enumerate() {
            for k in 0..3 {
                x[2 * i + 1][k] += b[k];
                x[2 * i][k] -= 0.5 * b[(k + 1) % 3];
            }
        }
        x
    }

    #[test]
    fn fb_gradient_equals_volume_average_of_gauss_gradients() {
        // ∫ ∂N/∂x dV is integrated exactly by 2x2x2 Gauss for a trilinear hex.
        let x = distorted();
        let (v, b) = mean_gradient(&x);
        let (vq, bq) = gauss_volume_gradient(&x);
        assert!((v - vq).abs() < 1e-14, "{v} vs {vq}");
        for i in 0..8 {
            for k in 0..3 {
                assert!((b[i][k] - bq[i][k] / vq).abs() < 1e-12, "node {i} comp {k}");
            }
        }
    }

    #[test]
    fn gammas_annihilate_linear_fields() {
        let x = distorted();
        let (_, b) = mean_gradient(&x);
        let g = hourglass_gammas(&x, &b);
        for ga in &g {
            assert!(ga.iter().sum::<f64>().abs() < 1e-14);
            for k in 0..3 {
                let s: f64 = (0..8).map(|i| ga[i] * x[i][k]).sum();
                assert!(s.abs() < 1e-14);
            }
        }
    }
}
