//! Mass scaling within a budget: the smallest elements of a model get a higher density, so
//! that no element's Courant step is below a target step, and the target is the largest whose
//! added mass stays within a given fraction of the model's mass (the idea of LS-DYNA's DT2MS
//! and Abaqus's fixed mass scaling, with the target chosen from the budget). One mechanism for
//! both models: the section's ring quads ([`crate::fe::section::mass_scaling`]) and the 3D
//! hexahedra ([`hex_steps_and_masses`], applied by [`crate::fe::solver::explicit`]).
//!
//! Why it is sound here: the elements that limit the step of an impact are those of the
//! contact pole and of an edge band, a region of size a (the contact radius) whose wave
//! transit a/c is three to four orders of magnitude shorter than the contact duration. A
//! density raised by s there slows that transit by √s and adds the mass s − 1 times the
//! region's, a fraction of about (a/R)³ of the ball's: the contact there stays
//! quasi-static. The budget bounds the added mass; its effect on e, δ_max and the contact
//! duration is measured, not assumed (docs/contact-penalty.md, "Mass scaling of the contact
//! region").
//!
//! An element's step scales as √s: dt_e = l_e √(s ρ / M) with l_e its characteristic length
//! and M its P-wave modulus, so s_e = max(1, (T / dt_e)²) for a target step T.

use crate::error::{Error, Result};
use crate::fe::solver::mass::element_lumped_mass;
use crate::fe::solver::timestep::characteristic_length;

/// Largest mass-scaling budget (added mass over the model's mass) accepted.
pub const MAX_BUDGET: f64 = 1e-2;

/// Bisection steps on ln T: the target is found to a relative 1e-12 of its bracket.
const BISECTIONS: usize = 80;

/// The density factors of a model's elements and what they cost.
#[derive(Debug, Clone, PartialEq)]
pub struct MassScaling {
    /// Density factor of each element (≥ 1; 1 where its own step is at least the target).
    pub scale: Vec<f64>,
    /// The target Courant step T, s (before the step factor): no scaled element's step is below it.
    pub target_step: f64,
    /// The smallest Courant step of the unscaled elements, s.
    pub unscaled_step: f64,
    /// Added mass over the model's mass (≤ the budget).
    pub added_fraction: f64,
}

/// Checks a budget: a finite fraction in [0, [`MAX_BUDGET`]].
pub fn check_budget(budget: f64) -> Result<()> {
    if budget.is_finite() && (0.0..=MAX_BUDGET).contains(&budget) {
        Ok(())
    } else {
        Err(Error::invalid(
            "mass_scaling",
            budget,
            format!("0 <= mass_scaling <= {MAX_BUDGET} (added mass over the model's)"),
        ))
    }
}

/// Mass (kg) added by raising every element of `sm` (Courant step, mass) to the step `t` (s).
fn added_mass(sm: &[(f64, f64)], t: f64) -> f64 {
    sm.iter()
        .map(|&(dt, m)| m * ((t / dt).powi(2) - 1.0).max(0.0))
        .sum()
}

/// The density factors that raise the smallest elements, given as (Courant step in s, mass in
/// kg) each, to the largest common target step whose added mass is at most `budget` times
/// their total mass. A budget of 0 returns factors of 1. `field` names the elements in
/// messages (e.g. `mesh.quads`).
///
/// Errors: a budget outside [0, [`MAX_BUDGET`]]; no elements; an element with a non-positive
/// or non-finite step or mass.
pub fn for_elements(sm: &[(f64, f64)], budget: f64, field: &str) -> Result<MassScaling> {
    check_budget(budget)?;
    if sm.is_empty() {
        return Err(Error::invalid(field, 0, "at least one element"));
    }
    if let Some(e) = sm
        .iter()
        .position(|&(dt, m)| !(dt.is_finite() && dt > 0.0 && m.is_finite() && m > 0.0))
    {
        return Err(Error::invalid(
            format!("{field}[{e}]"),
            format!("step {:.3e} s, mass {:.3e} kg", sm[e].0, sm[e].1),
            "a positive, finite Courant step and mass",
        ));
    }
    let (lo, hi) = sm
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(lo, hi), &(dt, _)| {
            (lo.min(dt), hi.max(dt))
        });
    let total: f64 = sm.iter().map(|&(_, m)| m).sum();
    let allowed = budget * total;
    // added_mass is continuous and increasing in t, zero at lo: bisect ln t on [lo, hi].
    let target = if budget == 0.0 {
        lo
    } else if added_mass(sm, hi) <= allowed {
        hi
    } else {
        let (mut a, mut b) = (lo.ln(), hi.ln());
        for _ in 0..BISECTIONS {
            let mid = 0.5 * (a + b);
            if added_mass(sm, mid.exp()) <= allowed {
                a = mid;
            } else {
                b = mid;
            }
        }
        a.exp()
    };
    let scale = sm
        .iter()
        .map(|&(dt, _)| (target / dt).powi(2).max(1.0))
        .collect();
    Ok(MassScaling {
        scale,
        target_step: target,
        unscaled_step: lo,
        added_fraction: added_mass(sm, target) / total,
    })
}

