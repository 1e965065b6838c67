//! Normal elastic impact of two identical copper balls
//! (yield set far above any stress) against Hertz's closed forms, energy over the impact,
//! and the sensitivity to the penalty factor.
//!
//! The refined runs are `#[ignore]`d (minutes each); rerun them with
//! `cargo test --release --test suite contact_hertz:: -- --ignored --nocapture`.
//! Relative speeds are those of the pair; the quarter ball against the frictionless wall
//! moves at half of it (the wall is the pair's mirror plane).

use crate::contact_support::hertz;

use hertz::{
    finite_ball_reference, hertz_pulse, impact, stiffened_pulse, windowed_peak, Impact, DIAMETER,
};
use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};
use twoball::analytic::hertz::HertzPair;
use twoball::fe::contact::PenaltyRule;

fn fkn(f: f64) -> PenaltyRule {
    PenaltyRule::Fkn { factor: f }
}

/// The wall impact at 2 m/s with FKN 10 on the (`pole`, `size`) mesh (m), run once per test
/// process: the ladder, the refined run, the penalty, element and geometry checks share runs.
fn wall_2_m_s(pole: f64, size: f64) -> Impact {
    type Cache = Mutex<HashMap<(u64, u64), Arc<OnceLock<Impact>>>>;
    static CACHE: OnceLock<Cache> = OnceLock::new();
    let cell = CACHE
        .get_or_init(Cache::default)
        .lock()
        .unwrap()
        .entry((pole.to_bits(), size.to_bits()))
        .or_default()
        .clone();
    cell.get_or_init(|| impact(2.0, pole, size, fkn(10.0), false))
        .clone()
}

fn report(label: &str, r: &Impact) {
    let (ed, et, ef) = r.errors();
    println!(
        "{label}: {} elements, {} steps | delta_max {:.4e} m ({:+.2}%) | t_c {:.4e} s ({:+.2}%) | \
         F_peak {:.4e} N ({:+.2}% t_c/20 window vs windowed Hertz, {:+.2}% t_c/100, {:+.2}% raw) | \
         e {:.5} | energy {:.2e} | residual {:.1e} | penetration/delta {:.4}",
        r.elements,
        r.steps,
        r.delta_max,
        100.0 * ed,
        r.duration,
        100.0 * et,
        r.peak_force_window,
        100.0 * r.force_window_error(),
        100.0 * ef,
        100.0 * (r.peak_force / r.hertz_force - 1.0),
        r.restitution,
        r.energy_error,
        r.residual_contact_energy,
        r.penetration_ratio
    );
    let w: Vec<String> = r
        .windows
        .iter()
        .map(|(d, f, h)| format!("t_c/{d}: {:+.2}%", 100.0 * (f / h - 1.0)))
        .collect();
    println!("  windowed peak force vs windowed Hertz: {}", w.join(", "));
    let (fd, ft, ff) = r.finite_ball_errors();
    println!(
        "  against the finite-ball reference (Hertz stiffened as CalculiX finds a finite ball): \
         delta_max {:+.2}%, t_c {:+.2}%, F_peak {:+.2}% (t_c/20 window)",
        100.0 * fd,
        100.0 * ft,
        100.0 * ff
    );
}

/// Energy, restitution and clean separation: what every impact must satisfy. An elastic impact
/// loses only what stays in the balls' vibration: e measured 0.99976 on the coarsest mesh of
/// the ladder (200 µm pole), 0.99996-1.00000 on the finer ones (verification/contact-penalty.md), so
/// e must lie in [0.999, 1.0001] (above 1 the contact would have created energy).
fn check_impact_invariants(r: &Impact) {
    assert!(
        (0.999..=1.0001).contains(&r.restitution),
        "restitution {}",
        r.restitution
    );
    assert!(r.energy_error < 0.01, "energy drift {}", r.energy_error);
    assert!(
        r.residual_contact_energy.abs() < 1e-12,
        "contact energy left {}",
        r.residual_contact_energy
    );
}

/// The 2 m/s impact on the 200 µm / 4 mm mesh (1,040 elements) against the finite-ball
/// reference (the exact finite ball, not Hertz's half-space). The 2 m/s ladder against that
/// reference (verification/contact-penalty.md, "The free ball") gives +4.34 / +3.03 / −0.86 %
/// on this mesh, +1.54 / +1.36 / −0.67 % on the 100 µm mesh of
/// `refined_quarter_ball_on_frictionless_wall_2_m_s`, +0.63 / +0.52 / −0.36 % on the 50 µm
/// mesh (δ_max / t_c / F_peak, t_c/20 window): converging to it. The bounds are the two-ball
/// test's below (5 %, 3.5 %, 1 %).
#[test]
fn quarter_ball_on_frictionless_wall_matches_hertz_at_2_m_s() {
    let r = wall_2_m_s(2e-4, 4e-3);
    report("wall 2 m/s pole 0.2 mm", &r);
    check_impact_invariants(&r);
    let (fd, ft, ff) = r.finite_ball_errors();
    assert!(
        fd.abs() < 0.05 && ft.abs() < 0.035 && ff.abs() < 0.01,
        "against the finite-ball reference: delta {fd}, duration {ft}, force {ff}"
    );
}

