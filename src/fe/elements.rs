//! The element loop of `getforce` (Box 6.1): for each element gather nodal coordinates and
//! velocities, compute the deformation measure, update the material, compute internal nodal
//! forces. Element state is stored as structure-of-arrays per part; the loop runs over batches
//! of elements in parallel (rayon) and writes one force block per element, so the result does
//! not depend on the number of threads.

use super::{
    hex_bbar, hex_one_point, hex_one_point::ElementOutput, model::Formulation,
    plasticity::J2Material, tensor::Sym,
};
use rayon::prelude::*;

/// Elements per parallel batch (fixed: results never depend on it, only scheduling does).
pub const BATCH: usize = 64;

/// State at one integration point.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct IntegrationPoint {
    /// Cauchy stress, Pa (Voigt [xx, yy, zz, xy, yz, zx]).
    pub stress: Sym,
    /// Equivalent plastic strain.
    pub eps_p: f64,
    /// Volume this point represents at the last update (J_g w_g or V), m³.
    pub volume: f64,
}

/// Mutable view of one element's state handed to a kernel.
#[derive(Debug)]
pub struct ElementStateMut<'a> {
    /// Integration points (1 for the one-point hex, 8 for B-bar).
    pub points: &'a mut [IntegrationPoint],
    /// Plastic work dissipated in the element so far, J.
    pub plastic_work: &'a mut f64,
    /// Internal energy: stress power integrated over time, ∫ V σ:D dt, J.
    pub internal_energy: &'a mut f64,
    /// Hourglass generalised forces Q_α, N (one-point hex only).
    pub hourglass: &'a mut [[f64; 3]; 4],
    /// Energy stored by the hourglass forces so far, J.
    pub hourglass_energy: &'a mut f64,
}

/// Why the element loop stopped.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ElementFailure {
    /// Non-positive Jacobian (value) at the element.
    Inverted(f64),
    /// Non-finite force or stress.
    NonFinite,
}

/// The elements of one part: connectivity, material and their state, structure-of-arrays.
#[derive(Debug, Clone)]
pub struct ElementBlock {
    /// Index of the part.
    pub part: usize,
    /// Global index of the first element.
    pub first: usize,
    /// Formulation.
    pub formulation: Formulation,
    /// Material constants.
    pub material: J2Material,
    /// Hourglass coefficient ε_hg (one-point only).
    pub hourglass_coeff: f64,
    /// Connectivity (global node numbers).
    pub conn: Vec<[u32; 8]>,
    /// Integration points, `points_per_element` per element.
    pub points: Vec<IntegrationPoint>,
    /// Plastic work per element, J.
    pub plastic_work: Vec<f64>,
    /// Internal energy ∫ V σ:D dt per element (elastic stored + plastic), J.
    pub internal_energy: Vec<f64>,
    /// Hourglass forces per element (zero for B-bar).
    pub hourglass: Vec<[[f64; 3]; 4]>,
    /// Hourglass energy per element, J.
    pub hourglass_energy: Vec<f64>,
    /// Volume per element, m³.
    pub volume: Vec<f64>,
    /// Critical time step per element, s.
    pub dt_crit: Vec<f64>,
}

impl ElementBlock {
    /// A stress-free block for the elements `conn` starting at global element `first`.
    pub fn new(
        part: usize,
        first: usize,
        conn: Vec<[u32; 8]>,
        formulation: Formulation,
        material: J2Material,
        hourglass_coeff: f64,
    ) -> Self {
        let n = conn.len();
        let npe = Self::points_for(formulation);
        ElementBlock {
            part,
            first,
            formulation,
            material,
            hourglass_coeff,
            conn,
            points: vec![IntegrationPoint::default(); n * npe],
            plastic_work: vec![0.0; n],
            internal_energy: vec![0.0; n],
            hourglass: vec![[[0.0; 3]; 4]; n],
            hourglass_energy: vec![0.0; n],
            volume: vec![0.0; n],
            dt_crit: vec![f64::INFINITY; n],
        }
    }

    /// Integration points per element of a formulation.
    pub fn points_for(f: Formulation) -> usize {
        match f {
            Formulation::OnePoint => 1,
            Formulation::BBar => 8,
        }
    }

    /// Integration points per element of this block.
    pub fn points_per_element(&self) -> usize {
        Self::points_for(self.formulation)
    }

    /// Runs the element loop: advances every element's state with positions `x` = x^{n+1},
    /// velocities `v` = v^{n+1/2} and step `dt` (0: evaluate only), writing each element's
    /// internal forces to `forces[e - first]`. Returns the smallest critical step and its
    /// global element, or the lowest-numbered failing element.
    pub fn update(
        &mut self,
        x: &[[f64; 3]],
        v: &[[f64; 3]],
        dt: f64,
        forces: &mut [[[f64; 3]; 8]],
    ) -> Result<(f64, usize), (usize, ElementFailure)> {
        self.update_range(0..self.conn.len(), x, v, dt, forces)
    }

