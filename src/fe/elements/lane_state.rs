//! The state of W hexahedra in SIMD lanes, as their lane kernels advance it, and its one load
//! from and store to the block's arrays: the integration points' stress and plastic strain
//! with the elements' energies ([`PointLanes`], every family) and the hourglass forces of a
//! family that keeps them ([`HourglassLanes`]; [`NoLanes`] for one that does not).
//!
//! Rows: a point is eight f64 (`IntegrationPoint`, `repr(C)`: stress, eps_p, volume), P of
//! them per element; hourglass forces are twelve f64 per element. A full group reads and
//! writes them as rows transposed in registers (`Lanes::load_rows`, `Lanes::store_rows`); the
//! group at a batch's end writes its live lanes one by one.

use super::batch::{contiguous, Batch, IntegrationPoint};
use crate::fe::simd::{build, prefetch::prefetch_ahead, LaneIsa, Lanes, Vec3};
use std::mem::MaybeUninit;

/// The state arrays of a batch or block that lane states are loaded from, by local element.
pub(crate) struct StateArrays<'a> {
    /// Integration points, P per element.
    pub(crate) pts: &'a [IntegrationPoint],
    /// Plastic work per element, J.
    pub(crate) wp: &'a [f64],
    /// Internal energy per element, J.
    pub(crate) ie: &'a [f64],
    /// Hourglass forces per element, N (empty for a family without them).
    pub(crate) hgq: &'a [[[f64; 3]; 4]],
    /// Hourglass energy per element, J (empty for a family without them).
    pub(crate) ehg: &'a [f64],
}

/// The elements of one lane group: lane l is local element `idx[l]` of `arrays`.
pub(crate) struct LaneGroup<'a, const W: usize> {
    /// The instruction-set token of the kernel path.
    pub(crate) isa: LaneIsa<W>,
    /// The arrays the group is read from.
    pub(crate) arrays: StateArrays<'a>,
    /// The local element of each lane.
    pub(crate) idx: &'a [usize; W],
}

/// A part of the lane state: loaded for a lane group, stored back after its update.
pub(crate) trait LaneState<const W: usize>: Copy {
    /// Loads the group `g` into `slot`, writing every field once (no zero fill first), and
    /// returns it initialised.
    ///
    /// # Safety
    /// Every `g.idx[l]` is below the element count n = `g.arrays.wp.len()`, and
    /// [`LaneState::holds`]`(&g.arrays, n)`.
    unsafe fn load<'s>(g: &LaneGroup<'_, W>, slot: &'s mut MaybeUninit<Self>) -> &'s mut Self;

