//! Results a user should not take at face value: each check compares one number of a run
//! with the limit beyond which it stops meaning what it says, and says so in one line.
//!
//! FE checks ([`fe_warnings`]): energy-balance error above 1 %; a coefficient of restitution
//! above 1 (the run made energy; in an oblique or spinning impact whose kinetic energy did
//! not grow, the rebound took energy from the sliding or the spin); penetration deeper than 5 % of δ_max (the penalty is too
//! soft for the contact it carries); a contact patch at δ_max narrower than 3 elements of
//! the pole mesh (the contact is not resolved); hourglass energy above 5 % of the internal
//! energy (the one-point elements deform in zero-energy modes); a plastic impact on the
//! meridian section run on one mesh (its e is one ring phase). Analytical checks
//! ([`analytic_warnings`]): a maximum approach above a tenth of the effective radius R*,
//! where the small-deformation contact laws the model is built on no longer hold.

use serde::Serialize;

/// Energy-balance error above which a run is flagged (fraction).
pub const ENERGY_ERROR_LIMIT: f64 = 0.01;
/// Penetration above which the penalty is too soft, as a fraction of δ_max.
pub const PENETRATION_LIMIT: f64 = 0.05;
/// Elements across the contact patch (diameter 2a at δ_max) below which it is unresolved.
pub const PATCH_ELEMENTS_MIN: f64 = 3.0;
/// Hourglass energy above which a run is flagged, as a fraction of the internal energy.
pub const HOURGLASS_LIMIT: f64 = 0.05;
/// Approach above which the analytical model leaves its range, as a fraction of R*.
pub const APPROACH_LIMIT: f64 = 0.1;

/// Which check raised a warning.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Check {
    /// Energy-balance error above [`ENERGY_ERROR_LIMIT`].
    EnergyError,
    /// FE coefficient of restitution above 1.
    RestitutionAboveOne,
    /// Penetration above [`PENETRATION_LIMIT`] of δ_max.
    Penetration,
    /// Contact patch narrower than [`PATCH_ELEMENTS_MIN`] elements.
    UnresolvedContact,
    /// Hourglass energy above [`HOURGLASS_LIMIT`] of the internal energy.
    Hourglass,
    /// Analytical approach above [`APPROACH_LIMIT`] of R*.
    AnalyticRange,
    /// A plastic impact on the meridian section run on one mesh alone: its e is one phase of
    /// the surface rings, not the phase mean.
    SingleRingPhase,
    /// A head-on section run whose default error estimate could not run (its mesh levels
    /// do not reach the contact's edge): one run of the scene's mesh, no error bar.
    NoErrorEstimate,
    /// A scene setting the chosen model does not use.
    IgnoredSetting,
    /// The default error bar of a head-on run on a rate-dependent (Johnson-Cook) metal, which
    /// has missed its error.
    RateDependentBar,
    /// A 3D bar on e raised to the share of its bulk, coarser than e's knee.
    BulkShareBar,
    /// A pole ladder's bulk share keeps its bars above its tolerance.
    PoleBulkShare,
    /// A 3D ball's contact patch, turned by its spin, may reach beyond its contact faces.
    ContactCap,
}

/// One warning: the check and its one-line message (values with units).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Warning {
    /// The check that fired.
    pub check: Check,
    /// What is wrong and why it matters, in one line.
    pub message: String,
}

/// What the FE checks need from a run (SI units; δ_max and penetration in m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FeFigures {
    /// Largest relative energy error (fraction).
    pub energy_error: f64,
    /// FE coefficient of restitution.
    pub e: f64,
    /// FE maximum approach of the mass centres, m.
    pub delta_max: f64,
    /// Largest contact penetration, m.
    pub max_penetration: f64,
    /// Effective radius R* = R1 R2 / (R1 + R2), m.
    pub r_star: f64,
    /// Element size at the contact pole, m (None when unknown, e.g. a mesh file).
    pub pole_size: Option<f64>,
    /// Largest hourglass energy over the run, J.
    pub hourglass: f64,
    /// Largest internal (elastic + plastic + hourglass) energy over the run, J.
    pub internal: f64,
    /// Rigid-body kinetic energy (translation and spin) after over before, for an oblique or
    /// spinning impact; None for a head-on one (its e alone bounds the energy).
    pub kinetic_ratio: Option<f64>,
}

