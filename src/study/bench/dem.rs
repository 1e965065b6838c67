//! Chung & Ooi's DEM benchmark tests by converged FE (`twoball bench dem`): the scenes of
//! `verification/dem-benchmarks/`, run as that folder's README runs them, into one report.
//!
//! The normal tests (1: two identical elastic spheres, 2: a sphere on a rigid plane) run on
//! the section to `--tolerance 0.5%` and are set beside Hertz's elastic impact; the oblique
//! test 4 (a sphere on a rigid plane at 3.9 m/s and eleven angles of incidence) and the same
//! impact between two identical balls run on the 3D half model with the two-level bar and are
//! set beside Maw, Barber & Fawcett's elastic theory.

use crate::analytic::laws::Registry;
use crate::atomic::{ensure_dir, write_atomic};
use crate::error::{Error, Result};
use crate::scene::{approach, Approach};
use crate::scene::{Override, Scene};
use crate::study::convergence::ladder::LadderPlan;
use crate::study::convergence::scene_estimate::run_scene_with_estimate;
use crate::study::records::estimate::Estimate;
use crate::study::records::number::sci;
use crate::study::run::law_compare::{tangential_laws, TangentialLawOutcome};
use crate::study::run::scene::RunReport;
use crate::study::run::simulation::RunOptions;
use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

/// The benchmark scenes, as committed under `verification/dem-benchmarks/`.
const SCENES: [(&str, &str); 6] = [
    (
        "test1-glass",
        include_str!("../../../verification/dem-benchmarks/test1-glass.toml"),
    ),
    (
        "test1-limestone",
        include_str!("../../../verification/dem-benchmarks/test1-limestone.toml"),
    ),
    (
        "test2-aluminium",
        include_str!("../../../verification/dem-benchmarks/test2-aluminium.toml"),
    ),
    (
        "test2-magnesium",
        include_str!("../../../verification/dem-benchmarks/test2-magnesium.toml"),
    ),
    (
        "test4-alumina",
        include_str!("../../../verification/dem-benchmarks/test4-alumina.toml"),
    ),
    (
        "oblique-pair-alumina",
        include_str!("../../../verification/dem-benchmarks/oblique-pair-alumina.toml"),
    ),
];

/// Test 4's angles of incidence, degrees.
pub const TEST4_ANGLES: [f64; 11] = [
    5.0, 10.0, 15.0, 20.0, 25.0, 30.0, 40.0, 50.0, 60.0, 70.0, 80.0,
];

/// The pair's angles of incidence, degrees.
pub const PAIR_ANGLES: [f64; 4] = [5.0, 10.0, 20.0, 30.0];

/// Resultant relative speed of test 4 and of the pair, m/s.
const OBLIQUE_SPEED: f64 = 3.9;

/// Relative tolerance on e of the normal tests' converged runs, -.
const NORMAL_TOLERANCE: f64 = 0.005;

/// One run of the suite: its name, the scene, how it is refined and its angle of incidence
/// (degrees; `None` head-on).
#[derive(Debug, Clone)]
pub struct DemCase {
    /// Scene name and, for an oblique case, `@` and the angle in degrees.
    pub name: String,
    /// The scene as run.
    pub scene: Scene,
    /// The mesh ladder.
    pub plan: LadderPlan,
    /// Angle of incidence, degrees (`None` for a normal test).
    pub angle: Option<f64>,
}

/// The scene `name` of the suite with `sets` applied.
fn scene(name: &str, sets: &[String]) -> Result<Scene> {
    let text = SCENES
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(_, t)| *t)
        .ok_or_else(|| Error::Parse(format!("no benchmark scene {name}")))?;
    let sets = sets
        .iter()
        .map(|s| Override::parse(s))
        .collect::<Result<Vec<_>>>()?;
    Scene::from_toml(text, Path::new("."), &sets)
}

/// The velocity `[v cos θ, v sin θ, 0]` (m/s) of speed `v` (m/s) at `deg` degrees from the
/// normal, as a `--set` value.
fn velocity(v: f64, deg: f64) -> String {
    let t = deg.to_radians();
    format!("[{:?}, {:?}, 0]", v * t.cos(), v * t.sin())
}

