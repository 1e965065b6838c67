//! Scene files: the default scene, presets with overrides, `--set`, and every kind of bad
//! input giving a one-line error that names the key.

use std::path::Path;
use twoball::scene::{approach, Approach, Friction, MeshSettings, Override, Scene, DEFAULT_SCENE};

fn parse(text: &str, sets: &[&str]) -> twoball::Result<Scene> {
    let sets: Vec<Override> = sets
        .iter()
        .map(|s| Override::parse(s))
        .collect::<Result<_, _>>()?;
    Scene::from_toml(text, Path::new("."), &sets)
}

fn err(text: &str, sets: &[&str]) -> String {
    let e = parse(text, sets)
        .expect_err("expected an error")
        .to_string();
    assert!(!e.contains('\n'), "error must be one line: {e}");
    e
}

#[test]
fn default_scene_is_the_papers_figure_8_case() {
    let s = Scene::default();
    assert_eq!(s.ball1.material_name, "copper-fe");
    assert_eq!(s.ball1.material.youngs, 120e9);
    assert_eq!(s.ball1.material.rho, 7900.0);
    assert_eq!(s.ball1.diameter, 0.02);
    assert_eq!(s.ball1.velocity, [1.0, 0.0, 0.0]);
    assert_eq!(s.ball2.velocity, [-1.0, 0.0, 0.0]);
    assert!(s.identical_balls());
    assert_eq!(s.contact.friction, Friction::On);
    match approach(&s).unwrap() {
        Approach::Impact(t) => {
            assert_eq!(t.t_touch, 0.0);
            assert!((t.approach_speed - 2.0).abs() < 1e-12);
            assert_eq!(t.slip_speed, 0.0);
        }
        other => panic!("expected an impact, got {other:?}"),
    }
}

#[test]
fn set_overrides_a_preset_field_by_field() {
    let s = parse(
        DEFAULT_SCENE,
        &["ball1.material.yield=1e11", "ball2.velocity=[-2.5,0,0]"],
    )
    .unwrap();
    assert_eq!(s.ball1.material.yield_strength, 1e11);
    assert_eq!(
        s.ball1.material.youngs, 120e9,
        "other fields keep the preset's values"
    );
    assert_eq!(s.ball1.material_name, "copper-fe");
    assert_eq!(s.ball2.material.yield_strength, 100e6);
    assert_eq!(s.ball2.velocity, [-2.5, 0.0, 0.0]);
    // A bare word is a string: switch preset.
    let s = parse(DEFAULT_SCENE, &["ball2.material=steel"]).unwrap();
    assert_eq!(s.ball2.material.youngs, 210e9);
    assert!(!s.identical_balls());
}

#[test]
fn material_tables_custom_and_preset_based() {
    let text = r#"
[ball1]
material = { E = 200e9, nu = 0.3, rho = 7800, yield = 300e6, mu = 0.1 }
diameter = 0.01
velocity = [1, 0, 0]
[ball2]
material = { preset = "copper", tangent = 0 }
diameter = 0.03
velocity = [0, 0, 0]
[ball2.mesh]
size = 0.003
pole_size = 0.0005
[contact]
friction = 0.35
penalty_factor = 2
[solver]
element = "b-bar"
time_step_factor = 0.5
"#;
    let s = parse(text, &[]).unwrap();
    assert_eq!(s.ball1.material_name, "custom");
    assert_eq!(
        s.ball1.material.tangent, 2e9,
        "custom tangent defaults to E/100"
    );
    assert_eq!(s.ball1.material.mu_static, 0.1);
    assert_eq!(s.ball2.material.tangent, 0.0);
    assert_eq!(s.ball2.material.rho, 8500.0);
    assert_eq!(
        s.ball2.mesh,
        MeshSettings::Builtin {
            size: 0.003,
            pole_size: 0.0005
        }
    );
    assert_eq!(s.contact.friction, Friction::Coefficient(0.35));
    assert_eq!(s.friction_coefficients(), (0.35, 0.35));
    assert_eq!(s.contact.penalty_factor, 2.0);
}

#[test]
fn syntax_errors_name_line_and_column() {
    let e = err(
        "[ball1]\nmaterial = \"copper-fe\"\ndiameter = 0.02 0.03\n",
        &[],
    );
    assert!(e.contains("line 3"), "{e}");
}

#[test]
fn unknown_keys_are_named_with_their_full_path() {
    let e = err(
        &DEFAULT_SCENE.replace("velocity = [1.0", "velocty = [1.0"),
        &[],
    );
    assert!(e.contains("ball1.velocty"), "{e}");
    let e = err(DEFAULT_SCENE, &["ball1.material.yeild=1e9"]);
    assert!(e.contains("unknown key ball1.material.yeild"), "{e}");
    let e = err(DEFAULT_SCENE, &["solver.dt=1e-9"]);
    assert!(e.contains("solver.dt"), "{e}");
    let e = err(&format!("{DEFAULT_SCENE}\n[ball3]\ndiameter = 1\n"), &[]);
    assert!(e.contains("unknown key ball3"), "{e}");
}

