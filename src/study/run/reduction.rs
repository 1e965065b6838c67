//! Which model a scene runs on: the symmetry reduction (meridian section, quarter, half or
//! the full pair) that the scene's `reduction.symmetry` and its motion allow, with the reason
//! results.json reports.

use crate::error::{Error, Result};
use crate::scene::{
    BallScene, MeshSettings, PlaneEnforcement, Scene, Switch, Symmetry, Touch, WallKind,
};
use serde::Serialize;

/// Which symmetry reduction a run used.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Reduction {
    /// The meridian section of a head-on impact (the axisymmetric model): one ball against
    /// the frictionless symmetry plane for identical balls, both balls' sections otherwise.
    Axisymmetric,
    /// One quarter of ball 1 against a frictionless rigid plane (1/8 of the system).
    Quarter,
    /// Both balls cut by the plane z = 0 of the motion (1/2 of the system).
    Half,
    /// Both whole balls.
    Full,
}

impl Reduction {
    /// Fraction of the whole system the model simulates: of the two balls, or of the one
    /// ball on a wall (`wall`); the section model reports whole-system figures itself: 1.
    pub fn fraction(self, wall: bool) -> f64 {
        match self {
            Reduction::Quarter if wall => 0.25,
            Reduction::Quarter => 1.0 / 8.0,
            Reduction::Half => 0.5,
            Reduction::Axisymmetric | Reduction::Full => 1.0,
        }
    }

    /// Lower-case name, as in results.json.
    pub fn name(self) -> &'static str {
        match self {
            Reduction::Axisymmetric => "axisymmetric",
            Reduction::Quarter => "quarter",
            Reduction::Half => "half",
            Reduction::Full => "full",
        }
    }
}

/// What the scene's motion at first touch allows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Allowed {
    /// Velocities along the line of centres, no spin, built-in meshes: axisymmetric.
    head_on: bool,
    /// Identical balls with built-in meshes.
    identical: bool,
    /// Tangential motion in one plane and spins normal to it.
    planar: bool,
    /// Ball 1 meshed by the built-in mesher.
    builtin: bool,
}

fn allowed(scene: &Scene, touch: &Touch) -> Allowed {
    let (v1, w1) = (touch.v[0], touch.w[0]);
    let (v2, w2) = touch.partner(scene);
    let scale = (v1[0] - v2[0]).abs();
    let tiny = |x: f64| x.abs() <= 1e-12 * scale;
    let spin_scale = scale / (scene.ball1.diameter.min(scene.ball2.diameter) / 2.0);
    let no_spin = |w: [f64; 3]| w.iter().all(|c| c.abs() <= 1e-12 * spin_scale);
    let planar_spin =
        |w: [f64; 3]| w[0].abs() <= 1e-12 * spin_scale && w[1].abs() <= 1e-12 * spin_scale;
    let builtin = |b: &BallScene| matches!(b.mesh, MeshSettings::Builtin { .. });
    let normal = tiny(v1[1] - v2[1]) && tiny(v1[2] - v2[2]) && no_spin(w1) && no_spin(w2);
    Allowed {
        head_on: normal && builtin(&scene.ball1) && builtin(&scene.ball2),
        identical: scene.identical_balls() && builtin(&scene.ball1),
        planar: tiny(v1[2] - v2[2]) && planar_spin(w1) && planar_spin(w2),
        builtin: builtin(&scene.ball1),
    }
}

