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
//!
//! A pole ladder holds its bulk (at most D/8) on every level, so it cannot see the bulk's
//! part of any figure; [`with_pole_bulk_floor`] raises its bars to what a bulk twice as fine
//! moved each figure on sixteen oblique and spinning cases of the DEM benchmarks (tests 4, 5
//! and 6: μ = 0.092-0.4, a/R = 0.02-0.16), each constant 1.2 times the largest move seen,
//! and checked on 20 cases at the ladder's level +1 (`scripts/pole_ladder_honesty.py`, table
//! in verification/design-measurements.md, "Error estimates": e, δ_max and t_c hold in 20,
//! e_t, the rebound angle and the spin in 19). The tangential moves scale with μ: the
//! traction the bulk's compliance acts on does.

use crate::error::Result;
use crate::scene::{approach, Approach, MeshSettings, Scene, Touch};
use crate::study::convergence::ladder::{scene_at_level, POLE_LADDER_BULK_PER_D};
use crate::study::records::error_estimate::{
    meets, spin_bar_from_inertia, spin_bar_from_restitution, ErrorEstimate,
};
use crate::study::records::estimate::Estimate;
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
pub fn bulk_per_d(scene: &Scene) -> Option<f64> {
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

/// A pole ladder's bulk share of the tangential exchange 1 + e_t (the share of the slip at
/// touch that the tangential impulse removes) at a bulk of D/8, relative, per unit friction
/// coefficient, -: the tangential traction, and with it what the bulk's compliance does to
/// the exchange, scales with μ.
pub const POLE_BULK_EXCHANGE: f64 = 0.06;

/// A pole ladder's bulk share of the rebound angle's part set by the tangential impulse at a
/// bulk of D/8, relative, per unit friction coefficient, -.
pub const POLE_BULK_REBOUND: f64 = 0.065;

/// A pole ladder's bulk share of δ_max and of the contact duration at a bulk of D/8,
/// relative, -.
pub const POLE_BULK_NORMAL: f64 = 0.003;

/// A pole ladder's bulk floor on e at a bulk of D/8, absolute, per unit friction
/// coefficient, -.
pub const POLE_BULK_E: f64 = 0.002;

/// The pole ladder's bulk shares for a bulk of `per_d` (≥ 8) elements per diameter relative
/// to D/8's: 8/per_d (first order in the bulk size), -.
pub fn pole_bulk_scale(per_d: f64) -> f64 {
    (POLE_LADDER_BULK_PER_D / per_d).min(1.0)
}

/// The rebound angle's part set by the tangential impulse, rad per unit relative impulse:
/// with tan θ = v_t/v_n before and after (`incidence`, `rebound`, rad) and v_n' = e v_n, the
/// impulse J_t moves tan θ' by (J_t/m)/v_n' = tan θ/e − tan θ', so θ' by cos²θ' times that.
/// 0 when `e` (-) is not positive.
pub fn rebound_per_impulse(incidence: f64, rebound: f64, e: f64) -> f64 {
    if e > 0.0 {
        rebound.cos().powi(2) * (incidence.tan() / e - rebound.tan()).abs()
    } else {
        0.0
    }
}

/// `est` (a pole ladder whose bulk has `per_d` elements per diameter, -, under friction
/// coefficient `mu`, -) with every bar at least the bulk's share ([`pole_bulk_scale`] times
/// the `POLE_BULK_*` constants): e by μ [`POLE_BULK_E`], δ_max and the contact duration by
/// [`POLE_BULK_NORMAL`], the tangential restitution by μ [`POLE_BULK_EXCHANGE`] of
/// |1 + e_t|, the rebound angle by μ [`POLE_BULK_REBOUND`] of [`rebound_per_impulse`], and
/// the spin by the share of the raised restitution bar plus the mesh's inertia share;
/// whether the tolerance on e is met is decided again.
pub fn with_pole_bulk_floor(est: ErrorEstimate, per_d: f64, mu: f64) -> ErrorEstimate {
    let s = pole_bulk_scale(per_d);
    let t_share = POLE_BULK_EXCHANGE * mu * s;
    let e = est.e.with_error(est.e.error.max(POLE_BULK_E * mu * s));
    let finest = est.meshes.last().and_then(|m| m.tangential);
    let tangential = est.tangential.map(|mut t| {
        if let Some(r) = t.restitution {
            let floor = t_share * (1.0 + r.finest).abs();
            t.restitution = Some(r.with_error(r.error.max(floor)));
        }
        if let Some(f) = finest {
            let reb = POLE_BULK_REBOUND
                * mu
                * s
                * rebound_per_impulse(f.incidence_angle, f.rebound_angle, e.finest);
            t.rebound_angle = t.rebound_angle.with_error(t.rebound_angle.error.max(reb));
            let dspin = f.spin1_after - f.spin1_before;
            let inertia = f
                .spin1_inertia_ratio
                .map_or(0.0, |k| spin_bar_from_inertia(dspin, k));
            let share = t.restitution.as_ref().map_or(t_share * dspin.abs(), |r| {
                spin_bar_from_restitution(dspin, r)
            });
            t.spin1_after = t
                .spin1_after
                .with_error(t.spin1_after.error.max(share + inertia));
        }
        t
    });
    let normal = |q: Estimate| q.with_relative_floor(POLE_BULK_NORMAL * s);
    ErrorEstimate {
        tolerance_met: est.tolerance.map(|t| meets(&e, t)),
        e,
        delta_max: normal(est.delta_max),
        contact_duration: normal(est.contact_duration),
        tangential,
        ..est
    }
}

/// True when the bulk's share alone ([`with_pole_bulk_floor`]'s floors on `est`, a pole
/// ladder with `per_d` elements per diameter in its bulk under friction `mu`) puts e's or the
/// tangential restitution's relative bar above `tolerance` (-): no finer pole can meet it.
pub fn pole_bulk_breaks(est: &ErrorEstimate, per_d: f64, mu: f64, tolerance: f64) -> bool {
    let s = pole_bulk_scale(per_d);
    let over = |q: &Estimate, floor: f64| {
        q.with_error(floor)
            .relative_error
            .is_some_and(|r| r > tolerance)
    };
    let restitution = est.tangential.as_ref().and_then(|t| t.restitution.as_ref());
    over(&est.e, POLE_BULK_E * mu * s)
        || restitution
            .is_some_and(|r| over(r, POLE_BULK_EXCHANGE * mu * s * (1.0 + r.finest).abs()))
}

/// True when a finer pole would lower a bar that misses `tolerance` (-): e's or the
/// tangential restitution's relative bar, the larger of its pole part (`est`, a pole ladder
/// with `per_d` elements per diameter in its bulk under friction `mu`) and the bulk's floor
/// ([`with_pole_bulk_floor`]), is above it while the pole part is above the floor.
pub fn finer_pole_helps(est: &ErrorEstimate, per_d: f64, mu: f64, tolerance: f64) -> bool {
    let s = pole_bulk_scale(per_d);
    let helps = |q: &Estimate, floor: f64| {
        let missed = q
            .with_error(q.error.max(floor))
            .relative_error
            .is_none_or(|r| r > tolerance);
        missed && q.error > floor
    };
    let restitution = est.tangential.as_ref().and_then(|t| t.restitution.as_ref());
    helps(&est.e, POLE_BULK_E * mu * s)
        || restitution
            .is_some_and(|r| helps(r, POLE_BULK_EXCHANGE * mu * s * (1.0 + r.finest).abs()))
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

    /// The moves a bulk of D/16 made against D/8 at the finest pole of a 1 % pole ladder
    /// (level +1 or +2), as (case, μ, e_t, |Δ(1 + e_t)|/(1 + e_t), |Δe|, |Δδ_max|/δ_max), the
    /// largest of each kind among the calibration's 16 cases (the runs:
    /// verification/design-measurements.md, "Error estimates").
    const MOVES: [(&str, f64, f64, f64, f64, f64); 7] = [
        ("test4-alumina@5", 0.092, 0.4893, 0.00325, 0.000052, 0.00078),
        (
            "test4-alumina@80",
            0.092,
            -0.8870,
            0.00152,
            0.000007,
            0.00198,
        ),
        ("test5-steel@vt1.5", 0.3, 0.3095, 0.01092, 0.000049, 0.00072),
        ("test5-steel@vt7.5", 0.3, 0.3323, 0.00852, 0.000246, 0.00058),
        (
            "test6-aluminium@w0.8",
            0.4,
            0.1737,
            0.00575,
            0.000057,
            0.00132,
        ),
        ("test6-nylon@w3", 0.4, 0.5211, 0.02026, 0.000293, 0.00218),
        (
            "test6-aluminium@w14",
            0.4,
            -0.6032,
            0.00081,
            0.000617,
            0.00211,
        ),
    ];

    #[test]
    fn the_pole_ladders_bulk_floors_cover_the_measured_moves() {
        for (case, mu, _, exchange, de, dmax) in MOVES {
            assert!(exchange <= POLE_BULK_EXCHANGE * mu, "{case}: e_t");
            assert!(de <= POLE_BULK_E * mu, "{case}: e");
            assert!(dmax <= POLE_BULK_NORMAL, "{case}: δ_max");
        }
        // A finer bulk lowers the floors in proportion; D/8 is the coarsest the ladder runs.
        assert_eq!(pole_bulk_scale(8.0), 1.0);
        assert_eq!(pole_bulk_scale(16.0), 0.5);
        assert_eq!(pole_bulk_scale(4.0), 1.0);
    }

    /// A pole ladder of test 4 (alumina on a wall, μ = 0.092, bulk D/8) with e 0.99 ± 9e-5
    /// and the tangential restitution `e_t` with its pole part's bar `bar`.
    fn test4_ladder(e_t: f64, bar: f64) -> ErrorEstimate {
        use crate::study::records::error_estimate::{EstimateMethod, TangentialEstimate};
        let r = |v: f64, err: f64| Estimate::recorded(v, err);
        ErrorEstimate {
            ratio: 2.0,
            e: r(0.99, 9e-5),
            delta_max: r(1e-5, 1e-8),
            contact_duration: r(1e-5, 1e-8),
            peak_force: r(1e3, 1.0),
            tangential: Some(TangentialEstimate {
                restitution: Some(r(e_t, bar)),
                rebound_angle: r(0.1, 1e-4),
                spin1_after: r(10.0, 0.01),
            }),
            meshes: vec![],
            tolerance: Some(0.01),
            tolerance_met: None,
            method: EstimateMethod::PoleLadder { bulk_size_m: 1e-3 },
        }
    }

    #[test]
    fn a_finer_pole_runs_only_where_it_lowers_a_bar_that_misses() {
        // Test 4's 1 % pole ladders at level +1 (`twoball bench dem`): at 5° the pole's part
        // (± 0.052) is six times the bulk's floor (0.092 × 6 % × 1.489 = 0.0082), so a
        // finer pole lowers the bar; at 30° the floor (0.0059) sets the bar, 8.8 % of e_t,
        // and no pole lowers it; at 60° the bar meets 1 %.
        let helps = |e_t, bar| finer_pole_helps(&test4_ladder(e_t, bar), 8.0, 0.092, 0.01);
        assert!(helps(0.4889, 0.052));
        assert!(!helps(0.0672, 0.004));
        assert!(!helps(-0.6310, 0.002));
        // A bulk twice as fine halves the floor (0.0029 at 30°): the pole's 0.004 then sets it.
        assert!(finer_pole_helps(
            &test4_ladder(0.0672, 0.004),
            16.0,
            0.092,
            0.01
        ));
    }

    #[test]
    fn the_rebound_angle_moves_with_the_tangential_impulse() {
        // Head-on: no tangential impulse moves it. A ball spun on a wall (θ = 0) leaves at
        // tan θ' = −(J_t/m)/v_n', so the part is tan θ' cos²θ'.
        assert_eq!(rebound_per_impulse(0.0, 0.0, 1.0), 0.0);
        let r: f64 = 0.3;
        assert!((rebound_per_impulse(0.0, r, 0.9) - r.tan() * r.cos().powi(2)).abs() < 1e-15);
        // Incidence 40 degrees, e = 1, rebound 0.5 rad: tan 40° − tan 0.5, times cos² 0.5.
        let t = 40f64.to_radians();
        let want = (t.tan() - 0.5f64.tan()) * 0.5f64.cos().powi(2);
        assert!((rebound_per_impulse(t, 0.5, 1.0) - want).abs() < 1e-15);
        assert_eq!(rebound_per_impulse(t, 0.5, 0.0), 0.0);
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
