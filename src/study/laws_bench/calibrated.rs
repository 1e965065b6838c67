//! The damped laws ranked calibrated. A damped law's restitution is a parameter, not a
//! property of the metal, so its default (e = 0.8, or A = 1e-7 s) says nothing about its
//! form. Per metal, each law's one damping parameter is set (bisection over its interval; e
//! is monotone in it) so that its e equals the FE's at one reference point, the metal's
//! median speed at the largest diameter; the law is then judged at the metal's other points and ranked as
//! the material laws are ([`super::ranking`]).

use super::law_side::head_on_law_with;
use super::matrix::HeadOnPoint;
use super::ranking::{against_fe, metals_of, LawErrors};
use super::HeadOnResult;
use crate::analytic::laws::Registry;
use crate::error::Result;
use rayon::prelude::*;

/// The damped laws, the one parameter a calibration sets (the others at their defaults) and
/// the interval searched for it: (law, parameter, low, high, searched in ln).
pub const DAMPED: [(&str, &str, f64, f64, bool); 6] = [
    ("linear-dashpot", "e", 0.01, 1.0, false),
    ("hertz-damped", "e", 0.01, 1.0, false),
    ("hunt-crossley", "e", 0.01, 1.0, false),
    ("lankarani-nikravesh", "e", 0.01, 1.0, false),
    ("kuwabara-kono", "A", 1e-12, 1e-4, true),
    ("walton-braun", "e", 0.01, 1.0, false),
];

/// Relative mismatch in e at the reference below which a calibration has converged.
pub const MATCH: f64 = 1e-9;

/// True for a law of [`DAMPED`].
pub fn is_damped(law: &str) -> bool {
    DAMPED.iter().any(|d| d.0 == law)
}

/// One damped law calibrated on one metal.
#[derive(Debug, Clone, PartialEq)]
pub struct Calibrated {
    /// The law's errors over the metal's other points (the reference left out).
    pub errors: LawErrors,
    /// The fitted parameter: name and value (its unit: `twoball laws`).
    pub parameter: (&'static str, f64),
}

/// The damped laws of one metal, best first, and where they were calibrated.
#[derive(Debug, Clone, PartialEq)]
pub struct MetalCalibration {
    /// Metal preset.
    pub metal: String,
    /// Relative speed of the reference point, m/s.
    pub speed: f64,
    /// Ball diameter of the reference point, m.
    pub diameter: f64,
    /// The laws, sorted by [`LawErrors::combined`].
    pub laws: Vec<Calibrated>,
    /// The laws whose fit failed (they cannot reach the FE's e at the reference).
    pub failed: Vec<String>,
}

/// The reference point of `metal`: the median-speed point (the faster of the two middle
/// ones) among its points with an FE answer at their largest diameter.
pub fn reference<'a>(head_on: &'a [HeadOnResult], metal: &str) -> Option<&'a HeadOnResult> {
    let done = || {
        head_on
            .iter()
            .filter(move |h| h.point.metal == metal && h.fe_done().is_some())
    };
    let d = done().map(|h| h.point.diameter).fold(f64::NAN, f64::max);
    let mut at_d: Vec<&HeadOnResult> = done().filter(|h| h.point.diameter == d).collect();
    at_d.sort_by(|a, b| a.point.speed.total_cmp(&b.point.speed));
    at_d.get(at_d.len() / 2).copied()
}

/// Relative errors (law − FE)/FE of `law` with `overrides` at point `h`, in the order of
/// [`super::ranking::QUANTITIES`]; None without an FE answer.
fn errors_with(
    registry: &Registry,
    law: &str,
    overrides: &[(String, f64)],
    h: &HeadOnResult,
) -> Result<Option<[f64; 4]>> {
    let Some(f) = h.fe_done() else {
        return Ok(None);
    };
    let l = head_on_law_with(registry, law, overrides, &h.point, h.point.speed)?;
    Ok(Some(against_fe(
        [l.e, l.delta_max, l.contact_duration, l.peak_force],
        f,
    )))
}

