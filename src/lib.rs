//! twoball: a finite-element verifier for the collision of two elastic-plastic balls.
//!
//! The crate has two halves that check each other, and a study that runs them:
//! - [`analytic`]: the closed-form three-phase collision model of Li, Yang & Shi (2019)
//!   (Hertz compression, elastoplastic compression, elastic recovery, friction revision);
//! - [`fe`]: a small explicit 3D solid finite-element code (8-node hexahedra, J2 plasticity
//!   with linear, power-law or Johnson-Cook hardening, penalty frictional contact) that
//!   simulates the same collision;
//! - [`study`]: both models on a scene or a sweep, and their result files; [`scene`] reads
//!   scenes, [`cli`] parses the command line. docs/architecture.md draws the layers.
//!
//! All quantities are SI: metres, seconds, kilograms, newtons, pascals, joules.

pub mod analytic;
pub mod atomic;
pub mod cli;
pub mod damper;
pub mod dem;
pub mod error;
pub mod fe;
pub mod material;
pub mod mesh;
pub mod scene;
pub mod study;

pub use error::{Error, Result};
pub use material::Material;
