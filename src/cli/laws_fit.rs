//! `twoball laws fit`: fit a normal law's free parameters to head-on e and δ_max data and
//! write what a DEM user needs (fit.json, e_of_v.csv, DEM input snippets).

use super::laws::parse_params;
use crate::analytic::law_fit::{dem_exports, fit, predict, read_observations};
use crate::analytic::laws::{ContactPair, Registry};
use crate::analytic::Body;
use crate::atomic::write_atomic;
use crate::error::{Error, Result};
use crate::material::{Material, PRESET_NAMES};
use clap::Args;
use serde_json::{json, Value};
use std::path::PathBuf;

/// Arguments of `twoball laws fit`.
#[derive(Debug, Args)]
pub struct LawFitArgs {
    /// Normal law to fit (see `twoball laws`).
    #[arg(long)]
    pub law: String,
    /// Data: a CSV with columns `v_r [m/s]`, `e [-]`, `delta_max [m]`, a `twoball sweep`
    /// CSV (head-on rows of --diameter and --mesh), or a directory holding `fe.csv`.
    #[arg(long, value_name = "CSV_OR_DIR")]
    pub against: PathBuf,
    /// Free parameter (repeatable) [default: every parameter of the law but `tension` and
    /// `R_star` (only E* √R* is identifiable from head-on data)].
    #[arg(long = "free", value_name = "KEY")]
    pub free: Vec<String>,
    /// Fix a parameter, KEY=VALUE in SI units; repeatable.
    #[arg(long = "param", value_name = "KEY=VALUE")]
    pub param: Vec<String>,
    /// Material preset of both balls.
    #[arg(long, default_value = "copper-fe")]
    pub material: String,
    /// Diameter of both balls, m (also selects the sweep rows).
    #[arg(long, default_value_t = 0.02)]
    pub diameter: f64,
    /// Mesh label of the sweep rows to use.
    #[arg(long, default_value = "graded")]
    pub mesh: String,
    /// Lowest approach speed used, m/s.
    #[arg(long, default_value_t = 0.0)]
    pub vmin: f64,
    /// Highest approach speed used, m/s.
    #[arg(long, default_value_t = f64::INFINITY)]
    pub vmax: f64,
    /// Output directory (created if missing).
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
}

fn num(x: f64) -> Value {
    if x.is_finite() {
        json!(x)
    } else {
        Value::Null
    }
}

/// Runs `laws fit` against `registry`.
pub fn run(a: LawFitArgs, registry: &Registry) -> Result<()> {
    let spec = *registry.normal(&a.law)?;
    let m = Material::preset(&a.material).map_err(|_| {
        Error::invalid(
            "--material",
            &a.material,
            format!("one of {}", PRESET_NAMES.join(", ")),
        )
    })?;
    if !(a.diameter.is_finite() && a.diameter > 0.0) {
        return Err(Error::invalid("--diameter", a.diameter, "> 0 m, finite"));
    }
    if !(a.vmin >= 0.0 && a.vmax > a.vmin) {
        return Err(Error::invalid(
            "--vmax",
            a.vmax,
            format!("> --vmin = {}", a.vmin),
        ));
    }
    let b = Body::ball(m, a.diameter, "ball1")?;
    let pair = ContactPair::between(&b, &b, m.mu);
    let path = if a.against.is_dir() {
        a.against.join("fe.csv")
    } else {
        a.against.clone()
    };
    let text = std::fs::read_to_string(&path).map_err(|e| Error::io(&path, e))?;
    let source = path.display().to_string();
    let obs: Vec<_> = read_observations(&text, &source, Some(a.diameter), Some(&a.mesh))?
        .into_iter()
        .filter(|o| o.speed >= a.vmin && o.speed <= a.vmax)
        .collect();
    if obs.is_empty() {
        return Err(Error::invalid(
            "--against",
            &source,
            format!(
                "head-on rows with D = {} m, mesh {}, {} <= v_r <= {} m/s",
                a.diameter, a.mesh, a.vmin, a.vmax
            ),
        ));
    }
    let free: Vec<String> = if a.free.is_empty() {
        spec.params
            .iter()
            .filter(|p| p.key != "tension" && p.key != "R_star")
            .map(|p| p.key.to_string())
            .collect()
    } else {
        a.free.clone()
    };
    let fixed = parse_params("--param", &a.param)?;
    let f = fit(&spec, &pair, &b, &b, &obs, &free, &fixed)?;
    std::fs::create_dir_all(&a.out).map_err(|e| Error::io(&a.out, e))?;
    // Tabulated e(v_n) over the data range widened to 0.01..10 m/s, 41 log-spaced speeds.
    let lo = obs.iter().map(|o| o.speed).fold(0.01, f64::min);
    let hi = obs.iter().map(|o| o.speed).fold(10.0, f64::max);
    let mut csv = String::from("v_r [m/s],e [-],delta_max [m],contact_duration [s]\n");
    for i in 0..41 {
        let v = lo * (hi / lo).powf(i as f64 / 40.0);
        let (e, d, t) = predict(&spec, &pair, &f.params, &b, &b, v)?;
        csv.push_str(&format!("{v:.9e},{e:.9e},{d:.9e},{t:.9e}\n"));
    }
    write_atomic(a.out.join("e_of_v.csv"), csv.as_bytes())?;
    let exports = dem_exports(spec.name, &f.params, &pair, m.nu, m.rho, m.mu);
    for (name, text) in &exports {
        write_atomic(a.out.join(name), text.as_bytes())?;
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
        "law": spec.name,
        "source": source,
        "material": a.material,
        "diameter": a.diameter,
        "params": f.params.iter().map(|(k, v)| (k.to_string(), num(v))).collect::<serde_json::Map<_, _>>(),
        "free": f.free,
        "sigma": f.free.iter().zip(&f.sigma).map(|(k, s)| (k.to_string(), num(*s))).collect::<serde_json::Map<_, _>>(),
        "rms_relative_residual": num(f.rms),
        "rows": rows,
        "dem_exports": exports.iter().map(|(n, _)| *n).collect::<Vec<_>>(),
    });
    write_atomic(
        a.out.join("fit.json"),
        serde_json::to_string_pretty(&report)
            .map_err(|e| Error::Parse(e.to_string()))?
            .as_bytes(),
    )?;
    println!(
        "Fitted {} to {} head-on impacts from {source} (D = {} m, {}):",
        spec.name,
        obs.len(),
        a.diameter,
        a.material
    );
    for (k, v) in f.params.iter() {
        match f.free.iter().position(|n| *n == k) {
            Some(j) => println!("  {k} = {v:.6e} +- {:.2e} (fitted)", f.sigma[j]),
            None => println!("  {k} = {v:.6e} (fixed)"),
        }
    }
    println!("  rms relative residual (e and delta_max) = {:.4}", f.rms);
    for (o, e, d) in &f.rows {
        println!(
            "  v_r = {:.4} m/s: e {:.4} vs {:.4} ({:+.2} %), delta_max {:.4e} vs {:.4e} m ({:+.2} %)",
            o.speed,
            e,
            o.e,
            100.0 * (e - o.e) / o.e,
            d,
            o.delta_max,
            100.0 * (d - o.delta_max) / o.delta_max
        );
    }
    println!(
        "wrote {}/fit.json, e_of_v.csv{}",
        a.out.display(),
        exports
            .iter()
            .map(|(n, _)| format!(", {n}"))
            .collect::<String>()
    );
    Ok(())
}
