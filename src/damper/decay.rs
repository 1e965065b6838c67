//! The damping ratio as a free-decay test reads it: the peaks of the response and the
//! logarithmic decrement between them.

use crate::error::{Error, Result};
use std::f64::consts::PI;

/// A positive maximum of a sampled response, refined by the parabola through the sample and
/// its two neighbours.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Peak {
    /// Time of the maximum, s.
    pub time: f64,
    /// Value there (the response's unit, e.g. m).
    pub value: f64,
}

/// Frequency and damping ratio from a decay.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Decay {
    /// Damped frequency: cycles over the time between the first and last peak, Hz.
    pub frequency: f64,
    /// Damping ratio ζ = Λ/√(4π² + Λ²), Λ the mean logarithmic decrement per cycle.
    pub ratio: f64,
    /// Cycles between the first and last peak used.
    pub cycles: usize,
    /// First and last peak used.
    pub span: (Peak, Peak),
}

/// The positive local maxima of `values` sampled at `times` (s, ascending, same length).
pub fn peaks(times: &[f64], values: &[f64]) -> Vec<Peak> {
    let mut out = Vec::new();
    for i in 1..values.len().saturating_sub(1) {
        let (a, b, c) = (values[i - 1], values[i], values[i + 1]);
        if b > 0.0 && b > a && b >= c {
            let curvature = a - 2.0 * b + c;
            let shift = if curvature < 0.0 {
                (0.5 * (a - c) / curvature).clamp(-1.0, 1.0)
            } else {
                0.0
            };
            let h = 0.5 * (times[i + 1] - times[i - 1]);
            out.push(Peak {
                time: times[i] + shift * h,
                value: b - 0.25 * (a - c) * shift,
            });
        }
    }
    out
}

/// The logarithmic decrement over the peaks in the window [t0, t1] (s): Λ = ln(x₀/x_n)/n
/// over the first and last peak in it, ζ = Λ/√(4π² + Λ²), f = n/(t_n − t₀). Errors: fewer
/// than two peaks in the window.
pub fn log_decrement(peaks: &[Peak], window: (f64, f64)) -> Result<Decay> {
    let inside: Vec<&Peak> = peaks
        .iter()
        .filter(|p| p.time >= window.0 && p.time <= window.1)
        .collect();
    if inside.len() < 2 {
        return Err(Error::invalid(
            "window",
            format!("[{}, {}] s", window.0, window.1),
            format!(
                "a window holding at least two peaks (it holds {})",
                inside.len()
            ),
        ));
    }
    let (first, last) = (*inside[0], *inside[inside.len() - 1]);
    let n = inside.len() - 1;
    let lambda = (first.value / last.value).ln() / n as f64;
    Ok(Decay {
        frequency: n as f64 / (last.time - first.time),
        ratio: lambda / (4.0 * PI * PI + lambda * lambda).sqrt(),
        cycles: n,
        span: (first, last),
    })
}

/// The logarithmic decrement of one window of a record.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WindowDecay {
    /// The window [t0, t1], s.
    pub window: (f64, f64),
    /// Its decay ([`log_decrement`] over the peaks inside); None with fewer than two peaks.
    pub decay: Option<Decay>,
}

/// The logarithmic decrement in consecutive windows [k w, (k + 1) w] (s, k = 0, 1, ...) that
/// end by `end` (s, to 1e-4 of a width: a record sampled to 9.99999 s holds five 2 s
/// windows): each over the peaks inside it alone, as a run whose `window` is that
/// window reads it. A window holding fewer than two peaks has no decay. Empty when `width`
/// is not positive and finite or no whole window fits.
pub fn window_decays(peaks: &[Peak], width: f64, end: f64) -> Vec<WindowDecay> {
    if !(width.is_finite() && width > 0.0 && end.is_finite()) {
        return Vec::new();
    }
    let n = (end / width + 1e-4).floor().max(0.0) as usize;
    (0..n)
        .map(|k| {
            let window = (k as f64 * width, (k + 1) as f64 * width);
            WindowDecay {
                window,
                decay: log_decrement(peaks, window).ok(),
            }
        })
        .collect()
}

