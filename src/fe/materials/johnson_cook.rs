//! Johnson-Cook hardening with its strain-rate term (Johnson & Cook 1983),
//! σ_y = (A + B ε_p^n)(1 + C ln ε̇*), ε̇* = max(ε̇_p/ε̇_0, 1), with the plastic strain rate
//! taken over the step, ε̇_p = Δε_p/Δt.
//!
//! Thermal softening (the factor 1 − T*^m) is off. The balls heat adiabatically by
//! ΔT = β ∫σ dε_p/(ρ c) with the Taylor-Quinney fraction β ≈ 0.9 (Taylor & Quinney 1934):
//! for OFHC copper (ρ c = 8960 × 385 J/(m³ K)) even a plastic strain of 0.05 at 300 MPa
//! heats by about 4 K, T* = ΔT/(T_m − T_r) ≈ 4/1058 = 0.004, and with m = 1.09 the flow
//! stress falls by 1 − T*^m ≈ 0.3 %. The collisions modelled here, at metres per second,
//! reach far smaller plastic strains.
//!
//! The parameters and the published presets are [`crate::material::hardening::JohnsonCook`],
//! [`OFHC_COPPER`] and [`STEEL_4340`], re-exported here.

use super::hardening::{newton_root, Hardening};
pub use crate::material::hardening::{JohnsonCook, OFHC_COPPER, STEEL_4340};

/// σ_y and dσ_y/dΔε_p of `jc` for the increment `dp` from `eps_p` over the step `dt` (s).
fn flow(jc: &JohnsonCook, eps_p: f64, dp: f64, dt: f64) -> (f64, f64) {
    let e = eps_p + dp;
    let en = e.powf(jc.n);
    let h = jc.a + jc.b * en;
    // n B e^(n−1) as n B e^n / e: one power per evaluation. At e = 0 the slope is not
    // finite either way (NaN here, ∞ as a power), and the Newton solve bisects.
    let dh = jc.n * jc.b * en / e;
    let ratio = if dt > 0.0 { dp / (dt * jc.rate0) } else { 0.0 };
    // At the knee itself the slope is the right-hand one (m = 1 either way): the upper
    // bracket of [`Hardening::plastic_increment`] starts there.
    if ratio >= 1.0 {
        let m = 1.0 + jc.c * ratio.ln();
        (h * m, dh * m + h * jc.c / dp)
    } else {
        (h, dh)
    }
}

impl Hardening for JohnsonCook {
    /// Without the rate term (C = 0) the law is rate-independent.
    fn rate_independent(&self) -> bool {
        self.c == 0.0
    }

    fn static_yield(&self, eps_p: f64) -> f64 {
        // 0^n = 0 for n > 0: a point that never yielded skips the power (same bits).
        if eps_p == 0.0 {
            return self.a;
        }
        self.a + self.b * eps_p.powf(self.n)
    }

    /// The safeguarded Newton solve of [`newton_root`] on one side of the knee Δp = ε̇₀Δt,
    /// where the rate factor starts and σ_y's slope jumps (by σ_y C/Δp): on either side the
    /// flow stress is concave, and Newton climbs from the bracket's left end. (Started at
    /// the perfectly plastic bound across the knee, the solve took 16 flow evaluations a
    /// return in a plastic impact, most of them bisection steps.) Plastic work by the
    /// trapezoidal rule, as [`super::hardening::newton_return`].
    fn plastic_increment(&self, q: f64, sy: f64, eps_p: f64, shear: f64, dt: f64) -> (f64, f64) {
        let three_g = 3.0 * shear;
        let hi = (q - sy) / three_g;
        let knee = dt * self.rate0;
        let bracket = if dt > 0.0 && self.c > 0.0 && knee < hi {
            if q - three_g * knee - flow(self, eps_p, knee, dt).0 > 0.0 {
                (knee, hi)
            } else {
                (0.0, knee)
            }
        } else {
            (0.0, hi)
        };
        // The left end, unless it is Δp = 0 on a virgin point (an infinite slope of ε_p^n).
        let start = if bracket.0 > 0.0 || eps_p > 0.0 {
            bracket.0
        } else {
            bracket.1
        };
        let x = newton_root(q, shear, bracket, start, |dp| flow(self, eps_p, dp, dt));
        (x, 0.5 * x * (sy + flow(self, eps_p, x, dt).0))
    }
}

#[cfg(test)]
mod tests {
    use super::super::hardening::newton_return;
    use super::*;

    /// On both sides of the knee (Δp = ε̇₀Δt, where the rate factor starts) the bracketed
    /// return meets the consistency condition q − 3GΔp = σ_y(Δp) and lands on the root the
    /// unbracketed solve finds, to round-off.
    #[test]
    fn the_return_is_consistent_on_both_sides_of_the_knee() {
        let g = 124e9 / (2.0 * 1.34);
        let jc = OFHC_COPPER;
        let mut sides = [0usize; 2];
        for eps_p in [0.0, 1e-5, 1e-3, 1e-2, 0.1, 0.3] {
            for over in [1e2, 1e3, 1e5, 1e6, 1e7, 1e8] {
                for dt in [1e-10, 1e-9, 1e-8, 1e-7] {
                    let sy = jc.static_yield(eps_p);
                    let q = sy + over;
                    let (dp, work) = jc.plastic_increment(q, sy, eps_p, g, dt);
                    let s = flow(&jc, eps_p, dp, dt).0;
                    let residual = (q - 3.0 * g * dp - s).abs() / q;
                    assert!(
                        dp > 0.0 && residual < 1e-12,
                        "{eps_p} {over} {dt}: {residual:e}"
                    );
                    let (old, _) = newton_return(q, sy, g, |x| flow(&jc, eps_p, x, dt));
                    assert!(
                        (dp / old - 1.0).abs() < 1e-9,
                        "{eps_p} {over} {dt}: {dp} {old}"
                    );
                    assert!(work > sy * dp * (1.0 - 1e-12), "{work} {sy} {dp}");
                    sides[usize::from(dp > dt * jc.rate0)] += 1;
                }
            }
        }
        // The grid has roots on both sides of the knee.
        assert!(sides[0] > 10 && sides[1] > 10, "{sides:?}");
    }

    /// A return of a plastic impact's contact zone (ε_p = 0.1, 1 MPa over the yield stress,
    /// Δt = 10 ns: the root lies 19 % above the knee): from the bracket's left end Newton
    /// needs 7 flow evaluations, from the perfectly plastic bound 16.
    #[test]
    fn newton_climbs_from_the_left_end_in_a_few_evaluations() {
        let (g, jc) = (124e9 / (2.0 * 1.34), OFHC_COPPER);
        let (eps_p, dt) = (0.1, 1e-8);
        let sy = jc.static_yield(eps_p);
        let q = sy + 1e6;
        let hi = (q - sy) / (3.0 * g);
        let count = |start: f64| {
            let n = std::cell::Cell::new(0);
            let x = newton_root(q, g, (dt, hi), start, |dp| {
                n.set(n.get() + 1);
                flow(&jc, eps_p, dp, dt)
            });
            (x, n.get())
        };
        let ((left, n_left), (right, n_right)) = (count(dt), count(hi));
        assert!((left / right - 1.0).abs() < 1e-12, "{left} {right}");
        assert!(n_left <= 8 && n_right >= 12, "{n_left} {n_right}");
    }
}
