//! `twoball mesh ...` end to end: the acceptance commands of the mesh issue.

use std::process::{Command, Output};

fn twoball(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_twoball"))
        .args(args)
        .output()
        .unwrap()
}

fn tmp(name: &str) -> String {
    let d = std::env::temp_dir().join(format!("twoball-mesh-cli-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d.join(name).display().to_string()
}

fn check_json(file: &str) -> serde_json::Value {
    let out = twoball(&["mesh", "check", file, "--json"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

#[test]
fn ball_then_check_meets_the_acceptance_figures() {
    let b = tmp("b.msh");
    let out = twoball(&[
        "mesh",
        "ball",
        "--diameter",
        "0.02",
        "--size",
        "0.002",
        "-o",
        &b,
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let j = check_json(&b);
    let v = 4.0 / 3.0 * std::f64::consts::PI * 1e-6;
    let vol = j["volume"].as_f64().unwrap();
    assert!((vol - v).abs() < 0.005 * v, "{vol}");
    assert!(j["min_scaled_jacobian"].as_f64().unwrap() > 0.2);
    for key in [
        "nodes",
        "elements",
        "min_edge",
        "mean_scaled_jacobian",
        "max_aspect_ratio",
    ] {
        assert!(j[key].is_number(), "{key}");
    }

    let p = tmp("p.msh");
    let out = twoball(&[
        "mesh",
        "ball",
        "--diameter",
        "0.02",
        "--size",
        "0.002",
        "--pole-size",
        "0.0001",
        "-o",
        &p,
    ]);
    assert!(out.status.success());
    let j = check_json(&p);
    let e = j["min_edge"].as_f64().unwrap();
    assert!((e - 1e-4).abs() <= 0.2e-4, "{e}");
    let at: Vec<f64> = j["min_edge_at"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    assert!(at[0] > 0.008, "shortest edge at {at:?}, not at the pole");
    assert!(j["elements"].as_u64().unwrap() < 80_000);

    let q = tmp("q.vtu");
    let out = twoball(&[
        "mesh",
        "ball",
        "--diameter",
        "0.02",
        "--size",
        "0.004",
        "--cut",
        "quarter",
        "-o",
        &q,
    ]);
    assert!(out.status.success());
    assert!(std::fs::read(&q).unwrap().starts_with(b"<?xml"));
}

#[test]
fn bad_arguments_are_one_line_errors() {
    for (args, needle) in [
        (
            vec![
                "mesh",
                "ball",
                "--diameter=-1",
                "--size",
                "0.002",
                "-o",
                "x.msh",
            ],
            "diameter",
        ),
        (
            vec![
                "mesh",
                "ball",
                "--diameter",
                "0.02",
                "--size",
                "0.002",
                "--cut",
                "third",
                "-o",
                "x.msh",
            ],
            "cut",
        ),
        (
            vec![
                "mesh",
                "ball",
                "--diameter",
                "0.02",
                "--size",
                "0.002",
                "-o",
                "x.stl",
            ],
            ".msh or .vtu",
        ),
        (
            vec!["mesh", "check", "/nonexistent/file.msh"],
            "/nonexistent/file.msh",
        ),
        (
            vec![
                "mesh",
                "gmsh",
                "meshes/ball.geo",
                "--set",
                "D",
                "-o",
                "x.msh",
            ],
            "NAME=VALUE",
        ),
    ] {
        let out = twoball(&args);
        assert_eq!(out.status.code(), Some(1), "{args:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(
            err.starts_with("error: ") && err.contains(needle),
            "{args:?}: {err}"
        );
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    }
    assert!(!std::path::Path::new("x.msh").exists());
}
