//! The FE side of the benchmark: one head-on point on the meridian section, converged over
//! the phase of its rings with error bars under an [`FePlan`] ([`head_on_fe`]; a point of a
//! rate-independent metal may be scaled from one of another diameter, [`FePoint::scaled`]),
//! and one oblique point on the 3D half model ([`oblique_fe`]), each with the numbers the
//! laws are compared with.

use super::matrix::{HeadOnPoint, ObliquePoint};
use crate::analytic::{Body, HertzPair};
use crate::error::{Error, Result};
use crate::fe::elements::ring::QuadFormulation;
use crate::mesh::section::band::depth_for;
use crate::scene::Scene;
use crate::study::convergence::ladder::LadderPlan;
use crate::study::convergence::phase_ensemble::{
    converged_head_on, HeadOnCase, HeadOnTarget, PhasePlan, MIN_LEVEL,
};
use crate::study::convergence::scene_estimate::run_scene_with_estimate;
use crate::study::records::estimate::value_and_error;
use crate::study::records::estimate::Estimate;
use crate::study::run::section_impact::PlaneContact;
use crate::study::run::simulate::RunOptions;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// What the FE says about one head-on point.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FePoint {
    /// Coefficient of restitution, -.
    #[serde(with = "value_and_error")]
    pub e: Estimate,
    /// Maximum approach of the centres, m.
    #[serde(with = "value_and_error")]
    pub delta_max: Estimate,
    /// Contact duration, s.
    #[serde(with = "value_and_error")]
    pub contact_duration: Estimate,
    /// Peak normal force, N.
    #[serde(with = "value_and_error")]
    pub peak_force: Estimate,
    /// The pilot run's contact history: rows [t (s), δ (m), F (N)].
    pub curve: Vec<[f64; 3]>,
    /// Seconds of one core the point cost (the runs' wall times, each run on one thread;
    /// 0 for a scaled point).
    pub cpu_seconds: f64,
    /// Diameter (m) of the run point this one is scaled from by similarity (`None`: run).
    #[serde(default)]
    pub scaled_from: Option<f64>,
    /// Family level of the fine ensemble that answered (the plan's, or one deeper where the
    /// plan's tolerance refined the point; `None` in caches written before it was recorded).
    #[serde(default)]
    pub fine_level: Option<i32>,
}

/// What the FE says about one oblique point (contact frame: normal x, tangential y, spins
/// about z), each figure with its two-level error bar (mesh levels −1 and 0).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ObliqueFe {
    /// Coefficient of restitution, -.
    #[serde(with = "value_and_error")]
    pub e: Estimate,
    /// Tangential restitution of the contact points −u⁺/u⁻, -.
    #[serde(with = "value_and_error")]
    pub tangential_restitution: Estimate,
    /// Spin of ball 1 after the impact, rad/s.
    #[serde(with = "value_and_error")]
    pub spin: Estimate,
    /// Tangential velocity of ball 1 after the impact, m/s.
    pub v1t_after: f64,
    /// Maximum approach, m.
    #[serde(with = "value_and_error")]
    pub delta_max: Estimate,
    /// Contact duration, s.
    #[serde(with = "value_and_error")]
    pub contact_duration: Estimate,
    /// Largest relative energy error of the level-0 run.
    pub energy_error: f64,
    /// Seconds of both runs (wall time; the 3D loop may use more than one core).
    pub wall_seconds: f64,
}

/// How converged every head-on FE point is: the phase ensembles of
/// [`crate::study::convergence::phase_ensemble::converged_head_on`], fine on family level `phase.level`,
/// coarse on `level − 1`, `meshes` meshes each.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FePlan {
    /// The phase ensembles' plan (level, meshes, band, tolerance; a point refines at most
    /// one level under a tolerance).
    pub phase: PhasePlan,
    /// Mass-scaling budget of every head-on run (added mass over the section's; 0: none;
    /// [`HeadOnCase::mass_scaling`]).
    pub mass_scaling: f64,
}

/// The bench's default plan: the banded family (a five-fold band confined to a sixth of the
/// rays below the surface, [`crate::mesh::section::band::SURFACE_DEPTH`]) with fine level 1 and
/// coarse level 0, two meshes each, every run mass-scaled within 1e-4 of the section's mass,
/// a point whose bar of e exceeds 0.5 % refined one level (docs/contact-laws.md, "FE error
/// bars").
pub const DEFAULT_FE_PLAN: FePlan = FePlan {
    phase: PhasePlan {
        level: 1,
        meshes: 2,
        band: Some(5),
        tolerance: Some(0.005),
        max_refinements: 1,
    },
    mass_scaling: 1e-4,
};