/// Elements of size `h` (m) across the contact patch at approach `delta` (m) between
/// surfaces of effective radius `r_star` (m): the patch diameter 2a with a = √(R* δ)
/// (Hertz geometry), over h.
pub fn patch_elements(r_star: f64, delta: f64, h: f64) -> f64 {
    2.0 * (r_star * delta.max(0.0)).sqrt() / h
}

/// The FE checks of one run; empty when every figure is within its limit.
pub fn fe_warnings(f: &FeFigures) -> Vec<Warning> {
    let mut w = Vec::new();
    if f.energy_error > ENERGY_ERROR_LIMIT {
        w.push(Warning {
            check: Check::EnergyError,
            message: format!(
                "energy error {:.2} % is above {:.0} %: the FE energies do not balance; refine the mesh or lower solver.time_step_factor",
                100.0 * f.energy_error,
                100.0 * ENERGY_ERROR_LIMIT
            ),
        });
    }
    if f.e > 1.0 {
        let message = match f.kinetic_ratio {
            Some(k) if k <= 1.0 => format!(
                "FE e = {:.5} is above 1 while the kinetic energy (translation and spin) is {k:.4} \
                 of its start: the rebound took energy from the sliding or the spin, through a \
                 contact force off the line of the centre (a faceted, coarse ball does this); \
                 refine the mesh before trusting e",
                f.e
            ),
            _ => format!(
                "FE e = {:.5} is above 1: the run made energy (numerical, not physical)",
                f.e
            ),
        };
        w.push(Warning {
            check: Check::RestitutionAboveOne,
            message,
        });
    }
    if f.delta_max > 0.0 && f.max_penetration > PENETRATION_LIMIT * f.delta_max {
        w.push(Warning {
            check: Check::Penetration,
            message: format!(
                "penetration {:.3e} m is {:.0} % of delta_max {:.3e} m (limit {:.0} %): the contact penalty is too soft; raise contact.penalty_factor",
                f.max_penetration,
                100.0 * f.max_penetration / f.delta_max,
                f.delta_max,
                100.0 * PENETRATION_LIMIT
            ),
        });
    }
    if let Some(h) = f.pole_size {
        let n = patch_elements(f.r_star, f.delta_max, h);
        if n < PATCH_ELEMENTS_MIN {
            w.push(Warning {
                check: Check::UnresolvedContact,
                message: format!(
                    "the contact patch at delta_max (diameter {:.3e} m) spans {n:.1} elements of {h:.3e} m (fewer than {PATCH_ELEMENTS_MIN:.0}): the contact is not resolved; refine mesh.pole_size",
                    2.0 * (f.r_star * f.delta_max.max(0.0)).sqrt()
                ),
            });
        }
    }
    if f.internal > 0.0 && f.hourglass > HOURGLASS_LIMIT * f.internal {
        w.push(Warning {
            check: Check::Hourglass,
            message: format!(
                "hourglass energy is {:.1} % of the internal energy (limit {:.0} %): zero-energy modes distort the result; use solver.element = \"b-bar\" or a finer mesh",
                100.0 * f.hourglass / f.internal,
                100.0 * HOURGLASS_LIMIT
            ),
        });
    }
    w
}

/// Plastic work above this fraction of the initial kinetic energy makes a single section
/// run's e a ring-phase sample.
pub const PLASTIC_SHARE_MIN: f64 = 1e-3;

/// The check of a section run on one mesh (no ensemble) whose plastic work is `plastic` (J)
/// out of an initial kinetic energy `kinetic` (J): its e is one ring phase.
pub fn single_ring_phase(plastic: f64, kinetic: f64) -> Option<Warning> {
    (kinetic > 0.0 && plastic > PLASTIC_SHARE_MIN * kinetic).then(|| Warning {
        check: Check::SingleRingPhase,
        message: "e of a plastic impact on the section from one mesh alone moves with where its surface nodes (rings) fall against the contact edge (about ±2 % on the default mesh); the default run's error estimate (mesh.size at most D/8) averages over ring positions and gives the bar".into(),
    })
}

