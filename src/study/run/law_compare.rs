//! The scene's `[laws]` comparison: each named normal law integrated on the run's balls and
//! speeds at first touch (the quantities `twoball laws run` gives), for results.json and the
//! printed summary.

use crate::analytic::impact::{integrate_spinning, LawImpact, DEFAULT_TOLERANCE};
use crate::analytic::laws::{ContactPair, NormalLaw, Registry, TangentialLaw};
use crate::analytic::Body;
use crate::error::{Error, Result};
use crate::scene::{Scene, Touch};
use crate::study::records::number::sci;
use serde::Serialize;
use std::collections::BTreeMap;

/// One law's answer for the scene's impact (results.json `laws[i]`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LawOutcome {
    /// Normal law name.
    pub law: String,
    /// Tangential law name.
    pub tangential_law: String,
    /// Resolved normal-law parameters (key → value in the parameter's SI unit).
    pub params: BTreeMap<String, f64>,
    /// Coefficient of restitution e, -.
    pub e: f64,
    /// Maximum approach δ_max, m.
    pub delta_max: f64,
    /// Contact duration t_c, s.
    pub contact_duration: f64,
    /// Peak normal force, N.
    pub peak_force: f64,
    /// One line when the impact lies outside the law's validity range (`twoball laws list`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub warning: Option<String>,
}

/// The analytical bodies of a scene at first touch: ball 1, its partner (ball 2, or a
/// `[wall]` scene's half-space at rest), their velocities in the contact frame (m/s), their
/// spins about the frame's z (rad/s) and the contact pair with the scene's kinetic friction
/// coefficient.
struct Bodies {
    b1: Body,
    b2: Body,
    v: [[f64; 3]; 2],
    w: [f64; 2],
    pair: ContactPair,
}

/// [`Bodies`] of `scene` at `touch`; errors: a ball or partner the analytical model refuses.
fn bodies(scene: &Scene, touch: &Touch) -> Result<Bodies> {
    let b1 = Body::ball(scene.ball1.material, scene.ball1.diameter, "ball1")?;
    let (mu, _) = scene.friction_coefficients();
    let [a, b] = touch.v;
    let (b2, b) = crate::study::records::outcome::analytic_partner(scene, b)?;
    let pair = ContactPair::between(&b1, &b2, mu);
    let (_, w2) = touch.partner(scene);
    Ok(Bodies {
        b1,
        b2,
        v: [a, b],
        w: [touch.w[0][2], w2[2]],
        pair,
    })
}

/// The impact of the bodies `b` at their contact-frame velocities and spins under laws `n`
/// and `t`; errors name the law `name` (an integration that fails, or balls that do not
/// approach).
fn impact(b: &Bodies, n: &dyn NormalLaw, t: &dyn TangentialLaw, name: &str) -> Result<LawImpact> {
    let [v1, v2] = b.v;
    let (v1, v2) = ([v1[0], v1[1]], [v2[0], v2[1]]);
    integrate_spinning(&b.b1, &b.b2, v1, v2, b.w, n, t, DEFAULT_TOLERANCE)
        .map_err(|e| Error::Numerical(format!("law {name}: {e}")))?
        .ok_or_else(|| Error::Numerical(format!("law {name}: the balls do not approach")))
}

/// Integrates every law of `scene.laws` on the balls of `scene` with the velocities (normal,
/// tangential) in the contact frame of `touch` and the scene's kinetic friction coefficient;
/// a `[wall]` scene's partner is the rigid half-space at rest.
/// Errors: a parameter outside its range (named `laws.params.LAW.KEY`), or an integration
/// that fails (named by the law).
pub fn compare_laws(scene: &Scene, touch: &Touch) -> Result<Vec<LawOutcome>> {
    if scene.laws.laws.is_empty() {
        return Ok(Vec::new());
    }
    let bodies = bodies(scene, touch)?;
    let pair = &bodies.pair;
    let registry = Registry::builtin();
    let tangential = &scene.laws.tangential;
    let (t, _) = registry
        .tangential(tangential)
        .and_then(|s| s.build_with(&[], pair))
        .map_err(|e| e.map_field(|f| format!("laws.tangential ({f})")))?;
    scene
        .laws
        .laws
        .iter()
        .map(|l| {
            let (n, p) = registry
                .normal(&l.name)
                .and_then(|s| s.build_with(&l.params, pair))
                .map_err(|e| e.map_field(|f| format!("laws.params.{f}")))?;
            let i = impact(&bodies, n.as_ref(), t.as_ref(), &l.name)?;
            let spec = registry.normal(&l.name)?;
            let warning = spec
                .validity
                .warning(spec.name, pair, &p, i.delta_max, i.approach_speed);
            Ok(LawOutcome {
                warning,
                law: l.name.clone(),
                tangential_law: tangential.clone(),
                params: p.iter().map(|(k, v)| (k.to_string(), v)).collect(),
                e: i.e,
                delta_max: i.delta_max,
                contact_duration: i.contact_duration,
                peak_force: i.peak_force,
            })
        })
        .collect()
}

/// One tangential law's answer for an oblique impact, with Hertz along the normal.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TangentialLawOutcome {
    /// Tangential law name.
    pub law: String,
    /// Tangential restitution −u⁺/u⁻ of the contact points, - (NaN without slip at touch).
    pub restitution: f64,
    /// Ball 1's spin after the impact about the contact frame's z axis, rad/s.
    pub spin1_after: f64,
}

/// Every built-in tangential law integrated, with Hertz along the normal, on the balls of
/// `scene` at first touch `touch` (the velocities in its contact frame, the scene's kinetic
/// friction coefficient; a `[wall]` scene's partner the rigid half-space at rest), in the
/// registry's order. Errors: an integration that fails (named by the law).
pub fn tangential_laws(scene: &Scene, touch: &Touch) -> Result<Vec<TangentialLawOutcome>> {
    let bodies = bodies(scene, touch)?;
    let pair = &bodies.pair;
    let registry = Registry::builtin();
    let (n, _) = registry.normal("hertz")?.build_with(&[], pair)?;
    registry
        .tangential
        .iter()
        .map(|spec| {
            let (t, _) = spec.build_with(&[], pair)?;
            let i = impact(&bodies, n.as_ref(), t.as_ref(), spec.name)?;
            Ok(TangentialLawOutcome {
                law: spec.name.to_string(),
                restitution: i.tangential_restitution().unwrap_or(f64::NAN),
                spin1_after: i.after.spin_after[0],
            })
        })
        .collect()
}

/// The printed table of the compared laws (empty string without laws).
pub fn law_table(laws: &[LawOutcome]) -> String {
    let Some(first) = laws.first() else {
        return String::new();
    };
    let mut s = format!(
        "contact laws (tangential {}; `twoball laws run` on the same balls and speeds):\n{:<22}{:>14}{:>16}{:>18}{:>16}\n",
        first.tangential_law, "law", "e [-]", "delta_max [m]", "contact time [s]", "peak force [N]"
    );
    for l in laws {
        s.push_str(&format!(
            "{:<22}{:>14}{:>16}{:>18}{:>16}\n",
            l.law,
            sci(l.e, 6),
            sci(l.delta_max, 6),
            sci(l.contact_duration, 6),
            sci(l.peak_force, 6)
        ));
    }
    for w in laws.iter().filter_map(|l| l.warning.as_ref()) {
        s.push_str(&format!("warning: {w}\n"));
    }
    s
}
