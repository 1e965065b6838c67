//! The quasi-static implicit solver: the loading and unloading curves F(δ) contact laws are
//! fitted to, without the waves and inertia of an impact.
//!
//! - [`element_tangent`]: one ring element over a load increment, forces and tangent from
//!   the element's own explicit update (one copy of the kinematics and of every law);
//! - [`system`]: the sparse tangent and its solve (faer: LDLᵀ of the symmetric part,
//!   refined);
//! - [`plane`]: the rigid frictionless plane, enforced exactly by an active set;
//! - [`contact_edge`]: where the surface leaves the plane, between the mesh's nodes;
//! - [`static_solver`]: Newton-Raphson with line search, increment by increment.

pub mod contact_edge;
pub mod element_tangent;
pub mod plane;
pub mod static_solver;
pub mod system;
