//! The one integrator of a two-body impact that every contact law uses.
//!
//! Unknowns: approach δ (m), approach rate δ̇ (m/s), normal work W_n = ∫F δ̇ dt (J), tangential
//! spring displacement ξ (m), slip speed u of the contact points (m/s) and tangential work
//! W_t = ∫f u dt (J), with m* δ̈ = −F and m_t u̇ = −f, 1/m_t = 1/m₁ + 1/m₂ + R₁²/I₁ + R₂²/I₂
//! (= 7/(2m*) for solid spheres). Dormand-Prince 5(4) with error control on every unknown;
//! events (located by bisection on the step to round-off): the turn δ̇ = 0 (loading →
//! unloading, the law's history), the law's loading thresholds (phase changes), stick → slip
//! (|k_t ξ| = μF) and slip → stick, and separation (F = 0, or δ = 0 for a law that may pull).

use super::body::{tangential_compliance, Body};
use super::exchange::{exchange_spinning, kinetic_energy, Exchange};
use super::hertz::HertzPair;
use super::laws::{NormalLaw, TangentialLaw, Turn};
use crate::error::{Error, Result};

/// Relative tolerance of one step (per unknown, against its reference scale).
pub const DEFAULT_TOLERANCE: f64 = 1e-11;

/// One accepted integrator step (or event) of the contact history.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LawSample {
    /// Time since first touch, s.
    pub t: f64,
    /// Approach δ, m.
    pub delta: f64,
    /// Approach rate δ̇, m/s.
    pub rate: f64,
    /// Normal force F, N.
    pub force: f64,
    /// Tangential force f on body 2 along +t, N.
    pub tangential_force: f64,
    /// Slip speed of the contact points u (body 1 minus body 2), m/s.
    pub slip: f64,
}

/// Everything the integrator says about one impact under one pair of laws.
#[derive(Debug, Clone, PartialEq)]
pub struct LawImpact {
    /// Effective modulus, radius and mass of the pair.
    pub pair: HertzPair,
    /// Normal approach speed before impact v_r, m/s.
    pub approach_speed: f64,
    /// Normal separation speed after impact v_r⁺, m/s.
    pub rebound_speed: f64,
    /// Coefficient of restitution e = v_r⁺/v_r.
    pub e: f64,
    /// Maximum approach δ_max, m.
    pub delta_max: f64,
    /// Time of maximum approach, s.
    pub time_of_max: f64,
    /// Approach at separation (the permanent approach δ_p of a plastic law), m.
    pub delta_end: f64,
    /// Contact duration t_c (first touch to separation), s.
    pub contact_duration: f64,
    /// Largest normal force over the integrator's steps and events, N.
    pub peak_force: f64,
    /// Times at which the loading crossed the law's thresholds (phase changes), s.
    pub phase_times: Vec<f64>,
    /// Slip speed of the contact points before impact, m/s.
    pub slip_before: f64,
    /// Slip speed of the contact points after impact, m/s.
    pub slip_after: f64,
    /// Normal impulse on body 2 along +n, N·s.
    pub normal_impulse: f64,
    /// Tangential impulse on body 2 along +t, N·s.
    pub tangential_impulse: f64,
    /// The state after the exchange of those impulses: velocities [normal, tangential]
    /// (m/s), spins about n × t (rad/s; 0 for a wall), kinetic energy (translation and spin,
    /// J).
    pub after: Exchange,
    /// Kinetic energy before (no initial spin), J.
    pub energy_before: f64,
    /// Work taken out of the bodies by the normal force, ∫F δ̇ dt, J.
    pub work_normal: f64,
    /// Work taken out of the bodies by the tangential force, ∫f u dt, J.
    pub work_tangential: f64,
    /// The contact history at every accepted step and event.
    pub history: Vec<LawSample>,
    /// Accepted steps.
    pub steps: usize,
}

