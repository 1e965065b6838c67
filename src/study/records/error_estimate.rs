//! A run's own error bar, as results.json writes it: the estimate of e, δ_max and the contact
//! duration from the runs of a mesh ladder ([`crate::study::records::estimate`]; the ladder itself is
//! [`crate::study::convergence::ladder`]), the levels that ran and how the estimate was obtained.

use crate::error::{Error, Result};
use crate::study::records::estimate::{estimate, estimate_assuming, Estimate};
use crate::study::records::tangential::Tangential;
use serde::Serialize;

/// The refinement ratio of the ladder: each level halves the element sizes.
pub const LADDER_RATIO: f64 = 2.0;

/// What one mesh level of the ladder produced.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LevelOutcome {
    /// Ladder level: 0 the scene's mesh, negative coarser, positive finer.
    pub level: i32,
    /// Pole element size of ball 1, m.
    pub pole_size: f64,
    /// Bulk element size of ball 1, m.
    pub size: f64,
    /// Coefficient of restitution e, -.
    pub e: f64,
    /// Maximum approach δ_max, m.
    pub delta_max: f64,
    /// Contact duration, s.
    pub contact_duration: f64,
    /// Peak of the smoothed normal force, N ([`crate::study::run::smoothed_force`]).
    pub peak_force: f64,
    /// Wall time of the run, s.
    pub wall_time_s: f64,
    /// The section model's phase ensemble behind e, δ_max and the contact duration (means
    /// over its meshes); None for a single run.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub phase: Option<PhaseSummary>,
    /// The FE tangential figures of an oblique or spinning impact (absent head-on).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tangential: Option<Tangential>,
}

/// What a level's phase ensemble adds ([`crate::study::convergence::phase_ensemble`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PhaseSummary {
    /// Meshes of the ensemble (the scene's own and M − 1 with scaled pole sizes).
    pub meshes: usize,
    /// Ring ratio q: the pole sizes run over q^{j/M}, -.
    pub ring_ratio: f64,
    /// Sampling error of the mean e (even members against all), -.
    pub e_sampling_error: f64,
    /// Smallest e of the members, -.
    pub e_min: f64,
    /// Largest e of the members, -.
    pub e_max: f64,
    /// Sampling error of the mean peak force (even members against all), N.
    pub peak_force_sampling_error: f64,
}

/// The error estimate written as results.json's `error_estimate`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ErrorEstimate {
    /// Refinement ratio between levels, -.
    pub ratio: f64,
    /// Coefficient of restitution e, -.
    pub e: Estimate,
    /// Maximum approach δ_max, m.
    pub delta_max: Estimate,
    /// Contact duration, s.
    pub contact_duration: Estimate,
    /// Peak of the smoothed normal force, N (with the phase sampling error on the section).
    pub peak_force: Estimate,
    /// The tangential figures' bars of an oblique or spinning impact (absent head-on).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tangential: Option<TangentialEstimate>,
    /// The runs of the ladder, coarse to fine (the finest is the reported run).
    pub meshes: Vec<LevelOutcome>,
    /// The requested relative tolerance on e, - (with `--tolerance`).
    pub tolerance: Option<f64>,
    /// Whether the estimate of e met the tolerance (with `--tolerance`).
    pub tolerance_met: Option<bool>,
    /// How the estimate was obtained: the scene's own ladder, or the banded family that
    /// `--tolerance` runs on a head-on section scene it covers.
    pub method: EstimateMethod,
}

/// The bars of the tangential figures ([`Tangential`]) from a ladder's runs.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TangentialEstimate {
    /// Tangential restitution of the contact point, - (absent without slip at touch).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub restitution: Option<Estimate>,
    /// Rebound angle of ball 1 relative to its partner, rad.
    pub rebound_angle: Estimate,
    /// Ball 1's spin about the contact frame's z axis after the impact, rad/s.
    pub spin1_after: Estimate,
}

