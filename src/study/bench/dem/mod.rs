//! Chung & Ooi's DEM benchmark tests by converged FE (`twoball bench dem`): the scenes of
//! `verification/dem-benchmarks/`, run as that folder's README runs them, into one report.
//!
//! The normal tests (1: two identical elastic spheres; 2 and 3: a sphere on a rigid plane)
//! run on the section to `--tolerance 0.5%` and are set beside Hertz's elastic impact and
//! every DEM normal law; test 3 also asks each damped law for the restitution it was set
//! to. The oblique and spinning tests (4: a sphere on a rigid plane at 3.9 m/s and eleven
//! angles of incidence, the same impact between two identical balls; 5: constant normal
//! speed, varying tangential speed; 6: a spinning sphere on a rigid plane; 7: two identical
//! spinning spheres; 8: a spinning sphere on a heavy sphere five times its size) run on the
//! 3D model's pole ladder to `--tolerance` (1 % by default) and are set beside Maw, Barber & Fawcett's elastic theory
//! and every DEM tangential law.

pub mod cases;
pub mod laws;
pub mod report;

pub use cases::{cases, DemCase, OBLIQUE_TOLERANCE, PAIR_ANGLES, TEST4_ANGLES};

use crate::atomic::{ensure_dir, write_atomic};
use crate::error::{Error, Result};
use crate::study::convergence::scene_estimate::run_scene_with_estimate;
use crate::study::records::estimate::Estimate;
use crate::study::run::law_compare::{tangential_laws, LawOutcome, TangentialLawOutcome};
use crate::study::run::scene::RunReport;
use crate::study::run::simulation::RunOptions;
use std::path::Path;
use std::time::Instant;

/// One case's figures: FE with its bar beside the reference (Hertz head-on, Maw, Barber &
/// Fawcett oblique) and the DEM laws. SI units; NaN where a figure does not apply.
#[derive(Debug, Clone, PartialEq)]
pub struct DemRow {
    /// The case's name.
    pub name: String,
    /// True for an oblique or spinning case.
    pub oblique: bool,
    /// Angle of incidence, degrees (test 4 and the pair; NaN otherwise).
    pub angle: f64,
    /// The contact points' slip at touch over μ times the normal approach speed, - (the
    /// tests' normalised angle of incidence; NaN head-on or frictionless).
    pub slip_ratio: f64,
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
    /// Meshes of the FE's ladder, -.
    pub levels: usize,
    /// Whether the ladder met its tolerance (`None` without one).
    pub tolerance_met: Option<bool>,
    /// Every normal law at its elastic setting (normal cases; empty oblique).
    pub normal_laws: Vec<LawOutcome>,
    /// Test 3: each damped law's e against the e it was set to, (law, set, out).
    pub damping: Vec<(String, f64, f64)>,
    /// Every tangential law with Hertz along the normal (oblique cases; empty head-on).
    pub laws: Vec<TangentialLawOutcome>,
    /// Wall time of the case, s.
    pub wall_time: f64,
}

/// The bar of an estimate, NaN without one.
fn bar(e: Option<&Estimate>) -> f64 {
    e.map_or(f64::NAN, |e| e.error)
}

/// The DEM laws of one case: normal, test 3's damping table and tangential.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CaseLaws {
    /// Every normal law at its elastic setting (normal cases).
    pub normal: Vec<LawOutcome>,
    /// Test 3's (law, e set, e out).
    pub damping: Vec<(String, f64, f64)>,
    /// Every tangential law with Hertz along the normal (oblique cases).
    pub tangential: Vec<TangentialLawOutcome>,
}

/// The row of `case` from its report `r`, its laws and wall time `wall` (s).
pub fn row(case: &DemCase, r: &RunReport, laws: CaseLaws, wall: f64) -> DemRow {
    let est = r.error_estimate.as_ref();
    let an = r.analytic.as_ref();
    let tan = r.tangential.as_ref();
    let theory = tan.and_then(|t| t.theory.as_ref());
    let t_est = est.and_then(|e| e.tangential.as_ref());
    let nan = f64::NAN;
    DemRow {
        name: case.name.clone(),
        oblique: case.oblique,
        angle: case.angle.unwrap_or(nan),
        slip_ratio: slip_ratio(case),
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
        levels: est.map_or(1, |e| e.meshes.len()),
        tolerance_met: est.and_then(|e| e.tolerance_met),
        normal_laws: laws.normal,
        damping: laws.damping,
        laws: laws.tangential,
        wall_time: wall,
    }
}

/// The slip of the contact points at touch over μ times the approach speed, -; NaN for a
/// normal case, a frictionless one, or balls that never touch.
fn slip_ratio(case: &DemCase) -> f64 {
    let (mu, _) = case.scene.friction_coefficients();
    match &case.touch {
        Some(t) if case.oblique && mu > 0.0 => {
            // Against the partner at touch: a wall's, not its image's, normal velocity.
            let v_n = t.v[0][0] - t.partner(&case.scene).0[0];
            t.slip_speed / (mu * v_n)
        }
        _ => f64::NAN,
    }
}

