//! LAMMPS decks (`pair_style granular`, GRANULAR package, as in Debian's 20220106 build).
//!
//! The normal force is F = F_e(δ) − η_n v_n with the damping η_n of the chosen damping model:
//! `velocity` η₀, `mass_velocity` η₀ m*, `viscoelastic` η₀ a m* (a = √(R*δ)), `tsuji`
//! α(e₀) √(m* k_n a) with α the Tsuji polynomial of the coefficient e₀ given;
//! `limit_damping` clips the total force at 0 (twoball's `tension = 0`).
//!
//! - `hertz` → `hertz k_n` (F_e = k_n a δ, k_n = (4/3)E*), no damping: exact.
//! - `hertz-damped` → `hertz` with `damping tsuji`: the Tsuji form's γ_n = √5 |β| √(m* k_n a),
//!   so e₀ is the root of α(e₀) = √5 |β(e)| (α is Tsuji's fit, not the inverse of β): exact
//!   where α reaches √5 |β|, i.e. for e from about 0.114 to 0.9996; elsewhere an error.
//! - `kuwabara-kono` → `hertz` with `damping viscoelastic`, η₀ = 2E*A/m*: exact.
//! - `linear-dashpot` → `hooke k` with `damping velocity`, η₀ = c: exact.
//! - Other laws (hysteretic or speed-scaled damping): no normal model of `pair_style
//!   granular` (hooke, hertz, hertz/material, dmt, jkr); one-line error.

use super::liggghts::deck_modulus;
use super::scene::DeckScene;
use super::{cannot, damping_ratio, Code};
use crate::analytic::laws::Params;
use crate::error::Result;

/// Tsuji, Tanaka & Ishida's (1992) fit α(e) as LAMMPS's `damping tsuji` evaluates it.
pub fn tsuji_alpha(e: f64) -> f64 {
    const C: [f64; 7] = [1.2728, -4.2783, 11.087, -22.348, 27.467, -18.022, 4.8218];
    C.iter().rev().fold(0.0, |acc, c| acc * e + c)
}

/// The coefficient e₀ in [0, 1] whose Tsuji α equals `alpha`, if α reaches it (bisection:
/// α falls monotonically over [0, 1]).
pub fn tsuji_root(alpha: f64) -> Option<f64> {
    let (mut lo, mut hi) = (0.0f64, 1.0f64);
    if !(alpha <= tsuji_alpha(lo) && alpha >= tsuji_alpha(hi)) {
        return None;
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if tsuji_alpha(mid) > alpha {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Some(0.5 * (lo + hi))
}

/// The LAMMPS deck of `law` with `params`, or the one-line refusal.
pub fn deck(law: &str, params: &Params, s: &DeckScene) -> Result<String> {
    let (normal, note) = match law {
        "hertz" => {
            let kn = 4.0 / 3.0 * deck_modulus(params, s);
            (
                coefficients(&format!("hertz {kn:.12e} 0.0"), s.mu, "velocity"),
                format!("Maps exactly: k_n = (4/3) E_star sqrt(R_star/R*) = {kn:.9e} Pa, no damping."),
            )
        }
        "hertz-damped" => {
            let kn = 4.0 / 3.0 * deck_modulus(params, s);
            let e = params.get("e");
            let target = 5f64.sqrt() * damping_ratio(e);
            let Some(e0) = tsuji_root(target) else {
                return Err(cannot(
                    Code::Lammps,
                    law,
                    format!(
                        "e within about [0.114, 0.9996]: LAMMPS's damping tsuji reaches sqrt(5)|beta| = {target:.4} \
                         only for e there (e = {e})"
                    )
                    .as_str(),
                ));
            };
            damped(
                &format!("hertz {kn:.12e} {e0:.15e}"),
                "tsuji",
                params,
                s,
                format!(
                    "Maps exactly: k_n = (4/3) E_star sqrt(R_star/R*) = {kn:.9e} Pa; the law's damping is sqrt(5)|beta| sqrt(m* k_n a)\n\
                     # with |beta| = {b:.9e} (e = {e}); LAMMPS's tsuji damping is alpha(e0) sqrt(m* k_n a) with Tsuji's polynomial alpha,\n\
                     # so the coefficient written is e0 = {e0:.12} (alpha(e0) = sqrt(5)|beta|), NOT the restitution e.",
                    b = damping_ratio(e),
                ),
            )
        }
        "kuwabara-kono" => {
            let e_deck = deck_modulus(params, s);
            let kn = 4.0 / 3.0 * e_deck;
            let eta = 2.0 * e_deck * params.get("A") / s.mass();
            damped(
                &format!("hertz {kn:.12e} {eta:.12e}"),
                "viscoelastic",
                params,
                s,
                format!(
                    "Maps exactly: k_n = (4/3) E_star sqrt(R_star/R*) = {kn:.9e} Pa; viscoelastic damping eta0 a m* with\n\
                     # eta0 = 2 E* A/m* = {eta:.9e} 1/(m s) gives K (3/2) A sqrt(delta) delta_dot."
                ),
            )
        }
        "linear-dashpot" => {
            let k = params.get("k");
            let c = 2.0 * damping_ratio(params.get("e")) * (k * s.mass()).sqrt();
            damped(
                &format!("hooke {k:.12e} {c:.12e}"),
                "velocity",
                params,
                s,
                format!(
                    "Maps exactly: k = {k:.9e} N/m, velocity damping eta0 = c = 2 zeta sqrt(k m*) = {c:.9e} N s/m."
                ),
            )
        }
        _ => {
            return Err(cannot(
                Code::Lammps,
                law,
                "a law pair_style granular can express: hertz, hertz-damped, kuwabara-kono, linear-dashpot \
                 (its normal models hooke, hertz, hertz/material, dmt, jkr have no plastic or hysteretic branch)",
            ))
        }
    };
    let run = "lmp -in lammps.in -var vr VR -log none";
    let mut out = s.header("#", "LAMMPS (pair_style granular)", run, params);
    out += &format!("# {note}\n");
    out += &s.box_and_neighbours("sphere", "comm_modify vel yes\n");
    out += &format!("pair_style granular\npair_coeff * * {normal}\n");
    out += &s.two_atoms_and_trace();
    Ok(out)
}

/// The `pair_coeff` coefficients: the normal model with its coefficients `normal`, the
/// tangential model without history at friction coefficient `mu`, and `damping`.
fn coefficients(normal: &str, mu: f64, damping: &str) -> String {
    format!("{normal} tangential linear_nohistory 0.0 {mu:.12e} damping {damping}")
}

/// The coefficients and note of a damped law: `normal` with the damping model `model`,
/// `limit_damping` added (the force clipped at 0) unless the law's force may pull
/// (`tension`), and the mapping's `note` followed by what it says of the force's sign.
fn damped(
    normal: &str,
    model: &str,
    params: &Params,
    s: &DeckScene,
    note: String,
) -> (String, String) {
    let (limit, sign) = if params.tension() {
        ("", "Attraction allowed (tension = 1).")
    } else {
        (" limit_damping", "limit_damping: force >= 0 (tension = 0).")
    };
    (
        coefficients(normal, s.mu, &format!("{model}{limit}")),
        format!("{note} {sign}"),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tsuji_root_inverts_the_polynomial() {
        for e in [0.05, 0.3, 0.6, 0.9] {
            let a = tsuji_alpha(e);
            let r = tsuji_root(a).unwrap();
            assert!((r - e).abs() < 1e-12, "{e} {r}");
        }
        assert!(tsuji_root(2.0).is_none());
    }
}
