//! Coulomb rigid impulse: sliding friction μ F_n against the slip of the contact points until
//! the slip stops, no tangential compliance (what `twoball analytic` uses).

use super::{ContactPair, ParamSpec, Params, TangentialLaw, TangentialSpec};

/// Rigid Coulomb friction.
#[derive(Debug, Clone, Copy)]
pub struct Coulomb {
    /// μ.
    pub mu: f64,
}

impl TangentialLaw for Coulomb {
    fn stiffness(&self, _delta: f64) -> f64 {
        0.0
    }

    fn friction(&self) -> f64 {
        self.mu
    }
}

/// Friction coefficient parameter, default the pair's μ.
pub const FRICTION: ParamSpec = ParamSpec {
    key: "mu",
    unit: "-",
    doc: "friction coefficient (default: the pair's, or --mu)",
    min: 0.0,
    max: 100.0,
    default: |p| p.mu,
};

/// The law's description.
pub const SPEC: TangentialSpec = TangentialSpec {
    name: "coulomb",
    title: "rigid Coulomb impulse: slip at mu F_n until the contact points roll",
    source: "Li, Yang & Shi 2019, sec. 2.2 (friction revision), read as a rigid-body impulse; Stronge, Impact Mechanics (2000) ch. 5",
    dem_codes: "every DEM code's friction cap; as a pure impulse: none",
    validity: (),
    params: &[FRICTION],
    build: |_pair: &ContactPair, p: &Params| Box::new(Coulomb { mu: p.get("mu") }),
};
