//! Hertz elastic-impact closed forms against direct ODE integration of m* δ̈ = −K δ^{3/2}.

use twoball::analytic::hertz::{effective_mass, effective_modulus, effective_radius};
use twoball::analytic::HertzPair;

/// Integrates m δ̈ = −K δ^{3/2} from δ = 0, δ̇ = v with classical RK4 until δ returns below 0;
/// returns (contact duration, max approach, peak force), the end time found by linear
/// interpolation of the last step.
fn rk4_impact(p: &HertzPair, v: f64, steps_estimate: usize) -> (f64, f64, f64) {
    let k = p.stiffness();
    let m = p.mass;
    let acc = |d: f64| -k * d.max(0.0).powf(1.5) / m;
    let dt = 3.0 * p.max_approach(v) / v / steps_estimate as f64;
    let (mut t, mut d, mut u) = (0.0, 0.0, v);
    let (mut dmax, mut fmax) = (0.0_f64, 0.0_f64);
    loop {
        let (k1d, k1u) = (u, acc(d));
        let (k2d, k2u) = (u + 0.5 * dt * k1u, acc(d + 0.5 * dt * k1d));
        let (k3d, k3u) = (u + 0.5 * dt * k2u, acc(d + 0.5 * dt * k2d));
        let (k4d, k4u) = (u + dt * k3u, acc(d + dt * k3d));
        let dn = d + dt / 6.0 * (k1d + 2.0 * k2d + 2.0 * k3d + k4d);
        let un = u + dt / 6.0 * (k1u + 2.0 * k2u + 2.0 * k3u + k4u);
        if dn < 0.0 {
            return (t + dt * d / (d - dn), dmax, fmax);
        }
        t += dt;
        d = dn;
        u = un;
        dmax = dmax.max(d);
        fmax = fmax.max(k * d.powf(1.5));
    }
}

#[test]
fn closed_forms_match_ode_integration() {
    // Two steel-like balls of different size and an elastic ball on a rigid wall.
    let et = 210e9 / (1.0 - 0.27f64.powi(2));
    let cases = [
        HertzPair::new(
            effective_modulus(et, et),
            effective_radius(0.01, 0.004),
            effective_mass(0.033, 0.002),
        ),
        HertzPair::new(
            effective_modulus(et, f64::INFINITY),
            effective_radius(0.01, f64::INFINITY),
            effective_mass(0.033, f64::INFINITY),
        ),
    ];
    for p in cases {
        for v in [0.1, 1.0, 3.0] {
            let (tc, dmax, fmax) = rk4_impact(&p, v, 200_000);
            let rel = |a: f64, b: f64| ((a - b) / b).abs();
            assert!(
                rel(p.contact_duration(v), tc) < 1e-6,
                "t_c {} vs {}",
                p.contact_duration(v),
                tc
            );
            assert!(rel(p.max_approach(v), dmax) < 1e-7);
            assert!(rel(p.peak_force(v), fmax) < 1e-7);
        }
    }
}

#[test]
fn contact_radius_follows_the_approach() {
    let p = HertzPair::new(1e11, 0.005, 0.01);
    assert!((p.contact_radius(2e-6) - (0.005f64 * 2e-6).sqrt()).abs() < 1e-18);
    assert_eq!(p.contact_radius(-1.0), 0.0);
    assert_eq!(p.force(-1.0), 0.0);
}
