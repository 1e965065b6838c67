//! The law side of the benchmark: every normal law of a registry, with its default
//! parameters for the pair (as `twoball laws run` resolves them), integrated on each head-on
//! point; each tangential law on each oblique point.

use super::matrix::{HeadOnPoint, ObliquePoint};
use crate::analytic::impact::{integrate, LawImpact, DEFAULT_TOLERANCE};
use crate::analytic::laws::coulomb::Coulomb;
use crate::analytic::laws::{ContactPair, Registry};
use crate::analytic::Body;
use crate::error::{Error, Result};

/// Most rows kept of a law's contact history (evenly thinned; the figures need no more).
pub const CURVE_ROWS: usize = 160;

/// One normal law's answer for one head-on point.
#[derive(Debug, Clone, PartialEq)]
pub struct LawPoint {
    /// Normal law name.
    pub law: String,
    /// Coefficient of restitution, -.
    pub e: f64,
    /// Maximum approach, m.
    pub delta_max: f64,
    /// Contact duration, s.
    pub contact_duration: f64,
    /// Peak normal force, N.
    pub peak_force: f64,
    /// Contact history, rows [t (s), δ (m), F (N)], at most [`CURVE_ROWS`].
    pub curve: Vec<[f64; 3]>,
    /// Why the point lies outside the law's validity range (`twoball laws list`), if it does.
    pub outside: Option<String>,
}

/// One tangential law's answer for one oblique point.
#[derive(Debug, Clone, PartialEq)]
pub struct ObliqueLaw {
    /// Tangential law name.
    pub law: String,
    /// Normal law it was paired with.
    pub normal_law: String,
    /// Coefficient of restitution, -.
    pub e: f64,
    /// Tangential restitution of the contact points −u⁺/u⁻, -.
    pub tangential_restitution: f64,
    /// Spin of ball 1 after the impact about n × t, rad/s.
    pub spin: f64,
    /// Tangential velocity of ball 1 after, m/s.
    pub v1t_after: f64,
}

/// Maw, Barber & Fawcett's elastic theory on one oblique point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Theory {
    /// Tangential restitution of the contact points −u⁺/u⁻, -.
    pub tangential_restitution: f64,
    /// Spin of ball 1 after the impact about n × t, rad/s.
    pub spin: f64,
}

/// The theory ([`crate::analytic::maw_barber_fawcett::impact`] at its default resolution)
/// on oblique point `p`: ball 1 at the relative velocity against ball 2 at rest (the same
/// relative motion as the FE's equal and opposite speeds).
///
/// Errors: a ball the body rejects, an impact that fails.
pub fn theory_on_point(p: &ObliquePoint) -> Result<Theory> {
    use crate::analytic::maw_barber_fawcett::{impact, DEFAULT_RESOLUTION};
    let (b, _) = pair_of(p.material, p.diameter)?;
    let v = [p.normal_speed, p.ratio * p.normal_speed];
    let i = impact(
        &b,
        &b,
        [v, [0.0, 0.0]],
        [0.0, 0.0],
        p.material.mu,
        DEFAULT_RESOLUTION,
    )?
    .ok_or_else(|| Error::invalid("oblique.normal_speed", p.normal_speed, "> 0 m/s"))?;
    Ok(Theory {
        tangential_restitution: i.tangential_restitution().unwrap_or(f64::NAN),
        spin: i.spin_after[0],
    })
}

/// `rows` thinned to at most `n` evenly spaced rows, the first and last kept.
pub fn thin<T: Copy>(rows: &[T], n: usize) -> Vec<T> {
    if rows.len() <= n || n < 2 {
        return rows.to_vec();
    }
    (0..n)
        .map(|i| rows[i * (rows.len() - 1) / (n - 1)])
        .collect()
}

/// The ball and the pair of two identical balls (friction coefficient from the material).
fn pair_of(material: crate::material::Material, diameter: f64) -> Result<(Body, ContactPair)> {
    let b = Body::ball(material, diameter, "ball")?;
    Ok((b, ContactPair::between(&b, &b, material.mu)))
}

