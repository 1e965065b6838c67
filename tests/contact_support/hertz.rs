#![allow(dead_code)]
//! Normal elastic impact harness: a quarter ball against a frictionless rigid wall (the exact
//! mirror image of two identical balls) and two quarter balls against each other.

use twoball::analytic::hertz::HertzPair;
use twoball::fe::contact::{ContactParams, ContactProbe, PenaltyRule, RigidPlane, SurfacePair};
use twoball::fe::interaction::Interaction;
use twoball::fe::{Formulation, Model, Settings, Solver};
use twoball::mesh::ball::{ball, BallSpec, Cut};
use twoball::mesh::Mesh;
use twoball::Material;

/// Ball diameter of every impact test, m.
pub const DIAMETER: f64 = 0.02;

/// Copper of the paper's FE study, made purely elastic (yield far above any stress).
pub fn elastic_copper() -> Material {
    let mut m = Material::preset("copper-fe").unwrap();
    m.yield_strength = 1e15;
    m
}

/// What one impact gave, with the Hertz values it is compared with.
#[derive(Debug, Clone, Copy)]
pub struct Impact {
    pub elements: usize,
    pub steps: u64,
    /// Maximum approach, m (the pair's: two balls, or twice the wall case).
    pub delta_max: f64,
    pub hertz_delta: f64,
    /// Contact duration, s.
    pub duration: f64,
    pub hertz_duration: f64,
    /// Peak contact force, N (full ball).
    pub peak_force: f64,
    pub hertz_force: f64,
    /// Peak of the force history averaged over a sliding window of t_c/100 (N, full ball):
    /// removes the ringing of surface nodes entering contact one ring at a time.
    pub peak_force_filtered: f64,
    /// Coefficient of restitution (normal, from centre-of-mass velocities).
    pub restitution: f64,
    /// Largest |total/initial − 1| over the impact.
    pub energy_error: f64,
    /// Contact stored energy after separation / initial kinetic energy.
    pub residual_contact_energy: f64,
    /// Largest penetration / delta_max.
    pub penetration_ratio: f64,
}

impl Impact {
    pub fn errors(&self) -> (f64, f64, f64) {
        (
            self.delta_max / self.hertz_delta - 1.0,
            self.duration / self.hertz_duration - 1.0,
            self.peak_force_filtered / self.hertz_force - 1.0,
        )
    }
}

/// A quarter ball (y ≥ 0, z ≥ 0) of the given pole and far-field element sizes.
pub fn quarter_ball(pole: f64, size: f64) -> Mesh {
    ball(&BallSpec {
        diameter: DIAMETER,
        size,
        pole_size: Some(pole),
        cut: Cut::Quarter,
    })
    .unwrap()
}

fn symmetric(model: &mut Model, p: usize) {
    model.fix_set(p, "sym_y", 1).unwrap();
    model.fix_set(p, "sym_z", 2).unwrap();
}

/// Runs the impact until the contact has ended and the balls have moved apart; returns what
/// it measured. `ball_ball`: two quarter balls at ±v/2 (relative speed v) with two-pass
/// contact; otherwise one quarter ball at v/2 against the frictionless wall.
pub fn impact(v: f64, pole: f64, size: f64, penalty: PenaltyRule, ball_ball: bool) -> Impact {
    impact_damped(v, pole, size, penalty, 0.0, ball_ball)
}