impl LawImpact {
    /// Tangential restitution −u⁺/u⁻ of the contact points; `None` without initial slip.
    pub fn tangential_restitution(&self) -> Option<f64> {
        (self.slip_before != 0.0).then(|| -self.slip_after / self.slip_before)
    }

    /// (KE before − KE after − W_n − W_t)/KE before: the energy balance's relative residual.
    pub fn energy_residual(&self) -> f64 {
        (self.energy_before - self.after.energy_after - self.work_normal - self.work_tangential)
            / self.energy_before
    }
}

#[derive(Debug, Clone, Copy)]
enum NormalMode {
    Loading { next: usize },
    Unloading(Turn),
}

/// Turning points a law with slip memory can hold at once.
const MAX_TURNS: usize = 16;

#[derive(Debug, Clone, Copy)]
enum TangentialMode {
    Stick,
    Slip(f64),
    /// A law with memory: the direction of the displacement (±1) and the turning points.
    Memory {
        direction: f64,
        turns: [f64; MAX_TURNS],
        len: usize,
    },
}

#[derive(Debug, Clone, Copy)]
struct Mode {
    normal: NormalMode,
    tangential: TangentialMode,
}

type State = [f64; 6];

/// Which event fired, in order of priority.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum Event {
    Separation,
    Turn,
    Threshold,
    Tangential,
    Reversal,
    Masing,
}

struct System<'a> {
    normal: &'a dyn NormalLaw,
    tangential: &'a dyn TangentialLaw,
    mass: f64,
    tangential_mass: f64,
    speed: f64,
    thresholds: Vec<f64>,
    rigid_tangential: bool,
    mu: f64,
    scale: State,
}

