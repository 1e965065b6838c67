//! Johnson-Cook hardening with its strain-rate term (Johnson & Cook 1983),
//! σ_y = (A + B ε_p^n)(1 + C ln ε̇*), ε̇* = max(ε̇_p/ε̇_0, 1), with the plastic strain rate
//! taken over the step, ε̇_p = Δε_p/Δt.
//!
//! Thermal softening (the factor 1 − T*^m) is off. The balls heat adiabatically by
//! ΔT = β ∫σ dε_p/(ρ c) with the Taylor-Quinney fraction β ≈ 0.9 (Taylor & Quinney 1934):
//! for OFHC copper (ρ c = 8960 × 385 J/(m³ K)) even a plastic strain of 0.05 at 300 MPa
//! heats by about 4 K, T* = ΔT/(T_m − T_r) ≈ 4/1058 = 0.004, and with m = 1.09 the flow
//! stress falls by 1 − T*^m ≈ 0.3 %. The collisions modelled here, at metres per second,
//! reach far smaller plastic strains.

use super::hardening::{newton_return, Hardening};
use crate::error::{Error, Result};

/// Johnson-Cook parameters (thermal term off).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct JohnsonCook {
    /// Yield strength A, Pa (> 0).
    #[serde(rename = "A")]
    pub a: f64,
    /// Strain-hardening coefficient B, Pa (≥ 0).
    #[serde(rename = "B")]
    pub b: f64,
    /// Strain-hardening exponent n (0 < n ≤ 1).
    pub n: f64,
    /// Strain-rate coefficient C (≥ 0).
    #[serde(rename = "C")]
    pub c: f64,
    /// Reference plastic strain rate ε̇_0, 1/s (> 0).
    pub rate0: f64,
}

/// OFHC copper, Johnson & Cook (1983), Table 1: A = 90 MPa, B = 292 MPa, n = 0.31,
/// C = 0.025, reference rate 1/s.
pub const OFHC_COPPER: JohnsonCook = JohnsonCook {
    a: 90e6,
    b: 292e6,
    n: 0.31,
    c: 0.025,
    rate0: 1.0,
};

/// 4340 steel (Rockwell C30), Johnson & Cook (1983), Table 1: A = 792 MPa, B = 510 MPa,
/// n = 0.26, C = 0.014, reference rate 1/s.
pub const STEEL_4340: JohnsonCook = JohnsonCook {
    a: 792e6,
    b: 510e6,
    n: 0.26,
    c: 0.014,
    rate0: 1.0,
};

impl JohnsonCook {
    /// Checks the parameters; `path` names the hardening table in messages.
    pub fn validated(self, path: &str) -> Result<Self> {
        let check = |key: &str, v: f64, ok: bool, allowed: &str| {
            if v.is_finite() && ok {
                Ok(())
            } else {
                Err(Error::invalid(format!("{path}.{key}"), v, allowed))
            }
        };
        check("A", self.a, self.a > 0.0, "A > 0 Pa, finite")?;
        check("B", self.b, self.b >= 0.0, "B >= 0 Pa, finite")?;
        check("n", self.n, self.n > 0.0 && self.n <= 1.0, "0 < n <= 1")?;
        check("C", self.c, self.c >= 0.0, "C >= 0, finite")?;
        check(
            "rate0",
            self.rate0,
            self.rate0 > 0.0,
            "rate0 > 0 1/s, finite",
        )?;
        Ok(self)
    }

    /// σ_y and dσ_y/dΔε_p for the increment `dp` from `eps_p` over the step `dt` (s).
    fn flow(&self, eps_p: f64, dp: f64, dt: f64) -> (f64, f64) {
        let e = eps_p + dp;
        let h = self.a + self.b * e.powf(self.n);
        let dh = self.n * self.b * e.powf(self.n - 1.0);
        let ratio = if dt > 0.0 {
            dp / (dt * self.rate0)
        } else {
            0.0
        };
        if ratio > 1.0 {
            let m = 1.0 + self.c * ratio.ln();
            (h * m, dh * m + h * self.c / dp)
        } else {
            (h, dh)
        }
    }
}

impl Hardening for JohnsonCook {
    fn static_yield(&self, eps_p: f64) -> f64 {
        self.a + self.b * eps_p.powf(self.n)
    }

    fn plastic_increment(&self, q: f64, sy: f64, eps_p: f64, shear: f64, dt: f64) -> (f64, f64) {
        newton_return(q, sy, shear, |dp| self.flow(eps_p, dp, dt))
    }
}
