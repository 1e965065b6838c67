//! The one-point hexahedron of [`crate::fe::elements::hex_one_point`], computed for W elements at once
//! (SIMD lanes) and in "mode space", which needs about half the arithmetic.
//!
//! Mode space: a trilinear hex maps x(ξ, η, ζ) = Σ_I N_I(ξ) x_I = (1/8) Σ_k A_k h_k(ξ) with the
//! eight modes h = (1, ξ, η, ζ, ηζ, ζξ, ξη, ξηζ) and the mode vectors A_k = Σ_I h_k(ξ_I) x_I
//! (a ±1 transform of the nodal coordinates: 72 additions, [`modes`]). The exact volume
//! V = ∫ det(∂x/∂ξ) dξ over [-1, 1]³ keeps only the integrands with even powers:
//!
//!   192 V = 3 [A₁, A₂, A₃] + [A₁, A₆, A₅] + [A₆, A₂, A₄] + [A₅, A₄, A₃]      ([a, b, c] = a·(b×c)),
//!
//! so the twist mode A₇ does not change the volume, and the volume derivatives are
//! ∂V/∂x_I = (1/192) Σ_k Ĝ_k h_k(ξ_I) with Ĝ_k = 192 ∂V/∂A_k, twelve cross products
//! ([`volume_gradient`]). This is Flanagan & Belytschko's B_I = (1/V) ∂V/∂x_I exactly, with no
//! per-node formula: the velocity gradient L = Σ_I v_I ⊗ B_I = (1/V̂) Σ_k U_k ⊗ Ĝ_k uses the
//! mode vectors U_k of the velocities; the mid-step modes are A_k − Δt/2 U_k (linearity); the FB
//! hourglass rates q_α = Σ_I v_I γ_αI = (U_{α+4} − L A_{α+4})/8 need no γ vectors; and all nodal
//! forces (stress and hourglass) are one 3x3 matrix applied to each Ĝ_k followed by the
//! inverse ±1 transform ([`nodes_from_modes`]). Σ_I |B_I|² = 8 Σ_k |Ĝ_k|² / V̂² because the
//! mode patterns are orthogonal over the nodes (Σ_I h_k h_l = 8 δ_kl).
//!
//! Every lane follows the same operation sequence, so results do not depend on how elements
//! are grouped into lanes; they equal the per-element kernel up to round-off (different, not
//! less accurate, operation order; checked to 1e-12 relative in the tests).

use crate::fe::elements::batch::LaneResult;
use crate::fe::elements::element::{Element, LaneStep};
use crate::fe::elements::lane_state::{HourglassLanes, PointLanes};
use crate::fe::{
    materials::{
        j2::{ddot_lanes as ddot, update_lanes},
        Hardening, J2Material,
    },
    simd::{cross, dot, Lanes, Vec3},
};
use crate::mesh::topology::HEX_FACES;

/// Mode vectors A_k = Σ_I h_k(ξ_I) p_I (k = 0..7: 1, ξ, η, ζ, ηζ, ζξ, ξη, ξηζ) of nodal
/// vectors `p` (gmsh node order), by three butterfly stages (ξ pairs, η pairs, ζ pairs).
#[inline(always)]
pub fn modes<const W: usize>(p: &[Vec3<W>; 8]) -> [Vec3<W>; 8] {
    let z = p[0][0].splat_like(0.0);
    let mut a = [[z; 3]; 8];
    for c in 0..3 {
        // ξ pairs (0,1), (3,2), (4,5), (7,6): sums and ξ-differences.
        let (s0, d0) = (p[0][c] + p[1][c], p[1][c] - p[0][c]);
        let (s1, d1) = (p[3][c] + p[2][c], p[2][c] - p[3][c]);
        let (s2, d2) = (p[4][c] + p[5][c], p[5][c] - p[4][c]);
        let (s3, d3) = (p[7][c] + p[6][c], p[6][c] - p[7][c]);
        // η pairs at ζ = −1 (0, 1) and ζ = +1 (2, 3).
        let (ss0, sd0, ds0, dd0) = (s0 + s1, s1 - s0, d0 + d1, d1 - d0);
        let (ss1, sd1, ds1, dd1) = (s2 + s3, s3 - s2, d2 + d3, d3 - d2);
        // ζ pairs.
        a[0][c] = ss0 + ss1;
        a[3][c] = ss1 - ss0;
        a[2][c] = sd0 + sd1;
        a[4][c] = sd1 - sd0;
        a[1][c] = ds0 + ds1;
        a[5][c] = ds1 - ds0;
        a[6][c] = dd0 + dd1;
        a[7][c] = dd1 - dd0;
    }
    a
}

