//! Error estimates from a mesh ladder: Richardson extrapolation, the observed order and
//! Roache's grid convergence index (GCI).
//!
//! A ladder holds one quantity f computed on meshes of size h, h/r, h/r², … (coarse to fine,
//! r > 1 the refinement ratio). With the three finest values f₃ (coarsest), f₂, f₁ (finest) and
//! the differences d₃₂ = f₂ − f₃, d₂₁ = f₁ − f₂:
//! - observed order p = ln(d₃₂/d₂₁)/ln r, defined when d₃₂/d₂₁ > 0 (monotone ladder);
//! - extrapolated value f₀ = f₁ + d₂₁/(r^p − 1), exact for f(h) = f₀ + C h^p;
//! - estimate of |f₁ − f₀|: GCI = F_s |d₂₁|/(r^p − 1) with F_s = 1.25 (three levels, observed
//!   order) or F_s = 3 (two levels, assumed order): Roache, *Verification and Validation in
//!   Computational Science and Engineering* (1998), ch. 5, and Celik et al., J. Fluids Eng.
//!   130 (2008) 078001.
//!
//! Two levels: the order is assumed to be 2, the formal order of linear elements. With r = 2
//! the two-level estimate 3 |d₂₁|/(2² − 1) = |d₂₁| is the full coarse-to-fine difference, which
//! bounds the finest value's error whenever the true order is at least 1 (|f₁ − f₀| =
//! |d₂₁|/(r^p − 1) ≤ |d₂₁| for p ≥ 1): a contact problem that converges slower than linear
//! elements do still gets an honest bar. A quantity known to converge at first order takes
//! its own assumed order ([`estimate_assuming`]; the tangential figures of an oblique impact).
//!
//! Ladders that do not converge monotonically get no extrapolation and a flag
//! ([`Behaviour`]): oscillatory (d₃₂ and d₂₁ of opposite sign) or an observed order outside
//! [`ORDER_RANGE`]; their estimate is F_s times the largest difference of the three finest
//! values. Nothing here returns NaN: undefined quantities are `None`.

use serde::Serialize;

/// Safety factor of the GCI with an observed order (three or more levels).
pub const SAFETY_OBSERVED: f64 = 1.25;
/// Safety factor of the GCI with an assumed order (two levels).
pub const SAFETY_ASSUMED: f64 = 3.0;
/// The order assumed for two levels: the formal order of linear elements.
pub const ASSUMED_ORDER: f64 = 2.0;
/// Observed orders trusted for extrapolation; outside it the ladder is flagged.
pub const ORDER_RANGE: (f64, f64) = (0.5, 6.0);

/// How the finest values of a ladder approach their limit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Behaviour {
    /// Three or more levels, monotone, observed order within [`ORDER_RANGE`].
    Monotone,
    /// Two levels only: the order is assumed ([`ASSUMED_ORDER`]).
    TwoLevels,
    /// The finest values are all equal: nothing left to estimate.
    Converged,
    /// The differences change sign: no order, no extrapolation.
    Oscillatory,
    /// Monotone, but the observed order is outside [`ORDER_RANGE`] (or the finest step is
    /// zero while the coarser one is not): no extrapolation.
    OrderOutOfRange,
    /// Read back from a record that keeps the finest value and its error only
    /// ([`value_and_error`]): how the ladder behaved is not known.
    Recorded,
}

impl Behaviour {
    /// The flag as printed and written (`monotone`, `two_levels`, …).
    pub fn name(self) -> &'static str {
        match self {
            Behaviour::Monotone => "monotone",
            Behaviour::TwoLevels => "two_levels",
            Behaviour::Converged => "converged",
            Behaviour::Oscillatory => "oscillatory",
            Behaviour::OrderOutOfRange => "order_out_of_range",
            Behaviour::Recorded => "recorded",
        }
    }

    /// True when the estimate rests on an asymptotic (extrapolated) ladder.
    pub fn is_asymptotic(self) -> bool {
        matches!(
            self,
            Behaviour::Monotone | Behaviour::TwoLevels | Behaviour::Converged
        )
    }
}

