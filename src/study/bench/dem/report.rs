//! The suite's report (Markdown) and its figures as CSV.

use super::DemRow;
use crate::analytic::laws::Registry;
use crate::study::records::number::sci;
use std::fmt::Write as _;

/// "1 case", "n cases".
pub fn count(n: usize) -> String {
    if n == 1 {
        "1 case".into()
    } else {
        format!("{n} cases")
    }
}

/// A value with its bar to `digits` significant digits, `-` when not a number.
fn with_bar(v: f64, b: f64, digits: usize) -> String {
    if b.is_finite() && v.is_finite() {
        format!("{} ± {}", sci(v, digits), sci(b, 1))
    } else {
        plain(v, digits)
    }
}

/// `v` to `digits` significant digits, `-` when not a number.
fn plain(v: f64, digits: usize) -> String {
    if v.is_finite() {
        sci(v, digits)
    } else {
        "-".into()
    }
}

/// The relative difference (a − b)/b in percent, `-` when not a number.
fn percent(a: f64, b: f64) -> String {
    let d = 100.0 * (a - b) / b;
    if d.is_finite() {
        format!("{d:+.2} %")
    } else {
        "-".into()
    }
}

/// The report in Markdown: the normal tests against Hertz and the DEM normal laws, test 3's
/// damping, the oblique and spinning tests against the theory and the DEM tangential laws,
/// and the total wall time `total` (s).
pub fn report(rows: &[DemRow], total: f64) -> String {
    let mut s = String::from("# Chung & Ooi's DEM benchmark tests by converged FE\n\n");
    let _ = writeln!(
        s,
        "`twoball bench dem`: {} in {total:.0} s. Scenes and their sources: \
         verification/dem-benchmarks/README.md.\n",
        count(rows.len())
    );
    let normal: Vec<_> = rows.iter().filter(|r| !r.oblique).collect();
    if !normal.is_empty() {
        s.push_str(&normal_table(&normal));
        s.push_str(&normal_law_table(&normal));
        s.push_str(&damping_tables(&normal));
    }
    let oblique: Vec<_> = rows.iter().filter(|r| r.oblique).collect();
    if !oblique.is_empty() {
        s.push_str(&oblique_table(&oblique));
        s.push_str(&law_table(&oblique));
    }
    s
}

/// The normal tests' FE against Hertz.
fn normal_table(rows: &[&DemRow]) -> String {
    let mut s = String::from("## Normal tests against Hertz\n\n");
    s.push_str(
        "| case | e | δ_max FE (m) | δ_max Hertz (m) | diff | t_c FE (s) | t_c Hertz (s) | diff |\n",
    );
    s.push_str("|---|---|---|---|---|---|---|---|\n");
    for r in rows {
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {} | {} | {} | {} |",
            r.name,
            with_bar(r.e.0, r.e.1, 4),
            with_bar(r.delta_max.0, r.delta_max.1, 4),
            plain(r.delta_max.2, 4),
            percent(r.delta_max.0, r.delta_max.2),
            with_bar(r.contact_duration.0, r.contact_duration.1, 4),
            plain(r.contact_duration.2, 4),
            percent(r.contact_duration.0, r.contact_duration.2),
        );
    }
    s.push('\n');
    s
}

/// Every DEM normal law at its elastic setting against the converged FE: e, and δ_max and
/// t_c as differences from the FE's.
fn normal_law_table(rows: &[&DemRow]) -> String {
    let head = "## The DEM normal laws on the normal tests\n\n\
         Each built-in normal law (`twoball laws list`) at its elastic setting (damped laws \
         at e = 1, Kuwabara-Kono at A = 0; other parameters the pair's defaults): e, then \
         δ_max and t_c against the converged FE's.\n\n| case |";
    law_table_of(rows, head, 1, |r| {
        let laws = r.normal_laws.iter().map(|l| {
            let cell = format!(
                "{} / {} / {}",
                plain(l.e, 3),
                percent(l.delta_max, r.delta_max.0),
                percent(l.contact_duration, r.contact_duration.0)
            );
            (l.law.as_str(), cell)
        });
        (format!("| {} |", r.name), laws.collect())
    })
}

