//! `twoball stress [--matrix FILE] --out DIR [--jobs N] [--quick]`: the stability matrix.

use crate::error::{Error, Result};
use crate::study::stress::{run_stress, StressOptions, StressSpec};
use clap::Args;
use std::io::IsTerminal;
use std::path::PathBuf;

/// Arguments of `twoball stress`.
#[derive(Debug, Args)]
pub struct StressArgs {
    /// Matrix file (TOML).
    #[arg(long, default_value = "verification/stress.toml")]
    pub matrix: PathBuf,
    /// Output folder: DIR/cases/ID.json per case, DIR/summary.md.
    #[arg(long)]
    pub out: PathBuf,
    /// Cases run at once (default: all cores).
    #[arg(long)]
    pub jobs: Option<usize>,
    /// Run only the matrix's quick subset.
    #[arg(long)]
    pub quick: bool,
}

/// Runs `twoball stress`; fails if any case failed silently.
pub fn run(a: StressArgs) -> Result<()> {
    let spec = StressSpec::from_file(&a.matrix)?;
    let jobs = match a.jobs {
        Some(0) => return Err(Error::invalid("--jobs", 0, "jobs >= 1")),
        Some(n) => n,
        None => std::thread::available_parallelism().map_or(1, |n| n.get()),
    };
    let exe = std::env::current_exe()
        .map_err(|e| Error::External(format!("cannot locate the twoball executable: {e}")))?;
    let opts = StressOptions {
        out: a.out.clone(),
        jobs,
        quick: a.quick,
        exe,
        verbose: std::io::stderr().is_terminal(),
    };
    let (c, _) = run_stress(&spec, &opts)?;
    println!(
        "stress: {} cases: {} completed (energy error < tolerance), {} flagged, {} stopped with a reason, {} silent failures; {}",
        c.total,
        c.clean,
        c.flagged,
        c.stopped,
        c.silent,
        a.out.join("summary.md").display()
    );
    if c.silent > 0 {
        return Err(Error::Numerical(format!(
            "{} silent failure(s): see {}",
            c.silent,
            a.out.join("summary.md").display()
        )));
    }
    Ok(())
}
