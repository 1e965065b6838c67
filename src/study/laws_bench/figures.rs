//! The benchmark's SVG figures: e(v) per metal (every law as a line, FE points with error
//! bars), e against v/v_y for both diameters (where D drops out), the oblique points' e_t
//! and spin against the normalised angle of incidence (every tangential law, FE with bars,
//! the elastic theory), each metal's quasi-static FE loop against every normal law, F(δ)
//! loading-unloading loops at three speeds and δ(t) (FE pilot curve against every law).

use super::fe::ObliqueFe;
use super::law_side::{head_on_law, thin};
use super::loops::phases;
use super::matrix::{log_spaced, loop_speeds};
use super::oblique_report::{group, groups, response};
use super::{BenchResults, HeadOnResult, LoopResult};
use crate::analytic::laws::Registry;
use crate::atomic::write_atomic;
use crate::error::{Error, Result};
use crate::study::common::plots::{Chart, Series, Style};
use std::path::Path;

/// Speeds of each law's e(v) line.
pub const LINE_SPEEDS: usize = 25;

/// Most points of a curve in a figure (keeps the committed SVGs small).
pub const FIGURE_ROWS: usize = 100;

/// One written figure: file name and caption.
#[derive(Debug, Clone, PartialEq)]
pub struct Figure {
    /// File name in the output folder.
    pub file: String,
    /// One-line caption.
    pub caption: String,
}

/// The head-on points of `metal` at `diameter`, speeds ascending.
fn points_of<'a>(r: &'a BenchResults, metal: &str, diameter: f64) -> Vec<&'a HeadOnResult> {
    r.head_on
        .iter()
        .filter(|h| h.point.metal == metal && h.point.diameter == diameter)
        .collect()
}

/// FE e as points and their error bars (bars only where the error is finite), x mapped by
/// `x`.
fn fe_series(pts: &[&HeadOnResult], label: &str, x: impl Fn(&HeadOnResult) -> f64) -> Vec<Series> {
    let mut points = vec![];
    let mut bars = vec![];
    for h in pts {
        if let Some(f) = h.fe_done() {
            points.push((x(h), f.e.finest));
            if f.e.error.is_finite() {
                bars.push((x(h), f.e.finest - f.e.error));
                bars.push((x(h), f.e.finest + f.e.error));
            }
        }
    }
    let mut out = vec![Series {
        label: label.to_string(),
        points,
        style: Style::Points,
    }];
    if !bars.is_empty() {
        out.push(Series {
            label: format!("{label} error bar"),
            points: bars,
            style: Style::Bars,
        });
    }
    out
}

/// e(log10 v) of every law (lines over the matrix's speed range) and FE, for `metal` at the
/// largest diameter.
fn e_of_v(r: &BenchResults, registry: &Registry, metal: &str) -> Result<Option<Chart>> {
    let d = r.matrix.largest_diameter();
    let pts = points_of(r, metal, d);
    let Some(first) = pts.first() else {
        return Ok(None);
    };
    let (lo, hi) = (pts[0].point.speed, pts[pts.len() - 1].point.speed);
    let speeds = if hi > lo {
        log_spaced(lo, hi, LINE_SPEEDS)
    } else {
        vec![lo]
    };
    let mut series = vec![];
    for law in &r.normal_laws {
        let mut points = vec![];
        for &v in &speeds {
            let i = head_on_law(registry, law, &first.point, v)?;
            points.push((v.log10(), i.e));
        }
        series.push(Series {
            label: law.clone(),
            points,
            style: Style::Line,
        });
    }
    series.extend(fe_series(&pts, "FE", |h| h.point.speed.log10()));
    Ok(Some(Chart {
        title: format!("{metal}, D = {} mm: e against speed", 1e3 * d),
        x_label: "log10 of the relative speed v (m/s)".into(),
        y_label: "coefficient of restitution e (-)".into(),
        series,
    }))
}

