//! `twoball analytic`, `twoball materials`, `twoball parametric`: the analytical model of
//! Li, Yang & Shi (2019) from the command line.

use crate::analytic::damping_index::{
    best_reading, candidate_readings, damping_index, reading_score, table1, EtaReading,
    ReadingScore, Table1Row, TABLE1_SPEEDS, ZETA_TABLE_SCALE,
};
use crate::analytic::exchange::Exchange;
use crate::analytic::friction::TangentialExit;
use crate::analytic::hertz::HertzPair;
use crate::analytic::parametric::all_figures;
use crate::analytic::{collide_with_mu, Body, Collision};
use crate::error::{Error, Result};
use crate::material::{Material, MaterialOverrides, PRESET_NAMES};
use crate::study::records::number::sci;
use crate::study::records::warnings::{analytic_warnings, Warning};
use clap::{Args, ValueEnum};
use serde_json::{json, Value};
use std::path::PathBuf;

/// What body 2 is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum WallArg {
    /// A rigid, immovable half-space.
    Rigid,
    /// An immovable elastic-plastic half-space of `--material2` (default: ball 1's material).
    Elastic,
}

/// The two bodies of an analytical impact: materials, diameters, overrides, wall.
#[derive(Debug, Args)]
pub struct BodyArgs {
    /// Material preset of both balls (copper, steel, concrete, cast-iron, alumina, glass,
    /// wood, aluminum, rubber, copper-fe).
    #[arg(long, default_value = "copper-fe")]
    pub material: String,
    /// Diameter of both balls, m.
    #[arg(long, default_value_t = 0.02, allow_negative_numbers = true)]
    pub diameter: f64,
    /// Material preset of ball 2 (default: --material).
    #[arg(long)]
    pub material2: Option<String>,
    /// Diameter of ball 2, m (default: --diameter).
    #[arg(long, allow_negative_numbers = true)]
    pub diameter2: Option<f64>,
    /// Override a material field in SI units (keys: E, nu, rho, yield, tangent, mu,
    /// mu_static) by its scene path, ball1.material.KEY=VALUE or ball2.material.KEY=VALUE
    /// (as `twoball run --set`), or KEY=VALUE for both balls; repeatable.
    #[arg(long = "set", value_name = "[ballN.material.]KEY=VALUE")]
    pub set: Vec<String>,
    /// Replace ball 2 by a half-space at rest (ball-on-wall limit).
    #[arg(long, value_enum)]
    pub wall: Option<WallArg>,
}

/// Arguments of `twoball analytic`.
#[derive(Debug, Args)]
pub struct AnalyticArgs {
    /// The two bodies.
    #[command(flatten)]
    pub bodies: BodyArgs,
    /// Normal speed of ball 1 before impact, m/s (positive towards +x, i.e. towards ball 2).
    #[arg(long, default_value_t = 1.0, allow_negative_numbers = true)]
    pub v1: f64,
    /// Normal speed of ball 2 before impact, m/s (positive towards +x) [default: -1, or 0
    /// with --wall].
    #[arg(long, allow_negative_numbers = true)]
    pub v2: Option<f64>,
    /// Tangential speed of ball 1 before impact, m/s.
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    pub v1t: f64,
    /// Tangential speed of ball 2 before impact, m/s.
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    pub v2t: f64,
    /// Friction coefficient of the pair (default: mean of the two materials' mu).
    #[arg(long, allow_negative_numbers = true)]
    pub mu: Option<f64>,
    /// Print one JSON object instead of the table.
    #[arg(long)]
    pub json: bool,
    /// Also write the contact history (t, delta, delta_dot, force) to this CSV file.
    #[arg(long, value_name = "FILE.csv")]
    pub curve: Option<PathBuf>,
    /// Number of samples in --curve (>= 2).
    #[arg(long, default_value_t = 2001)]
    pub samples: usize,
}

/// Arguments of `twoball materials`.
#[derive(Debug, Args)]
pub struct MaterialsArgs {
    /// Print one JSON object instead of the table.
    #[arg(long)]
    pub json: bool,
}

/// Arguments of `twoball parametric`.
#[derive(Debug, Args)]
pub struct ParametricArgs {
    /// Output directory (created if missing) for fig11..fig14 .csv and .svg.
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
}

/// A preset by name, the error naming the flag.
fn preset(flag: &str, name: &str) -> Result<Material> {
    Material::preset(name)
        .map_err(|_| Error::invalid(flag, name, format!("one of {}", PRESET_NAMES.join(", "))))
}

