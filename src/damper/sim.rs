//! The damper in motion: the state of the frame and the balls, one velocity-Verlet step, the
//! contact forces of a step and the energy ledger.

use super::contact::{Contact, ContactGeometry, Partner, StepWork};
use super::energy::Ledger;
use super::frame::Frame;
use super::neighbours::NeighbourList;
use super::pairs::{PairLaws, PairTable};
use super::scene::DamperScene;
use super::timestep::time_step;
use crate::analytic::laws::Registry;
use crate::error::{Error, Result};
use nalgebra::Vector3;
use std::f64::consts::PI;

/// Smallest characteristic impact speed the step is sized for, m/s.
const MIN_SPEED: f64 = 0.1;

/// Skin of the neighbour list as a fraction of the largest ball diameter.
const SKIN: f64 = 0.05;

/// One recorded instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    /// Time since release, s.
    pub time: f64,
    /// Frame displacement, m.
    pub displacement: f64,
    /// Frame velocity, m/s.
    pub velocity: f64,
    /// Frame acceleration, m/s².
    pub acceleration: f64,
    /// Horizontal force of the balls on the box, N.
    pub ball_force: f64,
    /// Number of open contacts.
    pub contacts: usize,
    /// The energy ledger.
    pub ledger: Ledger,
}

/// The state of a running damper simulation.
pub struct DamperSimulation {
    frame: Frame,
    size: Vector3<f64>,
    gravity: f64,
    table: PairTable,
    dt: f64,
    neighbours: NeighbourList,
    radius: Vec<f64>,
    mass: Vec<f64>,
    inertia: Vec<f64>,
    /// Time since release, s.
    pub time: f64,
    /// Ball centres, m (inertial frame; the box's inner corner is at (X, 0, 0)).
    pub position: Vec<Vector3<f64>>,
    /// Ball velocities, m/s.
    pub velocity: Vec<Vector3<f64>>,
    /// Ball spins, rad/s.
    pub spin: Vec<Vector3<f64>>,
    /// Frame displacement X, m.
    pub frame_x: f64,
    /// Frame velocity, m/s.
    pub frame_v: f64,
    force: Vec<Vector3<f64>>,
    torque: Vec<Vector3<f64>>,
    frame_force: f64,
    ball_force: f64,
    damper_force: f64,
    external_force: f64,
    contacts: Vec<Contact>,
    spare: Vec<Contact>,
    touching: Vec<(usize, Partner, ContactGeometry)>,
    pred_v: Vec<Vector3<f64>>,
    pred_w: Vec<Vector3<f64>>,
    pred_frame: f64,
    work_normal: f64,
    work_tangential: f64,
    structural: f64,
    impulse: f64,
    /// Steps taken.
    pub steps: u64,
}

fn cross(a: Vector3<f64>, b: Vector3<f64>) -> Vector3<f64> {
    a.cross(&b)
}

impl DamperSimulation {
    /// The scene at release: frame at rest at its release displacement, balls at rest at
    /// their positions in the displaced box. Errors: an invalid scene (one line naming the
    /// field), an unknown law or parameter.
    pub fn new(scene: &DamperScene, registry: &Registry) -> Result<DamperSimulation> {
        scene.validate()?;
        let frame = scene.frame()?;
        let table = PairTable::new(scene, registry)?;
        let bodies = scene.bodies()?;
        let size = Vector3::from(scene.container.size);
        let speed = scene.impact_speed.unwrap_or_else(|| {
            frame.natural_frequency() * scene.frame.release.abs()
                + (2.0 * scene.gravity * size[2]).sqrt()
        });
        let period = 2.0 * PI / frame.natural_frequency();
        let dt = time_step(
            table.kinds(),
            speed.max(MIN_SPEED),
            scene.steps_per_period,
            period,
        );
        let offset = Vector3::new(scene.frame.release, 0.0, 0.0);
        let n = scene.balls.len();
        let diameter = scene.balls.iter().map(|b| b.diameter).fold(0.0, f64::max);
        let mut sim = DamperSimulation {
            frame,
            size,
            gravity: scene.gravity,
            table,
            dt,
            neighbours: NeighbourList::new(SKIN * diameter, diameter),
            radius: bodies.iter().map(|b| b.radius()).collect(),
            mass: bodies.iter().map(|b| b.mass()).collect(),
            inertia: bodies.iter().map(|b| b.moment_of_inertia()).collect(),
            time: 0.0,
            position: scene
                .balls
                .iter()
                .map(|b| Vector3::from(b.position) + offset)
                .collect(),
            velocity: vec![Vector3::zeros(); n],
            spin: vec![Vector3::zeros(); n],
            frame_x: scene.frame.release,
            frame_v: 0.0,
            force: vec![Vector3::zeros(); n],
            torque: vec![Vector3::zeros(); n],
            frame_force: 0.0,
            ball_force: 0.0,
            damper_force: 0.0,
            external_force: 0.0,
            contacts: Vec::new(),
            spare: Vec::new(),
            touching: Vec::new(),
            pred_v: vec![Vector3::zeros(); n],
            pred_w: vec![Vector3::zeros(); n],
            pred_frame: 0.0,
            work_normal: 0.0,
            work_tangential: 0.0,
            structural: 0.0,
            impulse: 0.0,
            steps: 0,
        };
        sim.forces(0.0);
        Ok(sim)
    }

