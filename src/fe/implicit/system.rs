//! The linear system of one Newton iteration: element tangents assembled into a sparse
//! matrix over every degree of freedom (2 per node: r, z), the rows and columns of
//! constrained ones replaced by the identity (their known corrections moved to the
//! right-hand side), solved with faer.
//!
//! The tangent of the objective (Hughes-Winget) update is not symmetric away from the
//! reference configuration (its geometric and rotational terms), but nearly so: its skew
//! part is 1e-4 to 3e-2 of the symmetric one. The system is therefore solved by iterative
//! refinement on the sparse LDLᵀ factorisation of its symmetric part, x ← x + S⁻¹(b − K x),
//! each sweep gaining about three digits, to a residual of 1e-10 of the right-hand side:
//! the consistent tangent's solution, at a third of the sparse LU's cost (LDLᵀ orders by
//! minimum degree and does not pivot). A sweep that does not halve the residual (a skew
//! part too large, a zero pivot) hands the system to faer's sparse LU with partial
//! pivoting.
//!
//! The sparsity pattern (every element block and the diagonal) is fixed by the mesh, so both
//! orderings and symbolic factorisations ([`Pattern`]) are computed once per solver; a
//! constraint only changes values. A solve asked to a modest tolerance (Newton's last
//! iterations, whose tangents have settled) first refines on the last numeric LDLᵀ where it
//! was of the same constraints, and factorises afresh only when a sweep on it does not gain
//! ten (`results.json` counts `factorisations` beside `newton_iterations`). Both
//! factorisations are supernodal (dense blocks for the separators a 2D mesh's elimination
//! creates) and sequential, so a loop's numbers do not depend on the thread count.