impl System<'_> {
    fn raw_force(&self, mode: &Mode, d: f64, r: f64) -> f64 {
        match mode.normal {
            NormalMode::Loading { .. } => self.normal.loading(d, r, self.speed),
            NormalMode::Unloading(turn) => self.normal.unloading(d, r, self.speed, &turn),
        }
    }

    fn force(&self, mode: &Mode, d: f64, r: f64) -> f64 {
        let f = self.raw_force(mode, d, r);
        if self.normal.tensile() {
            f
        } else {
            f.max(0.0)
        }
    }

    fn tangential_force(&self, mode: &Mode, y: &State, force: f64) -> f64 {
        match mode.tangential {
            TangentialMode::Stick => self.tangential.stiffness(y[0]) * y[3],
            TangentialMode::Slip(s) => s * self.mu * force.max(0.0),
            TangentialMode::Memory {
                direction,
                ref turns,
                len,
            } => {
                let n = force.max(0.0);
                let f = self
                    .tangential
                    .force(y[3], y[0], n, &turns[..len], direction);
                let cap = self.mu * n;
                if cap.is_finite() {
                    f.clamp(-cap, cap)
                } else {
                    f
                }
            }
        }
    }

    fn derivs(&self, mode: &Mode, y: &State) -> State {
        let f = self.force(mode, y[0], y[1]);
        let ft = self.tangential_force(mode, y, f);
        let xi_rate = match mode.tangential {
            TangentialMode::Stick | TangentialMode::Memory { .. } => y[4],
            TangentialMode::Slip(_) => 0.0,
        };
        [
            y[1],
            -f / self.mass,
            f * y[1],
            xi_rate,
            -ft / self.tangential_mass,
            ft * y[4],
        ]
    }

    /// One Dormand-Prince 5(4) step: the fifth-order state and the scaled error norm.
    fn step(&self, mode: &Mode, y: &State, h: f64, tol: f64) -> (State, f64) {
        const A: [[f64; 6]; 6] = [
            [1.0 / 5.0, 0.0, 0.0, 0.0, 0.0, 0.0],
            [3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0, 0.0],
            [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0.0, 0.0, 0.0],
            [
                19372.0 / 6561.0,
                -25360.0 / 2187.0,
                64448.0 / 6561.0,
                -212.0 / 729.0,
                0.0,
                0.0,
            ],
            [
                9017.0 / 3168.0,
                -355.0 / 33.0,
                46732.0 / 5247.0,
                49.0 / 176.0,
                -5103.0 / 18656.0,
                0.0,
            ],
            [
                35.0 / 384.0,
                0.0,
                500.0 / 1113.0,
                125.0 / 192.0,
                -2187.0 / 6784.0,
                11.0 / 84.0,
            ],
        ];
        // First same as last: the fifth-order weights are the last stage's row.
        const B5: [f64; 7] = {
            let a = A[5];
            [a[0], a[1], a[2], a[3], a[4], a[5], 0.0]
        };
        const B4: [f64; 7] = [
            5179.0 / 57600.0,
            0.0,
            7571.0 / 16695.0,
            393.0 / 640.0,
            -92097.0 / 339200.0,
            187.0 / 2100.0,
            1.0 / 40.0,
        ];
        let mut k = [[0.0; 6]; 7];
        k[0] = self.derivs(mode, y);
        for s in 1..7 {
            let mut ys = *y;
            for (i, v) in ys.iter_mut().enumerate() {
                for j in 0..s {
                    *v += h * A[s - 1][j] * k[j][i];
                }
            }
            k[s] = self.derivs(mode, &ys);
        }
        let mut out = *y;
        let mut err: f64 = 0.0;
        for i in 0..6 {
            let mut e = 0.0;
            for s in 0..7 {
                out[i] += h * B5[s] * k[s][i];
                e += h * (B5[s] - B4[s]) * k[s][i];
            }
            err = err.max(e.abs() / (tol * self.scale[i]));
        }
        (out, err)
    }

    /// Event functions for `mode` at state y (an event fires when its value crosses 0).
    fn events(&self, mode: &Mode, y: &State) -> Vec<(Event, f64)> {
        let mut out = Vec::with_capacity(3);
        match mode.normal {
            NormalMode::Loading { next } => {
                out.push((Event::Turn, y[1]));
                if let Some(&d) = self.thresholds.get(next) {
                    out.push((Event::Threshold, d - y[0]));
                }
            }
            NormalMode::Unloading(_) => {
                let g = if self.normal.tensile() {
                    y[0]
                } else {
                    self.raw_force(mode, y[0], y[1])
                };
                out.push((Event::Separation, g));
            }
        }
        if let TangentialMode::Memory {
            direction,
            ref turns,
            len,
        } = mode.tangential
        {
            out.push((Event::Reversal, direction * y[4]));
            if len > 0 {
                let partner = if len >= 2 { turns[len - 2] } else { -turns[0] };
                out.push((Event::Masing, direction * (partner - y[3])));
            }
            return out;
        }
        if !self.mu.is_finite() || self.mu == 0.0 && self.rigid_tangential {
            return out;
        }
        let f = self.force(mode, y[0], y[1]);
        match mode.tangential {
            TangentialMode::Stick if !self.rigid_tangential => {
                let kt = self.tangential.stiffness(y[0]);
                out.push((Event::Tangential, self.mu * f - (kt * y[3]).abs()));
            }
            TangentialMode::Stick => {}
            TangentialMode::Slip(s) if self.rigid_tangential => {
                out.push((Event::Tangential, s * y[4]));
            }
            TangentialMode::Slip(s) => out.push((Event::Tangential, self.slip_margin(mode, y, s))),
            TangentialMode::Memory { .. } => {}
        }
        out
    }

    /// s(d(k_t ξ)/dt under sticking) − μ dF/dt with ξ at the cap: negative when the spring
    /// would fall below the cap, i.e. when sticking resumes.
    fn slip_margin(&self, mode: &Mode, y: &State, s: f64) -> f64 {
        let (d, r) = (y[0], y[1]);
        let f = self.force(mode, d, r);
        let acc = -f / self.mass;
        let ed = 1e-7 * d.abs().max(1e-3 * self.scale[0]);
        let er = 1e-7 * self.speed;
        let df_dd = (self.force(mode, d + ed, r) - self.force(mode, d - ed, r)) / (2.0 * ed);
        let df_dr = (self.force(mode, d, r + er) - self.force(mode, d, r - er)) / (2.0 * er);
        let f_rate = df_dd * r + df_dr * acc;
        let kt = self.tangential.stiffness(d);
        let kt_slope = (self.tangential.stiffness(d + ed)
            - self.tangential.stiffness(d - ed).max(0.0))
            / (2.0 * ed);
        let xi = s * self.mu * f.max(0.0) / kt;
        s * (kt_slope * r * xi + kt * y[4]) - self.mu * f_rate
    }
}