/// Applies the `--set [ballN.material.]KEY=VALUE` overrides that concern ball `ball` (1 or 2).
fn apply_sets(m: Material, flag: &str, sets: &[String], ball: u8) -> Result<Material> {
    let prefix = format!("ball{ball}.material");
    let mut o = MaterialOverrides::default();
    for s in sets {
        let (target, rest) = if let Some(r) = s.strip_prefix("ball1.material.") {
            (Some(1), r)
        } else if let Some(r) = s.strip_prefix("ball2.material.") {
            (Some(2), r)
        } else {
            (None, s.as_str())
        };
        if target.is_some_and(|t| t != ball) {
            continue;
        }
        let (key, value) = rest.split_once('=').ok_or_else(|| {
            Error::Parse(format!(
                "{flag} {s}: expected KEY=VALUE, e.g. {flag} yield=2e8"
            ))
        })?;
        let v: f64 = value
            .trim()
            .parse()
            .map_err(|_| Error::Parse(format!("{flag} {s}: value '{value}' is not a number")))?;
        let slot = match key.trim() {
            "E" => &mut o.youngs,
            "nu" => &mut o.nu,
            "rho" => &mut o.rho,
            "yield" => &mut o.yield_strength,
            "tangent" => &mut o.tangent,
            "mu" => &mut o.mu,
            "mu_static" => &mut o.mu_static,
            other => {
                return Err(Error::invalid(
                    format!("{flag} key"),
                    other,
                    "one of E, nu, rho, yield, tangent, mu, mu_static",
                ))
            }
        };
        *slot = Some(v);
    }
    m.overridden(&o).validated(&prefix).map_err(|e| {
        e.map_field(|field| {
            let key = field.rsplit('.').next().unwrap_or(&field).to_string();
            set_flag_of(sets, ball, &key).unwrap_or(field)
        })
    })
}

/// The `--set` that gave ball `ball` (1 or 2) its field `key` (the last one wins), as the
/// user wrote its target: `--set yield` for both balls, `--set 2.yield` for one.
fn set_flag_of(sets: &[String], ball: u8, key: &str) -> Option<String> {
    sets.iter().rev().find_map(|s| {
        let (target, rest) = match s.split_once('.') {
            Some(("1", r)) => (Some(1), r),
            Some(("2", r)) => (Some(2), r),
            _ => (None, s.as_str()),
        };
        let k = rest.split_once('=')?.0.trim();
        match target {
            _ if k != key => None,
            None => Some(format!("--set {key}")),
            Some(t) if t == ball => Some(format!("--set {t}.{key}")),
            Some(_) => None,
        }
    })
}

/// The two bodies described by the flags.
pub(super) fn bodies(a: &BodyArgs) -> Result<(Body, Body)> {
    for (flag, d) in [
        ("--diameter", Some(a.diameter)),
        ("--diameter2", a.diameter2),
    ] {
        if let Some(d) = d {
            if !crate::scene::DIAMETER_RANGE.contains(&d) {
                return Err(Error::invalid(
                    flag,
                    d,
                    "1e-4 <= diameter <= 1 m, as in a scene",
                ));
            }
        }
    }
    let m1 = preset("--material", &a.material)?;
    let m2 = match &a.material2 {
        Some(n) => preset("--material2", n)?,
        None => m1,
    };
    let m1 = apply_sets(m1, "--set", &a.set, 1)?;
    let m2 = apply_sets(m2, "--set", &a.set, 2)?;
    let b1 = Body::ball(m1, a.diameter, "ball1")?;
    let b2 = match a.wall {
        None => Body::ball(m2, a.diameter2.unwrap_or(a.diameter), "ball2")?,
        Some(WallArg::Rigid) => Body::RigidWall,
        Some(WallArg::Elastic) => Body::HalfSpace { material: m2 },
    };
    Ok((b1, b2))
}

/// Finite numbers as JSON numbers, anything else as null (no NaN is ever written).
pub(super) fn num(x: f64) -> Value {
    if x.is_finite() {
        json!(x)
    } else {
        Value::Null
    }
}

