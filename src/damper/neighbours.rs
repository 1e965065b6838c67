//! The Verlet neighbour list: ball pairs closer than their contact distance plus a skin,
//! found through the cell list and rebuilt only when some ball has moved more than half the
//! skin since the last build, so no pair that can touch in between is missed.

use super::cells::candidate_pairs;
use nalgebra::Vector3;

/// Ball pairs that may touch before the next rebuild.
#[derive(Debug, Clone)]
pub struct NeighbourList {
    skin: f64,
    cell: f64,
    anchor: Vec<Vector3<f64>>,
    pairs: Vec<(usize, usize)>,
    built: bool,
    /// Times the list was (re)built.
    pub builds: u64,
}

impl NeighbourList {
    /// An empty list with skin `skin` (m, > 0) for balls of largest diameter `diameter` (m).
    pub fn new(skin: f64, diameter: f64) -> NeighbourList {
        NeighbourList {
            skin,
            cell: diameter + skin,
            anchor: Vec::new(),
            pairs: Vec::new(),
            built: false,
            builds: 0,
        }
    }

    /// The pairs (i < j, ascending) whose distance was below R_i + R_j + skin at the last
    /// build.
    pub fn list(&self) -> &[(usize, usize)] {
        &self.pairs
    }

    /// Rebuilds the list if a ball moved more than skin/2 since the last build, and returns
    /// [`Self::list`]. `positions` and `radius` in m; the grid spans `extent` (m) from
    /// `origin`.
    pub fn pairs(
        &mut self,
        positions: &[Vector3<f64>],
        radius: &[f64],
        origin: Vector3<f64>,
        extent: Vector3<f64>,
    ) -> &[(usize, usize)] {
        let limit = 0.25 * self.skin * self.skin;
        let moved = !self.built
            || self.anchor.len() != positions.len()
            || positions
                .iter()
                .zip(&self.anchor)
                .any(|(p, a)| (p - a).norm_squared() > limit);
        if moved {
            self.rebuild(positions, radius, origin, extent);
        }
        &self.pairs
    }

    fn rebuild(
        &mut self,
        positions: &[Vector3<f64>],
        radius: &[f64],
        origin: Vector3<f64>,
        extent: Vector3<f64>,
    ) {
        let skin = self.skin;
        self.pairs = candidate_pairs(positions, origin, extent, self.cell);
        self.pairs
            .retain(|&(i, j)| (positions[j] - positions[i]).norm() < radius[i] + radius[j] + skin);
        self.anchor.clear();
        self.anchor.extend_from_slice(positions);
        self.built = true;
        self.builds += 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::damper::cells::tests::{assert_holds_touching, uniform};

    /// Balls drifting at random: every pair the brute force finds touching is in the list,
    /// which is rebuilt far less often than every step.
    #[test]
    fn keeps_every_touching_pair_between_rebuilds() {
        let mut seed = 987654321u64;
        let mut rnd = || uniform(&mut seed) - 0.5;
        let extent = Vector3::new(0.1, 0.04, 0.035);
        let r = vec![0.01; 12];
        let mut p: Vec<Vector3<f64>> = (0..12)
            .map(|_| {
                Vector3::new(0.05, 0.02, 0.0175)
                    + Vector3::new(rnd() * 0.1, rnd() * 0.04, rnd() * 0.035)
            })
            .collect();
        let v: Vec<Vector3<f64>> = (0..12)
            .map(|_| Vector3::new(rnd(), rnd(), rnd()) * 1e-4)
            .collect();
        let mut list = NeighbourList::new(2e-3, 0.02);
        let steps = 2000;
        for _ in 0..steps {
            for (x, u) in p.iter_mut().zip(&v) {
                *x += u;
            }
            let pairs = list.pairs(&p, &r, Vector3::zeros(), extent).to_vec();
            assert_holds_touching(&p, 0.02, &pairs);
        }
        assert!(
            list.builds > 1 && list.builds < steps / 5,
            "{}",
            list.builds
        );
    }
}
