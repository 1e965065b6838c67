//! `twoball sweep FILE --out DIR [--jobs N] [--shard I/N]`: a parameter sweep such as the
//! paper's ANSYS study, resumable and shardable; each impacting case runs the FE model
//! ([`crate::study::convergence::scene_estimate::sweep_case`]) beside the analytical one. `--slurm` writes the
//! sweep as a Slurm job array instead; `twoball sweep status DIR` tells where a sweep stands.

use crate::error::{Error, Result};
use crate::study::sweep::slurm::{self, ArrayCommand, SlurmOptions};
use crate::study::sweep::status::sweep_status;
use crate::study::sweep::{
    adopt_folder, folder_spec, run_sweep, select, shard_costs, Shard, SweepModel, SweepOptions,
    SweepSpec,
};
use clap::{Args, Subcommand};
use std::path::{Path, PathBuf};
use std::time::Duration;

/// Array tasks written by `--slurm` unless `--tasks` says otherwise (fewer for small sweeps).
const DEFAULT_TASKS: usize = 8;

/// Missing cases listed by `twoball sweep status` (the count covers the rest).
const MAX_LISTED: usize = 20;

/// Arguments of `twoball sweep`.
#[derive(Debug, Args)]
#[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
pub struct SweepArgs {
    /// `status DIR`: where a sweep folder stands.
    #[command(subcommand)]
    pub action: Option<SweepAction>,
    /// Sweep file (TOML), e.g. verification/ansys-study.toml.
    #[arg(required = true)]
    pub file: Option<PathBuf>,
    /// Output folder: one JSON per case in DIR/cases/, all cases in DIR/sweep.csv.
    #[arg(long, required = true)]
    pub out: Option<PathBuf>,
    /// Worker threads (default: all cores; with --slurm, --cpus-per-task sets them).
    #[arg(long, conflicts_with = "slurm")]
    pub jobs: Option<usize>,
    /// Run only shard I of N (1-based; shards are balanced by estimated cost).
    #[arg(long, conflicts_with = "slurm")]
    pub shard: Option<String>,
    /// Run the analytical model only, whatever the file says.
    #[arg(long)]
    pub analytic_only: bool,
    /// Run only the cases of this mesh setting (a `name` of the file's `[[mesh]]` tables).
    #[arg(long)]
    pub mesh: Option<String>,
    /// Minimum wall time per case in ms (testing aid for kill-and-resume).
    #[arg(long, default_value_t = 0, hide = true)]
    pub pace_ms: u64,
    /// Write DIR/sweep.sbatch, a Slurm job array of the sweep, instead of running it.
    #[arg(long)]
    pub slurm: bool,
    /// Array tasks (= shards) of --slurm (default: 8, or the number of cases if fewer).
    #[arg(long, requires = "slurm")]
    pub tasks: Option<usize>,
    /// Slurm partition of --slurm.
    #[arg(long, requires = "slurm")]
    pub partition: Option<String>,
    /// Wall-time limit per task of --slurm, [D-]HH:MM:SS.
    #[arg(long, requires = "slurm")]
    pub time: Option<String>,
    /// CPUs per task of --slurm (also each task's --jobs; default 1).
    #[arg(long, requires = "slurm")]
    pub cpus_per_task: Option<usize>,
    /// A further #SBATCH option for --slurm, e.g. --sbatch-arg=--mem=4G (repeatable).
    #[arg(long = "sbatch-arg", requires = "slurm", allow_hyphen_values = true)]
    pub sbatch_arg: Vec<String>,
    /// Submit the --slurm script with sbatch (else print the command).
    #[arg(long, requires = "slurm")]
    pub submit: bool,
}

/// Subcommands of `twoball sweep`.
#[derive(Debug, Subcommand)]
pub enum SweepAction {
    /// Cases done, failed (with reasons), running and missing; exit code 1 while any case
    /// has no result.
    Status(StatusArgs),
}

/// Arguments of `twoball sweep status`.
#[derive(Debug, Args)]
pub struct StatusArgs {
    /// Sweep output folder (from `twoball sweep FILE --out DIR`).
    pub dir: PathBuf,
    /// The sweep file (default: the copy the sweep keeps as DIR/sweep.toml).
    #[arg(long)]
    pub sweep: Option<PathBuf>,
    /// Only the cases of this mesh setting.
    #[arg(long)]
    pub mesh: Option<String>,
}

