//! `twoball laws`: list the contact laws; `laws run`: one impact under a chosen normal and
//! tangential law (same ball, speed and JSON flags as `twoball analytic`); `laws fit`: fit a
//! law's parameters to restitution and maximum-approach data and export them for DEM codes.

use super::analytic::{after_json, bodies, merged, num, pair_json, print_after, AnalyticArgs};
use super::law_params::parse_params;
use crate::analytic::collision::pair_friction;
use crate::analytic::friction::{normal_energy_loss, revised_eta, zhang_energy_loss};
use crate::analytic::impact::{integrate, LawImpact, DEFAULT_TOLERANCE};
use crate::analytic::laws::{ContactPair, ParamSpec, Params, Registry};
use crate::analytic::Body;
use crate::error::{Error, Result};
use crate::material::Material;
use clap::{Args, Subcommand};
use serde_json::{json, Map, Value};

/// Arguments of `twoball laws`.
#[derive(Debug, Args)]
pub struct LawsArgs {
    /// What to do (none: as `list`).
    #[command(subcommand)]
    pub command: Option<LawsCommand>,
}

/// The `laws` subcommands.
#[derive(Debug, Subcommand)]
pub enum LawsCommand {
    /// Every law with its parameters, source, validity range and the DEM codes it exports to.
    List,
    /// One impact under a normal and a tangential contact law, integrated with error control.
    Run(LawRunArgs),
    /// Fit a law's parameters to e and delta_max over a speed range; write e(v) and DEM input.
    Fit(super::laws_fit::LawFitArgs),
    /// Every law against cached FE over a matrix of metals, speeds and diameters; REPORT.md.
    Bench(LawBenchArgs),
    /// A law with given parameters as a two-ball deck for LIGGGHTS, LAMMPS, Yade, MercuryDPM.
    Export(super::laws_export::LawExportArgs),
    /// Run a deck from `laws fit` or `laws export` in its DEM code, compare with `laws run`.
    Dem(super::laws_export::LawDemArgs),
    /// Maw, Barber & Fawcett's elastic oblique impact: normalised rebound against incidence
    /// angle, tangential restitution, by the method of dimensionality reduction.
    Mbf(super::laws_mbf::MbfArgs),
}

/// Arguments of `twoball laws bench`.
#[derive(Debug, Args)]
pub struct LawBenchArgs {
    /// Output folder: REPORT.md, the SVG figures and the FE cache `fe/`.
    #[arg(long, value_name = "DIR")]
    pub out: std::path::PathBuf,
    /// A TOML file replacing parts of the default matrix (keys metals, speeds, diameters,
    /// [oblique]).
    #[arg(long, value_name = "FILE")]
    pub matrix: Option<std::path::PathBuf>,
    /// Only run the FE points missing from the cache.
    #[arg(long, conflicts_with = "laws_only")]
    pub fe_only: bool,
    /// Run no FE: the laws, fits and report on the cached FE points.
    #[arg(long)]
    pub laws_only: bool,
    /// FE points run at once.
    #[arg(long, default_value_t = 2)]
    pub jobs: usize,
    /// Family level of the fine phase ensemble of each head-on FE point (coarse: one below).
    #[arg(long, value_name = "L", allow_hyphen_values = true,
          default_value_t = crate::study::laws_bench::fe::DEFAULT_FE_PLAN.phase.level)]
    pub fe_level: i32,
    /// Meshes per phase ensemble (even, >= 2).
    #[arg(long, value_name = "M",
          default_value_t = crate::study::laws_bench::fe::DEFAULT_FE_PLAN.phase.meshes)]
    pub phase_meshes: usize,
    /// Split the surface rings at each head-on point's contact edge SPLIT-fold (the banded
    /// mesh family; needs --fe-level >= 1; an odd split stops a sixth of the rays below the
    /// surface, an even one runs through the depth); `none`: the plain family, sized from
    /// Hertz's contact radius.
    #[arg(long, value_name = "SPLIT|none", default_value = "5")]
    pub fe_band: String,
    /// Mass-scale every head-on FE run: raise the smallest quads' density, adding at most
    /// BUDGET of the section's mass (0: none); the bias bound 10 x BUDGET joins every bar.
    #[arg(long, value_name = "BUDGET",
          default_value_t = crate::study::laws_bench::fe::DEFAULT_FE_PLAN.mass_scaling)]
    pub fe_mass_scaling: f64,
    /// Run a head-on point one level finer when the relative bar of its e exceeds this
    /// fraction (0: never).
    #[arg(long, value_name = "FRACTION",
          default_value_t = crate::study::laws_bench::fe::DEFAULT_FE_PLAN.phase.tolerance.unwrap_or(0.0))]
    pub fe_tolerance: f64,
    /// Run every diameter of the bilinear metals instead of scaling the smaller ones from
    /// the largest (similarity).
    #[arg(long)]
    pub no_similarity: bool,
}

