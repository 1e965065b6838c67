//! The step classes of one cycle of the subcycling scheme: node levels, element update
//! levels (each element's finest node), both sorted by level, and which levels are due at
//! each fine step of the cycle.

/// The step classes of one cycle: node and element levels, and both sorted by level.
#[derive(Debug, Clone, Default)]
pub struct Schedule {
    /// Level of each node.
    pub node_level: Vec<u8>,
    /// Level of each element (its finest node's).
    pub element_level: Vec<u8>,
    /// Elements sorted by level (stable: ascending index within a level).
    pub elements: Vec<u32>,
    /// `elements[..element_end[k]]` are the elements of levels ≤ k.
    pub element_end: Vec<usize>,
    /// Nodes sorted by level.
    pub nodes: Vec<u32>,
    /// `nodes[..node_end[k]]` are the nodes of levels ≤ k.
    pub node_end: Vec<usize>,
    /// Highest level in use; a cycle is 2^top fine steps.
    pub top: u8,
    /// Fine steps taken since the last synchronisation.
    pub count: u64,
}

/// Indices `0..levels.len()` sorted by level (stable) and the end of each level's run.
fn sorted_by_level(levels: &[u8], top: u8) -> (Vec<u32>, Vec<usize>) {
    let mut order: Vec<u32> = (0..levels.len() as u32).collect();
    order.sort_by_key(|&i| levels[i as usize]);
    let ends = (0..=top)
        .map(|k| levels.iter().filter(|&&l| l <= k).count())
        .collect();
    (order, ends)
}

impl Schedule {
    /// The schedule of node levels `node_level` on the elements `elements` (each element's
    /// nodes, in element order).
    pub fn new<'a, const N: usize>(
        elements: impl IntoIterator<Item = &'a [u32; N]>,
        node_level: Vec<u8>,
    ) -> Self {
        let element_level: Vec<u8> = elements
            .into_iter()
            .map(|q| q.iter().map(|&i| node_level[i as usize]).min().unwrap_or(0))
            .collect();
        let top = node_level.iter().copied().max().unwrap_or(0);
        let (elements, element_end) = sorted_by_level(&element_level, top);
        let (nodes, node_end) = sorted_by_level(&node_level, top);
        Schedule {
            node_level,
            element_level,
            elements,
            element_end,
            nodes,
            node_end,
            top,
            count: 0,
        }
    }

    /// Fine steps in a cycle.
    pub fn cycle(&self) -> u64 {
        1 << self.top
    }

    /// The highest level due after fine step `count` of the cycle (every level at its end).
    pub fn due_level(&self, count: u64) -> u8 {
        if count >= self.cycle() {
            self.top
        } else {
            (count.trailing_zeros() as u8).min(self.top)
        }
    }

    /// Element updates per fine step, averaged over a cycle: Σ_e 2^{−u_e}.
    pub fn updates_per_step(&self) -> f64 {
        self.element_level
            .iter()
            .map(|&u| 1.0 / f64::from(1u32 << u))
            .sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn elements_take_their_finest_node_and_runs_are_sorted() {
        let quads = [[0, 1, 2, 3], [1, 4, 5, 2]];
        let s = Schedule::new(&quads, vec![2, 1, 3, 3, 3, 3]);
        assert_eq!(s.element_level, vec![1, 1]);
        assert_eq!(s.top, 3);
        assert_eq!(s.element_end, vec![0, 2, 2, 2]);
        assert_eq!(s.nodes[0], 1);
        assert_eq!(s.node_end, vec![0, 1, 2, 6]);
        assert_eq!(s.due_level(1), 0);
        assert_eq!(s.due_level(4), 2);
        assert_eq!(s.due_level(8), 3);
        assert!((s.updates_per_step() - 1.0).abs() < 1e-15);
    }
}
