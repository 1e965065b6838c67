//! The one-point ring quad: one stress state per element on the volume-averaged operator B̄
//! ([`shape::mean_gradient`]) with Flanagan-Belytschko stiffness hourglass control
//! (Q̇ = k q per direction, k = ε_hg (λ + 2G) V Σ_I |B̄_I|² / 2), the section's counterpart of
//! the one-point hexahedron.
//!
//! The strain rate and spin are evaluated on the mid-step configuration x^{n+1/2}, the stress
//! is rotated by the Hughes-Winget increment of the in-plane spin (the 3D code's objective
//! update: the rotation is about the hoop direction and leaves σ_θθ alone), advanced by
//! [`J2Material::update`] (every hardening law of the material seam), and the nodal forces
//! are V B̄ᵀσ on x^{n+1}. Forces are those of the whole ring (2π r weighting).

use super::element::{LaneStep, Quad, RingElement, Step};
use super::lanes::{self, rotation, Nodes, RingLaneOutput, RingLaneState};
use super::scalar::{advance_point, mid_step, output};
use super::shape::{
    add_stress_forces, hourglass_gamma, mean_gradient, velocity_gradient, Gradient, HOURGLASS_BASE,
};
use super::state::{QuadOutput, QuadState};
use crate::fe::{
    elements::objective::hughes_winget,
    materials::{Hardening, J2Material},
    simd::Lanes,
    tensor::{spin_vector, Mat3},
};

/// Default hourglass coefficient ε_hg of the one-point quad (as the hexahedron's).
pub const DEFAULT_HOURGLASS: f64 = 0.05;

/// The one-point quad with stiffness hourglass control of coefficient ε_hg.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OnePointQuad {
    /// Hourglass coefficient ε_hg (dimensionless, ≥ 0; 0.03-0.1 usual).
    pub hourglass: f64,
}

impl RingElement for OnePointQuad {
    const POINTS: usize = 1;

    #[inline]
    fn update(&self, s: Step<'_, Quad>, st: &mut QuadState) -> QuadOutput {
        let Step { x1, v, dt, mat } = s;
        let xm = mid_step(x1, v, dt);
        let mut force = [[0.0; 2]; 4];
        let (gm, _) = mean_gradient(&xm);
        let (g1, min_j) = mean_gradient(x1);
        let l = velocity_gradient(v, &gm);
        advance_point(st, 0, &l, None, dt, gm.volume, mat);
        add_stress_forces(&mut force, &st.points[0].stress, &g1);
        if self.hourglass > 0.0 {
            let k = hourglass_stiffness(self.hourglass, mat.p_modulus(), &g1);
            let rot = in_plane_rotation(&l, dt);
            let gam = hourglass_gamma(x1, &g1);
            let e = hourglass_update(&mut st.hourglass, &gam, v, k, rot, dt, &mut force);
            st.hourglass_energy += e;
        }
        output(x1, force, g1.volume, min_j, mat)
    }

    #[inline(always)]
    fn update_lanes<H: Hardening, const W: usize>(
        &self,
        s: LaneStep<'_, H, W>,
        st: &mut RingLaneState<W>,
    ) -> RingLaneOutput<W> {
        let LaneStep { step, law } = s;
        let Step { x1, v, dt, mat } = step;
        let zero = x1[0][0].splat_like(0.0);
        let xm = lanes::mid_step(x1, v, dt);
        let (gm, _) = lanes::mean_gradient(&xm);
        let (g1, min_j) = lanes::mean_gradient(x1);
        let l = lanes::velocity_gradient(v, &gm);
        // The point's update (scalar::advance_point): rotate, return, account.
        let d = lanes::strain_increment(&l, None, dt);
        let r = rotation(&l, dt);
        lanes::advance_point(mat, law, &r, &d, dt, gm.volume, 0, st);
        // Forces V B̄ᵀσ on x^{n+1} (shape::add_stress_forces onto zero).
        let mut force = [[zero; 2]; 4];
        lanes::add_stress_forces(&mut force, &st.stress[0], &g1);
        if self.hourglass > 0.0 {
            hourglass_forces(
                x1,
                v,
                &g1,
                mat,
                self.hourglass,
                [r[0], r[2]],
                dt,
                st,
                &mut force,
            );
        }
        lanes::output(x1, force, g1.volume, min_j, mat)
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
fn in_plane_rotation(l: &Mat3, dt: f64) -> [f64; 2] {
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

/// The Flanagan-Belytschko stiffness hourglass forces of W quads added to `force`
/// ([`hourglass_stiffness`], [`shape::hourglass_gamma`], [`hourglass_update`]); `rot`
/// is the in-plane rotation (cos, sin) of the step.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn hourglass_forces<const W: usize>(
    x1: &Nodes<W>,
    v: &Nodes<W>,
    g: &lanes::Gradient<W>,
    mat: &J2Material,
    coeff: f64,
    rot: [Lanes<W>; 2],
    dt: f64,
    st: &mut RingLaneState<W>,
    force: &mut [[Lanes<W>; 2]; 4],
) {
    let zero = x1[0][0].splat_like(0.0);
    let mut bb = zero.splat_like(-0.0);
    for b in &g.b {
        bb += b[0] * b[0] + b[1] * b[1];
    }
    let k = coeff * mat.p_modulus() * g.volume * bb / 2.0;
    let mut hx = [zero; 2];
    for i in 0..4 {
        hx[0] += HOURGLASS_BASE[i] * x1[i][0];
        hx[1] += HOURGLASS_BASE[i] * x1[i][1];
    }
    let gam: [Lanes<W>; 4] = std::array::from_fn(|i| {
        0.25 * (zero.splat_like(HOURGLASS_BASE[i]) - hx[0] * g.b[i][0] - hx[1] * g.b[i][1])
    });
    let [c, s] = rot;
    let q = st.hourglass;
    let mut q = [c * q[0] - s * q[1], s * q[0] + c * q[1]];
    let mut rate = [zero; 2];
    for i in 0..4 {
        rate[0] += gam[i] * v[i][0];
        rate[1] += gam[i] * v[i][1];
    }
    let mut e = zero;
    for a in 0..2 {
        let old = q[a];
        q[a] += k * dt * rate[a];
        e += 0.5 * (old + q[a]) * rate[a] * dt;
    }
    for i in 0..4 {
        force[i][0] += gam[i] * q[0];
        force[i][1] += gam[i] * q[1];
    }
    st.hourglass = q;
    st.hourglass_energy += e;
}
