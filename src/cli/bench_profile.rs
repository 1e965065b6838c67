//! `twoball bench profile [SCENE]`: the arguments; the run and its phase table are
//! `study::bench::profile`.

use crate::error::Result;
use clap::Args;
use std::path::PathBuf;

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

/// Reads the scene and runs it once with profiling on.
pub fn profile(a: ProfileArgs) -> Result<()> {
    let scene = super::read_scene(a.scene.as_deref(), &a.sets)?;
    crate::study::bench::profile::profile(&scene, a.threads, &mut std::io::stdout().lock())
}