/// Test 3: each damped law's e against the e it was set to, one table per case.
fn damping_tables(rows: &[&DemRow]) -> String {
    let mut s = String::new();
    for r in rows.iter().filter(|r| !r.damping.is_empty()) {
        let mut sets: Vec<f64> = r.damping.iter().map(|d| d.1).collect();
        sets.dedup();
        let mut laws: Vec<&str> = Vec::new();
        for (l, _, _) in &r.damping {
            if !laws.contains(&l.as_str()) {
                laws.push(l);
            }
        }
        let _ = writeln!(
            s,
            "## Test 3, {}: the e each damped law gives against the e it was set to\n\n\
             The elastic continuum's answer is e = {} (above).\n",
            r.name,
            with_bar(r.e.0, r.e.1, 4)
        );
        s.push_str("| law |");
        for e in &sets {
            let _ = write!(s, " e set {e} |");
        }
        s.push_str("\n|---|");
        s.push_str(&"---|".repeat(sets.len()));
        s.push('\n');
        for l in laws {
            let _ = write!(s, "| {l} |");
            for e in &sets {
                let out = r
                    .damping
                    .iter()
                    .find(|d| d.0 == l && d.1 == *e)
                    .map_or(f64::NAN, |d| d.2);
                let _ = write!(s, " {} |", plain(out, 4));
            }
            s.push('\n');
        }
        s.push('\n');
    }
    s
}

/// The oblique and spinning tests' FE against Maw, Barber & Fawcett.
fn oblique_table(rows: &[&DemRow]) -> String {
    let mut s = String::from("## Oblique and spinning tests against Maw, Barber & Fawcett\n\n");
    s.push_str(
        "slip/(μ v_n) is the contact points' slip at touch over μ times the normal approach \
         speed; levels, the pole ladder's meshes and whether its tolerance on e and e_t was \
         met.\n\n",
    );
    s.push_str(
        "| case | slip/(μ v_n) | e_t FE | e_t theory | ω₁ after FE (rad/s) | theory | \
         rebound FE (rad) | theory | levels |\n",
    );
    s.push_str("|---|---|---|---|---|---|---|---|---|\n");
    for r in rows {
        let (t, w, a) = (r.tangential_restitution, r.spin_after, r.rebound_angle);
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} |",
            r.name,
            plain(r.slip_ratio, 3),
            with_bar(t.0, t.1, 4),
            plain(t.2, 4),
            with_bar(w.0, w.1, 4),
            plain(w.2, 4),
            with_bar(a.0, a.1, 4),
            plain(a.2, 4),
            levels(r),
        );
    }
    s.push('\n');
    s
}

/// The ladder's mesh count and whether it met its tolerance, e.g. "3, met".
fn levels(r: &DemRow) -> String {
    match r.tolerance_met {
        Some(true) => format!("{}, met", r.levels),
        Some(false) => format!("{}, NOT met", r.levels),
        None => r.levels.to_string(),
    }
}

/// The oblique cases' tangential laws (Hertz along the normal): e_t and ω₁ after (rad/s)
/// of each, beside the FE's.
fn law_table(rows: &[&DemRow]) -> String {
    let head = "## The DEM tangential laws on the same impacts\n\n\
         Each built-in tangential law with Hertz along the normal (`twoball laws run`): the \
         contact point's e_t and ω₁ after (rad/s), beside the FE's.\n\n| case | FE |";
    law_table_of(rows, head, 2, |r| {
        let laws = r.laws.iter().map(|l| {
            let cell = format!("{} / {}", plain(l.restitution, 3), plain(l.spin1_after, 3));
            (l.law.as_str(), cell)
        });
        let fe = format!(
            "| {} | {} / {} |",
            r.name,
            plain(r.tangential_restitution.0, 3),
            plain(r.spin_after.0, 3)
        );
        (fe, laws.collect())
    })
}