/// Courant step (s) and lumped mass (kg) of each hexahedron `hexes` of `nodes` (m) in its
/// reference configuration, with `wave_speed` and `rho` (m/s, kg/m³) the element's
/// material's: the step is the one the hexahedra's kernels report, l_e(x, V)/c.
///
/// Errors: an element inverted at a Gauss point (named by its index).
pub fn hex_steps_and_masses(
    nodes: &[[f64; 3]],
    hexes: &[[u32; 8]],
    wave_speed: impl Fn(usize) -> f64,
    rho: impl Fn(usize) -> f64,
) -> Result<Vec<(f64, f64)>> {
    hexes
        .iter()
        .enumerate()
        .map(|(e, h)| {
            let x = h.map(|i| nodes[i as usize]);
            let volume: f64 = element_lumped_mass(&x, 1.0)
                .map_err(|err| Error::Numerical(format!("element {e}: {err}")))?
                .iter()
                .sum();
            Ok((
                characteristic_length(&x, volume) / wave_speed(e),
                rho(e) * volume,
            ))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The cube [0, h]³ with nodes in the hexahedra's order.
    fn cube(h: f64) -> Vec<[f64; 3]> {
        vec![
            [0.0, 0.0, 0.0],
            [h, 0.0, 0.0],
            [h, h, 0.0],
            [0.0, h, 0.0],
            [0.0, 0.0, h],
            [h, 0.0, h],
            [h, h, h],
            [0.0, h, h],
        ]
    }

    #[test]
    fn a_cube_steps_its_side_over_the_wave_speed_and_weighs_its_volume() {
        let h = 2e-3;
        let sm =
            hex_steps_and_masses(&cube(h), &[[0, 1, 2, 3, 4, 5, 6, 7]], |_| 5e3, |_| 8e3).unwrap();
        assert!((sm[0].0 / (h / 5e3) - 1.0).abs() < 1e-12, "{sm:?}");
        assert!((sm[0].1 / (8e3 * h * h * h) - 1.0).abs() < 1e-12, "{sm:?}");
    }

    #[test]
    fn the_scaled_steps_reach_the_target_and_the_added_mass_meets_the_budget() {
        // One light, short-stepped element among a hundred heavy ones.
        let mut sm = vec![(1.0, 1.0); 100];
        sm.push((0.1, 0.01));
        let s = for_elements(&sm, 1e-3, "model.hexes").unwrap();
        assert!((s.added_fraction / 1e-3 - 1.0).abs() < 1e-9, "{s:?}");
        assert!((0.1 * s.scale[100].sqrt() / s.target_step - 1.0).abs() < 1e-12);
        assert!(s.scale[..100].iter().all(|&f| f == 1.0));
    }

    #[test]
    fn an_inverted_hexahedron_and_a_bad_budget_are_one_line_errors() {
        let e = hex_steps_and_masses(&cube(1.0), &[[0, 3, 2, 1, 4, 7, 6, 5]], |_| 1.0, |_| 1.0)
            .unwrap_err()
            .to_string();
        assert!(e.contains("element 0") && !e.contains('\n'), "{e}");
        let e = for_elements(&[(1.0, 1.0)], 0.5, "model.hexes")
            .unwrap_err()
            .to_string();
        assert!(e.contains("mass_scaling") && !e.contains('\n'), "{e}");
    }
}
