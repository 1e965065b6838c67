//! The fully integrated ring quad: four 2x2 Gauss points, each with its own strain rate
//! (deviatoric and volumetric), stress and plastic strain; forces Σ_g W_g B_gᵀσ_g. No
//! hourglass modes and no hourglass control, the classical element of implicit codes
//! (Zienkiewicz & Taylor, vol. 1, §9; Hughes 1987, §4.5).
//!
//! Its limit is volumetric locking: four points each holding its own dilatation over-
//! constrain isochoric (plastic) flow, so a plastic run comes out too stiff (Nagtegaal,
//! Parks & Rice 1974) — the reason the B-bar quad ([`super::bbar`]) keeps the element's
//! mean dilatation instead. Elastic runs with ν well below ½ do not lock. Objective update
//! and material seam as the other formulations', at each Gauss point.

use super::four_point::FourPointQuad;

/// The fully integrated (2x2 Gauss) quad.
pub type FullQuad = FourPointQuad<false>;
