//! The FE side of the benchmark: one head-on point on the meridian section
//! ([`head_on_fe`]) and one oblique point on the 3D half model ([`oblique_fe`]), each with
//! the numbers the laws are compared with.

use super::matrix::{HeadOnPoint, ObliquePoint};
use crate::analytic::{Body, HertzPair};
use crate::error::{Error, Result};
use crate::fe::axisym::impact::{HeadOn, Target};
use crate::mesh::meridian::ladder_ball;
use crate::scene::Scene;
use crate::study::simulate::RunOptions;
use crate::study::single::run_scene;
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use std::path::Path;

/// A value with its absolute error (same unit); `error` is NaN when no estimate exists.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Bar {
    /// The value.
    pub value: f64,
    /// Its absolute error (NaN: not estimated; written as JSON null).
    #[serde(serialize_with = "nan_as_null", deserialize_with = "null_as_nan")]
    pub error: f64,
}

impl Bar {
    /// A value without an error estimate.
    pub fn bare(value: f64) -> Self {
        Bar {
            value,
            error: f64::NAN,
        }
    }

    /// The error relative to the value (NaN without an estimate).
    pub fn relative_error(&self) -> f64 {
        self.error / self.value.abs()
    }
}

fn nan_as_null<S: Serializer>(x: &f64, s: S) -> std::result::Result<S::Ok, S::Error> {
    if x.is_finite() {
        s.serialize_f64(*x)
    } else {
        s.serialize_none()
    }
}

fn null_as_nan<'de, D: Deserializer<'de>>(d: D) -> std::result::Result<f64, D::Error> {
    Ok(Option::<f64>::deserialize(d)?.unwrap_or(f64::NAN))
}

/// What the FE says about one head-on point.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FePoint {
    /// Coefficient of restitution, -.
    pub e: Bar,
    /// Maximum approach of the centres, m.
    pub delta_max: Bar,
    /// Contact duration, s.
    pub contact_duration: Bar,
    /// Peak normal force, N.
    pub peak_force: Bar,
    /// The pilot run's contact history: rows [t (s), δ (m), F (N)].
    pub curve: Vec<[f64; 3]>,
    /// Seconds of one core the point cost (the runs' wall time, each run on one thread).
    pub cpu_seconds: f64,
}

/// What the FE says about one oblique point (contact frame: normal x, tangential y, spins
/// about z).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ObliqueFe {
    /// Coefficient of restitution, -.
    pub e: f64,
    /// Tangential restitution of the contact points −u⁺/u⁻, -.
    pub tangential_restitution: f64,
    /// Spin of ball 1 after the impact, rad/s.
    pub spin: f64,
    /// Tangential velocity of ball 1 after the impact, m/s.
    pub v1t_after: f64,
    /// Maximum approach, m.
    pub delta_max: f64,
    /// Contact duration, s.
    pub contact_duration: f64,
    /// Largest relative energy error of the run.
    pub energy_error: f64,
    /// Seconds of the run (wall time; the 3D loop may use more than one core).
    pub wall_seconds: f64,
}

/// Hertz's contact radius a = √(R*δ_max) (m) of the point's pair at its speed.
///
/// Errors: a diameter or material the ball rejects.
pub fn hertz_contact_radius(p: &HeadOnPoint) -> Result<f64> {
    let b = Body::ball(p.material, p.diameter, "ball")?;
    let pair = HertzPair::between(&b, &b);
    Ok(pair.contact_radius(pair.max_approach(p.speed)))
}

/// The FE answer for one head-on point: e, δ_max, t_c and the peak force with their error
/// bars, the pilot run's (t, δ, F) rows and the CPU seconds spent.
///
/// Errors: a mesh the ladder rejects (contact radius outside its range), a run that fails
/// (named by the section model).
pub fn head_on_fe(point: &HeadOnPoint) -> Result<FePoint> {
    // One level-0 run: no error bar. `study::phase_ensemble::converged_head_on` gives the
    // bar at about 8-16 times this cost (over the bench's 20 min at the low speeds); using it
    // here must also rename super::FE_MODEL, so that cached single runs are rerun.
    let a = hertz_contact_radius(point)?;
    let mesh = ladder_ball(point.diameter, a, 0)?;
    let run = HeadOn::new(mesh, point.material, 0.5 * point.speed, Target::MirrorBall).run()?;
    Ok(FePoint {
        e: Bar::bare(run.e),
        delta_max: Bar::bare(run.delta_max),
        contact_duration: Bar::bare(run.contact_duration),
        peak_force: Bar::bare(run.peak_force),
        curve: run
            .history
            .iter()
            .map(|r| [r.t, r.delta, r.normal_force])
            .collect(),
        cpu_seconds: run.wall_time_s,
    })
}

/// The scene of an oblique point: two identical balls touching along x, relative velocity
/// (v_n, ratio·v_n, 0) split equally, default (graded) meshes, reduction chosen by the
/// scene reader's `auto` (the half model).
pub fn oblique_scene(p: &ObliquePoint) -> Result<Scene> {
    let (vn, vt) = (0.5 * p.normal_speed, 0.5 * p.ratio * p.normal_speed);
    let ball = |v: [f64; 2]| {
        format!(
            "material = \"{}\"\ndiameter = {:e}\nvelocity = [{:e}, {:e}, 0.0]\n",
            p.metal, p.diameter, v[0], v[1]
        )
    };
    let text = format!("[ball1]\n{}\n[ball2]\n{}", ball([vn, vt]), ball([-vn, -vt]));
    Scene::from_toml(&text, Path::new("."), &[])
}

/// The FE answer for one oblique point (one run of the 3D model the scene reader picks).
///
/// Errors: a scene or run that fails.
pub fn oblique_fe(p: &ObliquePoint) -> Result<ObliqueFe> {
    let scene = oblique_scene(p)?;
    let r = run_scene(
        &scene,
        &RunOptions {
            history_rows: 200,
            ..RunOptions::default()
        },
    )?;
    let e =
        r.e.ok_or_else(|| Error::Numerical("oblique point: the balls do not collide".into()))?;
    let radius = 0.5 * p.diameter;
    // Contact points: ball 1's at +R x, ball 2's at −R x; their y velocities.
    let slip = |v1: [f64; 3], w1: [f64; 3], v2: [f64; 3], w2: [f64; 3]| {
        v1[1] + radius * w1[2] - (v2[1] - radius * w2[2])
    };
    let before = slip(
        scene.ball1.velocity,
        scene.ball1.angular_velocity,
        scene.ball2.velocity,
        scene.ball2.angular_velocity,
    );
    let after = slip(r.v1_after, r.w1_after, r.v2_after, r.w2_after);
    Ok(ObliqueFe {
        e,
        tangential_restitution: -after / before,
        spin: r.w1_after[2],
        v1t_after: r.v1_after[1],
        delta_max: r.delta_max,
        contact_duration: r.contact_duration,
        energy_error: r.energy_error,
        wall_seconds: r.wall_time_s,
    })
}
