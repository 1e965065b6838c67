//! The normal three-phase impact (Li, Yang & Shi 2019, eqs. 5–30): Hertz compression up to
//! the yield approach δ₁, elastoplastic compression to δ₂ = δ_max, elastic (shifted-Hertz)
//! recovery down to the permanent approach δ_p.
//!
//! Closed forms: phase 2 is a harmonic oscillator m δ̈ = −πRσ_p (δ − δ_e) about the shifted
//! equilibrium δ_e = σ_p²π²R/(12E²) with ω² = πRσ_p/m, so t₂ − t₁ is an arctangent; phase 3 is a
//! Hertz unloading of amplitude δ₂ − δ_p, lasting half a Hertz impact at the rebound speed;
//! phase 1 is a partial Hertz loading (see [`super::hertz::loading_time_fraction`]).

use super::hertz::{HertzPair, HERTZ_DURATION_FACTOR};
use std::f64::consts::PI;

/// Which phase of the normal impact a state belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Phase {
    /// Elastic (Hertz) compression, 0 ≤ δ ≤ δ₁.
    ElasticCompression,
    /// Elastoplastic compression, δ₁ ≤ δ ≤ δ₂.
    ElastoplasticCompression,
    /// Elastic recovery, δ from δ₂ down to δ_p.
    ElasticRecovery,
}

impl Phase {
    /// 1, 2 or 3, as the paper numbers the phases.
    pub fn number(self) -> u8 {
        match self {
            Phase::ElasticCompression => 1,
            Phase::ElastoplasticCompression => 2,
            Phase::ElasticRecovery => 3,
        }
    }
}

/// The normal impact of a pair that approach at speed v_r > 0.
///
/// If the contact never yields (v_r too small for the centre pressure to reach σ_p) the impact
/// is pure Hertz: `yielded = false`, δ₁ = δ₂ = δ_max, δ_p = 0, t₁ = t₂ = t_c/2, t₃ = t_c, e = 1.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NormalImpact {
    /// Effective modulus, radius and mass of the pair.
    pub pair: HertzPair,
    /// Yield pressure σ_p = min(σ_p1, σ_p2), Pa (eq. 9).
    pub yield_pressure: f64,
    /// Relative normal approach speed before impact v_r, m/s (> 0).
    pub approach_speed: f64,
    /// Whether the contact yielded (phase 2 happened).
    pub yielded: bool,
    /// Approach at the end of phase 1, δ₁, m (eq. 10).
    pub delta1: f64,
    /// Approach speed at the end of phase 1, δ̇₁, m/s (eq. 12).
    pub delta1_rate: f64,
    /// Maximum approach δ₂ = δ_max, m (eq. 19).
    pub delta2: f64,
    /// Permanent (plastic) approach δ_p, m (eq. 24).
    pub delta_p: f64,
    /// End of phase 1, s (eq. 14).
    pub t1: f64,
    /// End of phase 2 (time of maximum approach), s (eq. 21).
    pub t2: f64,
    /// End of the contact, s (eq. 29).
    pub t3: f64,
    /// Relative separation speed after impact v_r⁺, m/s (eq. 27).
    pub rebound_speed: f64,
    /// Coefficient of restitution e = v_r⁺/v_r (eq. 30).
    pub e: f64,
}

/// Yield approach δ₁ = R (π σ_p / (2E))², m (eq. 10): the approach at which the Hertz centre
/// pressure reaches σ_p (Pa). Infinite if σ_p is infinite (a rigid pair never yields).
pub fn yield_approach(pair: &HertzPair, yield_pressure: f64) -> f64 {
    pair.radius * (PI * yield_pressure / (2.0 * pair.modulus)).powi(2)
}

/// Shifted equilibrium of phase 2, δ_e = σ_p²π²R/(12E²), m: the phase-2 force (eq. 16) is
/// πRσ_p (δ − δ_e).
pub fn plastic_offset(pair: &HertzPair, yield_pressure: f64) -> f64 {
    (PI * yield_pressure).powi(2) * pair.radius / (12.0 * pair.modulus.powi(2))
}

