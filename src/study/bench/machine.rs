//! The machine-ceiling harness of `twoball bench machine`: the two ceilings of a roofline
//! for this machine, measured with small kernels: floating-point throughput per core
//! (independent chains on 4-wide f64
//! vectors, and on 8-wide ones where the CPU has AVX-512, fused and as separate multiply +
//! add) and memory bandwidth (STREAM-style triad a = b + s c on arrays sized for L2, L3, the
//! working set of `bench kernel` and main memory, 1 thread and all threads), and the
//! throughput of two ways to load eight elements' node fields into eight lanes: the gather
//! instruction, and row loads transposed in registers (what the element loop uses); and the
//! cost of a 64-byte row (an integration point's state) updated in place when it is one
//! cache line and when it straddles two (why the point array is 64-byte aligned).

use crate::error::{Error, Result};
use rayon::prelude::*;
use std::hint::black_box;
use std::io::Write;
use std::time::Instant;

/// Independent accumulators: enough to hide the FMA latency (4 cycles) on 2 pipes.
const CHAINS: usize = 12;

/// `n` rounds of acc = acc·m + c on CHAINS x 4 lanes; returns a checksum. Plain arrays: the
/// compiler turns each `[f64; 4]` statement into one vector instruction.
#[inline(always)]
fn fma_rounds(n: u64, fused: bool) -> f64 {
    let mut acc = [[1.0f64; 4]; CHAINS];
    for (k, a) in acc.iter_mut().enumerate() {
        a[0] += k as f64 * 1e-3;
    }
    let m = black_box([0.999_999_9f64; 4]);
    let c = black_box([1e-7f64; 4]);
    for _ in 0..n {
        for a in acc.iter_mut() {
            for l in 0..4 {
                a[l] = if fused {
                    a[l].mul_add(m[l], c[l])
                } else {
                    a[l] * m[l] + c[l]
                };
            }
        }
    }
    acc.iter().flatten().sum()
}

/// `n` rounds of acc = acc·m + c on CHAINS vector registers of one x86 width, fused or as a
/// separate multiply and add; returns a checksum. Written with intrinsics because LLVM does
/// not keep the portable version's 12 x 4 accumulators in vector registers (it scalarises
/// and spills them), which measured one scalar FMA per cycle instead of the machine's
/// vector throughput.
macro_rules! simd_rounds {
    ($name:ident, $feature:literal, $lanes:literal, $set1:ident, $add:ident, $mul:ident,
     $fmadd:ident, $storeu:ident) => {
        #[cfg(target_arch = "x86_64")]
        #[target_feature(enable = $feature)]
        unsafe fn $name(n: u64, fused: bool) -> f64 {
            use std::arch::x86_64::*;
            let mut acc = [$set1(1.0); CHAINS];
            for (k, a) in acc.iter_mut().enumerate() {
                *a = $add(*a, $set1(k as f64 * 1e-3));
            }
            let m = $set1(black_box(0.999_999_9));
            let c = $set1(black_box(1e-7));
            if fused {
                for _ in 0..n {
                    for a in acc.iter_mut() {
                        *a = $fmadd(*a, m, c);
                    }
                }
            } else {
                for _ in 0..n {
                    for a in acc.iter_mut() {
                        *a = $add($mul(*a, m), c);
                    }
                }
            }
            let mut sum = 0.0;
            for a in acc {
                let mut lanes = [0.0f64; $lanes];
                $storeu(lanes.as_mut_ptr(), a);
                sum += lanes.iter().sum::<f64>();
            }
            sum
        }
    };
}

simd_rounds!(
    fma_rounds_avx2,
    "avx2,fma",
    4,
    _mm256_set1_pd,
    _mm256_add_pd,
    _mm256_mul_pd,
    _mm256_fmadd_pd,
    _mm256_storeu_pd
);
// The same rounds on 8-wide AVX-512 registers (the width of the element kernels on a CPU with
// AVX-512F; they use separate multiply and add, never fused).
simd_rounds!(
    fma_rounds_avx512,
    "avx512f",
    8,
    _mm512_set1_pd,
    _mm512_add_pd,
    _mm512_mul_pd,
    _mm512_fmadd_pd,
    _mm512_storeu_pd
);

/// Flops per second of one thread on 8-wide AVX-512 registers: (fused FMA, separate
/// multiply + add); `None` when the CPU lacks AVX-512F.
fn flops_512(rounds: u64) -> Option<(f64, f64)> {
    #[cfg(target_arch = "x86_64")]
    if std::is_x86_feature_detected!("avx512f") {
        let run = |fused: bool| {
            let t = Instant::now();
            // SAFETY: the CPU supports the feature the function was compiled for.
            black_box(unsafe { fma_rounds_avx512(rounds, fused) });
            (rounds * CHAINS as u64 * 8 * 2) as f64 / t.elapsed().as_secs_f64()
        };
        return Some((run(true), run(false)));
    }
    let _ = rounds;
    None
}

