//! The suite's cases: Chung & Ooi's tests as the scenes of `verification/dem-benchmarks/`,
//! each oblique series at the speeds or spins its README lists.

use crate::error::{Error, Result};
use crate::scene::{approach, Approach, Override, Scene, Touch};
use crate::study::convergence::ladder::LadderPlan;
use crate::study::convergence::scene_estimate::{
    POLE_LADDER_MAX_REFINEMENTS, POLE_LADDER_TOLERANCE,
};
use std::path::Path;

/// The benchmark scenes, as committed under `verification/dem-benchmarks/`.
const SCENES: [(&str, &str); 15] = [
    (
        "test1-glass",
        include_str!("../../../../verification/dem-benchmarks/test1-glass.toml"),
    ),
    (
        "test1-limestone",
        include_str!("../../../../verification/dem-benchmarks/test1-limestone.toml"),
    ),
    (
        "test2-aluminium",
        include_str!("../../../../verification/dem-benchmarks/test2-aluminium.toml"),
    ),
    (
        "test2-magnesium",
        include_str!("../../../../verification/dem-benchmarks/test2-magnesium.toml"),
    ),
    (
        "test3-alumina",
        include_str!("../../../../verification/dem-benchmarks/test3-alumina.toml"),
    ),
    (
        "test3-cast-iron",
        include_str!("../../../../verification/dem-benchmarks/test3-cast-iron.toml"),
    ),
    (
        "test4-alumina",
        include_str!("../../../../verification/dem-benchmarks/test4-alumina.toml"),
    ),
    (
        "oblique-pair-alumina",
        include_str!("../../../../verification/dem-benchmarks/oblique-pair-alumina.toml"),
    ),
    (
        "test5-steel",
        include_str!("../../../../verification/dem-benchmarks/test5-steel.toml"),
    ),
    (
        "test5-polyethylene",
        include_str!("../../../../verification/dem-benchmarks/test5-polyethylene.toml"),
    ),
    (
        "test6-aluminium",
        include_str!("../../../../verification/dem-benchmarks/test6-aluminium.toml"),
    ),
    (
        "test6-nylon",
        include_str!("../../../../verification/dem-benchmarks/test6-nylon.toml"),
    ),
    (
        "test7-aluminium",
        include_str!("../../../../verification/dem-benchmarks/test7-aluminium.toml"),
    ),
    (
        "test7-copper",
        include_str!("../../../../verification/dem-benchmarks/test7-copper.toml"),
    ),
    (
        "test8-aluminium",
        include_str!("../../../../verification/dem-benchmarks/test8-aluminium.toml"),
    ),
];

/// The normal tests: 1 (two identical spheres), 2 and 3 (a sphere on a rigid plane), each
/// with whether it asks the damped laws for the restitution they were set to (test 3).
pub const NORMAL: [(&str, bool); 6] = [
    ("test1-glass", false),
    ("test1-limestone", false),
    ("test2-aluminium", false),
    ("test2-magnesium", false),
    ("test3-alumina", true),
    ("test3-cast-iron", true),
];

/// Test 4's angles of incidence, degrees.
pub const TEST4_ANGLES: [f64; 11] = [
    5.0, 10.0, 15.0, 20.0, 25.0, 30.0, 40.0, 50.0, 60.0, 70.0, 80.0,
];

/// The pair's angles of incidence, degrees.
pub const PAIR_ANGLES: [f64; 4] = [5.0, 10.0, 20.0, 30.0];

/// Resultant relative speed of test 4 and of the pair, m/s.
const OBLIQUE_SPEED: f64 = 3.9;

/// Test 5's normal speed, m/s.
const TEST5_NORMAL_SPEED: f64 = 5.0;

/// Relative tolerance on e of the normal tests' converged runs, -.
const NORMAL_TOLERANCE: f64 = 0.005;

/// The default relative tolerance of the oblique and spinning cases' pole ladders on e and
/// the tangential restitution, -.
pub const OBLIQUE_TOLERANCE: f64 = POLE_LADDER_TOLERANCE;

/// One oblique or spinning series: a scene, the values of the quantity it varies and the
/// `--set`s that put one value in the scene.
struct Series {
    /// The scene's name.
    scene: &'static str,
    /// What the value is, written into the case's name before it: "" (an angle of
    /// incidence in degrees), "vt" (a tangential speed, m/s) or "w" (a spin, rad/s).
    key: &'static str,
    /// The values run.
    values: &'static [f64],
    /// The scene's `--set`s for one value.
    sets: fn(f64) -> Vec<String>,
}

