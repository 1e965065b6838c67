//! Kuwabara & Kono (1987) / Brilliantov et al. (1996) viscoelastic spheres:
//! F = K (δ^{3/2} + (3/2) A √δ δ̇), K = (4/3) E* √R*, A the dissipative constant (s).
//!
//! No closed form; Ramírez et al. (1999) give the series
//! e = 1 − C₁ A ρ^{2/5} v^{1/5} + C₂ A² ρ^{4/5} v^{2/5} − …, ρ = K/m*, C₁ = 1.15344,
//! C₂ = 0.79826, for a contact that ends at δ = 0 (`tension` = 1).

use super::hertz::{stiffness, ELASTIC_PARAMS};
use super::params::TENSION;
use super::{ContactPair, NormalLaw, NormalSpec, ParamSpec, Params};

/// The viscoelastic Hertz law.
#[derive(Debug, Clone, Copy)]
pub struct KuwabaraKono {
    /// K, N/m^{3/2}.
    pub stiffness: f64,
    /// Dissipative constant A, s.
    pub dissipation: f64,
    /// Whether the force may pull.
    pub tension: bool,
}

impl NormalLaw for KuwabaraKono {
    fn loading(&self, delta: f64, rate: f64, _speed: f64) -> f64 {
        let d = delta.max(0.0);
        self.stiffness * (d * d.sqrt() + 1.5 * self.dissipation * d.sqrt() * rate)
    }

    fn tensile(&self) -> bool {
        self.tension
    }
}

/// The law's description.
pub const SPEC: NormalSpec = NormalSpec {
    name: "kuwabara-kono",
    title: "viscoelastic Hertz, F = K (delta^(3/2) + 3/2 A sqrt(delta) delta_dot)",
    source: "G. Kuwabara, K. Kono, Jpn. J. Appl. Phys. 26 (1987) 1230; N. V. Brilliantov et al., Phys. Rev. E 53 (1996) 5382",
    dem_codes: "exported and run: LAMMPS (granular hertz, viscoelastic damping); not LIGGGHTS-PUBLIC or Yade (Hertz-Mindlin damping scales as delta^1/4)",
    validity: super::validity::VISCOELASTIC,
    params: &[
        ELASTIC_PARAMS[0],
        ELASTIC_PARAMS[1],
        ParamSpec {
            key: "A",
            unit: "s",
            doc: "dissipative constant A (default 1e-7 s)",
            min: 0.0,
            max: 1.0,
            default: |_| 1e-7,
        },
        TENSION,
    ],
    build: |_pair: &ContactPair, p: &Params| {
        Box::new(KuwabaraKono {
            stiffness: stiffness(p),
            dissipation: p.get("A"),
            tension: p.tension(),
        })
    },
};
