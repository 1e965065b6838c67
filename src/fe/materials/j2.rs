//! Isotropic elasticity with J2 (von Mises) isotropic hardening, integrated by the radial
//! return (Wilkins 1964; Simo & Hughes 1998, Box 3.1), in scalar form
//! ([`J2Material::update`], the per-element reference kernels) and lane form
//! ([`update_lanes`], the lane kernels of both formulations). The flow stress comes from the
//! part's [`Law`]; the return direction, the elastic predictor and the stress correction are
//! the same for every law.

use super::{
    bilinear::Bilinear,
    hardening::Hardening,
    law::{Law, LawDispatch, LawVisitor},
};
use crate::fe::simd::{select, Lanes};
use crate::fe::tensor::{ddot, deviator, trace, Sym};
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
    /// Hardening law (the flow stress after first yield).
    pub law: Law,
    /// Dilatational wave speed sqrt((λ + 2G)/ρ), m/s.
    pub wave_speed: f64,
    /// Mass density, kg/m³.
    pub rho: f64,
    /// Skip the yield check entirely (elastic-only fast path).
    pub elastic_only: bool,
}

impl J2Material {
    /// Constants of `m` (its hardening law, or linear hardening from its yield strength and
    /// tangent modulus); `elastic_only` turns plasticity off for this part.
    pub fn new(m: &Material, elastic_only: bool) -> Self {
        let law = m.hardening.unwrap_or(Law::Bilinear(Bilinear {
            yield0: m.yield_strength,
            h: m.hardening_modulus(),
        }));
        J2Material {
            lambda: m.lame_lambda(),
            shear: m.shear_modulus(),
            bulk: m.bulk_modulus(),
            yield0: law.initial_yield(),
            law,
            wave_speed: m.dilatational_wave_speed(),
            rho: m.rho,
            elastic_only,
        }
    }

    /// P-wave modulus λ + 2G, Pa.
    pub fn p_modulus(&self) -> f64 {
        self.lambda + 2.0 * self.shear
    }

    /// Elastic strain energy density p²/(2K) + s:s/(4G) of a stress state, J/m³.
    #[inline]
    pub fn elastic_energy_density(&self, s: &Sym) -> f64 {
        let p = trace(s) / 3.0;
        let d = deviator(s);
        p * p / (2.0 * self.bulk) + ddot(&d, &d) / (4.0 * self.shear)
    }

    /// Advances the Cauchy stress `stress` (Pa, already rotated to the current frame) by the
    /// strain increment `deps` (tensor Voigt, dimensionless) over the step `dt` (s; the rate
    /// of rate-dependent laws), and the equivalent plastic strain `eps_p`. Returns the
    /// plastic work per unit volume done in the increment, J/m³ (0 if elastic).
    ///
    /// The elastic trial stress is returned radially to the yield surface when it lies
    /// outside: s = s_trial (1 − 3G Δε_p / q_trial), with Δε_p from the law
    /// ([`Hardening::plastic_increment`]).
    #[inline]
    pub fn update(&self, stress: &mut Sym, eps_p: &mut f64, deps: &Sym, dt: f64) -> f64 {
        self.law.with(Scalar {
            mat: self,
            stress,
            eps_p,
            deps,
            dt,
        })
    }

    /// [`J2Material::update`] with the law's concrete type `law`.
    #[inline(always)]
    pub fn update_with<H: Hardening>(
        &self,
        law: &H,
        stress: &mut Sym,
        eps_p: &mut f64,
        deps: &Sym,
        dt: f64,
    ) -> f64 {
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
        let sy = law.static_yield(*eps_p);
        if q <= sy {
            return 0.0;
        }
        let (dp, work) = law.plastic_increment(q, sy, *eps_p, self.shear, dt);
        let scale = 3.0 * self.shear * dp / q;
        for (k, sk) in s.iter().enumerate() {
            stress[k] -= scale * sk;
        }
        *eps_p += dp;
        work
    }
}

/// [`J2Material::update`] as a law visitor.
struct Scalar<'a> {
    mat: &'a J2Material,
    stress: &'a mut Sym,
    eps_p: &'a mut f64,
    deps: &'a Sym,
    dt: f64,
}

impl LawVisitor for Scalar<'_> {
    type Output = f64;
    #[inline(always)]
    fn visit<H: Hardening>(self, law: &H) -> f64 {
        self.mat
            .update_with(law, self.stress, self.eps_p, self.deps, self.dt)
    }
}

/// Lane-wise [`J2Material::update_with`]: elastic predictor, and the radial return only when
/// some lane yields (elastic lanes then get a zero correction). `stress` in Pa, `deps`
/// dimensionless, `dt` in s. Returns the plastic work per unit volume, J/m³.
#[inline(always)]
pub fn update_lanes<H: Hardening, const W: usize>(
    mat: &J2Material,
    law: &H,
    stress: &mut [Lanes<W>; 6],
    eps_p: &mut Lanes<W>,
    deps: &[Lanes<W>; 6],
    dt: f64,
) -> Lanes<W> {
    let tr = deps[0] + deps[1] + deps[2];
    let two_g = 2.0 * mat.shear;
    let lt = mat.lambda * tr;
    for k in 0..3 {
        stress[k] += lt + two_g * deps[k];
    }
    for k in 3..6 {
        stress[k] += two_g * deps[k];
    }
    let zero = tr.splat_like(0.0);
    if mat.elastic_only {
        return zero;
    }
    let m = (stress[0] + stress[1] + stress[2]) / 3.0;
    let s = [
        stress[0] - m,
        stress[1] - m,
        stress[2] - m,
        stress[3],
        stress[4],
        stress[5],
    ];
    let q = (1.5 * ddot_lanes(&s, &s)).sqrt();
    let sy = law.static_yield_lanes(*eps_p);
    let yields = q.gt(sy);
    if !yields.iter().any(|&y| y) {
        return zero;
    }
    let (dp, work) = law.plastic_increment_lanes(yields, q, sy, *eps_p, mat.shear, dt);
    // Elastic lanes divide by their own q only to be multiplied by dp = 0: select guards q = 0.
    let scale = select(yields, (3.0 * mat.shear * dp) / q, zero);
    for k in 0..6 {
        stress[k] -= scale * s[k];
    }
    *eps_p += dp;
    work
}

/// a : b of two symmetric tensors (Voigt, tensor shears), lane-wise.
#[inline(always)]
pub fn ddot_lanes<const W: usize>(a: &[Lanes<W>; 6], b: &[Lanes<W>; 6]) -> Lanes<W> {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + 2.0 * (a[3] * b[3] + a[4] * b[4] + a[5] * b[5])
}
