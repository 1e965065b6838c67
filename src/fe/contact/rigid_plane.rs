//! A deformable surface against a rigid plane: the mirror image of a symmetric ball–ball impact
//! (frictionless), a wall (frictional), or a moving platen for quasi-static compression.

use super::friction::StickState;
use super::law::{respond, stored_energy, NodeKinematics, NodeLaw};
use super::ledger::ContactLedger;
use super::output::{ContactOutput, ContactProbe, NodeContact, OutputBuilder, PressureSample};
use super::params::ContactParams;
use super::penalty::stable_step;
use super::step_cache::StepCache;
use super::surface::ContactSurface;
use crate::error::{Error, Result};
use crate::fe::interaction::{Interaction, InteractionEnergy, StepContext};
use crate::fe::tensor::{add_into, axpy, dot, norm, scale, sub, tangential};
use crate::material::Material;

/// Penalty contact of one surface against the half-space behind a rigid plane.
#[derive(Debug, Clone)]
pub struct RigidPlane {
    name: String,
    surface: ContactSurface,
    /// A point of the plane at t = 0, m.
    point: [f64; 3],
    /// Unit normal pointing out of the rigid half-space (towards the body).
    normal: [f64; 3],
    /// Plane velocity (rigid translation), m/s.
    velocity: [f64; 3],
    /// The plane moves until this time, then stays (s; infinite = always).
    stop: f64,
    params: ContactParams,
    youngs: f64,
    bulk: f64,
    laws: Vec<NodeLaw>,
    ready: bool,
    stick: Vec<StickState>,
    ledger: ContactLedger,
    /// The stable step: the node laws change only in `prepare`, which clears it.
    dt_cache: StepCache,
}

impl RigidPlane {
    /// Contact of the outward quads `faces` of the hexahedra `hexes` over reference
    /// coordinates `nodes` (m), body material `material`, against the plane through
    /// `point` (m) with unit normal `normal` pointing towards the body.
    ///
    /// Fails with [`Error::Invalid`] for a bad face set, a zero or non-finite normal or point,
    /// or invalid `params`.
    pub fn new(
        nodes: &[[f64; 3]],
        hexes: &[[u32; 8]],
        faces: &[[u32; 4]],
        material: &Material,
        point: [f64; 3],
        normal: [f64; 3],
        params: ContactParams,
    ) -> Result<RigidPlane> {
        let params = params.validated("wall")?;
        let surface = ContactSurface::new(nodes, hexes, faces, "wall.faces")?;
        let l = norm(normal);
        if !(l.is_finite() && l > 0.0) {
            return Err(Error::invalid(
                "wall.normal",
                format!("{normal:?}"),
                "a non-zero finite vector",
            ));
        }
        if point.iter().any(|v| !v.is_finite()) {
            return Err(Error::invalid(
                "wall.point",
                format!("{point:?}"),
                "finite coordinates",
            ));
        }
        let laws = surface.node_laws(
            &params,
            1.0,
            material.youngs,
            material.bulk_modulus(),
            material.dilatational_wave_speed(),
        );
        let n = surface.nodes.len();
        Ok(RigidPlane {
            name: "rigid-plane contact".into(),
            surface,
            point,
            normal: scale(1.0 / l, normal),
            velocity: [0.0; 3],
            stop: f64::INFINITY,
            params,
            youngs: material.youngs,
            bulk: material.bulk_modulus(),
            laws,
            ready: false,
            stick: vec![StickState::default(); n],
            ledger: ContactLedger::new(n),
            dt_cache: StepCache::default(),
        })
    }

    /// The same plane translating rigidly at `velocity` (m/s).
    pub fn with_velocity(mut self, velocity: [f64; 3]) -> Self {
        self.velocity = velocity;
        self
    }

    /// The same plane translating at `velocity` (m/s) until time `duration` (s), then at rest:
    /// a ramp of depth |velocity| × duration for quasi-static compression.
    pub fn with_ramp(mut self, velocity: [f64; 3], duration: f64) -> Self {
        self.velocity = velocity;
        self.stop = duration;
        self
    }

    /// The contact surface (nodes, tributary areas).
    pub fn surface(&self) -> &ContactSurface {
        &self.surface
    }

    /// A shared handle on this pair's output that stays readable after the pair is boxed
    /// and handed to the solver.
    pub fn probe(&self) -> ContactProbe {
        self.ledger.probe()
    }

    /// Output of the last evaluated step.
    pub fn output(&self) -> &ContactOutput {
        self.ledger.output()
    }

    /// Pressure at every node in contact at the last evaluated step.
    pub fn pressures(&self) -> &[PressureSample] {
        self.ledger.pressures()
    }

    /// Normal penalty stiffness of each surface node (after the first step for the SOFT rule), N/m.
    pub fn node_stiffness(&self) -> Vec<f64> {
        self.laws.iter().map(|l| l.k).collect()
    }

    /// Young's and bulk moduli the penalty is scaled by, Pa.
    pub fn moduli(&self) -> (f64, f64) {
        (self.youngs, self.bulk)
    }