#[test]
fn missing_required_keys_are_named() {
    let e = err(
        &DEFAULT_SCENE.replace("diameter = 0.02\nvelocity = [-1.0", "velocity = [-1.0"),
        &[],
    );
    assert!(e.contains("missing required key ball2.diameter"), "{e}");
    let e = err(
        "[ball1]\nmaterial = \"steel\"\ndiameter = 0.01\nvelocity = [1,0,0]\n",
        &[],
    );
    assert!(e.contains("missing required key ball2"), "{e}");
    let e = err(&DEFAULT_SCENE.replace("material = \"copper-fe\"\ndiameter = 0.02\nvelocity = [1.0", "material = { E = 1e9, nu = 0.3, rho = 1000, mu = 0 }\ndiameter = 0.02\nvelocity = [1.0"), &[]);
    assert!(
        e.contains("missing required key ball1.material.yield"),
        "{e}"
    );
}

#[test]
fn wrong_types_are_named() {
    let e = err(DEFAULT_SCENE, &["ball1.diameter=\"big\""]);
    assert!(
        e.contains("ball1.diameter") && e.contains("wrong type"),
        "{e}"
    );
    let e = err(DEFAULT_SCENE, &["ball1.velocity=[1,0]"]);
    assert!(
        e.contains("ball1.velocity") && e.contains("3 numbers"),
        "{e}"
    );
    let e = err(DEFAULT_SCENE, &["ball2.velocity=[1,\"a\",0]"]);
    assert!(e.contains("ball2.velocity"), "{e}");
    let e = err(DEFAULT_SCENE, &["solver=3"]);
    assert!(e.contains("solver") && e.contains("table"), "{e}");
    let e = err(DEFAULT_SCENE, &["solver.max_steps=1.5"]);
    assert!(e.contains("solver.max_steps"), "{e}");
}

#[test]
fn out_of_range_values_name_key_value_and_range() {
    for (set, key) in [
        ("ball1.diameter=-0.02", "ball1.diameter"),
        ("ball1.diameter=5", "ball1.diameter"),
        ("ball2.material.E=-1", "ball2.material.E"),
        ("ball2.material.nu=0.5", "ball2.material.nu"),
        ("ball1.material.yield=nan", "ball1.material.yield"),
        ("ball1.material=unobtainium", "ball1.material"),
        ("ball1.velocity=[1e9,0,0]", "ball1.velocity[0]"),
        ("ball1.velocity=[inf,0,0]", "ball1.velocity[0]"),
        ("contact.penalty_factor=0", "contact.penalty_factor"),
        ("contact.friction=-0.1", "contact.friction"),
        ("contact.friction=\"sometimes\"", "contact.friction"),
        ("solver.time_step_factor=1.5", "solver.time_step_factor"),
        ("solver.element=\"tet4\"", "solver.element"),
        ("ball1.mesh.size=0.5", "ball1.mesh.size"),
        ("ball1.mesh.pole_size=1e-9", "ball1.mesh.pole_size"),
        ("reduction.symmetry=\"maybe\"", "reduction.symmetry"),
        ("output.vtu_snapshots=-3", "output.vtu_snapshots"),
    ] {
        let e = err(DEFAULT_SCENE, &[set]);
        assert!(e.contains(&format!("invalid {key} =")), "{set}: {e}");
        assert!(e.contains("allowed"), "{set}: {e}");
    }
    // pole size above bulk size
    let e = err(
        DEFAULT_SCENE,
        &["ball1.mesh.size=0.001", "ball1.mesh.pole_size=0.002"],
    );
    assert!(e.contains("ball1.mesh.pole_size"), "{e}");
}

#[test]
fn bad_set_syntax_is_an_error_not_a_panic() {
    for s in [
        "noequals",
        "=3",
        "a..b=1",
        "ball1.velocity=[1,",
        "ball1.diameter=",
    ] {
        let e = Override::parse(s).unwrap_err().to_string();
        assert!(e.contains("--set"), "{e}");
    }
    let e = err(DEFAULT_SCENE, &["ball1.diameter.x=1"]);
    assert!(
        e.contains("ball1.diameter") && e.contains("not a table"),
        "{e}"
    );
}

#[test]
fn overlapping_balls_are_an_error_and_moving_apart_is_no_impact() {
    let placed = |p1: &str, p2: &str, v2: &str| {
        format!(
            "[ball1]\nmaterial = \"steel\"\ndiameter = 0.02\nvelocity = [1, 0, 0]\nposition = {p1}\n\
             [ball2]\nmaterial = \"steel\"\ndiameter = 0.02\nvelocity = {v2}\nposition = {p2}\n"
        )
    };
    let e = err(&placed("[0,0,0]", "[0.015,0,0]", "[-1,0,0]"), &[]);
    assert!(e.contains("ball2.position") && e.contains("overlap"), "{e}");
    // Apart and separating: parses, but no impact.
    let s = parse(&placed("[0,0,0]", "[0.03,0,0]", "[2,0,0]"), &[]).unwrap();
    assert!(matches!(approach(&s).unwrap(), Approach::NoImpact { .. }));
    // Touching and moving apart (the paper's +1/+1 m/s case with the right ball faster).
    let s = parse(DEFAULT_SCENE, &["ball2.velocity=[1.5,0,0]"]).unwrap();
    assert!(matches!(approach(&s).unwrap(), Approach::NoImpact { .. }));
    // Paper's +1.0/+1.0: side by side, no impact.
    let s = parse(DEFAULT_SCENE, &["ball2.velocity=[1.0,0,0]"]).unwrap();
    assert!(matches!(approach(&s).unwrap(), Approach::NoImpact { .. }));
    // Only one position: a named error.
    let e = err(DEFAULT_SCENE, &["ball1.position=[0,0,0]"]);
    assert!(e.contains("ball2.position"), "{e}");
}

