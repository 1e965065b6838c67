//! What subcycling did over a run (for results.json) and what a level assignment saves.

use serde::Serialize;

/// What subcycling did over a run, for results.json.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct SubcycleReport {
    /// Subcycling in use.
    pub used: bool,
    /// Why it is (not) used.
    pub reason: String,
    /// Predicted saving at the start: elements / Σ_e 2^{−k_e}.
    pub predicted_saving: f64,
    /// Highest level allowed.
    pub max_level: u32,
    /// Elements per level at the start (index = level).
    pub initial_levels: Vec<usize>,
    /// Element updates taken, all levels.
    pub element_updates: u64,
    /// Times a node dropped level(s) because an element's limit fell (at a synchronisation
    /// or by the guard between them).
    pub level_drops: u64,
    /// Times the fine step dropped between synchronisations (a limit fell below it).
    pub fine_step_drops: u64,
    /// Synchronisations (all elements updated together; h and climbs decided there).
    pub synchronisations: u64,
}

/// Predicted saving of a level assignment: elements / Σ_e 2^{−k_e} (1 = none).
pub fn predicted_saving(levels: &[u8]) -> f64 {
    let cost: f64 = levels.iter().map(|&k| 0.5f64.powi(k as i32)).sum();
    if cost > 0.0 {
        levels.len() as f64 / cost
    } else {
        1.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn predicted_saving_counts_updates_per_fine_step() {
        assert_eq!(predicted_saving(&[0, 0, 0, 0]), 1.0);
        // One element every step, three every 4th: 4 / (1 + 3/4).
        assert!((predicted_saving(&[0, 2, 2, 2]) - 4.0 / 1.75).abs() < 1e-12);
    }
}
