//! The explicit finite-element solver, in layers (docs/architecture.md draws them):
//!
//! - [`solver`]: the explicit loop of Belytschko, Liu & Moran's Box 6.1 ([`solver::explicit`]),
//!   multi-time-step subcycling, the stable step, lumped masses, energy balance, the phase
//!   timer and the interaction interface;
//! - [`elements`]: the element block and its loop, and each hexahedron formulation with its
//!   scalar reference kernel beside its lane kernel, registered in [`elements::Formulation`];
//! - [`materials`]: J2 plasticity and the hardening laws behind one trait;
//! - [`simd`]: lanes, instruction-set tokens and kernel dispatch, row layouts, prefetch;
//! - [`contact`]: contact search and laws (interactions the loop calls);
//! - [`linear`]: small-strain linear tools for verification (modal analysis, Lamb's modes);
//! - [`model`] (what the solver is given) and [`tensor`] (small tensor algebra).
// Index loops mirror the index notation of the formulas (σ_ij B_Ij, ...): keep them.
#![allow(clippy::needless_range_loop)]
pub mod axisym;
pub mod contact;
pub mod elements;
pub mod linear;
pub mod materials;
pub mod model;
pub mod simd;
pub mod solver;
pub mod tensor;

pub use elements::{hex_bbar, hex_one_point, objective, shape};
pub use linear::{lamb, modal};
pub use model::{Formulation, Model, Part};
pub use simd::rows;
pub use solver::energy::EnergyReport;
pub use solver::explicit::{Settings, Solver};
pub use solver::{energy, explicit, interaction, mass, profile, subcycle, timestep};