/// The `--json` object (keys documented in the README, section "Analytical model").
fn collision_json(c: &Collision, b1: &Body, b2: &Body) -> Value {
    let n = c.normal.as_ref();
    let opt =
        |f: &dyn Fn(&crate::analytic::NormalImpact) -> f64| n.map_or(Value::Null, |n| num(f(n)));
    let (exit, exit_phase, exit_time, exit_delta) = match c.tangential.map(|t| t.exit) {
        None => ("none", Value::Null, Value::Null, Value::Null),
        Some(TangentialExit::NoSlip) => ("no-slip", Value::Null, Value::Null, Value::Null),
        Some(TangentialExit::Slip) => ("slip", Value::Null, Value::Null, Value::Null),
        Some(TangentialExit::Stick {
            phase,
            time,
            approach,
        }) => ("stick", json!(phase.number()), num(time), num(approach)),
    };
    let out = json!({
        "impact": c.impact,
        "yielded": n.is_some_and(|n| n.yielded),
        "e": opt(&|n| n.e),
        "delta1": opt(&|n| n.delta1),
        "delta2": opt(&|n| n.delta2),
        "delta_p": opt(&|n| n.delta_p),
        "t1": opt(&|n| n.t1),
        "t2": opt(&|n| n.t2),
        "t3": opt(&|n| n.t3),
        "v_r": num(c.v1_before[0] - c.v2_before[0]),
        "v_r_after": opt(&|n| n.rebound_speed),
        "peak_force": opt(&|n| n.pair.force(n.delta2 - n.delta_p)),
        "eta": num(c.eta),
        "eta_friction": num(c.eta_friction),
        "eta_impulse": num(c.eta_impulse),
        "zhang_loss": num(c.zhang_loss),
        "energy_before": num(c.energy_before),
        "energy_after": num(c.after.energy_after),
        "tangential_exit": exit,
        "tangential_exit_phase": exit_phase,
        "tangential_exit_time": exit_time,
        "tangential_exit_delta": exit_delta,
    });
    let out = merged(out, after_json(&c.after));
    let sigma_p = b1.yield_pressure().min(b2.yield_pressure());
    merged(out, pair_json(&c.pair, sigma_p, c.mu, b1, b2))
}

/// The velocities after impact, as `twoball analytic --json` and `twoball laws run --json`
/// write them: `v1_after`, `v2_after`, `v1t_after`, `v2t_after` from the `[normal,
/// tangential]` velocities of `after` (m/s), `w1_after`, `w2_after` from its spins (rad/s).
pub(super) fn after_json(after: &Exchange) -> Value {
    let (v1, v2, spin) = (after.v1_after, after.v2_after, after.spin_after);
    json!({
        "v1_after": num(v1[0]),
        "v2_after": num(v2[0]),
        "v1t_after": num(v1[1]),
        "v2t_after": num(v2[1]),
        "w1_after": num(spin[0]),
        "w2_after": num(spin[1]),
    })
}

/// Prints the state after an impact (velocities and spins), as `twoball analytic` and
/// `twoball laws run` show it.
pub(super) fn print_after(after: &Exchange) {
    let (v1, v2, w) = (after.v1_after, after.v2_after, after.spin_after);
    println!(
        "after:  v1 = ({:+.6}, {:+.6}) m/s, v2 = ({:+.6}, {:+.6}) m/s, spins = ({:+.4}, {:+.4}) rad/s",
        v1[0], v1[1], v2[0], v2[1], w[0], w[1]
    );
}

/// The pair's keys of both `--json` objects: `e_star` (Pa), `r_star` (m), `m_star` (kg) of
/// `pair`, the yield pressure `sigma_p` (Pa), the friction coefficient `mu` and the masses
/// `m1`, `m2` (kg) of the bodies.
pub(super) fn pair_json(pair: &HertzPair, sigma_p: f64, mu: f64, b1: &Body, b2: &Body) -> Value {
    json!({
        "e_star": num(pair.modulus),
        "r_star": num(pair.radius),
        "m_star": num(pair.mass),
        "sigma_p": num(sigma_p),
        "mu": num(mu),
        "m1": num(b1.mass()),
        "m2": num(b2.mass()),
    })
}

/// The JSON object `out` with the keys of the object `more` added.
pub(super) fn merged(mut out: Value, more: Value) -> Value {
    if let (Value::Object(o), Value::Object(m)) = (&mut out, more) {
        o.extend(m);
    }
    out
}

fn describe(b: &Body, name: &str) -> String {
    match b {
        Body::Ball { material, diameter } => format!(
            "{name}: D = {diameter} m, m = {} kg, E = {} Pa, nu = {}, rho = {} kg/m^3, \
             yield = {} Pa, mu = {}",
            sci(b.mass(), 6),
            sci(material.youngs, 4),
            material.nu,
            material.rho,
            sci(material.yield_strength, 4),
            material.mu
        ),
        Body::RigidWall => format!("{name}: rigid half-space at rest"),
        Body::HalfSpace { material } => format!(
            "{name}: elastic-plastic half-space at rest, E = {} Pa, nu = {}, yield = {} Pa",
            sci(material.youngs, 4),
            material.nu,
            sci(material.yield_strength, 4)
        ),
    }
}

