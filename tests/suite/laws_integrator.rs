//! Issue 27, acceptance 1: the one impact integrator against every law's closed form (e and
//! δ_max within 1e-6), and every law's integrated energy balance within 1e-8.

use twoball::analytic::friction::tangential_impact;
use twoball::analytic::impact::{integrate, integrate_spinning, LawImpact, DEFAULT_TOLERANCE};
use twoball::analytic::laws::{ContactPair, Registry};
use twoball::analytic::{Body, NormalImpact};
use twoball::material::Material;

fn balls(preset: &str, d: f64) -> (Body, Body) {
    let m = Material::preset(preset).unwrap();
    (
        Body::ball(m, d, "ball1").unwrap(),
        Body::ball(m, d, "ball2").unwrap(),
    )
}

fn run(
    reg: &Registry,
    b: &(Body, Body),
    normal: &str,
    tangential: &str,
    v: [f64; 2],
    over: &[(String, f64)],
) -> LawImpact {
    let pair = ContactPair::between(&b.0, &b.1, 0.3);
    let (n, _) = reg.normal(normal).unwrap().build_with(over, &pair).unwrap();
    let (t, _) = reg
        .tangential(tangential)
        .unwrap()
        .build_with(&[], &pair)
        .unwrap();
    integrate(
        &b.0,
        &b.1,
        [0.5 * v[0], 0.5 * v[1]],
        [-0.5 * v[0], -0.5 * v[1]],
        n.as_ref(),
        t.as_ref(),
        DEFAULT_TOLERANCE,
    )
    .unwrap()
    .unwrap()
}

const SPEEDS: [f64; 5] = [0.01, 0.1, 1.0, 3.0, 10.0];

#[test]
fn integrator_matches_every_closed_form() {
    let reg = Registry::builtin();
    let mut checked = 0;
    for (preset, d) in [("copper-fe", 0.02), ("steel", 0.005)] {
        let b = balls(preset, d);
        let pair = ContactPair::between(&b.0, &b.1, 0.3);
        for spec in &reg.normal {
            let (law, _) = reg
                .normal(spec.name)
                .unwrap()
                .build_with(&[], &pair)
                .unwrap();
            for &v in &SPEEDS {
                let Some(cf) = law.closed_form(v, pair.hertz.mass) else {
                    continue;
                };
                let r = run(&reg, &b, spec.name, "coulomb", [v, 0.0], &[]);
                let de = (r.e - cf.e).abs() / cf.e;
                let dd = (r.delta_max - cf.delta_max).abs() / cf.delta_max;
                assert!(
                    de < 1e-6 && dd < 1e-6,
                    "{} {preset} v = {v}: e {} vs {} ({de:e}), delta_max {} vs {} ({dd:e})",
                    spec.name,
                    r.e,
                    cf.e,
                    r.delta_max,
                    cf.delta_max
                );
                checked += 1;
            }
        }
    }
    // hertz, linear-dashpot, hunt-crossley, lankarani-nikravesh, walton-braun, thornton,
    // jackson-green, tabor-hardening, li-yang-shi: 9 laws x 5 speeds x 2 pairs.
    assert_eq!(checked, 90);
}

#[test]
fn every_law_closes_its_energy_balance() {
    let reg = Registry::builtin();
    let b = balls("copper-fe", 0.02);
    for spec in &reg.normal {
        for tang in &reg.tangential {
            for (v, vt) in [(0.1, 0.0), (1.0, 0.3), (5.0, 5.0)] {
                let r = run(&reg, &b, spec.name, tang.name, [v, vt], &[]);
                let res = r.energy_residual();
                assert!(
                    res.abs() < 1e-8,
                    "{} + {} at v = {v}, vt = {vt}: residual {res:e}",
                    spec.name,
                    tang.name
                );
                assert!(r.e > 0.0 && r.e <= 1.0 + 1e-9, "{} e = {}", spec.name, r.e);
            }
        }
    }
}

#[test]
fn the_three_phase_law_on_the_seam_is_the_closed_form_model() {
    let reg = Registry::builtin();
    let b = balls("copper-fe", 0.02);
    let pair = ContactPair::between(&b.0, &b.1, 0.3);
    for v in [0.05, 0.5, 2.0] {
        let r = run(&reg, &b, "li-yang-shi", "coulomb", [v, 0.0], &[]);
        let n = NormalImpact::solve(pair.hertz, pair.yield_pressure, v).unwrap();
        let rel = |a: f64, b: f64| (a - b).abs() / b.abs();
        assert!(rel(r.e, n.e) < 1e-6, "e {} vs {}", r.e, n.e);
        assert!(
            rel(r.delta_end, n.delta_p) < 1e-6,
            "delta_p {} vs {}",
            r.delta_end,
            n.delta_p
        );
        assert!(
            rel(r.contact_duration, n.t3) < 1e-6,
            "t3 {} vs {}",
            r.contact_duration,
            n.t3
        );
        assert!(
            rel(r.time_of_max, n.t2) < 1e-6,
            "t2 {} vs {}",
            r.time_of_max,
            n.t2
        );
        assert!(
            rel(r.phase_times[0], n.t1) < 1e-6,
            "t1 {} vs {}",
            r.phase_times[0],
            n.t1
        );
    }
}

