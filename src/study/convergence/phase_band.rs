//! The banded mesh family of a head-on impact: the ladder with an edge band of finer surface
//! rings at the contact edge ([`crate::mesh::section::band`]).
//!
//! A section run's plastic e is a sawtooth over the ring spacing at the contact edge
//! ([`crate::study::convergence::phase_ensemble`]). The band splits that spacing alone, which shrinks the
//! sawtooth for a fraction of the cost of refining the whole mesh: on the default scene (two
//! D = 20 mm copper-fe balls, ±1 m/s) the standard deviation of e over eleven meshes of
//! level 0 falls from 1.9 % to 0.35 % with a four-fold band, at 4.5 times the run's cost,
//! where level 1 (seven times the cost) leaves 0.95 % (verification/contact-penalty.md, "An edge
//! band of finer rings"). An odd split confines the band's shells to a sixth of the rays below
//! the surface ([`crate::mesh::section::band::SURFACE_DEPTH`]), which the bench's five-fold
//! band uses: the same answers at about half the cost.
//!
//! The band needs the edge: [`contact_edge`] runs the plain family's level 0 once and takes
//! the midpoint between the outermost ring in contact and the next. The banded family is
//! then the ladder sized from [`SIZING_PER_EDGE`] edges (so that the band lies in the
//! layers, outside the refined core), with the band [0.8, 1.15] edges split `split`-fold on
//! every level. Its levels are the ladder's (0, 1, …): a banded plan's fine level is ≥ 1.

use crate::error::Result;
pub use crate::mesh::section::band::check_split;
use crate::mesh::section::{ladder_ball_banded, EdgeBand, SectionMesh};
use crate::study::convergence::phase_ensemble::{
    ensemble_over, family_mesh, hertz_contact_radius, ring_ratio, run_head_on, HeadOnCase,
    PhaseEnsemble,
};
use crate::study::run::section_impact::ImpactResult;

/// The banded family's sizing radius over the edge: its core reaches 1.5 × 0.45 = 0.675
/// edges along the surface, inside the band's 0.8 even for an ensemble member scaled by a
/// ring ratio of 1.15.
pub const SIZING_PER_EDGE: f64 = 0.45;

/// The contact edge (m) of `case`: the midpoint of the rest radii of the outermost surface
/// ring that reached the plane and the next one, on the plain family's level 0 (sized from
/// Hertz's contact radius); and that run.
///
/// Errors: those of the run; a run that made no contact.
pub fn contact_edge(case: &HeadOnCase) -> Result<(f64, ImpactResult)> {
    let mesh = family_mesh(case.diameter, hertz_contact_radius(case), 0)?;
    let run = run_head_on(case, mesh.clone())?;
    let r = run.contact_radius_max;
    let q = ring_ratio(&mesh, r)?;
    Ok((0.5 * r * (1.0 + q), run))
}

/// The mesh of banded family level `level` for a ball of diameter `d` (m) whose contact edge
/// is `edge` (m), scaled by `s` (an ensemble member's phase; 1 for the pilot): the ladder
/// sized from [`SIZING_PER_EDGE`] · edge · s with the band [0.8, 1.15] · edge split
/// `split`-fold.
///
/// Errors: those of [`ladder_ball_banded`].
pub fn banded_mesh(d: f64, edge: f64, level: u32, split: usize, s: f64) -> Result<SectionMesh> {
    ladder_ball_banded(
        d,
        SIZING_PER_EDGE * edge * s,
        level,
        &EdgeBand::around(edge, split),
    )
}

/// The ensemble of `meshes` members of `case` on banded family level `level` around the
/// contact edge `edge` (m), all run at once, and the run at s = 1 ([`ensemble_over`]: the
/// ring ratio is the band's, read at the edge).
///
/// Errors: an odd or too small `meshes`, a bad `split`, and those of [`banded_mesh`] and the
/// runs.
pub fn banded_ensemble_at(
    case: &HeadOnCase,
    level: u32,
    meshes: usize,
    edge: f64,
    split: usize,
) -> Result<(PhaseEnsemble, ImpactResult)> {
    check_split(split)?;
    let d = case.diameter;
    let q = ring_ratio(&banded_mesh(d, edge, level, split, 1.0)?, edge)?;
    let mesh_at = |s: f64| banded_mesh(d, edge, level, split, s);
    let run = |mesh: SectionMesh| run_head_on(case, mesh);
    ensemble_over(q, meshes, &mesh_at, &run)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_bad_split_is_refused_before_running() {
        let case = HeadOnCase::default_scene();
        for split in [0, crate::mesh::section::band::MAX_SPLIT + 1] {
            let e = banded_ensemble_at(&case, 0, 2, 9e-4, split)
                .unwrap_err()
                .to_string();
            assert!(e.contains("band.split"), "{e}");
        }
    }

    #[test]
    fn the_banded_family_keeps_its_band_outside_the_core() {
        // The default scene's edge, 0.89 mm; members scaled up to a ring ratio of 1.15.
        for level in 0..2 {
            for s in [1.0, 1.15] {
                let m = banded_mesh(0.02, 8.9e-4, level, 4, s).unwrap();
                assert!(m.quads.len() > 800, "{}", m.quads.len());
            }
        }
    }
}
