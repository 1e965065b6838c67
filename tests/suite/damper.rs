//! The particle-damper model against what it must reproduce: the empty frame's free decay,
//! a ball's rebound on the box floor with its law's restitution, conservation of momentum
//! and the closed energy balance; bad scenes as one-line errors.

use crate::pvd_support;
use twoball::analytic::laws::{ContactPair, Registry};
use twoball::analytic::Body;
use twoball::damper::{log_decrement, peaks, BoxSpec, DamperBall, DamperScene, DamperSimulation};
use twoball::Material;

fn steel() -> Material {
    Material::preset("steel").unwrap()
}

fn paper_box() -> BoxSpec {
    BoxSpec {
        size: [0.11, 0.045, 0.035],
        material: steel(),
    }
}

fn ball(material: Material, d: f64, p: [f64; 3]) -> DamperBall {
    DamperBall {
        material,
        diameter: d,
        position: p,
    }
}

/// Nine 20 mm balls of `material` on the floor of the test box, rows of five and four with
/// 2 mm gaps.
fn nine(material: Material) -> Vec<DamperBall> {
    (0..9)
        .map(|k| {
            let (ix, iy) = (k % 5, k / 5);
            ball(
                material,
                0.02,
                [
                    0.011 + 0.022 * ix as f64 + 0.011 * iy as f64,
                    0.011 + 0.022 * iy as f64,
                    0.0101,
                ],
            )
        })
        .collect()
}

#[test]
fn empty_frame_decays_at_its_frequency_and_damping_ratio() {
    let mut scene = DamperScene::paper_frame(paper_box(), Vec::new());
    scene.duration = 12.0;
    let mut sim = DamperSimulation::new(&scene, &Registry::builtin()).unwrap();
    let s = sim.run(scene.duration, scene.sample_interval).unwrap();
    let t: Vec<f64> = s.iter().map(|s| s.time).collect();
    let x: Vec<f64> = s.iter().map(|s| s.displacement).collect();
    let d = log_decrement(&peaks(&t, &x), (0.0, 12.0)).unwrap();
    println!(
        "empty frame: f = {} Hz, zeta = {}, {} cycles",
        d.frequency, d.ratio, d.cycles
    );
    assert!(d.cycles >= 19);
    assert!((d.frequency / 1.69 - 1.0).abs() < 1e-3, "{d:?}");
    assert!((d.ratio / 0.0045 - 1.0).abs() < 1e-3, "{d:?}");
    let last = s.last().unwrap().ledger;
    let residual = last.residual(&s[0].ledger);
    println!("empty frame: energy residual {residual}");
    assert!(residual.abs() < 1e-5, "{last:?}");
}

/// A ball sent onto the floor at `v` (no gravity, frame at rest; with gravity dropped from
/// `drop` m) leaves with speed e v, e from the law's own closed form for a ball on the steel
/// half-space. Returns (measured, closed form).
fn rebound(
    law: &str,
    params: &[(&str, f64)],
    v: f64,
    gravity: f64,
    drop: f64,
    steps: f64,
) -> (f64, f64) {
    let d = 0.02;
    let mut scene = DamperScene::paper_frame(
        BoxSpec {
            size: [0.1, 0.1, 0.1],
            material: steel(),
        },
        vec![ball(steel(), d, [0.05, 0.05, 0.5 * d + drop])],
    );
    scene.frame.release = 0.0;
    scene.gravity = gravity;
    scene.impact_speed = Some(v);
    scene.steps_per_period = steps;
    scene.laws.normal = law.into();
    scene.laws.normal_params = params.iter().map(|(k, v)| (k.to_string(), *v)).collect();
    let registry = Registry::builtin();
    let mut sim = DamperSimulation::new(&scene, &registry).unwrap();
    if gravity == 0.0 {
        sim.velocity[0].z = -v;
    }
    let mut before = None;
    let mut touched = false;
    while sim.time < 1.0 {
        let v_prev = sim.velocity[0].z;
        sim.step();
        if !touched && !sim.contacts().is_empty() {
            touched = true;
            before = Some(-v_prev);
        }
        if touched && sim.contacts().is_empty() {
            break;
        }
    }
    let v_in = before.expect("the ball reached the floor");
    let measured = sim.velocity[0].z / v_in;
    let b = Body::ball(steel(), d, "ball").unwrap();
    let wall = Body::HalfSpace { material: steel() };
    let pair = ContactPair::between(&b, &wall, 0.1);
    let overrides: Vec<(String, f64)> = scene.laws.normal_params.clone();
    let (normal, _) = registry
        .normal(law)
        .unwrap()
        .build_with(&overrides, &pair)
        .unwrap();
    let expected = normal
        .closed_form(v_in, b.mass())
        .expect("a law with a closed form")
        .e;
    (measured, expected)
}

