//! The phase profile of `twoball bench profile`: one run of a scene with the solver's phase
//! timer on, and where its wall time went.

use crate::error::{Error, Result};
use crate::fe::profile::StepPhase;
use crate::scene::Scene;
use crate::study::run::scene::run_scene;
use crate::study::run::simulate::RunOptions;
use std::io::Write;
use std::time::Instant;

/// Runs `scene` once on `threads` threads (`None`: all available) with the phase timer on,
/// and writes the phase table, the setup and wall times (s) and the contact share to `out`.
/// The profile is the 3D solver's: `reduction.symmetry = "auto"` runs as `"auto-3d"`.
///
/// Errors: zero threads ([`Error::Invalid`] naming `--threads`); a thread pool that cannot be
/// built; any error of the run; a failed write to `out`.
pub fn profile(scene: &Scene, threads: Option<usize>, out: &mut impl Write) -> Result<()> {
    let threads = match threads {
        Some(0) => return Err(Error::invalid("--threads", 0, "at least 1")),
        Some(n) => n,
        None => std::thread::available_parallelism().map_or(1, |n| n.get()),
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| Error::External(format!("thread pool: {e}")))?;
    let mut scene = scene.clone();
    scene.reduction.symmetry = scene.reduction.symmetry.three_d();
    let t0 = Instant::now();
    let report = pool.install(|| {
        run_scene(
            &scene,
            &RunOptions {
                history_rows: 400,
                progress: false,
                profile: true,
                ..Default::default()
            },
        )
    });
    let wall = t0.elapsed().as_secs_f64();
    let report = report?;
    let t = report
        .fe
        .as_ref()
        .and_then(|s| s.phases)
        .unwrap_or_default();
    writeln!(
        out,
        "# twoball bench profile: {} threads, {} steps, {} element-cycles, e = {}",
        threads,
        t.steps,
        t.element_cycles,
        report.e.map_or("-".into(), |e| format!("{e:.6e}"))
    )
    .map_err(put)?;
    write!(out, "{}", t.table()).map_err(put)?;
    let setup = (wall - t.sum()).max(0.0);
    writeln!(
        out,
        "{:<48} {:>9.3}\n{:<48} {:>9.3}",
        "setup (mesh, model, analytic, first forces)", setup, "wall time of the run", wall
    )
    .map_err(put)?;
    let solver = t.sum() - t.get(StepPhase::Outside);
    if solver > 0.0 {
        writeln!(
            out,
            "# contact share of the solver's step time: {:.1}%",
            100.0 * t.get(StepPhase::Contact) / solver
        )
        .map_err(put)?;
    }
    Ok(())
}

/// A failed write of the results.
fn put(e: std::io::Error) -> Error {
    Error::io("standard output", e)
}
