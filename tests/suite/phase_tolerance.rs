//! `study::phase_ensemble::converged_head_on` with a tolerance: while e's bar exceeds it, the
//! next finer level runs and the fine ensemble becomes the coarse one.

use twoball::study::convergence::phase_ensemble::{
    converged_head_on, ensemble_at, HeadOnCase, PhasePlan,
};

/// The default scene on the plain family's coarsest levels (cheap runs).
fn plan(tolerance: Option<f64>, max_refinements: u32) -> PhasePlan {
    PhasePlan {
        level: -1,
        meshes: 2,
        tolerance,
        max_refinements,
        ..PhasePlan::default()
    }
}

#[test]
fn a_tolerance_refines_one_level_and_keeps_the_fine_ensemble_as_the_coarse_one() {
    let case = HeadOnCase::default_scene();
    // A tolerance no bar meets: one refinement, the most allowed.
    let refined = converged_head_on(&case, &plan(Some(1e-9), 1)).unwrap();
    assert_eq!(refined.fine_level, 0);
    let (level_m1, _) = ensemble_at(&case, -1, 2).unwrap();
    let (level_0, _) = ensemble_at(&case, 0, 2).unwrap();
    assert_eq!(refined.coarse.e.mean, level_m1.e.mean);
    assert_eq!(refined.fine.e.mean, level_0.e.mean);
    assert_eq!(refined.e.finest, level_0.e.mean);
    // A tolerance every bar meets, and no tolerance: the plan's level answers.
    for p in [plan(Some(0.5), 1), plan(None, 3)] {
        let a = converged_head_on(&case, &p).unwrap();
        assert_eq!(a.fine_level, -1);
        assert_eq!(a.e.finest, level_m1.e.mean);
    }
}

#[test]
fn a_bad_tolerance_or_too_many_refinements_is_one_line_naming_the_field() {
    let case = HeadOnCase::default_scene();
    for (p, field) in [
        (plan(Some(0.0), 1), "tolerance"),
        (plan(Some(f64::NAN), 1), "tolerance"),
        (plan(Some(0.01), 9), "max_refinements"),
    ] {
        let e = converged_head_on(&case, &p).unwrap_err().to_string();
        assert!(e.contains(field) && !e.contains('\n'), "{e}");
    }
}