/// The wall impact on the 100 µm / 2 mm mesh (`--ignored`, about a minute): bounds of 2 %
/// (δ_max, t_c) and 1 % (force) hold this mesh and anything more accurate, and fail the
/// 200 µm mesh's error.
#[test]
#[ignore]
fn refined_quarter_ball_on_frictionless_wall_2_m_s() {
    let r = wall_2_m_s(1e-4, 2e-3);
    report("wall 2 m/s pole 0.1 mm", &r);
    check_impact_invariants(&r);
    let (fd, ft, ff) = r.finite_ball_errors();
    assert!(
        fd.abs() < 0.02 && ft.abs() < 0.02 && ff.abs() < 0.01,
        "against the finite-ball reference: delta {fd}, duration {ft}, force {ff}"
    );
}

#[test]
fn two_balls_with_two_pass_contact_match_hertz_at_2_m_s() {
    // The deformable pair on a coarse mesh (pole element 0.2 mm, a ≈ 2.3 elements) against
    // the finite-ball reference. Measured +3.93 % / +2.60 % / −0.65 % (δ_max / t_c / F_peak);
    // the mirror-image wall run on the 200 µm mesh gives +4.34 / +3.03 / −0.86 %
    // (verification/contact-penalty.md, "The free ball"), and the errors shrink with the pole element.
    // The refined comparison is `refined_two_balls_2_m_s`.
    let pair = impact(2.0, 2e-4, 3e-3, fkn(10.0), true);
    report("ball-ball 2 m/s pole 0.2 mm", &pair);
    check_impact_invariants(&pair);
    let (fd, ft, ff) = pair.finite_ball_errors();
    assert!(
        fd.abs() < 0.05 && ft.abs() < 0.035 && ff.abs() < 0.01,
        "against the finite-ball reference: delta {fd}, duration {ft}, force {ff}"
    );
}

/// The two-ball (two-pass) model on the mesh of the cargo-test wall run, against the
/// finite-ball reference with the wall run's bounds (that run: +1.54 / +1.36 / −0.67 %).
#[test]
#[ignore]
fn refined_two_balls_2_m_s() {
    let r = impact(2.0, 1e-4, 2e-3, fkn(10.0), true);
    report("ball-ball 2 m/s pole 1.0e-4 m", &r);
    check_impact_invariants(&r);
    let (fd, ft, ff) = r.finite_ball_errors();
    assert!(
        fd.abs() < 0.02 && ft.abs() < 0.02 && ff.abs() < 0.01,
        "against the finite-ball reference: delta {fd}, duration {ft}, force {ff}"
    );
}

/// A refined run at relative speed `v` (m/s) with pole element `pole` (m, about a/10) and
/// far-field size `size` (m), δ_max, t_c and the peak force against Hertz; the peak force is the t_c/20 moving average against the same average of Hertz's pulse
/// (raw and other windows printed beside it). At 2 m/s Hertz is not within 1 %: on 50 µm / 1 mm,
/// δ_max −0.76 %, t_c −1.05 %, force +1.74 % (the same for every window from t_c/100 to
/// t_c/6: systematic, not noise; verification/contact-penalty.md), and the exact finite ball is
/// further still from Hertz (its quasi-static image, CalculiX's free ball: −1.38 / −1.56 /
/// +2.13 %). The Hertz bounds below are therefore 2.5 %, a sanity check; against the
/// finite-ball reference (Hertz stiffened by that CalculiX fit) all three quantities must be
/// within 1 %.
fn refined(v: f64, pole: f64, size: f64) {
    let r = if v == 2.0 {
        wall_2_m_s(pole, size)
    } else {
        impact(v, pole, size, fkn(10.0), false)
    };
    report(
        &format!("wall {v} m/s pole {pole:.1e} m size {size:.1e} m"),
        &r,
    );
    check_impact_invariants(&r);
    let (ed, et, _) = r.errors();
    let ef = r.force_window_error();
    assert!(
        ed.abs() < 0.025 && et.abs() < 0.025 && ef.abs() < 0.025,
        "{v} m/s: delta {ed}, duration {et}, force {ef}"
    );
    let (fd, ft, ff) = r.finite_ball_errors();
    assert!(
        fd.abs() < 0.01 && ft.abs() < 0.01 && ff.abs() < 0.01,
        "{v} m/s against the finite-ball reference: delta {fd}, duration {ft}, force {ff}"
    );
}

