//! The benchmark's quasi-static part: at each metal of the matrix, its largest diameter and
//! the loop speeds ([`super::matrix::loop_speeds`]: the matrix speeds nearest 0.1, 1 and
//! 10 m/s), the FE loop of one ball of the pair (`twoball static --support free`: the whole
//! ball under the body force that balances the contact, loaded to the kinetic energy it
//! brings to the symmetry plane, banded ladder levels 0 and 1) with its bars, cached as the
//! head-on points are, and every normal law's quasi-static curve on the finest loop
//! ([`super::loops`]).

use super::cache::CacheKey;
use super::fe::head_on_case;
use super::loops::{laws_on_loop, LawOnLoop, LoopPair};
use super::matrix::HeadOnPoint;
use crate::analytic::laws::Registry;
use crate::error::{Error, Result};
use crate::study::convergence::static_ladder::{
    free_ball_ladder, DEFAULT_INCREMENTS, DEFAULT_LEVEL,
};
use crate::study::records::estimate::{value_and_error, Estimate};
use crate::study::run::quasi_static::StaticLoop;
use serde::{Deserialize, Serialize};

/// The FE model of the loops, as their cache files name it.
pub const LOOP_MODEL: &str = "section static loop: free ball, banded ladder levels 0 and 1 \
                              (band 5 over 0.6-1.15 contact edges), 20 loading increments at \
                              level 0 and half as many unloading";

/// One loop of the matrix: the head-on point whose ball it loads.
#[derive(Debug, Clone, PartialEq)]
pub struct LoopCase(pub HeadOnPoint);

impl CacheKey for LoopCase {
    fn key(&self) -> String {
        let p = &self.0;
        format!("loop_{}_D{:.4e}_v{:.6e}", p.metal, p.diameter, p.speed)
    }
    fn describe(&self) -> String {
        let p = &self.0;
        format!(
            "static loop {} D = {} mm v = {:.4} m/s",
            p.metal,
            1e3 * p.diameter,
            p.speed
        )
    }
    /// Within a factor of two at every speed (the mesh follows the contact radius; the
    /// fastest loops take twice the increments), so all alike.
    fn cost(&self) -> f64 {
        1.0
    }
}

/// What the FE says about one loop: its numbers with their bars and the finest loop.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LoopFe {
    /// Quasi-static coefficient of restitution √(W_returned / W_in), -.
    #[serde(with = "value_and_error")]
    pub e: Estimate,
    /// Largest approach of the ball's centre of mass to the plane, m.
    #[serde(with = "value_and_error")]
    pub delta_max: Estimate,
    /// Contact force at δ_max, N.
    #[serde(with = "value_and_error")]
    pub force_at_max: Estimate,
    /// Approach left after unloading, m.
    #[serde(with = "value_and_error")]
    pub residual_approach: Estimate,
    /// The finest level's loop.
    pub finest: StaticLoop,
    /// Wall seconds of the pilot and the ladder.
    pub seconds: f64,
}

/// The loop of `case`'s ball, free, loaded to the kinetic energy it brings to the symmetry
/// plane, with its bars (as `twoball static --support free` on the pair's scene).
///
/// Errors: those of [`free_ball_ladder`] (a contact radius outside the ladder's range, a
/// static solve that does not converge).
pub fn loop_fe(case: &LoopCase) -> Result<LoopFe> {
    let start = std::time::Instant::now();
    let (mut loops, est) =
        free_ball_ladder(&head_on_case(&case.0), DEFAULT_LEVEL, DEFAULT_INCREMENTS)?;
    let finest = loops
        .pop()
        .ok_or_else(|| Error::Numerical("static ladder: no loop".into()))?;
    Ok(LoopFe {
        e: est.e.as_recorded(),
        delta_max: est.delta_max.as_recorded(),
        force_at_max: est.force_at_max.as_recorded(),
        residual_approach: est.residual_approach.as_recorded(),
        finest,
        seconds: start.elapsed().as_secs_f64(),
    })
}

/// The pair a loop of `point` stands for (two identical balls, the point's speed).
pub fn loop_pair(point: &HeadOnPoint) -> LoopPair {
    LoopPair {
        material: point.material,
        diameter_m: point.diameter,
        rigid_wall: false,
        approach_speed_m_per_s: point.speed,
    }
}

/// Every normal law of `registry` on the finest loop of `fe`, the loop of `point`.
///
/// Errors: those of [`laws_on_loop`].
pub fn laws_on(fe: &LoopFe, point: &HeadOnPoint, registry: &Registry) -> Result<Vec<LawOnLoop>> {
    laws_on_loop(&fe.finest, &loop_pair(point), registry)
}