fn print_table(c: &Collision, b1: &Body, b2: &Body) {
    println!("Three-phase collision model (Li, Yang & Shi 2019), SI units");
    println!("{}", describe(b1, "ball 1"));
    println!(
        "{}",
        describe(b2, if b2.is_wall() { "wall" } else { "ball 2" })
    );
    println!(
        "before: v1 = ({:+.6}, {:+.6}) m/s, v2 = ({:+.6}, {:+.6}) m/s  [normal, tangential]",
        c.v1_before[0], c.v1_before[1], c.v2_before[0], c.v2_before[1]
    );
    println!(
        "pair:   E* = {} Pa, R* = {} m, m* = {} kg, sigma_p = {} Pa, mu = {}",
        sci(c.pair.modulus, 6),
        sci(c.pair.radius, 6),
        sci(c.pair.mass, 6),
        sci(b1.yield_pressure().min(b2.yield_pressure()), 6),
        c.mu
    );
    let Some(n) = c.normal else {
        println!("impact: none (v_r = v1 - v2 <= 0: the bodies separate); velocities unchanged");
        return;
    };
    println!(
        "impact: yes, {}",
        if n.yielded {
            "elastic -> elastoplastic -> recovery"
        } else {
            "never yields (pure Hertz, e = 1)"
        }
    );
    let phase = |label: &str, name: &str, delta: f64, t_name: &str, t: f64| {
        println!(
            "  {label:<13} {name:<7} = {:<12} m     {t_name} = {} s",
            sci(delta, 6),
            sci(t, 6)
        );
    };
    phase("phase 1 end", "delta1", n.delta1, "t1", n.t1);
    phase("max approach", "delta2", n.delta2, "t2", n.t2);
    phase("permanent", "delta_p", n.delta_p, "t3", n.t3);
    println!(
        "  restitution   e = {:.6}   (v_r = {:.6} -> {:.6} m/s)",
        n.e, n.approach_speed, n.rebound_speed
    );
    print_after(&c.after);
    match c.tangential.map(|t| t.exit) {
        Some(TangentialExit::Stick {
            phase,
            time,
            approach,
        }) => println!(
            "tangential: slip stops in phase {} (t = {} s, delta = {} m), then rolls",
            phase.number(),
            sci(time, 4),
            sci(approach, 4)
        ),
        Some(TangentialExit::Slip) => println!("tangential: slides for the whole contact"),
        _ => println!("tangential: no slip"),
    }
    println!("eta (eq. 33)          = {:.6}", c.eta);
    println!("eta_friction (eq. 43) = {:.6}", c.eta_friction);
    println!("eta_impulse (Coulomb) = {:.6}", c.eta_impulse);
    println!("Zhang loss (eq. 42)   = {} J", sci(c.zhang_loss, 6));
}

/// The analytical model's range warnings for collision `c` (none without impact).
fn collision_warnings(c: &Collision) -> Vec<Warning> {
    c.normal
        .as_ref()
        .map_or_else(Vec::new, |n| analytic_warnings(n.delta2, c.pair.radius))
}

/// The collision the flags describe (checked as the CLI checks them), with its bodies; writes
/// `--curve` when asked.
fn collide_args(a: &AnalyticArgs) -> Result<(Collision, Body, Body)> {
    let (b1, b2) = bodies(&a.bodies)?;
    let v2n = a.v2.unwrap_or(if b2.is_wall() { 0.0 } else { -1.0 });
    for (flag, v) in [
        ("--v1", a.v1),
        ("--v2", v2n),
        ("--v1t", a.v1t),
        ("--v2t", a.v2t),
    ] {
        if v.is_nan() || v.abs() > crate::scene::SPEED_MAX {
            return Err(Error::invalid(
                flag,
                v,
                "|speed| <= 1000 m/s, as in a scene",
            ));
        }
    }
    let mu = match a.mu {
        Some(mu) if !(mu.is_finite() && mu >= 0.0) => {
            return Err(Error::invalid("--mu", mu, ">= 0, finite"))
        }
        Some(mu) => mu,
        None => crate::analytic::collision::pair_friction(&b1, &b2),
    };
    if b2.is_wall() && (v2n != 0.0 || a.v2t != 0.0) {
        let flag = if v2n != 0.0 { "--v2" } else { "--v2t" };
        let v = if v2n != 0.0 { v2n } else { a.v2t };
        return Err(Error::invalid(
            flag,
            v,
            "0 with --wall (a half-space does not move)",
        ));
    }
    let c = collide_with_mu(&b1, &b2, [a.v1, a.v1t], [v2n, a.v2t], mu)?;
    if let Some(path) = &a.curve {
        crate::study::report::curves::write_analytic_curve(&c, path, a.samples)?;
    }
    Ok((c, b1, b2))
}