/// The oblique and spinning series, in the report's order.
const SERIES: [Series; 9] = [
    Series {
        scene: "test4-alumina",
        key: "",
        values: &TEST4_ANGLES,
        sets: |deg| vec![format!("ball1.velocity={}", velocity(OBLIQUE_SPEED, deg))],
    },
    Series {
        scene: "oblique-pair-alumina",
        key: "",
        values: &PAIR_ANGLES,
        sets: |deg| {
            vec![
                format!("ball1.velocity={}", velocity(OBLIQUE_SPEED / 2.0, deg)),
                format!("ball2.velocity={}", velocity(-OBLIQUE_SPEED / 2.0, deg)),
            ]
        },
    },
    // v_t/(μ v_n) = 0.3-10 at μ = 0.3: stick, micro-slip and gross sliding.
    Series {
        scene: "test5-steel",
        key: "vt",
        values: &[0.45, 0.9, 1.5, 2.25, 3.0, 4.5, 7.5, 15.0],
        sets: |vt| {
            vec![format!(
                "ball1.velocity=[{TEST5_NORMAL_SPEED:?}, {vt:?}, 0]"
            )]
        },
    },
    Series {
        scene: "test5-polyethylene",
        key: "vt",
        values: &[0.45, 1.5, 3.0, 7.5, 15.0],
        sets: |vt| {
            vec![format!(
                "ball1.velocity=[{TEST5_NORMAL_SPEED:?}, {vt:?}, 0]"
            )]
        },
    },
    // R ω / v_n = 0.1-7 at v_n = 0.2 m/s, R = 0.1 m.
    Series {
        scene: "test6-aluminium",
        key: "w",
        values: &[0.2, 0.8, 1.5, 3.0, 6.0, 14.0],
        sets: |w| vec![format!("ball1.angular_velocity=[0, 0, {w:?}]")],
    },
    Series {
        scene: "test6-nylon",
        key: "w",
        values: &[0.8, 3.0, 14.0],
        sets: |w| vec![format!("ball1.angular_velocity=[0, 0, {w:?}]")],
    },
    Series {
        scene: "test7-aluminium",
        key: "w",
        values: &[1.0, 3.0, 14.0],
        sets: |w| spins(w),
    },
    Series {
        scene: "test7-copper",
        key: "w",
        values: &[3.0, 14.0],
        sets: |w| spins(w),
    },
    // The 3D full model (the balls differ): about 3 min a case.
    Series {
        scene: "test8-aluminium",
        key: "w",
        values: &[3.0, 14.0],
        sets: |w| vec![format!("ball1.angular_velocity=[0, 0, {w:?}]")],
    },
];

/// Both balls' spin `w` (rad/s) about z, in the same sense, as `--set`s.
fn spins(w: f64) -> Vec<String> {
    vec![
        format!("ball1.angular_velocity=[0, 0, {w:?}]"),
        format!("ball2.angular_velocity=[0, 0, {w:?}]"),
    ]
}

/// One run of the suite: its name, the scene, how it is refined and, for test 4 and the
/// pair, its angle of incidence (degrees).
#[derive(Debug, Clone)]
pub struct DemCase {
    /// Scene name and, for an oblique or spinning case, `@`, the series' key and its value.
    pub name: String,
    /// The scene as run.
    pub scene: Scene,
    /// The mesh ladder.
    pub plan: LadderPlan,
    /// True for an oblique or spinning case (3D, beside Maw, Barber & Fawcett).
    pub oblique: bool,
    /// Angle of incidence, degrees (test 4 and the pair; `None` otherwise).
    pub angle: Option<f64>,
    /// True when the test asks the damped laws for the restitution they were set to (test 3).
    pub damping: bool,
    /// The balls at first touch (`None` if they never meet).
    pub touch: Option<Touch>,
}

/// The scene `name` of the suite with `sets` applied.
fn scene(name: &str, sets: &[String]) -> Result<Scene> {
    let text = SCENES
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(_, t)| *t)
        .ok_or_else(|| Error::Parse(format!("no benchmark scene {name}")))?;
    let sets = sets
        .iter()
        .map(|s| Override::parse(s))
        .collect::<Result<Vec<_>>>()?;
    Scene::from_toml(text, Path::new("."), &sets)
}

/// The velocity `[v cos θ, v sin θ, 0]` (m/s) of speed `v` (m/s) at `deg` degrees from the
/// normal, as a `--set` value.
fn velocity(v: f64, deg: f64) -> String {
    let t = deg.to_radians();
    format!("[{:?}, {:?}, 0]", v * t.cos(), v * t.sin())
}

