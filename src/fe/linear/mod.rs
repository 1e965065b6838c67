//! Small-strain linear tools that verify the explicit solver: the assembled stiffness and
//! its lowest vibration modes ([`modal`]) and the free-sphere modes of Lamb (1882)
//! ([`lamb`]). Not used by the explicit loop.

pub mod lamb;
pub mod modal;