/// Nodal vectors p_I = Σ_k h_k(ξ_I) f_k from mode vectors `f` (the transpose of [`modes`]).
#[inline(always)]
pub fn nodes_from_modes<const W: usize>(f: &[Vec3<W>; 8]) -> [Vec3<W>; 8] {
    let z = f[0][0].splat_like(0.0);
    let mut p = [[z; 3]; 8];
    for c in 0..3 {
        // ζ = −1 (index 0) and ζ = +1 (index 1): coefficients of 1, η, ξ, ξη.
        let (ss0, ss1) = (f[0][c] - f[3][c], f[0][c] + f[3][c]);
        let (sd0, sd1) = (f[2][c] - f[4][c], f[2][c] + f[4][c]);
        let (ds0, ds1) = (f[1][c] - f[5][c], f[1][c] + f[5][c]);
        let (dd0, dd1) = (f[6][c] - f[7][c], f[6][c] + f[7][c]);
        // η = ∓1: coefficients of 1 and ξ.
        let (s0, s1, d0, d1) = (ss0 - sd0, ss0 + sd0, ds0 - dd0, ds0 + dd0);
        let (s2, s3, d2, d3) = (ss1 - sd1, ss1 + sd1, ds1 - dd1, ds1 + dd1);
        // ξ = ∓1.
        p[0][c] = s0 - d0;
        p[1][c] = s0 + d0;
        p[3][c] = s1 - d1;
        p[2][c] = s1 + d1;
        p[4][c] = s2 - d2;
        p[5][c] = s2 + d2;
        p[7][c] = s3 - d3;
        p[6][c] = s3 + d3;
    }
    p
}

/// 192 V (m³) and Ĝ_k = 192 ∂V/∂A_k for k = 1..6 (index k − 1; Ĝ₀ = Ĝ₇ = 0) from the mode
/// vectors `a` of the nodal coordinates. V ≤ 0 means an inverted element.
#[inline(always)]
pub fn volume_gradient<const W: usize>(a: &[Vec3<W>; 8]) -> (Lanes<W>, [Vec3<W>; 6]) {
    let c23 = cross(&a[2], &a[3]);
    let c31 = cross(&a[3], &a[1]);
    let c12 = cross(&a[1], &a[2]);
    let c65 = cross(&a[6], &a[5]);
    let c46 = cross(&a[4], &a[6]);
    let c54 = cross(&a[5], &a[4]);
    let c62 = cross(&a[6], &a[2]);
    let c35 = cross(&a[3], &a[5]);
    let c16 = cross(&a[1], &a[6]);
    let c43 = cross(&a[4], &a[3]);
    let c51 = cross(&a[5], &a[1]);
    let c24 = cross(&a[2], &a[4]);
    // Plain loops, no closures: a closure the compiler leaves out of line (it may, once the
    // kernel is instantiated in more than one place) runs its lane arithmetic as calls.
    let mut g = [[a[0][0].splat_like(0.0); 3]; 6];
    for k in 0..3 {
        g[0][k] = 3.0 * c23[k] + c65[k];
        g[1][k] = 3.0 * c31[k] + c46[k];
        g[2][k] = 3.0 * c12[k] + c54[k];
        g[3][k] = c62[k] + c35[k];
        g[4][k] = c16[k] + c43[k];
        g[5][k] = c51[k] + c24[k];
    }
    // 192 V = A₁·(3 A₂×A₃ + A₆×A₅) + A₆·(A₂×A₄) + A₅·(A₄×A₃).
    let v = dot(&a[1], &g[0]) + dot(&a[6], &c24) + dot(&a[5], &c43);
    (v, g)
}

/// L = (1/V̂) Σ_k U_k ⊗ Ĝ_k: velocity gradient (1/s, row-major [i][j] = ∂v_i/∂x_j) from the
/// velocity modes `u`, the volume-gradient modes `g` and `rv` = 1/V̂.
#[inline(always)]
fn velocity_gradient<const W: usize>(
    u: &[Vec3<W>; 8],
    g: &[Vec3<W>; 6],
    rv: Lanes<W>,
) -> [Vec3<W>; 3] {
    let mut l = [[rv.splat_like(0.0); 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            let mut s = u[1][i] * g[0][j];
            for k in 2..7 {
                s += u[k][i] * g[k - 1][j];
            }
            l[i][j] = s * rv;
        }
    }
    l
}

