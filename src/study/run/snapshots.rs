//! `.vtu` snapshots of a run for ParaView: the simulated model (a quarter, a half or both
//! balls, in the contact frame: x along the line of centres, y the tangential direction) with
//! displacement and velocity at the nodes and stress, von Mises stress and equivalent plastic
//! strain in the elements, plus a `.pvd` collection that plays them as a time series.
//!
//! Snapshot times are spread evenly over the analytical contact duration from first touch
//! (the window where the fields change); the state at the end of the run is always written
//! as the last snapshot. Each file is written atomically and the collection is rewritten
//! after every snapshot. Each snapshot stores its time since first touch (s) as `TimeValue`,
//! and the collection lists the same time per file. Files are compressed binary unless ASCII
//! is asked for.

use crate::atomic::write_atomic;
use crate::error::Result;
use crate::fe::section::solver::SectionSolver;
use crate::fe::{explicit::Solver, tensor::von_mises};
use crate::mesh::section::vtu::{to_vtu_bytes, SectionField};
use crate::mesh::section::SectionMesh;
use crate::mesh::{vtu, Mesh};
use std::path::{Path, PathBuf};

/// The snapshot plan of one run and what has been written so far.
#[derive(Debug)]
pub struct Snapshots {
    dir: PathBuf,
    /// Model time of snapshot k (s, solver clock), ascending.
    times: Vec<f64>,
    /// Written so far: (time since first touch in s, file name).
    written: Vec<(f64, String)>,
    /// File format.
    format: vtu::VtuFormat,
}

impl Snapshots {
    /// `count` snapshots (≥ 1) into `dir` over `[start, start + window]` of the solver clock
    /// (s); the last one is taken at the end of the run whatever its time.
    pub fn new(dir: PathBuf, count: u32, start: f64, window: f64) -> Self {
        let n = count.max(1) as usize;
        let times = (0..n.saturating_sub(1))
            .map(|k| start + window * k as f64 / (n - 1).max(1) as f64)
            .collect();
        Snapshots {
            dir,
            times,
            written: Vec::new(),
            format: vtu::VtuFormat::Binary,
        }
    }

    /// The same plan writing ASCII files when `ascii` (compressed binary otherwise).
    pub fn ascii(mut self, ascii: bool) -> Self {
        self.format = if ascii {
            vtu::VtuFormat::Ascii
        } else {
            vtu::VtuFormat::Binary
        };
        self
    }

    /// Writes a snapshot if the solver clock has reached the next planned time; `t0` is the
    /// time of first touch on the solver clock (s), used for the time written in the series.
    pub fn maybe_write(&mut self, solver: &Solver, t0: f64) -> Result<()> {
        let k = self.written.len();
        if k < self.times.len() && solver.time() >= self.times[k] {
            self.write(solver, t0)?;
        }
        Ok(())
    }

    /// Writes the final state (always the last snapshot of the series).
    pub fn finish(&mut self, solver: &Solver, t0: f64) -> Result<()> {
        self.write(solver, t0)
    }

    fn write(&mut self, solver: &Solver, t0: f64) -> Result<()> {
        self.write_with(solver.time() - t0, |path, time, format| {
            write_state(path, solver, time, format)
        })
    }

    /// Writes a snapshot of the meridian-section run `solver` if its clock (s since first
    /// touch) has reached the next planned time, or always when `last` (the end of the run).
    pub fn maybe_write_section(&mut self, solver: &SectionSolver, last: bool) -> Result<()> {
        let k = self.written.len();
        if last || (k < self.times.len() && solver.time() >= self.times[k]) {
            self.write_with(solver.time(), |path, time, format| {
                write_section_state(path, solver, time, format)
            })?;
        }
        Ok(())
    }

    /// The next file, written by `write(path, time, format)`, and the collection after it.
    fn write_with(
        &mut self,
        time: f64,
        write: impl FnOnce(&Path, f64, vtu::VtuFormat) -> Result<()>,
    ) -> Result<()> {
        let name = format!("snapshot_{:04}.vtu", self.written.len());
        write(&self.dir.join(&name), time, self.format)?;
        self.written.push((time, name));
        vtu::write_pvd(self.dir.join("snapshots.pvd"), &self.written)
    }

