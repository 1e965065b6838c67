//! The element loop of `getforce` (Box 6.1): for each element gather nodal coordinates and
//! velocities, compute the deformation measure, update the material, compute internal nodal
//! forces. Element state is stored as structure-of-arrays per part; the loop runs over batches
//! of elements in parallel (rayon) and writes one force block per element, so the result does
//! not depend on the number of threads.

use super::{
    hex_bbar_lanes as bp,
    hex_one_point::ElementOutput,
    hex_one_point_lanes as op,
    lanes::{build, Lanes},
    model::Formulation,
    plasticity::J2Material,
    tensor::Sym,
};
use rayon::prelude::*;

/// Elements per parallel batch (fixed: results never depend on it, only scheduling does).
pub const BATCH: usize = 64;

/// Fewest element batches one parallel task takes (8 x 64 = 512 elements, about 0.15 ms of
/// one-point work): shorter ranges are not worth a fork-join.
const MIN_BATCHES_PER_TASK: usize = 8;

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
        // Every node index of the range must address x and v: checked once here, so the
        // gathers in the hot loop need no bounds checks.
        let max_node = self.conn[r.clone()]
            .iter()
            .flatten()
            .fold(0u32, |m, &n| m.max(n));
        assert!(
            r.is_empty() || (max_node as usize) < x.len().min(v.len()),
            "node index out of range of x/v"
        );
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
            // Subcycled steps update short same-level ranges: below MIN_BATCHES_PER_TASK
            // batches a range runs on the calling thread (the fork-join would cost more than
            // the work). Each batch writes only its own outputs, so the split does not change
            // any result.
            .with_min_len(MIN_BATCHES_PER_TASK)
            .enumerate()
            .map(|(b, (conn, pts, wp, ie, hgq, ehg, vol, dtc, f))| {
                let base = first + b * BATCH;
                let mut batch = Batch {
                    conn,
                    pts,
                    wp,
                    ie,
                    hgq,
                    ehg,
                    vol,
                    dtc,
                    f,
                };
                let inp = StepInput {
                    x,
                    v,
                    dt,
                    mat: &mat,
                    hg,
                    form,
                };
                element_batch(&mut batch, inp, base)
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

/// One batch of elements of the element loop: its slices of every state array.
struct Batch<'a> {
    conn: &'a [[u32; 8]],
    pts: &'a mut [IntegrationPoint],
    wp: &'a mut [f64],
    ie: &'a mut [f64],
    hgq: &'a mut [[[f64; 3]; 4]],
    ehg: &'a mut [f64],
    vol: &'a mut [f64],
    dtc: &'a mut [f64],
    f: &'a mut [[[f64; 3]; 8]],
}

/// Result of a batch: smallest critical step and its element, or the first failing element.
type BatchResult = Result<(f64, usize), (usize, ElementFailure)>;

/// Checks one element's output, records it and updates the batch minimum.
#[inline(always)]
fn finish_element(
    out: &ElementOutput,
    b: &mut Batch<'_>,
    k: usize,
    base: usize,
    best: &mut (f64, usize),
) -> std::result::Result<(), (usize, ElementFailure)> {
    if out.min_jacobian.is_nan() || out.min_jacobian <= 0.0 {
        return Err((base + k, ElementFailure::Inverted(out.min_jacobian)));
    }
    if !out.force.iter().flatten().all(|c| c.is_finite()) {
        return Err((base + k, ElementFailure::NonFinite));
    }
    b.vol[k] = out.volume;
    b.dtc[k] = out.dt_crit;
    b.f[k] = out.force;
    if out.dt_crit < best.0 {
        *best = (out.dt_crit, base + k);
    }
    Ok(())
}

/// B-bar elements W at a time: gather nodes and the eight points' state into lanes, update
/// ([`bp::update`]), scatter state and forces back. Lanes past the batch end repeat its last
/// element and are discarded.
#[inline(always)]
fn bbar_lanes<const W: usize>(
    b: &mut Batch<'_>,
    x: &[[f64; 3]],
    v: &[[f64; 3]],
    dt: f64,
    mat: &J2Material,
    base: usize,
) -> BatchResult {
    let n = b.conn.len();
    let mut best = (f64::INFINITY, base);
    let mut k0 = 0;
    while k0 < n {
        let idx: [usize; W] = build(|l| (k0 + l).min(n - 1));
        let live = (n - k0).min(W);
        let mut xe = [[Lanes::<W>::default(); 3]; 8];
        let mut ve = [[Lanes::<W>::default(); 3]; 8];
        gather_nodes(&idx, b.conn, x, v, &mut xe, &mut ve);
        let mut st = bp::State::<W> {
            stress: [[Lanes::default(); 6]; 8],
            eps_p: [Lanes::default(); 8],
            plastic_work: Lanes::default(),
            internal_energy: Lanes::default(),
        };
        for (l, &e) in idx.iter().enumerate() {
            for g in 0..8 {
                let ip = &b.pts[8 * e + g];
                for c in 0..6 {
                    st.stress[g][c].0[l] = ip.stress[c];
                }
                st.eps_p[g].0[l] = ip.eps_p;
            }
            st.plastic_work.0[l] = b.wp[e];
            st.internal_energy.0[l] = b.ie[e];
        }
        let out = bp::update(&xe, &ve, dt, mat, &mut st);
        for l in 0..live {
            let k = k0 + l;
            for g in 0..8 {
                let ip = &mut b.pts[8 * k + g];
                for c in 0..6 {
                    ip.stress[c] = st.stress[g][c].0[l];
                }
                ip.eps_p = st.eps_p[g].0[l];
                ip.volume = out.point_volume[g].0[l];
            }
            b.wp[k] = st.plastic_work.0[l];
            b.ie[k] = st.internal_energy.0[l];
            let eo = lane_output(&out.force, out.volume, out.min_jacobian, out.dt_crit, l);
            finish_element(&eo, b, k, base, &mut best)?;
        }
        k0 += W;
    }
    Ok(best)
}

/// Nodal coordinates and velocities of the elements `idx` (local indices into `conn`) into
/// lanes (plain loops: nothing is left out of line, outside the AVX2 kernel).
#[inline(always)]
fn gather_nodes<const W: usize>(
    idx: &[usize; W],
    conn: &[[u32; 8]],
    x: &[[f64; 3]],
    v: &[[f64; 3]],
    xe: &mut [[Lanes<W>; 3]; 8],
    ve: &mut [[Lanes<W>; 3]; 8],
) {
    for (l, &e) in idx.iter().enumerate() {
        let c = &conn[e];
        for i in 0..8 {
            let node = c[i] as usize;
            // SAFETY: update_range checked every node index of the range < len.
            let (p, q) = unsafe { (x.get_unchecked(node), v.get_unchecked(node)) };
            for d in 0..3 {
                xe[i][d].0[l] = p[d];
                ve[i][d].0[l] = q[d];
            }
        }
    }
}

/// Lane `l` of a group's results as one element's output: nodal forces (N), volume (m³),
/// smallest Jacobian (m³) and Courant limit (s).
#[inline(always)]
fn lane_output<const W: usize>(
    force: &[[Lanes<W>; 3]; 8],
    volume: Lanes<W>,
    min_jacobian: Lanes<W>,
    dt_crit: Lanes<W>,
    l: usize,
) -> ElementOutput {
    let mut f = [[0.0; 3]; 8];
    for i in 0..8 {
        for c in 0..3 {
            f[i][c] = force[i][c].0[l];
        }
    }
    ElementOutput {
        force: f,
        volume: volume.0[l],
        min_jacobian: min_jacobian.0[l],
        dt_crit: dt_crit.0[l],
    }
}

/// What every element of a batch needs besides its own state.
#[derive(Clone, Copy)]
struct StepInput<'a> {
    /// Nodal coordinates at t^{n+1}, m.
    x: &'a [[f64; 3]],
    /// Nodal velocities at t^{n+1/2}, m/s.
    v: &'a [[f64; 3]],
    /// Step, s.
    dt: f64,
    mat: &'a J2Material,
    /// Hourglass coefficient (one-point hex; 0 = off).
    hg: f64,
    form: Formulation,
}

