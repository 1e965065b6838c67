//! The outcome of one collision, the same quantities from either model, so FE and analytical
//! answers can be put side by side and differenced.

use crate::analytic::maw_barber_fawcett::{impact, DEFAULT_RESOLUTION};
use crate::analytic::{Body, Collision};
use crate::error::{Error, Result};
use crate::scene::{Scene, Touch, WallScene};
use crate::study::records::tangential::slip_y;
use serde::{Deserialize, Serialize};

/// What a collision produced. Vectors are in the scene's (global) frame.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Outcome {
    /// Normal coefficient of restitution e = −(v1n⁺ − v2n⁺)/(v1n − v2n) along the line of
    /// centres at touch.
    pub e: f64,
    /// Centre-of-mass velocity of ball 1 after the impact, m/s.
    pub v1_after: [f64; 3],
    /// Centre-of-mass velocity of ball 2 after the impact, m/s.
    pub v2_after: [f64; 3],
    /// Angular velocity of ball 1 after the impact, rad/s.
    pub w1_after: [f64; 3],
    /// Angular velocity of ball 2 after the impact, rad/s.
    pub w2_after: [f64; 3],
    /// Maximum approach of the mass centres δ_max, m.
    pub delta_max: f64,
    /// Contact duration, s.
    pub contact_duration: f64,
    /// Energy dissipation factor η = (KE before − KE after)/(2π KE before), eq. 33, with the
    /// rigid-body kinetic energy (translation and spin) of both balls.
    pub eta: f64,
}

impl Outcome {
    /// True when every number is finite (nothing non-finite is ever written).
    pub fn is_finite(&self) -> bool {
        [self.e, self.delta_max, self.contact_duration, self.eta]
            .iter()
            .chain(self.v1_after.iter())
            .chain(self.v2_after.iter())
            .chain(self.w1_after.iter())
            .chain(self.w2_after.iter())
            .all(|v| v.is_finite())
    }

    /// Fails with a message naming the first non-finite quantity (`what` names the model).
    pub fn check_finite(&self, what: &str) -> Result<()> {
        if self.is_finite() {
            Ok(())
        } else {
            Err(Error::Numerical(format!(
                "{what}: non-finite result {self:?}"
            )))
        }
    }
}

/// Mass (kg) and moment of inertia (kg m²) of a solid homogeneous ball.
pub fn ball_inertia(rho: f64, diameter: f64) -> (f64, f64) {
    let r = diameter / 2.0;
    let m = rho * 4.0 / 3.0 * std::f64::consts::PI * r.powi(3);
    (m, 0.4 * m * r * r)
}

/// Rigid-body kinetic energy (J) of both balls of `scene` with the given velocities (m/s) and
/// angular velocities (rad/s).
pub fn rigid_kinetic_energy(scene: &Scene, v: [[f64; 3]; 2], w: [[f64; 3]; 2]) -> f64 {
    let mut ke = 0.0;
    // A wall scene's ball2 is the image of ball 1 in the wall: it carries no energy.
    let balls = if scene.wall.is_some() { 1 } else { 2 };
    for (i, b) in [&scene.ball1, &scene.ball2]
        .into_iter()
        .enumerate()
        .take(balls)
    {
        let (m, j) = ball_inertia(b.material.rho, b.diameter);
        let v2: f64 = v[i].iter().map(|c| c * c).sum();
        let w2: f64 = w[i].iter().map(|c| c * c).sum();
        ke += 0.5 * m * v2 + 0.5 * j * w2;
    }
    ke
}

/// η of eq. 33 from the rigid-body states before and after.
pub fn dissipation_factor(scene: &Scene, after_v: [[f64; 3]; 2], after_w: [[f64; 3]; 2]) -> f64 {
    let before = rigid_kinetic_energy(
        scene,
        [scene.ball1.velocity, scene.ball2.velocity],
        [scene.ball1.angular_velocity, scene.ball2.angular_velocity],
    );
    let after = rigid_kinetic_energy(scene, after_v, after_w);
    if before > 0.0 {
        (before - after) / (2.0 * std::f64::consts::PI * before)
    } else {
        0.0
    }
}

/// Ball 1's partner for the analytical model and the contact laws, with its velocity (m/s,
/// contact frame) given the scene's ball-2 velocity `v2`: ball 2, or for a `[wall]` scene the
/// rigid half-space at rest (`twoball analytic --wall rigid`), or for an elastic wall the
/// elastic-plastic half-space of its material at rest (`--wall elastic`). Errors: ball 2's
/// material.
pub fn analytic_partner(scene: &Scene, v2: [f64; 3]) -> Result<(Body, [f64; 3])> {
    Ok(match scene.wall {
        Some(WallScene {
            material: Some(material),
            ..
        }) => (Body::HalfSpace { material }, [0.0; 3]),
        Some(_) => (Body::RigidWall, [0.0; 3]),
        None => (
            Body::ball(scene.ball2.material, scene.ball2.diameter, "ball2")?,
            v2,
        ),
    })
}

/// A model's answer in the contact frame at touch: velocities (m/s) and spins (rad/s) after,
/// of ball 1 and its partner.
struct FrameAnswer {
    e: f64,
    v: [[f64; 3]; 2],
    w: [[f64; 3]; 2],
    delta_max: f64,
    contact_duration: f64,
}

