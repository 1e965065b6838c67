//! Meshes and loads shared by the axisymmetric tests.
#![allow(dead_code)]
// Index loops follow the mesh numbering (ray p, layer l): keep them.
#![allow(clippy::needless_range_loop)]

use std::f64::consts::PI;
use twoball::fe::materials::J2Material;
use twoball::fe::section::solver::SectionModel;
use twoball::material::Material;

/// A structured mesh (nodes, counter-clockwise quads) of the map `f(s, t)` on
/// [0, 1]² with `ns` x `nt` cells; node (i, j) has index j (ns + 1) + i.
pub fn mapped(
    ns: usize,
    nt: usize,
    f: impl Fn(f64, f64) -> [f64; 2],
) -> (Vec<[f64; 2]>, Vec<[u32; 4]>) {
    let mut nodes = Vec::new();
    for j in 0..=nt {
        for i in 0..=ns {
            nodes.push(f(i as f64 / ns as f64, j as f64 / nt as f64));
        }
    }
    let id = |i: usize, j: usize| (j * (ns + 1) + i) as u32;
    let mut quads = Vec::new();
    for j in 0..nt {
        for i in 0..ns {
            let mut q = [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)];
            let x = q.map(|k| nodes[k as usize]);
            if twoball::fe::elements::ring::shape::area(&x) < 0.0 {
                q = [q[0], q[3], q[2], q[1]];
            }
            quads.push(q);
        }
    }
    (nodes, quads)
}

/// Quarter annulus a ≤ ρ ≤ b, 0 ≤ φ ≤ π/2 of the meridian plane (a thick sphere's section
/// above its equator), `nr` cells radially and `nc` around; nodes on the axis have r = 0.
pub fn quarter_annulus(a: f64, b: f64, nr: usize, nc: usize) -> (Vec<[f64; 2]>, Vec<[u32; 4]>) {
    mapped(nr, nc, |s, t| {
        let rho = a + (b - a) * s;
        let phi = 0.5 * PI * t;
        let r = if t == 0.0 { 0.0 } else { rho * phi.sin() };
        let z = if t == 1.0 { 0.0 } else { rho * phi.cos() };
        [r, z]
    })
}

/// Radial displacement (m) at radius `rho` of Lamé's thick sphere (inner radius a, outer b,
/// inner pressure p, Young's modulus e, Poisson's ratio nu):
/// u(ρ) = p a³ ((1 − 2ν) ρ + (1 + ν) b³ / (2ρ²)) / (E (b³ − a³)).
pub fn lame_u(a: f64, b: f64, p: f64, e: f64, nu: f64, rho: f64) -> f64 {
    p * a.powi(3) * ((1.0 - 2.0 * nu) * rho + (1.0 + nu) * b.powi(3) / (2.0 * rho * rho))
        / (e * (b.powi(3) - a.powi(3)))
}

/// Hill's (1950) partly plastic thick sphere a = 10 mm, b = 20 mm of elastic-perfectly
/// plastic `m` with its plastic zone out to c = 15 mm: the inner pressure
/// p = 2σ_y ln(c/a) + (2σ_y/3)(1 − c³/b³) (Pa) and the outer surface's displacement
/// u(b) = σ_y c³ (1 − ν)/(E b²) (m).
pub fn hill(m: &Material) -> (f64, f64) {
    let (a, b, c) = (0.01f64, 0.02f64, 0.015f64);
    let sy = m.yield_strength;
    let p = 2.0 * sy * (c / a).ln() + 2.0 * sy / 3.0 * (1.0 - (c / b).powi(3));
    let ub = sy * c.powi(3) * (1.0 - m.nu) / (m.youngs * b * b);
    (p, ub)
}

/// Elastic-perfectly plastic steel-like material (E = 200 GPa, ν = 0.3, σ_y = 400 MPa).
pub fn perfect_steel() -> Material {
    let mut m = Material::preset("steel").unwrap();
    m.youngs = 200e9;
    m.nu = 0.3;
    m.yield_strength = 400e6;
    m.tangent = 0.0;
    m
}

/// Consistent ring loads of a pressure `p` (Pa) on the inner surface ρ = a of a
/// [`quarter_annulus`] (nodes i = 0), pushing outward.
pub fn inner_pressure(model: &mut SectionModel, nr: usize, nc: usize, p: f64) {
    for j in 0..nc {
        let (i0, i1) = (j * (nr + 1), (j + 1) * (nr + 1));
        let (x0, x1) = (model.nodes[i0], model.nodes[i1]);
        let l = ((x1[0] - x0[0]).powi(2) + (x1[1] - x0[1]).powi(2)).sqrt();
        // Outward normal of the cavity = the chord's mid-direction from the centre.
        let m = [0.5 * (x0[0] + x1[0]), 0.5 * (x0[1] + x1[1])];
        let nm = (m[0] * m[0] + m[1] * m[1]).sqrt();
        let n = [m[0] / nm, m[1] / nm];
        for (k, ri, rj) in [(i0, x0[0], x1[0]), (i1, x1[0], x0[0])] {
            let w = p * 2.0 * PI * l * (2.0 * ri + rj) / 6.0;
            model.loads[k][0] += w * n[0];
            model.loads[k][1] += w * n[1];
        }
    }
}

/// A section model of `mesh` in material `m`.
pub fn model(nodes: Vec<[f64; 2]>, quads: Vec<[u32; 4]>, m: &Material) -> SectionModel {
    SectionModel::new(nodes, quads, J2Material::new(m, false))
}

