//! `twoball stress [--matrix FILE] --out DIR [--jobs N] [--quick]`: the stability matrix.

use crate::error::{Error, Result};
use crate::study::bench::robustness::{run_stress, StressOptions, StressSpec};
use clap::Args;
use std::path::{Path, PathBuf};

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

/// Prints the warnings (results.json `warnings`) of every case run that has any, one line
/// each, `ID: warning: ...`.
fn print_flagged_warnings(out: &Path) {
    let Ok(entries) = std::fs::read_dir(out.join("runs")) else {
        return;
    };
    let mut dirs: Vec<PathBuf> = entries.flatten().map(|e| e.path()).collect();
    dirs.sort();
    for d in dirs {
        let Ok(text) = std::fs::read_to_string(d.join("results.json")) else {
            continue;
        };
        let Ok(v) = serde_json::from_str::<serde_json::Value>(&text) else {
            continue;
        };
        let id = d
            .file_name()
            .map_or(String::new(), |n| n.to_string_lossy().to_string());
        for w in v["warnings"].as_array().into_iter().flatten() {
            if let Some(m) = w["message"].as_str() {
                println!("{id}: warning: {m}");
            }
        }
    }
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
        verbose: true,
    };
    let (c, _) = run_stress(&spec, &opts)?;
    print_flagged_warnings(&a.out);
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
