//! Running damper cases (in parallel) and writing their results: the history CSV with units,
//! the cycle-by-cycle damping, and one summary row per case.

use super::decay::{cycle_ratios, log_decrement, peaks, Decay};
use super::file::{DamperCase, Measured};
use super::sim::{DamperSimulation, Sample};
use crate::analytic::laws::Registry;
use crate::atomic::{ensure_dir, write_atomic};
use crate::error::{Error, Result};
use crate::mesh::points_vtu::spheres_vtu_bytes;
use crate::mesh::vtu::{write_pvd, VtuFormat};
use rayon::prelude::*;
use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

/// What one case gave.
#[derive(Debug, Clone)]
pub struct CaseOutcome {
    /// Case name.
    pub name: String,
    /// Number of balls.
    pub balls: usize,
    /// Total ball mass, kg.
    pub ball_mass: f64,
    /// Frame mass, kg.
    pub frame_mass: f64,
    /// Frequency and damping ratio by the logarithmic decrement over the window.
    pub decay: Decay,
    /// Window of the decrement, s.
    pub window: (f64, f64),
    /// The paper's values, if given.
    pub measured: Option<Measured>,
    /// Damping ratio of the empty structure (the frame's, a fraction).
    pub empty_damping: f64,
    /// Largest |energy balance residual| over the samples (relative to the initial energy).
    pub worst_residual: f64,
    /// Time step, s.
    pub dt: f64,
    /// Steps taken.
    pub steps: u64,
    /// Wall-clock time of the simulation, s.
    pub wall_time: f64,
    /// The recorded samples.
    pub samples: Vec<Sample>,
    /// Ball radii, m.
    pub radii: Vec<f64>,
    /// The balls' states at up to [`BALL_FRAMES`] evenly spaced samples (none without balls).
    pub frames: Vec<BallFrame>,
}

/// The balls at one instant.
#[derive(Debug, Clone, PartialEq)]
pub struct BallFrame {
    /// Time since release, s.
    pub time: f64,
    /// Ball centres (inertial frame), m.
    pub position: Vec<[f64; 3]>,
    /// Ball velocities, m/s.
    pub velocity: Vec<[f64; 3]>,
}

impl CaseOutcome {
    /// The damping ratio the balls add, ζ − ζ_empty (a fraction; ζ over the window).
    pub fn added_damping(&self) -> f64 {
        self.decay.ratio - self.empty_damping
    }

    /// The damping ratio the balls added in the measurement, ζ_measured − ζ_empty (a
    /// fraction), if the case has a measured ζ.
    pub fn measured_added_damping(&self) -> Option<f64> {
        self.measured.map(|m| m.damping_ratio - self.empty_damping)
    }
}

/// Most ball frames kept per case (the VTU series of the balls).
pub const BALL_FRAMES: usize = 200;

/// Runs one case to its duration and reads its decay. Errors: an invalid scene or law, a
/// non-finite state, fewer than two peaks in the window (each naming the case).
pub fn run_case(case: &DamperCase, registry: &Registry) -> Result<CaseOutcome> {
    run_case_observed(case, registry, &|_| Ok(()))
}

/// How often a running case reports its simulated time, s.
pub const REPORT_INTERVAL: f64 = 0.05;

/// [`run_case`], calling `at(t)` with the simulated time t (s) at release and about every
/// [`REPORT_INTERVAL`]; an error of `at` (e.g. an interrupt) stops the case and is returned.
pub fn run_case_observed(
    case: &DamperCase,
    registry: &Registry,
    at: &dyn Fn(f64) -> Result<()>,
) -> Result<CaseOutcome> {
    let named = |e: Error| match e {
        Error::Numerical(m) => Error::Numerical(format!("case {}: {m}", case.name)),
        other => other.within(&format!("case {}", case.name)),
    };
    let start = Instant::now();
    let mut sim = DamperSimulation::new(&case.scene, registry).map_err(named)?;
    let expected = (case.scene.duration / case.scene.sample_interval).ceil() as usize + 1;
    let every = expected.div_ceil(BALL_FRAMES).max(1);
    let mut frames = Vec::new();
    let mut seen = 0usize;
    let report_every = ((REPORT_INTERVAL / case.scene.sample_interval).round() as usize).max(1);
    let samples = sim
        .run_observed(case.scene.duration, case.scene.sample_interval, &mut |s| {
            if seen.is_multiple_of(report_every) {
                at(s.time)?;
            }
            if !s.position.is_empty() && seen.is_multiple_of(every) {
                let v3 = |v: &nalgebra::Vector3<f64>| [v.x, v.y, v.z];
                frames.push(BallFrame {
                    time: s.time,
                    position: s.position.iter().map(v3).collect(),
                    velocity: s.velocity.iter().map(v3).collect(),
                });
            }
            seen += 1;
            Ok(())
        })
        .map_err(|e| match e {
            Error::Interrupted(_) => e,
            other => named(other),
        })?;
    let wall_time = start.elapsed().as_secs_f64();
    let t: Vec<f64> = samples.iter().map(|s| s.time).collect();
    let x: Vec<f64> = samples.iter().map(|s| s.displacement).collect();
    let decay = log_decrement(&peaks(&t, &x), case.window).map_err(named)?;
    let first = samples[0].ledger;
    let worst_residual = samples
        .iter()
        .map(|s| s.ledger.residual(&first).abs())
        .fold(0.0, f64::max);
    let bodies = case.scene.bodies()?;
    Ok(CaseOutcome {
        name: case.name.clone(),
        balls: bodies.len(),
        // 0.0 + : an empty sum of f64 is −0.0, printed "-0".
        ball_mass: 0.0 + bodies.iter().map(|b| b.mass()).sum::<f64>(),
        frame_mass: case.scene.frame.mass,
        decay,
        window: case.window,
        measured: case.measured,
        empty_damping: case.scene.frame.damping_ratio,
        worst_residual,
        dt: sim.dt(),
        steps: sim.steps,
        wall_time,
        samples,
        radii: sim.radii().to_vec(),
        frames,
    })
}

