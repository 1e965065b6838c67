//! Estimated cost of a sweep case and shards balanced by it.
//!
//! The cost of an FE case is its element count times its explicit steps: elements of the
//! meshes the run builds (one quarter ball against the mirror plane, or two half or whole
//! balls, as [`choose_reduction`] picks; the quads of the meridian sections of an
//! axisymmetric run, a quad-step counted as one element-step), steps = simulated time / stable step, with the
//! simulated time the analytical contact duration plus the stop rule's hold time and the
//! stable step the Courant limit of the smallest element (L_e / c, times the scene's
//! `solver.time_step_factor`). Subcycling is left out, so the estimate is an upper bound on
//! the element updates a run reports. A case without impact costs nothing but its overhead.
//! A sweep case on the meridian section runs phase ensembles, or with `[study] tolerance` the
//! banded family, and is costed as such ([`Estimator::estimate_to`]).

use crate::error::Result;
use crate::fe::section::mass_scaling::within_budget;
use crate::fe::solver::timestep::characteristic_length;
use crate::mesh::ball::{ball, BallSpec, Cut};
use crate::mesh::quality::hex_volume;
use crate::mesh::section::SectionMesh;
use crate::mesh::Mesh;
use crate::scene::{approach, Approach, MeshSettings, Scene};
use crate::study::convergence::phase_band::banded_mesh;
use crate::study::convergence::phase_ensemble::{
    family_mesh, hertz_contact_radius, HeadOnCase, HeadOnTarget,
};
use crate::study::records::outcome::analytic_outcome;
use crate::study::run::simulate::{choose_reduction, Reduction, DEFAULT_HOLD_FRACTION};
use std::collections::HashMap;
use std::sync::Mutex;

/// Cost of any case, in element-steps, besides its FE run (approach, analytical model, files):
/// keeps cases without impact from piling up on one shard.
pub const CASE_OVERHEAD: f64 = 1.0e3;

/// The estimated work of one case.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CostEstimate {
    /// Elements simulated (all parts of the reduced model).
    pub elements: usize,
    /// Explicit steps (simulated time / stable step).
    pub steps: f64,
}

impl CostEstimate {
    /// Element-steps plus [`CASE_OVERHEAD`].
    pub fn element_steps(&self) -> f64 {
        self.elements as f64 * self.steps + CASE_OVERHEAD
    }
}

/// Smallest Courant length L_e = V / (largest face area) of `mesh`'s elements, m.
fn smallest_length(mesh: &Mesh) -> f64 {
    mesh.hexes
        .iter()
        .map(|h| {
            let x = h.map(|n| mesh.nodes[n as usize]);
            characteristic_length(&x, hex_volume(&x).abs())
        })
        .fold(f64::INFINITY, f64::min)
}

/// Element count and smallest Courant length (m) of each ball mesh costed so far: a sweep
/// meshes the same ball for many speeds, and every task of a job array costs every case.
#[derive(Debug, Default)]
pub struct Estimator {
    meshes: Mutex<HashMap<String, (usize, f64)>>,
}

impl Estimator {
    /// Element count and smallest Courant length (m) of the ball mesh `spec`.
    fn mesh(&self, spec: &BallSpec) -> Result<(usize, f64)> {
        let key = format!(
            "{:e} {:e} {:?} {:?}",
            spec.diameter, spec.size, spec.pole_size, spec.cut
        );
        let cached = self.meshes.lock().ok().and_then(|m| m.get(&key).copied());
        if let Some(hit) = cached {
            return Ok(hit);
        }
        let mesh = ball(spec)?;
        let stats = (mesh.n_elements(), smallest_length(&mesh));
        if let Ok(mut m) = self.meshes.lock() {
            m.insert(key, stats);
        }
        Ok(stats)
    }

    /// Quad count and smallest characteristic length (m) of the meridian section of ball
    /// `name`, as the axisymmetric run meshes it.
    fn section(&self, name: &str, b: &crate::scene::BallScene) -> Result<(usize, f64)> {
        let key = match b.mesh {
            MeshSettings::Builtin { size, pole_size } => {
                format!("section {:e} {size:e} {pole_size:e}", b.diameter)
            }
            MeshSettings::File { .. } => String::new(),
        };
        let cached = self.meshes.lock().ok().and_then(|m| m.get(&key).copied());
        if let Some(hit) = cached {
            return Ok(hit);
        }
        let mesh = crate::study::run::section::section_mesh(name, b)?;
        let length = mesh
            .quads
            .iter()
            .map(|q| {
                crate::fe::elements::ring::shape::characteristic_length(
                    &q.map(|n| mesh.nodes[n as usize]),
                )
            })
            .fold(f64::INFINITY, f64::min);
        let stats = (mesh.quads.len(), length);
        if let Ok(mut m) = self.meshes.lock() {
            m.insert(key, stats);
        }
        Ok(stats)
    }