impl TangentialEstimate {
    /// The bars from the levels' tangential figures (coarse to fine); `None` unless every
    /// level has them and at least two do. Two levels assume
    /// [`TANGENTIAL_ASSUMED_ORDER`]; the spin's bar is at least the share of the
    /// restitution's bar ([`spin_bar_from_restitution`]), plus the finest mesh's inertia
    /// share ([`spin_bar_from_inertia`]).
    pub fn from_levels(levels: &[Option<Tangential>]) -> Option<TangentialEstimate> {
        let t: Vec<Tangential> = levels.iter().copied().collect::<Option<_>>()?;
        let ladder = |v: Vec<f64>| estimate_assuming(&v, LADDER_RATIO, TANGENTIAL_ASSUMED_ORDER);
        let of = |f: fn(&Tangential) -> f64| ladder(t.iter().map(f).collect());
        let restitution: Option<Vec<f64>> = t.iter().map(|x| x.restitution).collect();
        let restitution = restitution.and_then(ladder);
        let mut spin1_after = of(|x| x.spin1_after)?;
        if let Some(last) = t.last() {
            let dspin = last.spin1_after - last.spin1_before;
            let floor = restitution
                .as_ref()
                .map_or(0.0, |r| spin_bar_from_restitution(dspin, r));
            let inertia = last
                .spin1_inertia_ratio
                .map_or(0.0, |k| spin_bar_from_inertia(dspin, k));
            spin1_after = spin1_after.with_error(spin1_after.error.max(floor) + inertia);
        }
        Some(TangentialEstimate {
            restitution,
            rebound_angle: of(|x| x.rebound_angle)?,
            spin1_after,
        })
    }
}

/// The order a two-level ladder assumes for the tangential figures: 1. The stick-slip
/// boundary (and on a plastic ball the contact edge) is resolved node by node, so the
/// tangential impulse converges at first order in the pole size, not at the linear
/// elements' second: the two-level bar is 3 |d₂₁| (docs/design.md, "Error estimates").
pub const TANGENTIAL_ASSUMED_ORDER: f64 = 1.0;

/// A solid sphere's rotational inertia about a diameter over m R², -.
pub const SPHERE_INERTIA_RATIO: f64 = 0.4;

/// The part of the spin change `dspin` (rad/s, after minus before) that the mesh's rotational
/// inertia `ratio` (I/(m R²), -) puts off the sphere's: the angular impulse through I = ratio
/// m R² instead of 0.4 m R², so |Δω| |ratio/0.4 − 1| (rad/s). A lumped ball's surface nodes
/// carry mass out to R (ratio 0.4029-0.4046 on the wall scene's levels 1 and 0), and the
/// pole-graded ladder sees it shrink too slowly (order 0.1-0.7) to extrapolate it: the bar
/// carries it whole.
pub fn spin_bar_from_inertia(dspin: f64, ratio: f64) -> f64 {
    dspin.abs() * (ratio / SPHERE_INERTIA_RATIO - 1.0).abs()
}

/// The bar the tangential restitution's bar `restitution` puts on the spin change `dspin`
/// (rad/s, after minus before): both are the one tangential impulse J_t seen through the
/// balls' masses and inertias, and the slip after is u⁺ = u⁻ − J_t (1/m + R²/I + …), so
/// Δω ∝ J_t ∝ 1 + e_t and a bar b on e_t is a bar |Δω| b/|1 + e_t| on Δω (rad/s). A spin
/// ladder alone can miss it when the lumped inertia's change between levels cancels the
/// impulse's. 0 when 1 + e_t vanishes (no impulse to scale).
pub fn spin_bar_from_restitution(dspin: f64, restitution: &Estimate) -> f64 {
    let one_plus = (1.0 + restitution.finest).abs();
    if one_plus > 1e-9 {
        dspin.abs() * restitution.error / one_plus
    } else {
        0.0
    }
}

impl ErrorEstimate {
    /// The estimate from ladder runs (coarse to fine, at least two).
    pub fn from_runs(meshes: Vec<LevelOutcome>, tolerance: Option<f64>) -> Result<ErrorEstimate> {
        let of = |f: fn(&LevelOutcome) -> f64, what: &str| -> Result<Estimate> {
            let v: Vec<f64> = meshes.iter().map(f).collect();
            estimate(&v, LADDER_RATIO).ok_or_else(|| {
                Error::Numerical(format!(
                    "error estimate of {what}: needs two or more finite values, got {v:?}"
                ))
            })
        };
        let mut e = of(|m| m.e, "e")?;
        let mut peak_force = of(|m| m.peak_force, "peak_force")?;
        if let Some(p) = meshes.last().and_then(|m| m.phase) {
            // The ensemble's mean still carries its sampling error.
            e = e.with_error(e.error + p.e_sampling_error);
            peak_force = peak_force.with_error(peak_force.error + p.peak_force_sampling_error);
        }
        let tolerance_met = tolerance.map(|t| meets(&e, t));
        let levels: Vec<_> = meshes.iter().map(|m| m.tangential).collect();
        Ok(ErrorEstimate {
            tangential: TangentialEstimate::from_levels(&levels),
            ratio: LADDER_RATIO,
            delta_max: of(|m| m.delta_max, "delta_max")?,
            contact_duration: of(|m| m.contact_duration, "contact_duration")?,
            peak_force,
            e,
            meshes,
            tolerance,
            tolerance_met,
            method: EstimateMethod::SceneLadder {
                why_not_banded: None,
            },
        })
    }

