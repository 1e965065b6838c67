//! SIMD lanes for the element kernels: a value per element of a group of W elements
//! (structure of arrays), with the arithmetic written once, lane-wise.
//!
//! Why plain arrays and not a SIMD crate: every operation is a fixed-length loop over
//! `[f64; W]` marked `#[inline(always)]`, so inside a kernel compiled with
//! `#[target_feature(enable = "avx2,fma")]` (or `avx512f`) the compiler turns each into one
//! vector instruction, and the same source compiles to scalar code on any other target. No
//! dependency, no `unsafe` in the arithmetic, and the results are identical on every path:
//! no operation is fused or reordered (Rust never contracts a·b + c into an FMA on its own),
//! so lane l computes exactly what the scalar formula computes for element l.

use std::ops::{Add, AddAssign, Div, Mul, Neg, Sub, SubAssign};

/// One f64 per lane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lanes<const W: usize>(pub [f64; W]);

impl<const W: usize> Default for Lanes<W> {
    #[inline(always)]
    fn default() -> Self {
        Lanes([0.0; W])
    }
}

/// `[f(0), f(1), ..., f(N − 1)]`, always inlined: `std::array::from_fn` and `array::map`
/// are generic functions the compiler may leave out of line, and an out-of-line copy is
/// compiled without the calling kernel's AVX2 target feature (scalar code). With this
/// helper the closure body lands inside the kernel.
#[inline(always)]
pub fn build<T: Copy + Default, const N: usize>(mut f: impl FnMut(usize) -> T) -> [T; N] {
    let mut a = [T::default(); N];
    for (i, x) in a.iter_mut().enumerate() {
        *x = f(i);
    }
    a
}

impl<const W: usize> Lanes<W> {
    /// Every lane equal to `v`.
    #[inline(always)]
    pub fn splat(v: f64) -> Self {
        Lanes([v; W])
    }

    /// Lane-wise square root.
    #[inline(always)]
    pub fn sqrt(self) -> Self {
        let mut r = self.0;
        for x in &mut r {
            *x = x.sqrt();
        }
        Lanes(r)
    }

    /// Lane-wise maximum (the `f64::max` rule: a NaN lane yields the other operand).
    #[inline(always)]
    pub fn max(self, o: Self) -> Self {
        let mut r = self.0;
        for l in 0..W {
            r[l] = r[l].max(o.0[l]);
        }
        Lanes(r)
    }

    /// Lane-wise minimum (the `f64::min` rule: a NaN lane yields the other operand).
    #[inline(always)]
    pub fn min(self, o: Self) -> Self {
        let mut r = self.0;
        for l in 0..W {
            r[l] = r[l].min(o.0[l]);
        }
        Lanes(r)
    }

    /// Lane-wise reciprocal 1/x.
    #[inline(always)]
    pub fn recip(self) -> Self {
        Lanes::splat(1.0) / self
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
    Lanes(r)
}

macro_rules! lane_op {
    ($tr:ident, $f:ident, $op:tt) => {
        impl<const W: usize> $tr for Lanes<W> {
            type Output = Self;
            #[inline(always)]
            #[allow(clippy::assign_op_pattern)]
            fn $f(self, o: Self) -> Self {
                let mut r = self.0;
                for l in 0..W {
                    r[l] = r[l] $op o.0[l];
                }
                Lanes(r)
            }
        }
        impl<const W: usize> $tr<f64> for Lanes<W> {
            type Output = Self;
            #[inline(always)]
            #[allow(clippy::assign_op_pattern)]
            fn $f(self, o: f64) -> Self {
                let mut r = self.0;
                for l in 0..W {
                    r[l] = r[l] $op o;
                }
                Lanes(r)
            }
        }
    };
}
lane_op!(Add, add, +);
lane_op!(Sub, sub, -);
lane_op!(Mul, mul, *);
lane_op!(Div, div, /);

impl<const W: usize> Mul<Lanes<W>> for f64 {
    type Output = Lanes<W>;
    #[inline(always)]
    fn mul(self, o: Lanes<W>) -> Lanes<W> {
        let mut r = o.0;
        for l in 0..W {
            r[l] *= self;
        }
        Lanes(r)
    }
}

impl<const W: usize> Add<Lanes<W>> for f64 {
    type Output = Lanes<W>;
    #[inline(always)]
    fn add(self, o: Lanes<W>) -> Lanes<W> {
        let mut r = o.0;
        for l in 0..W {
            r[l] += self;
        }
        Lanes(r)
    }
}

impl<const W: usize> Neg for Lanes<W> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        let mut r = self.0;
        for x in &mut r {
            *x = -*x;
        }
        Lanes(r)
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

    #[test]
    fn lanes_compute_what_scalars_compute() {
        let a = Lanes([1.5, -2.0, 3.25, 0.1]);
        let b = Lanes([0.3, 4.0, -1.0, 7.0]);
        let r = (a * b + a - b * 2.0) / (b + 10.0);
        for l in 0..4 {
            let (x, y) = (a.0[l], b.0[l]);
            assert_eq!(r.0[l], (x * y + x - y * 2.0) / (y + 10.0));
        }
        let m = a.gt(b);
        assert_eq!(m, [true, false, true, false]);
        assert_eq!(select(m, a, b).0, [1.5, 4.0, 3.25, 7.0]);
        let c = cross(
            &[Lanes([1.0]), Lanes([0.0]), Lanes([0.0])],
            &[Lanes([0.0]), Lanes([1.0]), Lanes([0.0])],
        );
        assert_eq!(c.map(|v| v.0[0]), [0.0, 0.0, 1.0]);
    }
}
