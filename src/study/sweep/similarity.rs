//! Dimensional similarity of two scenes: when one is the other with every length and time
//! scaled by k and every speed kept, their FE runs are the same run in other units.
//!
//! The FE model has no length or time scale of its own when the material is rate-independent
//! and there is no body force: the equations of motion, the constitutive law (stresses in Pa,
//! strains dimensionless) and the contact (penalty stiffness FKN · E · A / h, a pressure over a
//! length) are unchanged under x → k x, t → k t at fixed speeds, and so are the meshes sized
//! per diameter, the stable step (∝ h / c) and the stop rule (times ∝ the contact duration).
//! The run of the scaled scene then gives e, the velocities and η unchanged, δ_max, the
//! contact duration and δ(t) scaled by k, and spins scaled by 1/k (measured: the law bench's
//! similarity check, 3.2e-10 relative; docs/contact-laws.md). A sweep over diameters with
//! per-diameter meshes derives its similar cases from one run ([`crate::study::sweep`]).

use crate::fe::materials::rate_independent;
use crate::scene::{BallScene, MeshSettings, OutputSettings, Scene, SolverSettings};
use crate::study::records::case::FeCase;
use serde_json::Value;

/// Relative tolerance of the comparison of two scaled scenes' numbers (per-diameter sizes
/// scaled back differ from the other scene's in the last bits).
const SAME: f64 = 1e-12;

/// Ball `b` with its lengths scaled by `k` (its spin by 1/k); None for a mesh read from a
/// file (not scalable here) or a rate-dependent material.
fn scaled_ball(b: &BallScene, k: f64) -> Option<BallScene> {
    let BallScene {
        material,
        material_name,
        diameter,
        velocity,
        angular_velocity,
        position,
        mesh,
    } = b.clone();
    let mesh = match mesh {
        MeshSettings::Builtin { size, pole_size } => MeshSettings::Builtin {
            size: k * size,
            pole_size: k * pole_size,
        },
        MeshSettings::File { .. } => return None,
    };
    rate_independent(&material).then(|| BallScene {
        material,
        material_name,
        diameter: k * diameter,
        velocity,
        angular_velocity: angular_velocity.map(|w| w / k),
        position: position.map(|p| p.map(|x| k * x)),
        mesh,
    })
}

/// `scene` with every length and time scaled by `k` (> 0) and every speed kept; None when it
/// cannot be scaled (a mesh file, a rate-dependent material, an elastic wall of another
/// material law). Each field is named, so a new scene field must be placed here.
pub fn scaled(scene: &Scene, k: f64) -> Option<Scene> {
    let Scene {
        ball1,
        ball2,
        wall,
        contact,
        solver,
        output,
        reduction,
        laws,
    } = scene.clone();
    let SolverSettings {
        element,
        section_element,
        time_step_factor,
        end_time,
        hold_time,
        max_steps,
        subcycling,
        mass_scaling,
    } = solver;
    let OutputSettings {
        history_interval,
        vtu_snapshots,
    } = output;
    let wall = match wall {
        Some(mut w) => {
            if w.material.is_some_and(|m| !rate_independent(&m)) {
                return None;
            }
            w.position = w.position.map(|x| k * x);
            w.size = w.size.map(|s| s.map(|x| k * x));
            Some(w)
        }
        None => None,
    };
    Some(Scene {
        ball1: scaled_ball(&ball1, k)?,
        ball2: scaled_ball(&ball2, k)?,
        wall,
        contact,
        solver: SolverSettings {
            element,
            section_element,
            time_step_factor,
            end_time: end_time.map(|t| k * t),
            hold_time: hold_time.map(|t| k * t),
            max_steps,
            subcycling,
            // A fraction of the model's mass: the same at every scale.
            mass_scaling,
        },
        output: OutputSettings {
            history_interval: history_interval.map(|t| k * t),
            vtu_snapshots,
        },
        reduction,
        laws,
    })
}

/// True when two JSON trees are equal, numbers within [`SAME`] relative.
fn same(a: &Value, b: &Value) -> bool {
    match (a, b) {
        (Value::Number(x), Value::Number(y)) => match (x.as_f64(), y.as_f64()) {
            (Some(x), Some(y)) => (x - y).abs() <= SAME * x.abs().max(y.abs()),
            _ => x == y,
        },
        (Value::Array(x), Value::Array(y)) => {
            x.len() == y.len() && x.iter().zip(y).all(|(p, q)| same(p, q))
        }
        (Value::Object(x), Value::Object(y)) => {
            x.len() == y.len()
                && x.iter()
                    .all(|(key, p)| y.get(key).is_some_and(|q| same(p, q)))
        }
        _ => a == b,
    }
}

/// The factor k (m/m) with `b` = `a` scaled by k ([`scaled`]), or None when the two scenes
/// are not similar (or either cannot be scaled).
pub fn similarity_factor(a: &Scene, b: &Scene) -> Option<f64> {
    let k = b.ball1.diameter / a.ball1.diameter;
    if !(k.is_finite() && k > 0.0) {
        return None;
    }
    let a_scaled = serde_json::to_value(scaled(a, k)?).ok()?;
    let b_value = serde_json::to_value(scaled(b, 1.0)?).ok()?;
    same(&a_scaled, &b_value).then_some(k)
}

