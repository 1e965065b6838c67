//! The selectively reduced (B-bar) ring quad: four 2x2 Gauss points for the deviatoric
//! strain rate and the element's mean dilatation for the volumetric one (Hughes 1980), so
//! the isochoric plastic flow does not lock; no hourglass modes, no hourglass control. The
//! section's counterpart of the B-bar hexahedron; objective update and forces as the
//! one-point quad's ([`super::one_point`]), at each Gauss point.

use super::four_point::FourPointQuad;

/// The selectively reduced (B-bar) quad.
pub type BBarQuad = FourPointQuad<true>;