use crate::error::{Error, Result};
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::ldlt::factor::LdltRegularization;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, LdltRef, SymbolicCholesky,
    SymmetricOrdering,
};
use faer::sparse::linalg::lu::{factorize_symbolic_lu, LuSymbolicParams, NumericLu, SymbolicLu};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::{Pair, SparseColMatRef, SymbolicSparseColMat};
use faer::{Conj, Mat, MatMut, Par, Side};
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
    /// Position in the compressed values of each position's transpose.
    transpose: Vec<usize>,
    /// The symbolic LDLᵀ of the pattern (its symmetric part is factorised).
    ldlt: SymbolicCholesky<usize>,
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
    /// The symmetric part's values and its LDLᵀ factor's.
    symmetric: Vec<f64>,
    factor: Vec<f64>,
    /// The constrained degrees of freedom of the matrix `factor` holds the LDLᵀ of (`None`:
    /// it holds none that can be used).
    factored_for: Option<Vec<bool>>,
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
        let transpose = (0..symbolic.ncols())
            .flat_map(|j| (col_ptr[j]..col_ptr[j + 1]).map(move |k| (j, k)))
            .map(|(j, k)| {
                let i = row_idx[k];
                let rows = &row_idx[col_ptr[i]..col_ptr[i + 1]];
                rows.binary_search(&j)
                    .map(|at| col_ptr[i] + at)
                    .map_err(|_| fail("an unsymmetric pattern".into()))
            })
            .collect::<Result<Vec<usize>>>()?;
        let ldlt = factorize_symbolic_cholesky(
            symbolic.as_ref(),
            Side::Lower,
            SymmetricOrdering::Amd,
            CholeskySymbolicParams {
                supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
                ..Default::default()
            },
        )
        .map_err(|e| fail(format!("{e:?}")))?;
        let scratch = lu
            .factorize_numeric_lu_scratch::<f64>(Par::Seq, Default::default())
            .or(lu.solve_in_place_scratch::<f64>(MAX_COLUMNS, Par::Seq))
            .or(ldlt.factorize_numeric_ldlt_scratch::<f64>(Par::Seq, Default::default()))
            .or(ldlt.solve_in_place_scratch::<f64>(MAX_COLUMNS, Par::Seq));
        let work = Workspace {
            numeric: NumericLu::new(),
            scratch: MemBuffer::try_new(scratch).map_err(|_| fail("out of memory".into()))?,
            values: vec![0.0; row_idx.len()],
            symmetric: vec![0.0; row_idx.len()],
            factor: vec![0.0; ldlt.len_val()],
            factored_for: None,
        };
        Ok(Pattern {
            dofs: n,
            quads: quads.to_vec(),
            symbolic,
            slot,
            lu,
            transpose,
            ldlt,
            work: Mutex::new(work),
            factorisations: AtomicU64::new(0),
        })
    }

    /// Degrees of freedom (2 per node).
    pub fn dofs(&self) -> usize {
        self.dofs
    }

    /// Numeric factorisations so far (an LDLᵀ per [`Pattern::solve`] that the last one does
    /// not serve, and an LU where refinement on it failed; including those of increments
    /// later cut or solved again).
    pub fn factorisations(&self) -> u64 {
        self.factorisations.load(Ordering::Relaxed)
    }

    /// Solves K d = `rhs` for the element tangents `blocks` (N/m, one 8 × 8 block per quad,
    /// in mesh order) with the rows of the `constrained` degrees of freedom replaced by the
    /// identity; `rhs` holds the free rows' residual forces (N) and the constrained rows'
    /// prescribed corrections (m). Returns d (m), its residual at most `tol` (clamped to
    /// [`REFINE_TOL`]..=[`LOOSEST_TOL`]) of the right-hand side's largest entry. Fails with a numerical
    /// error when the matrix is singular (a body free to move rigidly).
    pub fn solve(
        &self,
        blocks: &[[[f64; 8]; 8]],
        constrained: &[bool],
        rhs: &[f64],
        tol: f64,
    ) -> Result<Vec<f64>> {
        let mut d = self.solve_columns(blocks, constrained, &[rhs], tol)?;
        Ok(d.swap_remove(0))
    }

    /// [`Pattern::solve`] for up to [`MAX_COLUMNS`] right-hand sides with one factorisation
    /// (each as `rhs` there); returns one solution per column, in order.
    pub fn solve_columns(
        &self,
        blocks: &[[[f64; 8]; 8]],
        constrained: &[bool],
        columns: &[&[f64]],
        tol: f64,
    ) -> Result<Vec<Vec<f64>>> {
        let tol = tol.clamp(REFINE_TOL, LOOSEST_TOL);
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
            symmetric,
            factor,
            factored_for,
        } = &mut *work;
        // The constrained rows and columns become the identity; the columns' known
        // corrections move to the right-hand sides, so the free block keeps the tangent's
        // near symmetry.
        let mut b = Mat::<f64>::zeros(n, columns.len());
        for (j, rhs) in columns.iter().enumerate() {
            for (i, v) in rhs.iter().enumerate() {
                b[(i, j)] = *v;
            }
        }
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
                let (di, free_i) = (dof(q, i), !constrained[dof(q, i)]);
                for j in 0..8 {
                    let dj = dof(q, j);
                    let kept = free_i && !constrained[dj];
                    put(64 * e + 8 * i + j, if kept { k[i][j] } else { 0.0 });
                    if free_i && constrained[dj] {
                        for (c, rhs) in columns.iter().enumerate() {
                            b[(di, c)] -= k[i][j] * rhs[dj];
                        }
                    }
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
        let a = SparseColMatRef::new(self.symbolic.as_ref(), values);
        let stack = MemStack::new(scratch);
        // The last factorisation, where it was of the same constraints, often still solves
        // the new tangent (an increment's later iterations change few quads' tangents): it
        // is kept when every refinement sweep on it gains REUSE_GAIN.
        let reused = match factored_for {
            Some(held) if tol <= REUSE_BELOW && held.as_slice() == constrained => {
                let ldlt = LdltRef::new(&self.ldlt, factor);
                refine(a, &b, tol, REUSE_GAIN, |m| {
                    ldlt.solve_in_place_with_conj(Conj::No, m, Par::Seq, stack)
                })
            }
            _ => None,
        };
        let solved = match reused {
            Some(x) => Some(x),
            None => {
                self.factorisations.fetch_add(1, Ordering::Relaxed);
                *factored_for = None;
                for (k, s) in symmetric.iter_mut().enumerate() {
                    *s = 0.5 * (a.val()[k] + a.val()[self.transpose[k]]);
                }
                let sym = SparseColMatRef::new(self.symbolic.as_ref(), symmetric);
                match self.ldlt.factorize_numeric_ldlt(
                    factor,
                    sym,
                    Side::Lower,
                    LdltRegularization::default(),
                    Par::Seq,
                    stack,
                    Default::default(),
                ) {
                    Ok(ldlt) => refine(a, &b, tol, FRESH_GAIN, |m| {
                        ldlt.solve_in_place_with_conj(Conj::No, m, Par::Seq, stack)
                    }),
                    Err(_) => None,
                }
                .inspect(|_| *factored_for = Some(constrained.to_vec()))
            }
        };
        let x = match solved {
            Some(x) => x,
            None => {
                self.factorisations.fetch_add(1, Ordering::Relaxed);
                let lu = self
                    .lu
                    .factorize_numeric_lu(numeric, a, Par::Seq, stack, Default::default())
                    .map_err(|e| singular(format!("{e:?}")))?;
                let mut x = b.clone();
                lu.solve_in_place_with_conj(Conj::No, x.as_mut(), Par::Seq, stack);
                x
            }
        };
        let d: Vec<Vec<f64>> = (0..columns.len())
            .map(|j| (0..n).map(|i| x[(i, j)]).collect())
            .collect();
        if d.iter().flatten().any(|v| !v.is_finite()) {
            return Err(singular("a correction that is not finite".into()));
        }
        Ok(d)
    }
}

