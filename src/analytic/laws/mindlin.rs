//! Mindlin (1949) no-slip tangential stiffness k_t = 8 G* a, a = √(R* δ): an elastic
//! tangential spring that never slips.

use super::{ContactPair, ParamSpec, Params, TangentialLaw, TangentialSpec};

/// Mindlin's tangential stiffness without slip.
#[derive(Debug, Clone, Copy)]
pub struct Mindlin {
    /// G*, Pa.
    pub shear_modulus: f64,
    /// R*, m.
    pub radius: f64,
}

impl Mindlin {
    /// The spring of `pair` with the `G_star` parameter of `p`.
    pub fn from_params(pair: &ContactPair, p: &Params) -> Mindlin {
        Mindlin {
            shear_modulus: p.get("G_star"),
            radius: pair.hertz.radius,
        }
    }
}

/// Mindlin's no-slip stiffness k_t = 8 G* √(R* δ), N/m, for G* (Pa), R* (m) and approach δ
/// (m; none below 0).
pub fn no_slip_stiffness(shear_modulus: f64, radius: f64, delta: f64) -> f64 {
    8.0 * shear_modulus * (radius * delta.max(0.0)).sqrt()
}

impl TangentialLaw for Mindlin {
    fn stiffness(&self, delta: f64) -> f64 {
        no_slip_stiffness(self.shear_modulus, self.radius, delta)
    }

    fn friction(&self) -> f64 {
        f64::INFINITY
    }
}

/// Effective shear modulus parameter, default the pair's G*.
pub const SHEAR_MODULUS: ParamSpec = ParamSpec {
    key: "G_star",
    unit: "Pa",
    doc: "effective shear modulus G* (default: 1/((2 - nu1)/G1 + (2 - nu2)/G2))",
    min: 1.0,
    max: 1e15,
    default: |p| p.shear_modulus.min(1e15),
};

/// The law's description.
pub const SPEC: TangentialSpec = TangentialSpec {
    name: "mindlin",
    title: "Mindlin no-slip tangential spring, k_t = 8 G* sqrt(R* delta)",
    source: "R. D. Mindlin, J. Appl. Mech. 16 (1949) 259-268",
    dem_codes: "EDEM (Hertz-Mindlin no slip, with the Coulomb cap), LIGGGHTS (tangential history stiffness)",
    validity: (),
    params: &[SHEAR_MODULUS],
    build: |pair: &ContactPair, p: &Params| Box::new(Mindlin::from_params(pair, p)),
};
