//! The quads on their lane paths (`fe::elements::ring`, every formulation's lane update) against the scalar update of
//! each quad: whole impacts give the same bits on every path, for one material (the default
//! scene's mirror ball, on a coarser pole; one point and B-bar) and for two (steel on
//! aluminium, both meshed, whose lane groups break at the material change), single rate and
//! subcycled.

use twoball::fe::elements::ring::QuadFormulation;
use twoball::fe::simd::KernelPath;
use twoball::fe::subcycle::Integration;
use twoball::material::Material;
use twoball::mesh::section::{ball, SectionMesh, SectionSpec};
use twoball::study::run::section_impact::{HeadOn, ImpactResult, OtherBall, Target};

fn mesh(d: f64) -> SectionMesh {
    ball(&SectionSpec {
        diameter: d,
        size: d / 6.0,
        pole_size: Some(d / 60.0),
    })
    .unwrap()
}

fn run(
    target: Target,
    material: &str,
    integration: Integration,
    kernel: Option<KernelPath>,
    formulation: QuadFormulation,
) -> ImpactResult {
    let d = 0.02;
    let mut h = HeadOn::new(mesh(d), Material::preset(material).unwrap(), 1.0, target);
    h.integration = integration;
    h.kernel = kernel;
    h.formulation = formulation;
    h.run().unwrap()
}

/// Every output of `a` and `b` but the wall time, as text (so the bits are compared).
fn bits(r: &ImpactResult) -> String {
    let mut r = r.clone();
    r.wall_time_s = 0.0;
    format!("{r:?}")
}

fn same_on_every_path(target: impl Fn() -> Target, material: &str, form: QuadFormulation) {
    let sub = Integration::subcycled();
    let single = Integration::SingleRate;
    for (integration, paths) in [
        (
            sub,
            &[KernelPath::Avx512, KernelPath::Avx2, KernelPath::Portable][..],
        ),
        (single, &[KernelPath::Avx512][..]),
    ] {
        let scalar = run(target(), material, integration, None, form);
        assert!(scalar.plastic > 0.0 && scalar.e > 0.0 && scalar.e < 1.0);
        for &path in paths {
            let lanes = run(target(), material, integration, Some(path), form);
            assert_eq!(bits(&lanes), bits(&scalar), "{path:?}, {integration:?}");
        }
    }
}

#[test]
fn the_mirror_ball_gives_the_scalar_bits_on_every_lane_path() {
    same_on_every_path(
        || Target::MirrorBall,
        "copper-fe",
        QuadFormulation::default(),
    );
}

#[test]
fn b_bar_quads_give_the_scalar_bits_on_every_lane_path() {
    same_on_every_path(
        || Target::MirrorBall,
        "copper-fe",
        QuadFormulation::SelectiveReduced,
    );
}

#[test]
fn two_materials_give_the_scalar_bits_on_every_lane_path() {
    let other = || {
        Target::Ball(Box::new(OtherBall {
            mesh: mesh(0.03),
            material: Material::preset("aluminum").unwrap(),
            elastic_only: false,
            speed: 1.0,
        }))
    };
    same_on_every_path(other, "steel", QuadFormulation::default());
}
