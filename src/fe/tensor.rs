//! Small fixed-size tensor algebra for element kernels: 3-vectors, 3x3 matrices and
//! symmetric tensors in Voigt order [xx, yy, zz, xy, yz, zx] (tensor, not engineering, shears).

/// A 3x3 matrix, row-major: `m[i][j]`.
pub type Mat3 = [[f64; 3]; 3];
/// A symmetric second-order tensor [xx, yy, zz, xy, yz, zx].
pub type Sym = [f64; 6];

/// Identity matrix.
pub const IDENTITY: Mat3 = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

/// Determinant of a 3x3 matrix.
#[inline]
pub fn det(m: &Mat3) -> f64 {
    m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
        - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
        + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
}

/// Inverse and determinant of a 3x3 matrix; the inverse is meaningless when det = 0 (callers
/// check the determinant: a non-positive Jacobian means an inverted element).
#[inline]
pub fn inverse(m: &Mat3) -> (Mat3, f64) {
    let c00 = m[1][1] * m[2][2] - m[1][2] * m[2][1];
    let c01 = m[1][2] * m[2][0] - m[1][0] * m[2][2];
    let c02 = m[1][0] * m[2][1] - m[1][1] * m[2][0];
    let d = m[0][0] * c00 + m[0][1] * c01 + m[0][2] * c02;
    let r = 1.0 / d;
    let inv = [
        [
            c00 * r,
            (m[0][2] * m[2][1] - m[0][1] * m[2][2]) * r,
            (m[0][1] * m[1][2] - m[0][2] * m[1][1]) * r,
        ],
        [
            c01 * r,
            (m[0][0] * m[2][2] - m[0][2] * m[2][0]) * r,
            (m[0][2] * m[1][0] - m[0][0] * m[1][2]) * r,
        ],
        [
            c02 * r,
            (m[0][1] * m[2][0] - m[0][0] * m[2][1]) * r,
            (m[0][0] * m[1][1] - m[0][1] * m[1][0]) * r,
        ],
    ];
    (inv, d)
}

/// Cross product a × b.
#[inline]
pub fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// Dot product a · b.
#[inline]
pub fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Matrix-vector product m v.
#[inline]
pub fn mat_vec(m: &Mat3, v: [f64; 3]) -> [f64; 3] {
    [dot(m[0], v), dot(m[1], v), dot(m[2], v)]
}

/// Symmetric part of a matrix in Voigt order (tensor shears).
#[inline]
pub fn sym_part(l: &Mat3) -> Sym {
    [
        l[0][0],
        l[1][1],
        l[2][2],
        0.5 * (l[0][1] + l[1][0]),
        0.5 * (l[1][2] + l[2][1]),
        0.5 * (l[2][0] + l[0][2]),
    ]
}

/// Axial vector w of the skew part W = (L − Lᵀ)/2 of a matrix, so that W v = w × v.
#[inline]
pub fn spin_vector(l: &Mat3) -> [f64; 3] {
    [
        0.5 * (l[2][1] - l[1][2]),
        0.5 * (l[0][2] - l[2][0]),
        0.5 * (l[1][0] - l[0][1]),
    ]
}

/// Trace of a symmetric tensor.
#[inline]
pub fn trace(s: &Sym) -> f64 {
    s[0] + s[1] + s[2]
}

/// Double contraction a : b of two symmetric tensors.
#[inline]
pub fn ddot(a: &Sym, b: &Sym) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + 2.0 * (a[3] * b[3] + a[4] * b[4] + a[5] * b[5])
}

/// Deviatoric part of a symmetric tensor.
#[inline]
pub fn deviator(s: &Sym) -> Sym {
    let m = trace(s) / 3.0;
    [s[0] - m, s[1] - m, s[2] - m, s[3], s[4], s[5]]
}

/// Symmetric tensor times vector.
#[inline]
pub fn sym_vec(s: &Sym, v: [f64; 3]) -> [f64; 3] {
    [
        s[0] * v[0] + s[3] * v[1] + s[5] * v[2],
        s[3] * v[0] + s[1] * v[1] + s[4] * v[2],
        s[5] * v[0] + s[4] * v[1] + s[2] * v[2],
    ]
}

/// Von Mises equivalent stress sqrt(3/2 s:s), Pa.
#[inline]
pub fn von_mises(s: &Sym) -> f64 {
    let d = deviator(s);
    (1.5 * ddot(&d, &d)).sqrt()
}

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