#[test]
fn free_flight_reaches_touch_in_closed_form() {
    // Ball 2 starts 10 mm beyond touch, offset in y; closing at 2 m/s along x.
    let text = "[ball1]\nmaterial = \"steel\"\ndiameter = 0.02\nvelocity = [1, 0, 0]\nposition = [0, 0, 0]\n\
                [ball2]\nmaterial = \"steel\"\ndiameter = 0.02\nvelocity = [-1, 0, 0]\nposition = [0.03, 0.01, 0]\n";
    let s = parse(text, &[]).unwrap();
    let Approach::Impact(t) = approach(&s).unwrap() else {
        panic!("expected impact")
    };
    // At touch, centre distance = 0.02 with dy = 0.01: dx = sqrt(3)/100, so t = (0.03 - dx)/2.
    let dx = (0.02f64.powi(2) - 0.01f64.powi(2)).sqrt();
    assert!((t.t_touch - (0.03 - dx) / 2.0).abs() < 1e-15);
    // Normal along (dx, 0.01)/0.02; approach speed 2 * dx/0.02; slip 2 * 0.01/0.02.
    assert!((t.approach_speed - 2.0 * dx / 0.02).abs() < 1e-12);
    assert!((t.slip_speed - 1.0).abs() < 1e-12);
    // Local velocities: relative velocity (v1 - v2) along x is the approach speed.
    let rel = [
        t.v[0][0] - t.v[1][0],
        t.v[0][1] - t.v[1][1],
        t.v[0][2] - t.v[1][2],
    ];
    assert!(
        (rel[0] - t.approach_speed).abs() < 1e-12
            && (rel[1] - 1.0).abs() < 1e-12
            && rel[2].abs() < 1e-12
    );
}

#[test]
fn run_command_rejects_bad_input_with_one_line_and_exit_1() {
    let bin = env!("CARGO_BIN_EXE_twoball");
    for args in [
        vec!["run", "--set", "ball1.diameter=-1"],
        vec!["run", "--set", "nonsense"],
        vec!["run", "/nonexistent/scene.toml"],
        vec![
            "run",
            "--set",
            "ball1.position=[0,0,0]",
            "--set",
            "ball2.position=[0.001,0,0]",
        ],
    ] {
        let o = std::process::Command::new(bin)
            .args(&args)
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(1), "{args:?}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(
            err.starts_with("error: ") && err.trim_end().lines().count() == 1,
            "{args:?}: {err}"
        );
    }
}

/// A mesh setting that passes the scene's checks but not the mesh generator's is named from
/// the scene root, with the ball it belongs to (the generator itself knows only `size`).
#[test]
fn mesh_generator_errors_name_the_ball_and_key() {
    let bin = env!("CARGO_BIN_EXE_twoball");
    for (ball, field) in [("ball1", "ball1.mesh.size"), ("ball2", "ball2.mesh.size")] {
        // size below radius / 600: more than 2000 core cells along an edge. Half model (the
        // tangential speed), so that both balls' meshes are built.
        let o = std::process::Command::new(bin)
            .args([
                "run",
                "--set",
                "ball1.velocity=[1,0.5,0]",
                "--set",
                &format!("{ball}.mesh={{size=1e-5,pole_size=1e-5}}"),
            ])
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(1));
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(
            err.starts_with(&format!(
                "error: invalid {field} = 0.00001: allowed size >= radius"
            )),
            "{ball}: {err}"
        );
    }
}

#[test]
fn run_without_impact_reports_it_and_writes_no_nan() {
    let dir = std::env::temp_dir().join(format!("twoball-noimpact-{}", std::process::id()));
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_twoball"))
        .args([
            "run",
            "--set",
            "ball2.velocity=[1,0,0]",
            "--out",
            dir.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(String::from_utf8_lossy(&o.stdout).contains("no impact"));
    let json = std::fs::read_to_string(dir.join("results.json")).unwrap();
    let v: serde_json::Value = serde_json::from_str(&json).unwrap();
    assert_eq!(v["impact"], false);
    assert_eq!(v["reduction"], "none");
    assert_eq!(v["v1_after"][0], 1.0);
    assert!(!json.contains("NaN"));
    let csv = std::fs::read_to_string(dir.join("history.csv")).unwrap();
    assert!(csv.starts_with("t [s],delta [m]"));
    std::fs::remove_dir_all(&dir).unwrap();
}
