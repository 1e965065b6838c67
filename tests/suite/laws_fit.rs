//! Issue 27, item 5: `twoball laws fit` recovers known parameters from data a law made, and
//! the DEM export files parse back to the fitted values.

use std::path::Path;
use std::process::Command;
use twoball::analytic::law_fit::{predict, read_observations};
use twoball::analytic::laws::{ContactPair, Params, Registry};
use twoball::analytic::Body;
use twoball::material::Material;

fn twoball(args: &[&str]) -> (bool, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_twoball"))
        .args(args)
        .output()
        .unwrap();
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// Synthetic data from `law` with `over`, at six speeds, in the general CSV layout.
fn synthetic(dir: &Path, law: &str, over: &[(String, f64)]) -> std::path::PathBuf {
    let m = Material::preset("copper-fe").unwrap();
    let b = Body::ball(m, 0.02, "ball").unwrap();
    let pair = ContactPair::between(&b, &b, m.mu);
    let reg = Registry::builtin();
    let spec = reg.normal(law).unwrap();
    let p = Params::resolve(law, spec.params, over, &pair).unwrap();
    let mut s = String::from("v_r [m/s],e [-],delta_max [m]\n");
    for v in [0.1, 0.3, 1.0, 2.0, 5.0, 10.0] {
        let (e, d, _) = predict(spec, &pair, &p, &b, &b, v).unwrap();
        s.push_str(&format!("{v:e},{e:.15e},{d:.15e}\n"));
    }
    let path = dir.join(format!("{law}.csv"));
    std::fs::write(&path, s).unwrap();
    path
}

/// The number after `key` on the line that contains `key` (LIGGGHTS: last token; C++:
/// inside the parentheses).
fn value_after(text: &str, key: &str) -> f64 {
    let line = text
        .lines()
        .find(|l| !l.starts_with('#') && !l.starts_with("//") && l.contains(key))
        .unwrap_or_else(|| panic!("no line with {key}"));
    let tail = line.split(key).nth(1).unwrap();
    let tok = tail
        .trim_matches(|c: char| c == '(' || c == ')' || c == ';' || c.is_whitespace())
        .split_whitespace()
        .last()
        .unwrap()
        .trim_end_matches(");")
        .trim_start_matches('(');
    tok.parse().unwrap_or_else(|_| panic!("{key}: '{tok}'"))
}

/// A fresh folder for one test.
fn tmpdir(name: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("twoball-laws-fit-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn fitted(dir: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("fit.json")).unwrap()).unwrap()
}

#[test]
fn linear_dashpot_fit_recovers_its_parameters_and_exports_parse_back() {
    let tmp = tmpdir("dashpot");
    let over = vec![("k".to_string(), 3e7), ("e".to_string(), 0.6)];
    let data = synthetic(tmp.as_path(), "linear-dashpot", &over);
    let out = tmp.as_path().join("fit");
    let (ok, stdout, stderr) = twoball(&[
        "laws",
        "fit",
        "--law",
        "linear-dashpot",
        "--against",
        data.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(ok, "{stdout}{stderr}");
    let f = fitted(&out);
    let k = f["params"]["k"].as_f64().unwrap();
    let e = f["params"]["e"].as_f64().unwrap();
    assert!((k - 3e7).abs() < 1e-5 * 3e7, "k = {k}");
    assert!((e - 0.6).abs() < 1e-5, "e = {e}");
    // LIGGGHTS: kn = k, gamman = c/m*; MercuryDPM: stiffness k, dissipation c.
    let m = Material::preset("copper-fe").unwrap();
    let b = Body::ball(m, 0.02, "ball").unwrap();
    let mass = ContactPair::between(&b, &b, m.mu).hertz.mass;
    let l = e.ln();
    let c = 2.0 * (-l / (std::f64::consts::PI.powi(2) + l * l).sqrt()) * (k * mass).sqrt();
    let lig = std::fs::read_to_string(out.join("liggghts.in")).unwrap();
    assert!((value_after(&lig, "kn peratomtypepair 1") - k).abs() < 1e-8 * k);
    assert!((value_after(&lig, "gamman peratomtypepair 1") * mass - c).abs() < 1e-8 * c);
    assert!(lig.contains("limitForce off"));
    let mer = std::fs::read_to_string(out.join("mercurydpm.cpp")).unwrap();
    assert!((value_after(&mer, "setStiffness") - k).abs() < 1e-8 * k);
    assert!((value_after(&mer, "setDissipation") - c).abs() < 1e-8 * c);
    // The tabulated e(v) is the law's e at each speed (constant for this law).
    let tab = std::fs::read_to_string(out.join("e_of_v.csv")).unwrap();
    let mut lines = tab.lines();
    assert_eq!(
        lines.next().unwrap(),
        "v_r [m/s],e [-],delta_max [m],contact_duration [s]"
    );
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 41);
    assert!(rows.iter().all(|r| (r[1] - e).abs() < 1e-6));
}

#[test]
fn walton_braun_export_maps_the_unloading_stiffness() {
    let tmp = tmpdir("walton");
    let over = vec![("k".to_string(), 2e7), ("e".to_string(), 0.45)];
    let data = synthetic(tmp.as_path(), "walton-braun", &over);
    let out = tmp.as_path().join("fit");
    let (ok, stdout, stderr) = twoball(&[
        "laws",
        "fit",
        "--law",
        "walton-braun",
        "--against",
        data.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(ok, "{stdout}{stderr}");
    let f = fitted(&out);
    let e = f["params"]["e"].as_f64().unwrap();
    let k = f["params"]["k"].as_f64().unwrap();
    assert!(
        (e - 0.45).abs() < 1e-5 && (k - 2e7).abs() < 1e-5 * 2e7,
        "{e} {k}"
    );
    // LIGGGHTS hooke/hysteresis and MercuryDPM's Luding model: the unloading stiffness
    // reaches k/e^2 at the reference speed's maximum overlap, half way up to
    // k2max = k (2/e^2 - 1).
    let k2 = k * (2.0 / (e * e) - 1.0);
    let lig = std::fs::read_to_string(out.join("liggghts.in")).unwrap();
    assert!(
        (value_after(&lig, "coefficientMaxElasticStiffness peratomtypepair 1") - k2 / k).abs()
            < 1e-8 * k2 / k
    );
    assert!(lig.contains("Holds only for"), "{lig}");
    let mer = std::fs::read_to_string(out.join("mercurydpm.cpp")).unwrap();
    assert!((value_after(&mer, "setUnloadingStiffnessMax") - k2).abs() < 1e-8 * k2);
    assert!((value_after(&mer, "setLoadingStiffness") - k).abs() < 1e-8 * k);
}

#[test]
fn the_sweep_csv_is_read_as_head_on_fe_data() {
    let text = std::fs::read_to_string("verification/ansys/sweep.csv").unwrap();
    let obs = read_observations(&text, "sweep.csv", Some(0.02), Some("graded")).unwrap();
    // Head-on graded D = 20 mm rows: v_r = 3.5, 2.5, 2, 1, 0.5 m/s.
    let mut v: Vec<f64> = obs.iter().map(|o| o.speed).collect();
    v.sort_by(f64::total_cmp);
    assert_eq!(v, vec![0.5, 1.0, 2.0, 2.5, 3.5]);
    assert!(obs
        .iter()
        .all(|o| o.e > 0.0 && o.e < 1.0 && o.delta_max > 0.0));
    let tmp = tmpdir("sweep");
    let out = tmp.as_path().join("fit");
    let (ok, stdout, stderr) = twoball(&[
        "laws",
        "fit",
        "--law",
        "thornton",
        "--against",
        "verification/ansys/sweep.csv",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(ok, "{stdout}{stderr}");
    assert!(fitted(&out)["sigma"]["p_y"].as_f64().unwrap() > 0.0);
}

#[test]
fn bad_fit_input_is_one_clear_error() {
    let tmp = tmpdir("bad");
    let bad = tmp.as_path().join("bad.csv");
    std::fs::write(&bad, "v_r [m/s],e [-],delta_max [m]\n1.0,abc,1e-5\n").unwrap();
    let (ok, _, err) = twoball(&[
        "laws",
        "fit",
        "--law",
        "thornton",
        "--against",
        bad.to_str().unwrap(),
        "--out",
        tmp.as_path().to_str().unwrap(),
    ]);
    assert!(!ok);
    assert!(err.contains("column e [-] = 'abc'"), "{err}");
    let (ok, _, err) = twoball(&[
        "laws",
        "fit",
        "--law",
        "thornton",
        "--free",
        "k",
        "--against",
        "verification/ansys/sweep.csv",
        "--out",
        tmp.as_path().to_str().unwrap(),
    ]);
    assert!(
        !ok && err.contains("--free") && err.contains("p_y"),
        "{err}"
    );
}
