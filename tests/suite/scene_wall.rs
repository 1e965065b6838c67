//! A ball against a rigid wall (`[wall]`, issue 26 item 4): the scene and its one-line errors,
//! the method of images (a rigid wall is the symmetry plane of the ball and its mirror image,
//! so the wall at twice the penalty factor is the identical pair to the last digit), the
//! elastic impact against Hertz for a ball on a rigid half-space, the meridian section
//! against the quarter model for a plastic ball, and the two-ball runs' results.json keys.

use crate::contact_support::hertz;
use crate::run_support;

use std::path::Path;
use twoball::analytic::hertz::HertzPair;
use twoball::analytic::{collide, Body};
use twoball::error::Result;
use twoball::scene::{approach, Approach, Override, Scene, Touch, DEFAULT_SCENE, WALL_SCENE};
use twoball::study::records::outcome::ball_inertia;
use twoball::study::run::scene::{run_scene, RunReport};
use twoball::study::run::simulate::{choose_reduction, Reduction, RunOptions};

fn parse(text: &str, sets: &[&str]) -> Result<Scene> {
    let sets: Vec<Override> = sets.iter().map(|s| Override::parse(s).unwrap()).collect();
    Scene::from_toml(text, Path::new("."), &sets)
}

fn wall(sets: &[&str]) -> Scene {
    parse(WALL_SCENE, sets).unwrap()
}

fn touch(s: &Scene) -> Touch {
    match approach(s).unwrap() {
        Approach::Impact(t) => t,
        Approach::NoImpact { reason } => panic!("no impact: {reason}"),
    }
}

fn run(s: &Scene) -> RunReport {
    run_scene(
        s,
        &RunOptions {
            history_rows: 200,
            ..RunOptions::default()
        },
    )
    .unwrap()
}

fn peak_force(r: &RunReport) -> f64 {
    let sim = r.fe.as_ref().unwrap();
    sim.history
        .iter()
        .map(|h| h.normal_force)
        .fold(0.0, f64::max)
}

const AXI: &str = "reduction.symmetry=\"axisymmetric\"";
/// The section's plane as the 3D model's penalty (the default is kinematic).
const PENALTY_PLANE: &str = "contact.plane=\"penalty\"";
/// The cheapest exact 3D model: the quarter ball on the wall.
const QUARTER: &str = "reduction.symmetry=\"auto-3d\"";

