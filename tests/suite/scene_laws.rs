//! Issue 27 item 3: a scene's `[laws] compare` gives each law's e, δ_max, t_c and peak force
//! for the scene's balls and speeds, equal to `twoball laws run` on the same input; bad law
//! names and parameters are one-line errors naming the field and the allowed values.

use std::path::Path;
use twoball::scene::{approach, Approach, Scene};
use twoball::study::run::law_compare::{compare_laws, law_table};

const BALLS: &str = r#"
[ball1]
material = "copper-fe"
diameter = 0.02
velocity = [1.5, 0.0, 0.0]
[ball2]
material = "copper-fe"
diameter = 0.02
velocity = [-1.5, 0.0, 0.0]
"#;

fn scene(laws: &str) -> twoball::Result<Scene> {
    Scene::from_toml(&format!("{BALLS}{laws}"), Path::new("."), &[])
}

fn laws_run(args: &[&str]) -> serde_json::Value {
    let mut all = vec![
        "twoball", "laws", "run", "--v1", "1.5", "--v2", "-1.5", "--json",
    ];
    all.extend_from_slice(args);
    twoball::cli::json_from(all).unwrap()
}

#[test]
fn two_laws_equal_laws_run_on_the_same_balls() {
    let s =
        scene("[laws]\ncompare = [\"hertz\", \"thornton\"]\n[laws.params.thornton]\np_y = 5e8\n")
            .unwrap();
    let Approach::Impact(touch) = approach(&s).unwrap() else {
        panic!("no impact")
    };
    let out = compare_laws(&s, &touch).unwrap();
    assert_eq!(out.len(), 2);
    let expected = [
        ("hertz", laws_run(&["--law", "hertz"])),
        (
            "thornton",
            laws_run(&["--law", "thornton", "--param", "p_y=5e8"]),
        ),
    ];
    for (o, (name, j)) in out.iter().zip(&expected) {
        assert_eq!(o.law, *name);
        for (got, key) in [
            (o.e, "e"),
            (o.delta_max, "delta_max"),
            (o.contact_duration, "t3"),
            (o.peak_force, "peak_force"),
        ] {
            let want = j[key].as_f64().unwrap();
            assert!(
                (got - want).abs() <= 1e-12 * want.abs(),
                "{name} {key}: {got} vs laws run {want}"
            );
        }
    }
    assert_eq!(out[1].params["p_y"], 5e8);
    // The two laws differ (Hertz is elastic) and the summary prints both.
    assert!((out[0].e - 1.0).abs() < 1e-8 && out[1].e < 0.9);
    let table = law_table(&out);
    assert!(
        table.contains("hertz") && table.contains("thornton"),
        "{table}"
    );
    // results.json: the report's `laws` key, one object per law with the documented keys.
    let json = serde_json::to_value(&out).unwrap();
    for k in [
        "law",
        "tangential_law",
        "params",
        "e",
        "delta_max",
        "contact_duration",
        "peak_force",
    ] {
        assert!(json[1].get(k).is_some(), "missing key {k}");
    }
}

#[test]
fn bad_names_and_parameters_are_one_line_errors() {
    let msg = |laws: &str| {
        let m = scene(laws).unwrap_err().to_string();
        assert_eq!(m.lines().count(), 1, "{m}");
        m
    };
    let m = msg("[laws]\ncompare = [\"hertz\", \"hertzz\"]\n");
    assert!(
        m.contains("laws.compare[1]") && m.contains("hertzz") && m.contains("thornton"),
        "{m}"
    );
    let m = msg("[laws]\ncompare = [\"thornton\"]\n[laws.params.thornton]\npy = 5e8\n");
    assert!(
        m.contains("laws.params.thornton.py") && m.contains("p_y"),
        "{m}"
    );
    let m = msg("[laws]\ncompare = [\"hertz\"]\n[laws.params.thornton]\np_y = 5e8\n");
    assert!(m.contains("laws.params.thornton"), "{m}");
    let m = msg("[laws]\ncompare = [\"hertz\"]\ntangential = \"stick\"\n");
    assert!(
        m.contains("laws.tangential") && m.contains("thornton-yin"),
        "{m}"
    );
    let m = msg("[laws]\ncompar = [\"hertz\"]\n");
    assert!(m.contains("laws.compar") && m.contains("compare"), "{m}");
    // A value outside the parameter's range is caught when the laws are built.
    let s = scene("[laws]\ncompare = [\"thornton\"]\n[laws.params.thornton]\np_y = -1\n").unwrap();
    let Approach::Impact(touch) = approach(&s).unwrap() else {
        panic!("no impact")
    };
    let m = compare_laws(&s, &touch).unwrap_err().to_string();
    assert!(
        m.contains("laws.params.thornton.p_y") && m.contains("-1"),
        "{m}"
    );
    assert_eq!(m.lines().count(), 1);
}

#[test]
fn a_wall_scene_compares_the_laws_against_the_rigid_half_space() {
    // The three-phase law on the seam against a rigid wall equals the analytical model's rigid
    // wall (`twoball analytic --wall rigid`); a mirror-image ball would give the pair's e.
    let text = "[ball1]\nmaterial = \"copper-fe\"\ndiameter = 0.02\nvelocity = [1.0, 0.0, 0.0]\n\
                [wall]\nkind = \"rigid\"\n[laws]\ncompare = [\"li-yang-shi\"]\n";
    let s = Scene::from_toml(text, Path::new("."), &[]).unwrap();
    let Approach::Impact(touch) = approach(&s).unwrap() else {
        panic!("no impact")
    };
    let out = compare_laws(&s, &touch).unwrap();
    let wall = twoball::cli::json_from([
        "twoball", "analytic", "--wall", "rigid", "--v1", "1", "--json",
    ])
    .unwrap();
    let e = wall["e"].as_f64().unwrap();
    assert!((out[0].e - e).abs() < 1e-6 * e, "{} vs {e}", out[0].e);
    let pair = twoball::cli::json_from([
        "twoball",
        "laws",
        "run",
        "--law",
        "li-yang-shi",
        "--v1",
        "1",
        "--v2",
        "0",
        "--json",
    ])
    .unwrap()["e"]
        .as_f64()
        .unwrap();
    assert!(
        (out[0].e - pair).abs() > 1e-3,
        "the wall is not a ball: {pair}"
    );
}
