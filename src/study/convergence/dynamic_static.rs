//! A head-on impact beside its quasi-static image (`twoball run --compare-static`): the
//! dynamic e and δ_max with their bars, the free ball's static loop to the same work with
//! its bars, and where the impact energy ends up on each side, so that the gap in e is
//! accounted for in energies.
//!
//! The static image of a head-on impact is one ball pressed against a rigid plane by the
//! uniform body force of its own deceleration ([`Support::Free`]), loaded to the kinetic
//! energy it brings, W_in = ½ m v², and unloaded: e_qs² = W_returned / W_in. The impact
//! ends with the same split of that energy into plastic work and the elastic energy locked
//! in by residual stresses, plus what only a dynamic run has: the vibration the ball leaves
//! with. With E_vib that energy, the quasi-static loop predicts
//! e_dyn ≈ √(e_qs² − E_vib / KE₀); what remains of the gap is the difference in plastic
//! work and locked-in energy between the two load paths and both discretisations.
//!
//! E_vib is measured on a run held [`HOLD_SHEAR_TRANSITS`] shear-wave transits of the
//! diameter past separation (about eight periods of the ball's lowest mode): its kinetic
//! energy less the rigid-body part, K_int, and its elastic energy oscillate about their
//! means, and for small vibrations about the residual state the two vibration parts have
//! equal means (virial theorem), so E_vib = 2 ⟨K_int⟩ and the locked-in energy is
//! ⟨E_el⟩ − ⟨K_int⟩.

use super::scene_estimate::run_scene_alone;
use super::static_ladder::{
    case_of_scene, free_ball_ladder, impact_of_scene, static_image_of, LoopEstimate,
    DEFAULT_INCREMENTS, DEFAULT_LEVEL,
};
use crate::error::{Error, Result};
use crate::scene::Scene;
use crate::study::records::estimate::{estimate, Estimate};
use crate::study::run::history::HistoryRow;
use crate::study::run::quasi_static::{run_loop, LoopMesh, StaticCase, StaticLoop, Support};
use crate::study::run::scene::RunReport;
use crate::study::run::section::section_spec;
use crate::study::run::simulation::RunOptions;
use serde::Serialize;

/// The hold after separation of the vibration run, in shear-wave transits D / c_s.
pub const HOLD_SHEAR_TRANSITS: f64 = 10.0;

/// Where the impact energy is after separation, each a share of the kinetic energy before
/// touch (of both balls, or of the ball on a wall).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct EnergyAfter {
    /// Kinetic energy before touch, J.
    pub initial_kinetic: f64,
    /// Rigid-body kinetic energy after separation (e² for a head-on impact), share.
    pub rigid_body: f64,
    /// Vibration energy 2 ⟨K_int⟩, share.
    pub vibration: f64,
    /// Elastic energy locked in by residual stresses ⟨E_el⟩ − ⟨K_int⟩, share.
    pub locked_elastic: f64,
    /// Plastic work, share.
    pub plastic: f64,
    /// Hourglass energy (the one-point quads' control), share.
    pub hourglass: f64,
    /// The window after separation the means are taken over, s.
    pub window: f64,
}

/// The split of the loop's work in: returned, plastic, locked in; shares of W_in.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct StaticSplit {
    /// Work in, J.
    pub work_in: f64,
    /// Work returned on unloading (e_qs²), share.
    pub returned: f64,
    /// Plastic work, share.
    pub plastic: f64,
    /// Elastic energy (and hourglass work) left at release, share.
    pub locked_elastic: f64,
}

/// The comparison.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DynamicStatic {
    /// The dynamic e (the run's estimate).
    pub e_dynamic: Estimate,
    /// The quasi-static e of the free ball.
    pub e_static: Estimate,
    /// The dynamic approach of one ball to the mirror plane or the wall, m (half the centres'
    /// approach for two identical balls).
    pub delta_dynamic: Estimate,
    /// The free ball's largest approach, m.
    pub delta_static: Estimate,
    /// The dynamic run's energies after separation (one run on the scene's mesh).
    pub dynamic_energy: EnergyAfter,
    /// The finest static loop's split.
    pub static_split: StaticSplit,
    /// √(e_qs² − E_vib / KE₀).
    pub e_predicted: f64,
    /// The static loops' numbers.
    pub static_estimate: LoopEstimate,
    /// The free ball's loop on the dynamic run's own mesh.
    pub same_mesh: SameMesh,
}

