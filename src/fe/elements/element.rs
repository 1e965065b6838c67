//! The element-family seam: what a hexahedron family gives the element loop (its integration
//! points, the lane state beyond them, its lane update and what that update hands back), the
//! lane loop over one batch and the timing of the lane arithmetic, both written once here for
//! every family, and the visitor by which
//! [`crate::fe::elements::formulation::Formulation::with`] runs code generic over the family.

use super::batch::{
    finish_lanes, gather_nodes, time_updates, Batch, BatchResult, BlockState, LaneResult, StepInput,
};
use super::lane_state::{ExtraLanes, LaneGroup, LaneState, PointState, StateArrays};
use crate::fe::materials::{Hardening, J2Material};
use crate::fe::simd::{build, LaneIsa, Vec3};
use std::mem::MaybeUninit;

/// What a family's lane update reads besides its state: nodal coordinates x^{n+1} (m) and
/// velocities v^{n+1/2} (m/s) of W elements, the step (s), the material, the hourglass
/// coefficient (0 = off) and the hardening law.
pub(crate) struct LaneStep<'a, H, const W: usize> {
    pub(crate) x1: &'a [Vec3<W>; 8],
    pub(crate) v: &'a [Vec3<W>; 8],
    pub(crate) dt: f64,
    pub(crate) mat: &'a J2Material,
    pub(crate) hg: f64,
    pub(crate) law: &'a H,
}

/// What the element loop needs of a formulation: its integration points per element, its
/// lane state and lane update. Every function is `#[inline(always)]`, so that the loop
/// compiles with the features of the kernel path that runs it
/// ([`crate::fe::simd::Simd::vectorize`]).
pub(crate) trait Element {
    /// Integration points per element (rows of the block's point array), those of
    /// [`Element::Points`].
    const POINTS: usize = <Self::Points<1> as PointState<1>>::POINTS;

    /// Whether the family keeps hourglass forces and energy per element (the block
    /// allocates its hourglass arrays only then; a family without them gets empty slices).
    const HOURGLASS: bool;

    /// The lane state at the integration points
    /// ([`PointLanes`](super::lane_state::PointLanes)).
    type Points<const W: usize>: PointState<W>;

    /// The lane state beyond the points' (hourglass forces, or none).
    type Extra<const W: usize>: ExtraLanes<W>;

    /// What the lane update hands back.
    type Output<const W: usize>;

    /// Advances W elements by one step.
    fn update<H: Hardening, const W: usize>(
        s: LaneStep<'_, H, W>,
        points: &mut Self::Points<W>,
        extra: &mut Self::Extra<W>,
    ) -> Self::Output<W>;

    /// The update's forces, volume, smallest Jacobian and Courant limit, for the check.
    fn result<const W: usize>(out: &Self::Output<W>) -> LaneResult<'_, W>;

    /// The volume each integration point represents after the update, m³.
    fn point_volumes<const W: usize>(
        out: &Self::Output<W>,
    ) -> <Self::Points<W> as PointState<W>>::Volumes;

    /// True when `a` holds the rows of both state parts for `n` elements.
    fn holds(a: &StateArrays<'_>, n: usize) -> bool {
        <Self::Points<1> as LaneState<1>>::holds(a, n)
            && <Self::Extra<1> as LaneState<1>>::holds(a, n)
    }

