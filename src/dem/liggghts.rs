//! LIGGGHTS-PUBLIC 3.8 decks (`pair_style gran`, per-type properties through `fix
//! property/global`).
//!
//! - `hertz`, `hertz-damped` → `model hertz` (youngsModulus = 2(1 − ν²)E for two equal balls,
//!   coefficientRestitution = e, 1 for `hertz`; limitForce from `tension`): exact at every
//!   speed. LIGGGHTS refuses youngsModulus > 1e9 Pa in SI units unless `hard_particles yes`.
//! - `linear-dashpot` → `model hooke/stiffness` (kn = k, gamman = c/m*: LIGGGHTS multiplies
//!   gamman by m*): exact at every speed.
//! - `walton-braun` → `model hooke/hysteresis`: its loading stiffness is hooke's
//!   characteristic-velocity rule kn = (16/15)√R* Y* (15 m* v_c²/(16 √R* Y*))^{1/5} (Y* from
//!   youngsModulus and poissonsRatio), and its unloading stiffness grows with the largest
//!   overlap, k₂ = kn + (k₂,max − kn) δ_max/δ_lim for δ_max < δ_lim = k₂,max/(k₂,max − kn)
//!   φ_F 2R*, so e² = kn/k₂ holds at one speed only; the header gives the speeds over which e
//!   stays within 0.1 %.
//! - Other laws: no LIGGGHTS-PUBLIC model (one-line error).

use super::scene::DeckScene;
use super::{cannot, damping_ratio, Code};
use crate::analytic::laws::Params;
use crate::error::Result;

/// Relative change of e that bounds the speed range of the one-speed hysteresis mapping.
pub const HYSTERESIS_TOLERANCE: f64 = 1e-3;

/// The LIGGGHTS deck of `law` with `params`, or the one-line refusal.
pub fn deck(law: &str, params: &Params, s: &DeckScene) -> Result<String> {
    let nu = s.poisson;
    let (model, props, note, range) = match law {
        "hertz" | "hertz-damped" => {
            let e_deck = deck_modulus(params, s);
            let (e, tension) = if law == "hertz" {
                (1.0, true)
            } else {
                (params.get("e"), params.tension())
            };
            (
                format!(
                    "hertz tangential history limitForce {}",
                    if tension { "off" } else { "on" }
                ),
                vec![
                    format!("youngsModulus peratomtype {:.12e}", 2.0 * (1.0 - nu * nu) * e_deck),
                    format!("poissonsRatio peratomtype {nu:.12e}"),
                    format!("coefficientRestitution peratomtypepair 1 {e:.12e}"),
                    format!("coefficientFriction peratomtypepair 1 {:.12e}", s.mu),
                ],
                format!(
                    "Maps exactly at every speed: E* = E_star sqrt(R_star/R*) = {e_deck:.9e} Pa (youngsModulus = 2(1 - nu^2) E*),\n\
                     # coefficientRestitution = {e} (LIGGGHTS's damping is the Tsuji form of the law), limitForce {} (tension = {}).",
                    if tension { "off" } else { "on" },
                    u8::from(tension)
                ),
                s.range,
            )
        }
        "linear-dashpot" => {
            let k = params.get("k");
            let c = 2.0 * damping_ratio(params.get("e")) * (k * s.mass()).sqrt();
            let tension = params.tension();
            (
                format!(
                    "hooke/stiffness tangential history limitForce {}",
                    if tension { "off" } else { "on" }
                ),
                vec![
                    format!("kn peratomtypepair 1 {k:.12e}"),
                    format!("kt peratomtypepair 1 {:.12e}", 2.0 / 7.0 * k),
                    format!("gamman peratomtypepair 1 {:.12e}", c / s.mass()),
                    "gammat peratomtypepair 1 0.0".to_string(),
                    format!("coefficientFriction peratomtypepair 1 {:.12e}", s.mu),
                ],
                format!(
                    "Maps exactly at every speed: kn = k, gamman = c/m* = {:.9e} 1/s (LIGGGHTS multiplies gamman by m*),\n\
                     # c = 2 zeta sqrt(k m*) = {c:.9e} N s/m; limitForce {} (tension = {}). kt is not fitted (head-on: unused).",
                    c / s.mass(),
                    if tension { "off" } else { "on" },
                    u8::from(tension)
                ),
                s.range,
            )
        }
        "walton-braun" => hysteresis(params, s)?,
        "thornton" => {
            return Err(cannot(
                Code::Liggghts,
                law,
                "a law LIGGGHTS-PUBLIC 3.8 reproduces: its thornton_ning model without adhesion (surface energy 0) \
                 unloads with the tangent stiffness 2E* sqrt(R* delta) of the original radius, not with Thornton's R_p",
            ))
        }
        _ => {
            return Err(cannot(
                Code::Liggghts,
                law,
                "a law LIGGGHTS-PUBLIC 3.8 has a model for: hertz, hertz-damped (model hertz), \
                 linear-dashpot (hooke/stiffness), walton-braun (hooke/hysteresis, at one speed)",
            ))
        }
    };
    let run = "liggghts -in liggghts.in -var vr VR";
    let mut out = s.header("#", "LIGGGHTS-PUBLIC 3.8", run, params);
    out += &format!("# {note}\n");
    if range != s.range {
        out += &format!(
            "# Holds only for {:.9} <= VR <= {:.9} m/s (e within {} of the law's); outside, LIGGGHTS's e differs.\n",
            range.0, range.1, HYSTERESIS_TOLERANCE
        );
    }
    out += &s.box_and_neighbours(
        "granular",
        "communicate single vel yes\nhard_particles yes\n",
    );
    for (i, p) in props.iter().enumerate() {
        out += &format!("fix m{} all property/global {p}\n", i + 1);
    }
    out += &format!(
        "pair_style gran model {model}\n\
         pair_coeff * *\n"
    );
    out += &s.two_atoms_and_trace();
    Ok(out)
}

