//! The files of `twoball laws fit`: the fit as JSON (fit.json), the fitted law's e, δ_max and
//! contact duration against approach speed (e_of_v.csv), and the DEM input snippets.

use crate::analytic::law_fit::{dem_exports, predict, Fit, Observation};
use crate::analytic::laws::{ContactPair, NormalSpec};
use crate::analytic::Body;
use crate::atomic::write_atomic;
use crate::error::{Error, Result};
use crate::material::Material;
use serde_json::{json, Value};
use std::path::Path;

/// What a fit was made for: the law, the ball pair and where the data came from.
#[derive(Clone, Copy)]
pub struct FitSetting<'a> {
    /// The fitted normal law.
    pub spec: &'a NormalSpec,
    /// The contact pair of two equal balls.
    pub pair: &'a ContactPair,
    /// One of the two equal balls.
    pub ball: &'a Body,
    /// Their material.
    pub material: &'a Material,
    /// The material's preset name.
    pub material_name: &'a str,
    /// Ball diameter, m.
    pub diameter: f64,
    /// The data file, as named to the user.
    pub source: &'a str,
}

/// Writes fit.json, e_of_v.csv (41 log-spaced speeds over the data range widened to
/// 0.01-10 m/s; SI units in the header) and the DEM snippets of fit `f` against the
/// observations `obs` into `dir` (created if missing), each atomically; returns the DEM
/// file names.
///
/// Errors: a folder or file that cannot be written; a prediction of the fitted law that
/// fails.
pub fn write_fit_files(
    dir: &Path,
    s: &FitSetting<'_>,
    obs: &[Observation],
    f: &Fit,
) -> Result<Vec<&'static str>> {
    std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    // Tabulated e(v_n) over the data range widened to 0.01..10 m/s, 41 log-spaced speeds.
    let lo = obs.iter().map(|o| o.speed).fold(0.01, f64::min);
    let hi = obs.iter().map(|o| o.speed).fold(10.0, f64::max);
    let mut csv = String::from("v_r [m/s],e [-],delta_max [m],contact_duration [s]\n");
    for i in 0..41 {
        let v = lo * (hi / lo).powf(i as f64 / 40.0);
        let (e, d, t) = predict(s.spec, s.pair, &f.params, s.ball, s.ball, v)?;
        csv.push_str(&format!("{v:.9e},{e:.9e},{d:.9e},{t:.9e}\n"));
    }
    write_atomic(dir.join("e_of_v.csv"), csv.as_bytes())?;
    let exports = dem_exports(
        s.spec.name,
        &f.params,
        s.pair,
        s.material.nu,
        s.material.rho,
        s.material.mu,
    );
    for (name, text) in &exports {
        write_atomic(dir.join(name), text.as_bytes())?;
    }
    let rows: Vec<Value> = f
        .rows
        .iter()
        .map(|(o, e, d)| {
            json!({"v_r": num(o.speed), "e_data": num(o.e), "e_fit": num(*e),
                   "e_rel_error": num((e - o.e) / o.e),
                   "delta_max_data": num(o.delta_max), "delta_max_fit": num(*d),
                   "delta_max_rel_error": num((d - o.delta_max) / o.delta_max)})
        })
        .collect();
    let report = json!({
        "law": s.spec.name,
        "source": s.source,
        "material": s.material_name,
        "diameter": s.diameter,
        "params": f.params.iter().map(|(k, v)| (k.to_string(), num(v))).collect::<serde_json::Map<_, _>>(),
        "free": f.free,
        "sigma": f.free.iter().zip(&f.sigma).map(|(k, s)| (k.to_string(), num(*s))).collect::<serde_json::Map<_, _>>(),
        "rms_relative_residual": num(f.rms),
        "rows": rows,
        "dem_exports": exports.iter().map(|(n, _)| *n).collect::<Vec<_>>(),
    });
    write_atomic(
        dir.join("fit.json"),
        serde_json::to_string_pretty(&report)
            .map_err(|e| Error::Parse(e.to_string()))?
            .as_bytes(),
    )?;
    Ok(exports.iter().map(|(n, _)| *n).collect())
}

/// A JSON number, or null when not finite.
fn num(x: f64) -> Value {
    if x.is_finite() {
        json!(x)
    } else {
        Value::Null
    }
}
