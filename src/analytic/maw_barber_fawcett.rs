//! The elastic oblique impact of Maw, Barber & Fawcett (Wear 38, 1976, 101-114): two elastic
//! spheres, or a sphere and a half-space, meet with a normal and a tangential velocity and
//! spins; Hertz acts along the normal, Cattaneo-Mindlin partial slip under the normal force's
//! own history along the tangent, and the balls move as rigid bodies (translation and spin).
//! Normal and tangential contact are uncoupled, which is exact for elastically similar bodies
//! and is Maw, Barber & Fawcett's assumption otherwise.
//!
//! Method: the method of dimensionality reduction (Popov & Heß, *Method of Dimensionality
//! Reduction in Contact Mechanics and Friction*, Springer 2015, chapters 3 and 5). The contact
//! of the paraboloid z = r²/(2R*) maps exactly onto a row of independent springs on the line
//! with the profile g(x) = x²/R*, normal stiffness E* dx and tangential stiffness 4 G* dx (G*
//! Mindlin's effective shear modulus, so the row's tangential stiffness is Mindlin's 8 G* a).
//! A spring at |x| < a carries the normal displacement w(x) = δ − g(x); its tangential
//! displacement u(x) follows the tangential displacement of the contact points while it
//! sticks and is held at the Coulomb limit 4 G* |u| = μ E* w while it slips; a spring enters
//! and leaves the contact with u = 0. Forces: F = 2 ∫₀ᵃ E* w dx (Hertz's), f = 2 ∫₀ᵃ 4 G* u dx.
//! For any history of the normal and tangential displacement this row reproduces the
//! Cattaneo-Mindlin-Deresiewicz solution (Popov & Heß, ch. 5).
//!
//! Time: central differences on the approach δ and the slip displacement of the contact
//! points, m* δ̈ = −F and m_t ṡ = −f with 1/m_t = 1/m₁ + 1/m₂ + R₁²/I₁ + R₂²/I₂. Every spring
//! slipping gives f = μF exactly, so in gross sliding the tangential impulse is μ times the
//! normal one to round-off.

use super::body::{tangential_compliance, Body};
use super::hertz::HertzPair;
use super::laws::ContactPair;
use crate::error::{Error, Result};

/// How finely the spring row and the contact time are divided.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Resolution {
    /// Springs on the half-line from the centre to 1.02 times Hertz's largest contact radius.
    pub springs: usize,
    /// Time steps per Hertz contact duration.
    pub steps: usize,
}

/// The resolution whose tangential restitution moves by less than 1e-3 when both counts
/// double (tests/suite/analytic_mbf.rs).
pub const DEFAULT_RESOLUTION: Resolution = Resolution {
    springs: 800,
    steps: 4000,
};

/// Everything one oblique impact produces. Directions: n from ball 1 towards body 2,
/// t the tangential direction of the initial slip's frame, spins about n × t.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ObliqueImpact {
    /// Normal restitution v_r⁺/v_r (1 up to the time step's error).
    pub e: f64,
    /// Slip speed of the contact points before impact, s = v₁ₜ − v₂ₜ + ω₁R₁ + ω₂R₂, m/s.
    pub slip_before: f64,
    /// Slip speed of the contact points after impact, m/s.
    pub slip_after: f64,
    /// Normal impulse on body 2 along +n, N·s.
    pub normal_impulse: f64,
    /// Tangential impulse on body 2 along +t, N·s.
    pub tangential_impulse: f64,
    /// Contact duration (first touch to separation), s.
    pub contact_duration: f64,
    /// Velocity of body 1 after, [normal, tangential], m/s.
    pub v1_after: [f64; 2],
    /// Velocity of body 2 after, [normal, tangential], m/s (0 for a wall).
    pub v2_after: [f64; 2],
    /// Spins after about n × t, rad/s (0 for a wall).
    pub spin_after: [f64; 2],
    /// Fraction of the contact's time steps in which every spring in contact slipped.
    pub gross_slip_fraction: f64,
}

