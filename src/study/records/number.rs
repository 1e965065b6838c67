//! Numbers for people: scientific notation as Rust writes it (`1.234567e-5`), but plain `0`
//! for zero instead of `0.000000e0`.

/// `x` in scientific notation with `digits` decimals (`-3.200000e-5`), `0` for zero, and
/// `NaN`/`inf` as Rust spells them.
pub fn sci(x: f64, digits: usize) -> String {
    if x == 0.0 {
        return "0".into();
    }
    format!("{x:.digits$e}")
}

#[cfg(test)]
mod tests {
    use super::sci;

    #[test]
    fn zero_is_plain_and_other_numbers_are_scientific() {
        assert_eq!(sci(0.0, 6), "0");
        assert_eq!(sci(-0.0, 6), "0");
        assert_eq!(sci(1.0, 6), "1.000000e0");
        assert_eq!(sci(-3.2e-5, 3), "-3.200e-5");
        assert_eq!(sci(f64::NAN, 3), "NaN");
    }
}
