//! SIMD lanes for the element kernels: a value per element of a group of W elements
//! (structure of arrays), with the arithmetic written once, lane-wise.
//!
//! Every operation is a fixed-length loop over `[f64; W]` marked `#[inline(always)]`, so inside
//! a kernel compiled with `#[target_feature(enable = "avx2,fma")]` the compiler turns each
//! into one vector instruction, and the same source compiles to scalar code on any other
//! target; eight lanes on x86-64 use AVX-512 intrinsics, which pin the 512-bit form. The
//! results are identical on every path: no operation is fused or reordered (Rust never
//! contracts a·b + c into an FMA on its own), so lane l computes exactly what the scalar
//! formula computes for element l.
//!
//! Every value carries its [`LaneIsa`] token (a zero-sized field), so a `Lanes<8>` exists
//! only where AVX-512F was detected, and its safe operators cannot reach an instruction the
//! CPU lacks.

use super::isa::LaneIsa;
use std::mem::MaybeUninit;
use std::ops::{Add, AddAssign, Div, Mul, Neg, Sub, SubAssign};

/// One f64 per lane, with the token that proves W-lane arithmetic legal on this CPU (the
/// token is zero-sized: the layout is the array's).
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(transparent)]
pub struct Lanes<const W: usize>(pub [f64; W], pub LaneIsa<W>);

/// Eight lanes as one AVX-512 register. The lane loops below compile to whatever vector width
/// the compiler prefers for the calling kernel's target features, and for eight f64 lanes
/// that was two 256-bit halves (twice the instructions, and register spills); these ops pin
/// the 512-bit form. Only reached when W = 8, with a `LaneIsa<8>` token in hand: on x86-64
/// that token exists only where AVX-512F was detected.
#[cfg(target_arch = "x86_64")]
mod avx512 {
    use super::{LaneIsa, Lanes};
    use std::arch::x86_64::*;

    /// The same 64 bytes as eight f64 lanes or as one AVX-512 register. Moving lanes in and
    /// out of registers through this union, not `_mm512_loadu_pd`/`_mm512_storeu_pd`, keeps
    /// the moves free of the standard library's unsafe-precondition checks that builds with
    /// debug assertions (the test profile) run inside `ptr::read_unaligned`: each check made
    /// the value's address observable, so every lane value went through the stack and the
    /// element kernels ran about nine times slower under `cargo test` than in release.
    #[repr(C)]
    union Pun<const W: usize> {
        lanes: [f64; W],
        reg: __m512d,
    }

    #[inline(always)]
    pub(super) fn load<const W: usize>(a: Lanes<W>) -> __m512d {
        debug_assert_eq!(W, 8);
        // SAFETY: W == 8, so both fields are the same 64 bytes, and any bits are a valid
        // __m512d.
        unsafe { Pun { lanes: a.0 }.reg }
    }

    #[inline(always)]
    pub(super) fn store<const W: usize>(v: __m512d, isa: LaneIsa<W>) -> Lanes<W> {
        debug_assert_eq!(W, 8);
        // SAFETY: W == 8: the 64 bytes written are the W f64 read back.
        Lanes(unsafe { Pun::<W> { reg: v }.lanes }, isa)
    }

    macro_rules! bin {
        ($name:ident, $intr:ident) => {
            #[inline(always)]
            pub(super) fn $name<const W: usize>(a: Lanes<W>, b: Lanes<W>) -> Lanes<W> {
                // SAFETY: W = 8, and the token `a.1` proves AVX-512F present.
                store(unsafe { $intr(load(a), load(b)) }, a.1)
            }
        };
    }
    bin!(add, _mm512_add_pd);
    bin!(sub, _mm512_sub_pd);
    bin!(mul, _mm512_mul_pd);
    bin!(div, _mm512_div_pd);

