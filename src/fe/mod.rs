//! The explicit finite-element solver: elements, materials, contact, time integration, energy.
//!
//! Reading order: [`explicit`] (the Box 6.1 loop) calls [`elements`] (the element loop) which
//! calls the kernels [`hex_one_point`] and [`hex_bbar`]; those use [`shape`], [`objective`]
//! and [`plasticity`]. [`model`] builds the input, [`energy`] reports the balance.
// Index loops mirror the index notation of the formulas (σ_ij B_Ij, ...): keep them.
#![allow(clippy::needless_range_loop)]
pub mod contact;
pub mod elements;
pub mod energy;
pub mod explicit;
pub mod hex_bbar;
pub(crate) mod hex_bbar_lanes;
pub mod hex_one_point;
pub(crate) mod hex_one_point_lanes;
pub mod interaction;
pub mod lamb;
pub mod mass;
pub mod materials;
pub mod modal;
pub mod model;
pub mod objective;
pub mod profile;
pub mod rows;
pub mod shape;
pub mod simd;
pub mod subcycle;
pub mod tensor;
pub mod timestep;

pub use energy::EnergyReport;
pub use explicit::{Settings, Solver};
pub use model::{Formulation, Model, Part};
