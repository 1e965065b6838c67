//! Multi-time-step explicit integration (subcycling) by nodal partition (Belytschko, Yen &
//! Mullen 1979; stability: Smolinski, Sleith & Belytschko 1996) with LS-DYNA's aligned
//! power-of-two step classes: one scheme for every explicit model.
//!
//! - Fine step h: the single-step step (time_step_factor × the smallest Courant limit of the
//!   elements, or an interaction's limit).
//! - Node limit Δt_i: the smallest Courant step of the node's elements and, for a node a
//!   contact may act on, its spring's stable step
//!   ([`Interaction::node_limits`](crate::fe::interaction::Interaction::node_limits)), at most
//!   the neighbour ratio times the limit of any node it shares an element with.
//! - Node level L_i: the node steps 2^{L_i} h, the largest k up to the cap with 2^k h · margin
//!   ≤ time_step_factor · Δt_i, climbing only by the climbing factor ([`levels::LevelRule`]:
//!   one rule, each model's constants). A model may hold nodes at level 0 (the 3D model: the
//!   nodes its interactions act on, whose forces it applies every fine step).
//! - Element update level u_e = min of its nodes' levels: an element is updated whenever one
//!   of its nodes is due, with its own step 2^{u_e} h, from its nodes' current positions; a
//!   coarser node of it has not been kicked since its last update, so it drifted at constant
//!   velocity: BYM's linear interpolation of the coarse nodes. No element force is ever held
//!   or extrapolated for a finer node, so no force lags.
//! - Every node drifts every fine step (x += h v; a coarse node's velocity is constant between
//!   its kicks, so this is its own step exactly). A due node gets the Box 6.1 half-kicks of
//!   its own step with its (all fresh) element forces: closing 2^{L_old} h, opening
//!   2^{L_new} h.
//! - Levels are aligned (level-k nodes and elements are due at multiples of 2^k), so all are
//!   due together every 2^top fine steps (a synchronisation). There h and every level are
//!   chosen afresh from the limits of that instant; the 3D model also guards the interval
//!   between them ([`blocks`]).
//!
//! Energy: the Box 6.1 balance of the kicks stays exact; the element-side internal energy of
//! an element with coarser nodes differs from the nodal work by O(H ḟ·v) (BYM conserves a
//! pseudo-energy), a reversible difference of ~0.2 % of the peak strain energy in an impact.
//! The resonance instability of impulse (r-RESPA-type) schemes, where a coarse element kicks a
//! fine node once per coarse step, is absent because a fine node only ever sees fresh forces.
//!
//! The rule is [`levels::LevelRule`], the step classes of a cycle [`schedule::Schedule`]; each model's
//! phases apply them to its nodes: the 3D element blocks in [`blocks`], the meridian section
//! in [`crate::fe::section::fine_step`].

pub mod blocks;
pub mod levels;
pub mod report;
pub mod schedule;

pub use blocks::{node_force_sum, with_element_neighbours, Subcycler};
pub use levels::MAX_LEVEL;
pub use report::{predicted_saving, SubcycleReport};
pub use schedule::Schedule;

use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};

/// Whether element groups advance with their own time steps.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Subcycling {
    /// One step for every element (the single-step Box 6.1 loop).
    #[default]
    Off,
    /// On when the predicted saving is at least [`AUTO_MIN_SAVING`].
    Auto,
    /// Always on.
    On,
}

/// Smallest predicted saving (single-step element updates / subcycled ones) at which
/// [`Subcycling::Auto`] switches subcycling on: below it the extra node work and the
/// synchronisation bookkeeping eat most of the gain.
pub const AUTO_MIN_SAVING: f64 = 1.5;

/// How the section model is integrated in time (the 3D model: [`Subcycling`] and
/// `ExplicitSettings::subcycle_max_level`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Integration {
    /// One global step, the smallest stable step of all quads and contact springs.
    SingleRate,
    /// Power-of-two step classes up to 2^`max_level` times the fine step.
    Subcycled {
        /// Highest level K (0..=[`MAX_LEVEL`]); 0 is single-rate integration.
        max_level: u8,
    },
}

/// Default highest level of [`Integration::Subcycled`].
pub const DEFAULT_MAX_LEVEL: u8 = 2;

impl Integration {
    /// The default subcycled integration.
    pub fn subcycled() -> Self {
        Integration::Subcycled {
            max_level: DEFAULT_MAX_LEVEL,
        }
    }

    /// Checks the setting: a clear error for a level above [`MAX_LEVEL`].
    pub fn check(&self) -> Result<()> {
        match *self {
            Integration::Subcycled { max_level } if max_level > MAX_LEVEL => Err(Error::invalid(
                "solver.subcycle_max_level",
                max_level,
                format!("0..={MAX_LEVEL}"),
            )),
            _ => Ok(()),
        }
    }
}
