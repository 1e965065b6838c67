//! Is the bar of `twoball run --tolerance` honest? (verification/contact-penalty.md, "Is the
//! banded bar honest?") Each case is the default scene's pair of another metal and speed,
//! cased as `--tolerance 0.5%` cases it (`study::converged_scene::family_case`) and run on
//! the banded family (`study::converged_scene::plan`, five-fold band, two meshes per level),
//! levels 0 and 1, whose bar on e is the claim. The
//! reference is the same family one level finer (level 2, two meshes): the claim is kept
//! when level 1's mean lies within its bar of level 2's mean, and kept strictly when it also
//! lies within its bar of 2 e₂ − e₁ (the level-2 mean extrapolated at first order, the slowest
//! order the section's e shows). Two refinements finer (level 3) would cost about 16 times
//! level 2.
//!
//! `cargo test --release --test suite tolerance_honesty:: -- --ignored --nocapture` (about 12 min on
//! 2 cores); `HONESTY_MATERIALS=steel` and `HONESTY_SPEEDS=1,5` (m/s per ball) shrink it.

use std::path::Path;
use twoball::scene::{Override, Scene, DEFAULT_SCENE};
use twoball::study::convergence::converged_scene::{family_case, plan};
use twoball::study::convergence::phase_band::banded_ensemble_at;
use twoball::study::convergence::phase_ensemble::converged_head_on;

/// The default scene with two balls of metal `m` and diameter `d` (m) at ±`v` (m/s).
fn head_on(m: &str, d: f64, v: f64) -> Scene {
    let sets: Vec<Override> = [
        format!("ball1.material=\"{m}\""),
        format!("ball2.material=\"{m}\""),
        format!("ball1.diameter={d}"),
        format!("ball2.diameter={d}"),
        format!("ball1.velocity=[{v},0,0]"),
        format!("ball2.velocity=[-{v},0,0]"),
    ]
    .iter()
    .map(|s| Override::parse(s).unwrap())
    .collect();
    Scene::from_toml(DEFAULT_SCENE, Path::new("."), &sets).unwrap()
}

#[test]
#[ignore]
fn the_tolerance_bar_holds_in_nine_cases_of_ten() {
    let materials: Vec<String> = std::env::var("HONESTY_MATERIALS")
        .map(|s| s.split(',').map(str::to_string).collect())
        .unwrap_or_else(|_| vec!["copper-fe".into(), "steel".into(), "aluminum".into()]);
    let speeds: Vec<f64> = std::env::var("HONESTY_SPEEDS")
        .map(|s| s.split(',').map(|x| x.parse().unwrap()).collect())
        .unwrap_or_else(|_| vec![5.0, 2.5, 1.0, 0.5, 0.25, 0.1, 0.05]);
    let mut rows = Vec::new();
    println!("| material | v per ball (m/s) | e (level 1) | bar | level 2 | true error | within | strict | wall (s) |");
    println!("|---|---|---|---|---|---|---|---|---|");
    for m in &materials {
        for &v in &speeds {
            // The default scene (D = 20 mm) of metal `m` at ±v, as `--tolerance 0.5%` cases it.
            let scene = head_on(m, 0.02, v);
            let case = family_case(&scene, 0.005).unwrap().unwrap();
            let start = std::time::Instant::now();
            // The claim: levels 0 and 1, as `--tolerance` runs them before any refinement.
            let mut claim_plan = plan(0.005, 0);
            claim_plan.tolerance = None;
            let claim = converged_head_on(&case, &claim_plan).unwrap();
            let edge = claim.band_edge.expect("the banded family has an edge");
            let (finer, _) =
                banded_ensemble_at(&case, 2, claim_plan.meshes, edge, claim_plan.band.unwrap())
                    .unwrap();
            let (e1, bar, e2) = (claim.e.finest, claim.e.error, finer.e.mean);
            let within = (e1 - e2).abs() <= bar;
            let strict = (e1 - (2.0 * e2 - e1)).abs() <= bar;
            println!(
                "| {m} | {v} | {e1:.5} | {:.2} % | {e2:.5} | {:.2} % | {} | {} | {:.0} |",
                100.0 * bar / e1,
                100.0 * (e1 - e2).abs() / e2,
                if within { "yes" } else { "no" },
                if strict { "yes" } else { "no" },
                start.elapsed().as_secs_f64()
            );
            rows.push((within, strict));
        }
    }
    let within = rows.iter().filter(|r| r.0).count();
    let strict = rows.iter().filter(|r| r.1).count();
    println!("within {within} of {}, strictly {strict}", rows.len());
    assert!(
        10 * within >= 9 * rows.len(),
        "within in {within} of {}",
        rows.len()
    );
}

