//! The share of a 3D run's error in e that its mesh ladder cannot see: a hexahedral ball
//! whose bulk elements are coarser than D/8 is short of the knee of e's convergence in the
//! bulk, where the mesher's core-cell count changes in steps, so two levels can agree by
//! chance while both are off. Such a run's bar on e is at least [`bulk_share`] of the
//! energy-loss scale 1 − e.
//!
//! The share is measured on the default scene (copper-fe, D = 20 mm, ±1 m/s, pole D/200,
//! converged e 0.3190): bulk D/5 gives 0.3250 (0.88 % of 1 − e), D/6 0.3212 (0.32 %), D/7
//! 0.3207 (0.25 %, the pole's share included), D/8 0.3210 (verification/NOTES.md,
//! "Convergence of the graded mesh"). An elastic ball (e → 1) gets no share.

use crate::error::Result;
use crate::scene::{approach, Approach, MeshSettings, Scene, Touch};
use crate::study::convergence::ladder::scene_at_level;
use crate::study::records::error_estimate::ErrorEstimate;
use crate::study::run::simulate::{choose_reduction, Reduction};

/// Share of 1 − e at a bulk of [`SHARE_FULL_PER_D`] elements per diameter or coarser, -.
pub const BULK_SHARE: f64 = 0.01;

/// Elements per diameter at or below which the full [`BULK_SHARE`] applies, -.
pub const SHARE_FULL_PER_D: f64 = 5.0;

/// Elements per diameter from which the bulk is past e's knee (no share), -.
pub const SHARE_NONE_PER_D: f64 = 8.0;

/// The share of 1 − e a 3D bar on e carries for a bulk of `per_d` elements per diameter
/// (> 0): [`BULK_SHARE`] at [`SHARE_FULL_PER_D`] or fewer, falling linearly to 0 at
/// [`SHARE_NONE_PER_D`].
pub fn bulk_share(per_d: f64) -> f64 {
    let t = (SHARE_NONE_PER_D - per_d) / (SHARE_NONE_PER_D - SHARE_FULL_PER_D);
    BULK_SHARE * t.clamp(0.0, 1.0)
}

/// The coarsest bulk of `scene`'s built-in ball meshes in elements per diameter, -
/// (None for a mesh read from a file).
fn bulk_per_d(scene: &Scene) -> Option<f64> {
    [&scene.ball1, &scene.ball2]
        .iter()
        .map(|b| match b.mesh {
            MeshSettings::Builtin { size, .. } => Some(b.diameter / size),
            MeshSettings::File { .. } => None,
        })
        .try_fold(f64::INFINITY, |acc, n| n.map(|n| acc.min(n)))
}

/// True when `scene`, meeting at `touch`, runs on a 3D model (not the meridian section).
///
/// Errors: as [`choose_reduction`].
pub fn in_3d(scene: &Scene, touch: &Touch) -> Result<bool> {
    Ok(choose_reduction(scene, touch)?.0 != Reduction::Axisymmetric)
}

/// True when `scene` runs on a 3D model; false without impact.
///
/// Errors: as [`approach`] and [`choose_reduction`].
pub fn runs_in_3d(scene: &Scene) -> Result<bool> {
    match approach(scene)? {
        Approach::Impact(touch) => in_3d(scene, &touch),
        Approach::NoImpact { .. } => Ok(false),
    }
}

/// The bulk's floor on e's bar of `est` (a ladder of `scene`) when `three_d`: the share
/// ([`bulk_share`], -) of the finest level's bulk (its elements per diameter, -) times
/// 1 − e (the finest e), as (floor, share, per_d); None when the share is zero.
///
/// Errors: as [`scene_at_level`].
pub fn bulk_floor(
    scene: &Scene,
    three_d: bool,
    est: &ErrorEstimate,
) -> Result<Option<(f64, f64, f64)>> {
    let Some(finest) = est.meshes.last().filter(|_| three_d) else {
        return Ok(None);
    };
    let per_d = bulk_per_d(&scene_at_level(scene, finest.level)?);
    let one_minus_e = (1.0 - est.e.finest).max(0.0);
    Ok(per_d
        .map(|n| (bulk_share(n) * one_minus_e, bulk_share(n), n))
        .filter(|(_, share, _)| *share > 0.0))
}

/// `est` (a ladder of `scene`) with e's bar raised to its [`bulk_floor`] when `three_d`;
/// unchanged otherwise.
///
/// Errors: as [`scene_at_level`].
pub fn with_bulk_share(scene: &Scene, three_d: bool, est: ErrorEstimate) -> Result<ErrorEstimate> {
    Ok(match bulk_floor(scene, three_d, &est)? {
        Some((floor, _, _)) => est.with_e_floor(floor),
        None => est,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_share_is_full_below_five_elements_and_gone_from_eight() {
        assert_eq!(bulk_share(2.5), BULK_SHARE);
        assert_eq!(bulk_share(5.0), BULK_SHARE);
        assert!((bulk_share(6.5) - BULK_SHARE / 2.0).abs() < 1e-15);
        assert_eq!(bulk_share(8.0), 0.0);
        assert_eq!(bulk_share(20.0), 0.0);
    }

    #[test]
    fn the_share_covers_the_default_scenes_measured_bulk_errors() {
        // e against bulk D/n at pole D/200, converged 0.3190 (verification/NOTES.md).
        for (n, e) in [(5.0, 0.3250), (6.0, 0.3212), (7.0, 0.3207)] {
            let error: f64 = e - 0.3190;
            assert!(error <= bulk_share(n) * (1.0 - e), "D/{n}: {error}");
        }
    }

    #[test]
    fn the_default_scene_is_on_the_section_and_its_3d_reduction_is_not() {
        let scene = Scene::default();
        assert!(!runs_in_3d(&scene).unwrap());
        let mut quarter = scene.clone();
        quarter.reduction.symmetry = crate::scene::Symmetry::Quarter;
        assert!(runs_in_3d(&quarter).unwrap());
    }
}
