//! The rigid-body state after an impact, from the normal and tangential impulses: what the
//! three-phase model and the law integrator both hand back.

use super::body::Body;
use super::friction::kinetic;

/// Velocities, spins and kinetic energy of two bodies after exchanging impulses.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Exchange {
    /// Ball 1's centre velocity `[normal, tangential]` after impact (m/s).
    pub v1_after: [f64; 2],
    /// Ball 2's centre velocity `[normal, tangential]` after impact (m/s).
    pub v2_after: [f64; 2],
    /// Spins of ball 1 and ball 2 after impact (rad/s; 0 for a wall).
    pub spin_after: [f64; 2],
    /// Translational plus rotational kinetic energy after impact (J).
    pub energy_after: f64,
}

/// Applies the normal impulse `jn` (N s, ball 2 pushed along +n) and the tangential impulse `jt`
/// (N s, ball 1 slowed along t) to bodies `b1`, `b2` moving at `v1`, `v2` (`[normal,
/// tangential]`, m/s, no spin before). Friction −J_t t at +R₁ n on ball 1 and +J_t t at −R₂ n
/// on ball 2 spin both by −R J_t/I. A wall (infinite mass) keeps its velocity and no spin.
pub fn exchange(b1: &Body, b2: &Body, v1: [f64; 2], v2: [f64; 2], jn: f64, jt: f64) -> Exchange {
    exchange_spinning(b1, b2, v1, v2, [0.0; 2], jn, jt)
}

/// [`exchange`] for balls spinning at `w` (rad/s, about n × t; a wall's entry is ignored)
/// before the impact: each spin changes by −R J_t/I from its own.
pub fn exchange_spinning(
    b1: &Body,
    b2: &Body,
    v1: [f64; 2],
    v2: [f64; 2],
    w: [f64; 2],
    jn: f64,
    jt: f64,
) -> Exchange {
    let (m1, m2) = (b1.mass(), b2.mass());
    let v1_after = [v1[0] - jn / m1, v1[1] - jt / m1];
    let v2_after = [v2[0] + jn / m2, v2[1] + jt / m2];
    let spin = |b: &Body, w: f64| {
        if b.is_wall() {
            0.0
        } else {
            // + 0.0 turns −0 into 0 for printing.
            w + (-b.radius() * jt / b.moment_of_inertia() + 0.0)
        }
    };
    let spin_after = [spin(b1, w[0]), spin(b2, w[1])];
    let energy_after = kinetic_energy(b1, b2, v1_after, v2_after, spin_after);
    Exchange {
        v1_after,
        v2_after,
        spin_after,
        energy_after,
    }
}

/// Translational plus rotational kinetic energy (J) of bodies `b1`, `b2` moving at `v1`, `v2`
/// (`[normal, tangential]`, m/s) and spinning at `w` (rad/s; a body at rest or not spinning
/// adds nothing, so a wall's infinite mass and inertia never enter).
pub fn kinetic_energy(b1: &Body, b2: &Body, v1: [f64; 2], v2: [f64; 2], w: [f64; 2]) -> f64 {
    let rot = |b: &Body, w: f64| {
        if w == 0.0 {
            0.0
        } else {
            0.5 * b.moment_of_inertia() * w * w
        }
    };
    let (m1, m2) = (b1.mass(), b2.mass());
    kinetic(m1, v1[0])
        + kinetic(m1, v1[1])
        + kinetic(m2, v2[0])
        + kinetic(m2, v2[1])
        + rot(b1, w[0])
        + rot(b2, w[1])
}
