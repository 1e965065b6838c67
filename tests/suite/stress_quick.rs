//! Issue 7 item 1: the quick subset of the stress matrix runs clean (no silent failure), and
//! the classifier really catches the silent failures it is there for.

use std::path::Path;
use twoball::study::bench::robustness::{classify, Class, StressSpec};

#[test]
fn quick_stress_subset_has_no_silent_failure() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let matrix = root.join("verification/stress.toml");
    let spec = StressSpec::from_file(&matrix).unwrap();
    assert!(spec.cases().unwrap().len() >= 200, "matrix too small");
    assert!((10..=20).contains(&spec.stress.quick.len()));
    let out = std::env::temp_dir().join(format!("twoball-stress-quick-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&out);
    let run = std::process::Command::new(env!("CARGO_BIN_EXE_twoball"))
        .arg("stress")
        .arg("--matrix")
        .arg(&matrix)
        .arg("--out")
        .arg(&out)
        .args(["--quick", "--jobs", "2"])
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&run.stdout);
    let summary = std::fs::read_to_string(out.join("summary.md")).unwrap();
    assert!(run.status.success(), "{stdout}\n{summary}");
    assert!(stdout.contains(" 0 silent failures"), "{stdout}");
    let rows = summary
        .lines()
        .filter(|l| {
            l.contains("| Clean |") || l.contains("| Flagged |") || l.contains("| Stopped |")
        })
        .count();
    assert_eq!(rows, spec.stress.quick.len(), "{summary}");
    let _ = std::fs::remove_dir_all(&out);
}

fn dir_with(json: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!(
        "twoball-stress-classify-{}-{}",
        std::process::id(),
        json.len()
    ));
    std::fs::create_dir_all(&d).unwrap();
    std::fs::write(d.join("results.json"), json).unwrap();
    std::fs::write(d.join("history.csv"), "t [s],delta [m]\n0,0\n").unwrap();
    d
}

/// results.json of two 20 mm copper balls (7900 kg/m³) at ±1 m/s, with the given outcome.
fn results(e: &str, v1: &str, energy_error: &str) -> String {
    format!(
        r#"{{"impact": true, "e": {e}, "v1_after": [{v1}, 0, 0], "v2_after": [1.0, 0, 0],
        "w1_after": [0, 0, 0], "w2_after": [0, 0, 0], "energy_error": {energy_error},
        "fe": {{"stop_reason": "separated"}},
        "scene": {{"ball1": {{"diameter": 0.02, "material": {{"rho": 7900}}, "velocity": [1, 0, 0], "angular_velocity": [0, 0, 0], "position": null}},
                   "ball2": {{"diameter": 0.02, "material": {{"rho": 7900}}, "velocity": [-1, 0, 0], "angular_velocity": [0, 0, 0], "position": null}}}}}}"#
    )
}

#[test]
fn classifier_catches_silent_failures() {
    let sets = vec![];
    let c = |exit, timeout, stderr: &str, dir: &Path| {
        classify("x", &sets, exit, timeout, stderr, dir, 0.01, 1.0).class
    };
    // A clean elastic rebound: e = 1, kinetic energy kept.
    let ok = dir_with(&results("1.0", "-1.0", "0.001"));
    assert_eq!(c(Some(0), false, "", &ok), Class::Clean);
    // Same with a 5 % energy error: reported, so flagged, not silent.
    let flag = dir_with(&results("1.0", "-1.0", "0.05"));
    assert_eq!(c(Some(0), false, "", &flag), Class::Flagged);
    // NaN written as null in a numeric field.
    let nan = dir_with(&results("null", "-1.0", "0.001"));
    assert_eq!(c(Some(0), false, "", &nan), Class::Silent);
    // Energy from nothing without a stop: e = 1.5, ball 1 leaves faster than it came.
    let gain = dir_with(&results("1.5", "-2.0", "0.0001"));
    assert_eq!(c(Some(0), false, "", &gain), Class::Silent);
    // A panic, a timeout, a stop with a clear message.
    assert_eq!(
        c(Some(101), false, "thread 'main' panicked", &ok),
        Class::Silent
    );
    assert_eq!(c(None, true, "", &ok), Class::Silent);
    assert_eq!(
        c(Some(1), false, "error: numerical failure: node 3 ...", &ok),
        Class::Stopped
    );
    // An oblique impact (results.json `tangential`) whose rebound took energy from its
    // sliding: e = 1.04 with the kinetic energy down (ball 1 leaves at −1.04 m/s, ball 2 at
    // 0.5 of its 1 m/s) is flagged, not impossible; with the kinetic energy up it is.
    let oblique = |v2: &str| {
        results("1.04", "-1.04", "0.001").replace(
            r#""v2_after": [1.0, 0, 0]"#,
            &format!(r#""v2_after": [{v2}, 0, 0], "tangential": {{}}"#),
        )
    };
    let spun = dir_with(&oblique("0.50"));
    assert_eq!(c(Some(0), false, "", &spun), Class::Flagged);
    let made = dir_with(&oblique("1.0"));
    assert_eq!(c(Some(0), false, "", &made), Class::Silent);
    // A ball twisting about the normal has no slip at touch (no `tangential`) but spins: the
    // same e = 1.04 with its spin down from 100 to 50 rad/s and the kinetic energy down is
    // flagged too.
    let twist = results("1.04", "-1.04", "0.001")
        .replace(r#""v2_after": [1.0, 0, 0]"#, r#""v2_after": [0.5, 0, 0]"#)
        .replace(r#""w1_after": [0, 0, 0]"#, r#""w1_after": [50, 0, 0]"#)
        .replacen(
            r#""angular_velocity": [0, 0, 0]"#,
            r#""angular_velocity": [100, 0, 0]"#,
            1,
        );
    let twisted = dir_with(&twist);
    assert_eq!(c(Some(0), false, "", &twisted), Class::Flagged);
    for d in [ok, flag, nan, gain, spun, made, twisted] {
        let _ = std::fs::remove_dir_all(d);
    }
}
