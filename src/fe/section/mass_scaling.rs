//! Mass scaling within a budget: the smallest quads of a section get a higher density, so
//! that no quad's Courant step is below a target step, and the target is the largest whose
//! added mass stays within a given fraction of the section's mass (the idea of LS-DYNA's
//! DT2MS and Abaqus's fixed mass scaling, with the target chosen from the budget).
//!
//! Why it is sound here: the quads that limit the step of a head-on section are those of
//! the contact pole and of an edge band, a region of size a (the contact radius) whose wave
//! transit a/c is three to four orders of magnitude shorter than the contact duration. A
//! density raised by s there slows that transit by √s and adds the mass s − 1 times the
//! region's, a fraction of about (a/R)³ of the ball's: the contact there stays
//! quasi-static. The budget bounds the added mass; its effect on e, δ_max and the contact
//! duration is measured, not assumed (docs/contact-penalty.md, "Mass scaling of the contact
//! region").
//!
//! A quad's step scales as √s: dt_e = l_e √(s ρ / M) with l_e its characteristic length
//! and M its P-wave modulus, so s_e = max(1, (T / dt_e)²) for a target step T.

use crate::error::{Error, Result};
use crate::fe::elements::ring::mass::element_masses;
use crate::fe::elements::ring::shape::characteristic_length;

/// Largest mass-scaling budget (added mass over the section's mass) accepted.
pub const MAX_BUDGET: f64 = 1e-2;

/// Bisection steps on ln T: the target is found to a relative 1e-12 of its bracket.
const BISECTIONS: usize = 80;

/// The density factors of a section and what they cost.
#[derive(Debug, Clone, PartialEq)]
pub struct MassScaling {
    /// Density factor of each quad (≥ 1; 1 where the quad's own step is at least the target).
    pub scale: Vec<f64>,
    /// The target Courant step T, s (before the step factor): no scaled quad's step is below it.
    pub target_step: f64,
    /// The smallest Courant step of the unscaled quads, s.
    pub unscaled_step: f64,
    /// Added mass over the section's mass (≤ the budget).
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
            format!("0 <= mass_scaling <= {MAX_BUDGET} (added mass over the section's)"),
        ))
    }
}

/// Courant step (s) and ring mass (kg) of each quad of `nodes` (r, z in m) and `quads`, with
/// `wave_speed` and `rho` (m/s, kg/m³) the quad's material's.
fn steps_and_masses(
    nodes: &[[f64; 2]],
    quads: &[[u32; 4]],
    wave_speed: impl Fn(usize) -> f64,
    rho: impl Fn(usize) -> f64,
) -> Vec<(f64, f64)> {
    quads
        .iter()
        .enumerate()
        .map(|(e, q)| {
            let x = q.map(|i| nodes[i as usize]);
            let m: f64 = element_masses(&x, rho(e)).iter().sum();
            (characteristic_length(&x) / wave_speed(e), m)
        })
        .collect()
}

/// Mass (kg) added by raising every quad of `quads` (Courant step, mass) to the step `t` (s).
fn added_mass(quads: &[(f64, f64)], t: f64) -> f64 {
    quads
        .iter()
        .map(|&(dt, m)| m * ((t / dt).powi(2) - 1.0).max(0.0))
        .sum()
}

