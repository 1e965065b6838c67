//! Each law's relative errors against FE (e, δ_max, t_c, peak force) and the ranking of the
//! material laws per metal by their RMS relative error in e and δ_max over the head-on points.

use super::calibrated::is_damped;
use super::fe::FePoint;
use super::HeadOnResult;

/// The compared quantities, in the order of [`relative_errors`].
pub const QUANTITIES: [&str; 4] = ["e", "delta_max", "t_c", "peak force"];

/// Relative errors (law − FE)/FE of law number `k` at point `h`, in the order of
/// [`QUANTITIES`]; None without a finished FE answer.
pub fn relative_errors(h: &HeadOnResult, k: usize) -> Option<[f64; 4]> {
    let l = h.laws.get(k)?;
    Some(against_fe(
        [l.e, l.delta_max, l.contact_duration, l.peak_force],
        h.fe_done()?,
    ))
}

/// Relative errors (law − FE)/FE of a law's e, δ_max (m), t_c (s) and peak force (N), in
/// the order of [`QUANTITIES`].
pub fn against_fe(law: [f64; 4], f: &FePoint) -> [f64; 4] {
    let fe = [f.e, f.delta_max, f.contact_duration, f.peak_force].map(|b| b.finest);
    [0, 1, 2, 3].map(|q| law[q] / fe[q] - 1.0)
}

/// One law's RMS relative errors over a metal's points.
#[derive(Debug, Clone, PartialEq)]
pub struct LawErrors {
    /// Normal law name.
    pub law: String,
    /// RMS relative errors in the order of [`QUANTITIES`].
    pub rms: [f64; 4],
    /// √((rms_e² + rms_δmax²)/2): the ranking's key.
    pub combined: f64,
    /// Points compared.
    pub points: usize,
}

/// The laws of one metal, best first.
#[derive(Debug, Clone, PartialEq)]
pub struct MetalRanking {
    /// Metal preset.
    pub metal: String,
    /// The laws, sorted by [`LawErrors::combined`].
    pub laws: Vec<LawErrors>,
}

/// RMS of `v` (NaN when empty).
fn rms(v: &[f64]) -> f64 {
    (v.iter().map(|x| x * x).sum::<f64>() / v.len() as f64).sqrt()
}

/// The metals of `head_on`, in the order they first appear.
pub fn metals_of(head_on: &[HeadOnResult]) -> Vec<&str> {
    let mut metals: Vec<&str> = vec![];
    for h in head_on {
        if !metals.contains(&h.point.metal.as_str()) {
            metals.push(&h.point.metal);
        }
    }
    metals
}

impl LawErrors {
    /// The RMS of each quantity over `rows` (relative errors in the order of
    /// [`QUANTITIES`]) for law `law`.
    pub fn from_rows(law: &str, rows: &[[f64; 4]]) -> LawErrors {
        let r = [0, 1, 2, 3].map(|q| rms(&rows.iter().map(|x| x[q]).collect::<Vec<_>>()));
        LawErrors {
            law: law.to_string(),
            rms: r,
            combined: ((r[0] * r[0] + r[1] * r[1]) / 2.0).sqrt(),
            points: rows.len(),
        }
    }
}

/// The ranking per metal (in the order metals first appear) over every head-on point with
/// an FE answer; `laws` are the registry's normal law names. The damped laws are left out:
/// at their default restitution they say nothing ([`super::calibrated`] ranks them).
pub fn rank_all(head_on: &[HeadOnResult], laws: &[String]) -> Vec<MetalRanking> {
    metals_of(head_on)
        .into_iter()
        .map(|metal| {
            let mut errs: Vec<LawErrors> = laws
                .iter()
                .enumerate()
                .filter(|(_, law)| !is_damped(law))
                .map(|(k, law)| {
                    let rows: Vec<[f64; 4]> = head_on
                        .iter()
                        .filter(|h| h.point.metal == metal)
                        .filter_map(|h| relative_errors(h, k))
                        .collect();
                    LawErrors::from_rows(law, &rows)
                })
                .collect();
            errs.sort_by(|a, b| a.combined.total_cmp(&b.combined));
            MetalRanking {
                metal: metal.to_string(),
                laws: errs,
            }
        })
        .collect()
}

/// The best-ranked law of `metal` (None without FE points).
pub fn best_for<'a>(rank: &'a [MetalRanking], metal: &str) -> Option<&'a str> {
    rank.iter()
        .find(|r| r.metal == metal)?
        .laws
        .first()
        .filter(|l| l.points > 0)
        .map(|l| l.law.as_str())
}
