//! The analytical collision model of Li, Yang & Shi (2019) and the contact-law laboratory
//! (`laws`, `impact`, `law_fit`): Hertz compression, elastoplastic
//! compression, elastic recovery, the friction revision, the particle damping index and the
//! paper's parametric studies. Pure functions of SI inputs; no I/O except the parametric
//! writers.

pub mod body;
pub mod collision;
pub mod damping_index;
pub mod exchange;
pub mod friction;
pub mod hertz;
pub mod history;
pub mod impact;
pub mod law_fit;
pub mod laws;
pub mod maw_barber_fawcett;
pub mod parametric;
mod quadrature;
pub mod sliding_arm;
pub mod three_phase;

pub use body::Body;
pub use collision::{collide, collide_with_mu, Collision};
pub use hertz::HertzPair;
pub use three_phase::{NormalImpact, Phase};