/// Laws continuous at touch agree within 5e-4: Hertz at the default 60 steps per normal
/// contact period, the plastic laws (Thornton, three-phase) at 1000 (at 60 and 100 they are
/// within 1.5e-3: the turn, where the unloading curve takes over, is located to O(dt)).
/// Walton-Braun's stiffness jumps fourfold at the turn, which the steps locate to O(dt²)
/// (1.8e-3 in e at 60 steps), so it runs at 240; the linear dashpot's force jumps to c v at
/// touch, an O(dt) error of when the jump happens (1.6e-3 in e at 60 steps), so it runs at
/// 2000.
#[test]
fn a_ball_rebounds_from_the_floor_with_its_laws_restitution() {
    let mut failures = Vec::new();
    for (law, params, steps) in [
        ("hertz", vec![], 60.0),
        ("walton-braun", vec![("e", 0.5)], 240.0),
        ("thornton", vec![], 1000.0),
        ("li-yang-shi", vec![], 1000.0),
        ("linear-dashpot", vec![("e", 0.6)], 2000.0),
    ] {
        for v in [0.3, 1.0] {
            let (e, expected) = rebound(law, &params, v, 0.0, 1e-4, steps);
            println!("{law} v = {v}: e = {e}, closed form {expected}");
            if (e / expected - 1.0).abs() >= 5e-4 {
                failures.push(format!("{law} at {v} m/s: {e} vs {expected}"));
            }
        }
    }
    assert!(failures.is_empty(), "{failures:?}");
}

#[test]
fn a_dropped_ball_rebounds_with_its_laws_restitution_under_gravity() {
    let (e, expected) = rebound("li-yang-shi", &[], 1.0, 9.81, 0.05, 60.0);
    println!("dropped 50 mm: e = {e}, closed form {expected}");
    assert!((e / expected - 1.0).abs() < 3e-3, "{e} vs {expected}");
}

#[test]
fn horizontal_momentum_changes_only_by_spring_and_damper() {
    let mut scene = DamperScene::paper_frame(paper_box(), nine(steel()));
    scene.steps_per_period = 20.0;
    let mut sim = DamperSimulation::new(&scene, &Registry::builtin()).unwrap();
    let p0 = sim.momentum_x();
    let mut worst: f64 = 0.0;
    let mut largest: f64 = 0.0;
    for _ in 0..20 {
        sim.run(sim.time + 0.05, 0.05).unwrap();
        let drift = sim.momentum_x() - p0 - sim.spring_damper_impulse();
        worst = worst.max(drift.abs());
        largest = largest.max(sim.spring_damper_impulse().abs());
    }
    println!("momentum drift {worst} N s against impulse {largest} N s");
    assert!(largest > 0.1);
    assert!(worst < 1e-12 * largest.max(1.0), "{worst}");
}