/// [`impact`] with contact damping `zeta` (fraction of critical).
pub fn impact_damped(
    v: f64,
    pole: f64,
    size: f64,
    penalty: PenaltyRule,
    zeta: f64,
    ball_ball: bool,
) -> Impact {
    let mat = elastic_copper();
    let r = 0.5 * DIAMETER;
    let q = quarter_ball(pole, size);
    let mut model = Model::new();
    let a = model
        .add_part("ball1", &q, mat, Formulation::OnePoint)
        .unwrap();
    model.part_mut(a).unwrap().elastic_only = true;
    symmetric(&mut model, a);
    model
        .set_rigid_velocity(a, [0.5 * v, 0.0, 0.0], [0.0; 3], [0.0; 3])
        .unwrap();
    let params = ContactParams {
        penalty,
        damping: zeta,
        ..Default::default()
    };
    let faces_a = model.parts[a].face_sets["contact"].clone();
    let (contact, probe): (Box<dyn Interaction>, ContactProbe) = if ball_ball {
        let other = q.mirrored_x().translated([2.0 * r, 0.0, 0.0]);
        let b = model
            .add_part("ball2", &other, mat, Formulation::OnePoint)
            .unwrap();
        model.part_mut(b).unwrap().elastic_only = true;
        symmetric(&mut model, b);
        model
            .set_rigid_velocity(b, [-0.5 * v, 0.0, 0.0], [0.0; 3], [0.0; 3])
            .unwrap();
        let faces_b = model.parts[b].face_sets["contact"].clone();
        let pair = SurfacePair::new(
            &model.nodes,
            &model.hexes,
            &faces_a,
            &mat,
            &faces_b,
            &mat,
            params,
        )
        .unwrap();
        let probe = pair.probe();
        (Box::new(pair), probe)
    } else {
        let wall = RigidPlane::new(
            &model.nodes,
            &model.hexes,
            &faces_a,
            &mat,
            [r, 0.0, 0.0],
            [-1.0, 0.0, 0.0],
            params,
        )
        .unwrap();
        let probe = wall.probe();
        (Box::new(wall), probe)
    };
    let elements = model.hexes.len();
    let mut s = Solver::new(model, vec![contact], Settings::default()).unwrap();
    let m_quarter: f64 = s.mass()[s.model().parts[0].nodes.clone()].iter().sum();
    let m_ball = 4.0 * m_quarter;
    // Hertz with the FE ball's own (discretised) mass.
    let pair = HertzPair::new(mat.plane_strain_modulus() / 2.0, r / 2.0, m_ball / 2.0);
    let hertz_delta = pair.max_approach(v);
    let hertz_duration = pair.contact_duration(v);
    let hertz_force = pair.peak_force(v);
    let mut delta_max: f64 = 0.0;
    let mut energy_error: f64 = 0.0;
    let cm = |s: &Solver, p: usize| -> f64 {
        let part = &s.model().parts[p];
        let (mut m, mut mx) = (0.0, 0.0);
        for n in part.nodes.clone() {
            m += s.mass()[n];
            mx += s.mass()[n] * s.x()[n][0];
        }
        mx / m
    };
    let x0 = cm(&s, 0);
    let x1 = if ball_ball { cm(&s, 1) } else { 0.0 };
    let mut history: Vec<(f64, f64)> = Vec::new();
    let t_end = 1.3 * hertz_duration;
    let mut step = 0u64;
    while s.time() < t_end {
        if let (Some(_), Some(l)) = (probe.get().first_contact, probe.get().last_contact) {
            if s.time() > l + 0.05 * hertz_duration {
                break;
            }
        }
        s.step().unwrap();
        step += 1;
        // Approach of the centres of mass; the wall is the mirror plane of the pair.
        let d = if ball_ball {
            (cm(&s, 0) - x0) - (cm(&s, 1) - x1)
        } else {
            2.0 * (cm(&s, 0) - x0)
        };
        delta_max = delta_max.max(d);
        history.push((s.time(), 4.0 * probe.last().normal_force));
        if step.is_multiple_of(50) {
            energy_error = energy_error.max((s.energy().energy_ratio - 1.0).abs());
        }
    }
    let e = s.energy();
    energy_error = energy_error.max((e.energy_ratio - 1.0).abs());
    let pd = probe.get();
    let duration = pd.last_contact.unwrap_or(0.0) - pd.first_contact.unwrap_or(0.0);
    let v_after = s.part_motion(0).unwrap().0[0];
    let restitution = -v_after / (0.5 * v);
    // Sliding-window average of the force history.
    let w = hertz_duration / 100.0;
    let mut peak_force_filtered: f64 = 0.0;
    let (mut lo, mut sum) = (0usize, 0.0);
    for hi in 0..history.len() {
        sum += history[hi].1;
        while history[hi].0 - history[lo].0 > w {
            sum -= history[lo].1;
            lo += 1;
        }
        peak_force_filtered = peak_force_filtered.max(sum / (hi - lo + 1) as f64);
    }
    Impact {
        peak_force_filtered,
        elements,
        steps: s.step_count(),
        delta_max,
        hertz_delta,
        duration,
        hertz_duration,
        peak_force: 4.0 * pd.peak_normal_force,
        hertz_force,
        restitution,
        energy_error,
        residual_contact_energy: pd.last.stored_energy / (0.5 * m_ball * 0.25 * v * v),
        penetration_ratio: pd.peak_penetration / delta_max,
    }
}