impl Default for FePlan {
    fn default() -> Self {
        DEFAULT_FE_PLAN
    }
}

impl FePlan {
    /// A checked plan on the plain family (no band, no mass scaling).
    ///
    /// Errors: a level outside the fine levels phase_ensemble accepts, or `meshes` odd or
    /// below 2 (one line naming `--fe-level` or `--phase-meshes`).
    pub fn new(level: i32, meshes: usize) -> Result<FePlan> {
        let max = crate::mesh::section::ladder::MAX_LEVEL as i32;
        if !(MIN_LEVEL..=max).contains(&level) {
            return Err(Error::invalid(
                "--fe-level",
                level,
                format!("an integer in {MIN_LEVEL}..={max}"),
            ));
        }
        if meshes < 2 || !meshes.is_multiple_of(2) {
            return Err(Error::invalid(
                "--phase-meshes",
                meshes,
                "an even number >= 2",
            ));
        }
        Ok(FePlan {
            phase: PhasePlan {
                level,
                meshes,
                ..PhasePlan::default()
            },
            mass_scaling: 0.0,
        })
    }

    /// The plan with an edge band of `split` (`None`: none) on the banded family.
    ///
    /// Errors: a split outside 1..=16 (naming `--fe-band`), or a band with a fine level
    /// below 1 (naming `--fe-level`).
    pub fn with_band(mut self, split: Option<usize>) -> Result<FePlan> {
        if let Some(s) = split {
            if crate::study::convergence::phase_band::check_split(s).is_err() {
                return Err(Error::invalid(
                    "--fe-band",
                    s,
                    format!(
                        "an integer in [1, {}]",
                        crate::mesh::section::band::MAX_SPLIT
                    ),
                ));
            }
            if self.phase.level < 1 {
                return Err(Error::invalid(
                    "--fe-level",
                    self.phase.level,
                    ">= 1 with --fe-band (the banded family's coarse level is 0)",
                ));
            }
        }
        self.phase.band = split;
        Ok(self)
    }

    /// The plan with every head-on run mass-scaled within `budget` (0: none).
    ///
    /// Errors: a budget outside [0, 1e-2] (naming `--fe-mass-scaling`).
    pub fn with_mass_scaling(self, budget: f64) -> Result<FePlan> {
        use crate::fe::section::mass_scaling::{check_budget, MAX_BUDGET};
        if check_budget(budget).is_err() {
            return Err(Error::invalid(
                "--fe-mass-scaling",
                budget,
                format!("a fraction in [0, {MAX_BUDGET}] (added mass over the section's)"),
            ));
        }
        Ok(FePlan {
            mass_scaling: budget,
            ..self
        })
    }

    /// The plan refining a point one level where e's relative bar exceeds `tolerance`
    /// (`None`: never).
    ///
    /// Errors: a tolerance that is not finite and positive, or a fine level of 7 (naming
    /// `--fe-tolerance`).
    pub fn with_tolerance(mut self, tolerance: Option<f64>) -> Result<FePlan> {
        if let Some(t) = tolerance {
            let max = crate::mesh::section::ladder::MAX_LEVEL as i32;
            if !(t.is_finite() && t > 0.0) || self.phase.level >= max {
                return Err(Error::invalid(
                    "--fe-tolerance",
                    t,
                    format!("a fraction > 0 (or 0: none) with a fine level below {max}"),
                ));
            }
        }
        self.phase.tolerance = tolerance;
        self.phase.max_refinements = u32::from(tolerance.is_some());
        Ok(self)
    }