#[test]
fn ball_ball_contacts_conserve_momentum_and_angular_momentum() {
    let mut scene = DamperScene::paper_frame(
        BoxSpec {
            size: [1.0, 1.0, 1.0],
            material: steel(),
        },
        vec![
            ball(steel(), 0.02, [0.45, 0.5, 0.5]),
            ball(
                Material::preset("glass").unwrap(),
                0.015,
                [0.55, 0.505, 0.503],
            ),
        ],
    );
    scene.frame.release = 0.0;
    scene.gravity = 0.0;
    scene.impact_speed = Some(2.0);
    let mut sim = DamperSimulation::new(&scene, &Registry::builtin()).unwrap();
    sim.velocity[0] = nalgebra::Vector3::new(1.0, 0.1, 0.0);
    sim.velocity[1] = nalgebra::Vector3::new(-1.0, 0.0, 0.05);
    sim.spin[0] = nalgebra::Vector3::new(0.0, 0.0, 30.0);
    let (p0, l0) = (sim.balls_momentum(), sim.balls_angular_momentum());
    let mut touched = false;
    while sim.time < 0.1 {
        sim.step();
        touched |= !sim.contacts().is_empty();
    }
    assert!(touched, "the balls collided");
    let (p, l) = (sim.balls_momentum(), sim.balls_angular_momentum());
    println!(
        "dp = {}, dL = {}, L0 = {}",
        (p - p0).norm(),
        (l - l0).norm(),
        l0.norm()
    );
    assert!((sim.spin[1]).norm() > 1.0, "friction spun the second ball");
    assert!((p - p0).norm() < 1e-14, "{:?} vs {:?}", p, p0);
    assert!((l - l0).norm() < 1e-10 * l0.norm(), "{:?} vs {:?}", l, l0);
}

#[test]
fn energy_balance_closes_for_a_released_damper() {
    for (law, tangential) in [
        ("li-yang-shi", "mindlin-coulomb"),
        ("hertz-damped", "coulomb"),
    ] {
        let mut scene = DamperScene::paper_frame(paper_box(), nine(steel()));
        scene.laws.normal = law.into();
        scene.laws.tangential = tangential.into();
        let mut sim = DamperSimulation::new(&scene, &Registry::builtin()).unwrap();
        let s = sim.run(1.0, 0.01).unwrap();
        let start = s[0].ledger;
        let worst = s
            .iter()
            .map(|x| x.ledger.residual(&start).abs())
            .fold(0.0, f64::max);
        let end = s.last().unwrap().ledger;
        println!("{law}/{tangential}: worst residual {worst}; end {end:?}");
        assert!(end.contact_dissipated + end.friction_dissipated > 1e-4 * start.total());
        assert!(worst < 0.01, "{worst}");
    }
}

#[test]
fn elastic_frictionless_contacts_dissipate_nothing() {
    let mut scene = DamperScene::paper_frame(paper_box(), nine(steel()));
    scene.laws.normal = "hertz".into();
    scene.laws.mu_ball = Some(0.0);
    scene.laws.mu_wall = Some(0.0);
    scene.frame.damping_ratio = 0.0;
    let mut sim = DamperSimulation::new(&scene, &Registry::builtin()).unwrap();
    let s = sim.run(1.0, 0.01).unwrap();
    let start = s[0].ledger;
    let end = s.last().unwrap().ledger;
    let exchanged = s.iter().map(|x| x.ledger.balls_kinetic).fold(0.0, f64::max);
    println!("hertz frictionless: {end:?}, largest ball KE {exchanged}");
    assert!(exchanged > 1e-3 * start.total());
    assert!(
        end.contact_dissipated.abs() < 1e-3 * start.total(),
        "{end:?}"
    );
    assert!(end.residual(&start).abs() < 1e-3, "{end:?}");
}

fn error_of(scene: &DamperScene) -> String {
    match DamperSimulation::new(scene, &Registry::builtin()) {
        Ok(_) => panic!("accepted a bad scene"),
        Err(e) => {
            let e = e.to_string();
            assert_eq!(e.lines().count(), 1, "{e}");
            e
        }
    }
}