/// Every case of the suite whose name starts with one of `only` (all when `only` is empty).
/// Fails only if a committed scene no longer reads (a defect of the build).
pub fn cases(only: &[String]) -> Result<Vec<DemCase>> {
    let mut out = Vec::new();
    let tolerance = LadderPlan::Tolerance {
        tolerance: NORMAL_TOLERANCE,
        max_refinements: 2,
    };
    for name in [
        "test1-glass",
        "test1-limestone",
        "test2-aluminium",
        "test2-magnesium",
    ] {
        out.push(DemCase {
            name: name.into(),
            scene: scene(name, &[])?,
            plan: tolerance,
            angle: None,
        });
    }
    for deg in TEST4_ANGLES {
        let v = velocity(OBLIQUE_SPEED, deg);
        out.push(DemCase {
            name: format!("test4-alumina@{deg}"),
            scene: scene("test4-alumina", &[format!("ball1.velocity={v}")])?,
            plan: LadderPlan::TwoLevels,
            angle: Some(deg),
        });
    }
    for deg in PAIR_ANGLES {
        let (v, w) = (
            velocity(OBLIQUE_SPEED / 2.0, deg),
            velocity(-OBLIQUE_SPEED / 2.0, deg),
        );
        out.push(DemCase {
            name: format!("oblique-pair-alumina@{deg}"),
            scene: scene(
                "oblique-pair-alumina",
                &[format!("ball1.velocity={v}"), format!("ball2.velocity={w}")],
            )?,
            plan: LadderPlan::TwoLevels,
            angle: Some(deg),
        });
    }
    out.retain(|c| only.is_empty() || only.iter().any(|o| c.name.starts_with(o.as_str())));
    Ok(out)
}

/// One case's figures: FE with its bar beside the reference (Hertz head-on, Maw, Barber &
/// Fawcett oblique). SI units; NaN where a figure does not apply.
#[derive(Debug, Clone, PartialEq)]
pub struct DemRow {
    /// The case's name.
    pub name: String,
    /// Angle of incidence, degrees (NaN head-on).
    pub angle: f64,
    /// Coefficient of restitution and its bar, -.
    pub e: (f64, f64),
    /// δ_max with its bar and Hertz's, m.
    pub delta_max: (f64, f64, f64),
    /// Contact duration with its bar and Hertz's, s.
    pub contact_duration: (f64, f64, f64),
    /// Tangential restitution of the contact point with its bar and the theory's, -.
    pub tangential_restitution: (f64, f64, f64),
    /// Ball 1's spin after with its bar and the theory's, rad/s.
    pub spin_after: (f64, f64, f64),
    /// Rebound angle with its bar and the theory's, rad.
    pub rebound_angle: (f64, f64, f64),
    /// Every tangential law with Hertz along the normal (oblique cases; empty head-on).
    pub laws: Vec<TangentialLawOutcome>,
    /// Wall time of the case, s.
    pub wall_time: f64,
}

/// The bar of an estimate, NaN without one.
fn bar(e: Option<&Estimate>) -> f64 {
    e.map_or(f64::NAN, |e| e.error)
}

/// The row of `case` from its report `r`, its tangential laws `laws` and wall time `wall`
/// (s).
pub fn row(case: &DemCase, r: &RunReport, laws: Vec<TangentialLawOutcome>, wall: f64) -> DemRow {
    let est = r.error_estimate.as_ref();
    let an = r.analytic.as_ref();
    let tan = r.tangential.as_ref();
    let theory = tan.and_then(|t| t.theory.as_ref());
    let t_est = est.and_then(|e| e.tangential.as_ref());
    let nan = f64::NAN;
    DemRow {
        name: case.name.clone(),
        angle: case.angle.unwrap_or(nan),
        e: (r.e.unwrap_or(nan), bar(est.map(|e| &e.e))),
        delta_max: (
            r.delta_max,
            bar(est.map(|e| &e.delta_max)),
            an.map_or(nan, |a| a.delta_max),
        ),
        contact_duration: (
            r.contact_duration,
            bar(est.map(|e| &e.contact_duration)),
            an.map_or(nan, |a| a.contact_duration),
        ),
        tangential_restitution: (
            tan.and_then(|t| t.fe.restitution).unwrap_or(nan),
            bar(t_est.and_then(|t| t.restitution.as_ref())),
            theory.and_then(|t| t.restitution).unwrap_or(nan),
        ),
        spin_after: (
            tan.map_or(nan, |t| t.fe.spin1_after),
            bar(t_est.map(|t| &t.spin1_after)),
            theory.map_or(nan, |t| t.spin1_after),
        ),
        rebound_angle: (
            tan.map_or(nan, |t| t.fe.rebound_angle),
            bar(t_est.map(|t| &t.rebound_angle)),
            theory.map_or(nan, |t| t.rebound_angle),
        ),
        laws,
        wall_time: wall,
    }
}