    /// The x, y and z lanes of eight 3-vectors `base[nodes[l]]`, l = 0..8, by row loads and
    /// a register transpose (no gather instruction: on some AVX-512 cores, AMD's Zen 4 among
    /// them, one eight-lane gather costs as much as a dozen shuffles). Each 512-bit register
    /// holds two rows, as a masked load of three f64 into its low half and one into its high
    /// half (the high half's load starts four f64 before the row, with those four masked off:
    /// masked-off elements are never read); two unpacks and three 128-bit block shuffles per
    /// pair of registers then leave x, y and z of the eight rows in lane order.
    ///
    /// # Safety
    /// W = 8 (AVX-512F: `isa`), and every `base.add(nodes[l])` in bounds of one allocation.
    #[inline(always)]
    pub(super) unsafe fn load_vec3<const W: usize>(
        isa: LaneIsa<W>,
        base: *const [f64; 3],
        nodes: &[u32; W],
    ) -> [Lanes<W>; 3] {
        // A register holds rows (p, q) in its low and high half: A = (0, 2), B = (1, 3),
        // C = (4, 6), D = (5, 7), so that the block shuffles below put lane l in place l.
        // (A macro, not a closure: a closure can be compiled out of line, without AVX-512.)
        macro_rules! pair {
            ($p:expr, $q:expr) => {{
                let lo = _mm512_maskz_loadu_pd(0x07, base.add(nodes[$p] as usize).cast());
                let hi = base.add(nodes[$q] as usize).cast::<f64>().wrapping_sub(4);
                _mm512_mask_loadu_pd(lo, 0x70, hi)
            }};
        }
        let (a, b, c, d) = (pair!(0, 2), pair!(1, 3), pair!(4, 6), pair!(5, 7));
        // t0 = x0 x1 z0 z1 | x2 x3 z2 z3, t1 = y0 y1 . . | y2 y3 . ., t2, t3 the same for 4..8.
        let t0 = _mm512_unpacklo_pd(a, b);
        let t1 = _mm512_unpackhi_pd(a, b);
        let t2 = _mm512_unpacklo_pd(c, d);
        let t3 = _mm512_unpackhi_pd(c, d);
        [
            store(_mm512_shuffle_f64x2::<0x88>(t0, t2), isa),
            store(_mm512_shuffle_f64x2::<0x88>(t1, t3), isa),
            store(_mm512_shuffle_f64x2::<0xDD>(t0, t2), isa),
        ]
    }

    /// The 8 x 8 transpose: `out[j]` lane i = `r[i]` lane j (three stages: pairs, 128-bit
    /// blocks, 256-bit halves; 24 shuffles).
    #[inline(always)]
    unsafe fn transpose8(r: [__m512d; 8]) -> [__m512d; 8] {
        let t0 = _mm512_unpacklo_pd(r[0], r[1]);
        let t1 = _mm512_unpackhi_pd(r[0], r[1]);
        let t2 = _mm512_unpacklo_pd(r[2], r[3]);
        let t3 = _mm512_unpackhi_pd(r[2], r[3]);
        let t4 = _mm512_unpacklo_pd(r[4], r[5]);
        let t5 = _mm512_unpackhi_pd(r[4], r[5]);
        let t6 = _mm512_unpacklo_pd(r[6], r[7]);
        let t7 = _mm512_unpackhi_pd(r[6], r[7]);
        let u0 = _mm512_shuffle_f64x2::<0x88>(t0, t2);
        let u1 = _mm512_shuffle_f64x2::<0xDD>(t0, t2);
        let u2 = _mm512_shuffle_f64x2::<0x88>(t1, t3);
        let u3 = _mm512_shuffle_f64x2::<0xDD>(t1, t3);
        let u4 = _mm512_shuffle_f64x2::<0x88>(t4, t6);
        let u5 = _mm512_shuffle_f64x2::<0xDD>(t4, t6);
        let u6 = _mm512_shuffle_f64x2::<0x88>(t5, t7);
        let u7 = _mm512_shuffle_f64x2::<0xDD>(t5, t7);
        [
            _mm512_shuffle_f64x2::<0x88>(u0, u4),
            _mm512_shuffle_f64x2::<0x88>(u2, u6),
            _mm512_shuffle_f64x2::<0x88>(u1, u5),
            _mm512_shuffle_f64x2::<0x88>(u3, u7),
            _mm512_shuffle_f64x2::<0xDD>(u0, u4),
            _mm512_shuffle_f64x2::<0xDD>(u2, u6),
            _mm512_shuffle_f64x2::<0xDD>(u1, u5),
            _mm512_shuffle_f64x2::<0xDD>(u3, u7),
        ]
    }