    /// True when the arrays `a` hold this part's rows for `n` elements: the condition under
    /// which its loads and stores, which index rows unchecked, stay inside the arrays.
    fn holds(a: &StateArrays<'_>, n: usize) -> bool;

    /// Hints the prefetcher at the rows of the group two groups after local element `k0`.
    fn prefetch(b: &Batch<'_>, k0: usize);
}

/// The state at the P integration points of W elements, lane-wise, and their energies.
#[derive(Debug, Clone, Copy)]
pub struct PointLanes<const P: usize, const W: usize> {
    /// Cauchy stress at each point, Pa (Voigt [xx, yy, zz, xy, yz, zx]).
    pub stress: [[Lanes<W>; 6]; P],
    /// Equivalent plastic strain at each point.
    pub eps_p: [Lanes<W>; P],
    /// Plastic work so far, J.
    pub plastic_work: Lanes<W>,
    /// Internal energy ∫ σ:D dV dt so far, J.
    pub internal_energy: Lanes<W>,
}

impl<const P: usize, const W: usize> PointLanes<P, W> {
    /// Every lane and field `z` (a zero state to start from).
    #[cfg(test)]
    pub(crate) fn filled(z: Lanes<W>) -> Self {
        PointLanes {
            stress: [[z; 6]; P],
            eps_p: [z; P],
            plastic_work: z,
            internal_energy: z,
        }
    }
}

/// Row (f64 offset) of point `g` of local element `k` with P points per element.
#[inline(always)]
fn point_row<const P: usize>(k: usize, g: usize) -> usize {
    8 * (P * k + g)
}

impl<const P: usize, const W: usize> LaneState<W> for PointLanes<P, W> {
    #[inline(always)]
    unsafe fn load<'s>(g: &LaneGroup<'_, W>, slot: &'s mut MaybeUninit<Self>) -> &'s mut Self {
        let (isa, a, idx) = (g.isa, &g.arrays, g.idx);
        let pp = a.pts.as_ptr().cast::<f64>();
        let sp = slot.as_mut_ptr();
        for p in 0..P {
            let rows: [usize; W] = build(|l| point_row::<P>(idx[l], p));
            // SAFETY: the caller's contract: rows of eight f64 inside the point array.
            let f: [Lanes<W>; 7] = Lanes::load_rows(isa, pp, &rows);
            let stress = std::ptr::addr_of_mut!((*sp).stress).cast::<[Lanes<W>; 6]>();
            stress.add(p).write([f[0], f[1], f[2], f[3], f[4], f[5]]);
            std::ptr::addr_of_mut!((*sp).eps_p)
                .cast::<Lanes<W>>()
                .add(p)
                .write(f[6]);
        }
        std::ptr::addr_of_mut!((*sp).plastic_work).write(contiguous(isa, a.wp, idx));
        std::ptr::addr_of_mut!((*sp).internal_energy).write(contiguous(isa, a.ie, idx));
        // SAFETY: every field was written above.
        slot.assume_init_mut()
    }

    fn holds(a: &StateArrays<'_>, n: usize) -> bool {
        a.pts.len() == P * n && a.wp.len() == n && a.ie.len() == n
    }

    #[inline(always)]
    fn prefetch(b: &Batch<'_>, k0: usize) {
        prefetch_ahead(b.pts.as_ptr(), P * (k0 + 2 * W), P * W);
    }
}

/// The points' part of a family's lane state ([`PointLanes`]), as the family's generic code
/// sees it: its point count and its stores.
pub(crate) trait PointState<const W: usize>: LaneState<W> {
    /// Integration points per element.
    const POINTS: usize;

    /// The volume each point represents, lane-wise, m³.
    type Volumes;

    /// Writes the state of a full group back to local elements `k0..k0 + W`, with the
    /// volume each point represents after the update, `volume`.
    ///
    /// # Safety
    /// `k0 + W` is at most the batch's element count n, and [`LaneState::holds`] for the
    /// batch's arrays and n.
    unsafe fn store_group(&self, volume: &Self::Volumes, b: &mut Batch<'_>, k0: usize);

    /// Writes lane `l` back to local element `k`, with its points' volumes `volume`.
    fn store_lane(&self, volume: &Self::Volumes, b: &mut Batch<'_>, k: usize, l: usize);
}

impl<const P: usize, const W: usize> PointState<W> for PointLanes<P, W> {
    const POINTS: usize = P;

    type Volumes = [Lanes<W>; P];

    #[inline(always)]
    unsafe fn store_group(&self, volume: &[Lanes<W>; P], b: &mut Batch<'_>, k0: usize) {
        debug_assert!(k0 + W <= b.wp.len());
        let pp = b.pts.as_mut_ptr().cast::<f64>();
        for g in 0..P {
            let s = &self.stress[g];
            let cols = [s[0], s[1], s[2], s[3], s[4], s[5], self.eps_p[g], volume[g]];
            let rows: [usize; W] = build(|l| point_row::<P>(k0 + l, g));
            // SAFETY: W distinct elements inside the batch (the caller's contract).
            Lanes::store_rows(&cols, pp, &rows);
        }
        b.wp[k0..k0 + W].copy_from_slice(&self.plastic_work.0);
        b.ie[k0..k0 + W].copy_from_slice(&self.internal_energy.0);
    }

    #[inline(always)]
    fn store_lane(&self, volume: &[Lanes<W>; P], b: &mut Batch<'_>, k: usize, l: usize) {
        for g in 0..P {
            let ip = &mut b.pts[P * k + g];
            for c in 0..6 {
                ip.stress[c] = self.stress[g][c].0[l];
            }
            ip.eps_p = self.eps_p[g].0[l];
            ip.volume = volume[g].0[l];
        }
        b.wp[k] = self.plastic_work.0[l];
        b.ie[k] = self.internal_energy.0[l];
    }
}

/// What a lane state beyond the points' does after an update: the store of a full group and
/// of one lane.
pub(crate) trait ExtraLanes<const W: usize>: LaneState<W> {
    /// Writes a full group back to local elements `k0..k0 + W`.
    ///
    /// # Safety
    /// `k0 + W` is at most the batch's element count n, and [`LaneState::holds`] for the
    /// batch's arrays and n.
    unsafe fn store_group(&self, b: &mut Batch<'_>, k0: usize);

    /// Writes lane `l` back to local element `k`.
    fn store_lane(&self, b: &mut Batch<'_>, k: usize, l: usize);
}

/// No lane state beyond the points' (a family without hourglass forces).
#[derive(Debug, Clone, Copy, Default)]
pub struct NoLanes;

impl<const W: usize> LaneState<W> for NoLanes {
    #[inline(always)]
    unsafe fn load<'s>(_g: &LaneGroup<'_, W>, slot: &'s mut MaybeUninit<Self>) -> &'s mut Self {
        slot.write(NoLanes)
    }

    fn holds(_a: &StateArrays<'_>, _n: usize) -> bool {
        true
    }

    #[inline(always)]
    fn prefetch(_b: &Batch<'_>, _k0: usize) {}
}

impl<const W: usize> ExtraLanes<W> for NoLanes {
    #[inline(always)]
    unsafe fn store_group(&self, _b: &mut Batch<'_>, _k0: usize) {}

    #[inline(always)]
    fn store_lane(&self, _b: &mut Batch<'_>, _k: usize, _l: usize) {}
}

/// The hourglass forces of W one-point elements, lane-wise, and their energy.
#[derive(Debug, Clone, Copy)]
pub struct HourglassLanes<const W: usize> {
    /// Hourglass generalised forces Q_α, N.
    pub forces: [Vec3<W>; 4],
    /// Hourglass energy so far, J.
    pub energy: Lanes<W>,
}

impl<const W: usize> HourglassLanes<W> {
    /// Every lane and field `z` (a zero state to start from).
    #[cfg(test)]
    pub(crate) fn filled(z: Lanes<W>) -> Self {
        HourglassLanes {
            forces: [[z; 3]; 4],
            energy: z,
        }
    }
}

impl<const W: usize> LaneState<W> for HourglassLanes<W> {
    #[inline(always)]
    unsafe fn load<'s>(g: &LaneGroup<'_, W>, slot: &'s mut MaybeUninit<Self>) -> &'s mut Self {
        let (isa, a, idx) = (g.isa, &g.arrays, g.idx);
        let hp = a.hgq.as_ptr().cast::<f64>();
        let sp = slot.as_mut_ptr();
        // SAFETY: the caller's contract: rows of twelve f64 inside the hourglass array.
        let h0: [Lanes<W>; 8] = Lanes::load_rows(isa, hp, &build(|l| 12 * idx[l]));
        let h1: [Lanes<W>; 4] = Lanes::load_rows(isa, hp, &build(|l| 12 * idx[l] + 8));
        let q = std::ptr::addr_of_mut!((*sp).forces).cast::<Lanes<W>>();
        for (k, h) in h0.iter().chain(&h1).enumerate() {
            q.add(k).write(*h);
        }
        std::ptr::addr_of_mut!((*sp).energy).write(contiguous(isa, a.ehg, idx));
        // SAFETY: every field was written above.
        slot.assume_init_mut()
    }

    fn holds(a: &StateArrays<'_>, n: usize) -> bool {
        a.hgq.len() == n && a.ehg.len() == n
    }

    #[inline(always)]
    fn prefetch(b: &Batch<'_>, k0: usize) {
        prefetch_ahead(b.hgq.as_ptr(), k0 + 2 * W, W);
    }
}

impl<const W: usize> ExtraLanes<W> for HourglassLanes<W> {
    #[inline(always)]
    unsafe fn store_group(&self, b: &mut Batch<'_>, k0: usize) {
        debug_assert!(k0 + W <= b.wp.len());
        let hp = b.hgq.as_mut_ptr().cast::<f64>();
        let q = &self.forces;
        let h0 = [
            q[0][0], q[0][1], q[0][2], q[1][0], q[1][1], q[1][2], q[2][0], q[2][1],
        ];
        let h1 = [q[2][2], q[3][0], q[3][1], q[3][2]];
        // SAFETY: W distinct elements inside the batch (the caller's contract).
        Lanes::store_rows(&h0, hp, &build(|l| 12 * (k0 + l)));
        Lanes::store_rows(&h1, hp, &build(|l| 12 * (k0 + l) + 8));
        b.ehg[k0..k0 + W].copy_from_slice(&self.energy.0);
    }

    #[inline(always)]
    fn store_lane(&self, b: &mut Batch<'_>, k: usize, l: usize) {
        b.ehg[k] = self.energy.0[l];
        for a in 0..4 {
            for c in 0..3 {
                b.hgq[k][a][c] = self.forces[a][c].0[l];
            }
        }
    }
}
