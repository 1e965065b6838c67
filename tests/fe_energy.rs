//! Acceptance 6: energy conservation of free vibration. An elastic body keeps its total energy
//! (kinetic + elastic + hourglass) within 0.1 % over 10 000 steps; an elastic-plastic one keeps
//! kinetic + elastic + plastic + hourglass within 0.5 % of the initial energy, with hourglass
//! energy under 5 % of the internal energy.

use twoball::fe::{Formulation, Model, Settings, Solver};
use twoball::mesh::Mesh;
use twoball::Material;

/// A coarse ball of radius `r` (m): a cube mesh mapped onto the sphere (the cube's shells are
/// blended towards spheres), good enough for free-vibration energy checks.
fn coarse_ball(r: f64, n: usize) -> Mesh {
    let mut m = twoball::mesh::block::block([2.0; 3], [n; 3]);
    for p in &mut m.nodes {
        let q = p.map(|c| c - 1.0);
        let inf = q.iter().fold(0.0f64, |a, c| a.max(c.abs()));
        let two = (q[0] * q[0] + q[1] * q[1] + q[2] * q[2]).sqrt();
        // Blend: the outer shell becomes the sphere, the centre stays a cube.
        let s = if two > 0.0 { (1.0 - inf) + inf * inf / two } else { 1.0 };
        *p = q.map(|c| r * c * s);
    }
    m
}

fn run(formulation: Formulation, amplitude: f64, elastic_only: bool, steps: u64) -> (f64, f64, f64, f64) {
    let r = 0.01;
    let mesh = coarse_ball(r, 6);
    let mat = Material::preset("copper-fe").unwrap();
    let mut model = Model::new();
    let p = model.add_part("ball", &mesh, mat, formulation).unwrap();
    model.part_mut(p).unwrap().elastic_only = elastic_only;
    // Quadrupole (n = 2) plus a little breathing and a spin: every kind of motion at once.
    model
        .set_velocity_field(p, |x| {
            let s = amplitude / r;
            [s * (x[0] + 0.3 * x[1]) - 50.0 * x[1], s * (-x[1] + 0.2 * x[2]) + 50.0 * x[0], s * 0.1 * x[2]]
        })
        .unwrap();
    let mut s = Solver::new(model, vec![], Settings::default()).unwrap();
    let e0 = s.energy();
    let mut worst_total: f64 = 0.0;
    let mut worst_hg_ratio: f64 = 0.0;
    while s.step_count() < steps {
        s.step().unwrap();
        if s.step_count() % 100 == 0 {
            let e = s.energy();
            worst_total = worst_total.max((e.mechanical() - e0.total).abs() / e0.total);
            if e.internal > 0.05 * e0.total {
                worst_hg_ratio = worst_hg_ratio.max(e.hourglass / e.internal);
            }
        }
    }
    let e = s.energy();
    (worst_total, worst_hg_ratio, e.max_balance_error, e.plastic / e0.total)
}

#[test]
fn elastic_vibration_conserves_energy_one_point() {
    let (total, hg, balance, _) = run(Formulation::OnePoint, 0.5, true, 10_000);
    assert!(total < 1e-3, "total energy drift {total:e}");
    assert!(hg < 0.05, "hourglass / internal = {hg}");
    assert!(balance < 1e-3, "Box 6.1 balance error {balance:e}");
}

#[test]
fn elastic_vibration_conserves_energy_bbar() {
    let (total, _, balance, _) = run(Formulation::BBar, 0.5, true, 10_000);
    assert!(total < 1e-3, "total energy drift {total:e}");
    assert!(balance < 1e-3, "Box 6.1 balance error {balance:e}");
}

#[test]
fn elastic_plastic_vibration_keeps_energy_balance() {
    for formulation in [Formulation::OnePoint, Formulation::BBar] {
        let (total, hg, balance, plastic) = run(formulation, 40.0, false, 3_000);
        assert!(plastic > 0.05, "{formulation:?}: must dissipate plastically, got {plastic}");
        assert!(total < 5e-3, "{formulation:?}: energy drift {total:e}");
        assert!(hg < 0.05, "{formulation:?}: hourglass / internal = {hg}");
        assert!(balance < 5e-3, "{formulation:?}: balance error {balance:e}");
    }
}

