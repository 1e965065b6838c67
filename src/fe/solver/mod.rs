//! The explicit loop: central-difference time integration of Box 6.1 (Belytschko, Liu & Moran
//! 2014), its step written once in [`central_difference`] for every explicit model, the 3D
//! hexahedra's in [`explicit`], with multi-time-step subcycling ([`subcycle`]), the stable step
//! ([`timestep`]), lumped masses ([`mass`]), the energy balance ([`energy`]), the phase
//! timer ([`profile`]) and the interface of contact and walls ([`interaction`]).

pub(crate) mod central_difference;
pub mod energy;
pub mod explicit;
pub mod interaction;
pub mod mass;
pub mod profile;
pub mod subcycle;
pub mod timestep;
