//! The hardening seam: what a J2 return mapping needs from a law for the flow stress, in
//! scalar and lane form, and the safeguarded Newton solve shared by nonlinear laws.

use crate::fe::simd::{select, Lanes};

/// An isotropic hardening law of J2 plasticity: the flow stress σ_y as a function of the
/// equivalent plastic strain ε_p (and, for rate-dependent laws, of the plastic strain rate
/// over the step). Both element formulations reach it through
/// [`super::j2::J2Material::update`] (scalar) and [`super::j2::update_lanes`] (lanes).
///
/// A law implements the scalar methods; the lane methods default to the scalar ones lane by
/// lane (bit for bit the scalar result), and a law whose return has a closed form overrides
/// them with vector arithmetic (as [`super::Bilinear`] does).
///
/// A law that keeps history at each integration point declares how many values
/// ([`Hardening::HISTORY`]) and updates them in [`Hardening::update_history`]; the element
/// block keeps them in an array of their own beside the point rows, so that a law without
/// history (every built-in one) costs nothing.
pub trait Hardening: Copy + std::fmt::Debug + Send + Sync {
    /// History values the law keeps per integration point (0: none).
    const HISTORY: usize = 0;

    /// Updates one integration point's `history` ([`Hardening::HISTORY`] values, zero at
    /// the start of a run) after the point's step: `eps_p` is the equivalent plastic strain
    /// at the start of the step, `dp` its increment over the step (ε_p at the end minus
    /// `eps_p`; 0 when the point stayed elastic), `dt` the step, s. The element loop calls
    /// it for every point it advances, on every kernel path. Default: nothing.
    #[inline(always)]
    fn update_history(&self, _history: &mut [f64], _eps_p: f64, _dp: f64, _dt: f64) {}

    /// True when the flow stress does not depend on the strain rate: the law has no time
    /// scale, so a model of it scales with its lengths (similar scenes share one run). No
    /// default: every law says.
    fn rate_independent(&self) -> bool;

    /// Flow stress at `eps_p` and a plastic strain rate no higher than the law's reference
    /// rate (the elastic check), Pa.
    fn static_yield(&self, eps_p: f64) -> f64;

    /// The radial return of a trial von Mises stress `q` (Pa) above `sy` =
    /// [`Hardening::static_yield`]`(eps_p)`: the plastic strain increment Δε_p > 0 with
    /// q − 3G Δε_p = σ_y(ε_p + Δε_p, Δε_p/Δt) for shear modulus `shear` (Pa) and step `dt`
    /// (s; dt ≤ 0 evaluates at the reference rate), and the plastic work per unit volume of
    /// the increment, J/m³.
    fn plastic_increment(&self, q: f64, sy: f64, eps_p: f64, shear: f64, dt: f64) -> (f64, f64);

    /// Lane-wise [`Hardening::static_yield`].
    #[inline(always)]
    fn static_yield_lanes<const W: usize>(&self, eps_p: Lanes<W>) -> Lanes<W> {
        let mut r = eps_p;
        for l in 0..W {
            r.0[l] = self.static_yield(eps_p.0[l]);
        }
        r
    }

    /// Lane-wise [`Hardening::plastic_increment`] on the lanes where `yields`; zero on the
    /// others. Returns (Δε_p, plastic work per unit volume in J/m³).
    #[inline(always)]
    fn plastic_increment_lanes<const W: usize>(
        &self,
        yields: [bool; W],
        q: Lanes<W>,
        sy: Lanes<W>,
        eps_p: Lanes<W>,
        shear: f64,
        dt: f64,
    ) -> (Lanes<W>, Lanes<W>) {
        let zero = q.splat_like(0.0);
        let (mut dp, mut work) = (zero, zero);
        for l in 0..W {
            if yields[l] {
                let (d, w) = self.plastic_increment(q.0[l], sy.0[l], eps_p.0[l], shear, dt);
                dp.0[l] = d;
                work.0[l] = w;
            }
        }
        (select(yields, dp, zero), select(yields, work, zero))
    }
}

