//! `twoball report DIR [--to FOLDER] [--partial] [--sweep FILE] [--notes FILE]`: the
//! verification report from a sweep folder, written beside the sweep unless `--to` says
//! where (the committed one: `--to verification`).

use crate::error::{Error, Result};
use crate::study::report::{finished_cases, same_folder, write_report, Partial};
use clap::Args;
use std::path::PathBuf;

/// Arguments of `twoball report`.
#[derive(Debug, Args)]
pub struct ReportArgs {
    /// Sweep output folder (from `twoball sweep --out DIR`).
    pub dir: PathBuf,
    /// The sweep file that produced it [default: DIR/sweep.toml, the copy the sweep keeps,
    /// else verification/ansys-study.toml].
    #[arg(long)]
    pub sweep: Option<PathBuf>,
    /// Where REPORT.md and its files (ansys/sweep.csv, ansys/fig*.svg) go [default: DIR];
    /// `--to verification` replaces the committed report.
    #[arg(long)]
    pub to: Option<PathBuf>,
    /// Write a report of a sweep that has not finished every case into --to (its title
    /// then says how many cases it covers).
    #[arg(long)]
    pub partial: bool,
    /// Markdown appended as the discussion [default: NOTES.md in the --to folder, if present,
    /// for a whole sweep].
    #[arg(long)]
    pub notes: Option<PathBuf>,
}

/// Runs `twoball report`.
pub fn run(a: ReportArgs) -> Result<()> {
    if !a.dir.is_dir() {
        return Err(Error::invalid(
            "DIR",
            a.dir.display(),
            "a sweep output folder (twoball sweep FILE --out DIR)",
        ));
    }
    let to = a.to.clone().unwrap_or_else(|| a.dir.clone());
    let kept = a.dir.join(crate::study::sweep::SPEC_COPY);
    let sweep = a.sweep.clone().unwrap_or_else(|| {
        if kept.is_file() {
            kept
        } else {
            PathBuf::from("verification/ansys-study.toml")
        }
    });
    let (finished, total) = finished_cases(&sweep, &a.dir)?;
    let notes_path = a.notes.clone().unwrap_or_else(|| to.join("NOTES.md"));
    // The default notes describe the whole sweep: never appended under a partial one's tables.
    let want_default_notes = a.notes.is_none() && finished == total;
    let notes = match std::fs::read_to_string(&notes_path) {
        Ok(t) if a.notes.is_some() || want_default_notes => Some(t),
        Ok(_) => None,
        Err(_) if a.notes.is_none() => None,
        Err(e) => return Err(Error::io(&notes_path, e)),
    };
    // Beside the sweep a partial report is what the user asked for; elsewhere it must be.
    let partial = if a.partial || same_folder(&a.dir, &to) {
        Partial::Allow
    } else {
        Partial::Refuse
    };
    let s = write_report(&sweep, &a.dir, &to, notes.as_deref(), partial)?;
    println!(
        "wrote {} ({}{} of {} cases), {} and {} figures in {}{}",
        to.join("REPORT.md").display(),
        if s.is_partial() { "partial: " } else { "" },
        s.finished,
        s.total,
        to.join("ansys").join("sweep.csv").display(),
        s.figures.len(),
        to.join("ansys").display(),
        if s.removed.is_empty() {
            String::new()
        } else {
            format!("; removed stale {}", s.removed.join(", "))
        }
    );
    Ok(())
}
