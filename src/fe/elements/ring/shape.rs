//! Geometry of the axisymmetric 4-node quadrilateral on the meridian section (r, z): bilinear
//! shape functions, the ring volume V = ∫ 2π r dA, the volume-averaged gradient operator,
//! the hourglass shape vector and the characteristic length of the Courant step.
//!
//! Coordinates map onto the 3D tensor slots as r → x, z → y, θ → z, so a stress or strain
//! rate is the 3D [`Sym`](crate::fe::tensor::Sym) [rr, zz, θθ, rz, 0, 0].

use crate::fe::simd::Lanes;
use std::f64::consts::PI;
use std::ops::{AddAssign, Mul, Sub};

/// Natural coordinates (ξ, η) of the four nodes, counter-clockwise.
pub const NODE_XI: [[f64; 2]; 4] = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]];

/// The 2x2 Gauss points (ξ, η), weight 1 each, in node order.
pub const GAUSS_2X2: [[f64; 2]; 4] = {
    let g = 0.577_350_269_189_625_8;
    [[-g, -g], [g, -g], [g, g], [-g, g]]
};

/// The hourglass base vector h = ξη at the nodes.
pub const HOURGLASS_BASE: [f64; 4] = [1.0, -1.0, 1.0, -1.0];

/// The numbers the ring geometry is computed in: `f64` for one quad, [`Lanes`] for W quads
/// side by side (each lane the scalar's operations in the scalar's order).
pub trait Real:
    Copy + AddAssign + Mul<Output = Self> + Mul<f64, Output = Self> + Sub<Output = Self>
{
    /// Every lane equal to `v` (the value `v` itself for `f64`).
    fn splat_like(self, v: f64) -> Self;
    /// The smaller of the two, lane-wise (the `f64::min` rule).
    fn min(self, o: Self) -> Self;
    /// The reciprocal 1/x, lane-wise.
    fn recip(self) -> Self;
}

impl Real for f64 {
    #[inline(always)]
    fn splat_like(self, v: f64) -> f64 {
        v
    }

    #[inline(always)]
    fn min(self, o: f64) -> f64 {
        f64::min(self, o)
    }

    #[inline(always)]
    fn recip(self) -> f64 {
        1.0 / self
    }
}

impl<const W: usize> Real for Lanes<W> {
    #[inline(always)]
    fn splat_like(self, v: f64) -> Self {
        Lanes::splat_like(self, v)
    }

    #[inline(always)]
    fn min(self, o: Self) -> Self {
        Lanes::min(self, o)
    }

    #[inline(always)]
    fn recip(self) -> Self {
        Lanes::recip(self)
    }
}

/// The gradient operator of one integration point or of the whole element: for node I the
/// radial and axial derivatives b_I (1/m) and the hoop factor N_I/r (1/m), and the ring
/// volume `volume` (m³) it weights; of one quad (`f64`) or of W quads ([`Lanes`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Gradient<T = f64> {
    /// ∂N_I/∂r, ∂N_I/∂z per node, 1/m.
    pub b: [[T; 2]; 4],
    /// N_I / r per node, 1/m (the hoop strain rate is Σ v_rI N_I / r).
    pub hoop: [T; 4],
    /// Ring volume the operator stands for, m³ (2π r J w for a point; V for the element).
    pub volume: T,
}

/// One integration point of the element: its gradient and its radius (of one quad, `f64`,
/// or of W quads, [`Lanes`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Point<T = f64> {
    /// Gradient operator and the point's ring-volume weight 2π r det J (m³).
    pub grad: Gradient<T>,
    /// Radius of the point, m.
    pub r: T,
    /// Jacobian determinant det ∂(r, z)/∂(ξ, η), m² (≤ 0: inverted element).
    pub det_j: T,
}

/// Shape functions N_I at (ξ, η) and their natural derivatives ∂N_I/∂ξ, ∂N_I/∂η.
#[inline]
pub fn shape(xi: [f64; 2]) -> ([f64; 4], [[f64; 2]; 4]) {
    let mut n = [0.0; 4];
    let mut d = [[0.0; 2]; 4];
    for (i, p) in NODE_XI.iter().enumerate() {
        n[i] = 0.25 * (1.0 + p[0] * xi[0]) * (1.0 + p[1] * xi[1]);
        d[i] = [
            0.25 * p[0] * (1.0 + p[1] * xi[1]),
            0.25 * p[1] * (1.0 + p[0] * xi[0]),
        ];
    }
    (n, d)
}

