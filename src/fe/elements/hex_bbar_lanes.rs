//! The B-bar hexahedron of [`crate::fe::elements::hex_bbar`], computed for W elements at once (SIMD lanes)
//! and in mode space, like [`crate::fe::elements::hex_one_point_lanes`].
//!
//! With the mode vectors A_k of the nodal coordinates (x(ξ) = (1/8) Σ_k A_k h_k(ξ), modes
//! h = (1, ξ, η, ζ, ηζ, ζξ, ξη, ξηζ)), the Jacobian columns at a Gauss point are short sums:
//!
//!   8 ∂x/∂ξ = A₁ + ζ A₅ + η A₆ + ηζ A₇,  8 ∂x/∂η = A₂ + ζ A₄ + ξ A₆ + ζξ A₇,
//!   8 ∂x/∂ζ = A₃ + η A₄ + ξ A₅ + ξη A₇,
//!
//! and the same sums of the velocity modes U_k give ∂v/∂ξ_d. With c_d = ∂x/∂ξ_d and
//! n_d = c_{d+1} × c_{d+2} (cyclic), J⁻¹ has the rows n_d / det J, so the velocity gradient is
//! L = Σ_d (∂v/∂ξ_d) ⊗ n_d / det J: no per-node gradient is formed. The nodal forces
//! f_I = Σ_g J_g σ̂_g ∇N_I(g) (σ̂_g = s_g + p̄ I, the B-bar stress: point deviator plus the
//! element's volume-averaged pressure) become f_I = Σ_k h_k(ξ_I) F_k with mode forces built
//! from the vectors P_gd = σ̂_g n_gd, because ∂N_I/∂ξ_d is itself a short mode sum
//! (8 ∂N_I/∂ξ = h₁(ξ_I) + ζ h₅(ξ_I) + η h₆(ξ_I) + ηζ h₇(ξ_I), and cyclically). The inverse
//! ±1 transform [`nodes_from_modes`] then gives the nodal forces.
//!
//! Every lane follows the same operation sequence, so the results do not depend on how
//! elements are grouped into lanes; they equal the per-element kernel up to round-off
//! (checked to 1e-11 relative in the tests).

use crate::fe::elements::batch::LaneResult;
use crate::fe::elements::element::{Element, LaneStep};
use crate::fe::elements::lane_state::{NoLanes, PointLanes};
use std::mem::MaybeUninit;

use crate::fe::{
    elements::hex_one_point_lanes::{critical_step, modes, nodes_from_modes, point_update},
    elements::shape::{GAUSS2, NODE_XI},
    materials::{Hardening, J2Material},
    simd::{cross, dot, Lanes, Vec3},
};

/// The state of W B-bar elements, lane-wise; points in the order of
/// [`crate::fe::elements::shape::gauss_points_2x2x2`].
pub type BBarLaneState<const W: usize> = PointLanes<8, W>;

/// What a group update returns, lane-wise.
#[derive(Debug, Clone, Copy)]
pub struct BBarLaneOutput<const W: usize> {
    /// Internal nodal forces at t^{n+1}, N.
    pub force: [Vec3<W>; 8],
    /// Volume at t^{n+1}, m³.
    pub volume: Lanes<W>,
    /// Volume each Gauss point represents at t^{n+1} (det J, weights 1), m³.
    pub point_volume: [Lanes<W>; 8],
    /// Smallest det J of the eight points (≤ 0: inverted), m³.
    pub min_jacobian: Lanes<W>,
    /// Critical time step L_e/c, s.
    pub dt_crit: Lanes<W>,
}

/// Natural coordinates (ξ, η, ζ) of Gauss point `g`.
#[inline(always)]
fn gauss_point(g: usize) -> [f64; 3] {
    let n = NODE_XI[g];
    [n[0] * GAUSS2, n[1] * GAUSS2, n[2] * GAUSS2]
}

