//! The explicit finite-element solver, in layers (docs/architecture.md draws them):
//!
//! - [`solver`]: the explicit loop of Belytschko, Liu & Moran's Box 6.1 ([`solver::explicit`]),
//!   multi-time-step subcycling, the stable step, lumped masses, energy balance, the phase
//!   timer and the interaction interface;
//! - [`elements`]: the element block and its loop, and each hexahedron formulation with its
//!   scalar reference kernel beside its lane kernel, registered in [`elements::Formulation`];
//! - [`materials`]: J2 plasticity and the hardening laws behind one trait;
//! - [`simd`]: lanes, instruction-set tokens and kernel dispatch, row layouts, prefetch;
//! - [`contact`]: contact search and laws, rigid planes, the meridian section's contacts (the
//!   interactions the loops call);
//! - [`implicit`]: the quasi-static implicit solver of the section (Newton-Raphson, element
//!   tangents from the elements' own updates, sparse LDLᵀ and refinement, an exact rigid plane);
//! - [`mass_scaling`]: density factors within an added-mass budget, for both models;
//! - [`linear`]: small-strain linear tools for verification (modal analysis, Lamb's modes);
//! - [`section`]: the section model (the meridian section) of a head-on impact: ring quads,
//!   ring masses, mass scaling, its loop and subcycling;
//! - [`model`] (what the solver is given) and [`tensor`] (small tensor algebra).
// Index loops mirror the index notation of the formulas (σ_ij B_Ij, ...): keep them.
#![allow(clippy::needless_range_loop)]
pub mod contact;
pub mod elements;
pub mod implicit;
pub mod linear;
pub mod mass_scaling;
pub mod materials;
pub mod model;
pub mod section;
pub mod simd;
pub mod solver;
pub mod tensor;

// What the layers above use: the model, the solver and its settings and reports, and the
// interaction seam. Element kernels, shapes and materials' internals stay behind their
// modules' paths.
pub use model::{Formulation, Model, Part};
pub use solver::energy::EnergyReport;
pub use solver::explicit::{Settings, Solver};
pub use solver::{energy, explicit, interaction, profile, subcycle};
