//! DEM decks: a normal contact law with resolved parameters written for a DEM code as a
//! complete head-on collision of two equal balls that the code runs unedited (LIGGGHTS,
//! LAMMPS `pair_style granular`, Yade), or as a MercuryDPM driver written against its
//! published API (not compiled here). Where a code cannot express a law, the writer returns a
//! one-line error saying why; where it can only over a speed range, the deck's header gives
//! the range.
//!
//! Every runnable deck writes `trace.txt`, one line per step: t [s], x1 [m], x2 [m],
//! vx1 [m/s], vx2 [m/s], fx1 [N] (ball 1 moves along +x towards ball 2); [`trace`] reads it
//! into e, δ_max and the contact duration, and [`run`] drives the installed program.

pub mod lammps;
pub mod liggghts;
pub mod mercurydpm;
pub mod run;
pub mod scene;
pub mod trace;
pub mod yade;

use crate::analytic::laws::Params;
use crate::error::{Error, Result};
pub use scene::DeckScene;

/// A DEM code twoball writes decks for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Code {
    /// LIGGGHTS-PUBLIC 3.8 (`pair_style gran`).
    Liggghts,
    /// LAMMPS with the GRANULAR package (`pair_style granular`).
    Lammps,
    /// Yade (Python scene).
    Yade,
    /// MercuryDPM (C++ driver; not compiled here).
    MercuryDpm,
}

impl Code {
    /// Every code, in the order files are written.
    pub const ALL: [Code; 4] = [Code::Liggghts, Code::Lammps, Code::Yade, Code::MercuryDpm];

    /// Name used by `--code`.
    pub fn name(self) -> &'static str {
        match self {
            Code::Liggghts => "liggghts",
            Code::Lammps => "lammps",
            Code::Yade => "yade",
            Code::MercuryDpm => "mercurydpm",
        }
    }

    /// File name of the deck.
    pub fn file(self) -> &'static str {
        match self {
            Code::Liggghts => "liggghts.in",
            Code::Lammps => "lammps.in",
            Code::Yade => "yade.py",
            Code::MercuryDpm => "mercurydpm.cpp",
        }
    }

    /// The code called `name`; the error lists the names.
    pub fn parse(name: &str) -> Result<Code> {
        Code::ALL
            .into_iter()
            .find(|c| c.name() == name)
            .ok_or_else(|| {
                Error::invalid("--code", name, "one of liggghts, lammps, yade, mercurydpm")
            })
    }

    /// Whether the deck runs here (MercuryDPM needs its own build of a driver).
    pub fn runs(self) -> bool {
        self != Code::MercuryDpm
    }
}

/// The deck of `law` with `params` for `code` on `scene`, or an error saying in one line why
/// the code cannot express the law (naming the law, the code and what is missing).
pub fn deck(code: Code, law: &str, params: &Params, scene: &DeckScene) -> Result<String> {
    match code {
        Code::Liggghts => liggghts::deck(law, params, scene),
        Code::Lammps => lammps::deck(law, params, scene),
        Code::Yade => yade::deck(law, params, scene),
        Code::MercuryDpm => mercurydpm::driver(law, params, scene),
    }
}

/// The refusal for `law` in `code`: one line naming both and the reason.
pub(crate) fn cannot(code: Code, law: &str, why: &str) -> Error {
    Error::invalid(format!("{} export of law", code.name()), law, why)
}

/// |β| = −ln e/√(ln² e + π²): the damping ratio of a linear oscillator of restitution e.
pub(crate) fn damping_ratio(e: f64) -> f64 {
    crate::analytic::laws::linear_dashpot::damping_ratio(e)
}
