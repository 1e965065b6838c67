//! Scene settings the chosen model does not use: each one set away from its default gets one
//! note (`warnings` check `ignored_setting` in results.json, `note: ...` on stderr), so that
//! no setting is dropped in silence.
//!
//! [`SETTINGS`] names every key of the scene reference ([`crate::scene::reference_keys`]) with
//! the rule that says which models ignore it; a test keeps the two lists equal, so a new scene
//! key cannot be added without deciding its rule here.

use super::simulate::Reduction;
use crate::material::Material;
use crate::scene::{BallScene, ContactSettings, PlaneEnforcement, Scene, Switch, WallKind};
use crate::study::records::warnings::{Check, Warning};

/// Which models use a setting.
#[derive(Debug, Clone, Copy)]
pub enum Rule {
    /// Every model uses it (or refuses the scene when it cannot).
    Used,
    /// Some models ignore it: the note, when `scene` sets it away from its default and the
    /// model `Reduction` ignores it.
    Ignored(fn(&Scene, Reduction) -> Option<String>),
}

/// One key of the scene reference and its rule.
#[derive(Debug, Clone, Copy)]
pub struct Setting {
    /// Dotted path (`ballN` for either ball).
    pub key: &'static str,
    /// Which models use it.
    pub rule: Rule,
}

const fn used(key: &'static str) -> Setting {
    Setting {
        key,
        rule: Rule::Used,
    }
}

/// Every scene key with its rule, in the order of the scene reference.
pub const SETTINGS: &[Setting] = &[
    used("ballN.material.preset"),
    used("ballN.material.hardening"),
    used("ballN.material.E"),
    used("ballN.material.nu"),
    used("ballN.material.rho"),
    used("ballN.material.yield"),
    used("ballN.material.tangent"),
    Setting {
        key: "ballN.material.mu",
        rule: Rule::Ignored(ball_friction_note),
    },
    Setting {
        key: "ballN.material.mu_static",
        rule: Rule::Ignored(ball_friction_note),
    },
    used("ballN.diameter"),
    used("ballN.velocity"),
    used("ballN.angular_velocity"),
    used("ballN.position"),
    used("ballN.mesh.size"),
    used("ballN.mesh.pole_size"),
    used("ballN.mesh.file"),
    Setting {
        key: "contact.penalty_factor",
        rule: Rule::Ignored(penalty_note),
    },
    Setting {
        key: "contact.friction",
        rule: Rule::Ignored(friction_note),
    },
    Setting {
        key: "contact.plane",
        rule: Rule::Ignored(plane_note),
    },
    used("solver.element"),
    Setting {
        key: "solver.section_element",
        rule: Rule::Ignored(section_element_note),
    },
    used("solver.time_step_factor"),
    used("solver.end_time"),
    Setting {
        key: "solver.hold_time",
        rule: Rule::Ignored(hold_time_note),
    },
    used("solver.max_steps"),
    used("solver.subcycling"),
    used("solver.mass_scaling"),
    used("output.history_interval"),
    used("output.vtu_snapshots"),
    used("reduction.symmetry"),
    used("reduction.start_at_touch"),
    used("reduction.stop_at_separation"),
    used("reduction.skip_work"),
    used("wall.kind"),
    used("wall.position"),
    used("wall.normal"),
    used("wall.material"),
    used("wall.size"),
    used("laws.compare"),
    used("laws.tangential"),
    used("laws.params"),
];

/// The notes of every setting of `scene` that the model `model` ignores.
pub fn ignored_settings(scene: &Scene, model: Reduction) -> Vec<Warning> {
    SETTINGS
        .iter()
        .filter_map(|s| match s.rule {
            Rule::Used => None,
            Rule::Ignored(note) => note(scene, model),
        })
        .map(|message| Warning {
            check: Check::IgnoredSetting,
            message,
        })
        .collect()
}

