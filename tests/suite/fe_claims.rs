//! The project's central FE claims on a yielding impact, each against the documented number it
//! rests on: the default scene's e, δ_max, contact duration and η against the converged values
//! of the mesh ladder and against the analytical model (verification/NOTES.md,
//! docs/performance.md "Run time against error"); scale invariance of the D-scaled default
//! mesh; and a gross-sliding tangential impact against Coulomb's law and the analytical
//! Coulomb impulse (verification/ansys/sweep.csv). A model change that moves any of these by
//! more than the mesh ladder allows fails here.
//!
//! Print the figures with `cargo test --release --test suite fe_claims:: -- --nocapture`.

use std::path::Path;
use twoball::scene::{Override, Scene, DEFAULT_SCENE};
use twoball::study::run::scene::{run_scene, RunReport};
use twoball::study::run::simulate::RunOptions;

/// The default scene on the 3D model (`auto-3d`: these are the 3D model's claims) with
/// dotted-path overrides.
fn scene(sets: &[&str]) -> Scene {
    let sets: Vec<Override> = std::iter::once(&"reduction.symmetry=\"auto-3d\"")
        .chain(sets)
        .map(|s| Override::parse(s).unwrap())
        .collect();
    Scene::from_toml(DEFAULT_SCENE, Path::new("."), &sets).unwrap()
}

fn run(s: &Scene) -> RunReport {
    let opts = RunOptions {
        history_rows: 400,
        ..RunOptions::default()
    };
    run_scene(s, &opts).unwrap()
}

/// Relative difference a/b − 1.
fn rel(a: f64, b: f64) -> f64 {
    a / b - 1.0
}

/// Asserts that the relative offset `off` lies in `[lo, hi]` (fractions), naming the claim.
fn within(what: &str, off: f64, lo: f64, hi: f64) {
    assert!(
        (lo..=hi).contains(&off),
        "{what}: {:+.3} % outside [{:+.2} %, {:+.2} %]",
        100.0 * off,
        100.0 * lo,
        100.0 * hi
    );
}

/// Converged e of the default scene: the finest meshes of `twoball bench study` (bulk D/14 +
/// pole D/141: 0.31907; D/10 + D/400: 0.31900; D/20 + D/200: 0.31897), docs/performance.md.
const E_CONVERGED: f64 = 0.3190;
/// Converged δ_max of the default scene, m: the Richardson extrapolation of the one-point ladder
/// (observed order 2.6), docs/performance.md.
const DELTA_CONVERGED: f64 = 7.810138e-5;
/// Converged contact duration of the default scene, s: the finest one-point mesh (D/14 + D/141),
/// docs/performance.md.
const DURATION_CONVERGED: f64 = 8.073150e-5;

/// The default scene (D = 20 mm copper-fe, ±1 m/s, default mesh D/6 bulk + D/200 pole) against
/// the converged values and the analytical model. Measured: e 0.32116 (+0.67 % from 0.3190),
/// δ_max 7.7746e-5 m (−0.46 %), t_c 8.0086e-5 s (−0.80 %); against the analytical model e
/// −6.27 %, δ_max −39.3 %, t_c −43.2 %, η +1.6 %; energy error 2.8e-4.
#[test]
fn default_scene_matches_the_converged_and_analytical_figures() {
    let r = run(&scene(&[]));
    let e = r.e.unwrap();
    let eta = r.eta.unwrap();
    let an = r.analytic.as_ref().unwrap();
    println!(
        "default scene: e {e:.5} ({:+.2} % from converged), delta_max {:.4e} m ({:+.2} %), t_c {:.4e} s \
         ({:+.2} %), eta {eta:.5}; against analytical e {:+.2} %, delta_max {:+.2} %, t_c {:+.2} %, \
         eta {:+.2} %; energy error {:.1e}",
        100.0 * rel(e, E_CONVERGED),
        r.delta_max,
        100.0 * rel(r.delta_max, DELTA_CONVERGED),
        r.contact_duration,
        100.0 * rel(r.contact_duration, DURATION_CONVERGED),
        100.0 * rel(e, an.e),
        100.0 * rel(r.delta_max, an.delta_max),
        100.0 * rel(r.contact_duration, an.contact_duration),
        100.0 * rel(eta, an.eta),
        r.energy_error
    );
    // e: the documented offset of the default mesh is +0.7 % (NOTES.md: D/6 bulk with a D/200
    // pole gives 0.3212; D/7 0.3207, D/8 0.3210, D/5 0.3250). The band +0.4 .. +1.0 % holds
    // the D/6-D/8 meshes' spread (+0.5 .. +0.7 %) and excludes the next coarser mesh (+1.9 %).
    within(
        "e against converged 0.3190",
        rel(e, E_CONVERGED),
        0.004,
        0.010,
    );
    // δ_max converges with order 2.6; the ladder's δ_max errors are 0.27 % (D/10 + D/200)
    // to 1.6 % (D/10 + D/100). The default mesh sits at −0.46 %: ±0.5 % around it.
    within(
        "delta_max against converged 7.810e-5 m",
        rel(r.delta_max, DELTA_CONVERGED),
        -0.0096,
        0.0004,
    );
    // The duration's ladder errors are 0-0.8 % (no asymptotic order; reference the finest
    // mesh); the default mesh sits at −0.80 %: ±0.6 % around it.
    within(
        "contact duration against converged 8.073e-5 s",
        rel(r.contact_duration, DURATION_CONVERGED),
        -0.014,
        -0.002,
    );
    // Against the analytical model (NOTES.md, right ball at −1.0 m/s): e 6.3 % lower, δ_max
    // 39 % smaller, contact 43 % shorter, η within 2 %. Bands of about ±0.7 % (e), ±2 %
    // (δ_max, t_c) around the documented offsets: wider than the default mesh's own error
    // against converged (0.7 % in e, under 1 % in δ_max and t_c).
    within("e against analytical", rel(e, an.e), -0.070, -0.055);
    within(
        "delta_max against analytical",
        rel(r.delta_max, an.delta_max),
        -0.41,
        -0.37,
    );
    within(
        "contact duration against analytical",
        rel(r.contact_duration, an.contact_duration),
        -0.45,
        -0.41,
    );
    within("eta against analytical", rel(eta, an.eta), -0.02, 0.02);
    // Every graded case of the sweep stays below 8.6e-4 (NOTES.md, "Energy").
    assert!(r.energy_error < 1e-3, "energy error {:.2e}", r.energy_error);
}

