//! `twoball damper SCENE --out DIR`: the particle-damper cases of a scene file, in parallel;
//! flags override the laws, friction, frame mass, box and duration of every case.

use super::laws::parse_params;
use crate::analytic::laws::Registry;
use crate::damper::file::{read, Overrides};
use crate::damper::run::{run_cases, write_outputs};
use crate::error::{Error, Result};
use clap::Args;
use std::path::PathBuf;

/// Arguments of `twoball damper`.
#[derive(Debug, Args)]
pub struct DamperArgs {
    /// Damper scene file (TOML), e.g. verification/damper/table2.toml.
    pub scene: PathBuf,
    /// Output folder: summary.csv and CASE/history.csv, CASE/cycles.csv.
    #[arg(long)]
    pub out: PathBuf,
    /// Run only this case (repeatable); default every case.
    #[arg(long = "case")]
    pub case: Vec<String>,
    /// Normal contact law for every contact (drops the file's normal parameters).
    #[arg(long)]
    pub law: Option<String>,
    /// Normal-law parameter KEY=VALUE (SI); repeatable.
    #[arg(long = "param", value_name = "KEY=VALUE")]
    pub param: Vec<String>,
    /// Tangential contact law (drops the file's tangential parameters).
    #[arg(long)]
    pub tangential: Option<String>,
    /// Tangential-law parameter KEY=VALUE; repeatable.
    #[arg(long = "tparam", value_name = "KEY=VALUE")]
    pub tparam: Vec<String>,
    /// Ball-ball friction coefficient.
    #[arg(long)]
    pub mu_ball: Option<f64>,
    /// Ball-wall friction coefficient.
    #[arg(long)]
    pub mu_wall: Option<f64>,
    /// Frame mass, kg.
    #[arg(long)]
    pub frame_mass: Option<f64>,
    /// Box inner size X,Y,Z in m.
    #[arg(long, value_name = "X,Y,Z")]
    pub r#box: Option<String>,
    /// Diameter of the balls of one material, MATERIAL=D in m (e.g. glass=0.016).
    #[arg(long, value_name = "MATERIAL=D")]
    pub diameter: Option<String>,
    /// Simulated time, s.
    #[arg(long)]
    pub duration: Option<f64>,
}

fn box_size(text: &str) -> Result<[f64; 3]> {
    let v: Vec<f64> = text
        .split(',')
        .map(|s| s.trim().parse::<f64>())
        .collect::<std::result::Result<_, _>>()
        .map_err(|_| Error::invalid("--box", text, "three sizes in m, X,Y,Z"))?;
    <[f64; 3]>::try_from(v).map_err(|_| Error::invalid("--box", text, "three sizes in m, X,Y,Z"))
}

/// Runs `twoball damper`.
pub fn run(a: DamperArgs) -> Result<()> {
    let file = read(&a.scene)?;
    let diameter = match &a.diameter {
        None => None,
        Some(t) => {
            let (m, d) = t
                .split_once('=')
                .ok_or_else(|| Error::invalid("--diameter", t, "MATERIAL=D (m)"))?;
            let d: f64 = d
                .parse()
                .map_err(|_| Error::invalid("--diameter", t, "MATERIAL=D (m)"))?;
            Some((m.to_string(), d))
        }
    };
    let overrides = Overrides {
        normal: a.law.clone(),
        normal_params: parse_params("--param", &a.param)?,
        tangential: a.tangential.clone(),
        tangential_params: parse_params("--tparam", &a.tparam)?,
        mu_ball: a.mu_ball,
        mu_wall: a.mu_wall,
        frame_mass: a.frame_mass,
        box_size: a.r#box.as_deref().map(box_size).transpose()?,
        duration: a.duration,
        diameter,
    };
    let mut cases = file.cases(&overrides)?;
    if !a.case.is_empty() {
        for name in &a.case {
            if !cases.iter().any(|c| &c.name == name) {
                let names: Vec<&str> = cases.iter().map(|c| c.name.as_str()).collect();
                return Err(Error::invalid(
                    "--case",
                    name,
                    format!("one of {}", names.join(", ")),
                ));
            }
        }
        cases.retain(|c| a.case.contains(&c.name));
    }
    let outcomes = run_cases(&cases, &Registry::builtin())?;
    write_outputs(&a.out, &outcomes)?;
    crate::study::report::damper_plots::write_plots(&a.out, &outcomes)?;
    println!(
        "{:<14} {:>9} {:>9} {:>11} {:>11} {:>9} {:>8}",
        "case", "f [Hz]", "f_meas", "zeta [%]", "zeta_meas", "residual", "wall [s]"
    );
    for o in &outcomes {
        let (mf, mz) = o.measured.map_or((f64::NAN, f64::NAN), |m| {
            (m.frequency, 100.0 * m.damping_ratio)
        });
        println!(
            "{:<14} {:>9.4} {:>9.2} {:>11.4} {:>11.2} {:>9.1e} {:>8.1}",
            o.name,
            o.decay.frequency,
            mf,
            100.0 * o.decay.ratio,
            mz,
            o.worst_residual,
            o.wall_time
        );
    }
    println!("wrote {}", a.out.join("summary.csv").display());
    Ok(())
}
