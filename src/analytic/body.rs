//! A colliding body of the analytical model: an elastic-plastic ball, or the ball-on-wall limit
//! (a rigid half-space, or an elastic-plastic one).

use crate::error::{Error, Result};
use crate::material::Material;

/// One of the two colliding bodies. Build balls with [`Body::ball`], which validates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Body {
    /// A solid homogeneous sphere of the given material and diameter (m).
    Ball {
        /// Ball material.
        material: Material,
        /// Diameter D, m (> 0).
        diameter: f64,
    },
    /// A rigid, immovable half-space: infinite modulus, radius and mass; never yields; no
    /// friction coefficient of its own (the ball's is used).
    RigidWall,
    /// An immovable elastic-plastic half-space: infinite radius and mass, finite modulus; it
    /// yields like the ball (σ_p uses its yield strength too).
    HalfSpace {
        /// Half-space material.
        material: Material,
    },
}

impl Body {
    /// A ball, checked: `diameter` must be finite and > 0 m, the material valid.
    /// `name` prefixes field names in errors (e.g. `ball1`).
    pub fn ball(material: Material, diameter: f64, name: &str) -> Result<Body> {
        if !(diameter.is_finite() && diameter > 0.0) {
            return Err(Error::invalid(
                format!("{name}.diameter"),
                diameter,
                "diameter > 0 m, finite",
            ));
        }
        let material = material.validated(&format!("{name}.material"))?;
        Ok(Body::Ball { material, diameter })
    }

    /// The material, if the body has one (a rigid wall has none).
    pub fn material(&self) -> Option<&Material> {
        match self {
            Body::Ball { material, .. } | Body::HalfSpace { material } => Some(material),
            Body::RigidWall => None,
        }
    }

    /// True for the half-space limits (they have infinite mass and never move).
    pub fn is_wall(&self) -> bool {
        !matches!(self, Body::Ball { .. })
    }

    /// Radius R, m; `f64::INFINITY` for a half-space.
    pub fn radius(&self) -> f64 {
        match self {
            Body::Ball { diameter, .. } => 0.5 * diameter,
            _ => f64::INFINITY,
        }
    }

    /// Mass m = ρ (4/3) π R³, kg; `f64::INFINITY` for a half-space.
    pub fn mass(&self) -> f64 {
        match self {
            Body::Ball { material, diameter } => {
                let r = 0.5 * diameter;
                material.rho * 4.0 / 3.0 * std::f64::consts::PI * r * r * r
            }
            _ => f64::INFINITY,
        }
    }

    /// Moment of inertia about a diameter, (2/5) m R², kg·m²; infinite for a half-space.
    pub fn moment_of_inertia(&self) -> f64 {
        match self {
            Body::Ball { .. } => 0.4 * self.mass() * self.radius().powi(2),
            _ => f64::INFINITY,
        }
    }

    /// Plane-strain modulus E/(1 − ν²), Pa (the paper's E_ti); infinite for a rigid wall.
    pub fn plane_strain_modulus(&self) -> f64 {
        self.material()
            .map_or(f64::INFINITY, Material::plane_strain_modulus)
    }

    /// Yield pressure σ_p = (1 + π/2) σ_s (eq. 9, rigid flat punch), Pa; infinite for a rigid wall.
    pub fn yield_pressure(&self) -> f64 {
        self.material().map_or(f64::INFINITY, |m| {
            (1.0 + std::f64::consts::FRAC_PI_2) * m.yield_strength
        })
    }
}

/// 1/m_t = 1/m₁ + 1/m₂ + R₁²/I₁ + R₂²/I₂ (1/kg): how a tangential force at the contact
/// accelerates the slip of the contact points (a wall contributes nothing).
pub fn tangential_compliance(b1: &Body, b2: &Body) -> f64 {
    let part = |b: &Body| {
        if b.is_wall() {
            0.0
        } else {
            1.0 / b.mass() + b.radius().powi(2) / b.moment_of_inertia()
        }
    };
    part(b1) + part(b2)
}
