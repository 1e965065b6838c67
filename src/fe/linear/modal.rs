//! The linear (implicit) path: small-strain stiffness K and consistent mass M assembled as
//! sparse matrices (sprs triplets → CSC), and the lowest free-vibration modes K φ = ω² M φ by
//! shift-invert Lanczos with a sparse LU of K − σM (faer). It checks element stiffness against
//! closed forms (Lamb's sphere frequencies) independently of the time integrator, and serves
//! quasi-static checks (solve K u = f with the same assembly).
//!
//! K uses the same element operators as the explicit kernels on the reference configuration:
//! the one-point hex's mean-gradient B plus its hourglass stiffness k Σ_α γ_α γ_αᵀ, or the
//! B-bar hex's 2x2x2 operator with mean-dilatation volumetric part.

use crate::error::{Error, Result};
use crate::fe::{
    elements::hex_bbar::gauss_gradients,
    elements::hex_one_point::{hourglass_gammas, hourglass_stiffness, mean_gradient},
    elements::shape::{natural_derivatives, shape_functions, spatial_gradients},
    model::{Formulation, Model},
};
use faer::prelude::Solve;
use sprs::{CsMat, TriMat};

/// Sparse linear system of a model: free DOFs only (symmetry-constrained components removed).
#[derive(Debug, Clone)]
pub struct LinearSystem {
    /// Stiffness, N/m (n_free x n_free, CSC, symmetric).
    pub stiffness: CsMat<f64>,
    /// Consistent mass, kg (n_free x n_free, CSC, symmetric).
    pub mass: CsMat<f64>,
    /// Per node and component: index of the free DOF, or `usize::MAX` when held at zero.
    pub dof: Vec<[usize; 3]>,
}

/// One free-vibration mode.
#[derive(Debug, Clone)]
pub struct Mode {
    /// Angular frequency ω, rad/s.
    pub omega: f64,
    /// Nodal mode shape (m per unit modal amplitude), mass-normalised: φᵀ M φ = 1.
    pub shape: Vec<[f64; 3]>,
    /// Relative residual ‖K φ − ω² M φ‖ / ‖K φ‖.
    pub residual: f64,
}

/// Element stiffness (24x24, DOF 3I + i) of a hexahedron on coordinates `x` (m).
pub fn element_stiffness(
    x: &[[f64; 3]; 8],
    formulation: Formulation,
    lambda: f64,
    shear: f64,
    hourglass: f64,
) -> [[f64; 24]; 24] {
    let mut k = [[0.0; 24]; 24];
    // ε:C:ε' = λ tr ε tr ε' + 2G ε:ε' for strain operators given per DOF as 3x3 matrices.
    let mut add_point = |eps: &[[[f64; 3]; 3]; 24], w: f64| {
        for a in 0..24 {
            let ta = eps[a][0][0] + eps[a][1][1] + eps[a][2][2];
            for b in a..24 {
                let tb = eps[b][0][0] + eps[b][1][1] + eps[b][2][2];
                let mut dd = 0.0;
                for r in 0..3 {
                    for c in 0..3 {
                        dd += eps[a][r][c] * eps[b][r][c];
                    }
                }
                let v = w * (lambda * ta * tb + 2.0 * shear * dd);
                k[a][b] += v;
                if a != b {
                    k[b][a] += v;
                }
            }
        }
    };
    let sym = |i: usize, g: [f64; 3]| {
        let mut e = [[0.0; 3]; 3];
        for c in 0..3 {
            e[i][c] += 0.5 * g[c];
            e[c][i] += 0.5 * g[c];
        }
        e
    };
    match formulation {
        Formulation::OnePoint => {
            let (v, b) = mean_gradient(x);
            let eps: [[[f64; 3]; 3]; 24] = std::array::from_fn(|d| sym(d % 3, b[d / 3]));
            add_point(&eps, v);
            if hourglass > 0.0 {
                let gam = hourglass_gammas(x, &b);
                let kh = hourglass_stiffness(hourglass, lambda + 2.0 * shear, v, &b);
                for ga in &gam {
                    for i in 0..8 {
                        for j in 0..8 {
                            for c in 0..3 {
                                k[3 * i + c][3 * j + c] += kh * ga[i] * ga[j];
                            }
                        }
                    }
                }
            }
        }
        Formulation::BBar => {
            let (g, j) = gauss_gradients(x);
            let vol: f64 = j.iter().sum();
            let mut bbar = [[0.0; 3]; 8];
            for p in 0..8 {
                for i in 0..8 {
                    for c in 0..3 {
                        bbar[i][c] += j[p] * g[p][i][c] / vol;
                    }
                }
            }
            for p in 0..8 {
                let eps: [[[f64; 3]; 3]; 24] = std::array::from_fn(|d| {
                    let (i, c) = (d / 3, d % 3);
                    let mut e = sym(c, g[p][i]);
                    let shift = (bbar[i][c] - g[p][i][c]) / 3.0;
                    for r in 0..3 {
                        e[r][r] += shift;
                    }
                    e
                });
                add_point(&eps, j[p]);
            }
        }
    }
    k
}