/// Runs every case, in parallel across cases; the outcomes keep the cases' order.
pub fn run_cases(cases: &[DamperCase], registry: &Registry) -> Result<Vec<CaseOutcome>> {
    run_cases_observed(cases, registry, &|_, _| Ok(()))
}

/// [`run_cases`], calling `at(k, t)` as case `k` (its index in `cases`) reaches simulated
/// time t (s), as [`run_case_observed`] does; the first error stops every case.
pub fn run_cases_observed(
    cases: &[DamperCase],
    registry: &Registry,
    at: &(dyn Fn(usize, f64) -> Result<()> + Sync),
) -> Result<Vec<CaseOutcome>> {
    cases
        .par_iter()
        .enumerate()
        .map(|(k, c)| run_case_observed(c, registry, &|t| at(k, t)))
        .collect()
}

/// The history CSV of one case: frame motion, the ball force on the box and every energy term.
pub fn history_csv(samples: &[Sample]) -> String {
    let mut s = String::from(
        "time [s],displacement [m],velocity [m/s],acceleration [m/s^2],ball_force [N],contacts [-],\
frame_kinetic [J],frame_spring [J],balls_kinetic [J],balls_potential [J],contact_stored [J],\
contact_dissipated [J],friction_dissipated [J],structural_dissipated [J],energy_residual [-]\n",
    );
    let first = samples.first().map(|s| s.ledger).unwrap_or_default();
    for x in samples {
        let l = &x.ledger;
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}",
            x.time,
            x.displacement,
            x.velocity,
            x.acceleration,
            x.ball_force,
            x.contacts,
            l.frame_kinetic,
            l.frame_spring,
            l.balls_kinetic,
            l.balls_potential,
            l.contact_stored,
            l.contact_dissipated,
            l.friction_dissipated,
            l.structural_dissipated,
            l.residual(&first)
        );
    }
    s
}

/// The cycle-by-cycle damping CSV of one case (amplitude dependence).
pub fn cycles_csv(samples: &[Sample]) -> String {
    let t: Vec<f64> = samples.iter().map(|s| s.time).collect();
    let x: Vec<f64> = samples.iter().map(|s| s.displacement).collect();
    let mut s = String::from("time [s],amplitude [m],damping_ratio [-]\n");
    for (a, t, z) in cycle_ratios(&peaks(&t, &x)) {
        let _ = writeln!(s, "{t},{a},{z}");
    }
    s
}

/// Header of the summary CSV.
pub const SUMMARY_HEADER: &str = "case,balls [-],ball_mass [kg],mass_ratio [-],frequency [Hz],\
damping_ratio [-],measured_frequency [Hz],measured_damping_ratio [-],cycles [-],window_start [s],\
window_end [s],energy_residual [-],dt [s],steps [-],wall_time [s],empty_damping_ratio [-],\
added_damping_ratio [-],measured_added_damping_ratio [-]";

/// The summary CSV: one row per case.
pub fn summary_csv(outcomes: &[CaseOutcome]) -> String {
    let mut s = format!("{SUMMARY_HEADER}\n");
    for o in outcomes {
        let (mf, mz) = o.measured.map_or((String::new(), String::new()), |m| {
            (m.frequency.to_string(), m.damping_ratio.to_string())
        });
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{:.2},{},{},{}",
            o.name,
            o.balls,
            o.ball_mass,
            o.ball_mass / o.frame_mass,
            o.decay.frequency,
            o.decay.ratio,
            mf,
            mz,
            o.decay.cycles,
            o.window.0,
            o.window.1,
            o.worst_residual,
            o.dt,
            o.steps,
            o.wall_time,
            o.empty_damping,
            o.added_damping(),
            o.measured_added_damping()
                .map_or(String::new(), |d| d.to_string())
        );
    }
    s
}

/// Writes the balls' frames of `o` as a ParaView series into `case`: `balls_NNNN.vtu` (points
/// with `radius` [m] and `velocity` [m/s], compressed binary) and `balls.pvd`.
///
/// Errors: a non-finite state (nothing written for that frame), I/O errors naming the path.
pub fn write_ball_series(case: &Path, o: &CaseOutcome) -> Result<()> {
    let mut written = Vec::new();
    for (k, f) in o.frames.iter().enumerate() {
        let name = format!("balls_{k:04}.vtu");
        let bytes = spheres_vtu_bytes(
            &f.position,
            &o.radii,
            &f.velocity,
            f.time,
            VtuFormat::Binary,
        )?;
        write_atomic(case.join(&name), &bytes)?;
        written.push((f.time, name));
    }
    if written.is_empty() {
        return Ok(());
    }
    write_pvd(case.join("balls.pvd"), &written)
}

/// Writes `summary.csv` and, per case, `CASE/history.csv`, `CASE/cycles.csv` and the balls'
/// series ([`write_ball_series`]) into `dir` (created if needed; every file written
/// atomically).
pub fn write_outputs(dir: &Path, outcomes: &[CaseOutcome]) -> Result<()> {
    ensure_dir(dir)?;
    for o in outcomes {
        let case = dir.join(&o.name);
        ensure_dir(&case)?;
        write_atomic(case.join("history.csv"), history_csv(&o.samples).as_bytes())?;
        write_atomic(case.join("cycles.csv"), cycles_csv(&o.samples).as_bytes())?;
        write_ball_series(&case, o)?;
    }
    write_atomic(dir.join("summary.csv"), summary_csv(outcomes).as_bytes())
}