    /// The element loop over the local elements `range` only (for multi-time-step
    /// integration, where element groups advance with their own steps): as
    /// [`ElementBlock::update`], with `forces[k]` the force block of local element
    /// `range.start + k` (so `forces.len() == range.len()`). Elements outside `range` keep
    /// their state. Panics if `range` is out of bounds or `forces` has the wrong length
    /// (programming errors, not input errors).
    pub fn update_range(
        &mut self,
        range: std::ops::Range<usize>,
        x: &[[f64; 3]],
        v: &[[f64; 3]],
        dt: f64,
        forces: &mut [[[f64; 3]; 8]],
    ) -> Result<(f64, usize), (usize, ElementFailure)> {
        assert_eq!(
            forces.len(),
            range.len(),
            "one force block per element of the range"
        );
        let npe = self.points_per_element();
        let mat = self.material;
        let hg = self.hourglass_coeff;
        let form = self.formulation;
        let first = self.first + range.start;
        let r = range.clone();
        let rp = range.start * npe..range.end * npe;
        let res = (
            self.conn[r.clone()].par_chunks(BATCH),
            self.points[rp].par_chunks_mut(BATCH * npe),
            self.plastic_work[r.clone()].par_chunks_mut(BATCH),
            self.internal_energy[r.clone()].par_chunks_mut(BATCH),
            self.hourglass[r.clone()].par_chunks_mut(BATCH),
            self.hourglass_energy[r.clone()].par_chunks_mut(BATCH),
            self.volume[r.clone()].par_chunks_mut(BATCH),
            self.dt_crit[r].par_chunks_mut(BATCH),
            forces.par_chunks_mut(BATCH),
        )
            .into_par_iter()
            .enumerate()
            .map(|(b, (conn, pts, wp, ie, hgq, ehg, vol, dtc, f))| {
                let base = first + b * BATCH;
                let mut best = (f64::INFINITY, base);
                for k in 0..conn.len() {
                    let c = &conn[k];
                    let xe: [[f64; 3]; 8] = std::array::from_fn(|i| x[c[i] as usize]);
                    let ve: [[f64; 3]; 8] = std::array::from_fn(|i| v[c[i] as usize]);
                    let st = ElementStateMut {
                        points: &mut pts[k * npe..(k + 1) * npe],
                        plastic_work: &mut wp[k],
                        internal_energy: &mut ie[k],
                        hourglass: &mut hgq[k],
                        hourglass_energy: &mut ehg[k],
                    };
                    let out: ElementOutput = match form {
                        Formulation::OnePoint => hex_one_point::update(&xe, &ve, dt, &mat, hg, st),
                        Formulation::BBar => hex_bbar::update(&xe, &ve, dt, &mat, st),
                    };
                    if out.min_jacobian.is_nan() || out.min_jacobian <= 0.0 {
                        return Err((base + k, ElementFailure::Inverted(out.min_jacobian)));
                    }
                    if !out.force.iter().flatten().all(|c| c.is_finite()) {
                        return Err((base + k, ElementFailure::NonFinite));
                    }
                    vol[k] = out.volume;
                    dtc[k] = out.dt_crit;
                    f[k] = out.force;
                    if out.dt_crit < best.0 {
                        best = (out.dt_crit, base + k);
                    }
                }
                Ok(best)
            })
            .reduce(
                || Ok((f64::INFINITY, usize::MAX)),
                |a, b| match (a, b) {
                    (Err(x), Err(y)) => Err(if x.0 <= y.0 { x } else { y }),
                    (Err(x), _) | (_, Err(x)) => Err(x),
                    (Ok(x), Ok(y)) => Ok(if x.0 < y.0 || (x.0 == y.0 && x.1 <= y.1) {
                        x
                    } else {
                        y
                    }),
                },
            );
        res
    }

    /// Mean stress over the integration points of local element `k`, Pa.
    pub fn element_stress(&self, k: usize) -> Sym {
        let npe = self.points_per_element();
        let mut s = [0.0; 6];
        for p in &self.points[k * npe..(k + 1) * npe] {
            for c in 0..6 {
                s[c] += p.stress[c] / npe as f64;
            }
        }
        s
    }

    /// Mean equivalent plastic strain of local element `k`.
    pub fn element_eps_p(&self, k: usize) -> f64 {
        let npe = self.points_per_element();
        self.points[k * npe..(k + 1) * npe]
            .iter()
            .map(|p| p.eps_p)
            .sum::<f64>()
            / npe as f64
    }

    /// Elastic strain energy of the current stresses in local element `k`, p²/2K + s:s/4G
    /// per unit volume, J (a diagnostic: the hypoelastic update has no exact potential).
    pub fn element_elastic_energy(&self, k: usize) -> f64 {
        let npe = self.points_per_element();
        self.points[k * npe..(k + 1) * npe]
            .iter()
            .map(|p| p.volume * self.material.elastic_energy_density(&p.stress))
            .sum()
    }
}