impl ObliqueImpact {
    /// Tangential restitution of the contact points, −s⁺/s⁻ (`None` without initial slip).
    pub fn tangential_restitution(&self) -> Option<f64> {
        (self.slip_before != 0.0).then(|| -self.slip_after / self.slip_before)
    }

    /// J_t/(μJ_n), the tangential impulse over its gross-sliding value (1 when every spring
    /// slid throughout) at friction coefficient `mu`.
    pub fn impulse_ratio(&self, mu: f64) -> f64 {
        self.tangential_impulse / (mu * self.normal_impulse)
    }
}

/// The ratio κ = k_t/k_n = 4G*/E* of Mindlin's tangential to Hertz's normal contact stiffness
/// (2(1 − ν)/(2 − ν) for one material), the factor of Maw, Barber & Fawcett's angles.
pub fn stiffness_ratio(pair: &ContactPair) -> f64 {
    4.0 * pair.shear_modulus / pair.hertz.modulus
}

/// Maw, Barber & Fawcett's normalised angle ψ = κ s/(μ v_r) of a contact-point slip speed s
/// (m/s) at normal approach speed v_r (m/s): ψ₁ of the incidence with s⁻, ψ₂ of the rebound
/// with s⁺ (both against the incident v_r).
pub fn normalised_angle(pair: &ContactPair, slip: f64, speed: f64) -> f64 {
    stiffness_ratio(pair) * slip / (pair.mu * speed)
}

/// The row of springs: positions and tangential displacements on the half-line.
struct SpringRow {
    /// Spring positions x (m), at the middle of equal cells.
    x: Vec<f64>,
    /// Cell width dx, m.
    width: f64,
    /// Tangential displacement u of each spring, m.
    u: Vec<f64>,
}

/// The forces of the row at approach `delta` (m) after moving the contact points tangentially
/// by `step` (m): (F, f, every spring in contact slipping) in N, N.
fn advance(row: &mut SpringRow, pair: &ContactPair, delta: f64, step: f64) -> (f64, f64, bool) {
    let (e_star, g_mdr) = (pair.hertz.modulus, 4.0 * pair.shear_modulus);
    let radius = pair.hertz.radius;
    let slip_limit = pair.mu * e_star / g_mdr;
    let (mut w_sum, mut u_sum) = (0.0, 0.0);
    let mut all_slip = true;
    for (x, u) in row.x.iter().zip(row.u.iter_mut()) {
        let w = delta - x * x / radius;
        if w <= 0.0 {
            *u = 0.0;
            continue;
        }
        let limit = slip_limit * w;
        let trial = *u + step;
        if trial.abs() >= limit {
            *u = limit.copysign(trial);
        } else {
            *u = trial;
            all_slip = false;
        }
        w_sum += w;
        u_sum += *u;
    }
    let normal = 2.0 * e_star * w_sum * row.width;
    let tangential = 2.0 * g_mdr * u_sum * row.width;
    (normal, tangential, all_slip && w_sum > 0.0)
}