    /// The time step, s.
    pub fn dt(&self) -> f64 {
        self.dt
    }

    /// The frame.
    pub fn frame(&self) -> &Frame {
        &self.frame
    }

    /// Ball radii, m.
    pub fn radii(&self) -> &[f64] {
        &self.radius
    }

    /// Open contacts (δ > 0).
    pub fn contacts(&self) -> &[Contact] {
        &self.contacts
    }

    /// Horizontal momentum of frame and balls, M V + Σ m vₓ, N·s.
    pub fn momentum_x(&self) -> f64 {
        self.frame.mass * self.frame_v
            + self
                .velocity
                .iter()
                .zip(&self.mass)
                .map(|(v, m)| m * v.x)
                .sum::<f64>()
    }

    /// Impulse of the frame's spring and damper since release (what the steps applied), N·s.
    pub fn spring_damper_impulse(&self) -> f64 {
        self.impulse
    }

    /// Total momentum of the balls Σ m v, N·s.
    pub fn balls_momentum(&self) -> Vector3<f64> {
        self.velocity
            .iter()
            .zip(&self.mass)
            .map(|(v, m)| v * *m)
            .sum()
    }

    /// Total angular momentum of the balls about the origin, Σ r × m v + I ω, N·m·s.
    pub fn balls_angular_momentum(&self) -> Vector3<f64> {
        (0..self.mass.len())
            .map(|i| {
                cross(self.position[i], self.velocity[i] * self.mass[i])
                    + self.spin[i] * self.inertia[i]
            })
            .sum()
    }

    /// One velocity-Verlet step: half kick, drift, forces at the new positions (velocity
    /// terms at velocities predicted to the end of the step from the last accelerations,
    /// slip increments at the mid-step velocities), half kick.
    pub fn step(&mut self) {
        let h = 0.5 * self.dt;
        self.kick(h);
        for (x, v) in self.position.iter_mut().zip(&self.velocity) {
            *x += v * self.dt;
        }
        self.frame_x += self.frame_v * self.dt;
        self.forces(self.dt);
        self.kick(h);
        self.time += self.dt;
        self.steps += 1;
    }

    fn kick(&mut self, h: f64) {
        for i in 0..self.mass.len() {
            (self.velocity[i], self.spin[i]) = self.kicked(i, h);
        }
        self.frame_v = self.frame_kicked(h);
    }

    /// Predicts the velocities to the end of the step from the mid-step ones and the last
    /// accelerations (v, ω of every ball and the frame's velocity), `h` the half step (s).
    fn predict(&mut self, h: f64) {
        for i in 0..self.mass.len() {
            (self.pred_v[i], self.pred_w[i]) = self.kicked(i, h);
        }
        self.pred_frame = self.frame_kicked(h);
    }

    /// Ball `i`'s velocity (m/s) and spin (rad/s) after its force and torque act for `h` (s).
    fn kicked(&self, i: usize, h: f64) -> (Vector3<f64>, Vector3<f64>) {
        (
            self.velocity[i] + self.force[i] * (h / self.mass[i]),
            self.spin[i] + self.torque[i] * (h / self.inertia[i]),
        )
    }

    /// The frame's velocity (m/s) after the force on it acts for `h` (s).
    fn frame_kicked(&self, h: f64) -> f64 {
        self.frame_v + self.frame_force * h / self.frame.mass
    }

