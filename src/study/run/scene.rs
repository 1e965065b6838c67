//! One scene, both models: the FE run beside the analytical answer, with relative
//! differences, written as results.json and history.csv.

use crate::atomic::{ensure_dir, write_atomic};
use crate::error::{Error, Result};
use crate::scene::{approach, Approach, MeshSettings, Scene};
use crate::study::records::error_estimate::{ErrorEstimate, LevelOutcome};
use crate::study::records::number::sci;
use crate::study::records::outcome::{
    analytic_outcome, ball_inertia, dissipation_factor, elastic_theory_outcome,
    relative_difference, Outcome,
};
use crate::study::records::tangential::{is_oblique, tangential, TangentialPair};
use crate::study::records::warnings::{analytic_warnings, fe_warnings, FeFigures, Warning};
use crate::study::run::force_curve::ForceCurve;
use crate::study::run::law_compare::{compare_laws, law_table, LawOutcome};
use crate::study::run::simulate::{simulate, Reduction, RunOptions, Simulation, HISTORY_HEADER};
use serde::Serialize;
use std::path::Path;
use std::time::Instant;

/// Relative differences FE vs analytical, (FE − analytical)/|analytical|.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Differences {
    /// In e.
    pub e: f64,
    /// In ball 1's normal velocity after impact.
    pub v1n_after: f64,
    /// In ball 2's normal velocity after impact.
    pub v2n_after: f64,
    /// In δ_max.
    pub delta_max: f64,
    /// In the contact duration.
    pub contact_duration: f64,
    /// In η.
    pub eta: f64,
}

impl Differences {
    /// FE against analytical; normal components along the contact frame's x.
    pub fn between(fe: &Outcome, an: &Outcome, n: [f64; 3]) -> Differences {
        let dot = |a: [f64; 3]| a[0] * n[0] + a[1] * n[1] + a[2] * n[2];
        Differences {
            e: relative_difference(fe.e, an.e),
            v1n_after: relative_difference(dot(fe.v1_after), dot(an.v1_after)),
            v2n_after: relative_difference(dot(fe.v2_after), dot(an.v2_after)),
            delta_max: relative_difference(fe.delta_max, an.delta_max),
            contact_duration: relative_difference(fe.contact_duration, an.contact_duration),
            eta: relative_difference(fe.eta, an.eta),
        }
    }
}

/// Everything a run produced; serialised as results.json.
#[derive(Debug, Clone, Serialize)]
pub struct RunReport {
    /// Whether the balls collide at all.
    pub impact: bool,
    /// Why not, when they do not.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub no_impact_reason: Option<String>,
    /// FE coefficient of restitution (absent without impact).
    pub e: Option<f64>,
    /// FE centre-of-mass velocity of ball 1 after impact, m/s.
    pub v1_after: [f64; 3],
    /// FE centre-of-mass velocity of ball 2 after impact, m/s.
    pub v2_after: [f64; 3],
    /// FE angular velocity of ball 1 after impact, rad/s.
    pub w1_after: [f64; 3],
    /// FE angular velocity of ball 2 after impact, rad/s.
    pub w2_after: [f64; 3],
    /// FE maximum approach of the mass centres, m.
    pub delta_max: f64,
    /// FE contact duration, s.
    pub contact_duration: f64,
    /// FE energy dissipation factor η (eq. 33, rigid-body kinetic energy).
    pub eta: Option<f64>,
    /// Largest relative energy-balance error of the FE run.
    pub energy_error: f64,
    /// Symmetry reduction used: quarter, half, full (none without impact).
    pub reduction: String,
    /// Wall time of the whole run, s.
    pub wall_time_s: f64,
    /// Element updates (elements × steps).
    pub element_cycles: u64,
    /// FE run details (savings, sizes, steps, stop reason).
    pub fe: Option<Simulation>,
    /// The analytical model's outcome.
    pub analytic: Option<Outcome>,
    /// FE vs analytical.
    pub relative_difference: Option<Differences>,
    /// The tangential side of an oblique or spinning impact, FE and analytical (absent for
    /// a head-on impact).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tangential: Option<TangentialPair>,
    /// The scene's `[laws]`, each integrated on the same balls and speeds (absent without).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub laws: Vec<LawOutcome>,
    /// Results not to take at face value, one line each (empty when none).
    pub warnings: Vec<Warning>,
    /// The run's error bar from its mesh ladder (with `--error-estimate` or `--tolerance`);
    /// the other results are those of the ladder's finest mesh.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error_estimate: Option<ErrorEstimate>,
    /// The scene as run (presets and overrides resolved).
    pub scene: Scene,
    /// The loading branch F(δ) (force_curve.csv): the run's own, or on the section the
    /// phase mean of its error estimate's fine level with a bar; empty without impact.
    #[serde(skip)]
    pub force_curve: ForceCurve,
}