    /// Files written so far.
    pub fn count(&self) -> usize {
        self.written.len()
    }
}

/// Writes the solver's current state as one `.vtu` file: deformed coordinates (m); point
/// fields `displacement` (m) and `velocity` (m/s); cell fields `stress` (Pa, symmetric
/// tensor, components xx yy zz xy yz zx), `von_mises` (Pa), `plastic_strain` (-) and `part`
/// (0-based part index); `time` (s since first touch) as the field `TimeValue`; in `format`.
/// Everything is in the simulated model's frame (see [`crate::study::run::simulate`]).
///
/// Errors: a non-finite value anywhere (nothing is written), I/O errors naming the path.
pub fn write_state(
    path: &std::path::Path,
    solver: &Solver,
    time: f64,
    format: vtu::VtuFormat,
) -> Result<()> {
    let model = solver.model();
    let x = solver.x();
    let mesh = Mesh {
        nodes: x.to_vec(),
        hexes: model.hexes.clone(),
        ..Default::default()
    };
    let displacement: Vec<[f64; 3]> = x
        .iter()
        .zip(&model.nodes)
        .map(|(a, b)| [a[0] - b[0], a[1] - b[1], a[2] - b[2]])
        .collect();
    let ne = model.hexes.len();
    let stress: Vec<[f64; 6]> = (0..ne).map(|e| solver.element_stress(e)).collect();
    let mises: Vec<f64> = stress.iter().map(von_mises).collect();
    let eps_p: Vec<f64> = (0..ne).map(|e| solver.element_plastic_strain(e)).collect();
    let mut part = vec![0.0; ne];
    for (p, pt) in model.parts.iter().enumerate() {
        for e in pt.elements.clone() {
            part[e] = p as f64;
        }
    }
    vtu::write_with(
        path,
        &mesh,
        &[
            vtu::Field::vectors("displacement", &displacement),
            vtu::Field::vectors("velocity", solver.v()),
        ],
        &[
            vtu::Field::sym_tensors("stress", &stress),
            vtu::Field::scalars("von_mises", &mises),
            vtu::Field::scalars("plastic_strain", &eps_p),
            vtu::Field::scalars("part", &part),
        ],
        Some(time),
        format,
    )
}

/// Writes the meridian-section run's current state as one `.vtu` file, the section drawn in
/// the plane with x = r and y = z ([`crate::mesh::section::vtu`]): deformed coordinates (m);
/// point fields `displacement` (m) and `velocity` (m/s), components (r, z, 0); cell fields
/// `stress` (Pa; xx = rr, yy = zz, zz = θθ hoop, xy = rz), `von_mises` (Pa),
/// `plastic_strain` (-) of each quad's first integration point; `time` (s since first touch)
/// as `TimeValue`; in `format`.
///
/// Errors: a non-finite value anywhere (nothing is written), I/O errors naming the path.
pub fn write_section_state(
    path: &Path,
    solver: &SectionSolver,
    time: f64,
    format: vtu::VtuFormat,
) -> Result<()> {
    let x = solver.positions();
    let section = SectionMesh {
        nodes: x.to_vec(),
        quads: solver.quads().to_vec(),
        ..Default::default()
    };
    let displacement: Vec<[f64; 2]> = x
        .iter()
        .zip(solver.initial_positions())
        .map(|(a, b)| [a[0] - b[0], a[1] - b[1]])
        .collect();
    let points = solver.states().iter().map(|q| q.points[0]);
    let stress: Vec<[f64; 4]> = points
        .clone()
        .map(|p| [p.stress[0], p.stress[1], p.stress[2], p.stress[3]])
        .collect();
    let mises: Vec<f64> = points.clone().map(|p| von_mises(&p.stress)).collect();
    let eps_p: Vec<f64> = points.map(|p| p.eps_p).collect();
    let bytes = to_vtu_bytes(
        &section,
        &[
            SectionField::Vectors("displacement", &displacement),
            SectionField::Vectors("velocity", solver.velocities()),
        ],
        &[
            SectionField::Tensors("stress", &stress),
            SectionField::Scalars("von_mises", &mises),
            SectionField::Scalars("plastic_strain", &eps_p),
        ],
        Some(time),
        format,
    )?;
    write_atomic(path, &bytes)
}