/// The DEM laws of `case`: errors name the law that fails.
fn case_laws(case: &DemCase) -> Result<CaseLaws> {
    let Some(touch) = &case.touch else {
        return Ok(CaseLaws::default());
    };
    if case.oblique {
        return Ok(CaseLaws {
            tangential: tangential_laws(&case.scene, touch)?,
            ..CaseLaws::default()
        });
    }
    Ok(CaseLaws {
        normal: laws::normal_laws(&case.scene, touch, 1.0, 0.0)?,
        damping: if case.damping {
            laws::damping(&case.scene, touch)?
        } else {
            Vec::new()
        },
        tangential: Vec::new(),
    })
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
        let named = |e: Error| match e {
            Error::Interrupted(_) => e,
            e => Error::Numerical(format!("bench dem, case {}: {e}", c.name)),
        };
        let r = run_scene_with_estimate(&c.scene, &opts, c.plan).map_err(named)?;
        let laws = case_laws(c).map_err(named)?;
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

/// Runs the cases named by `only` (all when empty), the oblique and spinning ones to relative
/// tolerance `oblique` (-) on their pole ladders, and writes `report.md` and `cases.csv` into
/// `out` (each whole: written aside and renamed); prints the report and the wall time. Fails
/// on a bad `only` (no case matches), a failed case, or an unwritable folder.
pub fn bench(only: &[String], oblique: f64, out: Option<&Path>) -> Result<Vec<DemRow>> {
    let cases = cases(only, oblique)?;
    if cases.is_empty() {
        return Err(Error::invalid(
            "--only",
            only.join(","),
            format!("a prefix of a case name: {}", cases::prefixes()),
        ));
    }
    let start = Instant::now();
    let rows = run(&cases)?;
    let total = start.elapsed().as_secs_f64();
    let text = report::report(&rows, total);
    if let Some(dir) = out {
        ensure_dir(dir)?;
        write_atomic(dir.join("cases.csv"), report::csv(&rows).as_bytes())?;
        write_atomic(dir.join("report.md"), text.as_bytes())?;
    }
    print!("{text}");
    println!("bench dem: {} in {total:.1} s", report::count(rows.len()));
    Ok(rows)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analytic::laws::Registry;

    #[test]
    fn in_gross_sliding_the_coulomb_law_is_the_rigid_body_exchange() {
        // Test 4 at 80 degrees slides throughout: the contact point's slip falls by
        // (1 + mR²/I) μ (1 + e) v_n with e = 1 (Hertz), so e_t = −(1 − 7 μ v_n / v_t), and
        // the spin by (5/2) μ (1 + e) v_n / R.
        let c = &cases(&["test4-alumina@80".into()], OBLIQUE_TOLERANCE).unwrap()[0];
        let laws = case_laws(c).unwrap().tangential;
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
        // Its normalised angle of incidence: tan 80° / μ.
        let s = slip_ratio(c);
        assert!(
            (s / (80f64.to_radians().tan() / mu) - 1.0).abs() < 1e-9,
            "{s}"
        );
    }

    #[test]
    fn a_spinning_ball_sliding_throughout_loses_the_coulomb_spin() {
        // Test 6 at ω = 14 rad/s: the contact point slips at R ω = 1.4 m/s and slides
        // throughout, so the slip falls by (1 + mR²/I) μ (1 + e) v_n = 0.56 m/s (e = 1,
        // v_n = 0.2 m/s, μ = 0.4): e_t = −0.6, and the spin by (5/2) μ (1 + e) v_n / R = 4.
        let c = &cases(&["test6-aluminium@w14".into()], OBLIQUE_TOLERANCE).unwrap()[0];
        let laws = case_laws(c).unwrap().tangential;
        let coulomb = laws.iter().find(|l| l.law == "coulomb").unwrap();
        assert!((coulomb.restitution + 0.6).abs() < 1e-4, "{coulomb:?}");
        assert!((coulomb.spin1_after - 10.0).abs() < 1e-3, "{coulomb:?}");
    }

    #[test]
    fn a_spinning_ball_slips_at_r_omega_and_a_spinning_pair_at_twice_that() {
        // Test 6: v_n = 0.2 m/s, R ω = 0.3 m/s, μ = 0.4; test 7: each ball at 0.2 m/s, so
        // the approach is 0.4 m/s and the slip 2 R ω = 0.6 m/s.
        let six = &cases(&["test6-aluminium@w3".into()], OBLIQUE_TOLERANCE).unwrap()[0];
        assert!((slip_ratio(six) - 0.3 / (0.4 * 0.2)).abs() < 1e-9);
        let seven = &cases(&["test7-aluminium@w3".into()], OBLIQUE_TOLERANCE).unwrap()[0];
        assert!((slip_ratio(seven) - 0.6 / (0.4 * 0.4)).abs() < 1e-9);
        // Head-on cases have none.
        let one = &cases(&["test1-glass".into()], OBLIQUE_TOLERANCE).unwrap()[0];
        assert!(slip_ratio(one).is_nan());
    }

    #[test]
    fn a_prefix_that_names_no_case_is_refused_before_running() {
        let e = bench(&["test9".into()], OBLIQUE_TOLERANCE, None)
            .unwrap_err()
            .to_string();
        assert!(e.contains("--only") && e.contains("test9"), "{e}");
        assert!(e.contains("test6-aluminium@wVALUE"), "{e}");
    }
}
