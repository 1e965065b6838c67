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