/// The error estimate of one quantity from its ladder (same unit as the quantity).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Estimate {
    /// The finest value f₁.
    pub finest: f64,
    /// The Richardson-extrapolated value f₀ (the finest value when not extrapolated).
    pub extrapolated: f64,
    /// The observed order p (None with two levels or a non-monotone ladder).
    pub observed_order: Option<f64>,
    /// The order the estimate used (observed, or the assumed one: [`ASSUMED_ORDER`] unless
    /// [`estimate_assuming`] set another; None when not used).
    pub order_used: Option<f64>,
    /// Estimate of |f₁ − f_exact|: the GCI in the quantity's unit, ≥ 0.
    pub error: f64,
    /// `error` relative to |extrapolated| (None when the extrapolated value is 0).
    pub relative_error: Option<f64>,
    /// How the ladder converges.
    pub behaviour: Behaviour,
}

impl Estimate {
    /// The same estimate with its error raised to at least `floor` (relative) of
    /// |extrapolated|.
    pub fn with_relative_floor(self, floor: f64) -> Estimate {
        self.with_error(self.error.max(floor * self.extrapolated.abs()))
    }

    /// The estimate of k times the quantity (k > 0): values and error scaled, the relative
    /// error and the order unchanged.
    pub fn scaled(self, k: f64) -> Estimate {
        Estimate {
            finest: k * self.finest,
            extrapolated: k * self.extrapolated,
            error: k * self.error,
            ..self
        }
    }

    /// The estimate a record kept as `value` and its `error` (same unit; NaN: none made):
    /// the value is both the finest and the extrapolated one.
    pub fn recorded(value: f64, error: f64) -> Estimate {
        finish(value, value, None, None, error, Behaviour::Recorded)
    }

    /// The estimate as a record keeps it ([`Estimate::recorded`] of the finest value and
    /// the error), so that an answer just computed and one read back agree to the bit.
    pub fn as_recorded(self) -> Estimate {
        Estimate::recorded(self.finest, self.error)
    }

    /// The same estimate with its error set to `error` (the quantity's unit, ≥ 0) and the
    /// relative error recomputed against |extrapolated| (None when that is 0).
    pub fn with_error(self, error: f64) -> Estimate {
        Estimate {
            error,
            relative_error: (self.extrapolated != 0.0).then(|| error / self.extrapolated.abs()),
            ..self
        }
    }
}

/// The estimate for `values` (coarse to fine, at least two, all finite) on a ladder of
/// refinement ratio `ratio` (> 1). Uses the three finest values. None for fewer than two
/// values, a non-finite value or a ratio not above 1.
pub fn estimate(values: &[f64], ratio: f64) -> Option<Estimate> {
    estimate_assuming(values, ratio, ASSUMED_ORDER)
}

/// [`estimate`] with `assumed_order` (> 0) in place of [`ASSUMED_ORDER`] when only two levels
/// ran: 1 for a quantity known to converge at first order (a two-level bar of 3 |d₂₁| at
/// r = 2). Three levels use the observed order as [`estimate`] does. None as [`estimate`], or
/// for an assumed order not above 0.
pub fn estimate_assuming(values: &[f64], ratio: f64, assumed_order: f64) -> Option<Estimate> {
    if !(assumed_order.is_finite() && assumed_order > 0.0) {
        return None;
    }
    let ok = values.len() >= 2 && values.iter().all(|v| v.is_finite());
    if !(ok && ratio.is_finite() && ratio > 1.0) {
        return None;
    }
    let n = values.len();
    let f1 = values[n - 1];
    let f2 = values[n - 2];
    let d21 = f1 - f2;
    if n == 2 {
        return Some(two_level(f1, d21, ratio, assumed_order));
    }
    let d32 = f2 - values[n - 3];
    Some(three_level(f1, d21, d32, ratio))
}