    /// The estimated cost of running `scene` through the FE model (`fe`) or the analytical
    /// model only (`!fe`: no elements).
    ///
    /// Errors: as [`approach`] and [`analytic_outcome`]; the mesh generator's errors for the
    /// scene's mesh settings. A mesh read from a file is not read: it is costed as a built-in
    /// mesh with the default sizes.
    pub fn estimate(&self, scene: &Scene, fe: bool) -> Result<CostEstimate> {
        let none = CostEstimate {
            elements: 0,
            steps: 0.0,
        };
        let touch = match approach(scene)? {
            Approach::NoImpact { .. } => return Ok(none),
            Approach::Impact(t) => t,
        };
        if !fe {
            return Ok(none);
        }
        let (outcome, _) = analytic_outcome(scene, &touch)?;
        let (reduction, _) = choose_reduction(scene, &touch)?;
        let (cut, parts) = match reduction {
            Reduction::Axisymmetric => (Cut::Full, 0),
            Reduction::Quarter => (Cut::Quarter, 1),
            Reduction::Half => (Cut::Half, 2),
            Reduction::Full => (Cut::Full, 2),
        };
        let mut elements = 0;
        let mut dt = f64::INFINITY;
        if reduction == Reduction::Axisymmetric {
            let sections = if scene.identical_balls() { 1 } else { 2 };
            for (name, b) in [("ball1", &scene.ball1), ("ball2", &scene.ball2)]
                .into_iter()
                .take(sections)
            {
                let (n, length) = self.section(name, b)?;
                elements += n;
                dt = dt.min(length / b.material.dilatational_wave_speed());
            }
        }
        for b in [&scene.ball1, &scene.ball2].into_iter().take(parts) {
            let (size, pole_size) = match b.mesh {
                MeshSettings::Builtin { size, pole_size } => (size, pole_size),
                MeshSettings::File { .. } => (
                    crate::scene::DEFAULT_SIZE_PER_D * b.diameter,
                    crate::scene::DEFAULT_POLE_SIZE_PER_D * b.diameter,
                ),
            };
            let (n, length) = self.mesh(&BallSpec {
                diameter: b.diameter,
                size,
                pole_size: Some(pole_size),
                cut,
            })?;
            elements += n;
            dt = dt.min(length / b.material.dilatational_wave_speed());
        }
        let dt = dt * scene.solver.time_step_factor;
        let simulated = simulated_time(scene, outcome.contact_duration);
        let steps = if dt.is_finite() && dt > 0.0 && simulated.is_finite() {
            (simulated / dt).ceil()
        } else {
            0.0
        };
        Ok(CostEstimate { elements, steps })
    }
}

impl Estimator {
    /// The estimated cost of `scene` as a sweep case runs it ([`crate::study::convergence::scene_estimate::sweep_case_to`]
    /// with `tolerance`): a head-on scene on the meridian section runs phase ensembles, not
    /// its mesh once. With a tolerance that the banded family covers, the family's runs
    /// ([`Estimator::banded_family`]; for a tolerance of 2 % or looser an upper bound, since
    /// the scene's own levels −1 and 0, about a thirtieth of it, may meet it first and end
    /// the case: [`crate::study::convergence::scene_estimate::run_to_tolerance`]); otherwise its default ladder, levels
    /// −1 and 0 of [`crate::study::convergence::scene_estimate::SCENE_PHASE_MESHES`] meshes each (a level −1 mesh has a
    /// quarter of the quads and twice the step: an eighth of the cost). Any other case as
    /// [`Estimator::estimate`].
    ///
    /// Errors: as [`Estimator::estimate`].
    pub fn estimate_to(
        &self,
        scene: &Scene,
        fe: bool,
        tolerance: Option<f64>,
    ) -> Result<CostEstimate> {
        // The family's cost does not depend on the scene's own mesh: it is not meshed.
        if let (true, Some(t)) = (fe, tolerance) {
            let budget = crate::study::convergence::converged_scene::mass_scaling_for(t);
            if let Ok(case) =
                crate::study::convergence::converged_scene::head_on_case(scene, budget)?
            {
                if let Approach::Impact(touch) = approach(scene)? {
                    let (outcome, _) = analytic_outcome(scene, &touch)?;
                    let simulated = simulated_time(scene, outcome.contact_duration);
                    return self.banded_family(&case, simulated, outcome.delta_max);
                }
            }
        }
        let own = self.estimate(scene, fe)?;
        if !fe || own.elements == 0 {
            return Ok(own);
        }
        match crate::study::convergence::scene_estimate::default_plan(scene)? {
            Some(_) => Ok(CostEstimate {
                elements: own.elements,
                steps: own.steps
                    * crate::study::convergence::scene_estimate::SCENE_PHASE_MESHES as f64
                    * (1.0 + 1.0 / 8.0),
            }),
            None => Ok(own),
        }
    }