    /// Columns 0..C (C ≤ 8) of eight rows starting at `base.add(rows[l])`.
    ///
    /// # Safety
    /// W = 8 (AVX-512F: `isa`), and `base.add(rows[l] + c)` in bounds for every l and c < C.
    #[inline(always)]
    pub(super) unsafe fn load_rows<const W: usize, const C: usize>(
        isa: LaneIsa<W>,
        base: *const f64,
        rows: &[usize; W],
    ) -> [Lanes<W>; C] {
        let mask = ((1u32 << C) - 1) as __mmask8;
        let mut r = [_mm512_setzero_pd(); 8];
        for (l, x) in r.iter_mut().enumerate() {
            *x = _mm512_maskz_loadu_pd(mask, base.add(rows[l]));
        }
        let t = transpose8(r);
        let mut out = [isa.splat(0.0); C];
        for (c, o) in out.iter_mut().enumerate() {
            *o = store(t[c], isa);
        }
        out
    }

    /// Adds the three force columns of each of eight nodes to the padded nodal rows
    /// `f4[conn[l][i]]`, lane (element) by lane in order, nodes in order within a lane: each
    /// row gets one 256-bit load, add and store (the pad component gets −0.0, which leaves
    /// every value, ±0 included, as it was).
    ///
    /// # Safety
    /// W = 8 (AVX-512F: the forces' token), every `conn[l][i]` < the length of `f4`.
    #[inline(always)]
    pub(super) unsafe fn add_node_rows<const W: usize>(
        force: &[[Lanes<W>; 3]; 8],
        f4: *mut [f64; 4],
        conn: &[[u32; 8]],
    ) {
        let nz = _mm512_set1_pd(-0.0);
        // rows[i][q], q = 0..4: node i's rows [x, y, z, −0] of lanes (0, 2), (1, 3), (4, 6),
        // (5, 7) as low and high 256-bit halves: two unpacks pair x with y and z with −0,
        // one two-source permute per pair of rows (8 shuffles per node).
        let lo = _mm512_set_epi64(11, 10, 3, 2, 9, 8, 1, 0);
        let hi = _mm512_set_epi64(15, 14, 7, 6, 13, 12, 5, 4);
        let mut rows = [[_mm512_setzero_pd(); 4]; 8];
        for i in 0..8 {
            let (x, y, z) = (load(force[i][0]), load(force[i][1]), load(force[i][2]));
            let t0 = _mm512_unpacklo_pd(x, y); // X0 Y0 X2 Y2 X4 Y4 X6 Y6
            let t1 = _mm512_unpackhi_pd(x, y); // X1 Y1 X3 Y3 ...
            let t2 = _mm512_unpacklo_pd(z, nz); // Z0 N  Z2 N ...
            let t3 = _mm512_unpackhi_pd(z, nz);
            rows[i][0] = _mm512_permutex2var_pd(t0, lo, t2); // lanes 0, 2
            rows[i][1] = _mm512_permutex2var_pd(t1, lo, t3); // lanes 1, 3
            rows[i][2] = _mm512_permutex2var_pd(t0, hi, t2); // lanes 4, 6
            rows[i][3] = _mm512_permutex2var_pd(t1, hi, t3); // lanes 5, 7
        }
        for (l, c) in conn.iter().enumerate().take(8) {
            let (p, h) = match l {
                0 => (0, false),
                1 => (1, false),
                2 => (0, true),
                3 => (1, true),
                4 => (2, false),
                5 => (3, false),
                6 => (2, true),
                _ => (3, true),
            };
            for i in 0..8 {
                let r = if h {
                    _mm512_extractf64x4_pd::<1>(rows[i][p])
                } else {
                    _mm512_castpd512_pd256(rows[i][p])
                };
                let g = f4.add(c[i] as usize).cast::<f64>();
                _mm256_storeu_pd(g, _mm256_add_pd(_mm256_loadu_pd(g), r));
            }
        }
    }