/// Issue 52, acceptance 2: on rate-dependent (Johnson-Cook) metals, are the default run's bar
/// and the `--tolerance 0.5%` bar honest? Thirteen head-on cases: `ofhc-copper` and
/// `steel-4340` at D = 10 and 30 mm and ±0.05, ±1, ±10 m/s, and the `ofhc-copper` D = 20 mm
/// ±5 m/s case of the issue. The default claim is `twoball run`'s (levels −1 and 0 of the
/// scene's own ladder, each a phase ensemble); the tolerance claim is the banded family's
/// levels 0 and 1 as `--tolerance 0.5%` runs them (mass-scaling budget 1e-4). The reference
/// is the banded family one level finer than the tolerance claim (level 2, the same budget;
/// the bias of mass scaling on these rate-dependent metals is measured apart with
/// `examples/mass_scaling.rs`). A claim holds when |e − e_ref| ≤ bar.
///
/// `cargo test --release --test suite tolerance_honesty::johnson_cook -- --ignored --nocapture`.
#[test]
#[ignore]
fn johnson_cook_bars_hold_in_twelve_cases_of_thirteen() {
    use twoball::study::convergence::ladder::LadderPlan;
    use twoball::study::convergence::scene_estimate::run_scene_with_estimate;
    use twoball::study::run::simulate::RunOptions;
    let mut cases: Vec<(&str, f64, f64)> = Vec::new();
    for m in ["ofhc-copper", "steel-4340"] {
        for d in [0.010, 0.030] {
            for v in [0.05, 1.0, 10.0] {
                cases.push((m, d, v));
            }
        }
    }
    cases.push(("ofhc-copper", 0.020, 5.0));
    if let Ok(only) = std::env::var("HONESTY_CASES") {
        let keep: Vec<usize> = only.split(',').map(|s| s.parse().unwrap()).collect();
        cases = keep.iter().map(|&k| cases[k]).collect();
    }
    println!("| material | D (mm) | v per ball (m/s) | e default | bar | true error | covered | e tolerance | bar | true error | covered | e reference | wall (s) |");
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    let (mut default_ok, mut tolerance_ok) = (0, 0);
    for &(m, d, v) in &cases {
        let start = std::time::Instant::now();
        let scene = head_on(m, d, v);
        let opts = RunOptions {
            history_rows: 200,
            ..RunOptions::default()
        };
        let default = run_scene_with_estimate(&scene, &opts, LadderPlan::TwoLevels).unwrap();
        let (e0, bar0) = (
            default.e.unwrap(),
            default.error_estimate.as_ref().unwrap().e.error,
        );
        let case = family_case(&scene, 0.005).unwrap().unwrap();
        let mut claim_plan = plan(0.005, 0);
        claim_plan.tolerance = None;
        let claim = converged_head_on(&case, &claim_plan).unwrap();
        let edge = claim.band_edge.expect("the banded family has an edge");
        // The claim's mass-scaling budget: its bias on a rate-dependent metal is measured
        // apart (verification/contact-penalty.md, "Mass scaling of the contact region"); a
        // reference without it costs tens of CPU minutes a case at level 2.
        let (reference, _) =
            banded_ensemble_at(&case, 2, claim_plan.meshes, edge, claim_plan.band.unwrap())
                .unwrap();
        let e_ref = reference.e.mean;
        let (e1, bar1) = (claim.e.finest, claim.e.error);
        let covered0 = (e0 - e_ref).abs() <= bar0;
        let covered1 = (e1 - e_ref).abs() <= bar1;
        default_ok += usize::from(covered0);
        tolerance_ok += usize::from(covered1);
        let pct = |x: f64| 100.0 * x / e_ref;
        println!(
            "| {m} | {} | {v} | {e0:.5} | {:.2} % | {:+.2} % | {} | {e1:.5} | {:.2} % | {:+.2} % | {} | {e_ref:.5} | {:.0} |",
            1e3 * d,
            pct(bar0),
            pct(e0 - e_ref),
            if covered0 { "yes" } else { "**no**" },
            pct(bar1),
            pct(e1 - e_ref),
            if covered1 { "yes" } else { "**no**" },
            start.elapsed().as_secs_f64()
        );
    }
    let n = cases.len();
    println!("default bar covers {default_ok} of {n}, tolerance bar {tolerance_ok} of {n}");
    assert!(
        12 * default_ok >= 11 * n && 12 * tolerance_ok >= 11 * n,
        "default {default_ok} of {n}, tolerance {tolerance_ok} of {n}"
    );
}
