//! Ludwik/Swift power-law hardening, σ_y = σ_0 + K ε_p^n (Ludwik 1909), rate independent.
//! n = 1 is linear hardening with H = K, and returns exactly as the linear law does.

use super::hardening::{newton_return, Hardening};
use crate::error::{Error, Result};

/// Power-law hardening parameters.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Power {
    /// Initial yield strength σ_0, Pa (the material's `yield`).
    pub sigma0: f64,
    /// Strength coefficient K, Pa (≥ 0).
    #[serde(rename = "K")]
    pub k: f64,
    /// Hardening exponent n (0 < n ≤ 1).
    pub n: f64,
}

impl Power {
    /// Checks the parameters; `path` names the hardening table in messages.
    pub fn validated(self, path: &str) -> Result<Self> {
        if !(self.k >= 0.0 && self.k.is_finite()) {
            return Err(Error::invalid(
                format!("{path}.K"),
                self.k,
                "K >= 0 Pa, finite",
            ));
        }
        if !(self.n > 0.0 && self.n <= 1.0) {
            return Err(Error::invalid(format!("{path}.n"), self.n, "0 < n <= 1"));
        }
        Ok(self)
    }

    /// σ_y and dσ_y/dε_p at plastic strain `e`, Pa (an infinite slope at e = 0 when n < 1).
    fn flow(&self, e: f64) -> (f64, f64) {
        (
            self.sigma0 + self.k * e.powf(self.n),
            self.n * self.k * e.powf(self.n - 1.0),
        )
    }
}

impl Hardening for Power {
    fn rate_independent(&self) -> bool {
        true
    }

    fn static_yield(&self, eps_p: f64) -> f64 {
        self.flow(eps_p).0
    }

    /// For n = 1 the flow stress is linear in ε_p and the return has the closed form of
    /// [`super::Bilinear`] with H = K (the same operations, so the same bits); otherwise the
    /// safeguarded Newton solve of [`newton_return`].
    fn plastic_increment(&self, q: f64, sy: f64, eps_p: f64, shear: f64, _: f64) -> (f64, f64) {
        if self.n == 1.0 {
            let dp = (q - sy) / (3.0 * shear + self.k);
            return (dp, dp * (sy + 0.5 * self.k * dp));
        }
        newton_return(q, sy, shear, |dp| self.flow(eps_p + dp))
    }
}
