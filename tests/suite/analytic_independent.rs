//! An independent implementation of eqs. 10–33 (plain numerical quadrature of the printed
//! integrals, tanh–sinh rule, no closed forms) against the library and the `twoball analytic`
//! command, for several materials, diameters, unequal balls and speeds.

use std::f64::consts::PI;
use std::process::Command;
use twoball::analytic::{collide, Body};
use twoball::Material;

/// ∫_a^b f(x) dx by the tanh–sinh (double-exponential) rule, which tolerates inverse-square-
/// root singularities at both ends. `f` receives x; nodes approach the ends without rounding
/// onto them.
fn tanh_sinh(f: impl Fn(f64) -> f64, a: f64, b: f64) -> f64 {
    let h = 1.0 / 64.0;
    let half = 0.5 * (b - a);
    let mut sum = 0.0;
    for k in -400..=400 {
        let t = k as f64 * h;
        let u = 0.5 * PI * t.sinh();
        let w = 0.5 * PI * t.cosh() / u.cosh().powi(2);
        // Distance from the nearer end, computed without cancellation: 1 − tanh|u| = 2/(1+e^{2|u|}).
        let gap = 2.0 / (1.0 + (2.0 * u.abs()).exp());
        if gap == 0.0 || w < 1e-300 {
            continue;
        }
        let x = if u < 0.0 {
            a + half * gap
        } else {
            b - half * gap
        };
        sum += w * f(x);
    }
    sum * half * h
}

struct Ball {
    et: f64,
    sp: f64,
    r: f64,
    m: f64,
}

fn ball(name: &str, d: f64) -> Ball {
    let mat = Material::preset(name).unwrap();
    Ball {
        et: mat.youngs / (1.0 - mat.nu * mat.nu),
        sp: (1.0 + PI / 2.0) * mat.yield_strength,
        r: d / 2.0,
        m: mat.rho * 4.0 / 3.0 * PI * (d / 2.0).powi(3),
    }
}

/// (e, δ1, δ2, δp, t1, t2, t3, v1⁺, v2⁺, η) straight from the printed equations.
fn paper(b1: &Ball, b2: &Ball, v1: f64, v2: f64) -> [f64; 10] {
    let et = b1.et * b2.et / (b1.et + b2.et);
    let r = b1.r * b2.r / (b1.r + b2.r);
    let m = b1.m * b2.m / (b1.m + b2.m);
    let sp = b1.sp.min(b2.sp);
    let vr = v1 - v2;
    let c = 16.0 * et * r.sqrt() / (15.0 * m);
    let d1 = r * (PI * sp / (2.0 * et)).powi(2); // eq. 10
    let rate1 = (vr * vr - c * d1.powf(2.5)).sqrt(); // eq. 12
    let t1 = tanh_sinh(|d| 1.0 / (vr * vr - c * d.powf(2.5)).sqrt(), 0.0, d1); // eq. 14
    let a = (sp * PI).powi(2) * r / (6.0 * et * et);
    let d2 = (a * a + m * rate1 * rate1 / (PI * r * sp)).sqrt() + a / 2.0; // eq. 19
    let v2sq = |d: f64| {
        rate1 * rate1
            + sp.powi(5) * PI.powi(5) * r.powi(3) / (48.0 * m * et.powi(4))
            + sp.powi(3) * PI.powi(3) * r * r / (6.0 * m * et * et) * d
            - PI * r * sp / m * d * d
    }; // eqs. 18/20 with E_t⁴
       // Nodes so close to δ₂ that rounding makes δ̇² ≤ 0 carry negligible weight: skip them.
    let inv = |q: f64| if q > 0.0 { 1.0 / q.sqrt() } else { 0.0 };
    let t2 = t1 + tanh_sinh(|d| inv(v2sq(d)), d1, d2); // eq. 21
    let p2 = PI * r * sp * d2 - sp.powi(3) * PI.powi(3) * r * r / (12.0 * et * et);
    let dp = d2 - (3.0 * p2 / (4.0 * et * r.sqrt())).powf(2.0 / 3.0); // eq. 24
    let t3 = t2
        + tanh_sinh(
            |d| inv(c * ((d2 - dp).powf(2.5) - (d - dp).powf(2.5))),
            dp,
            d2,
        ); // eq. 29
    let vplus = (c * (d2 - dp).powf(2.5)).sqrt(); // eq. 27
    let e = vplus / vr; // eq. 30
    let v1a = v1 - (1.0 + e) * b2.m * vr / (b1.m + b2.m); // eq. 32
    let v2a = v2 + (1.0 + e) * b1.m * vr / (b1.m + b2.m);
    let ke0 = 0.5 * b1.m * v1 * v1 + 0.5 * b2.m * v2 * v2;
    let ke1 = 0.5 * b1.m * v1a * v1a + 0.5 * b2.m * v2a * v2a;
    let eta = (ke0 - ke1) / (2.0 * PI * ke0); // eq. 33
    [e, d1, d2, dp, t1, t2, t3, v1a, v2a, eta]
}