#[test]
#[ignore]
fn refined_hertz_2_m_s() {
    refined(2.0, 5e-5, 1e-3);
}

#[test]
#[ignore]
fn refined_hertz_0_5_m_s() {
    refined(0.5, 3e-5, 2e-3);
}

#[test]
#[ignore]
fn refined_hertz_0_1_m_s() {
    refined(0.1, 2e-5, 2e-3);
}

/// Mesh ladder at 2 m/s refining the pole and the far field together (verification/contact-penalty.md).
/// The errors against Hertz do not shrink monotonically to under 1 %, because the
/// converged finite ball is not Hertz's half-space. Against Hertz
/// (verification/contact-penalty.md): 200 µm / 4 mm: δ_max +2.91 %, t_c +1.43 %, force +1.23 %; 100 µm / 2 mm:
/// +0.14 %, −0.23 %, +1.43 %; 70 µm / 1.4 mm: −0.44 %, −0.74 %, +1.58 %; 50 µm / 1 mm:
/// −0.76 %, −1.05 %, +1.74 %, heading for the free-ball reference's −1.38 / −1.56 / +2.13 %.
/// What this test holds: every run conserves energy and rebounds elastically, the finer
/// meshes stay within 2.5 % of Hertz, and against the finite-ball reference all three errors
/// shrink on every refinement, the finest within 1 %.
#[test]
#[ignore]
fn convergence_table_2_m_s() {
    let mut finite = Vec::new();
    for (k, (pole, size)) in [(2e-4, 4e-3), (1e-4, 2e-3), (7e-5, 1.4e-3), (5e-5, 1e-3)]
        .into_iter()
        .enumerate()
    {
        let r = wall_2_m_s(pole, size);
        report(
            &format!("wall 2 m/s pole {pole:.1e} m size {size:.1e} m"),
            &r,
        );
        check_impact_invariants(&r);
        let (ed, et, _) = r.errors();
        let ef = r.force_window_error();
        if k > 0 {
            assert!(
                ed.abs() < 0.025 && et.abs() < 0.025 && ef.abs() < 0.025,
                "pole {pole}: delta {ed}, duration {et}, force {ef}"
            );
        }
        finite.push(r.finite_ball_errors());
    }
    // Against the finite-ball reference all three errors shrink on every refinement, and the
    // finest mesh is within 1 % in all three.
    for w in finite.windows(2) {
        assert!(
            w[1].0.abs() < w[0].0.abs()
                && w[1].1.abs() < w[0].1.abs()
                && w[1].2.abs() < w[0].2.abs(),
            "not shrinking against the finite-ball reference: {finite:?}"
        );
    }
    let last = finite[finite.len() - 1];
    assert!(
        last.0.abs() < 0.01 && last.1.abs() < 0.01 && last.2.abs() < 0.01,
        "finest mesh against the finite-ball reference: {last:?}"
    );
}

/// Hertz's maximum approach (m), peak force (N) and contact duration (s) for two solid
/// elastic copper-fe balls of the test diameter at relative speed `v` (m/s).
fn hertz_at(v: f64) -> (f64, f64, f64) {
    let mut mat = twoball::Material::preset("copper-fe").unwrap();
    mat.yield_strength = 1e15;
    let m = std::f64::consts::PI / 6.0 * DIAMETER.powi(3) * mat.rho;
    let pair = HertzPair::new(mat.plane_strain_modulus() / 2.0, DIAMETER / 4.0, m / 2.0);
    (
        pair.max_approach(v),
        pair.peak_force(v),
        pair.contact_duration(v),
    )
}

/// The reference pulse the peak force is compared with reproduces Hertz's closed forms, and the
/// t_c/20 window lowers its peak by the expected 0.17 %.
#[test]
fn hertz_pulse_reproduces_the_closed_forms() {
    let v = 2.0;
    let (d, f, tc) = hertz_at(v);
    let p = hertz_pulse(v, d, f, 200_000);
    let duration = p.last().unwrap().0;
    let peak = p.iter().map(|x| x.1).fold(0.0, f64::max);
    assert!((duration / tc - 1.0).abs() < 1e-4, "{duration} vs {tc}");
    assert!((peak / f - 1.0).abs() < 1e-6, "{peak} vs {f}");
    let bias = windowed_peak(&p, tc / 20.0) / f - 1.0;
    assert!((bias + 0.0017).abs() < 2e-4, "window bias {bias}");
}