/// Two levels: the order `order` assumed, safety factor 3.
fn two_level(f1: f64, d21: f64, ratio: f64, order: f64) -> Estimate {
    if d21 == 0.0 {
        return settled(f1);
    }
    let gain = ratio.powf(order) - 1.0;
    let extrapolated = f1 + d21 / gain;
    finish(
        f1,
        extrapolated,
        None,
        Some(order),
        SAFETY_ASSUMED * d21.abs() / gain,
        Behaviour::TwoLevels,
    )
}

/// Three levels: the observed order when the ladder is monotone and the order plausible.
fn three_level(f1: f64, d21: f64, d32: f64, ratio: f64) -> Estimate {
    if d21 == 0.0 && d32 == 0.0 {
        return settled(f1);
    }
    let spread = SAFETY_OBSERVED * d21.abs().max(d32.abs());
    if d21 * d32 < 0.0 {
        return finish(f1, f1, None, None, spread, Behaviour::Oscillatory);
    }
    let p = observed_order(d21, d32, ratio);
    match p {
        Some(p) if (ORDER_RANGE.0..=ORDER_RANGE.1).contains(&p) => {
            let gain = ratio.powf(p) - 1.0;
            finish(
                f1,
                f1 + d21 / gain,
                Some(p),
                Some(p),
                SAFETY_OBSERVED * d21.abs() / gain,
                Behaviour::Monotone,
            )
        }
        _ => finish(f1, f1, p, None, spread, Behaviour::OrderOutOfRange),
    }
}

/// The observed order ln(d₃₂/d₂₁)/ln r of a monotone ladder (None when a difference is 0).
pub fn observed_order(d21: f64, d32: f64, ratio: f64) -> Option<f64> {
    let q = d32 / d21;
    (q.is_finite() && q > 0.0).then(|| q.ln() / ratio.ln())
}

/// A ladder whose finest values are equal.
fn settled(f1: f64) -> Estimate {
    finish(f1, f1, None, None, 0.0, Behaviour::Converged)
}

fn finish(
    finest: f64,
    extrapolated: f64,
    observed_order: Option<f64>,
    order_used: Option<f64>,
    error: f64,
    behaviour: Behaviour,
) -> Estimate {
    let relative_error = (extrapolated != 0.0).then(|| error / extrapolated.abs());
    Estimate {
        finest,
        extrapolated,
        observed_order,
        order_used,
        error,
        relative_error,
        behaviour,
    }
}

/// Serde form `{"value": finest, "error": error}` of an [`Estimate`] in a cache record (an
/// error that is not a number written as null); read back as [`Estimate::recorded`].
/// Use as `#[serde(with = "value_and_error")]`.
pub mod value_and_error {
    use super::Estimate;
    use serde::{Deserialize, Deserializer, Serialize, Serializer};

    /// The record's fields.
    #[derive(Serialize, Deserialize)]
    struct Record {
        value: f64,
        error: Option<f64>,
    }

    /// Writes the finest value and the error.
    pub fn serialize<S: Serializer>(e: &Estimate, s: S) -> Result<S::Ok, S::Error> {
        let error = e.error.is_finite().then_some(e.error);
        Record {
            value: e.finest,
            error,
        }
        .serialize(s)
    }