/// The point at natural coordinates `xi` of the quad with nodes `x` = [(r, z)] (m), with Gauss
/// weight `w`. The gradient is meaningless when `det_j` ≤ 0; the hoop factor needs r > 0,
/// which holds at every interior point of an element with r ≥ 0 and positive area.
#[inline]
pub fn point(x: &[[f64; 2]; 4], xi: [f64; 2], w: f64) -> Point {
    let (n, d) = shape(xi);
    point_of(x, &n, &d, w)
}

/// Shape functions and natural derivatives at the four 2x2 Gauss points (the values of
/// [`shape`], computed once).
pub(super) const GAUSS_SHAPE: [([f64; 4], [[f64; 2]; 4]); 4] = {
    let mut t = [([0.0; 4], [[0.0; 2]; 4]); 4];
    let mut g = 0;
    while g < 4 {
        let xi = GAUSS_2X2[g];
        let mut i = 0;
        while i < 4 {
            let p = NODE_XI[i];
            t[g].0[i] = 0.25 * (1.0 + p[0] * xi[0]) * (1.0 + p[1] * xi[1]);
            t[g].1[i] = [
                0.25 * p[0] * (1.0 + p[1] * xi[1]),
                0.25 * p[1] * (1.0 + p[0] * xi[0]),
            ];
            i += 1;
        }
        g += 1;
    }
    t
};

/// The radius r (m) and the Jacobian jac[a][c] = ∂x_a/∂ξ_c (m) of the quad `x` (m; one quad
/// in f64, or W quads in lanes) at the point with shape values `n` and natural derivatives
/// `d`, the sums starting from `zero`.
#[inline(always)]
pub(super) fn radius_and_jacobian<T>(
    x: &[[T; 2]; 4],
    n: &[f64; 4],
    d: &[[f64; 2]; 4],
    zero: T,
) -> (T, [[T; 2]; 2])
where
    T: Copy + AddAssign,
    f64: Mul<T, Output = T>,
{
    let mut jac = [[zero; 2]; 2];
    let mut r = zero;
    for i in 0..4 {
        r += n[i] * x[i][0];
        for a in 0..2 {
            for c in 0..2 {
                jac[a][c] += d[i][c] * x[i][a];
            }
        }
    }
    (r, jac)
}

/// The point of the quad `x` (m) with shape values `n` and natural derivatives `d` at that
/// point and Gauss weight `w` (see [`point`]).
#[inline(always)]
fn point_of(x: &[[f64; 2]; 4], n: &[f64; 4], d: &[[f64; 2]; 4], w: f64) -> Point {
    let (r, jac) = radius_and_jacobian(x, n, d, 0.0);
    let det_j = jac[0][0] * jac[1][1] - jac[0][1] * jac[1][0];
    let inv = 1.0 / det_j;
    let mut b = [[0.0; 2]; 4];
    let mut hoop = [0.0; 4];
    for i in 0..4 {
        // ∂N/∂r = (∂N/∂ξ ∂z/∂η − ∂N/∂η ∂z/∂ξ)/J; ∂N/∂z = (∂N/∂η ∂r/∂ξ − ∂N/∂ξ ∂r/∂η)/J.
        b[i] = [
            (d[i][0] * jac[1][1] - d[i][1] * jac[1][0]) * inv,
            (d[i][1] * jac[0][0] - d[i][0] * jac[0][1]) * inv,
        ];
        hoop[i] = n[i] / r;
    }
    Point {
        grad: Gradient {
            b,
            hoop,
            volume: 2.0 * PI * r * det_j * w,
        },
        r,
        det_j,
    }
}

/// The four 2x2 Gauss points of the quad `x` (m).
#[inline]
pub fn gauss_points(x: &[[f64; 2]; 4]) -> [Point; 4] {
    let [g0, g1, g2, g3] = &GAUSS_SHAPE;
    [
        point_of(x, &g0.0, &g0.1, 1.0),
        point_of(x, &g1.0, &g1.1, 1.0),
        point_of(x, &g2.0, &g2.1, 1.0),
        point_of(x, &g3.0, &g3.1, 1.0),
    ]
}

