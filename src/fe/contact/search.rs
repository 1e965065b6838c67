//! Contact search: which segments each node could touch.
//!
//! Two levels. A global test compares the bounding boxes of the slave nodes and the master
//! segments (inflated by the search margin): while they are apart, as in free flight, a step
//! costs one pass over the surface nodes and no contact work. When they overlap, a bucket grid
//! over the master segments lists, for every slave node, the segments whose inflated boxes hold
//! it. The lists stay valid until some node has moved half the margin since they were built
//! (then no node and segment can have approached by more than the margin).

use crate::fe::tensor::sub;

/// Axis-aligned box.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Aabb {
    /// Lower corner, m.
    pub min: [f64; 3],
    /// Upper corner, m.
    pub max: [f64; 3],
}

impl Aabb {
    /// The empty box.
    pub fn empty() -> Self {
        Aabb {
            min: [f64::INFINITY; 3],
            max: [f64::NEG_INFINITY; 3],
        }
    }

    /// Grows the box to hold `p`.
    pub fn grow(&mut self, p: [f64; 3]) {
        for (a, v) in p.into_iter().enumerate() {
            self.min[a] = self.min[a].min(v);
            self.max[a] = self.max[a].max(v);
        }
    }

    /// True when the boxes, each inflated by `margin` (m), overlap.
    pub fn overlaps(&self, o: &Aabb, margin: f64) -> bool {
        (0..3).all(|a| self.min[a] - margin <= o.max[a] && o.min[a] - margin <= self.max[a])
    }

    /// True when `p` lies in the box inflated by `margin`.
    pub fn contains(&self, p: [f64; 3], margin: f64) -> bool {
        (0..3).all(|a| p[a] >= self.min[a] - margin && p[a] <= self.max[a] + margin)
    }
}

/// Candidate lists of one slave–master pass, rebuilt on motion.
#[derive(Debug, Clone, Default)]
pub struct BucketSearch {
    /// Inflation of the segment boxes, m.
    margin: f64,
    /// Coordinates of the watched nodes when the lists were built.
    reference: Vec<[f64; 3]>,
    /// For each slave node, the master segments it could touch.
    candidates: Vec<Vec<u32>>,
    /// Whether `candidates` is valid.
    built: bool,
    /// Extra inflation of each segment's box, m (how deep a node may be behind it).
    depth: Vec<f64>,
    /// Every segment that appears in some candidate list (sorted, no repeats).
    active: Vec<u32>,
    /// Number of rebuilds so far (for tests and reports).
    pub rebuilds: usize,
}

impl BucketSearch {
    /// A search with box inflation `margin` (m, > 0).
    pub fn new(margin: f64) -> Self {
        BucketSearch {
            margin,
            ..Default::default()
        }
    }

    /// The same search with each segment's box further inflated by `depth[f]` (m): nodes that
    /// have penetrated up to that depth behind segment f are still found (and can be flagged).
    pub fn with_depths(mut self, depth: Vec<f64>) -> Self {
        self.depth = depth;
        self
    }

    /// The search margin, m.
    pub fn margin(&self) -> f64 {
        self.margin
    }

    /// The current candidate lists (valid after [`BucketSearch::candidates`]).
    pub fn lists(&self) -> &[Vec<u32>] {
        &self.candidates
    }

    /// The segments of the current candidate lists (valid after [`BucketSearch::candidates`]).
    pub fn active_segments(&self) -> &[u32] {
        &self.active
    }

    /// Forgets the lists (after a free-flight step they would be stale).
    pub fn invalidate(&mut self) {
        self.built = false;
    }

    /// Candidate segments (indices into `faces`) of every slave node, rebuilding when needed.
    ///
    /// `x`: all nodal coordinates (m); `slave`: slave node numbers; `faces`: master segments;
    /// `watched`: every node whose motion can invalidate the lists (slave and master nodes).
    pub fn candidates(
        &mut self,
        x: &[[f64; 3]],
        slave: &[u32],
        faces: &[[u32; 4]],
        watched: &[u32],
    ) -> &[Vec<u32>] {
        let stale = !self.built
            || watched.iter().zip(&self.reference).any(|(&g, r)| {
                let d = sub(x[g as usize], *r);
                d[0] * d[0] + d[1] * d[1] + d[2] * d[2] > 0.25 * self.margin * self.margin
            });
        if stale {
            self.rebuild(x, slave, faces, watched);
        }
        &self.candidates
    }