    /// The cost of the banded family as `twoball run --tolerance` runs `case` for `simulated`
    /// seconds each run: the pilot (plain family level 0 at Hertz's contact radius) and
    /// levels 0 and 1 of [`crate::study::convergence::converged_scene::MESHES`] meshes each, banded around the
    /// edge of a ball flattened by `delta_max` (m; the analytical estimate): a = √(2 R h),
    /// h = δ/2 against the mirror ball, δ against a wall. Each mesh runs at its mass-scaled
    /// step; subcycling is left out (an upper bound).
    fn banded_family(
        &self,
        case: &HeadOnCase,
        simulated: f64,
        delta_max: f64,
    ) -> Result<CostEstimate> {
        use crate::study::convergence::converged_scene::{FINE_LEVEL, MESHES, SPLIT};
        let d = case.diameter;
        let depth = match case.target {
            HeadOnTarget::IdenticalBall => delta_max / 2.0,
            HeadOnTarget::RigidWall => delta_max,
        };
        let edge = (d * depth).sqrt();
        let mut elements = 0;
        let mut element_steps = 0.0;
        let mut add = |(quads, step): (usize, f64), runs: usize| {
            elements += runs * quads;
            element_steps += (runs * quads) as f64 * (simulated / (0.9 * step)).ceil();
        };
        let a = hertz_contact_radius(case);
        let pilot = format!("family {d:e} {a:e}");
        add(self.meridian(&pilot, case, || family_mesh(d, a, 0))?, 1);
        for level in FINE_LEVEL as u32 - 1..=FINE_LEVEL as u32 {
            let key = format!("banded {d:e} {edge:e} {level}");
            add(
                self.meridian(&key, case, || banded_mesh(d, edge, level, SPLIT, 1.0))?,
                MESHES,
            );
        }
        Ok(CostEstimate {
            elements,
            steps: element_steps / elements.max(1) as f64,
        })
    }

    /// Quad count and smallest Courant step (s) of the meridian mesh `make` builds, for
    /// `case`'s material and mass-scaling budget, cached under `key`.
    fn meridian(
        &self,
        key: &str,
        case: &HeadOnCase,
        make: impl Fn() -> Result<SectionMesh>,
    ) -> Result<(usize, f64)> {
        let m = &case.material;
        let key = format!(
            "{key} {:e} {:e} {:e}",
            m.dilatational_wave_speed(),
            m.rho,
            case.mass_scaling
        );
        let cached = self.meshes.lock().ok().and_then(|c| c.get(&key).copied());
        if let Some(hit) = cached {
            return Ok(hit);
        }
        let mesh = make()?;
        let c = m.dilatational_wave_speed();
        let scaled = within_budget(
            &mesh.nodes,
            &mesh.quads,
            |_| c,
            |_| m.rho,
            case.mass_scaling,
        )?;
        let stats = (
            mesh.quads.len(),
            scaled.target_step.max(scaled.unscaled_step),
        );
        if let Ok(mut cache) = self.meshes.lock() {
            cache.insert(key, stats);
        }
        Ok(stats)
    }
}

/// Time a run of `scene` simulates (s): its end time, or the analytical contact duration
/// `duration` (s) and the stop rule's hold time.
fn simulated_time(scene: &Scene, duration: f64) -> f64 {
    scene
        .solver
        .end_time
        .unwrap_or(duration * (1.0 + DEFAULT_HOLD_FRACTION))
}

