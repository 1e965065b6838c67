//! Energy accounting in the spirit of LS-DYNA's GLSTAT: where the energy of the model is at
//! one instant, and how well the discrete energy balance holds. One report for both explicit
//! models: the 3D solver fills every field, the section model those it keeps (the balance
//! of nodal work and the per-part sums are the 3D solver's alone).

use serde::Serialize;

/// Energies of the solids of one part or of the whole model, J.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct SolidEnergy {
    /// Kinetic energy ½ v^n·M v^n from full-step velocities, J.
    pub kinetic: f64,
    /// Central-difference kinetic energy ½ v^{n−1/2}·M v^{n+1/2}, J: the kinetic energy the
    /// scheme conserves exactly (with the trapezoidal internal work) for linear elasticity at
    /// constant step. ½ v^n·M v^n oscillates about it by O((ω Δt)²/8) while the body deforms
    /// (about 1 % for the coarsest modes of a coarse mesh); both agree in rigid motion. Used in
    /// `total` and `balance_error`.
    pub kinetic_central: f64,
    /// Internal energy: the stress power integrated in time, Σ_e ∫ V σ:D dt (as LS-DYNA's
    /// GLSTAT), J. Equals elastic + plastic.
    pub internal: f64,
    /// Elastic energy stored = internal − plastic, J.
    pub elastic: f64,
    /// Elastic energy p²/2K + s:s/4G of the current stresses, J: a diagnostic; it departs
    /// from `elastic` by O(ε²) relative because a hypoelastic (rate) law has no exact potential.
    pub elastic_from_stress: f64,
    /// Plastic work dissipated, J (radial return, exact for linear hardening).
    pub plastic: f64,
    /// Hourglass energy, J.
    pub hourglass: f64,
}

impl SolidEnergy {
    /// Adds the energies of `other` (another part's, J) to these, field by field.
    pub fn add(&mut self, other: &SolidEnergy) {
        self.kinetic += other.kinetic;
        self.kinetic_central += other.kinetic_central;
        self.elastic += other.elastic;
        self.elastic_from_stress += other.elastic_from_stress;
        self.internal += other.internal;
        self.plastic += other.plastic;
        self.hourglass += other.hourglass;
    }
}

/// Energies of one part, J.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct PartEnergy {
    /// Part name.
    pub name: String,
    /// The part's solid energies, J.
    #[serde(flatten)]
    pub energy: SolidEnergy,
}

/// The energy state of the whole model at time `time`, J.
///
/// Two independent balances are reported (the first by the 3D solver only):
/// - `balance_error`: the Box 6.1 check |W_kin + W_int − W_ext − W_kin⁰| / max(W_kin, W_int,
///   W_ext), with W_int and W_ext integrated over nodal forces by the trapezoidal rule
///   (W_int includes hourglass forces);
/// - `energy_ratio`: GLSTAT's total / initial total, where total = kinetic_central + internal
///   (elastic + plastic) + hourglass + interaction energy (stored + dissipated, as reported by
///   the interactions themselves, which are treated as part of the closed system), less the
///   work of the model's own loads and damping (`load_work`).
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct EnergyReport {
    /// Time, s.
    pub time: f64,
    /// Step number.
    pub step: u64,
    /// Energies of the solids (the sums over the parts in the 3D solver), J.
    #[serde(flatten)]
    pub solid: SolidEnergy,
    /// Work of the internal nodal forces (trapezoidal), J (3D solver; 0 on the section).
    pub internal_work: f64,
    /// Work of the interaction (external) nodal forces on the solid (trapezoidal), J (3D
    /// solver; 0 on the section).
    pub external_work: f64,
    /// Work of the model's own nodal loads and mass-proportional damping on the body, J (the
    /// section's loads and dynamic-relaxation damping; 0 in the 3D solver, which has none).
    pub load_work: f64,
    /// Energy stored in interactions (penalty springs), J.
    pub interaction_stored: f64,
    /// Energy dissipated by interactions (friction, damping), J.
    pub interaction_dissipated: f64,
    /// Work the interactions report they did, J.
    pub interaction_work: f64,
    /// Total = kinetic_central + internal + hourglass + interaction stored + dissipated −
    /// load work, J.
    pub total: f64,
    /// Total at t = 0, J.
    pub initial_total: f64,
    /// total / initial_total (1 is perfect).
    pub energy_ratio: f64,
    /// Relative Box 6.1 energy-balance error (see the type's doc; 3D solver, 0 on the
    /// section).
    pub balance_error: f64,
    /// Largest `balance_error` seen at any energy check so far.
    pub max_balance_error: f64,
    /// Per-part sums (3D solver; empty on the section).
    pub parts: Vec<PartEnergy>,
}

impl EnergyReport {
    /// Kinetic (central) + elastic + plastic + hourglass: the mechanical energy of the solids, J.
    pub fn mechanical(&self) -> f64 {
        self.solid.kinetic_central + self.solid.internal + self.solid.hourglass
    }
}
