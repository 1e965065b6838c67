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
    let tension = |p: &Params| p.get("tension") >= 0.5;
    let limit = |t: bool| if t { "" } else { " limit_damping" };
    let (normal, note) = match law {
        "hertz" => {
            let kn = 4.0 / 3.0 * deck_modulus(params, s);
            (
                format!("hertz {kn:.12e} 0.0 tangential linear_nohistory 0.0 {mu:.12e} damping velocity", mu = s.mu),
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
            let t = tension(params);
            (
                format!(
                    "hertz {kn:.12e} {e0:.15e} tangential linear_nohistory 0.0 {mu:.12e} damping tsuji{}",
                    limit(t),
                    mu = s.mu
                ),
                format!(
                    "Maps exactly: k_n = (4/3) E_star sqrt(R_star/R*) = {kn:.9e} Pa; the law's damping is sqrt(5)|beta| sqrt(m* k_n a)\n\
                     # with |beta| = {b:.9e} (e = {e}); LAMMPS's tsuji damping is alpha(e0) sqrt(m* k_n a) with Tsuji's polynomial alpha,\n\
                     # so the coefficient written is e0 = {e0:.12} (alpha(e0) = sqrt(5)|beta|), NOT the restitution e. {}",
                    if t { "Attraction allowed (tension = 1)." } else { "limit_damping: force >= 0 (tension = 0)." },
                    b = damping_ratio(e),
                ),
            )
        }
        "kuwabara-kono" => {
            let e_deck = deck_modulus(params, s);
            let kn = 4.0 / 3.0 * e_deck;
            let eta = 2.0 * e_deck * params.get("A") / s.mass();
            let t = tension(params);
            (
                format!(
                    "hertz {kn:.12e} {eta:.12e} tangential linear_nohistory 0.0 {mu:.12e} damping viscoelastic{}",
                    limit(t),
                    mu = s.mu
                ),
                format!(
                    "Maps exactly: k_n = (4/3) E_star sqrt(R_star/R*) = {kn:.9e} Pa; viscoelastic damping eta0 a m* with\n\
                     # eta0 = 2 E* A/m* = {eta:.9e} 1/(m s) gives K (3/2) A sqrt(delta) delta_dot. {}",
                    if t { "Attraction allowed (tension = 1)." } else { "limit_damping: force >= 0 (tension = 0)." }
                ),
            )
        }
        "linear-dashpot" => {
            let k = params.get("k");
            let c = 2.0 * damping_ratio(params.get("e")) * (k * s.mass()).sqrt();
            let t = tension(params);
            (
                format!(
                    "hooke {k:.12e} {c:.12e} tangential linear_nohistory 0.0 {mu:.12e} damping velocity{}",
                    limit(t),
                    mu = s.mu
                ),
                format!(
                    "Maps exactly: k = {k:.9e} N/m, velocity damping eta0 = c = 2 zeta sqrt(k m*) = {c:.9e} N s/m. {}",
                    if t { "Attraction allowed (tension = 1)." } else { "limit_damping: force >= 0 (tension = 0)." }
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
    let b = 2.0 * s.diameter;
    out += &format!(
        "variable vr index {v:.12e}\n\
         units si\n\
         atom_style sphere\n\
         atom_modify map array\n\
         boundary f f f\n\
         newton off\n\
         comm_modify vel yes\n\
         region box block -{b:e} {b:e} -{b:e} {b:e} -{b:e} {b:e} units box\n\
         create_box 1 box\n\
         neighbor {skin:e} bin\n\
         neigh_modify delay 0\n\
         pair_style granular\n\
         pair_coeff * * {normal}\n",
        v = s.speed,
        skin = s.diameter / 10.0,
    );
    out += &s.two_atoms_and_trace();
    Ok(out)
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