/// Flops per second of one thread: (fused FMA, separate multiply + add).
fn flops(rounds: u64) -> (f64, f64) {
    let run = |fused: bool| {
        let t = Instant::now();
        #[cfg(target_arch = "x86_64")]
        let s = if std::is_x86_feature_detected!("avx2") && std::is_x86_feature_detected!("fma") {
            // SAFETY: the CPU supports the features the function was compiled for.
            unsafe { fma_rounds_avx2(rounds, fused) }
        } else {
            fma_rounds(rounds, fused)
        };
        #[cfg(not(target_arch = "x86_64"))]
        let s = fma_rounds(rounds, fused);
        black_box(s);
        (rounds * CHAINS as u64 * 4 * 2) as f64 / t.elapsed().as_secs_f64()
    };
    (run(true), run(false))
}

/// Node-like data for the gather ceiling: 1 000 nodes of three f64 (24 KB, in L1 as a lane
/// group's nodes mostly are) and 4 096 pseudo-random node offsets 3n, as i64.
fn gather_data() -> (Vec<f64>, Vec<i64>) {
    let nodes = 1000usize;
    let data: Vec<f64> = (0..3 * nodes).map(|i| i as f64 * 0.25).collect();
    let mut state = 12_345u64;
    let idx = (0..4096)
        .map(|_| {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            3 * ((state >> 33) % nodes as u64) as i64
        })
        .collect();
    (data, idx)
}

/// Σ over `reps` passes of `data[idx[k]]`, gathered eight at a time (`vgatherqpd`) into four
/// independent accumulators.
///
/// # Safety
/// The CPU has AVX-512F; every `idx[k]` is in bounds of `data`; `idx.len()` is a multiple
/// of 32.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
unsafe fn gather_rounds_avx512(data: &[f64], idx: &[i64], reps: usize) -> f64 {
    use std::arch::x86_64::*;
    let mut acc = [_mm512_setzero_pd(); 4];
    for _ in 0..reps {
        for c in idx.chunks_exact(32) {
            for (j, a) in acc.iter_mut().enumerate() {
                let o = _mm512_loadu_si512(c[8 * j..].as_ptr().cast());
                *a = _mm512_add_pd(*a, _mm512_i64gather_pd::<8>(o, data.as_ptr()));
            }
        }
    }
    let mut sum = 0.0;
    for a in acc {
        let mut lanes = [0.0f64; 8];
        _mm512_storeu_pd(lanes.as_mut_ptr(), a);
        sum += lanes.iter().sum::<f64>();
    }
    sum
}

/// Seconds per eight-lane gather instruction (one lane vector of one node field for eight
/// elements), one thread, data in L1; `None` when the CPU lacks AVX-512F.
fn gather_512(reps: usize) -> Option<f64> {
    #[cfg(target_arch = "x86_64")]
    if std::is_x86_feature_detected!("avx512f") {
        let (data, idx) = gather_data();
        let t = Instant::now();
        // SAFETY: AVX-512F checked; offsets 3n + 0 < data.len(); 4096 = 128 x 32.
        black_box(unsafe { gather_rounds_avx512(&data, &idx, reps) });
        return Some(t.elapsed().as_secs_f64() / (reps * idx.len() / 8) as f64);
    }
    let _ = reps;
    None
}

/// Σ over `reps` passes of x + y + z of the nodes `idx[k] / 3` of `data` (rows of three
/// f64), eight nodes at a time by [`Lanes::load_vec3`] (row loads and a register transpose:
/// the element loop's node loads), into four independent accumulators.
///
/// # Safety
/// The CPU has AVX-512F; every `idx[k] / 3` is a node of `data`; `idx.len()` is a multiple
/// of 32.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f,avx2,fma")]
unsafe fn row_rounds_avx512(data: &[f64], idx: &[i64], reps: usize) -> f64 {
    use crate::fe::simd::{LaneIsa, Lanes};
    let isa = LaneIsa::<8>::detect().expect("the caller checked AVX-512F");
    let rows = data.as_ptr().cast::<[f64; 3]>();
    let nodes: Vec<u32> = idx.iter().map(|&k| (k / 3) as u32).collect();
    let mut acc = [isa.splat(0.0); 4];
    for _ in 0..reps {
        for c in nodes.chunks_exact(32) {
            for (j, a) in acc.iter_mut().enumerate() {
                let n: &[u32; 8] = c[8 * j..8 * j + 8].try_into().unwrap();
                let [x, y, z] = Lanes::load_vec3(isa, rows, n);
                *a += x + y + z;
            }
        }
    }
    acc.iter().flat_map(|a| a.0).sum()
}