/// The Hughes-Winget rotation increment for the spin increment with axial vector `w`
/// (lane-wise [`crate::fe::elements::objective::hughes_winget`]).
#[inline(always)]
pub fn hughes_winget<const W: usize>(w: &Vec3<W>) -> [Vec3<W>; 3] {
    let a = [0.5 * w[0], 0.5 * w[1], 0.5 * w[2]];
    let aa = a[0] * a[0] + a[1] * a[1] + a[2] * a[2];
    let f = aa.splat_like(2.0) / (aa + 1.0);
    let one = aa.splat_like(1.0);
    [
        [
            f * (a[0] * a[0] - aa) + one,
            f * (-a[2] + a[0] * a[1]),
            f * (a[1] + a[0] * a[2]),
        ],
        [
            f * (a[2] + a[1] * a[0]),
            f * (a[1] * a[1] - aa) + one,
            f * (-a[0] + a[1] * a[2]),
        ],
        [
            f * (-a[1] + a[2] * a[0]),
            f * (a[0] + a[2] * a[1]),
            f * (a[2] * a[2] - aa) + one,
        ],
    ]
}

/// R s Rᵀ for a symmetric tensor (Voigt [xx, yy, zz, xy, yz, zx]).
#[inline(always)]
pub fn rotate_symmetric<const W: usize>(r: &[Vec3<W>; 3], s: &[Lanes<W>; 6]) -> [Lanes<W>; 6] {
    let m = [[s[0], s[3], s[5]], [s[3], s[1], s[4]], [s[5], s[4], s[2]]];
    let mut t = [[s[0].splat_like(0.0); 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            t[i][j] = r[i][0] * m[0][j] + r[i][1] * m[1][j] + r[i][2] * m[2][j];
        }
    }
    let mut out = [s[0].splat_like(0.0); 6];
    for (o, (i, j)) in out
        .iter_mut()
        .zip([(0, 0), (1, 1), (2, 2), (0, 1), (1, 2), (2, 0)])
    {
        *o = t[i][0] * r[j][0] + t[i][1] * r[j][1] + t[i][2] * r[j][2];
    }
    out
}

/// One integration point over the step, lane-wise: strain increment D Δt and spin increment
/// W Δt from the velocity gradient `l` (1/s; `shift`, 1/s, is added to the normal rates: the
/// B-bar volumetric correction), Hughes-Winget rotation of `stress` (Pa), J2 update of
/// `stress` and `eps_p`. Returns the rotation (to turn other objective quantities with the
/// point), the plastic work per unit volume (J/m³) and σ:DΔt summed at the start and the end
/// of the step (J/m³; half of it is the trapezoidal internal-energy increment per volume).
#[inline(always)]
pub fn point_update<H: Hardening, const W: usize>(
    mat: &J2Material,
    law: &H,
    l: &[Vec3<W>; 3],
    shift: Option<Lanes<W>>,
    dt: f64,
    stress: &mut [Lanes<W>; 6],
    eps_p: &mut Lanes<W>,
) -> ([Vec3<W>; 3], Lanes<W>, Lanes<W>) {
    // No closure here: one left out of line would run its lane arithmetic as calls.
    let mut n = [l[0][0], l[1][1], l[2][2]];
    if let Some(sh) = shift {
        for x in &mut n {
            *x += sh;
        }
    }
    let d = [
        n[0] * dt,
        n[1] * dt,
        n[2] * dt,
        (0.5 * (l[0][1] + l[1][0])) * dt,
        (0.5 * (l[1][2] + l[2][1])) * dt,
        (0.5 * (l[2][0] + l[0][2])) * dt,
    ];
    let w = [
        (0.5 * (l[2][1] - l[1][2])) * dt,
        (0.5 * (l[0][2] - l[2][0])) * dt,
        (0.5 * (l[1][0] - l[0][1])) * dt,
    ];
    let rot = hughes_winget(&w);
    *stress = rotate_symmetric(&rot, stress);
    let before = *stress;
    let dwp = update_lanes(mat, law, stress, eps_p, &d, dt);
    (rot, dwp, ddot(&before, &d) + ddot(stress, &d))
}

