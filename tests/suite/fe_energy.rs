#![allow(clippy::needless_range_loop)]
//! Acceptance 6: energy conservation of free vibration. An elastic body keeps its total energy
//! (kinetic + elastic + hourglass) within 0.1 % over 10 000 steps; an elastic-plastic one keeps
//! kinetic + elastic + plastic + hourglass within 0.5 % of the initial energy, with hourglass
//! energy under 5 % of the internal energy.

use twoball::fe::{Formulation, Model, Settings, Solver};
use twoball::mesh::ball::{ball, BallSpec, Cut};
use twoball::mesh::Mesh;
use twoball::Material;

/// A coarse uniform ball of diameter 2r (m) with element size `h` (m).
fn coarse_ball(r: f64, h: f64) -> Mesh {
    ball(&BallSpec {
        diameter: 2.0 * r,
        size: h,
        pole_size: None,
        cut: Cut::Full,
    })
    .unwrap()
}

/// Runs a free vibration; returns (largest drift of kinetic + internal + hourglass, largest
/// hourglass/internal ratio, largest Box 6.1 balance error, plastic work / initial energy,
/// largest drift of kinetic + stress-based elastic + plastic + hourglass).
fn run(
    formulation: Formulation,
    amplitude: f64,
    elastic_only: bool,
    steps: u64,
) -> (f64, f64, f64, f64, f64) {
    let r = 0.01;
    let mesh = coarse_ball(r, 0.007);
    eprintln!("{} elements", mesh.hexes.len());
    let mat = Material::preset("copper-fe").unwrap();
    let mut model = Model::new();
    let p = model.add_part("ball", &mesh, mat, formulation).unwrap();
    model.part_mut(p).unwrap().elastic_only = elastic_only;
    // Quadrupole (n = 2) plus a little breathing and a spin: every kind of motion at once.
    model
        .set_velocity_field(p, |x| {
            let s = amplitude / r;
            [
                s * (x[0] + 0.3 * x[1]) - 50.0 * x[1],
                s * (-x[1] + 0.2 * x[2]) + 50.0 * x[0],
                s * 0.1 * x[2],
            ]
        })
        .unwrap();
    let mut s = Solver::new(model, vec![], Settings::default()).unwrap();
    let e0 = s.energy();
    let mut worst_total: f64 = 0.0;
    let mut worst_hg_ratio: f64 = 0.0;
    let mut worst_stress_based: f64 = 0.0;
    while s.step_count() < steps {
        s.step().unwrap();
        if s.step_count().is_multiple_of(100) {
            let e = s.energy();
            worst_total = worst_total.max((e.mechanical() - e0.total).abs() / e0.total);
            let alt = e.solid.kinetic_central
                + e.solid.elastic_from_stress
                + e.solid.plastic
                + e.solid.hourglass;
            worst_stress_based = worst_stress_based.max((alt - e0.total).abs() / e0.total);
            if e.solid.internal > 0.05 * e0.total {
                worst_hg_ratio = worst_hg_ratio.max(e.solid.hourglass / e.solid.internal);
            }
        }
    }
    let e = s.energy();
    eprintln!(
        "{formulation:?} amplitude {amplitude} m/s: drift {worst_total:.3e}, hourglass/internal {worst_hg_ratio:.3e}, \
         stress-based drift {worst_stress_based:.3e}, balance {:.3e}, plastic/E0 {:.3e}, elastic-from-stress/elastic {:.6}",
        e.max_balance_error,
        e.solid.plastic / e0.total,
        e.solid.elastic_from_stress / e.solid.elastic
    );
    (
        worst_total,
        worst_hg_ratio,
        e.max_balance_error,
        e.solid.plastic / e0.total,
        worst_stress_based,
    )
}

#[test]
fn elastic_vibration_conserves_energy_one_point() {
    let (total, hg, balance, _, alt) = run(Formulation::OnePoint, 0.5, true, 10_000);
    assert!(total < 1e-3, "total energy drift {total:e}");
    assert!(alt < 1e-3, "stress-based total energy drift {alt:e}");
    assert!(hg < 0.05, "hourglass / internal = {hg}");
    assert!(balance < 1e-3, "Box 6.1 balance error {balance:e}");
}

#[test]
fn elastic_vibration_conserves_energy_bbar() {
    let (total, _, balance, _, alt) = run(Formulation::BBar, 0.5, true, 10_000);
    assert!(total < 1e-3, "total energy drift {total:e}");
    assert!(alt < 1e-3, "stress-based total energy drift {alt:e}");
    assert!(balance < 1e-3, "Box 6.1 balance error {balance:e}");
}

#[test]
fn elastic_plastic_vibration_keeps_energy_balance() {
    for formulation in [Formulation::OnePoint, Formulation::BBar] {
        let (total, hg, balance, plastic, alt) = run(formulation, 40.0, false, 2_000);
        assert!(
            alt < 5e-3,
            "{formulation:?}: stress-based energy drift {alt:e}"
        );
        assert!(
            plastic > 0.05,
            "{formulation:?}: must dissipate plastically, got {plastic}"
        );
        assert!(total < 5e-3, "{formulation:?}: energy drift {total:e}");
        assert!(hg < 0.05, "{formulation:?}: hourglass / internal = {hg}");
        assert!(balance < 5e-3, "{formulation:?}: balance error {balance:e}");
    }
}