/// The object `twoball analytic --json` prints for the flags `a` (writes `--curve` when
/// asked).
pub fn analytic_json(a: &AnalyticArgs) -> Result<Value> {
    let (c, b1, b2) = collide_args(a)?;
    let mut v = collision_json(&c, &b1, &b2);
    v["warnings"] = json!(collision_warnings(&c));
    Ok(v)
}

/// `twoball analytic`.
pub fn run_analytic(a: AnalyticArgs) -> Result<()> {
    let (c, b1, b2) = collide_args(&a)?;
    let warnings = collision_warnings(&c);
    crate::study::records::warnings::print(&warnings);
    if a.json {
        let mut v = collision_json(&c, &b1, &b2);
        v["warnings"] = json!(warnings);
        println!("{v}");
    } else {
        print_table(&c, &b1, &b2);
        if let Some(path) = &a.curve {
            println!("contact history written to {}", path.display());
        }
    }
    Ok(())
}

fn reading_json(r: &EtaReading, s: &ReadingScore) -> Value {
    json!({
        "label": r.label,
        "v1": [r.v1[0], r.v1[1]],
        "v2": [r.v2[0], r.v2[1]],
        "wall": r.wall,
        "eta": format!("{:?}", r.kind),
        "rows_to_printed_digits": s.exact,
        "rows_within_5_percent": s.loose,
        "median_rel_diff": num(s.median_rel),
    })
}

fn row_json(r: &Table1Row) -> Value {
    json!({
        "material": r.material,
        "zeta": num(r.zeta),
        "zeta_printed": num(r.zeta_printed),
        "zeta_rel_diff": num(r.zeta_rel_diff),
        "zeta_agrees": r.zeta_agrees,
        "eta": num(r.eta),
        "eta_printed": num(r.eta_printed),
        "eta_rel_diff": num(r.eta_rel_diff),
        "eta_agrees": r.eta_agrees,
    })
}

/// Table 1 as computed: the best η reading with its score, the rows, and every reading tried.
type Table1 = (
    EtaReading,
    ReadingScore,
    Vec<Table1Row>,
    Vec<(EtaReading, ReadingScore)>,
);

fn table1_all() -> Result<Table1> {
    let (best, score) = best_reading()?;
    let rows = table1(&best)?;
    let mut readings = vec![];
    for r in candidate_readings() {
        let s = reading_score(&r)?;
        readings.push((r, s));
    }
    Ok((best, score, rows, readings))
}

/// The object `twoball materials --json` prints.
pub fn materials_json() -> Result<Value> {
    let (best, score, rows, readings) = table1_all()?;
    Ok(json!({
        "zeta_definition": "nu E rho (v_n^2 + mu v_t^2) / sigma_s^2 (eq. 44), SI, reported x 1e3 as in Table 1",
        "zeta_scale": ZETA_TABLE_SCALE,
        "zeta_speeds": {"v_n": TABLE1_SPEEDS.0, "v_t": TABLE1_SPEEDS.1},
        "eta_reading": reading_json(&best, &score),
        "rows": rows.iter().map(row_json).collect::<Vec<_>>(),
        "zeta_discrepancies": rows.iter().filter(|r| !r.zeta_agrees).map(|r| r.material.clone()).collect::<Vec<_>>(),
        "eta_not_reproduced": rows.iter().filter(|r| !r.eta_agrees).map(|r| r.material.clone()).collect::<Vec<_>>(),
        "eta_readings": readings.iter().map(|(r, s)| reading_json(r, s)).collect::<Vec<_>>(),
        "presets": PRESET_NAMES.iter().filter_map(|n| Material::preset(n).ok().map(|m| json!({
            "name": n, "E": m.youngs, "nu": m.nu, "rho": m.rho, "yield": m.yield_strength,
            "tangent": m.tangent, "mu": m.mu, "mu_static": m.mu_static,
            "hardening": hardening_text(&m),
            "zeta": num(damping_index(&m, TABLE1_SPEEDS.0, TABLE1_SPEEDS.1)),
        }))).collect::<Vec<_>>(),
    }))
}