/// The free ball's loop on the mesh of the dynamic run whose energies are split
/// ([`EnergyAfter`]), so that the account compares the two load paths on one
/// discretisation; its increments are refined ([`SAME_MESH_LEVELS`]) and e_qs extrapolated
/// in them.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SameMesh {
    /// Quads of the mesh.
    pub quads: usize,
    /// Increments of loading of each loop, coarse to fine (unloading takes half as many).
    pub increments: Vec<usize>,
    /// The quasi-static e over the increments.
    pub e_static: Estimate,
    /// The finest loop's split.
    pub split: StaticSplit,
    /// √(e_qs² − E_vib / KE₀) with e_qs extrapolated in the increments.
    pub e_predicted: f64,
}

/// The increment levels of the same-mesh loops: [`DEFAULT_INCREMENTS`] · 2^level each.
pub const SAME_MESH_LEVELS: [u32; 3] = [1, 2, 3];

/// The energies after separation of a head-on run's history: rows after the last one with
/// a contact force. The balls are identical (or ball 2 is a wall, at rest); each ball's mass
/// comes from the first row, whose motion is rigid: m = 2 K / (v₁² + v₂²).
///
/// Errors: an empty history, fewer than ten rows after separation.
pub fn energy_after(history: &[HistoryRow]) -> Result<EnergyAfter> {
    let first = history
        .first()
        .ok_or_else(|| Error::Numerical("compare-static: an empty history".into()))?;
    let ball_mass = 2.0 * first.kinetic / (first.v[0][0].powi(2) + first.v[1][0].powi(2));
    let last_contact = history
        .iter()
        .rposition(|r| r.normal_force != 0.0)
        .unwrap_or(0);
    let window = &history[last_contact + 1..];
    if window.len() < 10 {
        return Err(Error::Numerical(format!(
            "compare-static: {} history rows after separation, at least 10 needed",
            window.len()
        )));
    }
    let rigid = |r: &HistoryRow| 0.5 * ball_mass * (r.v[0][0].powi(2) + r.v[1][0].powi(2));
    let mean =
        |f: &dyn Fn(&HistoryRow) -> f64| window.iter().map(f).sum::<f64>() / window.len() as f64;
    let k_int = mean(&|r| r.kinetic - rigid(r));
    let elastic = mean(&|r| r.elastic);
    let end = window[window.len() - 1];
    let ke0 = first.kinetic;
    Ok(EnergyAfter {
        initial_kinetic: ke0,
        rigid_body: rigid(&end) / ke0,
        vibration: 2.0 * k_int / ke0,
        locked_elastic: (elastic - k_int) / ke0,
        plastic: end.plastic / ke0,
        hourglass: mean(&|r| r.hourglass) / ke0,
        window: end.t - window[0].t,
    })
}

/// The split of a loop's work in.
pub fn static_split(l: &StaticLoop) -> StaticSplit {
    let s = l.summary;
    let returned = s.work_returned / s.work_in;
    let plastic = s.plastic_work / s.work_in;
    StaticSplit {
        work_in: s.work_in,
        returned,
        plastic,
        locked_elastic: 1.0 - returned - plastic,
    }
}

/// The hold after separation (s) that [`energy_after`] needs for `scene`'s ball 1:
/// [`HOLD_SHEAR_TRANSITS`] · D / c_s.
pub fn vibration_hold(scene: &Scene) -> f64 {
    let m = &scene.ball1.material;
    HOLD_SHEAR_TRANSITS * scene.ball1.diameter / (m.shear_modulus() / m.rho).sqrt()
}

/// The static loops of `scene`'s free ball to the work one ball brings
/// ([`free_ball_ladder`]).
///
/// Errors: a scene that is not one ball on a plane; those of [`free_ball_ladder`].
pub fn static_image(
    scene: &Scene,
    level: u32,
    increments: usize,
) -> Result<(Vec<StaticLoop>, LoopEstimate)> {
    free_ball_ladder(&static_image_of(scene)?, level, increments)
}

