//! Jackson & Green (2005) elastic-plastic sphere on a rigid flat, from finite-element fits,
//! with the unloading of Jackson, Green & Marghitu (2010).
//!
//! Loading (x = δ/δ_c): Hertz for x ≤ 1.9; beyond,
//! F/F_c = exp(−¼ x^{5/12}) x^{3/2} + (4 H_G/(C S_y)) [1 − exp(−x^{5/9}/25)] x, with
//! C = 1.295 exp(0.736 ν), δ_c = R(π C S_y/(2E*))², F_c = (4/3)(R/E*)²(π C S_y/2)³,
//! H_G/S_y = 2.84 [1 − exp(−0.82 (a/R)^{−0.7})], a/R = √(δ/R) (x/1.9)^{B/2},
//! B = 0.14 exp(23 S_y/E*).
//! Unloading: F = F_max ((δ − δ_r)/(δ_max − δ_r))^{3/2},
//! δ_r/δ_max = 1.02 [1 − ((x_max + 5.9)/6.9)^{−0.54}] (0 for x_max ≤ 1).

use super::quasi_static::max_approach;
use super::validity::Validity;
use super::{ClosedForm, ContactPair, NormalLaw, NormalSpec, ParamSpec, Params, Turn};
use std::f64::consts::PI;

/// The Jackson-Green law for one pair.
#[derive(Debug, Clone, Copy)]
pub struct JacksonGreen {
    /// E*, Pa.
    pub modulus: f64,
    /// R*, m.
    pub radius: f64,
    /// Yield strength S_y, Pa.
    pub yield_strength: f64,
    /// Poisson's ratio ν of the yielding body.
    pub poisson: f64,
}

impl JacksonGreen {
    fn c(&self) -> f64 {
        1.295 * (0.736 * self.poisson).exp()
    }

    /// Critical approach δ_c, m.
    pub fn critical_approach(&self) -> f64 {
        self.radius * (PI * self.c() * self.yield_strength / (2.0 * self.modulus)).powi(2)
    }

    fn critical_force(&self) -> f64 {
        4.0 / 3.0
            * (self.radius / self.modulus).powi(2)
            * (0.5 * PI * self.c() * self.yield_strength).powi(3)
    }
}

impl NormalLaw for JacksonGreen {
    fn loading(&self, delta: f64, _rate: f64, _speed: f64) -> f64 {
        let d = delta.max(0.0);
        let x = d / self.critical_approach();
        let fc = self.critical_force();
        if x <= 1.9 {
            return fc * x.powf(1.5);
        }
        let b = 0.14 * (23.0 * self.yield_strength / self.modulus).exp();
        let a_over_r = (d / self.radius).sqrt() * (x / 1.9).powf(0.5 * b);
        let hardness = 2.84 * (1.0 - (-0.82 * a_over_r.powf(-0.7)).exp());
        fc * ((-0.25 * x.powf(5.0 / 12.0)).exp() * x.powf(1.5)
            + 4.0 * hardness / self.c() * (1.0 - (-x.powf(5.0 / 9.0) / 25.0).exp()) * x)
    }

    fn residual(&self, delta: f64, _force: f64) -> f64 {
        let x = delta / self.critical_approach();
        if x <= 1.0 {
            0.0
        } else {
            delta * 1.02 * (1.0 - ((x + 5.9) / 6.9).powf(-0.54))
        }
    }

    fn unloading(&self, delta: f64, _rate: f64, _speed: f64, turn: &Turn) -> f64 {
        let r = turn.residual();
        turn.force * ((delta - r).max(0.0) / (turn.delta - r)).powf(1.5)
    }

    fn thresholds(&self) -> Vec<f64> {
        vec![1.9 * self.critical_approach()]
    }

    fn closed_form(&self, speed: f64, mass: f64) -> Option<ClosedForm> {
        let e0 = 0.5 * mass * speed * speed;
        let guess = (1.25 * e0 / (4.0 / 3.0 * self.modulus * self.radius.sqrt())).powf(0.4);
        let delta_max = max_approach(self, e0, guess);
        let turn = Turn::new(self, delta_max, self.loading(delta_max, 0.0, speed));
        let back = 0.4 * turn.force * (delta_max - turn.residual());
        Some(ClosedForm {
            e: (back / e0).sqrt(),
            delta_max,
        })
    }
}

/// The law's description.
pub const SPEC: NormalSpec = NormalSpec {
    name: "jackson-green",
    title: "Jackson-Green elastic-plastic FE fit, Jackson-Green-Marghitu unloading",
    source: "R. L. Jackson, I. Green, J. Tribol. 127 (2005) 343-354; R. L. Jackson, I. Green, D. B. Marghitu, Nonlinear Dyn. 60 (2010) 217-229",
    dem_codes: "none of LIGGGHTS, LAMMPS, Yade, MercuryDPM",
    validity: VALIDITY,
    params: &[
        ParamSpec {
            key: "S_y",
            unit: "Pa",
            doc: "yield strength (default: the softer ball's)",
            min: 1.0,
            max: 1e12,
            default: |p| p.yield_strength.min(1e12),
        },
        ParamSpec {
            key: "nu",
            unit: "-",
            doc: "Poisson's ratio in C = 1.295 exp(0.736 nu) (default: the softer ball's)",
            min: 0.0,
            max: 0.5,
            default: |p| p.poisson,
        },
    ],
    build: |pair: &ContactPair, p: &Params| {
        Box::new(JacksonGreen {
            modulus: pair.hertz.modulus,
            radius: pair.hertz.radius,
            yield_strength: p.get("S_y"),
            poisson: p.get("nu"),
        })
    },
};

/// Jackson-Green: the FE fits' range of δ/δ_c.
pub const VALIDITY: Validity = Validity {
    range: "elastic-perfectly plastic, delta_max/delta_c <= 110: the residual-approach fit of Etsion, Kligerman & \
            Kadin (2005, Int. J. Solids Struct. 42, 3716) was made up to about that interference",
    check: |pair, params, delta_max, _| {
        let jg = JacksonGreen {
            modulus: pair.hertz.modulus,
            radius: pair.hertz.radius,
            yield_strength: params.get("S_y"),
            poisson: params.get("nu"),
        };
        let x = delta_max / jg.critical_approach();
        (x > 110.0).then(|| {
            format!(
                "delta_max/delta_c = {x:.0} > 110, outside the FE fits (Etsion, Kligerman & Kadin 2005): \
                 delta_r/delta_max is extrapolated"
            )
        })
    },
};