/// E* the deck gives the balls so that E* √R* equals the law's E_star √R_star (head-on
/// Hertz laws depend on that product only), Pa.
pub(crate) fn deck_modulus(params: &Params, s: &DeckScene) -> f64 {
    params.get("E_star") * (params.get("R_star") / s.radius()).sqrt()
}

type Mapping = (String, Vec<String>, String, (f64, f64));

/// `walton-braun` as `hooke/hysteresis`: exact at the reference speed, within
/// [`HYSTERESIS_TOLERANCE`] in e over the returned range.
fn hysteresis(params: &Params, s: &DeckScene) -> Result<Mapping> {
    let k = params.get("k");
    let e = params.get("e");
    let (m, r, nu) = (s.mass(), s.radius(), s.poisson);
    // kn = (16/15)(15 m*/16)^{1/5} (sqrt(R*) Y*)^{4/5} with v_c = 1 m/s.
    let y_star = (k / (16.0 / 15.0 * (15.0 * m / 16.0).powf(0.2))).powf(1.25) / r.sqrt();
    // At the reference speed δ_ref = v √(m*/k); δ_lim = 2 δ_ref puts it mid-way on the
    // ramp, where k₂(δ_ref) = k/e² needs k₂,max = k (2/e² − 1).
    let d_ref = s.speed * (m / k).sqrt();
    let d_lim = 2.0 * d_ref;
    let k2_max = k * (2.0 / (e * e) - 1.0);
    let ratio = k2_max / k;
    let phi = d_lim * (k2_max - k) / (k2_max * 2.0 * r);
    // e(v)² = 1/(1 + (1/e² − 1) v/v_ref) for v < 2 v_ref: the speeds where e stays within
    // the tolerance.
    let g = 1.0 / (e * e);
    let at = |f: f64| s.speed * (g / (f * f) - 1.0) / (g - 1.0);
    let range = if e < 1.0 {
        (
            at(1.0 + HYSTERESIS_TOLERANCE),
            at(1.0 - HYSTERESIS_TOLERANCE).min(2.0 * s.speed),
        )
    } else {
        s.range
    };
    Ok((
        "hooke/hysteresis tangential history".to_string(),
        vec![
            format!("youngsModulus peratomtype {:.12e}", 2.0 * (1.0 - nu * nu) * y_star),
            format!("poissonsRatio peratomtype {nu:.12e}"),
            "characteristicVelocity scalar 1.0".to_string(),
            "coefficientRestitution peratomtypepair 1 1.0".to_string(),
            format!("coefficientFriction peratomtypepair 1 {:.12e}", s.mu),
            format!("coefficientMaxElasticStiffness peratomtypepair 1 {ratio:.12e}"),
            "coefficientAdhesionStiffness peratomtypepair 1 0.0".to_string(),
            format!("coefficientPlasticityDepth peratomtypepair 1 {phi:.12e}"),
        ],
        format!(
            "Maps at the reference speed VR = {v} m/s only: LIGGGHTS's loading stiffness kn = k = {k:.9e} N/m comes from\n\
             # hooke's rule (characteristicVelocity 1 m/s, youngsModulus chosen for it); coefficientRestitution 1 turns its\n\
             # damping off; its unloading stiffness k2 = kn + (k2max - kn) delta_max/delta_lim grows with the largest overlap\n\
             # (k2max = {ratio:.6} kn, delta_lim = {d_lim:.6e} m from coefficientPlasticityDepth), so k2 = kn/e^2 (e = {e})\n\
             # at delta_max = {d_ref:.6e} m only: e(VR)^2 = 1/(1 + (1/e^2 - 1) VR/{v}) for VR < {hi} m/s.",
            v = s.speed,
            hi = 2.0 * s.speed,
        ),
        range,
    ))
}

/// The speed range (m/s) over which the LIGGGHTS export of `law` with `params` on `s`
/// reproduces the law: the deck's own range, or the narrow one of the one-speed mapping.
pub fn valid_range(law: &str, params: &Params, s: &DeckScene) -> Result<(f64, f64)> {
    if law == "walton-braun" {
        Ok(hysteresis(params, s)?.3)
    } else {
        Ok(s.range)
    }
}
