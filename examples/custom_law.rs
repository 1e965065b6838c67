//! A researcher's own contact law in one file: a power-law loading F = k δⁿ with an unloading
//! that returns the fraction e² of the loading work, F = F_max ((δ − δ₀)/(δ_max − δ₀))ⁿ,
//! δ₀ = δ_max (1 − e²). It implements the seam (`NormalLaw`), declares its parameters
//! (`NormalSpec`), checks the integrator against its own closed form and runs through
//! `twoball laws run` and `twoball laws fit`.
//!
//! Run: `cargo run --release --example custom_law`.

use twoball::analytic::impact::{integrate, DEFAULT_TOLERANCE};
use twoball::analytic::laws::coulomb::Coulomb;
use twoball::analytic::laws::{
    ClosedForm, ContactPair, NormalLaw, NormalSpec, ParamSpec, Params, Registry, Turn,
};
use twoball::analytic::Body;
use twoball::material::Material;

/// The law for one pair.
pub struct PowerHysteresis {
    /// Stiffness k, N/mⁿ.
    pub k: f64,
    /// Exponent n.
    pub n: f64,
    /// Restitution e.
    pub e: f64,
}

impl NormalLaw for PowerHysteresis {
    fn loading(&self, delta: f64, _rate: f64, _speed: f64) -> f64 {
        self.k * delta.max(0.0).powf(self.n)
    }

    fn unloading(&self, delta: f64, _rate: f64, _speed: f64, turn: &Turn) -> f64 {
        let d0 = turn.delta * (1.0 - self.e * self.e);
        turn.force * ((delta - d0).max(0.0) / (turn.delta - d0)).powf(self.n)
    }

    fn closed_form(&self, speed: f64, mass: f64) -> Option<ClosedForm> {
        // ½ m v² = k δ_max^{n+1}/(n + 1); the unloading gives back e² of it.
        Some(ClosedForm {
            e: self.e,
            delta_max: ((self.n + 1.0) * 0.5 * mass * speed * speed / self.k)
                .powf(1.0 / (self.n + 1.0)),
        })
    }
}

/// The law's description for the registry.
pub const SPEC: NormalSpec = NormalSpec {
    name: "power-hysteresis",
    title: "example: power-law loading k delta^n, unloading returning e^2 of the work",
    source: "examples/custom_law.rs",
    dem_codes: "none",
    validity: twoball::analytic::laws::validity::UNSTATED,
    params: &[
        ParamSpec {
            key: "k",
            unit: "N/m^n",
            doc: "stiffness (default: Hertz's K of the pair)",
            min: 1e-6,
            max: 1e20,
            default: |p| p.hertz.stiffness(),
        },
        ParamSpec {
            key: "n",
            unit: "-",
            doc: "exponent (default 1.5)",
            min: 1.0,
            max: 3.0,
            default: |_| 1.5,
        },
        ParamSpec {
            key: "e",
            unit: "-",
            doc: "restitution (default 0.5)",
            min: 0.01,
            max: 1.0,
            default: |_| 0.5,
        },
    ],
    build: |_pair: &ContactPair, p: &Params| {
        Box::new(PowerHysteresis {
            k: p.get("k"),
            n: p.get("n"),
            e: p.get("e"),
        })
    },
};

/// Integrates the law for two copper-fe balls at 1 m/s and returns (integrated e, closed-form
/// e, integrated δ_max, closed-form δ_max, energy residual).
pub fn check() -> (f64, f64, f64, f64, f64) {
    let m = Material::preset("copper-fe").expect("preset");
    let b = Body::ball(m, 0.02, "ball").expect("ball");
    let pair = ContactPair::between(&b, &b, m.mu);
    let params =
        Params::resolve(SPEC.name, SPEC.params, &[("n".into(), 2.0)], &pair).expect("parameters");
    let law = (SPEC.build)(&pair, &params);
    let r = integrate(
        &b,
        &b,
        [0.5, 0.0],
        [-0.5, 0.0],
        law.as_ref(),
        &Coulomb { mu: 0.0 },
        DEFAULT_TOLERANCE,
    )
    .expect("integration")
    .expect("impact");
    let cf = law.closed_form(1.0, pair.hertz.mass).expect("closed form");
    (r.e, cf.e, r.delta_max, cf.delta_max, r.energy_residual())
}

/// The built-in laws plus this one.
pub fn registry() -> Registry {
    let mut reg = Registry::builtin();
    reg.add_normal(SPEC);
    reg
}

#[allow(dead_code)]
fn main() {
    let (e, e_cf, d, d_cf, res) = check();
    println!("integrated e = {e:.9} (closed form {e_cf:.9}), delta_max = {d:.6e} m (closed form {d_cf:.6e} m), energy residual {res:.1e}");
    let code = twoball::cli::laws_main_with(
        [
            "twoball laws",
            "run",
            "--law",
            "power-hysteresis",
            "--param",
            "e=0.4",
            "--v1",
            "2",
            "--v2",
            "-2",
        ],
        &registry(),
    );
    std::process::exit(code);
}