/// The comparison for `scene`, whose dynamic run gave `report`: the vibration run (the
/// scene's mesh held [`vibration_hold`] past separation) and the free ball's static loops.
///
/// Errors: a scene that is not one ball on a plane by symmetry (one line naming `scene`), a
/// report without an FE outcome; those of the runs.
pub fn run_compare(scene: &Scene, report: &RunReport) -> Result<DynamicStatic> {
    let (_, wall) = impact_of_scene(scene)?;
    // The centres of two identical balls approach by twice one ball's travel.
    let pair = if wall { 1.0 } else { 2.0 };
    let single = |v: f64| estimate(&[v, v], 2.0).expect("a finite value");
    let (e, delta) = match (&report.error_estimate, report.e) {
        (Some(est), _) => (est.e, est.delta_max),
        (None, Some(e)) => (single(e), single(report.delta_max)),
        (None, None) => {
            return Err(Error::Numerical(
                "compare-static: the dynamic run has no e".into(),
            ))
        }
    };
    let mut held = scene.clone();
    held.solver.hold_time = Some(vibration_hold(scene));
    let quiet = RunOptions {
        history_rows: 2000,
        ..RunOptions::default()
    };
    let run = run_scene_alone(&held, &quiet)?;
    let history = run
        .fe
        .as_ref()
        .map(|f| f.history.as_slice())
        .unwrap_or_default();
    let energy = energy_after(history)?;
    let (loops, est) = static_image(scene, DEFAULT_LEVEL, DEFAULT_INCREMENTS)?;
    let same = same_mesh(scene, &energy)?;
    Ok(compare(e, delta, pair, energy, &loops, est, same))
}

/// The free ball's loops on ball 1's built-in section mesh (the dynamic run's), at the
/// increments of [`SAME_MESH_LEVELS`], against the dynamic run's `energy`.
///
/// Errors: those of [`section_spec`], [`case_of_scene`] and [`run_loop`].
pub fn same_mesh(scene: &Scene, energy: &EnergyAfter) -> Result<SameMesh> {
    let case = StaticCase {
        mesh: LoopMesh::Builtin(section_spec("ball1", &scene.ball1)?),
        ..case_of_scene(scene, Support::Free, None, 0, DEFAULT_INCREMENTS)?
    };
    let loops = SAME_MESH_LEVELS
        .iter()
        .map(|&level| run_loop(&StaticCase { level, ..case }))
        .collect::<Result<Vec<_>>>()?;
    let values: Vec<f64> = loops.iter().map(|l| l.summary.e).collect();
    let e_static = estimate(&values, 2.0).ok_or_else(|| {
        Error::Numerical(format!(
            "compare-static: no estimate of e_qs from {values:?}"
        ))
    })?;
    let finest = loops.last().expect("three loops");
    Ok(SameMesh {
        quads: finest.quads,
        increments: SAME_MESH_LEVELS
            .iter()
            .map(|&level| StaticCase { level, ..case }.steps())
            .collect(),
        e_static,
        split: static_split(finest),
        e_predicted: (e_static.extrapolated.powi(2) - energy.vibration)
            .max(0.0)
            .sqrt(),
    })
}

/// Puts the two sides together. `pair` is 2 for identical balls (δ of the centres is twice
/// one ball's) and 1 for a ball on a wall.
pub fn compare(
    e_dynamic: Estimate,
    delta_centres: Estimate,
    pair: f64,
    dynamic_energy: EnergyAfter,
    loops: &[StaticLoop],
    static_estimate: LoopEstimate,
    same_mesh: SameMesh,
) -> DynamicStatic {
    let finest = loops.last().expect("a ladder has loops");
    let e_static = static_estimate.e;
    DynamicStatic {
        e_dynamic,
        e_static,
        delta_dynamic: delta_centres.scaled(1.0 / pair),
        delta_static: static_estimate.delta_max,
        dynamic_energy,
        static_split: static_split(finest),
        e_predicted: (e_static.finest.powi(2) - dynamic_energy.vibration)
            .max(0.0)
            .sqrt(),
        static_estimate,
        same_mesh,
    }
}