/// One batch of elements on the best lane width this CPU supports: the AVX2 build of the
/// lane kernels when the CPU has AVX2 and FMA, otherwise the same source as plain arrays
/// (the results are the same on every path: see [`super::lanes`]).
fn element_batch(b: &mut Batch<'_>, inp: StepInput<'_>, base: usize) -> BatchResult {
    #[cfg(target_arch = "x86_64")]
    {
        if std::is_x86_feature_detected!("avx2") && std::is_x86_feature_detected!("fma") {
            // SAFETY: the CPU has the features the function is compiled for.
            return unsafe { element_batch_avx2(b, inp, base) };
        }
    }
    element_lanes::<4>(b, inp, base)
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
unsafe fn element_batch_avx2(b: &mut Batch<'_>, inp: StepInput<'_>, base: usize) -> BatchResult {
    element_lanes::<4>(b, inp, base)
}

/// The lane loop of the batch's formulation (both inline into the caller's target features).
#[inline(always)]
fn element_lanes<const W: usize>(
    b: &mut Batch<'_>,
    inp: StepInput<'_>,
    base: usize,
) -> BatchResult {
    let StepInput {
        x,
        v,
        dt,
        mat,
        hg,
        form,
    } = inp;
    match form {
        Formulation::OnePoint => one_point_lanes::<W>(b, x, v, dt, mat, hg, base),
        Formulation::BBar => bbar_lanes::<W>(b, x, v, dt, mat, base),
    }
}

/// Gathers W elements (`idx`: local element per lane) into lanes, updates them, scatters
/// state and forces back. Lanes past the batch end repeat its last element and are discarded.
#[inline(always)]
fn one_point_lanes<const W: usize>(
    b: &mut Batch<'_>,
    x: &[[f64; 3]],
    v: &[[f64; 3]],
    dt: f64,
    mat: &J2Material,
    hg: f64,
    base: usize,
) -> BatchResult {
    let n = b.conn.len();
    let mut best = (f64::INFINITY, base);
    let mut k0 = 0;
    while k0 < n {
        let idx: [usize; W] = build(|l| (k0 + l).min(n - 1));
        let live = (n - k0).min(W);
        // Gather nodal coordinates and velocities and the element state into lanes (plain
        // loops: no closure or generic helper is left out of the AVX2 kernel).
        let mut xe = [[Lanes::<W>::default(); 3]; 8];
        let mut ve = [[Lanes::<W>::default(); 3]; 8];
        let mut st = op::State::<W> {
            stress: [Lanes::default(); 6],
            eps_p: Lanes::default(),
            hourglass: [[Lanes::default(); 3]; 4],
            plastic_work: Lanes::default(),
            internal_energy: Lanes::default(),
            hourglass_energy: Lanes::default(),
        };
        gather_nodes(&idx, b.conn, x, v, &mut xe, &mut ve);
        for (l, &e) in idx.iter().enumerate() {
            let ip = &b.pts[e];
            for c in 0..6 {
                st.stress[c].0[l] = ip.stress[c];
            }
            st.eps_p.0[l] = ip.eps_p;
            for a in 0..4 {
                for c in 0..3 {
                    st.hourglass[a][c].0[l] = b.hgq[e][a][c];
                }
            }
            st.plastic_work.0[l] = b.wp[e];
            st.internal_energy.0[l] = b.ie[e];
            st.hourglass_energy.0[l] = b.ehg[e];
        }
        let out = op::update(&xe, &ve, dt, mat, hg, &mut st);
        for l in 0..live {
            let k = k0 + l;
            let ip = &mut b.pts[k];
            for c in 0..6 {
                ip.stress[c] = st.stress[c].0[l];
            }
            ip.eps_p = st.eps_p.0[l];
            ip.volume = out.volume.0[l];
            b.wp[k] = st.plastic_work.0[l];
            b.ie[k] = st.internal_energy.0[l];
            b.ehg[k] = st.hourglass_energy.0[l];
            for a in 0..4 {
                for c in 0..3 {
                    b.hgq[k][a][c] = st.hourglass[a][c].0[l];
                }
            }
            // One point: the element volume is its only Jacobian.
            let eo = lane_output(&out.force, out.volume, out.volume, out.dt_crit, l);
            finish_element(&eo, b, k, base, &mut best)?;
        }
        k0 += W;
    }
    Ok(best)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fe::{elements::ElementStateMut, hex_one_point};
    use crate::material::Material;
    use crate::mesh::ball::{ball, BallSpec, Cut};

    /// The batched lane loop against the per-element kernel on a real (graded, distorted)
    /// ball mesh with a yielding, spinning, hourglass-exciting velocity field, several steps.
    #[test]
    fn lane_loop_matches_per_element_kernel_on_a_ball_mesh() {
        let mesh = ball(&BallSpec {
            diameter: 0.02,
            size: 0.004,
            pole_size: Some(0.001),
            cut: Cut::Quarter,
        })
        .unwrap();
        let mat = J2Material::new(&Material::preset("copper-fe").unwrap(), false);
        let n = mesh.hexes.len();
        assert!(
            !n.is_multiple_of(4) || !n.is_multiple_of(BATCH),
            "want a ragged tail"
        );
        let mut blk = ElementBlock::new(0, 0, mesh.hexes.clone(), Formulation::OnePoint, mat, 0.05);
        let mut refb = blk.clone();
        let mut x = mesh.nodes.clone();
        let v: Vec<[f64; 3]> = x
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let wob = ((i * 7919) % 13) as f64 / 13.0 - 0.5;
                [
                    3000.0 * p[0] - 400.0 * p[1] + 2.0 * wob,
                    -1500.0 * p[1] + 400.0 * p[0],
                    -wob,
                ]
            })
            .collect();
        let dt = 1e-8;
        let mut f = vec![[[0.0; 3]; 8]; n];
        for step in 0..30 {
            for (p, u) in x.iter_mut().zip(&v) {
                for c in 0..3 {
                    p[c] += dt * u[c];
                }
            }
            let (dmin, _) = blk.update(&x, &v, dt, &mut f).unwrap();
            let mut rmin = f64::INFINITY;
            for k in 0..n {
                let c = refb.conn[k];
                let xe = c.map(|i| x[i as usize]);
                let ve = c.map(|i| v[i as usize]);
                let o = hex_one_point::update(
                    &xe,
                    &ve,
                    dt,
                    &mat,
                    0.05,
                    ElementStateMut {
                        points: &mut refb.points[k..k + 1],
                        plastic_work: &mut refb.plastic_work[k],
                        internal_energy: &mut refb.internal_energy[k],
                        hourglass: &mut refb.hourglass[k],
                        hourglass_energy: &mut refb.hourglass_energy[k],
                    },
                );
                rmin = rmin.min(o.dt_crit);
                let scale = o
                    .force
                    .iter()
                    .flatten()
                    .fold(1e-3f64, |m, c| m.max(c.abs()));
                for i in 0..8 {
                    for d in 0..3 {
                        assert!(
                            (f[k][i][d] - o.force[i][d]).abs() < 1e-10 * scale,
                            "step {step} element {k} node {i}: {} vs {}",
                            f[k][i][d],
                            o.force[i][d]
                        );
                    }
                }
                assert!((blk.points[k].eps_p - refb.points[k].eps_p).abs() < 1e-12);
            }
            assert!((dmin - rmin).abs() < 1e-12 * rmin);
        }
        assert!(
            blk.points.iter().any(|p| p.eps_p > 0.0),
            "must yield somewhere"
        );
    }
}
