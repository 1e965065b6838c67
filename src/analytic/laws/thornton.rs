//! Thornton (1997) elastic-perfectly plastic spheres: Hertz until the centre pressure reaches
//! the limiting pressure p_y (δ_y = R*(π p_y/(2E*))²), then F = F_y + π p_y R* (δ − δ_y);
//! unloading is Hertzian with an enlarged radius R_p = 4E* a_p³/(3F_max), a_p² = R* δ_max,
//! F = (4/3) E* √R_p (δ − δ_p)^{3/2}, δ_p = δ_max − a_p²/R_p.
//!
//! Closed form: the loading work is (2/5) F_y δ_y + F_y x + ½ π p_y R* x² (x = δ_max − δ_y);
//! the unloading returns (2/5) F_max (δ_max − δ_p), so e² = that / (½ m* v²).

use super::{ClosedForm, ContactPair, NormalLaw, NormalSpec, ParamSpec, Params, Turn};
use std::f64::consts::PI;

/// Thornton's elastic-perfectly plastic law.
#[derive(Debug, Clone, Copy)]
pub struct Thornton {
    /// E*, Pa.
    pub modulus: f64,
    /// R*, m.
    pub radius: f64,
    /// Limiting contact pressure p_y, Pa.
    pub limit_pressure: f64,
}

impl Thornton {
    /// Yield approach δ_y = R*(π p_y/(2E*))², m.
    pub fn yield_approach(&self) -> f64 {
        self.radius * (PI * self.limit_pressure / (2.0 * self.modulus)).powi(2)
    }

    /// Force gained since yield at approach `delta` (m): π p_y R* (δ − δ_y), N.
    fn plastic_gain(&self, dy: f64, delta: f64) -> f64 {
        PI * self.limit_pressure * self.radius * (delta - dy)
    }

    fn hertz(&self, delta: f64) -> f64 {
        hertz_force(self.modulus, self.radius, delta)
    }
}

/// Hertz force (4/3) E √R δ^{3/2}, N, for modulus E (Pa), radius R (m) and approach δ (m;
/// none below 0).
pub fn hertz_force(modulus: f64, radius: f64, delta: f64) -> f64 {
    4.0 / 3.0 * modulus * radius.sqrt() * delta.max(0.0).powf(1.5)
}

/// Maximum approach (m) at which a Hertz contact (E in Pa, R in m) has taken up `energy` (J).
pub fn hertz_max_approach(modulus: f64, radius: f64, energy: f64) -> f64 {
    (1.25 * energy / (4.0 / 3.0 * modulus * radius.sqrt())).powf(0.4)
}

/// Loading force of a Thornton-type law at approach `delta` (m), N: Hertz (E in Pa, R in m)
/// up to the yield approach `yield_approach` (m); beyond it the Hertz force there plus
/// `plastic(yield_approach)` (N), the force gained since yield.
pub fn yielding_loading(
    modulus: f64,
    radius: f64,
    yield_approach: f64,
    delta: f64,
    plastic: impl FnOnce(f64) -> f64,
) -> f64 {
    if delta <= yield_approach {
        hertz_force(modulus, radius, delta)
    } else {
        hertz_force(modulus, radius, yield_approach) + plastic(yield_approach)
    }
}

/// Unloading of a Thornton-type law from `turn`: enlarged radius R_p (m) and permanent
/// approach δ_p (m), with contact radius a_p² = R δ_max at the turn (δ_max, F_max) (R, E,
/// δ_max, F_max in m, Pa, m, N).
pub fn enlarged_radius(modulus: f64, radius: f64, delta_max: f64, force: f64) -> (f64, f64) {
    let a2 = radius * delta_max;
    let rp = 4.0 * modulus * a2 * a2.sqrt() / (3.0 * force);
    (rp, delta_max - a2 / rp)
}

/// Force on the enlarged-radius Hertz unloading curve, N.
pub fn enlarged_unloading(modulus: f64, radius: f64, delta: f64, turn: &Turn) -> f64 {
    if turn.force <= 0.0 {
        return 0.0;
    }
    let (rp, dp) = enlarged_radius(modulus, radius, turn.delta, turn.force);
    hertz_force(modulus, rp, delta - dp)
}

