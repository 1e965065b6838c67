//! Cell-list contact detection: balls are binned into cubic cells at least one largest
//! diameter wide, so only balls in the same or neighbouring cells can touch.

use nalgebra::Vector3;

/// Candidate ball pairs (i < j, ascending) whose cells are neighbours. `positions` in m,
/// `origin` the grid's low corner and `extent` its size (m), `cell` ≥ the largest diameter (m).
/// Balls outside the grid are binned into its border cells, so no pair is lost.
pub fn candidate_pairs(
    positions: &[Vector3<f64>],
    origin: Vector3<f64>,
    extent: Vector3<f64>,
    cell: f64,
) -> Vec<(usize, usize)> {
    let mut dims: [usize; 3] =
        std::array::from_fn(|k| ((extent[k] / cell).floor() as usize).clamp(1, 1 << 10));
    // Wider cells than needed are still correct: keep the grid near the number of balls.
    while dims.iter().product::<usize>() > 8 * positions.len() + 27 {
        let k = (0..3).max_by_key(|&k| dims[k]).unwrap_or(0);
        dims[k] = dims[k].div_ceil(2);
    }
    let index = |p: &Vector3<f64>| -> [usize; 3] {
        std::array::from_fn(|k| {
            let c = ((p[k] - origin[k]) / extent[k] * dims[k] as f64).floor();
            if c.is_finite() {
                (c.max(0.0) as usize).min(dims[k] - 1)
            } else {
                0
            }
        })
    };
    let flat = |c: [usize; 3]| (c[2] * dims[1] + c[1]) * dims[0] + c[0];
    let mut cells: Vec<Vec<usize>> = vec![Vec::new(); dims[0] * dims[1] * dims[2]];
    let binned: Vec<[usize; 3]> = positions.iter().map(index).collect();
    for (i, c) in binned.iter().enumerate() {
        cells[flat(*c)].push(i);
    }
    let mut pairs = Vec::new();
    for (i, c) in binned.iter().enumerate() {
        let range = |k: usize| c[k].saturating_sub(1)..=(c[k] + 1).min(dims[k] - 1);
        for z in range(2) {
            for y in range(1) {
                for x in range(0) {
                    pairs.extend(
                        cells[flat([x, y, z])]
                            .iter()
                            .filter(|&&j| j > i)
                            .map(|&j| (i, j)),
                    );
                }
            }
        }
    }
    pairs.sort_unstable();
    pairs
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;

    /// The next number in [0, 1) of a 64-bit linear congruential generator at `seed`.
    pub(crate) fn uniform(seed: &mut u64) -> f64 {
        *seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (*seed >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Asserts that the sorted pairs `found` hold every pair of centres `p` closer than `d` (m),
    /// as brute force finds them.
    pub(crate) fn assert_holds_touching(p: &[Vector3<f64>], d: f64, found: &[(usize, usize)]) {
        for i in 0..p.len() {
            for j in i + 1..p.len() {
                if (p[i] - p[j]).norm() < d {
                    assert!(found.binary_search(&(i, j)).is_ok(), "{i} {j}");
                }
            }
        }
    }

    /// Every touching pair of a random packing is found, as brute force finds it.
    #[test]
    fn finds_every_touching_pair_that_brute_force_finds() {
        let mut seed = 12345u64;
        let mut rnd = || uniform(&mut seed);
        let extent = Vector3::new(0.1, 0.04, 0.035);
        let d = 0.02;
        for _ in 0..20 {
            let p: Vec<Vector3<f64>> = (0..40)
                .map(|_| Vector3::new(rnd() * 0.12 - 0.01, rnd() * 0.04, rnd() * 0.035))
                .collect();
            let found = candidate_pairs(&p, Vector3::zeros(), extent, d);
            assert_holds_touching(&p, d, &found);
            assert!(found.len() < 40 * 39 / 2);
        }
    }
}
