//! `twoball laws fit`: fit a normal law's free parameters to head-on e and δ_max data (the
//! files a DEM user needs, fit.json, e_of_v.csv and DEM input snippets, are written by
//! `study::report::law_fit_files`), or to a quasi-static FE loop's forces
//! (`--against-static DIR`, `study::laws_bench::loop_fit`).

use super::law_params::parse_params;
use crate::analytic::law_fit::{fit_weighted, read_observations, Weights};
use crate::analytic::laws::{ContactPair, NormalSpec, Registry};
use crate::analytic::Body;
use crate::error::{Error, Result};
use crate::material::{Material, PRESET_NAMES};
use crate::study::laws_bench::loop_fit::{fit_law_on_loop, read_loop_folder, write_loop_fit};
use crate::study::report::law_fit_files::{write_fit_files, FitSetting};
use clap::Args;
use std::path::PathBuf;

/// Arguments of `twoball laws fit`.
#[derive(Debug, Args)]
pub struct LawFitArgs {
    /// Normal law to fit (see `twoball laws`).
    #[arg(long)]
    pub law: String,
    /// Data: a CSV with columns `v_r [m/s]`, `e [-]`, `delta_max [m]`, a `twoball sweep`
    /// CSV (head-on rows of --diameter and --mesh), or a directory holding `fe.csv`.
    #[arg(
        long,
        value_name = "CSV_OR_DIR",
        required_unless_present = "against_static"
    )]
    pub against: Option<PathBuf>,
    /// Fit the law's quasi-static loading and unloading forces to the loop of a
    /// `twoball static --out DIR` folder instead (its pair, material and diameter from
    /// DIR/results.json; --material, --diameter, --mesh, --vmin and --vmax do not apply).
    #[arg(long, value_name = "DIR", conflicts_with = "against")]
    pub against_static: Option<PathBuf>,
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

/// Runs `laws fit` against `registry`.
pub fn run(a: LawFitArgs, registry: &Registry) -> Result<()> {
    let spec = *registry.normal(&a.law)?;
    let free = free_or_default(&spec, &a.free);
    let fixed = parse_params("--param", &a.param)?;
    if let Some(dir) = &a.against_static {
        return fit_static(&spec, dir, &free, &fixed, &a.out);
    }
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
    let against = a
        .against
        .clone()
        .expect("clap: --against or --against-static");
    let path = if against.is_dir() {
        against.join("fe.csv")
    } else {
        against
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
    let f = fit_weighted(&spec, &pair, &b, &b, &obs, &free, &fixed, Weights::BOTH)?;
    let decks = write_fit_files(
        &a.out,
        &FitSetting {
            spec: &spec,
            pair: &pair,
            ball: &b,
            material: &m,
            material_name: &a.material,
            diameter: a.diameter,
            source: &source,
        },
        &obs,
        &f,
    )?;
    println!(
        "Fitted {} to {} head-on impacts from {source} (D = {} m, {}):",
        spec.name,
        obs.len(),
        a.diameter,
        a.material
    );
    for (k, v) in f.optimum.params.iter() {
        match f.optimum.free.iter().position(|n| *n == k) {
            Some(j) => println!("  {k} = {v:.6e} +- {:.2e} (fitted)", f.optimum.sigma[j]),
            None => println!("  {k} = {v:.6e} (fixed)"),
        }
    }
    println!(
        "  rms relative residual (e and delta_max) = {:.4}",
        f.optimum.rms
    );
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
        "wrote {}/fit.json, e_of_v.csv{} (DEM decks default to v_r = {} m/s)",
        a.out.display(),
        decks
            .written
            .iter()
            .map(|n| format!(", {n}"))
            .collect::<String>(),
        decks.reference_speed
    );
    for r in &decks.refused {
        println!("  no deck: {r}");
    }
    Ok(())
}

/// The free keys asked for, or every parameter of the law but `tension` and `R_star` (only
/// E* √R* is identifiable from head-on data or from F(δ)).
fn free_or_default(spec: &NormalSpec, asked: &[String]) -> Vec<String> {
    if !asked.is_empty() {
        return asked.to_vec();
    }
    spec.params
        .iter()
        .filter(|p| p.key != "tension" && p.key != "R_star")
        .map(|p| p.key.to_string())
        .collect()
}

/// `laws fit --against-static DIR`: the law fitted to the loop in `dir`, written to `out`.
fn fit_static(
    spec: &NormalSpec,
    dir: &std::path::Path,
    free: &[String],
    fixed: &[(String, f64)],
    out: &std::path::Path,
) -> Result<()> {
    let folder = read_loop_folder(dir)?;
    let f = fit_law_on_loop(&folder, spec, free, fixed)?;
    write_loop_fit(out, dir, spec, &f, &folder.finest)?;
    let p = &folder.pair;
    println!(
        "Fitted {} to the quasi-static loop in {} (D = {} m, {}, {} points):",
        spec.name,
        dir.display(),
        p.diameter_m,
        if p.rigid_wall {
            "ball on a rigid wall"
        } else {
            "two identical balls"
        },
        folder.finest.loading.len() + folder.finest.unloading.len()
    );
    for (k, v) in f.fit.params.iter() {
        match f.fit.free.iter().position(|n| *n == k) {
            Some(j) => println!("  {k} = {v:.6e} +- {:.2e} (fitted)", f.fit.sigma[j]),
            None => println!("  {k} = {v:.6e} (fixed)"),
        }
    }
    println!("  RMS force error over the FE peak force     loading  unloading");
    for (name, x) in [
        ("default parameters", &f.before),
        ("fitted parameters", &f.after),
    ] {
        println!(
            "    {name:<38} {:>6.2} % {:>8.2} %",
            100.0 * x.loading_rms,
            100.0 * x.unloading_rms
        );
    }
    println!("wrote {}/fit.json, loop_fit.csv", out.display());
    Ok(())
}
