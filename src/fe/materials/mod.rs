//! Materials of the element kernels: J2 (von Mises) plasticity with isotropic elasticity
//! ([`j2`]), and the hardening laws it returns to, behind one trait ([`hardening`]):
//! linear ([`bilinear`]), Ludwik/Swift power law ([`power`]) and Johnson-Cook with its rate
//! term ([`johnson_cook`]), dispatched from the stored law in [`law`]; a law may keep history
//! at each integration point ([`Hardening::HISTORY`]). The laws' parameters are constants of
//! the material layer ([`crate::material::hardening`]), re-exported here; the kernels are
//! implemented on them.

pub mod bilinear;
#[cfg(test)]
pub mod counting;
pub mod hardening;
pub mod j2;
pub mod johnson_cook;
pub mod law;
pub mod power;

pub use bilinear::Bilinear;
pub use hardening::Hardening;
pub use j2::J2Material;
pub use johnson_cook::JohnsonCook;
pub use law::{rate_independent, Law, LawDispatch, LawVisitor};
pub use power::Power;