    /// Reads a value and its error (null: NaN) as a recorded estimate.
    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Estimate, D::Error> {
        let r = Record::deserialize(d)?;
        Ok(Estimate::recorded(r.value, r.error.unwrap_or(f64::NAN)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// f(h) = f0 + C h^p on h = h0, h0/r, h0/r², … (coarse to fine).
    fn manufactured(f0: f64, c: f64, p: f64, h0: f64, r: f64, levels: usize) -> Vec<f64> {
        (0..levels)
            .map(|k| f0 + c * (h0 / r.powi(k as i32)).powf(p))
            .collect()
    }

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol * b.abs().max(1e-300)
    }

    #[test]
    fn recovers_the_limit_and_order_of_manufactured_ladders() {
        for &(f0, c, p, r) in &[
            (0.319, 0.05, 2.0, 2.0),
            (0.319, -0.05, 1.0, 2.0),
            (1.7e-5, 3e-3, 2.6, 2.0),
            (4.2e-5, -1e-4, 1.5, 2f64.sqrt()),
            (1.0, 0.3, 0.7, 1.5),
        ] {
            let v = manufactured(f0, c, p, 0.01, r, 4);
            let e = estimate(&v, r).unwrap();
            assert_eq!(e.behaviour, Behaviour::Monotone, "{v:?}");
            assert!(close(e.observed_order.unwrap(), p, 1e-9), "{e:?} p = {p}");
            assert!(close(e.extrapolated, f0, 1e-11), "{e:?} f0 = {f0}");
            let true_error = (e.finest - f0).abs();
            assert!(close(e.error, SAFETY_OBSERVED * true_error, 1e-8), "{e:?}");
        }
    }

    #[test]
    fn two_levels_assume_order_two_and_bound_orders_of_one_and_more() {
        for &p in &[1.0, 1.5, 2.0, 3.0] {
            let v = manufactured(0.5, 0.2, p, 0.1, 2.0, 2);
            let e = estimate(&v, 2.0).unwrap();
            assert_eq!(e.behaviour, Behaviour::TwoLevels);
            assert_eq!(e.observed_order, None);
            assert_eq!(e.order_used, Some(ASSUMED_ORDER));
            // With r = 2 the estimate is the coarse-to-fine difference.
            assert!(close(e.error, (v[1] - v[0]).abs(), 1e-12), "{e:?}");
            assert!(
                e.error >= (e.finest - 0.5).abs() * (1.0 - 1e-12),
                "p = {p}: {e:?}"
            );
        }
        // Order 2 exactly: the extrapolation is exact too.
        let v = manufactured(0.5, 0.2, 2.0, 0.1, 2.0, 2);
        assert!(close(estimate(&v, 2.0).unwrap().extrapolated, 0.5, 1e-12));
        // An order below 1 is not bounded by the two-level rule: a three-level ladder says so.
        let v = manufactured(0.5, 0.2, 0.6, 0.1, 2.0, 2);
        let e = estimate(&v, 2.0).unwrap();
        assert!(e.error < (e.finest - 0.5).abs());
    }

    #[test]
    fn two_levels_at_an_assumed_order_of_one_bound_orders_from_log2_of_four_thirds() {
        for &p in &[0.42, 0.5, 1.0, 2.0] {
            let v = manufactured(0.5, 0.2, p, 0.1, 2.0, 2);
            let e = estimate_assuming(&v, 2.0, 1.0).unwrap();
            assert_eq!(e.order_used, Some(1.0));
            // 3 |d₂₁|/(2 − 1): three times the order-2 bar.
            assert!(close(e.error, 3.0 * (v[1] - v[0]).abs(), 1e-12), "{e:?}");
            assert!(e.error >= (e.finest - 0.5).abs(), "p = {p}: {e:?}");
        }
        // The error is |d₂₁|/(2^p − 1): above 3 |d₂₁| once p < log₂(4/3) = 0.415.
        let v = manufactured(0.5, 0.2, 0.4, 0.1, 2.0, 2);
        let e = estimate_assuming(&v, 2.0, 1.0).unwrap();
        assert!(e.error < (e.finest - 0.5).abs());
        // Three levels ignore the assumption; a bad assumed order gives none.
        let v = manufactured(0.5, 0.2, 1.5, 0.1, 2.0, 3);
        assert_eq!(estimate_assuming(&v, 2.0, 1.0), estimate(&v, 2.0));
        assert_eq!(estimate_assuming(&v, 2.0, 0.0), None);
        assert_eq!(estimate_assuming(&v, 2.0, f64::NAN), None);
    }

    #[test]
    fn oscillatory_ladders_are_flagged_without_extrapolation() {
        let v = [0.330, 0.310, 0.322, 0.316];
        let e = estimate(&v, 2.0).unwrap();
        assert_eq!(e.behaviour, Behaviour::Oscillatory);
        assert_eq!(e.extrapolated, 0.316);
        assert_eq!(e.observed_order, None);
        assert!(close(e.error, 1.25 * 0.012, 1e-12), "{e:?}");
        // A decaying oscillation f0 + C (−1)^k h^p: the true error is inside the estimate.
        let f0 = 0.319;
        let v: Vec<f64> = (0..3)
            .map(|k| f0 + 0.02 * (-1f64).powi(k) * 0.5f64.powi(2 * k))
            .collect();
        let e = estimate(&v, 2.0).unwrap();
        assert_eq!(e.behaviour, Behaviour::Oscillatory);
        assert!(e.error >= (e.finest - f0).abs());
    }

    #[test]
    fn noisy_ladders_stay_inside_their_estimate() {
        // f0 (1 + 0.08 h²) on h = 1, 1/2, 1/4, with deterministic noise up to 2 % of the
        // finest step (0.015 f0).
        let f0 = 1.0e-4;
        let mut inside = 0;
        let n = 200;
        for k in 0..n {
            let noise = |i: usize| 0.02 * ((k * 7 + i * 13) % 11) as f64 / 10.0 - 0.01;
            let v: Vec<f64> = (0..3)
                .map(|i| f0 * (1.0 + 0.08 * 0.25f64.powi(i as i32) + noise(i) * 0.03))
                .collect();
            let e = estimate(&v, 2.0).unwrap();
            assert!(e.error.is_finite() && e.extrapolated.is_finite());
            if (e.finest - f0).abs() <= e.error {
                inside += 1;
            }
        }
        assert!(inside == n, "{inside} of {n} inside");
    }

    /// Scaling a quantity (a unit change, one ball's share) scales its values and bar and
    /// keeps its relative error and order.
    #[test]
    fn a_scaled_estimate_keeps_its_relative_error() {
        let e = estimate(&[1.0, 1.1, 1.12], 2.0).unwrap();
        let h = e.scaled(0.5);
        assert_eq!(h.finest, 0.5 * e.finest);
        assert_eq!(h.extrapolated, 0.5 * e.extrapolated);
        assert_eq!(h.error, 0.5 * e.error);
        let (r, rh) = (e.relative_error.unwrap(), h.relative_error.unwrap());
        assert!((r - rh).abs() < 1e-15 && h.observed_order == e.observed_order);
    }

    #[test]
    fn degenerate_ladders_give_flags_not_nan() {
        let e = estimate(&[2.0, 2.0, 2.0], 2.0).unwrap();
        assert_eq!(e.behaviour, Behaviour::Converged);
        assert_eq!(e.error, 0.0);
        let e = estimate(&[2.0, 2.0], 2.0).unwrap();
        assert_eq!(e.behaviour, Behaviour::Converged);
        // The finest step zero, the coarser not: no order, the coarser step as the bar.
        let e = estimate(&[1.0, 2.0, 2.0], 2.0).unwrap();
        assert_eq!(e.behaviour, Behaviour::OrderOutOfRange);
        assert!(close(e.error, 1.25, 1e-12));
        // An implausibly high order (a near-stall) is flagged, not extrapolated.
        let e = estimate(&[1.0, 2.0, 2.0 + 1e-9], 2.0).unwrap();
        assert_eq!(e.behaviour, Behaviour::OrderOutOfRange);
        assert_eq!(e.extrapolated, 2.0 + 1e-9);
        // A zero limit has no relative error.
        let e = estimate(&[0.0, 0.0], 2.0).unwrap();
        assert_eq!(e.relative_error, None);
        for bad in [
            estimate(&[1.0], 2.0),
            estimate(&[1.0, f64::NAN], 2.0),
            estimate(&[1.0, 2.0], 1.0),
            estimate(&[1.0, 2.0], f64::INFINITY),
        ] {
            assert!(bad.is_none());
        }
    }
}
