#![allow(clippy::needless_range_loop)]
//! Acceptance 2: rigid motion leaves an element stress-free. Translation through the full
//! solver; rotation by 360° at 1000 rad/s with the element loop driven by the exact rigid
//! motion (a freely spinning body would carry real centrifugal stress ρω²r², so the rotation
//! is prescribed to test objectivity of the stress update alone).

use twoball::fe::elements::ElementBlock;
use twoball::fe::materials::J2Material;
use twoball::fe::{Formulation, Model, Settings, Solver};
use twoball::mesh::block::block;
use twoball::Material;

fn distorted(n: usize, side: f64) -> twoball::mesh::Mesh {
    let mut m = block([side; 3], [n; 3]);
    let h = side / n as f64;
    for (i, p) in m.nodes.iter_mut().enumerate() {
        let s = i as f64;
        p[0] += 0.1 * h * (1.3 * s).sin();
        p[1] += 0.1 * h * (0.7 * s + 0.2).cos();
        p[2] += 0.1 * h * (2.1 * s + 0.5).sin();
    }
    m
}

fn rot_z(theta: f64, p: [f64; 3]) -> [f64; 3] {
    let (s, c) = theta.sin_cos();
    [c * p[0] - s * p[1], s * p[0] + c * p[1], p[2]]
}

fn rotate_full_turn(formulation: Formulation) {
    let mesh = distorted(2, 2e-3);
    let mat = Material::preset("copper-fe").unwrap();
    let j2 = J2Material::new(&mat, false);
    let mut blk = ElementBlock::new(0, 0, mesh.hexes.clone(), formulation, j2, 0.05);
    let mut forces = vec![[[0.0; 3]; 8]; mesh.hexes.len()];
    let omega = 1000.0;
    // Courant step of the mesh (h = 1 mm): about 1.9e-7 s, 33 000 steps per turn.
    let dt = 0.9 * 1e-3 / mat.dilatational_wave_speed();
    let steps = (2.0 * std::f64::consts::PI / omega / dt).ceil() as usize;
    let dt = 2.0 * std::f64::consts::PI / omega / steps as f64;
    let centre = [0.3e-3, -0.2e-3, 1e-3];
    let place = |theta: f64| -> Vec<[f64; 3]> {
        mesh.nodes
            .iter()
            .map(|p| {
                let r = rot_z(
                    theta,
                    [p[0] - centre[0], p[1] - centre[1], p[2] - centre[2]],
                );
                [r[0] + centre[0], r[1] + centre[1], r[2] + centre[2]]
            })
            .collect()
    };
    let mut x0 = place(0.0);
    let mut worst: f64 = 0.0;
    for n in 0..steps {
        let x1 = place(omega * dt * (n + 1) as f64);
        let v: Vec<[f64; 3]> = x1
            .iter()
            .zip(&x0)
            .map(|(a, b)| [0, 1, 2].map(|k| (a[k] - b[k]) / dt))
            .collect();
        blk.update(&x1, &v, dt, &mut forces).unwrap();
        for p in &blk.points {
            worst = p.stress.iter().fold(worst, |m, s| m.max(s.abs()));
        }
        x0 = x1;
    }
    assert!(
        worst < 1e-6 * mat.yield_strength,
        "{formulation:?}: max |σ| = {worst:e} Pa over {steps} steps"
    );
}

#[test]
fn full_turn_at_1000_rad_s_stays_stress_free_one_point() {
    rotate_full_turn(Formulation::OnePoint);
}

#[test]
fn full_turn_at_1000_rad_s_stays_stress_free_bbar() {
    rotate_full_turn(Formulation::BBar);
}

