//! `twoball damper SCENE --out DIR [--to FOLDER]`: the particle-damper cases of a scene file,
//! in parallel, with their report; flags override the laws, friction, frame mass, box and
//! duration of every case.

use super::law_params::parse_params;
use crate::analytic::laws::Registry;
use crate::damper::file::{read, Overrides};
use crate::damper::report::{write_report, ReportInput};
use crate::damper::run::write_outputs;
use crate::error::{Error, Result};
use crate::study::common::progress::Mode;
use crate::study::report::damper_plots::{write_plots, write_windows_chart};
use crate::study::run::damper::run_cases_with_progress;
use clap::Args;
use std::path::PathBuf;

/// Arguments of `twoball damper`.
#[derive(Debug, Args)]
pub struct DamperArgs {
    /// Damper scene file (TOML), e.g. verification/damper/table2.toml.
    pub scene: PathBuf,
    /// Output folder: summary.csv, REPORT.md, windows.csv, windows.svg and per case
    /// CASE/history.csv, CASE/cycles.csv and charts.
    #[arg(long)]
    pub out: PathBuf,
    /// Write REPORT.md, windows.csv and windows.svg into this folder instead, with its
    /// NOTES.md appended to REPORT.md (the committed one: --to verification/damper).
    #[arg(long)]
    pub to: Option<PathBuf>,
    /// Width of the consecutive windows of windows.csv and windows.svg, s.
    #[arg(long, default_value_t = 2.0)]
    pub window_width: f64,
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

/// The command that reproduces a run of `a`, with `--out DIR` (and without `--to`).
pub fn command_line(a: &DamperArgs) -> String {
    let mut c = format!("twoball damper {} --out DIR", a.scene.display());
    let mut flag = |name: &str, value: &dyn std::fmt::Display| {
        c.push_str(&format!(" --{name} {value}"));
    };
    for name in &a.case {
        flag("case", name);
    }
    if let Some(v) = &a.law {
        flag("law", v);
    }
    for v in &a.param {
        flag("param", v);
    }
    if let Some(v) = &a.tangential {
        flag("tangential", v);
    }
    for v in &a.tparam {
        flag("tparam", v);
    }
    if let Some(v) = a.mu_ball {
        flag("mu-ball", &v);
    }
    if let Some(v) = a.mu_wall {
        flag("mu-wall", &v);
    }
    if let Some(v) = a.frame_mass {
        flag("frame-mass", &v);
    }
    if let Some(v) = &a.r#box {
        flag("box", v);
    }
    if let Some(v) = &a.diameter {
        flag("diameter", v);
    }
    if let Some(v) = a.duration {
        flag("duration", &v);
    }
    if a.window_width != 2.0 {
        flag("window-width", &a.window_width);
    }
    c
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
    if !(a.window_width.is_finite() && a.window_width > 0.0) {
        return Err(Error::invalid(
            "--window-width",
            a.window_width,
            "a width > 0 s (windows longer than the run are left out)",
        ));
    }
    let claims = file.claims()?;
    let to = a.to.clone().unwrap_or_else(|| a.out.clone());
    let notes = match &a.to {
        Some(dir) => match std::fs::read_to_string(dir.join("NOTES.md")) {
            Ok(t) => Some(t),
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => None,
            Err(e) => return Err(Error::io(dir.join("NOTES.md"), e)),
        },
        None => None,
    };
    let outcomes = run_cases_with_progress(&cases, &Registry::builtin(), Mode::detect(true))?;
    write_outputs(&a.out, &outcomes)?;
    write_plots(&a.out, &outcomes)?;
    let command = command_line(&a);
    write_report(
        &to,
        &ReportInput {
            command: &command,
            outcomes: &outcomes,
            claims: &claims,
            width: a.window_width,
            notes: notes.as_deref(),
        },
    )?;
    write_windows_chart(&to, &outcomes, a.window_width)?;
    println!(
        "{:<14} {:>9} {:>9} {:>11} {:>11} {:>11} {:>11} {:>9} {:>8}",
        "case",
        "f [Hz]",
        "f_meas",
        "zeta [%]",
        "zeta_meas",
        "added [%]",
        "added_meas",
        "residual",
        "wall [s]"
    );
    let cell = |x: Option<f64>, digits: usize| {
        x.map_or("-".to_string(), |x| format!("{:.digits$}", 100.0 * x))
    };
    for o in &outcomes {
        println!(
            "{:<14} {:>9.4} {:>9} {:>11.4} {:>11} {:>11.4} {:>11} {:>9.1e} {:>8.1}",
            o.name,
            o.decay.frequency,
            o.measured
                .map_or("-".to_string(), |m| format!("{:.2}", m.frequency)),
            100.0 * o.decay.ratio,
            cell(o.measured.map(|m| m.damping_ratio), 2),
            100.0 * o.added_damping(),
            cell(o.measured_added_damping(), 2),
            o.worst_residual,
            o.wall_time
        );
    }
    println!(
        "wrote {} and {}",
        a.out.join("summary.csv").display(),
        to.join("REPORT.md").display()
    );
    Ok(())
}