/// FE e against log10(v/v_y) for every metal and diameter.
fn e_of_v_over_vy(r: &BenchResults) -> Chart {
    let mut series = vec![];
    for metal in &r.matrix.metals {
        for &d in &r.matrix.diameters {
            let pts = points_of(r, metal, d);
            series.extend(fe_series(
                &pts,
                &format!("{metal} D = {} mm", 1e3 * d),
                |h| (h.point.speed / h.yield_speed).log10(),
            ));
        }
    }
    Chart {
        title: "FE e against v/v_y: both diameters".into(),
        x_label: "log10 of v/v_y (-)".into(),
        y_label: "coefficient of restitution e (-)".into(),
        series,
    }
}

/// The quantity an oblique chart plots.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum ObliqueQuantity {
    /// Tangential restitution e_t of the contact points.
    Restitution,
    /// Spin of ball 1 after, rad/s.
    Spin,
}

/// e_t or ω against ψ₁ for one metal and response: each tangential law (lines through the
/// matrix's angles), FE points with their bars, and on the elastic twin Maw, Barber &
/// Fawcett's theory. `None` without points.
fn oblique_chart(
    r: &BenchResults,
    metal: &str,
    elastic: bool,
    q: ObliqueQuantity,
) -> Option<Chart> {
    let pts = group(r, metal, elastic);
    let first = pts.first()?;
    let pick_fe = |f: &ObliqueFe| match q {
        ObliqueQuantity::Restitution => f.tangential_restitution,
        ObliqueQuantity::Spin => f.spin,
    };
    let mut series: Vec<Series> = r
        .tangential_laws
        .iter()
        .enumerate()
        .map(|(k, law)| Series {
            label: law.clone(),
            points: pts
                .iter()
                .filter_map(|o| {
                    let l = o.laws.get(k)?;
                    let y = match q {
                        ObliqueQuantity::Restitution => l.tangential_restitution,
                        ObliqueQuantity::Spin => l.spin,
                    };
                    Some((o.point.angle, y))
                })
                .collect(),
            style: Style::Line,
        })
        .collect();
    let theory: Vec<(f64, f64)> = pts
        .iter()
        .filter_map(|o| {
            let t = o.theory?;
            let y = match q {
                ObliqueQuantity::Restitution => t.tangential_restitution,
                ObliqueQuantity::Spin => t.spin,
            };
            Some((o.point.angle, y))
        })
        .collect();
    if !theory.is_empty() {
        series.push(Series {
            label: "Maw, Barber & Fawcett".into(),
            points: theory,
            style: Style::Line,
        });
    }
    let (mut points, mut bars) = (vec![], vec![]);
    for o in &pts {
        if let Some(f) = o.fe.as_ref().and_then(|f| f.done()) {
            let v = pick_fe(f);
            points.push((o.point.angle, v.finest));
            if v.error.is_finite() {
                bars.push((o.point.angle, v.finest - v.error));
                bars.push((o.point.angle, v.finest + v.error));
            }
        }
    }
    series.push(Series {
        label: "FE".into(),
        points,
        style: Style::Points,
    });
    if !bars.is_empty() {
        series.push(Series {
            label: "FE error bar".into(),
            points: bars,
            style: Style::Bars,
        });
    }
    let (what, unit) = match q {
        ObliqueQuantity::Restitution => ("tangential restitution e_t", "(-)"),
        ObliqueQuantity::Spin => ("spin of ball 1 after", "(rad/s)"),
    };
    Some(Chart {
        title: format!(
            "{metal} ({}), D = {} mm, v_n = {} m/s: {what}",
            response(elastic),
            1e3 * first.point.diameter,
            first.point.normal_speed
        ),
        x_label: "normalised angle of incidence psi1 = kappa v_t/(mu v_n) (-)".into(),
        y_label: format!("{what} {unit}"),
        series,
    })
}

