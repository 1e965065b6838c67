//! The linear system of one Newton iteration: element tangents assembled into a sparse
//! matrix over every degree of freedom (2 per node: r, z), the rows and columns of
//! constrained ones replaced by the identity, solved by faer's sparse LU.
//!
//! The sparsity pattern (every element block and the diagonal) is fixed by the mesh, so its
//! ordering and symbolic factorisation ([`Pattern`]) are computed once per solver; a
//! constraint only changes values. The factorisation is supernodal (dense blocks for the
//! separators a 2D mesh's elimination creates) and sequential, so a loop's numbers do not
//! depend on the thread count. LU, not Cholesky: the tangent of the objective
//! (Hughes-Winget) update is not symmetric away from the reference configuration (its
//! geometric and rotational terms), so a symmetric factorisation would not be the
//! consistent tangent.

use crate::error::{Error, Result};
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::lu::{factorize_symbolic_lu, LuSymbolicParams, NumericLu, SymbolicLu};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::{Pair, SparseColMatRef, SymbolicSparseColMat};
use faer::{Conj, Mat, Par};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Mutex;

/// The fixed structure of a mesh's tangent: the entries' positions in the compressed matrix,
/// the symbolic LU, and the memory every numeric factorisation reuses.
pub struct Pattern {
    dofs: usize,
    quads: Vec<[u32; 4]>,
    symbolic: SymbolicSparseColMat<usize>,
    /// Position in the compressed values of each entry (the quads' 8 × 8 blocks in mesh order,
    /// then the diagonal), with [`FIRST`] set on the first entry of each position.
    slot: Vec<usize>,
    lu: SymbolicLu<usize>,
    work: Mutex<Workspace>,
    /// Numeric factorisations so far, by every solver sharing this pattern.
    factorisations: AtomicU64,
}

/// The most right-hand sides one factorisation solves ([`Pattern::solve_columns`]).
pub const MAX_COLUMNS: usize = 2;

/// Marks the first of the entries summed into one position.
const FIRST: usize = 1 << (usize::BITS - 1);

/// The numeric factorisation, its scratch memory and the compressed values, kept from one
/// solve to the next (the pattern never changes, so neither do their sizes).
struct Workspace {
    numeric: NumericLu<usize, f64>,
    scratch: MemBuffer,
    values: Vec<f64>,
}

/// The degree of freedom of entry `i` (0..8: node i / 2, component i % 2) of quad `q`.
fn dof(q: &[u32; 4], i: usize) -> usize {
    2 * q[i / 2] as usize + i % 2
}

impl Pattern {
    /// The pattern of `quads` over `nodes` nodes. Fails if faer cannot build it (memory).
    pub fn new(nodes: usize, quads: &[[u32; 4]]) -> Result<Self> {
        let n = 2 * nodes;
        let mut idx = Vec::with_capacity(64 * quads.len() + n);
        for q in quads {
            for i in 0..8 {
                for j in 0..8 {
                    idx.push(Pair::new(dof(q, i), dof(q, j)));
                }
            }
        }
        idx.extend((0..n).map(|d| Pair::new(d, d)));
        let fail = |e: String| Error::Numerical(format!("static tangent pattern: {e}"));
        let (symbolic, _) = SymbolicSparseColMat::try_new_from_indices(n, n, &idx)
            .map_err(|e| fail(format!("{e:?}")))?;
        let (col_ptr, row_idx) = (symbolic.col_ptr(), symbolic.row_idx());
        let mut seen = vec![false; row_idx.len()];
        let slot = idx
            .iter()
            .map(|p| {
                let rows = &row_idx[col_ptr[p.col]..col_ptr[p.col + 1]];
                let at = rows.binary_search(&p.row);
                let k = col_ptr[p.col] + at.map_err(|_| fail("an entry left out".into()))?;
                let first = !std::mem::replace(&mut seen[k], true);
                Ok(if first { k | FIRST } else { k })
            })
            .collect::<Result<Vec<usize>>>()?;
        let params = LuSymbolicParams {
            supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
            ..Default::default()
        };
        let lu =
            factorize_symbolic_lu(symbolic.as_ref(), params).map_err(|e| fail(format!("{e:?}")))?;
        let scratch = lu
            .factorize_numeric_lu_scratch::<f64>(Par::Seq, Default::default())
            .or(lu.solve_in_place_scratch::<f64>(MAX_COLUMNS, Par::Seq));
        let work = Workspace {
            numeric: NumericLu::new(),
            scratch: MemBuffer::try_new(scratch).map_err(|_| fail("out of memory".into()))?,
            values: vec![0.0; row_idx.len()],
        };
        Ok(Pattern {
            dofs: n,
            quads: quads.to_vec(),
            symbolic,
            slot,
            lu,
            work: Mutex::new(work),
            factorisations: AtomicU64::new(0),
        })
    }