/// Runs `scene`: analytical model, then FE (unless there is no impact).
pub fn run_scene(scene: &Scene, opts: &RunOptions) -> Result<RunReport> {
    let start = Instant::now();
    let touch = match approach(scene)? {
        Approach::NoImpact { reason } => {
            return Ok(RunReport {
                impact: false,
                no_impact_reason: Some(reason),
                e: None,
                v1_after: scene.ball1.velocity,
                v2_after: scene.ball2.velocity,
                w1_after: scene.ball1.angular_velocity,
                w2_after: scene.ball2.angular_velocity,
                delta_max: 0.0,
                contact_duration: 0.0,
                eta: None,
                energy_error: 0.0,
                reduction: "none".into(),
                wall_time_s: start.elapsed().as_secs_f64(),
                element_cycles: 0,
                fe: None,
                analytic: None,
                relative_difference: None,
                tangential: None,
                laws: Vec::new(),
                warnings: Vec::new(),
                error_estimate: None,
                scene: scene.clone(),
                force_curve: ForceCurve::default(),
            })
        }
        Approach::Impact(t) => t,
    };
    let (an, collision) = analytic_outcome(scene, &touch)?;
    let oblique = is_oblique(scene, &touch);
    let theory = if oblique {
        elastic_theory_outcome(scene, &touch, &collision)?
    } else {
        None
    };
    let laws = compare_laws(scene, &touch)?;
    let sim = simulate(scene, &touch, an.contact_duration, opts)?;
    let fe = sim.outcome;
    let r_star = collision.pair.radius;
    let mut warnings = analytic_warnings(an.delta_max, r_star);
    warnings.extend(fe_warnings(&fe_figures(scene, &sim, r_star, oblique)));
    if sim.savings.reduction != Reduction::Axisymmetric {
        warnings.extend(contact_caps(scene, &fe, r_star));
    }
    warnings.extend(super::ignored::ignored_settings(
        scene,
        sim.savings.reduction,
    ));
    Ok(RunReport {
        impact: true,
        no_impact_reason: None,
        e: Some(fe.e),
        v1_after: fe.v1_after,
        v2_after: fe.v2_after,
        w1_after: fe.w1_after,
        w2_after: fe.w2_after,
        delta_max: fe.delta_max,
        contact_duration: fe.contact_duration,
        eta: Some(fe.eta),
        energy_error: sim.energy_error,
        reduction: sim.savings.reduction.name().into(),
        wall_time_s: start.elapsed().as_secs_f64(),
        element_cycles: sim.element_cycles,
        relative_difference: Some(Differences::between(&fe, &an, touch.frame.axes[0])),
        tangential: oblique.then(|| TangentialPair {
            fe: tangential(scene, &touch, &fe).with_spin1_inertia_ratio(sim.spin1_inertia_ratio),
            analytic: tangential(scene, &touch, &an),
            theory: theory.map(|t| tangential(scene, &touch, &t)),
        }),
        force_curve: ForceCurve::of_run(&sim.history),
        fe: Some(sim),
        analytic: Some(an),
        laws,
        warnings,
        error_estimate: None,
        scene: scene.clone(),
    })
}

