//! Free flight up to first touch, in closed form, and the contact frame at touch.
//!
//! Before they touch, the balls move rigidly at constant velocity and spin, so nothing needs
//! simulating: the touch time solves |d + w t| = R1 + R2 (d the centre-to-centre vector, w the
//! relative velocity). At touch, the contact frame has x along the line of centres (ball 1 to
//! ball 2) and y along the tangential slip of the contact points.

use super::Scene;
use crate::error::{Error, Result};
use serde::Serialize;

type V3 = [f64; 3];

fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn add(a: V3, b: V3) -> V3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
fn scale(a: V3, s: f64) -> V3 {
    [a[0] * s, a[1] * s, a[2] * s]
}
fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn norm(a: V3) -> f64 {
    dot(a, a).sqrt()
}

/// An orthonormal frame: `axes[i]` is local axis i in scene (global) coordinates.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Frame {
    /// Local x (line of centres), y (tangential slip), z axes, as global unit vectors.
    pub axes: [V3; 3],
}

impl Frame {
    /// The scene's own axes.
    pub const IDENTITY: Frame = Frame {
        axes: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
    };

    /// Global vector → local components.
    pub fn to_local(&self, g: V3) -> V3 {
        [
            dot(self.axes[0], g),
            dot(self.axes[1], g),
            dot(self.axes[2], g),
        ]
    }

    /// Local components → global vector.
    pub fn to_global(&self, l: V3) -> V3 {
        let a = self.axes;
        add(add(scale(a[0], l[0]), scale(a[1], l[1])), scale(a[2], l[2]))
    }
}

/// The state of the two balls at first touch, in the contact frame.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Touch {
    /// Free-flight time from the scene's start to first touch, s.
    pub t_touch: f64,
    /// The contact frame.
    pub frame: Frame,
    /// Centre-of-mass velocities of ball 1 and 2 in the contact frame, m/s.
    pub v: [V3; 2],
    /// Angular velocities of ball 1 and 2 in the contact frame, rad/s.
    pub w: [V3; 2],
    /// Relative normal approach speed v_r = (v1 − v2)·n > 0, m/s.
    pub approach_speed: f64,
    /// Tangential slip speed of the contact points at touch, m/s.
    pub slip_speed: f64,
}

impl Touch {
    /// Ball 1's partner at touch, contact frame: ball 2's velocity (m/s) and spin (rad/s), or
    /// zero for a wall (a wall scene's ball 2 is ball 1's image, for the geometry only).
    pub fn partner(&self, scene: &Scene) -> ([f64; 3], [f64; 3]) {
        if scene.wall.is_some() {
            ([0.0; 3], [0.0; 3])
        } else {
            (self.v[1], self.w[1])
        }
    }
}

/// What free flight leads to.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Approach {
    /// The balls never touch or touch while moving apart: nothing to simulate.
    NoImpact {
        /// Why, in words.
        reason: String,
    },
    /// They touch while approaching.
    Impact(Touch),
}

/// Free flight of `scene` to first touch. Fails when the balls overlap at the start.
pub fn approach(scene: &Scene) -> Result<Approach> {
    let (r1, r2) = (scene.ball1.diameter / 2.0, scene.ball2.diameter / 2.0);
    let reach = r1 + r2;
    let (c1, c2) = scene.centres();
    let d = sub(c2, c1);
    let dist = norm(d);
    if dist < reach * (1.0 - 1e-9) {
        return Err(Error::invalid(
            "ball2.position",
            format!("{c2:?} (centre distance {dist:.6e} m)"),
            format!("centre distance >= r1 + r2 = {reach:.6e} m: the balls overlap at the start"),
        ));
    }
    let (v1, v2) = (scene.ball1.velocity, scene.ball2.velocity);
    let w = sub(v2, v1);
    let mut t_touch = 0.0;
    if dist > reach * (1.0 + 1e-9) {
        // Smallest t >= 0 with |d + w t| = reach.
        let a = dot(w, w);
        let b = dot(d, w);
        let disc = b * b - a * (dist * dist - reach * reach);
        if a == 0.0 || b >= 0.0 || disc < 0.0 {
            return Ok(Approach::NoImpact {
                reason: "the balls never touch: their paths do not meet".into(),
            });
        }
        t_touch = (-b - disc.sqrt()) / a;
    }
    let dt = add(d, scale(w, t_touch));
    let n = scale(dt, 1.0 / norm(dt));
    let v_r = dot(sub(v1, v2), n);
    if v_r <= 0.0 {
        return Ok(Approach::NoImpact {
            reason: format!("the balls are moving apart or side by side at touch (approach speed {v_r:.3e} m/s <= 0)"),
        });
    }
    // Velocities of the two contact points, their tangential difference is the slip.
    let (w1, w2) = (scene.ball1.angular_velocity, scene.ball2.angular_velocity);
    let p1 = add(v1, cross(w1, scale(n, r1)));
    // A wall's contact point is at rest (ball 2 is then ball 1's image, for the geometry).
    let p2 = if scene.wall.is_some() {
        [0.0; 3]
    } else {
        add(v2, cross(w2, scale(n, -r2)))
    };
    let rel = sub(p1, p2);
    let slip = sub(rel, scale(n, dot(rel, n)));
    let slip_speed = norm(slip);
    let speed_scale = norm(v1) + norm(v2) + norm(w1) * r1 + norm(w2) * r2;
    let ey = if slip_speed > 1e-12 * speed_scale {
        scale(slip, 1.0 / slip_speed)
    } else {
        // No slip: keep the scene's y (or z) axis as near as possible.
        let gy = [0.0, 1.0, 0.0];
        let py = sub(gy, scale(n, dot(gy, n)));
        if norm(py) > 1e-6 {
            scale(py, 1.0 / norm(py))
        } else {
            let gz = [0.0, 0.0, 1.0];
            let pz = sub(gz, scale(n, dot(gz, n)));
            scale(pz, 1.0 / norm(pz))
        }
    };
    let ez = cross(n, ey);
    let frame = Frame { axes: [n, ey, ez] };
    Ok(Approach::Impact(Touch {
        t_touch,
        frame,
        v: [frame.to_local(v1), frame.to_local(v2)],
        w: [frame.to_local(w1), frame.to_local(w2)],
        approach_speed: v_r,
        slip_speed,
    }))
}