    /// Ball `i`'s kinematics against wall `wall` (0..6, see [`Partner::Wall`]) if it touches
    /// it (δ > 0).
    fn wall_kinematics(&self, i: usize, wall: usize) -> Option<ContactGeometry> {
        let axis = wall / 2;
        let high = wall % 2 == 1;
        let p = self.position[i][axis] - if axis == 0 { self.frame_x } else { 0.0 };
        let gap = if high { self.size[axis] - p } else { p };
        let delta = self.radius[i] - gap;
        if delta <= 0.0 {
            return None;
        }
        let mut normal = Vector3::zeros();
        normal[axis] = if high { 1.0 } else { -1.0 };
        // The contact point lies on the wall plane.
        let r = gap;
        let at = |v: &Vector3<f64>, w: &Vector3<f64>, frame: f64| {
            v + cross(*w, normal * r) - Vector3::new(frame, 0.0, 0.0)
        };
        Some(ContactGeometry {
            normal,
            lever: [r, 0.0],
            delta,
            relative: at(&self.pred_v[i], &self.pred_w[i], self.pred_frame),
            midstep: at(&self.velocity[i], &self.spin[i], self.frame_v),
        })
    }

    /// Balls `i` and `j`'s kinematics if they touch (δ > 0).
    fn ball_kinematics(&self, i: usize, j: usize) -> Option<ContactGeometry> {
        let d = self.position[j] - self.position[i];
        let dist = d.norm();
        let delta = self.radius[i] + self.radius[j] - dist;
        if delta <= 0.0 {
            return None;
        }
        let normal = d / dist;
        // The contact point is midway through the overlap: the levers add up to the distance,
        // so the friction torques conserve angular momentum.
        let (ri, rj) = (self.radius[i] - 0.5 * delta, self.radius[j] - 0.5 * delta);
        let at = |v: &[Vector3<f64>], w: &[Vector3<f64>]| {
            v[i] + cross(w[i], normal * ri) - v[j] - cross(w[j], normal * (-rj))
        };
        Some(ContactGeometry {
            normal,
            lever: [ri, rj],
            delta,
            relative: at(&self.pred_v, &self.pred_w),
            midstep: at(&self.velocity, &self.spin),
        })
    }

    fn laws(&self, c: &Contact) -> &PairLaws {
        match c.partner {
            Partner::Ball(j) => self.table.ball(c.ball, j),
            Partner::Wall(_) => self.table.wall(c.ball),
        }
    }

    /// Fills `self.touching` with every touching (ball, partner) and its kinematics, in the
    /// order of the contacts' keys (ball, then partner: balls ascending, then walls).
    fn find_touching(&mut self) {
        let mut touching = std::mem::take(&mut self.touching);
        touching.clear();
        let origin = Vector3::new(self.frame_x, 0.0, 0.0);
        if self.mass.len() > 1 {
            self.neighbours
                .pairs(&self.position, &self.radius, origin, self.size);
        }
        let pairs = self.neighbours.list();
        let mut p = 0;
        for i in 0..self.mass.len() {
            while p < pairs.len() && pairs[p].0 == i {
                let j = pairs[p].1;
                if let Some(k) = self.ball_kinematics(i, j) {
                    touching.push((i, Partner::Ball(j), k));
                }
                p += 1;
            }
            for w in 0..6 {
                if let Some(k) = self.wall_kinematics(i, w) {
                    touching.push((i, Partner::Wall(w), k));
                }
            }
        }
        self.touching = touching;
    }