/// The volume-averaged gradient operator B̄_I = (1/V) ∫ B_I 2π r dA of the quad `x` (m),
/// with V = ∫ 2π r dA the ring volume; integrated by 2x2 Gauss, which is exact for both
/// (r det J and r ∂N/∂x det J are polynomials of degree ≤ 2 in each of ξ, η). It is the
/// axisymmetric analogue of Flanagan & Belytschko's mean-strain operator: Σ_I B̄_I = 0 and
/// Σ_I x_I ⊗ B̄_I = I, so linear velocity fields give their exact strain rate. Also returns
/// the smallest Gauss-point Jacobian (m², ≤ 0: the element is inverted).
///
/// Computed directly: with w = 2π r det J at each point, w ∂N/∂x = 2π r cof(J)ᵀ∂N/∂ξ and
/// w N/r = 2π det J N, so no point needs its own inverse Jacobian.
#[inline(always)]
pub fn mean_gradient<T: Real>(x: &[[T; 2]; 4]) -> (Gradient<T>, T)
where
    f64: Mul<T, Output = T>,
{
    let z = x[0][0].splat_like(0.0);
    let mut b = [[z; 2]; 4];
    let mut hoop = [z; 4];
    let mut sum = z;
    let mut min_j = z.splat_like(f64::INFINITY);
    for (n, d) in &GAUSS_SHAPE {
        let (r, jac) = radius_and_jacobian(x, n, d, z);
        let det_j = jac[0][0] * jac[1][1] - jac[0][1] * jac[1][0];
        min_j = min_j.min(det_j);
        sum += r * det_j;
        for i in 0..4 {
            b[i][0] += r * (d[i][0] * jac[1][1] - d[i][1] * jac[1][0]);
            b[i][1] += r * (d[i][1] * jac[0][0] - d[i][0] * jac[0][1]);
            hoop[i] += det_j * n[i];
        }
    }
    let inv = sum.recip();
    for i in 0..4 {
        b[i][0] = b[i][0] * inv;
        b[i][1] = b[i][1] * inv;
        hoop[i] = hoop[i] * inv;
    }
    // 2π as a constant (the bound on f64 × T would claim the product 2.0 × π): the same bits.
    const TWO_PI: f64 = 2.0 * PI;
    (
        Gradient {
            b,
            hoop,
            volume: TWO_PI * sum,
        },
        min_j,
    )
}

/// [`mean_gradient`] from already evaluated Gauss points: the volume-weighted mean operator
/// and the smallest Jacobian (m²).
#[inline(always)]
pub fn mean_of<T: Real>(pts: &[Point<T>; 4]) -> (Gradient<T>, T) {
    let z = pts[0].det_j.splat_like(0.0);
    let mut g = Gradient {
        b: [[z; 2]; 4],
        hoop: [z; 4],
        volume: z,
    };
    let mut min_j = z.splat_like(f64::INFINITY);
    for p in pts {
        let w = p.grad.volume;
        g.volume += w;
        min_j = min_j.min(p.det_j);
        for i in 0..4 {
            g.b[i][0] += w * p.grad.b[i][0];
            g.b[i][1] += w * p.grad.b[i][1];
            g.hoop[i] += w * p.grad.hoop[i];
        }
    }
    let inv = g.volume.recip();
    for i in 0..4 {
        g.b[i][0] = g.b[i][0] * inv;
        g.b[i][1] = g.b[i][1] * inv;
        g.hoop[i] = g.hoop[i] * inv;
    }
    (g, min_j)
}

/// Area of the quad `x`, m² (half the cross product of the diagonals; negative if clockwise).
#[inline]
pub fn area(x: &[[f64; 2]; 4]) -> f64 {
    0.5 * ((x[2][0] - x[0][0]) * (x[3][1] - x[1][1]) - (x[3][0] - x[1][0]) * (x[2][1] - x[0][1]))
}

/// The 3D velocity gradient L (1/s; slots r, z, θ) of nodal velocities `v` = [(v_r, v_z)]
/// (m/s) through the operator `g`: the in-plane block and the hoop rate v_r/r.
#[inline]
pub fn velocity_gradient(v: &[[f64; 2]; 4], g: &Gradient) -> crate::fe::tensor::Mat3 {
    let mut l = [[0.0; 3]; 3];
    for i in 0..4 {
        l[0][0] += v[i][0] * g.b[i][0];
        l[0][1] += v[i][0] * g.b[i][1];
        l[1][0] += v[i][1] * g.b[i][0];
        l[1][1] += v[i][1] * g.b[i][1];
        l[2][2] += v[i][0] * g.hoop[i];
    }
    l
}

/// Adds the nodal forces V Bᵀσ (N, per radian-complete ring) of the stress `s` = [rr, zz, θθ,
/// rz, ..] (Pa) through the operator `g` to `f`.
#[inline]
pub fn add_stress_forces(f: &mut [[f64; 2]; 4], s: &crate::fe::tensor::Sym, g: &Gradient) {
    for i in 0..4 {
        let b = g.b[i];
        f[i][0] += g.volume * (s[0] * b[0] + s[3] * b[1] + s[2] * g.hoop[i]);
        f[i][1] += g.volume * (s[3] * b[0] + s[1] * b[1]);
    }
}