/// The least-squares exponential envelope A(t) = A₀ exp(−σ (t − t₀)) of the peaks in the
/// window [t0, t1] (s): a straight-line fit of ln(value) against time, t₀ the first peak's
/// time. Returns (t₀ in s, A₀ in the response's unit, σ in 1/s); None with fewer than two
/// peaks in the window or a non-positive peak. With the damped frequency f (Hz) the fit's
/// damping ratio is ζ = σ/√(σ² + (2π f)²).
pub fn envelope_fit(peaks: &[Peak], window: (f64, f64)) -> Option<(f64, f64, f64)> {
    let inside: Vec<&Peak> = peaks
        .iter()
        .filter(|p| p.time >= window.0 && p.time <= window.1)
        .collect();
    if inside.len() < 2 || inside.iter().any(|p| p.value <= 0.0) {
        return None;
    }
    let t0 = inside[0].time;
    let n = inside.len() as f64;
    let (st, sy) = inside.iter().fold((0.0, 0.0), |(a, b), p| {
        (a + (p.time - t0), b + p.value.ln())
    });
    let (mt, my) = (st / n, sy / n);
    let (sxy, sxx) = inside.iter().fold((0.0, 0.0), |(a, b), p| {
        let dt = p.time - t0 - mt;
        (a + dt * (p.value.ln() - my), b + dt * dt)
    });
    let slope = sxy / sxx;
    Some((t0, (my - slope * mt).exp(), -slope))
}

/// Damping ratio cycle by cycle: for each pair of successive peaks, the mean amplitude (the
/// response's unit), the time midway (s) and ζ from their logarithmic decrement.
pub fn cycle_ratios(peaks: &[Peak]) -> Vec<(f64, f64, f64)> {
    peaks
        .windows(2)
        .map(|w| {
            let lambda = (w[0].value / w[1].value).ln();
            (
                0.5 * (w[0].value + w[1].value),
                0.5 * (w[0].time + w[1].time),
                lambda / (4.0 * PI * PI + lambda * lambda).sqrt(),
            )
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A sampled exponentially decaying cosine gives back its frequency and ratio.
    #[test]
    fn decaying_cosine_gives_its_frequency_and_ratio() {
        let (fd, zeta): (f64, f64) = (1.69, 0.0045);
        let wd = 2.0 * PI * fd;
        let wn = wd / (1.0 - zeta * zeta).sqrt();
        let t: Vec<f64> = (0..20000).map(|i| i as f64 * 1e-3).collect();
        let x: Vec<f64> = t
            .iter()
            .map(|&t| (-zeta * wn * t).exp() * (wd * t).cos())
            .collect();
        let d = log_decrement(&peaks(&t, &x), (0.0, 20.0)).unwrap();
        assert!((d.frequency / fd - 1.0).abs() < 1e-6, "{d:?}");
        assert!((d.ratio / zeta - 1.0).abs() < 1e-4, "{d:?}");
    }

    /// Windows of a decay whose rate halves at 6 s: each window gives its own rate, the
    /// windows tile [0, end] and a window without two peaks has none.
    #[test]
    fn windows_read_each_part_of_a_record_alone() {
        let (fd, z1, z2): (f64, f64, f64) = (1.69, 0.012, 0.006);
        let wd = 2.0 * PI * fd;
        let t: Vec<f64> = (0..10001).map(|i| i as f64 * 1e-3).collect();
        let x: Vec<f64> = t
            .iter()
            .map(|&t| {
                let a = if t < 6.0 {
                    -z1 * wd * t
                } else {
                    -z1 * wd * 6.0 - z2 * wd * (t - 6.0)
                };
                a.exp() * (wd * t).cos()
            })
            .collect();
        let w = window_decays(&peaks(&t, &x), 2.0, 10.0);
        assert_eq!(w.len(), 5);
        assert_eq!(w[4].window, (8.0, 10.0));
        for (k, want) in [z1, z1, z1, z2, z2].into_iter().enumerate() {
            let got = w[k].decay.unwrap().ratio;
            assert!(
                (got / want - 1.0).abs() < 1e-3,
                "window {k}: {got} against {want}"
            );
        }
        let short = window_decays(&peaks(&t, &x), 0.3, 0.6);
        assert_eq!(short.len(), 2);
        assert!(short.iter().all(|w| w.decay.is_none()));
        assert!(window_decays(&peaks(&t, &x), 0.0, 10.0).is_empty());
    }
}