/// `twoball laws bench` with `registry`.
pub fn bench_with(a: LawBenchArgs, registry: &Registry) -> Result<()> {
    use crate::study::laws_bench::{fe::FePlan, matrix::Matrix, run_bench, BenchOptions, Mode};
    if a.jobs == 0 {
        return Err(Error::invalid("--jobs", a.jobs, ">= 1"));
    }
    let matrix = match &a.matrix {
        Some(p) => {
            let text = std::fs::read_to_string(p).map_err(|e| Error::io(p, e))?;
            Matrix::from_toml(&text, &p.display().to_string())?
        }
        None => Matrix::default(),
    };
    let mode = match (a.fe_only, a.laws_only) {
        (true, _) => Mode::FeOnly,
        (_, true) => Mode::LawsOnly,
        _ => Mode::Full,
    };
    let band = match a.fe_band.as_str() {
        "none" => None,
        s => Some(
            s.parse::<usize>()
                .map_err(|_| Error::invalid("--fe-band", s, "an integer in [1, 16], or none"))?,
        ),
    };
    let plan = FePlan::new(a.fe_level, a.phase_meshes)?
        .with_band(band)?
        .with_mass_scaling(a.fe_mass_scaling)?
        .with_tolerance((a.fe_tolerance != 0.0).then_some(a.fe_tolerance))?;
    let default = FePlan::default();
    let mut command = format!(
        "twoball laws bench --out {}{} --jobs {}",
        a.out.display(),
        a.matrix
            .as_ref()
            .map_or(String::new(), |p| format!(" --matrix {}", p.display())),
        a.jobs
    );
    if (plan.phase.level, plan.phase.meshes) != (default.phase.level, default.phase.meshes) {
        command += &format!(
            " --fe-level {} --phase-meshes {}",
            plan.phase.level, plan.phase.meshes
        );
    }
    if plan.phase.band != default.phase.band {
        match plan.phase.band {
            Some(split) => command += &format!(" --fe-band {split}"),
            None => command += " --fe-band none",
        }
    }
    if plan.mass_scaling != default.mass_scaling {
        command += &format!(" --fe-mass-scaling {:e}", plan.mass_scaling);
    }
    if plan.phase.tolerance != default.phase.tolerance {
        command += &format!(" --fe-tolerance {:e}", plan.phase.tolerance.unwrap_or(0.0));
    }
    if a.no_similarity {
        command += " --no-similarity";
    }
    let opts = BenchOptions {
        out: a.out,
        matrix,
        mode,
        jobs: a.jobs,
        plan,
        similarity: !a.no_similarity,
        command,
    };
    let r = run_bench(&opts, registry, &|line: &str| eprintln!("{line}"))?;
    let [h, o, l] = r.stats;
    println!(
        "FE points: head-on {} run, {} from the cache, {} scaled, {} missing; oblique {} run, {} from the cache, {} missing; loops {} run, {} from the cache, {} missing",
        h.computed, h.reused, h.scaled, h.missing, o.computed, o.reused, o.missing, l.computed, l.reused, l.missing
    );
    if let Some(p) = r.report {
        println!("wrote {}", p.display());
    }
    Ok(())
}

/// Arguments of `twoball laws run`.
#[derive(Debug, Args)]
pub struct LawRunArgs {
    /// Normal contact law (see `twoball laws`).
    #[arg(long)]
    pub law: String,
    /// Override a normal-law parameter, KEY=VALUE in SI units; repeatable.
    #[arg(long = "param", value_name = "KEY=VALUE")]
    pub param: Vec<String>,
    /// Tangential contact law.
    #[arg(long, default_value = "coulomb")]
    pub tangential: String,
    /// Override a tangential-law parameter, KEY=VALUE in SI units; repeatable.
    #[arg(long = "tparam", value_name = "KEY=VALUE")]
    pub tparam: Vec<String>,
    /// Relative error of one integrator step.
    #[arg(long, default_value_t = DEFAULT_TOLERANCE)]
    pub tolerance: f64,
    /// Balls, speeds and output (as `twoball analytic`; --curve writes every integrator step
    /// and event, --samples does not apply).
    #[command(flatten)]
    pub ball: AnalyticArgs,
}

