//! Bounded fuzzing of the scene parser: arbitrary text, mutated scene files and random
//! `--set` overrides never panic; every error is one line; every accepted scene is finite.

use proptest::prelude::*;
use std::path::Path;
use twoball::scene::{approach, Approach, Override, Scene, DEFAULT_SCENE};

fn config(cases: u32) -> ProptestConfig {
    ProptestConfig {
        cases,
        max_shrink_iters: 200,
        ..ProptestConfig::default()
    }
}

fn check(result: twoball::Result<Scene>) {
    match result {
        Err(e) => {
            let msg = e.to_string();
            assert!(
                !msg.is_empty() && !msg.contains('\n'),
                "error must be one non-empty line: {msg:?}"
            );
        }
        Ok(s) => {
            for b in [&s.ball1, &s.ball2] {
                assert!(b.diameter.is_finite() && b.diameter > 0.0);
                assert!(b
                    .velocity
                    .iter()
                    .chain(&b.angular_velocity)
                    .all(|v| v.is_finite()));
            }
            if let Ok(Approach::Impact(t)) = approach(&s) {
                assert!(t.t_touch.is_finite() && t.t_touch >= 0.0);
                assert!(t.approach_speed > 0.0 && t.approach_speed.is_finite());
                assert!(t.v.iter().chain(&t.w).flatten().all(|v| v.is_finite()));
            }
        }
    }
}

const PATHS: [&str; 24] = [
    "ball1.material",
    "ball1.material.E",
    "ball1.material.nu",
    "ball1.material.yield",
    "ball1.material.preset",
    "ball2.material.tangent",
    "ball2.material.mu",
    "ball1.diameter",
    "ball2.diameter",
    "ball1.velocity",
    "ball2.velocity",
    "ball1.angular_velocity",
    "ball1.position",
    "ball2.position",
    "ball1.mesh.size",
    "ball2.mesh.pole_size",
    "ball1.mesh.file",
    "contact.friction",
    "contact.penalty_factor",
    "solver.time_step_factor",
    "solver.max_steps",
    "output.vtu_snapshots",
    "reduction.symmetry",
    "ball1.nonsense",
];

fn value() -> impl Strategy<Value = String> {
    prop_oneof![
        any::<f64>().prop_map(|x| format!("{x:e}")),
        (-1e3f64..1e3).prop_map(|x| format!("{x}")),
        any::<i64>().prop_map(|x| x.to_string()),
        Just("nan".to_string()),
        Just("-inf".to_string()),
        Just("\"steel\"".to_string()),
        Just("\"off\"".to_string()),
        Just("true".to_string()),
        "[a-z ]{0,8}".prop_map(|s| s),
        prop::collection::vec(-50.0f64..50.0, 0..5).prop_map(|v| format!("{v:?}")),
        Just("{ preset = \"rubber\", E = 1e3 }".to_string()),
        Just("[[1], 2, \"x\"]".to_string()),
    ]
}

proptest! {
    #![proptest_config(config(400))]

    #[test]
    fn arbitrary_text_never_panics(text in ".{0,300}") {
        check(Scene::from_toml(&text, Path::new("."), &[]));
    }

    #[test]
    fn mutated_default_scene_never_panics(
        cuts in prop::collection::vec((0usize..400, 0usize..6, "[\\[\\]{}=\".,0-9a-z \n-]{0,4}"), 1..4)
    ) {
        let mut text: Vec<char> = DEFAULT_SCENE.chars().collect();
        for (at, len, insert) in cuts {
            let at = at.min(text.len());
            let end = (at + len).min(text.len());
            text.splice(at..end, insert.chars());
        }
        let text: String = text.into_iter().collect();
        check(Scene::from_toml(&text, Path::new("."), &[]));
    }

    #[test]
    fn random_overrides_never_panic(sets in prop::collection::vec((0usize..PATHS.len(), value()), 1..4)) {
        let parsed: Result<Vec<Override>, _> =
            sets.iter().map(|(p, v)| Override::parse(&format!("{}={v}", PATHS[*p]))).collect();
        match parsed {
            Ok(sets) => check(Scene::from_toml(DEFAULT_SCENE, Path::new("."), &sets)),
            Err(e) => prop_assert!(!e.to_string().contains('\n')),
        }
    }

    #[test]
    fn random_geometry_never_panics(
        p2 in prop::array::uniform3(-0.1f64..0.1),
        v1 in prop::array::uniform3(-20.0f64..20.0),
        v2 in prop::array::uniform3(-20.0f64..20.0),
        w1 in prop::array::uniform3(-1e3f64..1e3),
        d in (0.001f64..0.05, 0.001f64..0.05),
    ) {
        let text = format!(
            "[ball1]\nmaterial = \"steel\"\ndiameter = {}\nvelocity = {v1:?}\nangular_velocity = {w1:?}\nposition = [0, 0, 0]\n\
             [ball2]\nmaterial = \"rubber\"\ndiameter = {}\nvelocity = {v2:?}\nposition = {p2:?}\n", d.0, d.1);
        check(Scene::from_toml(&text, Path::new("."), &[]));
    }
}
