//! What a damper simulation is given: the frame, the box, the balls, the contact laws and the
//! run controls, checked before anything runs.

use super::frame::Frame;
use crate::analytic::Body;
use crate::error::{Error, Result};
use crate::material::Material;

/// The frame as a free-decay test describes it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrameSpec {
    /// Mass moving with the top beam (the box included, the balls not), kg.
    pub mass: f64,
    /// Damped frequency of the empty frame, Hz.
    pub frequency: f64,
    /// Damping ratio of the empty frame (a fraction: 0.0045 is 0.45 %).
    pub damping_ratio: f64,
    /// Horizontal displacement at release, m (the frame starts at rest there).
    pub release: f64,
}

/// The closed rectangular box glued on the beam: inner size along x (the frame's motion),
/// y and z (up), m, and the wall material. Its inner corner is at (X, 0, 0), X the frame's
/// displacement.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BoxSpec {
    /// Inner size [x, y, z], m.
    pub size: [f64; 3],
    /// Wall material (a half-space in every ball-wall contact).
    pub material: Material,
}

/// One ball: material, diameter (m) and centre at release in box coordinates (m, from the
/// box's inner corner), at rest.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DamperBall {
    /// Material.
    pub material: Material,
    /// Diameter, m.
    pub diameter: f64,
    /// Centre [x, y, z] relative to the box's inner corner, m.
    pub position: [f64; 3],
}

/// The contact laws of every contact: a normal and a tangential law of the seam by name, with
/// parameter overrides (key, value) applied to every pair; friction coefficients per pair kind.
#[derive(Debug, Clone, PartialEq)]
pub struct LawChoice {
    /// Normal law name (`twoball laws` lists them).
    pub normal: String,
    /// Normal-law parameter overrides.
    pub normal_params: Vec<(String, f64)>,
    /// Tangential law name.
    pub tangential: String,
    /// Tangential-law parameter overrides.
    pub tangential_params: Vec<(String, f64)>,
    /// Ball-ball friction coefficient; `None`: the mean of the two materials' μ.
    pub mu_ball: Option<f64>,
    /// Ball-wall friction coefficient; `None`: the mean of ball and wall μ.
    pub mu_wall: Option<f64>,
}

impl Default for LawChoice {
    fn default() -> Self {
        LawChoice {
            normal: "li-yang-shi".into(),
            normal_params: Vec::new(),
            tangential: "mindlin-coulomb".into(),
            tangential_params: Vec::new(),
            mu_ball: None,
            mu_wall: None,
        }
    }
}

/// A complete damper scene.
#[derive(Debug, Clone, PartialEq)]
pub struct DamperScene {
    /// The frame.
    pub frame: FrameSpec,
    /// The box.
    pub container: BoxSpec,
    /// The balls.
    pub balls: Vec<DamperBall>,
    /// The contact laws.
    pub laws: LawChoice,
    /// Gravitational acceleration (downward, along −z), m/s².
    pub gravity: f64,
    /// Simulated time, s.
    pub duration: f64,
    /// Time steps per period of the stiffest contact oscillation (accuracy control, ≥ 10).
    pub steps_per_period: f64,
    /// Characteristic impact speed that sizes the step, m/s; `None`: the frame's peak speed
    /// at release plus the free-fall speed over the box height.
    pub impact_speed: Option<f64>,
    /// Interval between recorded samples, s.
    pub sample_interval: f64,
}

impl DamperScene {
    /// A scene with the paper's frame (5.76 kg, 1.69 Hz, 0.45 %, 30 mm release), the given
    /// box and balls, the default laws, g = 9.81 m/s², 10 s, 60 steps per period, 1 ms samples.
    pub fn paper_frame(container: BoxSpec, balls: Vec<DamperBall>) -> DamperScene {
        DamperScene {
            frame: FrameSpec {
                mass: 5.76,
                frequency: 1.69,
                damping_ratio: 0.0045,
                release: 0.03,
            },
            container,
            balls,
            laws: LawChoice::default(),
            gravity: 9.81,
            duration: 10.0,
            steps_per_period: 60.0,
            impact_speed: None,
            sample_interval: 1e-3,
        }
    }

