//! Mass scaling of a head-on section (`fe::section::mass_scaling`): within its budget it
//! moves e, δ_max and the contact duration by less than the bias bound every mass-scaled bar
//! carries (`study::convergence::phase_ensemble::MASS_SCALING_BIAS` × budget) and takes fewer steps.

use twoball::study::convergence::phase_ensemble::{
    family_mesh, hertz_contact_radius, HeadOnCase, MASS_SCALING_BIAS,
};
use twoball::study::run::section_impact::{HeadOn, ImpactResult, Target};

/// The default scene's balls at `v_rel` (m/s) on plain family level 0, mass-scaled within
/// `budget`.
fn run(v_rel: f64, budget: f64) -> ImpactResult {
    let case = HeadOnCase {
        relative_speed: v_rel,
        ..HeadOnCase::default_scene()
    };
    let mesh = family_mesh(case.diameter, hertz_contact_radius(&case), 0).unwrap();
    let mut h = HeadOn::new(mesh, case.material, v_rel / 2.0, Target::MirrorBall);
    h.plane_contact = case.plane;
    h.mass_scaling = budget;
    h.run().unwrap()
}

/// At 0.072 m/s (a contact radius of 0.12 mm on a 20 mm ball) a budget of 1e-4 cuts the
/// steps more than three-fold (measured 52 752 to 15 448) and moves e by 3.6e-4 of itself,
/// δ_max and t_c by less than 1e-5: all within 10 × budget.
#[test]
fn a_budget_moves_the_answer_less_than_its_bias_bound_and_saves_steps() {
    let budget = 1e-4;
    let (plain, scaled) = (run(0.072, 0.0), run(0.072, budget));
    assert_eq!(plain.added_mass_fraction, 0.0);
    assert!((scaled.added_mass_fraction / budget - 1.0).abs() < 1e-6);
    let bound = MASS_SCALING_BIAS * budget;
    for (name, a, b) in [
        ("e", plain.e, scaled.e),
        ("delta_max", plain.delta_max, scaled.delta_max),
        ("t_c", plain.contact_duration, scaled.contact_duration),
        ("F_peak", plain.peak_force, scaled.peak_force),
    ] {
        let rel = (b / a - 1.0).abs();
        println!("{name}: {a:.6e} -> {b:.6e} ({rel:.1e})");
        assert!(rel < bound, "{name}: {a} -> {b}, {rel:.2e} >= {bound:.0e}");
    }
    // The shift is real, not zero: the test would notice scaling that did nothing.
    assert!(scaled.e != plain.e && scaled.dt > 3.0 * plain.dt);
    assert!(
        plain.steps > 3 * scaled.steps,
        "{} {}",
        plain.steps,
        scaled.steps
    );
    assert!(scaled.energy_error < 1e-4, "{}", scaled.energy_error);
}

/// The default scene on the 3D quarter model, or on the section, with `sets` overrides.
fn scene_run(model_3d: bool, sets: &[&str]) -> twoball::study::run::scene::RunReport {
    use twoball::scene::{Override, Scene, DEFAULT_SCENE};
    let symmetry = if model_3d {
        "reduction.symmetry=\"auto-3d\""
    } else {
        "reduction.symmetry=\"auto\""
    };
    let sets: Vec<Override> = std::iter::once(symmetry)
        .chain(sets.iter().copied())
        .map(|s| Override::parse(s).unwrap())
        .collect();
    let scene = Scene::from_toml(DEFAULT_SCENE, std::path::Path::new("."), &sets).unwrap();
    let opts = twoball::study::run::simulate::RunOptions::default();
    twoball::study::run::scene::run_scene(&scene, &opts).unwrap()
}

/// `solver.mass_scaling` on the 3D quarter model of the default scene (the same mechanism
/// and key as the section's): a budget of 1e-3 takes about a third fewer element updates
/// (measured 10.16 to 6.69 million) and moves e, δ_max and the contact duration by less than
/// the bias bound (measured 3.4e-4, 5.4e-5 and 1.4e-5 of themselves); a budget of 0 is the
/// unscaled run to the bit.
#[test]
fn the_3d_model_takes_the_same_budget_and_keeps_within_the_bias_bound() {
    let budget = 1e-3;
    let plain = scene_run(true, &[]);
    let zero = scene_run(true, &["solver.mass_scaling=0"]);
    let scaled = scene_run(true, &["solver.mass_scaling=1e-3"]);
    assert_eq!(
        (zero.e, zero.element_cycles),
        (plain.e, plain.element_cycles)
    );
    let bound = MASS_SCALING_BIAS * budget;
    for (name, a, b) in [
        ("e", plain.e.unwrap(), scaled.e.unwrap()),
        ("delta_max", plain.delta_max, scaled.delta_max),
        ("t_c", plain.contact_duration, scaled.contact_duration),
    ] {
        let rel = (b / a - 1.0).abs();
        println!("{name}: {a:.6e} -> {b:.6e} ({rel:.1e})");
        assert!(rel < bound, "{name}: {a} -> {b}, {rel:.2e} >= {bound:.0e}");
    }
    assert!(scaled.e != plain.e);
    assert!(
        (scaled.element_cycles as f64) < 0.8 * plain.element_cycles as f64,
        "{} {}",
        plain.element_cycles,
        scaled.element_cycles
    );
}

/// The key is one for both models: on the section it is the budget of
/// [`HeadOn::mass_scaling`], and out of its range it is a one-line error naming it.
#[test]
fn the_section_takes_the_scene_key_and_a_bad_budget_is_named() {
    let plain = scene_run(false, &[]);
    let scaled = scene_run(false, &["solver.mass_scaling=1e-3"]);
    assert!(scaled.element_cycles < plain.element_cycles && scaled.e != plain.e);
    let e = twoball::scene::Override::parse("solver.mass_scaling=0.5")
        .and_then(|o| {
            twoball::scene::Scene::from_toml(
                twoball::scene::DEFAULT_SCENE,
                std::path::Path::new("."),
                &[o],
            )
        })
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("solver.mass_scaling") && !e.contains('\n'),
        "{e}"
    );
}