impl NormalImpact {
    /// Solves the three phases for a pair with yield pressure σ_p (Pa, may be infinite: never
    /// yields) approaching at v_r (m/s). Returns `None` when v_r ≤ 0 (no impact) or v_r is
    /// not finite. Pair quantities must be finite and positive.
    pub fn solve(pair: HertzPair, yield_pressure: f64, approach_speed: f64) -> Option<Self> {
        let v = approach_speed;
        if !(v.is_finite() && v > 0.0) {
            return None;
        }
        let d1 = yield_approach(&pair, yield_pressure);
        let dmax_elastic = pair.max_approach(v);
        if d1.is_nan() || d1 >= dmax_elastic {
            // Never yields: the whole impact is Hertz's.
            let tc = pair.contact_duration(v);
            return Some(NormalImpact {
                pair,
                yield_pressure,
                approach_speed: v,
                yielded: false,
                delta1: dmax_elastic,
                delta1_rate: 0.0,
                delta2: dmax_elastic,
                delta_p: 0.0,
                t1: 0.5 * tc,
                t2: 0.5 * tc,
                t3: tc,
                rebound_speed: v,
                e: 1.0,
            });
        }
        // Phase 1: partial Hertz loading.
        let t1 = pair.time_to_approach(v, d1);
        let rate1 = pair.approach_speed(v, d1);
        // Phase 2: harmonic oscillator about δ_e with ω² = πRσ_p/m (eqs. 17–21).
        let de = plastic_offset(&pair, yield_pressure);
        let omega = (PI * pair.radius * yield_pressure / pair.mass).sqrt();
        let d2 = de + (d1 - de).hypot(rate1 / omega);
        let t2 = t1 + (rate1 / omega).atan2(d1 - de) / omega;
        // Phase 3: shifted Hertz unloading from the force reached at δ₂ (eqs. 23–29).
        let p2 = PI * pair.radius * yield_pressure * (d2 - de);
        let recovery = (p2 / pair.stiffness()).powf(2.0 / 3.0);
        let dp = d2 - recovery;
        let k = 16.0 * pair.modulus * pair.radius.sqrt() / (15.0 * pair.mass);
        let rebound = k.sqrt() * recovery.powf(1.25);
        let t3 = t2 + 0.5 * HERTZ_DURATION_FACTOR * recovery / rebound;
        Some(NormalImpact {
            pair,
            yield_pressure,
            approach_speed: v,
            yielded: true,
            delta1: d1,
            delta1_rate: rate1,
            delta2: d2,
            delta_p: dp,
            t1,
            t2,
            t3,
            rebound_speed: rebound,
            e: rebound / v,
        })
    }

    /// Contact force p, N, at approach δ (m) in the given phase: eq. 5 in phase 1, eq. 16 in
    /// phase 2, eq. 22 in phase 3; never negative.
    pub fn force(&self, delta: f64, phase: Phase) -> f64 {
        match phase {
            Phase::ElasticCompression => self.pair.force(delta),
            Phase::ElastoplasticCompression => {
                let de = plastic_offset(&self.pair, self.yield_pressure);
                (PI * self.pair.radius * self.yield_pressure * (delta - de)).max(0.0)
            }
            Phase::ElasticRecovery => self.pair.force(delta - self.delta_p),
        }
    }

    /// Contact duration t₃, s.
    pub fn duration(&self) -> f64 {
        self.t3
    }

    /// Phase at time t (s) since first touch; `None` outside [0, t₃].
    pub fn phase_at(&self, t: f64) -> Option<Phase> {
        if !(0.0..=self.t3).contains(&t) {
            None
        } else if t <= self.t1 {
            Some(Phase::ElasticCompression)
        } else if t <= self.t2 {
            Some(Phase::ElastoplasticCompression)
        } else {
            Some(Phase::ElasticRecovery)
        }
    }

    /// Approach δ(t), m, and approach rate δ̇(t), m/s, at time t (s) since first touch, from the
    /// closed forms of each phase; (0, 0) outside the contact.
    pub fn state_at(&self, t: f64) -> (f64, f64) {
        let Some(phase) = self.phase_at(t) else {
            return (0.0, 0.0);
        };
        let v = self.approach_speed;
        match phase {
            Phase::ElasticCompression => {
                let d = self.pair.approach_at(v, t);
                (d, self.pair.approach_speed(v, d))
            }
            Phase::ElastoplasticCompression => {
                let de = plastic_offset(&self.pair, self.yield_pressure);
                let omega = (PI * self.pair.radius * self.yield_pressure / self.pair.mass).sqrt();
                let amp = self.delta2 - de;
                // δ − δ_e = A sin(ω(t − t₂) + π/2) = A cos(ω(t − t₂)).
                let arg = omega * (t - self.t2);
                (de + amp * arg.cos(), -amp * omega * arg.sin())
            }
            Phase::ElasticRecovery => {
                // A Hertz impact at the rebound speed, shifted by δ_p, past its maximum.
                let vr = self.rebound_speed;
                let half = 0.5 * HERTZ_DURATION_FACTOR * (self.delta2 - self.delta_p) / vr;
                let d = self.pair.approach_at(vr, half + (t - self.t2));
                let s = d;
                (self.delta_p + s, -self.pair.approach_speed(vr, s))
            }
        }
    }
}