/// The Flanagan-Belytschko hourglass shape vector γ_I = (h_I − (Σ_J h_J x_J)·B̄_I)/4 of the
/// quad `x` with mean operator `g`: orthogonal to every linear field (Σ γ_I = 0,
/// Σ γ_I x_I = 0), so rigid motion and uniform strain excite no hourglass force.
#[inline]
pub fn hourglass_gamma(x: &[[f64; 2]; 4], g: &Gradient) -> [f64; 4] {
    let mut hx = [0.0; 2];
    for i in 0..4 {
        hx[0] += HOURGLASS_BASE[i] * x[i][0];
        hx[1] += HOURGLASS_BASE[i] * x[i][1];
    }
    std::array::from_fn(|i| 0.25 * (HOURGLASS_BASE[i] - hx[0] * g.b[i][0] - hx[1] * g.b[i][1]))
}

/// Characteristic length of the Courant step, m: area over the longest side, shortened by
/// √2 near the axis where the hoop stiffness adds to the in-plane one (elements touching
/// r = 0, whose hoop term N_I/r at the Gauss points exceeds the in-plane gradients). For a
/// square of side h off the axis it is h.
#[inline]
pub fn characteristic_length(x: &[[f64; 2]; 4]) -> f64 {
    let mut l2max: f64 = 0.0;
    let mut rmin = f64::INFINITY;
    for i in 0..4 {
        let j = (i + 1) % 4;
        let d = [x[j][0] - x[i][0], x[j][1] - x[i][1]];
        l2max = l2max.max(d[0] * d[0] + d[1] * d[1]);
        rmin = rmin.min(x[i][0]);
    }
    // One square root: it is monotonic and correctly rounded, so this is the longest side.
    let l = area(x) / l2max.sqrt();
    if rmin < l {
        l / std::f64::consts::SQRT_2
    } else {
        l
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn distorted() -> [[f64; 2]; 4] {
        [[0.0, 0.0], [1.1, -0.1], [1.3, 0.9], [0.0, 1.2]]
    }

    #[test]
    fn mean_operator_reproduces_linear_fields_and_the_ring_volume() {
        let x = [[0.3, 0.1], [1.1, -0.1], [1.3, 0.9], [0.2, 1.2]];
        let (g, min_j) = mean_gradient(&x);
        assert!(min_j > 0.0);
        // Pappus: V = 2π r̄ A with r̄ the area centroid: check against a fine midpoint sum.
        let n = 400;
        let mut v = 0.0;
        for a in 0..n {
            for b in 0..n {
                let xi = [
                    -1.0 + (2 * a + 1) as f64 / n as f64,
                    -1.0 + (2 * b + 1) as f64 / n as f64,
                ];
                let p = point(&x, xi, 4.0 / (n * n) as f64);
                v += p.grad.volume;
            }
        }
        assert!((g.volume - v).abs() < 1e-5 * v, "{} vs {v}", g.volume);
        for a in 0..2 {
            for c in 0..2 {
                let s: f64 = (0..4).map(|i| x[i][a] * g.b[i][c]).sum();
                assert!((s - if a == c { 1.0 } else { 0.0 }).abs() < 1e-13);
            }
        }
        // Hoop: v_r = c r gives exactly c.
        let s: f64 = (0..4).map(|i| x[i][0] * g.hoop[i]).sum();
        assert!((s - 1.0).abs() < 1e-13);
        let gam = hourglass_gamma(&x, &g);
        assert!(gam.iter().sum::<f64>().abs() < 1e-14);
        for a in 0..2 {
            assert!((0..4).map(|i| gam[i] * x[i][a]).sum::<f64>().abs() < 1e-14);
        }
    }

    #[test]
    fn axis_element_has_finite_operators() {
        let (g, _) = mean_gradient(&distorted());
        assert!(g
            .hoop
            .iter()
            .chain(g.b.iter().flatten())
            .all(|c| c.is_finite()));
        let l = characteristic_length(&distorted());
        assert!(l > 0.0 && l < 1.0);
        let sq = [[1.0, 0.0], [2.0, 0.0], [2.0, 1.0], [1.0, 1.0]];
        assert!((characteristic_length(&sq) - 1.0).abs() < 1e-15);
    }
}