#[test]
fn a_wall_scene_is_ball_one_and_its_mirror_image() {
    let s = wall(&[]);
    let w = s.wall.unwrap();
    assert_eq!(w.normal, [-1.0, 0.0, 0.0]);
    assert_eq!(s.ball1.position, Some([-0.01, 0.0, 0.0]));
    assert_eq!(s.ball2.position, Some([0.01, 0.0, 0.0]));
    assert_eq!(s.ball2.velocity, [-1.0, 0.0, 0.0]);
    assert!(s.identical_balls());
    let t = touch(&s);
    assert_eq!(t.t_touch, 0.0);
    assert_eq!(t.approach_speed, 2.0);
    // The committed scene file is the built-in wall scene.
    let file = include_str!("../../verification/wall.toml");
    assert_eq!(parse(file, &[]).unwrap(), wall(&[]));
    // A wall of any orientation, the ball placed away from it: touch after free flight.
    let s = wall(&[
        "wall.normal=[0, -2, 0]",
        "wall.position=[0, 0.1, 0]",
        "ball1.position=[0, 0.05, 0]",
        "ball1.velocity=[0, 2, 0]",
    ]);
    assert_eq!(s.wall.unwrap().normal, [0.0, -1.0, 0.0]);
    let c2 = s.ball2.position.unwrap();
    assert!((c2[1] - 0.15).abs() < 1e-15 && c2[0] == 0.0 && c2[2] == 0.0);
    assert_eq!(s.ball2.velocity, [0.0, -2.0, 0.0]);
    let t = touch(&s);
    assert!((t.t_touch - 0.02).abs() < 1e-12, "{}", t.t_touch);
    let n = t.frame.axes[0];
    assert!(n[0].abs() < 1e-15 && (n[1] - 1.0).abs() < 1e-15 && n[2].abs() < 1e-15);
    // The models: the section automatically and when asked, the quarter ball as the 3D
    // model (and with the simulated free flight), no half or full model.
    let pick = |sets: &[&str]| {
        let s = wall(sets);
        choose_reduction(&s, &touch(&s))
    };
    let (r, why) = pick(&[]).unwrap();
    assert_eq!(r, Reduction::Axisymmetric);
    assert!(
        why.contains("rigid wall") && why.contains("kinematic"),
        "{why}"
    );
    let (r, why) = pick(&[AXI]).unwrap();
    assert_eq!(r, Reduction::Axisymmetric);
    assert!(why.contains("rigid wall"), "{why}");
    let (r, why) = pick(&[QUARTER]).unwrap();
    assert_eq!(r, Reduction::Quarter);
    assert!(why.contains("rigid wall"), "{why}");
    let flight = "reduction.start_at_touch=\"off\"";
    assert_eq!(pick(&[flight]).unwrap().0, Reduction::Quarter);
    assert_eq!(
        pick(&["reduction.symmetry=\"quarter\""]).unwrap().0,
        Reduction::Quarter
    );
    for m in ["half", "off"] {
        let e = pick(&[&format!("reduction.symmetry=\"{m}\"")])
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("reduction.symmetry") && e.contains("wall"),
            "{e}"
        );
    }
    // The wall is written with the scene; a two-ball scene has no `wall` key.
    let json = serde_json::to_value(wall(&[])).unwrap();
    assert_eq!(json["wall"]["kind"], "rigid");
    let json = serde_json::to_value(parse(DEFAULT_SCENE, &[]).unwrap()).unwrap();
    assert!(json.get("wall").is_none());
}

#[test]
fn bad_wall_scenes_get_one_line_errors_naming_the_field() {
    let two = format!("{WALL_SCENE}\n[ball2]\nmaterial = \"steel\"\ndiameter = 0.02\nvelocity = [-1.0, 0.0, 0.0]\n");
    let cases: Vec<(String, Vec<&str>, &str)> = vec![
        (two, vec![], "ball2 is given with [wall]"),
        (
            WALL_SCENE.into(),
            vec!["ball2.velocity=[-1,0,0]"],
            "ball2 is given with [wall]",
        ),
        (WALL_SCENE.into(), vec!["wall.kind=soft"], "wall.kind"),
        (WALL_SCENE.into(), vec!["wall.kind=3"], "wall.kind"),
        (
            WALL_SCENE.into(),
            vec!["wall.normal=[0,0,0]"],
            "wall.normal",
        ),
        (
            WALL_SCENE.into(),
            vec!["wall.side=1"],
            "unknown key wall.side",
        ),
        (
            WALL_SCENE.into(),
            vec!["ball1.velocity=[-1,0,0]"],
            "towards the wall",
        ),
        (
            WALL_SCENE.into(),
            vec!["ball1.position=[-0.005,0,0]"],
            "ball1.position",
        ),
    ];
    for (text, sets, want) in cases {
        let e = parse(&text, &sets).unwrap_err().to_string();
        assert!(e.contains(want), "{sets:?}: {e}");
        assert!(!e.contains('\n'), "{sets:?}: more than one line: {e}");
    }
    // A ball meshed from a file: the wall models cut the built-in ball by symmetry.
    let s = wall(&["ball1.mesh.file=\"Cargo.toml\""]);
    let e = choose_reduction(&s, &touch(&s)).unwrap_err().to_string();
    assert!(e.contains("ball1.mesh.file") && !e.contains('\n'), "{e}");
    // A wall without `kind`.
    let e = parse("[ball1]\nmaterial = \"steel\"\ndiameter = 0.02\nvelocity = [1.0, 0.0, 0.0]\n[wall]\nnormal = [-1.0, 0.0, 0.0]\n", &[])
        .unwrap_err()
        .to_string();
    assert!(e.contains("wall.kind"), "{e}");
}

