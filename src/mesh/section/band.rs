//! A band of finer surface rings at the contact edge of a meridian ball mesh.
//!
//! On the section every surface node is a whole ring, so a plastic contact grows ring by ring
//! and e follows where the last ring to land before maximum compression sits: a sawtooth over
//! the mesh whose half-width shrinks about as the ring spacing at the contact edge
//! (verification/contact-penalty.md, "Why the section's e scatters"). The band splits the ring
//! spacing there, and only there: the O-grid's layers are shells around the refined core, each
//! meeting the surface in one ring, so splitting the layer intervals whose surface rings fall
//! in the band into `split` shells each puts `split` times more rings across the band. An
//! even split runs the shells through the depth to the axis as thin quads; an odd one stops
//! them a share [`SURFACE_DEPTH`] of the rays below the surface, where s shells meet the
//! layer's two rings through a one-cell transition (s − 1 interior nodes, s quads on the fine
//! side, (s − 1)/2 on the coarse side; [`super::ball`]). Everything outside the band
//! keeps its nodes (a banded mesh contains every node of the mesh without the band).

use super::ball::LayerRing;
use crate::error::{Error, Result};

/// Most shells one layer may be split into.
pub const MAX_SPLIT: usize = 16;

/// Band around a predicted contact edge a: rest radii from `BAND_INNER_PER_EDGE` a to
/// `BAND_OUTER_PER_EDGE` a. The rings landing in the last 40 % of the loading of the default
/// scene lie between about 0.8 a and a; the outer margin covers an edge predicted short.
pub const BAND_INNER_PER_EDGE: f64 = 0.8;
/// Outer end of the band, in predicted contact edges (see [`BAND_INNER_PER_EDGE`]).
pub const BAND_OUTER_PER_EDGE: f64 = 1.15;

/// Share of a split layer's rays, from the surface, that an odd split's shells reach: a sixth
/// (3 of the 18 cells of a level-0 layer, 6 of level 1's). The rings at the surface are what
/// the sawtooth follows; shells run through the depth are thin quads down to the axis, among
/// the smallest of the mesh, which mass scaling must raise all the way down. Confined, the laws bench's five-fold points cost 0.54-0.75 of the four-fold
/// through-depth ones' CPU at the same answers (verification/contact-penalty.md, "A band confined to
/// the surface").
pub const SURFACE_DEPTH: f64 = 1.0 / 6.0;

/// Surface rings refined at the contact edge: every layer interval of the mesh whose surface
/// ring radii overlap [`inner`, `outer`] (rest radii, m) is split into `split` shells.
///
/// [`inner`]: EdgeBand::inner
/// [`outer`]: EdgeBand::outer
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EdgeBand {
    /// Inner rest radius of the band, m (> 0, outside the refined core).
    pub inner: f64,
    /// Outer rest radius of the band, m (> inner, < the ball radius).
    pub outer: f64,
    /// Shells per layer interval in the band, 1..=[`MAX_SPLIT`] (1: no refinement).
    pub split: usize,
    /// Share of each split layer's rays, from the surface, that its shells reach, in (0, 1]:
    /// 1 runs them through the depth to the axis; below 1 they end in a transition (an odd
    /// split only).
    pub depth: f64,
}

impl EdgeBand {
    /// The band [0.8 a, 1.15 a] around the predicted contact edge `edge` = a (m), each layer
    /// in it split into `split` shells: an odd split confined to the share [`SURFACE_DEPTH`]
    /// of the rays from the surface (ending in a transition), an even one through the depth.
    pub fn around(edge: f64, split: usize) -> EdgeBand {
        EdgeBand {
            inner: BAND_INNER_PER_EDGE * edge,
            outer: BAND_OUTER_PER_EDGE * edge,
            split,
            depth: depth_for(split),
        }
    }

    /// This band with its shells reaching the share `depth` of each layer's rays from the
    /// surface (see [`EdgeBand::depth`]).
    pub fn to_depth(self, depth: f64) -> EdgeBand {
        EdgeBand { depth, ..self }
    }

    /// The first ray (0 the axis, 2m the surface) that the band's shells reach on a layer of
    /// 2m cells: 0 through the depth, else 2m less the share `depth` of 2m (at least one).
    pub fn first_ray(&self, cells: usize) -> usize {
        if self.depth >= 1.0 {
            return 0;
        }
        let w = ((self.depth * cells as f64).round() as usize).clamp(1, cells);
        cells - w
    }

    /// Checks the band on a ball of radius `radius` (m).
    ///
    /// Errors: `band.inner`, `band.outer`, `band.split` or `band.depth` out of range, naming
    /// the range; an even split with a depth below 1 (naming `band.split`).
    pub fn check(&self, radius: f64) -> Result<()> {
        if !(self.inner.is_finite() && self.inner > 0.0) {
            return Err(Error::invalid("band.inner", self.inner, "> 0 m, finite"));
        }
        if !(self.outer.is_finite() && self.outer > self.inner && self.outer < radius) {
            return Err(Error::invalid(
                "band.outer",
                self.outer,
                format!(
                    "in ({:e}, {radius:e}) m (band.inner to the ball radius)",
                    self.inner
                ),
            ));
        }
        check_split(self.split)?;
        if !(self.depth > 0.0 && self.depth <= 1.0) {
            return Err(Error::invalid("band.depth", self.depth, "in (0, 1]"));
        }
        if self.depth < 1.0 && self.split.is_multiple_of(2) {
            return Err(Error::invalid(
                "band.split",
                self.split,
                "an odd split when band.depth < 1 (the transition needs it)",
            ));
        }
        Ok(())
    }
}