/// The point state of W one-point elements, lane-wise (their hourglass forces are
/// [`HourglassLanes`]).
pub type OnePointLanes<const W: usize> = PointLanes<1, W>;

/// What a group update returns, lane-wise.
#[derive(Debug, Clone, Copy)]
pub struct OnePointLaneOutput<const W: usize> {
    /// Internal nodal forces at t^{n+1}, N.
    pub force: [Vec3<W>; 8],
    /// Volume at t^{n+1} (≤ 0: inverted), m³.
    pub volume: Lanes<W>,
    /// Critical time step L_e/c, s.
    pub dt_crit: Lanes<W>,
}

/// Advances W one-point elements from t^n to t^{n+1}: nodal coordinates `x1` = x^{n+1} (m),
/// velocities `v` = v^{n+1/2} (m/s), step `dt` (s, 0 = evaluate only), hourglass coefficient
/// `hg` (0 = off). The same physics as [`crate::fe::elements::hex_one_point::update`]: velocity gradient on
/// the mid-step configuration, Hughes-Winget rotation of stress and hourglass forces, J2
/// update, forces on x^{n+1}. An inverted lane returns a non-positive volume and
/// meaningless forces.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub fn update<H: Hardening, const W: usize>(
    x1: &[Vec3<W>; 8],
    v: &[Vec3<W>; 8],
    dt: f64,
    mat: &J2Material,
    law: &H,
    hg: f64,
    points: &mut OnePointLanes<W>,
    hourglass: &mut HourglassLanes<W>,
) -> OnePointLaneOutput<W> {
    let a1 = modes(x1);
    let u = modes(v);
    let half = 0.5 * dt;
    let mut am = [[x1[0][0].splat_like(0.0); 3]; 8];
    for k in 0..8 {
        for c in 0..3 {
            am[k][c] = a1[k][c] - half * u[k][c];
        }
    }
    let (vhm, gm) = volume_gradient(&am);
    let vm = vhm * (1.0 / 192.0);
    let l = velocity_gradient(&u, &gm, vhm.recip());
    let (rot, dwp, dw) = point_update(
        mat,
        law,
        &l,
        None,
        dt,
        &mut points.stress[0],
        &mut points.eps_p[0],
    );
    for q in hourglass.forces.iter_mut() {
        let r = *q;
        for i in 0..3 {
            q[i] = rot[i][0] * r[0] + rot[i][1] * r[1] + rot[i][2] * r[2];
        }
    }
    points.plastic_work += dwp * vm;
    points.internal_energy += 0.5 * vm * dw;

    let (vh1, g1) = volume_gradient(&a1);
    let r1 = vh1.recip();
    let v1 = vh1 * (1.0 / 192.0);
    let s = points.stress[0];
    let sigma = [[s[0], s[3], s[5]], [s[3], s[1], s[4]], [s[5], s[4], s[2]]];
    // P = (V σ − M)/V̂ with M = (1/8) Σ_α Q_α ⊗ A_{α+4} (the hourglass part of −γ Q).
    let mut p = [[v1.splat_like(0.0); 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            p[i][j] = v1 * sigma[i][j];
        }
    }
    let z = v1.splat_like(0.0);
    let mut fm = [[z; 3]; 8];
    if hg > 0.0 {
        let l1 = velocity_gradient(&u, &g1, r1);
        let mut gg = z;
        for gk in &g1 {
            gg += dot(gk, gk);
        }
        // k = ε (λ + 2G) V Σ_I |B_I|²/3 with Σ_I |B_I|² = 8 Σ_k |Ĝ_k|²/V̂².
        let bb = 8.0 * gg * r1 * r1;
        let kdt = (hg * mat.p_modulus() * dt) * v1 * bb * (1.0 / 3.0);
        let mut e = z;
        for (al, q) in hourglass.forces.iter_mut().enumerate() {
            let ah = &a1[al + 4];
            let mut rate = [z; 3];
            for i in 0..3 {
                let la = l1[i][0] * ah[0] + l1[i][1] * ah[1] + l1[i][2] * ah[2];
                rate[i] = 0.125 * (u[al + 4][i] - la);
            }
            let old = *q;
            for c in 0..3 {
                q[c] += kdt * rate[c];
                e += 0.5 * (old[c] + q[c]) * rate[c] * dt;
            }
            for i in 0..3 {
                for j in 0..3 {
                    p[i][j] -= 0.125 * q[i] * ah[j];
                }
                fm[al + 4][i] = 0.125 * q[i];
            }
        }
        hourglass.energy += e;
    }
    for i in 0..3 {
        for j in 0..3 {
            p[i][j] = p[i][j] * r1;
        }
    }
    for (k, gk) in g1.iter().enumerate() {
        for i in 0..3 {
            fm[k + 1][i] += p[i][0] * gk[0] + p[i][1] * gk[1] + p[i][2] * gk[2];
        }
    }
    let force = nodes_from_modes(&fm);
    OnePointLaneOutput {
        force,
        volume: v1,
        dt_crit: critical_step(x1, v1, mat.wave_speed),
    }
}

