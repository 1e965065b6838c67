//! Numbers for people: scientific notation with a signed, two-digit exponent (`1.234567e-05`),
//! and plain `0` for zero instead of `0.000000e0`.

/// `x` in scientific notation with `digits` decimals (`-3.200000e-05`), `0` for zero, and
/// `NaN`/`inf` as Rust spells them.
pub fn sci(x: f64, digits: usize) -> String {
    if x == 0.0 {
        return "0".into();
    }
    if !x.is_finite() {
        return x.to_string();
    }
    let s = format!("{x:.digits$e}");
    match s.split_once('e') {
        Some((mantissa, exp)) => {
            let (sign, digits) = match exp.strip_prefix('-') {
                Some(d) => ('-', d),
                None => ('+', exp),
            };
            format!("{mantissa}e{sign}{digits:0>2}")
        }
        None => s,
    }
}

#[cfg(test)]
mod tests {
    use super::sci;

    #[test]
    fn zero_is_plain_and_exponents_are_signed_two_digits() {
        assert_eq!(sci(0.0, 6), "0");
        assert_eq!(sci(-0.0, 6), "0");
        assert_eq!(sci(1.0, 6), "1.000000e+00");
        assert_eq!(sci(-3.2e-5, 3), "-3.200e-05");
        assert_eq!(sci(6.02e23, 2), "6.02e+23");
        assert_eq!(sci(1e-300, 1), "1.0e-300");
        assert_eq!(sci(f64::NAN, 3), "NaN");
    }
}
