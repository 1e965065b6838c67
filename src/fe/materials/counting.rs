//! A test law with history (compiled in tests only): linear hardening that also counts, at
//! each integration point, the steps in which the point flowed plastically and keeps the
//! highest plastic strain rate it saw. It proves the history seam: the block sizes its
//! history array from [`Hardening::HISTORY`] and the element loop feeds every point's step
//! to [`Hardening::update_history`], on every kernel path. The parameters are
//! [`crate::material::hardening::Counting`], re-exported here.

use super::hardening::Hardening;
pub use crate::material::hardening::Counting;

impl Hardening for Counting {
    const HISTORY: usize = 2;

    fn rate_independent(&self) -> bool {
        true
    }

    #[inline(always)]
    fn static_yield(&self, eps_p: f64) -> f64 {
        self.0.static_yield(eps_p)
    }

    #[inline(always)]
    fn plastic_increment(&self, q: f64, sy: f64, eps_p: f64, shear: f64, dt: f64) -> (f64, f64) {
        self.0.plastic_increment(q, sy, eps_p, shear, dt)
    }

    fn update_history(&self, history: &mut [f64], _eps_p: f64, dp: f64, dt: f64) {
        if dp > 0.0 {
            history[0] += 1.0;
        }
        history[1] = history[1].max(dp / dt);
    }
}
