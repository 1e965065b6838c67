//! The head-on FE error bars in e, per metal: their range (min, median, max), how many lie
//! below the target [`TARGET_E_BAR`], and at how many points each law's e lies within the
//! FE bar (the law cannot be told from the FE there).

use super::BenchResults;

/// Relative FE error bar in e that the benchmark aims below (issue 27, acceptance 3).
pub const TARGET_E_BAR: f64 = 0.005;

/// The bars of one metal's head-on points with an FE answer.
#[derive(Debug, Clone, PartialEq)]
pub struct MetalBars {
    /// Metal preset.
    pub metal: String,
    /// Relative bars in e, ascending (points with an answer and a finite bar).
    pub relative: Vec<f64>,
    /// Points whose relative bar in e is below [`TARGET_E_BAR`].
    pub below_target: usize,
    /// Each law with the number of points at which |e_law − e_FE| ≤ the FE bar (laws with
    /// none left out), in registry order.
    pub laws_inside: Vec<(String, usize)>,
}

impl MetalBars {
    /// Smallest, median and largest relative bar (NaN without bars).
    pub fn min_median_max(&self) -> [f64; 3] {
        let v = &self.relative;
        if v.is_empty() {
            return [f64::NAN; 3];
        }
        let n = v.len();
        let median = if n % 2 == 1 {
            v[n / 2]
        } else {
            0.5 * (v[n / 2 - 1] + v[n / 2])
        };
        [v[0], median, v[n - 1]]
    }
}

/// The bars of every metal of `r`'s matrix, in matrix order.
pub fn metal_bars(r: &BenchResults) -> Vec<MetalBars> {
    r.matrix
        .metals
        .iter()
        .map(|metal| {
            let done: Vec<_> = r
                .head_on
                .iter()
                .filter(|h| &h.point.metal == metal)
                .filter_map(|h| h.fe_done().map(|f| (h, f)))
                .filter(|(_, f)| f.e.error.is_finite())
                .collect();
            let mut relative: Vec<f64> = done
                .iter()
                .map(|(_, f)| f.e.relative_error.unwrap_or(f64::NAN))
                .collect();
            relative.sort_by(f64::total_cmp);
            let below_target = relative.iter().filter(|&&x| x < TARGET_E_BAR).count();
            let laws_inside = r
                .normal_laws
                .iter()
                .enumerate()
                .map(|(k, law)| {
                    let n = done
                        .iter()
                        .filter(|(h, f)| {
                            h.laws
                                .get(k)
                                .is_some_and(|l| (l.e - f.e.finest).abs() <= f.e.error)
                        })
                        .count();
                    (law.clone(), n)
                })
                .filter(|(_, n)| *n > 0)
                .collect();
            MetalBars {
                metal: metal.clone(),
                relative,
                below_target,
                laws_inside,
            }
        })
        .collect()
}

/// A value ± its error (the error only when estimated).
pub(super) fn bar(value: f64, error: f64, scale: f64, digits: usize) -> String {
    if error.is_finite() {
        format!(
            "{:.*} ± {:.*}",
            digits,
            scale * value,
            digits,
            scale * error
        )
    } else {
        format!("{:.*}", digits, scale * value)
    }
}
