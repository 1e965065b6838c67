//! REPORT.md of the benchmark: the matrix, the FE points, each law's errors over speed per
//! metal, the ranking, where each law fails (in numbers), D = 5 against 20 mm, the oblique
//! impacts, the quasi-static loops, the fits and the cost.

use super::bars::{bar, metal_bars, TARGET_E_BAR};
use super::calibrated::MetalCalibration;
use super::figures::Figure;
use super::fit::{LawFit, MetalFit, FIT_RANGE, TARGET_E_ERROR};
use super::ranking::{relative_errors, LawErrors, MetalRanking, QUANTITIES};
use super::similarity::{check_differences, rate_independent};
use super::{BenchResults, HeadOnResult};
use crate::atomic::write_atomic;
use crate::error::{Error, Result};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// |relative error in e| within which a law "holds" at a point.
pub const HOLDS_E: f64 = 0.05;

/// A signed percentage with one decimal, or `n/a`.
fn pct(x: f64) -> String {
    if x.is_finite() {
        format!("{:+.1}", 100.0 * x)
    } else {
        "n/a".into()
    }
}

/// The elastic (Hertz) maximum approach of point `h`'s pair at its speed, m.
fn hertz_approach(h: &HeadOnResult) -> f64 {
    crate::analytic::Body::ball(h.point.material, h.point.diameter, "ball").map_or(f64::NAN, |b| {
        crate::analytic::HertzPair::between(&b, &b).max_approach(h.point.speed)
    })
}

/// The head-on points of `metal` at `d`.
fn points<'a>(r: &'a BenchResults, metal: &str, d: f64) -> Vec<&'a HeadOnResult> {
    r.head_on
        .iter()
        .filter(|h| h.point.metal == metal && h.point.diameter == d)
        .collect()
}

fn header(s: &mut String, command: &str, r: &BenchResults) {
    let _ = writeln!(s, "# Contact laws against FE: the benchmark\n");
    let _ = writeln!(
        s,
        "Reproduce (the FE cache is `DIR/fe`; delete it to rerun the FE from scratch, \
         `--laws-only` reruns the laws, fits, figures and this report on the cached FE):\n\n\
         ```sh\n{command}\n```\n"
    );
    let scaled = r
        .head_on
        .iter()
        .filter_map(|h| h.fe_done())
        .filter(|f| f.scaled_from.is_some())
        .count();
    let _ = writeln!(
        s,
        "What is measured. Head-on impacts of two identical balls: FE on the meridian section \
         (one ball against the symmetry plane; FE model: {}). Each FE quantity is the fine \
         ensemble's mean over the phase of the section's surface rings with its error bar: \
         the two-level estimate from the coarse ensemble plus the fine mean's sampling error{} \
         (`study::phase_ensemble::converged_head_on`; docs/contact-penalty.md, \"The section's \
         converged answer\" and \"Is the ensemble's bar honest?\"){}. Every normal law of \
         `twoball laws` with its default parameters for the pair (as `twoball laws run`), \
         integrated with the Coulomb tangential law (no tangential speed). Errors are relative, \
         (law − FE)/FE, in per cent. Oblique impacts: the 3D half model (default graded meshes, two-level error bars) \
         against every tangential law. v_y is the relative speed at which the pair \
         starts to yield: the Hertz impact whose maximum approach is the three-phase model's \
         yield approach δ₁ = R*(πσ_p/(2E*))² (Li, Yang & Shi eq. 10, σ_p = (1 + π/2)σ_s; two-ball \
         E*, R* = R/2, m* = m/2), v_y = √(16E*√R*δ₁^(5/2)/(15m*)); it does not depend on D. \
         Johnson's onset p₀ = 1.6σ_s gives a v_y smaller by (1.6/(1 + π/2))^(5/2) = 0.306.\n",
        r.plan.model(),
        if r.plan.mass_scaling > 0.0 {
            " plus the mass-scaling bias bound, 10 × the budget relative (docs/contact-penalty.md, \
             \"Mass scaling of the contact region\")"
        } else {
            ""
        },
        if scaled > 0 {
            format!(
                ". {scaled} head-on points of the bilinear metals are not run but scaled from the \
                 largest diameter by similarity (e unchanged, δ_max and t_c ∝ D, F ∝ D²; \
                 marked \"scaled\" in the FE table; the check is in \"D = … against …\")"
            )
        } else {
            String::new()
        }
    );
}

