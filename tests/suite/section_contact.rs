//! A ball section on the rigid plane: the elastic head-on impact of two equal copper-fe
//! balls (D = 20 mm) on their symmetry plane against Hertz at low a/R and the finite-ball
//! reference of verification/contact-penalty.md, with restitution and energy checks. The impacts take
//! minutes in the scalar kernels and are `#[ignore]`d: `cargo test --release --test
//! section_contact -- --ignored --nocapture`.

use crate::contact_support::hertz;
use crate::section_support;

use hertz::{elastic_copper, finite_ball_reference, windowed_peak, DIAMETER};
use section_support::test_ball;
use twoball::analytic::hertz::HertzPair;
use twoball::study::run::section_impact::{HeadOn, ImpactResult, Target};

struct Compared {
    run: ImpactResult,
    hertz: (f64, f64, f64),
    finite: (f64, f64, f64),
}

/// Runs the mirror-ball impact at relative speed `v_rel` on a ball with pole size `pole`.
fn impact(v_rel: f64, pole: f64, far: f64) -> Compared {
    let r = DIAMETER / 2.0;
    let mesh = test_ball(r, pole, far);
    let mut h = HeadOn::new(mesh, elastic_copper(), v_rel / 2.0, Target::MirrorBall);
    h.elastic_only = true;
    let run = h.run().unwrap();
    // Initial kinetic energy of the pair: 2 · ½ m (v_rel/2)².
    let m_ball = run.initial_kinetic / (0.25 * v_rel * v_rel);
    let mat = elastic_copper();
    let pair = HertzPair::new(mat.plane_strain_modulus() / 2.0, r / 2.0, m_ball / 2.0);
    let (dh, th, fh) = (
        pair.max_approach(v_rel),
        pair.contact_duration(v_rel),
        pair.peak_force(v_rel),
    );
    let (fd, ft, pulse) = finite_ball_reference(v_rel, r, dh, fh);
    let w = th / 20.0;
    let fw = windowed_peak(&run.pulse, w);
    let rel = |a: f64, b: f64| a / b - 1.0;
    let c = Compared {
        hertz: (
            rel(run.delta_max, dh),
            rel(run.contact_duration, th),
            rel(
                fw,
                windowed_peak(&hertz::hertz_pulse(v_rel, dh, fh, 200_000), w),
            ),
        ),
        finite: (
            rel(run.delta_max, fd),
            rel(run.contact_duration, ft),
            rel(fw, windowed_peak(&pulse, w)),
        ),
        run,
    };
    println!(
        "v_rel {v_rel} m/s, pole {:.0} µm, {} quads, {} steps, {:.2} s: vs Hertz δ {:+.2} % t_c {:+.2} % F {:+.2} %; vs finite ball δ {:+.2} % t_c {:+.2} % F {:+.2} %; e {:.5}, energy error {:.2e}, penetration/δ {:.2} %",
        pole * 1e6,
        c.run.elements,
        c.run.steps,
        c.run.wall_time_s,
        100.0 * c.hertz.0,
        100.0 * c.hertz.1,
        100.0 * c.hertz.2,
        100.0 * c.finite.0,
        100.0 * c.finite.1,
        100.0 * c.finite.2,
        c.run.e,
        c.run.energy_error,
        100.0 * c.run.max_penetration / c.run.delta_max
    );
    c
}

#[test]
#[ignore]
fn elastic_ball_on_the_symmetry_plane_matches_the_finite_ball_at_2_m_s() {
    let c = impact(2.0, 50e-6, 1e-3);
    assert!(c.run.e >= 0.995, "e = {}", c.run.e);
    assert!(c.run.energy_error < 1e-3, "{}", c.run.energy_error);
    let (d, t, f) = c.finite;
    assert!(
        d.abs() < 0.01 && t.abs() < 0.01 && f.abs() < 0.015,
        "{:?}",
        c.finite
    );
}

#[test]
#[ignore]
fn elastic_ball_on_the_symmetry_plane_matches_hertz_at_0_2_m_s() {
    // a/R ≈ 0.02: Hertz and the finite ball differ by under 1 %.
    let c = impact(0.2, 25e-6, 1e-3);
    assert!(c.run.e >= 0.995, "e = {}", c.run.e);
    assert!(c.run.energy_error < 1e-3, "{}", c.run.energy_error);
    let (d, t, f) = c.finite;
    assert!(
        d.abs() < 0.01 && t.abs() < 0.01 && f.abs() < 0.015,
        "{:?}",
        c.finite
    );
    let (d, t, _) = c.hertz;
    assert!(d.abs() < 0.015 && t.abs() < 0.015, "{:?}", c.hertz);
}