/// 8 ∂p/∂ξ_d (d = ξ, η, ζ) at the natural point `q` of a trilinear field with mode vectors `a`.
#[inline(always)]
fn natural_columns<const W: usize>(a: &[Vec3<W>; 8], q: [f64; 3]) -> [Vec3<W>; 3] {
    let [s, t, u] = q;
    let (tu, us, st) = (t * u, u * s, s * t);
    // Plain loops, no closures: a closure the compiler leaves out of line would run its
    // lane arithmetic as calls.
    let mut col = [[a[0][0].splat_like(0.0); 3]; 3];
    for c in 0..3 {
        col[0][c] = a[1][c] + u * a[5][c] + t * a[6][c] + tu * a[7][c];
        col[1][c] = a[2][c] + u * a[4][c] + s * a[6][c] + us * a[7][c];
        col[2][c] = a[3][c] + t * a[4][c] + s * a[5][c] + st * a[7][c];
    }
    col
}

/// The scaled cofactor rows n̂_d = ĉ_{d+1} × ĉ_{d+2} of the scaled Jacobian columns `c`
/// (ĉ = 8 c) and 512 det J.
#[inline(always)]
fn cofactor_rows<const W: usize>(c: &[Vec3<W>; 3]) -> ([Vec3<W>; 3], Lanes<W>) {
    let n = [
        cross(&c[1], &c[2]),
        cross(&c[2], &c[0]),
        cross(&c[0], &c[1]),
    ];
    let det = dot(&c[0], &n[0]);
    (n, det)
}