/// Consistent element mass ∫ ρ N_I N_J dV (8x8, kg), 3x3x3 Gauss (exact for the trilinear hex).
pub fn element_consistent_mass(x: &[[f64; 3]; 8], rho: f64) -> [[f64; 8]; 8] {
    let g3 = [-(0.6f64.sqrt()), 0.0, 0.6f64.sqrt()];
    let w3 = [5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0];
    let mut m = [[0.0; 8]; 8];
    for (a, wa) in g3.iter().zip(w3) {
        for (b, wb) in g3.iter().zip(w3) {
            for (c, wc) in g3.iter().zip(w3) {
                let p = [*a, *b, *c];
                let (_, det) = spatial_gradients(x, &natural_derivatives(p));
                let n = shape_functions(p);
                let w = rho * det * wa * wb * wc;
                for i in 0..8 {
                    for j in 0..8 {
                        m[i][j] += w * n[i] * n[j];
                    }
                }
            }
        }
    }
    m
}

/// Assembles K and M of `model` on its reference coordinates; constrained components are
/// removed. `hourglass` is the one-point hex's ε_hg. Fails on an inverted element.
pub fn assemble(model: &Model, hourglass: f64) -> Result<LinearSystem> {
    let n = model.nodes.len();
    let mut dof = vec![[0usize; 3]; n];
    for &(node, axis) in &model.fixed {
        dof[node as usize][axis as usize] = usize::MAX;
    }
    let mut nf = 0;
    for d in dof.iter_mut().flatten() {
        if *d == 0 {
            *d = nf;
            nf += 1;
        }
    }
    let mut kt = TriMat::new((nf, nf));
    let mut mt = TriMat::new((nf, nf));
    for part in &model.parts {
        let m = &part.material;
        for e in part.elements.clone() {
            let h = model.hexes[e];
            let x = h.map(|i| model.nodes[i as usize]);
            let (_, gj) = gauss_gradients(&x);
            if gj.iter().any(|j| j.is_nan() || *j <= 0.0) {
                return Err(Error::Numerical(format!(
                    "element {e} (part {}) is inverted",
                    part.name
                )));
            }
            let ke = element_stiffness(
                &x,
                part.formulation,
                m.lame_lambda(),
                m.shear_modulus(),
                hourglass,
            );
            let me = element_consistent_mass(&x, m.rho);
            for a in 0..24 {
                let ra = dof[h[a / 3] as usize][a % 3];
                if ra == usize::MAX {
                    continue;
                }
                for b in 0..24 {
                    let cb = dof[h[b / 3] as usize][b % 3];
                    if cb == usize::MAX {
                        continue;
                    }
                    kt.add_triplet(ra, cb, ke[a][b]);
                    if a % 3 == b % 3 {
                        mt.add_triplet(ra, cb, me[a / 3][b / 3]);
                    }
                }
            }
        }
    }
    Ok(LinearSystem {
        stiffness: kt.to_csc(),
        mass: mt.to_csc(),
        dof,
    })
}