    fn rebuild(&mut self, x: &[[f64; 3]], slave: &[u32], faces: &[[u32; 4]], watched: &[u32]) {
        self.rebuilds += 1;
        self.reference = watched.iter().map(|&g| x[g as usize]).collect();
        let boxes: Vec<Aabb> = faces
            .iter()
            .enumerate()
            .map(|(f, q)| {
                let mut b = Aabb::empty();
                q.iter().for_each(|&g| b.grow(x[g as usize]));
                let d = self.depth.get(f).copied().unwrap_or(0.0);
                b.min = b.min.map(|v| v - d);
                b.max = b.max.map(|v| v + d);
                b
            })
            .collect();
        let mut all = Aabb::empty();
        let mut size: f64 = 0.0;
        for b in &boxes {
            all.grow(b.min);
            all.grow(b.max);
            size = size.max((0..3).map(|a| b.max[a] - b.min[a]).fold(0.0, f64::max));
        }
        // Cells about one inflated segment wide: each segment lands in a handful of cells.
        let cell = (size + 2.0 * self.margin).max(1e-300);
        let lo = all.min.map(|v| v - self.margin);
        let dims: [usize; 3] = [0, 1, 2].map(|a| {
            (((all.max[a] - all.min[a] + 2.0 * self.margin) / cell).floor() as usize + 1)
                .min(1 << 10)
        });
        let cell_of = |p: [f64; 3]| -> Option<[usize; 3]> {
            let mut c = [0usize; 3];
            for a in 0..3 {
                let f = ((p[a] - lo[a]) / cell).floor();
                if f < 0.0 || f >= dims[a] as f64 {
                    return None;
                }
                c[a] = f as usize;
            }
            Some(c)
        };
        let flat = |c: [usize; 3]| c[0] + dims[0] * (c[1] + dims[1] * c[2]);
        let mut grid: Vec<Vec<u32>> = vec![Vec::new(); dims[0] * dims[1] * dims[2]];
        for (f, b) in boxes.iter().enumerate() {
            let clamp = |p: [f64; 3]| {
                [0, 1, 2]
                    .map(|a| (((p[a] - lo[a]) / cell).floor().max(0.0) as usize).min(dims[a] - 1))
            };
            let c0 = clamp(b.min.map(|v| v - self.margin));
            let c1 = clamp(b.max.map(|v| v + self.margin));
            for i in c0[0]..=c1[0] {
                for j in c0[1]..=c1[1] {
                    for k in c0[2]..=c1[2] {
                        grid[flat([i, j, k])].push(f as u32);
                    }
                }
            }
        }
        self.candidates = slave
            .iter()
            .map(|&g| {
                let p = x[g as usize];
                match cell_of(p) {
                    Some(c) => grid[flat(c)]
                        .iter()
                        .copied()
                        .filter(|&f| boxes[f as usize].contains(p, self.margin))
                        .collect(),
                    None => Vec::new(),
                }
            })
            .collect();
        self.active = self.candidates.iter().flatten().copied().collect();
        self.active.sort_unstable();
        self.active.dedup();
        self.built = true;
    }
}

/// Bounding box of the nodes `g` at coordinates `x`.
pub fn bounding_box(x: &[[f64; 3]], g: &[u32]) -> Aabb {
    let mut b = Aabb::empty();
    g.iter().for_each(|&i| b.grow(x[i as usize]));
    b
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A flat grid of unit quads on z = 0, n x n.
    fn grid(n: u32) -> (Vec<[f64; 3]>, Vec<[u32; 4]>) {
        let mut x = Vec::new();
        for j in 0..=n {
            for i in 0..=n {
                x.push([i as f64, j as f64, 0.0]);
            }
        }
        let id = |i: u32, j: u32| i + (n + 1) * j;
        let mut f = Vec::new();
        for j in 0..n {
            for i in 0..n {
                f.push([id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
            }
        }
        (x, f)
    }

    #[test]
    fn bucket_candidates_equal_brute_force() {
        let (mut x, faces) = grid(8);
        let nm = x.len() as u32;
        // Slave nodes scattered above the grid, some far away.
        let pts = [
            [0.5, 0.5, 0.1],
            [3.99, 4.01, -0.05],
            [7.9, 0.2, 0.2],
            [20.0, 3.0, 0.0],
            [4.0, 4.0, 5.0],
        ];
        x.extend(pts);
        let slave: Vec<u32> = (nm..nm + pts.len() as u32).collect();
        let watched: Vec<u32> = (0..x.len() as u32).collect();
        let mut s = BucketSearch::new(0.25);
        let c = s.candidates(&x, &slave, &faces, &watched).to_vec();
        for (k, &g) in slave.iter().enumerate() {
            let mut brute: Vec<u32> = (0..faces.len() as u32)
                .filter(|&f| bounding_box(&x, &faces[f as usize]).contains(x[g as usize], 0.25))
                .collect();
            let mut got = c[k].clone();
            brute.sort_unstable();
            got.sort_unstable();
            assert_eq!(got, brute, "slave {k}");
        }
        assert_eq!(c[1].len(), 4, "a node at a grid vertex sees its four quads");
        assert!(c[3].is_empty() && c[4].is_empty());
    }

    #[test]
    fn lists_are_rebuilt_only_after_enough_motion() {
        let (mut x, faces) = grid(2);
        x.push([0.5, 0.5, 0.3]);
        let slave = [x.len() as u32 - 1];
        let watched: Vec<u32> = (0..x.len() as u32).collect();
        let mut s = BucketSearch::new(0.4);
        s.candidates(&x, &slave, &faces, &watched);
        x[9][2] -= 0.1; // less than half the margin
        s.candidates(&x, &slave, &faces, &watched);
        assert_eq!(s.rebuilds, 1);
        x[9][0] += 0.5; // more than half the margin: rebuilt, now over the next quad too
        let c = s.candidates(&x, &slave, &faces, &watched).to_vec();
        assert_eq!(s.rebuilds, 2);
        assert_eq!(c[0].len(), 2);
    }

    #[test]
    fn inflated_boxes_overlap_test() {
        let a = Aabb {
            min: [0.0; 3],
            max: [1.0; 3],
        };
        let b = Aabb {
            min: [1.5, 0.0, 0.0],
            max: [2.0, 1.0, 1.0],
        };
        assert!(!a.overlaps(&b, 0.4));
        assert!(a.overlaps(&b, 0.6));
    }
}