    /// The smallest `penalty::stable_step` of the node springs as the laws are now, for nodal
    /// masses `mass` (kg): s, `None` for an empty surface.
    fn smallest_spring_step(&self, mass: &[f64]) -> Option<f64> {
        self.spring_steps(mass)
            .map(|(_, dt)| dt)
            .min_by(f64::total_cmp)
    }

    /// Each surface node (global number) with the stable step (s) of its spring on the
    /// lumped masses `mass` (kg).
    fn spring_steps<'a>(&'a self, mass: &'a [f64]) -> impl Iterator<Item = (usize, f64)> + 'a {
        self.surface.nodes.iter().zip(&self.laws).map(|(&g, l)| {
            let g = g as usize;
            (
                g,
                stable_step(l.k * self.params.coupling(), mass[g], l.omega_elem),
            )
        })
    }

    fn prepare(&mut self, ctx: &StepContext<'_>) {
        for (i, &g) in self.surface.nodes.iter().enumerate() {
            let m = ctx.mass[g as usize];
            let k_min = self.params.penalty.time_step_stiffness(m, ctx.dt);
            self.laws[i].stiffen(&self.params, k_min, m);
        }
        self.ready = true;
        self.dt_cache.clear();
    }
}

impl Interaction for RigidPlane {
    fn name(&self) -> &str {
        &self.name
    }

    fn add_forces(&mut self, ctx: &StepContext<'_>, f: &mut [[f64; 3]]) -> Result<()> {
        if !self.ready {
            self.prepare(ctx);
        }
        let origin = axpy(self.point, ctx.t.min(self.stop), self.velocity);
        let wall_v = if ctx.t < self.stop {
            self.velocity
        } else {
            [0.0; 3]
        };
        let n = self.normal;
        let dt_prev = self.ledger.last_step();
        let mut out = OutputBuilder::new(ctx.t);
        let mut stored = 0.0;
        for (i, &g) in self.surface.nodes.iter().enumerate() {
            let gi = g as usize;
            let gap = dot(sub(ctx.x[gi], origin), n);
            let mut force = [0.0; 3];
            if gap < 0.0 {
                if -gap > self.params.max_penetration * self.surface.thickness[i] {
                    return Err(Error::Numerical(format!(
                        "{}: node {g} penetrates {:.3e} m at t = {:.6e} s, more than {} of its element \
                         thickness {:.3e} m; raise the penalty factor or lower the time step",
                        self.name, -gap, ctx.t, self.params.max_penetration, self.surface.thickness[i]
                    )));
                }
                let rel = sub(ctx.v[gi], wall_v);
                let kin = NodeKinematics {
                    gap,
                    gap_rate: dot(rel, n),
                    slip: scale(dt_prev, tangential(rel, n)),
                    normal: n,
                    dt: dt_prev,
                };
                let r = respond(
                    &self.laws[i],
                    &mut self.stick[i],
                    &kin,
                    self.params.friction,
                );
                self.ledger.dissipate(&r);
                stored += stored_energy(&self.laws[i], &self.stick[i], gap);
                force = r.force(n);
                let s = PressureSample {
                    node: g,
                    position: ctx.x[gi],
                    normal: n,
                    pressure: r.normal / self.surface.area[i],
                    area: self.surface.area[i],
                };
                out.add(
                    1.0,
                    s,
                    NodeContact {
                        normal: r.normal,
                        tangential: r.tangential,
                        penetration: -gap,
                        sliding: self.stick[i].sliding,
                    },
                );
            } else {
                self.stick[i] = StickState::default();
            }
            add_into(f, gi, force);
            self.ledger.work(i, force, ctx.v[gi]);
        }
        self.ledger.finish(out, stored, ctx.dt);
        Ok(())
    }

    fn stable_time_step(&self, mass: &[f64], _omega: &[f64]) -> Option<f64> {
        self.dt_cache
            .get_or(mass, || self.smallest_spring_step(mass))
    }

    fn energy(&self) -> InteractionEnergy {
        self.ledger.energy()
    }

    fn active_nodes(&self) -> Option<&[u32]> {
        Some(&self.surface.nodes)
    }

