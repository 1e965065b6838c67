//! Hertz with restitution-based damping in the form of Tsuji, Tanaka & Ishida (1992) as
//! LIGGGHTS `hertz` and EDEM Hertz-Mindlin implement it:
//! F = k_n δ + γ_n δ̇, k_n = (4/3) E* √(R* δ), γ_n = 2 √(5/6) |β| √(S_n m*),
//! S_n = 2 E* √(R* δ), β = ln e / √(ln² e + π²).

use super::hertz::ELASTIC_PARAMS;
use super::params::{RESTITUTION, TENSION};
use super::{ContactPair, NormalLaw, NormalSpec, Params};
use std::f64::consts::PI;

/// The damped Hertz law.
#[derive(Debug, Clone, Copy)]
pub struct HertzDamped {
    /// Effective modulus E*, Pa.
    pub modulus: f64,
    /// Effective radius R*, m.
    pub radius: f64,
    /// Effective mass m*, kg.
    pub mass: f64,
    /// |β| from the target restitution.
    pub beta: f64,
    /// Whether the force may pull.
    pub tension: bool,
}

impl NormalLaw for HertzDamped {
    fn loading(&self, delta: f64, rate: f64, _speed: f64) -> f64 {
        let d = delta.max(0.0);
        let root = (self.radius * d).sqrt();
        let kn = 4.0 / 3.0 * self.modulus * root;
        let sn = 2.0 * self.modulus * root;
        let gn = 2.0 * (5.0f64 / 6.0).sqrt() * self.beta * (sn * self.mass).sqrt();
        kn * d + gn * rate
    }

    fn tensile(&self) -> bool {
        self.tension
    }
}

/// The law's description.
pub const SPEC: NormalSpec = NormalSpec {
    name: "hertz-damped",
    title: "Hertz with restitution-based damping (Tsuji form, as LIGGGHTS hertz and EDEM use it)",
    source: "Y. Tsuji, T. Tanaka, T. Ishida, Powder Technol. 71 (1992) 239-250; damping constant as in the LIGGGHTS hertz documentation",
    dem_codes: "exported and run: LIGGGHTS (hertz), LAMMPS (granular hertz, tsuji damping at an equivalent coefficient), Yade (Hertz-Mindlin with betan, tension = 0 only); MercuryDPM (HertzianViscoelastic, not run); EDEM (Hertz-Mindlin)",
    validity: super::validity::FITTED,
    params: &[ELASTIC_PARAMS[0], ELASTIC_PARAMS[1], RESTITUTION, TENSION],
    build: |pair: &ContactPair, p: &Params| {
        let l = p.get("e").ln();
        Box::new(HertzDamped {
            modulus: p.get("E_star"),
            radius: p.get("R_star"),
            mass: pair.hertz.mass,
            beta: (l / (l * l + PI * PI).sqrt()).abs(),
            tension: p.tension(),
        })
    },
};