/// A geometrically similar impact has no length scale (rate-independent material, no
/// gravity): with the default mesh scaled with D, e is the same at D = 5 and 20 mm and δ_max,
/// t_c scale with D. NOTES.md: the graded runs at D = 5, 10, 20 and 30 mm agree to 4e-5 in e
/// (sweep.csv at ±1 m/s: 0.3211550 and 0.3211574, δ_max/D and t_c/D within 2e-6 and 8e-5;
/// measured here −7.6e-6, −2.0e-6, 7.5e-5).
#[test]
fn d_scaled_mesh_gives_the_same_impact_at_5_and_20_mm() {
    let big = run(&scene(&[]));
    let small = run(&scene(&["ball1.diameter=0.005", "ball2.diameter=0.005"]));
    let (eb, es) = (big.e.unwrap(), small.e.unwrap());
    let k = 0.02 / 0.005;
    let (de, dd, dt) = (
        rel(es, eb),
        rel(k * small.delta_max, big.delta_max),
        rel(k * small.contact_duration, big.contact_duration),
    );
    println!(
        "D = 20 mm e {eb:.7}, D = 5 mm e {es:.7} ({de:.1e}); delta_max/D {dd:.1e}, t_c/D {dt:.1e}"
    );
    // 1e-4: the sweep's largest spread is 4e-5; the same pair with the yield stress raised by
    // 10 % differs by 5.6e-5 (the time step falls differently within the contact), while a
    // length that failed to scale with D moves e by per cents (NOTES.md: the unscaled 2 mm
    // mesh is +20 % to +207 %).
    assert!(de.abs() < 1e-4, "e differs by {de:.2e}");
    assert!(dd.abs() < 1e-4, "delta_max/D differs by {dd:.2e}");
    // The duration is read from the sampled force pulse: 400 history rows, 2.5e-3 of it.
    assert!(dt.abs() < 1e-3, "t_c/D differs by {dt:.2e}");
}

/// The sweep's gross-sliding case (left ball +1 m/s, right ball +0.5 m/s, tangential 0.5 /
/// −0.5 m/s): the analytical model predicts sliding throughout, so the tangential impulse is
/// μ times the normal one. FE and analytical tangential after-speeds agree within 0.3 %
/// (NOTES.md: 0.4294 against 0.4284 m/s; sweep.csv). Measured here: J_t/J_n +0.25 % from μ,
/// v1t after +0.22 % from the analytical model.
#[test]
#[ignore = "a 3D half-model run of the sweep: about 1.5 min; tests/contact_oblique.rs checks gross sliding in every run"]
fn gross_sliding_case_follows_coulomb() {
    // The sweep's mesh: its pole size is set (D/200), so the pole rule does not refine it.
    let s = scene(&[
        "ball1.velocity=[1,0.5,0]",
        "ball2.velocity=[0.5,-0.5,0]",
        "ball1.mesh.pole_size=1e-4",
        "ball2.mesh.pole_size=1e-4",
    ]);
    let mu = s.friction_coefficients().0;
    let r = run(&s);
    let an = r.analytic.as_ref().unwrap();
    // Equal balls: the impulses per unit mass are the velocity changes of ball 1.
    let jn = 1.0 - r.v1_after[0];
    let jt = 0.5 - r.v1_after[1];
    let ratio = jt / jn;
    let dv = rel(r.v1_after[1], an.v1_after[1]);
    println!(
        "J_t/J_n {ratio:.5} (mu {mu}: {:+.2} %), v1t after {:.5} against analytical {:.5} ({:+.2} %), \
         e {:.4}, energy error {:.1e}",
        100.0 * rel(ratio, mu),
        r.v1_after[1],
        an.v1_after[1],
        100.0 * dv,
        r.e.unwrap(),
        r.energy_error
    );
    assert!(
        rel(ratio, mu).abs() < 0.005,
        "J_t/J_n = {ratio} against mu = {mu}"
    );
    assert!(dv.abs() < 0.003, "tangential after-speed off by {dv:.2e}");
    assert!(r.energy_error < 1e-3, "energy error {:.2e}", r.energy_error);
}