    /// Degrees of freedom (2 per node).
    pub fn dofs(&self) -> usize {
        self.dofs
    }

    /// Numeric factorisations so far (every [`Pattern::solve`], including those of
    /// increments later cut or solved again).
    pub fn factorisations(&self) -> u64 {
        self.factorisations.load(Ordering::Relaxed)
    }

    /// Solves K d = `rhs` for the element tangents `blocks` (N/m, one 8 × 8 block per quad,
    /// in mesh order) with the rows of the `constrained` degrees of freedom replaced by the
    /// identity; `rhs` holds the free rows' residual forces (N) and the constrained rows'
    /// prescribed corrections (m). Returns d (m). Fails with a numerical error when the
    /// matrix is singular (a body free to move rigidly).
    pub fn solve(
        &self,
        blocks: &[[[f64; 8]; 8]],
        constrained: &[bool],
        rhs: &[f64],
    ) -> Result<Vec<f64>> {
        let mut d = self.solve_columns(blocks, constrained, &[rhs])?;
        Ok(d.swap_remove(0))
    }

    /// [`Pattern::solve`] for up to [`MAX_COLUMNS`] right-hand sides with one factorisation
    /// (each as `rhs` there); returns one solution per column, in order.
    pub fn solve_columns(
        &self,
        blocks: &[[[f64; 8]; 8]],
        constrained: &[bool],
        columns: &[&[f64]],
    ) -> Result<Vec<Vec<f64>>> {
        let n = self.dofs;
        if columns.is_empty() || columns.len() > MAX_COLUMNS {
            return Err(Error::invalid(
                "static.columns",
                columns.len(),
                format!("1 to {MAX_COLUMNS} right-hand sides"),
            ));
        }
        let mut work = self.work.lock().unwrap_or_else(|e| e.into_inner());
        let Workspace {
            numeric,
            scratch,
            values,
        } = &mut *work;
        // Each entry into its position, summed in entry order (the first one assigned).
        let mut put = |t: usize, v: f64| {
            let s = self.slot[t];
            if s & FIRST != 0 {
                values[s & !FIRST] = v;
            } else {
                values[s] += v;
            }
        };
        for (e, (q, k)) in self.quads.iter().zip(blocks).enumerate() {
            for i in 0..8 {
                let free = !constrained[dof(q, i)];
                for j in 0..8 {
                    put(64 * e + 8 * i + j, if free { k[i][j] } else { 0.0 });
                }
            }
        }
        let diagonal = 64 * self.quads.len();
        for (d, &c) in constrained.iter().enumerate() {
            put(diagonal + d, if c { 1.0 } else { 0.0 });
        }
        let singular = |why: String| {
            Error::Numerical(format!(
                "static tangent singular ({why}): the body is free to move rigidly; hold it or \
                 put it in contact"
            ))
        };
        self.factorisations.fetch_add(1, Ordering::Relaxed);
        let a = SparseColMatRef::new(self.symbolic.as_ref(), values);
        let stack = MemStack::new(scratch);
        let lu = self
            .lu
            .factorize_numeric_lu(numeric, a, Par::Seq, stack, Default::default())
            .map_err(|e| singular(format!("{e:?}")))?;
        let mut b = Mat::<f64>::zeros(n, columns.len());
        for (j, rhs) in columns.iter().enumerate() {
            for (i, v) in rhs.iter().enumerate() {
                b[(i, j)] = *v;
            }
        }
        lu.solve_in_place_with_conj(Conj::No, b.as_mut(), Par::Seq, stack);
        let d: Vec<Vec<f64>> = (0..columns.len())
            .map(|j| (0..n).map(|i| b[(i, j)]).collect())
            .collect();
        if d.iter().flatten().any(|v| !v.is_finite()) {
            return Err(singular("a correction that is not finite".into()));
        }
        Ok(d)
    }
}
