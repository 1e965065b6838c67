//! A contact interaction's stable time step, remembered between steps.

use std::cell::Cell;

/// The last stable step (s) an interaction computed and the nodal mass array it was computed
/// for (address and length). Penalty limits depend only on the node laws and the masses, and
/// both are constants of a run once the first step has set the laws, so the minimum over the
/// surface nodes need not be recomputed at every step.
/// The owner clears it whenever a law or a partner mass it used changes.
#[derive(Debug, Clone, Default)]
pub struct StepCache(Cell<Option<(f64, usize, usize)>>);

impl StepCache {
    /// The step cached for `mass`, or else `compute()` (s), which is then cached for it.
    /// `None` (no constraint) is not cached.
    pub fn get_or(&self, mass: &[f64], compute: impl FnOnce() -> Option<f64>) -> Option<f64> {
        let key = (mass.as_ptr() as usize, mass.len());
        if let Some((dt, p, n)) = self.0.get() {
            if (p, n) == key {
                return Some(dt);
            }
        }
        let dt = compute()?;
        self.0.set(Some((dt, key.0, key.1)));
        Some(dt)
    }

    /// Forgets the cached step: the next [`StepCache::get_or`] recomputes it.
    pub fn clear(&self) {
        self.0.set(None);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn recomputes_for_another_mass_array_and_after_clear() {
        let c = StepCache::default();
        let (a, b) = (vec![1.0; 4], vec![1.0; 4]);
        let calls = Cell::new(0);
        let step = |dt: f64| {
            calls.set(calls.get() + 1);
            Some(dt)
        };
        assert_eq!(c.get_or(&a, || step(1.0)), Some(1.0));
        assert_eq!(c.get_or(&a, || step(2.0)), Some(1.0));
        assert_eq!(calls.get(), 1);
        assert_eq!(c.get_or(&b, || step(3.0)), Some(3.0));
        c.clear();
        assert_eq!(c.get_or(&b, || step(4.0)), Some(4.0));
        assert_eq!(c.get_or(&b, || None), Some(4.0));
        c.clear();
        assert_eq!(c.get_or(&b, || None), None);
        assert_eq!(calls.get(), 3);
    }
}