/// The value of `param` in [lo, hi] (bisected in ln when `log`) at which `law`'s e equals
/// `target` at point `p`, within [`MATCH`]; None when e(lo) − target and e(hi) − target have
/// the same sign (no value in the interval reaches it; e is monotone in a damping parameter)
/// or the law fails to integrate at a value tried (the balls do not separate).
fn solve_parameter(
    registry: &Registry,
    law: &str,
    (param, lo, hi, log): (&str, f64, f64, bool),
    p: &HeadOnPoint,
    target: f64,
) -> Result<Option<f64>> {
    let gap = |x: f64| -> Option<f64> {
        let l = head_on_law_with(registry, law, &[(param.to_string(), x)], p, p.speed).ok()?;
        Some(l.e / target - 1.0)
    };
    let (to, from) = if log {
        (f64::ln as fn(f64) -> f64, f64::exp as fn(f64) -> f64)
    } else {
        (
            std::convert::identity as fn(f64) -> f64,
            std::convert::identity as fn(f64) -> f64,
        )
    };
    let (mut a, mut b) = (to(lo), to(hi));
    let (Some(ga), Some(gb)) = (gap(lo), gap(hi)) else {
        return Ok(None);
    };
    if ga.abs() < MATCH {
        return Ok(Some(lo));
    }
    if ga * gb > 0.0 {
        return Ok(None);
    }
    for _ in 0..200 {
        let m = 0.5 * (a + b);
        let Some(gm) = gap(from(m)) else {
            return Ok(None);
        };
        if gm.abs() < MATCH || (b - a).abs() <= 1e-14 * m.abs().max(1.0) {
            return Ok(Some(from(m)));
        }
        if (gm > 0.0) == (ga > 0.0) {
            a = m;
        } else {
            b = m;
        }
    }
    Ok(Some(from(0.5 * (a + b))))
}

/// Sets the damping parameter of `law` so that its e equals the FE's at `reference` and
/// judges the law at the other points of `points`; None when no value reaches it.
fn calibrate(
    registry: &Registry,
    (law, param, lo, hi, log): (&str, &'static str, f64, f64, bool),
    reference: &HeadOnResult,
    points: &[&HeadOnResult],
) -> Result<Option<Calibrated>> {
    let Some(fe) = reference.fe_done() else {
        return Ok(None);
    };
    let target = fe.e.value;
    let Some(value) = solve_parameter(
        registry,
        law,
        (param, lo, hi, log),
        &reference.point,
        target,
    )?
    else {
        return Ok(None);
    };
    let overrides = [(param.to_string(), value)];
    let mut rows = vec![];
    for h in points.iter().filter(|h| !std::ptr::eq(**h, reference)) {
        if let Some(r) = errors_with(registry, law, &overrides, h)? {
            rows.push(r);
        }
    }
    Ok(Some(Calibrated {
        errors: LawErrors::from_rows(law, &rows),
        parameter: (param, value),
    }))
}

/// Every damped law of `registry` calibrated on every metal of `head_on` (in the order
/// metals first appear) that has an FE answer.
///
/// Errors: a law that fails to integrate at a point.
pub fn calibrate_all(
    registry: &Registry,
    head_on: &[HeadOnResult],
) -> Result<Vec<MetalCalibration>> {
    let mut out = vec![];
    for metal in metals_of(head_on) {
        let Some(reference) = reference(head_on, metal) else {
            continue;
        };
        let points: Vec<&HeadOnResult> =
            head_on.iter().filter(|h| h.point.metal == metal).collect();
        let present: Vec<(&str, &'static str, f64, f64, bool)> = DAMPED
            .into_iter()
            .filter(|d| registry.normal(d.0).is_ok())
            .collect();
        let fitted: Vec<Option<Calibrated>> = present
            .par_iter()
            .map(|d| calibrate(registry, *d, reference, &points))
            .collect::<Result<_>>()?;
        let failed = present
            .iter()
            .zip(&fitted)
            .filter(|(_, f)| f.is_none())
            .map(|(d, _)| d.0.to_string())
            .collect();
        let mut laws: Vec<Calibrated> = fitted.into_iter().flatten().collect();
        laws.sort_by(|a, b| a.errors.combined.total_cmp(&b.errors.combined));
        out.push(MetalCalibration {
            metal: metal.to_string(),
            speed: reference.point.speed,
            diameter: reference.point.diameter,
            laws,
            failed,
        });
    }
    Ok(out)
}
