//! `twoball run --tolerance` on a head-on scene of the meridian section (issue 26 item 5):
//! the banded, mass-scaled family of `study::converged_scene` answers, its bar covers the
//! converged e, and results.json says how the estimate was made.

use std::path::Path;
use twoball::scene::{Override, Scene, DEFAULT_SCENE};
use twoball::study::convergence::ladder::LadderPlan;
use twoball::study::convergence::scene_estimate::run_scene_with_estimate;
use twoball::study::records::error_estimate::EstimateMethod;
use twoball::study::run::simulate::RunOptions;

/// The default scene's converged e: the four-fold banded level-2 answer 0.31847 ± 0.21 %
/// and the B-bar ladder's extrapolation 0.3184 (verification/contact-penalty.md, "The section's
/// converged answer").
const CONVERGED_E: f64 = 0.3184;

fn scene(sets: &[&str]) -> Scene {
    let sets: Vec<Override> = sets.iter().map(|s| Override::parse(s).unwrap()).collect();
    Scene::from_toml(DEFAULT_SCENE, Path::new("."), &sets).unwrap()
}

/// The default scene to 0.5 %: the banded family runs (levels 0 and 1, two meshes each,
/// mass scaling 1e-4), its bar meets the tolerance and covers the converged e, and the
/// report's e, velocities and differences are the family's fine mean.
#[test]
fn a_tolerance_on_the_default_scene_runs_the_banded_family_and_its_bar_holds() {
    let plan = LadderPlan::Tolerance {
        tolerance: 0.005,
        max_refinements: 2,
    };
    let opts = RunOptions {
        history_rows: 100,
        ..RunOptions::default()
    };
    let r = run_scene_with_estimate(&scene(&[]), &opts, plan).unwrap();
    let est = r.error_estimate.as_ref().unwrap();
    let EstimateMethod::BandedFamily {
        band_split,
        band_edge_m,
        mass_scaling,
        mass_scaling_bias,
        ..
    } = est.method
    else {
        panic!("{:?}", est.method);
    };
    assert_eq!((band_split, mass_scaling), (5, 1e-4));
    assert!((mass_scaling_bias - 1e-3).abs() < 1e-15);
    // The edge of the default contact, about 0.9 mm from the pole.
    assert!(
        band_edge_m > 0.8e-3 && band_edge_m < 1.0e-3,
        "{band_edge_m}"
    );
    let levels: Vec<i32> = est.meshes.iter().map(|m| m.level).collect();
    assert_eq!(levels, [0, 1]);
    assert_eq!(est.tolerance_met, Some(true), "{}", est.summary());
    let e = r.e.unwrap();
    assert_eq!(e, est.e.finest);
    assert_eq!(r.fe.as_ref().unwrap().outcome.e, e);
    let bar = est.e.error;
    assert!(
        (e - CONVERGED_E).abs() <= bar,
        "e {e} ± {bar} misses {CONVERGED_E}"
    );
    // The bar holds the mass-scaling bound and is within the tolerance.
    assert!(bar >= mass_scaling_bias * e && bar <= 0.005 * e, "{bar}");
    // ±1 m/s in the centre-of-mass frame: the balls leave at ∓e.
    assert!((r.v1_after[0] + e).abs() < 1e-12 && (r.v2_after[0] - e).abs() < 1e-12);
    let fine = est.meshes[1].phase.unwrap();
    assert_eq!(fine.meshes, 2);
    assert!(fine.e_min <= e && e <= fine.e_max);
    // Pole segments of the family's meshes halve from level 0 to 1.
    let ratio = est.meshes[0].pole_size / est.meshes[1].pole_size;
    assert!((ratio - 2.0).abs() < 0.05, "{ratio}");
    let json = serde_json::to_value(&r).unwrap();
    assert_eq!(json["error_estimate"]["method"]["kind"], "banded_family");
}

