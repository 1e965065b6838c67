//! Elastic-plastic contact with strain hardening by Johnson's method with Tabor's
//! representative strain: Thornton's loading and unloading, with the limiting pressure
//! rising with the flow stress at ε_r = 0.2 a/R, a = √(R* δ):
//! p_lim(δ) = c σ_f(ε_r), σ_f(ε) = S_y + E_t max(0, ε − S_y/E) (bilinear material),
//! dF/dδ = π R* p_lim(δ) beyond δ_y = R*(π c S_y/(2E*))², Hertz below; unloading as Thornton
//! (enlarged radius). c = 1 + π/2 by default, so that with E_t = 0 the law is Thornton's with
//! the three-phase model's σ_p.

use super::quasi_static::max_approach;
use super::thornton::{
    enlarged_radius, enlarged_unloading, hertz_max_approach, hertzian_rebound, thornton_curves,
    yielding_loading,
};
use super::{ClosedForm, ContactPair, NormalLaw, NormalSpec, ParamSpec, Params, Turn};
use std::f64::consts::PI;

/// The hardening law for one pair.
#[derive(Debug, Clone, Copy)]
pub struct TaborHardening {
    /// E*, Pa.
    pub modulus: f64,
    /// R*, m.
    pub radius: f64,
    /// Constraint factor c = p_lim/σ_f.
    pub constraint: f64,
    /// Initial yield strength S_y, Pa.
    pub yield_strength: f64,
    /// Young's modulus E of the yielding body, Pa.
    pub youngs: f64,
    /// Tangent modulus E_t, Pa.
    pub tangent: f64,
}

impl TaborHardening {
    /// Yield approach δ_y, m.
    pub fn yield_approach(&self) -> f64 {
        self.radius * (PI * self.constraint * self.yield_strength / (2.0 * self.modulus)).powi(2)
    }

    /// Approach where the representative strain reaches the yield strain, R*(5 S_y/E)², m.
    pub fn hardening_approach(&self) -> f64 {
        self.radius * (5.0 * self.yield_strength / self.youngs).powi(2)
    }

    /// ∫_a^b p_lim(s) ds, Pa·m, for 0 ≤ a ≤ b.
    fn pressure_integral(&self, a: f64, b: f64) -> f64 {
        let sh = self.hardening_approach();
        let c = self.constraint;
        let flat = |a: f64, b: f64| c * self.yield_strength * (b - a).max(0.0);
        let rising = |a: f64, b: f64| {
            if b <= a {
                return 0.0;
            }
            c * (self.yield_strength * (1.0 - self.tangent / self.youngs) * (b - a)
                + 0.2 * self.tangent / self.radius.sqrt()
                    * (2.0 / 3.0)
                    * (b * b.sqrt() - a * a.sqrt()))
        };
        flat(a, b.min(sh)) + rising(a.max(sh), b)
    }

    /// Force gained since yield at approach `delta` (m): π R* ∫_δy^δ p_lim, N.
    fn plastic_gain(&self, dy: f64, delta: f64) -> f64 {
        PI * self.radius * self.pressure_integral(dy, delta)
    }
}

impl NormalLaw for TaborHardening {
    thornton_curves!();

    fn thresholds(&self) -> Vec<f64> {
        let (dy, sh) = (self.yield_approach(), self.hardening_approach());
        if sh > dy {
            vec![dy, sh]
        } else {
            vec![dy]
        }
    }

    fn closed_form(&self, speed: f64, mass: f64) -> Option<ClosedForm> {
        let e0 = 0.5 * mass * speed * speed;
        let guess = hertz_max_approach(self.modulus, self.radius, e0);
        let delta_max = max_approach(self, e0, guess);
        Some(hertzian_rebound(self, speed, e0, delta_max))
    }
}

/// The law's description.
pub const SPEC: NormalSpec = NormalSpec {
    name: "tabor-hardening",
    title: "Thornton-type elastic-plastic law with linear strain hardening at Tabor's representative strain 0.2 a/R",
    source: "K. L. Johnson, Contact Mechanics (CUP 1985) sec. 6.2; D. Tabor, The Hardness of Metals (1951); unloading C. Thornton, J. Appl. Mech. 64 (1997) 383",
    dem_codes: "none of LIGGGHTS, LAMMPS, Yade, MercuryDPM",
    validity: super::validity::UNSTATED,
    params: &[
        ParamSpec {
            key: "c",
            unit: "-",
            doc: "constraint factor p_lim/flow stress (default 1 + pi/2, the three-phase model's)",
            min: 1.0,
            max: 10.0,
            default: |_| 1.0 + std::f64::consts::FRAC_PI_2,
        },
        ParamSpec {
            key: "S_y",
            unit: "Pa",
            doc: "initial yield strength (default: the softer ball's)",
            min: 1.0,
            max: 1e12,
            default: |p| p.yield_strength.min(1e12),
        },
        ParamSpec {
            key: "E_t",
            unit: "Pa",
            doc: "tangent modulus after yield (default: the softer ball's)",
            min: 0.0,
            max: 1e13,
            default: |p| p.tangent.min(1e13),
        },
        ParamSpec {
            key: "E",
            unit: "Pa",
            doc: "Young's modulus of the yielding ball (default: the softer ball's)",
            min: 1.0,
            max: 1e13,
            default: |p| p.youngs.min(1e13),
        },
    ],
    build: |pair: &ContactPair, p: &Params| {
        Box::new(TaborHardening {
            modulus: pair.hertz.modulus,
            radius: pair.hertz.radius,
            constraint: p.get("c"),
            yield_strength: p.get("S_y"),
            youngs: p.get("E"),
            tangent: p.get("E_t"),
        })
    },
};
