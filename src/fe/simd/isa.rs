//! Instruction-set tokens: values that exist only once run-time CPU detection has found the
//! instructions they stand for, and the trait that compiles a lane-generic kernel for each.
//!
//! Every lane value ([`super::Lanes`]) carries a [`LaneIsa`] token, so eight-lane arithmetic,
//! which executes AVX-512 instructions on x86-64, cannot be reached from safe code on a CPU
//! without AVX-512F: the token's only constructors are the detecting ones. A kernel path
//! ([`Kernel`]) holds the token of the target features its kernels are compiled for; a
//! [`LaneKernel`] runs on it through [`Simd::vectorize`] (a trait method, not a macro, so the
//! call is visible to tools).

/// Proof that W-lane arithmetic may run on this CPU: on x86-64, eight lanes need AVX-512F
/// (their operators execute AVX-512 instructions); other widths, and every width on other
/// targets, run as plain arrays and need nothing. Obtainable only from [`LaneIsa::detect`]
/// or from a kernel token ([`Avx512::lanes`], [`Avx2::lanes`], [`Portable::lanes`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LaneIsa<const W: usize>(());

impl<const W: usize> LaneIsa<W> {
    /// The token when this CPU can run W-lane arithmetic, else `None`.
    pub fn detect() -> Option<Self> {
        #[cfg(target_arch = "x86_64")]
        if W == 8 && !std::is_x86_feature_detected!("avx512f") {
            return None;
        }
        Some(LaneIsa(()))
    }

    /// Every lane equal to `v`.
    #[inline(always)]
    pub fn splat(self, v: f64) -> super::Lanes<W> {
        super::Lanes([v; W], self)
    }

    /// Lane l = `a[l]`.
    #[inline(always)]
    pub fn lanes(self, a: [f64; W]) -> super::Lanes<W> {
        super::Lanes(a, self)
    }
}

/// x86-64 AVX-512F, AVX2 and FMA, detected: the eight-lane kernel path.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Avx512(());

/// x86-64 AVX2 and FMA, detected: the four-lane AVX2 kernel path.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Avx2(());

/// Any CPU: the four-lane kernel path compiled for the baseline target.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Portable;

impl Avx512 {
    /// The token when this CPU has AVX-512F, AVX2 and FMA, else `None`.
    pub fn detect() -> Option<Self> {
        #[cfg(target_arch = "x86_64")]
        if std::is_x86_feature_detected!("avx512f")
            && std::is_x86_feature_detected!("avx2")
            && std::is_x86_feature_detected!("fma")
        {
            return Some(Avx512(()));
        }
        None
    }

    /// Eight-lane arithmetic is legal: AVX-512F is present.
    #[inline(always)]
    pub fn lanes(self) -> LaneIsa<8> {
        LaneIsa(())
    }
}

impl Avx2 {
    /// The token when this CPU has AVX2 and FMA, else `None`.
    pub fn detect() -> Option<Self> {
        #[cfg(target_arch = "x86_64")]
        if std::is_x86_feature_detected!("avx2") && std::is_x86_feature_detected!("fma") {
            return Some(Avx2(()));
        }
        None
    }

    /// Four-lane arithmetic (legal everywhere).
    #[inline(always)]
    pub fn lanes(self) -> LaneIsa<4> {
        LaneIsa(())
    }
}

impl Portable {
    /// Four-lane arithmetic (legal everywhere).
    #[inline(always)]
    pub fn lanes(self) -> LaneIsa<4> {
        LaneIsa(())
    }
}

/// A computation written once for any lane width W: the element loop, the kernel timing.
pub trait LaneKernel {
    /// What the computation returns.
    type Output;
    /// Runs on W lanes; `isa` proves W-lane arithmetic legal. Implementations are
    /// `#[inline(always)]`, so that they compile with the features of [`Simd::vectorize`].
    fn run<const W: usize>(self, isa: LaneIsa<W>) -> Self::Output;
}

/// An instruction-set token a [`LaneKernel`] can be compiled for.
pub trait Simd: Copy {
    /// Runs `k` compiled for this token's target features, at its lane width.
    fn vectorize<K: LaneKernel>(self, k: K) -> K::Output;
}

impl Simd for Avx512 {
    #[inline(always)]
    fn vectorize<K: LaneKernel>(self, k: K) -> K::Output {
        #[cfg(target_arch = "x86_64")]
        {
            #[target_feature(enable = "avx512f,avx2,fma")]
            fn wide<K: LaneKernel>(k: K, isa: LaneIsa<8>) -> K::Output {
                k.run::<8>(isa)
            }
            // SAFETY: an Avx512 token exists only after AVX-512F, AVX2 and FMA were detected.
            unsafe { wide(k, self.lanes()) }
        }
        #[cfg(not(target_arch = "x86_64"))]
        k.run::<8>(self.lanes())
    }
}

