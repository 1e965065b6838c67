//! The registry of ring-element formulations: the one enum a section model names its
//! element by, the scene names, and the dispatch from a formulation to code compiled for
//! its element type.
//!
//! Registering a formulation: a variant of [`QuadFormulation`], its name in
//! [`QuadFormulation::NAMES`] and its value in [`QuadFormulation::ALL`], and its arm in
//! [`QuadFormulation::with`]; its code implements [`RingElement`] in a file of its own.
//! Every test written against the registry (the lane paths against the scalar update, the
//! patch tests, the thick spheres) then runs it.

use super::bbar::BBarQuad;
use super::element::{RingElement, RingVisitor, Step};
use super::full::FullQuad;
use super::one_point::{OnePointQuad, DEFAULT_HOURGLASS};
use super::state::{QuadOutput, QuadState};
use crate::fe::materials::J2Material;

/// How the section's 4-node ring quad is integrated.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum QuadFormulation {
    /// One stress point with stiffness hourglass control of coefficient ε_hg ≥ 0
    /// (`one-point`, [`OnePointQuad`]).
    OnePoint {
        /// Hourglass coefficient ε_hg (dimensionless, 0.03-0.1 usual).
        hourglass: f64,
    },
    /// 2x2 Gauss points for the deviator, mean dilatation for the volume (`b-bar`,
    /// [`BBarQuad`]).
    SelectiveReduced,
    /// 2x2 Gauss points for the whole strain rate (`full`, [`FullQuad`]; locks in plastic
    /// flow).
    Full,
}

impl Default for QuadFormulation {
    fn default() -> Self {
        QuadFormulation::OnePoint {
            hourglass: DEFAULT_HOURGLASS,
        }
    }
}

impl QuadFormulation {
    /// Every formulation with its default parameters, in the order of
    /// [`QuadFormulation::NAMES`].
    pub const ALL: [QuadFormulation; 3] = [
        QuadFormulation::OnePoint {
            hourglass: DEFAULT_HOURGLASS,
        },
        QuadFormulation::SelectiveReduced,
        QuadFormulation::Full,
    ];

    /// The scene names, in the order of [`QuadFormulation::ALL`].
    pub const NAMES: [&'static str; 3] = ["one-point", "b-bar", "full"];

    /// The scene name.
    pub fn name(self) -> &'static str {
        match self {
            QuadFormulation::OnePoint { .. } => Self::NAMES[0],
            QuadFormulation::SelectiveReduced => Self::NAMES[1],
            QuadFormulation::Full => Self::NAMES[2],
        }
    }

    /// The formulation named `name` with its default parameters, if any.
    pub fn from_name(name: &str) -> Option<QuadFormulation> {
        let k = Self::NAMES.iter().position(|n| *n == name)?;
        Some(Self::ALL[k])
    }

    /// Integration points whose state the element keeps.
    pub fn points(self) -> usize {
        self.with(Points)
    }

    /// Runs `v` with this formulation's element (one match, here, for every generic
    /// caller: the section's loop, the scalar update, the point count).
    #[inline(always)]
    pub fn with<V: RingVisitor>(self, v: V) -> V::Output {
        match self {
            QuadFormulation::OnePoint { hourglass } => v.visit(OnePointQuad { hourglass }),
            QuadFormulation::SelectiveReduced => v.visit(BBarQuad {}),
            QuadFormulation::Full => v.visit(FullQuad {}),
        }
    }
}

impl serde::Serialize for QuadFormulation {
    /// As its scene name.
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.name())
    }
}

/// Updates one quad of formulation `form` (the scalar reference, [`RingElement::update`]):
/// nodal coordinates `x1` = x^{n+1} (m), velocities `v` = v^{n+1/2} (m/s), step `dt` (s; 0
/// evaluates the forces of the current state without advancing it), material `mat`, state
/// `st`. Never fails: an inverted quad shows as `min_jacobian` ≤ 0.
#[inline]
pub fn update(
    x1: &[[f64; 2]; 4],
    v: &[[f64; 2]; 4],
    dt: f64,
    mat: &J2Material,
    form: QuadFormulation,
    st: &mut QuadState,
) -> QuadOutput {
    form.with(Scalar { x1, v, dt, mat, st })
}

/// [`update`] as a visitor.
struct Scalar<'a> {
    x1: &'a [[f64; 2]; 4],
    v: &'a [[f64; 2]; 4],
    dt: f64,
    mat: &'a J2Material,
    st: &'a mut QuadState,
}

impl RingVisitor for Scalar<'_> {
    type Output = QuadOutput;
    #[inline(always)]
    fn visit<E: RingElement>(self, element: E) -> QuadOutput {
        let s = Step {
            x1: self.x1,
            v: self.v,
            dt: self.dt,
            mat: self.mat,
        };
        element.update(s, self.st)
    }
}

/// [`QuadFormulation::points`] as a visitor.
struct Points;

