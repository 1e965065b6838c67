//! A sweep as a Slurm job array: `DIR/sweep.sbatch`, one array task per shard, each running
//! `twoball sweep FILE --out DIR --shard $((SLURM_ARRAY_TASK_ID+1))/N` on a filesystem every
//! node sees. Resubmitting the same script reruns only what is missing: finished cases are
//! skipped by every task (see [`crate::study::sweep`]).

use crate::atomic::{ensure_dir, write_atomic};
use crate::error::{Error, Result};
use std::path::{Path, PathBuf};
use std::process::Command;

/// Largest job array written (Slurm's default `MaxArraySize` is 1001).
pub const MAX_TASKS: usize = 1000;

/// Scheduler settings of the job array.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SlurmOptions {
    /// Array tasks = shards (1..=[`MAX_TASKS`]).
    pub tasks: usize,
    /// Partition (`#SBATCH --partition`), or the cluster's default.
    pub partition: Option<String>,
    /// Wall-time limit per task, `[D-]HH:MM:SS`, or the partition's default.
    pub time: Option<String>,
    /// CPUs per task, also the sweep's `--jobs` (≥ 1).
    pub cpus_per_task: usize,
    /// Further `#SBATCH` arguments, each one `--key=value` word.
    pub sbatch_args: Vec<String>,
}

/// What each array task runs.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ArrayCommand {
    /// The `twoball` executable (absolute path).
    pub binary: PathBuf,
    /// The sweep file (absolute path).
    pub file: PathBuf,
    /// The sweep folder (absolute path).
    pub out: PathBuf,
    /// Only this mesh setting, if given.
    pub mesh: Option<String>,
    /// Analytical model only.
    pub analytic_only: bool,
    /// Minimum wall time per case, ms (testing aid; 0: none).
    pub pace_ms: u64,
}

/// Checks a `[D-]HH:MM:SS` wall time (minutes and seconds below 60).
///
/// Errors: anything else, as [`Error::Invalid`] naming `--time`.
pub fn check_time(s: &str) -> Result<()> {
    let bad = || Error::invalid("--time", s, "[D-]HH:MM:SS, e.g. 02:00:00 or 1-12:00:00");
    let (days, hms) = match s.split_once('-') {
        Some((d, rest)) => (Some(d), rest),
        None => (None, s),
    };
    let digits = |x: &str| !x.is_empty() && x.len() <= 4 && x.bytes().all(|b| b.is_ascii_digit());
    if days.is_some_and(|d| !digits(d)) {
        return Err(bad());
    }
    let parts: Vec<&str> = hms.split(':').collect();
    let [h, m, sec] = parts.as_slice() else {
        return Err(bad());
    };
    if !(digits(h) && digits(m) && digits(sec)) {
        return Err(bad());
    }
    let below_60 = |x: &str| x.len() == 2 && x.parse::<u32>().is_ok_and(|v| v < 60);
    if !(below_60(m) && below_60(sec)) {
        return Err(bad());
    }
    Ok(())
}

/// Checks the options: task count, a partition name of one word, `--key[=value]` sbatch words.
///
/// Errors: [`Error::Invalid`] naming the flag, its value and what is allowed.
pub fn check_options(o: &SlurmOptions, cases: usize) -> Result<()> {
    let most = cases.clamp(1, MAX_TASKS);
    if o.tasks == 0 || o.tasks > most {
        return Err(Error::invalid(
            "--tasks",
            o.tasks,
            format!("1 <= tasks <= {most} (the sweep's cases, at most {MAX_TASKS})"),
        ));
    }
    if o.cpus_per_task == 0 || o.cpus_per_task > 1024 {
        return Err(Error::invalid(
            "--cpus-per-task",
            o.cpus_per_task,
            "1 <= cpus <= 1024",
        ));
    }
    if let Some(p) = &o.partition {
        let ok = !p.is_empty()
            && p.chars()
                .all(|c| c.is_ascii_alphanumeric() || "-_.,".contains(c));
        if !ok {
            return Err(Error::invalid(
                "--partition",
                p,
                "a partition name (letters, digits, '-', '_', '.', ',')",
            ));
        }
    }
    if let Some(t) = &o.time {
        check_time(t)?;
    }
    for a in &o.sbatch_args {
        if !a.starts_with("--") || a.chars().any(|c| c.is_whitespace() || c.is_control()) {
            return Err(Error::invalid(
                "--sbatch-arg",
                a,
                "one sbatch option word such as --mem=4G or --account=abc (no spaces)",
            ));
        }
    }
    Ok(())
}

/// `s` quoted for a POSIX shell.
fn quote(s: &str) -> String {
    format!("'{}'", s.replace('\'', r"'\''"))
}

fn path_word(flag: &str, p: &Path) -> Result<String> {
    let s = p.to_str().ok_or_else(|| {
        Error::invalid(
            flag,
            p.display(),
            "a path in UTF-8 (it goes into a job script)",
        )
    })?;
    if s.chars().any(|c| c.is_whitespace() || c.is_control()) {
        return Err(Error::invalid(
            flag,
            s,
            "a path without spaces (Slurm reads #SBATCH lines word by word)",
        ));
    }
    Ok(s.to_string())
}

