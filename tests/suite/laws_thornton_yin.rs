//! Issue 27, the Mindlin-Deresiewicz / Thornton-Yin tangential law (`thornton-yin`): its
//! slopes are Thornton & Yin's reduced stiffness on loading, unloading and reloading; its
//! closed cycle dissipates the Mindlin-Deresiewicz loop energy; it tends to Mindlin's no-slip
//! spring as μ → ∞ and to the Coulomb impulse in gross slip; and an oblique impact's tangential
//! restitution lies between the rigid Coulomb and the no-slip values.

use twoball::analytic::friction::tangential_impact;
use twoball::analytic::impact::{integrate, LawImpact, DEFAULT_TOLERANCE};
use twoball::analytic::laws::mindlin::Mindlin;
use twoball::analytic::laws::thornton_yin::ThorntonYin;
use twoball::analytic::laws::{ContactPair, Registry, TangentialLaw};
use twoball::analytic::{Body, NormalImpact};
use twoball::material::Material;

fn balls() -> (Body, Body) {
    let m = Material::preset("copper-fe").unwrap();
    (
        Body::ball(m, 0.02, "ball1").unwrap(),
        Body::ball(m, 0.02, "ball2").unwrap(),
    )
}

fn law(name: &str, mu: f64) -> (Box<dyn TangentialLaw>, ContactPair) {
    let b = balls();
    let pair = ContactPair::between(&b.0, &b.1, mu);
    (
        Registry::builtin()
            .tangential(name)
            .unwrap()
            .build_with(&[], &pair)
            .unwrap()
            .0,
        pair,
    )
}

/// Head-on speed v_n and slip speed v_t (m/s) of the two balls meeting symmetrically.
fn impact(tangential: &str, mu: f64, vn: f64, vt: f64) -> LawImpact {
    let b = balls();
    let pair = ContactPair::between(&b.0, &b.1, mu);
    let reg = Registry::builtin();
    let (n, _) = reg.normal("hertz").unwrap().build_with(&[], &pair).unwrap();
    let (t, _) = reg
        .tangential(tangential)
        .unwrap()
        .build_with(&[], &pair)
        .unwrap();
    integrate(
        &b.0,
        &b.1,
        [0.5 * vn, 0.5 * vt],
        [-0.5 * vn, -0.5 * vt],
        n.as_ref(),
        t.as_ref(),
        DEFAULT_TOLERANCE,
    )
    .unwrap()
    .unwrap()
}

/// Contact radius a (m) and Hertz normal force F (N) at approach δ.
fn hertz(pair: &ContactPair, delta: f64) -> (f64, f64) {
    let h = pair.hertz;
    let a = (h.radius * delta).sqrt();
    (a, 4.0 / 3.0 * h.modulus * h.radius.sqrt() * delta.powf(1.5))
}

fn slope(f: impl Fn(f64) -> f64, x: f64, h: f64) -> f64 {
    (f(x + h) - f(x - h)) / (2.0 * h)
}