    /// Forces and torques at the present positions and (half-step) velocities; advances every
    /// contact's history by `dt` and books the work of the step. Allocates nothing once the
    /// buffers have grown to the largest number of contacts.
    fn forces(&mut self, dt: f64) {
        self.predict(0.5 * dt);
        for i in 0..self.mass.len() {
            self.force[i] = Vector3::new(0.0, 0.0, -self.gravity * self.mass[i]);
            self.torque[i] = Vector3::zeros();
        }
        self.find_touching();
        let old = std::mem::take(&mut self.contacts);
        let mut open = std::mem::take(&mut self.spare);
        open.clear();
        let mut cursor = 0;
        let mut box_force = 0.0;
        let mut work = StepWork::default();
        for &(i, partner, ref k) in &self.touching {
            let key = (i, partner);
            while cursor < old.len() && (old[cursor].ball, old[cursor].partner) < key {
                work.add(old[cursor].release_work());
                cursor += 1;
            }
            let mut c = if cursor < old.len() && (old[cursor].ball, old[cursor].partner) == key {
                cursor += 1;
                old[cursor - 1].clone()
            } else {
                Contact::touch(i, partner, k.relative.dot(&k.normal))
            };
            let laws = match partner {
                Partner::Ball(j) => self.table.ball(i, j),
                Partner::Wall(_) => self.table.wall(i),
            };
            work.add(c.update(laws, k, dt));
            let on_ball = -k.normal * c.force + c.friction;
            self.force[i] += on_ball;
            self.torque[i] += cross(k.normal * k.lever[0], c.friction);
            match partner {
                Partner::Ball(j) => {
                    self.force[j] -= on_ball;
                    self.torque[j] += cross(k.normal * k.lever[1], c.friction);
                }
                Partner::Wall(_) => box_force -= on_ball.x,
            }
            open.push(c);
        }
        for c in &old[cursor..] {
            work.add(c.release_work());
        }
        self.spare = old;
        self.contacts = open;
        self.work_normal += work.normal;
        self.work_tangential += work.tangential;
        let damper = -self.frame.damper_force(self.pred_frame);
        self.structural += 0.5 * (self.damper_force + damper) * self.frame_v * dt;
        let external = self.frame.spring_force(self.frame_x) - damper;
        self.impulse += 0.5 * dt * (self.external_force + external);
        self.damper_force = damper;
        self.external_force = external;
        self.ball_force = box_force;
        self.frame_force = external + box_force;
    }

    /// The energy ledger now (valid between steps).
    pub fn ledger(&self) -> Ledger {
        let (mut normal, mut tangential) = (0.0, 0.0);
        for c in &self.contacts {
            let (a, b) = c.stored(self.laws(c));
            normal += a;
            tangential += b;
        }
        let mut kinetic = 0.0;
        let mut potential = 0.0;
        for i in 0..self.mass.len() {
            kinetic += 0.5 * self.mass[i] * self.velocity[i].norm_squared()
                + 0.5 * self.inertia[i] * self.spin[i].norm_squared();
            potential += self.mass[i] * self.gravity * (self.position[i].z - self.radius[i]);
        }
        Ledger {
            frame_kinetic: 0.5 * self.frame.mass * self.frame_v * self.frame_v,
            frame_spring: 0.5 * self.frame.stiffness * self.frame_x * self.frame_x,
            balls_kinetic: kinetic,
            balls_potential: potential,
            contact_stored: normal + tangential,
            contact_dissipated: self.work_normal - normal,
            friction_dissipated: self.work_tangential - tangential,
            structural_dissipated: self.structural,
        }
    }

    /// The present instant as a sample.
    pub fn sample(&self) -> Sample {
        Sample {
            time: self.time,
            displacement: self.frame_x,
            velocity: self.frame_v,
            acceleration: self.frame_force / self.frame.mass,
            ball_force: self.ball_force,
            contacts: self.contacts.len(),
            ledger: self.ledger(),
        }
    }

    /// Runs to time `until` (s), recording a sample every `interval` (s) and at the start.
    /// Errors: a non-finite state (names the time and the likely cause).
    pub fn run(&mut self, until: f64, interval: f64) -> Result<Vec<Sample>> {
        self.run_observed(until, interval, &mut |_| Ok(()))
    }

    /// [`DamperSimulation::run`], calling `observe(self)` at release and after every recorded
    /// sample (to record the balls' states, show progress); an error of `observe` (e.g. an
    /// interrupt) stops the run and is returned.
    pub fn run_observed(
        &mut self,
        until: f64,
        interval: f64,
        observe: &mut dyn FnMut(&DamperSimulation) -> Result<()>,
    ) -> Result<Vec<Sample>> {
        observe(self)?;
        let mut samples = vec![self.sample()];
        let mut next = self.time + interval;
        while self.time + 0.5 * self.dt < until {
            self.step();
            if self.time + 0.5 * self.dt >= next {
                next += interval;
                let s = self.sample();
                if !(s.displacement.is_finite() && s.ledger.total().is_finite()) {
                    return Err(Error::Numerical(format!(
                        "damper state not finite at t = {} s (step {} s too large for the contact law?)",
                        self.time, self.dt
                    )));
                }
                samples.push(s);
                observe(self)?;
            }
        }
        Ok(samples)
    }
}
