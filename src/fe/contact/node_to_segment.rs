//! Two deformable surfaces in contact: symmetric two-pass node-to-segment penalty contact.
//!
//! Pass 1 takes the nodes of surface A as slaves against the quads of B, pass 2 the nodes of B
//! against the quads of A; each pass carries half the penalty stiffness, so two matching
//! surfaces pressed together by a penetration g still feel the pressure ε g of one spring layer
//! per unit area, and neither surface can pass through the other's nodes. A slave node's force
//! F = F_n n + F_t acts at its projection on the master quad and is spread over the quad's
//! nodes with the bilinear shape functions: −N_a(ξ, η) F on master node a.

use super::friction::StickState;
use super::law::{respond, stored_energy, Kinematics, NodeLaw};
use super::output::{ContactOutput, ContactProbe, NodeContact, OutputBuilder, PressureSample};
use super::penalty::{damping_constant, effective_mass, stable_step};
use super::projection::{project, shape, Projection};
use super::search::{bounding_box, BucketSearch};
use super::surface::ContactSurface;
use super::vec3::{add, dot, scale, sub, tangential};
use super::ContactParams;
use crate::error::{Error, Result};
use crate::fe::interaction::{Interaction, InteractionEnergy, StepContext};
use crate::material::Material;
use std::collections::HashMap;

/// One slave→master pass.
#[derive(Debug, Clone)]
struct Pass {
    slave: usize,
    master: usize,
    weight: f64,
    laws: Vec<NodeLaw>,
    stick: Vec<StickState>,
    search: BucketSearch,
    watched: Vec<u32>,
}

/// Penalty frictional contact between two deformable surfaces.
#[derive(Debug, Clone)]
pub struct SurfacePair {
    name: String,
    surfaces: [ContactSurface; 2],
    params: ContactParams,
    passes: Vec<Pass>,
    /// Union of the nodes of both surfaces; `local` maps a global node to its index here.
    nodes: Vec<u32>,
    local: HashMap<u32, usize>,
    force: Vec<[f64; 3]>,
    prev_force: Vec<[f64; 3]>,
    dt_prev: Option<f64>,
    ready: bool,
    energy: InteractionEnergy,
    output: ContactOutput,
    samples: Vec<PressureSample>,
    probe: ContactProbe,
    friction_energy: f64,
    /// Steps on which the global bounding-box test found the surfaces apart.
    pub free_steps: usize,
}

impl SurfacePair {
    /// Contact between the quads `faces_a` (body A, `mat_a`) and `faces_b` (body B, `mat_b`) of
    /// the hexahedra `hexes` over reference coordinates `nodes` (m; both bodies in one global
    /// numbering), symmetric two-pass.
    ///
    /// The penalty uses the smaller Young's and bulk moduli of the two bodies and the slave
    /// node's tributary area and element thickness. Fails with [`Error::Invalid`] for bad face
    /// sets, surfaces sharing nodes, or invalid `params`.
    pub fn new(
        nodes: &[[f64; 3]],
        hexes: &[[u32; 8]],
        faces_a: &[[u32; 4]],
        mat_a: &Material,
        faces_b: &[[u32; 4]],
        mat_b: &Material,
        params: ContactParams,
    ) -> Result<SurfacePair> {
        let params = params.validated("contact")?;
        let a = ContactSurface::new(nodes, hexes, faces_a, "contact.surface_a")?;
        let b = ContactSurface::new(nodes, hexes, faces_b, "contact.surface_b")?;
        if let Some(g) = a.nodes.iter().find(|g| b.nodes.binary_search(g).is_ok()) {
            return Err(Error::invalid(
                "contact.surface_b",
                format!("node {g} shared with surface A"),
                "two surfaces without common nodes",
            ));
        }
        let youngs = mat_a.youngs.min(mat_b.youngs);
        let bulk = mat_a.bulk_modulus().min(mat_b.bulk_modulus());
        let surfaces = [a, b];
        let margin = {
            let edge = surfaces[0].min_edge.min(surfaces[1].min_edge);
            let th = surfaces
                .iter()
                .flat_map(|s| s.thickness.iter())
                .cloned()
                .fold(f64::INFINITY, f64::min);
            (0.5 * edge).max(params.max_penetration * th)
        };
        let mut nodes: Vec<u32> = surfaces[0]
            .nodes
            .iter()
            .chain(&surfaces[1].nodes)
            .copied()
            .collect();
        nodes.sort_unstable();
        let local: HashMap<u32, usize> = nodes.iter().enumerate().map(|(i, &g)| (g, i)).collect();
        let passes = [(0usize, 1usize), (1, 0)]
            .iter()
            .map(|&(s, m)| {
                let sf = &surfaces[s];
                let laws = (0..sf.nodes.len())
                    .map(|i| {
                        let k = 0.5
                            * params.penalty.geometric_stiffness(
                                youngs,
                                bulk,
                                sf.area[i],
                                sf.thickness[i],
                                sf.volume[i],
                            );
                        NodeLaw {
                            k,
                            kt: params.tangential_ratio * k,
                            c: 0.0,
                        }
                    })
                    .collect();
                Pass {
                    slave: s,
                    master: m,
                    weight: 0.5,
                    laws,
                    stick: vec![StickState::default(); sf.nodes.len()],
                    search: BucketSearch::new(margin),
                    watched: nodes.clone(),
                }
            })
            .collect();
        let n = nodes.len();
        Ok(SurfacePair {
            name: "surface-pair contact".into(),
            surfaces,
            params,
            passes,
            nodes,
            local,
            force: vec![[0.0; 3]; n],
            prev_force: vec![[0.0; 3]; n],
            dt_prev: None,
            ready: false,
            energy: InteractionEnergy::default(),
            output: ContactOutput::default(),
            samples: Vec::new(),
            probe: ContactProbe::default(),
            friction_energy: 0.0,
            free_steps: 0,
        })
    }

