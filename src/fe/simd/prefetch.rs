//! Software prefetch hints for the element state streams.

/// Asks the CPU to bring `count` items of `T` from `base[first..]` into the L2 cache (one
/// prefetch hint per 64-byte line). The lane loops call it for the element state two lane
/// groups ahead: the state streams through once per step (28 MB for the benchmark's B-bar
/// ball, more than the L3), and on AMD's Zen 4 the hardware prefetchers do not keep up with
/// it among the loop's other streams (docs/performance.md has the figures). The items may lie
/// past the slice `base` points into (the next batch's, or past the block's end), since a
/// prefetch hint reads nothing and cannot fault.
#[inline(always)]
pub fn prefetch_ahead<T>(base: *const T, first: usize, count: usize) {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_mm_prefetch, _MM_HINT_T1};
        let start = base.wrapping_add(first).cast::<i8>();
        let bytes = count * std::mem::size_of::<T>();
        let mut off = 0;
        while off < bytes {
            // SAFETY: a prefetch hint has no architectural effect and never faults.
            unsafe { _mm_prefetch::<_MM_HINT_T1>(start.wrapping_add(off)) };
            off += 64;
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = (base, first, count);
}