/// The note of a head-on section run that fell back to one run because its default error
/// estimate could not run (`why`, the estimate's one-line error).
pub fn no_error_estimate(why: &str) -> Warning {
    Warning {
        check: Check::NoErrorEstimate,
        message: format!(
            "no error bar: the default error estimate cannot run this scene ({why}); the result is one run of the scene's mesh (twoball run --tolerance T converges it where the banded family holds it)"
        ),
    }
}

/// The note of a default run's bar on a rate-dependent metal: its default levels' bar
/// understated their error there, so the bar on e is at least `floor` (relative;
/// verification/contact-penalty.md, "Johnson-Cook metals").
pub fn rate_dependent_bar(floor: f64) -> Warning {
    Warning {
        check: Check::RateDependentBar,
        message: format!(
            "the default error bar on e is at least {:.0} % on a rate-dependent (Johnson-Cook) metal: its mesh levels' own bar missed their error in 3 of 13 cases (2.5 % under 1.7 % on ofhc-copper at ±5 m/s); twoball run --tolerance 0.5% gives a bar that held in all 13",
            100.0 * floor
        ),
    }
}

/// The note of a 3D run whose bar on e was raised to its bulk's share: `share` of 1 − e
/// (-) for a bulk of `per_d` elements per diameter (docs/design.md, "Error estimates").
pub fn bulk_share_bar(share: f64, per_d: f64) -> Warning {
    Warning {
        check: Check::BulkShareBar,
        message: format!(
            "the error bar on e is at least {:.2} % of 1 - e: a 3D bulk of D/{per_d:.1} is coarser than D/8, where its mesh levels can agree while both are off (bulk D/5 moved e by 0.9 % of 1 - e on the default scene); a finer ball1.mesh.size removes the share",
            100.0 * share
        ),
    }
}

/// The note of a pole ladder whose bars its bulk's share (`per_d` elements per diameter, -)
/// keeps above `tolerance` (-) on e or the tangential restitution: a finer pole cannot lower
/// them, a finer bulk can.
pub fn pole_bulk_share(tolerance: f64, per_d: f64) -> Warning {
    Warning {
        check: Check::PoleBulkShare,
        message: format!(
            "tolerance {:.2} % NOT met and no finer pole run: the bulk's share of the bars (a bulk of D/{per_d:.1}, held on every pole level) exceeds it; a finer ball1.mesh.size lowers the share, a finer pole does not",
            100.0 * tolerance
        ),
    }
}

