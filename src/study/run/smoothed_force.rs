//! The smoothed contact force: a triangular (Bartlett) window in time applied to the exact
//! impulse the run accumulated step by step, so the filter removes ring landings and penalty
//! ringing and leaves the impulse unchanged (docs/design.md, "The smoothed force history").
//!
//! The window of half-width w is a centred moving average of width w applied twice. Written
//! with the impulse I(t) = ∫F dt and its integral J(t) = ∫I dt, the smoothed force is
//! F_s(t) = (J(t + w) − 2 J(t) + J(t − w)) / w², and ∫F_s dt = ∫F dt exactly when F is zero
//! before the first sample and after the last (I constant there).

use crate::study::run::history::HistoryRow;
use serde::Serialize;

/// The contact force of a run in results.json (`fe.force`).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct ForceSummary {
    /// Largest raw normal force over the history rows, N.
    pub peak_raw: f64,
    /// Largest smoothed normal force, N: the peak to compare a contact law's with.
    pub peak_smoothed: f64,
    /// Root mean square of raw − smoothed over the rows in contact, over the smoothed peak, -.
    pub noise: f64,
    /// Half-width of the triangular window, s.
    pub filter_half_width: f64,
}

/// Fills `normal_force_smoothed` of `rows` (from their `impulse`) with the window for a
/// contact of `contact_duration` (s), and summarises the force.
pub fn smooth_history(rows: &mut [HistoryRow], contact_duration: f64) -> ForceSummary {
    let t: Vec<f64> = rows.iter().map(|r| r.t).collect();
    let impulse: Vec<f64> = rows.iter().map(|r| r.impulse).collect();
    let w = half_width(contact_duration);
    let smoothed = triangular(&t, &impulse, w);
    for (r, f) in rows.iter_mut().zip(&smoothed) {
        r.normal_force_smoothed = *f;
    }
    let raw: Vec<f64> = rows.iter().map(|r| r.normal_force).collect();
    ForceSummary {
        peak_raw: raw.iter().copied().fold(0.0, f64::max),
        peak_smoothed: smoothed.iter().copied().fold(0.0, f64::max),
        noise: noise(&raw, &smoothed),
        filter_half_width: w,
    }
}

/// The window's half-width as a fraction of the contact duration: it attenuates a ring or
/// penalty oscillation of period T_c/20 or shorter to at most 4.7 % of its amplitude (the
/// first side lobe of sinc²) and lowers the peak of a half-sine pulse by (π/20)²/12 ≈ 0.2 %.
pub const HALF_WIDTH_FRACTION: f64 = 1.0 / 20.0;

/// The window's half-width (s) for a contact of duration `contact_duration` (s).
pub fn half_width(contact_duration: f64) -> f64 {
    HALF_WIDTH_FRACTION * contact_duration
}

/// The smoothed force (N) at each sample time of `t` (s, increasing), from the accumulated
/// impulse `impulse` (N·s, the same length: ∫F dt from before the contact up to each time),
/// with a triangular window of half-width `w` (s).
///
/// The impulse is taken as linear between samples, zero before the first and constant after
/// the last. Failure modes: none; lengths that differ, fewer than two samples or a `w` that
/// is not positive and finite give zeros.
pub fn triangular(t: &[f64], impulse: &[f64], w: f64) -> Vec<f64> {
    let n = t.len();
    if n < 2 || impulse.len() != n || !(w.is_finite() && w > 0.0) {
        return vec![0.0; n];
    }
    let j = integral_table(t, impulse);
    let at = |x: f64| integral_at(t, impulse, &j, x);
    t.iter()
        .map(|&x| (at(x + w) - 2.0 * at(x) + at(x - w)) / (w * w))
        .collect()
}

/// J at each sample: the integral of the piecewise-linear impulse from the first sample, N·s².
fn integral_table(t: &[f64], impulse: &[f64]) -> Vec<f64> {
    let mut j = Vec::with_capacity(t.len());
    let mut sum = 0.0;
    j.push(0.0);
    for k in 1..t.len() {
        sum += 0.5 * (impulse[k] + impulse[k - 1]) * (t[k] - t[k - 1]);
        j.push(sum);
    }
    j
}

/// J(x), N·s²: zero impulse before the first sample, linear between, constant after the last.
fn integral_at(t: &[f64], impulse: &[f64], j: &[f64], x: f64) -> f64 {
    let n = t.len();
    if x <= t[0] {
        return impulse[0] * (x - t[0]).max(0.0);
    }
    if x >= t[n - 1] {
        return j[n - 1] + impulse[n - 1] * (x - t[n - 1]);
    }
    let k = t.partition_point(|&s| s <= x) - 1;
    let h = t[k + 1] - t[k];
    let s = x - t[k];
    let slope = if h > 0.0 {
        (impulse[k + 1] - impulse[k]) / h
    } else {
        0.0
    };
    j[k] + impulse[k] * s + 0.5 * slope * s * s
}

