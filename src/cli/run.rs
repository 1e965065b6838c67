//! `twoball run [SCENE] [--out DIR] [--set PATH=VALUE]...`: one scene, FE beside the
//! analytical model.

use crate::error::Result;
use crate::scene::{Override, Scene, DEFAULT_SCENE};
use crate::study::simulate::RunOptions;
use crate::study::single::{run_scene, side_by_side, write_outputs};
use clap::Args;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};

/// Arguments of `twoball run`.
#[derive(Debug, Args)]
pub struct RunArgs {
    /// Scene file (TOML); the built-in default is the paper's Figure 8 case.
    pub scene: Option<PathBuf>,
    /// Output folder for results.json and history.csv.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Override a scene value by its dotted path, e.g. --set ball1.material.yield=1e11.
    #[arg(long = "set", value_name = "PATH=VALUE")]
    pub sets: Vec<String>,
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
        progress: std::io::stderr().is_terminal(),
        snapshot_dir: a.out.clone(),
        ..RunOptions::default()
    };
    if let Some(dir) = &a.out {
        crate::atomic::ensure_dir(dir)?;
    } else if scene.output.vtu_snapshots > 0 {
        eprintln!("note: output.vtu_snapshots needs --out DIR; no snapshots written");
    }
    let report = run_scene(&scene, &opts)?;
    print!("{}", side_by_side(&report));
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
