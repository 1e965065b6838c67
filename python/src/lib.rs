//! The native half of the `twoball` Python package: thin calls into the twoball library.
//!
//! Results cross as JSON text (the CLI's own objects, parsed by the Python half) and history
//! columns as lists of floats (made numpy arrays by the Python half). Long jobs (`run`,
//! `sweep`) run on a worker thread with the GIL released; the calling thread polls every
//! [`POLL`] for Ctrl-C (`KeyboardInterrupt`), which cancels the job, and hands the latest
//! progress to the optional callback.

use pyo3::exceptions::{PyKeyboardInterrupt, PyOSError, PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};
use twoball::scene::{Override, Scene, DEFAULT_SCENE};
use twoball::study::common::interrupt::{self, CancelToken};
use twoball::study::common::progress::{self, Hook};
use twoball::study::convergence::ladder::LadderPlan;
use twoball::study::convergence::scene_estimate::{run_scene_default, run_scene_with_estimate};
use twoball::study::run::scene::write_outputs;
use twoball::study::run::simulate::{RunOptions, HISTORY_HEADER};
use twoball::Error;

/// How often the waiting Python thread checks for Ctrl-C and progress.
const POLL: Duration = Duration::from_millis(20);

/// History rows of a run (as `twoball run`).
const HISTORY_ROWS: usize = 400;

/// The Python exception of a library error, with the CLI's one-line message.
fn py_err(e: Error) -> PyErr {
    let msg = e.to_string();
    match e {
        Error::Invalid { .. } | Error::Parse(_) => PyValueError::new_err(msg),
        Error::Io { .. } => PyOSError::new_err(msg),
        Error::Interrupted(_) => PyKeyboardInterrupt::new_err(msg),
        _ => PyRuntimeError::new_err(msg),
    }
}

/// Runs `job` on a worker thread (in its own thread pool, as the CLI runs its commands) with
/// the GIL released; polls for Ctrl-C, which cancels the job and raises `KeyboardInterrupt`
/// once it has stopped, and calls `callback(done, total)` with the latest progress.
fn wait_job<T, F>(py: Python<'_>, callback: Option<&Bound<'_, PyAny>>, job: F) -> PyResult<T>
where
    T: Send + 'static,
    F: FnOnce() -> twoball::Result<T> + Send + 'static,
{
    let token = CancelToken::new();
    let latest: Arc<Mutex<Option<(f64, f64)>>> = Arc::new(Mutex::new(None));
    let sink = latest.clone();
    let hook: Hook = Arc::new(move |done, total| {
        if let Ok(mut l) = sink.lock() {
            *l = Some((done, total));
        }
    });
    let worker_token = token.clone();
    let handle = std::thread::spawn(move || {
        let work = move || {
            interrupt::within(Some(&worker_token), || {
                progress::reporting(Some(&hook), job)
            })
        };
        match rayon::ThreadPoolBuilder::new().build() {
            Ok(pool) => pool.install(work),
            Err(_) => work(),
        }
    });
    let stop = |py: Python<'_>, handle: std::thread::JoinHandle<twoball::Result<T>>| {
        token.cancel();
        py.allow_threads(|| {
            let _ = handle.join();
        });
    };
    loop {
        let finished = py.allow_threads(|| {
            let t0 = Instant::now();
            while !handle.is_finished() && t0.elapsed() < POLL {
                std::thread::sleep(Duration::from_millis(2));
            }
            handle.is_finished()
        });
        let report = latest.lock().ok().and_then(|mut l| l.take());
        if let (Some(cb), Some((done, total))) = (callback, report) {
            if let Err(e) = cb.call1((done, total)) {
                stop(py, handle);
                return Err(e);
            }
        }
        if finished {
            return match handle.join() {
                Ok(r) => r.map_err(py_err),
                Err(_) => Err(PyRuntimeError::new_err("twoball worker thread panicked")),
            };
        }
        if let Err(e) = py.check_signals() {
            stop(py, handle);
            return Err(e);
        }
    }
}

/// The JSON text of `twoball ARGS --json` (`args` without the program name).
#[pyfunction]
fn cli_json(py: Python<'_>, args: Vec<String>) -> PyResult<String> {
    py.allow_threads(move || {
        twoball::cli::json_from(std::iter::once("twoball".to_string()).chain(args))
            .map(|v| v.to_string())
    })
    .map_err(py_err)
}

/// Converts JSON scene text (a dict on the Python side) to TOML scene text.
fn scene_toml_of_json(json: &str) -> twoball::Result<String> {
    let value: toml::Value = serde_json::from_str(json).map_err(|e| {
        Error::Parse(format!(
            "scene dict: {e} (values: numbers, strings, booleans, lists, dicts; no None)"
        ))
    })?;
    toml::to_string(&value).map_err(|e| Error::Parse(format!("scene dict: {e}")))
}

/// Result of [`run`]: results.json's text, history.csv's column names and the columns.
type RunOutput = (String, Vec<String>, Vec<Vec<f64>>);

