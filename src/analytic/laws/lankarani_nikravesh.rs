//! Lankarani & Nikravesh (1990): the Hunt-Crossley form with the hysteresis factor from an
//! energy balance, χ = 3(1 − e²)/(4 v_r): F = K δ^{3/2}(1 + χ δ̇). Its closed form is
//! Hunt-Crossley's with this χ.

use super::hertz::{stiffness, ELASTIC_PARAMS};
use super::hunt_crossley::HuntCrossley;
use super::params::RESTITUTION;
use super::{ContactPair, NormalSpec, Params};

/// The law's description.
pub const SPEC: NormalSpec = NormalSpec {
    name: "lankarani-nikravesh",
    title: "Lankarani-Nikravesh, F = K delta^(3/2) (1 + 3(1 - e^2)/4 delta_dot/v_r)",
    source: "H. M. Lankarani, P. E. Nikravesh, J. Mech. Des. 112 (1990) 369-376",
    dem_codes: "none of LIGGGHTS, LAMMPS, Yade, MercuryDPM (multibody codes: Adams, Chrono)",
    validity: super::validity::NEAR_ELASTIC,
    params: &[ELASTIC_PARAMS[0], ELASTIC_PARAMS[1], RESTITUTION],
    build: |_pair: &ContactPair, p: &Params| {
        let e = p.get("e");
        Box::new(HuntCrossley {
            stiffness: stiffness(p),
            factor: 0.75 * (1.0 - e * e),
        })
    },
};