fn fired(event: Event, g0: f64, g1: f64) -> bool {
    match event {
        Event::Separation => g0 > 0.0 && g1 <= 0.0,
        _ => g0 >= 0.0 && g1 < 0.0,
    }
}

/// Integrates the impact of body 1 (a ball) on body 2 (ball or wall at rest) under a normal
/// and a tangential law. Velocities [normal, tangential] in m/s as in [`super::collide`];
/// `tolerance` is the relative error of one step (use [`DEFAULT_TOLERANCE`]).
///
/// Returns `Ok(None)` when the bodies do not approach (v₁ₙ ≤ v₂ₙ). Errors: body 1 a wall,
/// non-finite velocities, a law returning a non-finite force, no separation within 10⁴
/// Hertz contact times, or more than 10⁷ steps.
pub fn integrate(
    b1: &Body,
    b2: &Body,
    v1: [f64; 2],
    v2: [f64; 2],
    normal: &dyn NormalLaw,
    tangential: &dyn TangentialLaw,
    tolerance: f64,
) -> Result<Option<LawImpact>> {
    integrate_spinning(b1, b2, v1, v2, [0.0; 2], normal, tangential, tolerance)
}

/// [`integrate`] for balls spinning at `w` (rad/s, about n × t; a wall's entry must be 0)
/// before the impact: the contact points slip at v₁ₜ − v₂ₜ + R₁ω₁ + R₂ω₂ at touch. Errors
/// as [`integrate`], and a non-finite spin or a spinning wall.
#[allow(clippy::too_many_arguments)]
pub fn integrate_spinning(
    b1: &Body,
    b2: &Body,
    v1: [f64; 2],
    v2: [f64; 2],
    w: [f64; 2],
    normal: &dyn NormalLaw,
    tangential: &dyn TangentialLaw,
    tolerance: f64,
) -> Result<Option<LawImpact>> {
    for (name, (b, w)) in ["w1", "w2"].iter().zip([(b1, w[0]), (b2, w[1])]) {
        if !w.is_finite() || (b.is_wall() && w != 0.0) {
            return Err(Error::invalid(
                *name,
                w,
                "a finite spin in rad/s, 0 for a wall",
            ));
        }
    }
    if b1.is_wall() {
        return Err(Error::invalid("ball1", "a wall", "body 1 must be a ball"));
    }
    for (name, v) in ["v1", "v1t", "v2", "v2t"]
        .iter()
        .zip([v1[0], v1[1], v2[0], v2[1]])
    {
        if !v.is_finite() {
            return Err(Error::invalid(*name, v, "a finite speed in m/s"));
        }
    }
    if !(tolerance > 0.0 && tolerance < 1e-2) {
        return Err(Error::invalid(
            "tolerance",
            tolerance,
            "0 < tolerance < 0.01",
        ));
    }
    let speed = v1[0] - v2[0];
    if speed.is_nan() || speed <= 0.0 {
        return Ok(None);
    }
    let pair = HertzPair::between(b1, b2);
    let tangential_mass = 1.0 / tangential_compliance(b1, b2);
    let arm = |b: &Body, w: f64| if b.is_wall() { 0.0 } else { b.radius() * w };
    let slip0 = v1[1] - v2[1] + arm(b1, w[0]) + arm(b2, w[1]);
    let delta_ref = pair.max_approach(speed);
    let t_ref = pair.contact_duration(speed);
    let u_ref = slip0.abs().max(speed);
    let e_ref = 0.5 * pair.mass * speed * speed + 0.5 * tangential_mass * slip0 * slip0;
    let mu = tangential.friction();
    let sys = System {
        normal,
        tangential,
        mass: pair.mass,
        tangential_mass,
        speed,
        thresholds: normal
            .thresholds()
            .into_iter()
            .filter(|&d| d > 0.0)
            .collect(),
        rigid_tangential: tangential.stiffness(delta_ref) == 0.0,
        mu,
        scale: [delta_ref, speed, e_ref, u_ref * t_ref, u_ref, e_ref],
    };
    let mut mode = Mode {
        normal: NormalMode::Loading { next: 0 },
        tangential: initial_tangential(&sys, slip0, delta_ref),
    };
    let mut y: State = [0.0, speed, 0.0, 0.0, slip0, 0.0];
    let mut t = 0.0;
    let mut h = 1e-3 * t_ref;
    let h_max = t_ref / 200.0;
    let mut history = vec![sample(&sys, &mode, t, &y)];
    let (mut delta_max, mut time_of_max) = (0.0, 0.0);
    let mut phase_times = vec![];
    let mut steps = 0usize;
    let mut events = 0usize;
    loop {
        if steps > 10_000_000 || events > 100_000 || t > 1e4 * t_ref {
            return Err(Error::Numerical(format!(
                "contact law integration did not reach separation (t = {t:e} s, {steps} steps, \
                 {events} events; Hertz contact time {t_ref:e} s)"
            )));
        }
        h = h.min(h_max);
        let (y1, err) = sys.step(&mode, &y, h, tolerance);
        if err.is_nan() || err > 1.0 {
            if !err.is_finite() && h < 1e-12 * t_ref {
                return Err(Error::Numerical(format!(
                    "contact law returned a non-finite force near delta = {:e} m, rate = {:e} m/s",
                    y[0], y[1]
                )));
            }
            h *= if err.is_finite() {
                (0.9 * err.powf(-0.2)).max(0.1)
            } else {
                0.1
            };
            if h < 1e-16 * t_ref {
                return Err(Error::Numerical(format!(
                    "contact law integration: step below 1e-16 of the contact time at t = {t:e} s"
                )));
            }
            continue;
        }
        let g0 = sys.events(&mode, &y);
        let any = |ys: &State| -> Option<Event> {
            sys.events(&mode, ys)
                .iter()
                .zip(&g0)
                .filter(|((ev, g1), (_, g0))| fired(*ev, *g0, *g1))
                .map(|((ev, _), _)| *ev)
                .min()
        };
        let Some(_) = any(&y1) else {
            t += h;
            y = y1;
            steps += 1;
            history.push(sample(&sys, &mode, t, &y));
            h *= (0.9 * err.max(1e-10).powf(-0.2)).min(5.0);
            continue;
        };
        // Locate the earliest event by bisection on the step length.
        let (mut lo, mut hi) = (0.0, h);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if any(&sys.step(&mode, &y, mid, tolerance).0).is_some() {
                hi = mid;
            } else {
                lo = mid;
            }
            if hi - lo <= 4.0 * f64::EPSILON * (t + hi) {
                break;
            }
        }
        let y_hit = sys.step(&mode, &y, hi, tolerance).0;
        let event = any(&y_hit).unwrap_or(Event::Turn);
        t += hi;
        y = y_hit;
        steps += 1;
        events += 1;
        history.push(sample(&sys, &mode, t, &y));
        match event {
            Event::Separation => break,
            Event::Turn => {
                delta_max = y[0];
                time_of_max = t;
                let force = sys.raw_force(&mode, y[0], 0.0);
                mode.normal = NormalMode::Unloading(Turn::new(normal, y[0], force));
                y[1] = y[1].min(0.0);
            }
            Event::Threshold => {
                if let NormalMode::Loading { next } = mode.normal {
                    mode.normal = NormalMode::Loading { next: next + 1 };
                }
                phase_times.push(t);
            }
            Event::Reversal => {
                if let TangentialMode::Memory {
                    direction,
                    turns,
                    len,
                } = &mut mode.tangential
                {
                    if *len == MAX_TURNS {
                        return Err(Error::Numerical(format!(
                            "tangential law: more than {MAX_TURNS} open turning points at t = {t:e} s"
                        )));
                    }
                    turns[*len] = y[3];
                    *len += 1;
                    *direction = -*direction;
                }
            }
            Event::Masing => {
                if let TangentialMode::Memory { len, .. } = &mut mode.tangential {
                    *len = len.saturating_sub(2);
                }
            }
            Event::Tangential => {
                mode.tangential = match mode.tangential {
                    TangentialMode::Stick => TangentialMode::Slip(if y[3] != 0.0 {
                        y[3].signum()
                    } else {
                        y[4].signum()
                    }),
                    TangentialMode::Memory { .. } => mode.tangential,
                    TangentialMode::Slip(s) => {
                        let kt = sys.tangential.stiffness(y[0]);
                        let f = sys.force(&mode, y[0], y[1]);
                        y[3] = if kt > 0.0 { s * mu * f / kt } else { 0.0 };
                        if sys.rigid_tangential {
                            y[4] = 0.0;
                        }
                        TangentialMode::Stick
                    }
                };
            }
        }
    }
    let rebound = -y[1];
    let normal_impulse = pair.mass * (speed + rebound);
    let tangential_impulse = tangential_mass * (slip0 - y[4]);
    let energy_before = kinetic_energy(b1, b2, v1, v2, w);
    let after = exchange_spinning(b1, b2, v1, v2, w, normal_impulse, tangential_impulse);
    let peak_force = history.iter().map(|s| s.force).fold(0.0, f64::max);
    Ok(Some(LawImpact {
        pair,
        approach_speed: speed,
        rebound_speed: rebound,
        e: rebound / speed,
        delta_max,
        time_of_max,
        delta_end: y[0],
        contact_duration: t,
        peak_force,
        phase_times,
        slip_before: slip0,
        slip_after: y[4],
        normal_impulse,
        tangential_impulse,
        after,
        energy_before,
        work_normal: y[2],
        work_tangential: y[5],
        history,
        steps,
    }))
}

