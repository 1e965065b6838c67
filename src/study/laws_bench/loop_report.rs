//! The report's quasi-static part: per metal and loop speed the FE loop's numbers with their
//! bars beside the dynamic FE e of the same impact, and each normal law's RMS force error on
//! the loading and the unloading branch of the finest loop.

use super::bars::bar;
use super::cache::Stored;
use super::matrix::yield_speed;
use super::{BenchResults, LoopResult};
use std::fmt::Write as _;

/// The loops of `metal`, speeds ascending.
fn of_metal<'a>(r: &'a BenchResults, metal: &str) -> Vec<&'a LoopResult> {
    r.loops.iter().filter(|l| l.point.metal == metal).collect()
}

/// The dynamic FE e (value, bar) of the head-on point the loop `l` stands for.
fn dynamic_e(r: &BenchResults, l: &LoopResult) -> Option<(f64, f64)> {
    r.head_on
        .iter()
        .find(|h| h.point == l.point)
        .and_then(|h| h.fe_done())
        .map(|f| (f.e.finest, f.e.error))
}

/// The FE table: one row a loop.
fn fe_table(s: &mut String, r: &BenchResults) {
    let _ = writeln!(
        s,
        "| metal | v (m/s) | v/v_y | δ_max of the pair (µm) | F at δ_max (N) | residual δ of the pair (µm) | e quasi-static | e dynamic | dynamic/static − 1 |\n\
         |---|---|---|---|---|---|---|---|---|"
    );
    for l in &r.loops {
        let p = &l.point;
        let vy = yield_speed(&p.material, p.diameter).unwrap_or(f64::NAN);
        let f = match &l.fe {
            Some(Stored::Done(f)) => f,
            missing => {
                let why = match missing {
                    Some(Stored::Failed(m)) => format!("FE failed: {m}"),
                    _ => "not in the cache".to_string(),
                };
                let _ = writeln!(
                    s,
                    "| {} | {:.4} | {:.3} | {why} | | | | | |",
                    p.metal,
                    p.speed,
                    p.speed / vy
                );
                continue;
            }
        };
        let (dyn_cell, gap) = match dynamic_e(r, l) {
            Some((e, err)) => (
                bar(e, err, 1.0, 5),
                format!("{:+.2} %", 100.0 * (e / f.e.finest - 1.0)),
            ),
            None => ("n/a".into(), "n/a".into()),
        };
        let _ = writeln!(
            s,
            "| {} | {:.4} | {:.3} | {} | {} | {} | {} | {dyn_cell} | {gap} |",
            p.metal,
            p.speed,
            p.speed / vy,
            bar(2.0 * f.delta_max.finest, 2.0 * f.delta_max.error, 1e6, 3),
            bar(f.force_at_max.finest, f.force_at_max.error, 1.0, 2),
            bar(
                2.0 * f.residual_approach.finest,
                2.0 * f.residual_approach.error,
                1e6,
                3
            ),
            bar(f.e.finest, f.e.error, 1.0, 5),
        );
    }
    let _ = writeln!(s);
}

/// One metal's law table: a row a law, a column a loop speed, "loading / unloading" RMS.
fn law_table(s: &mut String, r: &BenchResults, metal: &str) {
    let loops = of_metal(r, metal);
    if loops.iter().all(|l| l.laws.is_empty()) {
        return;
    }
    let _ = writeln!(s, "### {metal}\n");
    let mut head = String::from("| law |");
    let mut rule = String::from("|---|");
    for l in &loops {
        let _ = write!(head, " v = {:.4} m/s: RMS (%) |", l.point.speed);
        rule.push_str("---|");
    }
    let _ = writeln!(s, "{head}\n{rule}");
    for name in &r.normal_laws {
        let mut row = format!("| {name} |");
        for l in &loops {
            match l.laws.iter().find(|x| &x.law == name) {
                Some(x) => {
                    let _ = write!(
                        row,
                        " {:.1} / {:.1} |",
                        100.0 * x.loading_rms,
                        100.0 * x.unloading_rms
                    );
                }
                None => row.push_str(" n/a |"),
            }
        }
        let _ = writeln!(s, "{row}");
    }
    let _ = writeln!(s);
}

/// The section, when the matrix has loops.
pub fn loop_section(s: &mut String, r: &BenchResults) {
    if r.loops.is_empty() {
        return;
    }
    let _ = writeln!(s, "## Quasi-static loops\n");
    let _ = writeln!(
        s,
        "One ball of each pair at the loop speeds (the matrix speeds nearest 0.1, 1 and 10 m/s), \
         largest diameter: the whole ball under the body force that balances the contact, \
         loaded on a rigid frictionless plane (the pair's symmetry plane) until it has taken \
         the kinetic energy it brings to that plane, then unloaded to release, by the implicit \
         static solver (`twoball static --support free` on the pair's scene: banded ladder \
         levels 0 and 1, each value with its two-level bar; Johnson-Cook at its reference rate). \
         The pair's approach is twice the ball's. \"e dynamic\" is the head-on FE point of the \
         same impact; the static loop has no waves, so the two differ by the ball's vibration \
         after separation and by the impact's extra plastic work (README, \"Quasi-static \
         loops\").\n"
    );
    fe_table(s, r);
    let _ = writeln!(
        s,
        "Each normal law on the finest loop: its quasi-static curve (approach rate 0; a \
         damped law shows its elastic backbone) at the loop's approaches, loading up to the \
         FE turn and unloading from the law's own turn there; RMS of F_law − F_FE over the \
         loading and over the unloading points, in per cent of the FE peak force \
         (loading / unloading).\n"
    );
    for metal in &r.matrix.metals {
        law_table(s, r, metal);
    }
}