const CASES: [(&str, f64, &str, f64, f64, f64); 6] = [
    ("copper-fe", 0.02, "copper-fe", 0.02, 1.0, -1.0),
    ("steel", 0.03, "steel", 0.03, 2.5, 0.0),
    ("copper", 0.01, "aluminum", 0.025, 1.0, -0.5),
    ("glass", 0.015, "cast-iron", 0.005, 0.7, -2.5),
    ("wood", 0.04, "concrete", 0.02, 3.0, 1.0),
    ("alumina", 0.005, "copper-fe", 0.03, 5.0, -1.0),
];

#[test]
fn library_agrees_with_the_printed_integrals() {
    for (n1, d1, n2, d2, v1, v2) in CASES {
        let want = paper(&ball(n1, d1), &ball(n2, d2), v1, v2);
        let b1 = Body::ball(Material::preset(n1).unwrap(), d1, "b1").unwrap();
        let b2 = Body::ball(Material::preset(n2).unwrap(), d2, "b2").unwrap();
        let c = collide(&b1, &b2, [v1, 0.0], [v2, 0.0]).unwrap();
        let n = c.normal.unwrap();
        assert!(n.yielded, "{n1}/{n2}");
        let got = [
            n.e,
            n.delta1,
            n.delta2,
            n.delta_p,
            n.t1,
            n.t2,
            n.t3,
            c.after.v1_after[0],
            c.after.v2_after[0],
            c.eta,
        ];
        for (k, (g, w)) in got.iter().zip(want).enumerate() {
            let tol = if (4..=6).contains(&k) { 1e-7 } else { 1e-9 };
            assert!(
                ((g - w) / w).abs() < tol,
                "{n1}/{n2} v={v1},{v2} item {k}: {g} vs {w}"
            );
        }
    }
}

#[test]
fn cli_json_agrees_with_the_printed_integrals() {
    for (n1, d1, n2, d2, v1, v2) in CASES.iter().take(4) {
        let out = Command::new(env!("CARGO_BIN_EXE_twoball"))
            .args(["analytic", "--json", "--material", n1, "--material2", n2])
            .args([
                "--diameter",
                &d1.to_string(),
                "--diameter2",
                &d2.to_string(),
            ])
            .args(["--v1", &v1.to_string(), "--v2", &v2.to_string()])
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let j: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        let want = paper(&ball(n1, *d1), &ball(n2, *d2), *v1, *v2);
        let keys = [
            "e", "delta1", "delta2", "delta_p", "t1", "t2", "t3", "v1_after", "v2_after", "eta",
        ];
        for (k, key) in keys.iter().enumerate() {
            let g = j[key].as_f64().unwrap();
            assert!(
                ((g - want[k]) / want[k]).abs() < 1e-6,
                "{key}: {g} vs {}",
                want[k]
            );
        }
    }
}

#[test]
fn acceptance_case_from_the_command_line() {
    let out = Command::new(env!("CARGO_BIN_EXE_twoball"))
        .args([
            "analytic",
            "--json",
            "--material",
            "copper-fe",
            "--diameter",
            "0.02",
        ])
        .args(["--v1", "1", "--v2", "-1"])
        .output()
        .unwrap();
    assert!(out.status.success());
    let j: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!((j["e"].as_f64().unwrap() - 0.342645).abs() < 1e-4);
    assert!((j["t3"].as_f64().unwrap() / 1.409233e-4 - 1.0).abs() < 1e-3);
    assert_eq!(j["impact"], serde_json::Value::Bool(true));
}

/// The worked case's golden numbers (tests/analytic_three_phase.rs,
/// `worked_case_of_the_notes_to_four_digits`) derived here, without the library: two D = 20 mm
/// copper-fe balls at +1 / −1 m/s through the printed integrals. The library is checked
/// against the same constants there, so neither side's output defines them.
#[test]
fn worked_case_numbers_come_from_the_printed_integrals() {
    let b = ball("copper-fe", 0.02);
    let [e, d1, d2, dp, t1, t2, t3, v1a, v2a, eta] = paper(&b, &b, 1.0, -1.0);
    let golden = [
        (d1, 1.7984e-7),
        (d2, 1.28080e-4),
        (dp, 1.09292e-4),
        (e, 0.342645),
        (t1, 8.992e-8),
        (t2, 1.005769e-4),
        (t3, 1.409233e-4),
        (v1a, -0.342645),
        (v2a, 0.342645),
        (eta, 0.140469),
    ];
    for (i, (got, want)) in golden.iter().enumerate() {
        assert!(
            ((got - want) / want).abs() < 5e-5,
            "quantity {i}: printed integrals give {got}, golden {want}"
        );
    }
}
