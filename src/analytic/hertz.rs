//! Hertz's elastic contact of two spheres (or a sphere on a half-space) and the closed forms of
//! a purely elastic impact.
//!
//! Notation: E* effective (plane-strain) modulus, R* effective radius, m* effective mass,
//! δ relative approach of the centres (overlap), v relative normal approach speed at first touch.
//! A half-space has infinite radius and mass; a rigid one also an infinite modulus: the
//! reciprocal sums below handle `f64::INFINITY` exactly (1/∞ = 0).

use super::body::Body;
use super::quadrature::integrate;

/// t_c v / δ_max for a Hertz impact: (4/5) √π Γ(2/5) / Γ(9/10) = 2.94327518432…
///
/// Derivation: energy gives δ̇² = v² (1 − (δ/δ_max)^{5/2}), so with x = δ/δ_max the duration is
/// t_c = 2 (δ_max/v) ∫₀¹ (1 − x^{5/2})^{-1/2} dx, and u = x^{5/2} turns the integral into
/// (2/5) B(2/5, 1/2) = (2/5) √π Γ(2/5)/Γ(9/10).
pub const HERTZ_DURATION_FACTOR: f64 = 2.943_275_184_324_705;

/// Reduced value 1/(1/a + 1/b) of two positive quantities (either may be `f64::INFINITY`).
fn reduced(a: f64, b: f64) -> f64 {
    1.0 / (1.0 / a + 1.0 / b)
}

/// Effective modulus E* = 1/(1/E_t1 + 1/E_t2), Pa, from the plane-strain moduli
/// E_ti = E_i/(1 − ν_i²) (Pa; `f64::INFINITY` for a rigid body). The paper's E_t.
pub fn effective_modulus(et1: f64, et2: f64) -> f64 {
    reduced(et1, et2)
}

/// Effective radius R* = R1 R2/(R1 + R2), m (`f64::INFINITY` for a half-space).
pub fn effective_radius(r1: f64, r2: f64) -> f64 {
    reduced(r1, r2)
}

/// Effective mass m* = m1 m2/(m1 + m2), kg (`f64::INFINITY` for an immovable body).
pub fn effective_mass(m1: f64, m2: f64) -> f64 {
    reduced(m1, m2)
}

/// The effective quantities of a Hertz contact pair; every method is a pure closed form.
///
/// Inputs must be finite and positive (a pair of two half-spaces is meaningless); methods do
/// not check and return NaN/∞ otherwise.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HertzPair {
    /// Effective modulus E*, Pa.
    pub modulus: f64,
    /// Effective radius R*, m.
    pub radius: f64,
    /// Effective mass m*, kg.
    pub mass: f64,
}

impl HertzPair {
    /// The pair from explicit effective quantities (Pa, m, kg).
    pub fn new(modulus: f64, radius: f64, mass: f64) -> Self {
        HertzPair {
            modulus,
            radius,
            mass,
        }
    }

    /// The pair formed by two bodies (ball–ball or ball–half-space).
    pub fn between(b1: &Body, b2: &Body) -> Self {
        HertzPair {
            modulus: effective_modulus(b1.plane_strain_modulus(), b2.plane_strain_modulus()),
            radius: effective_radius(b1.radius(), b2.radius()),
            mass: effective_mass(b1.mass(), b2.mass()),
        }
    }

    /// Hertz stiffness K = (4/3) E* √R*, N/m^{3/2}, so that p = K δ^{3/2}.
    pub fn stiffness(&self) -> f64 {
        4.0 / 3.0 * self.modulus * self.radius.sqrt()
    }

    /// Contact force p = (4/3) E* √R* δ^{3/2}, N (eq. 5); zero for δ ≤ 0 (no contact).
    pub fn force(&self, delta: f64) -> f64 {
        if delta <= 0.0 {
            0.0
        } else {
            self.stiffness() * delta * delta.sqrt()
        }
    }

    /// Elastic energy stored at approach δ, (2/5) K δ^{5/2}, J (zero for δ ≤ 0).
    pub fn energy(&self, delta: f64) -> f64 {
        if delta <= 0.0 {
            0.0
        } else {
            0.4 * self.stiffness() * delta.powf(2.5)
        }
    }

    /// Contact radius a = √(R* δ), m (eq. 4); zero for δ ≤ 0.
    pub fn contact_radius(&self, delta: f64) -> f64 {
        (self.radius * delta.max(0.0)).sqrt()
    }

