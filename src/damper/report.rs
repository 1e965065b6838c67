//! The report of a damper run against its measurements: every case's frequency and damping
//! ratio, the damping the balls add (ζ − ζ_empty) predicted against measured, the damping
//! ratio window by window, and the file's claims checked on both (Markdown and CSV).

use super::claims::Claim;
use super::decay::{peaks, window_decays, WindowDecay};
use super::run::CaseOutcome;
use crate::atomic::write_atomic;
use crate::error::Result;
use std::fmt::Write as _;
use std::path::Path;

/// The windows of `o`'s record, `width` s each ([`window_decays`] over its peaks).
pub fn case_windows(o: &CaseOutcome, width: f64) -> Vec<WindowDecay> {
    let t: Vec<f64> = o.samples.iter().map(|s| s.time).collect();
    let x: Vec<f64> = o.samples.iter().map(|s| s.displacement).collect();
    let end = t.last().copied().unwrap_or(0.0);
    window_decays(&peaks(&t, &x), width, end)
}

/// Header of `windows.csv`.
pub const WINDOWS_HEADER: &str = "case,window_start [s],window_end [s],cycles [-],frequency [Hz],\
damping_ratio [-],added_damping_ratio [-]";

/// `windows.csv`: one row per case and window; a window without two peaks has empty cells.
pub fn windows_csv(outcomes: &[CaseOutcome], width: f64) -> String {
    let mut s = format!("{WINDOWS_HEADER}\n");
    for o in outcomes {
        for w in case_windows(o, width) {
            let cells = w.decay.map_or(",,,".to_string(), |d| {
                format!(
                    "{},{},{},{}",
                    d.cycles,
                    d.frequency,
                    d.ratio,
                    d.ratio - o.empty_damping
                )
            });
            let _ = writeln!(s, "{},{},{},{cells}", o.name, w.window.0, w.window.1);
        }
    }
    s
}

/// What a report is made of.
#[derive(Debug, Clone, Copy)]
pub struct ReportInput<'a> {
    /// The command that reproduces the run (with `--out DIR`), shown beside every table.
    pub command: &'a str,
    /// The outcomes, in the file's case order.
    pub outcomes: &'a [CaseOutcome],
    /// The file's claims; those about a case not run are left out.
    pub claims: &'a [Claim],
    /// Width of the windows, s.
    pub width: f64,
    /// Markdown appended as the discussion, if any.
    pub notes: Option<&'a str>,
}

/// A percentage with three decimals (`0.707`), or `–` for a missing value.
fn pct(x: Option<f64>) -> String {
    x.map_or("–".into(), |x| format!("{:.3}", 100.0 * x))
}

/// A ratio to two significant digits (`0.061`, `1.6`), or `–`.
fn ratio(x: Option<f64>) -> String {
    match x {
        Some(r) if r.is_finite() => {
            let digits = (1.0 - r.abs().log10().floor()).clamp(0.0, 6.0) as usize;
            format!("{r:.digits$}")
        }
        _ => "–".into(),
    }
}

fn yes_no(b: bool) -> &'static str {
    if b {
        "yes"
    } else {
        "no"
    }
}

/// The cases table: frequency, ζ and the added damping, predicted against measured.
fn cases_table(r: &ReportInput, s: &mut String) {
    let _ = writeln!(
        s,
        "| case | balls | ball mass [kg] | mass ratio [%] | stated mass ratio [%] | f predicted [Hz] | f measured [Hz] | ζ predicted [%] | ζ measured [%] | added ζ predicted [%] | added ζ measured [%] | added: predicted / measured | energy residual |"
    );
    let _ = writeln!(s, "|{}", "---|".repeat(13));
    for o in r.outcomes {
        let m = o.measured;
        let added_pred = (o.balls > 0).then(|| o.added_damping());
        let added_meas = o.measured_added_damping().filter(|_| o.balls > 0);
        let _ = writeln!(
            s,
            "| {} | {} | {:.4} | {:.2} | {} | {:.4} | {} | {:.3} | {} | {} | {} | {} | {:.1e} |",
            o.name,
            o.balls,
            o.ball_mass,
            100.0 * o.ball_mass / o.frame_mass,
            m.and_then(|m| m.mass_ratio)
                .map_or("–".into(), |x| format!("{:.2}", 100.0 * x)),
            o.decay.frequency,
            m.map_or("–".into(), |m| format!("{}", m.frequency)),
            100.0 * o.decay.ratio,
            pct(m.map(|m| m.damping_ratio)),
            pct(added_pred),
            pct(added_meas),
            ratio(added_pred.zip(added_meas).map(|(p, q)| p / q)),
            o.worst_residual
        );
    }
}

/// The windows table: ζ of every case in each window, beside the whole window's and the
/// measured one.
fn windows_table(r: &ReportInput, s: &mut String) {
    let per_case: Vec<Vec<WindowDecay>> = r
        .outcomes
        .iter()
        .map(|o| case_windows(o, r.width))
        .collect();
    let heads: Vec<(f64, f64)> = per_case
        .iter()
        .max_by_key(|w| w.len())
        .map(|w| w.iter().map(|w| w.window).collect())
        .unwrap_or_default();
    let _ = write!(s, "| case |");
    for (a, b) in &heads {
        let _ = write!(s, " {a}-{b} s |");
    }
    let _ = writeln!(s, " whole window [%] | measured [%] |");
    let _ = writeln!(s, "|{}", "---|".repeat(heads.len() + 3));
    for (o, w) in r.outcomes.iter().zip(&per_case) {
        let _ = write!(s, "| {} |", o.name);
        for k in 0..heads.len() {
            let _ = write!(
                s,
                " {} |",
                pct(w.get(k).and_then(|w| w.decay).map(|d| d.ratio))
            );
        }
        let _ = writeln!(
            s,
            " {:.3} | {} |",
            100.0 * o.decay.ratio,
            pct(o.measured.map(|m| m.damping_ratio))
        );
    }
}