/// Every case of the suite whose name starts with one of `only` (all when `only` is empty),
/// the oblique and spinning ones on the pole ladder to relative tolerance `oblique` (-, on e
/// and the tangential restitution). Fails only if a committed scene no longer reads (a defect
/// of the build).
pub fn cases(only: &[String], oblique: f64) -> Result<Vec<DemCase>> {
    let mut out = Vec::new();
    for (name, damping) in NORMAL {
        let scene = scene(name, &[])?;
        out.push(DemCase {
            name: name.into(),
            touch: touch(&scene)?,
            scene,
            plan: LadderPlan::Tolerance {
                tolerance: NORMAL_TOLERANCE,
                max_refinements: 2,
            },
            oblique: false,
            angle: None,
            damping,
        });
    }
    for s in &SERIES {
        for &v in s.values {
            let scene = scene(s.scene, &(s.sets)(v))?;
            out.push(DemCase {
                name: format!("{}@{}{v}", s.scene, s.key),
                touch: touch(&scene)?,
                scene,
                plan: LadderPlan::Tolerance {
                    tolerance: oblique,
                    max_refinements: POLE_LADDER_MAX_REFINEMENTS,
                },
                oblique: true,
                angle: s.key.is_empty().then_some(v),
                damping: false,
            });
        }
    }
    out.retain(|c| only.is_empty() || only.iter().any(|o| c.name.starts_with(o.as_str())));
    Ok(out)
}

/// The balls of `scene` at first touch, `None` if they never meet.
fn touch(scene: &Scene) -> Result<Option<Touch>> {
    Ok(match approach(scene)? {
        Approach::Impact(t) => Some(t),
        Approach::NoImpact { .. } => None,
    })
}

/// The names `--only` may start: each scene, and the oblique series' `NAME@KEY`.
pub fn prefixes() -> String {
    let mut names: Vec<String> = NORMAL.iter().map(|(n, _)| n.to_string()).collect();
    names.extend(SERIES.iter().map(|s| {
        let what = match s.key {
            "" => "ANGLE".to_string(),
            k => format!("{k}VALUE"),
        };
        format!("{}@{what}", s.scene)
    }));
    names.join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_suite_reads_every_committed_scene_at_its_speeds() {
        let all = cases(&[], OBLIQUE_TOLERANCE).unwrap();
        let oblique: usize = SERIES.iter().map(|s| s.values.len()).sum();
        assert_eq!(all.len(), NORMAL.len() + oblique);
        // Every scene is run.
        for (name, _) in SCENES {
            assert!(all.iter().any(|c| c.name.starts_with(name)), "{name}");
        }
        // Test 4 at 30 degrees: 3.9 m/s resultant, the normal component along +x.
        let c = all.iter().find(|c| c.name == "test4-alumina@30").unwrap();
        let v = c.scene.ball1.velocity;
        assert!((v[0].hypot(v[1]) - 3.9).abs() < 1e-12);
        assert!((v[1].atan2(v[0]).to_degrees() - 30.0).abs() < 1e-9);
        assert_eq!(c.angle, Some(30.0));
        // The pair: equal and opposite velocities, relative speed 3.9 m/s.
        let p = all
            .iter()
            .find(|c| c.name == "oblique-pair-alumina@10")
            .unwrap();
        let (a, b) = (p.scene.ball1.velocity, p.scene.ball2.velocity);
        assert!((a[0] + b[0]).abs() < 1e-12 && (a[1] + b[1]).abs() < 1e-12);
        assert!(((a[0] - b[0]).hypot(a[1] - b[1]) - 3.9).abs() < 1e-12);
        // Test 5 at v_t = 7.5 m/s; test 7's balls spin alike.
        let t5 = all.iter().find(|c| c.name == "test5-steel@vt7.5").unwrap();
        assert_eq!(t5.scene.ball1.velocity, [5.0, 7.5, 0.0]);
        assert_eq!(t5.angle, None);
        let t7 = all.iter().find(|c| c.name == "test7-copper@w3").unwrap();
        assert_eq!(t7.scene.ball1.angular_velocity, [0.0, 0.0, 3.0]);
        assert_eq!(t7.scene.ball2.angular_velocity, [0.0, 0.0, 3.0]);
        assert_eq!(
            cases(&["test2".into()], OBLIQUE_TOLERANCE).unwrap().len(),
            2
        );
        // Only test 3 asks the damped laws for their restitution; every case meets.
        let asks: Vec<_> = all.iter().filter(|c| c.damping).map(|c| &c.name).collect();
        assert_eq!(asks, ["test3-alumina", "test3-cast-iron"]);
        assert!(all.iter().all(|c| c.touch.is_some()));
        assert_eq!(
            cases(&["test6-aluminium@w".into()], OBLIQUE_TOLERANCE)
                .unwrap()
                .len(),
            6
        );
    }
}
