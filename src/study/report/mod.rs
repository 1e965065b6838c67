//! The verification report: tables and the paper's Figures 6-10 regenerated from a finished
//! sweep folder, written as Markdown with its CSV and SVG files beside it.

pub mod curves;
pub mod damper_plots;
pub mod figures;
pub mod law_fit_files;

use crate::atomic::{ensure_dir, write_atomic};
use crate::error::{Error, Result};
use crate::study::common::plots::{Chart, Series, Style};
use crate::study::sweep::{read_records, CaseRecord, Status, SweepSpec};
use std::fmt::Write as _;
use std::path::Path;

/// Absolute relative difference |a − b|/|b| (None when either is missing).
fn rel(a: Option<f64>, b: Option<f64>) -> Option<f64> {
    match (a, b) {
        (Some(a), Some(b)) if b.abs() > 0.0 => Some(((a - b) / b).abs()),
        _ => None,
    }
}

/// Mean and max of the available values, as percentages.
fn stats(v: &[f64]) -> String {
    if v.is_empty() {
        return "-".into();
    }
    let mean = v.iter().sum::<f64>() / v.len() as f64;
    let max = v.iter().cloned().fold(0.0, f64::max);
    format!("{:.1} / {:.1}", 100.0 * mean, 100.0 * max)
}

type Getter = fn(&crate::study::records::outcome::Outcome) -> f64;

const QUANTITIES: [(&str, Getter); 5] = [
    ("e", |o| o.e),
    ("v1n after", |o| o.v1_after[0]),
    ("v2n after", |o| o.v2_after[0]),
    ("delta_max", |o| o.delta_max),
    ("contact duration", |o| o.contact_duration),
];

fn fe_an(r: &CaseRecord, g: Getter) -> (Option<f64>, Option<f64>) {
    (
        r.fe.as_ref().map(|f| g(&f.outcome)),
        r.analytic.as_ref().map(g),
    )
}

/// How a report treats a sweep that has not finished every case.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Partial {
    /// Refuse it (the committed report must describe the whole sweep).
    Refuse,
    /// Write it, saying in the title how many cases it covers.
    Allow,
}

/// What [`write_report`] wrote.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ReportSummary {
    /// Finished cases the report covers.
    pub finished: usize,
    /// Cases of the whole sweep.
    pub total: usize,
    /// Figure files written (names in `to/ansys/`).
    pub figures: Vec<String>,
    /// Figure files of an earlier report removed because this one has none of that name.
    pub removed: Vec<String>,
}

impl ReportSummary {
    /// Whether the report covers fewer cases than the sweep has.
    pub fn is_partial(&self) -> bool {
        self.finished < self.total
    }
}

/// Finished and total cases of the sweep file `spec_path` in the sweep folder `dir`.
///
/// Errors: the sweep file cannot be read or is invalid.
pub fn finished_cases(spec_path: &Path, dir: &Path) -> Result<(usize, usize)> {
    let cases = SweepSpec::from_file(spec_path)?.cases()?;
    Ok((read_records(dir, &cases).len(), cases.len()))
}

/// Whether `a` and `b` name the same folder (both existing), or the same path.
pub fn same_folder(a: &Path, b: &Path) -> bool {
    match (a.canonicalize(), b.canonicalize()) {
        (Ok(x), Ok(y)) => x == y,
        _ => a == b,
    }
}

/// Whether a file in a report's figure folder is one of the report's figures.
fn is_figure(name: &str) -> bool {
    name.starts_with("fig") && name.ends_with(".svg")
}

/// Removes the figures in `fig_dir` that are not in `keep`; returns their names.
fn remove_stale_figures(fig_dir: &Path, keep: &[String]) -> Result<Vec<String>> {
    let mut removed = Vec::new();
    let entries = std::fs::read_dir(fig_dir).map_err(|e| Error::io(fig_dir, e))?;
    for e in entries.flatten() {
        let name = e.file_name().to_string_lossy().to_string();
        if is_figure(&name) && !keep.contains(&name) {
            std::fs::remove_file(e.path()).map_err(|err| Error::io(e.path(), err))?;
            removed.push(name);
        }
    }
    removed.sort();
    Ok(removed)
}