/// The section's name in the notes.
const SECTION: &str = "the axisymmetric model";

/// True when the section meets a rigid plane (the mirror plane of identical balls, or a
/// rigid wall); two meshed bodies meet by node-to-segment contact instead.
fn section_has_plane(scene: &Scene) -> bool {
    match scene.wall {
        Some(w) => w.kind == WallKind::Rigid,
        None => scene.identical_balls(),
    }
}

/// What the section's rigid plane is, in words.
fn plane_name(scene: &Scene) -> &'static str {
    if scene.wall.is_some() {
        "rigid wall"
    } else {
        "symmetry plane"
    }
}

/// `contact.penalty_factor` on the section's kinematic plane, which has no penalty.
fn penalty_note(scene: &Scene, model: Reduction) -> Option<String> {
    let c = scene.contact;
    let ignored = model == Reduction::Axisymmetric
        && c.plane == PlaneEnforcement::Kinematic
        && section_has_plane(scene);
    (ignored && c.penalty_factor != ContactSettings::default().penalty_factor).then(|| {
        format!(
            "contact.penalty_factor = {} has no effect on {SECTION}'s kinematic {}; use contact.plane = \"penalty\" or reduction.symmetry = \"auto-3d\" to study it",
            c.penalty_factor,
            plane_name(scene)
        )
    })
}

/// Why `model` has no friction at the contact (None where it has).
fn frictionless(model: Reduction) -> Option<&'static str> {
    match model {
        Reduction::Axisymmetric => Some("the axisymmetric model's contact is frictionless"),
        Reduction::Quarter => Some("the quarter model's plane is frictionless"),
        Reduction::Half | Reduction::Full => None,
    }
}

/// `contact.friction` on a model without friction.
fn friction_note(scene: &Scene, model: Reduction) -> Option<String> {
    let why = frictionless(model)?;
    (scene.contact.friction != ContactSettings::default().friction).then(|| {
        format!(
            "contact.friction has no effect: {why}; use reduction.symmetry = \"half\" or \"off\" to include friction"
        )
    })
}

/// A ball's own friction coefficients where the model has no friction or the scene's
/// `contact.friction` replaces them.
fn ball_friction_note(scene: &Scene, model: Reduction) -> Option<String> {
    let why = match frictionless(model) {
        Some(why) => why,
        None if scene.contact.friction != ContactSettings::default().friction => {
            "contact.friction replaces the balls' coefficients"
        }
        None => return None,
    };
    // Set away from the preset's coefficients (a custom material's default is 0).
    let changed = |b: &BallScene| {
        let (mu, mu_static) = Material::preset(&b.material_name)
            .map_or((0.0, 0.0), |p: Material| (p.mu, p.mu_static));
        mu != b.material.mu || mu_static != b.material.mu_static
    };
    let mut balls = vec![];
    if changed(&scene.ball1) {
        balls.push("ball1");
    }
    if scene.wall.is_none() && changed(&scene.ball2) {
        balls.push("ball2");
    }
    (!balls.is_empty()).then(|| {
        format!(
            "{}.material.mu and mu_static have no effect on the FE model: {why}",
            balls.join(" and ")
        )
    })
}

/// `contact.plane` where there is no rigid plane to enforce.
fn plane_note(scene: &Scene, model: Reduction) -> Option<String> {
    let plane = scene.contact.plane;
    if plane == ContactSettings::default().plane {
        return None;
    }
    let why = match model {
        Reduction::Axisymmetric if section_has_plane(scene) => return None,
        Reduction::Axisymmetric => {
            "the two meshed bodies of the axisymmetric model meet by node-to-segment contact, without a rigid plane"
        }
        _ => "only the axisymmetric model has a kinematic plane; the 3D models' contact is always the penalty",
    };
    Some(format!("contact.plane has no effect: {why}"))
}

