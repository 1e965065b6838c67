//! A normal law fitted to a quasi-static FE loop (`twoball laws fit --against-static DIR`):
//! the folder `twoball static --out DIR` writes (loop.csv, results.json) read back, and the
//! law's free parameters fitted so that its loading and unloading forces at the loop's
//! approaches meet the FE's: least squares of the force error over the FE peak force, the
//! measure `twoball static --laws` reports ([`super::loops`]). The law unloads from its own
//! turn at the loop's largest approach, as there.

use super::loops::{on_loop, phases, LawOnLoop, LoopPair};
use crate::analytic::law_fit::{least_squares, LeastSquares};
use crate::analytic::laws::{NormalSpec, Params};
use crate::atomic::{ensure_dir, write_atomic};
use crate::error::{Error, Result};
use crate::study::run::quasi_static::{LoopPoint, LoopSummary, StaticLoop};
use serde::Deserialize;
use std::fmt::Write as _;
use std::path::Path;

/// A static loop read back from its folder.
#[derive(Debug, Clone, PartialEq)]
pub struct LoopFolder {
    /// The finest level's loop.
    pub finest: StaticLoop,
    /// The pair it stands for.
    pub pair: LoopPair,
}

/// The parts of results.json the fit reads.
#[derive(Deserialize)]
struct Results {
    contact_pair: Option<LoopPair>,
    levels: Vec<Level>,
}

#[derive(Deserialize)]
struct Level {
    quads: usize,
    newton_iterations: usize,
    /// Absent from folders written before the count was recorded.
    #[serde(default)]
    factorisations: u64,
    summary: LoopSummary,
}

/// Reads `dir/loop.csv` and `dir/results.json` as `twoball static --out dir` wrote them.
///
/// Errors: a missing or unreadable file, a results.json without `contact_pair` (written
/// before the pair was recorded: run `twoball static --out DIR` again), a loop.csv row that
/// is not `phase,approach,force,...` with finite numbers, a loop without loading or
/// unloading points.
pub fn read_loop_folder(dir: &Path) -> Result<LoopFolder> {
    let json_path = dir.join("results.json");
    let text = std::fs::read_to_string(&json_path).map_err(|e| Error::io(&json_path, e))?;
    let results: Results = serde_json::from_str(&text)
        .map_err(|e| Error::Parse(format!("{}: {e}", json_path.display())))?;
    let pair = results.contact_pair.ok_or_else(|| {
        Error::invalid(
            format!("{}: contact_pair", json_path.display()),
            "absent",
            "a folder written by this version of `twoball static --out DIR` (run it again)",
        )
    })?;
    let last = results.levels.last().ok_or_else(|| {
        Error::invalid(
            format!("{}: levels", json_path.display()),
            0,
            "at least one level",
        )
    })?;
    let csv_path = dir.join("loop.csv");
    let text = std::fs::read_to_string(&csv_path).map_err(|e| Error::io(&csv_path, e))?;
    let (mut loading, mut unloading) = (Vec::new(), Vec::new());
    for (k, line) in text.lines().enumerate().skip(1) {
        let cells: Vec<&str> = line.split(',').collect();
        let bad = || {
            Error::Parse(format!(
                "{} line {}: '{line}' is not phase,approach_m,force_N,contact_radius_m,plastic_work_J,stress_work_J",
                csv_path.display(),
                k + 1
            ))
        };
        let num = |i: usize| -> Result<f64> {
            let x: f64 = cells
                .get(i)
                .and_then(|c| c.trim().parse().ok())
                .ok_or_else(bad)?;
            x.is_finite().then_some(x).ok_or_else(bad)
        };
        let p = LoopPoint {
            approach: num(1)?,
            force: num(2)?,
            contact_radius: num(3)?,
            plastic_work: num(4)?,
            stress_work: num(5)?,
        };
        match cells[0] {
            "loading" => loading.push(p),
            "unloading" => unloading.push(p),
            _ => return Err(bad()),
        }
    }
    if loading.is_empty() || unloading.is_empty() {
        return Err(Error::invalid(
            csv_path.display().to_string(),
            format!(
                "{} loading, {} unloading rows",
                loading.len(),
                unloading.len()
            ),
            "a loop with loading and unloading points",
        ));
    }
    Ok(LoopFolder {
        finest: StaticLoop {
            quads: last.quads,
            iterations: last.newton_iterations,
            factorisations: last.factorisations,
            peak_residuals: Vec::new(),
            loading,
            unloading,
            summary: last.summary,
        },
        pair,
    })
}

