//! Acceptance 3 of issue 5: CoulombFriction friction of a block on a frictional rigid plane.
//! A sliding block decelerates at μ g; below the threshold it sticks; friction dissipation
//! equals the kinetic energy lost.

use crate::contact_support;

use contact_support::UniformLoad;
use twoball::fe::contact::{ContactParams, CoulombFriction, RigidPlane};
use twoball::fe::interaction::Interaction;
use twoball::fe::{Formulation, Model, Settings, Solver};
use twoball::mesh::block::block;
use twoball::Material;

const G: f64 = 9.81;
const MU: f64 = 0.2;

/// A 0.1 x 0.1 x 0.05 m steel block (2 x 2 x 1 hexes) resting on the plane z = 0, sliding at
/// `v0` along x, gravity −z and an extra push `push` (fraction of g, along +x) from `t_push`.
fn block_on_plane(
    v0: f64,
    push: f64,
    t_push: f64,
    damping: f64,
    friction: CoulombFriction,
) -> (Solver, twoball::fe::contact::ContactProbe) {
    let mesh = block([0.1, 0.1, 0.05], [2, 2, 1]);
    let mut model = Model::new();
    let mat = Material::preset("steel").unwrap();
    let p = model
        .add_part("block", &mesh, mat, Formulation::OnePoint)
        .unwrap();
    model.part_mut(p).unwrap().elastic_only = true;
    model
        .set_rigid_velocity(p, [v0, 0.0, 0.0], [0.0; 3], [0.0; 3])
        .unwrap();
    let bottom: Vec<[u32; 4]> = model.parts[p]
        .boundary
        .iter()
        .copied()
        .filter(|q| q.iter().all(|&i| model.nodes[i as usize][2].abs() < 1e-12))
        .collect();
    let params = ContactParams {
        friction: Some(friction),
        damping,
        ..Default::default()
    };
    let wall = RigidPlane::new(
        &model.nodes,
        &model.hexes,
        &bottom,
        &mat,
        [0.0; 3],
        [0.0, 0.0, 1.0],
        params,
    )
    .unwrap();
    let probe = wall.probe();
    let n = model.nodes.len();
    let loads: Vec<Box<dyn Interaction>> = vec![
        Box::new(wall),
        Box::new(UniformLoad::new("gravity", 0..n, [0.0, 0.0, -G], 0.0, 0.0)),
        Box::new(UniformLoad::new(
            "push",
            0..n,
            [push * G, 0.0, 0.0],
            t_push,
            1e-3,
        )),
    ];
    (
        Solver::new(model, loads, Settings::default()).unwrap(),
        probe,
    )
}

#[test]
fn sliding_block_decelerates_at_mu_g_and_dissipates_its_kinetic_energy() {
    let v0 = 0.05;
    // No contact damping (measured: deceleration error 1.0e-3, dissipation vs lost kinetic
    // energy 4.6e-4, energy ratio 1.00046).
    let (mut s, probe) = block_on_plane(v0, 0.0, f64::INFINITY, 0.0, CoulombFriction::new(MU));
    let m: f64 = s.mass().iter().sum();
    let ke0 = 0.5 * m * v0 * v0;
    // Deceleration from the centre-of-mass velocity over a long window while sliding.
    let (t1, t2) = (0.002, 0.020);
    s.run_until(|s| s.time() >= t1).unwrap();
    let v1 = s.part_motion(0).unwrap().0[0];
    let tt1 = s.time();
    s.run_until(|s| s.time() >= t2).unwrap();
    let v2 = s.part_motion(0).unwrap().0[0];
    let a = (v1 - v2) / (s.time() - tt1);
    let err = (a - MU * G).abs() / (MU * G);
    println!(
        "deceleration {a:.6} m/s^2 vs mu g = {:.6}: error {:.3e}",
        MU * G,
        err
    );
    assert!(err < 0.005, "deceleration {a} vs {}", MU * G);
    // Run to rest: friction dissipation = the kinetic energy lost.
    let stop = v0 / (MU * G);
    s.run_until(|s| s.time() >= 1.2 * stop).unwrap();
    let (vc, _) = s.part_motion(0).unwrap();
    assert!(vc[0].abs() < 1e-3 * v0, "still moving at {vc:?}");
    let e = s.energy();
    let lost = ke0 - e.solid.kinetic;
    let fric = probe.last().friction_energy;
    let derr = (fric - lost).abs() / lost;
    println!("friction dissipation {fric:.6e} J vs lost KE {lost:.6e} J: error {derr:.3e}; energy ratio {:.6}", e.energy_ratio);
    assert!(derr < 0.005);
    assert!(
        (e.energy_ratio - 1.0).abs() < 0.01,
        "energy ratio {}",
        e.energy_ratio
    );
}

#[test]
fn block_below_the_friction_threshold_sticks() {
    // Push at half the static limit after the contact has settled.
    let (mut s, probe) = block_on_plane(0.0, 0.5 * MU, 2e-3, 0.2, CoulombFriction::new(MU));
    s.run_until(|s| s.time() >= 2e-3).unwrap();
    let x0: f64 = s.x().iter().map(|x| x[0]).sum::<f64>() / s.x().len() as f64;
    s.run_until(|s| s.time() >= 30e-3).unwrap();
    let x1: f64 = s.x().iter().map(|x| x[0]).sum::<f64>() / s.x().len() as f64;
    let drift = (x1 - x0).abs();
    let o = probe.last();
    println!(
        "stick drift {drift:.3e} m, friction {:.4} N, normal {:.4} N",
        o.tangential_force, o.normal_force
    );
    assert!(drift < 1e-6, "drift {drift} m");
    let m: f64 = s.mass().iter().sum();
    assert!((o.tangential_force - 0.5 * MU * m * G).abs() < 0.02 * 0.5 * MU * m * G);
}

#[test]
fn block_above_the_threshold_slides_at_the_net_acceleration() {
    // Push at 1.5 μ g: it slides with a = (1.5 − 1) μ g = 0.5 μ g.
    let (mut s, _probe) = block_on_plane(0.0, 1.5 * MU, 0.0, 0.2, CoulombFriction::new(MU));
    s.run_until(|s| s.time() >= 4e-3).unwrap();
    let (v1, t1) = (s.part_motion(0).unwrap().0[0], s.time());
    s.run_until(|s| s.time() >= 20e-3).unwrap();
    let a = (s.part_motion(0).unwrap().0[0] - v1) / (s.time() - t1);
    println!("net acceleration {a:.5} vs {:.5}", 0.5 * MU * G);
    assert!((a - 0.5 * MU * G).abs() < 0.005 * 0.5 * MU * G);
}
