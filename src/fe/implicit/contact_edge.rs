//! The edge of a smooth frictionless contact between the nodes of a mesh: where the surface
//! leaves the plane, read from the gaps of the first three surface nodes past the outermost
//! node on it.
//!
//! Past its edge a the gap of a contact opens as g = C (r − a)^p: p = 3/2 at an elastic
//! edge (Hertz's gap, whose pressure falls as √(a − r) inside), towards 1 where plastic
//! flattening leaves the surface a corner at the edge. Three gaps fix C, p and a. The
//! outermost node on the plane alone places the edge only within one node spacing, a sawtooth
//! over the mesh (levels 0 and 1 of `twoball static` differ by 1 % in it; by 0.02 % in this
//! edge).

/// A surface node past the contact: its radius r (m) and its gap to the plane g (m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GapPoint {
    /// Distance from the axis, m.
    pub r: f64,
    /// Gap to the plane, m (positive apart).
    pub g: f64,
}

/// Bisection steps of the edge: the bracket, one node spacing, shrinks below 1e-15 of it.
const BISECTIONS: usize = 52;

/// The contact edge (m) from the radius `r_on` (m) of the outermost surface node on the
/// plane and the next three surface nodes outwards, `past` (radii ascending, beyond
/// `r_on`): the radius a where the gap law C (r − a)^p through their three gaps closes,
/// held within [`r_on`, `past[0].r`] (where the nodes say the edge lies).
///
/// Failure modes: none; gaps that do not open outwards (g₁ ≤ 0 or not increasing) or radii
/// out of order give the midpoint of [`r_on`, `past[0].r`].
pub fn contact_edge(r_on: f64, past: [GapPoint; 3]) -> f64 {
    let [p1, p2, p3] = past;
    let midpoint = 0.5 * (r_on + p1.r);
    let ordered = r_on <= p1.r && p1.r < p2.r && p2.r < p3.r;
    if !(ordered && p1.g > 0.0 && p2.g > p1.g && p3.g > p2.g) {
        return midpoint;
    }
    // Zero when the law through the first two gaps, with its edge at `a`, meets the third;
    // negative as `a` nears the first node.
    let misfit = |a: f64| {
        let p = (p2.g / p1.g).ln() / ((p2.r - a) / (p1.r - a)).ln();
        p * ((p3.r - a) / (p1.r - a)).ln() - (p3.g / p1.g).ln()
    };
    let (mut lo, mut hi) = (r_on, p1.r);
    let at_node = misfit(lo);
    if at_node.is_nan() || at_node <= 0.0 {
        return r_on;
    }
    for _ in 0..BISECTIONS {
        let mid = 0.5 * (lo + hi);
        if misfit(mid) > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn gap_law(a: f64, c: f64, p: f64, r: f64) -> GapPoint {
        GapPoint {
            r,
            g: c * (r - a).max(0.0).powf(p),
        }
    }

    #[test]
    fn the_edge_of_a_power_law_gap_is_recovered() {
        for p in [1.0, 1.15, 1.5] {
            for a in [1.0e-4, 3.3e-4, 4.9e-4] {
                let at = |r| gap_law(a, 7.0, p, r);
                let edge = contact_edge(1e-4, [at(5e-4), at(6e-4), at(7.5e-4)]);
                assert!((edge - a).abs() < 1e-12, "p {p}: {edge} against {a}");
            }
        }
    }

    #[test]
    fn the_edge_stays_between_the_nodes() {
        // A gap law whose edge lies inside the outermost node on the plane.
        let at = |r| gap_law(3e-4, 1.0, 1.5, r);
        assert_eq!(contact_edge(4e-4, [at(5e-4), at(6e-4), at(7e-4)]), 4e-4);
        // Gaps that do not open outwards: the midpoint.
        let g = |r, g| GapPoint { r, g };
        let flat = [g(5e-4, 1e-6), g(6e-4, 1e-6), g(7e-4, 2e-6)];
        assert_eq!(contact_edge(4e-4, flat), 4.5e-4);
        let closed = [g(5e-4, 0.0), g(6e-4, 1e-6), g(7e-4, 2e-6)];
        assert_eq!(contact_edge(4e-4, closed), 4.5e-4);
    }
}