fn bars_section(s: &mut String, r: &BenchResults) {
    let _ = writeln!(
        s,
        "## FE error bars
"
    );
    let _ = writeln!(
        s,
        "Per metal, over the head-on points with an FE answer (scaled points included): the \
         relative FE error bar in e (per cent), the points whose bar is below {:.1} %, and the \
         laws whose e lies within the FE bar at some points (there the law's error in e cannot \
         be told from the FE's; count of points).\n",
        100.0 * TARGET_E_BAR
    );
    let _ = writeln!(
        s,
        "| metal | points | e bar min (%) | median (%) | max (%) | bar < {:.1} % | laws with e within the FE bar |",
        100.0 * TARGET_E_BAR
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|---|");
    let stats = metal_bars(r);
    for m in &stats {
        let [lo, med, hi] = m.min_median_max();
        let laws = if m.laws_inside.is_empty() {
            "none".to_string()
        } else {
            m.laws_inside
                .iter()
                .map(|(l, n)| format!("{l} ({n})"))
                .collect::<Vec<_>>()
                .join(", ")
        };
        let _ = writeln!(
            s,
            "| {} | {} | {:.2} | {:.2} | {:.2} | {} | {laws} |",
            m.metal,
            m.relative.len(),
            100.0 * lo,
            100.0 * med,
            100.0 * hi,
            m.below_target
        );
    }
    let below: usize = stats.iter().map(|m| m.below_target).sum();
    let total: usize = stats.iter().map(|m| m.relative.len()).sum();
    let refined = r
        .head_on
        .iter()
        .filter_map(|h| h.fe_done())
        .filter(|f| f.fine_level.is_some_and(|l| l > r.plan.phase.level))
        .count();
    let refined = if refined > 0 {
        format!(
            " {refined} of them were refined one level (their bar on level {} exceeded the \
             tolerance; \"(level …)\" in the FE table).",
            r.plan.phase.level
        )
    } else {
        String::new()
    };
    let _ = writeln!(
        s,
        "\n{below} of {total} head-on points have an FE bar below {:.1} % in e.{refined} The cost and bars \
         of other plans (`--fe-level`, `--phase-meshes`, `--fe-band`, `--fe-mass-scaling`, `--fe-tolerance`) are in docs/contact-laws.md, \"FE error \
         bars\".\n",
        100.0 * TARGET_E_BAR
    );
}

fn matrix_section(s: &mut String, r: &BenchResults) {
    let _ = writeln!(s, "## Matrix\n");
    let _ = writeln!(
        s,
        "Speeds (relative, m/s): {}. Diameters: {} mm.\n",
        r.matrix
            .speeds
            .iter()
            .map(|v| format!("{v:.4}"))
            .collect::<Vec<_>>()
            .join(", "),
        r.matrix
            .diameters
            .iter()
            .map(|d| format!("{}", 1e3 * d))
            .collect::<Vec<_>>()
            .join(", ")
    );
    let _ = writeln!(
        s,
        "| metal | E (GPa) | ν | ρ (kg/m³) | σ_s (MPa) | hardening | v_y (mm/s) | v/v_y |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|");
    for metal in &r.matrix.metals {
        let Some(h) = r.head_on.iter().find(|h| &h.point.metal == metal) else {
            continue;
        };
        let m = &h.point.material;
        let hardening = if m.hardening.is_some() {
            "Johnson-Cook".to_string()
        } else {
            format!("bilinear, E_t = {} GPa", m.tangent / 1e9)
        };
        let (lo, hi) = (
            r.matrix.speeds[0],
            r.matrix.speeds[r.matrix.speeds.len() - 1],
        );
        let _ = writeln!(
            s,
            "| {metal} | {} | {} | {} | {} | {hardening} | {:.3} | {:.3} to {:.0} |",
            m.youngs / 1e9,
            m.nu,
            m.rho,
            m.yield_strength / 1e6,
            1e3 * h.yield_speed,
            lo / h.yield_speed,
            hi / h.yield_speed
        );
    }
    let _ = writeln!(s);
}

fn fe_section(s: &mut String, r: &BenchResults) {
    let _ = writeln!(s, "## FE points\n");
    let _ = writeln!(
        s,
        "FE δ_max over the elastic (Hertz) δ_max at the same speed in the column δ/δ_H.\n"
    );
    let _ = writeln!(
        s,
        "| metal | D (mm) | v (m/s) | v/v_y | e | e bar (%) | δ_max (µm) | δ/δ_H | t_c (µs) | F_peak (N) | CPU (s) |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|---|---|---|");
    for h in &r.head_on {
        let p = &h.point;
        let lead = format!(
            "| {} | {} | {:.4} | {:.1} |",
            p.metal,
            1e3 * p.diameter,
            p.speed,
            p.speed / h.yield_speed
        );
        match (&h.fe, h.fe_done()) {
            (_, Some(f)) => {
                let refined = match f.fine_level {
                    Some(l) if l > r.plan.phase.level => format!(" (level {l})"),
                    _ => String::new(),
                };
                let cpu = match f.scaled_from {
                    Some(d) => format!("scaled from {} mm{refined}", 1e3 * d),
                    None => format!("{:.1}{refined}", f.cpu_seconds),
                };
                let _ = writeln!(
                    s,
                    "{lead} {} | {:.2} | {} | {:.3} | {} | {} | {cpu} |",
                    bar(f.e.finest, f.e.error, 1.0, 4),
                    100.0 * f.e.relative_error.unwrap_or(f64::NAN),
                    bar(f.delta_max.finest, f.delta_max.error, 1e6, 3),
                    f.delta_max.finest / hertz_approach(h),
                    bar(f.contact_duration.finest, f.contact_duration.error, 1e6, 2),
                    bar(f.peak_force.finest, f.peak_force.error, 1.0, 1),
                );
            }
            (Some(super::cache::Stored::Failed(m)), None) => {
                let _ = writeln!(s, "{lead} failed: {} | | | | | | |", m.replace('|', "/"));
            }
            _ => {
                let _ = writeln!(s, "{lead} not run | | | | | | |");
            }
        }
    }
    let cpu: f64 = r
        .head_on
        .iter()
        .filter_map(|h| h.fe_done())
        .map(|f| f.cpu_seconds)
        .sum();
    let slowest = r
        .head_on
        .iter()
        .filter_map(|h| h.fe_done().map(|f| (f.cpu_seconds, h)))
        .max_by(|a, b| a.0.total_cmp(&b.0));
    let _ = write!(s, "\nFE CPU time of the head-on points: {cpu:.0} s");
    if let Some((t, h)) = slowest {
        let _ = write!(
            s,
            "; the slowest, {} D = {} mm at {:.4} m/s, {t:.1} s",
            h.point.metal,
            1e3 * h.point.diameter,
            h.point.speed
        );
    }
    let _ = writeln!(s, ".\n");
}

/// A law's RMS errors as table cells: e, δ_max, t_c, peak force and combined in per cent,
/// then the points compared.
fn rms_cells(l: &LawErrors) -> String {
    let [e, d, t, f] = l.rms.map(|x| format!("{:.1}", 100.0 * x));
    format!(
        "{e} | {d} | {t} | {f} | {:.1} | {}",
        100.0 * l.combined,
        l.points
    )
}

fn ranking_section(s: &mut String, rank: &[MetalRanking]) {
    let _ = writeln!(s, "## Ranking\n");
    let _ = writeln!(
        s,
        "Per metal, over every head-on point with an FE answer (both diameters): RMS relative \
         error in e, δ_max, t_c and peak force (per cent); ranked by √((RMS_e² + RMS_δmax²)/2). \
         The damped laws, whose restitution is a parameter, are ranked calibrated in the next \
         section.\n"
    );
    for m in rank {
        let _ = writeln!(s, "### {}\n", m.metal);
        let _ = writeln!(
            s,
            "| rank | law | RMS e | RMS δ_max | RMS t_c | RMS F_peak | combined | points |"
        );
        let _ = writeln!(s, "|---|---|---|---|---|---|---|---|");
        for (i, l) in m.laws.iter().enumerate() {
            let _ = writeln!(s, "| {} | {} | {} |", i + 1, l.law, rms_cells(l));
        }
        let _ = writeln!(s);
    }
}

fn calibrated_section(s: &mut String, cal: &[MetalCalibration]) {
    let _ = writeln!(s, "## Damped laws, calibrated\n");
    let _ = writeln!(
        s,
        "Per metal, each damped law's one damping parameter fitted so that its e equals the \
         FE's at the reference point (the median speed at the largest diameter, marked), then \
         judged at the metal's other points: RMS relative error (per cent) over those points, \
         ranked as above. The tables of errors over speed below show these laws at their \
         defaults.\n"
    );
    for m in cal {
        let _ = writeln!(
            s,
            "### {}: fitted at {:.4} m/s, D = {} mm\n",
            m.metal,
            m.speed,
            1e3 * m.diameter
        );
        let _ = writeln!(
            s,
            "| rank | law | fitted | RMS e | RMS δ_max | RMS t_c | RMS F_peak | combined | points |"
        );
        let _ = writeln!(s, "|---|---|---|---|---|---|---|---|---|");
        for (i, c) in m.laws.iter().enumerate() {
            let l = &c.errors;
            let (name, value) = c.parameter;
            let cells = rms_cells(l);
            let _ = writeln!(
                s,
                "| {} | {} | {name} = {value:.4e} | {cells} |",
                i + 1,
                l.law
            );
        }
        if !m.failed.is_empty() {
            let _ = writeln!(
                s,
                "\nNo parameter value reaches the FE's e at the reference: {}.",
                m.failed.join(", ")
            );
        }
        let _ = writeln!(s);
    }
}

fn errors_section(s: &mut String, r: &BenchResults) {
    let _ = writeln!(s, "## Errors over speed\n");
    let _ = writeln!(
        s,
        "(law − FE)/FE in per cent, per metal and diameter, columns the relative speeds (m/s); \
         † marks a point outside the law's validity range (`twoball laws list`; section \"Laws outside \
         their range\").\n"
    );
    for metal in &r.matrix.metals {
        for &d in &r.matrix.diameters {
            let pts = points(r, metal, d);
            if pts.iter().all(|h| h.fe_done().is_none()) {
                continue;
            }
            for (q, name) in QUANTITIES.iter().enumerate() {
                let _ = writeln!(s, "**{metal}, D = {} mm: {name}**\n", 1e3 * d);
                let _ = write!(s, "| law |");
                for h in &pts {
                    let _ = write!(s, " {:.3} |", h.point.speed);
                }
                let _ = writeln!(s);
                let _ = writeln!(s, "|---|{}", "---|".repeat(pts.len()));
                for (k, law) in r.normal_laws.iter().enumerate() {
                    let _ = write!(s, "| {law} |");
                    for h in &pts {
                        let e = relative_errors(h, k).map_or(f64::NAN, |x| x[q]);
                        let mark = if h.laws.get(k).is_some_and(|l| l.outside.is_some()) {
                            " †"
                        } else {
                            ""
                        };
                        let _ = write!(s, " {}{mark} |", pct(e));
                    }
                    let _ = writeln!(s);
                }
                let _ = writeln!(s);
            }
        }
    }
}

/// Per law, the head-on points outside its validity range: how many, and the warning at
/// the fastest of them.
fn validity_section(s: &mut String, r: &BenchResults) {
    let _ = writeln!(s, "## Laws outside their range\n");
    let _ = writeln!(
        s,
        "Each law's validity range as its source states it (`twoball laws list`); a point outside \
         it is marked † in the error tables.\n"
    );
    let _ = writeln!(
        s,
        "| law | points outside / all | at the fastest such point |"
    );
    let _ = writeln!(s, "|---|---|---|");
    for (k, law) in r.normal_laws.iter().enumerate() {
        let mut flagged: Vec<(f64, &str)> = r
            .head_on
            .iter()
            .filter_map(|h| {
                let o = h.laws.get(k)?.outside.as_deref()?;
                Some((h.point.speed, o))
            })
            .collect();
        flagged.sort_by(|a, b| a.0.total_cmp(&b.0));
        let last = flagged.last().map_or("-", |x| x.1);
        let _ = writeln!(
            s,
            "| {law} | {} / {} | {last} |",
            flagged.len(),
            r.head_on.len()
        );
    }
    let _ = writeln!(s);
}

/// The speeds (m/s) of `pts` at which law `k` holds e within [`HOLDS_E`], as ranges.
fn holds(pts: &[&HeadOnResult], k: usize) -> String {
    let mut parts: Vec<String> = vec![];
    let mut run: Option<(f64, f64)> = None;
    for h in pts {
        let Some(e) = relative_errors(h, k) else {
            continue;
        };
        if e[0].abs() <= HOLDS_E {
            run = Some(run.map_or((h.point.speed, h.point.speed), |(a, _)| (a, h.point.speed)));
        } else if let Some((a, b)) = run.take() {
            parts.push(range_text(a, b));
        }
    }
    if let Some((a, b)) = run {
        parts.push(range_text(a, b));
    }
    if parts.is_empty() {
        "nowhere".into()
    } else {
        parts.join(", ")
    }
}

fn range_text(a: f64, b: f64) -> String {
    if a == b {
        format!("{a:.3}")
    } else {
        format!("{a:.3}-{b:.3}")
    }
}

/// The signed error of largest magnitude of quantity `q` of law `k` and its speed.
fn worst_at(pts: &[&HeadOnResult], k: usize, q: usize) -> (f64, f64) {
    pts.iter()
        .filter_map(|h| relative_errors(h, k).map(|e| (e[q], h.point.speed)))
        .fold(
            (0.0, f64::NAN),
            |w, x| if x.0.abs() > w.0.abs() { x } else { w },
        )
}

fn failures_section(s: &mut String, r: &BenchResults) {
    let _ = writeln!(s, "## Where the laws fail\n");
    let _ = writeln!(
        s,
        "Per metal at the largest diameter: the speeds (m/s) at which a law's e is within \
         ±{:.0} % of FE, and its worst errors in e, δ_max and t_c with the speed where they occur.\n",
        100.0 * HOLDS_E
    );
    let d = r.matrix.largest_diameter();
    for metal in &r.matrix.metals {
        let pts = points(r, metal, d);
        if pts.iter().all(|h| h.fe_done().is_none()) {
            continue;
        }
        let _ = writeln!(s, "### {metal}, D = {} mm\n", 1e3 * d);
        let _ = writeln!(
            s,
            "| law | e within ±{:.0} % at v (m/s) | worst e (%, at m/s) | worst δ_max | worst t_c |",
            100.0 * HOLDS_E
        );
        let _ = writeln!(s, "|---|---|---|---|---|");
        for (k, law) in r.normal_laws.iter().enumerate() {
            let cell = |q: usize| {
                let (e, v) = worst_at(&pts, k, q);
                format!("{} at {v:.3}", pct(e))
            };
            let _ = writeln!(
                s,
                "| {law} | {} | {} | {} | {} |",
                holds(&pts, k),
                cell(0),
                cell(1),
                cell(2)
            );
        }
        if let Some(k) = r.normal_laws.iter().position(|l| l == "li-yang-shi") {
            let (e, ve) = worst_at(&pts, k, 0);
            let (dm, vd) = worst_at(&pts, k, 1);
            let (tc, vt) = worst_at(&pts, k, 2);
            let _ = writeln!(
                s,
                "\nThe paper's three-phase law (li-yang-shi) on {metal}: e within ±{:.0} % at {}; \
                 worst e {} % at {ve:.3} m/s, δ_max {} % at {vd:.3} m/s, t_c {} % at {vt:.3} m/s.",
                100.0 * HOLDS_E,
                holds(&pts, k),
                pct(e),
                pct(dm),
                pct(tc)
            );
        }
        let _ = writeln!(s);
    }
}

fn diameter_section(s: &mut String, r: &BenchResults) {
    if r.matrix.diameters.len() < 2 {
        return;
    }
    let mut ds = r.matrix.diameters.clone();
    ds.sort_by(f64::total_cmp);
    let (small, large) = (ds[0], ds[ds.len() - 1]);
    let _ = writeln!(s, "## D = {} mm against {} mm\n", 1e3 * small, 1e3 * large);
    let _ = writeln!(
        s,
        "v_y does not depend on D, so a rate-independent, size-free model gives the same e at \
         the same v (and the same v/v_y) for both diameters, and δ_max, t_c scale with D. \
         The FE's departures from that (per cent): e({s_}) / e({l_}) − 1 and \
         (δ_max/D)({s_}) / (δ_max/D)({l_}) − 1 (\"scaled\": the {s_} point is the {l_} one \
         scaled by similarity, so the ratio is 1 by construction; the check below); beside \
         them the laws whose e differs between the diameters (a law with a material time or a \
         speed-fixed stiffness).\n",
        s_ = format!("{} mm", 1e3 * small),
        l_ = format!("{} mm", 1e3 * large)
    );
    let _ = writeln!(
        s,
        "| metal | v (m/s) | v/v_y | FE e ratio − 1 | FE δ_max/D ratio − 1 | laws with e ratio − 1 \
         beyond ±0.1 % |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|");
    for metal in &r.matrix.metals {
        let a = points(r, metal, small);
        let b = points(r, metal, large);
        for (x, y) in a.iter().zip(&b) {
            let (Some(fx), Some(fy)) = (x.fe_done(), y.fe_done()) else {
                continue;
            };
            let laws: Vec<String> = x
                .laws
                .iter()
                .zip(&y.laws)
                .filter(|(p, q)| (p.e / q.e - 1.0).abs() > 1e-3)
                .map(|(p, q)| format!("{} {}", p.law, pct(p.e / q.e - 1.0)))
                .collect();
            let _ = writeln!(
                s,
                "| {metal} | {:.4} | {:.1} | {} | {} | {} |",
                x.point.speed,
                x.point.speed / x.yield_speed,
                if fx.scaled_from.is_some() {
                    "scaled".to_string()
                } else {
                    pct(fx.e.finest / fy.e.finest - 1.0)
                },
                if fx.scaled_from.is_some() {
                    "scaled".to_string()
                } else {
                    pct((fx.delta_max.finest / small) / (fy.delta_max.finest / large) - 1.0)
                },
                if laws.is_empty() {
                    "none".to_string()
                } else {
                    laws.join(", ")
                }
            );
        }
    }
    let _ = writeln!(s);
    similarity_check(s, r, small, large);
}

/// The similarity check: the rate-independent metals' points run at both diameters while
/// others of theirs are scaled.
fn similarity_check(s: &mut String, r: &BenchResults, small: f64, large: f64) {
    let mut rows = vec![];
    for metal in &r.matrix.metals {
        let a = points(r, metal, small);
        let b = points(r, metal, large);
        if !a
            .iter()
            .any(|h| h.fe_done().is_some_and(|f| f.scaled_from.is_some()))
        {
            continue;
        }
        for (x, y) in a.iter().zip(&b) {
            let (Some(fx), Some(fy)) = (x.fe_done(), y.fe_done()) else {
                continue;
            };
            if fx.scaled_from.is_some() || !rate_independent(&x.point.material) {
                continue;
            }
            let d = check_differences(fx, small, fy, large);
            rows.push(format!(
                "| {metal} | {:.4} | {:.1e} | {:.1e} | {:.1e} | {:.1e} |",
                x.point.speed, d[0], d[1], d[2], d[3]
            ));
        }
    }
    if rows.is_empty() {
        return;
    }
    let _ = writeln!(
        s,
        "Similarity check: the {} mm point run, against the {} mm point scaled to it (run / \
         scaled − 1):\n",
        1e3 * small,
        1e3 * large
    );
    let _ = writeln!(s, "| metal | v (m/s) | e | δ_max | t_c | F_peak |");
    let _ = writeln!(s, "|---|---|---|---|---|---|");
    for row in rows {
        let _ = writeln!(s, "{row}");
    }
    let _ = writeln!(s);
}

fn fit_table(s: &mut String, title: &str, fits: &[(String, std::result::Result<LawFit, String>)]) {
    let _ = writeln!(
        s,
        "| law ({title}) | fitted parameters (one sigma) | rms residual | worst e | worst δ_max |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|");
    for (law, f) in fits {
        match f {
            Ok(f) => {
                let params = f
                    .params
                    .iter()
                    .map(|(k, v, sg)| {
                        if sg.is_finite() {
                            format!("{k} = {v:.4e} ± {sg:.1e}")
                        } else {
                            format!("{k} = {v:.4e}")
                        }
                    })
                    .collect::<Vec<_>>()
                    .join(", ");
                let _ = writeln!(
                    s,
                    "| {law} | {params} | {:.4} | {} | {} |",
                    f.rms,
                    pct(f.worst_e),
                    pct(f.worst_delta)
                );
            }
            Err(e) => {
                let _ = writeln!(s, "| {law} | fit failed: {} | | | |", e.replace('|', "/"));
            }
        }
    }
    let _ = writeln!(s);
}

fn fit_section(s: &mut String, fits: &[MetalFit]) {
    let _ = writeln!(
        s,
        "## Fits (FE points {}-{} m/s)\n",
        FIT_RANGE.0, FIT_RANGE.1
    );
    let _ = writeln!(
        s,
        "`analytic::law_fit` per metal at the largest diameter: least squares on the relative \
         errors of e and δ_max (as `twoball laws fit`), and on e alone. Worst errors are signed, \
         per cent. Target: the best law fitted to e alone has its largest |error in e| within \
         {:.0} %.\n",
        100.0 * TARGET_E_ERROR
    );
    for m in fits {
        let _ = writeln!(
            s,
            "### {}, D = {} mm ({} FE points)\n",
            m.metal,
            1e3 * m.diameter,
            m.observations.len()
        );
        if m.observations.is_empty() {
            let _ = writeln!(s, "No FE points in range.\n");
            continue;
        }
        fit_table(s, "fitted to e and δ_max", &m.fits);
        fit_table(s, "fitted to e alone", &m.e_fits);
        if let Some(b) = m.best() {
            let verdict = if b.worst_e.abs() <= TARGET_E_ERROR {
                format!("within {:.0} %", 100.0 * TARGET_E_ERROR)
            } else {
                format!("not within {:.0} %", 100.0 * TARGET_E_ERROR)
            };
            let _ = writeln!(
                s,
                "Best law fitted to e alone: **{}**, largest |error in e| {:.1} % ({verdict}; its δ_max worst {} %).",
                b.law,
                100.0 * b.worst_e.abs(),
                pct(b.worst_delta)
            );
        }
        if let Some(p) = m.power_law {
            let _ = writeln!(
                s,
                "Which form would: a power law e = {:.4} (v / 1 m/s)^{:.4} through the FE points misses \
                 them by at most {} %; Johnson's elastic-perfectly-plastic exponent at high v/v_y is \
                 −0.25, and the FE's own log-log slope runs from {} (two slowest points) to {} (two \
                 fastest).",
                p.prefactor,
                p.exponent,
                pct(p.worst_e),
                m.bottom_slope.map_or("n/a".into(), |t| format!("{t:.4}")),
                m.top_slope.map_or("n/a".into(), |t| format!("{t:.4}")),
            );
        }
        if let Some(q) = m.log_quadratic {
            let _ = writeln!(
                s,
                "A restitution whose log-log slope steepens linearly in ln v, ln e = {:.4} {:+.4} ln v \
                 {:+.5} (ln v)² (slope {:.3} at {} m/s, {:.3} at {} m/s), misses them by at most {} %.",
                q.coefficients[0],
                q.coefficients[1],
                q.coefficients[2],
                q.slope(FIT_RANGE.0),
                FIT_RANGE.0,
                q.slope(FIT_RANGE.1),
                FIT_RANGE.1,
                pct(q.worst_e)
            );
        }
        let _ = writeln!(s);
    }
}

fn failed_points(s: &mut String, r: &BenchResults) {
    let failed: Vec<String> = r
        .head_on
        .iter()
        .filter_map(|h| match &h.fe {
            Some(super::cache::Stored::Failed(m)) => Some(format!(
                "- {} D = {} mm v = {:.4} m/s: {m}",
                h.point.metal,
                1e3 * h.point.diameter,
                h.point.speed
            )),
            _ => None,
        })
        .collect();
    let missing = r.head_on.iter().filter(|h| h.fe.is_none()).count();
    if failed.is_empty() && missing == 0 {
        return;
    }
    let _ = writeln!(s, "## FE points without an answer\n");
    for f in failed {
        let _ = writeln!(s, "{f}");
    }
    if missing > 0 {
        let _ = writeln!(
            s,
            "- {missing} head-on points not in the cache (`--laws-only`)"
        );
    }
    let _ = writeln!(s);
}

/// The report's text.
pub fn report_text(
    r: &BenchResults,
    rank: &[MetalRanking],
    figures: &[Figure],
    command: &str,
) -> String {
    let mut s = String::new();
    header(&mut s, command, r);
    matrix_section(&mut s, r);
    bars_section(&mut s, r);
    ranking_section(&mut s, rank);
    calibrated_section(&mut s, &r.calibrated);
    validity_section(&mut s, r);
    failures_section(&mut s, r);
    diameter_section(&mut s, r);
    super::oblique_report::oblique_section(&mut s, r);
    super::loop_report::loop_section(&mut s, r);
    fit_section(&mut s, &r.fits);
    let _ = writeln!(s, "## Figures\n");
    for f in figures {
        let _ = writeln!(s, "- [{}]({}): {}", f.file, f.file, f.caption);
    }
    let _ = writeln!(s);
    fe_section(&mut s, r);
    failed_points(&mut s, r);
    errors_section(&mut s, r);
    s
}

/// Writes `out/REPORT.md` (atomically) and returns its path.
///
/// Errors: the folder or file cannot be written.
pub fn write_report(
    out: &Path,
    r: &BenchResults,
    rank: &[MetalRanking],
    figures: &[Figure],
    command: &str,
) -> Result<PathBuf> {
    std::fs::create_dir_all(out).map_err(|e| Error::io(out, e))?;
    let path = out.join("REPORT.md");
    write_atomic(&path, report_text(r, rank, figures, command).as_bytes())?;
    Ok(path)
}
