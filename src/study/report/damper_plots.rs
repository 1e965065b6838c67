//! SVG charts of a damper case ([`crate::damper`]): the frame's free decay with its envelope,
//! and the damping ratio cycle by cycle against amplitude (particle dampers are strongly
//! amplitude dependent); and of a run, the damping ratio of every case window by window.
//!
//! The envelope is the least-squares exponential through the analysed window's peaks
//! ([`crate::damper::decay::envelope_fit`]), A(t) = A₀ exp(−σ (t − t₀)), its damping ratio
//! ζ_fit = σ/√(σ² + (2π f)²) in the title beside the log decrement's: where the decay is
//! exponential the peaks lie on it, and where the damping depends on amplitude they leave it.

use crate::atomic::write_atomic;
use crate::damper::decay::{cycle_ratios, envelope_fit, peaks};
use crate::damper::report::case_windows;
use crate::damper::run::CaseOutcome;
use crate::error::Result;
use crate::study::common::plots::{Chart, Series, Style};
use std::f64::consts::PI;
use std::path::Path;

/// Most samples of the displacement drawn per chart (the history is thinned evenly).
pub const MAX_DRAWN_SAMPLES: usize = 4000;

/// The decay chart: frame displacement (mm) against time (s), the peaks, and the envelope of
/// the window's fit.
pub fn decay_chart(o: &CaseOutcome) -> Chart {
    let every = o.samples.len().div_ceil(MAX_DRAWN_SAMPLES).max(1);
    let trace = o
        .samples
        .iter()
        .step_by(every)
        .map(|s| (s.time, 1e3 * s.displacement))
        .collect();
    let t: Vec<f64> = o.samples.iter().map(|s| s.time).collect();
    let x: Vec<f64> = o.samples.iter().map(|s| s.displacement).collect();
    let found = peaks(&t, &x);
    let (zeta, f) = (o.decay.ratio, o.decay.frequency);
    let t1 = o.decay.span.1.time;
    let (t0, a0, sigma) =
        envelope_fit(&found, o.window).unwrap_or((o.decay.span.0.time, o.decay.span.0.value, 0.0));
    let zeta_fit = sigma / (sigma * sigma + (2.0 * PI * f).powi(2)).sqrt();
    let envelope = (0..=100)
        .map(|k| {
            let tk = t0 + (t1 - t0) * k as f64 / 100.0;
            (tk, 1e3 * a0 * (-sigma * (tk - t0)).exp())
        })
        .collect();
    Chart {
        title: format!(
            "{}: free decay, f = {:.4} Hz, zeta = {:.3} % (log decrement), {:.3} % (envelope fit)",
            o.name,
            f,
            100.0 * zeta,
            100.0 * zeta_fit
        ),
        x_label: "time [s]".into(),
        y_label: "frame displacement [mm]".into(),
        series: vec![
            Series {
                label: "displacement".into(),
                points: trace,
                style: Style::Line,
            },
            Series {
                label: "peaks".into(),
                points: found.iter().map(|p| (p.time, 1e3 * p.value)).collect(),
                style: Style::Points,
            },
            Series {
                label: "least-squares envelope of the window's peaks".into(),
                points: envelope,
                style: Style::Line,
            },
        ],
    }
}

/// The amplitude chart: ζ (%) of each pair of successive peaks against their mean
/// amplitude (mm), beside the window's ζ.
pub fn damping_chart(o: &CaseOutcome) -> Chart {
    let t: Vec<f64> = o.samples.iter().map(|s| s.time).collect();
    let x: Vec<f64> = o.samples.iter().map(|s| s.displacement).collect();
    let cycles: Vec<(f64, f64)> = cycle_ratios(&peaks(&t, &x))
        .into_iter()
        .map(|(a, _, z)| (1e3 * a, 100.0 * z))
        .collect();
    let (lo, hi) = cycles.iter().fold((f64::INFINITY, 0.0f64), |(l, h), p| {
        (l.min(p.0), h.max(p.0))
    });
    let window = 100.0 * o.decay.ratio;
    Chart {
        title: format!("{}: damping ratio against amplitude", o.name),
        x_label: "amplitude [mm]".into(),
        y_label: "damping ratio [%]".into(),
        series: vec![
            Series {
                label: "cycle by cycle".into(),
                points: cycles,
                style: Style::Points,
            },
            Series {
                label: "window's log decrement".into(),
                points: vec![(lo, window), (hi, window)],
                style: Style::Line,
            },
        ],
    }
}

/// The windows chart: ζ (%) of each case in consecutive windows of `width` s, drawn at
/// each window's middle (one line per case; a window without two peaks is left out).
pub fn windows_chart(outcomes: &[CaseOutcome], width: f64) -> Chart {
    let series = outcomes
        .iter()
        .map(|o| Series {
            label: o.name.clone(),
            points: case_windows(o, width)
                .iter()
                .filter_map(|w| {
                    let d = w.decay?;
                    Some((0.5 * (w.window.0 + w.window.1), 100.0 * d.ratio))
                })
                .collect(),
            style: Style::Line,
        })
        .collect();
    Chart {
        title: format!("damping ratio per {width} s window (log decrement inside each window)"),
        x_label: "middle of the window [s]".into(),
        y_label: "damping ratio [%]".into(),
        series,
    }
}

/// Writes `windows.svg` ([`windows_chart`]) into `dir`, atomically.
///
/// Errors: plotters drawing failures, I/O errors naming the path.
pub fn write_windows_chart(dir: &Path, outcomes: &[CaseOutcome], width: f64) -> Result<()> {
    write_atomic(
        dir.join("windows.svg"),
        windows_chart(outcomes, width).svg()?.as_bytes(),
    )
}

/// Writes `CASE/decay.svg` and `CASE/damping.svg` of every outcome into `dir` (the case
/// folders exist: [`crate::damper::run::write_outputs`] made them), each atomically.
///
/// Errors: plotters drawing failures, I/O errors naming the path.
pub fn write_plots(dir: &Path, outcomes: &[CaseOutcome]) -> Result<()> {
    for o in outcomes {
        let case = dir.join(&o.name);
        write_atomic(case.join("decay.svg"), decay_chart(o).svg()?.as_bytes())?;
        write_atomic(case.join("damping.svg"), damping_chart(o).svg()?.as_bytes())?;
    }
    Ok(())
}
