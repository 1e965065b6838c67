//! Contact duration from the normal-force pulse F(t).
//!
//! The contact starts at the first step with a force: the bodies touch at one point, which
//! the discretisation resolves exactly. The end is the delicate part. Near release every
//! contact of smooth bodies is elastic and Hertzian (phase 3 of the analytical model:
//! F ∝ (δ − δ_r)^{3/2}) with the approach δ falling linearly in time (the bodies part at
//! finite speed), so F^{2/3} falls linearly to zero, and the contact ends where a straight
//! line fitted to the lower part of that flank reaches zero.
//!
//! Why not the last step with any node in contact: a discretised patch lets go ring by ring,
//! and the last ring carries a force of a few newtons for a while, its timing set by the
//! last nodes' vibration. That time moves by a few tenths of a percent of the duration with
//! anything that perturbs the trajectory at round-off level (time step, multi-time-step
//! levels, element order); the fitted line, averaging over several rings, moves by a few
//! hundredths. (The loading flank is not fitted: an elastic-plastic contact yields almost at
//! once, after which F grows like δ, not δ^{3/2}.)

/// Lower end of the fit window, as a fraction of the peak of F^{2/3}.
pub const FIT_LOW: f64 = 0.05;
/// Upper end of the fit window, as a fraction of the peak of F^{2/3}: half the peak covers
/// several rings of a patch resolved by ten elements across, while the flank stays straight
/// to a few 0.1 % of the duration.
pub const FIT_HIGH: f64 = 0.5;

/// Duration (s) of the force pulse `pulse` = [(t in s, F in N)] of the steps with a force,
/// in time order: from its first sample to the zero crossing of the straight line fitted
/// (least squares) to F^{2/3} over the samples between [`FIT_LOW`] and [`FIT_HIGH`] of its
/// peak after the last sample above `FIT_HIGH`.
///
/// Returns `None` when the falling flank is too short to fit (fewer than 3 samples, or a
/// flank that does not fall): callers then fall back to the last step with contact.
pub fn pulse_duration(pulse: &[(f64, f64)]) -> Option<f64> {
    let peak = pulse.iter().map(|p| p.1).fold(0.0, f64::max);
    if !(peak.is_finite() && peak > 0.0) {
        return None;
    }
    let y = |f: f64| (f.max(0.0) / peak).powf(2.0 / 3.0);
    let last_high = pulse.iter().rposition(|p| y(p.1) >= FIT_HIGH)?;
    let flank: Vec<(f64, f64)> = pulse[last_high + 1..]
        .iter()
        .map(|&(t, f)| (t, y(f)))
        .filter(|&(_, v)| (FIT_LOW..FIT_HIGH).contains(&v))
        .collect();
    let end = zero_crossing(&flank, -1.0)?;
    let start = pulse[0].0;
    (end > start).then_some(end - start)
}

/// Zero of the least-squares line through `pts` (t, y), if it has at least 3 points and a
/// slope of sign `sign`.
fn zero_crossing(pts: &[(f64, f64)], sign: f64) -> Option<f64> {
    if pts.len() < 3 {
        return None;
    }
    let n = pts.len() as f64;
    // Centred sums: t is an absolute time, its square would lose digits.
    let tm = pts.iter().map(|p| p.0).sum::<f64>() / n;
    let ym = pts.iter().map(|p| p.1).sum::<f64>() / n;
    let (mut stt, mut sty) = (0.0, 0.0);
    for &(t, v) in pts {
        stt += (t - tm) * (t - tm);
        sty += (t - tm) * (v - ym);
    }
    let slope = sty / stt;
    (stt > 0.0 && slope * sign > 0.0).then(|| tm - ym / slope)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analytic::hertz::HertzPair;

    /// Hertz's own pulse, sampled as an explicit run would sample it, gives back Hertz's
    /// duration (the curvature of the flank over the fit window leaves +0.14 %); so does a
    /// pulse that lingers with a small tail.
    #[test]
    fn hertz_pulse_gives_hertz_duration() {
        // Two copper balls of 20 mm (E* = E/(2(1 − ν²)), R* = R/2, m* = m/2).
        let m = 7900.0 * 4.0 / 3.0 * std::f64::consts::PI * 1e-6;
        let pair = HertzPair::new(120e9 / (2.0 * (1.0 - 0.33f64 * 0.33)), 0.005, 0.5 * m);
        let force_at = |v: f64, t: f64| pair.force(pair.approach_at(v, t));
        let v = 2.0;
        let tc = pair.contact_duration(v);
        for steps in [200usize, 2000, 20000] {
            let dt = 1.3 * tc / steps as f64;
            let pulse: Vec<(f64, f64)> = (0..steps)
                .map(|k| {
                    // First sample just after touch, as in a run that starts at touch.
                    let t = 1e-3 + (k as f64 + 1e-6) * dt;
                    (t, force_at(v, t - 1e-3))
                })
                .filter(|p| p.1 > 0.0)
                .collect();
            let d = pulse_duration(&pulse).unwrap();
            assert!((d / tc - 1.0).abs() < 2e-3, "{steps} samples: {d} vs {tc}");
            assert!(d > tc, "the flank's curvature lengthens the fit a little");
        }
        // A tail of 1 % of the peak for 3 % of the duration after release changes nothing.
        let dt = tc / 5000.0;
        let peak = force_at(v, 0.5 * tc);
        let pulse: Vec<(f64, f64)> = (0..5200)
            .map(|k| {
                let t = k as f64 * dt;
                let f = force_at(v, t);
                (
                    t,
                    if t > tc && t < 1.03 * tc {
                        0.01 * peak
                    } else {
                        f
                    },
                )
            })
            .filter(|p| p.1 > 0.0)
            .collect();
        let d = pulse_duration(&pulse).unwrap();
        assert!((d / tc - 1.0).abs() < 2e-3, "tail: {d} vs {tc}");
    }

    #[test]
    fn too_short_or_flat_pulses_give_none() {
        assert_eq!(pulse_duration(&[]), None);
        assert_eq!(pulse_duration(&[(0.0, 1.0), (1.0, 1.0)]), None);
        assert_eq!(pulse_duration(&[(0.0, 0.0), (1.0, 0.0)]), None);
    }
}
