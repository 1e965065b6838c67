//! A ball against a wall: the `[wall]` table, its checks, and ball 1's mirror image.
//!
//! ```toml
//! [ball1]
//! material = "copper-fe"
//! diameter = 0.02
//! velocity = [1.0, 0.0, 0.0]   # towards the wall, along its normal
//! [wall]
//! kind = "rigid"               # or "elastic" (a meshed block)
//! position = [0.0, 0.0, 0.0]   # a point of the wall's face, m (default: the origin)
//! normal = [-1.0, 0.0, 0.0]    # out of the wall, towards ball 1 (default: -x)
//! # kind = "elastic" only:
//! # material = "copper-fe"     # a preset or a table, as for the balls (required)
//! # size = [0.1, 0.1]          # block radius W and depth H, m (default: 5 D each)
//! ```
//!
//! An elastic wall is a block of depth H under the contact point, its base fixed, its rim
//! free: a cylinder of radius W on the section, a box of half-width W on the 3D models; a
//! finite stand-in for the analytical model's elastic half-space (design.md §6).
//!
//! A rigid frictionless wall acts on a ball exactly as the ball's mirror image in the wall
//! would (method of images): the scene's `ball2` is that image, which gives the touch, the
//! contact frame and the symmetry reduction of two identical balls; the models then put the
//! wall where the image's symmetry plane was, with the wall's own penalty (design.md §6).

use super::reader::Reader;
use crate::error::{Error, Result};
use crate::material::Material;
use serde::Serialize;

/// What the wall is made of.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum WallKind {
    /// A rigid, immovable half-space (the analytical model's `--wall rigid`).
    Rigid,
    /// An elastic-plastic block (the analytical model's `--wall elastic`).
    Elastic,
}

/// Default block radius and depth of an elastic wall, in ball-1 diameters: the Boussinesq
/// displacement at that depth under the peak Hertz force is below 0.5 % of δ_max up to
/// contact radii of a tenth of the ball's radius (design.md §6).
pub const DEFAULT_BLOCK_PER_D: f64 = 5.0;

/// A wall that ball 1 hits head-on.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct WallScene {
    /// What the wall is made of.
    pub kind: WallKind,
    /// A point of the wall's face, m.
    pub position: [f64; 3],
    /// Unit normal of the face, pointing out of the wall towards ball 1.
    pub normal: [f64; 3],
    /// The elastic wall's material (`None` for a rigid wall).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub material: Option<Material>,
    /// The elastic wall's block radius W and depth H, m (`None` for a rigid wall; the
    /// default is resolved when ball 1 is known).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub size: Option<[f64; 2]>,
}

pub(crate) const WALL_KEYS: [&str; 5] = ["kind", "position", "normal", "material", "size"];

pub(crate) fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

/// Reads the `[wall]` table: `kind` (required, `rigid` or `elastic`), `position` (m,
/// default the origin), `normal` (non-zero, normalised; default −x), and for an elastic wall
/// `material` (required) and `size` ([W, H] > 0 m, at most 100 m; default resolved by
/// [`WallScene::with_block_size`]).
pub(crate) fn read_wall(w: Reader<'_>) -> Result<WallScene> {
    w.only(&WALL_KEYS)?;
    let kind = match w.choice("kind", &["rigid", "elastic"]) {
        Ok(Some("elastic")) => WallKind::Elastic,
        Ok(Some(_)) => WallKind::Rigid,
        Ok(None) => return Err(w.missing("kind", "\"rigid\" or \"elastic\"")),
        Err(_) => {
            let given = w.string("kind")?.unwrap_or_default();
            return Err(Error::invalid(
                w.key_path("kind"),
                format!("\"{given}\""),
                "\"rigid\" or \"elastic\"",
            ));
        }
    };
    let (material, size) = match kind {
        WallKind::Rigid => {
            for key in ["material", "size"] {
                if w.raw(key).is_some() {
                    return Err(Error::Parse(format!(
                        "{} is set for a rigid wall: only kind = \"elastic\" takes it",
                        w.key_path(key)
                    )));
                }
            }
            (None, None)
        }
        WallKind::Elastic => {
            let (m, _) = super::material_table::read_material(&w)?;
            let size = w.array::<2>(
                "size",
                |x| x > 0.0 && x <= 100.0,
                "0 < size <= 100 m (block radius W and depth H)",
            )?;
            (Some(m), size)
        }
    };
    let position = w
        .vec3("position", |x| x.abs() <= 1e3, "|component| <= 1000 m")?
        .unwrap_or([0.0; 3]);
    let normal = w
        .vec3("normal", |x| x.abs() <= 1e3, "|component| <= 1000")?
        .unwrap_or([-1.0, 0.0, 0.0]);
    let l = norm(normal);
    if l <= 1e-12 {
        return Err(Error::invalid(
            w.key_path("normal"),
            format!("{normal:?}"),
            "a non-zero vector (out of the wall, towards ball 1)",
        ));
    }
    Ok(WallScene {
        kind,
        position,
        normal: normal.map(|c| c / l),
        material,
        size,
    })
}

