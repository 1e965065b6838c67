//! What the element loop hands an element family and what it hands back: the state at an
//! integration point, a batch's slices of the block's state arrays, the step input, and the
//! gather of nodal lanes and the check and scatter of a lane group's results, written once
//! for every family ([`crate::fe::elements::element::Element`]).

use crate::fe::{
    materials::J2Material,
    simd::{build, Kernel, LaneIsa, Lanes, Vec3},
    tensor::Sym,
};
use std::mem::MaybeUninit;

/// State at one integration point (`repr(C)`: eight f64 in this order, so the lane kernels
/// read W points as W rows of eight f64 and transpose them into lanes, `Lanes::load_rows`).
/// Aligned to 64 bytes, so that a point is exactly one cache line and one aligned 512-bit
/// row (unaligned, every row straddles two lines; `twoball bench machine` row
/// `row_update_512_offset_16b` against `_0b` shows the cost per row).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
#[repr(C, align(64))]
pub struct IntegrationPoint {
    /// Cauchy stress, Pa (Voigt [xx, yy, zz, xy, yz, zx]).
    pub stress: Sym,
    /// Equivalent plastic strain.
    pub eps_p: f64,
    /// Volume this point represents at the last update (J_g w_g or V), m³.
    pub volume: f64,
}

/// Mutable view of one element's state handed to a kernel.
#[derive(Debug)]
pub struct ElementStateMut<'a> {
    /// Integration points (1 for the one-point hex, 8 for B-bar).
    pub points: &'a mut [IntegrationPoint],
    /// Plastic work dissipated in the element so far, J.
    pub plastic_work: &'a mut f64,
    /// Internal energy: stress power integrated over time, ∫ V σ:D dt, J.
    pub internal_energy: &'a mut f64,
    /// Hourglass generalised forces Q_α, N (one-point hex only).
    pub hourglass: &'a mut [[f64; 3]; 4],
    /// Energy stored by the hourglass forces so far, J.
    pub hourglass_energy: &'a mut f64,
}

/// Why the element loop stopped.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ElementFailure {
    /// Non-positive Jacobian (value) at the element.
    Inverted(f64),
    /// Non-finite force or stress.
    NonFinite,
}

/// One batch of elements of the element loop: its slices of every state array.
pub(crate) struct Batch<'a> {
    pub(crate) conn: &'a [[u32; 8]],
    pub(crate) pts: &'a mut [IntegrationPoint],
    /// The law's history of the batch's points ([`Hardening::HISTORY`] values each).
    pub(crate) hist: &'a mut [f64],
    pub(crate) wp: &'a mut [f64],
    pub(crate) ie: &'a mut [f64],
    pub(crate) hgq: &'a mut [[[f64; 3]; 4]],
    pub(crate) ehg: &'a mut [f64],
    pub(crate) vol: &'a mut [f64],
    pub(crate) dtc: &'a mut [f64],
    pub(crate) f: Forces<'a>,
}

/// Where a batch puts its elements' internal forces.
pub(crate) enum Forces<'a> {
    /// One 8-node force block per element of the batch (parallel loops: the blocks are
    /// summed per node afterwards, in element order).
    Blocks(&'a mut [[[f64; 3]; 8]]),
    /// Added straight into the nodal force array, rows [x, y, z, 0] (one thread, elements in
    /// order: the same sums, in the same order, as the blocks summed per node; the padding
    /// lets a full lane group add each node's force as one 256-bit row).
    Nodes(&'a mut [[f64; 4]]),
}

/// Result of a batch: smallest critical step and its element, or the first failing element.
pub(crate) type BatchResult = Result<(f64, usize), (usize, ElementFailure)>;

/// What a lane group's update hands back for every lane: nodal forces (N), volume (m³),
/// smallest Jacobian (m³, ≤ 0 or NaN: inverted) and Courant limit (s).
pub(crate) struct LaneResult<'r, const W: usize> {
    pub(crate) force: &'r [Vec3<W>; 8],
    pub(crate) volume: Lanes<W>,
    pub(crate) min_jacobian: Lanes<W>,
    pub(crate) dt_crit: Lanes<W>,
}