/// The polar angle (rad, from the pole) a 3D ball's contact patch reaches during an impact:
/// its half-angle asin(a/R), a = √(R* δ_max) (Hertz geometry; `radius` R, `r_star` R* and
/// `delta_max` in m), plus the turn of the ball while in contact, the mean of its spin
/// magnitudes before and after (rad/s) times the contact duration (s). A twist about the
/// normal counts too, so the angle is an upper bound.
pub fn patch_reach(
    radius: f64,
    r_star: f64,
    delta_max: f64,
    spins: [[f64; 3]; 2],
    duration: f64,
) -> f64 {
    let a = (r_star * delta_max.max(0.0)).sqrt();
    let mag = |w: [f64; 3]| (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt();
    (a / radius).min(1.0).asin() + 0.5 * (mag(spins[0]) + mag(spins[1])) * duration
}

/// The note of ball `ball` whose contact patch reaches `reach_deg` degrees from its pole,
/// beyond the `cap_deg` half-angle of its contact faces: a patch outside them is not seen
/// by the contact.
pub fn contact_cap(ball: &str, reach_deg: f64, cap_deg: f64) -> Warning {
    Warning {
        check: Check::ContactCap,
        message: format!(
            "{ball}'s contact patch may reach {reach_deg:.1} degrees from its pole (the patch's half-angle plus the ball's turn while in contact), beyond its contact faces' {cap_deg:.0} degrees: the contact may miss part of it; lower the speed or spin, or use a stiffer wall"
        ),
    }
}

/// The analytical model's range check: maximum approach `delta2` (m) against the effective
/// radius `r_star` (m).
pub fn analytic_warnings(delta2: f64, r_star: f64) -> Vec<Warning> {
    let mut w = Vec::new();
    if r_star.is_finite() && r_star > 0.0 && delta2 > APPROACH_LIMIT * r_star {
        w.push(Warning {
            check: Check::AnalyticRange,
            message: format!(
                "analytical delta_2 = {delta2:.3e} m is {:.0} % of R* = {r_star:.3e} m (the model assumes small deformation, delta_2 < {:.0} % of R*): its results are outside its range",
                100.0 * delta2 / r_star,
                100.0 * APPROACH_LIMIT
            ),
        });
    }
    w
}

/// Prints each warning as one line on stderr: `note: ...` for a setting the model ignores,
/// `warning: ...` for a result not to take at face value.
pub fn print(warnings: &[Warning]) {
    for w in warnings {
        let kind = match w.check {
            Check::IgnoredSetting => "note",
            _ => "warning",
        };
        eprintln!("{kind}: {}", w.message);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_patch_reaches_its_half_angle_plus_the_balls_turn() {
        // a = √(R* δ) = 5 mm on R = 10 mm: 30°; a mean spin of 100 rad/s for 1 ms adds 0.1 rad.
        let still = patch_reach(0.01, 0.01, 2.5e-3, [[0.0; 3]; 2], 1e-3);
        assert!((still.to_degrees() - 30.0).abs() < 1e-9);
        let turned = patch_reach(0.01, 0.01, 2.5e-3, [[0.0, 0.0, 200.0], [0.0; 3]], 1e-3);
        assert!((turned - still - 0.1).abs() < 1e-12);
    }

    fn clean() -> FeFigures {
        FeFigures {
            energy_error: 1e-3,
            e: 0.32,
            delta_max: 7.8e-5,
            max_penetration: 1e-6,
            r_star: 5e-3,
            pole_size: Some(1e-4),
            hourglass: 1e-4,
            internal: 1e-2,
            kinetic_ratio: None,
        }
    }

    #[test]
    fn a_clean_run_has_no_warning_and_each_limit_fires_alone() {
        assert!(fe_warnings(&clean()).is_empty());
        let one = |f: FeFigures| {
            let w = fe_warnings(&f);
            assert_eq!(w.len(), 1, "{w:?}");
            w[0].check
        };
        let mut f = clean();
        f.energy_error = 0.018;
        assert_eq!(one(f), Check::EnergyError);
        let mut f = clean();
        f.e = 1.001;
        assert_eq!(one(f), Check::RestitutionAboveOne);
        let mut f = clean();
        f.max_penetration = 0.06 * f.delta_max;
        assert_eq!(one(f), Check::Penetration);
        let mut f = clean();
        f.hourglass = 0.06 * f.internal;
        assert_eq!(one(f), Check::Hourglass);
        // The paper's 2 mm mesh on a 5 mm ball: R* = 1.25 mm, delta ~ 1e-5 m.
        let mut f = clean();
        f.r_star = 1.25e-3;
        f.delta_max = 1e-5;
        f.max_penetration = 1e-8;
        f.pole_size = Some(2e-3);
        assert_eq!(one(f), Check::UnresolvedContact);
    }

    /// e above 1 in an oblique or spinning impact: energy made when the kinetic energy grew,
    /// energy taken from the sliding or the spin when it did not.
    #[test]
    fn e_above_one_says_where_the_energy_came_from() {
        let msg = |e: f64, k: Option<f64>| {
            let mut f = clean();
            f.e = e;
            f.kinetic_ratio = k;
            fe_warnings(&f)[0].message.clone()
        };
        assert!(msg(1.04, None).contains("made energy"));
        assert!(msg(1.04, Some(1.02)).contains("made energy"));
        let from_spin = msg(1.04, Some(0.98));
        assert!(from_spin.contains("sliding or the spin") && from_spin.contains("0.9800"));
    }

    #[test]
    fn analytic_range_is_a_tenth_of_r_star() {
        assert!(analytic_warnings(4.9e-4, 5e-3).is_empty());
        assert_eq!(analytic_warnings(5.1e-4, 5e-3).len(), 1);
        assert!(analytic_warnings(1.0, f64::INFINITY).is_empty());
    }
}