/// The residual noise of `raw` (N) about `smoothed` (N): the root mean square of their
/// difference over the samples with a raw force, divided by the smoothed peak (dimensionless;
/// 0 without contact).
pub fn noise(raw: &[f64], smoothed: &[f64]) -> f64 {
    let peak = smoothed.iter().copied().fold(0.0, f64::max);
    let (sum, count) = raw
        .iter()
        .zip(smoothed)
        .filter(|(r, _)| **r > 0.0)
        .fold((0.0, 0usize), |(s, c), (r, f)| (s + (r - f).powi(2), c + 1));
    if peak > 0.0 && count > 0 {
        (sum / count as f64).sqrt() / peak
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// A half-sine pulse of duration `tc` (s) and peak 1 N with a ringing of relative amplitude
    /// `ring` and period tc/`cycles`, sampled `per` times over the pulse with free time on both
    /// sides; returns (t, raw F, exact impulse).
    fn pulse(tc: f64, ring: f64, cycles: f64, per: usize) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
        let dt = tc / per as f64;
        let (mut t, mut f, mut imp) = (vec![], vec![], vec![]);
        let force = |x: f64| {
            if (0.0..=tc).contains(&x) {
                let s = (PI * x / tc).sin();
                s + ring * s * (2.0 * PI * cycles * x / tc).sin()
            } else {
                0.0
            }
        };
        // The impulse by a fine midpoint sum, as the run accumulates it step by step.
        let fine = 200;
        let mut acc = 0.0;
        for k in 0..(per + per / 2) {
            let x = -0.25 * tc + k as f64 * dt;
            t.push(x);
            f.push(force(x));
            imp.push(acc);
            for m in 0..fine {
                acc += force(x + (m as f64 + 0.5) * dt / fine as f64) * dt / fine as f64;
            }
        }
        (t, f, imp)
    }

    #[test]
    fn a_smooth_half_sine_keeps_its_peak_within_the_stated_bias() {
        let tc = 1e-4;
        let (t, _, imp) = pulse(tc, 0.0, 1.0, 400);
        let s = triangular(&t, &imp, half_width(tc));
        let peak = s.iter().copied().fold(0.0, f64::max);
        let bias = (PI * HALF_WIDTH_FRACTION).powi(2) / 12.0;
        assert!((peak - (1.0 - bias)).abs() < 2e-4, "peak {peak}");
    }

    #[test]
    fn ringing_faster_than_a_twentieth_of_the_contact_is_removed_and_the_impulse_kept() {
        let tc = 1e-4;
        // 29 cycles sit on the window's first side lobe, the worst case beyond T_c/20.
        let (t, f, imp) = pulse(tc, 0.1, 29.0, 400);
        let s = triangular(&t, &imp, half_width(tc));
        // The ring (10 %) alone: the smoothed ringing pulse against the smoothed clean one
        // (the window also rounds the pulse's kinks at touch and separation, by w/6 · π/T_c
        // = 2.6 % of the peak, the same in both).
        let (_, _, clean) = pulse(tc, 0.0, 29.0, 400);
        let s0 = triangular(&t, &clean, half_width(tc));
        let worst = s
            .iter()
            .zip(&s0)
            .map(|(y, y0)| (y - y0).abs())
            .fold(0.0, f64::max);
        assert!(worst < 0.01, "largest deviation {worst}");
        // The impulse: the trapezoid sums of the raw and smoothed forces agree.
        let trap = |g: &[f64]| {
            (1..t.len())
                .map(|k| 0.5 * (g[k] + g[k - 1]) * (t[k] - t[k - 1]))
                .sum::<f64>()
        };
        let exact = 2.0 * tc / PI;
        assert!((trap(&s) / exact - 1.0).abs() < 1e-4);
        // RMS of 0.1 sin(πt/T) sin(58πt/T) over the contact: 0.1 / 2.
        assert!(noise(&f, &s) > 0.04, "the raw ring is measured as noise");
    }

    #[test]
    fn degenerate_input_gives_zeros_not_nan() {
        assert_eq!(triangular(&[0.0], &[0.0], 1.0), vec![0.0]);
        assert_eq!(triangular(&[0.0, 1.0], &[0.0, 1.0], 0.0), vec![0.0, 0.0]);
        assert_eq!(noise(&[], &[]), 0.0);
    }
}