impl WallScene {
    /// The wall with an elastic block's size resolved: [`DEFAULT_BLOCK_PER_D`] ball-1
    /// diameters `d` (m) for each side when the scene gave none.
    ///
    /// Errors: a side below ball 1's radius (the block must hold the contact and its field).
    pub fn with_block_size(mut self, d: f64) -> Result<Self> {
        if self.kind != WallKind::Elastic {
            return Ok(self);
        }
        let size = self.size.unwrap_or([DEFAULT_BLOCK_PER_D * d; 2]);
        for (i, side) in size.iter().enumerate() {
            if *side < 0.5 * d {
                return Err(Error::invalid(
                    format!("wall.size[{i}]"),
                    side,
                    format!(
                        ">= ball 1's radius {:.6e} m (default {DEFAULT_BLOCK_PER_D} D)",
                        0.5 * d
                    ),
                ));
            }
        }
        self.size = Some(size);
        Ok(self)
    }

    /// Checks that ball 1 (`material`, `diameter` m, `velocity` m/s) keeps its contact on an
    /// elastic block's face: the centre's tangential speed times the Hertz contact time at
    /// its normal speed, plus the Hertz contact radius, within the half-width W (a ball that
    /// slides off the face would press past its edge and never separate). A rigid wall, or a
    /// ball not approaching the face, passes.
    ///
    /// Errors: `wall.size[0]` below that reach, with the reach named.
    pub fn check_block_reach(
        &self,
        material: Material,
        diameter: f64,
        velocity: [f64; 3],
    ) -> Result<()> {
        let (Some(block), Some([width, _])) = (self.material, self.size) else {
            return Ok(());
        };
        let v_n = -dot(velocity, self.normal);
        if v_n <= 0.0 {
            return Ok(());
        }
        let v_t = norm([0, 1, 2].map(|k| velocity[k] + v_n * self.normal[k]));
        let pair = crate::analytic::HertzPair::between(
            &crate::analytic::Body::Ball { material, diameter },
            &crate::analytic::Body::HalfSpace { material: block },
        );
        let (t_c, delta) = (pair.contact_duration(v_n), pair.max_approach(v_n));
        let reach = v_t * t_c + pair.contact_radius(delta);
        if width < reach {
            return Err(Error::invalid(
                "wall.size[0]",
                width,
                format!(
                    ">= {reach:.4e} m: ball 1 slides {:.4e} m along the block's face (tangential \
                     speed {v_t:.4e} m/s times the Hertz contact time {t_c:.4e} s) and its contact \
                     reaches {:.4e} m further; a narrower block lets it slide off the face",
                    v_t * t_c,
                    reach - v_t * t_c
                ),
            ));
        }
        Ok(())
    }

    /// Signed distance (m) of point `p` in front of the wall's face.
    pub fn distance(&self, p: [f64; 3]) -> f64 {
        dot([0, 1, 2].map(|k| p[k] - self.position[k]), self.normal)
    }

    /// The mirror image of point `p` in the wall's face, m.
    pub fn mirror_point(&self, p: [f64; 3]) -> [f64; 3] {
        let s = self.distance(p);
        [0, 1, 2].map(|k| p[k] - 2.0 * s * self.normal[k])
    }

    /// The mirror image of a (polar) vector `v` in the wall's face.
    pub fn mirror_vector(&self, v: [f64; 3]) -> [f64; 3] {
        let s = dot(v, self.normal);
        [0, 1, 2].map(|k| v[k] - 2.0 * s * self.normal[k])
    }
}
