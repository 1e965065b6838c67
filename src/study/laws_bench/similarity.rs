//! Similarity of the head-on points in the diameter. With a rate-independent metal (a
//! bilinear preset) and the mesh family sized from the Hertz contact radius (∝ D at fixed
//! v), the section model of a ball k times larger is the same discrete problem with lengths
//! and times k times larger and forces k² times: e is unchanged, δ_max and t_c scale as D,
//! the peak force as D². The bench therefore runs such a metal at the largest diameter at
//! every speed and at each smaller diameter only at the check speed (the matrix speed
//! nearest [`CHECK_SPEED`]), and scales the other points ([`FePoint::scaled`]); the report
//! prints the check's differences ([`check_differences`]). A rate-dependent metal
//! (Johnson-Cook) is run at every diameter.

use super::fe::FePoint;
use super::matrix::HeadOnPoint;
use crate::material::Material;

/// The relative speed (m/s) near which the smaller diameters of a rate-independent metal
/// are run as the similarity check.
pub const CHECK_SPEED: f64 = 1.0;

/// How the FE answer of a head-on point is obtained.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Source {
    /// Run.
    Run,
    /// Scaled from the run point of this index (same metal and speed, largest diameter).
    Scaled {
        /// Index of the run point in the point list.
        from: usize,
    },
}

/// Whether `material`'s response is free of a material time (bilinear hardening).
pub fn rate_independent(material: &Material) -> bool {
    material.hardening.is_none()
}

/// The speed of `speeds` (m/s) nearest [`CHECK_SPEED`] in ratio (NaN when empty).
pub fn check_speed(speeds: &[f64]) -> f64 {
    speeds
        .iter()
        .copied()
        .min_by(|a, b| {
            (a / CHECK_SPEED)
                .ln()
                .abs()
                .total_cmp(&(b / CHECK_SPEED).ln().abs())
        })
        .unwrap_or(f64::NAN)
}

/// The source of every point of `points`: a rate-independent metal's points below its
/// largest diameter are scaled from the largest diameter's point at the same speed, except
/// at the check speed; every other point is run.
pub fn sources(points: &[HeadOnPoint]) -> Vec<Source> {
    points
        .iter()
        .map(|p| {
            if !rate_independent(&p.material) {
                return Source::Run;
            }
            let same_metal: Vec<&HeadOnPoint> =
                points.iter().filter(|q| q.metal == p.metal).collect();
            let largest = same_metal
                .iter()
                .map(|q| q.diameter)
                .fold(f64::NAN, f64::max);
            let speeds: Vec<f64> = same_metal.iter().map(|q| q.speed).collect();
            if p.diameter == largest || p.speed == check_speed(&speeds) {
                return Source::Run;
            }
            points
                .iter()
                .position(|q| q.metal == p.metal && q.diameter == largest && q.speed == p.speed)
                .map_or(Source::Run, |from| Source::Scaled { from })
        })
        .collect()
}

/// The relative differences of a run point `small` (diameter `d_small`, m) from the point
/// `large` (diameter `d_large`, m) scaled to it: [e, δ_max, t_c, peak force], each
/// run/scaled − 1.
pub fn check_differences(small: &FePoint, d_small: f64, large: &FePoint, d_large: f64) -> [f64; 4] {
    let s = large.scaled(d_small / d_large, d_large);
    [
        small.e.finest / s.e.finest - 1.0,
        small.delta_max.finest / s.delta_max.finest - 1.0,
        small.contact_duration.finest / s.contact_duration.finest - 1.0,
        small.peak_force.finest / s.peak_force.finest - 1.0,
    ]
}