/// Courant limit L_e / c (s) with L_e = volume / largest face area (the lane-wise
/// [`crate::fe::solver::timestep::characteristic_length`]; a face's area is half the cross product of its
/// diagonals), for nodal coordinates `x1` (m), element `volume` (m³) and `wave_speed` (m/s).
#[inline(always)]
pub fn critical_step<const W: usize>(
    x1: &[Vec3<W>; 8],
    volume: Lanes<W>,
    wave_speed: f64,
) -> Lanes<W> {
    let mut a2 = volume.splat_like(0.0);
    for f in HEX_FACES {
        let mut d1 = [a2; 3];
        let mut d2 = [a2; 3];
        for c in 0..3 {
            d1[c] = x1[f[2]][c] - x1[f[0]][c];
            d2[c] = x1[f[3]][c] - x1[f[1]][c];
        }
        let cr = cross(&d1, &d2);
        a2 = a2.max(dot(&cr, &cr));
    }
    let amax = 0.5 * a2.sqrt();
    volume / amax * (1.0 / wave_speed)
}

/// The one-point hexahedron as an element of the element loop.
#[derive(Debug, Clone, Copy)]
pub struct OnePointHex;

impl Element for OnePointHex {
    const HOURGLASS: bool = true;
    type Points<const W: usize> = OnePointLanes<W>;
    type Extra<const W: usize> = HourglassLanes<W>;
    type Output<const W: usize> = OnePointLaneOutput<W>;

    #[inline(always)]
    fn update<H: Hardening, const W: usize>(
        s: LaneStep<'_, H, W>,
        points: &mut OnePointLanes<W>,
        hourglass: &mut HourglassLanes<W>,
    ) -> OnePointLaneOutput<W> {
        update(s.x1, s.v, s.dt, s.mat, s.law, s.hg, points, hourglass)
    }