/// A figure of one head-on point's contact history (rows t, δ, F): what it plots and how it
/// is named.
struct HistoryFigure {
    /// First word of the file name (`loop` → `loop_{metal}_v{v}.svg`).
    stem: &'static str,
    /// What the chart's title ends with.
    title: &'static str,
    /// What the caption begins with.
    caption: &'static str,
    /// The x and y axes: each its column of the (t, δ, F) rows, the factor from the rows'
    /// SI unit to the axis' unit, and its label.
    axes: [(usize, f64, &'static str); 2],
}

/// The loading-unloading loop F(δ), δ in µm.
const LOOP_FIGURE: HistoryFigure = HistoryFigure {
    stem: "loop",
    title: "F(delta)",
    caption: "F(δ) loading-unloading",
    axes: [
        (1, 1e6, "approach delta (um)"),
        (2, 1.0, "normal force F (N)"),
    ],
};

/// The approach δ(t), t and δ in µs and µm.
const DELTA_T_FIGURE: HistoryFigure = HistoryFigure {
    stem: "delta_t",
    title: "delta(t)",
    caption: "δ(t)",
    axes: [(0, 1e6, "time t (us)"), (1, 1e6, "approach delta (um)")],
};

/// File name, caption and chart of figure `fig` of point `h` of `metal` at diameter `d` (m)
/// and speed `v` (m/s).
fn history_figure(
    fig: &HistoryFigure,
    h: &HeadOnResult,
    metal: &str,
    d: f64,
    v: f64,
) -> (String, String, Chart) {
    let at = format!("{metal}, D = {} mm, v = {v:.3} m/s", 1e3 * d);
    let chart = curve_chart(h, fig, format!("{at}: {}", fig.title));
    let file = format!("{}_{metal}_v{v:.3}.svg", fig.stem);
    (file, format!("{}, {at}", fig.caption), chart)
}

/// The chart titled `title` of figure `fig` of point `h`: the FE pilot curve and every law.
fn curve_chart(h: &HeadOnResult, fig: &HistoryFigure, title: String) -> Chart {
    let [(cx, sx, x_label), (cy, sy, y_label)] = fig.axes;
    let pick = |rows: &[[f64; 3]]| -> Vec<(f64, f64)> {
        thin(rows, FIGURE_ROWS)
            .iter()
            .map(|r| (sx * r[cx], sy * r[cy]))
            .collect()
    };
    let mut series: Vec<Series> = h
        .laws
        .iter()
        .map(|l| Series {
            label: l.law.clone(),
            points: pick(&l.curve),
            style: Style::Line,
        })
        .collect();
    if let Some(f) = h.fe_done() {
        series.push(Series {
            label: "FE (pilot run)".into(),
            points: pick(&f.curve),
            style: Style::Points,
        });
    }
    Chart {
        title,
        x_label: x_label.into(),
        y_label: y_label.into(),
        series,
    }
}

/// Law forces above this multiple of the FE peak force are left out of a loop figure, so
/// that the elastic laws (several times the FE force) do not flatten the plastic ones.
pub const LOOP_FIGURE_FORCE_CAP: f64 = 1.5;

/// The quasi-static loop `l` of the pair's approach (µm) and force (N): the finest FE loop
/// (points) and each normal law's curve on it up to [`LOOP_FIGURE_FORCE_CAP`] times the FE
/// peak force (lines). `None` without an FE loop.
fn static_loop_chart(l: &LoopResult) -> Option<Chart> {
    let fe = l.fe.as_ref().and_then(|f| f.done())?;
    let cap = LOOP_FIGURE_FORCE_CAP * fe.finest.summary.force_at_max;
    let delta: Vec<f64> = phases(&fe.finest).map(|(_, p)| 2e6 * p.approach).collect();
    let mut series: Vec<Series> = l
        .laws
        .iter()
        .map(|law| Series {
            label: law.law.clone(),
            points: delta
                .iter()
                .copied()
                .zip(law.forces.iter().copied())
                .filter(|&(_, f)| f <= cap)
                .collect(),
            style: Style::Line,
        })
        .collect();
    series.push(Series {
        label: "FE (static loop, finest level)".into(),
        points: phases(&fe.finest)
            .map(|(_, p)| (2e6 * p.approach, p.force))
            .collect(),
        style: Style::Points,
    });
    let p = &l.point;
    Some(Chart {
        title: format!(
            "{}, D = {} mm, v = {:.3} m/s: quasi-static F(delta)",
            p.metal,
            1e3 * p.diameter,
            p.speed
        ),
        x_label: "approach of the pair delta (um)".into(),
        y_label: "normal force F (N)".into(),
        series,
    })
}

/// Writes the figures into `out` (law lines from `registry`) and returns them in report
/// order.
///
/// Errors: a law that fails to integrate, a drawing or file failure.
pub fn write_figures(out: &Path, r: &BenchResults, registry: &Registry) -> Result<Vec<Figure>> {
    std::fs::create_dir_all(out).map_err(|e| Error::io(out, e))?;
    let mut figs = vec![];
    let mut write = |file: String, caption: String, chart: &Chart| -> Result<()> {
        write_atomic(out.join(&file), chart.svg()?.as_bytes())?;
        figs.push(Figure { file, caption });
        Ok(())
    };
    let d = r.matrix.largest_diameter();
    for metal in &r.matrix.metals {
        if let Some(c) = e_of_v(r, registry, metal)? {
            write(
                format!("e_v_{metal}.svg"),
                format!(
                    "e(v), {metal}, D = {} mm: every law (lines) and FE (points with their error bars)",
                    1e3 * d
                ),
                &c,
            )?;
        }
    }
    write(
        "e_v_over_vy.svg".into(),
        "FE e against v/v_y, every metal at both diameters".into(),
        &e_of_v_over_vy(r),
    )?;
    for (metal, elastic) in groups(r) {
        for (q, name, what) in [
            (
                ObliqueQuantity::Restitution,
                "et",
                "tangential restitution e_t",
            ),
            (ObliqueQuantity::Spin, "spin", "spin of ball 1 after"),
        ] {
            if let Some(c) = oblique_chart(r, &metal, elastic, q) {
                let twin = if elastic { "_elastic" } else { "" };
                let theory = if elastic {
                    ", Maw, Barber & Fawcett's theory"
                } else {
                    ""
                };
                write(
                    format!("oblique_{name}_{metal}{twin}.svg"),
                    format!(
                        "{what} against ψ₁, {metal} ({}): every tangential law (lines), FE \
                         (points with their bars){theory}",
                        response(elastic)
                    ),
                    &c,
                )?;
            }
        }
    }
    for metal in &r.matrix.metals {
        // The loop at the middle loop speed, else the first with an FE loop.
        let done: Vec<&LoopResult> = r
            .loops
            .iter()
            .filter(|l| {
                &l.point.metal == metal && l.fe.as_ref().is_some_and(|f| f.done().is_some())
            })
            .collect();
        let middle = loop_speeds(&r.matrix.speeds).get(1).copied();
        let Some(l) = done
            .iter()
            .find(|l| Some(l.point.speed) == middle)
            .or(done.first())
        else {
            continue;
        };
        if let Some(c) = static_loop_chart(l) {
            write(
                format!("static_loop_{metal}_v{:.3}.svg", l.point.speed),
                format!(
                    "quasi-static F(δ), {metal}, D = {} mm, v = {:.3} m/s: FE loop (points) and \
                     every normal law (lines, up to 1.5 times the FE peak force)",
                    1e3 * l.point.diameter,
                    l.point.speed
                ),
                &c,
            )?;
        }
    }
    let Some(metal) = r.matrix.metals.first() else {
        return Ok(figs);
    };
    let pts = points_of(r, metal, d);
    let speeds: Vec<f64> = pts.iter().map(|h| h.point.speed).collect();
    for v in loop_speeds(&speeds) {
        let Some(h) = pts.iter().find(|h| h.point.speed == v) else {
            continue;
        };
        let (file, caption, c) = history_figure(&LOOP_FIGURE, h, metal, d, v);
        write(file, caption, &c)?;
    }
    if let Some(&v) = loop_speeds(&speeds).get(1).or(speeds.first()) {
        if let Some(h) = pts.iter().find(|h| h.point.speed == v) {
            let (file, caption, c) = history_figure(&DELTA_T_FIGURE, h, metal, d, v);
            write(file, caption, &c)?;
        }
    }
    Ok(figs)
}
