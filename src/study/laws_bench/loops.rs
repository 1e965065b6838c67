//! Contact laws against a quasi-static FE loop (`twoball static --laws`): each normal law's
//! quasi-static curve (approach rate 0) at the loop's approaches, loading up to the loop's
//! turn and unloading from the law's own turn there, and the RMS force error of each branch
//! relative to the loop's peak force: how far a law's F(δ) is from the continuum's.
//!
//! The loop is one ball of two identical ones against their frictionless symmetry plane: a
//! law's approach δ of the pair is twice the ball's approach to the plane, at the same
//! force; for a ball on a rigid wall the law's pair is the ball and the wall, δ the ball's
//! approach. Rate-dependent laws show their elastic backbone (their damping needs a
//! rate); their unloading retraces it.

use crate::analytic::laws::{ContactPair, NormalLaw, Registry, Turn};
use crate::analytic::Body;
use crate::error::Result;
use crate::material::Material;
use crate::study::run::quasi_static::{LoopPoint, StaticLoop};
use serde::{Deserialize, Serialize};

/// One law on one loop.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LawOnLoop {
    /// The law's name.
    pub law: String,
    /// RMS of (F_law − F_FE) over the loading points, over the FE peak force, -.
    pub loading_rms: f64,
    /// RMS of (F_law − F_FE) over the unloading points, over the FE peak force, -.
    pub unloading_rms: f64,
    /// The law's force at the loop's turn over the FE's, -.
    pub peak_ratio: f64,
    /// The law's permanent approach of the ball (half the pair's for two balls) after the
    /// turn, m.
    pub residual_approach: f64,
    /// The law's force at each loop point (loading, then unloading), N.
    pub forces: Vec<f64>,
}

/// The pair a static loop stands for, as results.json records it under `contact_pair`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct LoopPair {
    /// The ball's material.
    pub material: Material,
    /// Diameter of the ball, m.
    pub diameter_m: f64,
    /// True for a ball on a rigid wall; false for one of two identical balls (the loop's
    /// plane is their symmetry plane, so the pair's approach is twice the ball's).
    pub rigid_wall: bool,
    /// Relative approach speed of the impact the loop stands for, m/s (rate-dependent laws
    /// are set at it).
    pub approach_speed_m_per_s: f64,
}

impl LoopPair {
    /// The law's contact pair and the pair's approach per unit approach of the ball.
    ///
    /// Errors: a diameter or material [`Body::ball`] refuses.
    pub fn contact_pair(&self) -> Result<(ContactPair, f64)> {
        let b = Body::ball(self.material, self.diameter_m, "ball")?;
        let (partner, share) = if self.rigid_wall {
            (Body::RigidWall, 1.0)
        } else {
            (b, 2.0)
        };
        Ok((ContactPair::between(&b, &partner, self.material.mu), share))
    }
}

/// Every normal law of `registry` (default parameters for `pair`) on `l`.
///
/// Errors: a diameter or material [`Body::ball`] refuses; a law that cannot be built.
pub fn laws_on_loop(
    l: &StaticLoop,
    pair: &LoopPair,
    registry: &Registry,
) -> Result<Vec<LawOnLoop>> {
    let (contact, share) = pair.contact_pair()?;
    let speed = pair.approach_speed_m_per_s;
    registry
        .normal
        .iter()
        .map(|spec| {
            let (law, _) = registry.normal(spec.name)?.build_with(&[], &contact)?;
            Ok(on_loop(spec.name, law.as_ref(), l, speed, share))
        })
        .collect()
}

/// One law on `l` (the impact's approach speed `speed`, m/s); the pair's approach is `share`
/// times the ball's.
pub fn on_loop(
    name: &str,
    law: &dyn NormalLaw,
    l: &StaticLoop,
    speed: f64,
    share: f64,
) -> LawOnLoop {
    let peak = l.summary;
    let pair_delta = |p: &LoopPoint| share * p.approach;
    let top = share * peak.delta_max;
    let f_top = law.loading(top, 0.0, speed);
    let turn = Turn::new(law, top, f_top);
    let load: Vec<f64> = l
        .loading
        .iter()
        .map(|p| law.loading(pair_delta(p), 0.0, speed).max(0.0))
        .collect();
    let unload: Vec<f64> = l
        .unloading
        .iter()
        .map(|p| law.unloading(pair_delta(p), 0.0, speed, &turn).max(0.0))
        .collect();
    let rms = |fe: &[LoopPoint], law: &[f64]| {
        let s: f64 = fe.iter().zip(law).map(|(p, f)| (f - p.force).powi(2)).sum();
        (s / fe.len().max(1) as f64).sqrt() / peak.force_at_max
    };
    LawOnLoop {
        law: name.to_string(),
        loading_rms: rms(&l.loading, &load),
        unloading_rms: rms(&l.unloading, &unload),
        peak_ratio: f_top / peak.force_at_max,
        residual_approach: turn.residual() / share,
        forces: load.into_iter().chain(unload).collect(),
    }
}

/// The printed table, one law a line.
pub fn table(laws: &[LawOnLoop]) -> String {
    let mut out = String::from(
        "normal laws on the finest loop (quasi-static: rate 0), RMS force error over the FE peak:\n  \
         law                     loading  unloading  F_law/F_FE at the turn  residual approach\n",
    );
    for l in laws {
        out += &format!(
            "  {:<22} {:>7.2} % {:>8.2} % {:>14.4} {:>22.4e} m\n",
            l.law,
            100.0 * l.loading_rms,
            100.0 * l.unloading_rms,
            l.peak_ratio,
            l.residual_approach
        );
    }
    out
}

/// The loop's points in order, each with its phase (`loading`, `unloading`).
pub fn phases(l: &StaticLoop) -> impl Iterator<Item = (&'static str, &LoopPoint)> {
    let load = l.loading.iter().map(|p| ("loading", p));
    load.chain(l.unloading.iter().map(|p| ("unloading", p)))
}

/// laws.csv: each loop point with the FE force and every law's, N (approach of the ball, m).
pub fn csv(l: &StaticLoop, laws: &[LawOnLoop]) -> String {
    let mut out = String::from("phase,approach_m,fe_N");
    for law in laws {
        out += &format!(",{}_N", law.law);
    }
    out.push('\n');
    for (k, (phase, p)) in phases(l).enumerate() {
        out += &format!("{phase},{:.9e},{:.9e}", p.approach, p.force);
        for law in laws {
            out += &format!(",{:.9e}", law.forces[k]);
        }
        out.push('\n');
    }
    out
}