    /// Writes columns `cols` (C ≤ 8) into eight rows starting at `base.add(rows[l])`.
    ///
    /// # Safety
    /// As [`load_rows`], for writing; the rows must not overlap.
    #[inline(always)]
    pub(super) unsafe fn store_rows<const W: usize, const C: usize>(
        cols: &[Lanes<W>; C],
        base: *mut f64,
        rows: &[usize; W],
    ) {
        let mask = ((1u32 << C) - 1) as __mmask8;
        let mut c8 = [_mm512_setzero_pd(); 8];
        for (c, x) in cols.iter().enumerate() {
            c8[c] = load(*x);
        }
        let t = transpose8(c8);
        for (l, x) in t.iter().enumerate() {
            _mm512_mask_storeu_pd(base.add(rows[l]), mask, *x);
        }
    }

    /// −a by flipping the sign bit (exactly what scalar negation does, −0.0 included).
    #[inline(always)]
    pub(super) fn neg<const W: usize>(a: Lanes<W>) -> Lanes<W> {
        // SAFETY: W = 8, and the token `a.1` proves AVX-512F present.
        store(
            unsafe {
                _mm512_castsi512_pd(_mm512_xor_si512(
                    _mm512_castpd_si512(load(a)),
                    _mm512_set1_epi64(i64::MIN),
                ))
            },
            a.1,
        )
    }

    #[inline(always)]
    pub(super) fn sqrt<const W: usize>(a: Lanes<W>) -> Lanes<W> {
        // SAFETY: W = 8, and the token `a.1` proves AVX-512F present.
        store(unsafe { _mm512_sqrt_pd(load(a)) }, a.1)
    }
}

/// `[f(0), f(1), ..., f(N − 1)]`, always inlined: `std::array::from_fn` and `array::map`
/// are generic functions the compiler may leave out of line, and an out-of-line copy is
/// compiled without the calling kernel's target features (scalar code). The closure `f`
/// itself is still a function of its own, which the compiler may leave out of line once
/// its caller is instantiated in more than one place; so the lane kernels use plain loops,
/// and `build` serves the element loop's small index arrays.
#[inline(always)]
pub fn build<T: Copy, const N: usize>(mut f: impl FnMut(usize) -> T) -> [T; N] {
    let mut a = MaybeUninit::<[T; N]>::uninit();
    let p = a.as_mut_ptr().cast::<T>();
    for i in 0..N {
        // SAFETY: slot i < N of the array, written once.
        unsafe { p.add(i).write(f(i)) };
    }
    // SAFETY: all N slots were written above.
    unsafe { a.assume_init() }
}

impl<const W: usize> Lanes<W> {
    /// The token this value carries (to build more lanes of the same width).
    #[inline(always)]
    pub fn isa(self) -> LaneIsa<W> {
        self.1
    }

    /// Every lane equal to `v`, with this value's token.
    #[inline(always)]
    pub fn splat_like(self, v: f64) -> Self {
        Lanes([v; W], self.1)
    }