/// r ← r − `a` x for a compressed-column `a` (n × n) and columns x, r of length n.
fn subtract_product(a: SparseColMatRef<'_, usize, f64>, x: &[f64], r: &mut [f64]) {
    let (col_ptr, row_idx, val) = (a.col_ptr(), a.row_idx(), a.val());
    for (j, &xj) in x.iter().enumerate() {
        let span = col_ptr[j]..col_ptr[j + 1];
        for (&i, &v) in row_idx[span.clone()].iter().zip(&val[span]) {
            r[i] -= v * xj;
        }
    }
}

/// The largest magnitude in `v`, NaN if any entry is.
fn largest(v: &[f64]) -> f64 {
    v.iter().fold(0.0, |m: f64, x| {
        if x.is_nan() || m.is_nan() {
            f64::NAN
        } else {
            m.max(x.abs())
        }
    })
}

/// Most refinement sweeps of [`refine`] before it gives up.
const MAX_SWEEPS: usize = 40;

/// The least gain of each refinement sweep on a fresh factorisation of the tangent's
/// symmetric part (it must halve the residual).
const FRESH_GAIN: f64 = 0.5;

/// The least gain of each refinement sweep on an earlier factorisation: a tenth, so that a
/// kept factor reaches [`REFINE_TOL`] in at most ten sweeps, each about a tenth of the cost
/// of the factorisation it saves.
const REUSE_GAIN: f64 = 0.1;

/// The tolerance at or below which a solve tries the last factorisation first: those asked
/// of Newton's last iterations (relative residual 1e-2 or less), whose tangents have
/// settled; earlier ones change too many quads' tangents for it to hold.
const REUSE_BELOW: f64 = 1e-3;

/// The least residual a column is solved to, relative to its right-hand side's largest
/// entry: an inexact Newton step's forcing term far below the relative residuals Newton
/// converges to (1e-8).
pub const REFINE_TOL: f64 = 1e-10;

/// The loosest residual a column is solved to, relative to its right-hand side's largest
/// entry: a Newton step far from the solution is still solved to two digits.
pub const LOOSEST_TOL: f64 = 1e-2;