    /// The FE model's name stored in every cache file of this plan (a file of another plan
    /// is rerun).
    pub fn model(&self) -> String {
        let PhasePlan {
            level,
            meshes,
            band,
            tolerance,
            ..
        } = self.phase;
        let scaled = if self.mass_scaling > 0.0 {
            format!(
                ", mass-scaled within {:e} of the section's mass",
                self.mass_scaling
            )
        } else {
            String::new()
        };
        let refined = match tolerance {
            Some(t) => format!(", refined one level where the bar of e exceeds {t:e}"),
            None => String::new(),
        };
        let plan = match band {
            None => format!(
                "{FE_MODEL}: fine family level {}, coarse {}, {} meshes each, sized from the \
                 Hertz contact radius",
                level,
                level - 1,
                meshes
            ),
            Some(split) => {
                let depth = depth_for(split);
                let reach = if depth < 1.0 {
                    format!(" over {depth:.4} of each layer's rays from the surface")
                } else {
                    String::new()
                };
                format!(
                    "{FE_MODEL}: fine banded level {}, coarse {}, {} meshes each, the surface \
                     rings at the contact edge (found on level 0) split {split}-fold{reach}",
                    level,
                    level - 1,
                    meshes
                )
            }
        };
        plan + &scaled + &refined
    }
}

/// The FE model of the head-on points, the start of every cache file's model name
/// ([`FePlan::model`] adds the plan).
pub const FE_MODEL: &str =
    "section phase ensemble with error bars, kinematic symmetry plane, smoothed peak force";

/// The FE model of the oblique points: the 3D half model on the default graded meshes (level
/// 0) and on meshes twice as coarse (level −1) for the error bars ([`oblique_fe`]; the
/// tangential figures' bars assume order 1), whatever the head-on plan (its cache files are
/// not tied to it).
pub const OBLIQUE_MODEL: &str =
    "3D half model, default graded meshes, two-level error bars (levels -1 and 0; tangential order 1; spin with the mesh's inertia share; e with the bulk's share)";

/// Hertz's contact radius a = √(R*δ_max) (m) of the point's pair at its speed.
///
/// Errors: a diameter or material the ball rejects.
pub fn hertz_contact_radius(p: &HeadOnPoint) -> Result<f64> {
    let b = Body::ball(p.material, p.diameter, "ball")?;
    let pair = HertzPair::between(&b, &b);
    Ok(pair.contact_radius(pair.max_approach(p.speed)))
}

/// The head-on case of `point` for `study::convergence::phase_ensemble` (two identical balls, the
/// default one-point quads).
pub fn head_on_case(point: &HeadOnPoint) -> HeadOnCase {
    HeadOnCase {
        diameter: point.diameter,
        material: point.material,
        relative_speed: point.speed,
        target: HeadOnTarget::IdenticalBall,
        formulation: QuadFormulation::default(),
        plane: PlaneContact::Kinematic,
        mass_scaling: 0.0,
        integration: crate::fe::subcycle::Integration::subcycled(),
    }
}

/// The FE answer for one head-on point under `plan`: e, δ_max, t_c and the peak force as
/// the fine ensemble's means with their error bars (as the cache records them), the fine pilot run's (t, δ, F) rows and
/// the CPU seconds of all runs.
///
/// Errors: a mesh the ladder rejects (contact radius outside its range), a run that fails
/// (named by the section model).
pub fn head_on_fe(point: &HeadOnPoint, plan: &FePlan) -> Result<FePoint> {
    let case = HeadOnCase {
        mass_scaling: plan.mass_scaling,
        ..head_on_case(point)
    };
    let answer = converged_head_on(&case, &plan.phase)?;
    Ok(FePoint {
        e: answer.e.as_recorded(),
        delta_max: answer.delta_max.as_recorded(),
        contact_duration: answer.contact_duration.as_recorded(),
        peak_force: answer.peak_force.as_recorded(),
        curve: answer
            .pilot
            .history
            .iter()
            .map(|r| [r.t, r.delta, r.normal_force])
            .collect(),
        cpu_seconds: answer.cpu_time_s,
        scaled_from: None,
        fine_level: Some(answer.fine_level),
    })
}

impl FePoint {
    /// The point of the geometrically similar pair `factor` times larger (rate-independent
    /// material, mesh sized from the Hertz contact radius ∝ D): e unchanged, δ_max and t_c
    /// times `factor`, the peak force times `factor`², the curve likewise; no CPU time.
    /// `from_diameter` (m) is this point's diameter, recorded in `scaled_from`.
    pub fn scaled(&self, factor: f64, from_diameter: f64) -> FePoint {
        FePoint {
            e: self.e,
            delta_max: self.delta_max.scaled(factor),
            contact_duration: self.contact_duration.scaled(factor),
            peak_force: self.peak_force.scaled(factor * factor),
            curve: self
                .curve
                .iter()
                .map(|r| [factor * r[0], factor * r[1], factor * factor * r[2]])
                .collect(),
            cpu_seconds: 0.0,
            scaled_from: Some(from_diameter),
            fine_level: self.fine_level,
        }
    }
}

