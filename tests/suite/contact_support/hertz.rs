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
#[derive(Debug, Clone)]
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
    /// Peak of the force history averaged over a window of t_c/20 (N, full ball), and the same
    /// moving average applied to Hertz's own force pulse (N): the window removes the step-to-step
    /// ringing of nodes entering contact; comparing like with like removes its bias (−0.17 % of
    /// the peak for the Hertz pulse).
    pub peak_force_window: f64,
    pub hertz_force_window: f64,
    /// (t_c / window, FE windowed peak, Hertz windowed peak) for several windows, N.
    pub windows: Vec<(f64, f64, f64)>,
    /// Coefficient of restitution (normal, from centre-of-mass velocities).
    pub restitution: f64,
    /// Largest |total/initial − 1| over the impact.
    pub energy_error: f64,
    /// Contact stored energy after separation / initial kinetic energy.
    pub residual_contact_energy: f64,
    /// Largest penetration / delta_max.
    pub penetration_ratio: f64,
    /// The finite-ball reference ([`finite_ball_reference`]): maximum approach (m), contact
    /// duration (s) and t_c/20-windowed peak force (N).
    pub finite_delta: f64,
    pub finite_duration: f64,
    pub finite_force_window: f64,
}

impl Impact {
    pub fn errors(&self) -> (f64, f64, f64) {
        (
            self.delta_max / self.hertz_delta - 1.0,
            self.duration / self.hertz_duration - 1.0,
            self.peak_force_filtered / self.hertz_force - 1.0,
        )
    }

    /// Error of the t_c/20 moving-average peak force against the same average of Hertz's pulse.
    pub fn force_window_error(&self) -> f64 {
        self.peak_force_window / self.hertz_force_window - 1.0
    }

    /// Errors of δ_max, t_c and the t_c/20-windowed peak force against the finite-ball
    /// reference (Hertz stiffened as CalculiX finds a finite ball stiffened).
    pub fn finite_ball_errors(&self) -> (f64, f64, f64) {
        (
            self.delta_max / self.finite_delta - 1.0,
            self.duration / self.finite_duration - 1.0,
            self.peak_force_window / self.finite_force_window - 1.0,
        )
    }
}

/// Peak of the moving average, over a window of at least `w` (s), of a sampled history (t, F),
/// each sample holding over the step that ends at it (any spacing).
pub fn windowed_peak(history: &[(f64, f64)], w: f64) -> f64 {
    let mut peak: f64 = 0.0;
    let (mut lo, mut sum) = (0usize, 0.0);
    for hi in 1..history.len() {
        sum += history[hi].1 * (history[hi].0 - history[hi - 1].0);
        // Drop the oldest step while the rest still spans the window.
        while lo + 1 < hi && history[hi].0 - history[lo + 1].0 >= w {
            sum -= history[lo + 1].1 * (history[lo + 1].0 - history[lo].0);
            lo += 1;
        }
        let span = history[hi].0 - history[lo].0;
        if span >= w {
            peak = peak.max(sum / span);
        }
    }
    peak
}

/// Hertz's force pulse for approach speed `v` (m/s), maximum approach `delta_max` (m) and peak
/// force `f_max` (N), sampled with `n` steps over the contact: in ξ = δ/δ_max, τ = t v/δ_max the
/// impact is ξ'' = −(5/4) ξ^{3/2}, ξ(0) = 0, ξ'(0) = 1 (energy: ½ m* v² = (2/5) F_max δ_max), and
/// F = F_max ξ^{3/2}. Integrated with velocity Verlet (error O(1/n²)).
pub fn hertz_pulse(v: f64, delta_max: f64, f_max: f64, n: usize) -> Vec<(f64, f64)> {
    stiffened_pulse(v, delta_max, f_max, 0.0, 0.0, n).0
}

/// The finite ball's stiffening of Hertz's force at fixed approach of the centre of mass,
/// F/F_H − 1 = S0 + S1 a/R, fitted to CalculiX's converged static runs of the impact's
/// quasi-static image: the whole (free) ball on a rigid frictionless plane under the uniform
/// body force that balances the contact force, approach measured at the centre of mass, as
/// twoball's impacts measure it (a/R = 0.011 / 0.022 / 0.045: +0.89 / +1.92 / +4.06 %;
/// `python3 scripts/ccx_static_hertz.py --support free --depths 1.25,5,20 --per-a 20`,
/// verification/contact-penalty.md). Static, so an estimate of the exact impact good to the
/// quasi-static error (the pulse lasts about seven periods of the ball's lowest mode), not a
/// closed form. (The hemisphere held at its equator gives −0.26 % + 0.589 a/R: that support
/// carries the whole contact force to the equator, a softer image of the ball than its own
/// inertia is.)
pub const FINITE_BALL_S0: f64 = -0.00190;
/// See [`FINITE_BALL_S0`].
pub const FINITE_BALL_S1: f64 = 0.955;

