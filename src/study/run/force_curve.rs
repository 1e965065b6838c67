//! The loading branch F(δ) of a run on an equal-approach grid: the curve a contact law is
//! compared with, written as force_curve.csv.
//!
//! The force is the smoothed one of the history ([`crate::study::run::smoothed_force`]). On the
//! section a level of the default error estimate is a phase ensemble: its curve is the mean of
//! the members' curves at equal approach, and the two levels give each point an error bar as
//! they do e (docs/design.md, "The smoothed force history").

use crate::study::records::estimate::estimate;
use crate::study::run::history::HistoryRow;

/// Points of the grid, evenly spaced in approach from δ_max/N to δ_max.
pub const POINTS: usize = 50;

/// F(δ) on the loading branch at equal approach.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ForceCurve {
    /// Approach of the mass centres, m (increasing, > 0).
    pub delta: Vec<f64>,
    /// Smoothed normal force at each approach, N.
    pub force: Vec<f64>,
    /// Error bar of each force, N (the two-level estimate plus the phase sampling error);
    /// empty for one run alone.
    pub error: Vec<f64>,
    /// Sampling error of each force over the ring phase, N (zeros for one run).
    pub sampling_error: Vec<f64>,
}

/// The loading branch of `rows` (up to their largest approach): (δ in m, smoothed F in N).
fn loading_branch(rows: &[HistoryRow]) -> (Vec<f64>, Vec<f64>) {
    let peak = rows
        .iter()
        .enumerate()
        .fold((0, f64::NEG_INFINITY), |(k, m), (i, r)| {
            if r.delta > m {
                (i, r.delta)
            } else {
                (k, m)
            }
        })
        .0;
    // The approach can stall for a row or two at touch: keep strictly increasing points.
    let (mut d, mut f) = (Vec::new(), Vec::new());
    for r in rows.iter().take(peak + 1) {
        if r.delta > 0.0 && d.last().is_none_or(|&x| r.delta > x) {
            d.push(r.delta);
            f.push(r.normal_force_smoothed);
        }
    }
    (d, f)
}

/// The linear interpolant of (`x`, `y`) at `at` (clamped to the ends; 0 with no points).
fn interpolate(x: &[f64], y: &[f64], at: f64) -> f64 {
    match x.len() {
        0 => 0.0,
        _ if at <= x[0] => y[0],
        n if at >= x[n - 1] => y[n - 1],
        _ => {
            let k = x.partition_point(|&s| s <= at) - 1;
            let s = (at - x[k]) / (x[k + 1] - x[k]);
            y[k] + s * (y[k + 1] - y[k])
        }
    }
}

/// The grid of [`POINTS`] approaches up to `delta_max` (m).
fn grid(delta_max: f64) -> Vec<f64> {
    (1..=POINTS)
        .map(|k| delta_max * k as f64 / POINTS as f64)
        .collect()
}

/// The largest approach of `rows`, m (0 without rows).
fn largest_approach(rows: &[HistoryRow]) -> f64 {
    rows.iter().map(|r| r.delta).fold(0.0, f64::max)
}

impl ForceCurve {
    /// The curve of one run's history rows, no error bar.
    pub fn of_run(rows: &[HistoryRow]) -> ForceCurve {
        ForceCurve::phase_mean(&[rows])
    }

    /// The mean curve of the ensemble members `members` (their history rows, in phase order):
    /// the grid runs to the smallest member's δ_max, so every member has every point; the
    /// sampling error is the even members' mean against the mean of all.
    pub fn phase_mean(members: &[&[HistoryRow]]) -> ForceCurve {
        let top = members
            .iter()
            .map(|r| largest_approach(r))
            .fold(f64::INFINITY, f64::min);
        if members.is_empty() || !(top.is_finite() && top > 0.0) {
            return ForceCurve::default();
        }
        let delta = grid(top);
        let branches: Vec<(Vec<f64>, Vec<f64>)> =
            members.iter().map(|r| loading_branch(r)).collect();
        let mean_of = |picked: &[&(Vec<f64>, Vec<f64>)], d: f64| {
            picked
                .iter()
                .map(|(x, y)| interpolate(x, y, d))
                .sum::<f64>()
                / picked.len() as f64
        };
        let all: Vec<&(Vec<f64>, Vec<f64>)> = branches.iter().collect();
        let even: Vec<&(Vec<f64>, Vec<f64>)> = branches.iter().step_by(2).collect();
        let force: Vec<f64> = delta.iter().map(|&d| mean_of(&all, d)).collect();
        let sampling_error = delta
            .iter()
            .zip(&force)
            .map(|(&d, f)| (mean_of(&even, d) - f).abs())
            .collect();
        ForceCurve {
            delta,
            force,
            error: Vec::new(),
            sampling_error,
        }
    }

