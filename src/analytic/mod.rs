//! The analytical collision model of Li, Yang & Shi (2019): Hertz compression, elastoplastic
//! compression, elastic recovery, the friction revision, the particle damping index and the
//! paper's parametric studies. Pure functions of SI inputs; no I/O.

pub mod body;
pub mod hertz;
mod quadrature;

pub use body::Body;
pub use hertz::HertzPair;