/// The symmetry reduction `scene` runs with when touching as `touch`, and why.
///
/// Automatically (`auto`), a head-on impact (velocities along the line of centres, no spin)
/// of built-in meshes starting at first touch runs on the meridian section (a body of
/// revolution about the line of centres, exactly): one ball's section against the
/// frictionless symmetry plane for identical balls, both sections for unequal ones. Every
/// other scene gets the cheapest exact 3D model (`auto-3d`): a head-on impact of identical
/// balls runs as a quarter ball against the symmetry plane; with tangential motion in the
/// x-y plane (and spins about z only) the plane z = 0 stays a symmetry plane: half model;
/// anything else runs full. `reduction.symmetry` forces a model.
///
/// Errors: a forced model the motion does not allow (axisymmetric or quarter for an oblique
/// impact, quarter or half for unequal balls, any reduction for meshes read from files).
pub fn choose_reduction(scene: &Scene, touch: &Touch) -> Result<(Reduction, String)> {
    let ok = allowed(scene, touch);
    if scene.wall.is_some() {
        return wall_reduction(scene, ok);
    }
    let refuse = |what: &str, needs: &str| {
        Err(Error::invalid(
            "reduction.symmetry",
            format!("\"{what}\""),
            format!("auto or off for this scene: {what} needs {needs}"),
        ))
    };
    let quarter = || {
        (
            Reduction::Quarter,
            "identical balls, pure normal impact: quarter ball against a frictionless rigid plane"
                .to_string(),
        )
    };
    let half = || {
        (
            Reduction::Half,
            "identical balls, tangential motion in one plane: half model".to_string(),
        )
    };
    let axisymmetric = || {
        let how = if ok.identical {
            "one ball's section against the frictionless symmetry plane"
        } else {
            "both balls' sections"
        };
        (
            Reduction::Axisymmetric,
            format!(
                "head-on impact (velocities on the line of centres, no spin): axisymmetric, {how}"
            ),
        )
    };
    let head_on =
        "a head-on impact (velocities on the line of centres, no spin) of built-in meshes";
    let symmetry = resolve_auto(scene, ok.head_on);
    match symmetry {
        Symmetry::Off => Ok((Reduction::Full, "symmetry reduction switched off".into())),
        Symmetry::Axisymmetric if scene.reduction.start_at_touch == Switch::Off => refuse(
            "axisymmetric",
            "reduction.start_at_touch = \"auto\" (the section model starts at first touch)",
        ),
        Symmetry::Axisymmetric if ok.head_on => Ok(axisymmetric()),
        Symmetry::Axisymmetric => refuse("axisymmetric", head_on),
        Symmetry::Quarter if ok.head_on && ok.identical => Ok(quarter()),
        Symmetry::Quarter => refuse("quarter", &format!("identical balls in {head_on}")),
        Symmetry::Half if ok.identical && ok.planar => Ok(half()),
        Symmetry::Half => refuse(
            "half",
            "identical built-in balls with tangential motion in one plane",
        ),
        // `resolve_auto` leaves no `Auto`.
        Symmetry::Auto | Symmetry::Auto3d if !scene.identical_balls() => Ok((
            Reduction::Full,
            "the balls differ (material, diameter or mesh)".into(),
        )),
        Symmetry::Auto | Symmetry::Auto3d if !ok.identical => Ok((
            Reduction::Full,
            "meshes read from files are used whole".into(),
        )),
        Symmetry::Auto | Symmetry::Auto3d if ok.head_on => Ok(quarter()),
        Symmetry::Auto | Symmetry::Auto3d if ok.planar => Ok(half()),
        Symmetry::Auto | Symmetry::Auto3d => {
            Ok((Reduction::Full, "motion out of one plane".into()))
        }
    }
}

/// `reduction.symmetry` with `auto` made concrete: the section where the scene allows it
/// (`section`: a head-on impact of built-in meshes, or a block wall that only the section
/// models; and the run starting at touch), else `auto-3d`. Any other choice is kept.
fn resolve_auto(scene: &Scene, section: bool) -> Symmetry {
    match scene.reduction.symmetry {
        Symmetry::Auto if section && scene.reduction.start_at_touch != Switch::Off => {
            Symmetry::Axisymmetric
        }
        Symmetry::Auto => Symmetry::Auto3d,
        s => s,
    }
}

