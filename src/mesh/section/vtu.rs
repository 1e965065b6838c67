//! ParaView output of a meridian section: the quads in the plane z = 0 with x = r and y = z
//! (the usual picture of an axisymmetric model), in the format of [`crate::mesh::vtu`].
//!
//! Fields are given in the section's cylindrical components and written as VTK vectors and
//! symmetric tensors in that picture: a vector (v_r, v_z) becomes (v_r, v_z, 0), a stress
//! (σ_rr, σ_zz, σ_θθ, σ_rz) becomes xx = σ_rr, yy = σ_zz, zz = σ_θθ (the hoop component,
//! normal to the section), xy = σ_rz, yz = zx = 0.

use super::geometry::SectionMesh;
use crate::atomic::write_atomic;
use crate::error::Result;
use crate::mesh::vtu::{grid_bytes, Field, Grid, VtuFormat};
use std::path::Path;

/// A named field of a meridian section, one entry per node or per quad.
#[derive(Debug, Clone, Copy)]
pub enum SectionField<'a> {
    /// A scalar (e.g. equivalent plastic strain, dimensionless).
    Scalars(&'a str, &'a [f64]),
    /// A vector (v_r, v_z) (e.g. displacement in m, velocity in m/s).
    Vectors(&'a str, &'a [[f64; 2]]),
    /// A symmetric axisymmetric tensor (rr, zz, θθ, rz) (e.g. Cauchy stress in Pa).
    Tensors(&'a str, &'a [[f64; 4]]),
}

/// A field converted to the writer's components (owned, so that the writer can borrow it).
enum Converted<'a> {
    Scalars(&'a str, &'a [f64]),
    Vectors(&'a str, Vec<[f64; 3]>),
    Tensors(&'a str, Vec<[f64; 6]>),
}

impl<'a> SectionField<'a> {
    fn convert(&self) -> Converted<'a> {
        match *self {
            SectionField::Scalars(n, v) => Converted::Scalars(n, v),
            SectionField::Vectors(n, v) => {
                Converted::Vectors(n, v.iter().map(|a| [a[0], a[1], 0.0]).collect())
            }
            SectionField::Tensors(n, v) => Converted::Tensors(
                n,
                v.iter()
                    .map(|s| [s[0], s[1], s[2], s[3], 0.0, 0.0])
                    .collect(),
            ),
        }
    }
}

impl Converted<'_> {
    fn field(&self) -> Field<'_> {
        match self {
            Converted::Scalars(n, v) => Field::scalars(n, v),
            Converted::Vectors(n, v) => Field::vectors(n, v),
            Converted::Tensors(n, v) => Field::sym_tensors(n, v),
        }
    }
}

/// The section and its fields as a `.vtu` file (VTK_QUAD cells) in `format`, with the data
/// set's time `time` (s) when given. Fails, writing nothing, as [`crate::mesh::vtu::to_vtu_bytes`]
/// does: a field of the wrong length (per node for `point_fields`, per quad for
/// `cell_fields`), a bad name, or a non-finite value, node or time.
pub fn to_vtu_bytes(
    section: &SectionMesh,
    point_fields: &[SectionField],
    cell_fields: &[SectionField],
    time: Option<f64>,
    format: VtuFormat,
) -> Result<Vec<u8>> {
    let points: Vec<[f64; 3]> = section.nodes.iter().map(|p| [p[0], p[1], 0.0]).collect();
    let grid = Grid {
        points: &points,
        connectivity: section.quads.iter().flatten().map(|&n| n as i64).collect(),
        per_cell: 4,
        cell_type: 9,
    };
    let pc: Vec<Converted> = point_fields.iter().map(SectionField::convert).collect();
    let cc: Vec<Converted> = cell_fields.iter().map(SectionField::convert).collect();
    let pf: Vec<Field> = pc.iter().map(Converted::field).collect();
    let cf: Vec<Field> = cc.iter().map(Converted::field).collect();
    grid_bytes(&grid, &pf, &cf, time, format)
}

/// Writes the section with its fields to a binary `.vtu` file at `path`, atomically.
///
/// Errors: see [`to_vtu_bytes`]; I/O errors name the path.
pub fn write(
    path: impl AsRef<Path>,
    section: &SectionMesh,
    point_fields: &[SectionField],
    cell_fields: &[SectionField],
    time: Option<f64>,
) -> Result<()> {
    write_atomic(
        path,
        &to_vtu_bytes(section, point_fields, cell_fields, time, VtuFormat::Binary)?,
    )
}