    /// The x, y and z lanes of W 3-vectors `base[nodes[l]]` (nodal coordinates or velocities
    /// of one node of W elements). Eight lanes (AVX-512) load rows and transpose them in
    /// registers; other widths load the W values of each component.
    ///
    /// # Safety
    /// Every `base.add(nodes[l])` must be in bounds of the allocation `base` points into.
    #[inline(always)]
    pub unsafe fn load_vec3(isa: LaneIsa<W>, base: *const [f64; 3], nodes: &[u32; W]) -> Vec3<W> {
        #[cfg(target_arch = "x86_64")]
        if W == 8 {
            return avx512::load_vec3(isa, base, nodes);
        }
        let mut out = [isa.splat(0.0); 3];
        for (d, o) in out.iter_mut().enumerate() {
            for l in 0..W {
                o.0[l] = (*base.add(nodes[l] as usize))[d];
            }
        }
        out
    }

    /// Columns 0..C of W rows of f64: lane l of column c = `*base.add(rows[l] + c)`. With
    /// eight lanes (AVX-512) the rows are read as vectors and transposed in registers, the
    /// cheap way to turn an array of structures (a field per row) into lanes.
    ///
    /// # Safety
    /// Every `base.add(rows[l] + c)`, c < C ≤ 8, must be in bounds of the allocation `base`
    /// points into.
    #[inline(always)]
    pub unsafe fn load_rows<const C: usize>(
        isa: LaneIsa<W>,
        base: *const f64,
        rows: &[usize; W],
    ) -> [Self; C] {
        #[cfg(target_arch = "x86_64")]
        if W == 8 && C <= 8 {
            return avx512::load_rows(isa, base, rows);
        }
        let mut out = [isa.splat(0.0); C];
        for (c, o) in out.iter_mut().enumerate() {
            for l in 0..W {
                o.0[l] = *base.add(rows[l] + c);
            }
        }
        out
    }

    /// Adds the nodal forces of a full group (W elements `conn`) into the padded nodal array
    /// `f4`, element by element in lane order, nodes in order: the same additions as the
    /// scalar `f4[n][d] += force[i][d].0[l]` loop, in the same order.
    ///
    /// # Safety
    /// Every node of `conn` (at least W rows) < `f4.len()`-equivalent allocation of `f4`.
    #[inline(always)]
    pub unsafe fn add_node_rows(force: &[Vec3<W>; 8], f4: *mut [f64; 4], conn: &[[u32; 8]]) {
        #[cfg(target_arch = "x86_64")]
        if W == 8 {
            return avx512::add_node_rows(force, f4, conn);
        }
        for (l, c) in conn.iter().enumerate().take(W) {
            for (i, fi) in force.iter().enumerate() {
                let g = &mut *f4.add(c[i] as usize);
                for d in 0..3 {
                    g[d] += fi[d].0[l];
                }
            }
        }
    }

    /// The inverse of [`Lanes::load_rows`]: `*base.add(rows[l] + c)` = lane l of `cols[c]`.
    ///
    /// # Safety
    /// As [`Lanes::load_rows`], for writing; the W rows must not overlap (no repeated row).
    #[inline(always)]
    pub unsafe fn store_rows<const C: usize>(cols: &[Self; C], base: *mut f64, rows: &[usize; W]) {
        #[cfg(target_arch = "x86_64")]
        if W == 8 && C <= 8 {
            return avx512::store_rows(cols, base, rows);
        }
        for (c, col) in cols.iter().enumerate() {
            for l in 0..W {
                *base.add(rows[l] + c) = col.0[l];
            }
        }
    }

    /// Lane-wise square root.
    #[inline(always)]
    pub fn sqrt(self) -> Self {
        #[cfg(target_arch = "x86_64")]
        if W == 8 {
            return avx512::sqrt(self);
        }
        self.map(f64::sqrt)
    }

    /// Lane-wise `f(self)`, with this value's token.
    #[inline(always)]
    fn map(self, f: impl Fn(f64) -> f64) -> Self {
        let mut r = self.0;
        for x in &mut r {
            *x = f(*x);
        }
        Lanes(r, self.1)
    }

