//! Closest point of a node on a bilinear quadrilateral contact segment.
//!
//! The segment is x(ξ, η) = Σ N_a(ξ, η) p_a on [−1, 1]², nodes ordered (−1,−1), (1,−1), (1,1),
//! (−1,1) so that x_ξ × x_η is the outward normal. The interior candidate solves the stationarity
//! conditions x_ξ·(x − s) = x_η·(x − s) = 0 by Newton's method (Gauss–Newton when the Hessian
//! is indefinite, steps limited to the element size in parameter space). The edges of a bilinear
//! quad are straight, so the boundary candidates are exact segment projections. The closest of
//! the candidates is returned: an interior stationary point when it exists inside the quad,
//! otherwise the point on an edge or corner.

use crate::fe::tensor::{add, cross, dot, norm, scale, sub};

/// Where a node projects on a segment.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Projection {
    /// Parametric coordinates (ξ, η) in [−1, 1]².
    pub xi: [f64; 2],
    /// The closest point x(ξ, η), m.
    pub point: [f64; 3],
    /// Unit outward normal of the segment at (ξ, η).
    pub normal: [f64; 3],
    /// Signed normal gap (s − x)·n, m: negative when the node is behind the segment.
    pub gap: f64,
    /// Euclidean distance |s − x|, m.
    pub distance: f64,
    /// True when the closest point lies on an edge or corner of the quad.
    pub on_boundary: bool,
}

/// The bilinear shape functions N_a(ξ, η) of a 4-node quad.
#[inline]
pub fn shape(xi: [f64; 2]) -> [f64; 4] {
    let (r, s) = (xi[0], xi[1]);
    [
        0.25 * (1.0 - r) * (1.0 - s),
        0.25 * (1.0 + r) * (1.0 - s),
        0.25 * (1.0 + r) * (1.0 + s),
        0.25 * (1.0 - r) * (1.0 + s),
    ]
}

fn point_at(p: &[[f64; 3]; 4], xi: [f64; 2]) -> [f64; 3] {
    let n = shape(xi);
    let mut x = [0.0; 3];
    for a in 0..4 {
        x = add(x, scale(n[a], p[a]));
    }
    x
}

/// Tangent vectors x_ξ and x_η at (ξ, η).
fn tangents(p: &[[f64; 3]; 4], xi: [f64; 2]) -> ([f64; 3], [f64; 3]) {
    let (r, s) = (xi[0], xi[1]);
    let dr = [-(1.0 - s), 1.0 - s, 1.0 + s, -(1.0 + s)];
    let ds = [-(1.0 - r), -(1.0 + r), 1.0 + r, 1.0 - r];
    let mut a = [0.0; 3];
    let mut b = [0.0; 3];
    for k in 0..4 {
        a = add(a, scale(0.25 * dr[k], p[k]));
        b = add(b, scale(0.25 * ds[k], p[k]));
    }
    (a, b)
}

/// Unit outward normal of the quad at (ξ, η); falls back to the diagonal normal where the
/// parametrisation degenerates.
pub fn normal_at(p: &[[f64; 3]; 4], xi: [f64; 2]) -> [f64; 3] {
    let (a, b) = tangents(p, xi);
    let mut n = cross(a, b);
    let mut l = norm(n);
    if l <= 1e-300 {
        n = cross(sub(p[2], p[0]), sub(p[3], p[1]));
        l = norm(n);
    }
    scale(1.0 / l, n)
}

fn finish(p: &[[f64; 3]; 4], s: [f64; 3], xi: [f64; 2], on_boundary: bool) -> Projection {
    let point = point_at(p, xi);
    let normal = normal_at(p, xi);
    let d = sub(s, point);
    Projection {
        xi,
        point,
        normal,
        gap: dot(d, normal),
        distance: norm(d),
        on_boundary,
    }
}