/// A ball at 5 m/s on a rigid wall is the pair at ±5 m/s (the wall is the pair's symmetry
/// plane): under a tolerance both run the same banded family, and the sweep's runner carries
/// the bar into the case (`e_error`).
#[test]
fn a_ball_on_a_rigid_wall_converges_as_the_pair_and_a_sweep_case_carries_its_bar() {
    let plan = LadderPlan::Tolerance {
        tolerance: 0.01,
        max_refinements: 0,
    };
    let pair = scene(&["ball1.velocity=[5.0,0,0]", "ball2.velocity=[-5.0,0,0]"]);
    let r = run_scene_with_estimate(&pair, &RunOptions::default(), plan).unwrap();
    let est = r.error_estimate.as_ref().unwrap();
    assert!(matches!(est.method, EstimateMethod::BandedFamily { .. }));
    let sets: Vec<Override> = ["ball1.velocity=[5.0,0,0]"]
        .iter()
        .map(|s| Override::parse(s).unwrap())
        .collect();
    let wall = Scene::from_toml(twoball::scene::WALL_SCENE, Path::new("."), &sets).unwrap();
    let case =
        twoball::study::convergence::scene_estimate::sweep_case_to(&wall, Some(0.01)).unwrap();
    let s = &case.summary;
    assert_eq!(s.outcome.e, r.e.unwrap());
    assert_eq!(s.e_error, Some(est.e.error));
    assert!(est.e.error <= 0.01 * s.outcome.e, "{}", est.summary());
    // The ball leaves the wall at e times its speed.
    assert!((s.outcome.v1_after[0] + 5.0 * s.outcome.e).abs() < 1e-9);
}

/// A tolerance of 2 % or looser that the scene's own levels −1 and 0 meet takes their
/// answer (a fraction of a second, the same as the default run) and says so; one below 2 %
/// does not, even where their bar would claim it.
#[test]
fn a_loose_tolerance_that_the_default_levels_meet_takes_their_answer() {
    use twoball::study::convergence::scene_estimate::{
        run_scene_default, LEVELS_MET_TOLERANCE, LEVELS_TOLERANCE_FLOOR,
    };
    let opts = RunOptions {
        history_rows: 100,
        ..RunOptions::default()
    };
    let s = scene(&[]);
    let default = run_scene_default(&s, &opts).unwrap();
    let bar = default
        .error_estimate
        .as_ref()
        .unwrap()
        .e
        .relative_error
        .unwrap();
    // The default scene's levels −1 and 0 give a bar of about 2.1 %.
    assert!(bar > LEVELS_TOLERANCE_FLOOR && bar < 0.05, "{bar}");
    let loose = LadderPlan::Tolerance {
        tolerance: 0.05,
        max_refinements: 0,
    };
    let r = run_scene_with_estimate(&s, &opts, loose).unwrap();
    let est = r.error_estimate.as_ref().unwrap();
    let EstimateMethod::SceneLadder { why_not_banded } = &est.method else {
        panic!("{:?}", est.method);
    };
    assert_eq!(why_not_banded.as_deref(), Some(LEVELS_MET_TOLERANCE));
    assert_eq!((est.tolerance, est.tolerance_met), (Some(0.05), Some(true)));
    assert_eq!(r.e, default.e);
    // The default run's bar, above the floor, is kept.
    assert_eq!(est.e, default.error_estimate.as_ref().unwrap().e);
    let levels: Vec<i32> = est.meshes.iter().map(|m| m.level).collect();
    assert_eq!(levels, [-1, 0]);
    // At ±1.25 m/s the levels' bar is about 1.1 %: under a tolerance of 3 % their answer
    // carries the floor's 2 % instead (below it, the banded family answers:
    // `a_tolerance_below_the_floor_runs_the_banded_family_although_the_levels_meet_it`).
    let faster = scene(&["ball1.velocity=[1.25,0,0]", "ball2.velocity=[-1.25,0,0]"]);
    let own = run_scene_default(&faster, &opts).unwrap();
    let own_bar = own.error_estimate.unwrap().e.relative_error.unwrap();
    assert!(own_bar < 0.015, "{own_bar}");
    let loose = LadderPlan::Tolerance {
        tolerance: 0.03,
        max_refinements: 0,
    };
    let r = run_scene_with_estimate(&faster, &opts, loose).unwrap();
    let est = r.error_estimate.unwrap();
    assert!(matches!(est.method, EstimateMethod::SceneLadder { .. }));
    let floor = LEVELS_TOLERANCE_FLOOR * est.e.extrapolated;
    assert!((est.e.error - floor).abs() < 1e-15, "{}", est.summary());
    // A bulk of 6 mm has no coarser level (12 mm is above a quarter of the diameter): there
    // are no default levels to try, so even a loose tolerance runs the family.
    let coarse = scene(&[
        "ball1.velocity=[2.5,0,0]",
        "ball2.velocity=[-2.5,0,0]",
        "ball1.mesh.size=0.006",
        "ball2.mesh.size=0.006",
    ]);
    assert!(twoball::study::convergence::ladder::scene_at_level(&coarse, -1).is_err());
    let r = run_scene_with_estimate(&coarse, &opts, loose).unwrap();
    let method = r.error_estimate.unwrap().method;
    assert!(
        matches!(method, EstimateMethod::BandedFamily { .. }),
        "{method:?}"
    );
}