#[test]
fn bad_scenes_get_one_line_errors_naming_the_field() {
    let base = DamperScene::paper_frame(paper_box(), nine(steel()));
    let mut s = base.clone();
    s.balls[3].position = s.balls[2].position;
    s.balls[3].position[2] += 0.005;
    let e = error_of(&s);
    assert!(
        e.contains("balls[3].position") && e.contains("overlap"),
        "{e}"
    );

    let mut s = base.clone();
    s.balls[0].diameter = 0.05;
    let e = error_of(&s);
    assert!(
        e.contains("balls[0].diameter = 0.05") && e.contains("0.035"),
        "{e}"
    );

    let mut s = base.clone();
    s.frame.mass = -5.76;
    let e = error_of(&s);
    assert!(e.contains("frame.mass = -5.76"), "{e}");

    let mut s = base.clone();
    s.balls[1].material.rho = -7800.0;
    let e = error_of(&s);
    assert!(e.contains("balls[1].material.rho = -7800"), "{e}");

    let mut s = base.clone();
    s.balls[4].position[0] = 0.2;
    let e = error_of(&s);
    assert!(e.contains("balls[4].position[0] = 0.2"), "{e}");

    let mut s = base;
    s.laws.normal = "nope".into();
    let e = error_of(&s);
    assert!(e.contains("nope"), "{e}");
}

fn twoball(args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_twoball"))
        .args(args)
        .output()
        .unwrap()
}

