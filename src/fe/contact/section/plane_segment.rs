//! Penalty contact of a meridian boundary against a rigid frictionless plane z = z₀, with the
//! penalty pressure integrated over the penetrated part of each boundary segment instead of
//! lumped at its nodes.
//!
//! Along a segment from node a to node b (ξ ∈ [0, 1]) the gap g(ξ) = (1 − ξ) g_a + ξ g_b is
//! linear; the penalty pressure is p = −ε g where g < 0, ε = FKN · E / h (Pa/m) with h the
//! thickness of the quad under the segment (area / segment length), and the potential is
//!
//!   W = Σ_segments ∫ ½ ε min(g, 0)² 2π r(ξ) l dξ,
//!
//! r(ξ) and l the segment's radius and length at rest. W is C¹ in the nodal positions, its
//! gradient is the nodal force f_a = ∫ ε min(g, 0) N_a 2π r l dξ, and the integrals are exact:
//! the integrands are cubic in ξ on the penetrated sub-interval (bounded by the crossing point
//! ξ_c = g_a / (g_a − g_b)), where two-point Gauss integration is exact. So the contact force
//! grows continuously as the contact edge moves along a segment: a ring does not add its whole
//! spring at once when its node lands, which is what makes a nodal contact's plastic e a
//! sawtooth over the mesh (docs/contact-penalty.md, "Why the section's e scatters").
//!
//! On a segment in full contact with a uniform gap g the nodes carry ε (−g) A_I, A_I the
//! consistent ring area ∫ N_I 2π r l dξ: the nodal rule of [`super::plane_nodal`] with its k_I = FKN
//! E A_I / h_I. The step limits use that k_I (the row sum of the consistent penalty matrix,
//! which bounds its largest eigenvalue by Gershgorin's theorem), shared by the two nodes of a
//! segment, which the penalty couples.

use super::plane_nodal::{check_fkn, penalty_energy, segment_length_and_thickness, Side};
use crate::error::Result;
use crate::fe::contact::penalty::stable_step;
use crate::fe::interaction::{ContactState, Interaction, InteractionEnergy, StepContext};
use crate::mesh::section::SectionMesh;
use std::f64::consts::PI;

/// One boundary segment: its nodes, radii at rest (m), length at rest (m) and penalty ε (Pa/m).
#[derive(Debug, Clone, Copy)]
struct Ring {
    a: usize,
    b: usize,
    ra: f64,
    rb: f64,
    length: f64,
    eps: f64,
}

/// A rigid plane z = z₀ acting on the segments of a boundary by integrated penalty pressure.
#[derive(Debug, Clone)]
pub struct SegmentPlane {
    z0: f64,
    sign: f64,
    rings: Vec<Ring>,
    state: ContactState,
}

/// Penetrated sub-interval [ξ₀, ξ₁] ⊂ [0, 1] of a segment with nodal gaps `ga`, `gb` (m), or
/// `None` when no part of it penetrates (g ≥ 0 everywhere).
pub fn penetrated_interval(ga: f64, gb: f64) -> Option<(f64, f64)> {
    match (ga < 0.0, gb < 0.0) {
        (false, false) => None,
        (true, true) => Some((0.0, 1.0)),
        (true, false) => Some((0.0, ga / (ga - gb))),
        (false, true) => Some((ga / (ga - gb), 1.0)),
    }
}

/// Nodal forces (f_a, f_b; N, positive pushing out of the plane) and stored energy (J) of a
/// segment with gaps `ga`, `gb` (m), rest radii `ra`, `rb` (m), rest length `l` (m) and
/// penalty `eps` (Pa/m), integrated exactly over its penetrated part.
pub fn segment_forces(ga: f64, gb: f64, ra: f64, rb: f64, l: f64, eps: f64) -> (f64, f64, f64) {
    let Some((x0, x1)) = penetrated_interval(ga, gb) else {
        return (0.0, 0.0, 0.0);
    };
    let (mid, half) = (0.5 * (x0 + x1), 0.5 * (x1 - x0));
    let off = half / 3f64.sqrt();
    let (mut fa, mut fb, mut w) = (0.0, 0.0, 0.0);
    for xi in [mid - off, mid + off] {
        let g = (1.0 - xi) * ga + xi * gb;
        let ring = 2.0 * PI * ((1.0 - xi) * ra + xi * rb) * l * half;
        let p = -eps * g;
        fa += p * (1.0 - xi) * ring;
        fb += p * xi * ring;
        w += 0.5 * eps * g * g * ring;
    }
    (fa, fb, w)
}