    /// The same estimate with e's bar raised to at least `floor` (absolute, -) and whether it
    /// meets its tolerance decided again.
    pub fn with_e_floor(self, floor: f64) -> ErrorEstimate {
        let e = self.e.with_error(self.e.error.max(floor));
        ErrorEstimate {
            tolerance_met: self.tolerance.map(|t| meets(&e, t)),
            e,
            ..self
        }
    }

    /// Two lines for the terminal: the bar of each quantity of the table (and the meshes it
    /// comes from), then the values extrapolated to zero element size.
    pub fn summary(&self) -> String {
        let levels: Vec<String> = self.meshes.iter().map(|m| m.level.to_string()).collect();
        let bar = |name: &str, unit: &str, q: &Estimate| {
            let rel = q
                .relative_error
                .map_or("-".into(), |r| format!("{:.2} %", 100.0 * r));
            format!("{name} ± {:.2e}{unit} ({rel})", q.error)
        };
        let value =
            |name: &str, unit: &str, q: &Estimate| format!("{name} = {:.6e}{unit}", q.extrapolated);
        let family = match &self.method {
            EstimateMethod::SceneLadder { .. } => format!(
                "meshes at levels {} (0: the scene's mesh; each level down doubles the element sizes)",
                levels.join(", ")
            ),
            EstimateMethod::PoleLadder { bulk_size_m } => format!(
                "the pole ladder at levels {} (each level down doubles the pole size; bulk {bulk_size_m:.3e} m on all)",
                levels.join(", ")
            ),
            EstimateMethod::BandedFamily {
                band_split,
                band_edge_m,
                mass_scaling,
                ..
            } => format!(
                "the banded mesh family at levels {} (rings at {:.0} µm split {band_split}-fold, mass scaling {mass_scaling:.1e}); the table gives its finest level's phase means, the FE line the scene's own mesh",
                levels.join(", "),
                band_edge_m * 1e6
            ),
        };
        let mut s = format!(
            "error bars from {family}: {}, {}, {}, {}",
            bar("e", "", &self.e),
            bar("delta_max", " m", &self.delta_max),
            bar("contact duration", " s", &self.contact_duration),
            bar("peak force (smoothed)", " N", &self.peak_force)
        );
        if let Some(t) = &self.tangential {
            if let Some(r) = &t.restitution {
                s.push_str(&format!(", {}", bar("tangential restitution", "", r)));
            }
            s.push_str(&format!(
                ", {}, {}",
                bar("rebound angle", " rad", &t.rebound_angle),
                bar("spin 1 after", " rad/s", &t.spin1_after)
            ));
        }
        if let (Some(t), Some(met)) = (self.tolerance, self.tolerance_met) {
            let on = match self.method {
                EstimateMethod::PoleLadder { .. } => "e and the tangential restitution",
                _ => "e",
            };
            s.push_str(&format!(
                "; tolerance {:.3} % on {on} {}",
                100.0 * t,
                if met { "met" } else { "NOT met" }
            ));
        }
        if let EstimateMethod::SceneLadder {
            why_not_banded: Some(why),
        } = &self.method
        {
            s.push_str(&format!("; the scene's own ladder ran: {why}"));
        }
        let order = match (self.e.observed_order, self.e.order_used) {
            (Some(p), _) => format!("observed order {p:.2}"),
            (None, Some(p)) => format!("order {p} assumed"),
            _ => "no order".into(),
        };
        s.push_str(&format!(
            "\nextrapolated to zero element size ({order}): {}, {}, {}",
            value("e", "", &self.e),
            value("delta_max", " m", &self.delta_max),
            value("contact duration", " s", &self.contact_duration)
        ));
        s
    }
}

