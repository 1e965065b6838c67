//! Static Hertz. A quarter ball held on its equatorial disk is pressed
//! by a rigid frictionless plane ramped slowly into its pole and left to settle under
//! mass-proportional damping (dynamic relaxation). The nodal pressures must follow
//! p0 sqrt(1 − r²/a²) within 3 % of p0 inside 0.8 a and the contact radius must be within 2 %,
//! with a and p0 from Hertz's formulas for the measured total force.
//!
//! Heavy (minutes): `cargo test --release --test suite contact_static_hertz:: -- --ignored --nocapture`.

use crate::contact_support::static_hertz;

#[test]
#[ignore]
fn static_hertz_pressure_profile_and_contact_radius() {
    // Plane pushed 20 µm into a 20 mm copper ball (a ≈ 0.45 mm ≈ 9 pole elements) over 40 µs,
    // then held 30 µs; α = 10⁶ /s damps the ball's lowest modes (about 10⁵ Hz) near critically.
    let r = static_hertz::compress(2e-5, 5e-5, 2e-3, 40e-6, 30e-6, 1e6);
    let mut s = r.samples.clone();
    s.sort_by(|x, y| x.0.total_cmp(&y.0));
    for (ri, pi) in s.iter().filter(|p| p.0 < r.a_hertz).step_by(4) {
        let exact = (1.0 - (ri / r.a_hertz).powi(2)).max(0.0).sqrt();
        println!(
            "r/a {:.3}  p/p0 {:.4}  Hertz {:.4}",
            ri / r.a_hertz,
            pi / r.p0,
            exact
        );
    }
    let a_err = r.a_fit / r.a_hertz - 1.0;
    println!(
        "F {:.2} N, a_Hertz {:.4e} m, a_fit {:.4e} m ({:+.2} %), p0 {:.4e} Pa, max |p - p_H|/p0 inside 0.8a {:.4}, \
         {} elements, final KE {:.1e} J",
        r.force, r.a_hertz, r.a_fit, 100.0 * a_err, r.p0, r.max_pressure_error, r.elements, r.final_kinetic
    );
    assert!(
        r.max_pressure_error < 0.03,
        "pressure error {}",
        r.max_pressure_error
    );
    assert!(a_err.abs() < 0.02, "contact radius error {a_err}");
}

/// Whether the peak force's excess over Hertz at 2 m/s (1-2 %) is
/// the discretisation or Hertz's half-space idealisation. Here the patch is resolved alike at
/// every depth (pole element a/9) while a/R changes eightfold: a discretisation error would be
/// about the same at every depth, a finite-body effect grows with a/R. The force is compared
/// with Hertz's at the elastic approach, the plane's travel less the pole's penetration.
///
/// What must hold: the excess grows with a/R, in proportion to it, and the ball is stiffer
/// than the half-space (the direction of the dynamic excess). Measured: +1.45,
/// +2.68, +5.35 % at a/R = 0.022, 0.045, 0.089 (verification/contact-penalty.md).
/// `cargo test --release --test suite contact_static_hertz::static_force -- --ignored --nocapture`
#[test]
#[ignore]
fn static_force_excess_grows_with_contact_size() {
    let radius: f64 = 0.01;
    let mat = {
        let mut m = twoball::material::Material::preset("copper-fe").unwrap();
        m.yield_strength = 1e15;
        m
    };
    let e_star = mat.plane_strain_modulus();
    let mut rows = Vec::new();
    for depth in [5e-6_f64, 2e-5, 8e-5] {
        let a = (radius * depth).sqrt();
        let r = static_hertz::compress(depth, a / 9.0, 2e-3, 40e-6, 30e-6, 1e6);
        let approach = depth - r.max_penetration;
        let f_hertz = 4.0 / 3.0 * e_star * radius.sqrt() * approach.powf(1.5);
        let excess = r.force / f_hertz - 1.0;
        println!(
            "depth {:.1} µm, a/R {:.4}, pole {:.1} µm, {} elements, penetration {:.3} % of depth, \
             F {:.2} N, Hertz {:.2} N at the approach: {:+.3} %, a_fit/a_Hertz − 1 {:+.3} %, final KE {:.1e} J",
            depth * 1e6,
            a / radius,
            a / 9.0 * 1e6,
            r.elements,
            100.0 * r.max_penetration / depth,
            r.force,
            f_hertz,
            100.0 * excess,
            100.0 * (r.a_fit / r.a_hertz - 1.0),
            r.final_kinetic
        );
        rows.push((a / radius, excess));
    }
    assert!(
        rows.windows(2).all(|w| w[1].1 > w[0].1),
        "excess does not grow with a/R: {rows:?}"
    );
    assert!(
        rows[2].1 > 0.0,
        "largest contact not stiffer than Hertz: {rows:?}"
    );
    // Proportional to a/R: doubling a/R from the middle depth adds about twice what doubling
    // it from the smallest did (measured 1.09x of that; a resolution error would add nothing).
    let ratio = (rows[2].1 - rows[1].1) / (2.0 * (rows[1].1 - rows[0].1));
    assert!(
        (0.75..1.33).contains(&ratio),
        "excess not linear in a/R: {rows:?} (increment ratio {ratio})"
    );
}
