//! The benchmark's FE cache: the study's [`CaseCache`] in `DIR/fe/`, one file per FE point
//! named by its key (metal, diameter, speed), written as each point finishes; a file present
//! with the current FE model's name is reused, so a rerun (or `--laws-only`) costs no FE and
//! an interrupted run resumes. Failed points are cached too (delete the file to retry).

use super::matrix::{HeadOnPoint, ObliquePoint};
use crate::error::{Error, Result};
use crate::study::records::case_cache::{CaseCache, Layout};
use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

/// A point the cache files: its key (the file stem) and a one-line description.
pub trait CacheKey {
    /// File stem: the point's key, e.g. `head-on_copper-fe_D2.000e-2_v1.000e0`.
    fn key(&self) -> String;
    /// What the point is, for progress lines.
    fn describe(&self) -> String;
    /// Relative cost of its FE run (the costliest run first balances the workers).
    fn cost(&self) -> f64;
}

impl CacheKey for HeadOnPoint {
    fn key(&self) -> String {
        format!(
            "head-on_{}_D{:.4e}_v{:.6e}",
            self.metal, self.diameter, self.speed
        )
    }
    fn describe(&self) -> String {
        format!(
            "head-on {} D = {} mm v = {:.4} m/s",
            self.metal,
            1e3 * self.diameter,
            self.speed
        )
    }
    /// Steps of the section run grow as v^(-3/5): the duration as v^(-1/5), the step
    /// shrinks with the pole cells, sized from the contact radius ∝ v^(2/5).
    fn cost(&self) -> f64 {
        self.speed.powf(-0.6)
    }
}

impl CacheKey for ObliquePoint {
    fn key(&self) -> String {
        format!(
            "oblique_{}{}_D{:.4e}_vn{:.6e}_r{:.6e}",
            self.metal,
            if self.elastic { "-elastic" } else { "" },
            self.diameter,
            self.normal_speed,
            self.ratio
        )
    }
    fn describe(&self) -> String {
        format!(
            "oblique {}{} D = {} mm v_n = {} m/s v_t/v_n = {:.4} (psi = {:.3})",
            self.metal,
            if self.elastic { " (elastic)" } else { "" },
            1e3 * self.diameter,
            self.normal_speed,
            self.ratio,
            self.angle
        )
    }
    fn cost(&self) -> f64 {
        1.0 / self.normal_speed
    }
}

/// A cached FE answer: the result, or why the run failed.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Stored<T> {
    /// The run finished.
    Done(T),
    /// The run failed with this one-line message.
    Failed(String),
}

impl<T> Stored<T> {
    /// The result, if the run finished.
    pub fn done(&self) -> Option<&T> {
        match self {
            Stored::Done(t) => Some(t),
            Stored::Failed(_) => None,
        }
    }
}

/// One cache file.
#[derive(Debug, Serialize, Deserialize)]
struct Entry<R> {
    /// The point's key.
    key: String,
    /// The FE model that made it (a file of another model is not reused).
    model: String,
    /// The answer ([`Stored`], or a reference to one when written).
    result: R,
}

/// How many points were computed and how many came from the cache.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct CacheStats {
    /// Points run now.
    pub computed: usize,
    /// Points read from the cache.
    pub reused: usize,
    /// Points neither cached nor run (`--laws-only`).
    pub missing: usize,
    /// Points scaled from another point's answer (similarity), not run.
    pub scaled: usize,
}

/// The cache folder `DIR/fe` of a benchmark output folder.
#[derive(Debug, Clone)]
pub struct FeCache {
    cases: CaseCache,
    model: String,
}

impl FeCache {
    /// The cache of output folder `out` for FE model `model` (its name is stored in every
    /// file).
    pub fn new(out: &Path, model: &str) -> Self {
        FeCache {
            cases: CaseCache::new(out.join("fe")),
            model: model.to_string(),
        }
    }

    /// The file of `point`.
    pub fn path<P: CacheKey>(&self, point: &P) -> PathBuf {
        self.cases.path(&point.key())
    }