/// How a run's error estimate was obtained (results.json `error_estimate.method`).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(rename_all = "snake_case", tag = "kind")]
pub enum EstimateMethod {
    /// The scene's own mesh ladder: each level halves its pole and bulk sizes.
    SceneLadder {
        /// Why the banded family did not run with `--tolerance`: the scene is one it does
        /// not cover, or the scene's own levels −1 and 0 already met a tolerance of 2 % or
        /// looser; None when it was not asked for.
        #[serde(skip_serializing_if = "Option::is_none")]
        why_not_banded: Option<String>,
    },
    /// `--tolerance` on an oblique 3D scene (sliding contact points at touch, spin included): a
    /// ladder whose levels halve the pole size only, the bulk held at or below D/8 on every
    /// level (past e's and e_t's knee in the bulk), met when e's and the tangential
    /// restitution's bars are both within the tolerance.
    PoleLadder {
        /// The bulk size of every level, m.
        bulk_size_m: f64,
    },
    /// The banded, mass-scaled family of [`crate::study::convergence::phase_ensemble::converged_head_on`], sized
    /// from the physics.
    BandedFamily {
        /// Surface rings at the contact edge split this many times, -.
        band_split: usize,
        /// The contact edge the band is centred on, m.
        band_edge_m: f64,
        /// Meshes per level (phases of the rings), -.
        meshes_per_level: usize,
        /// Mass-scaling budget of every run (added mass over the section's), -.
        mass_scaling: f64,
        /// The bias bound of that budget, relative, in every bar, -.
        mass_scaling_bias: f64,
        /// CPU time of all the family's runs, s.
        cpu_time_s: f64,
    },
}

/// True when the relative estimate of `e` is at most `tolerance`.
pub fn meets(e: &Estimate, tolerance: f64) -> bool {
    e.relative_error.is_some_and(|r| r <= tolerance)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A ball on a wall without spin before (I = 0.4 m R²): slip u, restitution e_t, spin
    /// after −u (1 + e_t)/(R (1 + 0.4)) scaled by `inertia_error` (the lumped ball's).
    fn wall(e_t: f64, inertia_error: f64) -> Tangential {
        let (u, r) = (1.0, 0.01);
        Tangential {
            restitution: Some(e_t),
            incidence_angle: 0.3,
            rebound_angle: 0.3 * e_t,
            spin1_after: -u * (1.0 + e_t) / (r * 1.4) / (1.0 + inertia_error),
            spin1_before: 0.0,
            spin1_inertia_ratio: Some(SPHERE_INERTIA_RATIO * (1.0 + inertia_error)),
        }
    }

    #[test]
    fn two_tangential_levels_assume_order_one() {
        let t = TangentialEstimate::from_levels(&[Some(wall(0.50, 0.0)), Some(wall(0.52, 0.0))])
            .unwrap();
        let r = t.restitution.unwrap();
        assert_eq!(r.order_used, Some(TANGENTIAL_ASSUMED_ORDER));
        assert!((r.error - 3.0 * 0.02).abs() < 1e-12, "{r:?}");
        assert!((t.rebound_angle.error - 3.0 * 0.006).abs() < 1e-12);
        assert_eq!(
            TangentialEstimate::from_levels(&[Some(wall(0.5, 0.0)), None]),
            None
        );
    }

    #[test]
    fn a_spin_ladder_cancelled_by_the_inertia_keeps_the_impulses_bar() {
        // The coarse level's impulse is 2 % high and its inertia 2 % high: equal spins.
        let coarse = wall(0.53, (1.53 / 1.52) - 1.0);
        let fine = wall(0.52, 0.0);
        assert!((coarse.spin1_after - fine.spin1_after).abs() < 1e-9);
        let t = TangentialEstimate::from_levels(&[Some(coarse), Some(fine)]).unwrap();
        let want = fine.spin1_after.abs() * 3.0 * 0.01 / 1.52;
        assert!(
            (t.spin1_after.error - want).abs() < 1e-9 * want,
            "{:?}",
            t.spin1_after
        );
        // No impulse to scale when the slip is kept whole (e_t = −1).
        let kept = Estimate::recorded(-1.0, 0.1);
        assert_eq!(spin_bar_from_restitution(5.0, &kept), 0.0);
    }

    #[test]
    fn the_meshs_inertia_adds_its_share_to_the_spins_bar() {
        // Two levels with the same figures and a lumped inertia 1 % above the sphere's: the
        // ladder sees nothing, the bar is the inertia's 1 % of the spin change.
        let level = wall(0.52, 0.01);
        let t = TangentialEstimate::from_levels(&[Some(level), Some(level)]).unwrap();
        let want = 0.01 * level.spin1_after.abs();
        assert!(
            (t.spin1_after.error - want).abs() < 1e-9 * want,
            "{:?}",
            t.spin1_after
        );
        // The analytical sphere's (no ratio) adds nothing.
        let sphere = level.with_spin1_inertia_ratio(None);
        let t = TangentialEstimate::from_levels(&[Some(sphere), Some(sphere)]).unwrap();
        assert_eq!(t.spin1_after.error, 0.0);
    }
}
