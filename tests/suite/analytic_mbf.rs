//! Maw, Barber & Fawcett's elastic oblique impact (`analytic::maw_barber_fawcett`): the
//! rigid-body Coulomb limits it must meet in gross sliding, Hertz's normal impact, its
//! convergence in springs and steps, and the normalisation that makes a ball on a wall and
//! two identical balls one curve.

use twoball::analytic::laws::ContactPair;
use twoball::analytic::maw_barber_fawcett::{
    curve, impact, stiffness_ratio, Resolution, DEFAULT_RESOLUTION,
};
use twoball::analytic::{Body, HertzPair};
use twoball::Material;

/// An elastic ball of the preset `name` (yield raised out of reach), diameter `d` (m).
fn ball(name: &str, d: f64) -> Body {
    let m = Material {
        yield_strength: 1e12,
        ..Material::preset(name).unwrap()
    };
    Body::ball(m, d, "ball").unwrap()
}

/// In gross sliding every spring slips: the tangential impulse is μ times the normal one to
/// round-off, and the rebound angle follows the rigid-body Coulomb result
/// ψ₂ = ψ₁ − κ (1 + mR²/I)(1 + e).
#[test]
fn gross_sliding_is_rigid_body_coulomb() {
    let (b, wall) = (ball("copper-fe", 0.02), Body::RigidWall);
    let mu = 0.2;
    let points = curve(&b, &wall, 1.0, mu, &[7.0, 9.0, 12.0], DEFAULT_RESOLUTION).unwrap();
    let kappa = stiffness_ratio(&ContactPair::between(&b, &wall, mu));
    let inertia = 1.0 + b.mass() * b.radius().powi(2) / b.moment_of_inertia();
    for p in &points {
        let i = &p.impact;
        assert_eq!(i.gross_slip_fraction, 1.0, "psi1 = {}", p.psi_in);
        let ratio = i.tangential_impulse / (mu * i.normal_impulse);
        assert!((ratio - 1.0).abs() < 1e-12, "J_t/(mu J_n) = {ratio}");
        let want = p.psi_in - kappa * inertia * (1.0 + i.e);
        assert!((p.psi_out - want).abs() < 1e-9, "{} vs {want}", p.psi_out);
    }
}

/// The normal impact is Hertz's: e = 1 and the contact time within the time step's error.
#[test]
fn normal_impact_is_hertz() {
    let (b1, b2) = (ball("steel", 0.01), ball("steel", 0.01));
    let i = impact(
        &b1,
        &b2,
        [[0.5, 0.2], [-0.5, 0.0]],
        [0.0, 0.0],
        0.3,
        DEFAULT_RESOLUTION,
    )
    .unwrap()
    .unwrap();
    assert!((i.e - 1.0).abs() < 1e-5, "e = {}", i.e);
    let t_hertz = HertzPair::between(&b1, &b2).contact_duration(1.0);
    assert!(
        (i.contact_duration / t_hertz - 1.0).abs() < 1e-3,
        "{} vs {t_hertz}",
        i.contact_duration
    );
}

/// Doubling the springs and the steps moves the tangential restitution by less than 1e-3
/// (absolute) over stick, micro-slip and gross sliding.
#[test]
fn default_resolution_is_converged() {
    let (b, wall) = (ball("copper-fe", 0.02), Body::RigidWall);
    let psi = [0.3, 1.0, 2.0, 3.5, 5.0];
    let fine = Resolution {
        springs: 2 * DEFAULT_RESOLUTION.springs,
        steps: 2 * DEFAULT_RESOLUTION.steps,
    };
    let a = curve(&b, &wall, 1.0, 0.2, &psi, DEFAULT_RESOLUTION).unwrap();
    let f = curve(&b, &wall, 1.0, 0.2, &psi, fine).unwrap();
    for (a, f) in a.iter().zip(&f) {
        let (ea, ef) = (
            a.impact.tangential_restitution().unwrap(),
            f.impact.tangential_restitution().unwrap(),
        );
        assert!((ea - ef).abs() < 1e-3, "psi1 = {}: {ea} vs {ef}", a.psi_in);
    }
}

