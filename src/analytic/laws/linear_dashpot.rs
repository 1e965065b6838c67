//! Linear spring-dashpot (Cundall & Strack 1979): F = k δ + c δ̇ with the damping c set from a
//! coefficient of restitution, c = 2 ζ √(k m*), ζ = −ln e / √(π² + ln² e).

use super::params::{LINEAR_STIFFNESS, RESTITUTION, TENSION};
use super::{ClosedForm, ContactPair, NormalLaw, NormalSpec, Params};
use std::f64::consts::PI;

/// The Kelvin-Voigt normal contact.
#[derive(Debug, Clone, Copy)]
pub struct LinearDashpot {
    /// Spring stiffness k, N/m.
    pub stiffness: f64,
    /// Damping ratio ζ (< 1).
    pub damping_ratio: f64,
    /// Effective mass m* the damping was set for, kg.
    pub mass: f64,
    /// Whether the force may pull.
    pub tension: bool,
}

/// Damping ratio ζ that gives restitution e for a linear oscillator ending at δ = 0.
pub fn damping_ratio(e: f64) -> f64 {
    let l = e.ln();
    -l / (PI * PI + l * l).sqrt()
}

impl NormalLaw for LinearDashpot {
    fn loading(&self, delta: f64, rate: f64, _speed: f64) -> f64 {
        let c = 2.0 * self.damping_ratio * (self.stiffness * self.mass).sqrt();
        self.stiffness * delta + c * rate
    }

    fn tensile(&self) -> bool {
        self.tension
    }

    fn closed_form(&self, speed: f64, mass: f64) -> Option<ClosedForm> {
        if !self.tension {
            return None;
        }
        // δ(t) = (v/ω_d) e^{−ζω t} sin(ω_d t): ends at ω_d t = π, turns where
        // tan(ω_d t) = √(1 − ζ²)/ζ.
        let z = 2.0 * self.damping_ratio * (self.stiffness * self.mass).sqrt()
            / (2.0 * (self.stiffness * mass).sqrt());
        let w = (self.stiffness / mass).sqrt();
        let s = (1.0 - z * z).sqrt();
        let wd = w * s;
        let tm = s.atan2(z) / wd;
        Some(ClosedForm {
            e: (-z * PI / s).exp(),
            delta_max: speed / wd * (-z * w * tm).exp() * (wd * tm).sin(),
        })
    }
}

/// The law's description.
pub const SPEC: NormalSpec = NormalSpec {
    name: "linear-dashpot",
    title: "linear spring-dashpot, F = k delta + c delta_dot, c from e",
    source: "P. A. Cundall, O. D. L. Strack, Geotechnique 29 (1979) 47-65",
    dem_codes: "exported and run: LIGGGHTS (hooke/stiffness), LAMMPS (granular hooke, velocity damping), Yade (ViscEl, tension = 0 only); MercuryDPM (LinearViscoelastic, tension = 1, not run); EDEM (linear spring)",
    validity: super::validity::FITTED,
    params: &[LINEAR_STIFFNESS, RESTITUTION, TENSION],
    build: |pair: &ContactPair, p: &Params| {
        Box::new(LinearDashpot {
            stiffness: p.get("k"),
            damping_ratio: damping_ratio(p.get("e")),
            mass: pair.hertz.mass,
            tension: p.tension(),
        })
    },
};
