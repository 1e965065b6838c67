//! The pole element size from the physics: the predicted contact radius of the impact.
//!
//! The contact radius of an elastic impact grows with speed (Hertz: a = √(R* δ_max), δ_max ∝
//! v^{4/5}, so a ∝ v^{2/5}); a pole size fixed as a fraction of the diameter resolves slow
//! impacts with too few elements across the contact. The rule: [`POLE_ELEMENTS_PER_RADIUS`]
//! elements across the Hertz contact radius of the pair at its approach speed, never coarser
//! than [`super::DEFAULT_POLE_SIZE_PER_D`] of the diameter (so faster impacts, and the default
//! scene, keep that mesh) and never finer than [`MIN_POLE_SIZE_PER_D`] (the smallest pole a
//! scene may set).

use super::BallScene;
use crate::analytic::{Body, HertzPair};

/// Elements across the predicted Hertz contact radius at the pole. The default scene (copper,
/// D = 20 mm, 2 m/s relative) has a = D/42.5, 4.7 elements of D/200 across: with 4.5 the rule
/// refines below about 1.8 m/s relative speed for that pair and leaves the default mesh as is.
pub const POLE_ELEMENTS_PER_RADIUS: f64 = 4.5;

/// The finest pole size the rule gives, as a fraction of the diameter (the scene's lower bound
/// on `pole_size`).
pub const MIN_POLE_SIZE_PER_D: f64 = 1.0 / 2000.0;

/// The Hertz contact radius a = √(R* δ_max) (m) of an elastic impact of `b1` and `b2` at
/// relative normal approach speed `speed` (m/s, > 0). Materials must be valid (positive E, ρ).
pub fn hertz_contact_radius(b1: &BallScene, b2: &BallScene, speed: f64) -> f64 {
    let body = |b: &BallScene| Body::Ball {
        material: b.material,
        diameter: b.diameter,
    };
    let pair = HertzPair::between(&body(b1), &body(b2));
    pair.contact_radius(pair.max_approach(speed))
}

/// The pole element size (m) of `ball` meeting `other` at relative normal approach speed
/// `speed` (m/s): a/[`POLE_ELEMENTS_PER_RADIUS`], clamped to [D/2000, D/200] of `ball`'s
/// diameter D. A speed that is not positive and finite gives D/200.
pub fn physics_pole_size(ball: &BallScene, other: &BallScene, speed: f64) -> f64 {
    let d = ball.diameter;
    let coarsest = d * super::DEFAULT_POLE_SIZE_PER_D;
    if !(speed.is_finite() && speed > 0.0) {
        return coarsest;
    }
    let rule = hertz_contact_radius(ball, other, speed) / POLE_ELEMENTS_PER_RADIUS;
    if !rule.is_finite() {
        return coarsest;
    }
    rule.clamp(d * MIN_POLE_SIZE_PER_D, coarsest)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{MeshSettings, Override, Scene, DEFAULT_SCENE};
    use std::path::Path;

    fn scene(v: f64, extra: &[&str]) -> Scene {
        let mut sets = vec![
            format!("ball1.velocity=[{v},0,0]"),
            format!("ball2.velocity=[{},0,0]", -v),
        ];
        sets.extend(extra.iter().map(|s| s.to_string()));
        let sets: Vec<Override> = sets.iter().map(|s| Override::parse(s).unwrap()).collect();
        Scene::from_toml(DEFAULT_SCENE, Path::new("."), &sets).unwrap()
    }

    fn pole(s: &Scene) -> f64 {
        match s.ball1.mesh {
            MeshSettings::Builtin { pole_size, .. } => pole_size,
            MeshSettings::File { .. } => unreachable!(),
        }
    }

    #[test]
    fn the_default_scene_keeps_its_pole_of_d_over_200() {
        let d = 0.02;
        assert_eq!(
            pole(&Scene::default()),
            d * crate::scene::DEFAULT_POLE_SIZE_PER_D
        );
        assert_eq!(pole(&scene(5.0, &[])), d / 200.0);
    }

    #[test]
    fn slow_impacts_get_their_contact_radius_over_4_5() {
        let s = scene(0.1, &[]);
        let a = hertz_contact_radius(&s.ball1, &s.ball2, 0.2);
        // Hertz for copper-fe, D = 20 mm, 0.2 m/s: a = 0.18728 mm (closed form by hand).
        assert!((a - 1.8728e-4).abs() < 1e-8, "a = {a}");
        assert_eq!(pole(&s), a / POLE_ELEMENTS_PER_RADIUS);
        assert_eq!(s.ball2.mesh, s.ball1.mesh);
        // a ∝ v^{2/5}: ten times slower, 10^{-0.4} of the pole.
        let ratio = pole(&scene(0.01, &[])) / pole(&s);
        assert!((ratio - 10f64.powf(-0.4)).abs() < 1e-12, "{ratio}");
        // Never below D/2000.
        assert_eq!(pole(&scene(1e-4, &[])), 0.02 / 2000.0);
    }

    #[test]
    fn a_pole_size_the_scene_sets_is_kept() {
        let s = scene(0.1, &["ball1.mesh.pole_size=1e-4"]);
        assert_eq!(pole(&s), 1e-4);
        assert!(matches!(
            s.ball2.mesh,
            MeshSettings::Builtin { pole_size, .. } if pole_size < 1e-4
        ));
        // A coarse bulk still caps the pole.
        let s = scene(0.1, &["ball1.mesh.size=2e-5"]);
        assert_eq!(pole(&s), 2e-5);
    }
}