/// The stiffened pulse behind the finite-ball reference: a constant stiffening s scales
/// Hertz's law exactly, F = (1 + s) K δ^{3/2}, so δ_max and t_c scale by (1 + s)^{−2/5} and
/// the peak force by (1 + s)^{2/5}; and with CalculiX's free-ball stiffening at 2 m/s, δ_max
/// and the peak force agree with the first-order energy balance (verification/contact-penalty.md:
/// δ_max −1.38 %, t_c −1.56 %, F_peak +2.13 % against Hertz).
#[test]
fn stiffened_pulse_scales_as_the_closed_forms() {
    let v = 2.0;
    let (d, f, tc) = hertz_at(v);
    let s = 0.05;
    let (p, _) = stiffened_pulse(v, d, f, s, 0.0, 200_000);
    let duration = p.last().unwrap().0;
    let peak = p.iter().map(|x| x.1).fold(0.0, f64::max);
    let k = (1.0f64 + s).powf(0.4);
    assert!(
        (duration / (tc / k) - 1.0).abs() < 1e-4,
        "{duration} vs {}",
        tc / k
    );
    assert!((peak / (f * k) - 1.0).abs() < 1e-6, "{peak} vs {}", f * k);
    let (fd, ft, fp) = finite_ball_reference(v, DIAMETER / 2.0, d, f);
    let fpeak = fp.iter().map(|x| x.1).fold(0.0, f64::max);
    // First order in the stiffening s0 + β √ξ (ξ = δ/δ_H): the energy balance gives
    // δ_max/δ_H = 1 − 0.4 s0 − β/3 and F_peak/F_H = 1 + 0.4 s0 + β/2; the second-order terms
    // are of order β² (β ≈ 0.045 here), so 0.1 % is a tight but fair bound.
    let beta = hertz::FINITE_BALL_S1 * (d / DIAMETER).sqrt();
    let s0 = hertz::FINITE_BALL_S0;
    let a_over_r = (fd / DIAMETER).sqrt(); // a = √(R δ/2), R = D/2
    assert!(
        (fd / d - (1.0 - 0.4 * s0 - beta / 3.0)).abs() < 1e-3,
        "delta_max {}",
        fd / d
    );
    assert!(
        (fpeak / f - (1.0 + 0.4 * s0 + 0.5 * beta)).abs() < 1e-3,
        "F_peak {}",
        fpeak / f
    );
    assert!(
        ft < tc,
        "a stiffer law must shorten the contact: {ft} vs {tc}"
    );
    println!(
        "finite-ball reference at 2 m/s: delta_max {:+.3}%, t_c {:+.3}%, F_peak {:+.3}% (a/R {a_over_r:.4})",
        100.0 * (fd / d - 1.0),
        100.0 * (ft / tc - 1.0),
        100.0 * (fpeak / f - 1.0)
    );
}

/// Penalty sensitivity at 2 m/s (verification/contact-penalty.md): over FKN = 5 to 40
/// (a factor of 8 around the default 10) δ_max and t_c move by less than 1 %, the t_c/20
/// peak force by less than PENALTY_FORCE, and e by less than PENALTY_E; FKN = 5-20 (the
/// recommended range) also keeps the elastic invariants.
#[test]
#[ignore]
fn penalty_sensitivity_2_m_s() {
    let base = wall_2_m_s(1e-4, 2e-3);
    report("FKN 10", &base);
    for f in [5.0, 20.0, 40.0] {
        let r = impact(2.0, 1e-4, 2e-3, fkn(f), false);
        report(&format!("FKN {f}"), &r);
        let (dd, dt, df, de) = (
            r.delta_max / base.delta_max - 1.0,
            r.duration / base.duration - 1.0,
            r.peak_force_window / base.peak_force_window - 1.0,
            r.restitution - base.restitution,
        );
        println!(
            "  FKN {f} against FKN 10: delta_max {:+.2}%, t_c {:+.2}%, F_peak {:+.2}%, e {de:+.1e}",
            100.0 * dd,
            100.0 * dt,
            100.0 * df
        );
        assert!(
            dd.abs() < 0.01 && dt.abs() < 0.01,
            "FKN {f}: delta {dd}, duration {dt}"
        );
        assert!(df.abs() < PENALTY_FORCE, "FKN {f}: peak force {df}");
        assert!(de.abs() < PENALTY_E, "FKN {f}: e moved by {de}");
        if f <= 20.0 {
            check_impact_invariants(&r);
        }
    }
}

