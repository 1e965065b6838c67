//! Two deformable surfaces in contact: symmetric two-pass node-to-segment penalty contact.
//!
//! Pass 1 takes the nodes of surface A as slaves against the quads of B, pass 2 the nodes of B
//! against the quads of A; each pass carries half the penalty stiffness, so two matching
//! surfaces pressed together by a penetration g still feel the pressure ε g of one spring layer
//! per unit area, and neither surface can pass through the other's nodes. A slave node's force
//! F = F_n n + F_t acts at its projection on the master quad and is spread over the quad's
//! nodes with the bilinear shape functions: −N_a(ξ, η) F on master node a.

use super::friction::StickState;
use super::law::{respond, stored_energy, NodeKinematics, NodeLaw};
use super::ledger::ContactLedger;
use super::output::{ContactOutput, ContactProbe, NodeContact, OutputBuilder, PressureSample};
use super::params::ContactParams;
use super::penalty::{effective_mass, stable_step};
use super::projection::{project, shape, Projection};
use super::search::{bounding_box, Aabb, BucketSearch};
use super::step_cache::StepCache;
use super::surface::ContactSurface;
use crate::error::{Error, Result};
use crate::fe::interaction::{Interaction, InteractionEnergy, StepContext};
use crate::fe::tensor::{add, dot, norm, scale, sub, tangential};
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
    /// For each slave node, the nearest master node in the reference configuration: whose
    /// mass pairs with the slave's in the penalty time step.
    partner: Vec<u32>,
    /// For each slave node, the smallest master mass it has touched (or its partner's), kg.
    partner_mass: Vec<f64>,
    /// Index in `SurfacePair::nodes` of each slave node and of each master face's nodes.
    slave_local: Vec<usize>,
    face_local: Vec<[usize; 4]>,
    /// Per master face: the box of its corners at the current step (kept for the faces of
    /// the candidate lists only), m.
    boxes: Vec<Aabb>,
    /// Per slave node: a distance (m) it is known to keep from every candidate segment of
    /// the current lists, less the largest approach since; while positive the node cannot
    /// touch and is not projected. 0: project this step.
    clearance: Vec<f64>,
    /// The search's rebuild count the clearances belong to (new lists: project every node).
    lists_seen: usize,
}

/// Penalty frictional contact between two deformable surfaces.
#[derive(Debug, Clone)]
pub struct SurfacePair {
    name: String,
    surfaces: [ContactSurface; 2],
    params: ContactParams,
    passes: Vec<Pass>,
    /// Union of the nodes of both surfaces (each pass maps its nodes into it).
    nodes: Vec<u32>,
    force: Vec<[f64; 3]>,
    ready: bool,
    ledger: ContactLedger,
    /// Global-test inflation: search margin plus the deepest allowed penetration, m.
    reach: f64,
    /// Steps on which the global bounding-box test found the surfaces apart.
    pub free_steps: usize,
    /// The stable step: it changes only when a slave touches a lighter master node.
    dt_cache: StepCache,
}