impl SegmentPlane {
    /// The plane z = `z0` (m) with the body on `side`, acting on `segments` of `mesh`, with
    /// penalty factor `fkn` (> 0) on Young's modulus `youngs` (Pa).
    ///
    /// Errors: a non-positive or non-finite `fkn`, a segment that is no edge of a quad.
    pub fn new(
        mesh: &SectionMesh,
        segments: &[[u32; 2]],
        z0: f64,
        side: Side,
        fkn: f64,
        youngs: f64,
    ) -> Result<Self> {
        check_fkn(fkn)?;
        let mut rings = Vec::with_capacity(segments.len());
        for s in segments {
            let (a, b) = (s[0] as usize, s[1] as usize);
            let (length, h) = segment_length_and_thickness(mesh, *s)?;
            rings.push(Ring {
                a,
                b,
                ra: mesh.nodes[a][0],
                rb: mesh.nodes[b][0],
                length,
                eps: fkn * youngs / h,
            });
        }
        Ok(SegmentPlane {
            z0,
            sign: side.sign(),
            rings,
            state: ContactState::default(),
        })
    }

    /// Each node's spring stiffness k_I = Σ ε A_I over its segments (N/m).
    fn springs(&self) -> std::collections::BTreeMap<usize, f64> {
        let mut k = std::collections::BTreeMap::new();
        for s in &self.rings {
            let c = 2.0 * PI * s.length * s.eps / 6.0;
            *k.entry(s.a).or_insert(0.0) += c * (2.0 * s.ra + s.rb);
            *k.entry(s.b).or_insert(0.0) += c * (2.0 * s.rb + s.ra);
        }
        k
    }
}

impl Interaction<2> for SegmentPlane {
    fn name(&self) -> &str {
        "segment plane contact"
    }

    fn add_forces(&mut self, ctx: &StepContext<'_, 2>, f: &mut [[f64; 2]]) -> Result<()> {
        let x = ctx.x;
        let mut s = ContactState::default();
        let mut last_active = usize::MAX;
        for r in &self.rings {
            let ga = self.sign * (self.z0 - x[r.a][1]);
            let gb = self.sign * (self.z0 - x[r.b][1]);
            let Some((x0, x1)) = penetrated_interval(ga, gb) else {
                continue;
            };
            let (fa, fb, w) = segment_forces(ga, gb, r.ra, r.rb, r.length, r.eps);
            f[r.a][1] -= self.sign * fa;
            f[r.b][1] -= self.sign * fb;
            s.normal_force += fa + fb;
            s.stored += w;
            s.max_penetration = s.max_penetration.max(-ga).max(-gb);
            for (node, g) in [(r.a, ga), (r.b, gb)] {
                if g < 0.0 && node != last_active {
                    s.active_nodes += 1;
                    last_active = node;
                }
            }
            // The contact edge: the current radius where the gap closes.
            let edge = |xi: f64| (1.0 - xi) * x[r.a][0] + xi * x[r.b][0];
            s.contact_radius = s.contact_radius.max(edge(x0)).max(edge(x1));
        }
        self.state = s;
        Ok(())
    }

    fn energy(&self) -> InteractionEnergy {
        penalty_energy(&self.state)
    }

    fn state(&self) -> ContactState {
        self.state
    }

