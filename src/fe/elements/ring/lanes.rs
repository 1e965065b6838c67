//! What the ring elements' lane updates share (W quads at once, SIMD lanes): the lane-wise
//! state and output, the geometry of [`super::shape`], the mid-step configuration, the
//! velocity gradient and rotation, and the update of one integration point.
//!
//! Each lane runs the scalar update's operations in the scalar update's order, with only
//! the terms dropped that are zero on the section (the out-of-plane shear and spin of the
//! 3D tensors: x + 0 = x and x · 0 = 0 exactly). So a quad gets the same bits from an
//! element's lane update, on every kernel path, as from its scalar update
//! ([`super::element::RingElement::update`]), which stays the reference; the test in
//! [`super::formulation`] checks it for every registered element.

pub(super) use super::shape::{mean_gradient, mean_of};
use super::shape::{radius_and_jacobian, GAUSS_SHAPE};
use super::state::{PointState, QuadOutput, QuadState};
use crate::fe::materials::{
    j2::{ddot_lanes, update_lanes},
    Hardening, J2Material,
};
use crate::fe::simd::{select, LaneIsa, Lanes};
use std::f64::consts::{PI, SQRT_2};

/// Nodal (r, z) pairs of W quads, lane-wise: `[node][component]`.
pub type Nodes<const W: usize> = [[Lanes<W>; 2]; 4];

/// The volume-averaged operator of W quads (see [`super::shape::Gradient`]).
pub(super) type Gradient<const W: usize> = super::shape::Gradient<Lanes<W>>;

/// The state of W quads, lane-wise (the scalar [`QuadState`]; the one-point form uses the
/// first point only).
#[derive(Clone, Copy)]
pub struct RingLaneState<const W: usize> {
    /// Cauchy stress [rr, zz, θθ, rz] of each point, Pa.
    pub stress: [[Lanes<W>; 4]; 4],
    /// Equivalent plastic strain of each point.
    pub eps_p: [Lanes<W>; 4],
    /// Hourglass generalised force (r, z), N.
    pub hourglass: [Lanes<W>; 2],
    /// ∫ V σ:D dt, J.
    pub internal_energy: Lanes<W>,
    /// Plastic work, J.
    pub plastic_work: Lanes<W>,
    /// Hourglass energy, J.
    pub hourglass_energy: Lanes<W>,
}

impl<const W: usize> RingLaneState<W> {
    /// Lane l from `states[l]`, its first `points` points (1 or 4).
    #[inline(always)]
    pub fn gather(isa: LaneIsa<W>, states: [&QuadState; W], points: usize) -> Self {
        let z = isa.splat(0.0);
        let mut g = RingLaneState {
            stress: [[z; 4]; 4],
            eps_p: [z; 4],
            hourglass: [z; 2],
            internal_energy: z,
            plastic_work: z,
            hourglass_energy: z,
        };
        for (l, st) in states.iter().enumerate() {
            for k in 0..points {
                let p = &st.points[k];
                for c in 0..4 {
                    g.stress[k][c].0[l] = p.stress[c];
                }
                g.eps_p[k].0[l] = p.eps_p;
            }
            g.hourglass[0].0[l] = st.hourglass[0];
            g.hourglass[1].0[l] = st.hourglass[1];
            g.internal_energy.0[l] = st.internal_energy;
            g.plastic_work.0[l] = st.plastic_work;
            g.hourglass_energy.0[l] = st.hourglass_energy;
        }
        g
    }

    /// Writes lane `l`'s first `points` points and the rest into `st` (the stress's
    /// out-of-plane slots stay as they are: zero).
    #[inline(always)]
    pub fn scatter(&self, l: usize, st: &mut QuadState, points: usize) {
        for k in 0..points {
            let p: &mut PointState = &mut st.points[k];
            for c in 0..4 {
                p.stress[c] = self.stress[k][c].0[l];
            }
            p.eps_p = self.eps_p[k].0[l];
        }
        st.hourglass = [self.hourglass[0].0[l], self.hourglass[1].0[l]];
        st.internal_energy = self.internal_energy.0[l];
        st.plastic_work = self.plastic_work.0[l];
        st.hourglass_energy = self.hourglass_energy.0[l];
    }
}

/// Lane l of the scalar [`QuadOutput`], lane-wise.
#[derive(Clone, Copy)]
pub struct RingLaneOutput<const W: usize> {
    /// Internal nodal forces (r, z) of the whole ring, N.
    pub force: [[Lanes<W>; 2]; 4],
    /// Ring volume at t^{n+1}, m³.
    pub volume: Lanes<W>,
    /// Smallest Gauss-point Jacobian, m².
    pub min_jacobian: Lanes<W>,
    /// Courant step L_e / c, s.
    pub dt_crit: Lanes<W>,
}

