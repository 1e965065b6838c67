//! Where a sweep folder stands: cases done, failed (with their reasons), running and missing,
//! read from the per-case files alone, so that any number of writers on any number of hosts
//! share no index file.
//!
//! A case being run has a marker `DIR/running/ID.json` (host, process id, shard), written
//! atomically before the case starts and removed once its result file is in place. A marker
//! whose writer is gone (same host, process not alive; a killed task leaves one) counts as
//! missing; a marker from another host counts as running (its process cannot be checked from
//! here).

use crate::atomic::{ensure_dir, write_atomic};
use crate::error::Result;
use crate::study::sweep::{read_case, Case, Status};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// Who is running a case.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct RunningMarker {
    /// Host name of the writer.
    pub host: String,
    /// Its process id.
    pub pid: u32,
    /// Its shard, `I/N`.
    pub shard: String,
}

/// Path of case `id`'s running marker.
pub fn marker_path(out: &Path, id: &str) -> PathBuf {
    out.join("running").join(format!("{id}.json"))
}

/// This machine's host name (`unknown` if it cannot be read).
pub fn this_host() -> String {
    std::fs::read_to_string("/proc/sys/kernel/hostname")
        .ok()
        .or_else(|| std::env::var("HOSTNAME").ok())
        .map(|h| h.trim().to_string())
        .filter(|h| !h.is_empty())
        .unwrap_or_else(|| "unknown".into())
}

/// Whether process `pid` of this host is alive (where `/proc` is absent: assumed alive).
fn alive(pid: u32) -> bool {
    if !Path::new("/proc/self").exists() {
        return true;
    }
    Path::new(&format!("/proc/{pid}")).exists()
}

/// Marks case `id` as being run by this process for shard `shard` (`I/N`).
///
/// Errors: the folder cannot be created or written ([`crate::Error::Io`]).
pub fn mark_running(out: &Path, id: &str, shard: &str) -> Result<()> {
    let m = RunningMarker {
        host: this_host(),
        pid: std::process::id(),
        shard: shard.to_string(),
    };
    let path = marker_path(out, id);
    if let Some(dir) = path.parent() {
        ensure_dir(dir)?;
    }
    let json = serde_json::to_string(&m).unwrap_or_default();
    write_atomic(path, json.as_bytes())
}

/// Removes case `id`'s running marker (absent is fine).
pub fn clear_running(out: &Path, id: &str) {
    let _ = std::fs::remove_file(marker_path(out, id));
}

/// The live writer of case `id`, if a marker names one.
fn running(out: &Path, id: &str, host: &str) -> Option<RunningMarker> {
    let text = std::fs::read_to_string(marker_path(out, id)).ok()?;
    let m: RunningMarker = serde_json::from_str(&text).ok()?;
    (m.host != host || alive(m.pid)).then_some(m)
}

/// Where the cases of a sweep stand.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SweepStatus {
    /// Cases considered.
    pub total: usize,
    /// Finished cases (simulated, or without impact).
    pub done: usize,
    /// Of those, cases without impact.
    pub no_impact: usize,
    /// Failed cases: (id, one-line reason).
    pub failed: Vec<(String, String)>,
    /// Cases being run: (id, `host pid shard`).
    pub running: Vec<(String, String)>,
    /// Cases with no result and no live writer.
    pub missing: Vec<String>,
}

impl SweepStatus {
    /// Cases without a result file (running or missing).
    pub fn unfinished(&self) -> usize {
        self.running.len() + self.missing.len()
    }
}

/// Reads where each of `cases` stands in the sweep folder `out`.
pub fn sweep_status(out: &Path, cases: &[&Case]) -> SweepStatus {
    let host = this_host();
    let mut s = SweepStatus {
        total: cases.len(),
        ..SweepStatus::default()
    };
    for c in cases {
        match read_case(out, &c.id) {
            Some(r) if r.status == Status::Failed => {
                let reason = r.message.lines().next().unwrap_or("").to_string();
                s.failed.push((c.id.clone(), reason));
            }
            Some(r) => {
                s.done += 1;
                s.no_impact += usize::from(r.status == Status::NoImpact);
            }
            None => match running(out, &c.id, &host) {
                Some(m) => s.running.push((
                    c.id.clone(),
                    format!("{} pid {} shard {}", m.host, m.pid, m.shard),
                )),
                None => s.missing.push(c.id.clone()),
            },
        }
    }
    s
}
