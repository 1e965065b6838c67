//! The explicit stable step against the true highest frequency: for central differences with
//! a lumped mass the step must not exceed 2/ω_max, ω_max² the largest eigenvalue of
//! M_lumped⁻¹ K (K including the hourglass stiffness). ω_max is computed here by power
//! iteration on the assembled small-strain system, independently of the explicit loop.

use twoball::fe::linear::modal::assemble;
use twoball::fe::{Formulation, Model, Settings, Solver};
use twoball::material::Material;
use twoball::mesh::ball::{ball, BallSpec, Cut};
use twoball::mesh::block::block;
use twoball::mesh::Mesh;

/// Largest ω (rad/s) of M_lumped⁻¹ K by power iteration (row-sum lumped mass).
fn omega_max(model: &Model, hourglass: f64) -> f64 {
    let sys = assemble(model, hourglass).unwrap();
    let n = sys.stiffness.rows();
    let mut m = vec![0.0; n];
    for (v, (r, _)) in sys.mass.iter() {
        m[r] += *v;
    }
    let mut x: Vec<f64> = (0..n).map(|i| ((i * 7919) % 101) as f64 - 50.0).collect();
    let mut y = vec![0.0; n];
    let mut lam = 0.0;
    for _ in 0..3000 {
        y.iter_mut().for_each(|v| *v = 0.0);
        for (col, xv) in sys.stiffness.outer_iterator().zip(&x) {
            for (r, v) in col.iter() {
                y[r] += v * xv;
            }
        }
        for i in 0..n {
            y[i] /= m[i];
        }
        let ny = y.iter().map(|v| v * v).sum::<f64>().sqrt();
        let nx = x.iter().map(|v| v * v).sum::<f64>().sqrt();
        lam = ny / nx;
        x.iter_mut().zip(&y).for_each(|(a, b)| *a = b / ny);
    }
    lam.sqrt()
}

/// Smallest accepted Courant estimate / (2/ω_max): measured 1.035 / 1.040 (cube, one-point /
/// B-bar) and 0.639 / 0.655 (graded quarter ball, whose smallest elements are distorted). A
/// step half the graded ball's (or a tenth of any) fails.
const LOWER: f64 = 0.5;

fn check(mesh: &Mesh, f: Formulation, what: &str) -> f64 {
    let mut model = Model::new();
    model
        .add_part("b", mesh, Material::preset("copper-fe").unwrap(), f)
        .unwrap();
    let settings = Settings::default();
    let w = omega_max(&model, settings.hourglass);
    let s = Solver::new(
        model,
        vec![],
        Settings {
            time_step_factor: 1.0,
            ..settings
        },
    )
    .unwrap();
    let ratio = s.stable_step().dt / (2.0 / w);
    eprintln!("{what} {f:?}: Courant estimate / (2/ω_max) = {ratio:.4}");
    ratio
}

#[test]
fn courant_estimate_times_safety_is_below_the_true_limit() {
    let cube = block([0.01, 0.01, 0.01], [6, 6, 6]);
    let graded = ball(&BallSpec {
        diameter: 0.02,
        size: 0.004,
        pole_size: Some(0.0004),
        cut: Cut::Quarter,
    })
    .unwrap();
    for f in [Formulation::OnePoint, Formulation::BBar] {
        for (m, name) in [(&cube, "cube block"), (&graded, "graded quarter ball")] {
            let r = check(m, f, name);
            // A lower bound too: a step far below the limit is stable but wastes run time.
            assert!(r >= LOWER, "{name} {f:?}: estimate only {r:.3} of 2/ω_max");
            assert!(
                r * Settings::default().time_step_factor <= 1.0,
                "{name} {f:?}: default safety × estimate = {:.3} of 2/ω_max",
                r * Settings::default().time_step_factor
            );
        }
    }
}