/// The job-array script.
///
/// Errors: paths that are not UTF-8 or hold whitespace ([`Error::Invalid`]).
pub fn script(cmd: &ArrayCommand, o: &SlurmOptions) -> Result<String> {
    let out = path_word("--out", &cmd.out)?;
    let file = path_word("FILE", &cmd.file)?;
    let binary = path_word("twoball executable", &cmd.binary)?;
    let mut s = String::from("#!/bin/bash\n");
    s.push_str("# A twoball sweep as a Slurm job array: task k runs shard k+1 of the sweep.\n");
    s.push_str(
        "# Resubmit this script to run what is missing; `twoball sweep status DIR` tells.\n",
    );
    s.push_str("#SBATCH --job-name=twoball-sweep\n");
    s.push_str(&format!("#SBATCH --array=0-{}\n", o.tasks - 1));
    s.push_str("#SBATCH --ntasks=1\n");
    s.push_str(&format!("#SBATCH --cpus-per-task={}\n", o.cpus_per_task));
    s.push_str(&format!("#SBATCH --output={out}/slurm/%A_%a.out\n"));
    if let Some(p) = &o.partition {
        s.push_str(&format!("#SBATCH --partition={p}\n"));
    }
    if let Some(t) = &o.time {
        s.push_str(&format!("#SBATCH --time={t}\n"));
    }
    for a in &o.sbatch_args {
        s.push_str(&format!("#SBATCH {a}\n"));
    }
    s.push_str("set -eu\n");
    let mut line = format!(
        "exec {} sweep {} --out {} --shard \"$((SLURM_ARRAY_TASK_ID + 1))/{}\" --jobs {}",
        quote(&binary),
        quote(&file),
        quote(&out),
        o.tasks,
        o.cpus_per_task
    );
    if let Some(m) = &cmd.mesh {
        line.push_str(&format!(" --mesh {}", quote(m)));
    }
    if cmd.analytic_only {
        line.push_str(" --analytic-only");
    }
    if cmd.pace_ms > 0 {
        line.push_str(&format!(" --pace-ms {}", cmd.pace_ms));
    }
    s.push_str(&line);
    s.push('\n');
    Ok(s)
}

/// Writes `DIR/sweep.sbatch` (atomically) and creates `DIR/slurm/` for the tasks' logs;
/// returns the script's path.
///
/// Errors: as [`script`]; the folder cannot be written ([`Error::Io`]).
pub fn write_script(cmd: &ArrayCommand, o: &SlurmOptions) -> Result<PathBuf> {
    let text = script(cmd, o)?;
    ensure_dir(&cmd.out.join("slurm"))?;
    let path = cmd.out.join("sweep.sbatch");
    write_atomic(&path, text.as_bytes())?;
    Ok(path)
}

/// Submits `script` with `sbatch --parsable`; returns the job id.
///
/// Errors: sbatch missing or refusing the job ([`Error::External`], with sbatch's message).
pub fn submit(script: &Path) -> Result<String> {
    let o = Command::new("sbatch")
        .arg("--parsable")
        .arg(script)
        .output()
        .map_err(|e| Error::External(format!("sbatch: {e} (is Slurm installed here?)")))?;
    let text = String::from_utf8_lossy(&o.stdout);
    let id = text.trim().split(';').next().unwrap_or("").to_string();
    if !o.status.success() || id.is_empty() {
        let err = String::from_utf8_lossy(&o.stderr);
        return Err(Error::External(format!(
            "sbatch {} failed: {}",
            script.display(),
            err.trim().replace('\n', "; ")
        )));
    }
    Ok(id)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn opts() -> SlurmOptions {
        SlurmOptions {
            tasks: 8,
            partition: Some("short".into()),
            time: Some("01:30:00".into()),
            cpus_per_task: 2,
            sbatch_args: vec!["--mem=4G".into()],
        }
    }

    #[test]
    fn script_runs_one_shard_per_array_task() {
        let cmd = ArrayCommand {
            binary: "/opt/bin/twoball".into(),
            file: "/data/it's.toml".into(),
            out: "/data/out".into(),
            mesh: Some("graded".into()),
            analytic_only: false,
            pace_ms: 0,
        };
        let s = script(&cmd, &opts()).unwrap();
        for want in [
            "#SBATCH --array=0-7\n",
            "#SBATCH --cpus-per-task=2\n",
            "#SBATCH --partition=short\n",
            "#SBATCH --time=01:30:00\n",
            "#SBATCH --mem=4G\n",
            "#SBATCH --output=/data/out/slurm/%A_%a.out\n",
            "--shard \"$((SLURM_ARRAY_TASK_ID + 1))/8\" --jobs 2 --mesh 'graded'",
            r"'/data/it'\''s.toml'",
        ] {
            assert!(s.contains(want), "{want} missing from\n{s}");
        }
    }

    #[test]
    fn bad_options_name_the_flag() {
        for (o, flag) in [
            (SlurmOptions { tasks: 0, ..opts() }, "--tasks"),
            (
                SlurmOptions {
                    tasks: 73,
                    ..opts()
                },
                "--tasks",
            ),
            (
                SlurmOptions {
                    cpus_per_task: 0,
                    ..opts()
                },
                "--cpus-per-task",
            ),
            (
                SlurmOptions {
                    partition: Some("a b".into()),
                    ..opts()
                },
                "--partition",
            ),
            (
                SlurmOptions {
                    time: Some("1:5".into()),
                    ..opts()
                },
                "--time",
            ),
            (
                SlurmOptions {
                    time: Some("01:60:00".into()),
                    ..opts()
                },
                "--time",
            ),
            (
                SlurmOptions {
                    sbatch_args: vec!["--mem 4G".into()],
                    ..opts()
                },
                "--sbatch-arg",
            ),
        ] {
            let e = check_options(&o, 72).unwrap_err().to_string();
            assert!(e.contains(flag) && !e.contains('\n'), "{flag}: {e}");
        }
        check_options(&opts(), 72).unwrap();
        check_time("2-00:00:00").unwrap();
        check_time("100:00:00").unwrap();
    }
}