/// A law fitted to a loop: the optimum, and the law on the loop before (the parameters'
/// defaults and the fixed ones) and after.
#[derive(Debug, Clone, PartialEq)]
pub struct LoopFit {
    /// The optimum (its `rms`: the force error over the FE peak force, -).
    pub fit: LeastSquares,
    /// The law with its default (and fixed) parameters on the loop.
    pub before: LawOnLoop,
    /// The fitted law on the loop.
    pub after: LawOnLoop,
}

/// Fits the `free` parameters of `spec` (the others at `fixed` or their defaults) to the
/// loop of `folder`.
///
/// Errors: those of [`least_squares`] and of the pair.
pub fn fit_law_on_loop(
    folder: &LoopFolder,
    spec: &NormalSpec,
    free: &[String],
    fixed: &[(String, f64)],
) -> Result<LoopFit> {
    let (pair, share) = folder.pair.contact_pair()?;
    let speed = folder.pair.approach_speed_m_per_s;
    let l = &folder.finest;
    let fe: Vec<f64> = l
        .loading
        .iter()
        .chain(&l.unloading)
        .map(|p| p.force)
        .collect();
    let peak = l.summary.force_at_max;
    let law_on = |p: &Params| on_loop(spec.name, (spec.build)(&pair, p).as_ref(), l, speed, share);
    let residuals = |p: &Params| -> Result<Vec<f64>> {
        let forces = law_on(p).forces;
        Ok(forces
            .iter()
            .zip(&fe)
            .map(|(f, g)| (f - g) / peak)
            .collect())
    };
    let start = Params::resolve(spec.name, spec.params, fixed, &pair)?;
    let fit = least_squares(spec, &pair, free, fixed, residuals)?;
    Ok(LoopFit {
        before: law_on(&start),
        after: law_on(&fit.params),
        fit,
    })
}

/// Writes `out/fit.json` (the parameters, their uncertainties, the force errors before and
/// after) and `out/loop_fit.csv` (each loop point: the FE force, the law's with its default
/// and with its fitted parameters, N).
///
/// Errors: the folder or a file cannot be written.
pub fn write_loop_fit(
    out: &Path,
    source: &Path,
    spec: &NormalSpec,
    f: &LoopFit,
    l: &StaticLoop,
) -> Result<()> {
    ensure_dir(out)?;
    let params: serde_json::Map<String, serde_json::Value> = f
        .fit
        .params
        .iter()
        .map(|(k, v)| (k.to_string(), serde_json::json!(v)))
        .collect();
    let on = |x: &LawOnLoop| {
        serde_json::json!({
            "loading_rms": x.loading_rms,
            "unloading_rms": x.unloading_rms,
            "peak_ratio": x.peak_ratio,
            "residual_approach_m": x.residual_approach,
        })
    };
    let json = serde_json::json!({
        "units": "parameters SI (see `twoball laws`); force errors: RMS of (F_law - F_FE) over the FE peak force",
        "law": spec.name,
        "against_static": source.display().to_string(),
        "params": params,
        "free": f.fit.free,
        "sigma": f.fit.sigma.iter().map(|s| s.is_finite().then_some(*s)).collect::<Vec<_>>(),
        "force_rms": f.fit.rms,
        "default_params": on(&f.before),
        "fitted_params": on(&f.after),
    });
    let text = serde_json::to_string_pretty(&json)
        .map_err(|e| Error::Numerical(format!("fit.json: {e}")))?;
    write_atomic(out.join("fit.json"), (text + "\n").as_bytes())?;
    let mut csv = String::from("phase,approach_m,fe_N,default_N,fitted_N\n");
    for (k, (phase, p)) in phases(l).enumerate() {
        let _ = writeln!(
            csv,
            "{phase},{:.9e},{:.9e},{:.9e},{:.9e}",
            p.approach, p.force, f.before.forces[k], f.after.forces[k]
        );
    }
    write_atomic(out.join("loop_fit.csv"), csv.as_bytes())
}
