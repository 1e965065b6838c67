//! Walton & Braun (1986) hysteretic spring: loading F = k₁ δ, unloading F = k₂ (δ − δ₀) with
//! k₂ = k₁/e², δ₀ = δ_max (1 − k₁/k₂). Closed form: δ_max = v √(m*/k₁), restitution e.

use super::params::{LINEAR_STIFFNESS, RESTITUTION};
use super::{ClosedForm, ContactPair, NormalLaw, NormalSpec, Params, Turn};

/// The bilinear hysteretic spring.
#[derive(Debug, Clone, Copy)]
pub struct WaltonBraun {
    /// Loading stiffness k₁, N/m.
    pub loading: f64,
    /// Unloading stiffness k₂ = k₁/e², N/m.
    pub unloading: f64,
}

impl NormalLaw for WaltonBraun {
    fn loading(&self, delta: f64, _rate: f64, _speed: f64) -> f64 {
        self.loading * delta.max(0.0)
    }

    fn unloading(&self, delta: f64, _rate: f64, _speed: f64, turn: &Turn) -> f64 {
        (self.unloading * (delta - turn.residual())).max(0.0)
    }

    fn residual(&self, delta: f64, force: f64) -> f64 {
        delta - force / self.unloading
    }

    fn closed_form(&self, speed: f64, mass: f64) -> Option<ClosedForm> {
        Some(ClosedForm {
            e: (self.loading / self.unloading).sqrt(),
            delta_max: speed * (mass / self.loading).sqrt(),
        })
    }
}

/// The law's description.
pub const SPEC: NormalSpec = NormalSpec {
    name: "walton-braun",
    title: "hysteretic linear spring, k1 loading, k2 = k1/e^2 unloading",
    source: "O. R. Walton, R. L. Braun, J. Rheol. 30 (1986) 949-980",
    dem_codes: "exported and run: LIGGGHTS (hooke/hysteresis, at one speed only: its unloading stiffness grows with delta_max); MercuryDPM (LinearPlasticViscoelastic, one speed, not run); not LAMMPS or Yade",
    validity: super::validity::FITTED,
    params: &[LINEAR_STIFFNESS, RESTITUTION],
    build: |_pair: &ContactPair, p: &Params| {
        let k1 = p.get("k");
        let e = p.get("e");
        Box::new(WaltonBraun {
            loading: k1,
            unloading: k1 / (e * e),
        })
    },
};