/// Closest point of `s` (m) on the bilinear quad with corners `p` (m, outward order).
///
/// Always returns a point of the closed quad; never fails (degenerate quads fall back to
/// their edges).
pub fn project(p: &[[f64; 3]; 4], s: [f64; 3]) -> Projection {
    let mut best: Option<Projection> = None;
    // Interior candidate by Newton from the centre.
    let twist = scale(0.25, add(sub(p[0], p[1]), sub(p[2], p[3])));
    let mut xi = [0.0f64, 0.0];
    let mut converged = false;
    // Whether the last Newton step used the full Hessian of ½|x(ξ) − s|², positive definite:
    // then the converged point is a local minimum of the distance.
    let mut definite = false;
    for _ in 0..20 {
        let (a, b) = tangents(p, xi);
        let r = sub(point_at(p, xi), s);
        let g = [dot(a, r), dot(b, r)];
        let (haa, hbb) = (dot(a, a), dot(b, b));
        let mut hab = dot(a, b) + dot(twist, r);
        let mut det = haa * hbb - hab * hab;
        definite = det > 1e-12 * haa * hbb;
        if !definite {
            // Indefinite: Gauss–Newton (drop the curvature term).
            hab = dot(a, b);
            det = haa * hbb - hab * hab;
            if det <= 0.0 {
                break;
            }
        }
        let mut d = [
            -(hbb * g[0] - hab * g[1]) / det,
            -(-hab * g[0] + haa * g[1]) / det,
        ];
        let len = d[0].abs().max(d[1].abs());
        if len > 1.0 {
            d = [d[0] / len, d[1] / len];
        }
        xi = [xi[0] + d[0], xi[1] + d[1]];
        if xi[0].abs() > 3.0 || xi[1].abs() > 3.0 {
            break;
        }
        if len < 1e-12 {
            converged = true;
            break;
        }
    }
    if converged && xi[0].abs() <= 1.0 + 1e-12 && xi[1].abs() <= 1.0 + 1e-12 {
        let interior = finish(
            p,
            s,
            [xi[0].clamp(-1.0, 1.0), xi[1].clamp(-1.0, 1.0)],
            false,
        );
        // A local minimum inside the quad is the closest point when the squared distance is
        // convex over the quad: its Hessian JᵀJ + (x − s)·x_ξη stays positive definite while
        // |x − s| |x_ξη| is below the squared half-edges, i.e. for any node nearer than
        // about the radius of curvature of the segment (contact candidates are). No edge
        // can then be closer.
        if definite {
            return interior;
        }
        best = Some(interior);
    }
    // Boundary candidates: exact projections on the four straight edges. Only the distance
    // is needed to compare them; the normal is evaluated for the winner alone.
    let mut edge: Option<([f64; 2], f64)> = None;
    for e in 0..4 {
        let (a, b) = (p[e], p[(e + 1) % 4]);
        let ab = sub(b, a);
        let l2 = dot(ab, ab);
        let t = if l2 > 0.0 {
            (dot(sub(s, a), ab) / l2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let u = 2.0 * t - 1.0;
        let xi_e = match e {
            0 => [u, -1.0],
            1 => [1.0, u],
            2 => [-u, 1.0],
            _ => [-1.0, -u],
        };
        let distance = norm(sub(s, point_at(p, xi_e)));
        let incumbent = match (edge, &best) {
            (Some((_, d)), _) => Some(d),
            (None, Some(b)) => Some(b.distance),
            (None, None) => None,
        };
        // Prefer the interior point on ties (it carries the smooth normal).
        if incumbent.is_none_or(|d| distance < d * (1.0 - 1e-12) - 1e-300) {
            edge = Some((xi_e, distance));
        }
    }
    if let Some((xi_e, _)) = edge {
        best = Some(finish(p, s, xi_e, true));
    }
    best.expect("four edge candidates always exist")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit_square() -> [[f64; 3]; 4] {
        [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ]
    }

    #[test]
    fn interior_point_of_a_flat_quad() {
        let q = project(&unit_square(), [0.3, 0.6, -0.01]);
        assert!(!q.on_boundary);
        assert!((q.xi[0] - (-0.4)).abs() < 1e-12 && (q.xi[1] - 0.2).abs() < 1e-12);
        assert!((q.gap + 0.01).abs() < 1e-12, "{q:?}");
        assert!((q.normal[2] - 1.0).abs() < 1e-12);
        let n = shape(q.xi);
        assert!((n.iter().sum::<f64>() - 1.0).abs() < 1e-14);
    }

    #[test]
    fn edge_and_corner_regions() {
        let q = project(&unit_square(), [1.5, 0.5, 0.2]);
        assert!(q.on_boundary && (q.xi[0] - 1.0).abs() < 1e-12 && q.xi[1].abs() < 1e-12);
        assert!((q.distance - (0.25f64 + 0.04).sqrt()).abs() < 1e-12);
        let c = project(&unit_square(), [-1.0, -2.0, 0.0]);
        assert_eq!(c.xi, [-1.0, -1.0]);
        assert!((c.distance - 5f64.sqrt()).abs() < 1e-12);
    }

    #[test]
    fn warped_quad_matches_a_brute_force_minimum() {
        // A twisted quad (not planar): compare against a fine parameter grid.
        let p = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.2],
            [1.1, 1.0, -0.1],
            [0.0, 0.9, 0.3],
        ];
        for s in [
            [0.4, 0.5, 0.5],
            [0.9, 0.1, -0.4],
            [1.4, 1.3, 0.0],
            [0.5, -0.3, 0.1],
        ] {
            let q = project(&p, s);
            let mut dmin = f64::INFINITY;
            let m = 400;
            for i in 0..=m {
                for j in 0..=m {
                    let xi = [
                        -1.0 + 2.0 * i as f64 / m as f64,
                        -1.0 + 2.0 * j as f64 / m as f64,
                    ];
                    dmin = dmin.min(norm(sub(s, point_at(&p, xi))));
                }
            }
            assert!(
                q.distance <= dmin + 1e-9,
                "{s:?}: {} vs grid {}",
                q.distance,
                dmin
            );
            assert!(
                q.distance > dmin - 1e-4,
                "{s:?}: {} vs grid {}",
                q.distance,
                dmin
            );
        }
    }

    #[test]
    fn curved_surface_gap_is_the_distance_to_the_sphere_facet() {
        // A small facet of a sphere of radius 1 around the +z pole; a node just inside the pole.
        let h: f64 = 0.05;
        let on = |x: f64, y: f64| [x, y, (1.0 - x * x - y * y).sqrt()];
        let p = [on(-h, -h), on(h, -h), on(h, h), on(-h, h)];
        let q = project(&p, [0.0, 0.0, 0.999]);
        assert!(!q.on_boundary);
        let zc = (1.0 - 2.0 * h * h).sqrt();
        assert!((q.gap - (0.999 - zc)).abs() < 1e-12, "{q:?}");
    }
}