/// The reduction of a ball against a wall. Head-on: the quarter ball against the rigid wall
/// plane or the elastic wall's quarter block (`auto-3d`, `quarter`), or the ball's meridian
/// section against either (`auto`, `axisymmetric`); oblique or spinning:
/// [`oblique_wall_reduction`].
fn wall_reduction(scene: &Scene, ok: Allowed) -> Result<(Reduction, String)> {
    let refuse = |what: &str, needs: &str| {
        Err(Error::invalid(
            "reduction.symmetry",
            format!("\"{what}\""),
            format!(
                "auto, auto-3d, quarter or axisymmetric for a ball on a wall: {what} needs {needs}"
            ),
        ))
    };
    if !ok.builtin {
        return Err(Error::invalid(
            "ball1.mesh.file",
            "a mesh file",
            "the built-in mesher for a ball on a wall (its models cut the ball by symmetry)",
        ));
    }
    let elastic = scene.wall.is_some_and(|w| w.kind == WallKind::Elastic);
    let symmetry = scene.reduction.symmetry;
    if !ok.head_on {
        return oblique_wall_reduction(scene, ok, elastic);
    }
    let start_at_touch = scene.reduction.start_at_touch != Switch::Off;
    // An elastic wall has the section only: with start_at_touch = "off" its `auto` is
    // refused below as the section is.
    let symmetry = match resolve_auto(scene, true) {
        Symmetry::Auto3d if elastic && symmetry == Symmetry::Auto => Symmetry::Axisymmetric,
        s => s,
    };
    match symmetry {
        Symmetry::Axisymmetric if elastic && start_at_touch => Ok((
            Reduction::Axisymmetric,
            "ball head-on against an elastic wall: axisymmetric, the ball's section against \
                 the meshed block's face (node-to-segment penalty)"
                .into(),
        )),
        Symmetry::Off | Symmetry::Half => {
            let what = if scene.reduction.symmetry == Symmetry::Off {
                "off"
            } else {
                "half"
            };
            refuse(
                what,
                "two balls (the wall is modelled on the quarter ball or the section)",
            )
        }
        Symmetry::Axisymmetric if !start_at_touch => refuse(
            "axisymmetric",
            "reduction.start_at_touch = \"auto\" (the section model starts at first touch)",
        ),
        Symmetry::Axisymmetric => Ok((
            Reduction::Axisymmetric,
            format!(
                "ball head-on against a rigid wall: axisymmetric, the ball's section against the \
                 wall ({})",
                match scene.contact.plane {
                    PlaneEnforcement::Kinematic => "a unilateral kinematic constraint",
                    PlaneEnforcement::Penalty => "penalty of the ball's own stiffness",
                }
            ),
        )),
        Symmetry::Auto | Symmetry::Auto3d | Symmetry::Quarter if elastic => Ok((
            Reduction::Quarter,
            "ball head-on against an elastic wall: quarter ball against the quarter of the \
             meshed block (node-to-segment penalty)"
                .into(),
        )),
        Symmetry::Auto | Symmetry::Auto3d | Symmetry::Quarter => Ok((
            Reduction::Quarter,
            "ball head-on against a rigid wall: quarter ball against the rigid wall plane \
             (penalty of the ball's own stiffness)"
                .into(),
        )),
    }
}

/// The model of an oblique or spinning ball on a wall: the half ball when the motion is
/// planar (tangential velocity in one plane, spin normal to it), else the whole ball, on the
/// rigid wall plane or the elastic wall's block (cut alike) with friction. Errors: a symmetry
/// that needs a head-on impact.
fn oblique_wall_reduction(
    scene: &Scene,
    ok: Allowed,
    elastic: bool,
) -> Result<(Reduction, String)> {
    let symmetry = scene.reduction.symmetry;
    let (wall, against) = if elastic {
        (
            "an elastic wall",
            "the frictional face of the meshed block (node-to-segment penalty)",
        )
    } else {
        (
            "a rigid wall",
            "the frictional wall plane (penalty of the ball's own stiffness)",
        )
    };
    let half = || {
        (
            Reduction::Half,
            format!("ball on {wall}, motion in one plane: half ball against {against}"),
        )
    };
    let full = |why: &str| {
        (
            Reduction::Full,
            format!("ball on {wall}, {why}: whole ball against {against}"),
        )
    };
    match symmetry {
        Symmetry::Off => Ok(full("symmetry reduction switched off")),
        Symmetry::Half if ok.planar => Ok(half()),
        Symmetry::Auto | Symmetry::Auto3d if ok.planar => Ok(half()),
        Symmetry::Auto | Symmetry::Auto3d => Ok(full("motion out of one plane")),
        s => Err(Error::invalid(
            "reduction.symmetry",
            format!("\"{}\"", symmetry_name(s)),
            if ok.planar {
                "auto, auto-3d, half or off for an oblique or spinning ball on a wall"
            } else {
                "auto, auto-3d or off for a ball on a wall whose motion leaves one plane"
            },
        )),
    }
}

/// The scene word of `s`.
fn symmetry_name(s: Symmetry) -> &'static str {
    match s {
        Symmetry::Auto => "auto",
        Symmetry::Auto3d => "auto-3d",
        Symmetry::Axisymmetric => "axisymmetric",
        Symmetry::Quarter => "quarter",
        Symmetry::Half => "half",
        Symmetry::Off => "off",
    }
}