    /// A shared handle on this pair's output that stays readable after the pair is boxed
    /// and handed to the solver.
    pub fn probe(&self) -> ContactProbe {
        self.probe.clone()
    }

    /// Output of the last evaluated step (forces on body A).
    pub fn output(&self) -> &ContactOutput {
        &self.output
    }

    /// Pressure at every slave node in contact at the last step (both passes).
    pub fn pressures(&self) -> &[PressureSample] {
        &self.samples
    }

    /// Number of candidate-list rebuilds so far, summed over the passes.
    pub fn search_rebuilds(&self) -> usize {
        self.passes.iter().map(|p| p.search.rebuilds).sum()
    }

    /// Smallest node mass of surface `s`, kg.
    fn min_mass(&self, s: usize, mass: &[f64]) -> f64 {
        self.surfaces[s]
            .nodes
            .iter()
            .map(|&g| mass[g as usize])
            .fold(f64::INFINITY, f64::min)
    }

    fn prepare(&mut self, ctx: &StepContext<'_>) {
        let mins = [self.min_mass(0, ctx.mass), self.min_mass(1, ctx.mass)];
        for p in &mut self.passes {
            for (i, &g) in self.surfaces[p.slave].nodes.iter().enumerate() {
                let m = effective_mass(ctx.mass[g as usize], mins[p.master]);
                let law = &mut p.laws[i];
                law.k = law
                    .k
                    .max(p.weight * self.params.penalty.time_step_stiffness(m, ctx.dt));
                law.kt = self.params.tangential_ratio * law.k;
                law.c = damping_constant(self.params.damping, law.k, m);
            }
        }
        self.ready = true;
    }

    /// The closest candidate segment of slave node `s` (m), if any.
    fn closest(
        x: &[[f64; 3]],
        faces: &[[u32; 4]],
        cands: &[u32],
        s: [f64; 3],
    ) -> Option<(usize, Projection)> {
        let mut best: Option<(usize, Projection)> = None;
        for &f in cands {
            let q = faces[f as usize];
            let p = project(&q.map(|g| x[g as usize]), s);
            let better = match &best {
                None => true,
                Some((_, b)) => {
                    p.distance < b.distance * (1.0 - 1e-9)
                        || (p.distance <= b.distance * (1.0 + 1e-9)
                            && b.on_boundary
                            && !p.on_boundary)
                }
            };
            if better {
                best = Some((f as usize, p));
            }
        }
        best
    }
}

impl Interaction for SurfacePair {
    fn name(&self) -> &str {
        &self.name
    }