#[test]
fn prestress_rotates_with_the_body() {
    // Objectivity of the Jaumann/Hughes-Winget update: a uniform prestress carried through a
    // quarter turn about z becomes R σ Rᵀ (σ_xx ↔ σ_yy, σ_xy → −σ_xy).
    let mesh = distorted(1, 1e-3);
    let mat = Material::preset("copper-fe").unwrap();
    let mut blk = ElementBlock::new(
        0,
        0,
        mesh.hexes.clone(),
        Formulation::OnePoint,
        J2Material::new(&mat, true),
        0.05,
    );
    let s0 = [30e6, -10e6, 5e6, 12e6, -4e6, 7e6];
    blk.points[0].stress = s0;
    let mut forces = vec![[[0.0; 3]; 8]; 1];
    let steps = 4000;
    let dt = std::f64::consts::FRAC_PI_2 / steps as f64; // ω = 1 rad/s
    let mut x0 = mesh.nodes.clone();
    for n in 0..steps {
        let x1: Vec<[f64; 3]> = mesh
            .nodes
            .iter()
            .map(|p| rot_z(dt * (n + 1) as f64, *p))
            .collect();
        let v: Vec<[f64; 3]> = x1
            .iter()
            .zip(&x0)
            .map(|(a, b)| [0, 1, 2].map(|k| (a[k] - b[k]) / dt))
            .collect();
        blk.update(&x1, &v, dt, &mut forces).unwrap();
        x0 = x1;
    }
    // R = [[0, -1, 0], [1, 0, 0], [0, 0, 1]]: σ'_xx = σ_yy, σ'_yy = σ_xx, σ'_xy = −σ_xy,
    // σ'_yz = σ_zx, σ'_zx = −σ_yz.
    let expect = [s0[1], s0[0], s0[2], -s0[3], s0[5], -s0[4]];
    let s = blk.points[0].stress;
    for k in 0..6 {
        assert!(
            (s[k] - expect[k]).abs() < 1e-6 * 30e6,
            "{s:?} vs {expect:?}"
        );
    }
}

#[test]
fn translation_through_the_solver_stays_stress_free() {
    for formulation in [Formulation::OnePoint, Formulation::BBar] {
        let mesh = distorted(3, 3e-3);
        let mat = Material::preset("copper-fe").unwrap();
        let mut model = Model::new();
        let p = model.add_part("block", &mesh, mat, formulation).unwrap();
        model
            .set_rigid_velocity(p, [120.0, -40.0, 75.0], [0.0; 3], [0.0; 3])
            .unwrap();
        let mut s = Solver::new(model, vec![], Settings::default()).unwrap();
        s.run_until(|s| s.step_count() >= 2000).unwrap();
        for e in 0..27 {
            let st = s.element_stress(e);
            assert!(
                st.iter().all(|c| c.abs() < 1e-6 * mat.yield_strength),
                "{formulation:?} {st:?}"
            );
        }
        let (vc, w) = s.part_motion(0).unwrap();
        assert!(
            (vc[0] - 120.0).abs() < 1e-9
                && (vc[1] + 40.0).abs() < 1e-9
                && w.iter().all(|c| c.abs() < 1e-6)
        );
    }
}

/// `linear_geometry` takes gradients on the reference configuration, as small-displacement
/// theory (Hertz's) does, so it is not objective: a free body spun by θ = 0.02 rad is pushed
/// out of shape by about 1 − cos θ = 2e-4 in the plane of rotation (the body relaxes the
/// spurious strain of the rotation by growing), while the default large-displacement update
/// keeps every node distance to the real, suddenly applied centrifugal stretch (measured 2e-8).
/// Shows the setting acts, and the limit its documentation states.
#[test]
fn linear_geometry_distorts_a_spinning_body_large_geometry_does_not() {
    let stretch = |linear_geometry: bool| -> f64 {
        let mesh = distorted(2, 1e-3);
        let mat = Material::preset("copper-fe").unwrap();
        let mut model = Model::new();
        let p = model
            .add_part("block", &mesh, mat, Formulation::OnePoint)
            .unwrap();
        model
            .set_rigid_velocity(p, [0.0; 3], [0.0, 0.0, 1000.0], [0.5e-3; 3])
            .unwrap();
        let settings = Settings {
            linear_geometry,
            ..Settings::default()
        };
        let mut s = Solver::new(model, vec![], settings).unwrap();
        s.run_until(|s| s.time() >= 2e-5).unwrap();
        // Largest relative change of a node's distance from node 0.
        let dist = |a: [f64; 3], b: [f64; 3]| {
            ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
        };
        let (x, x0) = (s.x(), &s.model().nodes);
        (1..x.len())
            .map(|n| (dist(x[n], x[0]) / dist(x0[n], x0[0]) - 1.0).abs())
            .fold(0.0, f64::max)
    };
    let (large, small) = (stretch(false), stretch(true));
    println!("largest node-distance change: large displacements {large:.2e}, linear geometry {small:.2e}");
    assert!(large < 1e-6, "large-displacement update: {large:e}");
    assert!(small > 5e-5, "linear geometry: {small:e}");
}
