//! Acceptance 4 and 5 of issue 5: oblique elastic impact of a ball on a frictional rigid wall.
//! In gross sliding the tangential impulse is μ times the normal impulse; at small tangential
//! speed the contact patch stops sliding during the impact. Energy (with friction dissipation)
//! is conserved and the contact energy returns to zero, with no contact damping.

use twoball::fe::contact::{ContactParams, CoulombFriction, RigidPlane};
use twoball::fe::{Formulation, Model, Settings, Solver};
use twoball::mesh::ball::{ball, BallSpec, Cut};
use twoball::Material;

const MU: f64 = 0.2;
/// Allowed relative departure of the stick case's J_t/J_n from the rigid-body value (measured
/// +19.6 %).
const STICK_BAND: f64 = 0.3;

struct Oblique {
    /// Tangential / normal impulse from the change of centre-of-mass velocity.
    impulse_ratio: f64,
    /// Steps with contact in which no node slid.
    stuck_steps: usize,
    contact_steps: usize,
    energy_error: f64,
    residual_contact_energy: f64,
    friction_energy: f64,
}

/// A half ball (z ≥ 0) of copper, elastic, hitting the wall x = R at (vn, vt, 0).
fn oblique(vn: f64, vt: f64) -> Oblique {
    let d = 0.02;
    let r = 0.5 * d;
    let mut mat = Material::preset("copper-fe").unwrap();
    mat.yield_strength = 1e15;
    let mesh = ball(&BallSpec {
        diameter: d,
        size: 3e-3,
        pole_size: Some(2e-4),
        cut: Cut::Half,
    })
    .unwrap();
    let mut model = Model::new();
    let p = model
        .add_part("ball", &mesh, mat, Formulation::OnePoint)
        .unwrap();
    model.part_mut(p).unwrap().elastic_only = true;
    model.fix_set(p, "sym_z", 2).unwrap();
    model
        .set_rigid_velocity(p, [vn, vt, 0.0], [0.0; 3], [0.0; 3])
        .unwrap();
    let faces = model.parts[p].face_sets["contact"].clone();
    // No contact damping: the penalty time step keeps the chatter of the few contact nodes of
    // this coarse patch from pumping energy (tests/contact_friction_energy.rs).
    let params = ContactParams {
        friction: Some(CoulombFriction::new(MU)),
        damping: 0.0,
        ..Default::default()
    };
    let wall = RigidPlane::new(
        &model.nodes,
        &model.hexes,
        &faces,
        &mat,
        [r, 0.0, 0.0],
        [-1.0, 0.0, 0.0],
        params,
    )
    .unwrap();
    let probe = wall.probe();
    let mut s = Solver::new(model, vec![Box::new(wall)], Settings::default()).unwrap();
    let (v0, _) = s.part_motion(0).unwrap();
    let (mut stuck_steps, mut contact_steps, mut energy_error) = (0, 0, 0.0f64);
    loop {
        s.step().unwrap();
        let o = probe.last();
        if o.active_nodes > 0 {
            contact_steps += 1;
            if o.sliding_nodes == 0 {
                stuck_steps += 1;
            }
        }
        if s.step_count().is_multiple_of(50) {
            energy_error = energy_error.max((s.energy().energy_ratio - 1.0).abs());
        }
        // Done once the ball moves away from the wall and no node touches it.
        if o.active_nodes == 0 && probe.touched() && s.step_count().is_multiple_of(20) {
            let (v, _) = s.part_motion(0).unwrap();
            if v[0] < 0.0 {
                break;
            }
        }
        assert!(s.time() < 1e-3, "no separation");
    }
    let (v1, _) = s.part_motion(0).unwrap();
    let e = s.energy();
    let o = probe.last();
    Oblique {
        impulse_ratio: (v1[1] - v0[1]).abs() / (v1[0] - v0[0]).abs(),
        stuck_steps,
        contact_steps,
        energy_error: energy_error.max((e.energy_ratio - 1.0).abs()),
        residual_contact_energy: o.stored_energy,
        friction_energy: o.friction_energy,
    }
}

#[test]
fn gross_sliding_gives_tangential_impulse_mu_times_normal() {
    // v_t / v_n = 5 > (7/2) μ (1 + e) = 1.4: the contact slides throughout.
    let r = oblique(1.0, 5.0);
    println!(
        "J_t/J_n = {:.5} (mu {MU}), stuck steps {}/{}, energy {:.2e}, friction {:.3e} J",
        r.impulse_ratio, r.stuck_steps, r.contact_steps, r.energy_error, r.friction_energy
    );
    assert!(
        (r.impulse_ratio / MU - 1.0).abs() < 0.02,
        "J_t/J_n = {}",
        r.impulse_ratio
    );
    assert!(r.energy_error < 0.01);
    assert!(r.residual_contact_energy.abs() < 1e-15);
    assert!(r.friction_energy > 0.0);
}

#[test]
fn small_tangential_speed_stops_sliding_during_contact() {
    // v_t / v_n = 0.1 ≪ 1.4: friction brings the contact point to rest before separation: the
    // whole patch sticks for a stretch of the contact (measured: about 9 % of the contact
    // steps with no node sliding) and the tangential impulse stays well below μ J_n.
    let r = oblique(1.0, 0.1);
    println!(
        "J_t/J_n = {:.5} (mu {MU}), stuck steps {}/{}, energy {:.2e}",
        r.impulse_ratio, r.stuck_steps, r.contact_steps, r.energy_error
    );
    // A rigid ball whose contact point is brought to rest (stick): J_t = (2/7) m v_t against
    // J_n = (1 + e) m v_n with e ≈ 1, J_t/J_n = (2/7)(0.1)/2 = 0.0143. The elastic ball's
    // tangential compliance shifts it (NOTES.md: the FE sticking cases of the sweep take
    // 24-36 % more tangential impulse than the rigid-body value); measured 0.01709 (+19.6 %).
    // Gross sliding would give μ = 0.2, 14 times more.
    let stick = 2.0 / 7.0 * 0.1 / 2.0;
    assert!(
        (r.impulse_ratio / stick - 1.0).abs() < STICK_BAND,
        "J_t/J_n = {} against the rigid-body stick value {stick}",
        r.impulse_ratio
    );
    assert!(
        r.stuck_steps > r.contact_steps / 20,
        "stuck {} of {}",
        r.stuck_steps,
        r.contact_steps
    );
    assert!(r.energy_error < 0.01);
    assert!(r.residual_contact_energy.abs() < 1e-15);
}