fn params_json(p: &Params) -> Value {
    let mut m = Map::new();
    for (k, v) in p.iter() {
        m.insert(k.to_string(), num(v));
    }
    Value::Object(m)
}

/// One impact of the flags' bodies under the flags' laws.
pub struct LawRun {
    /// Ball 1 and body 2.
    pub bodies: (Body, Body),
    /// Velocities before, [normal, tangential], m/s.
    pub v: ([f64; 2], [f64; 2]),
    /// Friction coefficient of the pair.
    pub mu: f64,
    /// Resolved normal and tangential parameters.
    pub params: (Params, Params),
    /// The integrated impact (None: no approach).
    pub impact: Option<LawImpact>,
}

/// Runs `a` against `registry` (the built-in laws, or more).
pub fn run_law(a: &LawRunArgs, registry: &Registry) -> Result<LawRun> {
    let (b1, b2) = bodies(&a.ball.bodies)?;
    let v2n = a.ball.v2.unwrap_or(if b2.is_wall() { 0.0 } else { -1.0 });
    let mu = match a.ball.mu {
        Some(mu) if !(mu.is_finite() && mu >= 0.0) => {
            return Err(Error::invalid("--mu", mu, ">= 0, finite"))
        }
        Some(mu) => mu,
        None => pair_friction(&b1, &b2),
    };
    if b2.is_wall() && (v2n != 0.0 || a.ball.v2t != 0.0) {
        return Err(Error::invalid(
            "--v2",
            v2n,
            "0 with --wall (a half-space does not move)",
        ));
    }
    let pair = ContactPair::between(&b1, &b2, mu);
    let (normal, np) = registry
        .normal(&a.law)?
        .build_with(&parse_params("--param", &a.param)?, &pair)?;
    let (tang, tp) = registry
        .tangential(&a.tangential)?
        .build_with(&parse_params("--tparam", &a.tparam)?, &pair)?;
    let v1 = [a.ball.v1, a.ball.v1t];
    let v2 = [v2n, a.ball.v2t];
    let impact = integrate(
        &b1,
        &b2,
        v1,
        v2,
        normal.as_ref(),
        tang.as_ref(),
        a.tolerance,
    )
    .map_err(|e| Error::Numerical(format!("law {}: {e}", a.law)))?;
    Ok(LawRun {
        bodies: (b1, b2),
        v: (v1, v2),
        mu,
        params: (np, tp),
        impact,
    })
}

/// The `--json` object: the keys of `twoball analytic --json` plus the law's own.
pub fn run_json(a: &LawRunArgs, r: &LawRun) -> Value {
    let (b1, b2) = &r.bodies;
    let (v1, v2) = r.v;
    let pair = ContactPair::between(b1, b2, r.mu);
    let out = json!({
        "law": a.law,
        "tangential_law": a.tangential,
        "params": params_json(&r.params.0),
        "tangential_params": params_json(&r.params.1),
        "impact": r.impact.is_some(),
        "v_r": num(v1[0] - v2[0]),
        "tangential_exit": Value::Null,
    });
    let out = merged(
        out,
        pair_json(&pair.hertz, pair.yield_pressure, r.mu, b1, b2),
    );
    let Some(i) = &r.impact else {
        return out;
    };
    let two_pi = 2.0 * std::f64::consts::PI;
    let m = i.pair.mass;
    let vr = i.approach_speed;
    let ke_n = crate::analytic::friction::kinetic(b1.mass(), v1[0])
        + crate::analytic::friction::kinetic(b2.mass(), v2[0]);
    let extra = json!({
        "yielded": !i.phase_times.is_empty(),
        "e": num(i.e),
        "delta1": i.phase_times.first().and_then(|t| i.history.iter().find(|s| s.t == *t)).map_or(Value::Null, |s| num(s.delta)),
        "delta2": num(i.delta_max),
        "delta_p": num(i.delta_end),
        "t1": i.phase_times.first().map_or(Value::Null, |t| num(*t)),
        "t2": num(i.time_of_max),
        "t3": num(i.contact_duration),
        "v_r_after": num(i.rebound_speed),
        "peak_force": num(i.peak_force),
        "eta": num(normal_energy_loss(m, i.e, vr) / (two_pi * ke_n)),
        "eta_friction": num(revised_eta(b1.mass(), b2.mass(), v1, v2, i.e, r.mu)),
        "eta_impulse": num((i.energy_before - i.after.energy_after) / (two_pi * i.energy_before)),
        "zhang_loss": num(zhang_energy_loss(m, i.e, r.mu, vr, v1[1] - v2[1])),
        "energy_before": num(i.energy_before),
        "energy_after": num(i.after.energy_after),
        "delta_max": num(i.delta_max),
        "contact_duration": num(i.contact_duration),
        "work_normal": num(i.work_normal),
        "work_tangential": num(i.work_tangential),
        "energy_residual": num(i.energy_residual()),
        "tangential_restitution": i.tangential_restitution().map_or(Value::Null, num),
        "normal_impulse": num(i.normal_impulse),
        "tangential_impulse": num(i.tangential_impulse),
        "steps": i.steps,
    });
    let out = merged(out, after_json(&i.after));
    merged(out, extra)
}

