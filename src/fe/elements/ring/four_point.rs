//! The update of a ring quad with four (2x2) Gauss points, scalar and lane-wise, shared by
//! the fully integrated quad ([`super::full`]) and the B-bar quad ([`super::bbar`]). They
//! differ only in the volumetric strain rate a point takes: its own, or with `MEAN` the
//! element's mean dilatation (from the mean operator on the mid-step configuration), whose
//! forces then carry each point's pressure on the difference between the mean divergence
//! operator and its own, W_g (B_gᵀσ + p (B̄_vol − B_g,vol)).

use super::element::{LaneStep, Quad, RingElement, Step};
use super::lanes::{self, RingLaneOutput, RingLaneState};
use super::scalar::{advance_gauss_points, mid_step, output};
use super::shape::{add_stress_forces, gauss_points, mean_of, velocity_gradient, Gradient};
use super::state::{QuadOutput, QuadState};
use crate::fe::{materials::Hardening, tensor::Sym};

/// A ring quad with four Gauss points; `MEAN`: with the element's mean dilatation (the
/// B-bar quad, [`super::bbar::BBarQuad`]), else fully integrated ([`super::full::FullQuad`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FourPointQuad<const MEAN: bool>;

impl<const MEAN: bool> RingElement for FourPointQuad<MEAN> {
    const POINTS: usize = 4;

    #[inline]
    fn update(&self, s: Step<'_, Quad>, st: &mut QuadState) -> QuadOutput {
        update::<MEAN>(s, st)
    }

    #[inline(always)]
    fn update_lanes<H: Hardening, const W: usize>(
        &self,
        s: LaneStep<'_, H, W>,
        st: &mut RingLaneState<W>,
    ) -> RingLaneOutput<W> {
        update_lanes::<MEAN, H, W>(s, st)
    }
}

/// The scalar update of one quad; `MEAN`: the B-bar quad's mean dilatation.
#[inline]
fn update<const MEAN: bool>(s: Step<'_, Quad>, st: &mut QuadState) -> QuadOutput {
    let Step { x1, v, dt, mat } = s;
    let pm = gauss_points(&mid_step(x1, v, dt));
    let p1 = gauss_points(x1);
    let (g1, min_j) = mean_of(&p1);
    let vol_bar = MEAN.then(|| {
        let (gm, _) = mean_of(&pm);
        let lbar = velocity_gradient(v, &gm);
        lbar[0][0] + lbar[1][1] + lbar[2][2]
    });
    advance_gauss_points(st, &pm, v, vol_bar, dt, mat);
    let mut force = [[0.0; 2]; 4];
    for (k, p) in p1.iter().enumerate() {
        let s = &st.points[k].stress;
        add_stress_forces(&mut force, s, &p.grad);
        if MEAN {
            add_mean_dilatation_forces(&mut force, s, &p.grad, &g1);
        }
    }
    output(x1, force, g1.volume, min_j, mat)
}

/// Adds one Gauss point's B-bar correction: W_g p (B̄_vol − B_g,vol), with p the point's mean
/// stress and B_vol the divergence operator (∂N/∂r + N/r, ∂N/∂z).
#[inline]
fn add_mean_dilatation_forces(f: &mut [[f64; 2]; 4], s: &Sym, g: &Gradient, mean: &Gradient) {
    let p = (s[0] + s[1] + s[2]) / 3.0;
    for i in 0..4 {
        let dr = (mean.b[i][0] + mean.hoop[i]) - (g.b[i][0] + g.hoop[i]);
        let dz = mean.b[i][1] - g.b[i][1];
        f[i][0] += g.volume * p * dr;
        f[i][1] += g.volume * p * dz;
    }
}

/// The update of W quads, lane-wise (the scalar bits on every kernel path).
#[inline(always)]
fn update_lanes<const MEAN: bool, H: Hardening, const W: usize>(
    s: LaneStep<'_, H, W>,
    st: &mut RingLaneState<W>,
) -> RingLaneOutput<W> {
    let LaneStep { step, law } = s;
    let Step { x1, v, dt, mat } = step;
    let pm = lanes::gauss_points(&lanes::mid_step(x1, v, dt));
    let p1 = lanes::gauss_points(x1);
    let (g1, min_j) = lanes::mean_of(&p1);
    // No closure here: one compiled out of line would lose the kernel path's features.
    let vol_bar = if MEAN {
        let (gm, _) = lanes::mean_of(&pm);
        let lbar = lanes::velocity_gradient(v, &gm);
        Some(lbar[0] + lbar[3] + lbar[4])
    } else {
        None
    };
    lanes::advance_gauss_points(&pm, v, vol_bar, dt, mat, law, st);
    let mut force = [[x1[0][0].splat_like(0.0); 2]; 4];
    for (k, p) in p1.iter().enumerate() {
        let s = st.stress[k];
        lanes::add_stress_forces(&mut force, &s, &p.grad);
        if MEAN {
            let pressure = (s[0] + s[1] + s[2]) / 3.0;
            for i in 0..4 {
                let dr = (g1.b[i][0] + g1.hoop[i]) - (p.grad.b[i][0] + p.grad.hoop[i]);
                let dz = g1.b[i][1] - p.grad.b[i][1];
                force[i][0] += p.grad.volume * pressure * dr;
                force[i][1] += p.grad.volume * pressure * dz;
            }
        }
    }
    lanes::output(x1, force, g1.volume, min_j, mat)
}