/// Makes `report` (the run of a section scene's finest level) that level's answer: e,
/// δ_max and the contact duration become the means of its phase ensemble `level`, since one
/// ring phase alone scatters by about ±2 % in e ([`crate::study::convergence::phase_ensemble`]). The after-impact
/// velocities are the run's with their normal parts about the fixed one (the centre of mass,
/// or the wall) scaled to the mean e, which keeps momentum and the head-on direction; η and
/// the differences from the analytical model and `fe.outcome` follow; the rest of `fe`
/// (steps, energy, history) stays the run's.
///
/// Errors: a report without an impact or without its analytical outcome.
pub fn take_phase_mean(report: &mut RunReport, level: &LevelOutcome) -> Result<()> {
    let (Some(e_run), Some(an)) = (report.e, report.analytic.as_ref()) else {
        return Err(Error::Numerical(
            "phase mean: the finest run reports no impact".into(),
        ));
    };
    let scene = &report.scene;
    let Approach::Impact(touch) = approach(scene)? else {
        return Err(Error::Numerical(
            "phase mean: the scene has no impact".into(),
        ));
    };
    let n = touch.frame.axes[0];
    let weight = |b: &crate::scene::BallScene| ball_inertia(b.material.rho, b.diameter).0;
    let (m1, m2) = (weight(&scene.ball1), weight(&scene.ball2));
    // The wall (ball 2's columns) does not move: all the weight is its.
    let share1 = if scene.wall.is_some() {
        0.0
    } else {
        m1 / (m1 + m2)
    };
    let dot = |a: [f64; 3]| a[0] * n[0] + a[1] * n[1] + a[2] * n[2];
    let fixed = share1 * dot(report.v1_after) + (1.0 - share1) * dot(report.v2_after);
    let scale = if e_run != 0.0 { level.e / e_run } else { 1.0 };
    let rescale = |v: [f64; 3]| {
        let shift = (dot(v) - fixed) * (scale - 1.0);
        [
            v[0] + shift * n[0],
            v[1] + shift * n[1],
            v[2] + shift * n[2],
        ]
    };
    report.v1_after = rescale(report.v1_after);
    report.v2_after = rescale(report.v2_after);
    report.e = Some(level.e);
    report.delta_max = level.delta_max;
    report.contact_duration = level.contact_duration;
    let eta = dissipation_factor(
        scene,
        [report.v1_after, report.v2_after],
        [report.w1_after, report.w2_after],
    );
    report.eta = Some(eta);
    let fe = Outcome {
        e: level.e,
        v1_after: report.v1_after,
        v2_after: report.v2_after,
        w1_after: report.w1_after,
        w2_after: report.w2_after,
        delta_max: level.delta_max,
        contact_duration: level.contact_duration,
        eta,
    };
    report.relative_difference = Some(Differences::between(&fe, an, n));
    if let Some(sim) = report.fe.as_mut() {
        sim.outcome = fe;
    }
    Ok(())
}

/// Element size at the contact pole of the built-in meshes (the coarser ball's), m; None
/// for meshes read from files.
fn pole_size(scene: &Scene) -> Option<f64> {
    let h = |m: &MeshSettings| match m {
        MeshSettings::Builtin { pole_size, .. } => Some(*pole_size),
        MeshSettings::File { .. } => None,
    };
    Some(h(&scene.ball1.mesh)?.max(h(&scene.ball2.mesh)?))
}

/// The figures the FE warnings check, from a finished run (`oblique`: an oblique or spinning
/// impact, whose kinetic energy after over before is 1 − 2π η).
fn fe_figures(scene: &Scene, sim: &Simulation, r_star: f64, oblique: bool) -> FeFigures {
    let peak = |f: fn(&crate::study::run::simulate::HistoryRow) -> f64| {
        sim.history.iter().map(f).fold(0.0, f64::max)
    };
    FeFigures {
        energy_error: sim.energy_error,
        e: sim.outcome.e,
        delta_max: sim.outcome.delta_max,
        max_penetration: sim.max_penetration,
        r_star,
        pole_size: pole_size(scene),
        hourglass: peak(|r| r.hourglass),
        internal: peak(|r| r.elastic + r.plastic + r.hourglass),
        kinetic_ratio: oblique.then_some(1.0 - 2.0 * std::f64::consts::PI * sim.outcome.eta),
    }
}

