//! `twoball bench profile [SCENE]`: one run of a scene (default: the built-in Figure 8 case)
//! with the solver's phase timer on; prints where the wall time went.

use crate::error::{Error, Result};
use crate::fe::profile::{self, Phase};
use crate::scene::{Override, Scene, DEFAULT_SCENE};
use crate::study::simulate::RunOptions;
use crate::study::single::run_scene;
use clap::Args;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Arguments of `twoball bench profile`.
#[derive(Debug, Args)]
pub struct ProfileArgs {
    /// Scene file (TOML); the built-in default scene if absent.
    pub scene: Option<PathBuf>,
    /// Override a scene value by its dotted path (as `twoball run --set`).
    #[arg(long = "set", value_name = "PATH=VALUE")]
    pub sets: Vec<String>,
    /// Thread count (default: all available).
    #[arg(long)]
    pub threads: Option<usize>,
}

/// Runs the scene once with profiling on and prints the phase table.
pub fn profile(a: ProfileArgs) -> Result<()> {
    let sets = a
        .sets
        .iter()
        .map(|s| Override::parse(s))
        .collect::<Result<Vec<_>>>()?;
    let scene = match &a.scene {
        Some(p) => Scene::from_file(p, &sets)?,
        None => Scene::from_toml(DEFAULT_SCENE, Path::new("."), &sets)?,
    };
    let threads = match a.threads {
        Some(0) => return Err(Error::invalid("--threads", 0, "at least 1")),
        Some(n) => n,
        None => std::thread::available_parallelism().map_or(1, |n| n.get()),
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| Error::External(format!("thread pool: {e}")))?;
    profile::take_totals();
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
    let t = profile::take_totals();
    println!(
        "# twoball bench profile: {} threads, {} steps, {} element-cycles, e = {}",
        threads,
        t.steps,
        t.element_cycles,
        report.e.map_or("-".into(), |e| format!("{e:.6e}"))
    );
    print!("{}", t.table());
    let setup = (wall - t.sum()).max(0.0);
    println!(
        "{:<48} {:>9.3}\n{:<48} {:>9.3}",
        "setup (mesh, model, analytic, first forces)", setup, "wall time of the run", wall
    );
    let solver = t.sum() - t.get(Phase::Outside);
    if solver > 0.0 {
        println!(
            "# contact share of the solver's step time: {:.1}%",
            100.0 * t.get(Phase::Contact) / solver
        );
    }
    Ok(())
}