/// The loading, unloading and residual of a Thornton-type law, as items of its
/// `impl NormalLaw`: [`yielding_loading`] with the law's plastic force gain, then the
/// enlarged-radius Hertz unloading ([`enlarged_unloading`], [`enlarged_radius`]). The law has
/// the fields `modulus` (E*, Pa) and `radius` (R*, m) and the methods `yield_approach()`
/// (δ_y, m) and `plastic_gain(dy, delta)` (the force gained since yield at `delta`, N).
macro_rules! thornton_curves {
    () => {
        fn loading(&self, delta: f64, _rate: f64, _speed: f64) -> f64 {
            yielding_loading(
                self.modulus,
                self.radius,
                self.yield_approach(),
                delta,
                |dy: f64| self.plastic_gain(dy, delta),
            )
        }

        fn unloading(&self, delta: f64, _rate: f64, _speed: f64, turn: &Turn) -> f64 {
            enlarged_unloading(self.modulus, self.radius, delta, turn)
        }

        fn residual(&self, delta: f64, force: f64) -> f64 {
            enlarged_radius(self.modulus, self.radius, delta, force).1
        }
    };
}
pub(super) use thornton_curves;

impl NormalLaw for Thornton {
    thornton_curves!();

    fn thresholds(&self) -> Vec<f64> {
        vec![self.yield_approach()]
    }

    fn closed_form(&self, speed: f64, mass: f64) -> Option<ClosedForm> {
        let e0 = 0.5 * mass * speed * speed;
        let dy = self.yield_approach();
        let fy = self.hertz(dy);
        let wy = 0.4 * fy * dy;
        let delta_max = if e0 <= wy {
            hertz_max_approach(self.modulus, self.radius, e0)
        } else {
            let c = PI * self.limit_pressure * self.radius;
            let x = 2.0 * (e0 - wy) / (fy + (fy * fy + 2.0 * c * (e0 - wy)).sqrt());
            dy + x
        };
        Some(hertzian_rebound(self, speed, e0, delta_max))
    }
}

/// The closed form of a law that unloads along a Hertz curve (an enlarged radius), from the
/// maximum approach `delta_max` (m) it reaches from the kinetic energy `e0` (J) of approach
/// speed `speed` (m/s): the unloading returns (2/5) F_max (δ_max − δ_p), so e² = that / e0.
pub fn hertzian_rebound<L: NormalLaw>(law: &L, speed: f64, e0: f64, delta_max: f64) -> ClosedForm {
    let turn = Turn::new(law, delta_max, law.loading(delta_max, 0.0, speed));
    let dp = turn.residual();
    let back = 0.4 * turn.force * (delta_max - dp);
    ClosedForm {
        e: (back / e0).sqrt().min(1.0),
        delta_max,
    }
}

/// Limiting-pressure parameter shared by the Thornton-type laws: default the pair's σ_p.
pub const LIMIT_PRESSURE: ParamSpec = ParamSpec {
    key: "p_y",
    unit: "Pa",
    doc: "limiting contact pressure (default: the pair's sigma_p = (1 + pi/2) sigma_s, as the three-phase model)",
    min: 1.0,
    max: 1e13,
    default: |p| p.yield_pressure.min(1e13),
};

/// The law's description.
pub const SPEC: NormalSpec = NormalSpec {
    name: "thornton",
    title: "Thornton elastic-perfectly plastic: Hertz, linear plastic loading at p_y, Hertz unloading with enlarged radius",
    source: "C. Thornton, J. Appl. Mech. 64 (1997) 383-386",
    dem_codes: "not exported: LIGGGHTS thornton_ning without adhesion unloads with the original radius, not R_p; not LAMMPS, Yade, MercuryDPM",
    validity: super::validity::PERFECTLY_PLASTIC,
    params: &[LIMIT_PRESSURE],
    build: |pair: &ContactPair, p: &Params| {
        Box::new(Thornton {
            modulus: pair.hertz.modulus,
            radius: pair.hertz.radius,
            limit_pressure: p.get("p_y"),
        })
    },
};