/// The depth [`EdgeBand::around`] gives a band of `split` shells: [`SURFACE_DEPTH`] for an
/// odd split, 1 (through the depth) for an even one.
pub fn depth_for(split: usize) -> f64 {
    if split % 2 == 1 {
        SURFACE_DEPTH
    } else {
        1.0
    }
}

/// Checks a band's split.
///
/// Errors: `split` outside 1..=[`MAX_SPLIT`] (naming `band.split`).
pub fn check_split(split: usize) -> Result<()> {
    if (1..=MAX_SPLIT).contains(&split) {
        Ok(())
    } else {
        Err(Error::invalid(
            "band.split",
            split,
            format!("an integer in [1, {MAX_SPLIT}]"),
        ))
    }
}

/// The rings of [`layer_fractions`], the band's own starting at ray `first_ray` (0: through
/// the depth; [`EdgeBand::first_ray`]).
///
/// Errors: those of [`layer_fractions`].
pub(super) fn layer_rings(
    layers: usize,
    band: Option<&EdgeBand>,
    surface_radius: impl Fn(f64) -> f64,
    first_ray: usize,
) -> Result<Vec<LayerRing>> {
    let fracs = layer_fractions(layers, band, surface_radius)?;
    let full = |f: f64| {
        let l = f * layers as f64;
        (l - l.round()).abs() < 1e-9
    };
    Ok(fracs
        .into_iter()
        .map(|frac| LayerRing {
            frac,
            from: if full(frac) { 0 } else { first_ray },
        })
        .collect())
}

/// Layer fractions l/L, l = 1..=`layers` (0 is the core's side, 1 the last layer), with
/// every interval whose surface ring radii overlap `band` split into `band.split` equal
/// parts. `surface_radius(f)` is the rest radius (m) of the surface ring at fraction f,
/// increasing in f; `surface_radius(0)` is the core's outermost surface ring.
///
/// Errors: a band that starts inside the refined core (`band.inner` ≤ `surface_radius(0)`),
/// where layers cannot split it; `band.inner` names the core's radius.
pub fn layer_fractions(
    layers: usize,
    band: Option<&EdgeBand>,
    surface_radius: impl Fn(f64) -> f64,
) -> Result<Vec<f64>> {
    let uniform = (1..=layers).map(|l| l as f64 / layers as f64);
    let Some(band) = band else {
        return Ok(uniform.collect());
    };
    let core = surface_radius(0.0);
    if band.inner <= core {
        return Err(Error::invalid(
            "band.inner",
            band.inner,
            format!(
                "> {core:e} m (the refined core's surface radius: size the mesh from a \
                 smaller contact radius)"
            ),
        ));
    }
    let mut fracs = Vec::with_capacity(layers * band.split);
    let mut prev = 0.0;
    for f in uniform {
        let (r0, r1) = (surface_radius(prev), surface_radius(f));
        if r0 < band.outer && r1 > band.inner {
            let s = band.split as f64;
            fracs.extend((1..band.split).map(|k| prev + (f - prev) * k as f64 / s));
        }
        fracs.push(f);
        prev = f;
    }
    Ok(fracs)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Surface rings at 1 + 9 f mm: the core's at 1 mm, the layers' at 2, 3, ..., 10 mm.
    fn radius(f: f64) -> f64 {
        1e-3 + 9e-3 * f
    }

    /// The band [`inner`, `outer`] (m) with `split` shells through the depth.
    fn through_depth(inner: f64, outer: f64, split: usize) -> EdgeBand {
        EdgeBand {
            inner,
            outer,
            split,
            depth: 1.0,
        }
    }

    #[test]
    fn only_the_intervals_in_the_band_are_split() {
        // The spacings below are those between the layers' rings.
        let band = through_depth(3.5e-3, 4.5e-3, 4);
        let f = layer_fractions(9, Some(&band), radius).unwrap();
        // The intervals [3, 4] and [4, 5] mm overlap the band: 3 extra fractions each.
        assert_eq!(f.len(), 9 + 6);
        let rings: Vec<f64> = f.iter().map(|&x| radius(x) * 1e3).collect();
        let fine: Vec<f64> = rings.windows(2).map(|w| w[1] - w[0]).collect();
        assert!(fine.iter().filter(|&&d| (d - 0.25).abs() < 1e-9).count() == 8);
        assert!(fine.iter().filter(|&&d| (d - 1.0).abs() < 1e-9).count() == 6);
        assert!(f.windows(2).all(|w| w[1] > w[0]) && *f.last().unwrap() == 1.0);
        // Without a band, or with split 1: the uniform fractions.
        let plain = layer_fractions(9, None, radius).unwrap();
        let one = EdgeBand { split: 1, ..band };
        assert_eq!(layer_fractions(9, Some(&one), radius).unwrap(), plain);
        assert_eq!(plain.len(), 9);
    }

    #[test]
    fn a_band_inside_the_core_or_out_of_range_is_refused() {
        let inside = through_depth(0.5e-3, 2e-3, 2);
        let e = layer_fractions(9, Some(&inside), radius).unwrap_err();
        assert!(e.to_string().contains("band.inner"), "{e}");
        let r = 10e-3;
        let bad = |b: EdgeBand| b.check(r).unwrap_err().to_string();
        let ok = EdgeBand::around(5e-3, 4);
        assert!(ok.check(r).is_ok());
        assert!(bad(EdgeBand { inner: -1.0, ..ok }).contains("band.inner"));
        assert!(bad(EdgeBand { outer: 2e-3, ..ok }).contains("band.outer"));
        assert!(bad(EdgeBand { outer: r, ..ok }).contains("band.outer"));
        assert!(bad(EdgeBand { split: 0, ..ok }).contains("band.split"));
        assert!(bad(EdgeBand { split: 17, ..ok }).contains("band.split"));
    }
}