    fn add_forces(&mut self, ctx: &StepContext<'_>, f: &mut [[f64; 3]]) -> Result<()> {
        if !self.ready {
            self.prepare(ctx);
        }
        let dt_prev = self.dt_prev.unwrap_or(0.0);
        self.force.iter_mut().for_each(|v| *v = [0.0; 3]);
        let mut out = OutputBuilder::new(ctx.t);
        let mut stored = 0.0;
        // Global gap test: the boxes of the two surfaces, inflated by the search margin.
        let margin = self.passes[0].search.margin();
        let apart = !bounding_box(ctx.x, &self.surfaces[0].nodes)
            .overlaps(&bounding_box(ctx.x, &self.surfaces[1].nodes), margin);
        if apart {
            self.free_steps += 1;
            for p in &mut self.passes {
                p.search.invalidate();
                p.stick.iter_mut().for_each(|s| *s = StickState::default());
            }
        } else {
            for p in &mut self.passes {
                let (slave, master) = (&self.surfaces[p.slave], &self.surfaces[p.master]);
                let cands = p
                    .search
                    .candidates(ctx.x, &slave.nodes, &master.faces, &p.watched);
                for (i, &g) in slave.nodes.iter().enumerate() {
                    let s = ctx.x[g as usize];
                    let hit = Self::closest(ctx.x, &master.faces, &cands[i], s);
                    let Some((fi, pr)) = hit.filter(|(_, pr)| pr.gap < 0.0) else {
                        p.stick[i] = StickState::default();
                        continue;
                    };
                    if -pr.gap > self.params.max_penetration * slave.thickness[i] {
                        return Err(Error::Numerical(format!(
                            "{}: node {g} penetrates {:.3e} m at t = {:.6e} s, more than {} of its element \
                             thickness {:.3e} m; raise the penalty factor or lower the time step",
                            self.name, -pr.gap, ctx.t, self.params.max_penetration, slave.thickness[i]
                        )));
                    }
                    let quad = master.faces[fi];
                    let nsh = shape(pr.xi);
                    let mut vm = [0.0; 3];
                    for a in 0..4 {
                        vm = add(vm, scale(nsh[a], ctx.v[quad[a] as usize]));
                    }
                    let rel = sub(ctx.v[g as usize], vm);
                    let n = pr.normal;
                    let kin = Kinematics {
                        gap: pr.gap,
                        gap_rate: dot(rel, n),
                        slip: scale(dt_prev, tangential(rel, n)),
                        normal: n,
                        dt: dt_prev,
                    };
                    let r = respond(&p.laws[i], &mut p.stick[i], &kin, self.params.friction);
                    self.energy.dissipated += r.dissipated;
                    self.friction_energy += r.friction;
                    stored += stored_energy(&p.laws[i], &p.stick[i], pr.gap);
                    let fs = r.force(n);
                    let li = self.local[&g];
                    self.force[li] = add(self.force[li], fs);
                    for a in 0..4 {
                        let la = self.local[&quad[a]];
                        self.force[la] = sub(self.force[la], scale(nsh[a], fs));
                    }
                    let area = p.weight * slave.area[i];
                    let sample = PressureSample {
                        node: g,
                        position: s,
                        normal: n,
                        pressure: r.normal / area,
                        area,
                    };
                    // Forces on body A: the slave's own force in pass A→B, the reaction on
                    // master A in pass B→A.
                    let sign = if p.slave == 0 { 1.0 } else { -1.0 };
                    out.add(
                        sign,
                        sample,
                        NodeContact {
                            normal: r.normal,
                            tangential: r.tangential,
                            penetration: -pr.gap,
                            sliding: p.stick[i].sliding,
                        },
                    );
                }
            }
        }
        for (li, &g) in self.nodes.iter().enumerate() {
            let gi = g as usize;
            let (fp, fnw) = (self.prev_force[li], self.force[li]);
            if fp != [0.0; 3] || fnw != [0.0; 3] {
                let avg = [
                    0.5 * (fp[0] + fnw[0]),
                    0.5 * (fp[1] + fnw[1]),
                    0.5 * (fp[2] + fnw[2]),
                ];
                self.energy.work += dot(avg, ctx.v[gi]) * dt_prev;
                f[gi] = add(f[gi], fnw);
            }
        }
        std::mem::swap(&mut self.prev_force, &mut self.force);
        self.energy.stored = stored;
        let (o, s) = out.finish(stored, self.energy.dissipated, self.friction_energy);
        self.probe.update(&o, &s);
        self.output = o;
        self.samples = s;
        self.dt_prev = Some(ctx.dt);
        Ok(())
    }

    fn stable_time_step(&self, mass: &[f64]) -> Option<f64> {
        let mins = [self.min_mass(0, mass), self.min_mass(1, mass)];
        self.passes
            .iter()
            .flat_map(|p| {
                self.surfaces[p.slave]
                    .nodes
                    .iter()
                    .zip(&p.laws)
                    .map(move |(&g, l)| {
                        // Both passes can load a node pair: take the full (unweighted) spring.
                        stable_step(
                            l.k / p.weight,
                            effective_mass(mass[g as usize], mins[p.master]),
                        )
                    })
            })
            .min_by(f64::total_cmp)
    }

    fn energy(&self) -> InteractionEnergy {
        self.energy
    }
}