/// A graded all-quad half-disc ball section for the tests (radius `radius`, centre at the
/// origin, pole at (0, R)): a half-square core of half-side R/2 (transfinite interpolation of
/// its sides) and an outer ring of rays from the origin, from the core's outline to the arc.
/// The arc is split at ±45°: the top section's spacing grows geometrically (×1.1) from `pole`
/// at the north pole to at most `far`, the other two are uniform with as many segments per
/// 45° as the top one. Radial layers are graded alike towards the surface. Contact
/// segments: the arc within 45° of the north pole.
pub fn test_ball(radius: f64, pole: f64, far: f64) -> twoball::mesh::section::SectionMesh {
    let growth = 1.1;
    let graded = |total: f64| -> Vec<f64> {
        let mut ds = Vec::new();
        let (mut s, mut h) = (0.0, pole);
        while s < total {
            ds.push(h);
            s += h;
            h = (h * growth).min(far);
        }
        let sum: f64 = ds.iter().sum();
        ds.iter().map(|d| d * total / sum).collect()
    };
    let top = graded(0.25 * PI * radius);
    let n = top.len();
    let k = 4 * n;
    // Ray angles θ_p (from the equator), p = 0 (south pole) .. k (north pole).
    let mut theta = vec![0.0; k + 1];
    for p in 0..=3 * n {
        theta[p] = -0.5 * PI + 0.75 * PI * p as f64 / (3 * n) as f64;
    }
    let mut acc = 0.0;
    theta[k] = 0.5 * PI;
    for (i, d) in top.iter().enumerate().take(n - 1) {
        acc += d;
        theta[k - 1 - i] = 0.5 * PI - acc / radius;
    }
    let c = 0.5 * radius;
    let outline = |p: usize| -> [f64; 2] {
        let (s, co) = theta[p].sin_cos();
        if p == 0 {
            [0.0, -c]
        } else if p == k {
            [0.0, c]
        } else if p <= n {
            [-c * co / s, -c]
        } else if p < 3 * n {
            [c, c * s / co]
        } else {
            [c * co / s, c]
        }
    };
    // Core by transfinite interpolation: bottom B(i) = outline(i), right R(j) = outline(n + j),
    // top T(i) = outline(4n − i), left L(j) on the axis.
    let mut nodes: Vec<[f64; 2]> = Vec::new();
    for j in 0..=2 * n {
        for i in 0..=n {
            let (u, v) = (i as f64 / n as f64, j as f64 / (2 * n) as f64);
            let (b, t) = (outline(i), outline(4 * n - i));
            let (l, r) = ([0.0, -c + 2.0 * c * v], outline(n + j));
            let (c00, c10, c01, c11) = ([0.0, -c], [c, -c], [0.0, c], [c, c]);
            let x: [f64; 2] = std::array::from_fn(|a| {
                (1.0 - v) * b[a] + v * t[a] + (1.0 - u) * l[a] + u * r[a]
                    - ((1.0 - u) * (1.0 - v) * c00[a]
                        + u * (1.0 - v) * c10[a]
                        + (1.0 - u) * v * c01[a]
                        + u * v * c11[a])
            });
            nodes.push(if i == 0 { [0.0, x[1]] } else { x });
        }
    }
    let core = |i: usize, j: usize| (j * (n + 1) + i) as u32;
    let outline_node = |p: usize| -> u32 {
        if p <= n {
            core(p, 0)
        } else if p <= 3 * n {
            core(n, p - n)
        } else {
            core(4 * n - p, 2 * n)
        }
    };
    // Radial layer fractions along each ray, thinnest at the surface.
    let depth = radius - c;
    let layers = graded(depth);
    let m = layers.len();
    let mut frac = vec![0.0; m + 1];
    let mut acc = 0.0;
    for (l, h) in layers.iter().enumerate() {
        acc += h / depth;
        frac[m - 1 - l] = 1.0 - acc;
    }
    frac[0] = 0.0;
    frac[m] = 1.0;
    let base = nodes.len();
    for f in frac.iter().skip(1) {
        for p in 0..=k {
            let a = outline(p);
            let (s, co) = theta[p].sin_cos();
            let b = [radius * co, radius * s];
            let mut x = [a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1])];
            if p == 0 || p == k {
                x[0] = 0.0;
            }
            nodes.push(x);
        }
    }
    let ring = |l: usize, p: usize| -> u32 {
        if l == 0 {
            outline_node(p)
        } else {
            (base + (l - 1) * (k + 1) + p) as u32
        }
    };
    let mut quads = Vec::new();
    let mut push = |q: [u32; 4], nodes: &Vec<[f64; 2]>| {
        let x = q.map(|i| nodes[i as usize]);
        if twoball::fe::elements::ring::shape::area(&x) > 0.0 {
            quads.push(q);
        } else {
            quads.push([q[0], q[3], q[2], q[1]]);
        }
    };
    for j in 0..2 * n {
        for i in 0..n {
            push(
                [
                    core(i, j),
                    core(i + 1, j),
                    core(i + 1, j + 1),
                    core(i, j + 1),
                ],
                &nodes,
            );
        }
    }
    for l in 0..m {
        for p in 0..k {
            push(
                [
                    ring(l, p),
                    ring(l, p + 1),
                    ring(l + 1, p + 1),
                    ring(l + 1, p),
                ],
                &nodes,
            );
        }
    }
    let boundary: Vec<[u32; 2]> = (0..k).map(|p| [ring(m, p), ring(m, p + 1)]).collect();
    let contact: Vec<[u32; 2]> = (3 * n..k).map(|p| [ring(m, p), ring(m, p + 1)]).collect();
    let mut mesh = twoball::mesh::section::SectionMesh {
        nodes,
        quads,
        boundary: boundary.clone(),
        ..Default::default()
    };
    mesh.segment_sets.insert("surface".into(), boundary);
    mesh.segment_sets.insert("contact".into(), contact);
    mesh
}
