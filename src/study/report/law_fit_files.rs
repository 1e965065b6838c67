//! The files of `twoball laws fit`: the fit as JSON (fit.json), the fitted law's e, δ_max and
//! contact duration against approach speed (e_of_v.csv), and the DEM decks (`crate::dem`).

use crate::analytic::law_fit::{predict, Fit, Observation};
use crate::analytic::laws::{ContactPair, NormalSpec};
use crate::analytic::Body;
use crate::atomic::write_atomic;
use crate::dem::{deck, Code, DeckScene};
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

/// The DEM files of a fit: the decks written and the codes that cannot express the law.
#[derive(Debug, Clone, Default)]
pub struct FitDecks {
    /// File names written.
    pub written: Vec<&'static str>,
    /// One line per code that cannot express the law: why.
    pub refused: Vec<String>,
    /// Reference speed of the decks (the data speed nearest the geometric mean of the data's
    /// extremes), m/s.
    pub reference_speed: f64,
}

/// The reference speed of data at `speeds` (m/s): the one nearest the geometric mean of
/// the lowest and highest.
pub fn reference_speed(speeds: &[f64]) -> f64 {
    let lo = speeds.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = speeds.iter().copied().fold(0.0, f64::max);
    let mid = (lo * hi).sqrt();
    speeds
        .iter()
        .copied()
        .min_by(|a, b| (a / mid).ln().abs().total_cmp(&(b / mid).ln().abs()))
        .unwrap_or(mid)
}

/// Writes fit.json, e_of_v.csv (41 log-spaced speeds over the data range widened to
/// 0.01-10 m/s; SI units in the header) and the DEM decks of fit `f` against the
/// observations `obs` into `dir` (created if missing), each atomically: for every code that
/// can express the law a two-ball deck sized for the data's speed range, defaulting to the
/// reference speed ([`reference_speed`]).
///
/// Errors: a folder or file that cannot be written; a prediction of the fitted law that
/// fails.
pub fn write_fit_files(
    dir: &Path,
    s: &FitSetting<'_>,
    obs: &[Observation],
    f: &Fit,
) -> Result<FitDecks> {
    std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    // Tabulated e(v_n) over the data range widened to 0.01..10 m/s, 41 log-spaced speeds.
    let lo = obs.iter().map(|o| o.speed).fold(0.01, f64::min);
    let hi = obs.iter().map(|o| o.speed).fold(10.0, f64::max);
    let mut csv = String::from("v_r [m/s],e [-],delta_max [m],contact_duration [s]\n");
    for i in 0..41 {
        let v = lo * (hi / lo).powf(i as f64 / 40.0);
        let (e, d, t) = predict(s.spec, s.pair, &f.optimum.params, s.ball, s.ball, v)?;
        csv.push_str(&format!("{v:.9e},{e:.9e},{d:.9e},{t:.9e}\n"));
    }
    write_atomic(dir.join("e_of_v.csv"), csv.as_bytes())?;
    let speeds: Vec<f64> = obs.iter().map(|o| o.speed).collect();
    let reference = reference_speed(&speeds);
    let range = (
        speeds.iter().copied().fold(f64::INFINITY, f64::min),
        speeds.iter().copied().fold(0.0, f64::max),
    );
    let scene = DeckScene::new(
        s.spec,
        &f.optimum.params,
        s.material,
        s.diameter,
        reference,
        range,
        &format!("fitted by `twoball laws fit` to {}", s.source),
    )?;
    let mut decks = FitDecks {
        reference_speed: reference,
        ..FitDecks::default()
    };
    for code in Code::ALL {
        match deck(code, s.spec.name, &f.optimum.params, &scene) {
            Ok(text) => {
                write_atomic(dir.join(code.file()), text.as_bytes())?;
                decks.written.push(code.file());
            }
            Err(e) => decks.refused.push(e.to_string()),
        }
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
        "params": f.optimum.params.iter().map(|(k, v)| (k.to_string(), num(v))).collect::<serde_json::Map<_, _>>(),
        "free": f.optimum.free,
        "sigma": f.optimum.free.iter().zip(&f.optimum.sigma).map(|(k, s)| (k.to_string(), num(*s))).collect::<serde_json::Map<_, _>>(),
        "rms_relative_residual": num(f.optimum.rms),
        "rows": rows,
        "reference_speed": num(reference),
        "speed_range": [num(range.0), num(range.1)],
        "dem_exports": decks.written,
        "dem_refusals": decks.refused,
    });
    write_atomic(
        dir.join("fit.json"),
        serde_json::to_string_pretty(&report)
            .map_err(|e| Error::Parse(e.to_string()))?
            .as_bytes(),
    )?;
    Ok(decks)
}

/// A JSON number, or null when not finite.
fn num(x: f64) -> Value {
    if x.is_finite() {
        json!(x)
    } else {
        Value::Null
    }
}
