//! Closed-form free vibrations of a homogeneous elastic sphere (Lamb 1882): the radial
//! (breathing, n = 0) and spheroidal (n ≥ 1) mode frequencies from the traction-free
//! condition at r = a, solved numerically with spherical Bessel functions.
//!
//! Displacement u = ∇φ + ∇×∇×(x ψ), φ = A j_n(h r) Y_n, ψ = B j_n(k r) Y_n, h = ω/c_p,
//! k = ω/c_s. With U = f' + n(n+1) g/r and V = (f + (r g)')/r (f = A j_n(hr), g = B j_n(kr)):
//! σ_rr = (−λ h² f + 2μ U') Y_n and σ_rθ = μ (2f'/r − 2f/r² + g'' + (n(n+1) − 2) g/r²) ∂_θ Y_n.
//! Both vanish at r = a: a 2x2 determinant in (A, B) that is zero at the eigenfrequencies.

/// Spherical Bessel function j_n(x) of the first kind, n ≤ 8, x > 0 (upward recurrence from
/// the closed forms; accurate for the x ≳ n used here).
pub fn spherical_jn(n: usize, x: f64) -> f64 {
    let (s, c) = x.sin_cos();
    let j0 = s / x;
    if n == 0 {
        return j0;
    }
    let mut jm = j0;
    let mut j = s / (x * x) - c / x;
    for l in 1..n {
        let next = (2 * l + 1) as f64 / x * j - jm;
        jm = j;
        j = next;
    }
    j
}

/// (j_n, j_n', j_n'') at x.
fn jn_derivs(n: usize, x: f64) -> (f64, f64, f64) {
    let j = spherical_jn(n, x);
    // j_n' = j_{n−1} − (n+1)/x j_n for n ≥ 1; j_0' = −j_1.
    let d = if n == 0 {
        -spherical_jn(1, x)
    } else {
        spherical_jn(n - 1, x) - (n + 1) as f64 / x * j
    };
    let nn = (n * (n + 1)) as f64;
    let dd = -2.0 / x * d - (1.0 - nn / (x * x)) * j;
    (j, d, dd)
}

/// The frequency determinant of spheroidal modes of angular order `n` at the dimensionless
/// frequency η = ω a / c_s, for wave-speed ratio `cp_over_cs` = c_p/c_s (> √2 for ν > 0).
/// For n = 0 the (single) radial condition σ_rr = 0 is returned.
pub fn spheroidal_determinant(n: usize, eta: f64, cp_over_cs: f64) -> f64 {
    // Units: a = 1, μ = 1, c_s = 1, so λ = c_p²/c_s² − 2, k = η, h = η c_s/c_p.
    let lam = cp_over_cs * cp_over_cs - 2.0;
    let k = eta;
    let h = eta / cp_over_cs;
    let (jh, dh, ddh) = jn_derivs(n, h);
    let (jk, dk, ddk) = jn_derivs(n, k);
    let nn = (n * (n + 1)) as f64;
    // Row 1 (σ_rr): A(−λ h² j + 2 h² j'') + B 2 n(n+1)(k j'(k) − j(k)).
    let a11 = -lam * h * h * jh + 2.0 * h * h * ddh;
    if n == 0 {
        return a11;
    }
    let a12 = 2.0 * nn * (k * dk - jk);
    // Row 2 (σ_rθ): A(2 h j'(h) − 2 j(h)) + B(k² j''(k) + (n(n+1) − 2) j(k)).
    let a21 = 2.0 * h * dh - 2.0 * jh;
    let a22 = k * k * ddk + (nn - 2.0) * jk;
    a11 * a22 - a12 * a21
}

/// The lowest root η = ω a / c_s of the spheroidal determinant of order `n` (n = 0: breathing
/// mode), for Poisson's ratio `nu` (−1 < ν < 0.5). Scans η upward from 0.5 in steps of 0.01
/// and bisects the first sign change to 1e-13.
pub fn lowest_spheroidal_root(n: usize, nu: f64) -> f64 {
    let ratio = (2.0 * (1.0 - nu) / (1.0 - 2.0 * nu)).sqrt();
    let f = |e: f64| spheroidal_determinant(n, e, ratio);
    let mut a = 0.5;
    let mut fa = f(a);
    loop {
        let b = a + 0.01;
        let fb = f(b);
        if fa == 0.0 {
            return a;
        }
        if fa * fb < 0.0 {
            let (mut lo, mut hi, mut flo) = (a, b, fa);
            while hi - lo > 1e-13 {
                let mid = 0.5 * (lo + hi);
                let fm = f(mid);
                if fm * flo > 0.0 {
                    lo = mid;
                    flo = fm;
                } else {
                    hi = mid;
                }
            }
            return 0.5 * (lo + hi);
        }
        a = b;
        fa = fb;
        assert!(a < 100.0, "no spheroidal root below η = 100");
    }
}

/// Angular frequency (rad/s) of the lowest spheroidal mode of order `n` (0 = breathing) of a
/// sphere of radius `a` (m) made of `m`.
pub fn sphere_frequency(n: usize, a: f64, m: &crate::Material) -> f64 {
    let cs = (m.shear_modulus() / m.rho).sqrt();
    lowest_spheroidal_root(n, m.nu) * cs / a
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bessel_closed_forms() {
        let x: f64 = 2.7;
        let j2 = (3.0 / (x * x) - 1.0) * x.sin() / x - 3.0 * x.cos() / (x * x);
        assert!((spherical_jn(2, x) - j2).abs() < 1e-14);
    }

    #[test]
    fn breathing_mode_matches_lambs_tangent_form() {
        // Lamb (1882) eq. (59): tan x (4 − x² c_p²/c_s²) = 4x with x = ω a / c_p.
        for nu in [0.25, 0.33] {
            let r2 = 2.0 * (1.0 - nu) / (1.0 - 2.0 * nu);
            let eta = lowest_spheroidal_root(0, nu);
            let x = eta / r2.sqrt();
            assert!(
                (x.tan() * (4.0 - x * x * r2) - 4.0 * x).abs() < 1e-8,
                "ν = {nu}"
            );
        }
    }

    #[test]
    fn quadrupole_mode_matches_lambs_value() {
        // Lamb (1882) for Poisson's ratio 1/4: the gravest spheroidal mode (n = 2) has
        // ω a / c_s ≈ 2.64.
        let eta = lowest_spheroidal_root(2, 0.25);
        assert!((eta - 2.64).abs() < 0.01, "{eta}");
    }
}