    /// Lane-wise `f(self, o)`, with this value's token.
    #[inline(always)]
    fn zip_with(self, o: Self, f: impl Fn(f64, f64) -> f64) -> Self {
        let mut r = self.0;
        for l in 0..W {
            r[l] = f(r[l], o.0[l]);
        }
        Lanes(r, self.1)
    }

    /// Lane-wise maximum (the `f64::max` rule: a NaN lane yields the other operand).
    #[inline(always)]
    pub fn max(self, o: Self) -> Self {
        self.zip_with(o, f64::max)
    }

    /// Lane-wise minimum (the `f64::min` rule: a NaN lane yields the other operand).
    #[inline(always)]
    pub fn min(self, o: Self) -> Self {
        self.zip_with(o, f64::min)
    }

    /// Lane-wise reciprocal 1/x.
    #[inline(always)]
    pub fn recip(self) -> Self {
        self.splat_like(1.0) / self
    }

    /// Lane-wise `self > o`.
    #[inline(always)]
    pub fn gt(self, o: Self) -> [bool; W] {
        let mut m = [false; W];
        for l in 0..W {
            m[l] = self.0[l] > o.0[l];
        }
        m
    }
}

/// Lane `l` of `a` where `m[l]`, else of `b`.
#[inline(always)]
pub fn select<const W: usize>(m: [bool; W], a: Lanes<W>, b: Lanes<W>) -> Lanes<W> {
    let mut r = b.0;
    for l in 0..W {
        if m[l] {
            r[l] = a.0[l];
        }
    }
    Lanes(r, b.1)
}

macro_rules! lane_op {
    ($tr:ident, $f:ident, $op:tt) => {
        impl<const W: usize> $tr for Lanes<W> {
            type Output = Self;
            #[inline(always)]
            fn $f(self, o: Self) -> Self {
                #[cfg(target_arch = "x86_64")]
                if W == 8 {
                    return avx512::$f(self, o);
                }
                self.zip_with(o, |a, b| a $op b)
            }
        }
        impl<const W: usize> $tr<f64> for Lanes<W> {
            type Output = Self;
            #[inline(always)]
            fn $f(self, o: f64) -> Self {
                #[cfg(target_arch = "x86_64")]
                if W == 8 {
                    return avx512::$f(self, self.splat_like(o));
                }
                self.map(|a| a $op o)
            }
        }
    };
}
lane_op!(Add, add, +);
lane_op!(Sub, sub, -);
lane_op!(Mul, mul, *);
lane_op!(Div, div, /);

/// A commutative operator with a scalar on the left: `s op lanes`, every lane `lane op s`.
macro_rules! scalar_lane_op {
    ($tr:ident, $f:ident, $op:tt) => {
        impl<const W: usize> $tr<Lanes<W>> for f64 {
            type Output = Lanes<W>;
            #[inline(always)]
            fn $f(self, o: Lanes<W>) -> Lanes<W> {
                #[cfg(target_arch = "x86_64")]
                if W == 8 {
                    return avx512::$f(o.splat_like(self), o);
                }
                o.map(|a| a $op self)
            }
        }
    };
}
scalar_lane_op!(Mul, mul, *);
scalar_lane_op!(Add, add, +);

impl<const W: usize> Neg for Lanes<W> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        #[cfg(target_arch = "x86_64")]
        if W == 8 {
            return avx512::neg(self);
        }
        self.map(|x| -x)
    }
}

impl<const W: usize> AddAssign for Lanes<W> {
    #[inline(always)]
    fn add_assign(&mut self, o: Self) {
        *self = *self + o;
    }
}

impl<const W: usize> SubAssign for Lanes<W> {
    #[inline(always)]
    fn sub_assign(&mut self, o: Self) {
        *self = *self - o;
    }
}

/// A 3-vector of lanes.
pub type Vec3<const W: usize> = [Lanes<W>; 3];

