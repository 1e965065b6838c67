//! Li, Yang & Shi (2019) three-phase model on the seam: Hertz loading to δ₁, elastoplastic
//! loading F = π R* σ_p (δ − δ_e) (δ_e = δ₁/3), Hertz unloading with the original radius
//! shifted by δ_p = δ_max − (F_max/K)^{2/3}. Its closed form is [`NormalImpact`].

use super::thornton::LIMIT_PRESSURE;
use super::{ClosedForm, ContactPair, NormalLaw, NormalSpec, Params, Turn};
use crate::analytic::hertz::HertzPair;
use crate::analytic::three_phase::{plastic_offset, yield_approach, NormalImpact};
use std::f64::consts::PI;

/// The three-phase law for one pair.
#[derive(Debug, Clone, Copy)]
pub struct LiYangShi {
    /// E*, R*, m* of the pair.
    pub pair: HertzPair,
    /// Yield pressure σ_p, Pa.
    pub yield_pressure: f64,
}

impl NormalLaw for LiYangShi {
    fn loading(&self, delta: f64, _rate: f64, _speed: f64) -> f64 {
        let d1 = yield_approach(&self.pair, self.yield_pressure);
        if delta <= d1 {
            self.pair.force(delta)
        } else {
            let de = plastic_offset(&self.pair, self.yield_pressure);
            PI * self.pair.radius * self.yield_pressure * (delta - de)
        }
    }

    fn unloading(&self, delta: f64, _rate: f64, _speed: f64, turn: &Turn) -> f64 {
        self.pair.force(delta - turn.residual())
    }

    fn residual(&self, delta: f64, force: f64) -> f64 {
        // δ_p = δ_max − (F_max/K)^{2/3} (eq. 27), the recovery as a cube root.
        let ratio = force / self.pair.stiffness();
        delta - (ratio * ratio).cbrt()
    }

    fn thresholds(&self) -> Vec<f64> {
        vec![yield_approach(&self.pair, self.yield_pressure)]
    }

    fn closed_form(&self, speed: f64, mass: f64) -> Option<ClosedForm> {
        let pair = HertzPair { mass, ..self.pair };
        NormalImpact::solve(pair, self.yield_pressure, speed).map(|n| ClosedForm {
            e: n.e,
            delta_max: n.delta2,
        })
    }
}

/// The law's description.
pub const SPEC: NormalSpec = NormalSpec {
    name: "li-yang-shi",
    title: "three-phase model: Hertz, elastoplastic (slope pi R sigma_p), shifted Hertz recovery",
    source: "Li, Yang & Shi, Shock and Vibration 2019, eqs. 5-30",
    dem_codes: "none of LIGGGHTS, LAMMPS, Yade, MercuryDPM",
    validity: super::validity::UNSTATED,
    params: &[LIMIT_PRESSURE],
    build: |pair: &ContactPair, p: &Params| {
        Box::new(LiYangShi {
            pair: pair.hertz,
            yield_pressure: p.get("p_y"),
        })
    },
};