#[test]
fn damper_command_runs_table2_cases_and_writes_csv_with_units() {
    let out = std::env::temp_dir().join(format!("twoball-damper-{}", std::process::id()));
    let o = twoball(&[
        "damper",
        "verification/damper/table2.toml",
        "--out",
        out.to_str().unwrap(),
        "--case",
        "1-empty",
        "--case",
        "5-steel-3",
        "--duration",
        "1.5",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let summary = std::fs::read_to_string(out.join("summary.csv")).unwrap();
    assert!(
        summary.starts_with("case,balls [-],ball_mass [kg]"),
        "{summary}"
    );
    assert_eq!(summary.lines().count(), 3, "{summary}");
    let history = std::fs::read_to_string(out.join("5-steel-3/history.csv")).unwrap();
    assert!(history.starts_with("time [s],displacement [m]"));
    assert!(history.lines().count() > 1400);
    assert!(!history.contains("NaN"));
    let cycles = std::fs::read_to_string(out.join("5-steel-3/cycles.csv")).unwrap();
    assert!(cycles.starts_with("time [s],amplitude [m],damping_ratio [-]"));
    for chart in ["decay.svg", "damping.svg"] {
        let svg = std::fs::read_to_string(out.join("5-steel-3").join(chart)).unwrap();
        assert!(
            svg.starts_with("<svg") && svg.contains("5-steel-3"),
            "{chart}"
        );
    }
    // The balls as a ParaView series: every listed file exists; the empty frame has none.
    let pvd = std::fs::read_to_string(out.join("5-steel-3/balls.pvd")).unwrap();
    let files = pvd_support::files(&pvd);
    assert!(files.len() > 100 && files.len() <= 201, "{}", files.len());
    for f in &files {
        assert!(out.join("5-steel-3").join(f).is_file(), "{f}");
    }
    assert!(!out.join("1-empty/balls.pvd").exists());
    std::fs::remove_dir_all(&out).unwrap();
}

/// Case `name` of verification/damper/table2.toml run for `duration` s.
fn table2_case(name: &str, duration: f64) -> twoball::damper::run::CaseOutcome {
    use twoball::damper::file::{read, Overrides};
    let file = read(std::path::Path::new("verification/damper/table2.toml")).unwrap();
    let cases = file
        .cases(&Overrides {
            duration: Some(duration),
            ..Overrides::default()
        })
        .unwrap();
    let case = cases.iter().find(|c| c.name == name).unwrap();
    twoball::damper::run::run_case(case, &Registry::builtin()).unwrap()
}

/// The balls' frames start at release at rest, run forward in time, number at most
/// `BALL_FRAMES` + 1, and carry the balls' radii (three 20 mm steel balls here).
#[test]
fn ball_frames_start_at_release_and_follow_the_run() {
    use twoball::damper::run::BALL_FRAMES;
    let o = table2_case("5-steel-3", 1.5);
    assert_eq!(o.radii, vec![0.01; 3]);
    assert!(o.frames.len() > 10 && o.frames.len() <= BALL_FRAMES + 1);
    let first = &o.frames[0];
    assert_eq!(first.time, 0.0);
    assert_eq!(first.position.len(), 3);
    assert!(first.velocity.iter().flatten().all(|&v| v == 0.0));
    assert!(o.frames.windows(2).all(|w| w[1].time > w[0].time));
    let last = o.frames.last().unwrap();
    assert!(last.time > 1.4 && last.velocity.iter().flatten().any(|&v| v != 0.0));
}

/// The empty frame decays exponentially: every peak of the analysed window lies on the
/// envelope the decay chart draws (to 1e-3 of the first peak), and its damping chart is flat
/// at the window's ζ; the envelope fit's ζ equals the log decrement's. A wrong fit (a doubled
/// rate, a misplaced anchor) moves the later peaks off by far more.
#[test]
fn the_empty_frames_peaks_lie_on_the_drawn_envelope() {
    use twoball::damper::decay::envelope_fit;
    use twoball::study::report::damper_plots::{damping_chart, decay_chart};
    let o = table2_case("1-empty", 6.0);
    let chart = decay_chart(&o);
    let envelope = &chart.series[2].points;
    let (t0, a0) = envelope[0];
    let (t1, _) = *envelope.last().unwrap();
    let at = |t: f64| {
        let k = ((t - t0) / (t1 - t0) * 100.0).round() as usize;
        envelope[k.min(100)]
    };
    let mut checked = 0;
    for &(t, a) in &chart.series[1].points {
        let (te, ae) = at(t);
        if t < t0 || t > t1 || (te - t).abs() > 0.6 * (t1 - t0) / 100.0 {
            continue;
        }
        // The envelope is sampled: compare at the sample nearest the peak, corrected to t.
        let slope = (a0 / ae).ln() / (te - t0).max(1e-12);
        let on = ae * (-slope * (t - te)).exp();
        assert!(
            (a - on).abs() < 1e-3 * a0,
            "peak {a} mm at {t} s, envelope {on} mm"
        );
        checked += 1;
    }
    assert!(checked >= 3, "{checked} peaks checked");
    let zeta = 100.0 * o.decay.ratio;
    let t: Vec<f64> = o.samples.iter().map(|s| s.time).collect();
    let x: Vec<f64> = o.samples.iter().map(|s| s.displacement).collect();
    let (_, _, sigma) = envelope_fit(&peaks(&t, &x), o.window).unwrap();
    let w = 2.0 * std::f64::consts::PI * o.decay.frequency;
    let zeta_fit = 100.0 * sigma / (sigma * sigma + w * w).sqrt();
    assert!(
        (zeta_fit / zeta - 1.0).abs() < 1e-3,
        "{zeta_fit} % against {zeta} %"
    );
    for &(_, z) in &damping_chart(&o).series[0].points {
        assert!(
            (z - zeta).abs() < 1e-2 * zeta,
            "cycle zeta {z} % against {zeta} %"
        );
    }
}

#[test]
fn damper_command_names_bad_input_in_one_line() {
    let dir = std::env::temp_dir().join(format!("twoball-damper-bad-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let good = std::fs::read_to_string("verification/damper/table2.toml").unwrap();
    let release_line = format!(
        "line {}",
        good.lines()
            .position(|l| l.starts_with("release = 0.03"))
            .unwrap()
            + 1
    );
    for (edit, expect) in [
        (
            good.replace("count = 19", "count = 90"),
            "case[6].balls.count = 90",
        ),
        (
            good.replace("mass = 5.76", "mass = -5.76"),
            "frame.mass = -5.76",
        ),
        (
            good.replace("diameter = 0.015", "diameter = 0.05"),
            "diameter = 0.05",
        ),
        (
            good.replace("release = 0.03", "relaese = 0.03"),
            release_line.as_str(),
        ),
    ] {
        let path = dir.join("scene.toml");
        std::fs::write(&path, edit).unwrap();
        let o = twoball(&[
            "damper",
            path.to_str().unwrap(),
            "--out",
            dir.join("o").to_str().unwrap(),
        ]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success());
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.contains(expect), "{err}");
    }
    let o = twoball(&[
        "damper",
        "verification/damper/table2.toml",
        "--out",
        dir.to_str().unwrap(),
        "--case",
        "8-lead",
    ]);
    assert!(String::from_utf8_lossy(&o.stderr).contains("--case = 8-lead"));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Column `name` of a CSV text's data rows, by its header.
fn csv_column(text: &str, name: &str) -> Vec<String> {
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let k = header.iter().position(|h| *h == name).unwrap_or_else(|| {
        panic!("no column {name} in {header:?}");
    });
    lines
        .map(|l| l.split(',').nth(k).unwrap_or("").to_string())
        .collect()
}

/// The damping the balls add, in summary.csv, windows.csv and REPORT.md, is ζ − ζ_empty with
/// ζ_empty read here from the scene file (not from the program's structures), for the
/// prediction and Table 2's measurement; the window figure and table are written, the
/// empty frame's window ratios are its damping ratio, the notes are appended, progress
/// lines are printed.
#[test]
fn the_added_damping_is_zeta_less_the_empty_frames_and_the_windows_are_written() {
    let root = std::env::temp_dir().join(format!("twoball-damper-added-{}", std::process::id()));
    let (out, to) = (root.join("o"), root.join("report"));
    std::fs::create_dir_all(&to).unwrap();
    std::fs::write(to.join("NOTES.md"), "## Notes\n\nThe discussion.\n").unwrap();
    let o = twoball(&[
        "damper",
        "verification/damper/table2.toml",
        "--out",
        out.to_str().unwrap(),
        "--to",
        to.to_str().unwrap(),
        "--case",
        "1-empty",
        "--case",
        "5-steel-3",
        "--duration",
        "2.5",
        "--window-width",
        "1.25",
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert!(err.contains("damper: 2 cases started"), "{err}");
    assert!(err.contains("damper: 2 cases done"), "{err}");

    let scene: toml::Value = std::fs::read_to_string("verification/damper/table2.toml")
        .unwrap()
        .parse()
        .unwrap();
    let empty = scene["frame"]["damping_ratio"].as_float().unwrap();
    let measured = |name: &str| {
        scene["case"]
            .as_array()
            .unwrap()
            .iter()
            .find(|c| c["name"].as_str() == Some(name))
            .unwrap()["measured"]["damping_ratio"]
            .as_float()
            .unwrap()
    };
    let num = |s: &String| s.parse::<f64>().unwrap();
    let summary = std::fs::read_to_string(out.join("summary.csv")).unwrap();
    let names = csv_column(&summary, "case");
    let zeta = csv_column(&summary, "damping_ratio [-]");
    let added = csv_column(&summary, "added_damping_ratio [-]");
    let added_measured = csv_column(&summary, "measured_added_damping_ratio [-]");
    let report = std::fs::read_to_string(to.join("REPORT.md")).unwrap();
    assert_eq!(names, ["1-empty", "5-steel-3"]);
    for k in 0..2 {
        let want = num(&zeta[k]) - empty;
        assert!((num(&added[k]) - want).abs() <= 1e-15, "{summary}");
        let want_measured = measured(&names[k]) - empty;
        assert!(
            (num(&added_measured[k]) - want_measured).abs() <= 1e-15,
            "{summary}"
        );
    }
    // The steel case's row: added predicted and measured side by side, then their ratio.
    let (a, m) = (100.0 * (num(&zeta[1]) - empty), 100.0 * (0.0079 - empty));
    let cells = format!("| {a:.3} | {m:.3} |");
    let row = report
        .lines()
        .find(|l| l.starts_with("| 5-steel-3 | 3 |"))
        .unwrap();
    assert!(row.contains(&cells), "{cells} not in {row}");
    assert!(report.contains("twoball damper verification/damper/table2.toml --out DIR"));
    assert!(report.trim_end().ends_with("The discussion."), "{report}");
    assert!(report.contains("claims about cases this run did not include are left out"));

    // Windows: two per case; the empty frame's are its damping ratio; added = ζ − ζ_empty.
    let windows = std::fs::read_to_string(to.join("windows.csv")).unwrap();
    let wz = csv_column(&windows, "damping_ratio [-]");
    let wa = csv_column(&windows, "added_damping_ratio [-]");
    assert_eq!(
        csv_column(&windows, "case"),
        ["1-empty", "1-empty", "5-steel-3", "5-steel-3"]
    );
    assert_eq!(
        csv_column(&windows, "window_end [s]"),
        ["1.25", "2.5", "1.25", "2.5"]
    );
    for k in 0..4 {
        assert!(
            (num(&wa[k]) - (num(&wz[k]) - empty)).abs() <= 1e-15,
            "{windows}"
        );
    }
    for z in &wz[..2] {
        assert!((num(z) / empty - 1.0).abs() < 1e-3, "{windows}");
    }
    let svg = std::fs::read_to_string(to.join("windows.svg")).unwrap();
    assert!(svg.starts_with("<svg") && svg.contains("5-steel-3") && svg.contains("1-empty"));
    assert!(svg.len() < 300_000, "{} bytes", svg.len());
    assert!(!out.join("REPORT.md").exists());
    std::fs::remove_dir_all(&root).unwrap();
}

/// Every claim of the scene file holds on Table 2's measured damping ratios (the claims
/// say what the paper's Section 6 says), and each names the cases it compares; the glass
/// claim has the 14 balls damping more than the 19.
#[test]
fn the_scene_files_claims_hold_on_table2() {
    use twoball::damper::file::read;
    let file = read(std::path::Path::new("verification/damper/table2.toml")).unwrap();
    let empty = file.empty_damping_ratio();
    let cases = file.cases(&Default::default()).unwrap();
    let zeta = |name: &str| {
        cases
            .iter()
            .find(|c| c.name == name)
            .unwrap()
            .measured
            .unwrap()
            .damping_ratio
    };
    let claims = file.claims().unwrap();
    assert_eq!(claims.len(), 10);
    for c in &claims {
        let (a, b) = (zeta(&c.cases[0]), zeta(&c.cases[1]));
        assert!(c.relation.holds(a, b, empty), "{}: {a} against {b}", c.says);
    }
    assert!(claims
        .iter()
        .any(|c| c.compares() == "4-glass-14 > 7-glass-19"
            && c.says.contains("14 balls damp more than 19")));
}

/// Ctrl-C during a damper run stops it within a report interval, exits 130 naming the case
/// and the time reached, and writes nothing.
#[test]
fn ctrl_c_stops_a_damper_run_with_130_and_writes_nothing() {
    use std::io::BufRead;
    let out = std::env::temp_dir().join(format!("twoball-damper-sigint-{}", std::process::id()));
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_twoball"))
        .args([
            "damper",
            "verification/damper/table2.toml",
            "--out",
            out.to_str().unwrap(),
            "--case",
            "5-steel-3",
            "--duration",
            "60",
        ])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let mut err = std::io::BufReader::new(child.stderr.take().unwrap());
    let mut first = String::new();
    err.read_line(&mut first).unwrap();
    assert!(first.starts_with("damper: 1 case started"), "{first}");
    // SAFETY: kill(2) on our own child's pid with a valid signal number.
    assert_eq!(
        unsafe { libc::kill(child.id() as libc::pid_t, libc::SIGINT) },
        0
    );
    let mut rest = String::new();
    std::io::Read::read_to_string(&mut err, &mut rest).unwrap();
    let status = child.wait().unwrap();
    assert_eq!(status.code(), Some(130), "{rest}");
    let last = rest.trim().lines().last().unwrap();
    assert!(
        last.starts_with("interrupted in case 5-steel-3 at t = ")
            && last.ends_with("nothing written"),
        "{rest}"
    );
    assert!(!out.exists());
}