/// Checks the `live` lanes of a group starting at local element `k0`, records their volume,
/// step and forces, and updates the batch minimum; fails on the first element (in order)
/// that is inverted or has a non-finite force, as the per-element check would (a failing
/// group's forces are then not all written: the solver stops anyway).
#[inline(always)]
pub(crate) fn finish_lanes<const W: usize>(
    r: &LaneResult<'_, W>,
    b: &mut Batch<'_>,
    k0: usize,
    live: usize,
    base: usize,
    best: &mut (f64, usize),
) -> std::result::Result<(), (usize, ElementFailure)> {
    // Σ 0·f over the 24 force components: ±0 when all are finite, NaN when one is ±∞ or NaN.
    let mut nonfinite = r.volume.splat_like(0.0);
    for fi in r.force {
        for c in fi {
            nonfinite += *c * 0.0;
        }
    }
    for l in 0..live {
        let k = k0 + l;
        let j = r.min_jacobian.0[l];
        if j.is_nan() || j <= 0.0 {
            return Err((base + k, ElementFailure::Inverted(j)));
        }
        if nonfinite.0[l].is_nan() {
            return Err((base + k, ElementFailure::NonFinite));
        }
        b.vol[k] = r.volume.0[l];
        b.dtc[k] = r.dt_crit.0[l];
        match &mut b.f {
            Forces::Blocks(_) if live == W => {}
            Forces::Blocks(f) => {
                for (i, fi) in r.force.iter().enumerate() {
                    for d in 0..3 {
                        f[k][i][d] = fi[d].0[l];
                    }
                }
            }
            Forces::Nodes(_) if live == W => {}
            Forces::Nodes(f) => {
                for (&n, fi) in b.conn[k].iter().zip(r.force) {
                    // SAFETY: the caller checked every node index of the range < len of x,
                    // and f has at least that length.
                    let g = unsafe { f.get_unchecked_mut(n as usize) };
                    for d in 0..3 {
                        g[d] += fi[d].0[l];
                    }
                }
            }
        }
        let dtc = r.dt_crit.0[l];
        if dtc < best.0 {
            *best = (dtc, base + k);
        }
    }
    // A full group's forces leave as rows: transposed in registers, then one row per node
    // (added into padded nodal rows) or three 512-bit rows per element (its force block),
    // instead of 24 scalar stores or read-add-writes per element.
    if live == W {
        match &mut b.f {
            // SAFETY: the caller checked every node index of the range < len of f.
            Forces::Nodes(f) => unsafe {
                Lanes::add_node_rows(r.force, f.as_mut_ptr(), &b.conn[k0..k0 + W])
            },
            Forces::Blocks(f) => {
                let c: [Lanes<W>; 24] = build(|q| r.force[q / 3][q % 3]);
                let p = f[k0..k0 + W].as_mut_ptr().cast::<f64>();
                let rows: [usize; W] = build(|l| 24 * l);
                // SAFETY: W blocks of 24 f64 from element k0 (a full group inside the batch).
                unsafe {
                    Lanes::store_rows::<8>(c[..8].try_into().unwrap(), p, &rows);
                    Lanes::store_rows::<8>(c[8..16].try_into().unwrap(), p.add(8), &rows);
                    Lanes::store_rows::<8>(c[16..].try_into().unwrap(), p.add(16), &rows);
                }
            }
        }
    }
    Ok(())
}

/// The block's state as an element family's kernel timing reads it (the block's arrays, read
/// only; [`crate::fe::elements::block::ElementBlock::state`]).
pub(crate) struct BlockState<'a> {
    /// Material constants.
    pub(crate) material: &'a J2Material,
    /// Integration points, the family's points per element each.
    pub(crate) points: &'a [IntegrationPoint],
    /// Plastic work per element, J.
    pub(crate) plastic_work: &'a [f64],
    /// Internal energy per element, J.
    pub(crate) internal_energy: &'a [f64],
    /// Hourglass coefficient ε_hg (one-point hex).
    pub(crate) hourglass_coeff: f64,
    /// Hourglass forces per element, N.
    pub(crate) hourglass: &'a [[[f64; 3]; 4]],
    /// Hourglass energy per element, J.
    pub(crate) hourglass_energy: &'a [f64],
}

