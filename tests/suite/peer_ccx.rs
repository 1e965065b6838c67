//! The CalculiX peer (scripts/ccx_peer.py) on a tiny, coarse case: the default scene on the
//! coarsest ball mesh, C3D8 elements, a short end time. Needs `ccx` (Debian package
//! calculix-ccx) and python3 with numpy: a missing one fails the test under `CI=true` and is
//! skipped with a notice otherwise.
//!
//! What it checks does not depend on CalculiX being accurate on so coarse a mesh (it is not):
//! that the deck runs, that the extraction conserves momentum (equal balls leave with equal
//! and opposite centre-of-mass velocities, constant after separation), that the collision
//! quantities are physical, and that the analytical reference is the scene's.

use std::path::PathBuf;
use std::process::Command;

use crate::tool_support as tools;

fn script() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("scripts/ccx_peer.py")
}

#[test]
fn ccx_peer_tiny_default_scene() {
    let test = "ccx_peer_tiny_default_scene";
    if !tools::require(
        tools::ccx(),
        test,
        "ccx (CalculiX, Debian package calculix-ccx)",
    ) || !tools::require(
        tools::python("numpy, tomllib"),
        test,
        "python3 >= 3.11 with numpy",
    ) {
        return;
    }
    let dir = std::env::temp_dir().join(format!("twoball_peer_test_{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let json = dir.join("peer.json");
    let out = Command::new("python3")
        .arg(script())
        .args(["--twoball", env!("CARGO_BIN_EXE_twoball")])
        .args(["--size", "0.01", "--pole-size", "0.01", "--element", "C3D8"])
        .args(["--end-factor", "0.5", "--samples", "60"])
        .args(["--run-twoball", "--reference-e", "0.3190"])
        .args(["--twoball-variant", "full=reduction.symmetry=\"off\""])
        .arg("--work")
        .arg(&dir)
        .arg("--json")
        .arg(&json)
        .output()
        .expect("python3 runs");
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "script failed:\n{stdout}\n{stderr}");
    println!("{stdout}");
    let r: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let num = |path: &[&str]| -> f64 {
        let mut v = &r;
        for p in path {
            v = &v[*p];
        }
        v.as_f64()
            .unwrap_or_else(|| panic!("{path:?} is not a number: {v}"))
    };

    // The analytical reference is the scene's (the worked case of the three-phase model).
    assert!((num(&["analytic", "e"]) - 0.342645).abs() < 1e-5);
    assert!((num(&["analytic", "contact_duration_s"]) - 1.409233e-4).abs() < 1e-9);

    // Momentum: equal balls, equal and opposite speeds -> equal and opposite after, and the
    // centre-of-mass velocities are constant once the balls are apart.
    let v1 = num(&["calculix", "v1_after_m_per_s"]);
    let v2 = num(&["calculix", "v2_after_m_per_s"]);
    assert!(
        (v1 + v2).abs() < 1e-6 * v1.abs().max(1e-3),
        "v1+ {v1}, v2+ {v2}"
    );
    assert!(num(&["calculix", "v_after_spread_m_per_s"]) < 1e-4);

    // Physical collision quantities.
    let e = num(&["calculix", "e"]);
    assert!(e > 0.0 && e <= 1.0, "e = {e}");
    let dmax = num(&["calculix", "delta_max_m"]);
    assert!(dmax > 0.0 && dmax < 1e-3, "delta_max = {dmax}");
    let tc = num(&["calculix", "contact_duration_s"]);
    assert!(
        tc > 0.0 && tc < num(&["ccx", "end_time_s"]),
        "contact duration {tc}"
    );
    assert!(num(&["ccx", "wall_time_s"]) > 0.0);
    assert_eq!(r["ccx"]["element"], "C3D8");

    // One command runs both codes: twoball's default (automatic reductions: a quarter ball
    // here) and the full-model variant on the same mesh, each with its wall-time ratio.
    let variants = r["twoball_variants"].as_array().expect("twoball variants");
    assert_eq!(variants.len(), 2);
    assert_eq!(variants[0]["label"], "twoball");
    assert_eq!(variants[0]["model"], "quarter");
    assert_eq!(variants[1]["label"], "full");
    assert_eq!(variants[1]["model"], "full");
    for v in variants {
        let ratio = v["wall_time_ratio_ccx_over_twoball"].as_f64().unwrap();
        assert!(ratio > 0.0 && ratio.is_finite(), "ratio {ratio}");
        let e = v["e"].as_f64().unwrap();
        assert!(e > 0.0 && e <= 1.0, "twoball e = {e}");
    }
    // The reductions are exact for this scene: quarter and full model agree on e.
    let (eq, ef) = (
        variants[0]["e"].as_f64().unwrap(),
        variants[1]["e"].as_f64().unwrap(),
    );
    assert!((eq - ef).abs() < 0.01 * ef, "quarter e {eq}, full e {ef}");

    // The two codes on the same mesh. CalculiX's fully integrated C3D8 locks (too stiff in
    // bending and near-incompressible flow), so it approaches less than twoball's one-point
    // hex: on the documented 5 mm / 0.5 mm mesh δ_max 7.624e-5 against 8.543e-5 m (−10.8 %,
    // docs/performance.md, "CalculiX on the same mesh"). On this one-element-pole mesh the
    // gap is larger (measured ccx 2.316e-5 against 4.292e-5 m for the full model, −46 %);
    // e is not compared here because neither code resolves the plastic zone of a
    // one-element pole (ccx 0.62, twoball 0.98, converged 0.319):
    // `ccx_and_twoball_on_the_documented_mesh` compares e on the documented mesh.
    let (dc, df) = (
        num(&["calculix", "delta_max_m"]),
        variants[1]["delta_max_m"].as_f64().unwrap(),
    );
    assert!(
        (0.45..0.65).contains(&(dc / df)),
        "delta_max: ccx {dc:.4e}, twoball full {df:.4e} (ratio {:.3}, measured 0.54)",
        dc / df
    );
    assert!(num(&["error_in_e_vs_reference", "calculix"]).is_finite());
    assert!(num(&["error_in_e_vs_reference", "full"]).is_finite());

    // The deck: one element-face line per contact quad of each ball (16 on this mesh).
    let deck = std::fs::read_to_string(dir.join("peer.inp")).unwrap();
    let faces = deck
        .lines()
        .filter(|l| {
            l.rsplit(", ")
                .next()
                .is_some_and(|s| s.len() == 2 && s.starts_with('S'))
        })
        .count();
    let patch: u64 = r["mesh"]["contact_faces"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_u64().unwrap())
        .sum();
    assert_eq!(faces as u64, patch);
    assert!(patch > 0);
    let _ = std::fs::remove_dir_all(&dir);
}

/// Runs scripts/ccx_static_hertz.py with `args` and returns the words of its 20 µm table row
/// and the whole output, or None (with a SKIPPED line) when ccx, gmsh or numpy is missing.
fn static_hertz_20um(args: &[&str]) -> Option<(Vec<String>, String)> {
    let test = "ccx_static_hertz";
    if !tools::require(tools::ccx(), test, "ccx (CalculiX)")
        || !tools::require(tools::gmsh(), test, "gmsh")
        || !tools::require(tools::python("numpy"), test, "python3 with numpy")
    {
        return None;
    }
    let script = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("scripts/ccx_static_hertz.py");
    let out = Command::new("python3")
        .arg(script)
        .args(args)
        .output()
        .expect("python3 runs");
    let stdout = String::from_utf8_lossy(&out.stdout).to_string();
    assert!(
        out.status.success(),
        "script failed:\n{stdout}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    println!("{stdout}");
    // The table row: depth (µm), a/R, h_c, elements, δ_e, F, F_H, F/F_H − 1 (%), ...
    let row = stdout
        .lines()
        .find(|l| l.split_whitespace().next() == Some("20"))
        .unwrap_or_else(|| panic!("no 20 µm row in:\n{stdout}"))
        .split_whitespace()
        .map(str::to_string)
        .collect();
    Some((row, stdout))
}

/// Word `i` of a table row as a number (a trailing % or F dropped).
fn number(row: &[String], i: usize) -> f64 {
    row.get(i)
        .and_then(|w| w.trim_end_matches(['%', ',']).parse().ok())
        .unwrap_or_else(|| panic!("word {i} of {row:?} is not a number"))
}

/// The finite-ball check of the contact issue (scripts/ccx_static_hertz.py), coarsest mesh:
/// CalculiX, axisymmetric and static, finds an elastic hemisphere held at its equator
/// stiffer than Hertz's half-space law at a/R = 0.045: +2.39 % at h = a/10, +2.33 %
/// converged (a/40), against twoball's +2.68 % at a pole element of a/9
/// (verification/contact-penalty.md). A code that matched Hertz there, or a broken force
/// convention (CalculiX reports a 2-degree segment), would fall outside 1.8-3.0 %.
#[test]
fn ccx_finite_ball_is_stiffer_than_hertz() {
    let Some((row, _)) = static_hertz_20um(&["--depths", "20", "--per-a", "10"]) else {
        return;
    };
    let (a_over_r, excess) = (number(&row, 1), number(&row, 7));
    assert!((a_over_r - 0.0447).abs() < 1e-3, "a/R {a_over_r}");
    assert!(
        (1.8..3.0).contains(&excess),
        "finite ball against Hertz: {excess:+.3} % (expected about +2.4 %)"
    );
}

/// The impact's own finite-ball reference (scripts/ccx_static_hertz.py --support free),
/// coarsest mesh: the whole ball under the uniform body force that balances the contact,
/// approach at the centre of mass, is stiffer than Hertz by +4.06 % at a/R = 0.045 (+4.06 %
/// converged at a/20; verification/contact-penalty.md, "The free ball"), clearly more than the held
/// hemisphere's +2.39 %; and the secant steps must leave the north pole (which only fixes
/// the rigid-body mode) carrying under 1e-4 of the contact force. A body force applied to
/// the wrong set or with the wrong sign, or the approach taken at the pole instead of the
/// centre of mass, would fall outside 3.5-4.6 %.
#[test]
#[ignore = "a CalculiX static solve on a fine free ball: about 1.5 min"]
fn ccx_free_ball_is_stiffer_than_the_held_one() {
    let Some((row, out)) =
        static_hertz_20um(&["--support", "free", "--depths", "20", "--per-a", "10"])
    else {
        return;
    };
    let (a_over_r, excess) = (number(&row, 1), number(&row, 7));
    assert!((a_over_r - 0.0445).abs() < 1e-3, "a/R {a_over_r}");
    assert!(
        (3.5..4.6).contains(&excess),
        "free ball against Hertz: {excess:+.3} % (expected about +4.06 %)"
    );
    let at = row
        .iter()
        .position(|w| w == "north-pole")
        .unwrap_or_else(|| panic!("no north-pole force in:\n{out}"));
    let north = number(&row, at + 2);
    assert!(north.abs() < 1e-4, "north-pole force {north} F");
}

/// twoball and CalculiX on the mesh of docs/performance.md ("CalculiX on the same mesh": D/4
/// bulk, 0.5 mm pole; ccx 6400 C3D8, about 5-13 min on one thread, hence ignored): the
/// documented gap. ccx e 0.37278 (+16.9 % from the converged 0.3190: C3D8 locking), twoball's
/// quarter model 0.32264 (+1.14 %) and full model 0.32177 (+0.87 %); δ_max ccx 7.624e-5 m
/// against twoball's 8.543e-5 m (−10.8 %). Bands: ±2 % of e for ccx (its increments depend on
/// the time step), ±0.3 % for twoball, ±3 % for the δ_max gap.
/// `cargo test --release --test suite peer_ccx::ccx_and_twoball_on_the_documented_mesh -- --ignored --nocapture`
#[test]
#[ignore]
fn ccx_and_twoball_on_the_documented_mesh() {
    let test = "ccx_and_twoball_on_the_documented_mesh";
    if !tools::require(tools::ccx(), test, "ccx (CalculiX)")
        || !tools::require(
            tools::python("numpy, tomllib"),
            test,
            "python3 >= 3.11 with numpy",
        )
    {
        return;
    }
    let dir = std::env::temp_dir().join(format!("twoball_peer_doc_{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let json = dir.join("peer.json");
    let out = Command::new("python3")
        .arg(script())
        .args(["--twoball", env!("CARGO_BIN_EXE_twoball")])
        .args(["--size", "0.005", "--pole-size", "0.0005"])
        .args(["--run-twoball", "--reference-e", "0.3190"])
        .args(["--twoball-variant", "full=reduction.symmetry=\"off\""])
        .arg("--work")
        .arg(&dir)
        .arg("--json")
        .arg(&json)
        .output()
        .expect("python3 runs");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "script failed:\n{stdout}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    println!("{stdout}");
    let r: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let ccx_e = r["calculix"]["e"].as_f64().unwrap();
    let ccx_d = r["calculix"]["delta_max_m"].as_f64().unwrap();
    let v = r["twoball_variants"].as_array().unwrap();
    let (tq, tf) = (v[0]["e"].as_f64().unwrap(), v[1]["e"].as_f64().unwrap());
    let tq_d = v[0]["delta_max_m"].as_f64().unwrap();
    let within = |x: f64, want: f64, tol: f64| (x / want - 1.0).abs() < tol;
    assert!(within(ccx_e, 0.37278, 0.02), "ccx e {ccx_e}");
    assert!(within(tq, 0.32264, 0.003), "twoball quarter e {tq}");
    assert!(within(tf, 0.32177, 0.003), "twoball full e {tf}");
    let gap = ccx_d / tq_d - 1.0;
    assert!(
        (gap + 0.108).abs() < 0.03,
        "delta_max: ccx {ccx_d:.4e} against twoball {tq_d:.4e} ({:+.1} %)",
        100.0 * gap
    );
    let _ = std::fs::remove_dir_all(&dir);
}
