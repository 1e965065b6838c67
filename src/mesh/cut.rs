//! Which part of a symmetric body to mesh: the cut planes through the impact axis x.

use crate::error::{Error, Result};

/// Which part of a ball (or a wall's block) to mesh, for solvers that exploit symmetry of a
/// collision along x.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Cut {
    /// The whole ball.
    Full,
    /// z >= 0: the plane z = 0 contains the impact axis x and the tangential direction y.
    Half,
    /// y >= 0 and z >= 0: two orthogonal planes through the impact axis.
    Quarter,
}

impl std::str::FromStr for Cut {
    type Err = Error;
    fn from_str(s: &str) -> Result<Cut> {
        match s {
            "full" => Ok(Cut::Full),
            "half" => Ok(Cut::Half),
            "quarter" => Ok(Cut::Quarter),
            _ => Err(Error::invalid("cut", s, "one of full, half, quarter")),
        }
    }
}
