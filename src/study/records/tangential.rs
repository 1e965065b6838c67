//! The tangential side of an oblique or spinning impact, in the contact frame at touch (x the
//! line of centres from ball 1 to ball 2, y the slip of the contact points): the tangential
//! restitution of the contact point and the incidence and rebound angles of ball 1 relative
//! to its partner (ball 2, or the wall at rest).

use crate::scene::{Scene, Touch};
use crate::study::records::outcome::Outcome;
use serde::Serialize;

/// The tangential figures of one model's outcome.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Tangential {
    /// Tangential restitution of the contact point, −(slip after)/(slip before) along the
    /// slip at touch, - (1: the slip reversed in full, −1: kept, 0: rolling); null without
    /// slip at touch.
    pub restitution: Option<f64>,
    /// Angle of ball 1's velocity relative to its partner from the contact normal at touch,
    /// rad (0: head-on).
    pub incidence_angle: f64,
    /// The same angle after the impact, from the outward normal, rad.
    pub rebound_angle: f64,
    /// Ball 1's spin about the contact frame's z axis (normal to the normal and the slip)
    /// after the impact, rad/s.
    pub spin1_after: f64,
    /// The same spin at touch, rad/s.
    pub spin1_before: f64,
    /// Ball 1's rotational inertia about that axis over m R², -: the FE mesh's (absent for
    /// the analytical models' solid sphere, 0.4).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub spin1_inertia_ratio: Option<f64>,
}

impl Tangential {
    /// The same figures with ball 1's rotational inertia over m R² (-) of the model behind them.
    pub fn with_spin1_inertia_ratio(self, ratio: Option<f64>) -> Tangential {
        Tangential {
            spin1_inertia_ratio: ratio,
            ..self
        }
    }
}

/// FE and analytical tangential figures of an oblique or spinning impact (results.json
/// `tangential`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TangentialPair {
    /// From the FE outcome.
    pub fe: Tangential,
    /// From the analytical model's outcome.
    pub analytic: Tangential,
    /// From Maw, Barber & Fawcett's elastic theory ([`crate::analytic::maw_barber_fawcett`]);
    /// absent when the analytical model says the contact yields.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub theory: Option<Tangential>,
}

/// True when the impact has a tangential side: slip of the contact points, or a tangential
/// relative velocity of the centres, at touch.
pub fn is_oblique(scene: &Scene, touch: &Touch) -> bool {
    let g = sub(touch.v[0], touch.partner(scene).0);
    let scale = touch.approach_speed.abs().max(f64::MIN_POSITIVE);
    touch.slip_speed > 1e-12 * scale || g[1].hypot(g[2]) > 1e-12 * scale
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// Slip of ball 1's contact point against its partner's along the contact frame's y, from
/// the relative velocity `g` (m/s) and the spins `w1`, `w2` (rad/s, contact frame): the
/// contact point sits at +R1 x on ball 1 and −R2 x on ball 2, so ω × r adds ω_z R along y.
pub(crate) fn slip_y(scene: &Scene, g: [f64; 3], w1: [f64; 3], w2: [f64; 3]) -> f64 {
    let (r1, r2) = (scene.ball1.diameter / 2.0, scene.ball2.diameter / 2.0);
    g[1] + w1[2] * r1 + w2[2] * r2
}

/// The tangential figures of `out` (scene frame) for `scene` touching as `touch`.
pub fn tangential(scene: &Scene, touch: &Touch, out: &Outcome) -> Tangential {
    let f = touch.frame;
    // After the impact a wall's outcome is at rest already; at touch ball 2 is its image.
    let (v2, w2_touch) = touch.partner(scene);
    let g0 = sub(touch.v[0], v2);
    let g1 = sub(f.to_local(out.v1_after), f.to_local(out.v2_after));
    let (w1, w2) = (f.to_local(out.w1_after), f.to_local(out.w2_after));
    let before = slip_y(scene, g0, touch.w[0], w2_touch);
    let after = slip_y(scene, g1, w1, w2);
    let scale = touch.approach_speed.abs().max(f64::MIN_POSITIVE);
    Tangential {
        // `+ 0.0` writes a rolling contact point's −0 as 0.
        restitution: (before.abs() > 1e-12 * scale).then(|| -after / before + 0.0),
        incidence_angle: g0[1].hypot(g0[2]).atan2(g0[0]),
        rebound_angle: g1[1].hypot(g1[2]).atan2(-g1[0]),
        spin1_after: w1[2],
        spin1_before: touch.w[0][2],
        spin1_inertia_ratio: None,
    }
}
