//! The explicit finite-element solver: elements, materials, contact, time integration, energy.
pub mod contact;
pub mod interaction;