/// Writes `REPORT.md` into `to` (and its CSV/SVG files into `to/ansys/`), from the sweep
/// results in `dir` for the sweep file `spec_path`; `notes` (Markdown, optional) is appended
/// as the discussion. Figures of an earlier report in `to/ansys/` that this one does not
/// draw are removed, so no stale figure stays beside new tables.
///
/// Errors: no finished case; a partial sweep with [`Partial::Refuse`] (nothing is written);
/// I/O errors naming the path.
pub fn write_report(
    spec_path: &Path,
    dir: &Path,
    to: &Path,
    notes: Option<&str>,
    partial: Partial,
) -> Result<ReportSummary> {
    let spec = SweepSpec::from_file(spec_path)?;
    let cases = spec.cases()?;
    let recs = read_records(dir, &cases);
    if recs.is_empty() {
        return Err(Error::Parse(format!(
            "{}: no finished cases (run twoball sweep first)",
            dir.display()
        )));
    }
    let is_partial = recs.len() < cases.len();
    if is_partial && partial == Partial::Refuse {
        return Err(Error::invalid(
            "--to",
            to.display(),
            format!(
                "a folder for a whole sweep ({} holds {} of {} cases; add --partial to write a partial report there, or leave out --to to write it beside the sweep)",
                dir.display(),
                recs.len(),
                cases.len()
            ),
        ));
    }
    let fig_dir = to.join("ansys");
    ensure_dir(&fig_dir)?;
    let mut figures: Vec<String> = Vec::new();
    // The CSV from the finished case files (also while a sweep is running or after a kill).
    let (csv, _, _) = crate::study::sweep::csv_text(dir, &cases);
    write_atomic(fig_dir.join("sweep.csv"), csv.as_bytes())?;

    let mut md = String::new();
    let w = &mut md;
    let _ = writeln!(
        w,
        "# Verification report: the paper's FE study, FE beside the analytical model{}\n",
        if is_partial {
            format!(" (partial: {} of {} cases)", recs.len(), cases.len())
        } else {
            String::new()
        }
    );
    let _ = writeln!(
        w,
        "Regenerate with `twoball sweep {} --out DIR` then `twoball report DIR{}{}`. \
         Source numbers: [ansys/sweep.csv](ansys/sweep.csv) (one row per case, units in the header).\n",
        spec_path.display(),
        if same_folder(dir, to) {
            String::new()
        } else {
            format!(" --to {}", to.display())
        },
        if is_partial { " --partial" } else { "" }
    );
    let n_done = recs.iter().filter(|r| r.status == Status::Done).count();
    let n_fe = recs.iter().filter(|r| r.fe.is_some()).count();
    let n_none = recs.iter().filter(|r| r.status == Status::NoImpact).count();
    let n_fail = recs.iter().filter(|r| r.status == Status::Failed).count();
    let _ = writeln!(
        w,
        "Cases: {} of {} finished: {} with impact ({} with an FE result), {} no impact (not simulated), {} failed.\n",
        recs.len(),
        cases.len(),
        n_done,
        n_fe,
        n_none,
        n_fail
    );
    let size = |s: crate::study::sweep::Size| match s {
        crate::study::sweep::Size::Absolute(m) => format!("{} mm", m * 1000.0),
        crate::study::sweep::Size::PerDiameter(f) => format!("D/{}", (1.0 / f).round()),
    };
    let _ = writeln!(
        w,
        "Meshes: {}.\n",
        spec.meshes
            .iter()
            .map(|m| format!(
                "`{}` (element size {} in the bulk, {} at the contact pole)",
                m.name,
                size(m.size),
                size(m.pole_size)
            ))
            .collect::<Vec<_>>()
            .join("; ")
    );

    // Agreement table per mesh x tangential pair.
    let _ = writeln!(w, "## Agreement, FE against analytical\n");
    let _ = writeln!(w, "Mean / max of |FE − analytical| / |analytical| in %, over the impacting cases with an FE result.\n");
    let _ = write!(w, "| mesh | tangential v1t/v2t (m/s) | cases |");
    for (q, _) in QUANTITIES {
        let _ = write!(w, " {q} |");
    }
    let _ = writeln!(w, "\n|---|---|---|{}", "---|".repeat(QUANTITIES.len()));
    for m in &spec.meshes {
        for t in &spec.tangential {
            let sel: Vec<&CaseRecord> = recs
                .iter()
                .filter(|r| {
                    r.params.mesh == m.name
                        && r.params.v1t == t[0]
                        && r.params.v2t == t[1]
                        && r.fe.is_some()
                })
                .collect();
            let _ = write!(w, "| {} | {}/{} | {} |", m.name, t[0], t[1], sel.len());
            for (_, g) in QUANTITIES {
                let v: Vec<f64> = sel
                    .iter()
                    .filter_map(|r| {
                        let (a, b) = fe_an(r, g);
                        rel(a, b)
                    })
                    .collect();
                let _ = write!(w, " {} |", stats(&v));
            }
            let _ = writeln!(w);
        }
    }

    // The Figure 8 case.
    let _ = writeln!(
        w,
        "\n## The Figure 8 case (D = 20 mm, +1 / -1 m/s, no tangential speed)\n"
    );
    let _ = writeln!(
        w,
        "| mesh | quantity | FE | analytical | difference |\n|---|---|---|---|---|"
    );
    for r in recs.iter().filter(|r| {
        (r.params.diameter - 0.02).abs() < 1e-12
            && r.params.v2n == -1.0
            && r.params.v1t == 0.0
            && r.params.v2t == 0.0
    }) {
        for (q, g) in QUANTITIES {
            let (a, b) = fe_an(r, g);
            let f = |x: Option<f64>| x.map_or("-".to_string(), |v| format!("{v:.4e}"));
            let d = match (a, b) {
                (Some(a), Some(b)) if b != 0.0 => format!("{:+.2}%", 100.0 * (a - b) / b.abs()),
                _ => "-".into(),
            };
            let _ = writeln!(w, "| {} | {q} | {} | {} | {d} |", r.params.mesh, f(a), f(b));
        }
        if let Some(fe) = &r.fe {
            let _ = writeln!(
                w,
                "| {} | energy error, elements, reduction | {:.2e} | {} | {} |",
                r.params.mesh, fe.energy_error, fe.elements, fe.reduction
            );
        }
    }

    // Figures 6 and 7 per mesh: after-impact normal speeds against the right ball's speed.
    let _ = writeln!(
        w,
        "\n## Figures 6 and 7: after-impact speeds against the right ball's speed\n"
    );
    let _ = writeln!(w, "No tangential speed. Analytical curve: it does not depend on D for equal balls of one material.\n");
    for m in &spec.meshes {
        for (fig, ball, getter) in [(6, "left", 0usize), (7, "right", 1usize)] {
            let mut series = Vec::new();
            let sel = |r: &&CaseRecord| {
                r.params.mesh == m.name && r.params.v1t == 0.0 && r.params.v2t == 0.0
            };
            let speed = |o: &crate::study::records::outcome::Outcome| {
                if getter == 0 {
                    o.v1_after[0]
                } else {
                    o.v2_after[0]
                }
            };
            let d0 = spec.diameters[0];
            let mut an: Vec<(f64, f64)> = recs
                .iter()
                .filter(sel)
                .filter(|r| r.params.diameter == d0)
                .map(|r| match &r.analytic {
                    Some(o) => (r.params.v2n, speed(o)),
                    None => (
                        r.params.v2n,
                        if getter == 0 {
                            r.params.v1n
                        } else {
                            r.params.v2n
                        },
                    ),
                })
                .collect();
            an.sort_by(|a, b| a.0.total_cmp(&b.0));
            series.push(Series {
                label: "analytical".into(),
                points: an,
                style: Style::Line,
            });
            for &d in &spec.diameters {
                let pts: Vec<(f64, f64)> = recs
                    .iter()
                    .filter(sel)
                    .filter(|r| r.params.diameter == d)
                    .filter_map(|r| match (&r.fe, r.status) {
                        (Some(f), _) => Some((r.params.v2n, speed(&f.outcome))),
                        (None, Status::NoImpact) => Some((
                            r.params.v2n,
                            if getter == 0 {
                                r.params.v1n
                            } else {
                                r.params.v2n
                            },
                        )),
                        _ => None,
                    })
                    .collect();
                if !pts.is_empty() {
                    series.push(Series {
                        label: format!("FE, D = {} mm", d * 1000.0),
                        points: pts,
                        style: Style::Points,
                    });
                }
            }
            let chart = Chart {
                title: format!("Figure {fig}: {ball} ball after impact, mesh {}", m.name),
                x_label: "speed of right ball before collision (m/s)".into(),
                y_label: format!("speed of {ball} ball after collision (m/s)"),
                series,
            };
            let name = format!("fig{fig}_{}.svg", m.name);
            write_atomic(fig_dir.join(&name), chart.svg()?.as_bytes())?;
            let _ = writeln!(w, "![Figure {fig}, {}](ansys/{name})\n", m.name);
            figures.push(name);
        }
    }

    // Figures 8-10: delta(t) for the three tangential pairs at D = 20 mm, right ball -1 m/s.
    let _ = writeln!(
        w,
        "## Figures 8-10: relative deformation δ(t), D = 20 mm, +1 / -1 m/s\n"
    );
    for (k, t) in spec.tangential.iter().enumerate() {
        let fig = 8 + k;
        let mut series = Vec::new();
        let pick = |r: &&CaseRecord| {
            (r.params.diameter - 0.02).abs() < 1e-12
                && r.params.v2n == -1.0
                && r.params.v1t == t[0]
                && r.params.v2t == t[1]
        };
        if let Some(r) = recs
            .iter()
            .filter(pick)
            .find(|r| !r.analytic_history.is_empty())
        {
            series.push(Series {
                label: "analytical".into(),
                points: r.analytic_history.iter().map(|p| (p[0], p[1])).collect(),
                style: Style::Line,
            });
        }
        for r in recs
            .iter()
            .filter(pick)
            .filter(|r| !r.fe_history.is_empty())
        {
            series.push(Series {
                label: format!("FE, mesh {}", r.params.mesh),
                points: r.fe_history.iter().map(|p| (p[0], p[1])).collect(),
                style: Style::Line,
            });
        }
        if series.is_empty() {
            continue;
        }
        let chart = Chart {
            title: format!(
                "Figure {fig}: tangential velocities {} and {} m/s",
                t[0], t[1]
            ),
            x_label: "time since first touch (s)".into(),
            y_label: "relative deformation delta (m)".into(),
            series,
        };
        let name = format!("fig{fig}.svg");
        write_atomic(fig_dir.join(&name), chart.svg()?.as_bytes())?;
        let _ = writeln!(w, "![Figure {fig}](ansys/{name})\n");
        figures.push(name);
    }

    // Convergence evidence, if a mesh ladder was run.
    let conv = dir.join("convergence.md");
    if let Ok(text) = std::fs::read_to_string(&conv) {
        let _ = writeln!(w, "## Mesh convergence\n\n{text}\n");
    }

    if n_none > 0 {
        let _ = writeln!(w, "## No impact\n");
        let _ = writeln!(w, "The right ball at +{} m/s moves with the left ball (+{} m/s): they never press on each other. These {} cases are reported, not simulated (the paper lists them in its speed range; notes, inconsistency 7).\n", spec.right_velocities.iter().cloned().fold(f64::NEG_INFINITY, f64::max), spec.left_velocity, n_none);
    }
    if n_fail > 0 {
        let _ = writeln!(w, "## Failed cases\n");
        for r in recs.iter().filter(|r| r.status == Status::Failed) {
            let _ = writeln!(w, "- `{}`: {}", r.id, r.message);
        }
        let _ = writeln!(w);
    }
    if let Some(n) = notes {
        let _ = writeln!(w, "## Discussion\n\n{n}");
    }
    write_atomic(to.join("REPORT.md"), md.as_bytes())?;
    let removed = remove_stale_figures(&fig_dir, &figures)?;
    Ok(ReportSummary {
        finished: recs.len(),
        total: cases.len(),
        figures,
        removed,
    })
}
