//! Independent closed forms for rate-independent laws: the loading work ∫₀^δ F dδ by
//! Gauss-Legendre quadrature on the law's smooth pieces, and the δ_max that absorbs a given
//! kinetic energy. Used where a law's work has no elementary antiderivative worth writing.

use super::NormalLaw;
use crate::analytic::quadrature::integrate;

/// ∫₀^δ F_load(s) ds, J, for a rate-independent law (rate 0, speed 1 are passed). The first
/// piece uses s = y² to remove the δ^{1/2}-type branch point at 0; later pieces start at the
/// law's thresholds, where the force is smooth on each side.
pub fn loading_work(law: &dyn NormalLaw, delta: f64) -> f64 {
    let f = |s: f64| law.loading(s, 0.0, 1.0);
    let mut edges: Vec<f64> = law
        .thresholds()
        .into_iter()
        .filter(|&t| t > 0.0 && t < delta)
        .collect();
    edges.push(delta);
    let mut sum = 0.0;
    let mut a = 0.0;
    for (i, &b) in edges.iter().enumerate() {
        sum += if i == 0 {
            integrate(|y| 2.0 * y * f(y * y), 0.0, b.sqrt(), 8)
        } else {
            integrate(f, a, b, 8)
        };
        a = b;
    }
    sum
}

/// The approach (m) at which the loading work equals `energy` (J > 0); `guess` (m, > 0)
/// starts the bracket. Bisection to round-off.
pub fn max_approach(law: &dyn NormalLaw, energy: f64, guess: f64) -> f64 {
    let (mut lo, mut hi) = (0.0, guess);
    while loading_work(law, hi) < energy {
        lo = hi;
        hi *= 2.0;
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if loading_work(law, mid) < energy {
            lo = mid;
        } else {
            hi = mid;
        }
        if hi - lo <= 1e-15 * hi {
            break;
        }
    }
    0.5 * (lo + hi)
}
