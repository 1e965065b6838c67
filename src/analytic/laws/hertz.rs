//! Hertz (1882): elastic spheres, F = (4/3) E* √R* δ^{3/2}; no dissipation (e = 1).

use super::{ClosedForm, ContactPair, NormalLaw, NormalSpec, ParamSpec, Params};

/// Hertz's elastic law with stiffness K = (4/3) E* √R*.
#[derive(Debug, Clone, Copy)]
pub struct Hertz {
    /// K, N/m^{3/2}.
    pub stiffness: f64,
}

impl NormalLaw for Hertz {
    fn loading(&self, delta: f64, _rate: f64, _speed: f64) -> f64 {
        self.stiffness * delta.max(0.0).powf(1.5)
    }

    fn closed_form(&self, speed: f64, mass: f64) -> Option<ClosedForm> {
        // ½ m v² = (2/5) K δ_max^{5/2}.
        Some(ClosedForm {
            e: 1.0,
            delta_max: (1.25 * mass * speed * speed / self.stiffness).powf(0.4),
        })
    }
}

/// Effective modulus and radius parameters shared by the Hertz-based laws.
pub const ELASTIC_PARAMS: [ParamSpec; 2] = [
    ParamSpec {
        key: "E_star",
        unit: "Pa",
        doc: "effective modulus E* (default: the pair's, 1/((1-nu1^2)/E1 + (1-nu2^2)/E2))",
        min: 1.0,
        max: 1e15,
        default: |p| p.hertz.modulus,
    },
    ParamSpec {
        key: "R_star",
        unit: "m",
        doc: "effective radius R* (default: the pair's, R1 R2/(R1 + R2))",
        min: 1e-9,
        max: 1e3,
        default: |p| p.hertz.radius,
    },
];

/// K = (4/3) E* √R* from the `E_star` and `R_star` parameters, N/m^{3/2}.
pub fn stiffness(params: &Params) -> f64 {
    4.0 / 3.0 * params.get("E_star") * params.get("R_star").sqrt()
}

/// The law's description.
pub const SPEC: NormalSpec = NormalSpec {
    name: "hertz",
    title: "Hertz elastic contact, F = (4/3) E* sqrt(R*) delta^(3/2), e = 1",
    source: "H. Hertz, J. reine angew. Math. 92 (1882) 156-171",
    dem_codes: "exported and run: LIGGGHTS (hertz, e = 1), LAMMPS (granular hertz), Yade (Hertz-Mindlin); MercuryDPM (HertzianViscoelastic, not run); EDEM (Hertz-Mindlin)",
    validity: super::validity::ELASTIC,
    params: &ELASTIC_PARAMS,
    build: |_pair: &ContactPair, params: &Params| {
        Box::new(Hertz {
            stiffness: stiffness(params),
        })
    },
};
