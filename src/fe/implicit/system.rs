//! The linear system of one Newton iteration: element tangents assembled into a sparse
//! matrix over every degree of freedom (2 per node: r, z), the rows and columns of
//! constrained ones replaced by the identity, solved by faer's sparse LU.
//!
//! LU, not Cholesky: the tangent of the objective (Hughes-Winget) update is not symmetric
//! away from the reference configuration (its geometric and rotational terms), so a
//! symmetric factorisation would not be the consistent tangent.

use crate::error::{Error, Result};
use faer::prelude::Solve;
use sprs::TriMat;

/// A sparse square matrix being assembled from 8 × 8 element blocks (N/m).
pub struct Assembly {
    tri: TriMat<f64>,
    constrained: Vec<bool>,
}

impl Assembly {
    /// An empty matrix over `constrained.len()` degrees of freedom; those marked get an
    /// identity row and column.
    pub fn new(constrained: Vec<bool>, blocks: usize) -> Self {
        let n = constrained.len();
        let mut tri = TriMat::with_capacity((n, n), 64 * blocks + n);
        for (d, &c) in constrained.iter().enumerate() {
            if c {
                tri.add_triplet(d, d, 1.0);
            }
        }
        Assembly { tri, constrained }
    }

    /// Adds the block `k` (N/m) of the quad with nodes `nodes` (row and column 2k + c).
    pub fn add(&mut self, nodes: &[u32; 4], k: &[[f64; 8]; 8]) {
        let dof = |i: usize| 2 * nodes[i / 2] as usize + i % 2;
        for i in 0..8 {
            let r = dof(i);
            if self.constrained[r] {
                continue;
            }
            for j in 0..8 {
                let c = dof(j);
                if !self.constrained[c] && k[i][j] != 0.0 {
                    self.tri.add_triplet(r, c, k[i][j]);
                }
            }
        }
    }

    /// Solves K d = `rhs` (N; zero on constrained rows), returning d (m). Fails with a
    /// numerical error when the matrix is singular (a body free to move rigidly).
    pub fn solve(self, rhs: &[f64]) -> Result<Vec<f64>> {
        let n = self.constrained.len();
        let csc = self.tri.to_csc::<usize>();
        let mut t = Vec::with_capacity(csc.nnz());
        for (v, (r, c)) in csc.iter() {
            t.push(faer::sparse::Triplet::new(r, c, *v));
        }
        let a = faer::sparse::SparseColMat::try_new_from_triplets(n, n, &t)
            .map_err(|e| Error::Numerical(format!("static tangent assembly failed: {e:?}")))?;
        let lu = a.sp_lu().map_err(|e| {
            Error::Numerical(format!(
                "static tangent singular ({e:?}): the body is free to move rigidly; hold it or \
                 put it in contact"
            ))
        })?;
        let mut b = faer::Mat::<f64>::zeros(n, 1);
        for (i, v) in rhs.iter().enumerate() {
            b[(i, 0)] = *v;
        }
        lu.solve_in_place(b.as_mut());
        let d: Vec<f64> = (0..n).map(|i| b[(i, 0)]).collect();
        if d.iter().any(|v| !v.is_finite()) {
            return Err(Error::Numerical(
                "static tangent singular: the Newton correction is not finite; hold the body or \
                 put it in contact"
                    .into(),
            ));
        }
        Ok(d)
    }
}
