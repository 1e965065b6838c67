//! Isotropic elasticity with J2 (von Mises) bilinear isotropic hardening, integrated by the
//! radial return (Wilkins 1964; Simo & Hughes 1998, Box 3.1). For linear hardening the return
//! is exact in one step: no iteration, no error beyond round-off.

use super::tensor::{ddot, deviator, trace, Sym};
use crate::material::Material;

/// Constitutive constants of one part, precomputed for the element kernels.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct J2Material {
    /// Lamé λ, Pa.
    pub lambda: f64,
    /// Shear modulus G, Pa.
    pub shear: f64,
    /// Bulk modulus K, Pa.
    pub bulk: f64,
    /// Initial yield strength σ_y0, Pa.
    pub yield0: f64,
    /// Plastic hardening modulus H = E E_T/(E − E_T), Pa (0 = perfectly plastic).
    pub hardening: f64,
    /// Dilatational wave speed sqrt((λ + 2G)/ρ), m/s.
    pub wave_speed: f64,
    /// Mass density, kg/m³.
    pub rho: f64,
    /// Skip the yield check entirely (elastic-only fast path).
    pub elastic_only: bool,
}

impl J2Material {
    /// Constants of `m`; `elastic_only` turns plasticity off for this part.
    pub fn new(m: &Material, elastic_only: bool) -> Self {
        J2Material {
            lambda: m.lame_lambda(),
            shear: m.shear_modulus(),
            bulk: m.bulk_modulus(),
            yield0: m.yield_strength,
            hardening: m.hardening_modulus(),
            wave_speed: m.dilatational_wave_speed(),
            rho: m.rho,
            elastic_only,
        }
    }

    /// P-wave modulus λ + 2G, Pa.
    pub fn p_modulus(&self) -> f64 {
        self.lambda + 2.0 * self.shear
    }

    /// Current yield stress σ_y0 + H ε_p for equivalent plastic strain `eps_p`, Pa.
    #[inline]
    pub fn yield_stress(&self, eps_p: f64) -> f64 {
        self.yield0 + self.hardening * eps_p
    }

    /// Elastic strain energy density p²/(2K) + s:s/(4G) of a stress state, J/m³.
    #[inline]
    pub fn elastic_energy_density(&self, s: &Sym) -> f64 {
        let p = trace(s) / 3.0;
        let d = deviator(s);
        p * p / (2.0 * self.bulk) + ddot(&d, &d) / (4.0 * self.shear)
    }

    /// Advances the Cauchy stress `stress` (Pa, already rotated to the current frame) by the
    /// strain increment `deps` (tensor Voigt, dimensionless) and the equivalent plastic strain
    /// `eps_p`. Returns the plastic work per unit volume done in the increment, J/m³ (0 if
    /// elastic).
    ///
    /// The elastic trial stress is returned radially to the yield surface when it lies
    /// outside: Δε_p = (q_trial − σ_y)/(3G + H), s = s_trial (1 − 3G Δε_p / q_trial).
    /// The plastic work uses the mean of the yield stresses before and after, which is exact
    /// for linear hardening (the flow stress is linear in ε_p).
    #[inline]
    pub fn update(&self, stress: &mut Sym, eps_p: &mut f64, deps: &Sym) -> f64 {
        let tr = trace(deps);
        let two_g = 2.0 * self.shear;
        let lt = self.lambda * tr;
        stress[0] += lt + two_g * deps[0];
        stress[1] += lt + two_g * deps[1];
        stress[2] += lt + two_g * deps[2];
        stress[3] += two_g * deps[3];
        stress[4] += two_g * deps[4];
        stress[5] += two_g * deps[5];
        if self.elastic_only {
            return 0.0;
        }
        let s = deviator(stress);
        let q = (1.5 * ddot(&s, &s)).sqrt();
        let sy = self.yield_stress(*eps_p);
        if q <= sy {
            return 0.0;
        }
        let dp = (q - sy) / (3.0 * self.shear + self.hardening);
        let scale = 3.0 * self.shear * dp / q;
        for (k, sk) in s.iter().enumerate() {
            stress[k] -= scale * sk;
        }
        *eps_p += dp;
        dp * (sy + 0.5 * self.hardening * dp)
    }
}
