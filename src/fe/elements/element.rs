//! The element-family seam: what the element loop needs of a family (its integration points
//! per element, its lane loop over one batch, its kernel timing) and the visitor by which
//! [`crate::fe::elements::formulation::Formulation::with`] runs code generic over the family.

use super::batch::{Batch, BatchResult, BlockState, StepInput};
use crate::fe::materials::Hardening;
use crate::fe::simd::{LaneIsa, Vec3};

/// What the element loop needs of a formulation: its integration points per element, its
/// lane loop over one batch, and the timing of its lane kernel's arithmetic alone. Both
/// lane functions are `#[inline(always)]`, so that they compile with the features of the
/// kernel path that runs them ([`crate::fe::simd::Simd::vectorize`]).
pub(crate) trait Element {
    /// Integration points per element (rows of the block's point array).
    const POINTS: usize;

    /// Whether the family keeps hourglass forces and energy per element (the block
    /// allocates its hourglass arrays only then; a family without them gets empty slices).
    const HOURGLASS: bool;

    /// Advances the batch `b` W elements at a time with hardening law `law`: gathers nodes
    /// and state into lanes, updates, scatters state and forces back, checks each element.
    #[allow(clippy::too_many_arguments)]
    fn lane_loop<H: Hardening, const W: usize>(
        isa: LaneIsa<W>,
        law: &H,
        b: &mut Batch<'_>,
        inp: StepInput<'_>,
        base: usize,
    ) -> BatchResult;

    /// Time of `repeats` updates of the first lane group of `b` (local elements `idx`,
    /// nodal lanes `xe` in m and `ve` in m/s, step `dt` in s), state restarted every 64.
    #[allow(clippy::too_many_arguments)]
    fn time_arithmetic<H: Hardening, const W: usize>(
        isa: LaneIsa<W>,
        law: &H,
        b: &BlockState<'_>,
        xe: &[Vec3<W>; 8],
        ve: &[Vec3<W>; 8],
        idx: &[usize; W],
        dt: f64,
        repeats: u32,
    ) -> std::time::Duration;
}

/// Code generic over the element type, run by [`Formulation::with`].
pub(crate) trait ElementVisitor {
    /// What the visit returns.
    type Output;
    /// Runs with the concrete element type.
    fn visit<E: Element>(self) -> Self::Output;
}