/// Writes results.json, history.csv and (with an impact) force_curve.csv into `dir` (created
/// if needed), each atomically.
pub fn write_outputs(report: &RunReport, dir: &Path) -> Result<()> {
    ensure_dir(dir)?;
    let json = serde_json::to_string_pretty(report)
        .map_err(|e| Error::Parse(format!("results.json: {e}")))?;
    if !report.energy_error.is_finite()
        || report.fe.as_ref().is_some_and(|f| !f.outcome.is_finite())
    {
        return Err(Error::Numerical(
            "results contain a non-finite value; nothing written".into(),
        ));
    }
    write_atomic(dir.join("results.json"), json.as_bytes())?;
    let mut csv = String::from(HISTORY_HEADER);
    csv.push('\n');
    if let Some(sim) = &report.fe {
        for r in &sim.history {
            csv.push_str(&r.csv());
            csv.push('\n');
        }
    }
    write_atomic(dir.join("history.csv"), csv.as_bytes())?;
    let curve = &report.force_curve;
    if curve.delta.is_empty() {
        return Ok(());
    }
    if !curve.is_finite() {
        return Err(Error::Numerical(
            "force_curve.csv: a non-finite force or bar; not written".into(),
        ));
    }
    write_atomic(dir.join("force_curve.csv"), curve.csv().as_bytes())
}