    /// Maximum approach of an elastic impact at relative speed v (m/s):
    /// δ_max = (15 m* v² / (16 E* √R*))^{2/5}, m.
    pub fn max_approach(&self, v: f64) -> f64 {
        (15.0 * self.mass * v * v / (16.0 * self.modulus * self.radius.sqrt())).powf(0.4)
    }

    /// Peak contact force of an elastic impact at speed v, K δ_max^{3/2}, N.
    pub fn peak_force(&self, v: f64) -> f64 {
        self.force(self.max_approach(v))
    }

    /// Duration of an elastic impact at speed v (> 0 m/s), t_c = 2.9433 δ_max / v, s.
    pub fn contact_duration(&self, v: f64) -> f64 {
        HERTZ_DURATION_FACTOR * self.max_approach(v) / v.abs()
    }

    /// Approach speed δ̇ = √(v² − (16 E*√R*/(15 m*)) δ^{5/2}) at approach δ of an elastic
    /// impact that began at speed v (eq. 11), m/s; zero beyond δ_max.
    pub fn approach_speed(&self, v: f64, delta: f64) -> f64 {
        let k = 16.0 * self.modulus * self.radius.sqrt() / (15.0 * self.mass);
        (v * v - k * delta.max(0.0).powf(2.5)).max(0.0).sqrt()
    }

    /// Time for an elastic impact that began at speed v (> 0) to reach approach δ on loading,
    /// t = ∫₀^δ dδ'/δ̇ (eq. 13), s. δ is clamped to [0, δ_max]; t(δ_max) = t_c/2.
    pub fn time_to_approach(&self, v: f64, delta: f64) -> f64 {
        let dm = self.max_approach(v);
        dm / v.abs() * loading_time_fraction((delta / dm).clamp(0.0, 1.0))
    }

    /// Approach δ(t) of an elastic impact that began at speed v (> 0) at t = 0, m, for
    /// 0 ≤ t ≤ t_c (loading then the mirror-image unloading); 0 outside.
    pub fn approach_at(&self, v: f64, t: f64) -> f64 {
        let dm = self.max_approach(v);
        let half = 0.5 * HERTZ_DURATION_FACTOR;
        let tau = t * v.abs() / dm;
        if !(0.0..=2.0 * half).contains(&tau) {
            return 0.0;
        }
        dm * inverse_loading_time_fraction(tau.min(2.0 * half - tau))
    }
}

/// F(x) = ∫₀^x (1 − u^{5/2})^{-1/2} du for 0 ≤ x ≤ 1: the loading time to δ = x δ_max in units
/// of δ_max/v. F(1) = HERTZ_DURATION_FACTOR/2.
///
/// Both ends are made analytic before Gauss–Legendre quadrature: u = y² on [0, ½] removes the
/// u^{5/2} branch point at 0; 1 − u = s² on [½, x] removes the inverse-square-root singularity
/// at 1, leaving 2/√g(s) with g(s) = (1 − (1 − s²)^{5/2})/s² (→ 5/2 as s → 0). Accurate to
/// about 1e-15 relative. Input outside [0, 1] is clamped.
pub fn loading_time_fraction(x: f64) -> f64 {
    let x = x.clamp(0.0, 1.0);
    let split = 0.5;
    let xa = x.min(split);
    // Piece 1: u = y², du = 2y dy.
    let mut sum = integrate(|y| 2.0 * y / (1.0 - y.powi(5)).sqrt(), 0.0, xa.sqrt(), 2);
    if x > split {
        // Piece 2: u = 1 − s², du = −2s ds; integrand 2/√g(s), s from √(1−x) to √(1−split).
        let g = |s: f64| {
            let s2 = s * s;
            if s2 == 0.0 {
                2.5
            } else {
                -(2.5 * (-s2).ln_1p()).exp_m1() / s2
            }
        };
        sum += integrate(
            |s| 2.0 / g(s).sqrt(),
            (1.0 - x).sqrt(),
            (1.0 - split).sqrt(),
            4,
        );
    }
    sum
}