/// Solves `a` x = `b` (n × n, n × columns) by iterative refinement with `precondition`, an
/// exact solve in place with a nearby matrix M: x ← x + M⁻¹(b − a x), until every column's
/// residual is below `tol` of its right-hand side. `None` when a sweep does not
/// bring the worst column's relative residual below `gain` times the last sweep's (M too
/// far from `a`) or after [`MAX_SWEEPS`].
fn refine(
    a: SparseColMatRef<'_, usize, f64>,
    b: &Mat<f64>,
    tol: f64,
    gain: f64,
    mut precondition: impl FnMut(MatMut<'_, f64>),
) -> Option<Mat<f64>> {
    let scale: Vec<f64> = (0..b.ncols())
        .map(|c| largest(b.col_as_slice(c)).max(f64::MIN_POSITIVE))
        .collect();
    let mut x = b.clone();
    precondition(x.as_mut());
    let mut last = f64::INFINITY;
    for _ in 0..MAX_SWEEPS {
        let mut r = b.clone();
        for c in 0..b.ncols() {
            subtract_product(a, x.col_as_slice(c), r.col_as_slice_mut(c));
        }
        let ratios: Vec<f64> = (0..b.ncols())
            .map(|c| largest(r.col_as_slice(c)) / scale[c])
            .collect();
        let worst = largest(&ratios);
        if worst <= tol {
            return Some(x);
        }
        // Not gained, or not a number (a zero pivot): M is too far from `a`.
        if worst.is_nan() || worst >= gain * last {
            return None;
        }
        last = worst;
        precondition(r.as_mut());
        x += r;
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{DMatrix, DVector};

    /// A 3 × 2 grid of quads over 12 nodes.
    fn grid() -> (usize, Vec<[u32; 4]>) {
        let node = |i: u32, j: u32| j * 4 + i;
        let quads = (0..2)
            .flat_map(|j| (0..3).map(move |i| (i, j)))
            .map(|(i, j)| {
                [
                    node(i, j),
                    node(i + 1, j),
                    node(i + 1, j + 1),
                    node(i, j + 1),
                ]
            })
            .collect();
        (12, quads)
    }

    /// Element blocks with a positive definite symmetric part and a skew part of relative
    /// size `skew` (deterministic pseudo-random entries).
    fn blocks(count: usize, skew: f64) -> Vec<[[f64; 8]; 8]> {
        let mut seed = 12345u64;
        let mut draw = move || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        (0..count)
            .map(|_| {
                let a: [[f64; 8]; 8] = std::array::from_fn(|_| std::array::from_fn(|_| draw()));
                let n: [[f64; 8]; 8] = std::array::from_fn(|_| std::array::from_fn(|_| draw()));
                std::array::from_fn(|i| {
                    std::array::from_fn(|j| {
                        let spd: f64 = (0..8).map(|k| a[k][i] * a[k][j]).sum::<f64>()
                            + if i == j { 0.5 } else { 0.0 };
                        1e9 * (spd + skew * (n[i][j] - n[j][i]))
                    })
                })
            })
            .collect()
    }

    /// The dense solution of the same system: free rows K d = r, constrained rows d = r.
    fn dense(
        nodes: usize,
        quads: &[[u32; 4]],
        k: &[[[f64; 8]; 8]],
        c: &[bool],
        r: &[f64],
    ) -> Vec<f64> {
        let n = 2 * nodes;
        let mut a = DMatrix::<f64>::zeros(n, n);
        for (q, b) in quads.iter().zip(k) {
            for i in 0..8 {
                for j in 0..8 {
                    a[(dof(q, i), dof(q, j))] += b[i][j];
                }
            }
        }
        for d in (0..n).filter(|&d| c[d]) {
            a.row_mut(d).fill(0.0);
            a[(d, d)] = 1.0;
        }
        let x = a.lu().solve(&DVector::from_column_slice(r)).unwrap();
        x.iter().copied().collect()
    }

    fn check(skew: f64, factorisations: u64) {
        let (nodes, quads) = grid();
        let k = blocks(quads.len(), skew);
        let c: Vec<bool> = (0..2 * nodes).map(|d| d < 2 || d == 2 * 11 + 1).collect();
        let r: Vec<f64> = (0..2 * nodes)
            .map(|d| {
                if c[d] {
                    1e-6 * (d as f64 + 1.0)
                } else {
                    50.0 - 7.0 * d as f64
                }
            })
            .collect();
        let p = Pattern::new(nodes, &quads).unwrap();
        let x = p.solve(&k, &c, &r, REFINE_TOL).unwrap();
        let want = dense(nodes, &quads, &k, &c, &r);
        let size = want.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for (d, (a, b)) in x.iter().zip(&want).enumerate() {
            assert!((a - b).abs() <= 1e-11 * size, "dof {d}: {a} vs {b}");
        }
        assert_eq!(p.factorisations(), factorisations);
    }

    /// A nearly symmetric tangent is solved by refinement on the LDLᵀ of its symmetric part
    /// (one factorisation) to the dense LU's solution, constrained values included.
    #[test]
    fn a_nearly_symmetric_system_is_refined_to_the_dense_solution() {
        check(1e-2, 1);
    }

    /// A second solve of the same constraints at a modest tolerance refines on the first
    /// factorisation when its tangent is near the first (a few blocks changed by 1e-3) and
    /// factorises again when it is not (every block doubled): both reach the dense solution.
    #[test]
    fn a_near_tangent_reuses_the_last_factorisation_and_a_far_one_does_not() {
        let (nodes, quads) = grid();
        let k = blocks(quads.len(), 1e-3);
        let c: Vec<bool> = (0..2 * nodes).map(|d| d < 2 || d == 2 * 11 + 1).collect();
        let r: Vec<f64> = (0..2 * nodes)
            .map(|d| if c[d] { 0.0 } else { 10.0 + d as f64 })
            .collect();
        let p = Pattern::new(nodes, &quads).unwrap();
        p.solve(&k, &c, &r, REFINE_TOL).unwrap();
        let mut near = k.clone();
        near[2] = near[2].map(|row| row.map(|v| v * (1.0 + 1e-3)));
        let tol = 1e-6;
        let solved = |k: &[[[f64; 8]; 8]]| {
            let x = p.solve(k, &c, &r, tol).unwrap();
            let want = dense(nodes, &quads, k, &c, &r);
            let size = want.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            for (d, (a, b)) in x.iter().zip(&want).enumerate() {
                assert!((a - b).abs() <= 1e-4 * size, "dof {d}: {a} vs {b}");
            }
        };
        solved(&near);
        assert_eq!(p.factorisations(), 1, "the near tangent reuses the factor");
        let far: Vec<_> = k
            .iter()
            .map(|b| b.map(|row| row.map(|v| 2.0 * v)))
            .collect();
        solved(&far);
        assert_eq!(p.factorisations(), 2, "the far tangent is factorised");
    }

    /// A tangent far from symmetric goes to the sparse LU (a second factorisation) and is
    /// still solved exactly.
    #[test]
    fn a_far_from_symmetric_system_falls_back_to_lu() {
        check(3.0, 2);
    }
}
