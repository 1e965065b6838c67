//! Gauss–Legendre quadrature for the smooth integrands left after the Hertz-type endpoint
//! singularities have been removed by substitution.

use std::sync::OnceLock;

/// Number of Gauss–Legendre points per panel.
const ORDER: usize = 24;

/// Nodes and weights of the `ORDER`-point Gauss–Legendre rule on [−1, 1], found once by Newton
/// iteration on the Legendre polynomial P_n (three-term recurrence); accurate to round-off.
fn rule() -> &'static [(f64, f64)] {
    static RULE: OnceLock<Vec<(f64, f64)>> = OnceLock::new();
    RULE.get_or_init(|| {
        let n = ORDER;
        let nf = n as f64;
        (0..n)
            .map(|i| {
                // Tricomi's initial guess for the i-th root, then Newton.
                let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (nf + 0.5)).cos();
                let mut dp = 0.0;
                for _ in 0..100 {
                    let (p, d) = legendre(n, x);
                    dp = d;
                    let dx = p / d;
                    x -= dx;
                    if dx.abs() < 1e-16 {
                        break;
                    }
                }
                let (_, d) = legendre(n, x);
                if d != 0.0 {
                    dp = d;
                }
                (x, 2.0 / ((1.0 - x * x) * dp * dp))
            })
            .collect()
    })
}

/// P_n(x) and P_n'(x) by the recurrence (k+1) P_{k+1} = (2k+1) x P_k − k P_{k−1}.
fn legendre(n: usize, x: f64) -> (f64, f64) {
    let (mut p0, mut p1) = (1.0, x);
    for k in 1..n {
        let kf = k as f64;
        let p2 = ((2.0 * kf + 1.0) * x * p1 - kf * p0) / (kf + 1.0);
        p0 = p1;
        p1 = p2;
    }
    let dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
    (p1, dp)
}

/// ∫_a^b f(x) dx by composite Gauss–Legendre quadrature on `panels` equal panels
/// (`ORDER` points each). For integrands that are smooth on [a, b]; exact for polynomials of
/// degree < 2·ORDER. `panels` is clamped to at least 1.
pub fn integrate(f: impl Fn(f64) -> f64, a: f64, b: f64, panels: usize) -> f64 {
    let panels = panels.max(1);
    let h = (b - a) / panels as f64;
    let mut sum = 0.0;
    for p in 0..panels {
        let mid = a + (p as f64 + 0.5) * h;
        for &(x, w) in rule() {
            sum += w * f(mid + 0.5 * h * x);
        }
    }
    0.5 * h * sum
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn weights_sum_to_two_and_polynomials_are_exact() {
        let s: f64 = rule().iter().map(|&(_, w)| w).sum();
        assert!((s - 2.0).abs() < 1e-14);
        // ∫_0^1 x^40 dx = 1/41 (degree 40 < 48).
        let v = integrate(|x| x.powi(40), 0.0, 1.0, 1);
        assert!((v - 1.0 / 41.0).abs() < 1e-15);
    }

    #[test]
    fn smooth_transcendental_integrand() {
        let v = integrate(f64::exp, 0.0, 2.0, 2);
        assert!((v - (2f64.exp() - 1.0)).abs() < 1e-13);
    }
}
