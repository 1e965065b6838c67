//! Ludwik/Swift power-law hardening, σ_y = σ_0 + K ε_p^n (Ludwik 1909), rate independent.
//! n = 1 is linear hardening with H = K, and returns exactly as the linear law does.
//!
//! The parameters are [`crate::material::hardening::Power`], re-exported here.

use super::hardening::{newton_return, Hardening};
pub use crate::material::hardening::Power;

/// σ_y and dσ_y/dε_p of `p` at plastic strain `e`, Pa (an infinite slope at e = 0 when n < 1).
fn flow(p: &Power, e: f64) -> (f64, f64) {
    (p.sigma0 + p.k * e.powf(p.n), p.n * p.k * e.powf(p.n - 1.0))
}

impl Hardening for Power {
    fn rate_independent(&self) -> bool {
        true
    }

    fn static_yield(&self, eps_p: f64) -> f64 {
        flow(self, eps_p).0
    }

    /// For n = 1 the flow stress is linear in ε_p and the return has the closed form of
    /// [`super::Bilinear`] with H = K (the same operations, so the same bits); otherwise the
    /// safeguarded Newton solve of [`newton_return`].
    fn plastic_increment(&self, q: f64, sy: f64, eps_p: f64, shear: f64, _: f64) -> (f64, f64) {
        if self.n == 1.0 {
            let dp = (q - sy) / (3.0 * shear + self.k);
            return (dp, dp * (sy + 0.5 * self.k * dp));
        }
        newton_return(q, sy, shear, |dp| flow(self, eps_p + dp))
    }
}
