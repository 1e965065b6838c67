//! `twoball sweep FILE --out DIR [--jobs N] [--shard I/N]`: a parameter sweep such as the
//! paper's ANSYS study, resumable and shardable; each impacting case runs the FE model
//! ([`crate::study::simulate::sweep_case`]) beside the analytical one.

use crate::error::Result;
use crate::study::sweep::{run_sweep, Shard, SweepModel, SweepOptions, SweepSpec};
use clap::Args;
use std::path::PathBuf;
use std::time::Duration;

/// Arguments of `twoball sweep`.
#[derive(Debug, Args)]
pub struct SweepArgs {
    /// Sweep file (TOML), e.g. verification/ansys-study.toml.
    pub file: PathBuf,
    /// Output folder: one JSON per case in DIR/cases/, all cases in DIR/sweep.csv.
    #[arg(long)]
    pub out: PathBuf,
    /// Worker threads (default: all cores).
    #[arg(long)]
    pub jobs: Option<usize>,
    /// Run only shard I of N (1-based), for cluster job arrays.
    #[arg(long, default_value = "1/1")]
    pub shard: String,
    /// Run the analytical model only, whatever the file says.
    #[arg(long)]
    pub analytic_only: bool,
    /// Run only the cases of this mesh setting (a `name` of the file's `[[mesh]]` tables).
    #[arg(long)]
    pub mesh: Option<String>,
    /// Minimum wall time per case in ms (testing aid for kill-and-resume).
    #[arg(long, default_value_t = 0, hide = true)]
    pub pace_ms: u64,
}

/// Runs `twoball sweep`.
pub fn run(a: SweepArgs) -> Result<()> {
    let mut spec = SweepSpec::from_file(&a.file)?;
    if a.analytic_only {
        spec.model = SweepModel::Analytic;
    }
    let shard = Shard::parse(&a.shard)?;
    let jobs = match a.jobs {
        Some(0) => return Err(crate::Error::invalid("--jobs", 0, "jobs >= 1")),
        Some(n) => n,
        None => std::thread::available_parallelism().map_or(1, |n| n.get()),
    };
    let opts = SweepOptions {
        out: a.out.clone(),
        jobs,
        shard,
        pace: Duration::from_millis(a.pace_ms),
        verbose: true,
        mesh: a.mesh.clone(),
    };
    let fe: crate::study::sweep::FeRunner<'_> = &crate::study::simulate::sweep_case;
    let s = run_sweep(&spec, &opts, Some(fe))?;
    println!(
        "sweep {}: {} cases, shard {}/{} has {} ({} already done, {} run now); {} in {} ({} failed)",
        a.file.display(),
        s.total,
        shard.index,
        shard.count,
        s.in_shard,
        s.skipped,
        s.ran,
        s.in_csv,
        a.out.join("sweep.csv").display(),
        s.failed
    );
    Ok(())
}
