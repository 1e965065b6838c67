//! The selectively reduced (B-bar) ring quad: four 2x2 Gauss points for the deviatoric
//! strain rate and the element's mean dilatation for the volumetric one (Hughes 1980), so
//! the isochoric plastic flow does not lock; no hourglass modes, no hourglass control. The
//! section's counterpart of the B-bar hexahedron; objective update and forces as the
//! one-point quad's ([`super::one_point`]), at each Gauss point.

use super::element::{LaneStep, Quad, RingElement, Step};
use super::lanes::{self, RingLaneOutput, RingLaneState};
use super::scalar::{advance_gauss_points, mid_step, output};
use super::shape::{add_stress_forces, gauss_points, mean_of, velocity_gradient, Gradient};
use super::state::{QuadOutput, QuadState};
use crate::fe::{materials::Hardening, tensor::Sym};

/// The selectively reduced (B-bar) quad.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BBarQuad;

impl RingElement for BBarQuad {
    const POINTS: usize = 4;

    #[inline]
    fn update(&self, s: Step<'_, Quad>, st: &mut QuadState) -> QuadOutput {
        let Step { x1, v, dt, mat } = s;
        let xm = mid_step(x1, v, dt);
        let mut force = [[0.0; 2]; 4];
        let pm = gauss_points(&xm);
        let (gm, _) = mean_of(&pm);
        let p1 = gauss_points(x1);
        let (g1, min_j) = mean_of(&p1);
        let lbar = velocity_gradient(v, &gm);
        let vol_bar = lbar[0][0] + lbar[1][1] + lbar[2][2];
        advance_gauss_points(st, &pm, v, Some(vol_bar), dt, mat);
        for (k, p) in p1.iter().enumerate() {
            bbar_forces(&mut force, &st.points[k].stress, &p.grad, &g1);
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
        let pm = lanes::gauss_points(&xm);
        let (gm, _) = lanes::mean_of(&pm);
        let p1 = lanes::gauss_points(x1);
        let (g1, min_j) = lanes::mean_of(&p1);
        let lbar = lanes::velocity_gradient(v, &gm);
        let vol_bar = lbar[0] + lbar[3] + lbar[4];
        lanes::advance_gauss_points(&pm, v, Some(vol_bar), dt, mat, law, st);
        let mut force = [[zero; 2]; 4];
        for (k, p) in p1.iter().enumerate() {
            // bbar_forces: W_g (B_gᵀσ + p (B̄_vol − B_g,vol)).
            let s = st.stress[k];
            lanes::add_stress_forces(&mut force, &s, &p.grad);
            let pressure = (s[0] + s[1] + s[2]) / 3.0;
            for i in 0..4 {
                let dr = (g1.b[i][0] + g1.hoop[i]) - (p.grad.b[i][0] + p.grad.hoop[i]);
                let dz = g1.b[i][1] - p.grad.b[i][1];
                force[i][0] += p.grad.volume * pressure * dr;
                force[i][1] += p.grad.volume * pressure * dz;
            }
        }
        lanes::output(x1, force, g1.volume, min_j, mat)
    }
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