/// Inverse of [`loading_time_fraction`]: the x in [0, 1] with F(x) = tau (tau clamped to
/// [0, F(1)]). Safeguarded Newton iteration in s = √(1 − x), where F is smooth.
pub fn inverse_loading_time_fraction(tau: f64) -> f64 {
    let full = 0.5 * HERTZ_DURATION_FACTOR;
    let tau = tau.clamp(0.0, full);
    if tau == 0.0 {
        return 0.0;
    }
    if tau == full {
        return 1.0;
    }
    // h(s) = F(1 − s²) − tau is decreasing in s on [0, 1]; dF/ds = −2s (1 − x^{5/2})^{-1/2}.
    let (mut lo, mut hi) = (0.0_f64, 1.0_f64); // h(lo) > 0 > h(hi)
    let mut s = (1.0 - tau / full).clamp(0.0, 1.0).sqrt().clamp(0.05, 0.95);
    for _ in 0..100 {
        let x = 1.0 - s * s;
        let h = loading_time_fraction(x) - tau;
        if h > 0.0 {
            lo = s;
        } else {
            hi = s;
        }
        let g = if s == 0.0 {
            2.5
        } else {
            -(2.5 * (-(s * s)).ln_1p()).exp_m1() / (s * s)
        };
        // dF/ds = −2s/√(s² g) = −2/√g.
        let dh = -2.0 / g.sqrt();
        let mut next = s - h / dh;
        if !(next > lo && next < hi) {
            next = 0.5 * (lo + hi);
        }
        if (next - s).abs() < 1e-15 {
            s = next;
            break;
        }
        s = next;
    }
    1.0 - s * s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Γ(x) for x in (0, 2] from the convergent Euler product limit, written out only to check
    /// the duration constant independently of the quadrature.
    fn gamma_euler(x: f64) -> f64 {
        // Γ(x) = lim n^x n! / (x (x+1) … (x+n)); accelerate with Richardson in 1/n.
        let g = |n: usize| {
            let mut ln = x * (n as f64).ln() - x.ln();
            for k in 1..=n {
                ln += (k as f64).ln() - (x + k as f64).ln();
            }
            ln.exp()
        };
        let (a, b) = (g(200_000), g(400_000));
        2.0 * b - a
    }

    #[test]
    fn duration_constant_is_the_beta_function_value() {
        let c = 0.8 * std::f64::consts::PI.sqrt() * gamma_euler(0.4) / gamma_euler(0.9);
        assert!((c - HERTZ_DURATION_FACTOR).abs() < 1e-9, "{c}");
        let q = 2.0 * loading_time_fraction(1.0);
        assert!((q - HERTZ_DURATION_FACTOR).abs() < 1e-13, "{q}");
    }

    #[test]
    fn infinite_partner_gives_the_ball_on_wall_limit() {
        assert_eq!(effective_radius(0.01, f64::INFINITY), 0.01);
        assert_eq!(effective_mass(2.0, f64::INFINITY), 2.0);
        assert_eq!(effective_modulus(1e11, f64::INFINITY), 1e11);
        assert!((effective_modulus(1e11, 1e11) - 5e10).abs() < 1.0);
    }

    #[test]
    fn inverse_time_fraction_round_trips() {
        for &x in &[1e-6, 0.01, 0.3, 0.5, 0.7, 0.99, 0.999999] {
            let t = loading_time_fraction(x);
            let back = inverse_loading_time_fraction(t);
            assert!((back - x).abs() < 1e-10, "{x} -> {t} -> {back}");
        }
    }

    #[test]
    fn energy_at_max_approach_equals_initial_kinetic_energy() {
        let p = HertzPair::new(6e10, 5e-3, 0.0165);
        let v = 2.0;
        let ke = 0.5 * p.mass * v * v;
        assert!((p.energy(p.max_approach(v)) - ke).abs() < 1e-12 * ke);
        assert!(p.approach_speed(v, p.max_approach(v)) < 1e-6 * v);
    }

    #[test]
    fn approach_history_is_symmetric_and_peaks_at_half_time() {
        let p = HertzPair::new(6e10, 5e-3, 0.0165);
        let v = 1.5;
        let tc = p.contact_duration(v);
        assert!((p.approach_at(v, 0.5 * tc) - p.max_approach(v)).abs() < 1e-12);
        let a = p.approach_at(v, 0.2 * tc);
        let b = p.approach_at(v, 0.8 * tc);
        assert!((a - b).abs() < 1e-12 * p.max_approach(v));
        assert_eq!(p.approach_at(v, 1.01 * tc), 0.0);
    }
}