/// Advances W B-bar elements from t^n to t^{n+1}: nodal coordinates `x1` = x^{n+1} (m),
/// velocities `v` = v^{n+1/2} (m/s), step `dt` (s, 0 = evaluate only). The same physics as
/// [`crate::fe::elements::hex_bbar::update`]: mean-dilatation velocity gradient on the mid-step
/// configuration, Hughes-Winget rotation and J2 update per point, forces on x^{n+1}. An
/// inverted lane returns a non-positive `min_jacobian` and meaningless forces.
#[inline(always)]
pub fn update<H: Hardening, const W: usize>(
    x1: &[Vec3<W>; 8],
    v: &[Vec3<W>; 8],
    dt: f64,
    mat: &J2Material,
    law: &H,
    st: &mut BBarLaneState<W>,
) -> BBarLaneOutput<W> {
    let a1 = modes(x1);
    let u = modes(v);
    let half = 0.5 * dt;
    let mut am = a1;
    for (m, uk) in am.iter_mut().zip(&u) {
        for c in 0..3 {
            m[c] -= half * uk[c];
        }
    }
    let z = x1[0][0].splat_like(0.0);

    // Mid-step velocity gradients L_g = Σ_d (8 ∂v/∂ξ_d) ⊗ n̂_d / (512 det J) and their mean
    // dilatation Σ_g J_g tr L_g / Σ_g J_g.
    // The eight gradients are written into uninitialised storage, each slot once: a
    // zero-filled array overwritten afterwards cost a 4.6 KB `memset` call per lane group
    // (likewise `n1` below).
    let mut ls = MaybeUninit::<[[Vec3<W>; 3]; 8]>::uninit();
    let mut jm = [z; 8];
    let mut div_sum = z;
    let mut vol_m = z;
    for g in 0..8 {
        let q = gauss_point(g);
        let (n, det) = cofactor_rows(&natural_columns(&am, q));
        let dv = natural_columns(&u, q);
        let r = det.recip();
        let mut l = [[z; 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                l[i][j] = (dv[0][i] * n[0][j] + dv[1][i] * n[1][j] + dv[2][i] * n[2][j]) * r;
            }
        }
        jm[g] = det * (1.0 / 512.0);
        div_sum += jm[g] * (l[0][0] + l[1][1] + l[2][2]);
        vol_m += jm[g];
        // SAFETY: slot g < 8 of the array, written once.
        unsafe { ls.as_mut_ptr().cast::<[Vec3<W>; 3]>().add(g).write(l) };
    }
    // SAFETY: all eight slots were written above.
    let ls = unsafe { ls.assume_init_ref() };
    let div_mean = div_sum / vol_m;

    for g in 0..8 {
        let l = &ls[g];
        let shift = (div_mean - (l[0][0] + l[1][1] + l[2][2])) * (1.0 / 3.0);
        let (_, dwp, dw) = point_update(
            mat,
            law,
            l,
            Some(shift),
            dt,
            &mut st.stress[g],
            &mut st.eps_p[g],
        );
        st.plastic_work += dwp * jm[g];
        st.internal_energy += 0.5 * jm[g] * dw;
    }

    // Forces on x^{n+1}: the pressure is averaged over the element (B-bar), the deviator is
    // the point's own.
    let mut n1 = MaybeUninit::<[[Vec3<W>; 3]; 8]>::uninit();
    let mut j1 = [z; 8];
    let mut vol = z;
    let mut pj = z;
    let mut jmin = z.splat_like(f64::INFINITY);
    for g in 0..8 {
        let (n, det) = cofactor_rows(&natural_columns(&a1, gauss_point(g)));
        // SAFETY: slot g < 8 of the array, written once.
        unsafe { n1.as_mut_ptr().cast::<[Vec3<W>; 3]>().add(g).write(n) };
        j1[g] = det * (1.0 / 512.0);
        jmin = jmin.min(j1[g]);
        vol += j1[g];
        let s = &st.stress[g];
        pj += j1[g] * ((s[0] + s[1] + s[2]) * (1.0 / 3.0));
    }
    // SAFETY: all eight slots were written above.
    let n1 = unsafe { n1.assume_init_ref() };
    let p_mean = pj / vol;
    // Mode forces F_k (k = 1..7) from P_gd = σ̂_g n̂_gd; the factor 1/512 (n̂ = 64 n, and 1/8
    // from ∂N_I/∂ξ_d) is applied once at the end.
    let mut fm = [[z; 3]; 8];
    for g in 0..8 {
        let s = &st.stress[g];
        let shift = p_mean - (s[0] + s[1] + s[2]) * (1.0 / 3.0);
        let sig = [
            [s[0] + shift, s[3], s[5]],
            [s[3], s[1] + shift, s[4]],
            [s[5], s[4], s[2] + shift],
        ];
        let mut p = [[z; 3]; 3];
        for d in 0..3 {
            for i in 0..3 {
                p[d][i] = dot(&sig[i], &n1[g][d]);
            }
        }
        let [xi, eta, zeta] = gauss_point(g);
        for i in 0..3 {
            fm[1][i] += p[0][i];
            fm[2][i] += p[1][i];
            fm[3][i] += p[2][i];
            fm[4][i] += zeta * p[1][i] + eta * p[2][i];
            fm[5][i] += zeta * p[0][i] + xi * p[2][i];
            fm[6][i] += eta * p[0][i] + xi * p[1][i];
            fm[7][i] += (eta * zeta) * p[0][i] + (zeta * xi) * p[1][i] + (xi * eta) * p[2][i];
        }
    }
    for f in fm.iter_mut().skip(1) {
        for c in f.iter_mut() {
            *c = *c * (1.0 / 512.0);
        }
    }
    let force = nodes_from_modes(&fm);
    BBarLaneOutput {
        force,
        volume: vol,
        point_volume: j1,
        min_jacobian: jmin,
        dt_crit: critical_step(x1, vol, mat.wave_speed),
    }
}

/// The B-bar hexahedron as an element of the element loop.
#[derive(Debug, Clone, Copy)]
pub struct BBarHex;

impl Element for BBarHex {
    const HOURGLASS: bool = false;
    type Points<const W: usize> = BBarLaneState<W>;
    type Extra<const W: usize> = NoLanes;
    type Output<const W: usize> = BBarLaneOutput<W>;