/// Integrates normal law `law` (default parameters) on two balls of `p.material`,
/// `p.diameter` at relative speed `speed` (m/s), head-on.
///
/// Errors: an unknown law, an integration that fails (named by the law).
pub fn head_on_law(
    registry: &Registry,
    law: &str,
    p: &HeadOnPoint,
    speed: f64,
) -> Result<LawImpact> {
    head_on_law_with(registry, law, &[], p, speed)
}

/// [`head_on_law`] with the parameters `overrides` (name, value in the parameter's unit).
///
/// Errors: as [`head_on_law`]; an unknown parameter or one out of its range.
pub fn head_on_law_with(
    registry: &Registry,
    law: &str,
    overrides: &[(String, f64)],
    p: &HeadOnPoint,
    speed: f64,
) -> Result<LawImpact> {
    let (b, pair) = pair_of(p.material, p.diameter)?;
    let (n, _) = registry.normal(law)?.build_with(overrides, &pair)?;
    integrate(
        &b,
        &b,
        [0.5 * speed, 0.0],
        [-0.5 * speed, 0.0],
        n.as_ref(),
        &Coulomb { mu: pair.mu },
        DEFAULT_TOLERANCE,
    )
    .map_err(|e| Error::Numerical(format!("law {law}: {e}")))?
    .ok_or_else(|| Error::invalid("speed", speed, "> 0 m/s"))
}

/// Every normal law of `registry` on head-on point `p`.
///
/// Errors: as [`head_on_law`].
pub fn laws_on_point(registry: &Registry, p: &HeadOnPoint) -> Result<Vec<LawPoint>> {
    registry
        .normal
        .iter()
        .map(|s| {
            let i = head_on_law(registry, s.name, p, p.speed)?;
            let (_, pair) = pair_of(p.material, p.diameter)?;
            let params = crate::analytic::laws::Params::resolve(s.name, s.params, &[], &pair)?;
            let outside = s
                .validity
                .warning(s.name, &pair, &params, i.delta_max, p.speed);
            let rows: Vec<[f64; 3]> = i.history.iter().map(|h| [h.t, h.delta, h.force]).collect();
            Ok(LawPoint {
                law: s.name.to_string(),
                e: i.e,
                delta_max: i.delta_max,
                contact_duration: i.contact_duration,
                peak_force: i.peak_force,
                curve: thin(&rows, CURVE_ROWS),
                outside,
            })
        })
        .collect()
}

/// Every tangential law of `registry`, each with normal law `normal` (default parameters),
/// on oblique point `p`.
///
/// Errors: an unknown law, an integration that fails.
pub fn tangential_laws_on_point(
    registry: &Registry,
    normal: &str,
    p: &ObliquePoint,
) -> Result<Vec<ObliqueLaw>> {
    let (b, pair) = pair_of(p.material, p.diameter)?;
    let (vn, vt) = (0.5 * p.normal_speed, 0.5 * p.ratio * p.normal_speed);
    registry
        .tangential
        .iter()
        .map(|s| {
            let (n, _) = registry.normal(normal)?.build_with(&[], &pair)?;
            let (t, _) = registry.tangential(s.name)?.build_with(&[], &pair)?;
            let i = integrate(
                &b,
                &b,
                [vn, vt],
                [-vn, -vt],
                n.as_ref(),
                t.as_ref(),
                DEFAULT_TOLERANCE,
            )
            .map_err(|e| Error::Numerical(format!("laws {normal} + {}: {e}", s.name)))?
            .ok_or_else(|| Error::invalid("oblique.normal_speed", p.normal_speed, "> 0 m/s"))?;
            Ok(ObliqueLaw {
                law: s.name.to_string(),
                normal_law: normal.to_string(),
                e: i.e,
                tangential_restitution: i.tangential_restitution().unwrap_or(f64::NAN),
                spin: i.after.spin_after[0],
                v1t_after: i.after.v1_after[1],
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn thin_keeps_ends_and_count() {
        let v: Vec<usize> = (0..1000).collect();
        let t = thin(&v, 10);
        assert_eq!(t.len(), 10);
        assert_eq!((t[0], t[9]), (0, 999));
        assert_eq!(thin(&v[..5], 10).len(), 5);
    }
}
