#![allow(clippy::needless_range_loop)]
//! Acceptance 1: the patch test. A linear velocity field on a distorted mesh must give the
//! same (constant) strain increment in every element and zero internal-force residual at the
//! interior node, for both formulations, with hourglass control switched on.

use twoball::fe::elements::ElementBlock;
use twoball::fe::materials::J2Material;
use twoball::fe::Formulation;
use twoball::mesh::block::block;
use twoball::Material;

/// A 2x2x2 block of side 2 mm whose nodes are all perturbed (interior node included).
fn distorted_block() -> twoball::mesh::Mesh {
    let mut m = block([2e-3, 2e-3, 2e-3], [2, 2, 2]);
    for (i, p) in m.nodes.iter_mut().enumerate() {
        let s = i as f64;
        p[0] += 1.5e-4 * (1.7 * s).sin();
        p[1] += 1.5e-4 * (2.3 * s + 0.4).cos();
        p[2] += 1.5e-4 * (0.9 * s + 1.1).sin();
    }
    m
}

fn lin_solve(a: [[f64; 3]; 3], b: [f64; 3]) -> [f64; 3] {
    let det = |m: [[f64; 3]; 3]| {
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    };
    let d = det(a);
    [0, 1, 2].map(|k| {
        let mut m = a;
        for r in 0..3 {
            m[r][k] = b[r];
        }
        det(m) / d
    })
}

fn patch(formulation: Formulation) {
    let mesh = distorted_block();
    let mat = Material::preset("steel").unwrap();
    let j2 = J2Material::new(&mat, true);
    let mut blk = ElementBlock::new(0, 0, mesh.hexes.clone(), formulation, j2, 0.1);
    // Velocity gradient with stretch, shear and spin parts, 1/s.
    let g = [[3.0, 1.0, -2.0], [0.5, -1.0, 2.5], [1.5, -0.7, 2.0]];
    let dt = 1e-7;
    // Nodes move from x0 with v = G x0: x1 = x0 + dt v.
    let v: Vec<[f64; 3]> = mesh
        .nodes
        .iter()
        .map(|p| [0, 1, 2].map(|r| (0..3).map(|c| g[r][c] * p[c]).sum()))
        .collect();
    let x1: Vec<[f64; 3]> = mesh
        .nodes
        .iter()
        .zip(&v)
        .map(|(p, w)| [0, 1, 2].map(|k| p[k] + dt * w[k]))
        .collect();
    let mut forces = vec![[[0.0; 3]; 8]; mesh.hexes.len()];
    blk.update(&x1, &v, dt, &mut forces).unwrap();
    // Independent expectation: on the mid-step configuration x_m = (I + dt/2 G) x0 the field is
    // v = G (I + dt/2 G)⁻¹ x_m, so L = G (I + dt/2 G)⁻¹; Δε = sym(L) dt; σ = λ tr Δε I + 2G Δε.
    let a =
        [0, 1, 2].map(|r| [0, 1, 2].map(|c| if r == c { 1.0 } else { 0.0 } + 0.5 * dt * g[r][c]));
    // L = G A⁻¹ ⇔ Lᵀ = A⁻ᵀ Gᵀ: solve Aᵀ (column of Lᵀ) = column of Gᵀ.
    let at = [0, 1, 2].map(|r| [0, 1, 2].map(|c| a[c][r]));
    let mut l = [[0.0; 3]; 3];
    for row in 0..3 {
        let x = lin_solve(at, g[row]);
        l[row] = x;
    }
    let eps = [
        l[0][0],
        l[1][1],
        l[2][2],
        0.5 * (l[0][1] + l[1][0]),
        0.5 * (l[1][2] + l[2][1]),
        0.5 * (l[2][0] + l[0][2]),
    ]
    .map(|e| e * dt);
    let (lam, mu) = (mat.lame_lambda(), mat.shear_modulus());
    let tr = eps[0] + eps[1] + eps[2];
    let expect: [f64; 6] =
        std::array::from_fn(|k| if k < 3 { lam * tr } else { 0.0 } + 2.0 * mu * eps[k]);
    let scale = expect.iter().fold(0.0f64, |m, s| m.max(s.abs()));
    for p in &blk.points {
        for k in 0..6 {
            assert!(
                (p.stress[k] - expect[k]).abs() < 1e-9 * scale,
                "{formulation:?}: {:?} vs {expect:?}",
                p.stress
            );
        }
    }
    // Residual at the interior node (the only node not on the boundary) vanishes.
    let interior = (0..mesh.nodes.len())
        .find(|&n| mesh.boundary.iter().all(|q| !q.contains(&(n as u32))))
        .unwrap();
    let mut r = [0.0; 3];
    let mut fmax = 0.0f64;
    for (e, h) in mesh.hexes.iter().enumerate() {
        for (l, &n) in h.iter().enumerate() {
            fmax = fmax.max(forces[e][l].iter().fold(0.0f64, |m, c| m.max(c.abs())));
            if n as usize == interior {
                for k in 0..3 {
                    r[k] += forces[e][l][k];
                }
            }
        }
    }
    for c in r {
        assert!(
            c.abs() < 1e-10 * fmax,
            "{formulation:?}: interior residual {r:?} (force scale {fmax:e})"
        );
    }
    // Hourglass forces were not excited by the linear field.
    assert!(blk
        .hourglass
        .iter()
        .flatten()
        .flatten()
        .all(|q| q.abs() < 1e-12 * fmax));
}

#[test]
fn patch_test_one_point_with_hourglass_control() {
    patch(Formulation::OnePoint);
}

#[test]
fn patch_test_bbar() {
    patch(Formulation::BBar);
}