fn to_faer(a: &CsMat<f64>) -> Result<faer::sparse::SparseColMat<usize, f64>> {
    let mut t = Vec::with_capacity(a.nnz());
    for (v, (r, c)) in a.iter() {
        t.push(faer::sparse::Triplet::new(r, c, *v));
    }
    faer::sparse::SparseColMat::try_new_from_triplets(a.rows(), a.cols(), &t)
        .map_err(|e| Error::Numerical(format!("sparse matrix assembly failed: {e:?}")))
}

fn mat_vec(a: &CsMat<f64>, x: &[f64], y: &mut [f64]) {
    y.iter_mut().for_each(|v| *v = 0.0);
    for (col, xv) in a.outer_iterator().zip(x) {
        for (r, v) in col.iter() {
            y[r] += v * xv;
        }
    }
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Free-vibration modes near `shift` (rad²/s²; a small negative value targets the lowest
/// modes, rigid-body modes included at ω ≈ 0) by shift-invert Lanczos with full
/// reorthogonalisation in the M inner product, 3 `count` + 20 steps. Returns every Ritz pair,
/// sorted by ω (ω of a rigid mode is 0): at least the `count` nearest the shift are converged
/// in practice, but keep only those with a small [`Mode::residual`] (say < 1e-6).
///
/// `start` (nodal vectors) seeds the Krylov space: the modes that this field excites converge
/// first (e.g. a radial field finds the breathing mode in a few steps); `None` uses a generic
/// field. Check [`Mode::residual`] to keep only converged modes. Fails if the factorisation
/// fails, `count` exceeds the free DOFs or the start field has no free component.
pub fn modes_near(
    sys: &LinearSystem,
    count: usize,
    shift: f64,
    start: Option<&[[f64; 3]]>,
) -> Result<Vec<Mode>> {
    let n = sys.stiffness.rows();
    if count == 0 || count > n {
        return Err(Error::invalid("modal.count", count, format!("1..={n}")));
    }
    let mut shifted = TriMat::new((n, n));
    for (v, (r, c)) in sys.stiffness.iter() {
        shifted.add_triplet(r, c, *v);
    }
    for (v, (r, c)) in sys.mass.iter() {
        shifted.add_triplet(r, c, -shift * v);
    }
    let a = to_faer(&shifted.to_csc())?;
    // Below the spectrum (σ < 0) K − σM is symmetric positive definite: sparse Cholesky with
    // a fill-reducing ordering; otherwise a sparse LU with partial pivoting.
    enum Factor {
        Llt(faer::sparse::linalg::solvers::Llt<usize, f64>),
        Lu(Box<faer::sparse::linalg::solvers::Lu<usize, f64>>),
    }
    let lu =
        if shift < 0.0 {
            Factor::Llt(a.sp_cholesky(faer::Side::Lower).map_err(|e| {
                Error::Numerical(format!("sparse Cholesky of K − σM failed: {e:?}"))
            })?)
        } else {
            Factor::Lu(Box::new(a.sp_lu().map_err(|e| {
                Error::Numerical(format!("sparse LU of K − σM failed: {e:?}"))
            })?))
        };
    let steps = (3 * count + 20).min(n);
    let mut q: Vec<Vec<f64>> = Vec::with_capacity(steps + 1);
    let mut mq: Vec<Vec<f64>> = Vec::with_capacity(steps + 1);
    // Deterministic start vector with components in every DOF.
    let mut v: Vec<f64> = (0..n)
        .map(|i| 1.0 + 0.5 * ((i as f64) * 0.618_033_988_7).fract())
        .collect();
    if let Some(f) = start {
        if f.len() != sys.dof.len() {
            return Err(Error::invalid(
                "modal.start",
                f.len(),
                format!("{} nodal vectors", sys.dof.len()),
            ));
        }
        for (d, fv) in sys.dof.iter().zip(f) {
            for k in 0..3 {
                if d[k] != usize::MAX {
                    v[d[k]] = fv[k];
                }
            }
        }
    }
    let mut mv = vec![0.0; n];
    mat_vec(&sys.mass, &v, &mut mv);
    let nrm = dot(&v, &mv).sqrt();
    if nrm.is_nan() || nrm <= 0.0 {
        return Err(Error::invalid(
            "modal.start",
            "zero field",
            "a field with free components",
        ));
    }
    v.iter_mut().for_each(|c| *c /= nrm);
    mv.iter_mut().for_each(|c| *c /= nrm);
    let (mut alpha, mut beta) = (Vec::new(), Vec::new());
    let mut rhs = faer::Mat::<f64>::zeros(n, 1);
    for j in 0..steps {
        q.push(v.clone());
        mq.push(mv.clone());
        for i in 0..n {
            rhs[(i, 0)] = mq[j][i];
        }
        match &lu {
            Factor::Llt(f) => f.solve_in_place(rhs.as_mut()),
            Factor::Lu(f) => f.solve_in_place(rhs.as_mut()),
        }
        let mut w: Vec<f64> = (0..n).map(|i| rhs[(i, 0)]).collect();
        // Full reorthogonalisation (twice) against every Lanczos vector, M inner product.
        for _ in 0..2 {
            for (qk, mqk) in q.iter().zip(&mq) {
                let c = dot(&w, mqk);
                w.iter_mut().zip(qk).for_each(|(a, b)| *a -= c * b);
            }
        }
        let a_j = dot(&rhs.col(0).iter().copied().collect::<Vec<_>>(), &mq[j]);
        alpha.push(a_j);
        let mut mw = vec![0.0; n];
        mat_vec(&sys.mass, &w, &mut mw);
        let b = dot(&w, &mw).sqrt();
        if j + 1 == steps || b < 1e-14 * a_j.abs() {
            break;
        }
        beta.push(b);
        v = w.iter().map(|c| c / b).collect();
        mv = mw.iter().map(|c| c / b).collect();
    }
    let m = alpha.len();
    let mut t = nalgebra::DMatrix::<f64>::zeros(m, m);
    for i in 0..m {
        t[(i, i)] = alpha[i];
        if i + 1 < m {
            t[(i, i + 1)] = beta[i];
            t[(i + 1, i)] = beta[i];
        }
    }
    let eig = t.symmetric_eigen();
    // θ = 1/(λ − σ): the largest |θ| are the eigenvalues nearest the shift.
    let mut order: Vec<usize> = (0..m).collect();
    order.sort_by(|&a, &b| {
        eig.eigenvalues[b]
            .abs()
            .total_cmp(&eig.eigenvalues[a].abs())
    });
    let mut modes = Vec::with_capacity(count);
    let mut kx = vec![0.0; n];
    let mut mx = vec![0.0; n];
    for &i in order.iter() {
        let theta = eig.eigenvalues[i];
        let lam = shift + 1.0 / theta;
        let mut x = vec![0.0; n];
        for (k, qk) in q.iter().take(m).enumerate() {
            let s = eig.eigenvectors[(k, i)];
            x.iter_mut().zip(qk).for_each(|(a, b)| *a += s * b);
        }
        mat_vec(&sys.mass, &x, &mut mx);
        let nm = dot(&x, &mx).sqrt();
        x.iter_mut().for_each(|c| *c /= nm);
        mx.iter_mut().for_each(|c| *c /= nm);
        mat_vec(&sys.stiffness, &x, &mut kx);
        let r: f64 = kx
            .iter()
            .zip(&mx)
            .map(|(k, m)| (k - lam * m).powi(2))
            .sum::<f64>()
            .sqrt();
        let kn = dot(&kx, &kx).sqrt().max(lam.abs() * dot(&mx, &mx).sqrt());
        let shape = sys
            .dof
            .iter()
            .map(|d| d.map(|k| if k == usize::MAX { 0.0 } else { x[k] }))
            .collect();
        modes.push(Mode {
            omega: lam.max(0.0).sqrt(),
            shape,
            residual: if kn > 0.0 { r / kn } else { r },
        });
    }
    modes.sort_by(|a, b| a.omega.total_cmp(&b.omega));
    Ok(modes)
}