/// Solves q − 3G Δp = σ_y(Δp) for Δp by Newton's method kept inside a shrinking bracket
/// (bisection whenever a step would leave it or the slope is not finite), for a flow
/// stress `flow(Δp) = (σ_y, dσ_y/dΔp)` non-decreasing in Δp. `q` (Pa) exceeds `sy` =
/// σ_y at Δp = 0 at the reference rate; the root lies in (0, (q − sy)/(3G)], since σ_y never
/// falls below `sy`; `flow(0)` must be exactly (`sy`, ·). Returns Δp and the plastic work per unit volume by the trapezoidal rule
/// on the flow stress at the two ends of the increment, J/m³.
pub fn newton_return(q: f64, sy: f64, shear: f64, flow: impl Fn(f64) -> (f64, f64)) -> (f64, f64) {
    let hi = (q - sy) / (3.0 * shear);
    let x = newton_root(q, shear, (0.0, hi), hi, &flow);
    // σ_y at Δp = 0 is `sy` (the contract above): no second evaluation of the flow stress.
    let end = flow(x).0;
    (x, 0.5 * x * (sy + end))
}

/// The root Δp (dimensionless) of q − 3G Δp = σ_y(Δp) in the bracket `(lo, hi]`, where
/// the residual is positive at lo and not positive at hi: Newton's method from `start`
/// (in the bracket) kept inside the shrinking bracket, bisection whenever a step would
/// leave it or the slope is not finite. `q` and `flow` as in [`newton_return`]; `shear` G
/// in Pa. Where the residual is convex (a concave flow stress), Newton from the left end
/// climbs to the root monotonically, while from the right it overshoots below the root
/// (and out of a tight bracket, into bisection steps).
pub fn newton_root(
    q: f64,
    shear: f64,
    bracket: (f64, f64),
    start: f64,
    flow: impl Fn(f64) -> (f64, f64),
) -> f64 {
    let three_g = 3.0 * shear;
    let (mut lo, mut hi) = bracket;
    let mut x = start;
    for _ in 0..200 {
        let (s, ds) = flow(x);
        let f = q - three_g * x - s;
        if f > 0.0 {
            lo = x;
        } else {
            hi = x;
        }
        if f == 0.0 || hi - lo <= 4.0 * f64::EPSILON * hi {
            break;
        }
        let step = f / (three_g + ds);
        let next = x + step;
        if step.is_finite() && next > lo && next < hi {
            x = next;
            if step.abs() <= 4.0 * f64::EPSILON * x {
                break;
            }
        } else {
            x = 0.5 * (lo + hi);
        }
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Linear hardening: the Newton solve lands on the closed form Δp = (q − σ_y)/(3G + H).
    #[test]
    fn newton_return_reproduces_the_linear_closed_form() {
        let (g, h, sy, q) = (45e9, 1.2e9, 100e6, 180e6);
        let (dp, w) = newton_return(q, sy, g, |x| (sy + h * x, h));
        let want = (q - sy) / (3.0 * g + h);
        assert!((dp - want).abs() <= 1e-14 * want, "{dp} vs {want}");
        let wwant = want * (sy + 0.5 * h * want);
        assert!((w - wwant).abs() <= 1e-13 * wwant, "{w} vs {wwant}");
    }

    /// A flow stress with an infinite slope at the start (ε^0.3 from zero) still converges.
    #[test]
    fn newton_return_survives_an_infinite_initial_slope() {
        let (g, sy, k, n) = (45e9, 100e6, 300e6, 0.3);
        let q = 400e6;
        let flow = |x: f64| (sy + k * x.powf(n), n * k * x.powf(n - 1.0));
        let (dp, _) = newton_return(q, sy, g, flow);
        let r = q - 3.0 * g * dp - flow(dp).0;
        assert!(dp > 0.0 && r.abs() <= 1e-6 * q, "dp {dp}, residual {r} Pa");
    }
}
