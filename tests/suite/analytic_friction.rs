//! The friction revision: Coulomb stick/slip impulse, Figure 4's exit phase, eqs. 42–43.

use twoball::analytic::friction::TangentialExit;
use twoball::analytic::{collide_with_mu, Body, Phase};
use twoball::Material;

fn ball(name: &str, d: f64) -> Body {
    Body::ball(Material::preset(name).unwrap(), d, "ball").unwrap()
}

/// Relative tangential speed of the contact points after impact, from the velocities and spins.
fn slip_after(b1: &Body, b2: &Body, c: &twoball::analytic::Collision) -> f64 {
    (c.after.v1_after[1] + c.after.spin_after[0] * b1.radius())
        - (c.after.v2_after[1] - c.after.spin_after[1] * b2.radius())
}

#[test]
fn sliding_impact_loses_zhangs_energy() {
    let (b1, b2) = (ball("steel", 0.02), ball("copper", 0.016));
    let c = collide_with_mu(&b1, &b2, [1.0, 2.0], [-0.5, -1.0], 0.1).unwrap();
    let t = c.tangential.unwrap();
    assert_eq!(t.exit, TangentialExit::Slip);
    // Eq. 42 is the loss of an impact that slides throughout: compare with the velocities.
    let lost = c.energy_before - c.after.energy_after;
    assert!(
        ((lost - c.zhang_loss) / lost).abs() < 1e-9,
        "{lost} {}",
        c.zhang_loss
    );
    assert!(slip_after(&b1, &b2, &c) > 0.0);
}

#[test]
fn sticking_impact_stops_the_slip_in_the_phase_figure_4_predicts() {
    let b = ball("copper-fe", 0.02);
    let mu = 0.2;
    let base = collide_with_mu(&b, &b, [1.0, 0.0], [-1.0, 0.0], mu).unwrap();
    let n = base.normal.unwrap();
    let (m, vr) = (n.pair.mass, n.approach_speed);
    // Slip stops when μ m (v_r − δ̇) = (2/7) m v_rt: choose v_rt for δ̇ inside each phase.
    let rate_end1 = n.delta1_rate;
    let cases = [
        (0.5 * (vr + rate_end1), Phase::ElasticCompression),
        (0.5 * rate_end1, Phase::ElastoplasticCompression),
        (-0.5 * n.rebound_speed, Phase::ElasticRecovery),
    ];
    for (rate, phase) in cases {
        let v_rt = 3.5 * mu * (vr - rate);
        let c = collide_with_mu(&b, &b, [1.0, v_rt], [-1.0, 0.0], mu).unwrap();
        match c.tangential.unwrap().exit {
            TangentialExit::Stick {
                phase: p,
                time,
                approach,
            } => {
                assert_eq!(p, phase);
                let (d, dd) = n.state_at(time);
                assert!((dd - rate).abs() < 1e-6 * vr, "{dd} vs {rate}");
                assert!((d - approach).abs() < 1e-6 * n.delta2);
                // Figure 4: slip ends in phase 1 exactly when δ_t < δ₁.
                assert_eq!(approach < n.delta1, phase == Phase::ElasticCompression);
            }
            other => panic!("expected stick, got {other:?}"),
        }
        assert!(slip_after(&b, &b, &c).abs() < 1e-12);
        // Stick loses (1/7) m* v_rt² on top of the normal loss.
        let lost = c.energy_before - c.after.energy_after;
        let normal = 0.5 * m * vr * vr * (1.0 - n.e * n.e);
        assert!((lost - normal - m * v_rt * v_rt / 7.0).abs() < 1e-9 * lost);
    }
}

#[test]
fn eq_43_adds_the_linear_friction_term_to_eq_33() {
    let b = ball("copper", 0.02);
    let (vn, vt, mu) = (1.0, 0.1, 0.2);
    let c = collide_with_mu(&b, &b, [vn, vt], [-vn, -vt], mu).unwrap();
    let e = c.normal.unwrap().e;
    let m = b.mass();
    let ke = m * (vn * vn + vt * vt);
    let num = 0.5 * (m / 2.0) * (2.0 * vn).powi(2) * (1.0 - e * e)
        + (m / 2.0) * (1.0 + e) * mu * (2.0 * vn) * (2.0 * vt);
    assert!((c.eta_friction - num / (2.0 * std::f64::consts::PI * ke)).abs() < 1e-12);
    assert!(c.eta_friction > c.eta * (vn * vn) / (vn * vn + vt * vt));
}