#[test]
fn slopes_are_thornton_yins_reduced_stiffness() {
    let mu = 0.3;
    let (t, pair) = law("thornton-yin", mu);
    let delta = 2e-5;
    let (a, n) = hertz(&pair, delta);
    let k0 = 8.0 * pair.shear_modulus * a;
    let cap = mu * n;
    let xs = 3.0 * cap / (16.0 * pair.shear_modulus * a);
    let h = 1e-6 * xs;
    let rel = |x: f64, y: f64| (x - y).abs() / y.abs();
    // Virgin loading: Mindlin's closed form and k_t = 8 G* a (1 − f/μF)^{1/3}.
    for q in [0.05, 0.3, 0.6, 0.9, 0.99] {
        let xi = q * xs;
        let f = t.force(xi, delta, n, &[], 1.0);
        let closed =
            cap * (1.0 - (1.0 - 16.0 * pair.shear_modulus * a * xi / (3.0 * cap)).powf(1.5));
        assert!(rel(f, closed) < 1e-12, "loading force {f} vs {closed}");
        let k = slope(|x| t.force(x, delta, n, &[], 1.0), xi, h);
        let ty = k0 * (1.0 - f / cap).cbrt();
        assert!(rel(k, ty) < 1e-6, "loading slope {k} vs {ty} at {q}");
        assert!(rel(t.force(-xi, delta, n, &[], -1.0), -f) < 1e-14);
    }
    // Beyond full slip the force is the Coulomb limit.
    assert!(rel(t.force(1.5 * xs, delta, n, &[], 1.0), cap) < 1e-14);
    // Unloading from the turning point ξ* = 0.7 ξ_s, then reloading from ξ** = −0.4 ξ_s.
    let turn = 0.7 * xs;
    let f_turn = t.force(turn, delta, n, &[], 1.0);
    for d in [0.1, 0.5, 1.0, 1.3] {
        let xi = turn - d * xs;
        let f = t.force(xi, delta, n, &[turn], -1.0);
        let k = slope(|x| t.force(x, delta, n, &[turn], -1.0), xi, h);
        let ty = k0 * (1.0 - (f_turn - f) / (2.0 * cap)).cbrt();
        assert!(rel(k, ty) < 1e-6, "unloading slope {k} vs {ty}");
    }
    let back = -0.4 * xs;
    let f_back = t.force(back, delta, n, &[turn], -1.0);
    for d in [0.1, 0.5, 1.0] {
        let xi = back + d * xs;
        let f = t.force(xi, delta, n, &[turn, back], 1.0);
        let k = slope(|x| t.force(x, delta, n, &[turn, back], 1.0), xi, h);
        let ty = k0 * (1.0 - (f - f_back) / (2.0 * cap)).cbrt();
        assert!(rel(k, ty) < 1e-6, "reloading slope {k} vs {ty}");
    }
    // Masing: the reloading curve passes through the turning point it started below.
    assert!(rel(t.force(turn, delta, n, &[turn, back], 1.0), f_turn) < 1e-12);
}

#[test]
fn closed_cycle_dissipates_the_mindlin_deresiewicz_loop() {
    // Loop between ±f* at constant F: the area ∮ f dξ against Mindlin & Deresiewicz (1953),
    // ΔW = 9μ²F²/(10 G* a) [1 − (1 − q)^{5/3} − (5q/6)(1 + (1 − q)^{2/3})], q = f*/μF.
    let mu = 0.3;
    let (t, pair) = law("thornton-yin", mu);
    let delta = 2e-5;
    let (a, n) = hertz(&pair, delta);
    let cap = mu * n;
    let xs = 3.0 * cap / (16.0 * pair.shear_modulus * a);
    for amp in [0.1, 0.5, 0.9] {
        let xa = amp * xs;
        let q = t.force(xa, delta, n, &[], 1.0) / cap;
        let simpson = |f: &dyn Fn(f64) -> f64, x0: f64, x1: f64| {
            let m = 20_000;
            let h = (x1 - x0) / m as f64;
            (0..=m)
                .map(|i| {
                    let w = if i == 0 || i == m {
                        1.0
                    } else if i % 2 == 1 {
                        4.0
                    } else {
                        2.0
                    };
                    w * f(x0 + i as f64 * h)
                })
                .sum::<f64>()
                * h
                / 3.0
        };
        let unload = simpson(&|x| t.force(x, delta, n, &[xa], -1.0), xa, -xa);
        let reload = simpson(&|x| t.force(x, delta, n, &[xa, -xa], 1.0), -xa, xa);
        let area = unload + reload;
        let g = pair.shear_modulus;
        let closed = 9.0 * cap * cap / (10.0 * g * a)
            * (1.0 - (1.0 - q).powf(5.0 / 3.0) - 5.0 * q / 6.0 * (1.0 + (1.0 - q).powf(2.0 / 3.0)));
        assert!(
            (area.abs() - closed).abs() / closed < 1e-6,
            "loop at q = {q}: {} J vs {closed} J",
            area.abs()
        );
    }
    // Small amplitudes: the cubic law ΔW = f*³/(36 G* a μF) (first order in q).
    let q: f64 = 1e-3;
    let g = pair.shear_modulus;
    let full = 9.0 * cap * cap / (10.0 * g * a)
        * (1.0 - (1.0 - q).powf(5.0 / 3.0) - 5.0 * q / 6.0 * (1.0 + (1.0 - q).powf(2.0 / 3.0)));
    let cubic = (q * cap).powi(3) / (36.0 * g * a * cap);
    assert!((full - cubic).abs() / cubic < 1e-2, "{full} vs {cubic}");
}