/// The level-2 means of the banded family (two meshes, mass scaling 1e-4, subcycled to
/// level 3) for D = 20 mm identical balls: (material, speed of each ball m/s, e). From
/// `cargo test --release --test suite tolerance_honesty:: -- --ignored --nocapture`
/// (verification/contact-penalty.md, "Is the banded bar honest?").
const LEVEL_2: [(&str, f64, f64); 21] = [
    ("copper-fe", 5.0, 0.21808),
    ("copper-fe", 2.5, 0.25956),
    ("copper-fe", 1.0, 0.31839),
    ("copper-fe", 0.5, 0.36733),
    ("copper-fe", 0.25, 0.42283),
    ("copper-fe", 0.1, 0.50039),
    ("copper-fe", 0.05, 0.56335),
    ("steel", 5.0, 0.25904),
    ("steel", 2.5, 0.30667),
    ("steel", 1.0, 0.37488),
    ("steel", 0.5, 0.42940),
    ("steel", 0.25, 0.48846),
    ("steel", 0.1, 0.57040),
    ("steel", 0.05, 0.63708),
    ("aluminum", 5.0, 0.49848),
    ("aluminum", 2.5, 0.57511),
    ("aluminum", 1.0, 0.67572),
    ("aluminum", 0.5, 0.75043),
    ("aluminum", 0.25, 0.82468),
    ("aluminum", 0.1, 0.91635),
    ("aluminum", 0.05, 0.97244),
];

/// The floor under the default levels' answer to a tolerance holds: over three metals and
/// 0.05-5 m/s per ball, `twoball run`'s e (levels −1 and 0, four meshes each) lies within
/// 2 % of the banded family's level-2 mean, whatever its own bar says (docs/contact-
/// penalty.md, "The default levels against the floor").
#[test]
#[ignore = "21 default runs: about a minute in release, more in the test profile"]
fn the_default_levels_stay_within_the_floor() {
    use twoball::study::convergence::scene_estimate::{run_scene_default, LEVELS_TOLERANCE_FLOOR};
    let opts = RunOptions {
        history_rows: 10,
        ..RunOptions::default()
    };
    let mut worst: f64 = 0.0;
    for (m, v, e2) in LEVEL_2 {
        let s = scene(&[
            &format!("ball1.material=\"{m}\""),
            &format!("ball2.material=\"{m}\""),
            &format!("ball1.velocity=[{v},0,0]"),
            &format!("ball2.velocity=[-{v},0,0]"),
        ]);
        let r = run_scene_default(&s, &opts).unwrap();
        let (e, bar) = (
            r.e.unwrap(),
            r.error_estimate.unwrap().e.relative_error.unwrap(),
        );
        let error = e / e2 - 1.0;
        println!(
            "{m} {v} m/s: e {e:.5} bar {:.2} % level 2 {e2:.5} error {:+.2} %",
            100.0 * bar,
            100.0 * error
        );
        assert!(
            error.abs() <= LEVELS_TOLERANCE_FLOOR,
            "{m} at {v} m/s: {error:+.4}"
        );
        worst = worst.max(error.abs());
    }
    // The floor is not loose by an order of magnitude either.
    assert!(worst > 0.25 * LEVELS_TOLERANCE_FLOOR, "{worst}");
}

/// A tolerance of 1.5 %, below the floor, runs the banded family at ±1.25 m/s although the
/// default levels' own bar (about 1.1 %) is within it (`--ignored`: about 90 s; the branch it
/// takes is the one the 0.5 % test above takes).
#[test]
#[ignore]
fn a_tolerance_below_the_floor_runs_the_banded_family_although_the_levels_meet_it() {
    let opts = RunOptions {
        history_rows: 100,
        ..RunOptions::default()
    };
    let faster = scene(&["ball1.velocity=[1.25,0,0]", "ball2.velocity=[-1.25,0,0]"]);
    let tight = LadderPlan::Tolerance {
        tolerance: 0.015,
        max_refinements: 0,
    };
    let r = run_scene_with_estimate(&faster, &opts, tight).unwrap();
    let method = r.error_estimate.unwrap().method;
    assert!(
        matches!(method, EstimateMethod::BandedFamily { .. }),
        "{method:?}"
    );
}