/// A law table: heading `head` ending in its `lead` leading header cells, a column per law
/// of the first row that has laws (no table when none has), then per row its leading cells
/// and a cell per law, both from `cells` (each law as its name and its cell).
fn law_table_of<'r>(
    rows: &[&'r DemRow],
    head: &str,
    lead: usize,
    cells: impl Fn(&'r DemRow) -> (String, Vec<(&'r str, String)>),
) -> String {
    let table: Vec<_> = rows.iter().map(|r| cells(r)).collect();
    let Some((_, first)) = table.iter().find(|(_, laws)| !laws.is_empty()) else {
        return String::new();
    };
    let mut s = law_columns(head, lead, first.iter().map(|l| l.0));
    for (leading, laws) in &table {
        s.push_str(leading);
        for (_, cell) in laws {
            let _ = write!(s, " {cell} |");
        }
        s.push('\n');
    }
    s.push('\n');
    s
}

/// A law table's heading `head` (ending in its `lead` leading header cells, e.g. "| case |"),
/// one column per law in `names`, and the separator row.
fn law_columns<'a>(head: &str, lead: usize, names: impl Iterator<Item = &'a str>) -> String {
    let mut s = String::from(head);
    let mut n = 0;
    for name in names {
        let _ = write!(s, " {name} |");
        n += 1;
    }
    s.push('\n');
    s.push_str(&"|---".repeat(lead));
    s.push('|');
    s.push_str(&"---|".repeat(n));
    s.push('\n');
    s
}

/// The rows as CSV (SI units in the header; empty fields where a figure does not apply).
pub fn csv(rows: &[DemRow]) -> String {
    let mut s = String::from(
        "case,angle_deg,slip_ratio,e,e_bar,delta_max_m,delta_max_bar_m,delta_max_hertz_m,\
         contact_duration_s,contact_duration_bar_s,contact_duration_hertz_s,\
         tangential_restitution,tangential_restitution_bar,tangential_restitution_theory,\
         spin1_after_rad_per_s,spin1_after_bar_rad_per_s,spin1_after_theory_rad_per_s,\
         rebound_angle_rad,rebound_angle_bar_rad,rebound_angle_theory_rad,ladder_levels,\
         tolerance_met,wall_time_s",
    );
    let registry = Registry::builtin();
    let normal: Vec<&str> = registry.normal.iter().map(|n| n.name).collect();
    let tangential: Vec<&str> = registry.tangential.iter().map(|t| t.name).collect();
    for n in &normal {
        let _ = write!(s, ",{n}_e,{n}_delta_max_m,{n}_contact_duration_s");
    }
    for n in &tangential {
        let _ = write!(s, ",{n}_tangential_restitution,{n}_spin1_after_rad_per_s");
    }
    s.push('\n');
    let f = |v: f64| {
        if v.is_finite() {
            format!("{:?}", v + 0.0)
        } else {
            String::new()
        }
    };
    for r in rows {
        let cells = [
            r.angle,
            r.slip_ratio,
            r.e.0,
            r.e.1,
            r.delta_max.0,
            r.delta_max.1,
            r.delta_max.2,
            r.contact_duration.0,
            r.contact_duration.1,
            r.contact_duration.2,
            r.tangential_restitution.0,
            r.tangential_restitution.1,
            r.tangential_restitution.2,
            r.spin_after.0,
            r.spin_after.1,
            r.spin_after.2,
            r.rebound_angle.0,
            r.rebound_angle.1,
            r.rebound_angle.2,
            r.levels as f64,
            r.tolerance_met.map_or(f64::NAN, |m| f64::from(u8::from(m))),
            r.wall_time,
        ];
        let mut line: Vec<String> = cells.iter().map(|&v| f(v)).collect();
        for n in &normal {
            let l = r.normal_laws.iter().find(|l| l.law == *n);
            line.push(f(l.map_or(f64::NAN, |l| l.e)));
            line.push(f(l.map_or(f64::NAN, |l| l.delta_max)));
            line.push(f(l.map_or(f64::NAN, |l| l.contact_duration)));
        }
        for n in &tangential {
            let l = r.laws.iter().find(|l| l.law == *n);
            line.push(f(l.map_or(f64::NAN, |l| l.restitution)));
            line.push(f(l.map_or(f64::NAN, |l| l.spin1_after)));
        }
        let _ = writeln!(s, "{},{}", r.name, line.join(","));
    }
    s
}