#[test]
#[ignore]
fn two_balls_with_node_to_segment_contact_agree_with_the_symmetry_plane() {
    use twoball::study::run::section_impact::OtherBall;
    let r = DIAMETER / 2.0;
    let (pole, far) = (50e-6, 1e-3);
    let mut one = HeadOn::new(
        test_ball(r, pole, far),
        elastic_copper(),
        1.0,
        Target::MirrorBall,
    );
    one.elastic_only = true;
    let one = one.run().unwrap();
    let other = OtherBall {
        mesh: test_ball(r, pole, far),
        material: elastic_copper(),
        elastic_only: true,
        speed: 1.0,
    };
    let mut two = HeadOn::new(
        test_ball(r, pole, far),
        elastic_copper(),
        1.0,
        Target::Ball(Box::new(other)),
    );
    two.elastic_only = true;
    let two = two.run().unwrap();
    let rel = |a: f64, b: f64| a / b - 1.0;
    println!(
        "two balls vs mirror plane: δ {:+.3} % t_c {:+.3} % F {:+.3} %, e {:.5} / {:.5}, energy {:.1e} / {:.1e}",
        100.0 * rel(two.delta_max, one.delta_max),
        100.0 * rel(two.contact_duration, one.contact_duration),
        100.0 * rel(two.peak_force, one.peak_force),
        two.e,
        one.e,
        two.energy_error,
        one.energy_error
    );
    assert!(rel(two.delta_max, one.delta_max).abs() < 0.01);
    assert!(rel(two.contact_duration, one.contact_duration).abs() < 0.01);
    assert!(
        two.e > 0.99 && two.energy_error < 1e-3,
        "{} {}",
        two.e,
        two.energy_error
    );
}

/// The default scene (D = 20 mm copper-fe, ±1 m/s, plastic) on the mirror plane at pole
/// D/200, D/1000 and D/2000. `cargo test --release --test suite section_contact::default_scene --
/// --ignored --nocapture`.
#[test]
#[ignore]
fn default_scene_ladder() {
    use twoball::fe::elements::ring::QuadFormulation;
    use twoball::Material;
    let r = DIAMETER / 2.0;
    for pole in [DIAMETER / 200.0, DIAMETER / 1000.0, DIAMETER / 2000.0] {
        for form in [
            QuadFormulation::default(),
            QuadFormulation::SelectiveReduced,
        ] {
            let mesh = test_ball(r, pole, DIAMETER / 20.0);
            let mut h = HeadOn::new(
                mesh,
                Material::preset("copper-fe").unwrap(),
                1.0,
                Target::MirrorBall,
            );
            h.formulation = form;
            let o = h.run().unwrap();
            println!(
                "{form:?} pole D/{:.0}: {} quads, {} steps, e {:.5}, δ_max {:.4} µm, t_c {:.3} µs, F {:.1} N, energy error {:.1e}, wall {:.3} s",
                DIAMETER / pole,
                o.elements,
                o.steps,
                o.e,
                o.delta_max * 1e6,
                o.contact_duration * 1e6,
                o.peak_force,
                o.energy_error,
                o.wall_time_s
            );
        }
    }
}

/// The kinematic plane (the default) is the penalty plane's FKN → ∞ limit: on the level-0
/// ladder at 2 m/s, elastic, the penalty's δ_max falls as 1/FKN (FKN = 40, 80 extrapolated
/// linearly in 1/FKN), and the kinematic plane run on the same small step lands on that
/// limit; at its own step (the quads', 3x the FKN = 10 penalty's) it stays within 0.1 %, and
/// it returns the energy (the run's last energy balance and e). Fails if the plane keeps a
/// compliance (e.g. a node put at a fixed fraction of its predicted penetration) or pulls.
#[test]
fn the_kinematic_plane_is_the_stiff_limit_of_the_penalty_plane() {
    use twoball::mesh::section::ladder_ball;
    use twoball::study::run::section_impact::PlaneContact;
    let run = |plane: PlaneContact, fkn: f64, factor: f64| {
        let mesh = ladder_ball(DIAMETER, 470.4e-6, 0).unwrap();
        let mut h = HeadOn::new(mesh, elastic_copper(), 1.0, Target::MirrorBall);
        h.elastic_only = true;
        h.plane_contact = plane;
        h.fkn = fkn;
        h.time_step_factor = factor;
        h.run().unwrap()
    };
    let p40 = run(PlaneContact::Nodal, 40.0, 0.9);
    let p80 = run(PlaneContact::Nodal, 80.0, 0.9);
    let stiff = 2.0 * p80.delta_max - p40.delta_max;
    let own = run(PlaneContact::Kinematic, 10.0, 0.9);
    let small = run(PlaneContact::Kinematic, 10.0, 0.9 * p80.dt / own.dt);
    let p10 = run(PlaneContact::Nodal, 10.0, 0.9);
    let rel = |a: f64, b: f64| a / b - 1.0;
    println!(
        "δ_max: penalty 40 {:.4e}, 80 {:.4e}, limit {:.4e}; kinematic at step {:.2e} s {:.4e}, \
         at its own {:.2e} s {:.4e} (penalty 10: step {:.2e} s); e {:.6}, energy error {:.1e}",
        p40.delta_max,
        p80.delta_max,
        stiff,
        small.dt,
        small.delta_max,
        own.dt,
        own.delta_max,
        p10.dt,
        own.e,
        own.energy_error
    );
    assert!(rel(small.delta_max, stiff).abs() < 2e-4);
    assert!(rel(own.delta_max, stiff).abs() < 1e-3);
    assert!(own.dt > 3.0 * p10.dt);
    assert!(own.max_penetration <= 1e-12 * own.delta_max);
    assert!((0.9999..=1.0).contains(&own.e), "e {}", own.e);
    let first = own.history.first().unwrap().total;
    let last = own.history.last().unwrap().total;
    assert!(rel(last, first).abs() < 1e-5, "{last} vs {first}");
}
