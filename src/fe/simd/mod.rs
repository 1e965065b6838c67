//! The SIMD layer of the element kernels: lane values ([`lanes`]), the instruction-set tokens
//! that make eight-lane arithmetic reachable only on CPUs that have it and the dispatch that
//! compiles a lane-generic kernel for each kernel path ([`isa`]), padded nodal rows
//! ([`rows`]) and cache hints ([`prefetch`]).
//!
//! Soundness: every [`Lanes`] value carries a [`LaneIsa`] token, whose constructors detect
//! the CPU's features first; so no safe function reaches an instruction the CPU lacks. The
//! kernel entry points with `#[target_feature]` are called only through [`Simd::vectorize`]
//! of a token that proves their features.

pub mod isa;
pub mod lanes;
pub mod prefetch;
pub mod rows;

pub use isa::{Avx2, Avx512, Kernel, KernelPath, LaneIsa, LaneKernel, Portable, Simd};
pub use lanes::{build, cross, dot, select, Lanes, Vec3};
