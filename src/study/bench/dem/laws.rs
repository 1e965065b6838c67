//! The DEM normal laws on the suite's normal impacts: every built-in law at the elastic
//! setting (the tests' row), and test 3's question, the e a damped law gives against the e
//! it was set to.

use crate::analytic::laws::Registry;
use crate::error::Result;
use crate::scene::ComparedLaw;
use crate::scene::{Scene, Touch};
use crate::study::run::law_compare::{compare_laws, LawOutcome};

/// The coefficients of restitution test 3 sets a damped law to, -.
pub const TEST3_RESTITUTIONS: [f64; 5] = [0.2, 0.4, 0.6, 0.8, 1.0];

/// Every built-in normal law (Coulomb tangentially) on `scene`'s impact at `touch`, each
/// damped law set to restitution `e` (-) and Kuwabara-Kono's constant A to `a` (s); the
/// other parameters at their defaults for the pair. Errors: a value outside a law's range,
/// or an integration that fails (named by the law).
pub fn normal_laws(scene: &Scene, touch: &Touch, e: f64, a: f64) -> Result<Vec<LawOutcome>> {
    normal_laws_where(scene, touch, e, a, |_| true)
}

/// [`normal_laws`] for the laws `keep` accepts by their parameter keys.
fn normal_laws_where(
    scene: &Scene,
    touch: &Touch,
    e: f64,
    a: f64,
    keep: impl Fn(&[&str]) -> bool,
) -> Result<Vec<LawOutcome>> {
    let mut s = scene.clone();
    s.laws.laws = Registry::builtin()
        .normal
        .iter()
        .filter(|spec| keep(&spec.params.iter().map(|p| p.key).collect::<Vec<_>>()))
        .map(|spec| ComparedLaw {
            name: spec.name.into(),
            params: spec
                .params
                .iter()
                .filter_map(|p| match p.key {
                    "e" => Some(("e".to_string(), e)),
                    "A" => Some(("A".to_string(), a)),
                    _ => None,
                })
                .collect(),
        })
        .collect();
    compare_laws(&s, touch)
}

/// Test 3: each law with a restitution parameter, set to each of [`TEST3_RESTITUTIONS`],
/// and the e its integration gives: (law, e set, e out).
pub fn damping(scene: &Scene, touch: &Touch) -> Result<Vec<(String, f64, f64)>> {
    let mut out = Vec::new();
    for e in TEST3_RESTITUTIONS {
        for l in normal_laws_where(scene, touch, e, 0.0, |keys| keys.contains(&"e"))? {
            out.push((l.law, e, l.e));
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::study::bench::dem::cases::cases;

    fn touch(name: &str) -> (Scene, Touch) {
        let c = cases(&[name.into()], crate::study::bench::dem::OBLIQUE_TOLERANCE)
            .unwrap()
            .remove(0);
        (c.scene, c.touch.expect("the balls meet"))
    }

    #[test]
    fn at_the_elastic_setting_every_law_returns_the_energy() {
        // Test 2, aluminium at 0.2 m/s: far below yield, so every law at e = 1 and A = 0
        // is elastic, and the Hertzian ones share Hertz's δ_max.
        let (s, t) = touch("test2-aluminium");
        let laws = normal_laws(&s, &t, 1.0, 0.0).unwrap();
        assert_eq!(laws.len(), Registry::builtin().normal.len());
        let hertz = laws.iter().find(|l| l.law == "hertz").unwrap();
        for l in &laws {
            assert!((l.e - 1.0).abs() < 1e-3, "{l:?}");
        }
        for name in ["hertz-damped", "thornton", "kuwabara-kono"] {
            let l = laws.iter().find(|l| l.law == name).unwrap();
            assert!((l.delta_max / hertz.delta_max - 1.0).abs() < 1e-3, "{l:?}");
        }
    }

    #[test]
    fn test3_asks_each_damped_law_for_the_restitution_it_was_set_to() {
        let (s, t) = touch("test3-alumina");
        let d = damping(&s, &t).unwrap();
        assert!(!d.is_empty());
        // The linear spring-dashpot's damping is derived exactly from e.
        for (law, set, out) in &d {
            if law == "linear-dashpot" {
                assert!((out - set).abs() < 1e-3, "{law}: {set} -> {out}");
            }
        }
        assert_eq!(d.len() % TEST3_RESTITUTIONS.len(), 0);
    }
}