/// `solver.section_element` on the 3D models (their element is `solver.element`).
fn section_element_note(scene: &Scene, model: Reduction) -> Option<String> {
    let f = scene.solver.section_element?;
    (model != Reduction::Axisymmetric).then(|| {
        format!(
            "solver.section_element = \"{}\" has no effect: the {} model's element is solver.element",
            f.name(),
            model.name()
        )
    })
}

/// `solver.hold_time` when the run stops at a fixed end time instead of by separation.
fn hold_time_note(scene: &Scene, _model: Reduction) -> Option<String> {
    let fixed_end =
        scene.solver.end_time.is_some() || scene.reduction.stop_at_separation == Switch::Off;
    (scene.solver.hold_time.is_some() && fixed_end).then(|| {
        "solver.hold_time has no effect: the run stops at a fixed end time (solver.end_time or reduction.stop_at_separation = \"off\"), not by the separation rule".to_string()
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::BTreeSet;
    use std::path::Path;

    fn scene(sets: &[&str]) -> Scene {
        let sets: Vec<_> = sets
            .iter()
            .map(|s| crate::scene::Override::parse(s).unwrap())
            .collect();
        Scene::from_toml(crate::scene::DEFAULT_SCENE, Path::new("."), &sets).unwrap()
    }

    fn notes(sets: &[&str], model: Reduction) -> Vec<String> {
        ignored_settings(&scene(sets), model)
            .into_iter()
            .map(|w| w.message)
            .collect()
    }

    #[test]
    fn every_key_of_the_scene_reference_has_a_rule() {
        let reference: BTreeSet<String> = crate::scene::reference_keys().into_iter().collect();
        let ruled: BTreeSet<String> = SETTINGS.iter().map(|s| s.key.to_string()).collect();
        assert_eq!(SETTINGS.len(), ruled.len(), "a key is ruled twice");
        assert_eq!(reference, ruled);
    }

    #[test]
    fn the_default_scene_notes_nothing_on_any_model() {
        for model in [
            Reduction::Axisymmetric,
            Reduction::Quarter,
            Reduction::Half,
            Reduction::Full,
        ] {
            assert!(notes(&[], model).is_empty(), "{model:?}");
        }
    }

    #[test]
    fn each_rule_notes_its_key_where_the_model_ignores_it() {
        let penalty = ["contact.penalty_factor=0.001"];
        assert!(notes(&penalty, Reduction::Axisymmetric)[0].starts_with("contact.penalty_factor"));
        assert!(notes(&penalty, Reduction::Quarter).is_empty());
        let on_penalty = ["contact.penalty_factor=0.001", "contact.plane=\"penalty\""];
        assert!(notes(&on_penalty, Reduction::Axisymmetric).is_empty());
        let plane = ["contact.plane=\"penalty\""];
        assert!(notes(&plane, Reduction::Quarter)[0].starts_with("contact.plane"));
        let friction = ["contact.friction=0.3"];
        assert!(notes(&friction, Reduction::Axisymmetric)[0].starts_with("contact.friction"));
        assert!(notes(&friction, Reduction::Quarter)[0].starts_with("contact.friction"));
        assert!(notes(&friction, Reduction::Half).is_empty());
        let mu = ["ball1.material={preset=\"copper-fe\",mu=0.5}"];
        assert!(notes(&mu, Reduction::Axisymmetric)[0].starts_with("ball1.material.mu"));
        assert!(notes(&mu, Reduction::Full).is_empty());
        let ring = ["solver.section_element=\"full\""];
        assert!(notes(&ring, Reduction::Quarter)[0].starts_with("solver.section_element"));
        assert!(notes(&ring, Reduction::Axisymmetric).is_empty());
        let hold = ["solver.hold_time=1e-5", "solver.end_time=1e-4"];
        assert!(notes(&hold, Reduction::Full)[0].starts_with("solver.hold_time"));
        assert!(notes(&hold[..1], Reduction::Full).is_empty());
    }
}
