//! A sweep over diameters with meshes sized per diameter runs each similar family of cases
//! once on the meridian section and scales the others (`study::similarity`): the scaled case
//! says where it comes from, equals its own run to printed precision, stays in its twin's
//! shard, and the 3D models run every case.

use std::path::PathBuf;
use std::time::Duration;
use twoball::study::sweep::{
    read_case, run_sweep, shard_plan, twins, Case, Shard, SweepOptions, SweepSpec,
};

/// Two diameters, two speeds, head-on copper-fe; a coarse section (bulk D/5, pole D/100,
/// which has no coarser level: one run per case).
const SWEEP: &str = r#"
[study]
model = "fe"
diameters = [0.01, 0.025]
left_velocity = 1.0
right_velocities = [-1.0, 0.0]
[base]
ball1.material = "copper-fe"
ball2.material = "copper-fe"
[[mesh]]
name = "coarse"
size_per_diameter = 0.2
pole_size_per_diameter = 0.01
"#;

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!(
        "twoball-sweep-similarity-{name}-{}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

#[test]
fn similar_cases_on_the_section_are_scaled_from_one_run() {
    let spec = SweepSpec::from_toml(SWEEP, "test").unwrap();
    let cases = spec.cases().unwrap();
    let refs: Vec<&Case> = cases.iter().collect();
    // Cases: D10 at −1, 0 m/s, then D25 at −1, 0 m/s: each D25 case is its D10 twin × 2.5.
    let t = twins(&spec, &refs);
    assert_eq!(t[0], None);
    assert_eq!(t[1], None);
    let (j, k) = t[2].unwrap();
    assert_eq!(j, 0);
    assert!((k - 2.5).abs() < 1e-12, "{k}");
    assert_eq!(t[3].map(|t| t.0), Some(1));
    // A shard plan keeps each twin with its case.
    for count in 2..=3 {
        let plan = shard_plan(&spec, &refs, count);
        assert_eq!(plan[2], plan[0], "{count} shards");
        assert_eq!(plan[3], plan[1], "{count} shards");
    }
    let out = scratch("similarity");
    let opts = SweepOptions {
        out: out.clone(),
        jobs: 2,
        shard: Shard::ALL,
        pace: Duration::ZERO,
        verbose: false,
        mesh: None,
    };
    let fe: twoball::study::sweep::FeRunner<'_> =
        &twoball::study::convergence::scene_estimate::sweep_case;
    let s = run_sweep(&spec, &opts, Some(fe)).unwrap();
    assert_eq!((s.total, s.failed, s.scaled), (4, 0, 2));
    let run = read_case(&out, &cases[0].id).unwrap();
    let scaled = read_case(&out, &cases[2].id).unwrap();
    let (a, b) = (run.fe.as_ref().unwrap(), scaled.fe.as_ref().unwrap());
    assert_eq!(a.scaled_from, None);
    assert_eq!(b.scaled_from.as_deref(), Some(cases[0].id.as_str()));
    assert!(scaled.message.contains(&cases[0].id), "{}", scaled.message);
    assert_eq!(b.element_cycles, 0);
    assert_eq!(b.outcome.e, a.outcome.e);
    let ratio = b.outcome.delta_max / a.outcome.delta_max;
    assert!((ratio - 2.5).abs() < 1e-12, "{ratio}");
    let last = |h: &[[f64; 2]]| *h.last().unwrap();
    let (ha, hb) = (last(&run.fe_history), last(&scaled.fe_history));
    assert!((hb[0] - 2.5 * ha[0]).abs() <= 1e-12 * hb[0]);
    // The case's own run agrees to printed precision (six digits).
    let own = twoball::study::convergence::scene_estimate::sweep_case(&cases[2].scene).unwrap();
    let rel = |x: f64, y: f64| (x - y).abs() / y.abs();
    let o = &own.summary.outcome;
    assert!(rel(b.outcome.e, o.e) < 1e-6, "{} {}", b.outcome.e, o.e);
    assert!(rel(b.outcome.delta_max, o.delta_max) < 1e-6);
    assert!(rel(b.outcome.contact_duration, o.contact_duration) < 1e-6);
    std::fs::remove_dir_all(&out).unwrap();
}

#[test]
fn the_3d_models_run_every_case() {
    let text = SWEEP.replace(
        "ball2.material = \"copper-fe\"",
        "ball2.material = \"copper-fe\"\nreduction.symmetry = \"auto-3d\"",
    );
    let spec = SweepSpec::from_toml(&text, "test").unwrap();
    let cases = spec.cases().unwrap();
    let refs: Vec<&Case> = cases.iter().collect();
    assert!(twins(&spec, &refs).iter().all(Option::is_none));
    // So does an analytic-only sweep (its cases run no FE).
    let analytic = SweepSpec::from_toml(&SWEEP.replace("\"fe\"", "\"analytic\""), "t").unwrap();
    let cases = analytic.cases().unwrap();
    let refs: Vec<&Case> = cases.iter().collect();
    assert!(twins(&analytic, &refs).iter().all(Option::is_none));
}