/// Seconds per eight-lane vector of a node field loaded as rows and transposed (a third of a
/// [`Lanes::load_vec3`] call), one thread, data in L1; `None` without AVX-512F.
fn rows_512(reps: usize) -> Option<f64> {
    #[cfg(target_arch = "x86_64")]
    if std::is_x86_feature_detected!("avx512f")
        && std::is_x86_feature_detected!("avx2")
        && std::is_x86_feature_detected!("fma")
    {
        let (data, idx) = gather_data();
        let t = Instant::now();
        // SAFETY: features checked; nodes idx / 3 < 1000; 4096 = 128 x 32.
        black_box(unsafe { row_rounds_avx512(&data, &idx, reps) });
        return Some(t.elapsed().as_secs_f64() / (reps * idx.len() / 8 * 3) as f64);
    }
    let _ = reps;
    None
}

/// `reps` passes of row += 1 over `rows` rows of eight f64 starting at `base`, one 512-bit
/// load, add and store per row (the element state's point rows, read and written once per
/// step).
///
/// # Safety
/// The CPU has AVX-512F; `base..base + 8 rows` is writable.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
unsafe fn row_update_rounds_avx512(base: *mut f64, rows: usize, reps: usize) {
    use std::arch::x86_64::*;
    let one = _mm512_set1_pd(1.0);
    for _ in 0..reps {
        for r in 0..rows {
            let p = base.add(8 * r);
            _mm512_storeu_pd(p, _mm512_add_pd(_mm512_loadu_pd(p), one));
        }
    }
}

/// Seconds per 64-byte row updated in place (512-bit load, add, store), one thread, 4 096
/// rows (256 KB, in L2), with the rows starting `offset` bytes (a multiple of 8) past a
/// 64-byte boundary: at 0 each row is one cache line, otherwise every row straddles two.
/// `None` without AVX-512F.
fn row_update_512(offset: usize, reps: usize) -> Option<f64> {
    #[cfg(target_arch = "x86_64")]
    if std::is_x86_feature_detected!("avx512f") {
        let rows = 4096;
        let mut buf = vec![0.0f64; 8 * rows + 16];
        let skew = (64 - buf.as_ptr() as usize % 64) % 64 + offset;
        let base = buf[skew / 8..].as_mut_ptr();
        let t = Instant::now();
        // SAFETY: AVX-512F checked; skew / 8 + 8 rows ≤ the buffer's 8 rows + 16 f64.
        unsafe { row_update_rounds_avx512(base, rows, reps) };
        black_box(&buf);
        return Some(t.elapsed().as_secs_f64() / (rows * reps) as f64);
    }
    let _ = (offset, reps);
    None
}

/// Triad bandwidth (bytes/s counted as STREAM does: 3 x 8 B per element) over arrays of `n`
/// doubles, on the current thread pool with chunks of `chunk` elements.
fn triad(n: usize, chunk: usize, passes: usize) -> f64 {
    let b = vec![1.0f64; n];
    let c = vec![2.0f64; n];
    let mut a = vec![0.0f64; n];
    let s = black_box(0.5);
    let t = Instant::now();
    for _ in 0..passes {
        a.par_chunks_mut(chunk)
            .zip(b.par_chunks(chunk))
            .zip(c.par_chunks(chunk))
            .for_each(|((a, b), c)| {
                for i in 0..a.len() {
                    a[i] = b[i] + s * c[i];
                }
            });
        black_box(&mut a);
    }
    (passes * n * 24) as f64 / t.elapsed().as_secs_f64()
}