/// The force pulse (t, F) of Hertz's law stiffened by s0 + s1 a/R, for two identical balls
/// of radius `radius` (m) at relative speed `v` (m/s) with Hertz's own maximum approach
/// `delta_h` (m) and peak force `f_h` (N): ξ'' = −(5/4) ξ^{3/2} (1 + s0 + β √ξ), ξ = δ/δ_h,
/// τ = t v/δ_h, with β = s1 √(δ_h / (2R)) (a = √(R δ/2) for the pair: each ball's own
/// approach is δ/2), F = f_h ξ^{3/2} (1 + s0 + β √ξ). s0 = s1 = 0 is Hertz's pulse. Returns
/// the pulse and its largest approach (m).
pub fn stiffened_pulse(
    v: f64,
    delta_h: f64,
    f_h: f64,
    s0: f64,
    beta: f64,
    n: usize,
) -> (Vec<(f64, f64)>, f64) {
    let dtau = 3.5 / n as f64;
    let (mut x, mut u, mut tau) = (0.0f64, 1.0f64, 0.0f64);
    let law = |x: f64| {
        let x = x.max(0.0);
        x.powf(1.5) * (1.0 + s0 + beta * x.sqrt())
    };
    let mut a = -1.25 * law(x);
    let mut out = vec![(0.0, 0.0)];
    let mut x_max = 0.0f64;
    loop {
        u += 0.5 * dtau * a;
        x += dtau * u;
        a = -1.25 * law(x);
        u += 0.5 * dtau * a;
        tau += dtau;
        if x <= 0.0 {
            break;
        }
        x_max = x_max.max(x);
        out.push((tau * delta_h / v, f_h * law(x)));
    }
    (out, x_max * delta_h)
}

/// The finite-ball reference of an impact at relative speed `v` (m/s) of two balls of radius
/// `radius` (m), from Hertz's maximum approach `delta_h` (m) and peak force `f_h` (N):
/// (maximum approach m, contact duration s, the pulse (t, F)) of [`stiffened_pulse`] with the
/// CalculiX stiffening [`FINITE_BALL_S0`], [`FINITE_BALL_S1`].
pub fn finite_ball_reference(
    v: f64,
    radius: f64,
    delta_h: f64,
    f_h: f64,
) -> (f64, f64, Vec<(f64, f64)>) {
    let beta = FINITE_BALL_S1 * (delta_h / (2.0 * radius)).sqrt();
    let (pulse, delta_max) = stiffened_pulse(v, delta_h, f_h, FINITE_BALL_S0, beta, 200_000);
    let duration = pulse.last().map_or(0.0, |p| p.0);
    (delta_max, duration, pulse)
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
    impact_variant(v, pole, size, penalty, zeta, ball_ball, Variant::default())
}

/// Element formulation and hourglass coefficient of an impact run (the harness default is the
/// one-point hex with ε_hg = 0.05, the solver's default).
#[derive(Debug, Clone, Copy)]
pub struct Variant {
    pub formulation: Formulation,
    pub hourglass: f64,
    /// Elements on the reference geometry (small displacements), as Hertz's theory assumes.
    pub linear_geometry: bool,
}

impl Default for Variant {
    fn default() -> Self {
        Variant {
            formulation: Formulation::OnePoint,
            hourglass: Settings::default().hourglass,
            linear_geometry: false,
        }
    }
}

/// [`impact_damped`] with a chosen element formulation and hourglass coefficient.
pub fn impact_variant(
    v: f64,
    pole: f64,
    size: f64,
    penalty: PenaltyRule,
    zeta: f64,
    ball_ball: bool,
    variant: Variant,
) -> Impact {
    let mat = elastic_copper();
    let r = 0.5 * DIAMETER;
    let q = quarter_ball(pole, size);
    let mut model = Model::new();
    let a = model
        .add_part("ball1", &q, mat, variant.formulation)
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
            .add_part("ball2", &other, mat, variant.formulation)
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
    let settings = Settings {
        hourglass: variant.hourglass,
        linear_geometry: variant.linear_geometry,
        ..Settings::default()
    };
    let mut s = Solver::new(model, vec![contact], settings).unwrap();
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
        if let (Some(_), Some(l)) = probe.contact_span() {
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
    let pulse = hertz_pulse(v, hertz_delta, hertz_force, 200_000);
    let windows: Vec<(f64, f64, f64)> = [100.0, 50.0, 20.0, 10.0, 6.0]
        .iter()
        .map(|&d| {
            let w = hertz_duration / d;
            (d, windowed_peak(&history, w), windowed_peak(&pulse, w))
        })
        .collect();
    let w20 = hertz_duration / 20.0;
    let peak_force_window = windowed_peak(&history, w20);
    let hertz_force_window = windowed_peak(&hertz_pulse(v, hertz_delta, hertz_force, 200_000), w20);
    let (finite_delta, finite_duration, finite_pulse) =
        finite_ball_reference(v, r, hertz_delta, hertz_force);
    let finite_force_window = windowed_peak(&finite_pulse, w20);
    Impact {
        finite_delta,
        finite_duration,
        finite_force_window,
        windows,
        peak_force_window,
        hertz_force_window,
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
