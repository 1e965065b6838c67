//! `twoball laws export`: a law with given parameters written as a two-ball DEM deck;
//! `twoball laws dem`: a deck (from `laws fit` or `laws export`) run unedited in its DEM code
//! and compared with `twoball laws run` of the same law and parameters.

use super::law_params::parse_params;
use crate::analytic::laws::{ContactPair, Params, Registry};
use crate::analytic::Body;
use crate::atomic::write_atomic;
use crate::dem::run::{law_outcome, run_deck, tensile};
use crate::dem::{deck, Code, DeckScene};
use crate::error::{Error, Result};
use crate::material::{Material, PRESET_NAMES};
use clap::Args;
use serde_json::{json, Value};
use std::path::{Path, PathBuf};

/// Arguments of `twoball laws export`.
#[derive(Debug, Args)]
pub struct LawExportArgs {
    /// Normal law (see `twoball laws list`).
    #[arg(long)]
    pub law: String,
    /// Override a law parameter, KEY=VALUE in SI units; repeatable.
    #[arg(long = "param", value_name = "KEY=VALUE")]
    pub param: Vec<String>,
    /// DEM code: liggghts, lammps, yade, mercurydpm, or all (every code that can express
    /// the law; the others are listed with the reason).
    #[arg(long, default_value = "all")]
    pub code: String,
    /// Material preset of both balls.
    #[arg(long, default_value = "copper-fe")]
    pub material: String,
    /// Diameter of both balls, m.
    #[arg(long, default_value_t = 0.02)]
    pub diameter: f64,
    /// Reference relative approach speed, m/s (the deck's default).
    #[arg(long, default_value_t = 1.0)]
    pub speed: f64,
    /// Lowest speed the deck's run length is sized for, m/s [default: speed/2].
    #[arg(long)]
    pub vmin: Option<f64>,
    /// Highest speed the deck's time step is sized for, m/s [default: 2 speed].
    #[arg(long)]
    pub vmax: Option<f64>,
    /// Output directory (created if missing): the deck(s) and law.json.
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
}

/// Arguments of `twoball laws dem`.
#[derive(Debug, Args)]
pub struct LawDemArgs {
    /// Folder written by `twoball laws fit` (fit.json) or `twoball laws export` (law.json),
    /// holding the deck; the code's trace.txt is written there.
    #[arg(long, value_name = "DIR")]
    pub dir: PathBuf,
    /// DEM code: liggghts, lammps or yade (MercuryDPM decks are not run here).
    #[arg(long)]
    pub code: String,
    /// Relative approach speed, m/s [default: the deck's reference speed].
    #[arg(long)]
    pub speed: Option<f64>,
    /// Print one JSON object.
    #[arg(long)]
    pub json: bool,
}

/// The material preset `name`, or the error naming `--material`.
fn preset(name: &str) -> Result<Material> {
    Material::preset(name).map_err(|_| {
        Error::invalid(
            "--material",
            name,
            format!("one of {}", PRESET_NAMES.join(", ")),
        )
    })
}

/// The law.json object of a law with parameters, read back by `laws dem`.
fn law_json(law: &str, params: &Params, material: &str, diameter: f64, speed: f64) -> Value {
    json!({
        "law": law,
        "material": material,
        "diameter": diameter,
        "reference_speed": speed,
        "params": params.iter().map(|(k, v)| (k.to_string(), json!(v))).collect::<serde_json::Map<_, _>>(),
    })
}

/// `twoball laws export` against `registry`.
pub fn export(a: LawExportArgs, registry: &Registry) -> Result<()> {
    let spec = *registry.normal(&a.law)?;
    let m = preset(&a.material)?;
    if !(a.diameter.is_finite() && a.diameter > 0.0) {
        return Err(Error::invalid("--diameter", a.diameter, "> 0 m, finite"));
    }
    if !(a.speed.is_finite() && a.speed > 0.0) {
        return Err(Error::invalid("--speed", a.speed, "> 0 m/s, finite"));
    }
    let b = Body::ball(m, a.diameter, "ball")?;
    let pair = ContactPair::between(&b, &b, m.mu);
    let params = Params::resolve(
        spec.name,
        spec.params,
        &parse_params("--param", &a.param)?,
        &pair,
    )?;
    let range = (
        a.vmin.unwrap_or(a.speed / 2.0),
        a.vmax.unwrap_or(a.speed * 2.0),
    );
    let scene = DeckScene::new(
        &spec,
        &params,
        &m,
        a.diameter,
        a.speed,
        range,
        "given to `twoball laws export`",
    )?;
    let codes: Vec<Code> = if a.code == "all" {
        Code::ALL.to_vec()
    } else {
        vec![Code::parse(&a.code)?]
    };
    let mut written = Vec::new();
    let mut refused = Vec::new();
    for code in &codes {
        match deck(*code, spec.name, &params, &scene) {
            Ok(text) => written.push((*code, text)),
            Err(e) if codes.len() > 1 => refused.push(e.to_string()),
            Err(e) => return Err(e),
        }
    }
    std::fs::create_dir_all(&a.out).map_err(|e| Error::io(&a.out, e))?;
    for (code, text) in &written {
        write_atomic(a.out.join(code.file()), text.as_bytes())?;
        println!("wrote {}", a.out.join(code.file()).display());
    }
    let j = law_json(spec.name, &params, &a.material, a.diameter, a.speed);
    write_atomic(
        a.out.join("law.json"),
        serde_json::to_string_pretty(&j)
            .map_err(|e| Error::Parse(e.to_string()))?
            .as_bytes(),
    )?;
    for r in &refused {
        println!("no deck: {r}");
    }
    Ok(())
}