    /// This (fine) curve with an error bar from `coarse`, the curve one level coarser (ratio
    /// 2): at each approach the two-level estimate of the force plus this curve's sampling
    /// error. Points beyond the coarse curve's last approach get the bar of its last point.
    pub fn with_bar(mut self, coarse: &ForceCurve) -> ForceCurve {
        self.error = self
            .delta
            .iter()
            .zip(&self.force)
            .zip(&self.sampling_error)
            .map(|((&d, &f), &s)| {
                let c = interpolate(&coarse.delta, &coarse.force, d);
                estimate(&[c, f], 2.0).map_or(f64::INFINITY, |e| e.error) + s
            })
            .collect();
        self
    }

    /// The curve as CSV: `delta [m],force [N]` and, with a bar, `error [N]`.
    pub fn csv(&self) -> String {
        let bar = !self.error.is_empty();
        let mut s = String::from(if bar {
            "delta [m],force [N],error [N]\n"
        } else {
            "delta [m],force [N]\n"
        });
        for (k, (d, f)) in self.delta.iter().zip(&self.force).enumerate() {
            s.push_str(&format!("{d:.9e},{f:.9e}"));
            if bar {
                s.push_str(&format!(",{:.9e}", self.error[k]));
            }
            s.push('\n');
        }
        s
    }

    /// Whether every number of the curve is finite.
    pub fn is_finite(&self) -> bool {
        self.delta
            .iter()
            .chain(&self.force)
            .chain(&self.error)
            .all(|x| x.is_finite())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rows of a Hertz-like loading F = k δ^1.5 up to `top` (m) and back, smoothed = raw.
    fn rows(k: f64, top: f64) -> Vec<HistoryRow> {
        let n = 100;
        (0..=2 * n)
            .map(|i| {
                let s = if i <= n { i } else { 2 * n - i } as f64 / n as f64;
                let delta = top * s;
                let f = k * delta.powf(1.5);
                HistoryRow {
                    t: i as f64,
                    delta,
                    normal_force: f,
                    tangential_force: 0.0,
                    v: [[0.0; 3]; 2],
                    w: [[0.0; 3]; 2],
                    kinetic: 0.0,
                    elastic: 0.0,
                    plastic: 0.0,
                    hourglass: 0.0,
                    contact_stored: 0.0,
                    contact_dissipated: 0.0,
                    total: 0.0,
                    impulse: 0.0,
                    normal_force_smoothed: f,
                }
            })
            .collect()
    }

    #[test]
    fn one_run_reads_its_loading_branch_at_equal_approach() {
        let c = ForceCurve::of_run(&rows(1e9, 1e-4));
        assert_eq!(c.delta.len(), POINTS);
        assert!((c.delta[POINTS - 1] - 1e-4).abs() < 1e-18);
        let exact = 1e9 * (0.5e-4f64).powf(1.5);
        assert!((c.force[POINTS / 2 - 1] / exact - 1.0).abs() < 1e-3);
        assert!(c.error.is_empty() && c.csv().starts_with("delta [m],force [N]\n"));
    }

    #[test]
    fn the_phase_mean_stops_at_the_smallest_reach_and_measures_the_spread() {
        let (a, b) = (rows(1.0e9, 1e-4), rows(1.1e9, 0.9e-4));
        let c = ForceCurve::phase_mean(&[&a, &b]);
        assert!((c.delta[POINTS - 1] - 0.9e-4).abs() < 1e-18);
        let d = c.delta[10];
        let mean = 1.05e9 * d.powf(1.5);
        assert!((c.force[10] / mean - 1.0).abs() < 1e-3);
        // Even members: the first alone, 1e9 δ^1.5, half the 10 % spread from the mean (to
        // the rows' linear interpolation).
        assert!((c.sampling_error[10] / (0.05e9 * d.powf(1.5)) - 1.0).abs() < 1e-2);
    }

    #[test]
    fn the_bar_is_the_two_level_estimate_plus_the_sampling_error() {
        let fine = ForceCurve::of_run(&rows(1.0e9, 1e-4));
        let coarse = ForceCurve::of_run(&rows(1.03e9, 1e-4));
        let c = fine.with_bar(&coarse);
        let k = POINTS - 1;
        let expected = estimate(&[coarse.force[k], c.force[k]], 2.0).unwrap().error;
        assert!((c.error[k] - expected).abs() <= 1e-12 * expected);
        assert!(c.error[k] > 0.0 && c.is_finite());
        assert!(c.csv().starts_with("delta [m],force [N],error [N]\n"));
    }
}