/// One scene, FE beside the analytical model, as `twoball run`: `scene_path` a TOML file,
/// else `scene_json` a scene as JSON text, else the default scene; `sets` the `--set`
/// overrides; `out` a folder for results.json and history.csv.
#[pyfunction]
#[pyo3(signature = (scene_path, scene_json, sets, out, vtu_ascii, progress, tolerance, max_refinements))]
#[allow(clippy::too_many_arguments)]
fn run(
    py: Python<'_>,
    scene_path: Option<PathBuf>,
    scene_json: Option<String>,
    sets: Vec<String>,
    out: Option<PathBuf>,
    vtu_ascii: bool,
    progress: Option<&Bound<'_, PyAny>>,
    tolerance: Option<f64>,
    max_refinements: u32,
) -> PyResult<RunOutput> {
    let plan = match tolerance {
        Some(t) if t > 0.0 && t < 1.0 => Some(LadderPlan::Tolerance {
            tolerance: t,
            max_refinements,
        }),
        Some(t) => {
            let range = "a fraction 0 < tolerance < 1, e.g. 0.005";
            return Err(py_err(Error::invalid("tolerance", t, range)));
        }
        None => None,
    };
    let sets = sets
        .iter()
        .map(|s| Override::parse(s))
        .collect::<twoball::Result<Vec<_>>>()
        .map_err(py_err)?;
    let scene = match (&scene_path, &scene_json) {
        (Some(p), _) => Scene::from_file(p, &sets),
        (None, Some(j)) => {
            scene_toml_of_json(j).and_then(|t| Scene::from_toml(&t, Path::new("."), &sets))
        }
        (None, None) => Scene::from_toml(DEFAULT_SCENE, Path::new("."), &sets),
    }
    .map_err(py_err)?;
    if let Some(dir) = &out {
        twoball::atomic::ensure_dir(dir).map_err(py_err)?;
    }
    let opts = RunOptions {
        history_rows: HISTORY_ROWS,
        snapshot_dir: out.clone(),
        vtu_ascii,
        ..RunOptions::default()
    };
    wait_job(py, progress, move || {
        let report = match plan {
            Some(plan) => run_scene_with_estimate(&scene, &opts, plan)?,
            None => run_scene_default(&scene, &opts)?,
        };
        if let Some(dir) = &out {
            write_outputs(&report, dir)?;
        }
        let json = serde_json::to_string_pretty(&report)
            .map_err(|e| Error::Parse(format!("results.json: {e}")))?;
        let names: Vec<String> = HISTORY_HEADER.split(',').map(str::to_string).collect();
        let mut columns = vec![Vec::new(); names.len()];
        if let Some(sim) = &report.fe {
            for r in &sim.history {
                let row = r.values();
                for (c, x) in columns.iter_mut().zip(row) {
                    c.push(x);
                }
            }
        }
        Ok((json, names, columns))
    })
}

/// A sweep as `twoball sweep FILE --out DIR --jobs N` (resumable: finished cases are kept);
/// returns the summary as JSON text.
#[pyfunction]
#[pyo3(signature = (path, out, jobs, progress))]
fn sweep(
    py: Python<'_>,
    path: PathBuf,
    out: PathBuf,
    jobs: Option<usize>,
    progress: Option<&Bound<'_, PyAny>>,
) -> PyResult<String> {
    use twoball::study::sweep::{adopt_folder, run_sweep, Shard, SweepOptions, SweepSpec};
    let jobs = match jobs {
        Some(0) => return Err(py_err(Error::invalid("--jobs", 0, "jobs >= 1"))),
        Some(n) => n,
        None => std::thread::available_parallelism().map_or(1, |n| n.get()),
    };
    let spec = SweepSpec::from_file(&path).map_err(py_err)?;
    adopt_folder(&out, &path, &spec).map_err(py_err)?;
    let opts = SweepOptions {
        out: out.clone(),
        jobs,
        shard: Shard::parse("1/1").map_err(py_err)?,
        pace: Duration::ZERO,
        verbose: false,
        mesh: None,
    };
    wait_job(py, progress, move || {
        let tolerance = spec.tolerance;
        let runner = move |s: &twoball::scene::Scene| {
            twoball::study::convergence::scene_estimate::sweep_case_to(s, tolerance)
        };
        let fe: twoball::study::sweep::FeRunner<'_> = &runner;
        let s = run_sweep(&spec, &opts, Some(fe))?;
        Ok(serde_json::json!({
            "total": s.total,
            "skipped": s.skipped,
            "ran": s.ran,
            "scaled": s.scaled,
            "failed": s.failed,
            "in_csv": s.in_csv,
            "csv": opts.out.join("sweep.csv"),
        })
        .to_string())
    })
}

/// The native module `twoball._native`.
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(cli_json, m)?)?;
    m.add_function(wrap_pyfunction!(run, m)?)?;
    m.add_function(wrap_pyfunction!(sweep, m)?)?;
    Ok(())
}