impl RingVisitor for Points {
    type Output = usize;
    fn visit<E: RingElement>(self, _: E) -> usize {
        E::POINTS
    }
}

#[cfg(test)]
mod tests {
    use super::super::element::LaneStep;
    use super::super::lanes::{Nodes, RingLaneOutput, RingLaneState};
    use super::*;
    use crate::fe::materials::{Hardening, Law};
    use crate::fe::simd::{Avx2, Avx512, LaneIsa, LaneKernel, Portable, Simd};
    use crate::material::Material;

    /// W quads distorted and moving differently, with stresses past yield.
    fn quads(k: usize) -> ([[f64; 2]; 4], [[f64; 2]; 4], QuadState) {
        let f = k as f64;
        let r0 = if k.is_multiple_of(3) { 0.0 } else { 1e-3 * f };
        let x = [
            [r0, 0.0],
            [r0 + 1e-3 + 1e-5 * f, -2e-5 * f],
            [r0 + 1.1e-3, 0.9e-3 + 1e-5 * f],
            [r0 + 1e-5 * f, 1e-3],
        ];
        let v = [
            [0.0, -1.0],
            [0.3 - 0.05 * f, -0.7],
            [0.2, 0.4 + 0.1 * f],
            [0.01 * f, 0.5],
        ];
        let mut st = QuadState::default();
        st.points[0].stress = [3e8 + 1e7 * f, -2e8, 1e8, 5e7 * (f - 2.0), 0.0, 0.0];
        st.points[0].eps_p = 1e-3 * f;
        st.hourglass = [1.0 + f, -2.0];
        st.internal_energy = 1e-3;
        (x, v, st)
    }

    /// One lane update of step 2e-8 s as a visitor.
    struct LaneUpdate<'a, H: Hardening, const W: usize> {
        x: &'a Nodes<W>,
        v: &'a Nodes<W>,
        mat: &'a J2Material,
        law: &'a H,
        st: &'a mut RingLaneState<W>,
    }

    impl<H: Hardening, const W: usize> RingVisitor for LaneUpdate<'_, H, W> {
        type Output = RingLaneOutput<W>;
        fn visit<E: RingElement>(self, e: E) -> RingLaneOutput<W> {
            let step = Step {
                x1: self.x,
                v: self.v,
                dt: 2e-8,
                mat: self.mat,
            };
            e.update_lanes(
                LaneStep {
                    step,
                    law: self.law,
                },
                self.st,
            )
        }
    }

    /// Every lane of W quads against the scalar update of formulation `.0`.
    struct Check(QuadFormulation);
    impl LaneKernel for Check {
        type Output = ();
        fn run<const W: usize>(self, isa: LaneIsa<W>) {
            let mat = J2Material::new(&Material::preset("copper-fe").unwrap(), false);
            let Law::Bilinear(law) = mat.law else {
                panic!("copper-fe is bilinear")
            };
            let form = self.0;
            let points = form.points();
            let mut scalar: [_; W] = std::array::from_fn(quads);
            if points > 1 {
                for (_, _, st) in &mut scalar {
                    let first = st.points[0];
                    for (k, p) in st.points.iter_mut().enumerate() {
                        *p = first;
                        p.stress[3] *= 1.0 + 0.1 * k as f64;
                    }
                }
            }
            let z = isa.splat(0.0);
            let (mut x, mut v) = ([[z; 2]; 4], [[z; 2]; 4]);
            for (l, (xl, vl, _)) in scalar.iter().enumerate() {
                for k in 0..4 {
                    for c in 0..2 {
                        x[k][c].0[l] = xl[k][c];
                        v[k][c].0[l] = vl[k][c];
                    }
                }
            }
            let mut st = RingLaneState::gather(isa, std::array::from_fn(|l| &scalar[l].2), points);
            for _ in 0..3 {
                let out = form.with(LaneUpdate {
                    x: &x,
                    v: &v,
                    mat: &mat,
                    law: &law,
                    st: &mut st,
                });
                for (l, (xl, vl, sl)) in scalar.iter_mut().enumerate() {
                    let want = update(xl, vl, 2e-8, &mat, form, sl);
                    assert_eq!(out.lane(l), want, "lane {l}");
                    let mut got = *sl;
                    st.scatter(l, &mut got, points);
                    assert_eq!(got, *sl, "lane {l}");
                }
            }
            assert!(
                scalar.iter().any(|q| q.2.plastic_work > 0.0),
                "no lane yielded"
            );
        }
    }

    #[test]
    fn every_element_on_every_lane_path_gives_its_scalar_update_s_bits() {
        for form in QuadFormulation::ALL {
            Portable.vectorize(Check(form));
            if let Some(t) = Avx2::detect() {
                t.vectorize(Check(form));
            }
            if let Some(t) = Avx512::detect() {
                t.vectorize(Check(form));
            }
        }
    }
}