/// The method of images: a rigid frictionless wall acts on a ball as the ball's mirror image
/// does, so the wall at twice the penalty factor (the pair's plane carries 2 FKN) runs the
/// identical pair's model: the same e, contact duration and force, half the pair's approach
/// and energies, and ball 2 (the wall) at rest. At its own factor the wall is softer.
#[test]
fn a_rigid_wall_at_twice_the_penalty_is_the_mirror_pair() {
    for model in [&[QUARTER][..], &[AXI, PENALTY_PLANE][..]] {
        let coarse = |b: &str| format!("{b}.mesh={{size=0.004,pole_size=0.0004}}");
        let (c1, c2) = (coarse("ball1"), coarse("ball2"));
        let mut pair_sets = vec![c1.as_str(), c2.as_str()];
        pair_sets.extend(model);
        let pair = run(&parse(DEFAULT_SCENE, &pair_sets).unwrap());
        let mut wall_sets = vec![c1.as_str(), "contact.penalty_factor=2"];
        wall_sets.extend(model);
        let w = run(&wall(&wall_sets));
        assert_eq!(w.reduction, pair.reduction);
        let rel = |a: f64, b: f64| (a / b - 1.0).abs();
        assert!(rel(w.e.unwrap(), pair.e.unwrap()) < 1e-9, "{model:?}");
        assert!(rel(2.0 * w.delta_max, pair.delta_max) < 1e-9, "{model:?}");
        assert!(
            rel(w.contact_duration, pair.contact_duration) < 1e-9,
            "{model:?}"
        );
        assert!(rel(peak_force(&w), peak_force(&pair)) < 1e-9, "{model:?}");
        let (fw, fp) = (w.fe.as_ref().unwrap(), pair.fe.as_ref().unwrap());
        let total = |r: &twoball::study::run::simulate::Simulation| r.history[0].total;
        assert!(rel(2.0 * total(fw), total(fp)) < 1e-9, "{model:?}");
        assert_eq!(w.v2_after, [0.0; 3]);
        assert!((w.v1_after[0] + w.e.unwrap()).abs() < 1e-12);
        // The analytical model's rigid wall is its pair's image too.
        let (aw, ap) = (w.analytic.unwrap(), pair.analytic.unwrap());
        assert!(rel(aw.e, ap.e) < 1e-9 && rel(2.0 * aw.delta_max, ap.delta_max) < 1e-9);
        assert_eq!(aw.v2_after, [0.0; 3]);
        // ... and `twoball analytic --wall rigid` (the rigid half-space at rest).
        let b = Body::ball(wall(&[]).ball1.material, 0.02, "ball1").unwrap();
        let c = collide(&b, &Body::RigidWall, [1.0, 0.0], [0.0, 0.0]).unwrap();
        let n = c.normal.unwrap();
        assert!(rel(aw.e, n.e) < 1e-12 && rel(aw.delta_max, n.delta2) < 1e-12);
        assert!(rel(aw.contact_duration, n.t3) < 1e-12);
        // At its own penalty factor the wall's springs are half the pair's plane's.
        // It differs from the pair in δ_max or in e (on the section δ_max by 8.9e-5, e by 0.6 %).
        let soft = run(&wall(&[&[c1.as_str()][..], model].concat()));
        assert!(
            rel(2.0 * soft.delta_max, pair.delta_max) > 1e-4
                || rel(soft.e.unwrap(), pair.e.unwrap()) > 1e-3,
            "{model:?}: the wall's penalty is not its own ({} against {}; e {} against {})",
            2.0 * soft.delta_max,
            pair.delta_max,
            soft.e.unwrap(),
            pair.e.unwrap()
        );
    }
    // The section's default kinematic plane has no penalty: the wall at its own factor is
    // the pair's image.
    let coarse = |b: &str| format!("{b}.mesh={{size=0.004,pole_size=0.0004}}");
    let (c1, c2) = (coarse("ball1"), coarse("ball2"));
    let pair = run(&parse(DEFAULT_SCENE, &[c1.as_str(), c2.as_str(), AXI]).unwrap());
    let w = run(&wall(&[c1.as_str(), AXI]));
    let rel = |a: f64, b: f64| (a / b - 1.0).abs();
    assert!(rel(w.e.unwrap(), pair.e.unwrap()) < 1e-9);
    assert!(rel(2.0 * w.delta_max, pair.delta_max) < 1e-9);
}