    /// Advances the batch `b` W elements at a time with hardening law `law`: gathers nodes
    /// and state into lanes, updates, scatters state and forces back, checks each element.
    /// Lanes past the batch end repeat its last element and are discarded.
    #[inline(always)]
    fn lane_loop<H: Hardening, const W: usize>(
        isa: LaneIsa<W>,
        law: &H,
        b: &mut Batch<'_>,
        inp: StepInput<'_>,
        base: usize,
    ) -> BatchResult {
        let StepInput {
            x, v, dt, mat, hg, ..
        } = inp;
        let n = b.conn.len();
        // The loads and stores below read and write rows unchecked: once per batch, every
        // array holds its rows for the batch's n elements.
        assert!(
            Self::holds(&b.arrays(), n),
            "batch arrays do not match its {n} elements"
        );
        let mut best = (f64::INFINITY, base);
        let mut k0 = 0;
        while k0 < n {
            let idx: [usize; W] = build(|l| (k0 + l).min(n - 1));
            let live = (n - k0).min(W);
            let (mut xe, mut ve) = (MaybeUninit::uninit(), MaybeUninit::uninit());
            let (xe, ve) = gather_nodes(isa, &idx, b.conn, x, v, &mut xe, &mut ve);
            let (mut ps, mut es) = (MaybeUninit::uninit(), MaybeUninit::uninit());
            let g = LaneGroup {
                isa,
                arrays: b.arrays(),
                idx: &idx,
            };
            // SAFETY: every index is a local element < n of this batch, whose arrays hold
            // both parts' rows for n elements (asserted above).
            let (points, extra) = unsafe {
                (
                    Self::Points::<W>::load(&g, &mut ps),
                    Self::Extra::<W>::load(&g, &mut es),
                )
            };
            Self::Points::<W>::prefetch(b, k0);
            Self::Extra::<W>::prefetch(b, k0);
            let s = LaneStep {
                x1: xe,
                v: ve,
                dt,
                mat,
                hg,
                law,
            };
            let out = Self::update(s, points, extra);
            let volume = Self::point_volumes(&out);
            if live == W {
                // SAFETY: full group: W distinct elements k0.. < n.
                unsafe {
                    points.store_group(&volume, b, k0);
                    extra.store_group(b, k0);
                }
            } else {
                for l in 0..live {
                    points.store_lane(&volume, b, k0 + l, l);
                    extra.store_lane(b, k0 + l, l);
                }
            }
            finish_lanes(&Self::result(&out), b, k0, live, base, &mut best)?;
            k0 += W;
        }
        Ok(best)
    }

    /// Time of `repeats` updates of the first lane group of `b` (local elements `idx`,
    /// nodal lanes `xe` in m and `ve` in m/s, step `dt` in s), state restarted every 64.
    /// Panics if an index of `idx` is not an element of `b` (a programming error).
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn time_arithmetic<H: Hardening, const W: usize>(
        isa: LaneIsa<W>,
        law: &H,
        b: &BlockState<'_>,
        xe: &[Vec3<W>; 8],
        ve: &[Vec3<W>; 8],
        idx: &[usize; W],
        dt: f64,
        repeats: u32,
    ) -> std::time::Duration {
        let g = LaneGroup {
            isa,
            arrays: b.arrays(),
            idx,
        };
        let n = g.arrays.wp.len();
        assert!(
            idx.iter().all(|&k| k < n) && Self::holds(&g.arrays, n),
            "lane group outside the block"
        );
        let (mut ps, mut es) = (MaybeUninit::uninit(), MaybeUninit::uninit());
        // SAFETY: checked above: every index is an element of the block.
        let st0 = unsafe {
            (
                *Self::Points::<W>::load(&g, &mut ps),
                *Self::Extra::<W>::load(&g, &mut es),
            )
        };
        let (mat, hg) = (b.material, b.hourglass_coeff);
        time_updates!(repeats, xe, ve, st0, |st, xr, vr| Self::update(
            LaneStep {
                x1: xr,
                v: vr,
                dt,
                mat,
                hg,
                law,
            },
            &mut st.0,
            &mut st.1
        ))
    }
}

/// Code generic over the element type, run by [`Formulation::with`].
pub(crate) trait ElementVisitor {
    /// What the visit returns.
    type Output;
    /// Runs with the concrete element type.
    fn visit<E: Element>(self) -> Self::Output;
}

// The arrays a lane state is read from, for the loop (a batch) and for the timing (a block).
impl Batch<'_> {
    /// The batch's state arrays, read only.
    pub(crate) fn arrays(&self) -> StateArrays<'_> {
        StateArrays {
            pts: self.pts,
            wp: self.wp,
            ie: self.ie,
            hgq: self.hgq,
            ehg: self.ehg,
        }
    }
}

impl BlockState<'_> {
    /// The block's state arrays.
    pub(crate) fn arrays(&self) -> StateArrays<'_> {
        StateArrays {
            pts: self.points,
            wp: self.plastic_work,
            ie: self.internal_energy,
            hgq: self.hourglass,
            ehg: self.hourglass_energy,
        }
    }
}
