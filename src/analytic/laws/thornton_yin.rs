//! Mindlin-Deresiewicz partial slip with Thornton & Yin's stiffness reduction: the tangential
//! force follows the Mindlin-Deresiewicz loading, unloading and reloading curves of the
//! displacement ξ of the contact points, with their turning points (Masing memory).
//!
//! With ξ_s = 3μF/(16 G* a) the displacement of full slip, a = √(R* δ), and
//! r(z) = 1 − (1 − min(z, 1))^{3/2}:
//!
//! - virgin loading: f = sign(ξ) μF r(|ξ|/ξ_s);
//! - from a turning point (ξ_k, f_k), moving in direction s: f = f_k + 2 s μF r(s(ξ − ξ_k)/(2ξ_s)),
//!   until ξ regains the turning point before (the mirror −ξ₁ for the first), where both are
//!   forgotten (Masing).
//!
//! The slope of these curves is Thornton & Yin's k_t = 8 G* a θ, θ³ = 1 − f/(μF) on loading
//! and 1 − |f − f_k|/(2μF) on unloading and reloading. The turning forces f_k are re-evaluated
//! with the current F and a, so the force is a function of (ξ, δ, F, turns): at fixed ξ its
//! rate is μḞ(1 − θ) on virgin loading (Thornton & Yin's normal-force term, exactly, for a
//! Hertz contact), it equals Mindlin's 8 G* a ξ as μ → ∞, and it reaches μF at full slip.

use super::coulomb::FRICTION;
use super::mindlin::{no_slip_stiffness, SHEAR_MODULUS};
use super::{ContactPair, Params, TangentialLaw, TangentialSpec};

/// Mindlin-Deresiewicz / Thornton-Yin tangential law with slip memory.
#[derive(Debug, Clone, Copy)]
pub struct ThorntonYin {
    /// G*, Pa.
    pub shear_modulus: f64,
    /// R*, m.
    pub radius: f64,
    /// μ.
    pub mu: f64,
}

/// r(z) = 1 − (1 − z)^{3/2} for z clipped to [0, 1], without cancellation at small z.
fn rise(z: f64) -> f64 {
    let z = z.clamp(0.0, 1.0);
    -(1.5 * (-z).ln_1p()).exp_m1()
}

impl ThorntonYin {
    /// Force on virgin loading at displacement ξ (m) with slip limit `cap` = μF (N) and
    /// full-slip displacement `slip` = ξ_s (m), N.
    fn virgin(xi: f64, cap: f64, slip: f64) -> f64 {
        xi.signum() * cap * rise(xi.abs() / slip)
    }
}

impl TangentialLaw for ThorntonYin {
    fn stiffness(&self, delta: f64) -> f64 {
        no_slip_stiffness(self.shear_modulus, self.radius, delta)
    }

    fn friction(&self) -> f64 {
        self.mu
    }

    fn memory(&self) -> bool {
        true
    }

    fn force(&self, xi: f64, delta: f64, normal: f64, turns: &[f64], direction: f64) -> f64 {
        let k = self.stiffness(delta);
        if !self.mu.is_finite() {
            return k * xi;
        }
        let cap = self.mu * normal.max(0.0);
        if !(cap > 0.0 && k > 0.0) {
            return 0.0;
        }
        let slip = 1.5 * cap / k;
        let Some((&first, _)) = turns.split_first() else {
            return Self::virgin(xi, cap, slip);
        };
        // Branch j runs from turns[j - 1] in direction d_j; the last has `direction`.
        let mut d = if turns.len() % 2 == 1 {
            direction
        } else {
            -direction
        };
        let mut f = Self::virgin(first, cap, slip);
        let mut from = first;
        for &to in &turns[1..] {
            f += d * 2.0 * cap * rise(d * (to - from) / (2.0 * slip));
            from = to;
            d = -d;
        }
        f + d * 2.0 * cap * rise(d * (xi - from) / (2.0 * slip))
    }
}

/// The law's description.
pub const SPEC: TangentialSpec = TangentialSpec {
    name: "thornton-yin",
    title: "Mindlin-Deresiewicz partial slip, Thornton-Yin stiffness 8 G* a (1 - f/(mu F))^(1/3), loading/unloading/reloading with turning points",
    source: "Mindlin & Deresiewicz, J. Appl. Mech. 20 (1953) 327-344; Thornton & Yin, Powder Technol. 65 (1991) 153-166; Thornton, Cummins & Cleary, Powder Technol. 210 (2011) 189-197",
    dem_codes: "Yade (Law2_ScGeom_MindlinPhys_MindlinDeresiewitz, documented as Thornton 1991 partial slip); not LIGGGHTS-PUBLIC; LAMMPS mindlin_rescale/force is a capped Mindlin spring without the reduction",
    validity: (),
    params: &[SHEAR_MODULUS, FRICTION],
    build: |pair: &ContactPair, p: &Params| {
        Box::new(ThorntonYin {
            shear_modulus: p.get("G_star"),
            radius: pair.hertz.radius,
            mu: p.get("mu"),
        })
    },
};