    fn node_limits(&self, mass: &[f64], omega: &[f64]) -> Vec<(usize, f64)> {
        let mut dt = self.springs();
        for (i, v) in dt.iter_mut() {
            *v = stable_step(*v, mass[*i], omega[*i]);
        }
        // The two nodes of a segment are coupled: both take the smaller step.
        for s in &self.rings {
            let m = dt[&s.a].min(dt[&s.b]);
            dt.insert(s.a, m);
            dt.insert(s.b, m);
        }
        dt.into_iter().collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// ∫₀¹ F(ξ) dξ by a fine midpoint rule.
    fn midpoint(f: impl Fn(f64) -> f64) -> f64 {
        let n = 200_000;
        (0..n).map(|i| f((i as f64 + 0.5) / n as f64)).sum::<f64>() / n as f64
    }

    #[test]
    fn segment_integrals_are_exact_on_the_penetrated_part() {
        let (ra, rb, l, eps) = (1.0e-3, 1.2e-3, 0.2e-3, 3.0e15);
        for (ga, gb) in [(-2e-7, 1e-7), (3e-7, -1e-7), (-1e-7, -3e-7), (1e-7, 2e-7)] {
            let (fa, fb, w) = segment_forces(ga, gb, ra, rb, l, eps);
            let g = |x: f64| ((1.0 - x) * ga + x * gb).min(0.0);
            let ring = |x: f64| 2.0 * PI * ((1.0 - x) * ra + x * rb) * l;
            let fa_ref = midpoint(|x| -eps * g(x) * (1.0 - x) * ring(x));
            let fb_ref = midpoint(|x| -eps * g(x) * x * ring(x));
            let w_ref = midpoint(|x| 0.5 * eps * g(x) * g(x) * ring(x));
            let scale = (fa_ref + fb_ref).abs().max(1e-30);
            assert!((fa - fa_ref).abs() < 1e-7 * scale, "{fa} {fa_ref}");
            assert!((fb - fb_ref).abs() < 1e-7 * scale, "{fb} {fb_ref}");
            assert!(
                (w - w_ref).abs() <= 1e-7 * w_ref.abs().max(1e-30),
                "{w} {w_ref}"
            );
        }
    }

    #[test]
    fn forces_are_the_gradient_of_the_stored_energy() {
        let (ra, rb, l, eps) = (1.0e-3, 1.2e-3, 0.2e-3, 3.0e15);
        let (ga, gb) = (-2e-7, 1e-7);
        let (fa, fb, _) = segment_forces(ga, gb, ra, rb, l, eps);
        let w = |ga: f64, gb: f64| segment_forces(ga, gb, ra, rb, l, eps).2;
        let h = 1e-12;
        // f = −∂W/∂g (a smaller gap stores more).
        let da = -(w(ga + h, gb) - w(ga - h, gb)) / (2.0 * h);
        let db = -(w(ga, gb + h) - w(ga, gb - h)) / (2.0 * h);
        assert!((fa - da).abs() < 1e-6 * fa.abs(), "{fa} {da}");
        assert!((fb - db).abs() < 1e-6 * fa.abs(), "{fb} {db}");
    }

    #[test]
    fn a_uniform_gap_gives_the_nodal_rule() {
        let (ra, rb, l, eps, g) = (1.0e-3, 1.2e-3, 0.2e-3, 3.0e15, -1e-7);
        let (fa, fb, _) = segment_forces(g, g, ra, rb, l, eps);
        let area_a = 2.0 * PI * l * (2.0 * ra + rb) / 6.0;
        let area_b = 2.0 * PI * l * (2.0 * rb + ra) / 6.0;
        assert!((fa - eps * (-g) * area_a).abs() < 1e-12 * fa);
        assert!((fb - eps * (-g) * area_b).abs() < 1e-12 * fb);
    }

    #[test]
    fn the_force_grows_continuously_as_a_node_lands() {
        // Node b crosses the plane: the segment's force passes zero without a jump, and its
        // slope too (the force is quadratic in the penetrated length near the crossing).
        let (ra, rb, l, eps) = (1.0e-3, 1.2e-3, 0.2e-3, 3.0e15);
        let f = |gb: f64| {
            let (fa, fb, _) = segment_forces(1e-7, gb, ra, rb, l, eps);
            fa + fb
        };
        assert_eq!(f(1e-12), 0.0);
        assert!(f(-1e-12) > 0.0 && f(-1e-12) < 1e-9 * f(-1e-7));
    }
}