    fn node_limits(&self, mass: &[f64], _omega: &[f64]) -> Vec<(usize, f64)> {
        self.spring_steps(mass).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fe::contact::PenaltyRule;
    use crate::mesh::{block::block, Mesh};

    /// A 1 x 1 x 0.5 m block of 3 x 3 x 1 elements (h = 0.5 m) and its bottom faces (z = 0).
    fn block_and_bottom() -> (Mesh, Vec<[u32; 4]>) {
        let m = block([1.0, 1.0, 0.5], [3, 3, 1]);
        let bottom = m
            .boundary
            .iter()
            .copied()
            .filter(|q| q.iter().all(|&i| m.nodes[i as usize][2] == 0.0))
            .collect();
        (m, bottom)
    }

    /// `wall.add_forces` at t = 0 with step `dt` (s) for the nodes of `m` at rest where they
    /// were made, with masses `mass` (kg); forces (N) into `f`.
    fn at_rest(
        wall: &mut RigidPlane,
        m: &Mesh,
        mass: &[f64],
        dt: f64,
        f: &mut [[f64; 3]],
    ) -> Result<()> {
        let v = vec![[0.0; 3]; m.nodes.len()];
        let ctx = StepContext {
            t: 0.0,
            dt,
            x: &m.nodes,
            v: &v,
            mass,
        };
        wall.add_forces(&ctx, f)
    }

    #[test]
    fn flat_face_pressed_into_the_plane_carries_eps_g_per_area() {
        // Bottom face of a 1 x 1 x 0.5 block, 3 x 3 x 1 elements (h = 0.5), plane at z = g.
        let (m, bottom) = block_and_bottom();
        let mat = Material::preset("steel").unwrap();
        let g = 1e-6;
        let mut wall = RigidPlane::new(
            &m.nodes,
            &m.hexes,
            &bottom,
            &mat,
            [0.0, 0.0, g],
            [0.0, 0.0, 1.0],
            ContactParams::default(),
        )
        .unwrap();
        let mass = vec![1.0; m.nodes.len()];
        let mut f = vec![[0.0; 3]; m.nodes.len()];
        at_rest(&mut wall, &m, &mass, 1e-7, &mut f).unwrap();
        let eps = 10.0 * mat.youngs / 0.5;
        let fz: f64 = f.iter().map(|v| v[2]).sum();
        assert!((fz - eps * g).abs() < 1e-9 * eps * g, "{fz}");
        assert!(wall
            .pressures()
            .iter()
            .all(|s| (s.pressure - eps * g).abs() < 1e-9 * eps * g));
        let o = *wall.output();
        assert_eq!(o.active_nodes, 16);
        assert!((o.stored_energy - 0.5 * eps * g * g).abs() < 1e-9 * eps * g * g);
        // Stable step of the stiffest spring: interior node, A = 1/9, k = ε A, m = 1, on
        // elements 1/3 x 1/3 x 0.5 (Courant length V / largest face = 1/3: frequency 6 c).
        let dt = wall.stable_time_step(&mass, &[]).unwrap();
        let (wp, we) = ((eps / 9.0).sqrt(), 6.0 * mat.dilatational_wave_speed());
        let expect = (2.0 / (wp + we)).min(1.0 / wp);
        assert!((dt - expect).abs() < 1e-12 * dt, "{dt} vs {expect}");
        // A node pushed through half its element thickness stops the run.
        let deep = RigidPlane::new(
            &m.nodes,
            &m.hexes,
            &bottom,
            &mat,
            [0.0, 0.0, 0.3],
            [0.0, 0.0, 1.0],
            ContactParams::default(),
        );
        let e = at_rest(&mut deep.unwrap(), &m, &mass, 1e-7, &mut f);
        assert!(matches!(e, Err(Error::Numerical(_))));
        // Bad input is an error naming the field.
        let bad = RigidPlane::new(
            &m.nodes,
            &m.hexes,
            &bottom,
            &mat,
            [0.0; 3],
            [0.0; 3],
            ContactParams::default(),
        );
        assert!(bad.unwrap_err().to_string().contains("wall.normal"));
    }

    /// The stable step is cached, so it must follow what it depends on: the node laws (the
    /// Soft rule stiffens them at the first step) and the mass array it is asked about.
    #[test]
    fn cached_stable_step_follows_laws_and_masses() {
        let (m, bottom) = block_and_bottom();
        let mat = Material::preset("steel").unwrap();
        let params = ContactParams {
            penalty: PenaltyRule::Soft {
                scale: 0.1,
                dt_scale: 0.05,
            },
            ..Default::default()
        };
        let mut wall = RigidPlane::new(
            &m.nodes,
            &m.hexes,
            &bottom,
            &mat,
            [0.0, 0.0, -1.0],
            [0.0, 0.0, 1.0],
            params,
        )
        .unwrap();
        let light = vec![1e-6; m.nodes.len()];
        let before = wall.stable_time_step(&light, &[]).unwrap();
        assert_eq!(before, wall.smallest_spring_step(&light).unwrap());
        // A step so short that the Soft rule's m/Δt² term (5e10 N/m here) outweighs its bulk
        // term (0.2e9-3.4e9 N/m): the first step stiffens every law.
        let mut f = vec![[0.0; 3]; m.nodes.len()];
        at_rest(&mut wall, &m, &light, 1e-9, &mut f).unwrap();
        let after = wall.stable_time_step(&light, &[]).unwrap();
        assert_eq!(after, wall.smallest_spring_step(&light).unwrap());
        assert!(
            after < 0.5 * before,
            "{after} vs {before}: the stiffer laws must show"
        );
        let heavy = vec![1.0; m.nodes.len()];
        let h = wall.stable_time_step(&heavy, &[]).unwrap();
        assert_eq!(h, wall.smallest_spring_step(&heavy).unwrap());
        assert!(h > 10.0 * after);
    }
}