impl Simd for Avx2 {
    #[inline(always)]
    fn vectorize<K: LaneKernel>(self, k: K) -> K::Output {
        #[cfg(target_arch = "x86_64")]
        {
            #[target_feature(enable = "avx2,fma")]
            fn four<K: LaneKernel>(k: K, isa: LaneIsa<4>) -> K::Output {
                // A 32-byte-aligned local on the stack makes the compiler realign this frame,
                // so that its 256-bit stack slots are aligned wherever the caller's stack
                // pointer is (the AVX-512 entry realigns by itself).
                #[repr(align(32))]
                struct Aligned32(u8);
                let frame = Aligned32(std::hint::black_box(0));
                std::hint::black_box(&frame.0);
                k.run::<4>(isa)
            }
            // SAFETY: an Avx2 token exists only after AVX2 and FMA were detected.
            unsafe { four(k, self.lanes()) }
        }
        #[cfg(not(target_arch = "x86_64"))]
        k.run::<4>(self.lanes())
    }
}

impl Simd for Portable {
    #[inline(always)]
    fn vectorize<K: LaneKernel>(self, k: K) -> K::Output {
        k.run::<4>(self.lanes())
    }
}

/// The name of a kernel path (a cap, a report); [`Kernel`] is the path with its token.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum KernelPath {
    /// Eight lanes, AVX-512 (x86-64 with AVX-512F, AVX2 and FMA).
    #[default]
    Avx512,
    /// Four lanes, AVX2 (x86-64 with AVX2 and FMA).
    Avx2,
    /// Four lanes as plain arrays, compiled for the baseline target (any CPU).
    Portable,
}

impl KernelPath {
    /// Elements per lane group.
    pub fn lanes(self) -> usize {
        match self {
            KernelPath::Avx512 => 8,
            KernelPath::Avx2 | KernelPath::Portable => 4,
        }
    }
}

/// The kernel path the element loop runs, holding the token its target features need.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kernel {
    /// Eight AVX-512 lanes.
    Avx512(Avx512),
    /// Four AVX2 lanes.
    Avx2(Avx2),
    /// Four plain lanes.
    Portable(Portable),
}

impl Kernel {
    /// The widest path this CPU supports, at most `cap` (a setting: to measure and test, on
    /// one machine, the paths other CPUs take). Results are the same bits on every path.
    pub fn widest(cap: KernelPath) -> Kernel {
        choose(cap, Avx2::detect(), Avx512::detect())
    }

    /// The path's name.
    pub fn path(self) -> KernelPath {
        match self {
            Kernel::Avx512(_) => KernelPath::Avx512,
            Kernel::Avx2(_) => KernelPath::Avx2,
            Kernel::Portable(_) => KernelPath::Portable,
        }
    }

    /// Runs `k` on this path.
    #[inline(always)]
    pub fn run<K: LaneKernel>(self, k: K) -> K::Output {
        match self {
            Kernel::Avx512(t) => t.vectorize(k),
            Kernel::Avx2(t) => t.vectorize(k),
            Kernel::Portable(t) => t.vectorize(k),
        }
    }

    /// Every path this CPU supports, widest first (the tests run each).
    pub fn all_supported() -> Vec<Kernel> {
        let mut out = Vec::new();
        if let Some(t) = Avx512::detect() {
            out.push(Kernel::Avx512(t));
        }
        if let Some(t) = Avx2::detect() {
            out.push(Kernel::Avx2(t));
        }
        out.push(Kernel::Portable(Portable));
        out
    }
}

/// The path for `cap` given the detected tokens (`avx512` implies `avx2` on real CPUs).
fn choose(cap: KernelPath, avx2: Option<Avx2>, avx512: Option<Avx512>) -> Kernel {
    match (cap, avx512, avx2) {
        (KernelPath::Avx512, Some(t), _) => Kernel::Avx512(t),
        (KernelPath::Avx512 | KernelPath::Avx2, _, Some(t)) => Kernel::Avx2(t),
        _ => Kernel::Portable(Portable),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The cap only narrows the path, and never past what the CPU has.
    #[test]
    fn kernel_choice_respects_cap_and_cpu() {
        use KernelPath as P;
        // Tokens built here stand for a CPU that has the features (the choice only).
        let (a2, a5) = (Some(Avx2(())), Some(Avx512(())));
        for (cap, avx2, avx512, want) in [
            (P::Avx512, a2, a5, P::Avx512),
            (P::Avx512, a2, None, P::Avx2),
            (P::Avx512, None, None, P::Portable),
            (P::Avx2, a2, a5, P::Avx2),
            (P::Avx2, None, None, P::Portable),
            (P::Portable, a2, a5, P::Portable),
            (P::Portable, a2, None, P::Portable),
        ] {
            assert_eq!(choose(cap, avx2, avx512).path(), want, "{cap:?}");
        }
        assert_eq!(
            Kernel::widest(KernelPath::Avx512).path(),
            Kernel::all_supported()[0].path()
        );
    }
}