/// Measures the ceilings, best of `repeats` each, and writes them to `out` as CSV
/// (`measure,threads,value,unit`) after a `#` header line.
///
/// Errors: `repeats` = 0 ([`Error::Invalid`] naming `--repeats`); a thread pool that cannot
/// be built; a failed write to `out`.
pub fn machine(repeats: usize, out: &mut impl Write) -> Result<()> {
    if repeats == 0 {
        return Err(Error::invalid("--repeats", 0, "at least 1"));
    }
    let all = std::thread::available_parallelism().map_or(1, |n| n.get());
    writeln!(out, "# twoball bench machine: best of {} repeats", repeats).map_err(put)?;
    let rounds = 20_000_000;
    let (mut fused, mut sep) = (0.0f64, 0.0f64);
    for _ in 0..repeats {
        let (f, s) = flops(rounds);
        fused = fused.max(f);
        sep = sep.max(s);
    }
    writeln!(out, "measure,threads,value,unit").map_err(put)?;
    writeln!(out, "fma_throughput,1,{:.2},Gflop/s", fused * 1e-9).map_err(put)?;
    writeln!(out, "mul_add_separate,1,{:.2},Gflop/s", sep * 1e-9).map_err(put)?;
    let mut wide: Option<(f64, f64)> = None;
    for _ in 0..repeats {
        if let Some((f, s)) = flops_512(rounds) {
            let w = wide.get_or_insert((0.0, 0.0));
            *w = (w.0.max(f), w.1.max(s));
        }
    }
    if let Some((f, s)) = wide {
        writeln!(out, "fma_throughput_avx512,1,{:.2},Gflop/s", f * 1e-9).map_err(put)?;
        writeln!(out, "mul_add_separate_avx512,1,{:.2},Gflop/s", s * 1e-9).map_err(put)?;
    }
    let gather = best_time(repeats, || gather_512(20_000));
    write_ns(out, "gather_avx512", gather, "ns per 8-lane gather")?;
    let rows = best_time(repeats, || rows_512(20_000));
    write_ns(out, "node_rows_avx512", rows, "ns per 8-lane vector")?;
    for offset in [0, 16] {
        let t = best_time(repeats, || row_update_512(offset, 200));
        let measure = format!("row_update_512_offset_{offset}b");
        write_ns(out, &measure, t, "ns per 64-byte row")?;
    }
    // 24 MB: about the working set of `bench kernel`'s default 55 000-element ball.
    for (label, bytes) in [
        ("triad_l2", 1usize << 19),
        ("triad_l3", 12 << 20),
        ("triad_24mb", 24 << 20),
        ("triad_dram", 384 << 20),
    ] {
        let n = bytes / 24;
        let passes = ((2usize << 30) / bytes).clamp(2, 4000);
        for threads in [1, all] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .map_err(|e| Error::External(format!("thread pool: {e}")))?;
            let chunk = n.div_ceil(threads);
            let mut best = 0.0f64;
            for _ in 0..repeats {
                best = best.max(pool.install(|| triad(n, chunk, passes)));
            }
            writeln!(out, "{label},{threads},{:.2},GB/s", best * 1e-9).map_err(put)?;
            if all == 1 {
                break;
            }
        }
    }
    Ok(())
}

/// The least of `repeats` timings `time()` (s); None when it cannot be measured here.
fn best_time(repeats: usize, mut time: impl FnMut() -> Option<f64>) -> Option<f64> {
    (0..repeats).filter_map(|_| time()).reduce(f64::min)
}

/// Writes the row `measure,1,value,unit` of a time `t` (s) in nanoseconds to 3 decimals; no
/// row when `t` is None.
fn write_ns(out: &mut impl Write, measure: &str, t: Option<f64>, unit: &str) -> Result<()> {
    match t {
        Some(t) => writeln!(out, "{measure},1,{:.3},{unit}", t * 1e9).map_err(put),
        None => Ok(()),
    }
}

/// A failed write of the results.
fn put(e: std::io::Error) -> Error {
    Error::io("standard output", e)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The gather kernel sums what it is asked to (a timing of the wrong loads would be no
    /// ceiling at all).
    #[test]
    fn gather_rounds_sum_the_indexed_values() {
        #[cfg(target_arch = "x86_64")]
        if std::is_x86_feature_detected!("avx512f") {
            let (data, idx) = gather_data();
            let want: f64 = 3.0 * idx.iter().map(|&k| data[k as usize]).sum::<f64>();
            // SAFETY: AVX-512F checked; offsets in bounds; 4096 is a multiple of 32.
            let got = unsafe { gather_rounds_avx512(&data, &idx, 3) };
            assert!((got - want).abs() <= 1e-12 * want, "{got} vs {want}");
            // The row loads see whole nodes: x + y + z of each.
            let want: f64 = 3.0
                * idx
                    .iter()
                    .map(|&k| data[k as usize..k as usize + 3].iter().sum::<f64>())
                    .sum::<f64>();
            if std::is_x86_feature_detected!("avx2") && std::is_x86_feature_detected!("fma") {
                // SAFETY: features checked; nodes in bounds; 4096 is a multiple of 32.
                let got = unsafe { row_rounds_avx512(&data, &idx, 3) };
                assert!((got - want).abs() <= 1e-12 * want, "{got} vs {want}");
            }
            return;
        }
        eprintln!("skipped: this CPU lacks AVX-512F");
    }
}