/// An elastic ball on a rigid half-space (yield out of reach), 0.1 m/s, on the section with
/// its default mesh (pole from the contact radius, a/R = 0.019): Hertz with E* = E/(1 − ν²),
/// R* = R, m* = m within 1 % in δ_max and t_c, and the finite-ball reference of
/// verification/contact-penalty.md (CalculiX's free ball on a rigid plane) within 1 %.
#[test]
fn an_elastic_ball_on_a_rigid_wall_matches_hertz() {
    let v = 0.1;
    let s = wall(&[AXI, "ball1.velocity=[0.1,0,0]", "ball1.material.yield=1e11"]);
    let r = run(&s);
    let m = &s.ball1.material;
    let radius = s.ball1.diameter / 2.0;
    let mass = ball_inertia(m.rho, s.ball1.diameter).0;
    let h = HertzPair::new(m.youngs / (1.0 - m.nu * m.nu), radius, mass);
    let (dh, th) = (h.max_approach(v), h.contact_duration(v));
    assert!(
        (dh / radius).sqrt() < 0.02,
        "a/R = {}",
        (dh / radius).sqrt()
    );
    // The reference is written for the image pair: relative speed 2v, approach 2δ.
    let (d2, tf, _) = hertz::finite_ball_reference(2.0 * v, radius, 2.0 * dh, h.peak_force(v));
    let rel = |a: f64, b: f64| a / b - 1.0;
    let (ed, et) = (rel(r.delta_max, dh), rel(r.contact_duration, th));
    let (fd, ft) = (rel(r.delta_max, d2 / 2.0), rel(r.contact_duration, tf));
    println!(
        "wall 0.1 m/s: δ_max {:.4e} m ({:+.2} % Hertz, {:+.2} % finite ball), t_c {:.4e} s ({:+.2} %, {:+.2} %), e {:.5}, energy error {:.2e}",
        r.delta_max,
        100.0 * ed,
        100.0 * fd,
        r.contact_duration,
        100.0 * et,
        100.0 * ft,
        r.e.unwrap(),
        r.energy_error
    );
    assert!(
        ed.abs() < 0.01 && et.abs() < 0.01,
        "Hertz: {ed:+.4} {et:+.4}"
    );
    assert!(
        fd.abs() < 0.01 && ft.abs() < 0.01,
        "finite: {fd:+.4} {ft:+.4}"
    );
    assert!(r.e.unwrap() >= 0.995, "e = {}", r.e.unwrap());
    assert!(r.energy_error < 1e-3, "{}", r.energy_error);
    // The analytical model beside it is Hertz's elastic impact on the wall.
    let an = r.analytic.unwrap();
    assert!(rel(an.delta_max, dh).abs() < 1e-3, "{}", an.delta_max);
}

