//! `twoball run [SCENE] [--out DIR] [--set PATH=VALUE]... [--vtu-ascii]`: one scene, FE beside
//! the analytical model.

use crate::error::{Error, Result};
use crate::scene::{Override, Scene, DEFAULT_SCENE};
use crate::study::simulate::RunOptions;
use crate::study::single::{run_scene, side_by_side, write_outputs};
use clap::Args;
use std::path::{Path, PathBuf};
use std::time::SystemTime;

/// Arguments of `twoball run`.
#[derive(Debug, Args)]
pub struct RunArgs {
    /// Scene file (TOML); the built-in default is the paper's Figure 8 case.
    pub scene: Option<PathBuf>,
    /// Output folder for results.json and history.csv (and the .vtu snapshots).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Override a scene value by its dotted path, e.g. --set ball1.material.yield=1e11.
    #[arg(long = "set", value_name = "PATH=VALUE", allow_hyphen_values = true)]
    pub sets: Vec<String>,
    /// Write the .vtu snapshots as ASCII text (default: compressed binary, as ParaView does).
    #[arg(long)]
    pub vtu_ascii: bool,
}

/// Runs `twoball run`.
pub fn run(a: RunArgs) -> Result<()> {
    let sets = a
        .sets
        .iter()
        .map(|s| Override::parse(s))
        .collect::<Result<Vec<_>>>()?;
    let scene = match &a.scene {
        Some(p) => Scene::from_file(p, &sets)?,
        None => Scene::from_toml(DEFAULT_SCENE, Path::new("."), &sets)?,
    };
    let opts = RunOptions {
        history_rows: 400,
        progress: true,
        snapshot_dir: a.out.clone(),
        vtu_ascii: a.vtu_ascii,
        ..RunOptions::default()
    };
    let created = a.out.as_ref().is_some_and(|d| !d.exists());
    if let Some(dir) = &a.out {
        crate::atomic::ensure_dir(dir)?;
    } else if scene.output.vtu_snapshots > 0 {
        eprintln!("note: output.vtu_snapshots needs --out DIR; no snapshots written");
    }
    let started = SystemTime::now();
    let report = match run_scene(&scene, &opts) {
        Err(Error::Interrupted(at)) => {
            let removed = a
                .out
                .as_ref()
                .map_or(0, |d| remove_partial_output(d, started, created));
            let what = if removed > 0 {
                format!("; nothing written ({removed} snapshot files of this run removed)")
            } else {
                "; nothing written".into()
            };
            return Err(Error::Interrupted(format!("{at}{what}")));
        }
        r => r?,
    };
    print!("{}", side_by_side(&report));
    crate::study::warnings::print(&report.warnings);
    if let Some(dir) = &a.out {
        write_outputs(&report, dir)?;
        println!(
            "wrote {} and {}",
            dir.join("results.json").display(),
            dir.join("history.csv").display()
        );
    }
    Ok(())
}

/// Removes the snapshot files (`snapshot_*.vtu`, `snapshots.pvd`) that an interrupted run
/// wrote into `dir` since `started`, and `dir` itself if the run `created` it and it is now
/// empty, so that no folder looks complete; returns the number of files removed.
fn remove_partial_output(dir: &Path, started: SystemTime, created: bool) -> usize {
    let mut removed = 0;
    if let Ok(entries) = std::fs::read_dir(dir) {
        for e in entries.flatten() {
            let name = e.file_name().to_string_lossy().to_string();
            let ours = (name.starts_with("snapshot_") && name.ends_with(".vtu"))
                || name == "snapshots.pvd";
            let new = e
                .metadata()
                .and_then(|m| m.modified())
                .is_ok_and(|t| t >= started);
            if ours && new && std::fs::remove_file(e.path()).is_ok() {
                removed += 1;
            }
        }
    }
    if created {
        // Fails (and keeps the folder) if anything else is in it.
        let _ = std::fs::remove_dir(dir);
    }
    removed
}