/// The FE run of a scene similar to the run `fe` with factor `k`: δ_max, the contact duration
/// and δ(t) scaled by k, spins by 1/k, the rest (e, velocities, η, energy error, element
/// count, error bar) as they are; the wall time and the element updates 0 (nothing ran).
pub fn scaled_fe_case(fe: &FeCase, k: f64) -> FeCase {
    let mut s = fe.summary.clone();
    s.outcome.delta_max *= k;
    s.outcome.contact_duration *= k;
    s.outcome.w1_after = s.outcome.w1_after.map(|w| w / k);
    s.outcome.w2_after = s.outcome.w2_after.map(|w| w / k);
    s.wall_time_s = 0.0;
    s.element_cycles = 0;
    FeCase {
        summary: s,
        delta_history: fe
            .delta_history
            .iter()
            .map(|p| [k * p[0], k * p[1]])
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Override, DEFAULT_SCENE};
    use std::path::Path;

    fn scene(sets: &[&str]) -> Scene {
        let sets: Vec<Override> = sets.iter().map(|s| Override::parse(s).unwrap()).collect();
        Scene::from_toml(DEFAULT_SCENE, Path::new("."), &sets).unwrap()
    }

    fn at(d: f64, extra: &[&str]) -> Scene {
        let mesh = format!("{{size={},pole_size={}}}", d / 6.0, d / 200.0);
        let mut sets = vec![
            format!("ball1.diameter={d}"),
            format!("ball2.diameter={d}"),
            format!("ball1.mesh={mesh}"),
            format!("ball2.mesh={mesh}"),
        ];
        sets.extend(extra.iter().map(|s| s.to_string()));
        let refs: Vec<&str> = sets.iter().map(String::as_str).collect();
        scene(&refs)
    }

    #[test]
    fn scenes_with_per_diameter_meshes_are_similar() {
        let k = similarity_factor(&at(0.005, &[]), &at(0.03, &[])).unwrap();
        assert!((k - 6.0).abs() < 1e-12, "{k}");
        assert_eq!(similarity_factor(&at(0.02, &[]), &at(0.02, &[])), Some(1.0));
        // A spin scales as 1/D.
        let spin = |d: f64, w: f64| at(d, &[&format!("ball1.angular_velocity=[0,0,{w}]")]);
        assert!(similarity_factor(&spin(0.01, 100.0), &spin(0.02, 50.0)).is_some());
        assert!(similarity_factor(&spin(0.01, 100.0), &spin(0.02, 100.0)).is_none());
    }

    #[test]
    fn what_breaks_similarity_is_refused() {
        let (a, b) = (0.01, 0.02);
        // Another speed, an absolute end time, an absolute mesh, unequal materials.
        let cases: [(Scene, Scene); 4] = [
            (at(a, &[]), at(b, &["ball1.velocity=[1.5,0,0]"])),
            (
                at(a, &["solver.end_time=2e-4"]),
                at(b, &["solver.end_time=2e-4"]),
            ),
            (
                scene(&["ball1.diameter=0.01", "ball2.diameter=0.01"]),
                at(
                    b,
                    &[
                        "ball1.mesh={size=0.003,pole_size=1e-4}",
                        "ball2.mesh={size=0.003,pole_size=1e-4}",
                    ],
                ),
            ),
            (at(a, &[]), at(b, &["ball2.material=steel"])),
        ];
        for (i, (x, y)) in cases.iter().enumerate() {
            assert_eq!(similarity_factor(x, y), None, "case {i}");
        }
        // The default mesh follows the diameter (bulk D/6, pole from the contact): similar.
        let d = |d: f64| {
            scene(&[
                &format!("ball1.diameter={d}"),
                &format!("ball2.diameter={d}"),
            ])
        };
        assert!(similarity_factor(&d(a), &d(b)).is_some());
        // The same end time in units of the size is similar.
        let t = |d: f64| format!("solver.end_time={}", 0.01 * d);
        assert!(similarity_factor(&at(a, &[&t(a)]), &at(b, &[&t(b)])).is_some());
        // A strain-rate term gives the material a time scale.
        let jc = "ball1.material.hardening={law=\"johnson-cook\",A=9e7,B=2.9e8,n=0.31,C=0.025,rate0=1.0}";
        let jc2 = jc.replace("ball1", "ball2");
        assert_eq!(
            similarity_factor(&at(a, &[jc, &jc2]), &at(b, &[jc, &jc2])),
            None
        );
        let rate_free = jc.replace("C=0.025", "C=0.0");
        let rate_free2 = rate_free.replace("ball1", "ball2");
        assert!(similarity_factor(
            &at(a, &[&rate_free, &rate_free2]),
            &at(b, &[&rate_free, &rate_free2])
        )
        .is_some());
    }
}