/// [`Estimator::estimate`] for one scene.
///
/// Errors: as [`Estimator::estimate`].
pub fn estimate(scene: &Scene, fe: bool) -> Result<CostEstimate> {
    Estimator::default().estimate(scene, fe)
}

/// Deals items of cost `costs` (≥ 0) to `n` ≥ 1 shards, costliest first, each to the shard
/// with the least cost so far (ties: lower item index first, lower shard first). Returns the
/// 0-based shard of each item. Deterministic: every task of a job array computes the same plan.
///
/// The costliest shard exceeds the mean by at most the costliest single item.
pub fn balance(costs: &[f64], n: usize) -> Vec<usize> {
    let n = n.max(1);
    let mut order: Vec<usize> = (0..costs.len()).collect();
    order.sort_by(|&a, &b| costs[b].total_cmp(&costs[a]).then(a.cmp(&b)));
    let mut load = vec![0.0f64; n];
    let mut plan = vec![0; costs.len()];
    for i in order {
        let s = (0..n)
            .min_by(|&a, &b| load[a].total_cmp(&load[b]).then(a.cmp(&b)))
            .unwrap_or(0);
        load[s] += costs[i];
        plan[i] = s;
    }
    plan
}

/// The total cost of each of `n` shards under `plan` (from [`balance`]).
pub fn shard_loads(costs: &[f64], plan: &[usize], n: usize) -> Vec<f64> {
    let mut load = vec![0.0; n.max(1)];
    for (c, &s) in costs.iter().zip(plan) {
        load[s] += c;
    }
    load
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn balance_partitions_and_bounds_the_longest_shard() {
        // Blocks of equal costs in case order (as a sweep lists them): dealt by cost, not order.
        let costs: Vec<f64> = (0..72)
            .map(|i| {
                if i % 6 == 5 {
                    1.0
                } else {
                    (1 + i / 6) as f64 * 100.0
                }
            })
            .collect();
        for n in [1, 3, 8, 72] {
            let plan = balance(&costs, n);
            assert_eq!(plan.len(), costs.len());
            assert!(plan.iter().all(|&s| s < n));
            let load = shard_loads(&costs, &plan, n);
            let mean = costs.iter().sum::<f64>() / n as f64;
            let most = costs.iter().cloned().fold(0.0, f64::max);
            let longest = load.iter().cloned().fold(0.0, f64::max);
            assert!(
                longest <= mean + most + 1e-9,
                "n = {n}: {longest} > {mean} + {most}"
            );
            assert!((load.iter().sum::<f64>() - costs.iter().sum::<f64>()).abs() < 1e-6);
        }
        // Equal costs: round-robin, every shard one more or one fewer.
        let plan = balance(&[1.0; 10], 4);
        assert_eq!(plan, vec![0, 1, 2, 3, 0, 1, 2, 3, 0, 1]);
    }

    #[test]
    fn a_section_case_costs_its_ensembles_and_a_tolerance_its_family() {
        use crate::scene::{Override, DEFAULT_SCENE};
        let scene = |sets: &[&str]| {
            let sets: Vec<Override> = sets.iter().map(|s| Override::parse(s).unwrap()).collect();
            Scene::from_toml(DEFAULT_SCENE, std::path::Path::new("."), &sets).unwrap()
        };
        let est = Estimator::default();
        let section = scene(&[]);
        let work = |t: Option<f64>| {
            est.estimate_to(&section, true, t).unwrap().element_steps() - CASE_OVERHEAD
        };
        let own = est.estimate(&section, true).unwrap().element_steps() - CASE_OVERHEAD;
        let (ladder, family) = (work(None), work(Some(0.005)));
        assert!((ladder / own - 4.5).abs() < 1e-3, "{ladder} / {own}");
        // Measured: 6.4 s of CPU for `--tolerance 0.5%` against 0.28 s for the default run
        // (23 times); the estimate leaves subcycling out, so it may lie above that.
        eprintln!("family / ladder {:.1}", family / ladder);
        assert!(
            (20.0..45.0).contains(&(family / ladder)),
            "{family} / {ladder}"
        );
        let quarter = scene(&["reduction.symmetry=\"auto-3d\""]);
        assert_eq!(
            est.estimate_to(&quarter, true, Some(0.005)).unwrap(),
            est.estimate(&quarter, true).unwrap()
        );
    }
}
