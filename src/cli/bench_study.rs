//! `twoball bench study`: run time against error on a ladder of meshes, element formulations
//! and time-step factors (the logic is in `study::bench`).

use crate::error::{Error, Result};
use crate::scene::{Formulation, DEFAULT_SCENE};
use crate::study::bench::{run_settings, write_outputs, Ladder};
use clap::Args;
use std::path::{Path, PathBuf};

/// Arguments of `twoball bench study`.
#[derive(Debug, Args)]
pub struct StudyArgs {
    /// Scene file (TOML); default: the built-in default scene (the paper's Figure 8 case).
    pub scene: Option<PathBuf>,
    /// Output folder: bench-study.csv/.md/.svg and cases/ (finished runs, reused on rerun).
    #[arg(long)]
    pub out: PathBuf,
    /// Mesh densities m (bulk size D/(10 m), pole size D/(100 m)), ascending; the three
    /// finest must be in a constant ratio (Richardson).
    #[arg(long, value_delimiter = ',', default_values_t = [0.5, std::f64::consts::FRAC_1_SQRT_2, 1.0, std::f64::consts::SQRT_2, 2.0])]
    pub densities: Vec<f64>,
    /// Element formulations run on every density: one-point, b-bar.
    #[arg(long, value_delimiter = ',', default_values_t = ["one-point".to_string(), "b-bar".to_string()])]
    pub elements: Vec<String>,
    /// Extra time-step factors run on the middle density with the first formulation.
    #[arg(long, value_delimiter = ',', default_values_t = [0.6, 0.3])]
    pub time_step_factors: Vec<f64>,
    /// Time-step factor of the mesh ladder.
    #[arg(long, default_value_t = 0.9)]
    pub time_step_factor: f64,
    /// Extra pole refinements k (pole size D/(100 m k)) run on the middle density with the
    /// first formulation; an empty value runs none.
    #[arg(long, value_delimiter = ',', default_values_t = [2.0, 4.0])]
    pub pole_refinements: Vec<f64>,
}

/// Runs `twoball bench study`.
pub fn run(a: StudyArgs) -> Result<()> {
    let elements = a
        .elements
        .iter()
        .map(|e| {
            Formulation::from_name(e)
                .ok_or_else(|| Error::invalid("--elements", e, Formulation::NAMES.join(", ")))
        })
        .collect::<Result<Vec<_>>>()?;
    let ladder = Ladder {
        densities: a.densities,
        elements,
        time_step_factors: a.time_step_factors,
        base_factor: a.time_step_factor,
        pole_refinements: a.pole_refinements,
    }
    .validated()?;
    let (toml, dir) = match &a.scene {
        Some(p) => (
            std::fs::read_to_string(p).map_err(|e| crate::error::Error::io(p, e))?,
            p.parent().unwrap_or(Path::new(".")).to_path_buf(),
        ),
        None => (DEFAULT_SCENE.to_string(), PathBuf::from(".")),
    };
    println!("# twoball bench study: {} runs", ladder.settings().len());
    let runs = run_settings(&toml, &dir, &ladder, &a.out, |m, reused| {
        println!(
            "{:<28} {:>7} elements {:>8.2} s  e = {:.6}{}",
            m.setting.label(),
            m.elements,
            m.wall_time_s,
            m.e,
            if reused { " (reused)" } else { "" }
        );
    })?;
    let md = write_outputs(&runs, &ladder, &a.out)?;
    println!("\n{md}");
    println!("wrote {}/bench-study.csv, .md, .svg", a.out.display());
    Ok(())
}