/// The scene of an oblique point: two identical balls touching along x, relative velocity
/// (v_n, ratio·v_n, 0) split equally, default (graded) meshes, reduction chosen by the
/// scene reader's `auto` (the half model); the elastic twin with the yield strength
/// [`super::matrix::ELASTIC_YIELD`].
pub fn oblique_scene(p: &ObliquePoint) -> Result<Scene> {
    let (vn, vt) = (0.5 * p.normal_speed, 0.5 * p.ratio * p.normal_speed);
    let material = if p.elastic {
        format!(
            "{{ preset = \"{}\", yield = {:e} }}",
            p.metal, p.material.yield_strength
        )
    } else {
        format!("\"{}\"", p.metal)
    };
    let ball = |v: [f64; 2]| {
        format!(
            "material = {material}\ndiameter = {:e}\nvelocity = [{:e}, {:e}, 0.0]\n",
            p.diameter, v[0], v[1]
        )
    };
    let text = format!("[ball1]\n{}\n[ball2]\n{}", ball([vn, vt]), ball([-vn, -vt]));
    Scene::from_toml(&text, Path::new("."), &[])
}

/// The FE answer for one oblique point: the 3D model the scene reader picks, on the
/// scene's meshes and on meshes twice as coarse, each figure with its two-level bar.
///
/// Errors: a scene or run that fails, an impact without slip at touch.
pub fn oblique_fe(p: &ObliquePoint) -> Result<ObliqueFe> {
    let scene = oblique_scene(p)?;
    let r = run_scene_with_estimate(
        &scene,
        &RunOptions {
            history_rows: 200,
            ..RunOptions::default()
        },
        LadderPlan::TwoLevels,
    )?;
    let missing = |what: &str| Error::Numerical(format!("oblique point: no {what}"));
    let est = r
        .error_estimate
        .as_ref()
        .ok_or_else(|| missing("error estimate (the balls do not collide)"))?;
    let tangential = est
        .tangential
        .as_ref()
        .ok_or_else(|| missing("tangential figures"))?;
    let restitution = tangential
        .restitution
        .ok_or_else(|| missing("slip at touch"))?;
    Ok(ObliqueFe {
        e: est.e.as_recorded(),
        tangential_restitution: restitution.as_recorded(),
        spin: tangential.spin1_after.as_recorded(),
        v1t_after: r.v1_after[1],
        delta_max: est.delta_max.as_recorded(),
        contact_duration: est.contact_duration.as_recorded(),
        energy_error: r.energy_error,
        wall_seconds: r.wall_time_s,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A banded plan names its band in the cache's model (so that its files are not taken
    /// for a plain plan's, nor the other way round), and the plain plans keep their names.
    #[test]
    fn a_banded_plan_has_a_model_of_its_own() {
        let plain = FePlan::new(1, 2).unwrap();
        let banded = plain.with_band(Some(4)).unwrap();
        assert_ne!(plain.model(), banded.model());
        assert!(
            banded.model().contains("split 4-fold"),
            "{}",
            banded.model()
        );
        assert_eq!(plain.with_band(None).unwrap(), plain);
        assert_eq!(
            FePlan::new(0, 4).unwrap().model(),
            format!(
                "{FE_MODEL}: fine family level 0, coarse -1, 4 meshes each, sized from the \
                 Hertz contact radius"
            )
        );
        assert_eq!(banded.phase.band, Some(4));
    }

    /// A mass-scaled plan names its budget in the cache's model; a budget of 0 leaves the
    /// model (and so the cache) of the unscaled plan.
    #[test]
    fn a_mass_scaled_plan_has_a_model_of_its_own() {
        let banded = FePlan::new(1, 2).unwrap().with_band(Some(4)).unwrap();
        let scaled = banded.with_mass_scaling(1e-4).unwrap();
        assert_ne!(banded.model(), scaled.model());
        assert!(scaled
            .model()
            .ends_with("mass-scaled within 1e-4 of the section's mass"));
        assert_eq!(
            banded.with_mass_scaling(0.0).unwrap().model(),
            banded.model()
        );
        let e = banded.with_mass_scaling(0.02).unwrap_err().to_string();
        assert!(e.contains("--fe-mass-scaling"), "{e}");
    }
}
