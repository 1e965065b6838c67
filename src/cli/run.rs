//! `twoball run [SCENE] [--out DIR] [--set PATH=VALUE]... [--vtu-ascii] [--error-estimate
//! [--observed-order]] [--tolerance T [--max-refinements N]] [--compare-static]`: one scene,
//! FE beside the analytical model, optionally with its error bar from a mesh ladder and its
//! quasi-static loop.

use crate::error::{Error, Result};
use crate::scene::Scene;
use crate::study::convergence::dynamic_static;
use crate::study::convergence::ladder::{LadderPlan, DEFAULT_MAX_REFINEMENTS};
use crate::study::convergence::scene_estimate::{
    default_plan, run_scene_alone, run_scene_with_estimate,
};
use crate::study::convergence::static_ladder::impact_of_scene;
use crate::study::run::scene::{side_by_side, write_outputs};
use crate::study::run::simulate::RunOptions;
use clap::Args;
use std::collections::HashMap;
use std::ffi::OsString;
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
    /// Also run the next-coarser mesh of the ladder (pole and bulk sizes doubled) and write
    /// `error_estimate` in results.json (in 3D about 1.2 times the cost of the run).
    #[arg(long)]
    pub error_estimate: bool,
    /// With --error-estimate: also run the mesh before that, for an observed order.
    #[arg(long, requires = "error_estimate")]
    pub observed_order: bool,
    /// Refine until the error estimate of e is at most this, e.g. 0.5% or 0.005. A head-on
    /// scene of identical balls or of a ball on a rigid wall runs the section's banded,
    /// mass-scaled mesh family sized from its contact (e, δ_max and the contact duration the
    /// fine level's mean); any other scene refines its own ladder (halving pole and bulk
    /// sizes), the results the finest mesh's.
    #[arg(long, value_name = "FRACTION|PERCENT%")]
    pub tolerance: Option<String>,
    /// With --tolerance: the most refinements beyond the first fine level (the scene's own
    /// mesh, or the banded family's level 1).
    #[arg(long, default_value_t = DEFAULT_MAX_REFINEMENTS, requires = "tolerance")]
    pub max_refinements: u32,
    /// Run the scene's mesh alone: no error estimate, not even the one a head-on run on the
    /// meridian section gets by default.
    #[arg(long, conflicts_with_all = ["error_estimate", "tolerance"])]
    pub no_error_estimate: bool,
    /// Also load the scene's ball quasi-statically (`twoball static --support free`, to the
    /// kinetic energy it brings) and print both e and δ_max and where the energy went on
    /// each side (vibration after separation from a run held longer); with --out,
    /// compare_static.json. Head-on scenes of identical balls or of a ball on a rigid wall.
    #[arg(long)]
    pub compare_static: bool,
}

/// The ladder `--error-estimate`, `--observed-order` and `--tolerance` ask for, else the
/// scene's default ([`default_plan`]; None: a single run).
fn ladder_plan(a: &RunArgs, scene: &Scene) -> Result<Option<LadderPlan>> {
    if a.no_error_estimate {
        return Ok(None);
    }
    if let Some(t) = &a.tolerance {
        return Ok(Some(LadderPlan::Tolerance {
            tolerance: parse_tolerance(t)?,
            max_refinements: a.max_refinements,
        }));
    }
    Ok(match (a.error_estimate, a.observed_order) {
        (false, _) => default_plan(scene)?,
        (true, false) => Some(LadderPlan::TwoLevels),
        (true, true) => Some(LadderPlan::ThreeLevels),
    })
}

/// A relative tolerance: `0.1%` (a percentage) or `0.001` (a fraction), in (0, 1).
pub(crate) fn parse_tolerance(text: &str) -> Result<f64> {
    let t = text.trim();
    let value = match t.strip_suffix('%') {
        Some(p) => p.trim().parse::<f64>().map(|x| x / 100.0),
        None => t.parse::<f64>(),
    };
    match value {
        Ok(x) if x > 0.0 && x < 1.0 => Ok(x),
        _ => Err(Error::invalid(
            "--tolerance",
            text,
            "a fraction 0 < t < 1 or a percentage 0% < t < 100%, e.g. 0.1%",
        )),
    }
}

