//! Linear isotropic hardening, σ_y = σ_y0 + H ε_p (a bilinear uniaxial stress-strain curve
//! with tangent modulus E_T, H = E E_T/(E − E_T)): the radial return is exact in one step
//! (Wilkins 1964; Simo & Hughes 1998, Box 3.1).
//!
//! The parameters are [`crate::material::hardening::Bilinear`], re-exported here.

use super::hardening::Hardening;
use crate::fe::simd::{select, Lanes};
pub use crate::material::hardening::Bilinear;

impl Hardening for Bilinear {
    fn rate_independent(&self) -> bool {
        true
    }

    #[inline(always)]
    fn static_yield(&self, eps_p: f64) -> f64 {
        self.yield0 + self.h * eps_p
    }

    /// Δε_p = (q − σ_y)/(3G + H); the work uses the mean of the yield stresses before and
    /// after, exact for a flow stress linear in ε_p. Rate independent: `dt` is unused.
    #[inline(always)]
    fn plastic_increment(&self, q: f64, sy: f64, _: f64, shear: f64, _: f64) -> (f64, f64) {
        let dp = (q - sy) / (3.0 * shear + self.h);
        (dp, dp * (sy + 0.5 * self.h * dp))
    }

    #[inline(always)]
    fn static_yield_lanes<const W: usize>(&self, eps_p: Lanes<W>) -> Lanes<W> {
        self.yield0 + self.h * eps_p
    }

    #[inline(always)]
    fn plastic_increment_lanes<const W: usize>(
        &self,
        yields: [bool; W],
        q: Lanes<W>,
        sy: Lanes<W>,
        _: Lanes<W>,
        shear: f64,
        _: f64,
    ) -> (Lanes<W>, Lanes<W>) {
        let dp = select(yields, (q - sy) / (3.0 * shear + self.h), q.splat_like(0.0));
        (dp, dp * (sy + 0.5 * self.h * dp))
    }
}
