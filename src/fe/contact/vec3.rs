//! Small 3-vector helpers on `[f64; 3]` (the crate's nodal-vector type).

/// a + b.
#[inline]
pub fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

/// a − b.
#[inline]
pub fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// s · a.
#[inline]
pub fn scale(s: f64, a: [f64; 3]) -> [f64; 3] {
    [s * a[0], s * a[1], s * a[2]]
}

/// a · b.
#[inline]
pub fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// a × b.
#[inline]
pub fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// |a|.
#[inline]
pub fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

/// The tangential part of `a` with respect to the unit normal `n`: a − (a·n) n.
#[inline]
pub fn tangential(a: [f64; 3], n: [f64; 3]) -> [f64; 3] {
    sub(a, scale(dot(a, n), n))
}

/// a + s b (axpy).
#[inline]
pub fn axpy(a: [f64; 3], s: f64, b: [f64; 3]) -> [f64; 3] {
    [a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2]]
}

/// Adds `v` into `f[i]`.
#[inline]
pub fn add_into(f: &mut [[f64; 3]], i: usize, v: [f64; 3]) {
    f[i][0] += v[0];
    f[i][1] += v[1];
    f[i][2] += v[2];
}

/// Area of a (possibly warped) quadrilateral p0-p1-p2-p3: half the norm of the cross product of
/// its diagonals (exact for planar quads), m².
pub fn quad_area(p: &[[f64; 3]; 4]) -> f64 {
    0.5 * norm(cross(sub(p[2], p[0]), sub(p[3], p[1])))
}
