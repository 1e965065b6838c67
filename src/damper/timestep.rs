//! The time step from the stiffest contact: each contact kind's normal and tangential
//! oscillation at the approach a Hertz impact reaches at the characteristic speed.

use super::pairs::PairLaws;
use crate::analytic::laws::Turn;
use std::f64::consts::PI;

/// Stiffness, damping and period of one contact kind at its reference approach.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactScale {
    /// Reference approach: the Hertz δ_max at the characteristic speed, m.
    pub delta: f64,
    /// Normal stiffness: the largest of the law's loading tangent, its secant, its unloading
    /// tangent from a turn there and Hertz's tangent 2E*√(R*δ), N/m.
    pub normal_stiffness: f64,
    /// Normal damping ∂F/∂δ̇ at the reference approach, N·s/m.
    pub normal_damping: f64,
    /// Tangential stiffness k_t(δ), N/m.
    pub tangential_stiffness: f64,
    /// Normal oscillation period with m*, s.
    pub normal_period: f64,
    /// Tangential oscillation period with m_t (infinite for k_t = 0), s.
    pub tangential_period: f64,
    /// Stability limit of the damped normal oscillator in velocity Verlet,
    /// (2/ω)(√(1 + ζ²) − ζ), s.
    pub critical: f64,
}

/// The scales of contact kind `laws` for characteristic impact speed `speed` (m/s).
pub fn contact_scale(laws: &PairLaws, speed: f64) -> ContactScale {
    let h = laws.pair.hertz;
    let delta = h.max_approach(speed);
    let law = laws.normal.as_ref();
    let f = |d: f64, r: f64| law.loading(d, r, speed);
    let eps = 1e-6 * delta;
    let tangent = (f(delta + eps, 0.0) - f(delta - eps, 0.0)) / (2.0 * eps);
    let secant = f(delta, 0.0) / delta;
    let hertz = 2.0 * h.modulus * (h.radius * delta).sqrt();
    let turn = Turn::new(law, delta, f(delta, 0.0));
    let u = |d: f64| law.unloading(d, 0.0, speed, &turn);
    let unloading = (u(delta) - u(delta - eps)) / eps;
    let k = tangent.max(secant).max(hertz).max(unloading);
    let dv = 1e-3 * speed;
    let c = ((f(delta, dv) - f(delta, 0.0)) / dv).max(0.0);
    let kt = laws.tangential.stiffness(delta);
    let wn = (k / h.mass).sqrt();
    let wt = (kt / laws.tangential_mass).sqrt();
    let zeta = c / (2.0 * (k * h.mass).sqrt());
    ContactScale {
        delta,
        normal_stiffness: k,
        normal_damping: c,
        tangential_stiffness: kt,
        normal_period: 2.0 * PI / wn,
        tangential_period: 2.0 * PI / wt,
        critical: 2.0 / wn * ((1.0 + zeta * zeta).sqrt() - zeta),
    }
}

/// The tangential spring's share of the normal law's steps per period: the stick oscillation
/// of the Mindlin spring carries little energy and is capped by friction, and a third of the
/// normal resolution (20 steps per tangential period at the default 60) leaves the rebound,
/// the energy balance and the frame's damping ratio as they are at full resolution
/// (docs/damper.md).
pub const TANGENTIAL_SHARE: f64 = 1.0 / 3.0;

/// The step (s): over `kinds`, the shortest normal period divided by `steps_per_period` and
/// tangential period divided by `steps_per_period` × [`TANGENTIAL_SHARE`], at most a tenth of
/// the damped normal stability limit and at most the frame's period (`frame`, s) over 2000.
pub fn time_step<'a>(
    kinds: impl Iterator<Item = &'a PairLaws>,
    speed: f64,
    steps_per_period: f64,
    frame: f64,
) -> f64 {
    kinds
        .map(|l| {
            let s = contact_scale(l, speed);
            (s.normal_period / steps_per_period)
                .min(s.tangential_period / (steps_per_period * TANGENTIAL_SHARE))
                .min(0.1 * s.critical)
        })
        .fold(frame / 2000.0, f64::min)
}