/// The density factors that raise the smallest quads of the section (`nodes` in m, `quads`
/// counter-clockwise, each quad's material's P-wave speed `wave_speed(e)` in m/s and density
/// `rho(e)` in kg/m³) to the largest common target step whose added mass is at most `budget`
/// times the section's mass. A budget of 0 returns factors of 1.
///
/// Errors: a budget outside [0, [`MAX_BUDGET`]]; an empty mesh or a quad with a non-positive
/// or non-finite step or mass.
pub fn within_budget(
    nodes: &[[f64; 2]],
    quads: &[[u32; 4]],
    wave_speed: impl Fn(usize) -> f64,
    rho: impl Fn(usize) -> f64,
    budget: f64,
) -> Result<MassScaling> {
    check_budget(budget)?;
    if quads.is_empty() {
        return Err(Error::invalid("mesh.quads", 0, "at least one quad"));
    }
    let sm = steps_and_masses(nodes, quads, wave_speed, rho);
    if let Some(e) = sm
        .iter()
        .position(|&(dt, m)| !(dt.is_finite() && dt > 0.0 && m.is_finite() && m > 0.0))
    {
        return Err(Error::invalid(
            format!("mesh.quads[{e}]"),
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
    } else if added_mass(&sm, hi) <= allowed {
        hi
    } else {
        let (mut a, mut b) = (lo.ln(), hi.ln());
        for _ in 0..BISECTIONS {
            let mid = 0.5 * (a + b);
            if added_mass(&sm, mid.exp()) <= allowed {
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
        added_fraction: added_mass(&sm, target) / total,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A strip of `n` unit-depth quads along r ∈ [1, 2], of heights h_k = 2^{-k} m.
    fn strip(n: usize) -> (Vec<[f64; 2]>, Vec<[u32; 4]>) {
        let mut nodes = vec![[1.0, 0.0], [2.0, 0.0]];
        let mut quads = Vec::new();
        let mut z = 0.0;
        for k in 0..n {
            z += 0.5f64.powi(k as i32);
            let b = nodes.len() as u32;
            nodes.push([1.0, z]);
            nodes.push([2.0, z]);
            quads.push([b - 2, b - 1, b + 1, b]);
        }
        (nodes, quads)
    }

    #[test]
    fn a_zero_budget_scales_nothing() {
        let (nodes, quads) = strip(4);
        let s = within_budget(&nodes, &quads, |_| 1.0, |_| 1.0, 0.0).unwrap();
        assert!(s.scale.iter().all(|&f| f == 1.0));
        assert_eq!(s.added_fraction, 0.0);
        assert!((s.target_step - s.unscaled_step).abs() <= 1e-12 * s.unscaled_step);
    }

    #[test]
    fn the_added_mass_meets_the_budget_and_no_scaled_step_is_below_the_target() {
        let (nodes, quads) = strip(6);
        let budget = 5e-3;
        let s = within_budget(&nodes, &quads, |_| 3.0, |_| 2.0, budget).unwrap();
        assert!((s.added_fraction - budget).abs() < 1e-9 * budget, "{s:?}");
        let sm = steps_and_masses(&nodes, &quads, |_| 3.0, |_| 2.0);
        for (&(dt, _), &f) in sm.iter().zip(&s.scale) {
            assert!(dt * f.sqrt() >= s.target_step * (1.0 - 1e-12));
            if f > 1.0 {
                assert!((dt * f.sqrt() / s.target_step - 1.0).abs() < 1e-12);
            }
        }
        // The thinnest quad is scaled the most, the thickest not at all.
        assert!(s.scale[5] > s.scale[4] && s.scale[0] == 1.0);
        assert!(s.target_step > s.unscaled_step);
    }

    #[test]
    fn a_budget_too_small_for_the_thin_quad_leaves_the_target_between_the_steps() {
        // Two quads of heights 1 and 1/2: raising the thin one to the thick one's step costs
        // three of its masses, all of the strip's, far above 1 %.
        let (nodes, quads) = strip(2);
        let s = within_budget(&nodes, &quads, |_| 1.0, |_| 1.0, MAX_BUDGET).unwrap();
        let sm = steps_and_masses(&nodes, &quads, |_| 1.0, |_| 1.0);
        assert!(s.target_step > sm[1].0 && s.target_step < sm[0].0, "{s:?}");
        assert!((s.added_fraction / MAX_BUDGET - 1.0).abs() < 1e-9, "{s:?}");
        assert_eq!(s.scale[0], 1.0);
    }

    #[test]
    fn a_budget_that_covers_every_quad_stops_at_the_largest_step() {
        // 200 unit squares and one of height 1/2 on top: raising the thin one costs three
        // of its half masses, 0.75 % of the strip, within a budget of 1 %.
        let mut nodes = Vec::new();
        for k in 0..=200 {
            nodes.push([1.0, k as f64]);
            nodes.push([2.0, k as f64]);
        }
        nodes.push([1.0, 200.5]);
        nodes.push([2.0, 200.5]);
        let quads: Vec<[u32; 4]> = (0..201u32)
            .map(|k| [2 * k, 2 * k + 1, 2 * k + 3, 2 * k + 2])
            .collect();
        let s = within_budget(&nodes, &quads, |_| 1.0, |_| 1.0, MAX_BUDGET).unwrap();
        assert_eq!(s.target_step, 1.0);
        assert!((s.scale[200] - 4.0).abs() < 1e-12 && s.scale[..200].iter().all(|&f| f == 1.0));
        assert!(s.added_fraction < MAX_BUDGET && s.added_fraction > 0.5 * MAX_BUDGET);
    }

    #[test]
    fn a_bad_budget_is_one_line_naming_the_field() {
        let (nodes, quads) = strip(2);
        for b in [-1e-3, 0.5, f64::NAN] {
            let e = within_budget(&nodes, &quads, |_| 1.0, |_| 1.0, b)
                .unwrap_err()
                .to_string();
            assert!(e.contains("mass_scaling") && !e.contains('\n'), "{e}");
        }
    }
}