/// The oblique impact of ball `b1` on `b2` (ball or wall) with friction coefficient `mu`:
/// velocities [normal, tangential] (m/s) and spins about n × t (rad/s) before impact, the
/// normal along the line of centres from ball 1 to body 2.
///
/// Returns `Ok(None)` when the bodies do not approach. Errors: body 1 a wall, a body that
/// does not deform elastically, non-finite velocities or spins, μ ≤ 0 or non-finite, a
/// resolution below 50 springs or 200 steps, or no separation within ten Hertz contact times.
pub fn impact(
    b1: &Body,
    b2: &Body,
    velocity: [[f64; 2]; 2],
    spin: [f64; 2],
    mu: f64,
    res: Resolution,
) -> Result<Option<ObliqueImpact>> {
    if b1.is_wall() {
        return Err(Error::invalid("ball1", "a wall", "body 1 must be a ball"));
    }
    let [v1, v2] = velocity;
    for (name, v) in ["v1", "v1t", "v2", "v2t", "w1", "w2"]
        .iter()
        .zip([v1[0], v1[1], v2[0], v2[1], spin[0], spin[1]])
    {
        if !v.is_finite() {
            return Err(Error::invalid(
                *name,
                v,
                "a finite speed (m/s) or spin (rad/s)",
            ));
        }
    }
    if !(mu > 0.0 && mu.is_finite()) {
        return Err(Error::invalid(
            "mu",
            mu,
            "a finite friction coefficient > 0",
        ));
    }
    if res.springs < 50 || res.steps < 200 {
        return Err(Error::invalid(
            "resolution",
            format!("{} springs, {} steps", res.springs, res.steps),
            ">= 50 springs and >= 200 steps per contact time",
        ));
    }
    let speed = v1[0] - v2[0];
    if speed.is_nan() || speed <= 0.0 {
        return Ok(None);
    }
    let pair = ContactPair::between(b1, b2, mu);
    if !(pair.hertz.modulus.is_finite() && pair.shear_modulus > 0.0) {
        return Err(Error::invalid(
            "bodies",
            "two rigid bodies",
            "at least one elastic body",
        ));
    }
    let radii = [b1.radius(), if b2.is_wall() { 0.0 } else { b2.radius() }];
    let slip0 = v1[1] - v2[1] + spin[0] * radii[0] + spin[1] * radii[1];
    let hertz: HertzPair = pair.hertz;
    let t_hertz = hertz.contact_duration(speed);
    let reach = 1.02 * hertz.contact_radius(hertz.max_approach(speed));
    let width = reach / res.springs as f64;
    let mut row = SpringRow {
        x: (0..res.springs).map(|i| (i as f64 + 0.5) * width).collect(),
        width,
        u: vec![0.0; res.springs],
    };
    let compliance = tangential_compliance(b1, b2);
    let dt = t_hertz / res.steps as f64;
    // Leapfrog: rate and slip at half steps, approach and spring state at whole steps.
    let (mut delta, mut rate, mut slip) = (0.0, speed, slip0);
    let (mut normal_impulse, mut tangential_impulse) = (0.0, 0.0);
    let mut t = 0.0;
    let (mut contact_steps, mut sliding_steps) = (0usize, 0usize);
    loop {
        delta += rate * dt;
        t += dt;
        if delta <= 0.0 {
            break;
        }
        let (force, friction, all_slip) = advance(&mut row, &pair, delta, slip * dt);
        contact_steps += 1;
        sliding_steps += usize::from(all_slip);
        rate -= force / hertz.mass * dt;
        slip -= friction * compliance * dt;
        normal_impulse += force * dt;
        tangential_impulse += friction * dt;
        if t > 10.0 * t_hertz {
            return Err(Error::Numerical(format!(
                "oblique impact: no separation within ten Hertz contact times ({t_hertz:e} s)"
            )));
        }
    }
    let after = |b: &Body, v: [f64; 2], sign: f64| {
        if b.is_wall() {
            [0.0, 0.0]
        } else {
            [
                v[0] + sign * normal_impulse / b.mass(),
                v[1] + sign * tangential_impulse / b.mass(),
            ]
        }
    };
    let spin_after = |b: &Body, w: f64, r: f64| {
        if b.is_wall() {
            0.0
        } else {
            w - r * tangential_impulse / b.moment_of_inertia()
        }
    };
    Ok(Some(ObliqueImpact {
        e: -rate / speed,
        slip_before: slip0,
        slip_after: slip,
        normal_impulse,
        tangential_impulse,
        contact_duration: t,
        v1_after: after(b1, v1, -1.0),
        v2_after: after(b2, v2, 1.0),
        spin_after: [
            spin_after(b1, spin[0], radii[0]),
            spin_after(b2, spin[1], radii[1]),
        ],
        gross_slip_fraction: sliding_steps as f64 / contact_steps.max(1) as f64,
    }))
}

/// One point of Maw, Barber & Fawcett's curve: the rebound against the incidence.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CurvePoint {
    /// Normalised incidence angle ψ₁ = κ s⁻/(μ v_r).
    pub psi_in: f64,
    /// Normalised rebound angle ψ₂ = κ s⁺/(μ v_r).
    pub psi_out: f64,
    /// Tangential slip speed of ball 1's contact point before impact, m/s.
    pub slip_speed: f64,
    /// The impact itself.
    pub impact: ObliqueImpact,
}

