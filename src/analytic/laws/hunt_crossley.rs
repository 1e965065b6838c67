//! Hunt & Crossley (1975): Hertz with a damping proportional to the elastic force,
//! F = K δ^{3/2} (1 + χ δ̇), χ = 3(1 − e)/(2 v_r) (their low-loss estimate of χ from e).
//!
//! Closed form: m* δ̇ dδ̇/dδ = −K δ^{3/2}(1 + χ δ̇) separates; with
//! Φ(u) = (χu − ln(1 + χu))/χ², Φ(δ̇) − Φ(v_r) = −(2/5)(K/m*) δ^{5/2}, so
//! δ_max^{5/2} = (5/2)(m*/K) Φ(v_r) and the exit speed w solves Φ(−w) = Φ(v_r) (δ back to 0).

use super::hertz::{stiffness, ELASTIC_PARAMS};
use super::params::RESTITUTION;
use super::{ClosedForm, ContactPair, NormalLaw, NormalSpec, Params};

/// A Hertz law with Hunt-Crossley-type damping: F = K δ^{3/2}(1 + (c/v_r) δ̇).
#[derive(Debug, Clone, Copy)]
pub struct HuntCrossley {
    /// K, N/m^{3/2}.
    pub stiffness: f64,
    /// c = χ v_r, dimensionless (3(1 − e)/2 for Hunt-Crossley).
    pub factor: f64,
}

impl NormalLaw for HuntCrossley {
    fn loading(&self, delta: f64, rate: f64, speed: f64) -> f64 {
        self.stiffness * delta.max(0.0).powf(1.5) * (1.0 + self.factor * rate / speed)
    }

    fn closed_form(&self, speed: f64, mass: f64) -> Option<ClosedForm> {
        closed_form(self.stiffness, self.factor / speed, speed, mass)
    }
}

/// Φ(u) = (χu − ln(1 + χu))/χ², m²/s²; requires 1 + χu > 0.
fn phi(chi: f64, u: f64) -> f64 {
    let x = chi * u;
    (x - x.ln_1p()) / (chi * chi)
}

/// Closed form of F = K δ^{3/2}(1 + χ δ̇) at approach speed v (m/s), mass m (kg); `None` when
/// χ v ≥ 1 (the force would pull before δ returns to 0, outside the closed form).
pub fn closed_form(k: f64, chi: f64, v: f64, m: f64) -> Option<ClosedForm> {
    if (chi * v).is_nan() || chi * v >= 1.0 || chi <= 0.0 {
        return None;
    }
    let target = phi(chi, v);
    let delta_max = (2.5 * m / k * target).powf(0.4);
    // Φ(−w) rises from 0 (w = 0) to ∞ (w → 1/χ): bisect for Φ(−w) = Φ(v).
    let (mut lo, mut hi) = (0.0, (1.0 / chi).min(v));
    if phi(chi, -hi) < target {
        return None;
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if phi(chi, -mid) < target {
            lo = mid;
        } else {
            hi = mid;
        }
        if hi - lo <= 1e-16 * v {
            break;
        }
    }
    Some(ClosedForm {
        e: 0.5 * (lo + hi) / v,
        delta_max,
    })
}

/// The law's description.
pub const SPEC: NormalSpec = NormalSpec {
    name: "hunt-crossley",
    title: "Hunt-Crossley, F = K delta^(3/2) (1 + 3(1 - e)/2 delta_dot/v_r)",
    source: "K. H. Hunt, F. R. E. Crossley, J. Appl. Mech. 42 (1975) 440-445",
    dem_codes: "none of LIGGGHTS, LAMMPS, Yade, MercuryDPM (multibody codes: Adams, Chrono)",
    validity: super::validity::NEAR_ELASTIC,
    params: &[ELASTIC_PARAMS[0], ELASTIC_PARAMS[1], RESTITUTION],
    build: |_pair: &ContactPair, p: &Params| {
        Box::new(HuntCrossley {
            stiffness: stiffness(p),
            factor: 1.5 * (1.0 - p.get("e")),
        })
    },
};
