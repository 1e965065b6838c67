//! Mindlin-Deresiewicz stick-slip as the DEM codes implement it: a Mindlin spring
//! k_t = 8 G* √(R* δ) on the accumulated tangential displacement, truncated at the Coulomb
//! limit μ F_n (the spring force stays at μ F_n while the cap binds and the displacement is
//! shortened to match). It gives tangential restitution (the contact points can rebound),
//! which the rigid Coulomb impulse cannot.

use super::coulomb::FRICTION;
use super::mindlin::{Mindlin, SHEAR_MODULUS};
use super::{ContactPair, Params, TangentialLaw, TangentialSpec};

/// Mindlin spring with Coulomb truncation.
#[derive(Debug, Clone, Copy)]
pub struct MindlinCoulomb {
    /// The Mindlin spring (G*, R*).
    pub spring: Mindlin,
    /// μ.
    pub mu: f64,
}

impl TangentialLaw for MindlinCoulomb {
    fn stiffness(&self, delta: f64) -> f64 {
        self.spring.stiffness(delta)
    }

    fn friction(&self) -> f64 {
        self.mu
    }
}

/// The law's description.
pub const SPEC: TangentialSpec = TangentialSpec {
    name: "mindlin-coulomb",
    title: "Mindlin spring with Coulomb truncation (stick-slip history), as DEM codes use Mindlin-Deresiewicz",
    source: "R. D. Mindlin, H. Deresiewicz, J. Appl. Mech. 20 (1953) 327-344; DEM simplification as in LIGGGHTS tangential history",
    dem_codes: "LIGGGHTS (tangential history), EDEM (Hertz-Mindlin), Yade (HertzMindlin), MercuryDPM (sliding friction spring)",
    validity: (),
    params: &[SHEAR_MODULUS, FRICTION],
    build: |pair: &ContactPair, p: &Params| {
        Box::new(MindlinCoulomb {
            spring: Mindlin::from_params(pair, p),
            mu: p.get("mu"),
        })
    },
};
