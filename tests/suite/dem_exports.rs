//! The DEM exports run in the real codes (issue 47): for each law a code can express, the
//! deck `twoball laws fit` (or `laws export`) writes is run unedited in LIGGGHTS, LAMMPS or
//! Yade at the deck's reference speed and two other speeds where its header claims the
//! mapping holds, and its e, δ_max and contact duration agree with `twoball laws run` of the
//! same law and parameters within 0.5 %; a law a code cannot express is a one-line error.
//! A missing code skips the test locally and fails it under CI=true (scripts/setup.sh).

use crate::tool_support;

use std::path::{Path, PathBuf};
use std::process::Command;

/// Largest relative difference accepted in e, δ_max and t_c.
const TOLERANCE: f64 = 5e-3;

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

/// A fresh folder for one case.
fn tmpdir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("twoball-dem-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// The project's 3D FE points (copper-fe, D = 20 mm, 0.5-3.5 m/s), as in the issue.
fn sweep() -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("verification/ansys/sweep.csv")
        .display()
        .to_string()
}

/// `twoball laws fit --law LAW --against sweep.csv` with extra flags into a fresh folder.
fn fit(name: &str, law: &str, extra: &[&str]) -> PathBuf {
    let dir = tmpdir(name);
    let against = sweep();
    let mut args = vec![
        "laws",
        "fit",
        "--law",
        law,
        "--against",
        &against,
        "--out",
        dir.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    let (ok, out, err) = twoball(&args);
    assert!(ok, "laws fit {law}: {out}{err}");
    dir
}

/// `twoball laws export --law LAW --code all` with extra flags into a fresh folder.
fn export(name: &str, law: &str, extra: &[&str]) -> PathBuf {
    let dir = tmpdir(name);
    let mut args = vec![
        "laws",
        "export",
        "--law",
        law,
        "--out",
        dir.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    let (ok, out, err) = twoball(&args);
    assert!(ok, "laws export {law}: {out}{err}");
    dir
}

/// The deck's reference speed and the speed range its header claims (m/s).
fn claimed(dir: &Path, code: &str) -> (f64, f64, f64) {
    let file = match code {
        "liggghts" => "liggghts.in",
        "lammps" => "lammps.in",
        _ => "yade.py",
    };
    let text = std::fs::read_to_string(dir.join(file)).unwrap();
    let num = |s: &str| s.trim().parse::<f64>().unwrap();
    let reference = text
        .lines()
        .find_map(|l| {
            l.strip_prefix("variable vr index ").or_else(|| {
                l.starts_with("vr = float(")
                    .then(|| l.split_once("else ").map(|(_, v)| v))
                    .flatten()
            })
        })
        .map(num)
        .unwrap();
    // "sized for LO <= VR <= HI m/s", narrowed by "Holds only for LO <= VR <= HI m/s".
    let range = |key: &str| {
        text.lines().find_map(|l| {
            let tail = l.split(key).nth(1)?;
            let mut it = tail.split("<=");
            let lo = num(it.next()?);
            let hi = num(it.nth(1)?.split("m/s").next()?);
            Some((lo, hi))
        })
    };
    let (lo, hi) = range("Holds only for ")
        .or_else(|| range("are sized for "))
        .unwrap();
    (reference, lo, hi)
}

/// Runs `code` on the deck in `dir` at `speed` through `twoball laws dem` and checks e,
/// δ_max and t_c against `laws run` within [`TOLERANCE`]; returns the row for the report.
fn check(dir: &Path, code: &str, speed: f64) -> String {
    let v = format!("{speed}");
    let (ok, out, err) = twoball(&[
        "laws",
        "dem",
        "--dir",
        dir.to_str().unwrap(),
        "--code",
        code,
        "--speed",
        &v,
        "--json",
    ]);
    assert!(
        ok,
        "laws dem {code} at {speed} in {}: {out}{err}",
        dir.display()
    );
    let j: serde_json::Value = serde_json::from_str(&out).unwrap();
    for key in ["e", "delta_max", "contact_duration"] {
        let d = j[format!("{key}_rel_diff")].as_f64().unwrap();
        assert!(
            d.abs() < TOLERANCE,
            "{} in {code} at v_r = {speed}: {key} differs by {d:+.3e} ({} vs {})",
            j["law"],
            j[format!("{key}_dem")],
            j[format!("{key}_twoball")]
        );
    }
    format!(
        "{} {code} {speed}: e {:+.1e}, delta_max {:+.1e}, t_c {:+.1e}",
        j["law"],
        j["e_rel_diff"].as_f64().unwrap(),
        j["delta_max_rel_diff"].as_f64().unwrap(),
        j["contact_duration_rel_diff"].as_f64().unwrap()
    )
}

/// The reference speed and two others inside the claimed range (its ends, pulled in by a
/// hundredth of the width).
fn three_speeds(dir: &Path, code: &str) -> [f64; 3] {
    let (reference, lo, hi) = claimed(dir, code);
    let w = hi - lo;
    [reference, lo + 0.01 * w, hi - 0.01 * w]
}

/// Every case of `code`: the decks in `dirs`, each at three speeds.
fn run_all(code: &str, dirs: &[PathBuf]) {
    for d in dirs {
        for v in three_speeds(d, code) {
            eprintln!("{}", check(d, code, v));
        }
    }
}

/// `twoball laws export --code CODE` of `law` fails with one line naming the law and why.
fn refused(code: &str, law: &str, extra: &[&str], why: &str) {
    let dir = tmpdir(&format!("refuse-{code}-{law}"));
    let mut args = vec![
        "laws",
        "export",
        "--law",
        law,
        "--code",
        code,
        "--out",
        dir.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    let (ok, out, err) = twoball(&args);
    assert!(!ok, "{code} {law} was exported: {out}");
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    assert!(err.contains(law) && err.contains(why), "{err}");
    assert!(!dir.join("law.json").exists());
}

#[test]
fn liggghts_runs_the_exported_decks_unedited() {
    if !tool_support::require(
        tool_support::dem_code("liggghts"),
        "liggghts_runs_the_exported_decks_unedited",
        "liggghts",
    ) {
        return;
    }
    let dirs = [
        fit("lig-dashpot", "linear-dashpot", &[]),
        fit("lig-dashpot0", "linear-dashpot", &["--param", "tension=0"]),
        fit("lig-hertzd", "hertz-damped", &[]),
        fit("lig-hertzd0", "hertz-damped", &["--param", "tension=0"]),
        fit("lig-walton", "walton-braun", &[]),
        export("lig-hertz", "hertz", &[]),
    ];
    run_all("liggghts", &dirs);
    // The hysteresis mapping holds at one speed: its header says where.
    let (r, lo, hi) = claimed(&dirs[4], "liggghts");
    assert!(lo < r && r < hi && (hi - lo) / r < 0.05, "{lo} {r} {hi}");
    refused("liggghts", "kuwabara-kono", &[], "hertz-damped");
    refused("liggghts", "thornton", &[], "thornton_ning");
}

#[test]
fn lammps_runs_the_exported_decks_unedited() {
    if !tool_support::require(
        tool_support::dem_code("lmp"),
        "lammps_runs_the_exported_decks_unedited",
        "lmp (lammps)",
    ) {
        return;
    }
    let dirs = [
        fit("lmp-dashpot", "linear-dashpot", &[]),
        fit("lmp-dashpot0", "linear-dashpot", &["--param", "tension=0"]),
        fit("lmp-hertzd", "hertz-damped", &[]),
        fit("lmp-hertzd0", "hertz-damped", &["--param", "tension=0"]),
        export("lmp-hertz", "hertz", &[]),
        export("lmp-kk", "kuwabara-kono", &["--param", "A=2e-6"]),
    ];
    run_all("lammps", &dirs);
    refused("lammps", "walton-braun", &[], "hysteretic");
    refused("lammps", "hertz-damped", &["--param", "e=0.05"], "tsuji");
}

#[test]
fn yade_runs_the_exported_decks_unedited() {
    if !tool_support::require(
        tool_support::dem_code("yade"),
        "yade_runs_the_exported_decks_unedited",
        "yade",
    ) {
        return;
    }
    let dirs = [
        fit("yade-dashpot0", "linear-dashpot", &["--param", "tension=0"]),
        fit("yade-hertzd0", "hertz-damped", &["--param", "tension=0"]),
        export("yade-hertz", "hertz", &[]),
    ];
    run_all("yade", &dirs);
    refused("yade", "hertz-damped", &[], "tension = 0");
    refused("yade", "walton-braun", &[], "linear-dashpot");
}

#[test]
fn mercurydpm_drivers_say_they_are_not_compiled_and_use_species_classes() {
    let dir = fit("mercury", "hertz-damped", &[]);
    let text = std::fs::read_to_string(dir.join("mercurydpm.cpp")).unwrap();
    assert!(text.starts_with("// NOT COMPILED HERE"), "{text}");
    assert!(text.contains("HertzianViscoelasticSpecies species;"));
    assert!(!text.contains("NormalSpecies"));
    // The header gives the fitted modulus, not only the pair's.
    let f: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("fit.json")).unwrap()).unwrap();
    let e_star = f["params"]["E_star"].as_f64().unwrap();
    assert!(text.contains(&format!("E_star = {e_star:.9e}")), "{text}");
}