/// What a deck folder was written for (fit.json of `laws fit`, or law.json of `laws export`).
struct Setting {
    /// The normal law's name.
    law: String,
    /// Its parameters by name, in their SI units.
    params: Vec<(String, f64)>,
    /// The material preset.
    material: String,
    /// Ball diameter, m.
    diameter: f64,
    /// Reference speed, m/s.
    speed: f64,
}

/// The [`Setting`] of the deck folder `dir`.
fn read_setting(dir: &Path) -> Result<Setting> {
    let path = [dir.join("fit.json"), dir.join("law.json")]
        .into_iter()
        .find(|p| p.exists())
        .ok_or_else(|| {
            Error::invalid(
                "--dir",
                dir.display(),
                "a folder written by `twoball laws fit` or `twoball laws export` (fit.json or law.json)",
            )
        })?;
    let text = std::fs::read_to_string(&path).map_err(|e| Error::io(&path, e))?;
    let v: Value = serde_json::from_str(&text)
        .map_err(|e| Error::Parse(format!("{}: {e}", path.display())))?;
    let field = |k: &str| Error::Parse(format!("{}: missing or wrong key {k}", path.display()));
    let law = v["law"].as_str().ok_or_else(|| field("law"))?.to_string();
    let material = v["material"]
        .as_str()
        .ok_or_else(|| field("material"))?
        .to_string();
    let diameter = v["diameter"].as_f64().ok_or_else(|| field("diameter"))?;
    let speed = v["reference_speed"]
        .as_f64()
        .ok_or_else(|| field("reference_speed"))?;
    let params = v["params"]
        .as_object()
        .ok_or_else(|| field("params"))?
        .iter()
        .map(|(k, x)| x.as_f64().map(|x| (k.clone(), x)).ok_or_else(|| field(k)))
        .collect::<Result<Vec<_>>>()?;
    Ok(Setting {
        law,
        params,
        material,
        diameter,
        speed,
    })
}

/// `twoball laws dem` against `registry`.
pub fn dem(a: LawDemArgs, registry: &Registry) -> Result<()> {
    let code = Code::parse(&a.code)?;
    let Setting {
        law,
        params: over,
        material,
        diameter,
        speed: reference,
    } = read_setting(&a.dir)?;
    let spec = *registry.normal(&law)?;
    let m = preset(&material)?;
    let b = Body::ball(m, diameter, "ball")?;
    let pair = ContactPair::between(&b, &b, m.mu);
    let params = Params::resolve(spec.name, spec.params, &over, &pair)?;
    let speed = a.speed.unwrap_or(reference);
    if !(speed.is_finite() && speed > 0.0) {
        return Err(Error::invalid("--speed", speed, "> 0 m/s, finite"));
    }
    if !a.dir.join(code.file()).exists() {
        return Err(Error::invalid(
            "--code",
            code.name(),
            format!(
                "a code with a deck in {} (laws fit or laws export said why a code has none)",
                a.dir.display()
            ),
        ));
    }
    let dem = run_deck(code, &a.dir, diameter, speed, tensile(&spec, &params))?;
    let own = law_outcome(&spec, &params, &m, diameter, speed)?;
    let rel = |x: f64, y: f64| (x - y) / y;
    if a.json {
        println!(
            "{}",
            json!({
                "law": law, "code": code.name(), "v_r": speed,
                "e_dem": dem.e, "e_twoball": own.e, "e_rel_diff": rel(dem.e, own.e),
                "delta_max_dem": dem.delta_max, "delta_max_twoball": own.delta_max,
                "delta_max_rel_diff": rel(dem.delta_max, own.delta_max),
                "contact_duration_dem": dem.contact_duration, "contact_duration_twoball": own.contact_duration,
                "contact_duration_rel_diff": rel(dem.contact_duration, own.contact_duration),
            })
        );
    } else {
        println!(
            "{law} in {} at v_r = {speed} m/s (DEM vs twoball laws run):",
            code.name()
        );
        println!(
            "  e          {:.6} vs {:.6} ({:+.2e})",
            dem.e,
            own.e,
            rel(dem.e, own.e)
        );
        println!(
            "  delta_max  {:.6e} vs {:.6e} m ({:+.2e})",
            dem.delta_max,
            own.delta_max,
            rel(dem.delta_max, own.delta_max)
        );
        println!(
            "  t_c        {:.6e} vs {:.6e} s ({:+.2e})",
            dem.contact_duration,
            own.contact_duration,
            rel(dem.contact_duration, own.contact_duration)
        );
    }
    Ok(())
}