impl FrameAnswer {
    /// The [`Outcome`] in the scene's frame, η from its rigid-body kinetic energy. Errors: a
    /// non-finite number, named by `model`.
    fn outcome(&self, scene: &Scene, touch: &Touch, model: &str) -> Result<Outcome> {
        let f = touch.frame;
        let (v1, v2) = (f.to_global(self.v[0]), f.to_global(self.v[1]));
        let (w1, w2) = (f.to_global(self.w[0]), f.to_global(self.w[1]));
        let out = Outcome {
            e: self.e,
            v1_after: v1,
            v2_after: v2,
            w1_after: w1,
            w2_after: w2,
            delta_max: self.delta_max,
            contact_duration: self.contact_duration,
            eta: dissipation_factor(scene, [v1, v2], [w1, w2]),
        };
        out.check_finite(model)?;
        Ok(out)
    }
}

/// The analytical model's answer for `scene` touching as `touch`: its [`Collision`] and the
/// [`Outcome`] built from it.
///
/// The analytical model is two-dimensional (normal, and one tangential direction: the slip
/// direction of the contact frame) and starts without spin. Initial spins enter through the
/// slip they give the contact points, ω₁R₁ + ω₂R₂ about the frame's z: the Coulomb impulse
/// depends on the slip alone, so the model runs with that slip added to ball 1's tangential
/// speed and the same amount is taken off its tangential speed after. The out-of-plane
/// velocity component passes unchanged.
pub fn analytic_outcome(scene: &Scene, touch: &Touch) -> Result<(Outcome, Collision)> {
    let b1 = Body::ball(scene.ball1.material, scene.ball1.diameter, "ball1")?;
    let (mu, _) = scene.friction_coefficients();
    let [a, b] = touch.v;
    let (b2, b) = analytic_partner(scene, b)?;
    let (_, w2) = touch.partner(scene);
    let spin_slip = slip_y(scene, [0.0; 3], touch.w[0], w2);
    // Without spin the speeds pass untouched (no signed zero turned positive).
    let shift = |v: f64, by: f64| if spin_slip == 0.0 { v } else { v + by };
    let v1t = shift(a[1], spin_slip);
    let c = crate::analytic::collide_with_mu(&b1, &b2, [a[0], v1t], [b[0], b[1]], mu)?;
    let [wa, wb] = touch.w;
    let (e, delta_max, contact_duration) = match &c.normal {
        Some(n) => (n.e, n.delta2, n.t3),
        None => (1.0, 0.0, 0.0),
    };
    let (v1, v2, spin) = (c.after.v1_after, c.after.v2_after, c.after.spin_after);
    let answer = FrameAnswer {
        e,
        v: [
            [v1[0], shift(v1[1], -spin_slip), a[2]],
            [v2[0], v2[1], b[2]],
        ],
        w: [
            [wa[0], wa[1], wa[2] + spin[0]],
            [wb[0], wb[1], wb[2] + spin[1]],
        ],
        delta_max,
        contact_duration,
    };
    let out = answer.outcome(scene, touch, "analytical model")?;
    Ok((out, c))
}

/// Maw, Barber & Fawcett's elastic answer for `scene` touching as `touch`
/// ([`crate::analytic::maw_barber_fawcett`], Hertz normal, Cattaneo-Mindlin partial slip), or
/// `None` when the analytical model's `collision` yields (the theory is elastic). δ_max is
/// Hertz's from the collision.
pub fn elastic_theory_outcome(
    scene: &Scene,
    touch: &Touch,
    collision: &Collision,
) -> Result<Option<Outcome>> {
    let Some(normal) = collision.normal.as_ref().filter(|n| !n.yielded) else {
        return Ok(None);
    };
    let b1 = Body::ball(scene.ball1.material, scene.ball1.diameter, "ball1")?;
    let (mu, _) = scene.friction_coefficients();
    if mu <= 0.0 {
        return Ok(None);
    }
    let [a, b] = touch.v;
    let (b2, b) = analytic_partner(scene, b)?;
    let (_, w2) = touch.partner(scene);
    let [wa, _] = touch.w;
    let velocity = [[a[0], a[1]], [b[0], b[1]]];
    let spin = [wa[2], w2[2]];
    let Some(i) = impact(&b1, &b2, velocity, spin, mu, DEFAULT_RESOLUTION)? else {
        return Ok(None);
    };
    let answer = FrameAnswer {
        e: i.e,
        v: [
            [i.v1_after[0], i.v1_after[1], a[2]],
            [i.v2_after[0], i.v2_after[1], b[2]],
        ],
        w: [
            [wa[0], wa[1], i.spin_after[0]],
            [w2[0], w2[1], i.spin_after[1]],
        ],
        delta_max: normal.delta2,
        contact_duration: i.contact_duration,
    };
    let out = answer.outcome(scene, touch, "elastic oblique theory")?;
    Ok(Some(out))
}

/// Relative difference (a − b)/|b|, or the absolute difference when |b| is tiny.
pub fn relative_difference(a: f64, b: f64) -> f64 {
    if b.abs() > 1e-300 {
        (a - b) / b.abs()
    } else {
        a - b
    }
}