/// Runs every case, one line on stderr each; fails with the first case that fails, named.
pub fn run(cases: &[DemCase]) -> Result<Vec<DemRow>> {
    let opts = RunOptions {
        history_rows: 200,
        ..RunOptions::default()
    };
    let mut rows = Vec::with_capacity(cases.len());
    for (k, c) in cases.iter().enumerate() {
        let start = Instant::now();
        // An interruption passes as it is; any other failure names its case.
        let r = run_scene_with_estimate(&c.scene, &opts, c.plan).map_err(|e| match e {
            Error::Interrupted(_) => e,
            e => Error::Numerical(format!("bench dem, case {}: {e}", c.name)),
        })?;
        let laws = match (c.angle, approach(&c.scene)?) {
            (Some(_), Approach::Impact(touch)) => tangential_laws(&c.scene, &touch)?,
            _ => Vec::new(),
        };
        let wall = start.elapsed().as_secs_f64();
        eprintln!(
            "bench dem: {}/{} {} in {wall:.1} s",
            k + 1,
            cases.len(),
            c.name
        );
        rows.push(row(c, &r, laws, wall));
    }
    Ok(rows)
}

/// "1 case", "n cases".
fn count(n: usize) -> String {
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

/// The report in Markdown: the normal tests against Hertz, the oblique ones against the
/// theory, and the total wall time `total` (s).
pub fn report(rows: &[DemRow], total: f64) -> String {
    let mut s = String::from("# Chung & Ooi's DEM benchmark tests by converged FE\n\n");
    let _ = writeln!(
        s,
        "`twoball bench dem`: {} in {total:.0} s. Scenes and their sources: \
         verification/dem-benchmarks/README.md.\n",
        count(rows.len())
    );
    let normal: Vec<_> = rows.iter().filter(|r| r.angle.is_nan()).collect();
    if !normal.is_empty() {
        s.push_str("## Normal tests against Hertz\n\n");
        s.push_str("| case | e | δ_max FE (m) | δ_max Hertz (m) | diff | t_c FE (s) | t_c Hertz (s) | diff |\n");
        s.push_str("|---|---|---|---|---|---|---|---|\n");
        for r in normal {
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
    }
    let oblique: Vec<_> = rows.iter().filter(|r| !r.angle.is_nan()).collect();
    if !oblique.is_empty() {
        s.push_str("## Oblique tests against Maw, Barber & Fawcett\n\n");
        s.push_str("| case | e_t FE | e_t theory | ω₁ after FE (rad/s) | theory | rebound FE (rad) | theory |\n");
        s.push_str("|---|---|---|---|---|---|---|\n");
        for r in &oblique {
            let (t, w, a) = (r.tangential_restitution, r.spin_after, r.rebound_angle);
            let _ = writeln!(
                s,
                "| {} | {} | {} | {} | {} | {} | {} |",
                r.name,
                with_bar(t.0, t.1, 4),
                plain(t.2, 4),
                with_bar(w.0, w.1, 4),
                plain(w.2, 4),
                with_bar(a.0, a.1, 4),
                plain(a.2, 4),
            );
        }
        s.push('\n');
        s.push_str(&law_table(&oblique));
    }
    s
}

/// The oblique cases' tangential laws (Hertz along the normal): e_t and ω₁ after (rad/s)
/// of each, beside the FE's.
fn law_table(rows: &[&DemRow]) -> String {
    let Some(first) = rows.iter().find(|r| !r.laws.is_empty()) else {
        return String::new();
    };
    let mut s = String::from(
        "## The DEM tangential laws on the same impacts\n\n\
         Each built-in tangential law with Hertz along the normal (`twoball laws run`): the \
         contact point's e_t and ω₁ after (rad/s), beside the FE's.\n\n| case | FE |",
    );
    for l in &first.laws {
        let _ = write!(s, " {} |", l.law);
    }
    s.push_str("\n|---|---|");
    s.push_str(&"---|".repeat(first.laws.len()));
    s.push('\n');
    for r in rows {
        let _ = write!(
            s,
            "| {} | {} / {} |",
            r.name,
            plain(r.tangential_restitution.0, 3),
            plain(r.spin_after.0, 3)
        );
        for l in &r.laws {
            let _ = write!(
                s,
                " {} / {} |",
                plain(l.restitution, 3),
                plain(l.spin1_after, 3)
            );
        }
        s.push('\n');
    }
    s.push('\n');
    s
}

/// The rows as CSV (SI units in the header; empty fields where a figure does not apply).
pub fn csv(rows: &[DemRow]) -> String {
    let mut s = String::from(
        "case,angle_deg,e,e_bar,delta_max_m,delta_max_bar_m,delta_max_hertz_m,\
         contact_duration_s,contact_duration_bar_s,contact_duration_hertz_s,\
         tangential_restitution,tangential_restitution_bar,tangential_restitution_theory,\
         spin1_after_rad_per_s,spin1_after_bar_rad_per_s,spin1_after_theory_rad_per_s,\
         rebound_angle_rad,rebound_angle_bar_rad,rebound_angle_theory_rad,wall_time_s",
    );
    let names: Vec<&str> = Registry::builtin()
        .tangential
        .iter()
        .map(|t| t.name)
        .collect();
    for n in &names {
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
            r.wall_time,
        ];
        let mut line: Vec<String> = cells.iter().map(|&v| f(v)).collect();
        for n in &names {
            let l = r.laws.iter().find(|l| l.law == *n);
            line.push(f(l.map_or(f64::NAN, |l| l.restitution)));
            line.push(f(l.map_or(f64::NAN, |l| l.spin1_after)));
        }
        let _ = writeln!(s, "{},{}", r.name, line.join(","));
    }
    s
}

/// Runs the cases named by `only` (all when empty) and writes `report.md` and `cases.csv`
/// into `out` (each whole: written aside and renamed); prints the report and the wall time. Fails on a bad
/// `only` (no case matches), a failed case, or an unwritable folder.
pub fn bench(only: &[String], out: Option<&Path>) -> Result<Vec<DemRow>> {
    let cases = cases(only)?;
    if cases.is_empty() {
        return Err(Error::invalid(
            "--only",
            only.join(","),
            "a prefix of a case name: test1-glass, test1-limestone, test2-aluminium, \
             test2-magnesium, test4-alumina@ANGLE, oblique-pair-alumina@ANGLE",
        ));
    }
    let start = Instant::now();
    let rows = run(&cases)?;
    let total = start.elapsed().as_secs_f64();
    let text = report(&rows, total);
    if let Some(dir) = out {
        ensure_dir(dir)?;
        write_atomic(dir.join("cases.csv"), csv(&rows).as_bytes())?;
        write_atomic(dir.join("report.md"), text.as_bytes())?;
    }
    print!("{text}");
    println!("bench dem: {} in {total:.1} s", count(rows.len()));
    Ok(rows)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_suite_reads_every_committed_scene_at_its_speeds() {
        let all = cases(&[]).unwrap();
        assert_eq!(all.len(), 4 + TEST4_ANGLES.len() + PAIR_ANGLES.len());
        // Test 4 at 30 degrees: 3.9 m/s resultant, the normal component along +x.
        let c = all.iter().find(|c| c.name == "test4-alumina@30").unwrap();
        let v = c.scene.ball1.velocity;
        assert!((v[0].hypot(v[1]) - 3.9).abs() < 1e-12);
        assert!((v[1].atan2(v[0]).to_degrees() - 30.0).abs() < 1e-9);
        // The pair: equal and opposite velocities, relative speed 3.9 m/s.
        let p = all
            .iter()
            .find(|c| c.name == "oblique-pair-alumina@10")
            .unwrap();
        let (a, b) = (p.scene.ball1.velocity, p.scene.ball2.velocity);
        assert!((a[0] + b[0]).abs() < 1e-12 && (a[1] + b[1]).abs() < 1e-12);
        assert!(((a[0] - b[0]).hypot(a[1] - b[1]) - 3.9).abs() < 1e-12);
        assert_eq!(cases(&["test2".into()]).unwrap().len(), 2);
    }

    #[test]
    fn in_gross_sliding_the_coulomb_law_is_the_rigid_body_exchange() {
        // Test 4 at 80 degrees slides throughout: the contact point's slip falls by
        // (1 + mR²/I) μ (1 + e) v_n with e = 1 (Hertz), so e_t = −(1 − 7 μ v_n / v_t), and
        // the spin by (5/2) μ (1 + e) v_n / R.
        let c = &cases(&["test4-alumina@80".into()]).unwrap()[0];
        let Approach::Impact(touch) = approach(&c.scene).unwrap() else {
            panic!("no impact")
        };
        let laws = tangential_laws(&c.scene, &touch).unwrap();
        let coulomb = laws.iter().find(|l| l.law == "coulomb").unwrap();
        let (vn, vt, mu, r) = (
            3.9 * 80f64.to_radians().cos(),
            3.9 * 80f64.to_radians().sin(),
            0.092,
            0.0025,
        );
        let et = -(1.0 - 7.0 * mu * vn / vt);
        assert!(
            (coulomb.restitution - et).abs() < 1e-4,
            "{coulomb:?} against {et}"
        );
        let spin = -2.5 * mu * 2.0 * vn / r;
        assert!(
            (coulomb.spin1_after / spin - 1.0).abs() < 1e-4,
            "{coulomb:?} against {spin}"
        );
        assert_eq!(laws.len(), Registry::builtin().tangential.len());
    }

    #[test]
    fn a_prefix_that_names_no_case_is_refused_before_running() {
        let e = bench(&["test9".into()], None).unwrap_err().to_string();
        assert!(e.contains("--only") && e.contains("test9"), "{e}");
    }
}
