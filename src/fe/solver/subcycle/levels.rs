//! The level rule of the subcycling scheme: each node's limit from its elements' Courant
//! steps and its contact springs, capped by its element neighbours' limits, and the
//! power-of-two level that fits inside it. One rule; its constants are each model's
//! ([`LevelRule::SECTION`], [`LevelRule::HEXAHEDRA`]: docs/design.md, "Multi-time-step
//! integration").

/// The largest allowed subcycling level (steps up to 2^10 times the fine step).
pub const MAX_LEVEL: u8 = 10;

/// The constants of the level rule.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LevelRule {
    /// Margin on a node's limit for the levels above 0 (≥ 1): room for its elements to
    /// deform during a cycle, whose limits are measured at its start.
    pub margin: f64,
    /// Factor (≥ 1) by which a node's limit must exceed the next level's need before the
    /// node climbs there: a hysteresis, so that a node whose limit hovers about a threshold
    /// does not change its step at every synchronisation; 1: none.
    pub climb: f64,
    /// Most a node's limit may exceed the own limit of a node it shares an element with (∞:
    /// no cap): a contact node on its spring oscillates at ω ≤ 1/limit, which reaches its
    /// neighbours through their element, and ω H < 2 keeps it inside their step H.
    pub neighbour_ratio: f64,
}

impl LevelRule {
    /// The meridian section's: a 2 % margin, no hysteresis, the neighbour cap 2 (a node
    /// under a landing ring's spring at 4 h gained energy: design-measurements.md,
    /// "Subcycling of the section").
    pub const SECTION: LevelRule = LevelRule {
        margin: 1.02,
        climb: 1.0,
        neighbour_ratio: 2.0,
    };

    /// The 3D model's: no margin (its guard drops a level between synchronisations; a 2 %
    /// margin makes energy in 3D, `fe_subcycle::level_rules_on_the_elastic_impact`), climbs by
    /// 10 %, no neighbour cap (the nodes its interactions act on are held at level 0).
    pub const HEXAHEDRA: LevelRule = LevelRule {
        margin: 1.0,
        climb: 1.1,
        neighbour_ratio: f64::INFINITY,
    };

    /// Level of a node of limit `limit` (s) for fine step `h` (s), step factor `factor`
    /// and cap `max_level`: the largest k ≤ max_level with 2^k h ≤ factor · limit (with the
    /// margin for k ≥ 1); 0 when even that fails.
    pub fn level(&self, limit: f64, h: f64, factor: f64, max_level: u8) -> u8 {
        let room = factor * limit / (self.margin * h);
        let mut k = 0;
        while k < max_level && f64::from(1u32 << (k + 1)) <= room {
            k += 1;
        }
        k
    }

    /// The level at a synchronisation of a node of limit `limit` (s) that was at level
    /// `current` (`None` at the start), as [`LevelRule::level`]: it climbs only when the
    /// climbing factor times its need fits, and otherwise keeps its level if that still fits.
    pub fn next_level(
        &self,
        limit: f64,
        h: f64,
        factor: f64,
        max_level: u8,
        current: Option<u8>,
    ) -> u8 {
        let fit = self.level(limit, h, factor, max_level);
        match current {
            Some(cur) => {
                let climb = self.level(limit / self.climb, h, factor, max_level);
                if climb > cur {
                    climb
                } else {
                    cur.min(fit)
                }
            }
            None => fit,
        }
    }

    /// Each node's limit (s): the smallest Courant step (s) of the elements holding it and
    /// its contact limit `contact_dt` (s, one per node; ∞ for none), capped at the neighbour
    /// ratio times the own limit of every node it shares an element with. `elements` yields
    /// each element's nodes and Courant step; it is walked once, twice with a cap.
    pub fn node_limits<'a, const N: usize>(
        &self,
        elements: impl Iterator<Item = (&'a [u32; N], f64)> + Clone,
        contact_dt: &[f64],
    ) -> Vec<f64> {
        let mut own = contact_dt.to_vec();
        for (e, dt) in elements.clone() {
            for &i in e {
                let l = &mut own[i as usize];
                *l = l.min(dt);
            }
        }
        if self.neighbour_ratio.is_infinite() {
            return own;
        }
        let mut lim = own.clone();
        for (e, _) in elements {
            let m = e
                .iter()
                .map(|&i| own[i as usize])
                .fold(f64::INFINITY, f64::min);
            for &i in e {
                let l = &mut lim[i as usize];
                *l = l.min(self.neighbour_ratio * m);
            }
        }
        lim
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn node_level_is_the_largest_power_of_two_inside_the_limit() {
        let r = LevelRule::SECTION;
        // h = 0.9 · 1 (the smallest limit); limit 4.5 allows 2^2 h = 3.6 ≤ 4.05 / 1.02.
        assert_eq!(r.level(4.5, 0.9, 0.9, 6), 2);
        assert_eq!(r.level(1.0, 0.9, 0.9, 6), 0);
        assert_eq!(r.level(1e9, 0.9, 0.9, 6), 6);
        // Just above 2 (within the margin) stays at level 0.
        assert_eq!(r.level(2.01, 0.9, 0.9, 6), 0);
        assert_eq!(r.level(2.1, 0.9, 0.9, 6), 1);
        // Without a margin, 2 h itself fits.
        assert_eq!(LevelRule::HEXAHEDRA.level(2.0, 1.0, 1.0, 6), 1);
        assert_eq!(LevelRule::HEXAHEDRA.level(1.99, 1.0, 1.0, 6), 0);
    }

    #[test]
    fn a_node_climbs_only_with_the_climbing_factor_and_keeps_a_level_that_fits() {
        let r = LevelRule::HEXAHEDRA;
        // Limit 2.1 fits level 1, but not with the 10 % climbing factor.
        assert_eq!(r.next_level(2.1, 1.0, 1.0, 6, None), 1);
        assert_eq!(r.next_level(2.1, 1.0, 1.0, 6, Some(0)), 0);
        assert_eq!(r.next_level(2.1, 1.0, 1.0, 6, Some(1)), 1);
        assert_eq!(r.next_level(2.3, 1.0, 1.0, 6, Some(0)), 1);
        // A level that no longer fits drops at once.
        assert_eq!(r.next_level(1.9, 1.0, 1.0, 6, Some(1)), 0);
        // Without hysteresis the level is the fit, whatever the node had.
        assert_eq!(LevelRule::SECTION.next_level(2.2, 0.9, 0.9, 6, Some(0)), 1);
    }

    #[test]
    fn a_node_takes_at_most_twice_the_limit_of_its_element_neighbours() {
        // Node 0 carries a stiff spring (limit 1); its quad's other nodes would allow 8, the
        // second quad's far nodes 8 too: only the first quad's nodes are capped at 2.
        let quads = [[0, 1, 2, 3], [1, 4, 5, 2]];
        let inf = f64::INFINITY;
        let contact = [1.0, inf, inf, inf, inf, inf];
        let elements = quads.iter().zip([8.0, 8.0]);
        let lim = LevelRule::SECTION.node_limits(elements.clone(), &contact);
        assert_eq!(lim, vec![1.0, 2.0, 2.0, 2.0, 8.0, 8.0]);
        // Without the cap each node keeps its own.
        let own = LevelRule::HEXAHEDRA.node_limits(elements, &contact);
        assert_eq!(own, vec![1.0, 8.0, 8.0, 8.0, 8.0, 8.0]);
    }
}