/// Runs `twoball sweep`.
pub fn run(a: SweepArgs) -> Result<()> {
    if let Some(SweepAction::Status(s)) = a.action {
        return status(s);
    }
    let (Some(file), Some(out)) = (a.file.clone(), a.out.clone()) else {
        return Err(Error::Parse(
            "twoball sweep needs FILE and --out DIR".into(),
        ));
    };
    let file_spec = SweepSpec::from_file(&file)?;
    let mut spec = file_spec.clone();
    if a.analytic_only {
        spec.model = SweepModel::Analytic;
    }
    let cases = spec.cases()?;
    let selected = select(&spec, &cases, a.mesh.as_deref())?;
    if a.slurm {
        let o = SlurmOptions {
            tasks: a.tasks.unwrap_or(DEFAULT_TASKS.min(selected.len().max(1))),
            partition: a.partition.clone(),
            time: a.time.clone(),
            cpus_per_task: a.cpus_per_task.unwrap_or(1),
            sbatch_args: a.sbatch_arg.clone(),
        };
        slurm::check_options(&o, selected.len())?;
        adopt_folder(&out, &file, &file_spec)?;
        let cmd = ArrayCommand {
            binary: std::env::current_exe().map_err(|e| Error::io("twoball executable", e))?,
            file: absolute(&file)?,
            out: absolute(&out)?,
            mesh: a.mesh.clone(),
            analytic_only: a.analytic_only,
            pace_ms: a.pace_ms,
        };
        return write_array(&spec, &selected, &cmd, &o, a.submit);
    }
    let shard = Shard::parse(a.shard.as_deref().unwrap_or("1/1"))?;
    let jobs = match a.jobs {
        Some(0) => return Err(Error::invalid("--jobs", 0, "jobs >= 1")),
        Some(n) => n,
        None => std::thread::available_parallelism().map_or(1, |n| n.get()),
    };
    adopt_folder(&out, &file, &file_spec)?;
    let opts = SweepOptions {
        out: out.clone(),
        jobs,
        shard,
        pace: Duration::from_millis(a.pace_ms),
        verbose: true,
        mesh: a.mesh.clone(),
    };
    let tolerance = spec.tolerance;
    let runner = move |s: &crate::scene::Scene| {
        crate::study::convergence::scene_estimate::sweep_case_to(s, tolerance)
    };
    let fe: crate::study::sweep::FeRunner<'_> = &runner;
    let s = run_sweep(&spec, &opts, Some(fe))?;
    let csv = if s.csv_written {
        format!("{} in {}", s.in_csv, out.join("sweep.csv").display())
    } else {
        format!(
            "{} of the sweep finished (sweep.csv: an unsharded run or twoball report merges them)",
            s.in_csv
        )
    };
    println!(
        "sweep {}: {} cases, shard {}/{} has {} ({} already done, {} run now{}); {} ({} failed)",
        file.display(),
        s.total,
        shard.index,
        shard.count,
        s.in_shard,
        s.skipped,
        s.ran,
        if s.scaled > 0 {
            format!(", {} of them scaled from a similar case's FE run", s.scaled)
        } else {
            String::new()
        },
        csv,
        s.failed
    );
    Ok(())
}

/// `p` as an absolute path (the job script runs on other nodes, from another folder).
fn absolute(p: &Path) -> Result<PathBuf> {
    std::path::absolute(p).map_err(|e| Error::io(p, e))
}

/// Writes the job-array script, prints each task's estimated cost, and submits or prints the
/// sbatch command.
fn write_array(
    spec: &SweepSpec,
    selected: &[&crate::study::sweep::Case],
    cmd: &ArrayCommand,
    o: &SlurmOptions,
    submit: bool,
) -> Result<()> {
    let path = slurm::write_script(cmd, o)?;
    let loads = shard_costs(spec, selected, o.tasks);
    let mean = loads.iter().map(|l| l.1).sum::<f64>() / loads.len() as f64;
    let longest = loads.iter().map(|l| l.1).fold(0.0, f64::max);
    println!(
        "wrote {}: {} cases in {} array tasks",
        path.display(),
        selected.len(),
        o.tasks
    );
    for (k, (n, cost)) in loads.iter().enumerate() {
        println!(
            "task {k} (shard {}/{}): {n} cases, estimated cost {cost:.3e} element-steps",
            k + 1,
            o.tasks
        );
    }
    println!(
        "longest task: {longest:.3e} element-steps, {:.3} x the mean {mean:.3e}",
        if mean > 0.0 { longest / mean } else { 1.0 }
    );
    if submit {
        let id = slurm::submit(&path)?;
        println!("submitted job array {id}");
    } else {
        println!("submit with: sbatch {}", path.display());
    }
    let mesh = cmd
        .mesh
        .as_ref()
        .map_or(String::new(), |m| format!(" --mesh {m}"));
    println!(
        "then: twoball sweep status {}{mesh} ; twoball report {}",
        cmd.out.display(),
        cmd.out.display()
    );
    Ok(())
}

/// Runs `twoball sweep status DIR`.
fn status(a: StatusArgs) -> Result<()> {
    let spec = match &a.sweep {
        Some(f) => SweepSpec::from_file(f)?,
        None => folder_spec(&a.dir)?,
    };
    let cases = spec.cases()?;
    let selected = select(&spec, &cases, a.mesh.as_deref())?;
    let s = sweep_status(&a.dir, &selected);
    println!(
        "sweep {}: {} cases: {} done ({} without impact), {} failed, {} running, {} missing",
        a.dir.display(),
        s.total,
        s.done,
        s.no_impact,
        s.failed.len(),
        s.running.len(),
        s.missing.len()
    );
    for (id, why) in &s.failed {
        println!("failed  {id}: {why}");
    }
    for (id, who) in &s.running {
        println!("running {id}: {who}");
    }
    for id in s.missing.iter().take(MAX_LISTED) {
        println!("missing {id}");
    }
    if s.missing.len() > MAX_LISTED {
        println!("missing ... and {} more", s.missing.len() - MAX_LISTED);
    }
    if s.unfinished() > 0 {
        return Err(Error::Incomplete(format!(
            "{} of {} cases have no result yet ({} running, {} missing): rerun the sweep or resubmit {}",
            s.unfinished(),
            s.total,
            s.running.len(),
            s.missing.len(),
            a.dir.join("sweep.sbatch").display()
        )));
    }
    Ok(())
}