/// A plastic copper-fe ball (D = 20 mm, 1 m/s) on a rigid wall: the meridian section (pole
/// D/200, bulk D/40, step factor 0.6) and the 3D quarter model (its default mesh, pole
/// D/200) agree within 0.5 % in e and δ_max, each with an energy error below 0.1 %. (The
/// section's e moves by about 2 % with its bulk size at D/6-D/20, docs/status.md; D/40 is
/// the finest of that ladder. Its subcycled energy error is 1.1e-3 at step factor 0.9.) Both
/// use the penalty plane, the same contact model; the section's default kinematic plane
/// gives e 0.31954 (−0.72 %), δ_max +0.36 %: no penalty compliance, on a single mesh's phase.
#[test]
fn plastic_ball_on_a_wall_section_and_quarter_agree() {
    let quarter = run(&wall(&[QUARTER]));
    let section = run(&wall(&[
        AXI,
        PENALTY_PLANE,
        "ball1.mesh.size=0.0005",
        "solver.time_step_factor=0.6",
    ]));
    assert_eq!(quarter.reduction, "quarter");
    assert_eq!(section.reduction, "axisymmetric");
    let rel = |a: f64, b: f64| a / b - 1.0;
    let de = rel(section.e.unwrap(), quarter.e.unwrap());
    let dd = rel(section.delta_max, quarter.delta_max);
    println!(
        "wall 1 m/s: section e {:.5} δ_max {:.4e} m energy {:.2e}; quarter e {:.5} δ_max {:.4e} m energy {:.2e}; Δe {:+.2} %, Δδ {:+.2} %",
        section.e.unwrap(),
        section.delta_max,
        section.energy_error,
        quarter.e.unwrap(),
        quarter.delta_max,
        quarter.energy_error,
        100.0 * de,
        100.0 * dd
    );
    assert!(de.abs() < 0.005 && dd.abs() < 0.005, "{de:+.4} {dd:+.4}");
    assert!(section.energy_error < 1e-3, "{}", section.energy_error);
    assert!(quarter.energy_error < 1e-3, "{}", quarter.energy_error);
}

/// results.json and history.csv of a wall run have the two-ball run's keys and columns (the
/// scene's `wall` table aside), ball 2's velocity is the wall's (zero), and `fe.savings` says
/// why the reduction was chosen.
#[test]
fn a_wall_run_writes_the_two_ball_keys() {
    let dir = std::env::temp_dir().join(format!("twoball-wall-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let scene = dir.join("wall.toml");
    std::fs::write(&scene, WALL_SCENE).unwrap();
    let cli = |name: &str, file: Option<&Path>, sets: &[&str]| {
        run_support::run_cli(&dir.join(name), file, sets)
    };
    let coarse = |b: &str| format!("{b}.mesh={{size=0.004,pole_size=0.002}}");
    let (c1, c2) = (coarse("ball1"), coarse("ball2"));
    let (w, hw, printed) = cli("wall", Some(&scene), &[&c1]);
    let (p, hp, _) = cli("pair", None, &[&c1, &c2]);
    assert!(printed.contains("rigid wall"), "{printed}");
    assert_eq!(w["v2_after"], serde_json::json!([0.0, 0.0, 0.0]));
    // The velocity after carries e (the wall at rest). (This coarse bulk has no coarser
    // level, so no bar and no phase mean: scene_axisymmetric checks those.)
    let (e, v1) = (w["e"].as_f64().unwrap(), w["v1_after"][0].as_f64().unwrap());
    assert!((v1 + e).abs() < 1e-12, "v1 {v1} e {e}");
    let why = w["fe"]["savings"]["reduction_reason"].as_str().unwrap();
    assert!(why.contains("rigid wall"), "{why}");
    let keys = |v: &serde_json::Value| {
        let mut out = run_support::json_keys(v);
        out.retain(|k| !k.starts_with(".scene.wall") && !k.starts_with(".warnings[]"));
        out
    };
    assert_eq!(keys(&w), keys(&p));
    assert_eq!(hw, hp);
    let _ = std::fs::remove_dir_all(&dir);
}
