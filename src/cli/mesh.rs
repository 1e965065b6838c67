//! `twoball mesh ball|check|gmsh`.
//! (Placeholder arguments: the mesh work replaces this file.)

use crate::error::{Error, Result};
use clap::Args;

/// Arguments of `twoball mesh`.
#[derive(Debug, Args)]
pub struct MeshArgs {}

pub fn run(_a: MeshArgs) -> Result<()> {
    Err(Error::External("twoball mesh: not built yet".into()))
}
