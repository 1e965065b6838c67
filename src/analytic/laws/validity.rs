//! Where a law holds, as its source states it: a one-line range (δ/δ_c, v/v_y, material
//! class) with the source, and a check that turns an impact outside it into a one-line
//! warning.

use super::{ContactPair, Params};
use std::f64::consts::PI;

/// The validity range of a normal law.
#[derive(Clone, Copy)]
pub struct Validity {
    /// One line: the range and the material class, with the source that states it.
    pub range: &'static str,
    /// The warning for an impact of the pair `pair` under parameters `params` that reached
    /// the maximum approach `delta_max` (m) from approach speed `speed` (m/s); `None` inside
    /// the range.
    pub check:
        fn(pair: &ContactPair, params: &Params, delta_max: f64, speed: f64) -> Option<String>,
}

impl Validity {
    /// The warning for an impact (see [`Validity::check`]), prefixed with the law's name.
    pub fn warning(
        &self,
        law: &str,
        pair: &ContactPair,
        params: &Params,
        delta_max: f64,
        speed: f64,
    ) -> Option<String> {
        (self.check)(pair, params, delta_max, speed)
            .map(|w| format!("law {law} at v_r = {speed:.4} m/s: {w}"))
    }
}

/// Approach at the onset of yield of the pair, m: the Hertz approach at which the centre
/// pressure reaches 1.6 σ_s of the softer ball, δ_y = R*(1.6πσ_s/(2E*))² (Johnson 1985,
/// sec. 4.2); infinite when neither ball yields.
pub fn yield_approach(pair: &ContactPair) -> f64 {
    let h = pair.hertz;
    h.radius * (1.6 * PI * pair.yield_strength / (2.0 * h.modulus)).powi(2)
}

/// Laws whose constants are fitted (e, k, A): no range of their own.
pub const FITTED: Validity = Validity {
    range: "any speed and material: e (or k, A) is a fitted constant, not a material law; \
            its e is independent of speed or set by its damping form (Cundall & Strack 1979; Tsuji et al. 1992)",
    check: |_, _, _, _| None,
};

/// Elastic laws: below the onset of yield.
pub const ELASTIC: Validity = Validity {
    range: "elastic contact, delta_max <= delta_y = R*(1.6 pi sigma_s/(2E*))^2 (onset of yield at p0 = 1.6 sigma_s, \
            Johnson 1985 sec. 4.2); any material below yield",
    check: |pair, _, delta_max, _| elastic_check(pair, delta_max),
};

/// The elastic law's warning beyond the onset of yield.
fn elastic_check(pair: &ContactPair, delta_max: f64) -> Option<String> {
    let dy = yield_approach(pair);
    (delta_max > dy).then(|| {
        format!(
            "delta_max/delta_y = {:.1} > 1: the softer ball yields (Johnson 1985), outside this elastic law's range",
            delta_max / dy
        )
    })
}

/// Viscoelastic laws: elastic contact, dissipation by material viscosity.
pub const VISCOELASTIC: Validity = Validity {
    range: "viscoelastic spheres below yield, delta_max <= delta_y (Brilliantov et al. 1996; quasi-static: v_r much \
            below the sound speed); not for plastic metals",
    check: |pair, _, delta_max, _| elastic_check(pair, delta_max),
};

/// Impact-damping laws built for restitution near 1.
pub const NEAR_ELASTIC: Validity = Validity {
    range: "small losses, e near 1: chi v_r < 1 for the closed form (Hunt & Crossley 1975; Lankarani & Nikravesh 1990 \
            derive their damping for e close to 1); no material range",
    check: |_, params, _, _| {
        let e = params.get("e");
        (e < 0.5).then(|| {
            format!("e = {e} is far from 1; the damping was derived for e near 1 (Hunt & Crossley 1975)")
        })
    },
};

/// Elastic-perfectly plastic spheres.
pub const PERFECTLY_PLASTIC: Validity = Validity {
    range:
        "elastic-perfectly plastic spheres beyond yield (Thornton 1997); no bound on v/v_y stated",
    check: |_, _, _, _| None,
};

/// A composition or model without a published range.
pub const UNSTATED: Validity = Validity {
    range: "no range stated by its source",
    check: |_, _, _, _| None,
};