/// Times `repeats` updates of the lane state `$st0` (restarted every 64 updates, so that it
/// does not drift far from a real step's) by `$update`, with `$st`, `$xr`, `$vr` bound to
/// the state and the nodal lanes `$xe`, `$ve` (through `black_box`, as is every update's
/// output, so none of the arithmetic can be optimised out). A macro, so that it expands in
/// place: a helper taking the update as a closure could see that closure compiled out of
/// line, without the target features, and time the wrong code.
macro_rules! time_updates {
    ($repeats:expr, $xe:expr, $ve:expr, $st0:expr, |$st:ident, $xr:ident, $vr:ident| $update:expr) => {{
        let st0 = $st0;
        let mut $st = st0;
        let start = std::time::Instant::now();
        for r in 0..$repeats {
            if r % 64 == 0 {
                $st = st0;
            }
            let ($xr, $vr) = (std::hint::black_box($xe), std::hint::black_box($ve));
            std::hint::black_box(&$update);
        }
        start.elapsed()
    }};
}
pub(crate) use time_updates;

/// Lane l = `a[idx[l]]` for one f64 per element: a plain vector load when `idx` is a run
/// of consecutive elements (every full group), else W loads.
#[inline(always)]
pub(crate) fn contiguous<const W: usize>(isa: LaneIsa<W>, a: &[f64], idx: &[usize; W]) -> Lanes<W> {
    let k0 = idx[0];
    if idx[W - 1] == k0 + W - 1 {
        let mut r = [0.0; W];
        r.copy_from_slice(&a[k0..k0 + W]);
        return isa.lanes(r);
    }
    isa.lanes(build(|l| a[idx[l]]))
}

/// Nodal coordinates and velocities of the elements `idx` (local indices into `conn`) into
/// lanes, by [`Lanes::load_vec3`] (on eight lanes: node rows loaded and transposed in
/// registers). Writes every slot of `xe` and `ve` and returns them initialised: the
/// caller's arrays need no zero fill first (it was a 1.5 KB `memset` call per lane group).
#[inline(always)]
pub(crate) fn gather_nodes<'e, const W: usize>(
    isa: LaneIsa<W>,
    idx: &[usize; W],
    conn: &[[u32; 8]],
    x: &[[f64; 3]],
    v: &[[f64; 3]],
    xe: &'e mut MaybeUninit<[[Lanes<W>; 3]; 8]>,
    ve: &'e mut MaybeUninit<[[Lanes<W>; 3]; 8]>,
) -> (&'e [[Lanes<W>; 3]; 8], &'e [[Lanes<W>; 3]; 8]) {
    let (xq, vq) = (
        xe.as_mut_ptr().cast::<Vec3<W>>(),
        ve.as_mut_ptr().cast::<Vec3<W>>(),
    );
    for i in 0..8 {
        let nodes: [u32; W] = build(|l| conn[idx[l]][i]);
        // SAFETY: update_range checked every node index of the range < len of x and v.
        // Slot i < 8 of the [Vec3; 8] arrays, each written once.
        unsafe {
            xq.add(i).write(Lanes::load_vec3(isa, x.as_ptr(), &nodes));
            vq.add(i).write(Lanes::load_vec3(isa, v.as_ptr(), &nodes));
        }
    }
    // SAFETY: all eight slots of both arrays were written above.
    unsafe { (xe.assume_init_ref(), ve.assume_init_ref()) }
}

/// What every element of a batch needs besides its own state.
#[derive(Clone, Copy)]
pub(crate) struct StepInput<'a> {
    /// Nodal coordinates at t^{n+1}, m.
    pub(crate) x: &'a [[f64; 3]],
    /// Nodal velocities at t^{n+1/2}, m/s.
    pub(crate) v: &'a [[f64; 3]],
    /// Step, s.
    pub(crate) dt: f64,
    pub(crate) mat: &'a J2Material,
    /// Hourglass coefficient (one-point hex; 0 = off).
    pub(crate) hg: f64,
    /// The kernel path (with its instruction-set token).
    pub(crate) kernel: Kernel,
}