/// The claims table: each claim with the two cases it compares, checked on the measured
/// and the predicted ζ and in each window.
fn claims_table(r: &ReportInput, s: &mut String) -> usize {
    let find = |name: &str| r.outcomes.iter().find(|o| o.name == name);
    let _ = writeln!(
        s,
        "| the paper says (Section 6) | compares | ζ measured [%] | holds measured | ζ predicted [%] | holds predicted | {} s windows where it holds predicted |",
        r.width
    );
    let _ = writeln!(s, "|{}", "---|".repeat(7));
    let mut left_out = 0;
    for c in r.claims {
        let (Some(a), Some(b)) = (find(&c.cases[0]), find(&c.cases[1])) else {
            left_out += 1;
            continue;
        };
        let empty = a.empty_damping;
        let measured = a.measured.zip(b.measured);
        let holds_measured =
            measured.map(|(ma, mb)| c.relation.holds(ma.damping_ratio, mb.damping_ratio, empty));
        let holds = c.relation.holds(a.decay.ratio, b.decay.ratio, empty);
        let (wa, wb) = (case_windows(a, r.width), case_windows(b, r.width));
        let pairs: Vec<bool> = wa
            .iter()
            .zip(&wb)
            .filter_map(|(x, y)| Some(c.relation.holds(x.decay?.ratio, y.decay?.ratio, empty)))
            .collect();
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {:.3} {} {:.3} | {} | {} of {} |",
            c.says,
            c.compares(),
            measured.map_or("–".into(), |(ma, mb)| format!(
                "{:.2} {} {:.2}",
                100.0 * ma.damping_ratio,
                c.relation.symbol(),
                100.0 * mb.damping_ratio
            )),
            holds_measured.map_or("–", yes_no),
            100.0 * a.decay.ratio,
            c.relation.symbol(),
            100.0 * b.decay.ratio,
            yes_no(holds),
            pairs.iter().filter(|&&h| h).count(),
            pairs.len()
        );
    }
    left_out
}

/// The report as Markdown: the command, the cases table, the windows table (with
/// `windows.svg`), the claims table, then the notes.
pub fn report_markdown(r: &ReportInput) -> String {
    let mut s = String::new();
    let empty = r.outcomes.first().map_or(0.0, |o| o.empty_damping);
    let _ = writeln!(
        s,
        "# The particle damper against its measurements\n\n\
The tables of the next three sections are written by one command (`REPORT.md`, `windows.csv` \
and `windows.svg`; `--to FOLDER` writes them into FOLDER with FOLDER/NOTES.md appended):\n\n```sh\n{}\n```\n\n\
ζ is the logarithmic decrement of the frame's free decay over the run's window; the damping \
the balls add is ζ − ζ_empty, ζ_empty = {:.3} % the empty structure's damping ratio \
(`frame.damping_ratio` of the scene file), for the prediction and the measurement alike.",
        r.command,
        100.0 * empty
    );
    let _ = writeln!(
        s,
        "\n## Predicted against measured\n\n`{}`; one case alone: add `--case CASE` (a case's \
result does not depend on which others run beside it). Mass ratio: the balls' mass over the \
frame mass of the run; stated: the paper's.\n",
        r.command
    );
    cases_table(r, &mut s);
    let _ = writeln!(
        s,
        "\n## The damping ratio window by window\n\n`{}` (`windows.csv`, `windows.svg`). ζ [%] \
by the logarithmic decrement over the peaks inside each {} s window alone (two or three \
cycles), beside the whole window's and the measured ζ; `–`: fewer than two peaks.\n",
        r.command, r.width
    );
    windows_table(r, &mut s);
    let _ = writeln!(
        s,
        "\n![ζ per {} s window of every case](windows.svg)\n",
        r.width
    );
    let _ = writeln!(
        s,
        "## The paper's claims\n\n`{}`; the claims are the scene file's `[[claim]]` entries. \
`A > B`: case A damps more than case B; `A ≈ B`: the damping they add differs by at most \
the claim's `within` of the larger. Checked on Table 2's ζ (measured), on the model's ζ over \
the whole window (predicted) and in each {} s window.\n",
        r.command, r.width
    );
    let left_out = claims_table(r, &mut s);
    if left_out > 0 {
        let _ = writeln!(
            s,
            "\n{left_out} claims about cases this run did not include are left out."
        );
    }
    if let Some(notes) = r.notes {
        let _ = write!(s, "\n{}", notes.trim_start());
        if !s.ends_with('\n') {
            s.push('\n');
        }
    }
    s
}

/// Writes `REPORT.md` and `windows.csv` of `r` into `dir` (created if needed), atomically.
///
/// Errors: I/O errors naming the path.
pub fn write_report(dir: &Path, r: &ReportInput) -> Result<()> {
    crate::atomic::ensure_dir(dir)?;
    write_atomic(
        dir.join("windows.csv"),
        windows_csv(r.outcomes, r.width).as_bytes(),
    )?;
    write_atomic(dir.join("REPORT.md"), report_markdown(r).as_bytes())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ratios_keep_two_significant_digits() {
        assert_eq!(ratio(Some(0.0614)), "0.061");
        assert_eq!(ratio(Some(1.62)), "1.6");
        assert_eq!(ratio(Some(0.5)), "0.50");
        assert_eq!(ratio(Some(f64::NAN)), "–");
        assert_eq!(ratio(None), "–");
        assert_eq!(ratio(Some(0.0)), "0.000000");
        assert_eq!(ratio(Some(36.4)), "36");
        assert_eq!(pct(Some(0.0045)), "0.450");
    }
}
