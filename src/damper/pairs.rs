//! The contact laws of every kind of contact in a scene, built once through the seam's
//! registry: one entry per pair of ball species (same material and diameter) and one per
//! species against the wall.

use super::scene::DamperScene;
use crate::analytic::collision::pair_friction;
use crate::analytic::laws::{ContactPair, NormalLaw, Registry, TangentialLaw};
use crate::analytic::Body;
use crate::error::Result;

/// The laws of one kind of contact and the inertia the step and friction need.
pub struct PairLaws {
    /// Normal law.
    pub normal: Box<dyn NormalLaw>,
    /// Tangential law.
    pub tangential: Box<dyn TangentialLaw>,
    /// The pair's effective properties (E*, R*, m*, …).
    pub pair: ContactPair,
    /// Tangential effective mass m_t, 1/m_t = Σ (1/m + R²/I) over the moving bodies, kg.
    pub tangential_mass: f64,
}

/// The laws of every contact kind of a scene.
pub struct PairTable {
    /// Species index of each ball.
    pub species: Vec<usize>,
    /// The body of each species.
    pub bodies: Vec<Body>,
    ball: Vec<PairLaws>,
    wall: Vec<PairLaws>,
}

fn tangential_inverse_mass(b: &Body) -> f64 {
    if b.is_wall() {
        0.0
    } else {
        1.0 / b.mass() + b.radius().powi(2) / b.moment_of_inertia()
    }
}

fn build(
    registry: &Registry,
    scene: &DamperScene,
    a: &Body,
    b: &Body,
    mu: f64,
) -> Result<PairLaws> {
    let pair = ContactPair::between(a, b, mu);
    let (normal, _) = registry
        .normal(&scene.laws.normal)?
        .build_with(&scene.laws.normal_params, &pair)?;
    let (tangential, _) = registry
        .tangential(&scene.laws.tangential)?
        .build_with(&scene.laws.tangential_params, &pair)?;
    Ok(PairLaws {
        normal,
        tangential,
        pair,
        tangential_mass: 1.0 / (tangential_inverse_mass(a) + tangential_inverse_mass(b)),
    })
}

impl PairTable {
    /// Builds every law of `scene` from `registry`. Errors: an unknown law or parameter (named
    /// by the registry), an invalid ball.
    pub fn new(scene: &DamperScene, registry: &Registry) -> Result<PairTable> {
        let all = scene.bodies()?;
        let mut bodies: Vec<Body> = Vec::new();
        let mut species = Vec::with_capacity(all.len());
        for b in &all {
            let k = bodies.iter().position(|s| s == b).unwrap_or_else(|| {
                bodies.push(*b);
                bodies.len() - 1
            });
            species.push(k);
        }
        let wall = Body::HalfSpace {
            material: scene.container.material,
        };
        let mut ball = Vec::new();
        for i in 0..bodies.len() {
            for j in 0..bodies.len() {
                let mu = scene
                    .laws
                    .mu_ball
                    .unwrap_or_else(|| pair_friction(&bodies[i], &bodies[j]));
                ball.push(build(registry, scene, &bodies[i], &bodies[j], mu)?);
            }
        }
        let mut walls = Vec::new();
        for b in &bodies {
            let mu = scene
                .laws
                .mu_wall
                .unwrap_or_else(|| pair_friction(b, &wall));
            walls.push(build(registry, scene, b, &wall, mu)?);
        }
        Ok(PairTable {
            species,
            bodies,
            ball,
            wall: walls,
        })
    }

    /// The laws between balls `i` and `j`.
    pub fn ball(&self, i: usize, j: usize) -> &PairLaws {
        let n = self.bodies.len();
        &self.ball[self.species[i] * n + self.species[j]]
    }

    /// The laws between ball `i` and a wall.
    pub fn wall(&self, i: usize) -> &PairLaws {
        &self.wall[self.species[i]]
    }

    /// Every contact kind (for the time step).
    pub fn kinds(&self) -> impl Iterator<Item = &PairLaws> {
        self.ball.iter().chain(self.wall.iter())
    }
}