/// Largest change of the t_c/20 peak force over FKN 5-40 against FKN 10: measured −0.24 %,
/// +0.11 %, +0.17 % (FKN 5, 20, 40).
const PENALTY_FORCE: f64 = 0.005;
/// Largest change of e over FKN 5-40 against FKN 10: measured 1.5e-6, −1.5e-6, 4.8e-5.
const PENALTY_E: f64 = 2e-4;

/// Where the peak-force excess at 2 m/s comes from: the same impact (pole 100 µm, far field
/// 2 mm) with the one-point hex at three hourglass coefficients and with the B-bar hex (no
/// hourglass control). If the excess were hourglass stiffness it would follow ε_hg and vanish
/// with B-bar. Prints the rows of verification/contact-penalty.md, "Peak force: element check".
#[test]
#[ignore]
fn peak_force_element_check_2_m_s() {
    use hertz::{impact_variant, Variant};
    use twoball::fe::Formulation;
    let runs = [
        ("one-point eps_hg 0.05", Formulation::OnePoint, 0.05),
        ("one-point eps_hg 0.01", Formulation::OnePoint, 0.01),
        ("one-point eps_hg 0.15", Formulation::OnePoint, 0.15),
        ("B-bar", Formulation::BBar, 0.0),
    ];
    let mut excess = Vec::new();
    for (label, formulation, hourglass) in runs {
        let variant = Variant {
            formulation,
            hourglass,
            linear_geometry: false,
        };
        let r = if formulation == Variant::default().formulation
            && hourglass == Variant::default().hourglass
        {
            wall_2_m_s(1e-4, 2e-3) // the default element: the shared run
        } else {
            impact_variant(2.0, 1e-4, 2e-3, fkn(10.0), 0.0, false, variant)
        };
        report(label, &r);
        check_impact_invariants(&r);
        excess.push((label, r.force_window_error()));
    }
    // What verification/contact-penalty.md concludes: the excess (+1.37 to +1.46 % over a 15-fold
    // change of ε_hg, +1.29 % with B-bar) is not the hourglass control nor the one-point
    // integration. Each variant is within 0.3 % of the default element's excess and keeps
    // more than +1 %: an excess that followed ε_hg or vanished with B-bar fails.
    let default = excess[0].1;
    for (label, x) in &excess {
        assert!(
            (x - default).abs() < 0.003 && *x > 0.01,
            "{label}: excess {:+.2} % against the default element's {:+.2} %: {excess:?}",
            100.0 * x,
            100.0 * default
        );
    }
}

/// The peak-force excess against the geometry of the elements: the same impact with
/// geometrically linear elements (reference configuration, Hertz's small-displacement
/// assumption) at the three speeds of the contact tests. Prints the rows of verification/contact-penalty.md,
/// "Peak force: large against small displacements".
#[test]
#[ignore]
fn peak_force_linear_geometry() {
    use hertz::{impact_variant, Variant};
    let large = wall_2_m_s(1e-4, 2e-3);
    report("large geometry 2 m/s pole 1.0e-4 m size 2.0e-3 m", &large);
    for (v, pole, size) in [(2.0, 1e-4, 2e-3), (0.5, 3e-5, 2e-3)] {
        let r = impact_variant(
            v,
            pole,
            size,
            fkn(10.0),
            0.0,
            false,
            Variant {
                linear_geometry: true,
                ..Variant::default()
            },
        );
        report(
            &format!("linear geometry {v} m/s pole {pole:.1e} m size {size:.1e} m"),
            &r,
        );
        check_impact_invariants(&r);
        // What verification/contact-penalty.md concludes: the large-displacement kinematics are not
        // the excess (linear geometry +1.53 % against +1.43 % at 2 m/s): small-displacement
        // elements keep the excess within 0.3 % of the large-displacement run and above +1 %.
        if v == 2.0 {
            let (lin, big) = (r.force_window_error(), large.force_window_error());
            assert!(
                (lin - big).abs() < 0.003 && lin > 0.01,
                "linear geometry excess {:+.2} % against {:+.2} %",
                100.0 * lin,
                100.0 * big
            );
        }
        // Both meshes resolve the patch (a/10): against the finite-ball reference within
        // 2 % (δ_max, t_c) and 1 % (force), as the large-displacement runs.
        let (fd, ft, ff) = r.finite_ball_errors();
        assert!(
            fd.abs() < 0.02 && ft.abs() < 0.02 && ff.abs() < 0.01,
            "{v} m/s linear geometry against the finite ball: {fd} {ft} {ff}"
        );
    }
}