/// The side-by-side table printed by `twoball run`.
pub fn side_by_side(r: &RunReport) -> String {
    let mut s = String::new();
    let sc = &r.scene;
    match &sc.wall {
        None => s.push_str(&format!(
            "scene: ball1 {} D = {} m v = {:?} m/s; ball2 {} D = {} m v = {:?} m/s\n",
            sc.ball1.material_name,
            sc.ball1.diameter,
            sc.ball1.velocity,
            sc.ball2.material_name,
            sc.ball2.diameter,
            sc.ball2.velocity
        )),
        Some(w) => {
            let kind = match (w.material, w.size) {
                (Some(m), Some(size)) => format!(
                    "elastic wall (E = {:.4e} Pa, block W x H = {} x {} m)",
                    m.youngs, size[0], size[1]
                ),
                _ => "rigid wall".to_string(),
            };
            s.push_str(&format!(
                "scene: ball1 {} D = {} m v = {:?} m/s; {kind} through {:?} m, normal {:?}\n",
                sc.ball1.material_name, sc.ball1.diameter, sc.ball1.velocity, w.position, w.normal
            ))
        }
    }
    if !r.impact {
        s.push_str(&format!(
            "no impact: {}\n",
            r.no_impact_reason.as_deref().unwrap_or("")
        ));
        return s;
    }
    let (Some(sim), Some(an), Some(d)) = (&r.fe, &r.analytic, &r.relative_difference) else {
        return s;
    };
    let fe = &sim.outcome;
    let n = |v: [f64; 3]| v[0];
    let t = |v: [f64; 3]| v[1];
    s.push_str(&format!(
        "{:<34}{:>14}{:>14}{:>10}\n",
        "quantity", "FE", "analytical", "diff"
    ));
    let mut row = |name: &str, a: f64, b: f64, diff: Option<f64>| {
        let d = diff.map_or(String::from("-"), |x| format!("{:+.2}%", 100.0 * x));
        s.push_str(&format!(
            "{name:<34}{:>14}{:>14}{d:>10}\n",
            sci(a, 6),
            sci(b, 6)
        ));
    };
    row("e [-]", fe.e, an.e, Some(d.e));
    row(
        "ball 1 normal velocity after [m/s]",
        n(fe.v1_after),
        n(an.v1_after),
        Some(d.v1n_after),
    );
    row(
        "ball 2 normal velocity after [m/s]",
        n(fe.v2_after),
        n(an.v2_after),
        Some(d.v2n_after),
    );
    row(
        "ball 1 tangential velocity [m/s]",
        t(fe.v1_after),
        t(an.v1_after),
        Some(relative_difference(t(fe.v1_after), t(an.v1_after))),
    );
    row(
        "ball 2 tangential velocity [m/s]",
        t(fe.v2_after),
        t(an.v2_after),
        Some(relative_difference(t(fe.v2_after), t(an.v2_after))),
    );
    row(
        "delta_max [m]",
        fe.delta_max,
        an.delta_max,
        Some(d.delta_max),
    );
    row(
        "contact duration [s]",
        fe.contact_duration,
        an.contact_duration,
        Some(d.contact_duration),
    );
    row("eta [-]", fe.eta, an.eta, Some(d.eta));
    if let Some(tp) = &r.tangential {
        let f = tp.fe;
        // The analytical model's rows, then (elastic impacts) Maw, Barber & Fawcett's in the
        // analytical column.
        let sides = [("", Some(tp.analytic)), (", MBF", tp.theory)];
        for (label, other) in sides {
            let Some(a) = other else { continue };
            // No relative difference: e_t is 0 for a contact point that rolls off.
            if let (Some(x), Some(y)) = (f.restitution, a.restitution) {
                row(&format!("tangential restitution{label} [-]"), x, y, None);
            }
            let angle = relative_difference(f.rebound_angle, a.rebound_angle);
            let name = format!("rebound angle{label} [rad]");
            row(&name, f.rebound_angle, a.rebound_angle, Some(angle));
            let spin = relative_difference(f.spin1_after, a.spin1_after);
            let name = format!("ball 1 spin after{label} [rad/s]");
            row(&name, f.spin1_after, a.spin1_after, Some(spin));
        }
    }
    s.push_str(&format!(
        "FE: {} model ({}), {} elements, {} steps, dt = {:.3e} s, energy error {:.2e}, {:.2} s wall; {}\n",
        sim.savings.reduction.name(),
        sim.savings.reduction_reason,
        sim.elements,
        sim.steps,
        sim.dt,
        sim.energy_error,
        r.wall_time_s,
        sim.stop_reason
    ));
    if an.e < 1.0 {
        s.push_str(DELTA_MAX_NOTE);
        s.push('\n');
    }
    s.push_str(&law_table(&r.laws));
    s
}

/// Why FE and analytical δ_max and contact duration differ, printed under every plastic
/// impact's table.
pub const DELTA_MAX_NOTE: &str = "note: the FE delta_max and contact duration are about 40 % below the analytical ones by design: the model's phase-2 contact (Hertz area, pressure capped at 2.57 yield) is softer than a resolved elastic-plastic contact, so it reaches deeper and lasts longer; see verification/NOTES.md";

/// The contact-cap warnings of a 3D run's balls ([`crate::study::records::warnings::patch_reach`]
/// against [`crate::mesh::ball::CONTACT_HALF_ANGLE_DEG`]); a wall's image ball is not meshed.
fn contact_caps(
    scene: &Scene,
    fe: &crate::study::records::outcome::Outcome,
    r_star: f64,
) -> Vec<Warning> {
    use crate::study::records::warnings::{contact_cap, patch_reach};
    let cap = crate::mesh::ball::CONTACT_HALF_ANGLE_DEG;
    let balls = [
        ("ball1", &scene.ball1, fe.w1_after),
        ("ball2", &scene.ball2, fe.w2_after),
    ];
    let meshed = if scene.wall.is_some() { 1 } else { 2 };
    balls[..meshed]
        .iter()
        .filter_map(|(name, b, after)| {
            let spins = [b.angular_velocity, *after];
            let reach = patch_reach(
                b.diameter / 2.0,
                r_star,
                fe.delta_max,
                spins,
                fe.contact_duration,
            )
            .to_degrees();
            (reach > cap).then(|| contact_cap(name, reach, cap))
        })
        .collect()
}