    /// The cached answer of `point`, if a readable file of this model holds it.
    pub fn load<P: CacheKey, T: DeserializeOwned>(&self, point: &P) -> Option<Stored<T>> {
        let key = point.key();
        let mine = |e: &Entry<Stored<T>>| e.key == key && e.model == self.model;
        self.cases.read(&key, mine).map(|e| e.result)
    }

    /// Writes the answer of `point` (atomically).
    ///
    /// Errors: the folder or file cannot be written.
    pub fn store<P: CacheKey, T: Serialize>(&self, point: &P, result: &Stored<T>) -> Result<()> {
        let key = point.key();
        let entry = Entry {
            key: key.clone(),
            model: self.model.clone(),
            result,
        };
        self.cases.write(&key, &entry, Layout::Compact)
    }

    /// The answers of `points`, in order: cached ones read, the others run by `run` on
    /// `jobs` threads of a rayon pool, costliest first, each stored as it finishes (unless
    /// `laws_only`, in which case they are `None`). `progress` receives one line per point run.
    ///
    /// Errors: a cache file that cannot be written, the thread pool.
    pub fn run_all<P, T, F>(
        &self,
        points: &[P],
        jobs: usize,
        laws_only: bool,
        run: F,
        progress: &(dyn Fn(&str) + Sync),
    ) -> Result<(Vec<Option<Stored<T>>>, CacheStats)>
    where
        P: CacheKey + Sync,
        T: Serialize + DeserializeOwned + Send,
        F: Fn(&P) -> Result<T> + Sync,
    {
        let mut out: Vec<Option<Stored<T>>> = points.iter().map(|p| self.load(p)).collect();
        let pending: Vec<usize> = (0..points.len()).filter(|&i| out[i].is_none()).collect();
        let mut stats = CacheStats {
            reused: points.len() - pending.len(),
            ..CacheStats::default()
        };
        if laws_only {
            stats.missing = pending.len();
            return Ok((out, stats));
        }
        let done = AtomicUsize::new(0);
        let total = pending.len();
        let work = |&i: &usize| -> Result<(usize, Stored<T>)> {
            let p = &points[i];
            let start = std::time::Instant::now();
            let r = match run(p) {
                Ok(t) => Stored::Done(t),
                Err(e) => Stored::Failed(e.to_string()),
            };
            self.store(p, &r)?;
            let k = done.fetch_add(1, Ordering::SeqCst) + 1;
            let status = match &r {
                Stored::Done(_) => "done".to_string(),
                Stored::Failed(m) => format!("FAILED: {m}"),
            };
            progress(&format!(
                "[{k}/{total}] {} {status} ({:.1} s)",
                p.describe(),
                start.elapsed().as_secs_f64()
            ));
            Ok((i, r))
        };
        let mut order = pending.clone();
        order.sort_by(|&a, &b| points[b].cost().total_cmp(&points[a].cost()));
        let results: Vec<(usize, Stored<T>)> = if jobs > 1 && total > 1 {
            // Costliest first, each worker taking the next point when it is free.
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(jobs)
                .build()
                .map_err(|e| Error::External(format!("thread pool: {e}")))?;
            let next = AtomicUsize::new(0);
            let found = Mutex::new(Vec::with_capacity(total));
            pool.scope(|s| {
                for _ in 0..jobs.min(total) {
                    s.spawn(|_| loop {
                        let k = next.fetch_add(1, Ordering::SeqCst);
                        let Some(i) = order.get(k) else { break };
                        let r = work(i);
                        let failed = r.is_err();
                        found.lock().unwrap_or_else(|e| e.into_inner()).push(r);
                        if failed {
                            next.store(order.len(), Ordering::SeqCst);
                        }
                    });
                }
            });
            found
                .into_inner()
                .unwrap_or_else(|e| e.into_inner())
                .into_iter()
                .collect::<Result<Vec<_>>>()?
        } else {
            order.iter().map(work).collect::<Result<_>>()?
        };
        stats.computed = results.len();
        for (i, r) in results {
            out[i] = Some(r);
        }
        Ok((out, stats))
    }
}
