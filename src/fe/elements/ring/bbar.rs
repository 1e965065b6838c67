//! The selectively reduced (B-bar) ring quad: four 2x2 Gauss points for the deviatoric
//! strain rate and the element's mean dilatation for the volumetric one (Hughes 1980), so
//! the isochoric plastic flow does not lock; no hourglass modes, no hourglass control. The
//! section's counterpart of the B-bar hexahedron; objective update and forces as the
//! one-point quad's ([`super::one_point`]), at each Gauss point.

use super::element::{LaneStep, Quad, RingElement, Step};
use super::four_point::{update, update_lanes};
use super::lanes::{RingLaneOutput, RingLaneState};
use super::state::{QuadOutput, QuadState};
use crate::fe::materials::Hardening;

/// The selectively reduced (B-bar) quad.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BBarQuad;

impl RingElement for BBarQuad {
    const POINTS: usize = 4;

    #[inline]
    fn update(&self, s: Step<'_, Quad>, st: &mut QuadState) -> QuadOutput {
        update::<true>(s, st)
    }

    #[inline(always)]
    fn update_lanes<H: Hardening, const W: usize>(
        &self,
        s: LaneStep<'_, H, W>,
        st: &mut RingLaneState<W>,
    ) -> RingLaneOutput<W> {
        update_lanes::<true, H, W>(s, st)
    }
}