impl<const W: usize> RingLaneOutput<W> {
    /// Lane `l` as the scalar output.
    #[inline(always)]
    pub fn lane(&self, l: usize) -> QuadOutput {
        let mut force = [[0.0; 2]; 4];
        for (f, o) in force.iter_mut().zip(&self.force) {
            *f = [o[0].0[l], o[1].0[l]];
        }
        QuadOutput {
            force,
            volume: self.volume.0[l],
            min_jacobian: self.min_jacobian.0[l],
            dt_crit: self.dt_crit.0[l],
        }
    }
}

/// The mid-step nodes x^{n+1/2} = x^{n+1} − Δt/2 v^{n+1/2} of W quads (m), from `x1` (m),
/// `v` (m/s) and `dt` (s).
#[inline(always)]
pub(super) fn mid_step<const W: usize>(x1: &Nodes<W>, v: &Nodes<W>, dt: f64) -> Nodes<W> {
    let half = 0.5 * dt;
    let mut xm = *x1;
    for i in 0..4 {
        for c in 0..2 {
            xm[i][c] = x1[i][c] - half * v[i][c];
        }
    }
    xm
}

/// The section's velocity gradient of W quads: (L_rr, L_rz, L_zr, L_zz, L_θθ), 1/s.
#[inline(always)]
pub(super) fn velocity_gradient<const W: usize>(v: &Nodes<W>, g: &Gradient<W>) -> [Lanes<W>; 5] {
    let z = v[0][0].splat_like(0.0);
    let mut l = [z; 5];
    for i in 0..4 {
        l[0] += v[i][0] * g.b[i][0];
        l[1] += v[i][0] * g.b[i][1];
        l[2] += v[i][1] * g.b[i][0];
        l[3] += v[i][1] * g.b[i][1];
        l[4] += v[i][0] * g.hoop[i];
    }
    l
}

/// The in-plane Hughes-Winget rotation (r_rr, r_rz, r_zr, r_zz) of the spin of `l` over `dt`.
#[inline(always)]
pub(super) fn rotation<const W: usize>(l: &[Lanes<W>; 5], dt: f64) -> [Lanes<W>; 4] {
    let w = (0.5 * (l[2] - l[1])) * dt;
    let a = 0.5 * w;
    let f = a.splat_like(2.0) / (1.0 + a * a);
    let aa = a * a;
    let zero = a.splat_like(0.0);
    let diag = f * (zero - aa) + 1.0;
    [diag, f * (zero - a), f * a, diag]
}

/// One 2x2 Gauss point of W quads: its operator (ring-volume weight 2π r det J), radius and
/// det J (see [`super::shape::Point`]).
pub(super) type Point<const W: usize> = super::shape::Point<Lanes<W>>;

/// [`super::shape::gauss_points`] of W quads.
#[inline(always)]
pub(super) fn gauss_points<const W: usize>(x: &Nodes<W>) -> [Point<W>; 4] {
    let z = x[0][0].splat_like(0.0);
    let mut pts = [Point {
        grad: Gradient {
            b: [[z; 2]; 4],
            hoop: [z; 4],
            volume: z,
        },
        r: z,
        det_j: z,
    }; 4];
    for (p, (n, d)) in pts.iter_mut().zip(&GAUSS_SHAPE) {
        let (r, jac) = radius_and_jacobian(x, n, d, z);
        let det_j = jac[0][0] * jac[1][1] - jac[0][1] * jac[1][0];
        let inv = det_j.recip();
        for i in 0..4 {
            p.grad.b[i] = [
                (d[i][0] * jac[1][1] - d[i][1] * jac[1][0]) * inv,
                (d[i][1] * jac[0][0] - d[i][0] * jac[0][1]) * inv,
            ];
            p.grad.hoop[i] = r.splat_like(n[i]) / r;
        }
        p.grad.volume = 2.0 * PI * r * det_j * 1.0;
        p.r = r;
        p.det_j = det_j;
    }
    pts
}

/// The strain increment D Δt (Voigt [rr, zz, θθ, rz, 0, 0]) of the velocity gradient `l`
/// (1/s, as [`velocity_gradient`]) over `dt` (s), its volumetric part replaced by `vol_bar`
/// (1/s) when given (scalar::advance_point).
#[inline(always)]
pub(super) fn strain_increment<const W: usize>(
    l: &[Lanes<W>; 5],
    vol_bar: Option<Lanes<W>>,
    dt: f64,
) -> [Lanes<W>; 6] {
    let zero = l[0].splat_like(0.0);
    let diag = match vol_bar {
        Some(vb) => {
            let shift = (vb - (l[0] + l[3] + l[4])) / 3.0;
            [l[0] + shift, l[3] + shift, l[4] + shift]
        }
        None => [l[0], l[3], l[4]],
    };
    [
        diag[0] * dt,
        diag[1] * dt,
        diag[2] * dt,
        (0.5 * (l[1] + l[2])) * dt,
        zero,
        zero,
    ]
}