/// The hardening of a preset in one line (SI units).
pub fn hardening_text(m: &Material) -> String {
    use crate::material::hardening::Law;
    match m.hardening {
        Some(Law::JohnsonCook(j)) => format!(
            "Johnson-Cook: sigma = (A + B eps_p^n)(1 + C ln(rate/rate0)), A = {:.4e} Pa, B = {:.4e} Pa, n = {}, C = {}, rate0 = {} 1/s",
            j.a, j.b, j.n, j.c, j.rate0
        ),
        Some(other) => format!("{other:?}"),
        None => format!(
            "bilinear: yield {:.4e} Pa, tangent modulus E_t = {:.4e} Pa",
            m.yield_strength, m.tangent
        ),
    }
}

/// Every preset a scene accepts (`material = "NAME"`), with its properties and hardening.
fn print_presets() {
    println!("\nPresets a scene accepts (material = \"NAME\"; SI units):");
    println!(
        "{:<12} {:>11} {:>5} {:>7} {:>11} {:>5}  hardening",
        "name", "E [Pa]", "nu", "rho", "yield [Pa]", "mu"
    );
    for name in PRESET_NAMES {
        if let Ok(m) = Material::preset(name) {
            println!(
                "{:<12} {:>11.4e} {:>5} {:>7} {:>11.4e} {:>5}  {}",
                name,
                m.youngs,
                m.nu,
                m.rho,
                m.yield_strength,
                m.mu,
                hardening_text(&m)
            );
        }
    }
}

/// `twoball materials`.
pub fn run_materials(a: MaterialsArgs) -> Result<()> {
    if a.json {
        println!("{}", materials_json()?);
        return Ok(());
    }
    let (best, score, rows, readings) = table1_all()?;
    println!(
        "Table 1 of Li, Yang & Shi (2019): particle damping index zeta (eq. 44, x 1e3, v_n = {} m/s, \
         v_t = {} m/s) and energy dissipation factor eta",
        TABLE1_SPEEDS.0, TABLE1_SPEEDS.1
    );
    println!(
        "eta reading: {} ({:?}); {} rows to the printed digits, {} within 5 %",
        best.label, best.kind, score.exact, score.loose
    );
    println!(
        "{:<10} {:>10} {:>10} {:>9} {:<5} {:>8} {:>8} {:>9} {:<5}",
        "material", "zeta", "printed", "rel diff", "ok", "eta", "printed", "rel diff", "ok"
    );
    for r in &rows {
        println!(
            "{:<10} {:>10.4} {:>10} {:>+9.4} {:<5} {:>8.4} {:>8.3} {:>+9.4} {:<5}",
            r.material,
            r.zeta,
            r.zeta_printed,
            r.zeta_rel_diff,
            if r.zeta_agrees { "yes" } else { "NO" },
            r.eta,
            r.eta_printed,
            r.eta_rel_diff,
            if r.eta_agrees {
                "yes"
            } else if r.eta_rel_diff.abs() <= crate::analytic::damping_index::ETA_LOOSE_TOLERANCE {
                "~5%"
            } else {
                "NO"
            },
        );
    }
    let bad: Vec<&str> = rows
        .iter()
        .filter(|r| !r.zeta_agrees)
        .map(|r| r.material.as_str())
        .collect();
    println!(
        "zeta: printed values inconsistent with eq. 44 (discrepancies of the paper): {}",
        bad.join(", ")
    );
    println!("ok: yes = agrees to the printed digits, ~5% = within 5 % only, NO = neither");
    print_presets();
    println!("eta readings tried (rows to printed digits / within 5 % / median |rel diff|):");
    for (r, s) in &readings {
        println!(
            "  {:<26} {} / {} / {:.3}",
            r.label, s.exact, s.loose, s.median_rel
        );
    }
    Ok(())
}

/// `twoball parametric`.
pub fn run_parametric(a: ParametricArgs) -> Result<()> {
    std::fs::create_dir_all(&a.out).map_err(|e| Error::io(&a.out, e))?;
    for f in all_figures()? {
        crate::study::report::figures::write(&f, &a.out)?;
        println!(
            "{}: {} curves x {} points -> {}/{}.csv, .svg",
            f.name,
            f.curves.len(),
            f.x.len(),
            a.out.display(),
            f.name
        );
    }
    Ok(())
}