    /// One point: the element volume is its only Jacobian.
    #[inline(always)]
    fn result<const W: usize>(out: &OnePointLaneOutput<W>) -> LaneResult<'_, W> {
        LaneResult {
            force: &out.force,
            volume: out.volume,
            min_jacobian: out.volume,
            dt_crit: out.dt_crit,
        }
    }

    #[inline(always)]
    fn point_volumes<const W: usize>(out: &OnePointLaneOutput<W>) -> [Lanes<W>; 1] {
        [out.volume]
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::fe::elements::{
        batch::ElementStateMut,
        hex_one_point,
        shape::{gauss_volume_gradient, NODE_XI},
    };
    use crate::material::Material;

    /// A pseudo-random number in [-1, 1) (xorshift, fixed seed: reproducible).
    pub(crate) fn rnd(s: &mut u64) -> f64 {
        *s ^= *s << 13;
        *s ^= *s >> 7;
        *s ^= *s << 17;
        (*s >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }

    pub(crate) fn distorted(s: &mut u64, h: f64) -> [[f64; 3]; 8] {
        let rot = 0.7 * rnd(s);
        NODE_XI.map(|p| {
            let q = p.map(|c| 0.5 * h * (c + 1.0) + 0.15 * h * rnd(s));
            [
                q[0] * rot.cos() - q[1] * rot.sin(),
                q[0] * rot.sin() + q[1] * rot.cos(),
                q[2],
            ]
        })
    }

    /// Moves the four elements' nodes `x` (m) by `dt` (s) at their velocities `vs` (m/s).
    pub(crate) fn drift(x: &mut [Hex; 4], vs: &[Hex; 4], dt: f64) {
        for (xl, vl) in x.iter_mut().zip(vs) {
            for (xi, vi) in xl.iter_mut().zip(vl) {
                for c in 0..3 {
                    xi[c] += dt * vi[c];
                }
            }
        }
    }

    /// Four zero lanes on this CPU's four-lane path.
    pub(crate) fn zero_lanes() -> Lanes<4> {
        crate::fe::simd::LaneIsa::<4>::detect().unwrap().splat(0.0)
    }

    /// The copper of the default scene and its linear hardening law.
    pub(crate) fn copper() -> (J2Material, crate::fe::materials::Bilinear) {
        let mat = J2Material::new(&Material::preset("copper-fe").unwrap(), false);
        let crate::fe::materials::Law::Bilinear(law) = mat.law else {
            panic!("copper-fe hardens linearly")
        };
        (mat, law)
    }

    /// Nodal vectors of one hexahedron, gmsh order.
    pub(crate) type Hex = [[f64; 3]; 8];

    /// Four distorted elements of size `h` (m) and nodal velocities (m/s), reproducible from
    /// `seed`: lane `rigid` translates and spins without strain; lane l of the others
    /// stretches along x at g = `gain` (l + 1) (1/s), contracts along y at g/2 and along z at
    /// `squeeze` g, plus uniform noise of amplitude `noise` per component (m/s).
    pub(crate) fn four_elements(
        seed: u64,
        h: f64,
        rigid: usize,
        gain: f64,
        noise: [f64; 3],
        squeeze: f64,
    ) -> ([Hex; 4], [Hex; 4]) {
        let mut s = seed;
        let xs: [[[f64; 3]; 8]; 4] = std::array::from_fn(|_| distorted(&mut s, h));
        let mut jitter = |a: f64| if a != 0.0 { a * rnd(&mut s) } else { 0.0 };
        let vs = std::array::from_fn(|l| {
            std::array::from_fn(|i| {
                let x = xs[l][i];
                if l == rigid {
                    [1.0 - 300.0 * x[1], 2.0 + 300.0 * x[0], 0.5]
                } else {
                    let g = gain * (l as f64 + 1.0);
                    let vx = g * x[0] + jitter(noise[0]);
                    let vy = -0.5 * g * x[1] + jitter(noise[1]);
                    let vz = jitter(noise[2]) - squeeze * g * x[2];
                    [vx, vy, vz]
                }
            })
        });
        (xs, vs)
    }

    /// Lane `l` of `lanes` against the per-element `reference` forces (N) to 1e-11 of the
    /// largest force, floored at 1e-3 `face_yield_force` (a force of 0.1 % of yield on a face,
    /// so the round-off noise of a rigidly moving lane is compared on a physical scale).
    /// Returns the scale used.
    pub(crate) fn assert_forces_match(
        lanes: &[Vec3<4>; 8],
        l: usize,
        reference: &Hex,
        face_yield_force: f64,
    ) -> f64 {
        let scale = reference
            .iter()
            .flatten()
            .fold(1e-3 * face_yield_force, |m, c| m.max(c.abs()));
        for i in 0..8 {
            for c in 0..3 {
                let (a, b) = (lanes[i][c].0[l], reference[i][c]);
                assert!(
                    (a - b).abs() <= 1e-11 * scale,
                    "lane {l} node {i} force {a} vs {b} ({scale})"
                );
            }
        }
        scale
    }

    pub(crate) fn lanes<const W: usize>(e: &[[[f64; 3]; 8]; W]) -> [Vec3<W>; 8] {
        std::array::from_fn(|i| {
            std::array::from_fn(|c| {
                crate::fe::simd::LaneIsa::<W>::detect()
                    .unwrap()
                    .lanes(std::array::from_fn(|l| e[l][i][c]))
            })
        })
    }

    #[test]
    fn mode_space_volume_gradient_equals_gauss_average() {
        // ∂V/∂x_I = ∫ ∂N_I/∂x dV, integrated exactly by 2x2x2 Gauss for a trilinear hex.
        let mut s = 0x9e37_79b9_7f4a_7c15;
        for _ in 0..20 {
            let x = distorted(&mut s, 1e-3);
            let (vh, g) = volume_gradient(&modes(&lanes(&[x])));
            let mut f = [[vh.splat_like(0.0); 3]; 8];
            f[1..7].copy_from_slice(&g);
            let dv = nodes_from_modes(&f);
            let (vq, dq) = gauss_volume_gradient(&x);
            let v = vh.0[0] / 192.0;
            assert!((v - vq).abs() < 1e-12 * vq, "{v} vs {vq}");
            for i in 0..8 {
                for k in 0..3 {
                    let d = dv[i][k].0[0] / 192.0;
                    assert!(
                        (d - dq[i][k]).abs() < 1e-11 * 1e-6,
                        "node {i}: {d} vs {}",
                        dq[i][k]
                    );
                }
            }
        }
    }

    #[test]
    fn modes_round_trip_is_eight_times_identity() {
        let one = crate::fe::simd::LaneIsa::<1>::detect().unwrap();
        let mut s = 12345;
        let p: [Vec3<1>; 8] =
            std::array::from_fn(|_| std::array::from_fn(|_| one.lanes([rnd(&mut s)])));
        let back = nodes_from_modes(&modes(&p));
        for i in 0..8 {
            for c in 0..3 {
                assert!((back[i][c].0[0] - 8.0 * p[i][c].0[0]).abs() < 1e-14);
            }
        }
    }

    /// Four lanes of distorted, spinning, yielding elements against the per-element kernel,
    /// over several steps (state carried): equal to round-off.
    #[test]
    fn lanes_match_the_per_element_kernel() {
        let (mat, law) = copper();
        let h = 1e-3;
        // Lane 2 moves rigidly (no yield); the others stretch hard (yield within a few steps).
        let (xs, vs) = four_elements(0xdead_beef_1234_5678, h, 2, 60.0, [5.0, 0.0, 3.0], 0.0);
        let dt = 2e-8;
        let mut x = xs;
        let z = zero_lanes();
        let (mut st, mut hgs) = (OnePointLanes::filled(z), HourglassLanes::filled(z));
        let mut refs = [(
            [crate::fe::elements::batch::IntegrationPoint::default()],
            0.0,
            0.0,
            [[0.0; 3]; 4],
            0.0,
        ); 4];
        let mut yielded = [false; 4];
        for _ in 0..400 {
            drift(&mut x, &vs, dt);
            let out = update(
                &lanes(&x),
                &lanes(&vs),
                dt,
                &mat,
                &law,
                0.05,
                &mut st,
                &mut hgs,
            );
            for l in 0..4 {
                let r = &mut refs[l];
                let o = hex_one_point::update(
                    &x[l],
                    &vs[l],
                    dt,
                    &mat,
                    0.05,
                    ElementStateMut {
                        points: &mut r.0,
                        plastic_work: &mut r.1,
                        internal_energy: &mut r.2,
                        hourglass: &mut r.3,
                        hourglass_energy: &mut r.4,
                    },
                );
                let close = |a: f64, b: f64, scale: f64| (a - b).abs() <= 1e-11 * scale;
                let fscale = assert_forces_match(&out.force, l, &o.force, mat.yield0 * h * h);
                let sscale = r.0[0]
                    .stress
                    .iter()
                    .fold(1e-3 * mat.yield0, |m, c| m.max(c.abs()));
                let escale = 1e-6 * mat.yield0 * h * h * h;
                for k in 0..6 {
                    assert!(
                        close(st.stress[0][k].0[l], r.0[0].stress[k], sscale),
                        "lane {l} stress"
                    );
                }
                assert!(close(st.eps_p[0].0[l], r.0[0].eps_p, 1e-3));
                assert!(close(out.volume.0[l], o.volume, o.volume));
                assert!(close(out.dt_crit.0[l], o.dt_crit, o.dt_crit));
                assert!(close(st.plastic_work.0[l], r.1, r.2.abs().max(escale)));
                assert!(close(st.internal_energy.0[l], r.2, r.2.abs().max(escale)));
                let hq = r.3.iter().flatten().fold(fscale, |m, c| m.max(c.abs()));
                for al in 0..4 {
                    for c in 0..3 {
                        assert!(close(hgs.forces[al][c].0[l], r.3[al][c], hq), "lane {l} Q");
                    }
                }
                assert!(close(hgs.energy.0[l], r.4, r.4.abs().max(escale)));
                yielded[l] = r.0[0].eps_p > 0.0;
            }
        }
        assert_eq!(
            yielded,
            [true, true, false, true],
            "the test must exercise both paths"
        );
    }
}