impl DynamicStatic {
    /// The printed comparison.
    pub fn summary(&self) -> String {
        let pct = |a: f64, b: f64| 100.0 * (a / b - 1.0);
        let d = &self.dynamic_energy;
        let s = &self.static_split;
        let mut out = String::from(
            "dynamic against quasi-static (the free ball loaded to the kinetic energy it brings, \
             then unloaded):\n",
        );
        out += &format!(
            "  e                    dynamic {:.5} ± {:.5}   quasi-static {:.5} ± {:.5}   \
             dynamic / quasi-static − 1 = {:+.2} %\n",
            self.e_dynamic.finest,
            self.e_dynamic.error,
            self.e_static.finest,
            self.e_static.error,
            pct(self.e_dynamic.finest, self.e_static.finest)
        );
        out += &format!(
            "  δ_max of one ball    dynamic {:.5e} ± {:.1e} m   quasi-static {:.5e} ± {:.1e} m   \
             {:+.2} %\n",
            self.delta_dynamic.finest,
            self.delta_dynamic.error,
            self.delta_static.finest,
            self.delta_static.error,
            pct(self.delta_dynamic.finest, self.delta_static.finest)
        );
        out += &format!(
            "  energy after separation (dynamic, scene's mesh, {:.2e} s held), shares of KE₀: \
             rigid-body {:.5}, vibration {:.5}, locked elastic {:.5}, plastic {:.5}, \
             hourglass {:.5}\n",
            d.window, d.rigid_body, d.vibration, d.locked_elastic, d.plastic, d.hourglass
        );
        out += &format!(
            "  quasi-static loop (finest level), shares of W_in: returned {:.5}, locked \
             elastic {:.5}, plastic {:.5}\n",
            s.returned, s.locked_elastic, s.plastic
        );
        let e_run = d.rigid_body.sqrt();
        out += &account("the two runs' account", "quasi-static", d, s);
        out += &format!(
            "  e predicted √(e_qs² − E_vib/KE₀) = {:.5} against the dynamic run's {:.5}: \
             {:+.2} %\n",
            self.e_predicted,
            e_run,
            pct(e_run, self.e_predicted)
        );
        let m = &self.same_mesh;
        out += &format!(
            "  on the dynamic run's own mesh ({} quads), the free ball's loop at {:?} \
             increments: e_qs {:.5} ± {:.5} (extrapolated in the increments {:.5}); shares of \
             W_in: returned {:.5}, locked elastic {:.5}, plastic {:.5}\n",
            m.quads,
            m.increments,
            m.e_static.finest,
            m.e_static.error,
            m.e_static.extrapolated,
            m.split.returned,
            m.split.locked_elastic,
            m.split.plastic
        );
        out += &account(
            "one mesh's account",
            "quasi-static, finest increments",
            d,
            &m.split,
        );
        out += &format!(
            "  e predicted on one mesh √(e_qs² − E_vib/KE₀) = {:.5} against the dynamic run's \
             {:.5}: {:+.2} %\n",
            m.e_predicted,
            e_run,
            pct(e_run, m.e_predicted)
        );
        out
    }
}

/// One printed line of the account e²_dyn = e_qs² − E_vib/KE₀ + (static less dynamic plastic,
/// locked-in and hourglass energy) + energy error, all shares, for the dynamic run's `d` and
/// the loop's split `s`.
fn account(label: &str, loop_label: &str, d: &EnergyAfter, s: &StaticSplit) -> String {
    let rest = (s.plastic + s.locked_elastic) - (d.plastic + d.locked_elastic + d.hourglass);
    format!(
        "  {label}: e² {:.5} (dynamic run) = {:.5} ({loop_label}) − {:.5} (vibration) {:+.5} \
         (plastic, locked-in and hourglass energy: static less dynamic) {:+.5} (energy error)\n",
        d.rigid_body,
        s.returned,
        d.vibration,
        rest,
        d.rigid_body - (s.returned - d.vibration + rest)
    )
}
