//! One contact's history and forces: the normal law's loading/unloading state with its turn,
//! the approach speed at first touch, and the tangential spring (or the rigid Coulomb limit).

use super::pairs::PairLaws;
use crate::analytic::laws::Turn;
use nalgebra::Vector3;

/// Which partner a ball touches: another ball (index) or one of the box's six walls.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Partner {
    /// Ball with this index (always larger than the first ball's).
    Ball(usize),
    /// Wall: 0, 1 the x-walls (low, high), 2, 3 the y-walls, 4 the floor, 5 the lid.
    Wall(usize),
}

/// The loading state of the normal law.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum NormalState {
    /// First loading; the largest approach so far, m.
    Loading(f64),
    /// After the turn (unloading, or reloading below the turn).
    Unloading(Turn),
}

/// The geometry and kinematics of a contact at one instant.
#[derive(Debug, Clone, Copy)]
pub struct ContactGeometry {
    /// Unit normal from the ball to its partner.
    pub normal: Vector3<f64>,
    /// Distances from the ball's and the partner's centre to the contact point, m (0 for a
    /// wall).
    pub lever: [f64; 2],
    /// Approach δ (overlap), m.
    pub delta: f64,
    /// Velocity of the ball's contact point relative to the partner's, predicted to the end
    /// of the step (sets the approach rate and the direction of rigid friction), m/s.
    pub relative: Vector3<f64>,
    /// The same at mid-step (its tangential part times the step is the slip of the step), m/s.
    pub midstep: Vector3<f64>,
}

/// One open contact (δ > 0) and its history.
#[derive(Debug, Clone)]
pub struct Contact {
    /// The first ball.
    pub ball: usize,
    /// Its partner.
    pub partner: Partner,
    /// Normal-law state.
    pub state: NormalState,
    /// Approach speed at first touch, m/s.
    pub speed: f64,
    /// Approach at the last evaluation, m.
    pub delta: f64,
    /// Normal force at the last evaluation (positive repulsive), N.
    pub force: f64,
    /// Tangential spring displacement, m.
    pub spring: Vector3<f64>,
    /// Tangential force on the first ball at the last evaluation, N.
    pub friction: Vector3<f64>,
}

/// Work done on one contact over a step (taken out of the bodies), J.
#[derive(Debug, Clone, Copy, Default)]
pub struct StepWork {
    /// Normal: ½(F_old + F_new)(δ_new − δ_old).
    pub normal: f64,
    /// Tangential: −½(f_old + f_new)·Δs, Δs the tangential slip of the contact points.
    pub tangential: f64,
}

impl StepWork {
    /// Adds `other` to this work.
    pub fn add(&mut self, other: StepWork) {
        self.normal += other.normal;
        self.tangential += other.tangential;
    }
}

impl Contact {
    /// A new contact at first touch with approach rate `rate` (m/s).
    pub fn touch(ball: usize, partner: Partner, rate: f64) -> Contact {
        Contact {
            ball,
            partner,
            state: NormalState::Loading(0.0),
            speed: rate.max(f64::MIN_POSITIVE),
            delta: 0.0,
            force: 0.0,
            spring: Vector3::zeros(),
            friction: Vector3::zeros(),
        }
    }

    /// Updates the history to the kinematics `k` after a step `dt` (s) and returns the work
    /// of the step. The normal force follows the law's loading curve until the approach
    /// turns, then its unloading curve from the turn (loading again beyond the turn); it is
    /// clipped at 0 for a law that may not pull. The tangential spring is carried into the
    /// new tangent plane, extended by the slip and capped at μF; a law with k_t = 0 is the
    /// rigid Coulomb limit (the friction force at most stops the slip within the step).
    pub fn update(&mut self, laws: &PairLaws, k: &ContactGeometry, dt: f64) -> StepWork {
        let n = k.normal;
        let rate = k.relative.dot(&n);
        let law = laws.normal.as_ref();
        self.state = match self.state {
            NormalState::Loading(max) if rate <= 0.0 && max > 0.0 => {
                NormalState::Unloading(Turn::new(law, max, law.loading(max, 0.0, self.speed)))
            }
            NormalState::Loading(max) => NormalState::Loading(max.max(k.delta)),
            NormalState::Unloading(t) if k.delta > t.delta => NormalState::Loading(k.delta),
            s => s,
        };
        let raw = match &self.state {
            NormalState::Loading(_) => law.loading(k.delta, rate, self.speed),
            NormalState::Unloading(t) => law.unloading(k.delta, rate, self.speed, t),
        };
        let force = if law.tensile() { raw } else { raw.max(0.0) };

        let slip_velocity = k.relative - n * rate;
        let slip = (k.midstep - n * k.midstep.dot(&n)) * dt;
        let kt = laws.tangential.stiffness(k.delta);
        let cap = laws.tangential.friction() * force.max(0.0);
        let carried = {
            let old = self.spring.norm();
            let mut s = self.spring - n * self.spring.dot(&n);
            let new = s.norm();
            if new > 0.0 {
                s *= old / new;
            }
            s
        };
        let friction = if kt > 0.0 {
            let mut s = carried + slip;
            let mut f = -s * kt;
            let magnitude = f.norm();
            if magnitude > cap {
                f *= cap / magnitude;
                s = -f / kt;
            }
            self.spring = s;
            f
        } else {
            self.spring = Vector3::zeros();
            let speed = slip_velocity.norm();
            if speed > 0.0 {
                -slip_velocity / speed * cap.min(laws.tangential_mass * speed / dt)
            } else {
                Vector3::zeros()
            }
        };
        let work = StepWork {
            normal: 0.5 * (self.force + force) * (k.delta - self.delta),
            tangential: -0.5 * (self.friction + friction).dot(&slip),
        };
        self.delta = k.delta;
        self.force = force;
        self.friction = friction;
        work
    }

    /// Work of the last step when the contact opens (δ ≤ 0): the force falls to zero over the
    /// remaining approach, J.
    pub fn release_work(&self) -> StepWork {
        StepWork {
            normal: 0.5 * self.force * (0.0 - self.delta),
            tangential: 0.0,
        }
    }

    /// Energy the contact would return if it unloaded from now, J: the normal law's unloading
    /// curve (rate 0) from the present approach (from a turn here if still loading), where it
    /// pushes, plus the tangential spring ½|f|²/k_t.
    pub fn stored(&self, laws: &PairLaws) -> (f64, f64) {
        let law = laws.normal.as_ref();
        let turn = match self.state {
            NormalState::Loading(_) => {
                Turn::new(law, self.delta, law.loading(self.delta, 0.0, self.speed))
            }
            NormalState::Unloading(t) => t,
        };
        let d = self.delta.max(0.0);
        let force = |x: f64| {
            let f = law.unloading(x, 0.0, self.speed, &turn);
            if law.tensile() {
                f
            } else {
                f.max(0.0)
            }
        };
        let normal = simpson(force, d, 32);
        let kt = laws.tangential.stiffness(d);
        let tangential = if kt > 0.0 {
            0.5 * self.friction.norm_squared() / kt
        } else {
            0.0
        };
        (normal, tangential)
    }
}

/// ∫₀^b f by composite Simpson's rule on `n` (even) intervals.
fn simpson(f: impl Fn(f64) -> f64, b: f64, n: usize) -> f64 {
    if b <= 0.0 {
        return 0.0;
    }
    let h = b / n as f64;
    let inner: f64 = (1..n)
        .map(|i| if i % 2 == 1 { 4.0 } else { 2.0 } * f(i as f64 * h))
        .sum();
    h / 3.0 * (f(0.0) + inner + f(b))
}
