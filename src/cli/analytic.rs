//! `twoball analytic`, `twoball materials`, `twoball parametric`.
//! (Placeholder arguments: the analytical-model work replaces this file.)

use crate::error::{Error, Result};
use clap::Args;

/// Arguments of `twoball analytic`.
#[derive(Debug, Args)]
pub struct AnalyticArgs {}

/// Arguments of `twoball materials`.
#[derive(Debug, Args)]
pub struct MaterialsArgs {}

/// Arguments of `twoball parametric`.
#[derive(Debug, Args)]
pub struct ParametricArgs {}

pub fn run_analytic(_a: AnalyticArgs) -> Result<()> {
    Err(Error::External("twoball analytic: not built yet".into()))
}

pub fn run_materials(_a: MaterialsArgs) -> Result<()> {
    Err(Error::External("twoball materials: not built yet".into()))
}

pub fn run_parametric(_a: ParametricArgs) -> Result<()> {
    Err(Error::External("twoball parametric: not built yet".into()))
}