#[test]
fn integrated_coulomb_impulse_is_the_rigid_closed_form() {
    let reg = Registry::builtin();
    let b = balls("copper-fe", 0.02);
    let pair = ContactPair::between(&b.0, &b.1, 0.3);
    // Small tangential speed: the slip stops (stick); large: it slides throughout.
    for vt in [0.05, 0.3, 3.0] {
        let r = run(&reg, &b, "li-yang-shi", "coulomb", [1.0, vt], &[]);
        let n = NormalImpact::solve(pair.hertz, pair.yield_pressure, 1.0).unwrap();
        let closed = tangential_impact(&n, 0.3, vt).impulse;
        let rel = (r.tangential_impulse - closed).abs() / closed.abs();
        assert!(
            rel < 1e-6,
            "vt = {vt}: {} vs {closed} ({rel:e})",
            r.tangential_impulse
        );
    }
}

#[test]
fn thornton_restitution_is_thorntons_published_formula() {
    // Thornton (1997): e = (6√3/5)^{1/2} [1 − (1/6)(v_y/v)²]^{1/2}
    //   × [(v_y/v) / ((v_y/v) + 2 √(6/5 − (1/5)(v_y/v)²))]^{1/4}, v_y the speed that just yields.
    let reg = Registry::builtin();
    let b = balls("copper-fe", 0.02);
    let pair = ContactPair::between(&b.0, &b.1, 0.3);
    let (law, _) = reg
        .normal("thornton")
        .unwrap()
        .build_with(&[], &pair)
        .unwrap();
    let h = pair.hertz;
    let dy = h.radius * (std::f64::consts::PI * pair.yield_pressure / (2.0 * h.modulus)).powi(2);
    let vy = (2.0 * h.energy(dy) / h.mass).sqrt();
    for ratio in [1.5, 5.0, 50.0, 500.0] {
        let v = ratio * vy;
        let x = vy / v;
        let published = (6.0 * 3f64.sqrt() / 5.0).sqrt()
            * (1.0 - x * x / 6.0).sqrt()
            * (x / (x + 2.0 * (1.2 - 0.2 * x * x).sqrt())).powf(0.25);
        let r = run(&reg, &b, "thornton", "coulomb", [v, 0.0], &[]);
        let cf = law.closed_form(v, h.mass).unwrap();
        assert!(
            (cf.e - published).abs() < 1e-12,
            "v/v_y = {ratio}: {} vs {published}",
            cf.e
        );
        assert!(
            (r.e - published).abs() < 1e-6 * published,
            "{} vs {published}",
            r.e
        );
    }
}

#[test]
fn kuwabara_kono_follows_the_viscoelastic_series() {
    // Ramírez et al. (1999): e = 1 − C1 β + C2 β² + O(β³), β = b ρ^{2/5} v^{1/5}, ρ = K/m*,
    // b the coefficient of √δ δ̇ in F/K (here (3/2) A), for a contact that ends at δ = 0.
    // C1 = 2 (5/4)^{3/5} (2/5) B(3/5, 3/2) = 1.15344 is the first-order energy loss.
    let reg = Registry::builtin();
    let b = balls("copper-fe", 0.02);
    let pair = ContactPair::between(&b.0, &b.1, 0.3);
    let rho = pair.hertz.stiffness() / pair.hertz.mass;
    let v: f64 = 1.0;
    for small in [0.003, 0.01] {
        let a = small / (1.5 * rho.powf(0.4) * v.powf(0.2));
        let over = vec![("A".to_string(), a), ("tension".to_string(), 1.0)];
        let r = run(&reg, &b, "kuwabara-kono", "coulomb", [v, 0.0], &over);
        let series = 1.0 - 1.15344 * small + 0.79826 * small * small;
        // Third-order term: |e − series| ~ small³.
        assert!(
            (r.e - series).abs() < 2.0 * small.powi(3),
            "{small}: {} vs {series}",
            r.e
        );
    }
}