/// Cross product a × b, lane-wise.
#[inline(always)]
pub fn cross<const W: usize>(a: &Vec3<W>, b: &Vec3<W>) -> Vec3<W> {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// Dot product a · b, lane-wise.
#[inline(always)]
pub fn dot<const W: usize>(a: &Vec3<W>, b: &Vec3<W>) -> Lanes<W> {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn four() -> LaneIsa<4> {
        LaneIsa::detect().expect("four lanes run everywhere")
    }

    fn one() -> LaneIsa<1> {
        LaneIsa::detect().expect("one lane runs everywhere")
    }

    #[test]
    fn lanes_compute_what_scalars_compute() {
        let a = four().lanes([1.5, -2.0, 3.25, 0.1]);
        let b = four().lanes([0.3, 4.0, -1.0, 7.0]);
        let r = (a * b + a - b * 2.0) / (b + 10.0);
        for l in 0..4 {
            let (x, y) = (a.0[l], b.0[l]);
            assert_eq!(r.0[l], (x * y + x - y * 2.0) / (y + 10.0));
        }
        let m = a.gt(b);
        assert_eq!(m, [true, false, true, false]);
        assert_eq!(select(m, a, b).0, [1.5, 4.0, 3.25, 7.0]);
        // Rows to lanes and back, eight lanes (the AVX-512 transpose where the CPU has it)
        // and four (scalar), with a partial row width.
        let data: Vec<f64> = (0..100).map(|i| i as f64 * 1.5 - 7.0).collect();
        let rows8 = [3, 17, 40, 41, 60, 9, 90, 0];
        if let Some(isa) = LaneIsa::<8>::detect() {
            // SAFETY: every row + c < 100.
            let cols: [Lanes<8>; 7] = unsafe { Lanes::load_rows(isa, data.as_ptr(), &rows8) };
            for (c, col) in cols.iter().enumerate() {
                for l in 0..8 {
                    assert_eq!(col.0[l], data[rows8[l] + c], "column {c} lane {l}");
                }
            }
            let mut back = vec![0.0; 100];
            let rows_disjoint = [0, 10, 20, 30, 40, 50, 60, 70];
            // SAFETY: as above, rows do not overlap.
            unsafe { Lanes::store_rows(&cols, back.as_mut_ptr(), &rows_disjoint) };
            for l in 0..8 {
                for c in 0..10 {
                    let want = if c < 7 { data[rows8[l] + c] } else { 0.0 };
                    assert_eq!(back[rows_disjoint[l] + c], want, "row {l} column {c}");
                }
            }
        }
        let rows4 = [5, 1, 33, 2];
        // SAFETY: every row + c < 100.
        let cols: [Lanes<4>; 3] = unsafe { Lanes::load_rows(four(), data.as_ptr(), &rows4) };
        for (c, col) in cols.iter().enumerate() {
            for l in 0..4 {
                assert_eq!(col.0[l], data[rows4[l] + c]);
            }
        }
        let c = cross(
            &[one().splat(1.0), one().splat(0.0), one().splat(0.0)],
            &[one().splat(0.0), one().splat(1.0), one().splat(0.0)],
        );
        assert_eq!(c.map(|v| v.0[0]), [0.0, 0.0, 1.0]);
    }

    /// Node rows to lanes: every lane of x, y, z equals the node's component, for nodes at
    /// both ends of the array (the high half's masked load starts before node 0; node 0 and
    /// the last node are where a read past the rows would leave the allocation).
    #[test]
    fn node_rows_load_into_lanes() {
        let nodes: Vec<[f64; 3]> = (0..37)
            .map(|n| [n as f64 + 0.25, -(n as f64) * 3.0, 1e-300 * n as f64])
            .collect();
        fn check<const W: usize>(isa: LaneIsa<W>, nodes: &[[f64; 3]], pick: &[u32; W]) {
            // SAFETY: every index < nodes.len().
            let got = unsafe { Lanes::load_vec3(isa, nodes.as_ptr(), pick) };
            for (d, lane) in got.iter().enumerate() {
                for l in 0..W {
                    let want = nodes[pick[l] as usize][d];
                    assert_eq!(
                        lane.0[l].to_bits(),
                        want.to_bits(),
                        "lane {l} component {d}"
                    );
                }
            }
        }
        check(four(), &nodes, &[36, 0, 5, 36]);
        if let Some(isa) = LaneIsa::<8>::detect() {
            check(isa, &nodes, &[0, 36, 1, 35, 7, 0, 36, 19]);
            check(isa, &nodes, &[36, 0, 36, 0, 2, 3, 4, 5]);
        }
    }

    /// The scalar loop `add_node_rows` must reproduce: element (lane) by element, nodes in
    /// order, component by component.
    fn add_in_order<const W: usize>(force: &[Vec3<W>; 8], f4: &mut [[f64; 4]], conn: &[[u32; 8]]) {
        for (l, c) in conn.iter().enumerate().take(W) {
            for (i, fi) in force.iter().enumerate() {
                for d in 0..3 {
                    f4[c[i] as usize][d] += fi[d].0[l];
                }
            }
        }
    }

    /// Forces whose sums depend on their order (1e16 + 1 − 1e16 ≠ 1e16 − 1e16 + 1) and signed
    /// zeros, on nodes shared by several lanes, as a lane group of neighbouring elements has.
    fn order_sensitive_group<const W: usize>(isa: LaneIsa<W>) -> ([Vec3<W>; 8], Vec<[u32; 8]>) {
        let vals = [1e16, 1.0, -1e16, -0.0, 0.5, -3.25, 0.0, 7e-300];
        let mut force = [[isa.splat(0.0); 3]; 8];
        for (i, fi) in force.iter_mut().enumerate() {
            for (d, c) in fi.iter_mut().enumerate() {
                for l in 0..W {
                    c.0[l] = vals[(3 * i + 5 * d + 3 * l) % vals.len()];
                }
            }
        }
        // Node 0 in every element at a different local index; nodes 1..=3 shared by pairs.
        let conn = (0..W as u32)
            .map(|l| {
                let mut c = [0u32; 8];
                for (i, n) in c.iter_mut().enumerate() {
                    *n = if i as u32 == l % 8 {
                        0
                    } else {
                        1 + (l / 2 + i as u32) % 9
                    };
                }
                c
            })
            .collect();
        (force, conn)
    }

    #[test]
    fn node_rows_add_in_element_order_bit_for_bit() {
        fn check<const W: usize>(isa: LaneIsa<W>) {
            let (force, conn) = order_sensitive_group(isa);
            let start: Vec<[f64; 4]> = (0..12)
                .map(|n| [n as f64 - 6.0, -0.0, 0.25 * n as f64, 0.0])
                .collect();
            let mut want = start.clone();
            add_in_order(&force, &mut want, &conn);
            let mut got = start;
            // SAFETY: nodes < 12.
            unsafe { Lanes::add_node_rows(&force, got.as_mut_ptr(), &conn) };
            let bits =
                |f: &[[f64; 4]]| -> Vec<u64> { f.iter().flatten().map(|c| c.to_bits()).collect() };
            assert_eq!(bits(&got), bits(&want), "{W} lanes");
            assert!(got.iter().all(|g| g[3].to_bits() == 0), "the pad stays +0");
        }
        check(four());
        if let Some(isa) = LaneIsa::<8>::detect() {
            check(isa);
        }
        // The test data must make the order matter, or the test could not fail.
        let (force, conn) = order_sensitive_group(four());
        let mut fwd = vec![[0.0; 4]; 12];
        add_in_order(&force, &mut fwd, &conn);
        let mut rev = vec![[0.0; 4]; 12];
        let rconn: Vec<[u32; 8]> = conn.iter().rev().copied().collect();
        let mut rforce = force;
        for fi in &mut rforce {
            for c in fi {
                c.0.reverse();
            }
        }
        add_in_order(&rforce, &mut rev, &rconn);
        assert_ne!(fwd, rev, "the test forces must be order sensitive");
    }
}