#[test]
fn no_slip_limit_is_mindlin() {
    // Oblique impact; as μ grows the partial-slip law tends to Mindlin's no-slip spring, with
    // an error falling as 1/μ (μ beyond the parameter range of 100 through the law's type).
    let b = balls();
    let pair = ContactPair::between(&b.0, &b.1, 0.3);
    let (n, _) = Registry::builtin()
        .normal("hertz")
        .unwrap()
        .build_with(&[], &pair)
        .unwrap();
    let go = |t: &dyn TangentialLaw| {
        integrate(
            &b.0,
            &b.1,
            [0.5, 0.05],
            [-0.5, -0.05],
            n.as_ref(),
            t,
            DEFAULT_TOLERANCE,
        )
        .unwrap()
        .unwrap()
        .slip_after
    };
    let m = go(&Mindlin {
        shear_modulus: pair.shear_modulus,
        radius: pair.hertz.radius,
    });
    let mut last = f64::INFINITY;
    for mu in [1.0, 1e2, 1e4, 1e6] {
        let u = go(&ThorntonYin {
            shear_modulus: pair.shear_modulus,
            radius: pair.hertz.radius,
            mu,
        });
        let d = (u - m).abs() / m.abs();
        println!("mu = {mu:e}: slip after {u} vs Mindlin {m}, rel {d:e}");
        assert!(d < 0.1 * last, "no 1/mu convergence at mu = {mu}: {d:e}");
        last = d;
    }
    assert!(last < 1e-6, "mu = 1e6: {last:e}");
}

#[test]
fn gross_slip_is_the_coulomb_impulse() {
    // v_t/v_n = 5: the contact slides throughout, the force is μF, the impulse Coulomb's.
    let mu = 0.3;
    let r = impact("thornton-yin", mu, 1.0, 5.0);
    let b = balls();
    let pair = ContactPair::between(&b.0, &b.1, mu);
    let n = NormalImpact::solve(pair.hertz, f64::INFINITY, 1.0).unwrap();
    let closed = tangential_impact(&n, mu, 5.0).impulse;
    let rel = (r.tangential_impulse - closed).abs() / closed.abs();
    assert!(rel < 1e-6, "{} vs {closed}: {rel:e}", r.tangential_impulse);
}

#[test]
fn oblique_restitution_between_the_limits_and_rebound_in_partial_slip() {
    // μ = 0.3, copper-fe D = 20 mm, v_n = 1 m/s. Small v_t/v_n: partial slip, e_t strictly
    // between the rigid Coulomb value (0: the slip stops) and Mindlin's no-slip value. Gross
    // slip (v_t/v_n = 5): the Coulomb value. In between, the contact points rebound (e_t > 0),
    // as Maw, Barber & Fawcett's partial-slip theory has it, which neither limit can give.
    let mu = 0.3;
    let et = |law: &str, ratio: f64| {
        impact(law, mu, 1.0, ratio)
            .tangential_restitution()
            .unwrap()
    };
    for ratio in [0.02, 0.05, 0.1, 0.2, 0.3] {
        let (c, ty, m) = (
            et("coulomb", ratio),
            et("thornton-yin", ratio),
            et("mindlin", ratio),
        );
        println!("v_t/v_n = {ratio}: coulomb {c:.6}, thornton-yin {ty:.6}, mindlin {m:.6}");
        let (lo, hi) = (c.min(m), c.max(m));
        assert!(
            ty > lo + 1e-3 && ty < hi - 1e-3,
            "{ty} not inside [{lo}, {hi}]"
        );
    }
    for ratio in [0.5, 0.7, 1.0] {
        let ty = et("thornton-yin", ratio);
        println!("v_t/v_n = {ratio}: thornton-yin {ty:.6}");
        assert!(ty > 0.1, "no tangential rebound at {ratio}: {ty}");
    }
    let (c, ty) = (et("coulomb", 5.0), et("thornton-yin", 5.0));
    assert!((ty - c).abs() < 1e-6 * c.abs(), "gross slip: {ty} vs {c}");
}