    #[inline(always)]
    fn update<H: Hardening, const W: usize>(
        s: LaneStep<'_, H, W>,
        points: &mut BBarLaneState<W>,
        _: &mut NoLanes,
    ) -> BBarLaneOutput<W> {
        update(s.x1, s.v, s.dt, s.mat, s.law, points)
    }

    #[inline(always)]
    fn result<const W: usize>(out: &BBarLaneOutput<W>) -> LaneResult<'_, W> {
        LaneResult {
            force: &out.force,
            volume: out.volume,
            min_jacobian: out.min_jacobian,
            dt_crit: out.dt_crit,
        }
    }

    #[inline(always)]
    fn point_volumes<const W: usize>(out: &BBarLaneOutput<W>) -> [Lanes<W>; 8] {
        out.point_volume
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fe::elements::{
        batch::{ElementStateMut, IntegrationPoint},
        hex_bbar,
        hex_one_point_lanes::tests::{
            assert_forces_match, copper, drift, four_elements, lanes, zero_lanes,
        },
    };

    /// Four lanes of distorted, spinning, yielding elements against the per-element B-bar
    /// kernel over many steps (state carried): equal to round-off, on both the elastic and
    /// the plastic path.
    #[test]
    fn lanes_match_the_per_element_kernel() {
        let (mat, law) = copper();
        let h = 1e-3;
        // Lane 1 moves rigidly (spin, no strain); the others stretch hard and yield.
        let (xs, vs) = four_elements(0x0bad_cafe_2468_1357, h, 1, 50.0, [4.0, 2.0, 3.0], 0.3);
        let dt = 2e-8;
        let mut x = xs;
        let z = zero_lanes();
        let mut st = BBarLaneState::<4>::filled(z);
        let mut refs = [([IntegrationPoint::default(); 8], 0.0, 0.0); 4];
        let mut yielded = [false; 4];
        for _ in 0..400 {
            drift(&mut x, &vs, dt);
            let out = update(&lanes(&x), &lanes(&vs), dt, &mat, &law, &mut st);
            for l in 0..4 {
                let r = &mut refs[l];
                let mut hg = [[0.0; 3]; 4];
                let mut ehg = 0.0;
                let o = hex_bbar::update(
                    &x[l],
                    &vs[l],
                    dt,
                    &mat,
                    ElementStateMut {
                        points: &mut r.0,
                        plastic_work: &mut r.1,
                        internal_energy: &mut r.2,
                        hourglass: &mut hg,
                        hourglass_energy: &mut ehg,
                    },
                );
                let close = |a: f64, b: f64, scale: f64| (a - b).abs() <= 1e-11 * scale;
                assert_forces_match(&out.force, l, &o.force, mat.yield0 * h * h);
                for g in 0..8 {
                    let p = &r.0[g];
                    let sscale = p
                        .stress
                        .iter()
                        .fold(1e-3 * mat.yield0, |m, c| m.max(c.abs()));
                    for k in 0..6 {
                        assert!(
                            close(st.stress[g][k].0[l], p.stress[k], sscale),
                            "lane {l} point {g} stress"
                        );
                    }
                    assert!(close(st.eps_p[g].0[l], p.eps_p, 1e-3));
                    assert!(close(out.point_volume[g].0[l], p.volume, p.volume));
                }
                let escale = 1e-6 * mat.yield0 * h * h * h;
                assert!(close(out.volume.0[l], o.volume, o.volume));
                assert!(close(out.min_jacobian.0[l], o.min_jacobian, o.volume));
                assert!(close(out.dt_crit.0[l], o.dt_crit, o.dt_crit));
                assert!(close(st.plastic_work.0[l], r.1, r.2.abs().max(escale)));
                assert!(close(st.internal_energy.0[l], r.2, r.2.abs().max(escale)));
                yielded[l] = r.0.iter().any(|p| p.eps_p > 0.0);
            }
        }
        assert_eq!(
            yielded,
            [true, false, true, true],
            "the test must exercise both paths"
        );
    }
}