/// Maw, Barber & Fawcett's curve of ball `b1` hitting `b2` at normal speed `speed` (m/s) with
/// no spin, ball 1 sliding tangentially at the speed that gives each normalised incidence
/// angle of `psi` (≥ 0). Errors as [`impact`], and `speed` ≤ 0 or non-finite.
pub fn curve(
    b1: &Body,
    b2: &Body,
    speed: f64,
    mu: f64,
    psi: &[f64],
    res: Resolution,
) -> Result<Vec<CurvePoint>> {
    if !(speed > 0.0 && speed.is_finite()) {
        return Err(Error::invalid(
            "speed",
            speed,
            "a finite normal speed > 0 m/s",
        ));
    }
    let pair = ContactPair::between(b1, b2, mu);
    let per_psi = mu * speed / stiffness_ratio(&pair);
    psi.iter()
        .map(|&p| {
            let slip = p * per_psi;
            let impact = impact(b1, b2, [[speed, slip], [0.0, 0.0]], [0.0, 0.0], mu, res)?
                .ok_or_else(|| Error::Numerical("oblique impact: no approach".into()))?;
            Ok(CurvePoint {
                psi_in: normalised_angle(&pair, impact.slip_before, speed),
                psi_out: normalised_angle(&pair, impact.slip_after, speed),
                slip_speed: slip,
                impact,
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::Material;

    /// A steel-like ball on a rigid wall: its contact pair (μ = 0.3).
    fn pair() -> ContactPair {
        let m = Material::preset("steel").unwrap();
        let b = Body::ball(m, 0.01, "ball1").unwrap();
        ContactPair::between(&b, &Body::RigidWall, 0.3)
    }

    /// Mindlin's force under constant normal force P (N) at tangential displacement ξ (m)
    /// on first loading: μP(1 − (1 − ξ/ξ_s)^{3/2}), ξ_s = 3μP/(16 G* a).
    fn mindlin(pair: &ContactPair, p: f64, a: f64, xi: f64) -> f64 {
        let slip = 3.0 * pair.mu * p / (16.0 * pair.shear_modulus * a);
        pair.mu * p * (1.0 - (1.0 - (xi / slip).min(1.0)).powf(1.5))
    }

    /// The spring row under a constant approach, pushed tangentially and back, against
    /// Cattaneo-Mindlin's loading curve and Mindlin-Deresiewicz's unloading curve (Masing:
    /// twice the loading curve from the turn), within 2e-4 of μP.
    #[test]
    fn spring_row_is_cattaneo_mindlin() {
        let pair = pair();
        let delta = 1e-6;
        let a = (pair.hertz.radius * delta).sqrt();
        let springs = 4000;
        let width = 1.02 * a / springs as f64;
        let mut row = SpringRow {
            x: (0..springs).map(|i| (i as f64 + 0.5) * width).collect(),
            width,
            u: vec![0.0; springs],
        };
        let (p, _, _) = advance(&mut row, &pair, delta, 0.0);
        assert!(
            (p / pair.hertz.force(delta) - 1.0).abs() < 1e-6,
            "Hertz force"
        );
        let slip = 3.0 * pair.mu * p / (16.0 * pair.shear_modulus * a);
        let (n, turn) = (400, 0.8 * slip);
        let mut f_turn = 0.0;
        for k in 1..=n {
            let (_, f, _) = advance(&mut row, &pair, delta, turn / n as f64);
            let want = mindlin(&pair, p, a, turn * k as f64 / n as f64);
            assert!(
                (f - want).abs() < 2e-4 * pair.mu * p,
                "loading {k}: {f} vs {want}"
            );
            f_turn = f;
        }
        for k in 1..=n {
            let (_, f, _) = advance(&mut row, &pair, delta, -turn / n as f64);
            let back = turn * k as f64 / n as f64;
            let want = f_turn - 2.0 * mindlin(&pair, p, a, back / 2.0);
            assert!(
                (f - want).abs() < 2e-4 * pair.mu * p,
                "unloading {k}: {f} vs {want}"
            );
        }
    }
}
