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
use super::four_point::{update, update_lanes};
use super::lanes::{RingLaneOutput, RingLaneState};
use super::state::{QuadOutput, QuadState};
use crate::fe::materials::Hardening;

/// The fully integrated (2x2 Gauss) quad.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FullQuad;

impl RingElement for FullQuad {
    const POINTS: usize = 4;

    #[inline]
    fn update(&self, s: Step<'_, Quad>, st: &mut QuadState) -> QuadOutput {
        update::<false>(s, st)
    }

    #[inline(always)]
    fn update_lanes<H: Hardening, const W: usize>(
        &self,
        s: LaneStep<'_, H, W>,
        st: &mut RingLaneState<W>,
    ) -> RingLaneOutput<W> {
        update_lanes::<false, H, W>(s, st)
    }
}
