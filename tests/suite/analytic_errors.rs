//! Every bad-input path of the library entry points returns an error naming the field; plus
//! random collisions obey the conservation laws and bounds.

use proptest::prelude::*;
use twoball::analytic::{collide, collide_with_mu, Body};
use twoball::Material;

fn copper() -> Material {
    Material::preset("copper-fe").unwrap()
}

#[test]
fn library_rejects_bad_input_naming_the_field() {
    let b = Body::ball(copper(), 0.02, "ball1").unwrap();
    let cases: Vec<(twoball::Error, &str)> = vec![
        (
            Body::ball(copper(), -0.02, "ball1").unwrap_err(),
            "ball1.diameter",
        ),
        (
            Body::ball(copper(), f64::NAN, "ball2").unwrap_err(),
            "ball2.diameter",
        ),
        (
            Body::ball(
                Material {
                    nu: 0.6,
                    ..copper()
                },
                0.02,
                "ball2",
            )
            .unwrap_err(),
            "ball2.material.nu",
        ),
        (
            collide(&b, &b, [f64::NAN, 0.0], [0.0, 0.0]).unwrap_err(),
            "v1",
        ),
        (
            collide(&b, &b, [1.0, f64::INFINITY], [0.0, 0.0]).unwrap_err(),
            "v1t",
        ),
        (
            collide(&b, &b, [1.0, 0.0], [0.0, f64::NAN]).unwrap_err(),
            "v2t",
        ),
        (
            collide_with_mu(&b, &b, [1.0, 0.0], [0.0, 0.0], -0.1).unwrap_err(),
            "mu",
        ),
        (
            collide(&b, &Body::RigidWall, [1.0, 0.0], [0.5, 0.0]).unwrap_err(),
            "v2",
        ),
        (
            collide(&Body::RigidWall, &b, [1.0, 0.0], [0.0, 0.0]).unwrap_err(),
            "ball1",
        ),
    ];
    for (err, field) in cases {
        let msg = err.to_string();
        assert!(msg.starts_with(&format!("invalid {field} =")), "{msg}");
        assert!(msg.contains("allowed"), "{msg}");
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]
    #[test]
    fn random_collisions_conserve_momentum_and_lose_energy(
        i in 0usize..10, j in 0usize..10,
        d1 in 0.002f64..0.05, d2 in 0.002f64..0.05,
        v1 in -5.0f64..5.0, v2 in -5.0f64..5.0, t1 in -2.0f64..2.0, t2 in -2.0f64..2.0,
        mu in 0.0f64..0.8,
    ) {
        let names = twoball::material::PRESET_NAMES;
        let b1 = Body::ball(Material::preset(names[i]).unwrap(), d1, "b1").unwrap();
        let b2 = Body::ball(Material::preset(names[j]).unwrap(), d2, "b2").unwrap();
        let c = collide_with_mu(&b1, &b2, [v1, t1], [v2, t2], mu).unwrap();
        let (m1, m2) = (b1.mass(), b2.mass());
        for k in 0..2 {
            let p0 = m1 * c.v1_before[k] + m2 * c.v2_before[k];
            let p1 = m1 * c.after.v1_after[k] + m2 * c.after.v2_after[k];
            prop_assert!((p0 - p1).abs() <= 1e-12 * (m1 + m2) * 10.0);
        }
        prop_assert!(c.after.energy_after <= c.energy_before * (1.0 + 1e-12));
        prop_assert!(c.eta >= 0.0 && c.eta_friction >= 0.0 && c.eta_impulse >= 0.0);
        prop_assert!(c.eta <= 1.0 / (2.0 * std::f64::consts::PI) + 1e-12);
        if let Some(n) = c.normal {
            prop_assert!(n.e > 0.0 && n.e <= 1.0);
            prop_assert!(n.t1 <= n.t2 && n.t2 < n.t3);
            prop_assert!(0.0 <= n.delta_p && n.delta_p < n.delta2 && n.delta1 <= n.delta2);
        } else {
            prop_assert!(v1 <= v2);
        }
    }
}