fn print_run(a: &LawRunArgs, r: &LawRun) {
    println!(
        "Contact law {} + {} (integrated, relative step tolerance {:e}), SI units",
        a.law, a.tangential, a.tolerance
    );
    let show = |p: &Params| {
        p.iter()
            .map(|(k, v)| format!("{k} = {v:.6e}"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    println!("normal parameters:     {}", show(&r.params.0));
    println!("tangential parameters: {}", show(&r.params.1));
    let Some(i) = &r.impact else {
        println!("impact: none (v_r = v1 - v2 <= 0: the bodies separate); velocities unchanged");
        return;
    };
    println!(
        "restitution   e = {:.9}   (v_r = {:.6} -> {:.6} m/s)",
        i.e, i.approach_speed, i.rebound_speed
    );
    println!(
        "max approach  delta_max = {:.6e} m at t = {:.6e} s; at separation delta = {:.6e} m",
        i.delta_max, i.time_of_max, i.delta_end
    );
    println!(
        "contact       t_c = {:.6e} s, peak force = {:.6e} N, {} phase change(s), {} steps",
        i.contact_duration,
        i.peak_force,
        i.phase_times.len(),
        i.steps
    );
    print_after(&i.after);
    if let Some(et) = i.tangential_restitution() {
        println!("tangential restitution of the contact points = {et:.6}");
    }
    println!(
        "energy: before {:.6e} J, after {:.6e} J, normal work {:.6e} J, tangential work {:.6e} J, residual {:.1e}",
        i.energy_before, i.after.energy_after, i.work_normal, i.work_tangential, i.energy_residual()
    );
}

/// Prints one law of the list: name, title, source, DEM codes, and each parameter with its
/// unit and its default for `pair`.
fn print_spec(
    name: &str,
    title: &str,
    source: &str,
    (dem_codes, validity): (&str, Option<&str>),
    params: &[ParamSpec],
    pair: &ContactPair,
) {
    println!("\n  {name:<20} {title}");
    println!("  {:<20} source: {source}", "");
    if let Some(v) = validity {
        println!("  {:<20} holds for: {v}", "");
    }
    println!("  {:<20} DEM codes: {dem_codes}", "");
    for p in params {
        println!(
            "  {:<20}   {} [{}] = {:.6e}: {}",
            "",
            p.key,
            p.unit,
            (p.default)(pair),
            p.doc
        );
    }
}

/// `twoball laws run` with `registry`.
pub fn run_with(a: LawRunArgs, registry: &Registry) -> Result<()> {
    let r = run_law(&a, registry)?;
    if let Some(w) = validity_warning(&a, &r, registry) {
        eprintln!("warning: {w}");
    }
    if let (Some(path), Some(i)) = (&a.ball.curve, &r.impact) {
        crate::study::report::curves::write_law_curve(i, path)?;
    }
    if a.ball.json {
        println!("{}", run_json(&a, &r));
    } else {
        print_run(&a, &r);
        if let (Some(path), Some(_)) = (&a.ball.curve, &r.impact) {
            println!("contact history written to {}", path.display());
        }
    }
    Ok(())
}

/// The one-line warning when the impact of `r` lies outside the validity range of the law
/// of `a` (see `twoball laws list`).
pub fn validity_warning(a: &LawRunArgs, r: &LawRun, registry: &Registry) -> Option<String> {
    let i = r.impact.as_ref()?;
    let spec = registry.normal(&a.law).ok()?;
    let (b1, b2) = &r.bodies;
    let pair = ContactPair::between(b1, b2, r.mu);
    spec.validity
        .warning(spec.name, &pair, &r.params.0, i.delta_max, i.approach_speed)
}

/// One law of the list as JSON: name, title, source, DEM codes, and each parameter with its
/// unit, meaning and default for `pair`.
fn spec_json(
    name: &str,
    title: &str,
    source: &str,
    dem_codes: &str,
    params: &[ParamSpec],
    pair: &ContactPair,
) -> Value {
    json!({
        "name": name,
        "title": title,
        "source": source,
        "dem_codes": dem_codes,
        "params": params.iter().map(|p| json!({
            "key": p.key,
            "unit": p.unit,
            "doc": p.doc,
            "default": num((p.default)(pair)),
        })).collect::<Vec<_>>(),
    })
}

/// The laws of `registry` as JSON (what `twoball laws` lists): `normal` and `tangential`,
/// defaults for two copper-fe balls of D = 20 mm.
pub fn list_json(registry: &Registry) -> Result<Value> {
    let m = Material::preset("copper-fe")?;
    let b = Body::ball(m, 0.02, "ball")?;
    let pair = ContactPair::between(&b, &b, m.mu);
    Ok(json!({
        "defaults_for": "two copper-fe balls, D = 0.02 m",
        "normal": registry.normal.iter().map(|s| {
            let mut j = spec_json(s.name, s.title, s.source, s.dem_codes, s.params, &pair);
            j["validity"] = json!(s.validity.range);
            j
        }).collect::<Vec<_>>(),
        "tangential": registry.tangential.iter().map(|s| spec_json(s.name, s.title, s.source, s.dem_codes, s.params, &pair)).collect::<Vec<_>>(),
    }))
}

/// The object `twoball laws run --json` prints for `a` (writes `--curve` when asked).
pub fn law_run_json(a: &LawRunArgs, registry: &Registry) -> Result<Value> {
    let r = run_law(a, registry)?;
    if let (Some(path), Some(i)) = (&a.ball.curve, &r.impact) {
        crate::study::report::curves::write_law_curve(i, path)?;
    }
    Ok(run_json(a, &r))
}

fn list(registry: &Registry) -> Result<()> {
    let m = Material::preset("copper-fe")?;
    let b = Body::ball(m, 0.02, "ball")?;
    let pair = ContactPair::between(&b, &b, m.mu);
    println!("Contact laws (defaults shown for two copper-fe balls, D = 20 mm)");
    println!("\nNormal laws (--law NAME, --param KEY=VALUE):");
    for s in &registry.normal {
        print_spec(
            s.name,
            s.title,
            s.source,
            (s.dem_codes, Some(s.validity.range)),
            s.params,
            &pair,
        );
    }
    println!("\nTangential laws (--tangential NAME, --tparam KEY=VALUE):");
    for s in &registry.tangential {
        print_spec(
            s.name,
            s.title,
            s.source,
            (s.dem_codes, None),
            s.params,
            &pair,
        );
    }
    Ok(())
}

/// Runs one `laws` subcommand against `registry`.
fn dispatch(command: Option<LawsCommand>, registry: &Registry) -> Result<()> {
    match command {
        None | Some(LawsCommand::List) => list(registry),
        Some(LawsCommand::Run(r)) => run_with(r, registry),
        Some(LawsCommand::Fit(f)) => super::laws_fit::run(f, registry),
        Some(LawsCommand::Bench(b)) => bench_with(b, registry),
        Some(LawsCommand::Export(e)) => super::laws_export::export(e, registry),
        Some(LawsCommand::Dem(d)) => super::laws_export::dem(d, registry),
        Some(LawsCommand::Mbf(m)) => super::laws_mbf::run(m),
    }
}

/// `twoball laws …`.
pub fn run(a: LawsArgs) -> Result<()> {
    let registry = Registry::builtin();
    dispatch(a.command, &registry)
}

/// Command line of `twoball laws …` alone (for programs that add laws).
#[derive(Debug, clap::Parser)]
#[command(name = "twoball laws")]
struct LawsCli {
    #[command(flatten)]
    laws: LawsArgs,
}

/// Runs `twoball laws …` with `args` (the first is the program name) against `registry`
/// (the built-in laws plus a program's own) and returns the exit code: how an example or a
/// researcher's program runs its law through `laws run` and `laws fit`.
pub fn main_with<I, T>(args: I, registry: &Registry) -> i32
where
    I: IntoIterator<Item = T>,
    T: Into<std::ffi::OsString> + Clone,
{
    use clap::Parser;
    let cli = match LawsCli::try_parse_from(args) {
        Ok(c) => c,
        Err(e) => {
            let _ = e.print();
            return e.exit_code();
        }
    };
    let result = dispatch(cli.laws.command, registry);
    match result {
        Ok(()) => 0,
        Err(e) => {
            eprintln!("error: {e}");
            1
        }
    }
}