#[test]
fn hertz_damped_restitution_does_not_depend_on_speed() {
    // The Tsuji form's damping scales so that e is a constant of the law (dimensional
    // analysis: the only speed-dependent group cancels).
    let reg = Registry::builtin();
    let b = balls("copper-fe", 0.02);
    let e: Vec<f64> = [0.01, 1.0, 10.0]
        .iter()
        .map(|&v| run(&reg, &b, "hertz-damped", "coulomb", [v, 0.0], &[]).e)
        .collect();
    assert!(
        (e[0] - e[2]).abs() < 1e-7 && (e[1] - e[2]).abs() < 1e-7,
        "{e:?}"
    );
}

#[test]
fn mindlin_coulomb_gives_tangential_rebound_and_tends_to_no_slip() {
    let reg = Registry::builtin();
    let b = balls("copper-fe", 0.02);
    // Small tangential speed: the contact points stick and the tangential spring oscillates
    // (its period is shorter than the contact): the slip after is neither 0 nor larger.
    let r = run(&reg, &b, "hertz", "mindlin-coulomb", [1.0, 0.02], &[]);
    let et = r.tangential_restitution().unwrap();
    assert!(
        et.abs() > 0.1 && et.abs() < 1.0,
        "tangential restitution {et}"
    );
    // Coulomb alone can only bring the slip to 0.
    let c = run(&reg, &b, "hertz", "coulomb", [1.0, 0.02], &[]);
    assert!(c.tangential_restitution().unwrap().abs() < 1e-9);
    // μ = 100: the same as the no-slip spring, but for the last instants of the contact, where
    // μF → 0 faster than the spring force and the cap binds (a relative 1e-6 effect).
    let pair = ContactPair::between(&b.0, &b.1, 100.0);
    let (n, _) = reg.normal("hertz").unwrap().build_with(&[], &pair).unwrap();
    let (t1, _) = reg
        .tangential("mindlin-coulomb")
        .unwrap()
        .build_with(&[], &pair)
        .unwrap();
    let (t2, _) = reg
        .tangential("mindlin")
        .unwrap()
        .build_with(&[], &pair)
        .unwrap();
    let go = |t: &dyn twoball::analytic::laws::TangentialLaw| {
        integrate(
            &b.0,
            &b.1,
            [0.5, 0.1],
            [-0.5, -0.1],
            n.as_ref(),
            t,
            DEFAULT_TOLERANCE,
        )
        .unwrap()
        .unwrap()
        .slip_after
    };
    let (a, bb) = (go(t1.as_ref()), go(t2.as_ref()));
    assert!((a - bb).abs() < 1e-5 * bb.abs(), "{a} vs {bb}");
}

#[test]
fn a_spin_acts_through_the_slip_it_gives_the_contact_point() {
    // A ball spinning at ω with no tangential velocity meets the partner with the contact
    // point slipping at R ω, as a ball sliding at v_t = R ω does: every tangential law gives
    // the same impulses, and the spin's energy closes the balance.
    let reg = Registry::builtin();
    let b = balls("copper-fe", 0.02);
    let pair = ContactPair::between(&b.0, &b.1, 0.3);
    let (n, _) = reg.normal("hertz").unwrap().build_with(&[], &pair).unwrap();
    let (v, slip) = (1.0, 0.4);
    let w = slip / 0.01;
    for tang in &reg.tangential {
        let (t, _) = reg
            .tangential(tang.name)
            .unwrap()
            .build_with(&[], &pair)
            .unwrap();
        let sliding = integrate(
            &b.0,
            &b.1,
            [0.5 * v, slip],
            [-0.5 * v, 0.0],
            n.as_ref(),
            t.as_ref(),
            DEFAULT_TOLERANCE,
        )
        .unwrap()
        .unwrap();
        let spinning = integrate_spinning(
            &b.0,
            &b.1,
            [0.5 * v, 0.0],
            [-0.5 * v, 0.0],
            [w, 0.0],
            n.as_ref(),
            t.as_ref(),
            DEFAULT_TOLERANCE,
        )
        .unwrap()
        .unwrap();
        let jt = sliding.tangential_impulse;
        assert!(
            (spinning.tangential_impulse - jt).abs() <= 1e-9 * jt.abs().max(1e-12),
            "{}: {} against {jt}",
            tang.name,
            spinning.tangential_impulse
        );
        assert!((spinning.slip_before - slip).abs() < 1e-12, "{}", tang.name);
        // The spin after is the spin before less R J_t / I.
        let d_spin = sliding.after.spin_after[0];
        assert!(
            (spinning.after.spin_after[0] - (w + d_spin)).abs() <= 1e-9 * w,
            "{}",
            tang.name
        );
        let res = spinning.energy_residual();
        assert!(res.abs() < 1e-8, "{}: residual {res:e}", tang.name);
    }
}