/// Normal and tangential equations scale alike for a ball on a wall and for two identical
/// balls (m*/m_t = 1 + mR²/I in both), so their normalised curves coincide, whatever the
/// speed and size.
#[test]
fn wall_and_twin_ball_share_one_curve() {
    let psi = [0.5, 1.5, 3.0, 4.5];
    let on_wall = curve(
        &ball("glass", 0.02),
        &Body::RigidWall,
        1.0,
        0.3,
        &psi,
        DEFAULT_RESOLUTION,
    );
    let twins = curve(
        &ball("glass", 0.005),
        &ball("glass", 0.005),
        3.0,
        0.3,
        &psi,
        DEFAULT_RESOLUTION,
    );
    for (w, t) in on_wall.unwrap().iter().zip(&twins.unwrap()) {
        assert!(
            (w.psi_out - t.psi_out).abs() < 2e-3,
            "{} vs {}",
            w.psi_out,
            t.psi_out
        );
    }
}

/// A spinning ball dropped on a wall without tangential speed (Chung & Ooi's spin test) at a
/// spin that slides throughout: the spin after and the rebound's tangential velocity are the
/// rigid-body Coulomb ones from the normal impulse, Δω = −μ J_n R/I, Δv_t = −μ J_n/m.
#[test]
fn spinning_ball_in_sliding_loses_coulomb_spin() {
    let (b, mu) = (ball("steel", 0.01), 0.1);
    let (r, w0) = (b.radius(), 300.0);
    let i = impact(
        &b,
        &Body::RigidWall,
        [[0.5, 0.0], [0.0, 0.0]],
        [w0, 0.0],
        mu,
        DEFAULT_RESOLUTION,
    )
    .unwrap()
    .unwrap();
    assert_eq!(i.gross_slip_fraction, 1.0);
    let jn = i.normal_impulse;
    let spin = w0 - mu * jn * r / b.moment_of_inertia();
    assert!(
        (i.spin_after[0] / spin - 1.0).abs() < 1e-12,
        "{} vs {spin}",
        i.spin_after[0]
    );
    let vt = -mu * jn / b.mass();
    assert!(
        (i.v1_after[1] / vt - 1.0).abs() < 1e-12,
        "{} vs {vt}",
        i.v1_after[1]
    );
    assert!((i.v1_after[0] + 0.5 * i.e).abs() < 1e-12);
}

/// A scene's run takes the theory from the same impact: a copper ball at [1, 0.5, 0] m/s on a
/// rigid wall gets Maw, Barber & Fawcett's tangential restitution when it stays elastic, and
/// none when the analytical model says it yields.
#[test]
fn a_scene_gets_the_theory_only_while_elastic() {
    use std::path::Path;
    use twoball::scene::{approach, Approach, Override, Scene, WALL_SCENE};
    use twoball::study::records::outcome::{analytic_outcome, elastic_theory_outcome};
    use twoball::study::records::tangential::tangential;
    let theory = |sets: &[&str]| {
        let sets: Vec<Override> = sets.iter().map(|s| Override::parse(s).unwrap()).collect();
        let scene = Scene::from_toml(WALL_SCENE, Path::new("."), &sets).unwrap();
        let Approach::Impact(touch) = approach(&scene).unwrap() else {
            panic!("no impact")
        };
        let (_, c) = analytic_outcome(&scene, &touch).unwrap();
        elastic_theory_outcome(&scene, &touch, &c)
            .unwrap()
            .map(|o| tangential(&scene, &touch, &o))
    };
    assert!(
        theory(&["ball1.velocity=[1,0.5,0]"]).is_none(),
        "copper-fe yields at 1 m/s"
    );
    let t = theory(&["ball1.velocity=[1,0.5,0]", "ball1.material.yield=1e12"]).unwrap();
    let b = ball("copper-fe", 0.02);
    let i = impact(
        &b,
        &Body::RigidWall,
        [[1.0, 0.5], [0.0, 0.0]],
        [0.0, 0.0],
        0.2,
        DEFAULT_RESOLUTION,
    )
    .unwrap()
    .unwrap();
    let want = i.tangential_restitution().unwrap();
    assert!(
        (t.restitution.unwrap() - want).abs() < 1e-12,
        "{:?} vs {want}",
        t.restitution
    );
}