/// Stick or slip at first touch: rigid friction slips while there is slip; a spring sticks
/// unless its force would exceed μF right from the start (the ratio of both at δ → 0).
fn initial_tangential(sys: &System, slip0: f64, delta_ref: f64) -> TangentialMode {
    if sys.tangential.memory() {
        return TangentialMode::Memory {
            direction: if slip0 < 0.0 { -1.0 } else { 1.0 },
            turns: [0.0; MAX_TURNS],
            len: 0,
        };
    }
    if slip0 == 0.0 || sys.mu == 0.0 && sys.rigid_tangential {
        return TangentialMode::Stick;
    }
    if sys.rigid_tangential {
        return TangentialMode::Slip(slip0.signum());
    }
    if !sys.mu.is_finite() {
        return TangentialMode::Stick;
    }
    let d = 1e-6 * delta_ref;
    let t = d / sys.speed;
    let mode = Mode {
        normal: NormalMode::Loading { next: 0 },
        tangential: TangentialMode::Stick,
    };
    let f = sys.force(&mode, d, sys.speed);
    if (sys.tangential.stiffness(d) * slip0 * t).abs() > sys.mu * f {
        TangentialMode::Slip(slip0.signum())
    } else {
        TangentialMode::Stick
    }
}

fn sample(sys: &System, mode: &Mode, t: f64, y: &State) -> LawSample {
    let force = sys.force(mode, y[0], y[1]);
    LawSample {
        t,
        delta: y[0],
        rate: y[1],
        force,
        tangential_force: sys.tangential_force(mode, y, force),
        slip: y[4],
    }
}