    /// The frame this scene describes (validated).
    pub fn frame(&self) -> Result<Frame> {
        Frame::from_free_decay(
            self.frame.mass,
            self.frame.frequency,
            self.frame.damping_ratio,
        )
    }

    /// The ball bodies (validated: diameter > 0, material valid, so mass > 0).
    pub fn bodies(&self) -> Result<Vec<Body>> {
        self.balls
            .iter()
            .enumerate()
            .map(|(i, b)| Body::ball(b.material, b.diameter, &format!("balls[{i}]")))
            .collect()
    }

    /// Checks every field and the geometry: each ball fits the box and lies inside it, no two
    /// balls overlap at release. Errors are one line naming the field, value and range.
    pub fn validate(&self) -> Result<()> {
        self.frame()?;
        let r = self.frame.release;
        if !r.is_finite() {
            return Err(Error::invalid(
                "frame.release",
                r,
                "a finite displacement in m",
            ));
        }
        for (k, &s) in self.container.size.iter().enumerate() {
            if !(s.is_finite() && s > 0.0) {
                return Err(Error::invalid(
                    format!("box.size[{k}]"),
                    s,
                    "size > 0 m, finite",
                ));
            }
        }
        self.container.material.validated("box.material")?;
        let bodies = self.bodies()?;
        for (i, b) in self.balls.iter().enumerate() {
            let smallest = self
                .container
                .size
                .iter()
                .copied()
                .fold(f64::INFINITY, f64::min);
            if b.diameter > smallest {
                return Err(Error::invalid(
                    format!("balls[{i}].diameter"),
                    b.diameter,
                    format!("diameter <= {smallest} m (the box's smallest inner size)"),
                ));
            }
            for k in 0..3 {
                let (p, lo, hi) = (
                    b.position[k],
                    0.5 * b.diameter,
                    self.container.size[k] - 0.5 * b.diameter,
                );
                if !(p.is_finite() && p >= lo && p <= hi) {
                    return Err(Error::invalid(
                        format!("balls[{i}].position[{k}]"),
                        p,
                        format!("{lo} <= position <= {hi} m (the ball inside the box)"),
                    ));
                }
            }
            debug_assert!(bodies[i].mass() > 0.0);
        }
        for i in 0..self.balls.len() {
            for j in 0..i {
                let (a, b) = (&self.balls[i], &self.balls[j]);
                let d: f64 = (0..3)
                    .map(|k| (a.position[k] - b.position[k]).powi(2))
                    .sum::<f64>()
                    .sqrt();
                let touch = 0.5 * (a.diameter + b.diameter);
                if d < touch {
                    return Err(Error::invalid(
                        format!("balls[{i}].position"),
                        format!("{:?}", a.position),
                        format!("centre distance to balls[{j}] >= {touch} m (no overlap at release; it is {d} m)"),
                    ));
                }
            }
        }
        let checks = [
            (
                "gravity",
                self.gravity,
                self.gravity >= 0.0,
                "gravity >= 0 m/s^2",
            ),
            (
                "duration",
                self.duration,
                self.duration > 0.0,
                "duration > 0 s",
            ),
            (
                "steps_per_period",
                self.steps_per_period,
                self.steps_per_period >= 10.0,
                "steps_per_period >= 10",
            ),
            (
                "sample_interval",
                self.sample_interval,
                self.sample_interval > 0.0,
                "sample_interval > 0 s",
            ),
        ];
        for (name, v, ok, allowed) in checks {
            if !(v.is_finite() && ok) {
                return Err(Error::invalid(name, v, allowed));
            }
        }
        if let Some(v) = self.impact_speed {
            if !(v.is_finite() && v > 0.0) {
                return Err(Error::invalid("impact_speed", v, "impact_speed > 0 m/s"));
            }
        }
        for (name, mu) in [
            ("laws.mu_ball", self.laws.mu_ball),
            ("laws.mu_wall", self.laws.mu_wall),
        ] {
            if let Some(m) = mu {
                if m.is_nan() || m < 0.0 {
                    return Err(Error::invalid(name, m, "mu >= 0"));
                }
            }
        }
        Ok(())
    }
}
