//! The fully integrated ring quad: four 2x2 Gauss points, each with its own strain rate
//! (deviatoric and volumetric), stress and plastic strain; forces Σ_g W_g B_gᵀσ_g. No
//! hourglass modes and no hourglass control, the classical element of implicit codes
//! (Zienkiewicz & Taylor, vol. 1, §9; Hughes 1987, §4.5).
//!
//! Its limit is volumetric locking: four points each holding its own dilatation over-
//! constrain isochoric (plastic) flow, so a plastic run comes out too stiff (Nagtegaal,
//! Parks & Rice 1974) — the reason the B-bar quad ([`super::bbar`]) keeps the element's
//! mean dilatation instead. Elastic runs with ν well below ½ do not lock. Objective update
//! and material seam as the other formulations', at each Gauss point.

use super::element::{LaneStep, Quad, RingElement, Step};
use super::lanes::{self, RingLaneOutput, RingLaneState};
use super::scalar::{advance_gauss_points, mid_step, output};
use super::shape::{add_stress_forces, gauss_points, mean_of};
use super::state::{QuadOutput, QuadState};
use crate::fe::materials::Hardening;

/// The fully integrated (2x2 Gauss) quad.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FullQuad;

impl RingElement for FullQuad {
    const POINTS: usize = 4;

    #[inline]
    fn update(&self, s: Step<'_, Quad>, st: &mut QuadState) -> QuadOutput {
        let Step { x1, v, dt, mat } = s;
        let pm = gauss_points(&mid_step(x1, v, dt));
        let p1 = gauss_points(x1);
        let (g1, min_j) = mean_of(&p1);
        advance_gauss_points(st, &pm, v, None, dt, mat);
        let mut force = [[0.0; 2]; 4];
        for (k, p) in p1.iter().enumerate() {
            add_stress_forces(&mut force, &st.points[k].stress, &p.grad);
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
        let pm = lanes::gauss_points(&lanes::mid_step(x1, v, dt));
        let p1 = lanes::gauss_points(x1);
        let (g1, min_j) = lanes::mean_of(&p1);
        lanes::advance_gauss_points(&pm, v, None, dt, mat, law, st);
        let mut force = [[x1[0][0].splat_like(0.0); 2]; 4];
        for (k, p) in p1.iter().enumerate() {
            lanes::add_stress_forces(&mut force, &st.stress[k], &p.grad);
        }
        lanes::output(x1, force, g1.volume, min_j, mat)
    }
}