impl SurfacePair {
    /// Every slave node (global number, per pass) with the stable step (s) of its full
    /// (both-pass) spring on the lumped masses `mass` (kg): `penalty::stable_step` with the
    /// element frequency under the slave and m* pairing the slave with its reference partner
    /// or the lightest master node it has touched since. This assumes the two surfaces have
    /// similar element sizes where they meet (as the graded balls do); the penetration guard
    /// in `add_forces` catches a violation.
    fn spring_steps<'a>(&'a self, mass: &'a [f64]) -> impl Iterator<Item = (usize, f64)> + 'a {
        self.passes.iter().flat_map(move |p| {
            self.surfaces[p.slave]
                .nodes
                .iter()
                .zip(&p.laws)
                .enumerate()
                .map(move |(i, (&g, l))| {
                    let mp = p
                        .partner_mass
                        .get(i)
                        .copied()
                        .unwrap_or(mass[p.partner[i] as usize]);
                    // Both passes can load a node pair: take the full (unweighted) spring.
                    let dt = stable_step(
                        l.k / p.weight * self.params.coupling(),
                        effective_mass(mass[g as usize], mp),
                        l.omega_elem,
                    );
                    (g as usize, dt)
                })
        })
    }

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
        let wave = [
            mat_a.dilatational_wave_speed(),
            mat_b.dilatational_wave_speed(),
        ];
        let xref = nodes;
        // Boxes inflated by half the smallest edge, plus, per segment, 1.5x the allowed
        // penetration behind it, so a node beyond the limit is still found and flagged.
        let margin = 0.5 * surfaces[0].min_edge.min(surfaces[1].min_edge);
        let depths: Vec<Vec<f64>> = surfaces
            .iter()
            .map(|s| {
                s.face_thickness
                    .iter()
                    .map(|t| 1.5 * params.max_penetration * t)
                    .collect()
            })
            .collect();
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
                let laws = sf.node_laws(&params, 0.5, youngs, bulk, wave[s]);
                Pass {
                    slave: s,
                    master: m,
                    weight: 0.5,
                    laws,
                    stick: vec![StickState::default(); sf.nodes.len()],
                    search: BucketSearch::new(margin).with_depths(depths[m].clone()),
                    watched: nodes.clone(),
                    partner: sf
                        .nodes
                        .iter()
                        .map(|&g| {
                            let x = xref[g as usize];
                            *surfaces[m]
                                .nodes
                                .iter()
                                .min_by(|&&a, &&b| {
                                    norm(sub(xref[a as usize], x))
                                        .total_cmp(&norm(sub(xref[b as usize], x)))
                                })
                                .expect("surfaces are not empty")
                        })
                        .collect(),
                    partner_mass: Vec::new(),
                    slave_local: sf.nodes.iter().map(|g| local[g]).collect(),
                    face_local: surfaces[m]
                        .faces
                        .iter()
                        .map(|q| q.map(|g| local[&g]))
                        .collect(),
                    boxes: vec![Aabb::empty(); surfaces[m].faces.len()],
                    clearance: vec![0.0; sf.nodes.len()],
                    lists_seen: 0,
                }
            })
            .collect();
        let n = nodes.len();
        let reach = margin + depths.iter().flatten().cloned().fold(0.0, f64::max);
        Ok(SurfacePair {
            name: "surface-pair contact".into(),
            surfaces,
            params,
            passes,
            nodes,
            force: vec![[0.0; 3]; n],
            ready: false,
            ledger: ContactLedger::new(n),
            free_steps: 0,
            reach,
            dt_cache: StepCache::default(),
        })
    }

    /// A shared handle on this pair's output that stays readable after the pair is boxed
    /// and handed to the solver.
    pub fn probe(&self) -> ContactProbe {
        self.ledger.probe()
    }

    /// Output of the last evaluated step (forces on body A).
    pub fn output(&self) -> &ContactOutput {
        self.ledger.output()
    }

    /// Pressure at every slave node in contact at the last step (both passes).
    pub fn pressures(&self) -> &[PressureSample] {
        self.ledger.pressures()
    }

    /// Number of candidate-list rebuilds so far, summed over the passes.
    pub fn search_rebuilds(&self) -> usize {
        self.passes.iter().map(|p| p.search.rebuilds).sum()
    }

    fn prepare(&mut self, ctx: &StepContext<'_>) {
        for p in &mut self.passes {
            p.partner_mass = p.partner.iter().map(|&g| ctx.mass[g as usize]).collect();
            for (i, &g) in self.surfaces[p.slave].nodes.iter().enumerate() {
                let m = effective_mass(ctx.mass[g as usize], p.partner_mass[i]);
                let k_min = p.weight * self.params.penalty.time_step_stiffness(m, ctx.dt);
                p.laws[i].stiffen(&self.params, k_min, m);
            }
        }
        self.ready = true;
        self.dt_cache.clear();
    }

    /// The closest candidate segment of slave node `s` (m), if any.
    ///
    /// Candidates are scanned in list order (ties between equally close segments go to the
    /// first, or to an interior projection over an edge one), but a segment is projected
    /// only if the box of its corners, which holds the whole bilinear segment, comes within
    /// the distance to the segment whose box is nearest: the rest cannot be closer. On a
    /// patch of small segments this leaves one or two projections per node instead of a
    /// dozen.
    fn closest(
        x: &[[f64; 3]],
        faces: &[[u32; 4]],
        boxes: &[Aabb],
        cands: &[u32],
        s: [f64; 3],
    ) -> Option<(usize, Projection)> {
        let corners = |f: u32| faces[f as usize].map(|g| x[g as usize]);
        let (f0, _) = cands
            .iter()
            .map(|&f| (f, box_distance2(&boxes[f as usize], s)))
            .min_by(|a, b| a.1.total_cmp(&b.1))?;
        let p0 = project(&corners(f0), s);
        let cut = (p0.distance * (1.0 + 1e-8)).powi(2);
        let mut best: Option<(usize, Projection)> = None;
        for &f in cands {
            let p = if f == f0 {
                p0
            } else if box_distance2(&boxes[f as usize], s) > cut {
                continue;
            } else {
                project(&corners(f), s)
            };
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

/// Squared distance (m²) from `s` to the box `b` of a segment's corners: a lower bound of
/// the distance to the bilinear segment they span (it lies in their convex hull).
fn box_distance2(b: &Aabb, s: [f64; 3]) -> f64 {
    let mut d2 = 0.0;
    for a in 0..3 {
        let d = (b.min[a] - s[a]).max(s[a] - b.max[a]).max(0.0);
        d2 += d * d;
    }
    d2
}

impl Interaction for SurfacePair {
    fn name(&self) -> &str {
        &self.name
    }

    fn add_forces(&mut self, ctx: &StepContext<'_>, f: &mut [[f64; 3]]) -> Result<()> {
        if !self.ready {
            self.prepare(ctx);
        }
        let dt_prev = self.ledger.last_step();
        self.force.iter_mut().for_each(|v| *v = [0.0; 3]);
        let mut out = OutputBuilder::new(ctx.t);
        let mut stored = 0.0;
        // Global gap test: the boxes of the two surfaces, inflated by the search margin.
        let margin = self.reach;
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
                p.search
                    .candidates(ctx.x, &slave.nodes, &master.faces, &p.watched);
                let cands = p.search.lists();
                // Corner boxes of the candidate faces, once per step (not per node and face).
                for &f in p.search.active_segments() {
                    let mut b = Aabb::empty();
                    master.faces[f as usize]
                        .iter()
                        .for_each(|&g| b.grow(ctx.x[g as usize]));
                    p.boxes[f as usize] = b;
                }
                if p.search.rebuilds != p.lists_seen {
                    p.lists_seen = p.search.rebuilds;
                    p.clearance.iter_mut().for_each(|c| *c = 0.0);
                }
                // No point of a master segment (a convex combination of its corners) moves
                // faster than the fastest master node.
                let v_master = master
                    .nodes
                    .iter()
                    .map(|&g| norm(ctx.v[g as usize]))
                    .fold(0.0, f64::max);
                for (i, &g) in slave.nodes.iter().enumerate() {
                    // Skip a node that was clear of every candidate by more than it and the
                    // master surface can have approached since (positions moved by
                    // dt_prev v^{n+1/2} in the step just taken): to touch a convex master
                    // surface it must first cross it, at distance zero.
                    if p.clearance[i] > 0.0 {
                        p.clearance[i] -= (norm(ctx.v[g as usize]) + v_master) * dt_prev;
                        if p.clearance[i] > 0.0 {
                            continue;
                        }
                    }
                    let s = ctx.x[g as usize];
                    let hit = Self::closest(ctx.x, &master.faces, &p.boxes, &cands[i], s);
                    let Some((fi, pr)) = hit.filter(|(_, pr)| pr.gap < 0.0) else {
                        p.stick[i] = StickState::default();
                        // Half the distance found: a margin for round-off and the faceted
                        // surface's edges.
                        p.clearance[i] = hit.map_or(0.0, |(_, pr)| 0.5 * pr.distance);
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
                    let mq = quad
                        .iter()
                        .map(|&a| ctx.mass[a as usize])
                        .fold(f64::INFINITY, f64::min);
                    if mq < p.partner_mass[i] {
                        p.partner_mass[i] = mq;
                        self.dt_cache.clear();
                    }
                    let mut vm = [0.0; 3];
                    for a in 0..4 {
                        vm = add(vm, scale(nsh[a], ctx.v[quad[a] as usize]));
                    }
                    let rel = sub(ctx.v[g as usize], vm);
                    let n = pr.normal;
                    let kin = NodeKinematics {
                        gap: pr.gap,
                        gap_rate: dot(rel, n),
                        slip: scale(dt_prev, tangential(rel, n)),
                        normal: n,
                        dt: dt_prev,
                    };
                    let r = respond(&p.laws[i], &mut p.stick[i], &kin, self.params.friction);
                    self.ledger.dissipate(&r);
                    stored += stored_energy(&p.laws[i], &p.stick[i], pr.gap);
                    let fs = r.force(n);
                    let li = p.slave_local[i];
                    self.force[li] = add(self.force[li], fs);
                    for a in 0..4 {
                        let la = p.face_local[fi][a];
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
            let fnw = self.force[li];
            if fnw != [0.0; 3] {
                f[gi] = add(f[gi], fnw);
            }
            self.ledger.work(li, fnw, ctx.v[gi]);
        }
        self.ledger.finish(out, stored, ctx.dt);
        Ok(())
    }

    /// The smallest of the slave nodes' spring steps ([`SurfacePair::spring_steps`]).
    fn stable_time_step(&self, mass: &[f64], _omega: &[f64]) -> Option<f64> {
        self.dt_cache.get_or(mass, || {
            self.spring_steps(mass)
                .map(|(_, dt)| dt)
                .min_by(f64::total_cmp)
        })
    }

    fn node_limits(&self, mass: &[f64], _omega: &[f64]) -> Vec<(usize, f64)> {
        self.spring_steps(mass).collect()
    }

    fn energy(&self) -> InteractionEnergy {
        self.ledger.energy()
    }

    fn active_nodes(&self) -> Option<&[u32]> {
        Some(&self.nodes)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fe::contact::{CoulombFriction, PenaltyRule};
    use crate::mesh::block::block;
    use crate::mesh::Mesh;

    /// Block A = [0,1]² x [0,0.5] cut n_a x n_a x 1, block B on top of it cut n_b x n_b x 1,
    /// overlapping by `overlap` (m). Returns the mesh, A's top quads and B's bottom quads.
    fn stacked(n_a: usize, n_b: usize, overlap: f64) -> (Mesh, Vec<[u32; 4]>, Vec<[u32; 4]>) {
        let a = block([1.0, 1.0, 0.5], [n_a, n_a, 1]);
        let b = block([1.0, 1.0, 0.5], [n_b, n_b, 1]).translated([0.0, 0.0, 0.5 - overlap]);
        let mut m = a.clone();
        let (off, _) = m.append(&b, "b").unwrap();
        let on = |m: &Mesh, q: &[u32; 4], z: f64| {
            q.iter()
                .all(|&i| (m.nodes[i as usize][2] - z).abs() < 1e-12)
        };
        let top: Vec<[u32; 4]> = m.boundary[..a.boundary.len()]
            .iter()
            .copied()
            .filter(|q| on(&m, q, 0.5))
            .collect();
        let bottom: Vec<[u32; 4]> = m
            .boundary
            .iter()
            .copied()
            .filter(|q| q[0] as usize >= off && on(&m, q, 0.5 - overlap))
            .collect();
        (m, top, bottom)
    }

    fn eval(pair: &mut SurfacePair, m: &Mesh, v: &[[f64; 3]], dt: f64) -> Vec<[f64; 3]> {
        let mass = vec![1.0; m.nodes.len()];
        let mut f = vec![[0.0; 3]; m.nodes.len()];
        pair.add_forces(
            &StepContext {
                t: 0.0,
                dt,
                x: &m.nodes,
                v,
                mass: &mass,
            },
            &mut f,
        )
        .unwrap();
        f
    }

    /// The pair of `top` against `bottom` on mesh `m`, both of steel.
    fn steel_pair(
        m: &Mesh,
        top: &[[u32; 4]],
        bottom: &[[u32; 4]],
        params: ContactParams,
    ) -> SurfacePair {
        let mat = steel();
        SurfacePair::new(&m.nodes, &m.hexes, top, &mat, bottom, &mat, params).unwrap()
    }

    fn steel() -> Material {
        Material::preset("steel").unwrap()
    }

    #[test]
    fn flat_patch_carries_uniform_pressure_and_balances_forces() {
        // Pressure ε g with ε = FKN E / h (h = 0.5 m), on matching and non-matching meshes.
        let g = 1e-6;
        for (na, nb) in [(2, 2), (2, 3), (4, 3)] {
            let (m, top, bottom) = stacked(na, nb, g);
            let mat = steel();
            let mut pair = steel_pair(&m, &top, &bottom, ContactParams::default());
            let f = eval(&mut pair, &m, &vec![[0.0; 3]; m.nodes.len()], 1e-7);
            let eps = 10.0 * mat.youngs / 0.5;
            let total: [f64; 3] = f.iter().fold([0.0; 3], |s, v| add(s, *v));
            let o = *pair.output();
            assert!(
                total.iter().all(|c| c.abs() < 1e-9 * eps * g),
                "{na}x{nb}: net force {total:?}"
            );
            assert!(
                (o.normal_resultant[2] + eps * g).abs() < 1e-9 * eps * g,
                "{na}x{nb}: {:?}",
                o.normal_resultant
            );
            assert!((o.area - 1.0).abs() < 1e-12, "{}", o.area);
            assert!((o.stored_energy - 0.5 * eps * g * g).abs() < 1e-9 * eps * g * g);
            if na == nb {
                // Patch test: every node sees the same pressure.
                for s in pair.pressures() {
                    assert!((s.pressure - eps * g).abs() < 1e-9 * eps * g, "{s:?}");
                }
            }
        }
    }

    /// Skipping slave nodes known to be clear of the master surface changes nothing: two
    /// balls driven into each other (prescribed motion with a tangential slide) give
    /// bit-identical contact forces with the skip and with every node projected every step,
    /// and the skip does happen (most patch nodes never come near contact).
    #[test]
    fn clear_nodes_are_skipped_without_changing_any_force() {
        use crate::mesh::ball::{ball, BallSpec, Cut};
        let b1 = ball(&BallSpec {
            diameter: 0.02,
            size: 0.004,
            pole_size: Some(0.001),
            cut: Cut::Full,
        })
        .unwrap();
        // Ball 2 faces ball 1 pole to pole across a 0.1 mm gap.
        let b2 = b1.mirrored_x().translated([0.0201, 0.0, 0.0]);
        let mut m = b1.clone();
        m.append(&b2, "b2").unwrap();
        let (fa, fb) = (&m.face_sets["contact"], &m.face_sets["b2.contact"]);
        let n1 = b1.nodes.len();
        let mat = Material::preset("copper-fe").unwrap();
        let make = || {
            SurfacePair::new(
                &m.nodes,
                &m.hexes,
                fa,
                &mat,
                fb,
                &mat,
                ContactParams::default(),
            )
            .unwrap()
        };
        let (mut skipping, mut brute) = (make(), make());
        // Relative approach 4 m/s with a 1 m/s slide: touch after 25 µs, about 20 µm of
        // overlap at the end.
        let v: Vec<[f64; 3]> = (0..m.nodes.len())
            .map(|i| {
                if i < n1 {
                    [2.0, 0.5, 0.0]
                } else {
                    [-2.0, -0.5, 0.0]
                }
            })
            .collect();
        let dt = 2e-8;
        let mass = vec![1e-4; m.nodes.len()];
        let (mut touched, mut skipped) = (0, 0);
        for step in 0..1500 {
            let t = step as f64 * dt;
            let x: Vec<[f64; 3]> = m
                .nodes
                .iter()
                .zip(&v)
                .map(|(p, u)| [p[0] + u[0] * t, p[1] + u[1] * t, p[2]])
                .collect();
            let ctx = StepContext {
                t,
                dt,
                x: &x,
                v: &v,
                mass: &mass,
            };
            for p in &mut brute.passes {
                p.clearance.iter_mut().for_each(|c| *c = 0.0);
            }
            let mut fs = vec![[0.0; 3]; m.nodes.len()];
            let mut fb = vec![[0.0; 3]; m.nodes.len()];
            skipping.add_forces(&ctx, &mut fs).unwrap();
            brute.add_forces(&ctx, &mut fb).unwrap();
            assert_eq!(fs, fb, "step {step}: forces differ");
            if fs.iter().any(|f| *f != [0.0; 3]) {
                touched += 1;
            }
            skipped += skipping
                .passes
                .iter()
                .map(|p| p.clearance.iter().filter(|&&c| c > 0.0).count())
                .sum::<usize>();
        }
        assert!(touched > 100, "contact in {touched} steps only");
        assert!(skipped > 0, "no node was ever skipped");
    }

    #[test]
    fn surfaces_apart_cost_no_contact_work() {
        let (m, top, bottom) = stacked(2, 2, -1.0);
        let mut pair = steel_pair(&m, &top, &bottom, ContactParams::default());
        let f = eval(&mut pair, &m, &vec![[0.0; 3]; m.nodes.len()], 1e-7);
        assert!(f.iter().all(|v| *v == [0.0; 3]));
        assert_eq!((pair.free_steps, pair.search_rebuilds()), (1, 0));
    }

    #[test]
    fn sliding_drags_the_lower_block_with_mu_times_the_normal_force() {
        let g = 1e-6;
        let (m, top, bottom) = stacked(2, 2, g);
        let mat = steel();
        let params = ContactParams {
            friction: Some(CoulombFriction::new(0.3)),
            ..Default::default()
        };
        let mut pair =
            SurfacePair::new(&m.nodes, &m.hexes, &top, &mat, &bottom, &mat, params).unwrap();
        // B slides along +x at 10 m/s: slip 1e-5 m per step, far beyond the elastic μ g.
        let nb0 = m.nodes.len() / 2;
        let v: Vec<[f64; 3]> = (0..m.nodes.len())
            .map(|i| if i >= nb0 { [10.0, 0.0, 0.0] } else { [0.0; 3] })
            .collect();
        eval(&mut pair, &m, &v, 1e-6);
        eval(&mut pair, &m, &v, 1e-6);
        let o = *pair.output();
        let fnorm = o.normal_resultant[2].abs();
        assert!(
            (o.tangential_resultant[0] - 0.3 * fnorm).abs() < 1e-9 * fnorm,
            "{o:?}"
        );
        assert!(o.tangential_resultant[1].abs() < 1e-12 * fnorm);
        assert_eq!(o.sliding_nodes, o.active_nodes);
        // Dissipation of the second step: μ F_n |slip| (the first step had no previous step).
        let expect = 0.3 * fnorm * 1e-5;
        assert!(
            (o.friction_energy - expect).abs() < 0.05 * expect,
            "{} vs {expect}",
            o.friction_energy
        );
    }

    #[test]
    fn too_deep_penetration_is_an_error_not_a_pass_through() {
        let (m, top, bottom) = stacked(2, 2, 0.3);
        let mut pair = steel_pair(&m, &top, &bottom, ContactParams::default());
        let mass = vec![1.0; m.nodes.len()];
        let v = vec![[0.0; 3]; m.nodes.len()];
        let mut f = vec![[0.0; 3]; m.nodes.len()];
        let e = pair
            .add_forces(
                &StepContext {
                    t: 0.0,
                    dt: 1e-7,
                    x: &m.nodes,
                    v: &v,
                    mass: &mass,
                },
                &mut f,
            )
            .unwrap_err();
        assert!(matches!(e, Error::Numerical(_)), "{e}");
        assert!(e.to_string().contains("penetrates"));
    }

    #[test]
    fn stable_step_follows_the_penalty_spring() {
        let (m, top, bottom) = stacked(2, 2, 1e-6);
        let mat = steel();
        let params = ContactParams {
            penalty: PenaltyRule::Fkn { factor: 1.0 },
            ..Default::default()
        };
        let pair = SurfacePair::new(&m.nodes, &m.hexes, &top, &mat, &bottom, &mat, params).unwrap();
        let mass = vec![2.0; m.nodes.len()];
        // Stiffest node spring: an interior node, area 0.25, h = 0.5: k = E/2; m* = 1. Its
        // elements are 0.5 m cubes: Courant frequency 2 c / 0.5.
        let k = mat.youngs * 0.25 / 0.5;
        let (wp, we) = (k.sqrt(), 4.0 * mat.dilatational_wave_speed());
        let expect = (2.0 / (wp + we)).min(1.0 / wp);
        let dt = pair.stable_time_step(&mass, &[]).unwrap();
        assert!((dt - expect).abs() < 1e-12 * expect, "{dt} vs {expect}");
    }
}