/// Runs `twoball run`.
pub fn run(a: RunArgs) -> Result<()> {
    let scene = super::read_scene(a.scene.as_deref(), &a.sets)?;
    let opts = RunOptions {
        history_rows: 400,
        progress: true,
        snapshot_dir: a.out.clone(),
        vtu_ascii: a.vtu_ascii,
        ..RunOptions::default()
    };
    // Everything that can be refused is read before the output folder is made.
    let plan = ladder_plan(&a, &scene)?;
    if a.compare_static {
        impact_of_scene(&scene)?;
    }
    let created = a.out.as_ref().is_some_and(|d| !d.exists());
    if let Some(dir) = &a.out {
        crate::atomic::ensure_dir(dir)?;
    } else if scene.output.vtu_snapshots > 0 {
        eprintln!("note: output.vtu_snapshots needs --out DIR; no snapshots written");
    }
    let before = a.out.as_deref().map(snapshot_files).unwrap_or_default();
    let outcome = plan.map_or_else(
        || run_scene_alone(&scene, &opts),
        |p| run_scene_with_estimate(&scene, &opts, p),
    );
    let report = match outcome {
        Ok(r) => r,
        Err(e) => {
            // A failed or interrupted run leaves no snapshot of its own, nor the folder it made.
            let removed = a
                .out
                .as_ref()
                .map_or(0, |d| remove_partial_output(d, &before, created));
            return Err(match e {
                Error::Interrupted(at) if removed > 0 => Error::Interrupted(format!(
                    "{at}; nothing written ({removed} snapshot files of this run removed)"
                )),
                Error::Interrupted(at) => Error::Interrupted(format!("{at}; nothing written")),
                e => e,
            });
        }
    };
    print!("{}", side_by_side(&report));
    if let Some(est) = &report.error_estimate {
        println!("{}", est.summary());
    }
    crate::study::records::warnings::print(&report.warnings);
    if let Some(dir) = &a.out {
        write_outputs(&report, dir)?;
        println!(
            "wrote {} and {}",
            dir.join("results.json").display(),
            dir.join("history.csv").display()
        );
    }
    if a.compare_static {
        let cmp = dynamic_static::run_compare(&report.scene, &report)?;
        print!("{}", cmp.summary());
        if let Some(dir) = &a.out {
            let json = serde_json::to_string_pretty(&cmp)
                .map_err(|e| Error::Numerical(format!("compare_static.json: {e}")))?;
            let path = dir.join("compare_static.json");
            crate::atomic::write_atomic(&path, (json + "\n").as_bytes())?;
            println!("wrote {}", path.display());
        }
    }
    Ok(())
}

/// The snapshot files (`snapshot_*.vtu`, `snapshots.pvd`) in `dir`, with their modification
/// times; empty if `dir` cannot be read.
fn snapshot_files(dir: &Path) -> HashMap<OsString, Option<SystemTime>> {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return HashMap::new();
    };
    entries
        .flatten()
        .filter(|e| {
            let name = e.file_name().to_string_lossy().to_string();
            (name.starts_with("snapshot_") && name.ends_with(".vtu")) || name == "snapshots.pvd"
        })
        .map(|e| (e.file_name(), e.metadata().and_then(|m| m.modified()).ok()))
        .collect()
}

/// Removes the snapshot files that a failed or interrupted run wrote into `dir` (those not in `before`
/// or modified since), and `dir` itself if the run `created` it and it is now empty, so that
/// no folder looks complete; returns the number of files removed.
///
/// The comparison is with the listing taken before the run, not with a clock: file-system
/// timestamps come from a coarse clock and can lag the moment the run started.
fn remove_partial_output(
    dir: &Path,
    before: &HashMap<OsString, Option<SystemTime>>,
    created: bool,
) -> usize {
    let mut removed = 0;
    for (name, modified) in snapshot_files(dir) {
        let ours = before.get(&name).is_none_or(|m| *m != modified);
        if ours && std::fs::remove_file(dir.join(&name)).is_ok() {
            removed += 1;
        }
    }
    if created {
        // Fails (and keeps the folder) if anything else is in it.
        let _ = std::fs::remove_dir(dir);
    }
    removed
}

#[cfg(test)]
mod tests {
    use super::parse_tolerance;

    #[test]
    fn tolerances_read_as_percent_or_fraction_and_bad_ones_are_named() {
        assert_eq!(parse_tolerance("0.1%").unwrap(), 0.001);
        assert_eq!(parse_tolerance("0.002").unwrap(), 0.002);
        for bad in ["0%", "100%", "-1", "abc", "1.5", "nan"] {
            let e = parse_tolerance(bad).unwrap_err().to_string();
            assert!(e.contains("--tolerance") && e.contains(bad), "{e}");
        }
    }
}