/// Advances the four Gauss points `pm` (on the mid-step configuration) of W quads with the
/// nodal velocities `v` (m/s) over `dt` (s), each on its own strain rate with its volumetric
/// part replaced by `vol_bar` (1/s) when given (scalar::advance_gauss_points).
#[inline(always)]
pub(super) fn advance_gauss_points<H: Hardening, const W: usize>(
    pm: &[Point<W>; 4],
    v: &Nodes<W>,
    vol_bar: Option<Lanes<W>>,
    dt: f64,
    mat: &J2Material,
    law: &H,
    st: &mut RingLaneState<W>,
) {
    for (k, p) in pm.iter().enumerate() {
        let l = velocity_gradient(v, &p.grad);
        let d = strain_increment(&l, vol_bar, dt);
        let r = rotation(&l, dt);
        advance_point(mat, law, &r, &d, dt, p.grad.volume, k, st);
    }
}

/// The output of W updates: nodal forces `force` (N) on the quads `x1` (m) of ring volumes
/// `volume` (m³) and smallest Jacobians `min_jacobian` (m²), with their Courant steps
/// (scalar::output).
#[inline(always)]
pub(super) fn output<const W: usize>(
    x1: &Nodes<W>,
    force: [[Lanes<W>; 2]; 4],
    volume: Lanes<W>,
    min_jacobian: Lanes<W>,
    mat: &J2Material,
) -> RingLaneOutput<W> {
    RingLaneOutput {
        force,
        volume,
        min_jacobian,
        dt_crit: characteristic_length(x1) / mat.wave_speed,
    }
}

/// Rotates point `k`'s stress by `r` (the in-plane rotation of [`rotation`]), advances it by
/// the strain increment `d` through the material, and accounts its energies over the ring
/// volume `volume` (scalar::advance_point).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(super) fn advance_point<H: Hardening, const W: usize>(
    mat: &J2Material,
    law: &H,
    r: &[Lanes<W>; 4],
    d: &[Lanes<W>; 6],
    dt: f64,
    volume: Lanes<W>,
    k: usize,
    st: &mut RingLaneState<W>,
) {
    let s = st.stress[k];
    let zero = s[0].splat_like(0.0);
    let t = [
        [r[0] * s[0] + r[1] * s[3], r[0] * s[3] + r[1] * s[1]],
        [r[2] * s[0] + r[3] * s[3], r[2] * s[3] + r[3] * s[1]],
    ];
    let mut stress = [
        t[0][0] * r[0] + t[0][1] * r[1],
        t[1][0] * r[2] + t[1][1] * r[3],
        s[2],
        t[0][0] * r[2] + t[0][1] * r[3],
        zero,
        zero,
    ];
    let before = stress;
    let dwp = update_lanes(mat, law, &mut stress, &mut st.eps_p[k], d, dt);
    st.internal_energy += 0.5 * volume * (ddot_lanes(&before, d) + ddot_lanes(&stress, d));
    st.plastic_work += dwp * volume;
    st.stress[k] = [stress[0], stress[1], stress[2], stress[3]];
}

/// Adds V Bᵀσ of the stress `s` = [rr, zz, θθ, rz] through the operator `g` to `f`
/// (shape::add_stress_forces).
#[inline(always)]
pub(super) fn add_stress_forces<const W: usize>(
    f: &mut [[Lanes<W>; 2]; 4],
    s: &[Lanes<W>; 4],
    g: &Gradient<W>,
) {
    for i in 0..4 {
        let b = g.b[i];
        f[i][0] += g.volume * (s[0] * b[0] + s[3] * b[1] + s[2] * g.hoop[i]);
        f[i][1] += g.volume * (s[3] * b[0] + s[1] * b[1]);
    }
}

/// [`super::shape::characteristic_length`] of W quads, m.
#[inline(always)]
pub(super) fn characteristic_length<const W: usize>(x: &Nodes<W>) -> Lanes<W> {
    let mut l2max = x[0][0].splat_like(0.0);
    let mut rmin = x[0][0].splat_like(f64::INFINITY);
    for i in 0..4 {
        let j = (i + 1) % 4;
        let d = [x[j][0] - x[i][0], x[j][1] - x[i][1]];
        l2max = l2max.max(d[0] * d[0] + d[1] * d[1]);
        rmin = rmin.min(x[i][0]);
    }
    let area = 0.5
        * ((x[2][0] - x[0][0]) * (x[3][1] - x[1][1]) - (x[3][0] - x[1][0]) * (x[2][1] - x[0][1]));
    let l = area / l2max.sqrt();
    select(l.gt(rmin), l / SQRT_2, l)
}
