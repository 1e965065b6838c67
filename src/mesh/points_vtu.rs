//! ParaView output of spheres as points: one VTK_VERTEX cell per sphere, with its radius and
//! velocity as point fields (ParaView draws them with the Point Gaussian representation,
//! scale array `radius`), in the format of [`super::vtu`].

use super::vtu::{grid_bytes, Field, Grid, VtuFormat};
use crate::error::Result;

/// The spheres centred at `centres` (m) with radii `radius` (m) and velocities `velocity`
/// (m/s) as a `.vtu` file's bytes, with the data set's time `time` (s).
///
/// Errors: fields of another length than `centres`, or a non-finite value (nothing is
/// produced), as [`super::vtu::to_vtu_bytes`].
pub fn spheres_vtu_bytes(
    centres: &[[f64; 3]],
    radius: &[f64],
    velocity: &[[f64; 3]],
    time: f64,
    format: VtuFormat,
) -> Result<Vec<u8>> {
    let grid = Grid {
        points: centres,
        connectivity: (0..centres.len() as i64).collect(),
        per_cell: 1,
        cell_type: 1,
    };
    grid_bytes(
        &grid,
        &[
            Field::scalars("radius", radius),
            Field::vectors("velocity", velocity),
        ],
        &[],
        Some(time),
        format,
    )
}
